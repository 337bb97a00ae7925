#!/usr/bin/env bash
# Builds bkquake into build/ (installing missing Debian packages first) and runs a scene.
# With arguments they go to `bkquake run` as they are: ./run.sh SCENE --set k=v --out DIR.
set -euo pipefail
cd "$(dirname "$0")"
scripts/build.sh  # apt-get installs any missing Debian package, then cmake builds into build/

if (($# == 0)); then
  # The default run: bkquake's built-in default scene (the Carlson-Langer reference,
  # event-driven, the same as data/scenes/carlson-langer.ini). --force so that running
  # ./run.sh again simply redoes it instead of refusing to overwrite the finished run.
  build/bkquake run --out runs/default --force
  if [[ -f analysis/plot_gr.py ]]; then
    /usr/bin/python3 analysis/plot_gr.py runs/default --out runs/default/gr.png &&
      echo "Gutenberg-Richter plot: runs/default/gr.png"
  fi
  exit 0
fi
exec build/bkquake run "$@"
