#!/usr/bin/env -S /usr/bin/python3
"""Plot the magnitude distributions of bkquake runs (Gutenberg-Richter plots).

    analysis/plot_gr.py RUN_DIR... [--out PNG] [--rates] [--mu-min A --mu-max B]

For each run folder (an event run or a merge; any folder with histogram.csv) it reads
histogram.csv and summary.json and draws D(mu) (events per unit magnitude) and R(mu)
(events with magnitude >= mu) on logarithmic y-axes, in two panels, with the fit of
summary.json (b = b_mle on the window [mu_min, mu_max), thesis eqs. 2.7-2.8; the legend
says why the automatic window ends where it does (gap, rise, departure, goodness of fit) and
gives b's block-bootstrap error where the run has it;
docs/explanation/b-fit.md): the window is shaded (several runs: a strip per run at the bottom), and the fitted law is drawn where it applies, over the
window, so that it passes through the data there:
  D(mu): the expected counts per unit magnitude of the window's (truncated) geometric law;
  R(mu): the same law's survival function times the window's events, plus the events
         above the window (R counts them too).
The band around the line is b's systematic error (b_mle_sys_err of summary.json: half the
range of b over the windows within 1 unit of mu inside both ends; docs/how-to/fit-window.md).
--mu-min/--mu-max refit every run on that window here (binned maximum likelihood of Tinti &
Mulargia, truncated at mu_max, as `bkquake fit --mu-min A --mu-max B`; the systematic band
by the same rule) and mark it. A run whose summary has no b (no acceptable window) gets the
reason in the legend and no line. --rates plots the per-unit-loading-per-block columns D_rate, R_rate instead, so runs
of different lengths compare. The legend label is taken from scene.ini (alpha, N) or the
folder name. Default output: RUN_DIR/gr.png for one run, gr.png for several. A folder
without histogram.csv is refused with a one-line message (exit 2).

Runs with Debian's python3 (/usr/bin/python3, with python3-numpy and
python3-matplotlib); the python3 first on PATH may lack numpy and matplotlib.
"""

import argparse
import os
import sys
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bkquake_io  # noqa: E402


# Why the automatic window ends where it does (summary.json's fit_window.mu_max_reason).
STOP_TEXT = {
    "gap": "; ends below a gap of empty bins",
    "rise": "; ends below the rise into the bump",
    "departure": "; ends where the events above depart from the law",
    "goodness of fit": "; lowered until it passes the goodness-of-fit test",
    "end of data": "; ends at the largest event",
}


def fitted_law(h, b, lo, hi):
    """The window's fitted law on its bins: (edges, centres, expected D, expected R).

    The counts in [lo, hi) follow a geometric law in the bin index (exponential in mu),
    truncated at hi when events lie above it; R adds the events at or above hi.
    """
    w = float(h["mu_high"][0] - h["mu_low"][0])
    edges = np.arange(np.round(lo / w), np.round(hi / w) + 1) * w  # lo, lo + w, ..., hi
    above_lo = h["mu_low"] >= lo - 1e-9 * max(1.0, abs(lo))
    below_hi = h["mu_low"] < hi - 1e-9 * max(1.0, abs(hi))
    n_win = float(h["count"][above_lo & below_hi].sum())
    n_above = float(h["count"][~below_hi].sum())
    span = hi - lo
    truncated = n_above > 0
    x = edges - lo
    if truncated:
        surv = (np.exp(-b * x) - np.exp(-b * span)) / -np.expm1(-b * span)
    else:
        surv = np.exp(-b * x)
    r_fit = n_above + n_win * surv
    d_fit = n_win * (surv[:-1] - surv[1:]) / w  # expected count per bin / bin width
    centres = 0.5 * (edges[:-1] + edges[1:])
    return edges, centres, d_fit, r_fit


