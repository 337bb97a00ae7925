#!/usr/bin/env bash
# Builds what users run into build/ (the program and the Python module, installing missing
# Debian packages first; ./test.sh builds the rest) and runs a scene.
# With arguments they go to `bkquake run` as they are: ./run.sh SCENE --set k=v --out DIR.
set -euo pipefail
cd "$(dirname "$0")"
scripts/build.sh programs  # apt-get installs any missing package, then cmake builds into build/

if (($# == 0)); then
  # The default run: bkquake's built-in default scene (the Carlson-Langer reference,
  # event-driven, the same as data/scenes/carlson-langer.ini). --force so that running
  # ./run.sh again simply redoes it instead of refusing to overwrite the finished run.
  build/bkquake run --out runs/default --force
  if [[ -f analysis/plot_gr.py ]]; then
    PYTHONPATH=build/python${PYTHONPATH:+:$PYTHONPATH} /usr/bin/python3 analysis/plot_gr.py runs/default --out runs/default/gr.png &&
      echo "Gutenberg-Richter plot: runs/default/gr.png"
  fi
  exit 0
fi
exec build/bkquake run "$@"
