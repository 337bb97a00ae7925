#!/usr/bin/env -S /usr/bin/python3
"""Time per event against event size, log axes, from the CSV that `build/event_sizes N EVENTS
--csv FILE` writes (bench/event_sizes.cpp: per event size in blocks, the number of events,
their mean time in microseconds, mean steps and mean sliding block-steps). Each CSV (one per
chain length, N = 100 and N = 1000 for docs/validation/performance.md) is drawn as its per-size means (dots,
sizes seen fewer than --min-count times left out) and the mean over logarithmic bins of
size, weighted by count (line); dotted, what the same events would take at issue 20's goal
of 5 ns per sliding block-step.

Usage: /usr/bin/python3 analysis/plot_event_sizes.py sizes_n100.csv [sizes_n1000.csv ...]
           [--out FILE.png] [--min-count 3]
Needs numpy and matplotlib: use Debian's /usr/bin/python3 (python3-numpy,
python3-matplotlib); the python3 first on PATH may lack them.
"""

import argparse
import os
import re

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import bkquake_io  # noqa: E402


def read_sizes(path):
    """The CSV's columns as arrays, and its label (from the '# N = ...' line)."""
    label = path
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                m = re.search(r"N = (\d+)", line)
                if m:
                    label = f"N = {m.group(1)}"
                continue
            if line.startswith("blocks"):
                continue
            if line.strip():
                rows.append([float(x) for x in line.split(",")])
    if not rows:
        raise SystemExit(f"{path}: no rows")
    data = np.array(rows)
    return label, data[:, 0], data[:, 1], data[:, 2], data[:, 4]


def binned(blocks, count, time_us, per_decade=5):
    """Count-weighted mean time per event over logarithmic bins of size."""
    edges = 10.0 ** np.arange(0, np.log10(blocks.max()) + 1.0 / per_decade, 1.0 / per_decade)
    edges = np.append(edges, blocks.max() + 1)
    centres, means = [], []
    for lo, hi in zip(edges[:-1], edges[1:]):
        inside = (blocks >= lo) & (blocks < hi)
        if count[inside].sum() == 0:
            continue
        w = count[inside]
        centres.append(np.sum(w * blocks[inside]) / w.sum())
        means.append(np.sum(w * time_us[inside]) / w.sum())
    return np.array(centres), np.array(means)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("csv", nargs="+", help="CSV files written by build/event_sizes --csv")
    ap.add_argument("--out", help="PNG file (default: event_sizes.png beside the first CSV)")
    ap.add_argument("--min-count", type=int, default=3,
                    help="leave out sizes seen fewer times than this (default 3)")
    args = ap.parse_args()
    out = args.out or os.path.join(os.path.dirname(os.path.abspath(args.csv[0])),
                                   "event_sizes.png")
    bkquake_io.check_output_or_exit(out, args.csv, "plot_event_sizes.py")

    fig, ax = plt.subplots(figsize=(5.6, 4.0), dpi=100)
    colours = ["tab:blue", "tab:orange", "tab:green", "tab:red"]
    for i, path in enumerate(args.csv):
        label, blocks, count, time_us, sliding = read_sizes(path)
        colour = colours[i % len(colours)]
        keep = count >= args.min_count
        ax.scatter(blocks[keep], time_us[keep], s=6, color=colour, alpha=0.45, linewidths=0)
        centres, means = binned(blocks, count, time_us)
        events = int(count.sum())
        ax.plot(centres, means, "-", color=colour, lw=1.6,
                label=f"{label} ({events:.0e} events)".replace("e+0", "e"))
        centres, goal = binned(blocks, count, 5e-3 * sliding)
        ax.plot(centres, goal, ":", color=colour, lw=1.2,
                label=f"{label} at 5 ns per sliding block-step")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("event size (blocks that slipped)")
    ax.set_ylabel("time per event (µs, wall clock)")
    ax.set_title("Event engine: time per event against size\n"
                 "carlson-langer scene, rk4 dt = 0.01", fontsize=10)
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    bkquake_io.save_figure(fig, out, args.csv, "plot_event_sizes.py")


if __name__ == "__main__":
    main()
