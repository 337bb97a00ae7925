#!/usr/bin/env bash
# Builds bkquake into build/ (installing missing Debian packages first) and runs the
# test suite with ctest; extra arguments go to ctest (e.g. -R Scene).
set -euo pipefail
cd "$(dirname "$0")"
scripts/build.sh  # apt-get installs any missing Debian package, then cmake builds into build/

cd build
ctest --output-on-failure -j2 "$@"