def binned_mle(h, lo, hi):
    """Truncated binned MLE (Tinti & Mulargia 1987) on the bins in [lo, hi), with the
    Shi & Bolt error: the model's mean bin offset solved for b by bisection."""
    w = float(h["mu_high"][0] - h["mu_low"][0])
    sel = (h["mu_low"] >= lo - 1e-9) & (h["mu_low"] < hi - 1e-9)
    c = h["count"][sel].astype(float)
    n = c.sum()
    if n < 2:
        return float("nan"), float("nan")
    j = np.round((h["mu_low"][sel] - lo) / w)
    mean = (c * j * w).sum() / n
    var = (c * (j * w - mean) ** 2).sum()
    span = round((hi - lo) / w) * w

    def hfun(x):
        return 0.5 - x / 12 if abs(x) < 1e-6 else 1 / x - 1 / np.expm1(x)

    def m(b):
        return span * hfun(b * span) - w * hfun(b * w)

    a, z = -20.0, 50.0
    for _ in range(200):
        mid = 0.5 * (a + z)
        a, z = (mid, z) if m(mid) > mean else (a, mid)
    b = 0.5 * (a + z)
    eps = 1e-6
    dm = (m(b + eps) - m(b - eps)) / (2 * eps)
    return b, np.sqrt(var / (n * (n - 1))) / abs(dm)


def systematic(h, lo, hi, width=1.0, min_bins=10, min_tail=50):
    """Half the range of b over the windows with ends within `width` inside [lo, hi)
    (populated end bins, >= min_bins bins, >= min_tail events): the rule of
    b_mle_sys_err."""
    w = float(h["mu_high"][0] - h["mu_low"][0])
    nb = int(round(width / w))
    counts = {int(round(m / w)): int(c) for m, c in zip(h["mu_low"], h["count"])}
    klo, khi = int(round(lo / w)), int(round(hi / w)) - 1
    bs = []
    for a in range(klo, klo + nb):
        for z in range(khi, khi - nb, -1):
            if (a != klo and counts.get(a, 0) == 0) or (z != khi and counts.get(z, 0) == 0):
                continue
            if z - a + 1 < min_bins or sum(counts.get(k, 0) for k in range(a, z + 1)) < min_tail:
                continue
            b, _ = binned_mle(h, a * w, (z + 1) * w)
            if np.isfinite(b) and b > 0:
                bs.append(b)
    return 0.5 * (max(bs) - min(bs)) if bs else float("nan")


