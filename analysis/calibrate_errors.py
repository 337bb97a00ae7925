#!/usr/bin/python3
"""Calibrates the statistical errors of b and tau between seeds.

Runs each case's scene with seeds 1..S (skipping runs already in WORK), fits every run on a
fixed window (b: mu in [mu_min, mu_max); tau: the size measure on [x_min, x_max]) and
compares the standard deviation of the estimates between seeds with the mean error the
fits report: Shi & Bolt (b) or Fisher (tau), which treat events as independent, and the
block bootstrap over the catalogue's order (b_mle_boot_err, tau's err). A ratio sd/err
near 1 means the error describes the spread; with S seeds the sd itself is uncertain by
about 1/sqrt(2 (S - 1)) (16 % at 20 seeds, 13 % at 30).

    PYTHONPATH=build/python /usr/bin/python3 analysis/calibrate_errors.py \\
        --bkquake build/bkquake --work calib --jobs 2 [--case lattice --seeds 12] [--csv t.csv]

Prints a markdown table (the one in docs/validation/b-errors.md). Writes nothing but the
runs under WORK and the --csv file when given.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import bkquake

# name: scene (under data/scenes), seeds, events, transient (None: the scene's), b window,
# tau's measure and range.
CASES = {
    "a1": ("cl-l10-a1-n100.ini", 30, 100_000, None, (-7.6, -2.0), ("blocks", 2, 50)),
    "a2.5": ("cl-l10-a2.5-n100.ini", 30, 100_000, None, (-7.6, -2.0), ("blocks", 2, 50)),
    "a3": ("cl-l10-a3-n100.ini", 30, 100_000, None, (-7.6, -2.0), ("blocks", 2, 50)),
    "lattice": ("lattice/bk-nearest-l3-a2-64x64.ini", 24, 30_000, 20_000, (-6.0, -3.0),
                ("blocks", 2, 100)),
}


def sci(n):
    """3·10⁴ for 30000."""
    e = int(math.floor(math.log10(n)))
    m = n / 10**e
    sup = str(e).translate(str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹"))
    return (f"{m:g}·" if m != 1 else "") + "10" + sup


def run_one(args, scene, seed, events, transient, folder):
    if os.path.exists(os.path.join(folder, "summary.json")):
        return
    cmd = [args.bkquake, "run", scene, "--set", f"run.events={events}", "--set",
           f"run.seed={seed}", "--out", folder, "--force"]
    if transient is not None:
        cmd += ["--set", f"run.transient_events={transient}"]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


def spread(values, errors):
    sd = statistics.stdev(values)
    return statistics.mean(values), sd, [statistics.mean(e) for e in errors]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--bkquake", default="build/bkquake")
    p.add_argument("--scenes", default="data/scenes")
    p.add_argument("--work", required=True, help="folder for the runs (reused when present)")
    p.add_argument("--jobs", type=int, default=2, choices=[1, 2])
    p.add_argument("--case", action="append", choices=sorted(CASES), help="default: all")
    p.add_argument("--seeds", type=int, help="seeds 1..S (default: the case's)")
    p.add_argument("--csv", help="also write one row per run and estimate here")
    args = p.parse_args()
    rows, per_run = [], []
    for name in args.case or list(CASES):
        scene, seeds, events, transient, (lo, hi), (measure, x_min, x_max) = CASES[name]
        seeds = args.seeds or seeds
        folders = [os.path.join(args.work, f"{name}_s{s}") for s in range(1, seeds + 1)]
        with ThreadPoolExecutor(args.jobs) as pool:
            list(pool.map(lambda sf: run_one(args, os.path.join(args.scenes, scene), sf[0],
                                             events, transient, sf[1]),
                          zip(range(1, seeds + 1), folders)))
        b, b_sb, b_boot, b_block, t, t_fi, t_boot, t_block = ([] for _ in range(8))
        for s, folder in zip(range(1, seeds + 1), folders):
            r = bkquake.load(folder).fit(mu_min=lo, mu_max=hi, measure=measure, x_min=x_min,
                                         x_max=x_max)
            f, tau = r["fit"], r["tau"]
            b.append(f["b_mle"]), b_sb.append(f["b_mle_err"])
            b_boot.append(f["b_mle_boot_err"]), b_block.append(f["boot_block"])
            t.append(tau["value"]), t_fi.append(tau["err_fisher"])
            t_boot.append(tau["err"]), t_block.append(tau["boot_block"])
            per_run.append((name, s, f["b_mle"], f["b_mle_err"], f["b_mle_boot_err"],
                            f["boot_block"], tau["value"], tau["err_fisher"], tau["err"],
                            tau["boot_block"]))
        size = f"{seeds} × {sci(events)}" + (f" ({sci(transient)} transient)" if transient else "")
        for what, rng, v, e_ind, e_boot, blocks in (
                ("b", f"μ in [{lo}, {hi})", b, b_sb, b_boot, b_block),
                ("τ", f"{measure} in [{x_min}, {x_max}]", t, t_fi, t_boot, t_block)):
            mean, sd, (m_ind, m_boot) = spread(v, [e_ind, e_boot])
            rows.append(f"| `{scene}` | {what} | {rng} | {size} | {mean:.3f} | {sd:.4f} | "
                        f"{m_ind:.4f} ({sd / m_ind:.2f}) | {m_boot:.4f} ({sd / m_boot:.2f}) | "
                        f"{int(statistics.median(blocks))} |")
    print("| scene | estimate | range | seeds × events | mean | sd between seeds | "
          "mean independent-event error (sd/err) | mean bootstrap error (sd/err) | "
          "median block |")
    print("|---|---|---|---|---|---|---|---|---|")
    print("\n".join(rows))
    if args.csv:
        with open(args.csv, "w") as out:
            out.write("case,seed,b,b_err,b_boot_err,b_block,tau,tau_err_fisher,tau_err,"
                      "tau_block\n")
            for r in per_run:
                out.write(",".join(str(x) for x in r) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
