#!/usr/bin/env bash
# Measures a from-scratch build: CPU time (user + sys of every process the build runs, from
# /usr/bin/time over `cmake --build`) of the bkquake target, then of the rest of the targets
# (all = the two added), with ccache off (CCACHE_DISABLE=1) in a new build folder; and the
# CPU time of every compile and link (scripts/time_units.sh), the costliest printed.
#   scripts/build_times.sh [SOURCE_DIR] [BUILD_DIR] [extra cmake arguments...]
# Costs the whole build's CPU time: on a shared machine run it rarely.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
src=${1:-$here/..}
build=${2:-/tmp/bkquake-build-times}
shift $(($# < 2 ? $# : 2))
rm -rf "$build"
mkdir -p "$build"
log=$build/units.log
export CCACHE_DISABLE=1 BKQUAKE_UNIT_LOG=$log
cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DBKQUAKE_CCACHE="$here/time_units.sh" \
  "$@" >"$build/configure.log"
cpu() { awk '{u += $1; s += $2} END {printf "%.2f", (u + s) / 60}' "$1"; }
/usr/bin/time -o "$build/bkquake.time" -f "%U %S %e" cmake --build "$build" -j2 --target bkquake \
  >"$build/build-bkquake.log"
/usr/bin/time -o "$build/rest.time" -f "%U %S %e" cmake --build "$build" -j2 >"$build/build-rest.log"
b=$(cpu "$build/bkquake.time")
r=$(cpu "$build/rest.time")
echo "bkquake target: $b CPU-min (wall $(awk '{print $3}' "$build/bkquake.time") s)"
echo "all targets:    $(awk -v b="$b" -v r="$r" 'BEGIN {printf "%.2f", b + r}') CPU-min" \
  "(the rest: $r CPU-min, wall $(awk '{print $3}' "$build/rest.time") s)"
echo "costliest compiles and links (user + sys s, output):"
awk '{printf "%8.1f  %s\n", $1 + $2, $4}' "$log" | sort -rn | head -25
