#!/usr/bin/env -S /usr/bin/python3
"""Draw a rate-and-state run's block samples (rsf_blocks.csv, written with output.blocks = true).

    analysis/plot_rsf.py RUN_DIR [--blocks J ...] [--out PNG]

Left column: slip rate (log scale), state theta (log scale) and frictional stress sigma f
against time for the chosen blocks (default: the first sampled block). Right: the space-time
picture of log10 slip rate over every sampled block, when more than one was sampled. The
catalogue's events are marked on the time axes (their load / V_pl is the hypocentre time).
Default output: rsf.png in RUN_DIR. Runs with Debian's python3 (numpy and matplotlib).
"""

import argparse
import csv
import os
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_samples(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.DictReader(f)]
    if not rows:
        raise SystemExit(f"{path}: no samples")
    cols = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    cols["block"] = cols["block"].astype(int)
    return cols


def plate_rate(run_dir):
    """drive.speed from the run's scene.ini (V_pl, m/s)."""
    section = ""
    with open(os.path.join(run_dir, "scene.ini")) as f:
        for line in f:
            line = line.strip()
            if line.startswith("["):
                section = line.strip("[]")
            m = re.match(r"speed\s*=\s*(\S+)", line)
            if section == "drive" and m:
                return float(m.group(1))
    return None


def event_times(run_dir, v_pl):
    path = os.path.join(run_dir, "catalog.csv")
    if not v_pl or not os.path.exists(path):
        return np.array([])
    with open(path, newline="") as f:
        return np.array([float(r["load"]) / v_pl for r in csv.DictReader(f)])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run_dir")
    ap.add_argument("--blocks", type=int, nargs="*")
    ap.add_argument("--out")
    a = ap.parse_args()
    s = read_samples(os.path.join(a.run_dir, "rsf_blocks.csv"))
    blocks = sorted(set(s["block"].tolist()))
    chosen = a.blocks or blocks[:1]
    events = event_times(a.run_dir, plate_rate(a.run_dir))
    space_time = len(blocks) > 1
    fig, axes = plt.subplots(3, 2 if space_time else 1, figsize=(12 if space_time else 7, 8),
                             squeeze=False, sharex="col")
    for j in chosen:
        sel = s["block"] == j
        t = s["t"][sel]
        axes[0][0].semilogy(t, s["slip_rate"][sel], label=f"block {j}")
        axes[1][0].semilogy(t, s["theta"][sel])
        axes[2][0].plot(t, s["shear_stress"][sel] / 1e6)
    for ax in (axes[0][0], axes[1][0], axes[2][0]):
        for te in events:
            ax.axvline(te, color="0.85", lw=0.5, zorder=0)
    axes[0][0].set_ylabel("slip rate V [m/s]")
    axes[1][0].set_ylabel("state theta [s]")
    axes[2][0].set_ylabel("sigma f [MPa]")
    axes[2][0].set_xlabel("time [s]")
    axes[0][0].legend(fontsize=8)
    if space_time:
        times = np.unique(s["t"])
        grid = np.full((len(blocks), len(times)), np.nan)
        ti = np.searchsorted(times, s["t"])
        bi = np.searchsorted(blocks, s["block"])
        grid[bi, ti] = np.log10(s["slip_rate"])
        gs = axes[0][1].get_gridspec()
        for row in axes:
            row[1].remove()
        ax = fig.add_subplot(gs[:, 1])
        im = ax.imshow(grid, aspect="auto", origin="lower", cmap="magma",
                       extent=[times[0], times[-1], blocks[0] - 0.5, blocks[-1] + 0.5])
        fig.colorbar(im, ax=ax, label="log10 V [m/s]")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("block")
        ax.set_title("slip rate along the chain")
    fig.tight_layout()
    out = a.out or os.path.join(a.run_dir, "rsf.png")
    fig.savefig(out, dpi=120)
    print(f"written {out}")


if __name__ == "__main__":
    main()
