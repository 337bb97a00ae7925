#!/usr/bin/python3
"""Stability charts of `bkquake stability` folders (seed 004 §4.2, Figs. 5 and 7).

  eigen DIR[=LABEL]...  the eigenvalues at one parameter value, one panel per folder side by
                        side (e.g. without and with block damping): frequency Im(lambda)/2pi
                        against growth rate Re(lambda); unstable modes (Re > 0) in red, the pad
                        family as squares, chain:0 and chain:1 labelled.
  sweep DIR             a sweep (stability.csv with many values): frequency (top) and Re(lambda)
                        (bottom) of every mode against the swept value, unstable points in red,
                        the pad mode and chain:0 highlighted; name the swept key with --xlabel.

Each figure goes into the (first) folder it reads, under that folder's lock (stability_eigen.png,
stability_sweep.png), or to --out; never over an input.

Usage:
  /usr/bin/python3 analysis/plot_stability.py eigen runs/st/v0.1 runs/st/v0.1-damped=damped --out eig.png
  /usr/bin/python3 analysis/plot_stability.py sweep runs/st/speed --xlabel "disc speed v" --out sweep.png
Needs numpy and matplotlib: use Debian's /usr/bin/python3 (python3-numpy,
python3-matplotlib); the python3 first on PATH may lack them.
"""

import argparse
import csv
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import bkquake_io  # noqa: E402


def read_modes(folder):
    """stability.csv -> list of dicts (value, mode, re, im, frequency, unstable)."""
    rows = []
    path = os.path.join(folder, "stability.csv")
    if not os.path.isfile(path):
        print(f"plot_stability.py: {folder} holds no stability.csv (not an output folder of "
              "bkquake stability)", file=sys.stderr)
        sys.exit(2)
    with open(path) as f:
        for r in csv.DictReader(f):
            rows.append({
                "value": float(r["value"]),
                "mode": r["mode"],
                "re": float(r["re"]),
                "frequency": float(r["frequency"]),
                "unstable": r["unstable"] == "1",
            })
    if not rows:
        print(f"plot_stability.py: {path}: no eigenvalues", file=sys.stderr)
        sys.exit(2)
    return rows


def style(mode):
    if mode.startswith("pad:"):
        return dict(marker="s", ms=7, color="tab:blue", label="pad:0")
    if mode == "chain:0":
        return dict(marker="D", ms=6, color="tab:green", label="chain:0")
    return dict(marker="o", ms=3, color="0.4", label=None)


def eigen(args):
    folders = [a.split("=", 1) for a in args.folders]
    # By default into the first folder (under its lock), never over an input.
    out = args.out or os.path.join(folders[0][0], "stability_eigen.png")
    inputs = [os.path.join(item[0], "stability.csv") for item in folders]
    bkquake_io.check_output_or_exit(out, inputs, "plot_stability.py")
    fig, axes = plt.subplots(1, len(folders), figsize=(5.2 * len(folders), 4.4), squeeze=False,
                             sharey=True)
    for ax, item in zip(axes[0], folders):
        folder = item[0]
        title = item[1] if len(item) > 1 else os.path.basename(folder.rstrip("/"))
        rows = read_modes(folder)
        value = rows[0]["value"]
        rows = [r for r in rows if r["value"] == value]
        for r in rows:
            st = style(r["mode"])
            color = "tab:red" if r["unstable"] else st["color"]
            ax.plot(r["re"], r["frequency"], st["marker"], ms=st["ms"], color=color,
                    mfc=color if r["unstable"] else "none")
            if r["mode"] in ("pad:0", "chain:0", "chain:1"):
                ax.annotate(r["mode"], (r["re"], r["frequency"]), textcoords="offset points",
                            xytext=(5, 3), fontsize=8)
        ax.axvline(0, color="k", lw=0.8)
        n_unst = sum(r["unstable"] for r in rows)
        ax.set_title(f"{title}: {n_unst} of {len(rows)} unstable", fontsize=10)
        ax.set_xlabel("growth rate Re λ")
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("frequency Im λ / 2π")
    axes[0][0].set_ylim(bottom=0, top=args.fmax)
    fig.tight_layout()
    bkquake_io.save_figure(fig, out, inputs, "plot_stability.py", dpi=130)
    print(f"wrote {out}")


def sweep(args):
    out = args.out or os.path.join(args.folder, "stability_sweep.png")
    inputs = [os.path.join(args.folder, "stability.csv")]
    bkquake_io.check_output_or_exit(out, inputs, "plot_stability.py")
    rows = read_modes(args.folder)
    by_mode = defaultdict(list)
    for r in rows:
        by_mode[r["mode"]].append(r)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 7.5), sharex=True)
    # Chain modes first (grey), highlighted families on top.
    order = sorted(by_mode, key=lambda m: (m.startswith("pad") or m == "chain:0", m))
    shown = set()
    for mode in order:
        if args.max_chain is not None and mode.startswith("chain:") and mode != "chain:0" and \
                int(mode.split(":")[1]) > args.max_chain:
            continue
        pts = sorted(by_mode[mode], key=lambda r: r["value"])
        x = np.array([r["value"] for r in pts])
        f = np.array([r["frequency"] for r in pts])
        g = np.array([r["re"] for r in pts])
        u = np.array([r["unstable"] for r in pts])
        st = style(mode)
        lw = 1.6 if st["label"] else 0.6
        label = st["label"] if st["label"] and st["label"] not in shown else None
        shown.add(st["label"])
        top.plot(x, f, "-", color=st["color"], lw=lw, label=label)
        bottom.plot(x, g, "-", color=st["color"], lw=lw)
        top.plot(x[u], f[u], ".", color="tab:red", ms=4)
        bottom.plot(x[u], g[u], ".", color="tab:red", ms=4)
    top.plot([], [], ".", color="tab:red", label="unstable (Re λ > 0)")
    bottom.axhline(0, color="k", lw=0.8)
    top.set_ylabel("frequency Im λ / 2π")
    if args.fmax:
        top.set_ylim(0, args.fmax)
    bottom.set_ylabel("growth rate Re λ")
    bottom.set_xlabel(args.xlabel)
    if args.log:
        bottom.set_xscale("log")
    top.legend(fontsize=8, loc="best")
    top.grid(alpha=0.3)
    bottom.grid(alpha=0.3)
    if args.title:
        top.set_title(args.title, fontsize=10)
    fig.tight_layout()
    bkquake_io.save_figure(fig, out, inputs, "plot_stability.py", dpi=130)
    print(f"wrote {out}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="what", required=True)
    e = sub.add_parser("eigen")
    e.add_argument("folders", nargs="+")
    e.add_argument("--out", help="PNG file (default: stability_eigen.png in the first folder)")
    e.add_argument("--fmax", type=float, default=None, help="top of the frequency axis")
    s = sub.add_parser("sweep")
    s.add_argument("folder")
    s.add_argument("--out", help="PNG file (default: stability_sweep.png in the folder)")
    s.add_argument("--xlabel", default="swept value")
    s.add_argument("--title", default="")
    s.add_argument("--log", action="store_true", help="logarithmic x axis")
    s.add_argument("--fmax", type=float, default=None, help="top of the frequency axis")
    s.add_argument("--max-chain", type=int, default=None,
                   help="draw chain modes up to this index only")
    args = ap.parse_args()
    eigen(args) if args.what == "eigen" else sweep(args)


if __name__ == "__main__":
    main()
