#!/usr/bin/env -S /usr/bin/python3
"""Plots of the brake study (thesis ch. 4) from bkquake outputs.

Needs numpy and matplotlib: use Debian's /usr/bin/python3 (python3-numpy,
python3-matplotlib; the python3 first on PATH may lack them).

  plot_brake.py timeseries RUN_DIR [--signal pad_x|pad_v|pad_friction] [--from T0 --to T1]
      time series of a continuous run with segment boundaries and speeds (Figs. 4.1-4.3)
  plot_brake.py spectrum RUN_DIR      spectrum.csv of `bkquake spectrum`, peaks labelled,
                                      the natural frequencies marked (Figs. 4.13-4.14)
  plot_brake.py blocks RUN_DIR [--from T0 --to T1]
                                      blocks.csv trajectories over the pad (Figs. 4.11-4.12)
  plot_brake.py study STUDY_DIR       friction_study.csv of `bkquake friction-study` (Fig. 4.6)
  plot_brake.py amp-mean STUDY_DIR    amplitude against mean, v 0.08-0.19 (Fig. 4.9)
  plot_brake.py special STUDY_DIR     the study around the special speed (Fig. 4.15)

Each writes a PNG into the folder it reads (or --png FILE) and prints its path. A folder of
the wrong kind (an event-driven run, a run without the file) is a one-line error, exit 2.
"""

import argparse
import configparser
import csv
import os
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import bkquake_io  # noqa: E402

V_SPECIAL = 0.2785  # bkquake special-speed data/scenes/brake/bkp.ini (thesis: 0.28)


READ = []  # the files this invocation read: a figure is never written over one of them


def fail(msg):
    print(f"plot_brake.py: error: {msg}", file=sys.stderr)
    sys.exit(2)


def scene_of(run_dir):
    path = os.path.join(run_dir, "scene.ini")
    if not os.path.exists(path):
        fail(f"{run_dir} is not a run folder (no scene.ini)")
    READ.append(path)
    cp = configparser.ConfigParser(comment_prefixes=("#",), inline_comment_prefixes=None)
    with open(path) as f:
        cp.read_file(f)
    return cp


def require_continuous(run_dir):
    scene = scene_of(run_dir)
    mode = scene.get("drive", "mode", fallback="events")
    if mode != "continuous":
        fail(f"{run_dir} is a drive.mode = {mode} run; this plot needs a continuous run")
    return scene


def read_table(path):
    """Headed CSV ('#' lines skipped) -> dict name -> numpy array (text columns as str)."""
    if not os.path.exists(path):
        fail(f"{path} is missing")
    READ.append(path)
    with open(path) as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    header, body = rows[0], rows[1:]
    out = {}
    for k, name in enumerate(header):
        col = [r[k] for r in body]
        try:
            out[name] = np.array([float(x) for x in col])
        except ValueError:
            out[name] = np.array(col)
    return out


def save(fig, path):
    """Into the folder read (under its lock when bkquake wrote it) or --png, never over an
    input or a run's own file (bkquake_io.save_figure)."""
    fig.tight_layout()
    bkquake_io.save_figure(fig, path, READ, "plot_brake.py", dpi=120)
    print(path)


def span(t, a):
    lo = a.from_ if a.from_ is not None else t.min()
    hi = a.to if a.to is not None else t.max()
    return (t >= lo) & (t <= hi)


def cmd_timeseries(a):
    require_continuous(a.dir)
    ts = read_table(os.path.join(a.dir, "timeseries.csv"))
    t, y = ts["t"], ts[a.signal]
    m = span(t, a)
    fig, ax = plt.subplots(figsize=(11, 4))
    ax.plot(t[m], y[m], lw=0.4, color="tab:blue")
    seg_path = os.path.join(a.dir, "segments.csv")
    seg = read_table(seg_path) if os.path.exists(seg_path) else None
    shown = None
    if seg is not None:
        shown = (seg["t_end"] >= t[m].min()) & (seg["t_start"] <= t[m].max())
    if seg is not None and shown.sum() <= 60:
        for t0, t1, v in zip(seg["t_start"][shown], seg["t_end"][shown], seg["speed"][shown]):
            ax.axvline(t0, color="k", lw=0.6, ls=":")
            ax.axvspan(0.5 * (t0 + t1), t1, color="0.9", zorder=0)
            ax.text(max(t0, t[m].min()), 1.0, f" v={v:.3g}", transform=ax.get_xaxis_transform(),
                    va="bottom", fontsize=7)
    else:
        # A ramp, or a staircase of many short segments: the speed on a second axis.
        ax2 = ax.twinx()
        ax2.plot(t[m], ts["speed"][m], color="tab:red", lw=1)
        ax2.set_ylabel("speed", color="tab:red")
    ax.set_xlabel("t")
    ax.set_ylabel(a.signal)
    ax.set_title(f"{a.dir}: {a.signal} (shaded: each segment's last half, the input of segments.csv)",
                 fontsize=9, pad=14)
    save(fig, a.png or os.path.join(a.dir, f"timeseries_{a.signal}.png"))


