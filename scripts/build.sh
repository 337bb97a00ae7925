#!/usr/bin/env bash
# Installs the Debian packages bkquake needs when any is missing, then configures and
# builds into build/. Shared by ./run.sh and ./test.sh so a fresh machine needs nothing else.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake libboost-program-options-dev libboost-dev libgsl-dev
          googletest libgtest-dev libbenchmark-dev clang-format python3-numpy python3-matplotlib
          libboost-mpi-dev openmpi-bin libopenmpi-dev libhdf5-dev python3-h5py)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "bkquake: installing missing packages: ${missing[*]}" >&2
  sudo=""
  [[ $(id -u) -ne 0 ]] && sudo="sudo"
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
