#!/usr/bin/env bash
# Scaling with the chain length (performance issue, goals 7 and 8): for each N, one event
# run of the built-in carlson-langer scene (rk4, dt = 0.01) with N blocks, past a transient
# of 20 events per block (the engine's steady state; N = 10^5 takes a few minutes), the
# catalogue off (output.catalog = none) so the engine is what is timed. Prints one CSV row
# per N: events per second, ns per sliding block-step and per block-step (the whole run's
# recorded wall time over summary.json's work counters), and the peak resident memory
# with its bytes per block.
#
#   analysis/scaling.sh [N...] > scaling.csv      (default: 100 1000 10000 100000)
#   /usr/bin/python3 analysis/plot_scaling.py scaling.csv --out scaling.png
#
# Environment: BKQUAKE (default build/bkquake), EVENTS (recorded events, default 100000),
# TRANSIENT_PER_BLOCK (default 20). Needs /usr/bin/time (Debian package time).
set -euo pipefail

cd "$(dirname "$0")/.."
BKQUAKE=${BKQUAKE:-build/bkquake}
EVENTS=${EVENTS:-100000}
TRANSIENT_PER_BLOCK=${TRANSIENT_PER_BLOCK:-20}
if [[ ! -x $BKQUAKE || ! -x /usr/bin/time ]]; then
  echo "scaling.sh: needs $BKQUAKE (build it, or set BKQUAKE) and /usr/bin/time" >&2
  exit 2
fi
if [[ $# -eq 0 ]]; then set -- 100 1000 10000 100000; fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# A number from summary.json: the first "key": value.
field() { grep -o "\"$2\": *[-0-9.e+]*" "$1" | head -1 | sed 's/.*: *//'; }

echo "blocks,events,events_per_second,ns_per_sliding_block_step,ns_per_block_step,peak_rss_mib,rss_bytes_per_block"
for n in "$@"; do
  out="$work/run-$n"
  /usr/bin/time -v -o "$work/time.txt" "$BKQUAKE" run --set "model.blocks=$n" \
    --set "run.events=$EVENTS" --set "run.transient_events=$((TRANSIENT_PER_BLOCK * n))" \
    --set output.catalog=none --out "$out" --quiet >/dev/null
  kib=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$work/time.txt")
  s="$out/summary.json"
  awk -v n="$n" -v e="$(field "$s" events)" -v w="$(field "$s" wall_seconds)" \
    -v bs="$(field "$s" block_steps)" -v sbs="$(field "$s" sliding_block_steps)" \
    -v k="$kib" \
    'BEGIN { printf "%d,%d,%.4g,%.4g,%.4g,%.1f,%.1f\n", n, e, e / w, w * 1e9 / sbs,
             w * 1e9 / bs, k / 1024, k * 1024 / n }'
  rm -rf "$out"
done
