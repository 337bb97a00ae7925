#!/usr/bin/env -S /usr/bin/python3
"""Event-driven against continuous rate-and-state runs in one figure.

    analysis/plot_rsf_events.py RUN_DIR... --from LOAD --to LOAD [--t-a LOAD] --out PNG

Left: the cumulative distribution of the magnitudes mu = ln M of each run's events with
FROM < load <= TO (the window `bkquake compare` reads). Right: the event rate stacked after
the mainshocks (seismicity/omori.csv of `bkquake seismicity RUN_DIR --mainshock-mu X`),
divided by the run's mean rate over the catalogue, against the time after the mainshock in
load (V_pl t for rate-and-state), with Dieterich's aftershock duration t_a = a sigma / taudot
(in load: a sigma / k) marked when --t-a is given. Runs without seismicity/ are left out of the
right panel. The first run is drawn in black as the reference.

Runs with Debian's python3 (/usr/bin/python3, with python3-numpy and python3-matplotlib).
"""

import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import bkquake_io  # noqa: E402


def window_mu(run, lo, hi):
    cols = bkquake_io.read_catalog_file(os.path.join(run, "catalog.csv"))
    load = np.asarray(cols["load"], dtype=float)
    mu = np.log(np.asarray(cols["moment"], dtype=float))
    return np.sort(mu[(load > lo) & (load <= hi)]), load


def omori_after(run):
    path = os.path.join(run, "seismicity", "omori.csv")
    if not os.path.isfile(path):
        return None
    rows = [line for line in open(path) if not line.startswith("#")]
    header = rows[0].strip().split(",")
    data = [r.strip().split(",") for r in rows[1:] if r.startswith("after")]
    if not data:
        return None
    col = {h: i for i, h in enumerate(header)}
    t_low = np.array([float(r[col["t_low"]]) for r in data])
    t_high = np.array([float(r[col["t_high"]]) for r in data])
    rate = np.array([float(r[col["rate"]]) for r in data])
    count = np.array([float(r[col["count"]]) for r in data])
    return np.sqrt(t_low * t_high), rate, count


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--from", dest="lo", type=float, required=True)
    ap.add_argument("--to", dest="hi", type=float, required=True)
    ap.add_argument("--t-a", type=float, help="Dieterich's t_a in load, marked on the right")
    ap.add_argument("--out", required=True)
    args = ap.parse_args(argv)
    for run in args.runs:
        if not os.path.isfile(os.path.join(run, "catalog.csv")):
            print(f"plot_rsf_events.py: {run} has no catalog.csv", file=sys.stderr)
            return 2

    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    for k, run in enumerate(args.runs):
        name = os.path.basename(os.path.normpath(run))
        mu, load = window_mu(run, args.lo, args.hi)
        colour = "k" if k == 0 else f"C{k - 1}"
        if mu.size:
            ax[0].step(mu, np.arange(1, mu.size + 1) / mu.size, where="post", color=colour,
                       lw=1.4 if k == 0 else 1, label=f"{name} ({mu.size} events)")
        om = omori_after(run)
        if om is not None and load.size > 1:
            t, rate, count = om
            mean_rate = load.size / (load.max() - load.min())
            ok = count > 0
            ax[1].loglog(t[ok], rate[ok] / mean_rate, "o-", ms=3, lw=0.8, color=colour,
                         label=name)
    ax[0].set_xlabel("mu = ln M")
    ax[0].set_ylabel("fraction of the window's events below")
    ax[0].set_title(f"magnitudes, {args.lo:g} < load <= {args.hi:g}", fontsize=10)
    ax[0].legend(fontsize=7)
    if args.t_a:
        ax[1].axvline(args.t_a, color="grey", ls=":", lw=1)
        ax[1].text(args.t_a, ax[1].get_ylim()[1], " t_a", va="top", fontsize=8, color="grey")
    ax[1].axhline(1, color="grey", lw=0.5)
    ax[1].set_xlabel("time after the mainshock (load)")
    ax[1].set_ylabel("stacked rate / the catalogue's mean rate")
    ax[1].set_title("aftershocks (seismicity/omori.csv)", fontsize=10)
    ax[1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
