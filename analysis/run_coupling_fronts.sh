#!/usr/bin/env bash
# Rupture fronts with and without viscous coupling as the chain is refined (Myers & Langer
# 1993; the grid-independence question of Shaw 1997): continuous carlson-langer runs
# (clst91, alpha = 2.5, sigma = 0.01, drive speed 0.01, rk4 dt = 0.001) of N = 100, 200,
# 400 blocks with l = 10 N/100 (the same length of fault discretised finer), for each ETA0
# with model.viscosity = ETA0 (N/100)^2 (one continuum viscosity; its length eta/l is
# ETA0 N/1000 blocks, ETA0/1000 of the fault). Each run writes every block's displacement
# and velocity every 0.01 time units (output.blocks) for DURATION time units into
# runs/coupling-fronts/N<N>-eta<ETA0>/; then analysis/plot_coupling_fronts.py measures the
# fronts' speed and width in the large events.
#
#   analysis/run_coupling_fronts.sh [DURATION] [ETA0 ...]   (defaults: 300, ETA0 = 0 2 20)
#
# blocks.csv takes about 16 MB per 100 blocks per 10 time units. Environment: BKQUAKE
# (default build/bkquake), PYTHON (default /usr/bin/python3), JOBS (runs at once, default
# 2). Existing runs are replaced (--force).
set -euo pipefail

cd "$(dirname "$0")/.."
DURATION=${1:-300}
shift $(($# < 1 ? $# : 1))
ETAS=("$@")
[[ ${#ETAS[@]} -gt 0 ]] || ETAS=(0 2 20)
BKQUAKE=${BKQUAKE:-build/bkquake}
PYTHON=${PYTHON:-/usr/bin/python3}
JOBS=${JOBS:-2}
OUT=runs/coupling-fronts

if [[ ! -x $BKQUAKE ]]; then
  echo "run_coupling_fronts.sh: $BKQUAKE not found; build it (./run.sh) or set BKQUAKE" >&2
  exit 2
fi
mkdir -p "$OUT"
for n in 100 200 400; do
  l=$((10 * n / 100))
  for eta0 in "${ETAS[@]}"; do
    eta=$("$PYTHON" -c "print($eta0 * ($n / 100) ** 2)")
    while [[ $(jobs -rp | wc -l) -ge $JOBS ]]; do sleep 1; done
    "$BKQUAKE" run --quiet --force --out "$OUT/N$n-eta$eta0" \
      --set drive.mode=continuous --set model.blocks="$n" --set model.l="$l" \
      --set model.viscosity="$eta" --set integrator.dt=0.001 \
      --set run.duration="$DURATION" --set output.every=0.01 --set output.blocks=true &
  done
done
wait
"$PYTHON" analysis/plot_coupling_fronts.py "$OUT" --out "$OUT/fronts.png"
