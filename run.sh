#!/usr/bin/env bash
# Builds bkquake into build/ (installing missing Debian packages first) and runs a scene.
# With arguments they go to `bkquake run` as they are: ./run.sh SCENE --set k=v --out DIR.
set -euo pipefail
cd "$(dirname "$0")"

packages=(build-essential cmake libboost-program-options-dev libboost-dev libgsl-dev
          googletest libgtest-dev libbenchmark-dev python3-numpy python3-matplotlib)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "run.sh: installing missing packages: ${missing[*]}" >&2
  sudo=""
  [[ $(id -u) -ne 0 ]] && sudo="sudo"
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"

if (($# == 0)); then
  # The default run: bkquake's built-in default scene (the Carlson-Langer reference,
  # event-driven, the same as data/scenes/carlson-langer.ini). --force so that running
  # ./run.sh again simply redoes it instead of refusing to overwrite the finished run.
  set -- --out runs/default --force
fi
exec build/bkquake run "$@"
