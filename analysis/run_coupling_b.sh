#!/usr/bin/env bash
# b against the coupling's range R (Xia, Gould, Klein & Rundle 2005): event-driven runs of
# the carlson-langer chain (l = 10, sigma = 0.01, rk4 dt = 0.01) at N blocks with
# model.coupling = range for each R, for two friction laws: clst91 (Carlson et al. 1991,
# alpha = 2.5, no backslip) and thesis (Ferre 2018 eq. 3.5 in these units, backslip
# allowed). Each run records EVENTS events after TRANSIENT into runs/coupling/<law>-R<R>/;
# its summary.json holds the binned-MLE b with its statistical and systematic errors
# (docs/explanation/b-fit.md). Then analysis/plot_coupling.py draws b against R and the
# magnitude distributions.
#
#   analysis/run_coupling_b.sh [EVENTS] [TRANSIENT] [N] [R ...]
#                              (defaults: 20000, 20000, 1000, R = 1 3 10 30 100)
#
# Environment: BKQUAKE (default build/bkquake), PYTHON (default /usr/bin/python3), JOBS
# (runs at once, default 2), SEED (run.seed; default the scene's), OUT (default
# runs/coupling). Existing runs are replaced (--force).
set -euo pipefail

cd "$(dirname "$0")/.."
EVENTS=${1:-20000}
TRANSIENT=${2:-20000}
N=${3:-1000}
shift $(($# < 3 ? $# : 3))
RANGES=("$@")
[[ ${#RANGES[@]} -gt 0 ]] || RANGES=(1 3 10 30 100)
BKQUAKE=${BKQUAKE:-build/bkquake}
PYTHON=${PYTHON:-/usr/bin/python3}
JOBS=${JOBS:-2}
OUT=${OUT:-runs/coupling}
SEED_SET=()
[[ -z ${SEED:-} ]] || SEED_SET=(--set run.seed="$SEED")

if [[ ! -x $BKQUAKE ]]; then
  echo "run_coupling_b.sh: $BKQUAKE not found; build it (./run.sh) or set BKQUAKE" >&2
  exit 2
fi
mkdir -p "$OUT"
jobs_running() { jobs -rp | wc -l; }
for law in clst91 thesis; do
  for r in "${RANGES[@]}"; do
    while [[ $(jobs_running) -ge $JOBS ]]; do sleep 1; done
    "$BKQUAKE" run --quiet --force --out "$OUT/$law-N$N-R$r" \
      --set model.blocks="$N" --set friction.law="$law" \
      --set model.coupling=range --set model.range="$r" \
      --set run.events="$EVENTS" --set run.transient_events="$TRANSIENT" "${SEED_SET[@]}" &
  done
done
wait
"$PYTHON" analysis/plot_coupling.py "$OUT" --out "$OUT/b_vs_range.png"
