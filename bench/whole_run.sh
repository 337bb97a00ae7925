#!/usr/bin/env bash
# Goal 1 of the performance issue: the wall clock of a whole `bkquake run` (start-up, the
# transient, the events, every output file) against the naive full-chain integration of
# the same scene and the same events (build/naive_chain, bench/naive_chain.cpp), timed
# side by side: the two alternate, A B A B ..., and the ratio is taken pair by pair, so a
# drift of the shared machine's speed falls on both. Prints each pair and the median.
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

# Runs the command given as arguments, output discarded; prints its wall time in seconds.
wall() {
  local t0 t1
  t0=$(date +%s.%N)
  "$@" >/dev/null
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.6f\n", b - a}'
}

median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

for n in "$@"; do
  # shellcheck disable=SC2086  # EXTRA is a list of words
  sets=(--set "model.blocks=$n" --set "run.events=$EVENTS" $EXTRA)
  ratios=()
  printf 'N = %s, %s events, %s rounds\n' "$n" "$EVENTS" "$rounds"
  printf '%8s %12s %12s %10s\n' round bkquake_s naive_s ratio
  for ((r = 1; r <= rounds; ++r)); do
    a=$(wall "$BKQUAKE" run "${sets[@]}" --out "$work/run" --force --quiet)
    b=$(wall "$NAIVE" "${sets[@]}")
    ratio=$(awk -v a="$a" -v b="$b" 'BEGIN {printf "%.6f\n", b / a}')
    ratios+=("$ratio")
    printf '%8d %12.3f %12.3f %10.1f\n' "$r" "$a" "$b" "$ratio"
  done
  printf 'N = %s: whole bkquake run is %.1fx faster than the naive integration (median of %d pairs)\n\n' \
    "$n" "$(printf '%s\n' "${ratios[@]}" | median)" "$rounds"
done
