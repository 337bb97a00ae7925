#!/usr/bin/env bash
# Measures a from-scratch build as a fresh machine makes it, with ccache off
# (CCACHE_DISABLE=1) in a new build folder:
#   1. the bkquake target without the optional extras (BKQUAKE_HDF5=OFF, BKQUAKE_MPI=OFF:
#      what ./run.sh builds before ./test.sh installs them): its CPU time (user + sys of every
#      process the build runs, from /usr/bin/time over `cmake --build`) and wall time;
#   2. the extras turned on, as ./test.sh finds them installed: the files the bkquake target
#      then compiles (the extras' own files) and how many of them it compiled before
#      (recompiled objects of the program; 0 is the goal);
#   3. the rest of the targets (all = the three added),
# and the CPU time of every compile and link (scripts/time_units.sh), the costliest printed.
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
configure() {
  cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DBKQUAKE_CCACHE="$here/time_units.sh" \
    "$@" >>"$build/configure.log"
}
timed_build() {  # NAME [cmake --build arguments...]
  local name=$1
  shift
  /usr/bin/time -o "$build/$name.time" -f "%U %S %e" cmake --build "$build" -j2 "$@" \
    >"$build/build-$name.log"
}
cpu() { awk '{u += $1; s += $2} END {printf "%.2f", (u + s) / 60}' "$1"; }
wall() { awk '{print $3}' "$1"; }
configure -DBKQUAKE_HDF5=OFF -DBKQUAKE_MPI=OFF "$@"
timed_build bkquake --target bkquake
configure -DBKQUAKE_HDF5=ON -DBKQUAKE_MPI=ON "$@"
timed_build extras --target bkquake
timed_build rest
b=$(cpu "$build/bkquake.time")
e=$(cpu "$build/extras.time")
r=$(cpu "$build/rest.time")
# Objects compiled with the extras on that the first build had compiled already.
first=$(sed -n 's/.*Building CXX object \(.*\)$/\1/p' "$build/build-bkquake.log" | sort)
second=$(sed -n 's/.*Building CXX object \(.*\)$/\1/p' "$build/build-extras.log" | sort)
again=$(comm -12 <(echo "$first") <(echo "$second") | grep -c . || true)
echo "bkquake target: $b CPU-min (wall $(wall "$build/bkquake.time") s), without the extras"
echo "extras on:      compiled $(echo "$second" | grep -c . || true) files ($e CPU-min):" \
  "$(echo "$second" | sed 's|.*/src/||; s|\.o$||' | tr '\n' ' ')"
echo "                recompiled objects of the program: $again"
echo "all targets:    $(awk -v b="$b" -v e="$e" -v r="$r" 'BEGIN {printf "%.2f", b + e + r}')" \
  "CPU-min (the rest: $r CPU-min, wall $(wall "$build/rest.time") s)"
echo "costliest compiles and links (user + sys s, output):"
awk '{printf "%8.1f  %s\n", $1 + $2, $4}' "$log" | sort -rn | head -25
