#!/usr/bin/env -S /usr/bin/python3
"""Draw b_scan.csv (`bkquake fit ... --scan`): how b moves with the fit window.

    analysis/plot_b_scan.py DIR_OR_B_SCAN_CSV [--out PNG]

Left: b (binned maximum likelihood, per unit of mu = ln M) against the window's lower end
mu_min, one line per upper end mu_max (every unit of mu), with the Shi & Bolt error as a
band. Right: the map of b over (mu_min, mu_max). The windows the automatic method accepts
(those of b's systematic error, column `accepted`) are marked with black rings; their spread
is b_mle_sys_err (docs/how-to/fit-window.md). The right axis of the left panel gives
b_mw = 1.5 b, the slope per unit of moment magnitude. Default output: b_scan.png beside
the CSV. Runs with Debian's python3 (/usr/bin/python3, numpy and matplotlib).
"""

import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import bkquake_io  # noqa: E402

COLUMNS = ["mu_min", "mu_max", "events", "b", "b_err", "ks_distance", "accepted"]


def load(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or any(c not in rows[0] for c in COLUMNS):
        raise ValueError(f"{path}: expected the columns {','.join(COLUMNS)}")

    def num(x):
        return float(x) if x != "" else float("nan")

    return {c: np.array([num(r[c]) for r in rows]) for c in COLUMNS}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scan", metavar="DIR_OR_B_SCAN_CSV")
    ap.add_argument("--out", help="PNG file (default: b_scan.png beside the CSV)")
    args = ap.parse_args(argv)
    path = os.path.join(args.scan, "b_scan.csv") if os.path.isdir(args.scan) else args.scan
    try:
        s = load(path)
    except (OSError, ValueError) as e:
        print(f"plot_b_scan.py: {e}", file=sys.stderr)
        return 2
    out = args.out or os.path.join(os.path.dirname(os.path.abspath(path)), "b_scan.png")
    bkquake_io.check_output_or_exit(out, [path], "plot_b_scan.py")
    acc = s["accepted"] > 0
    fig, (ax, ax_map) = plt.subplots(1, 2, figsize=(13, 5))
    tops = np.unique(s["mu_max"])
    # One line per whole unit of mu_max (and the accepted tops), so the panel stays legible.
    shown = [t for t in tops if abs(t - round(t)) < 1e-6 or np.any(acc & (s["mu_max"] == t))]
    cmap = plt.get_cmap("viridis")
    for i, t in enumerate(shown):
        sel = (s["mu_max"] == t) & np.isfinite(s["b"])
        if not np.any(sel):
            continue
        x, b, e = s["mu_min"][sel], s["b"][sel], s["b_err"][sel]
        colour = cmap(i / max(1, len(shown) - 1))
        ax.plot(x, b, "-", color=colour, lw=1, label=f"mu_max = {t:.1f}")
        ax.fill_between(x, b - e, b + e, color=colour, alpha=0.15, lw=0)
    ax.plot(s["mu_min"][acc], s["b"][acc], "o", mfc="none", mec="k", ms=6,
            label="accepted (systematic error)")
    if np.any(acc):
        b_acc = s["b"][acc]
        half = 0.5 * (b_acc.max() - b_acc.min())
        ax.axhspan(b_acc.min(), b_acc.max(), color="k", alpha=0.08, lw=0)
        ax.set_title(f"b against mu_min; accepted: {b_acc.min():.3f}..{b_acc.max():.3f} "
                     f"(sys. ± {half:.3f})", fontsize=10)
    ax.set(xlabel="window start mu_min (μ = ln M)", ylabel="b per unit of μ")
    ax.grid(True, alpha=0.3)
    finite = s["b"][np.isfinite(s["b"]) & (s["b"] > 0)]
    if finite.size:
        lo, hi = np.percentile(finite, [2, 98])
        ax.set_ylim(max(0.0, lo - 0.1), hi + 0.1)
    sec = ax.secondary_yaxis("right", functions=(lambda b: 1.5 * b, lambda m: m / 1.5))
    sec.set_ylabel("b_mw = 1.5 b per unit of Mw")
    ax.legend(fontsize=6, ncol=2)

    sel = np.isfinite(s["b"])
    sc = ax_map.scatter(s["mu_min"][sel], s["mu_max"][sel], c=s["b"][sel], s=12, cmap="viridis",
                        vmin=ax.get_ylim()[0], vmax=ax.get_ylim()[1])
    ax_map.plot(s["mu_min"][acc], s["mu_max"][acc], "o", mfc="none", mec="k", ms=6)
    fig.colorbar(sc, ax=ax_map, label="b")
    ax_map.set(xlabel="mu_min", ylabel="mu_max", title="b over the windows (rings: accepted)")
    ax_map.grid(True, alpha=0.3)
    fig.tight_layout()
    bkquake_io.save_figure(fig, out, [path], "plot_b_scan.py", dpi=120)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
