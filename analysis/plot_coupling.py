#!/usr/bin/env python3
"""b against the coupling's range R, and the magnitude distributions, from the runs of
analysis/run_coupling_b.sh (folders <law>-N<N>-R<R> under RUNS).

Left: the binned-MLE b of each run with its statistical error (bars) and its systematic
error over the fit windows (shaded), one line per friction law and chain length N (solid:
the smallest N, dashed: larger; --blocks N keeps one N). Right: the magnitude
distributions (events per unit magnitude per recorded event) of the first law at the
largest N, one curve per R. Prints a table of R, law, b, errors and the largest event's blocks.

    /usr/bin/python3 analysis/plot_coupling.py RUNS [--blocks N] [--out PNG]
"""
import argparse
import json
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bkquake_io  # noqa: E402


def runs_of(root, blocks):
    found = {}
    for name in sorted(os.listdir(root)):
        m = re.fullmatch(r"(\w+)-N(\d+)-R(\d+)", name)
        if not m or (blocks and int(m.group(2)) != blocks):
            continue
        path = os.path.join(root, name)
        if not os.path.exists(os.path.join(path, "summary.json")):
            continue
        found.setdefault((m.group(1), int(m.group(2))), []).append((int(m.group(3)), path))
    for law in found:
        found[law].sort()
    return found


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs")
    ap.add_argument("--blocks", type=int, default=0)
    ap.add_argument("--out", default="b_vs_range.png")
    a = ap.parse_args()
    found = runs_of(a.runs, a.blocks)
    if not found:
        sys.exit(f"plot_coupling.py: no runs <law>-N<N>-R<R> with a summary.json in {a.runs}")
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    print("law,blocks,range,b,b_err,b_sys_err,events,largest_blocks")
    sizes = sorted({n for _, n in found})
    for (law, n), runs in sorted(found.items()):
        rs, bs, errs, syss = [], [], [], []
        for r, path in runs:
            s = json.load(open(os.path.join(path, "summary.json")))
            if s.get("b_mle") is None:
                continue
            cat = bkquake_io.load_catalog(path)
            largest = int(max(cat["blocks"]))
            print(f"{law},{n},{r},{s['b_mle']:.4f},{s['b_mle_err']:.4f},"
                  f"{s.get('b_mle_sys_err', float('nan')):.4f},{s['events']},{largest}")
            rs.append(r)
            bs.append(s["b_mle"])
            errs.append(s["b_mle_err"])
            syss.append(s.get("b_mle_sys_err") or 0.0)
        style = "-" if n == sizes[0] else "--"
        line = left.errorbar(rs, bs, yerr=errs, marker="o" if n == sizes[0] else "s", capsize=3,
                             linestyle=style, label=f"{law}, N = {n}")
        left.fill_between(rs, [b - e for b, e in zip(bs, syss)], [b + e for b, e in zip(bs, syss)],
                          color=line[0].get_color(), alpha=0.15)
    left.set_xscale("log")
    left.set_xlabel("range R (model.range)")
    left.set_ylabel("b (binned MLE)")
    left.set_title("b against the coupling's range")
    left.legend()
    law, n = min(found, key=lambda k: (k[0], -k[1]))
    for r, path in found[(law, n)]:
        h = bkquake_io.load_histogram(path)
        events = json.load(open(os.path.join(path, "summary.json")))["events"]
        mids = [(lo + hi) / 2 for lo, hi in zip(h["mu_low"], h["mu_high"])]
        dens = [c / ((hi - lo) * events) for c, lo, hi in zip(h["count"], h["mu_low"], h["mu_high"])]
        keep = [(m, d) for m, d in zip(mids, dens) if d > 0]
        right.semilogy([m for m, _ in keep], [d for _, d in keep], label=f"R = {r}")
    right.set_xlabel("magnitude μ = ln M")
    right.set_ylabel("events per unit μ per event")
    right.set_title(f"magnitude distributions ({law}, N = {n})")
    right.legend()
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
