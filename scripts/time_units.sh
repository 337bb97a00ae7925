#!/usr/bin/env bash
# Compiler launcher that records the CPU time of every compile and link: configure a build
# folder with -DBKQUAKE_CCACHE=$PWD/scripts/time_units.sh (the launcher slot ccache uses) and
# BKQUAKE_UNIT_LOG=FILE in the environment; each line of FILE is
#   user_s sys_s wall_s output_file
# Used to find what dominates a from-scratch build (scripts/build_times.sh sums it).
set -u
log=${BKQUAKE_UNIT_LOG:-/dev/null}
out=unknown
prev=""
for a in "$@"; do
  [[ $prev == -o ]] && out=$a
  prev=$a
done
exec /usr/bin/time -a -o "$log" -f "%U %S %e $out" "$@"
