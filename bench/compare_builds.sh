#!/usr/bin/env bash
# Two builds of the same revision side by side, e.g. the portable default (x86-64-v3) against
# a native one (-DBKQUAKE_NATIVE=ON): events per second of the event engine (bench_events:
# carlson-langer bk at N = 100 and 1000, bkp at N = 100) and block-steps per second of the
# continuous steppers (bench_steppers: rk2, rk4, verlet on the 1000-block thesis chain). The
# two builds' programs alternate, A B A B ..., and the ratio B/A of each rate (per CPU
# second, Google Benchmark's counters) is taken pair by pair, so a drift of a shared
# machine's speed falls on both. Prints each pair and the medians.
#
#   bench/compare_builds.sh A_BUILD_DIR B_BUILD_DIR [ROUNDS=5]
#
# Each build folder needs bench_events and bench_steppers, e.g.
#   cmake -S . -B build && cmake --build build --target bench_events bench_steppers
#   cmake -S . -B build-native -DBKQUAKE_NATIVE=ON
#   cmake --build build-native --target bench_events bench_steppers
# `build/bkquake --version` names the instruction set each was built for.
set -euo pipefail

cd "$(dirname "$0")/.."
A=${1:?usage: bench/compare_builds.sh A_BUILD_DIR B_BUILD_DIR [ROUNDS]}
B=${2:?usage: bench/compare_builds.sh A_BUILD_DIR B_BUILD_DIR [ROUNDS]}
rounds=${3:-5}
for dir in "$A" "$B"; do
  for exe in bench_events bench_steppers; do
    if [[ ! -x $dir/$exe ]]; then
      echo "compare_builds.sh: $dir/$exe not found" >&2
      exit 2
    fi
  done
done

# "name rate" lines of one run of both programs of build folder $1: events/s of the event
# benchmarks, block-steps/s of the stepper benchmarks.
rates() {
  {
    "$1/bench_events" --benchmark_filter='BM_Events/(bk/(100|1000)|bkp/100)/' \
      --benchmark_format=csv 2>/dev/null
    "$1/bench_steppers" --benchmark_filter='BM_Continuous/.*/1000$' --benchmark_min_time=0.5 \
      --benchmark_format=csv 2>/dev/null
  } | awk -F, '
      /^name,/ { for (i = 1; i <= NF; ++i) head[i] = $i; next }
      /^"BM_/ {
        want = $1 ~ /BM_Events/ ? "\"events\"" : "\"block_steps\""
        for (i = 1; i <= NF; ++i) if (head[i] == want) {
          name = $1; gsub(/"/, "", name); sub(/\/min_time:.*/, "", name)
          print name, $i
        }
      }'
}

all=$(mktemp)
trap 'rm -f "$all"' EXIT
for ((r = 1; r <= rounds; ++r)); do
  a=$(rates "$A")
  b=$(rates "$B")
  join <(sort <<<"$a") <(sort <<<"$b") |
    awk -v r="$r" '{ printf "round %d %-28s A %.4g B %.4g B/A %.3f\n", r, $1, $2, $3, $3 / $2 }' |
    tee -a "$all"
done
for dir in "$A" "$B"; do
  [[ -x $dir/bkquake ]] && echo "$dir: $("$dir"/bkquake --version)"
done
echo "median B/A over $rounds rounds, and the rates of that pair (events/s for BM_Events,"
echo "block-steps/s for BM_Continuous):"
for name in $(awk '{ print $3 }' "$all" | sort -u); do
  awk -v s="$name" '$3 == s { print $9, $5, $7 }' "$all" | sort -n |
    awk -v s="$name" '{ r[NR] = $1; a[NR] = $2; b[NR] = $3 }
      END { m = int((NR + 1) / 2); printf "%-28s B/A %.3f (range %.3f-%.3f)  A %.4g  B %.4g\n", s, r[m], r[1], r[NR], a[m], b[m] }'
done
