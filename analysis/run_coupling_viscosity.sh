#!/usr/bin/env bash
# Large events with and without viscous coupling as the chain is refined (Myers & Langer
# 1993; the grid-independence question of Shaw 1997): event-driven carlson-langer runs
# (clst91, alpha = 2.5, sigma = 0.01, rk4 dt = 0.005) of N = 100, 200, 400 blocks with the
# stiffness l = 10 N/100, so that N blocks always discretise the same length of fault
# (k_c = l^2 grows as 1/a^2 with the block spacing a), without dashpots and with
# model.viscosity = ETA0 (N/100)^2 (the discrete form of one continuum viscosity, which
# scales as k_c does). Each run records EVENTS events after TRANSIENT into
# runs/coupling-viscosity/N<N>-eta<0|1>/; then analysis/plot_coupling_viscosity.py compares
# the large events (slipping at least a tenth of the chain) across N.
#
#   analysis/run_coupling_viscosity.sh [EVENTS] [TRANSIENT] [ETA0]   (defaults 50000 20000 2)
#
# Environment: BKQUAKE (default build/bkquake), PYTHON (default /usr/bin/python3), JOBS
# (runs at once, default 2). Existing runs are replaced (--force).
set -euo pipefail

cd "$(dirname "$0")/.."
EVENTS=${1:-50000}
TRANSIENT=${2:-20000}
ETA0=${3:-2}
BKQUAKE=${BKQUAKE:-build/bkquake}
PYTHON=${PYTHON:-/usr/bin/python3}
JOBS=${JOBS:-2}
OUT=runs/coupling-viscosity

if [[ ! -x $BKQUAKE ]]; then
  echo "run_coupling_viscosity.sh: $BKQUAKE not found; build it (./run.sh) or set BKQUAKE" >&2
  exit 2
fi
mkdir -p "$OUT"
for n in 100 200 400; do
  l=$((10 * n / 100))
  for on in 0 1; do
    eta=$("$PYTHON" -c "print($on * $ETA0 * ($n / 100) ** 2)")
    while [[ $(jobs -rp | wc -l) -ge $JOBS ]]; do sleep 1; done
    "$BKQUAKE" run --quiet --force --out "$OUT/N$n-eta$on" \
      --set model.blocks="$n" --set model.l="$l" --set model.viscosity="$eta" \
      --set integrator.dt=0.005 \
      --set run.events="$EVENTS" --set run.transient_events="$TRANSIENT" &
  done
done
wait
"$PYTHON" analysis/plot_coupling_viscosity.py "$OUT" --out "$OUT/large_events.png"
