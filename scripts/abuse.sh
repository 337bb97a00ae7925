#!/usr/bin/env bash
# The abuse test at scale (tests/regression/test_abuse.cpp: random scenes, damaged files,
# the readers' bounds, links among a run's files, the Python readers on devices and garbage,
# wide stencils under SIGTERM): N cases per seed for each of the given seeds (default: 2000
# cases, seeds 1..5). A failure names the seed, the case and its
# command; rerun it alone with BKQUAKE_ABUSE_SEED=S BKQUAKE_ABUSE_CASES=N.
#   scripts/abuse.sh [CASES] [SEED...]
set -euo pipefail
cd "$(dirname "$0")/.."
cases=${1:-2000}
shift || true
seeds=("$@")
[ ${#seeds[@]} -eq 0 ] && seeds=(1 2 3 4 5)
for seed in "${seeds[@]}"; do
  echo "abuse: seed $seed, $cases cases"
  BKQUAKE_ABUSE_SEED=$seed BKQUAKE_ABUSE_CASES=$cases build/bkquake_tests --gtest_filter='Abuse.*'
done
