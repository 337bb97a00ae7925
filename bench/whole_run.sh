#!/usr/bin/env bash
# Goal 1 of the performance issue: the wall clock of a whole `bkquake run` (start-up, the
# transient, the events, every output file) against the naive full-chain integration of
# the same scene and the same events (build/naive_chain, bench/naive_chain.cpp), timed
# side by side: the two alternate, A B A B ..., and the ratio is taken pair by pair, so a
# drift of the shared machine's speed falls on both. Prints each pair and the medians of
# the wall-clock ratio and of the CPU-time (user + sys) ratio, which a loaded machine
# disturbs less.
#
#   bench/whole_run.sh [ROUNDS=3] [N...]          (default N: 100 1000)
#
# Scene: the built-in default (carlson-langer, l = 10, alpha = 2.5, sigma = 0.01, rk4 at
# dt = 0.01, 1000 transient events) with model.blocks = N and run.events = $EVENTS
# (default 100000). The naive program takes about 3 s at N = 100 and 30 s at N = 1000.
# Environment: BKQUAKE (default build/bkquake), NAIVE (default build/naive_chain),
# EVENTS, EXTRA (more --set arguments for both, e.g. "--set output.catalog=none"),
# TRANSITIONS (default "step located": the bkquake run is timed with each
# integrator.transitions mode at the scene's dt, against one naive run per round, which
# integrates with its transitions at the step; MODE@DT runs bkquake at integrator.dt = DT,
# e.g. TRANSITIONS="step located@0.03", the naive run keeping the scene's dt).
set -euo pipefail

cd "$(dirname "$0")/.."
BKQUAKE=${BKQUAKE:-build/bkquake}
NAIVE=${NAIVE:-build/naive_chain}
EVENTS=${EVENTS:-100000}
EXTRA=${EXTRA:-}
TRANSITIONS=${TRANSITIONS:-step located}
rounds=${1:-3}
shift || true
if [[ $# -eq 0 ]]; then set -- 100 1000; fi
for exe in "$BKQUAKE" "$NAIVE"; do
  if [[ ! -x $exe ]]; then
    echo "whole_run.sh: $exe not found; build it (scripts/build.sh) or set BKQUAKE / NAIVE" >&2
    exit 2
  fi
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Runs the command given as arguments, output discarded; prints its wall time and its CPU
# time (user + sys) in seconds.
measure() {
  local TIMEFORMAT='%R %U %S' t
  t=$({ time "$@" >/dev/null; } 2>&1)
  awk -v t="$t" 'BEGIN {split(t, a, " "); printf "%.4f %.4f\n", a[1], a[2] + a[3]}'
}

median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

for n in "$@"; do
  # shellcheck disable=SC2086,SC2206  # EXTRA is a list of words
  sets=(--set "model.blocks=$n" --set "run.events=$EVENTS" $EXTRA)
  declare -A ratios=() cpu_ratios=()
  printf 'N = %s, %s events, %s rounds (seconds)\n' "$n" "$EVENTS" "$rounds"
  printf '%6s %-12s %10s %10s %10s %10s %9s %9s\n' round transitions bkq_wall naive_wall bkq_cpu \
    naive_cpu wall_x cpu_x
  for ((r = 1; r <= rounds; ++r)); do
    read -r bw bc < <(measure "$NAIVE" "${sets[@]}")
    for mode in $TRANSITIONS; do
      mode_sets=(--set "integrator.transitions=${mode%@*}")
      if [[ $mode == *@* ]]; then mode_sets+=(--set "integrator.dt=${mode#*@}"); fi
      read -r aw ac < <(measure "$BKQUAKE" run "${sets[@]}" "${mode_sets[@]}" \
        --out "$work/run" --force --quiet)
      ratios[$mode]+="$(awk -v a="$aw" -v b="$bw" 'BEGIN {printf "%.6f", b / a}') "
      cpu_ratios[$mode]+="$(awk -v a="$ac" -v b="$bc" 'BEGIN {printf "%.6f", b / a}') "
      printf '%6d %-12s %10.3f %10.3f %10.3f %10.3f %9.1f %9.1f\n' "$r" "$mode" "$aw" "$bw" "$ac" \
        "$bc" "$(awk -v a="$aw" -v b="$bw" 'BEGIN {print b / a}')" \
        "$(awk -v a="$ac" -v b="$bc" 'BEGIN {print b / a}')"
    done
  done
  for mode in $TRANSITIONS; do
    # shellcheck disable=SC2086  # the lists are words
    printf 'N = %s, transitions = %s: whole bkquake run is %.1fx (wall) / %.1fx (CPU) faster than the naive integration (medians of %d pairs)\n' \
      "$n" "$mode" "$(printf '%s\n' ${ratios[$mode]} | median)" \
      "$(printf '%s\n' ${cpu_ratios[$mode]} | median)" "$rounds"
  done
  echo
done
