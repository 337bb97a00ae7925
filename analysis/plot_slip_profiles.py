#!/usr/bin/env -S /usr/bin/python3
"""The slip profiles of the largest events of a run written with output.event_slip = MU
(event_slip.csv: event,block,slip, one row per block that slipped): slip against block for
the K events of largest moment, each labelled with its event number and moment.

Usage: /usr/bin/python3 analysis/plot_slip_profiles.py RUN_DIR [--largest K] [--out FILE.png]
       (default RUN_DIR/slip_profiles.png, written under the run folder's lock)
Needs numpy and matplotlib: use Debian's /usr/bin/python3 (python3-numpy,
python3-matplotlib); the python3 first on PATH may lack them.
"""

import argparse
import os
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bkquake_io  # noqa: E402


def largest_profiles(path, k):
    """{event: (blocks, slips)} of the k events of largest total slip (moment)."""
    with open(path) as f:
        header = f.readline().strip()
    if header.startswith("event,block,row,"):
        sys.exit(f"plot_slip_profiles: {path} holds a lattice's slip maps (a row column): "
                 "draw them with analysis/plot_lattice.py")
    # A chain's file, or a single row of the OFC automaton's (a topplings column after slip).
    if header not in ("event,block,slip", "event,block,slip,topplings"):
        sys.exit(f"plot_slip_profiles: {path}: header '{header}', expected event,block,slip")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    if data.size == 0:
        sys.exit(f"plot_slip_profiles: {path} holds no event")
    events = data[:, 0].astype(np.int64)
    ids, inverse = np.unique(events, return_inverse=True)
    moment = np.bincount(inverse, weights=data[:, 2])
    keep = ids[np.argsort(moment)[::-1][:k]]
    out = {}
    for e in keep:
        m = events == e
        out[int(e)] = (data[m, 1], data[m, 2])
    return out


def draw(run_dir, k):
    path = os.path.join(run_dir, "event_slip.csv")
    if not os.path.isfile(path):
        sys.exit(f"plot_slip_profiles: {run_dir} has no event_slip.csv (run with "
                 "--set output.event_slip=MU)")
    profiles = largest_profiles(path, k)
    fig, ax = plt.subplots(figsize=(10, 5.5))
    for e, (blocks, slips) in profiles.items():
        order = np.argsort(blocks)
        ax.plot(blocks[order], slips[order], "-", lw=1.2,
                label=f"event {e}: M = {slips.sum():.4g}, {len(blocks)} blocks")
    ax.set_xlabel("block")
    ax.set_ylabel("slip over the event")
    ax.set_title(f"slip profiles of the {len(profiles)} largest events ({run_dir})", fontsize=10)
    ax.legend(fontsize=7)
    fig.tight_layout()
    return fig


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("run_dir")
    p.add_argument("--largest", type=int, default=8)
    p.add_argument("--out")
    args = p.parse_args()
    # By default into the run folder, under its lock; never over an input or a run's own file.
    out = args.out or os.path.join(args.run_dir, "slip_profiles.png")
    inputs = [os.path.join(args.run_dir, "event_slip.csv")]
    bkquake_io.check_output_or_exit(out, inputs, "plot_slip_profiles")
    bkquake_io.save_figure(draw(args.run_dir, args.largest), out, inputs, "plot_slip_profiles",
                           dpi=110)
    print(f"written {out}")


if __name__ == "__main__":
    main()
