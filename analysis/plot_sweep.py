#!/usr/bin/env -S /usr/bin/python3
"""Plot b against each swept key of a `bkquake sweep` (from its sweep.csv or sweep_fit.csv).

    analysis/plot_sweep.py SWEEP_DIR [--out PNG] [--sweep-csv] [--reference CSV] [--dump CSV]

One panel per swept key: b (the binned maximum-likelihood Gutenberg-Richter exponent of
each point's merged replicas) against that key, with error bars of its total error: the
statistical error (b_err) and the window's systematic error (b_sys_err) added in
quadrature, sqrt(b_err^2 + b_sys_err^2). Where SWEEP_DIR holds sweep_fit.csv (written by
`bkquake fit SWEEP_DIR`, every point refitted on one window) its b and errors are drawn,
otherwise those of sweep.csv; --sweep-csv draws sweep.csv's even where sweep_fit.csv
exists. The title says which file the points come from.

When more keys were swept, each combination of the others is its own line (so the
Carlson-Langer table, alpha x N, gives b against alpha for each N and b against N for
each alpha). Keys whose values are all numbers are plotted as numbers (on a log axis when
they span more than two decades), others as categories. Points that failed or whose fit
found no window (empty b) are left out and counted in the title. Legends are placed
outside the axes, so they never cover a point or an error bar.

--reference CSV draws published values beside the points: a CSV with a column named after
one swept key, a column b, optionally b_err and source (the legend's text); each row is an
open black marker on that key's panel (data/reference/carlson-langer-published.csv holds
the Carlson-Langer papers' values). --dump CSV writes every drawn point (panel, line,
x, b, b_err, b_sys_err, total error, source file) for checks and tables.

Default output: SWEEP_DIR/sweep_b.png.

Runs with Debian's python3 (/usr/bin/python3, with python3-numpy and
python3-matplotlib); the python3 first on PATH may lack numpy and matplotlib.
"""

import argparse
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import bkquake_io  # noqa: E402


def read_csv(path):
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        return header, [dict(zip(header, r)) for r in reader]


def read_sweep(sweep_dir):
    """(swept keys, rows as dicts) of SWEEP_DIR/sweep.csv; exits 2 when it is not a sweep."""
    path = os.path.join(sweep_dir, "sweep.csv")
    if not os.path.isfile(path):
        sys.exit(f"plot_sweep.py: error: {sweep_dir} holds no sweep.csv (not a bkquake sweep folder)")
    header, rows = read_csv(path)
    if "point" not in header or "status" not in header or "b" not in header:
        sys.exit(f"plot_sweep.py: error: {path} lacks the point/status/b columns of sweep.csv")
    keys = header[header.index("point") + 1 : header.index("status")]
    return keys, rows


def apply_refit(sweep_dir, rows):
    """Replaces b, b_err, b_sys_err, mu_min, mu_max of every row by those of
    SWEEP_DIR/sweep_fit.csv; exits 2 when that file does not match sweep.csv."""
    path = os.path.join(sweep_dir, "sweep_fit.csv")
    header, fit_rows = read_csv(path)
    if "point" not in header or "b" not in header or "b_err" not in header:
        sys.exit(f"plot_sweep.py: error: {path} lacks the point/b/b_err columns of sweep_fit.csv")
    by_point = {r["point"]: r for r in fit_rows}
    for r in rows:
        f = by_point.get(r["point"])
        if f is None:
            # A point without a refit (failed, or sweep.csv newer than sweep_fit.csv): no b.
            r["b"] = ""
            continue
        for col in ("b", "b_err", "b_sys_err", "mu_min", "mu_max"):
            r[col] = f.get(col, "")


def as_number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def total_error(row):
    """sqrt(b_err^2 + b_sys_err^2), a missing part counted as 0."""
    stat = as_number(row.get("b_err")) or 0.0
    sys_ = as_number(row.get("b_sys_err")) or 0.0
    stat = 0.0 if math.isnan(stat) else stat
    sys_ = 0.0 if math.isnan(sys_) else sys_
    return math.hypot(stat, sys_)


def read_reference(path, keys):
    """(key, rows) of a reference CSV: a swept key's column and b."""
    if not os.path.isfile(path):
        sys.exit(f"plot_sweep.py: error: reference file {path} not found")
    header, rows = read_csv(path)
    key = next((k for k in header if k in keys), None)
    if key is None or "b" not in header:
        sys.exit(
            f"plot_sweep.py: error: {path} needs a column b and one named after a swept key "
            f"({', '.join(keys)})"
        )
    return key, rows


