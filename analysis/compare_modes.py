#!/usr/bin/env -S /usr/bin/python3
"""Event-driven against continuous driving: magnitude distributions of the same chain.

    analysis/compare_modes.py [--bkquake BIN] [--out-dir DIR] [--speeds NU...] [--set KEY=VALUE]...
                              [--events-run DIR] [--transient-load X] [--png PNG]

The chain is the Carlson-Langer reference (data/scenes/cl-l10-a2.5-n100.ini: N = 100,
l = 10, alpha = 2.5, sigma = 0.01, clst91 friction, rk4 dt = 0.01). It is run
  - event-driven (nu -> 0): the catalogue of --events-run if given (e.g.
    runs/cl/cl-l10-a2.5-n100 from analysis/run_carlson_langer.sh), otherwise a fresh
    run of --events events into DIR/events;
  - continuously driven at each substrate speed nu (default 0.01, 0.001 and 0.0001) for
    T = D/nu time units into DIR/continuous-nu<NU>, where the substrate displacement D is
    chosen per speed so that each run keeps at least ~5000 slip episodes (episodes merge
    at larger nu, so fewer of them per unit of loading).
The first episodes of a continuous run are the start-up transient from the nearly uniform
initial state: episodes whose `load` (substrate displacement at the trigger) is below
--transient-load (default 2) are dropped. As a check that the rest is stationary, the
KS distance between the first and second halves of each kept continuous catalogue is
printed too (it should be of the order of the sampling noise, 1.36 sqrt(2/(n/2)) at 95 %).

For every nu it prints the two-sample Kolmogorov-Smirnov distance between the magnitude
samples (continuous vs event-driven), with the 5 % critical value 1.36 sqrt((n+m)/(n m)):
  - "KS all": the plain two-sample statistic over all episodes. Caveat: about 78 % of the
    event-driven events are single-block slips whose moment is one exact value (an atom at
    mu = -8.898); at finite nu the substrate keeps loading the block while it slips, which
    shifts that atom up by O(nu) (-8.795 at nu = 0.01, -8.8968 at nu = 0.0001). Any shift,
    however small, puts the whole atom into the plain KS distance, so it stays ~0.77 and
    does not measure convergence;
  - "binned": the same distance with both CDFs read only at the histogram's bin edges
    (multiples of --bin-width, 0.2), i.e. at the resolution of D(mu): the comparison
    that matters for the Gutenberg-Richter statistics;
  - "KS mu>=cut": the plain statistic over mu >= --mu-cut (the scaling region and above).
It draws the empirical CDFs into --png (default DIR/compare_modes.png). The binned and
mu >= cut distances should shrink as nu -> 0.

Runs with Debian's python3 (/usr/bin/python3, with python3-numpy and python3-matplotlib);
the python3 first on PATH may lack numpy and matplotlib.
"""

import argparse
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import bkquake_io  # noqa: E402  (the bkquake module's reader when it is importable)

SCENE = "data/scenes/cl-l10-a2.5-n100.ini"
# substrate displacement per speed: >= ~5000 episodes after the transient at each nu
DEFAULT_LOAD = {0.01: 100.0, 0.001: 30.0, 0.0001: 25.0}


def read_magnitudes(catalog, min_load=None):
    columns = bkquake_io.read_catalog_file(catalog)
    mu = np.asarray(columns["magnitude"], dtype=float)
    if min_load is not None:
        mu = mu[np.asarray(columns["load"]) >= min_load]
    return mu


def ks_two_sample(a, b):
    """Two-sample KS distance sup |F_a - F_b| over the pooled sample."""
    a = np.sort(a)
    b = np.sort(b)
    x = np.concatenate([a, b])
    fa = np.searchsorted(a, x, side="right") / a.size
    fb = np.searchsorted(b, x, side="right") / b.size
    return float(np.max(np.abs(fa - fb)))


def ks_binned(a, b, width):
    """KS distance between the CDFs evaluated only at magnitude-bin edges (multiples of
    width, the edges of histogram.csv): insensitive to shifts inside one bin."""
    lo = np.floor(min(a.min(), b.min()) / width) * width
    hi = np.ceil(max(a.max(), b.max()) / width) * width
    edges = np.arange(lo, hi + width / 2, width)
    fa = np.searchsorted(np.sort(a), edges, side="left") / a.size
    fb = np.searchsorted(np.sort(b), edges, side="left") / b.size
    return float(np.max(np.abs(fa - fb)))


def ks_critical(n, m, c=1.36):
    return c * np.sqrt((n + m) / (n * m))


