#!/usr/bin/python3
"""Plot the magnitude distributions of bkquake runs (Gutenberg-Richter plots).

    analysis/plot_gr.py RUN_DIR... [--out PNG] [--rates]

For each run folder it reads histogram.csv and summary.json and draws D(mu) (events per
unit magnitude) and R(mu) (events with magnitude >= mu) on logarithmic y-axes, in two
panels, with the fitted line R = A exp(-b mu) over the fit window (b = b_mle from
summary.json, A normalised to R at the window's lower edge; thesis eqs. 2.7-2.8).
--rates plots the per-unit-loading-per-block columns D_rate, R_rate instead, so runs of
different lengths compare. The legend label is taken from scene.ini (alpha, N) or the
folder name. Default output: RUN_DIR/gr.png for one run, gr.png for several.

Runs with Debian's python3 (/usr/bin/python3, with python3-numpy and
python3-matplotlib); the python3 first on PATH may lack numpy and matplotlib.
"""

import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bkquake_io  # noqa: E402


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("runs", nargs="+", metavar="RUN_DIR")
    ap.add_argument("--out", help="PNG file (default RUN_DIR/gr.png for one run, else gr.png)")
    ap.add_argument("--rates", action="store_true", help="plot D_rate and R_rate")
    args = ap.parse_args(argv)

    fig, (ax_d, ax_r) = plt.subplots(1, 2, figsize=(11, 4.5))
    dcol, rcol = ("D_rate", "R_rate") if args.rates else ("D", "R")
    for i, run in enumerate(args.runs):
        colour = f"C{i % 10}"
        h = bkquake_io.load_histogram(run)
        summary = bkquake_io.load_summary(run)
        name = bkquake_io.label(run)
        if h["count"].size == 0:
            print(f"{run}: empty histogram, skipped", file=sys.stderr)
            continue
        centre = 0.5 * (h["mu_low"] + h["mu_high"])
        d, r = h[dcol], h[rcol]
        keep = h["count"] > 0
        ax_d.plot(centre[keep], d[keep], "o", ms=3, color=colour, label=name)
        ax_r.plot(h["mu_low"], r, "o", ms=3, color=colour, label=name)
        fit = bkquake_io.fit_window(summary)
        if fit is not None:
            b, lo, hi = fit
            at = np.argmin(np.abs(h["mu_low"] - lo))
            if r[at] > 0 and np.isfinite(r[at]):
                mu = np.linspace(lo, hi, 50)
                ax_r.plot(mu, r[at] * np.exp(-b * (mu - h["mu_low"][at])), "-", color=colour,
                          label=f"b = {b:.3f} ± {summary.get('b_mle_err', float('nan')):.3f}, "
                                f"[{lo:g}, {hi:g})")
    unit = " per unit load per block" if args.rates else ""
    ax_d.set(yscale="log", xlabel="magnitude mu = ln M", ylabel=f"D(mu){unit}",
             title="D(mu): events per unit magnitude")
    ax_r.set(yscale="log", xlabel="magnitude mu = ln M", ylabel=f"R(mu){unit}",
             title="R(mu): events with magnitude >= mu")
    for ax in (ax_d, ax_r):
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    out = args.out or (os.path.join(args.runs[0], "gr.png") if len(args.runs) == 1 else "gr.png")
    fig.savefig(out, dpi=120)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
