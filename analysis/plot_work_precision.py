#!/usr/bin/python3
"""Work-precision plot of a `bkquake accuracy` folder: error against time per event.

Left panel: median relative error of the event moment against the event-located
reference (per-event errors from identical pre-event states), log-log, one curve per
scheme, each point labelled with its dt (adaptive: its tolerance). Right panel: the
Kolmogorov-Smirnov distance of each long run's magnitude distribution from the
reference run's, with the noise floor (the reference from another seed) as a band:
points under it are statistically as good as the reference. Unstable or failed points
are drawn as crosses on the bottom axis, not dropped.

Usage: /usr/bin/python3 analysis/plot_work_precision.py ACCURACY_DIR [--out FILE.png] [--title T]
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

STYLE = {
    "rk2": ("tab:red", "o"),
    "rk4": ("tab:blue", "s"),
    "verlet": ("tab:green", "^"),
    "theta": ("tab:purple", "D"),
    "adaptive": ("black", "v"),
}


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{path}: no rows")
    need = {"scheme", "dt", "tolerance", "status", "moment_error_median", "ks_distance", "seconds_per_event"}
    missing = need - set(rows[0].keys())
    if missing:
        sys.exit(f"{path}: missing columns {sorted(missing)}")
    return rows


def num(row, key):
    text = row.get(key, "")
    return float(text) if text not in ("", None) else None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder", help="output folder of bkquake accuracy (holds accuracy.csv)")
    ap.add_argument("--out", help="PNG to write (default: FOLDER/work_precision.png)")
    ap.add_argument("--title", default=None)
    args = ap.parse_args()
    rows = read_rows(os.path.join(args.folder, "accuracy.csv"))
    out = args.out or os.path.join(args.folder, "work_precision.png")

    fig, (ax_e, ax_ks) = plt.subplots(1, 2, figsize=(12, 5))
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
        ax_e.loglog(t, err, marker=marker, color=color, label=scheme)
        ax_ks.semilogx(t, ks, marker=marker, color=color, label=scheme)
        for r, x, y in zip(ok, t, err):
            tag = f"tol {r['tolerance']}" if scheme == "adaptive" else f"dt {r['dt']}"
            ax_e.annotate(tag, (x, y), textcoords="offset points", xytext=(4, 3), fontsize=7, color=color)
        if bad:
            label = f"{scheme}: " + ", ".join(f"dt {r['dt']} {r['status']}" for r in bad)
            ax_e.plot([], [], "x", color=color, label=label)
    if floor is not None:
        ax_ks.axhspan(0, num(floor, "ks_distance"), color="0.85", label="noise floor (reference, other seed)")
    if reference is not None:
        ax_e.axvline(num(reference, "seconds_per_event"), color="0.6", ls=":", label="reference long run")
        ax_ks.axvline(num(reference, "seconds_per_event"), color="0.6", ls=":")
    ax_e.set_xlabel("wall seconds per event")
    ax_e.set_ylabel("median |M - M_ref| / M_ref per event")
    ax_e.set_title("per-event error vs cost")
    ax_ks.set_xlabel("wall seconds per event")
    ax_ks.set_ylabel("KS distance of the magnitude distribution")
    ax_ks.set_title("statistics vs cost")
    ax_e.legend(fontsize=7)
    ax_ks.legend(fontsize=7)
    if args.title:
        fig.suptitle(args.title)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