def natural_lines(header_lines):
    return header_lines


def cmd_spectrum(a):
    require_continuous(a.dir)
    path = os.path.join(a.dir, "spectrum.csv")
    if not os.path.exists(path):
        fail(f"{a.dir} has no spectrum.csv: run 'bkquake spectrum {a.dir}' first")
    with open(path) as f:
        notes = [line[2:].strip() for line in f if line.startswith("#")]
    sp = read_table(path)
    f, amp = sp["frequency"], sp["amplitude"]
    fmax = a.fmax if a.fmax else min(f.max(), 3.0)
    m = (f > 0) & (f <= fmax)
    fig, ax = plt.subplots(figsize=(9, 4))
    ax.plot(f[m], amp[m], lw=0.8)
    # Peaks: local maxima above f = fmin, the five largest labelled.
    k = np.where(m[1:-1] & (amp[1:-1] > amp[:-2]) & (amp[1:-1] >= amp[2:]) & (f[1:-1] >= a.fmin))[0] + 1
    for i in k[np.argsort(amp[k])[::-1][:5]]:
        ax.annotate(f"{f[i]:.3f}", (f[i], amp[i]), textcoords="offset points", xytext=(3, 3),
                    fontsize=8, color="tab:red")
    scene = scene_of(a.dir)
    kind = scene.get("model", "kind", fallback="bk")
    if kind == "bkp":
        ax.axvline(0.2243, color="tab:green", ls="--", lw=0.8, label="pad f_d (eq. 4.6)")
    ax.axvline(2.256, color="tab:purple", ls="--", lw=0.8, label="block f (eq. 4.7)")
    ax.set_xlim(0, fmax)
    ax.set_xlabel("frequency")
    ax.set_ylabel("amplitude")
    ax.legend(fontsize=8)
    ax.set_title("\n".join(n for n in notes if n.startswith(("spectrum", "samples", "window"))),
                 fontsize=8)
    save(fig, a.png or os.path.join(a.dir, "spectrum.png"))


def cmd_blocks(a):
    require_continuous(a.dir)
    bl = read_table(os.path.join(a.dir, "blocks.csv"))
    ts = read_table(os.path.join(a.dir, "timeseries.csv"))
    t = bl["t"]
    m = span(t, a)
    fig, ax = plt.subplots(figsize=(11, 4))
    cols = [c for c in bl if c.startswith("u")]
    for c in cols[:6]:
        ax.plot(t[m], bl[c][m], lw=0.6, label=f"block {c[1:]}")
    mt = span(ts["t"], a)
    ax.plot(ts["t"][mt], ts["pad_x"][mt], color="k", lw=1.0, label="pad")
    ax.set_xlabel("t")
    ax.set_ylabel("position (lab frame)")
    ax.legend(fontsize=8, ncol=4)
    ax.set_title(f"{a.dir}: block and pad positions", fontsize=9)
    save(fig, a.png or os.path.join(a.dir, "blocks.png"))


COLOURS = {"bkp": "tab:red", "bk": "tab:green", "1dof": "tab:orange", "special-1dof": "k"}


def study(a):
    path = os.path.join(a.dir, "friction_study.csv")
    if not os.path.exists(path):
        fail(f"{a.dir} is not a friction-study folder (no friction_study.csv; run "
             "'bkquake friction-study --out DIR')")
    return read_table(path)


def draw_study(ax, st, lo, hi, seeds_band=True):
    cfg, seed = st["configuration"], st["seed"]
    for c in ["bkp", "bk", "1dof", "special-1dof"]:
        sel = cfg == c
        if not sel.any():
            continue
        first = seed[sel].min()
        s0 = sel & (seed == first)
        labelled = False
        for run in np.unique(st["run"][s0]):
            r = s0 & (st["run"] == run)
            r &= (st["speed"] >= lo) & (st["speed"] <= hi)
            if not r.any():
                continue
            lab, labelled = not labelled, True
            v = st["speed"][r]
            ax.errorbar(v, st["friction_amp"][r], yerr=st["friction_amp_err"][r], color=COLOURS[c],
                        lw=1, capsize=1.5, label=f"{c} amplitude" if lab else None)
            ax.errorbar(v, -st["friction_mean"][r], yerr=st["friction_mean_err"][r],
                        color=COLOURS[c], lw=1, ls="--", capsize=1.5,
                        label=f"{c} -mean" if lab else None)
            if c == "bkp":
                ax.plot(v, st["position_amp_scaled"][r], color="lightskyblue", ls="--", lw=1,
                        label="bkp pad-position amplitude x m_x" if lab else None)
        # Seed spread: min..max of the amplitude over seeds at each speed.
        seeds = np.unique(seed[sel])
        if seeds_band and len(seeds) > 1:
            labelled = False
            for run in np.unique(st["run"][sel]):
                r = sel & (st["run"] == run) & (st["speed"] >= lo) & (st["speed"] <= hi)
                v = np.unique(st["speed"][r])
                if len(v) == 0:
                    continue
                amps = np.array([[st["friction_amp"][r & (seed == s) & (st["speed"] == x)][0]
                                  for x in v] for s in seeds])
                ax.fill_between(v, amps.min(0), amps.max(0), color=COLOURS[c], alpha=0.15, lw=0,
                                label=None if labelled else f"{c} amplitude, {len(seeds)} seeds")
                labelled = True
    b = (cfg == "bkp") & (seed == seed[cfg == "bkp"].min()) if (cfg == "bkp").any() else cfg == cfg[0]
    order = np.argsort(st["speed"][b])
    v = st["speed"][b][order]
    m = (v >= lo) & (v <= hi)
    ax.plot(v[m], st["friction_law"][b][order][m], color="navy", lw=1.5, label="friction law N m_u phi(v)")


