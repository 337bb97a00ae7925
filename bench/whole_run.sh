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
# EVENTS, EXTRA (more --set arguments for both, e.g. "--set output.catalog=none").
set -euo pipefail

cd "$(dirname "$0")/.."
BKQUAKE=${BKQUAKE:-build/bkquake}
NAIVE=${NAIVE:-build/naive_chain}
EVENTS=${EVENTS:-100000}
EXTRA=${EXTRA:-}
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
  ratios=() cpu_ratios=()
  printf 'N = %s, %s events, %s rounds (seconds)\n' "$n" "$EVENTS" "$rounds"
  printf '%6s %10s %10s %10s %10s %9s %9s\n' round bkq_wall naive_wall bkq_cpu naive_cpu wall_x cpu_x
  for ((r = 1; r <= rounds; ++r)); do
    read -r aw ac < <(measure "$BKQUAKE" run "${sets[@]}" --out "$work/run" --force --quiet)
    read -r bw bc < <(measure "$NAIVE" "${sets[@]}")
    ratios+=("$(awk -v a="$aw" -v b="$bw" 'BEGIN {printf "%.6f\n", b / a}')")
    cpu_ratios+=("$(awk -v a="$ac" -v b="$bc" 'BEGIN {printf "%.6f\n", b / a}')")
    printf '%6d %10.3f %10.3f %10.3f %10.3f %9.1f %9.1f\n' "$r" "$aw" "$bw" "$ac" "$bc" \
      "${ratios[-1]}" "${cpu_ratios[-1]}"
  done
  printf 'N = %s: whole bkquake run is %.1fx (wall) / %.1fx (CPU) faster than the naive integration (medians of %d pairs)\n\n' \
    "$n" "$(printf '%s\n' "${ratios[@]}" | median)" "$(printf '%s\n' "${cpu_ratios[@]}" | median)" "$rounds"
done
