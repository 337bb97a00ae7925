#!/usr/bin/env bash
# Rupture fronts with and without viscous coupling as the chain is refined (Myers & Langer
# 1993; the grid-independence question of Shaw 1997): continuous carlson-langer runs
# (clst91, alpha = 2.5, sigma = 0.01, drive speed 0.01, rk4 dt = 0.001, halved until the
# dashpots' fastest rate 4 eta times dt is at most 1) of N = 100, 200,
# 400 blocks with l = 10 N/100 (the same length of fault discretised finer), for each ETA0
# with model.viscosity = ETA0 (N/100)^2 (one continuum viscosity; its length eta/l is
# ETA0 N/1000 blocks, ETA0/1000 of the fault). Each run writes every block's displacement
# and velocity every 0.01 time units (output.blocks) for DURATION time units into
# runs/coupling-fronts/N<N>-eta<ETA0>/; then analysis/plot_coupling_fronts.py measures the
# fronts' speed and width in the large events.
#
#   analysis/run_coupling_fronts.sh [DURATION] [ETA0 ...]   (defaults: 900, ETA0 = 0 20)
#
# blocks.csv takes about 2.7 MB per 100 blocks per 10 time units (1 GB at N = 400 for 900). Environment: BKQUAKE
# (default build/bkquake), PYTHON (default /usr/bin/python3), JOBS (runs at once, default
# 2), OUT (default runs/coupling-fronts). Existing runs are replaced (--force).
set -euo pipefail

cd "$(dirname "$0")/.."
DURATION=${1:-900}
shift $(($# < 1 ? $# : 1))
ETAS=("$@")
[[ ${#ETAS[@]} -gt 0 ]] || ETAS=(0 20)
BKQUAKE=${BKQUAKE:-build/bkquake}
PYTHON=${PYTHON:-/usr/bin/python3}
JOBS=${JOBS:-2}
OUT=${OUT:-runs/coupling-fronts}

if [[ ! -x $BKQUAKE ]]; then
  echo "run_coupling_fronts.sh: $BKQUAKE not found; build it (./run.sh) or set BKQUAKE" >&2
  exit 2
fi
mkdir -p "$OUT"
for n in 100 200 400; do
  l=$((10 * n / 100))
  for eta0 in "${ETAS[@]}"; do
    eta=$("$PYTHON" -c "print($eta0 * ($n / 100) ** 2)")
    # The dashpots' fastest rate is 4 eta / m_u: halve dt until 4 eta dt <= 1 (omega_dt).
    dt=$("$PYTHON" -c "
dt = 0.001
while 4 * $eta * dt > 1: dt /= 2
print(dt)")
    while [[ $(jobs -rp | wc -l) -ge $JOBS ]]; do sleep 1; done
    "$BKQUAKE" run --quiet --force --out "$OUT/N$n-eta$eta0" \
      --set drive.mode=continuous --set model.blocks="$n" --set model.l="$l" \
      --set model.viscosity="$eta" --set integrator.dt="$dt" \
      --set run.duration="$DURATION" --set output.every=0.01 --set output.blocks=true &
  done
done
wait
"$PYTHON" analysis/plot_coupling_fronts.py "$OUT" --out "$OUT/fronts.png"
