#!/usr/bin/env bash
# The BK lattice's magnitude-frequency distributions beside the papers
# (docs/explanation/lattice.md): event-driven runs of the shipped lattice scenes
# (data/scenes/lattice/; Carlson-Langer units, l = 3, sigma = 0.01, clst91 friction,
# rk4 dt = 0.01, free edges) into runs/lattice/<name>/, then `bkquake fit` on each
# (fit.json: b on the automatic window and the excess of large events) and the figures of
# analysis/plot_lattice.py:
#   nn16-a2                  nearest neighbours, 16 x 16, alpha = 2
#   nn32-a2-s1, nn32-a2-s2   nearest neighbours, 32 x 32, alpha = 2, two seeds
#   nn64-a2                  nearest neighbours, 64 x 64, alpha = 2 (the shipped scene)
#   nn32-a1, nn32-a1.5, nn32-a3   nearest neighbours, 32 x 32, alpha = 1, 1.5, 3
#   nn32-l10-a2.5            nearest neighbours, 32 x 32, the chain's reference l = 10, alpha = 2.5
#   pw32-a2                  1/r^3 springs within r <= 4, 32 x 32, alpha = 2 (the shipped scene)
#   pw32-a1, pw32-a1.5       the same at alpha = 1 and 1.5
#   co32                     the continuous scene (nu = 0.01, 3000 time units)
#
#   analysis/run_lattice.sh [NAME ...]     (default: all of the above, one after the other)
#
# Environment: BKQUAKE (default build/bkquake), PYTHON (default /usr/bin/python3). Existing
# runs are replaced (--force). About 30 CPU-minutes in all (2026-11-26).
set -euo pipefail

cd "$(dirname "$0")/.."
BKQUAKE=${BKQUAKE:-build/bkquake}
PYTHON=${PYTHON:-/usr/bin/python3}
OUT=runs/lattice
S=data/scenes/lattice
if [[ ! -x $BKQUAKE ]]; then
  echo "run_lattice.sh: $BKQUAKE not found; build it (./run.sh) or set BKQUAKE" >&2
  exit 2
fi
NAMES=("$@")
[[ ${#NAMES[@]} -gt 0 ]] || NAMES=(nn16-a2 nn32-a2-s1 nn32-a2-s2 nn64-a2 nn32-a1 nn32-a1.5 nn32-a3 nn32-l10-a2.5 pw32-a2
           pw32-a1 pw32-a1.5 co32)
NN=$S/bk-nearest-l3-a2-64x64.ini
SMALL=(--set model.blocks=32 --set model.rows=32 --set run.transient_events=20000
       --set run.events=100000)
mkdir -p "$OUT"
for name in "${NAMES[@]}"; do
  case $name in
    nn16-a2) args=("$NN" --set model.blocks=16 --set model.rows=16 --set run.transient_events=5000
                   --set run.events=100000) ;;
    nn32-a2-s1) args=("$NN" "${SMALL[@]}" --set run.seed=1) ;;
    nn32-a2-s2) args=("$NN" "${SMALL[@]}" --set run.seed=2) ;;
    nn64-a2) args=("$NN") ;;
    nn32-a1) args=("$NN" "${SMALL[@]}" --set friction.alpha=1) ;;
    nn32-a1.5) args=("$NN" "${SMALL[@]}" --set friction.alpha=1.5) ;;
    nn32-a3) args=("$NN" "${SMALL[@]}" --set friction.alpha=3) ;;
    nn32-l10-a2.5) args=("$NN" "${SMALL[@]}" --set model.l=10 --set friction.alpha=2.5) ;;
    pw32-a2) args=("$S/bk-power3-r4-l3-a2-32x32.ini") ;;
    pw32-a1) args=("$S/bk-power3-r4-l3-a2-32x32.ini" --set friction.alpha=1
                   --set run.transient_events=60000 --set run.events=100000) ;;
    pw32-a1.5) args=("$S/bk-power3-r4-l3-a2-32x32.ini" --set friction.alpha=1.5
                     --set run.transient_events=30000 --set run.events=100000) ;;
    co32) args=("$S/bk-continuous-l3-a2-32x32.ini") ;;
    *) echo "run_lattice.sh: unknown run '$name'" >&2; exit 2 ;;
  esac
  echo "== $name: bkquake run ${args[*]}"
  "$BKQUAKE" run "${args[@]}" --quiet --force --out "$OUT/$name"
  "$BKQUAKE" fit "$OUT/$name" --json "$OUT/$name/fit.json" > "$OUT/$name/fit.txt"
  "$PYTHON" analysis/plot_lattice.py "$OUT/$name" --out "$OUT/$name/lattice.png" || true
done
