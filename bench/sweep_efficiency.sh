#!/usr/bin/env bash
# How a sweep of independent points scales from one rank to K: runs
# bench/sweep_efficiency.ini without mpirun and with `mpirun -n K` in turn, REPEATS times
# each (default 3), and prints wall and CPU seconds of each run and the ratio
# T_K / T_1 per pair (the goal is <= 1/(0.9 K)), with the dispatcher's line (messages,
# idle at the end). Pairs taken in turn keep the ratio meaningful on a noisy machine. The
# yardstick: two copies of the one-rank sweep run side by side (no MPI at all); half their
# wall time over the one-rank time is what the machine allows a perfect split of the work
# (column `ceiling`; 0.5 on K = 2 idle cores).
#   bench/sweep_efficiency.sh [K] [REPEATS] [extra sweep options, e.g. --set run.events=20000]
set -euo pipefail
cd "$(dirname "$0")/.."
k=${1:-2}
repeats=${2:-3}
shift $(($# < 2 ? $# : 2))
bin=${BKQUAKE:-build/bkquake}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
[[ $(id -u) -eq 0 ]] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

timed() {  # timed LABEL COMMAND...: prints "wall cpu" of the command
  local out=$tmp/$1
  rm -rf "$out"
  /usr/bin/time -f "%e %U %S" -o "$tmp/time" "${@:2}" --out "$out" >"$tmp/log" 2>&1
  grep -h 'dispatcher' "$tmp/log" >&2 || true
  awk '{printf "%.2f %.2f\n", $1, $2 + $3}' "$tmp/time"
}

side_by_side() {  # K one-rank sweeps at once: prints the wall seconds of the slowest
  local start end
  start=$(date +%s.%N)
  for ((j = 1; j <= k; j++)); do
    rm -rf "$tmp/copy$j"
    "$bin" sweep bench/sweep_efficiency.ini "$@" --out "$tmp/copy$j" >/dev/null 2>&1 &
  done
  wait
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f\n", b - a }'
}

printf '%-6s %8s %8s %8s %8s %8s %8s\n' pair wall_1 cpu_1 "wall_$k" "cpu_$k" ratio ceiling
for ((i = 1; i <= repeats; i++)); do
  read -r w1 c1 < <(timed one "$bin" sweep bench/sweep_efficiency.ini "$@")
  read -r wk ck < <(timed many mpirun -n "$k" --oversubscribe "$bin" sweep bench/sweep_efficiency.ini "$@")
  wp=$(side_by_side "$@")
  printf '%-6s %8s %8s %8s %8s %8.3f %8.3f\n' "$i" "$w1" "$c1" "$wk" "$ck" \
    "$(awk -v a="$wk" -v b="$w1" 'BEGIN { print a / b }')" \
    "$(awk -v a="$wp" -v b="$w1" -v k="$k" 'BEGIN { print a / k / b }')"
done
awk -v k="$k" 'BEGIN { printf "goal: ratio <= %.3f\n", 1 / (0.9 * k) }'