def make_figure(sweep_dir, use_fit=True, reference=None):
    """(figure, drawn points as dicts, source file name). Exits 2 on a folder of the wrong
    kind or when no point has a b."""
    keys, rows = read_sweep(sweep_dir)
    source = "sweep.csv"
    if use_fit and os.path.isfile(os.path.join(sweep_dir, "sweep_fit.csv")):
        apply_refit(sweep_dir, rows)
        source = "sweep_fit.csv"
    ref_key, ref_rows = read_reference(reference, keys) if reference else (None, [])
    fitted = [r for r in rows if r["status"] == "ok" and as_number(r["b"]) is not None
              and not math.isnan(float(r["b"]))]
    if not fitted:
        sys.exit(
            f"plot_sweep.py: error: no point of {sweep_dir} has a b in {source} "
            "(a continuous-mode sweep, or every fit failed): nothing to plot"
        )
    left_out = len(rows) - len(fitted)
    drawn = []

    fig, axes = plt.subplots(1, len(keys), figsize=(5.2 * len(keys), 5.0), squeeze=False)
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
            err = [total_error(r) for r in members]
            label = ", ".join(f"{k} = {v}" for k, v in zip(others, group)) or None
            ax.errorbar(x, y, yerr=err, marker="o", capsize=3, label=label)
            for r, xi, yi, ei in zip(members, x, y, err):
                drawn.append({"panel": key, "line": label or "", "x": xi, "b": yi,
                              "b_err": r.get("b_err", ""), "b_sys_err": r.get("b_sys_err", ""),
                              "total_err": ei, "source": source})
        if key == ref_key:
            rx, ry, re = [], [], []
            for r in ref_rows:
                v = r[key]
                xv = as_number(v) if numeric else (categories.index(v) if v in categories else None)
                if xv is None or as_number(r["b"]) is None:
                    continue
                rx.append(xv)
                ry.append(float(r["b"]))
                re.append(as_number(r.get("b_err")) or 0.0)
            if rx:
                texts = sorted({r.get("source", "") for r in ref_rows} - {""})
                ax.errorbar(rx, ry, yerr=re if any(re) else None, ls="none", marker="D",
                            mfc="none", mec="black", ecolor="black", ms=8, capsize=3,
                            label="; ".join(texts) or "published")
        if numeric:
            xs = [as_number(r[key]) for r in fitted]
            if min(xs) > 0 and max(xs) / min(xs) > 100:
                ax.set_xscale("log")
        else:
            ax.set_xticks(range(len(categories)))
            ax.set_xticklabels(categories)
        ax.set_xlabel(key)
        ax.set_ylabel("b (binned MLE) ± total error")
        ax.grid(alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            # Outside the axes, below the key's label: it cannot cover a point or an error bar.
            ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16),
                      borderaxespad=0.0, ncol=2, frameon=False)
    title = (f"{os.path.basename(os.path.normpath(sweep_dir))}: b against the swept keys "
             f"(from {source}; error bars: statistical and systematic in quadrature)")
    if left_out:
        title += f"\n{left_out} point(s) without b left out"
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return fig, drawn, source


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sweep_dir")
    ap.add_argument("--out", help="PNG to write (default SWEEP_DIR/sweep_b.png)")
    ap.add_argument("--sweep-csv", action="store_true",
                    help="draw sweep.csv's b even where sweep_fit.csv exists")
    ap.add_argument("--reference", metavar="CSV",
                    help="published values to draw beside the points (a swept key's column, b)")
    ap.add_argument("--dump", metavar="CSV", help="write the drawn points to CSV")
    args = ap.parse_args()
    read_sweep(args.sweep_dir)
    out = args.out or os.path.join(args.sweep_dir, "sweep_b.png")
    inputs = [os.path.join(args.sweep_dir, n) for n in ("sweep.csv", "sweep_fit.csv")]
    if args.reference:
        inputs.append(args.reference)
    bkquake_io.check_output_or_exit(out, inputs, "plot_sweep.py")
    if args.dump and any(os.path.realpath(args.dump) == os.path.realpath(p)
                         for p in inputs + [out]):
        sys.exit(f"plot_sweep.py: error: --dump {args.dump} is an input or the figure; "
                 "choose another file")
    fig, drawn, source = make_figure(args.sweep_dir, not args.sweep_csv, args.reference)
    bkquake_io.save_figure(fig, out, inputs, "plot_sweep.py", dpi=110, bbox_inches="tight")
    print(f"plot_sweep.py: wrote {out} (b from {source})")
    if args.dump:
        with open(args.dump, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(drawn[0].keys()))
            w.writeheader()
            w.writerows(drawn)
        print(f"plot_sweep.py: wrote {args.dump}")


if __name__ == "__main__":
    main()
