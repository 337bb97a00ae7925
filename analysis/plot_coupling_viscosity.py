#!/usr/bin/env python3
"""Large events with and without viscous coupling as the chain is refined, from the runs of
analysis/run_coupling_viscosity.sh (folders N<N>-eta<0|1> under RUNS).

A large event slips at least a tenth of the chain. Left: the distribution of the slipping
fraction blocks/N over the large events (complementary cumulative), one curve per N, solid
without dashpots and dashed with them. Right: the large events' mean slip per slipped block
(moment / blocks) against N. Prints, per run: N, eta, the large events' share of all events,
their mean slipping fraction and mean slip.

    /usr/bin/python3 analysis/plot_coupling_viscosity.py RUNS [--out PNG]
"""
import argparse
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bkquake_io  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs")
    ap.add_argument("--out", default="large_events.png")
    a = ap.parse_args()
    runs = []
    for name in sorted(os.listdir(a.runs)):
        m = re.fullmatch(r"N(\d+)-eta([01])", name)
        path = os.path.join(a.runs, name)
        if m and os.path.exists(os.path.join(path, "summary.json")):
            runs.append((int(m.group(1)), int(m.group(2)), path))
    if not runs:
        sys.exit(f"plot_coupling_viscosity.py: no runs N<N>-eta<0|1> with a summary.json in {a.runs}")
    runs.sort()
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    slips = {0: ([], []), 1: ([], [])}
    print("blocks,viscous,large_share,mean_fraction,mean_slip")
    for n, on, path in runs:
        cat = bkquake_io.load_catalog(path)
        frac = np.asarray(cat["blocks"], dtype=float) / n
        large = frac >= 0.1
        if not large.any():
            print(f"{n},{on},0,,")
            continue
        slip = np.asarray(cat["moment"])[large] / np.asarray(cat["blocks"], dtype=float)[large]
        print(f"{n},{on},{large.mean():.4g},{frac[large].mean():.4g},{slip.mean():.4g}")
        f = np.sort(frac[large])
        left.step(f, 1.0 - np.arange(len(f)) / len(f), where="post",
                  linestyle="--" if on else "-", label=f"N = {n}, {'eta > 0' if on else 'eta = 0'}")
        slips[on][0].append(n)
        slips[on][1].append(slip.mean())
    left.set_xlabel("fraction of the chain that slipped (large events)")
    left.set_ylabel("share of large events at or above")
    left.set_title("large events as the chain is refined")
    left.legend(fontsize=8)
    for on, (ns, s) in slips.items():
        right.plot(ns, s, marker="o", linestyle="--" if on else "-",
                   label="with dashpots" if on else "without")
    right.set_xscale("log", base=2)
    right.set_xlabel("blocks N (l = 10 N/100)")
    right.set_ylabel("mean slip per slipped block")
    right.set_title("large events' slip")
    right.legend()
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
