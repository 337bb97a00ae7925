#!/usr/bin/env -S /usr/bin/python3
"""Plot b against each swept key of a `bkquake sweep` (from its sweep.csv).

    analysis/plot_sweep.py SWEEP_DIR [--out PNG]

One panel per swept key: b (the binned maximum-likelihood Gutenberg-Richter exponent of
each point's merged replicas) with its standard error as error bars, against that key;
when more keys were swept, each combination of the others is its own line (so the
Carlson-Langer table, alpha x N, gives b against alpha for each N and b against N for
each alpha). Keys whose values are all numbers are plotted as numbers (on a log axis when
they span more than two decades), others as categories. Points that failed or whose fit
found no window (empty b) are left out and counted in the title. Default output:
SWEEP_DIR/sweep_b.png.

Runs with Debian's python3 (/usr/bin/python3, with python3-numpy and
python3-matplotlib); the python3 first on PATH may lack numpy and matplotlib.
"""

import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import bkquake_io  # noqa: E402


def read_sweep(sweep_dir):
    """(swept keys, rows as dicts) of SWEEP_DIR/sweep.csv; exits 2 when it is not a sweep."""
    path = os.path.join(sweep_dir, "sweep.csv")
    if not os.path.isfile(path):
        sys.exit(f"plot_sweep.py: error: {sweep_dir} holds no sweep.csv (not a bkquake sweep folder)")
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        rows = [dict(zip(header, r)) for r in reader]
    if "point" not in header or "status" not in header or "b" not in header:
        sys.exit(f"plot_sweep.py: error: {path} lacks the point/status/b columns of sweep.csv")
    keys = header[header.index("point") + 1 : header.index("status")]
    return keys, rows


def as_number(text):
    try:
        return float(text)
    except ValueError:
        return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sweep_dir")
    ap.add_argument("--out", help="PNG to write (default SWEEP_DIR/sweep_b.png)")
    args = ap.parse_args()
    keys, rows = read_sweep(args.sweep_dir)
    out = args.out or os.path.join(args.sweep_dir, "sweep_b.png")
    inputs = [os.path.join(args.sweep_dir, "sweep.csv")]
    bkquake_io.check_output_or_exit(out, inputs, "plot_sweep.py")
    fitted = [r for r in rows if r["status"] == "ok" and r["b"] not in ("", "nan")]
    if not fitted:
        sys.exit(
            f"plot_sweep.py: error: no point of {args.sweep_dir} has a b "
            "(a continuous-mode sweep, or every fit failed): nothing to plot"
        )
    left_out = len(rows) - len(fitted)

    fig, axes = plt.subplots(1, len(keys), figsize=(5.2 * len(keys), 4.2), squeeze=False)
    for ax, key in zip(axes[0], keys):
        others = [k for k in keys if k != key]
        numeric = all(as_number(r[key]) is not None for r in fitted)
        categories = sorted({r[key] for r in fitted}, key=lambda v: (as_number(v) or 0, v))
        groups = {}
        for r in fitted:
            groups.setdefault(tuple(r[k] for k in others), []).append(r)
        for group, members in sorted(groups.items()):
            members.sort(key=lambda r: as_number(r[key]) if numeric else categories.index(r[key]))
            x = [as_number(r[key]) if numeric else categories.index(r[key]) for r in members]
            y = [float(r["b"]) for r in members]
            err = [as_number(r["b_err"]) or 0.0 for r in members]
            label = ", ".join(f"{k} = {v}" for k, v in zip(others, group)) or None
            ax.errorbar(x, y, yerr=err, marker="o", capsize=3, label=label)
        if numeric:
            xs = [as_number(r[key]) for r in fitted]
            if min(xs) > 0 and max(xs) / min(xs) > 100:
                ax.set_xscale("log")
        else:
            ax.set_xticks(range(len(categories)))
            ax.set_xticklabels(categories)
        ax.set_xlabel(key)
        ax.set_ylabel("b (binned MLE)")
        ax.grid(alpha=0.3)
        if others:
            ax.legend(fontsize=8)
    title = f"{os.path.basename(os.path.normpath(args.sweep_dir))}: b against the swept keys"
    if left_out:
        title += f" ({left_out} point(s) without b left out)"
    fig.suptitle(title)
    fig.tight_layout()
    bkquake_io.save_figure(fig, out, inputs, "plot_sweep.py", dpi=110)
    print(f"plot_sweep.py: wrote {out}")


if __name__ == "__main__":
    main()