def plot_run(run, i, args, ax_d, ax_r, dcol, rcol):
    bkquake_io.require_files(
        run, ["histogram.csv"], "plot_gr.py needs a run or merge folder with a histogram")
    colour = f"C{i % 10}"
    h = bkquake_io.load_histogram(run)
    summary = bkquake_io.load_summary(run)
    name = bkquake_io.label(run)
    if h["count"].size == 0:
        print(f"{run}: empty histogram, skipped", file=sys.stderr)
        return
    centre = 0.5 * (h["mu_low"] + h["mu_high"])
    d, r = h[dcol], h[rcol]
    # Rates are the counts over (load * N): one factor for the whole histogram.
    scale = float(r[0] / h["R"][0]) if args.rates and h["R"][0] > 0 else 1.0
    keep = h["count"] > 0
    ax_d.plot(centre[keep], d[keep], "o", ms=3, color=colour, label=name)
    ax_r.plot(h["mu_low"][r > 0], r[r > 0], "o", ms=3, color=colour, label=name)
    fit = bkquake_io.fit_window(summary)
    # The statistical error of correlated events (block bootstrap) where the run has it.
    err = summary.get("b_mle_boot_err") or summary.get("b_mle_err", float("nan"))
    window_info = summary.get("fit_window") or summary.get("fit") or {}
    stop = STOP_TEXT.get(window_info.get("mu_max_reason", ""), "")
    sys_err = summary.get("b_mle_sys_err", float("nan"))
    if args.mu_min is not None:
        lo, hi = args.mu_min, args.mu_max
        stop = ""
        b, err = binned_mle(h, lo, hi)
        sys_err = systematic(h, lo, hi)
        fit = (b, lo, hi) if np.isfinite(b) else None
    if fit is None:
        reason = bkquake_io.no_fit_reason(summary) or "no fit in summary.json"
        ax_r.plot([], [], " ", label=textwrap.fill(f"no b: {reason}", 60))
        return
    b, lo, hi = fit
    if sys_err is None:
        sys_err = float("nan")
    # One run: the window shaded over the whole height; several: a strip per run at the
    # bottom, so that the windows stay apart.
    for ax in (ax_d, ax_r):
        if len(args.runs) == 1:
            ax.axvspan(lo, hi, color=colour, alpha=0.08, lw=0)
        else:
            ax.axvspan(lo, hi, ymin=0.025 * i, ymax=0.025 * (i + 1), color=colour, alpha=0.6, lw=0)
    edges, centres, d_fit, r_fit = fitted_law(h, b, lo, hi)
    mark = "shaded" if len(args.runs) == 1 else "strip at the bottom"
    given = " given" if args.mu_min is not None else ""
    text = (f"b = {b:.3f} ± {err:.3f} (stat.) ± {sys_err:.3f} (sys.), b_mw = 1.5 b = "
            f"{1.5 * b:.3f}, on{given} [{lo:.1f}, {hi:.1f}) ({mark}{stop})")
    ax_d.plot(centres, d_fit * scale, "-", color=colour, lw=1.5, label=text)
    ax_r.plot(edges, r_fit * scale, "-", color=colour, lw=1.5, label=text)
    # b's systematic band: the law with b -/+ sys, normalised alike.
    if np.isfinite(sys_err) and sys_err > 0:
        lows = fitted_law(h, b - sys_err, lo, hi)
        highs = fitted_law(h, b + sys_err, lo, hi)
        ax_d.fill_between(centres, lows[2] * scale, highs[2] * scale, color=colour, alpha=0.25,
                          lw=0)
        ax_r.fill_between(edges, lows[3] * scale, highs[3] * scale, color=colour, alpha=0.25,
                          lw=0)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("runs", nargs="+", metavar="RUN_DIR")
    ap.add_argument("--out", help="PNG file (default RUN_DIR/gr.png for one run, else "
                    "gr_runs.png in the first RUN_DIR)")
    ap.add_argument("--rates", action="store_true", help="plot D_rate and R_rate")
    ap.add_argument("--mu-min", type=float, help="refit every run on [MU_MIN, MU_MAX)")
    ap.add_argument("--mu-max", type=float, help="upper end of the refit window")
    args = ap.parse_args(argv)
    if (args.mu_min is None) != (args.mu_max is None) or (
            args.mu_min is not None and not args.mu_max > args.mu_min):
        print("plot_gr.py: --mu-min and --mu-max go together, with --mu-max > --mu-min",
              file=sys.stderr)
        return 2

    out = args.out or os.path.join(args.runs[0], "gr.png" if len(args.runs) == 1 else "gr_runs.png")
    inputs = list(args.runs)
    bkquake_io.check_output_or_exit(out, inputs, "plot_gr.py")
    fig, (ax_d, ax_r) = plt.subplots(1, 2, figsize=(12, 5))
    dcol, rcol = ("D_rate", "R_rate") if args.rates else ("D", "R")
    try:
        for i, run in enumerate(args.runs):
            plot_run(run, i, args, ax_d, ax_r, dcol, rcol)
    except bkquake_io.WrongFolder as e:
        print(f"plot_gr.py: {e}", file=sys.stderr)
        return 2
    except (OSError, ValueError, KeyError) as e:
        print(f"plot_gr.py: {run}: cannot read the run ({e})".replace("\n", " "), file=sys.stderr)
        return 2
    unit = " per unit load per block" if args.rates else ""
    ax_d.set(yscale="log", xlabel="magnitude μ = ln M", ylabel=f"D(μ){unit}",
             title="D(μ): events per unit magnitude")
    ax_r.set(yscale="log", xlabel="magnitude μ = ln M", ylabel=f"R(μ){unit}",
             title="R(μ): events with magnitude ≥ μ")
    for ax in (ax_d, ax_r):
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    # One legend, below both panels, outside the axes: it never covers a point or a line
    # (the saved figure is cropped to include it).
    handles, labels = ax_r.get_legend_handles_labels()
    if handles:
        fig.legend(handles, labels, fontsize=7, loc="upper center", bbox_to_anchor=(0.5, 0.0),
                   frameon=False)
    bkquake_io.save_figure(fig, out, inputs, "plot_gr.py", dpi=120, bbox_inches="tight")
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
