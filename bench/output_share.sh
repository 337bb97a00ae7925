#!/usr/bin/env bash
# Goals 4 and 5 of the performance issue: the share of a whole `bkquake run` spent writing
# the event catalogue (output.catalog = csv, hdf5) and on the end-of-run fit.
#
#   bench/output_share.sh [ROUNDS=5]
#
# Each round runs the same scene four times, one after the other: output.catalog = none,
# csv, hdf5, hdf5-deflate. A format's share of its run is 1 - cpu(none) / cpu(format), taken round by
# round (so a drift of the shared machine's speed falls on all alike); the median of
# the rounds is printed. CPU time = user + sys of the whole process (bash's `time`), which
# a loaded machine disturbs less than wall time. The fit's share: build/fit_time repeats
# the end-of-run fit on the run's histogram, its time per fit over cpu(csv), the default
# run's. Also prints the catalogue's size per 10^6 events for each format.
#
# Scene: the built-in default (./run.sh's: carlson-langer, N = 100, 1000 transient events)
# with run.events = $EVENTS (default 300000). Environment: BKQUAKE (default build/bkquake),
# FIT_TIME (default build/fit_time), EVENTS, EXTRA (more --set arguments for every run).
set -euo pipefail

cd "$(dirname "$0")/.."
BKQUAKE=${BKQUAKE:-build/bkquake}
FIT_TIME=${FIT_TIME:-build/fit_time}
EVENTS=${EVENTS:-300000}
EXTRA=${EXTRA:-}
rounds=${1:-5}
for exe in "$BKQUAKE" "$FIT_TIME"; do
  if [[ ! -x $exe ]]; then
    echo "output_share.sh: $exe not found; build it (scripts/build.sh) or set BKQUAKE / FIT_TIME" >&2
    exit 2
  fi
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Runs bkquake with output.catalog = $1 into $work/$1; prints its CPU seconds (user + sys).
# An old bkquake that does not know hdf5-deflate gets 0 (its column then reads "-").
cpu_run() {
  local TIMEFORMAT='%U %S' t
  # shellcheck disable=SC2086  # EXTRA is a list of words
  t=$({ time "$BKQUAKE" run --set "run.events=$EVENTS" --set "output.catalog=$1" $EXTRA \
    --out "$work/$1" --force --quiet >/dev/null 2>&1 || echo FAILED; } 2>&1)
  if [[ $t == *FAILED* ]]; then
    echo 0
    return
  fi
  awk -v t="$t" 'BEGIN {split(t, a, " "); printf "%.4f\n", a[1] + a[2]}'
}

median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
share() { awk -v a="$1" -v b="$2" 'BEGIN {if (b > 0) printf "%.4f\n", 1 - a / b; else print "-"}'; }
pct() { awk -v s="$1" -v d="${2:-1}" 'BEGIN {if (s == "-") print "-"; else printf "%.*f", d, 100 * s}'; }

printf 'default scene, %s events, %s rounds (CPU seconds of whole runs)\n' "$EVENTS" "$rounds"
printf '%6s %8s %8s %8s %8s %8s %8s %8s\n' round none csv hdf5 h5-defl 'csv%' 'hdf5%' 'defl%'
csv_shares=() h5_shares=() z_shares=() csv_cpus=()
for ((r = 1; r <= rounds; ++r)); do
  none=$(cpu_run none)
  csv=$(cpu_run csv)
  h5=$(cpu_run hdf5)
  z=$(cpu_run hdf5-deflate)
  csv_shares+=("$(share "$none" "$csv")")
  h5_shares+=("$(share "$none" "$h5")")
  z_shares+=("$(share "$none" "$z")")
  csv_cpus+=("$csv")
  printf '%6d %8.3f %8.3f %8.3f %8.3f %8s %8s %8s\n' "$r" "$none" "$csv" "$h5" "$z" \
    "$(pct "${csv_shares[-1]}")" "$(pct "${h5_shares[-1]}")" "$(pct "${z_shares[-1]}")"
done
per_million() {
  if [[ -f $1 ]]; then awk -v b="$(stat -c %s "$1")" -v e="$EVENTS" 'BEGIN {printf "%.1f", b / e}'; else echo -; fi
}
med() {  # the median of the numbers among the arguments, "-" when there are none
  local nums
  nums=$(printf '%s\n' "$@" | grep -v '^-$' || true)
  if [[ -n $nums ]]; then median <<<"$nums"; else echo -; fi
}
printf 'catalogue share of a run (median): csv %s %%, hdf5 %s %%, hdf5-deflate %s %%, none 0 %%\n' \
  "$(pct "$(med "${csv_shares[@]}")")" "$(pct "$(med "${h5_shares[@]}")")" \
  "$(pct "$(med "${z_shares[@]}")")"
per_h5z=$(per_million "$work/hdf5-deflate/catalog.h5")
printf 'catalogue size per 10^6 events: csv %s MB, hdf5 %s MB, hdf5-deflate %s MB\n' \
  "$(per_million "$work/csv/catalog.csv")" "$(per_million "$work/hdf5/catalog.h5")" "$per_h5z"
fit_line=$("$FIT_TIME" "$work/csv" 20)
fit_s=$(awk '{print $2}' <<<"$fit_line")
echo "$fit_line"
printf 'end-of-run fit: %.2f ms, %s %% of the run (csv, median %.3f s)\n' \
  "$(awk -v s="$fit_s" 'BEGIN {print 1000 * s}')" \
  "$(pct "$(awk -v f="$fit_s" -v r="$(printf '%s\n' "${csv_cpus[@]}" | median)" 'BEGIN {print f / r}')" 2)" \
  "$(printf '%s\n' "${csv_cpus[@]}" | median)"
