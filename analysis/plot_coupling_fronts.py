#!/usr/bin/env python3
"""Rupture fronts with and without viscous coupling as the chain is refined, from the
continuous runs of analysis/run_coupling_fronts.sh (folders N<N>-eta<ETA0> under RUNS, each
with blocks.csv: every block's displacement and velocity every output.every).

A block slips while its velocity differs from a stuck block's (minus the drive speed:
displacements are measured from the drive) by more than THRESHOLD (default 0.1, a tenth
of the large events' typical slip speed; slow creep below it is not a front). A large
event is a stretch of samples in which some block slips (gaps of at most 1 % of the
samples) that slips at least a quarter of the chain. A block's onset is the time at which
it first slips, linearly interpolated between samples. A front is a run of adjacent blocks
along which the onset rises monotonically (from a nucleation point to where it meets
another front or an end), at least a tenth of the chain and 8 blocks long. Over the middle
60 % of its blocks a least-squares line of onset time against position gives the front's
speed; two widths follow as the speed times a median time over the same blocks: the width
from the onset to half the block's largest velocity in the event (the rise), and the
leading edge from the onset (THRESHOLD) to twice THRESHOLD. Speeds are in units of the
sound speed (l blocks per unit time), widths in blocks and in fault length (blocks / N).

Panels: front speed, width and leading edge against N (medians, and every front); solid
without dashpots, dashed with. Prints one row per measured front and per run the
quartiles of the speed, the width and the leading edge over its fronts.

Large events that start before TRANSIENT (default 150 time units) are left out: the first
chain-wide event after the random start releases the start's disorder, and its blocks fail
nearly together rather than behind a front.

    /usr/bin/python3 analysis/plot_coupling_fronts.py RUNS [--threshold V] [--transient T]
                                                      [--out PNG]
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


def load_blocks(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
    n = sum(1 for h in header if h.startswith("u"))
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return data[:, 0], data[:, 1:1 + n], data[:, 1 + n:1 + 2 * n]


def crossing(t, x, level, start):
    """First time at or after sample `start` at which x reaches `level`, linearly
    interpolated; None if it never does."""
    above = np.nonzero(x[start:] >= level)[0]
    if len(above) == 0:
        return None
    k = start + above[0]
    if k == 0 or x[k - 1] >= level:
        return t[k]
    return t[k - 1] + (level - x[k - 1]) / (x[k] - x[k - 1]) * (t[k] - t[k - 1])


def fronts(t, v, stuck, threshold, min_fraction=0.25, transient=0.0):
    n = v.shape[1]
    rel = np.abs(v - stuck)
    sliding = rel > threshold
    active = sliding.any(axis=1)
    gap = max(1, len(t) // 100)
    out = []
    k = 0
    while k < len(t):
        if not active[k]:
            k += 1
            continue
        end = k
        while end + 1 < len(t) and active[end + 1:end + 1 + gap].any():
            end += 1
        window = slice(k, end + 1)
        slipped = sliding[window].any(axis=0)
        if slipped.sum() >= min_fraction * n and k > 0 and t[k] >= transient:
            out.extend(event_fronts(t[window], rel[window], sliding[window], threshold,
                                    max(8, n // 10)))
        k = end + 1
    return out


def event_fronts(t, rel, sliding, threshold, min_blocks):
    n = rel.shape[1]
    onset = np.full(n, np.nan)
    rise = np.full(n, np.nan)
    edge = np.full(n, np.nan)
    for j in range(n):
        first = np.nonzero(sliding[:, j])[0]
        if len(first) == 0:
            continue
        t0 = crossing(t, rel[:, j], threshold, 0)
        half = crossing(t, rel[:, j], 0.5 * rel[:, j].max(), first[0])
        double = crossing(t, rel[:, j], 2 * threshold, first[0])
        onset[j] = t0
        if half is not None:
            rise[j] = half - t0
        if double is not None:
            edge[j] = double - t0
    # Split the slipped blocks into runs along which the onset rises monotonically (each
    # run is one front, from a nucleation point to where it meets another front or an end).
    result = []
    j = 0
    while j < n - 1:
        if np.isnan(onset[j]) or np.isnan(onset[j + 1]) or onset[j + 1] == onset[j]:
            j += 1
            continue
        side = 1 if onset[j + 1] > onset[j] else -1
        k = j + 1
        while k + 1 < n and not np.isnan(onset[k + 1]) and side * (onset[k + 1] - onset[k]) > 0:
            k += 1
        if k - j + 1 >= min_blocks:
            lo, hi = j + int(0.2 * (k - j + 1)), j + int(0.8 * (k - j + 1))
            sel = np.arange(lo, hi + 1)
            slope, _ = np.polyfit(sel.astype(float), onset[sel], 1)
            speed = 1.0 / abs(slope)  # blocks per unit time
            width = speed * np.nanmedian(rise[sel])
            edge_width = speed * np.nanmedian(edge[sel])
            result.append((t[0], side, k - j + 1, speed, width, edge_width))
        j = k
    return result


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs")
    ap.add_argument("--threshold", type=float, default=0.1)
    ap.add_argument("--transient", type=float, default=150.0)
    ap.add_argument("--out", default="fronts.png")
    a = ap.parse_args()
    runs = []
    for name in sorted(os.listdir(a.runs)):
        m = re.fullmatch(r"N(\d+)-eta([0-9.]+)", name)
        path = os.path.join(a.runs, name)
        if m and os.path.exists(os.path.join(path, "blocks.csv")):
            runs.append((float(m.group(2)), int(m.group(1)), path))
    if not runs:
        sys.exit(f"plot_coupling_fronts.py: no runs N<N>-eta<ETA0> with a blocks.csv in {a.runs}")
    runs.sort()
    fig, (left, right, edge_ax) = plt.subplots(1, 3, figsize=(15, 4.2))
    print("blocks,eta0,event_start,direction,front_blocks,speed_over_l,width_blocks,width_length,"
          "edge_blocks,edge_length")
    table = []
    curves = {}
    for eta0, n, path in runs:
        scene = bkquake_io.load_scene(path)
        l = float(scene["model"]["l"])
        t, _, v = load_blocks(os.path.join(path, "blocks.csv"))
        stuck = -float(scene["drive"]["speed"])  # a stuck block moves back with the drive
        fr = fronts(t, v, stuck, a.threshold, transient=a.transient)
        for t0, side, extent, speed, width, edge in fr:
            print(f"{n},{eta0:g},{t0:.6g},{side},{extent},{speed / l:.4g},{width:.4g},"
                  f"{width / n:.4g},{edge:.4g},{edge / n:.4g}")
        if not fr:
            table.append((n, eta0, 0, [float("nan")] * 3, [float("nan")] * 3, [float("nan")] * 3))
            continue
        speeds = np.array([f[3] / l for f in fr])
        widths = np.array([f[4] for f in fr])
        edges = np.array([f[5] for f in fr])
        edges = edges[np.isfinite(edges)]
        table.append((n, eta0, len(fr), np.percentile(speeds, [25, 50, 75]),
                      np.percentile(widths, [25, 50, 75]), np.percentile(edges, [25, 50, 75])))
        c = curves.setdefault(eta0, {"n": [], "s": [], "w": [], "e": []})
        c["n"].append(n)
        c["s"].append(speeds)
        c["w"].append(widths / n)
        c["e"].append(edges / n)
    print("blocks,eta0,fronts,speed_over_l_q25,q50,q75,width_blocks_q25,q50,q75,"
          "median_width_length,edge_blocks_q25,q50,q75,median_edge_length")
    for n, eta0, count, s, w, e in table:
        print(f"{n},{eta0:g},{count},{s[0]:.3g},{s[1]:.3g},{s[2]:.3g},{w[0]:.3g},{w[1]:.3g},"
              f"{w[2]:.3g},{w[1] / n:.3g},{e[0]:.3g},{e[1]:.3g},{e[2]:.3g},{e[1] / n:.3g}")
    for eta0, c in sorted(curves.items()):
        style = "-" if eta0 == 0 else "--"
        label = "eta = 0" if eta0 == 0 else f"eta = {eta0:g} (N/100)^2"
        colour = None
        for ax, key in ((left, "s"), (right, "w"), (edge_ax, "e")):
            line = ax.plot(c["n"], [np.median(x) for x in c[key]], style, marker="o",
                           color=colour, label=label)[0]
            colour = line.get_color()
            for n, xs in zip(c["n"], c[key]):
                ax.scatter([n] * len(xs), xs, s=8, alpha=0.4, color=colour)
    for ax in (left, right, edge_ax):
        ax.set_xscale("log", base=2)
        ax.set_xlabel("blocks N (l = 10 N/100)")
        ax.legend()
    left.set_ylabel("front speed / sound speed l")
    left.set_title("rupture front speed (median, and every front)")
    right.set_yscale("log")
    right.set_ylabel("front width / fault length")
    right.set_title("front width: speed x rise to half the peak")
    edge_ax.set_yscale("log")
    edge_ax.set_ylabel("leading edge / fault length")
    edge_ax.set_title("leading edge: speed x rise from 0.1 to 0.2")
    fig.tight_layout()
    bkquake_io.save_figure(fig, a.out, [p for _, _, p in runs], "plot_coupling_fronts.py", dpi=110)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
