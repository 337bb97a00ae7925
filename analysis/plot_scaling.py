#!/usr/bin/env -S /usr/bin/python3
"""Scaling with the chain length: events per second and ns per sliding block-step against
N, log axes, from the CSV that analysis/scaling.sh prints.

Usage: /usr/bin/python3 analysis/plot_scaling.py scaling.csv [--out FILE.png]
Needs numpy and matplotlib: use Debian's /usr/bin/python3 (python3-numpy,
python3-matplotlib); the python3 first on PATH may lack them.
"""

import argparse
import csv

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv")
    ap.add_argument("--out", default="scaling.png")
    args = ap.parse_args()
    with open(args.csv) as f:
        rows = list(csv.DictReader(f))
    n = [float(r["blocks"]) for r in rows]
    fig, (a, b) = plt.subplots(1, 2, figsize=(9, 3.6))
    a.loglog(n, [float(r["events_per_second"]) for r in rows], "o-")
    a.set_xlabel("blocks N")
    a.set_ylabel("events per second")
    a.set_title("event rate")
    b.loglog(n, [float(r["ns_per_sliding_block_step"]) for r in rows], "s-",
             label="per sliding block-step")
    b.loglog(n, [float(r["ns_per_block_step"]) for r in rows], "^-",
             label="per block-step (stepped blocks)")
    b.set_xlabel("blocks N")
    b.set_ylabel("ns (whole run's wall time)")
    b.set_title("cost per block-step")
    b.legend(fontsize=8)
    for ax in (a, b):
        ax.grid(True, which="both", alpha=0.3)
    fig.suptitle("carlson-langer l = 10, alpha = 2.5, rk4 dt = 0.01, one core", fontsize=9)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)


if __name__ == "__main__":
    main()
