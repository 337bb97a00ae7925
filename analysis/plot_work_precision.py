#!/usr/bin/env -S /usr/bin/python3
"""Work-precision plot of a `bkquake accuracy` folder: error against time per event.

Left panel: median relative error of the event moment against the event-located
reference (per-event errors from identical pre-event states), log-log, one curve per
scheme, each point labelled with its dt (adaptive: its tolerance); labels are placed
where they overlap neither each other nor the points. Right panel: the
Kolmogorov-Smirnov distance of each long run's magnitude distribution from the
reference run's, on a log axis (the distances span two decades or more), with the noise
floor (the reference from another seed) as a band: points in it are statistically as
good as the reference. Unstable or failed points are listed in the legend, not dropped.

Usage: /usr/bin/python3 analysis/plot_work_precision.py ACCURACY_DIR|accuracy.csv [--out FILE.png] [--title T]
A folder without accuracy.csv (or a CSV without its columns) is refused with one line.
Needs numpy and matplotlib: use Debian's /usr/bin/python3 (python3-numpy,
python3-matplotlib); the python3 first on PATH may lack them.
"""

import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import bkquake_io  # noqa: E402

STYLE = {
    "rk2": ("tab:red", "o"),
    "rk4": ("tab:blue", "s"),
    "verlet": ("tab:green", "^"),
    "theta": ("tab:purple", "D"),
    "adaptive": ("black", "v"),
    # integrator.transitions = located (accuracy.csv's transitions column): dashed, hollow.
    "rk2 located": ("tab:red", "o"),
    "rk4 located": ("tab:blue", "s"),
    "verlet located": ("tab:green", "^"),
}


def fail(message):
    print(f"plot_work_precision.py: {message}", file=sys.stderr)
    sys.exit(2)


def read_rows(path):
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except (OSError, UnicodeDecodeError, csv.Error) as e:
        fail(f"{path}: cannot read ({e})")
    if not rows:
        fail(f"{path}: no rows")
    need = {"scheme", "dt", "tolerance", "status", "moment_error_median", "ks_distance", "seconds_per_event"}
    missing = need - set(rows[0].keys())
    if missing:
        fail(f"{path}: missing columns {sorted(missing)} (not an accuracy.csv of bkquake accuracy)")
    return rows


def place_labels(ax, items, fontsize=7):
    """Annotates (text, x, y, colour) items at the first offset where the label overlaps
    no earlier label and no point (display coordinates, after the axes are final)."""
    fig = ax.figure
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    points = [ax.transData.transform((x, y)) for _, x, y, _ in items]
    taken = []
    frame = ax.get_window_extent(renderer)
    offsets = [(4, 3), (4, -11), (-4, 3), (-4, -11), (4, 12), (4, -20), (-4, 12), (-4, -20),
               (4, 21), (4, -29), (-4, 21), (-4, -29)]
    for text, x, y, colour in items:
        for dx, dy in offsets:
            a = ax.annotate(text, (x, y), textcoords="offset points", xytext=(dx, dy),
                            ha="left" if dx > 0 else "right", fontsize=fontsize, color=colour)
            box = a.get_window_extent(renderer).expanded(1.05, 1.1)
            hits_point = any(box.contains(px, py) for px, py in points)
            inside = frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0 and box.y1 <= frame.y1
            if inside and not hits_point and not any(box.overlaps(t) for t in taken):
                taken.append(box)
                break
            a.remove()
        else:  # nowhere free: the first place, as before
            a = ax.annotate(text, (x, y), textcoords="offset points", xytext=offsets[0],
                            fontsize=fontsize, color=colour)
            taken.append(a.get_window_extent(renderer))


