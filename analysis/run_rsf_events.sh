#!/bin/bash
# Event-driven against continuous rate-and-state runs, and the aftershocks beside
# velocity-weakening BK and OFC with relaxation (docs/validation/rsf-events.md):
#
#   analysis/run_rsf_events.sh [OUT_DIR]        (default runs/rsf-events)
#
# The chain of 100 (data/scenes/rsf/chain100-asperities.ini) at V_pl = 1e-9 m/s and at
# 1e-6 m/s, each continuously from two starts (rsf.v_init = V_pl and 1.1 V_pl) and event-driven
# at the auto hand-over speed (both starts) and at 3 V_pl; the 16 x 8 lattice
# (data/scenes/rsf/lattice-patches.ini, 1e-6 m/s) continuously and at 3 V_pl from the two
# starts; the uniform chain of 100 (data/scenes/rsf/chain-events.ini with rsf.pattern =
# uniform) continuously from the two starts and event-driven at 3 V_pl and the auto V_h.
# Then `bkquake seismicity` on every folder and `bkquake compare` of each set, written to
# OUT_DIR/compare-*.txt. Each run's user CPU seconds go to OUT_DIR/NAME.cpu. A folder that
# already holds summary.json is kept, so the script resumes where it stopped.
#
# Environment: BKQUAKE (default build/bkquake); EVENTS_SET, extra --set options for the
# event-driven runs only; REUSE, a folder of an earlier run of this script whose continuous,
# velocity-weakening and OFC runs are linked instead of run again. So a change of the
# event-driven engine is measured against the same continuous runs with, e.g.,
#   REUSE=runs/rsf-events EVENTS_SET="--set rsf.creep_quantum=1e-6" \
#     analysis/run_rsf_events.sh runs/rsf-events-creep
# Runs at nice 10, one at a time.
set -euo pipefail
B=${BKQUAKE:-build/bkquake}
OUT=${1:-runs/rsf-events}
read -r -a EXTRA <<<"${EVENTS_SET:-}"
mkdir -p "$OUT"

run() {
  local name=$1
  shift
  if [ -f "$OUT/$name/summary.json" ]; then return; fi
  echo "+ $B run $* --out $OUT/$name" >&2
  /usr/bin/time -f %U -o "$OUT/$name.cpu" nice -n 10 "$B" run "$@" --out "$OUT/$name" --quiet
}
events() { run "$@" --set drive.mode=events --set run.transient_events=0 "${EXTRA[@]}"; }
# A run that does not depend on the event-driven engine: linked from $REUSE when it is there.
kept() {
  if [ -n "${REUSE:-}" ] && [ -f "$REUSE/$1/summary.json" ] && [ ! -e "$OUT/$1" ]; then
    ln -s "$(cd "$REUSE" && pwd)/$1" "$OUT/$1"
    [ ! -f "$REUSE/$1.cpu" ] || cp "$REUSE/$1.cpu" "$OUT/$1.cpu"
  fi
  run "$@"
}

C=data/scenes/rsf/chain100-asperities.ini
L=data/scenes/rsf/lattice-patches.ini
# The chain at 1e-9 m/s over 4e7 s; event-driven until past 4e7 s.
kept c1-9 "$C" --set run.duration=4e7
kept c2-9 "$C" --set run.duration=4e7 --set rsf.v_init=1.1e-9
events ea1-9 "$C" --set run.events=5000
events ea2-9 "$C" --set run.events=5000 --set rsf.v_init=1.1e-9
events eh-9 "$C" --set run.events=5000 --set rsf.handover_speed=3e-9
# The same chain at 1e-6 m/s over 4e4 s.
F6=(--set drive.speed=1e-6 --set rsf.v_init=1e-6)
kept c1-6 "$C" "${F6[@]}" --set run.duration=4e4
kept c2-6 "$C" "${F6[@]}" --set run.duration=4e4 --set rsf.v_init=1.1e-6
events ea1-6 "$C" "${F6[@]}" --set run.events=5000
events ea2-6 "$C" "${F6[@]}" --set run.events=5000 --set rsf.v_init=1.1e-6
events eh-6 "$C" "${F6[@]}" --set run.events=5000 --set rsf.handover_speed=3e-6
# The 16 x 8 lattice at 1e-6 m/s over 1e5 s; event-driven until past it.
kept lc1 "$L" --set run.duration=1e5
kept lc2 "$L" --set run.duration=1e5 --set rsf.v_init=1.1e-6
# Event-driven at 3 V_pl only: bkquake refuses lattices at a higher (or the auto) V_h.
events leh "$L" --set run.events=6500 --set rsf.handover_speed=3e-6
events leh2 "$L" --set run.events=6500 --set rsf.handover_speed=3e-6 --set rsf.v_init=1.1e-6
# The uniform chain of 100 (QDYN's block on every site, chain-wide events) at 1e-6 m/s over
# 1e6 s; event-driven until past it.
U=(data/scenes/rsf/chain-events.ini --set rsf.pattern=uniform)
kept uc1 "${U[@]}" --set drive.mode=continuous --set run.duration=1e6
kept uc2 "${U[@]}" --set drive.mode=continuous --set run.duration=1e6 --set rsf.v_init=1.1e-6
events ueh "${U[@]}" --set run.events=2300
events uea "${U[@]}" --set run.events=2300 --set rsf.handover_speed=auto
# Aftershocks beside: velocity-weakening BK (the Carlson-Langer chain of 100) and OFC with
# relaxation (docs/explanation/ofc.md).
kept vw data/scenes/carlson-langer.ini --set run.events=200000
kept ofc data/scenes/lattice/ofc-relaxation-64.ini

# Mainshocks (and the large events of the recurrence) by magnitude: the rate-and-state runs
# have no events spanning half the system.
seis() {
  local mu=$1 d
  shift
  for d in "$@"; do
    [ -f "$OUT/$d/seismicity/seismicity.json" ] ||
      nice -n 10 "$B" seismicity "$OUT/$d" --mainshock-mu "$mu" >"$OUT/$d.seismicity.log" 2>&1 ||
      echo "bkquake seismicity $OUT/$d failed: $(tail -1 "$OUT/$d.seismicity.log")" >&2
  done
}
seis -6.5 c1-9 c2-9 ea1-9 ea2-9 eh-9
seis -6.5 c1-6 c2-6 ea1-6 ea2-6 eh-6
seis -6.5 lc1 lc2 leh leh2
seis -3.5 uc1 uc2 ueh uea
seis 5 ofc
[ -f "$OUT/vw/seismicity/seismicity.json" ] || "$B" seismicity "$OUT/vw" >"$OUT/vw.seismicity.log"

compare_set() {
  local name=$1 mu=$2
  shift 2
  "$B" compare "$@" --mu-large "$mu" >"$OUT/compare-$name.txt" || true
  cat "$OUT/compare-$name.txt"
}
compare_set 9 -6.5 "$OUT"/{c1-9,c2-9,ea1-9,ea2-9,eh-9} --from 4e-3 --to 4e-2
compare_set 6 -6.5 "$OUT"/{c1-6,c2-6,ea1-6,ea2-6,eh-6} --from 4e-3 --to 4e-2
compare_set lattice -6.5 "$OUT"/{lc1,lc2,leh,leh2} --from 5e-3 --to 1e-1
compare_set uniform -3.5 "$OUT"/{uc1,uc2,ueh,uea} --from 0.1 --to 1
