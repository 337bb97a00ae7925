#!/usr/bin/env bash
# Builds everything into build/ (the program, the Python module, the tests and benchmarks,
# installing missing Debian packages first) and runs the test suite with ctest; extra
# arguments go to ctest (e.g. -R Scene).
set -euo pipefail
cd "$(dirname "$0")"
scripts/build.sh all  # apt-get installs any missing package, then cmake builds into build/

cd build
ctest --output-on-failure -j2 "$@"
