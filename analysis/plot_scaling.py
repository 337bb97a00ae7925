#!/usr/bin/env -S /usr/bin/python3
"""Scaling with the chain length: events per second and ns per block-step against N, log
axes, from the CSV that analysis/scaling.sh (whole runs, wall time) or build/scaling
(bench/scaling.cpp, the engine in CPU time) prints; --before draws a second CSV of the
same kind dashed, for a before/after comparison.

Usage: /usr/bin/python3 analysis/plot_scaling.py scaling.csv [--before old.csv] [--out FILE.png]
Needs numpy and matplotlib: use Debian's /usr/bin/python3 (python3-numpy,
python3-matplotlib); the python3 first on PATH may lack them.
"""

import argparse
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import bkquake_io  # noqa: E402


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    cpu = "events_per_cpu_second" in rows[0]
    rate = "events_per_cpu_second" if cpu else "events_per_second"
    return {
        "n": [float(r["blocks"]) for r in rows],
        "rate": [float(r[rate]) for r in rows],
        "sliding": [float(r["ns_per_sliding_block_step"]) for r in rows],
        "step": [float(r["ns_per_block_step"]) for r in rows],
        "clock": "CPU time" if cpu else "whole run's wall time",
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv")
    ap.add_argument("--before", help="a CSV of the same kind, drawn dashed")
    ap.add_argument("--out", help="PNG file (default: scaling.png beside the CSV)")
    args = ap.parse_args()
    out = args.out or os.path.join(os.path.dirname(os.path.abspath(args.csv)), "scaling.png")
    inputs = [args.csv] + ([args.before] if args.before else [])
    bkquake_io.check_output_or_exit(out, inputs, "plot_scaling.py")
    runs = [(read(args.csv), "-", "")]
    if args.before:
        runs.insert(0, (read(args.before), "--", " (before)"))
    fig, (a, b) = plt.subplots(1, 2, figsize=(9, 3.6))
    for d, style, tag in runs:
        a.loglog(d["n"], d["rate"], "o" + style, color="C0", label="events/s" + tag)
        b.loglog(d["n"], d["sliding"], "s" + style, color="C1",
                 label="per sliding block-step" + tag)
        b.loglog(d["n"], d["step"], "^" + style, color="C2",
                 label="per block-step (stepped blocks)" + tag)
    a.set_xlabel("blocks N")
    a.set_ylabel("events per second")
    a.set_title("event rate")
    b.set_xlabel("blocks N")
    b.set_ylabel("ns (" + runs[-1][0]["clock"] + ")")
    b.set_title("cost per block-step")
    for ax in (a, b):
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("carlson-langer l = 10, alpha = 2.5, rk4 dt = 0.01, one core", fontsize=9)
    fig.tight_layout()
    bkquake_io.save_figure(fig, out, inputs, "plot_scaling.py", dpi=110)


if __name__ == "__main__":
    main()
