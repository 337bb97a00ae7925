#!/usr/bin/env bash
# Reproduce the Carlson-Langer magnitude distributions (Carlson & Langer 1989; Carlson,
# Langer, Shaw & Tang 1991) over alpha = 1, 2, 2.5, 3 and N = 100, 200 (l = 10,
# sigma = 0.01, clst91 friction, event-driven, rk4 dt = 0.01).
#
#   analysis/run_carlson_langer.sh [EVENTS]
#
# For every data/scenes/cl-l10-*.ini it runs EVENTS events (default 10^6) after the
# scene's transient into runs/cl/<scene>/, fits Gutenberg-Richter with `bkquake fit`
# twice: on the automatic window (docs/how-to/fit-window.md) -> fit_auto.txt/.json, and on a fixed
# scaling-region window chosen by eye from the histograms (MU_MIN..MU_MAX, default
# -7.6..-2.0; see data/reference/carlson-langer-runs.md) -> fit_eye.txt/.json, and
# overlays the N = 100 runs in runs/cl/gr_alpha.png with analysis/plot_gr.py.
#
# Environment: BKQUAKE (the binary; default build/bkquake, build it with ./run.sh or
# cmake), PYTHON (default /usr/bin/python3: Debian's python with numpy and matplotlib;
# the python3 first on PATH may lack them), MU_MIN, MU_MAX (the by-eye window).
# Existing finished runs are replaced (--force).
set -euo pipefail

cd "$(dirname "$0")/.."
EVENTS=${1:-1000000}
BKQUAKE=${BKQUAKE:-build/bkquake}
PYTHON=${PYTHON:-/usr/bin/python3}
MU_MIN=${MU_MIN:--7.6}
MU_MAX=${MU_MAX:--2.0}
OUT=runs/cl

if [[ ! -x $BKQUAKE ]]; then
  echo "run_carlson_langer.sh: $BKQUAKE not found; build it (./run.sh) or set BKQUAKE" >&2
  exit 2
fi
mkdir -p "$OUT"

for scene in data/scenes/cl-l10-a*-n*.ini; do
  name=$(basename "$scene" .ini)
  dir=$OUT/$name
  echo "== $name: $EVENTS events"
  "$BKQUAKE" run "$scene" --set run.events="$EVENTS" --out "$dir" --force --quiet
  "$BKQUAKE" fit "$dir/catalog.csv" --json "$dir/fit_auto.json" | tee "$dir/fit_auto.txt"
  "$BKQUAKE" fit "$dir/catalog.csv" --mu-min "$MU_MIN" --mu-max "$MU_MAX" \
    --json "$dir/fit_eye.json" >"$dir/fit_eye.txt"
  grep -E '^(window|b  binned)' "$dir/fit_eye.txt" | sed 's/^/  by eye: /'
done

if [[ -f analysis/plot_gr.py ]]; then
  "$PYTHON" analysis/plot_gr.py "$OUT"/cl-l10-a1-n100 "$OUT"/cl-l10-a2-n100 \
    "$OUT"/cl-l10-a2.5-n100 "$OUT"/cl-l10-a3-n100 --out "$OUT/gr_alpha.png"
  "$PYTHON" analysis/plot_gr.py "$OUT"/cl-l10-a1-n200 "$OUT"/cl-l10-a2-n200 \
    "$OUT"/cl-l10-a2.5-n200 "$OUT"/cl-l10-a3-n200 --out "$OUT/gr_alpha_n200.png"
  echo "plots: $OUT/gr_alpha.png (N = 100), $OUT/gr_alpha_n200.png (N = 200)"
else
  echo "run_carlson_langer.sh: analysis/plot_gr.py missing, no plot" >&2
fi
