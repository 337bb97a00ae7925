#!/usr/bin/env bash
# Builds bkquake into build/ (installing missing Debian packages first) and runs the
# test suite with ctest; extra arguments go to ctest (e.g. -R Scene, -L numeric).
set -euo pipefail
cd "$(dirname "$0")"

packages=(build-essential cmake libboost-program-options-dev libboost-dev libgsl-dev
          googletest libgtest-dev libbenchmark-dev python3-numpy python3-matplotlib)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "test.sh: installing missing packages: ${missing[*]}" >&2
  sudo=""
  [[ $(id -u) -ne 0 ]] && sudo="sudo"
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"

cd build
ctest --output-on-failure -j2 "$@"
