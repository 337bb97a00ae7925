#!/usr/bin/env bash
# Installs the Debian packages a build needs when any is missing, then configures and
# builds into build/. Shared by ./run.sh and ./test.sh so a fresh machine needs nothing else.
#
#   scripts/build.sh programs   what users run: the program and the Python module (./run.sh)
#   scripts/build.sh all        everything: also the tests and benchmarks, with every
#                               optional extra (HDF5, MPI) and the test tools (./test.sh)
#
# The optional extras are found at configure time; what a build leaves out is said on its
# "bkquake: left out:" line (e.g. HDF5 catalogues until ./test.sh or apt-get installs
# libhdf5-dev). A compiler cache (ccache) is used when installed.
set -euo pipefail
cd "$(dirname "$0")/.."
what=${1:-all}

programs=(build-essential cmake libboost-program-options-dev libboost-dev libgsl-dev
          python3-dev pybind11-dev python3-numpy python3-matplotlib)
extras=(pkg-config libhdf5-dev python3-h5py libboost-mpi-dev openmpi-bin libopenmpi-dev
        googletest libgtest-dev libbenchmark-dev clang-format python3-pytest python3-pandas
        python3-nbclient python3-nbformat python3-ipykernel mkdocs mkdocs-material)
case $what in
  programs) packages=("${programs[@]}") target=(--target programs) ;;
  all) packages=("${programs[@]}" "${extras[@]}") target=() ;;
  *) echo "scripts/build.sh: expected 'programs' or 'all', got '$what'" >&2; exit 2 ;;
esac
scripts/ensure_packages.sh --no-install-recommends "${packages[@]}"

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" "${target[@]}"