def cmd_study(a):
    st = study(a)
    fig, ax = plt.subplots(figsize=(11, 6))
    draw_study(ax, st, 0.004, 1.01)
    ax.set_xscale("log")
    ax.set_xlim(0.005, 1)
    ax.set_xlabel("disc speed v")
    ax.set_ylabel("pad friction (mean with opposite sign; amplitude)")
    ax.legend(fontsize=7, ncol=3)
    ax.set_title("Friction study (thesis Fig. 4.6): dashed = -mean, solid = amplitude; gaps "
                 "separate the five runs", fontsize=9)
    save(fig, a.png or os.path.join(a.dir, "friction_study.png"))


def cmd_special(a):
    st = study(a)
    fig, ax = plt.subplots(figsize=(9, 5))
    draw_study(ax, st, 0.15, 0.45)
    ax.axvline(V_SPECIAL, color="gray", lw=0.8, ls=":", label=f"v_special = {V_SPECIAL}")
    ax.set_xlim(0.15, 0.45)
    ax.set_xlabel("disc speed v")
    ax.legend(fontsize=7, ncol=2)
    ax.set_title("Around the special speed (thesis Fig. 4.15)", fontsize=9)
    save(fig, a.png or os.path.join(a.dir, "friction_study_special.png"))


def cmd_amp_mean(a):
    st = study(a)
    fig, ax = plt.subplots(figsize=(7, 5))
    for c in ["bkp", "bk"]:
        sel = (st["configuration"] == c) & (st["speed"] >= 0.08) & (st["speed"] <= 0.19)
        if not sel.any():
            continue
        sel &= st["seed"] == st["seed"][sel].min()
        ax.errorbar(-st["friction_mean"][sel], st["friction_amp"][sel],
                    xerr=st["friction_mean_err"][sel], yerr=st["friction_amp_err"][sel],
                    color=COLOURS[c], marker="o", ms=3, lw=0.8, capsize=1.5, label=c)
        for v, x, y in zip(st["speed"][sel], -st["friction_mean"][sel], st["friction_amp"][sel]):
            ax.annotate(f"{v:.2f}", (x, y), fontsize=7, textcoords="offset points", xytext=(3, 2),
                        color=COLOURS[c])
    ax.set_xlabel("-mean pad friction")
    ax.set_ylabel("pad friction amplitude")
    ax.legend()
    ax.set_title("Amplitude against mean, v = 0.08 .. 0.19 (thesis Fig. 4.9)", fontsize=9)
    save(fig, a.png or os.path.join(a.dir, "amplitude_mean.png"))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="what", required=True)
    for name, fn in [("timeseries", cmd_timeseries), ("spectrum", cmd_spectrum), ("blocks", cmd_blocks),
                     ("study", cmd_study), ("amp-mean", cmd_amp_mean), ("special", cmd_special)]:
        s = sub.add_parser(name)
        s.add_argument("dir")
        s.add_argument("--png")
        s.set_defaults(fn=fn)
        if name in ("timeseries", "blocks"):
            s.add_argument("--from", dest="from_", type=float)
            s.add_argument("--to", type=float)
        if name == "timeseries":
            s.add_argument("--signal", default="pad_x", choices=["pad_x", "pad_v", "pad_friction"])
        if name == "spectrum":
            s.add_argument("--fmax", type=float)
            s.add_argument("--fmin", type=float, default=0.01)
    a = p.parse_args()
    if not os.path.isdir(a.dir):
        fail(f"{a.dir} is not a folder")
    if a.png:
        bkquake_io.check_output_or_exit(a.png, [a.dir], "plot_brake.py")
    a.fn(a)


if __name__ == "__main__":
    main()
