#!/usr/bin/env bash
# The cost of the tabulated friction law (friction.law = table) against its number of rows:
# events/s of the same event-driven run on tables of 10, 10^3 and 10^5 rows, and of
# several binaries side by side (e.g. before and after a change, or a portable and a
# native build). Runs alternate within each round (rows x binaries), so a drift of the
# shared machine's speed falls on all alike; the medians over the rounds are printed.
#
#   bench/table_rows.sh [ROUNDS=3] [ROWS...]            (default ROWS: 10 1000 100000)
#
# The table is the same law at every row count: friction 0.99 (1 - 9 y) for speeds y in
# [0, 0.1] (linear, so linear interpolation reproduces it whatever the rows; velocity
# weakening about as steep as Carlson-Langer's alpha = 2.5), the thesis law scaled to
# meet it beyond. So the events are the same physics and only the lookup's
# cost differs. Scene: the built-in default with friction.law = table, model.blocks = $N
# (default 100), run.events = $EVENTS (default 2000), run.transient_events = 200,
# output.catalog = none. Two rates per run: events per CPU second (user + sys of the whole
# process, start-up and the table's reading included; a loaded machine disturbs it less)
# and summary.json's events_per_second (wall clock of the run alone).
# Environment: BKQUAKE (one binary or several separated by spaces; default build/bkquake),
# N, EVENTS, EXTRA (more --set arguments for every run).
set -euo pipefail

cd "$(dirname "$0")/.."
read -r -a binaries <<<"${BKQUAKE:-build/bkquake}"
N=${N:-100}
EVENTS=${EVENTS:-2000}
EXTRA=${EXTRA:-}
rounds=${1:-3}
shift || true
if [[ $# -eq 0 ]]; then set -- 10 1000 100000; fi
for exe in "${binaries[@]}"; do
  if [[ ! -x $exe ]]; then
    echo "table_rows.sh: $exe not found; build it (scripts/build.sh) or set BKQUAKE" >&2
    exit 2
  fi
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

for rows in "$@"; do
  awk -v n="$rows" 'BEGIN {
    print "speed,friction"
    for (i = 0; i < n; ++i) { y = 0.1 * i / (n - 1); printf "%.17g,%.17g\n", y, 0.99 * (1 - 9 * y) }
  }' >"$work/table_$rows.csv"
done

median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

printf "N = %s, %s events, %s rounds\n" "$N" "$EVENTS" "$rounds"
printf '%6s %8s %12s %12s  %s\n' round rows events/cpu-s events/s binary
TIMEFORMAT='%U %S'
declare -A results
for ((r = 1; r <= rounds; ++r)); do
  for rows in "$@"; do
    for b in "${!binaries[@]}"; do
      exe=${binaries[$b]}
      # shellcheck disable=SC2086  # EXTRA is a list of words
      t=$({ time "$exe" run --set friction.law=table --set "friction.table=$work/table_$rows.csv" \
        --set "model.blocks=$N" --set "run.events=$EVENTS" --set run.transient_events=200 \
        --set output.catalog=none $EXTRA --out "$work/run" --force --quiet >/dev/null; } 2>&1)
      cps=$(awk -v t="$t" -v e="$EVENTS" 'BEGIN {split(t, a, " "); printf "%.1f\n", e / (a[1] + a[2])}')
      eps=$(sed -n 's/.*"events_per_second": *\([-0-9.eE+]*\).*/\1/p' "$work/run/summary.json")
      results[$rows,$b]+="$cps "
      printf '%6d %8s %12.1f %12.1f  %s\n' "$r" "$rows" "$cps" "$eps" "$exe"
    done
  done
done

printf '\nmedian events per CPU second over %s rounds\n%8s' "$rounds" rows
for exe in "${binaries[@]}"; do printf ' %22s' "$exe"; done
printf '\n'
for rows in "$@"; do
  printf '%8s' "$rows"
  for b in "${!binaries[@]}"; do
    printf ' %22.1f' "$(tr ' ' '\n' <<<"${results[$rows,$b]}" | sed '/^$/d' | median)"
  done
  printf '\n'
done
