#!/usr/bin/env bash
# Peak resident memory of event runs of the built-in default scene (Carlson-Langer, N = 100)
# at 10^5 and 10^7 events. It should not grow with the number of events: the catalogue is
# streamed to disk, the histogram holds one counter per magnitude bin, and checkpoints
# copy the chain, not the run.
#
#   analysis/peak_memory.sh [EVENTS...]      (default: 100000 10000000)
#
# Peak RSS comes from /usr/bin/time -v when it exists, otherwise from polling VmHWM in
# /proc/PID/status while the run lasts (VmHWM only grows, so the last reading is the peak
# up to ~50 ms before the exit). 10^7 events take about a minute and write a 1.4 GB
# catalogue into a temporary folder, removed at the end.
#
# Environment: BKQUAKE (the binary; default build/bkquake, build it with ./run.sh or cmake).
set -euo pipefail

cd "$(dirname "$0")/.."
BKQUAKE=${BKQUAKE:-build/bkquake}
if [[ ! -x $BKQUAKE ]]; then
  echo "peak_memory.sh: $BKQUAKE not found; build it (./run.sh) or set BKQUAKE" >&2
  exit 2
fi
if [[ $# -eq 0 ]]; then set -- 100000 10000000; fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Runs the command given as arguments (output discarded); prints its peak RSS in KiB.
peak_rss_kib() {
  if [[ -x /usr/bin/time ]]; then
    /usr/bin/time -v -o "$work/time.txt" "$@" >/dev/null
    awk -F': ' '/Maximum resident set size/ {print $2}' "$work/time.txt"
  else
    "$@" >/dev/null &
    local pid=$! peak=0 v
    while kill -0 "$pid" 2>/dev/null; do
      v=$(awk '/^VmHWM:/ {print $2}' "/proc/$pid/status" 2>/dev/null || true)
      [[ -n $v ]] && peak=$v
      sleep 0.05
    done
    wait "$pid"
    echo "$peak"
  fi
}

printf '%12s %14s %10s %14s\n' events peak_rss_MiB wall_s catalog_MB
for events in "$@"; do
  out="$work/run-$events"
  start=$(date +%s.%N)
  kib=$(peak_rss_kib "$BKQUAKE" run --set "run.events=$events" --out "$out" --quiet)
  end=$(date +%s.%N)
  catalog=$(stat -c %s "$out/catalog.csv")
  awk -v e="$events" -v k="$kib" -v s="$start" -v t="$end" -v c="$catalog" \
    'BEGIN { printf "%12d %14.1f %10.1f %14.1f\n", e, k / 1024, t - s, c / 1e6 }'
  rm -rf "$out"
done
