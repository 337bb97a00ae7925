#!/usr/bin/env bash
# Continuous block-steps per second of rk2, rk4 and verlet (build/bench_steppers, thesis
# Table 3.1 chain, 1000 blocks) for this build against another revision's build of the
# same benchmark, side by side: the two programs alternate, OLD NEW OLD NEW ..., and the
# ratio new/old of each scheme's rate (block-steps per CPU second) is taken pair by pair,
# so a drift of the shared machine's speed falls on both. Prints each pair and the medians.
#
#   bench/compare_steppers.sh OLD_BENCH [ROUNDS=5]
#
# OLD_BENCH: bench_steppers built from the other revision with this revision's
# bench/bench_steppers.cpp (for example: git worktree add /tmp/base main; copy
# bench/bench_steppers.cpp there; cmake -S /tmp/base -B /tmp/base/build
# -DCMAKE_BUILD_TYPE=Release; cmake --build /tmp/base/build --target bench_steppers).
# NEW (environment) defaults to build/bench_steppers.
set -euo pipefail

cd "$(dirname "$0")/.."
OLD=${1:?usage: bench/compare_steppers.sh OLD_BENCH [ROUNDS]}
NEW=${NEW:-build/bench_steppers}
rounds=${2:-5}
for exe in "$OLD" "$NEW"; do
  if [[ ! -x $exe ]]; then
    echo "compare_steppers.sh: $exe not found" >&2
    exit 2
  fi
done

# Prints "scheme rate" lines (block-steps/s) of one run of a benchmark program.
rates() {
  "$1" --benchmark_min_time=0.3 --benchmark_format=csv 2>/dev/null |
    awk -F, '/^"BM_Continuous/ {
      split($1, name, "/"); for (i = 1; i <= NF; ++i) if (head[i] == "\"block_steps\"") print name[2] "/" substr(name[3], 1, length(name[3]) - 1), $i
    } /^name,/ { for (i = 1; i <= NF; ++i) head[i] = $i }'
}

all=$(mktemp)
trap 'rm -f "$all"' EXIT
for ((r = 1; r <= rounds; ++r)); do
  old=$(rates "$OLD")
  new=$(rates "$NEW")
  join <(sort <<<"$old") <(sort <<<"$new") |
    awk -v r="$r" '{ printf "round %d %-11s old %.3g new %.3g new/old %.3f\n", r, $1, $2, $3, $3 / $2 }' |
    tee -a "$all"
done
echo "median new/old and rates over $rounds rounds:"
for scheme in $(awk '{ print $3 }' "$all" | sort -u); do
  awk -v s="$scheme" '$3 == s { print $9, $5, $7 }' "$all" | sort -n |
    awk -v s="$scheme" '{ r[NR] = $1; o[NR] = $2; n[NR] = $3 }
      END { m = int((NR + 1) / 2); printf "%-11s new/old %.3f (range %.3f-%.3f)  old %.3g  new %.3g block-steps/s\n", s, r[m], r[1], r[NR], o[m], n[m] }'
done