def num(row, key):
    text = row.get(key, "")
    return float(text) if text not in ("", None) else None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder", help="output folder of bkquake accuracy (holds accuracy.csv)")
    ap.add_argument("--out", help="PNG to write (default: FOLDER/work_precision.png)")
    ap.add_argument("--title", default=None)
    args = ap.parse_args()
    if os.path.isdir(args.folder):
        csv_path = os.path.join(args.folder, "accuracy.csv")
        if not os.path.exists(csv_path):
            fail(f"{args.folder} has no accuracy.csv: not an output folder of bkquake accuracy")
        out = args.out or os.path.join(args.folder, "work_precision.png")
    elif os.path.isfile(args.folder):
        csv_path = args.folder
        out = args.out or os.path.splitext(csv_path)[0] + "_work_precision.png"
    else:
        fail(f"{args.folder}: no such folder or file")
    bkquake_io.check_output_or_exit(out, [csv_path], "plot_work_precision.py")
    rows = read_rows(csv_path)
    # Rows of located transitions are their own curve (a CSV without the column has none).
    for r in rows:
        if r.get("transitions") == "located" and r["scheme"] in ("rk2", "rk4", "verlet"):
            r["scheme"] += " located"

    fig, (ax_e, ax_ks) = plt.subplots(1, 2, figsize=(13, 5.5))
    labels = []
    floor = next((r for r in rows if r["scheme"] == "noise-floor"), None)
    reference = next((r for r in rows if r["scheme"] == "reference"), None)
    for scheme, (color, marker) in STYLE.items():
        pts = [r for r in rows if r["scheme"] == scheme]
        if not pts:
            continue
        ok = [r for r in pts if r["status"] == "ok" and num(r, "moment_error_median") is not None]
        bad = [r for r in pts if r["status"] != "ok"]
        ok.sort(key=lambda r: num(r, "seconds_per_event"))
        t = [num(r, "seconds_per_event") for r in ok]
        # An exact 0 cannot go on a log axis: show it at the smallest error we can print.
        err = [max(num(r, "moment_error_median"), 1e-16) for r in ok]
        ks = [num(r, "ks_distance") for r in ok]
        located = scheme.endswith(" located")
        line = dict(ls="--", markerfacecolor="none") if located else {}
        ax_e.loglog(t, err, marker=marker, color=color, label=scheme, **line)
        # A KS distance of exactly 0 (the same histogram) has no place on a log axis.
        pos = [(x, k) for x, k in zip(t, ks) if k is not None and k > 0]
        zero = len(ks) - len(pos)
        ax_ks.loglog([x for x, _ in pos], [k for _, k in pos], marker=marker, color=color, **line,
                     label=scheme + (f" ({zero} point{'s' * (zero > 1)} at KS = 0 not drawn)" if zero else ""))
        for r, x, y in zip(ok, t, err):
            tag = f"tol {r['tolerance']}" if scheme == "adaptive" else f"dt {r['dt']}"
            labels.append((tag, x, y, color))
        if bad:
            label = f"{scheme}: " + ", ".join(f"dt {r['dt']} {r['status']}" for r in bad)
            ax_e.plot([], [], "x", color=color, label=label)
    if floor is not None:
        positive = [num(r, "ks_distance") for r in rows if (num(r, "ks_distance") or 0) > 0]
        bottom = min(positive) / 2
        ax_ks.set_ylim(bottom=bottom)
        ax_ks.axhspan(bottom, num(floor, "ks_distance"), color="0.85",
                      label="noise floor (reference, other seed)")
    if reference is not None:
        ax_e.axvline(num(reference, "seconds_per_event"), color="0.6", ls=":", label="reference long run")
        ax_ks.axvline(num(reference, "seconds_per_event"), color="0.6", ls=":")
    ax_e.set_xlabel("wall seconds per event")
    ax_e.set_ylabel("median |M - M_ref| / M_ref per event")
    ax_e.set_title("per-event error vs cost")
    ax_ks.set_xlabel("wall seconds per event")
    ax_ks.set_ylabel("KS distance of the magnitude distribution (log)")
    ax_ks.set_title("statistics vs cost")
    ax_e.legend(fontsize=7)
    ax_ks.legend(fontsize=7)
    if args.title:
        fig.suptitle(args.title)
    fig.tight_layout()
    place_labels(ax_e, labels)
    bkquake_io.save_figure(fig, out, [csv_path], "plot_work_precision.py", dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