def run(cmd):
    print("+", " ".join(cmd), flush=True)
    subprocess.run(cmd, check=True)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bkquake", default=os.environ.get("BKQUAKE", "build/bkquake"))
    ap.add_argument("--out-dir", default="runs/modes")
    ap.add_argument("--speeds", type=float, nargs="+", default=[0.01, 0.001, 0.0001])
    ap.add_argument("--events-run", help="existing event-driven run folder to compare against")
    ap.add_argument("--events", type=int, default=200000, help="events of a fresh event run")
    ap.add_argument("--transient-load", type=float, default=2.0)
    ap.add_argument("--mu-cut", type=float, default=-7.6)
    ap.add_argument("--bin-width", type=float, default=0.2)
    ap.add_argument("--png")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="scene key for every run made here, after the script's own (repeatable; "
                         "e.g. integrator.transitions=located)")
    args = ap.parse_args(argv)
    extra = [a for kv in args.set for a in ("--set", kv)]

    if args.events_run and not os.path.isfile(os.path.join(args.events_run, "catalog.csv")):
        print(f"compare_modes.py: {args.events_run} has no catalog.csv: --events-run needs the "
              "folder of an event-driven run", file=sys.stderr)
        return 2
    os.makedirs(args.out_dir, exist_ok=True)
    if args.events_run:
        ev_dir = args.events_run
    else:
        ev_dir = os.path.join(args.out_dir, "events")
        run([args.bkquake, "run", SCENE, "--set", f"run.events={args.events}", *extra,
             "--out", ev_dir, "--force", "--quiet"])
    mu_ev = read_magnitudes(os.path.join(ev_dir, "catalog.csv"))

    rows = []
    curves = []
    for nu in args.speeds:
        load = DEFAULT_LOAD.get(nu, 14.0)
        T = (load + args.transient_load) / nu
        d = os.path.join(args.out_dir, f"continuous-nu{nu:g}")
        run([args.bkquake, "run", SCENE, "--set", "drive.mode=continuous",
             "--set", f"drive.speed={nu:g}", "--set", f"run.duration={T:g}",
             "--set", "integrator.scheme=rk4", "--set", "integrator.dt=0.01", *extra,
             "--out", d, "--force", "--quiet"])
        mu_all = read_magnitudes(os.path.join(d, "catalog.csv"))
        mu_c = read_magnitudes(os.path.join(d, "catalog.csv"), min_load=args.transient_load)
        half = mu_c.size // 2
        ks_halves = ks_binned(mu_c[:half], mu_c[half:], args.bin_width)
        ks_all = ks_two_sample(mu_c, mu_ev)
        ks_bin = ks_binned(mu_c, mu_ev, args.bin_width)
        hi_c, hi_e = mu_c[mu_c >= args.mu_cut], mu_ev[mu_ev >= args.mu_cut]
        ks_hi = ks_two_sample(hi_c, hi_e)
        rows.append(dict(nu=nu, T=T, total=mu_all.size, kept=mu_c.size,
                         per_load=mu_c.size / load, ks=ks_all, ks_bin=ks_bin,
                         crit=ks_critical(mu_c.size, mu_ev.size), ks_hi=ks_hi,
                         n_hi=hi_c.size, crit_hi=ks_critical(hi_c.size, hi_e.size),
                         halves=ks_halves, crit_halves=ks_critical(half, mu_c.size - half),
                         single=np.mean(mu_c < args.mu_cut)))
        curves.append((nu, mu_c))

    ev_per_load = None
    try:
        import json
        with open(os.path.join(ev_dir, "summary.json")) as f:
            s = json.load(f)
        ev_per_load = s["events"] / s["total_load"]
    except (OSError, KeyError, ValueError):
        pass

    print()
    print(f"event-driven: {mu_ev.size} events from {ev_dir}"
          + (f", {ev_per_load:.0f} per unit load" if ev_per_load else "")
          + f", fraction mu < {args.mu_cut:g}: {np.mean(mu_ev < args.mu_cut):.3f}")
    print(f"{'nu':>8} {'T':>9} {'episodes':>9} {'kept':>7} {'per load':>8} "
          f"{'frac<cut':>8} {'KS all':>7} {'binned':>7} {'KS5%':>6} {'KS mu>=cut':>10} {'n':>6} "
          f"{'KS5%':>6} {'KS halves':>9} {'KS5%':>6}")
    for r in rows:
        print(f"{r['nu']:8g} {r['T']:9g} {r['total']:9d} {r['kept']:7d} {r['per_load']:8.0f} "
              f"{r['single']:8.3f} {r['ks']:7.4f} {r['ks_bin']:7.4f} {r['crit']:6.4f} {r['ks_hi']:10.4f} "
              f"{r['n_hi']:6d} {r['crit_hi']:6.4f} {r['halves']:9.4f} {r['crit_halves']:6.4f}")

    png = args.png or os.path.join(args.out_dir, "compare_modes.png")
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    for ax, cut in zip(axes, (None, args.mu_cut)):
        def cdf(x):
            x = np.sort(x if cut is None else x[x >= cut])
            return x, np.arange(1, x.size + 1) / x.size
        x, y = cdf(mu_ev)
        ax.step(x, y, where="post", color="k", lw=1.6, label=f"event-driven (n = {x.size})")
        for nu, mu_c in curves:
            x, y = cdf(mu_c)
            ax.step(x, y, where="post", lw=1.0, label=f"continuous nu = {nu:g} (n = {x.size})")
        ax.set_xlabel("magnitude mu = ln M")
        ax.set_ylabel("empirical CDF")
        ax.set_title("all episodes" if cut is None else f"mu >= {cut:g}")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="lower right" if cut is not None else "upper left")
    fig.suptitle("CL chain N = 100, l = 10, alpha = 2.5, sigma = 0.01: continuous vs event-driven")
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    print(f"plot: {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
