#!/usr/bin/env -S /usr/bin/python3
"""The seismicity statistics of a run (`bkquake seismicity RUN_DIR` writes RUN_DIR/seismicity/)
in one figure of six panels: the waiting-time pdf against the Poisson law, the event rate
stacked around mainshocks with the Omori-Utsu fit (or its absence), the recurrence intervals
of mainshocks with the maximum-likelihood Weibull and lognormal laws, moment against rupture
length with the fitted exponent, the Mogi picture (event density before mainshocks against
distance from the coming hypocentre and time before it) and b before mainshocks against the
time to the mainshock.

Usage: /usr/bin/python3 analysis/plot_seismicity.py RUN_DIR [--out FILE.png]
       (RUN_DIR may also be the seismicity/ folder itself, or a --out folder of the command)
Needs numpy and matplotlib: use Debian's /usr/bin/python3 (python3-numpy,
python3-matplotlib); the python3 first on PATH may lack them.
"""

import argparse
import csv
import json
import os
import sys

import matplotlib
import numpy as np

import bkquake_io

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

FILES = ["interevent.csv", "recurrence.csv", "omori.csv", "scaling.csv", "spacetime.csv",
         "seismicity.json"]


def folder_of(path):
    """The folder holding the seismicity files; exits with one line when there is none."""
    for d in (os.path.join(path, "seismicity"), path):
        if os.path.isfile(os.path.join(d, "seismicity.json")):
            missing = [f for f in FILES if not os.path.isfile(os.path.join(d, f))]
            if missing:
                sys.exit(f"plot_seismicity: {d} lacks {', '.join(missing)}")
            return d
    sys.exit(f"plot_seismicity: {path} has no seismicity/ (run bkquake seismicity {path} first)")


def read_table(path):
    """A '#'-commented CSV as a dict of columns: numbers as float arrays, words as str arrays."""
    with open(path) as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#") and line.strip()))
    header, body = rows[0], rows[1:]
    cols = {}
    for i, name in enumerate(header):
        values = [r[i] for r in body]
        try:
            cols[name] = np.array([float(v) for v in values])
        except ValueError:
            cols[name] = np.array(values)
    return cols


def where(t, column, value):
    m = t[column] == value
    return {k: v[m] for k, v in t.items()}


def centre(lo, hi):
    return np.where(lo > 0, np.sqrt(np.maximum(lo, 1e-300) * hi), 0.5 * hi)


def fmt(x, err=None, digits=3):
    if x is None:
        return "none"
    return f"{x:.{digits}f}" + (f" ± {err:.{digits}f}" if err is not None else "")


def draw(d):
    j = json.load(open(os.path.join(d, "seismicity.json")))
    fig, ax = plt.subplots(2, 3, figsize=(16, 9.5))

    ie = read_table(os.path.join(d, "interevent.csv"))
    a = ax[0, 0]
    for subset, colour in (("all", "C0"), ("mainshocks", "C3")):
        t = where(ie, "subset", subset)
        if len(t["t_low"]) == 0:
            continue
        x = centre(t["t_low"], t["t_high"])
        ok = t["count"] > 0
        a.loglog(x[ok], t["pdf"][ok], "o", ms=3, color=colour, label=f"{subset}")
        a.loglog(x, t["poisson_pdf"], "-", color=colour, lw=1, alpha=0.7,
                 label=f"Poisson, same mean ({subset})")
    ok = ie["pdf"] > 0
    if ok.any():
        a.set_ylim(0.3 * ie["pdf"][ok].min(), 3 * ie["pdf"][ok].max())
    a.set_xlabel("waiting time (clock)")
    a.set_ylabel("pdf")
    a.set_title(f"waiting times: COV {fmt(j['interevent']['cov'], j['interevent']['cov_err'])}"
                " (Poisson: 1)", fontsize=10)
    a.legend(fontsize=7)

    om = read_table(os.path.join(d, "omori.csv"))
    a = ax[0, 1]
    for side, colour, mark in (("after", "C0", "o"), ("before", "C3", "s")):
        t = where(om, "side", side)
        if len(t["t_low"]) == 0:
            continue
        x = centre(t["t_low"], t["t_high"])
        ok = t["count"] > 0
        a.loglog(x[ok], t["rate"][ok], mark, ms=3, color=colour,
                 label=f"{side} mainshocks ({int(t['sequences'].max())} sequences)")
        a.loglog(x, t["fit_rate"], "-", color=colour, lw=1)
    o, fo = j["omori"], j["foreshock"]
    after = (f"Omori p = {fmt(o['p'], o['p_err'])}" if o["excess"]
             else "no aftershock excess")
    before = (f"inverse Omori p = {fmt(fo['p_inverse'], fo['p_inverse_err'])}" if fo["excess"]
              else "no foreshock power law")
    a.axvline(o["fit_t_max"], color="grey", ls=":", lw=1)
    a.set_xlabel("time since (after) / before (before) the mainshock")
    a.set_ylabel("stacked rate per sequence")
    a.set_title(f"{after}; {before}", fontsize=10)
    a.legend(fontsize=7)

    rc = read_table(os.path.join(d, "recurrence.csv"))
    a = ax[0, 2]
    for scope, colour in (("system", "C0"), ("block", "C2")):
        t = where(rc, "scope", scope)
        if len(t["t_low"]) == 0:
            continue
        x = centre(t["t_low"], t["t_high"])
        a.plot(x, t["pdf"], "o", ms=3, color=colour, label=f"{scope}")
        a.plot(x, t["weibull_pdf"], "-", color=colour, lw=1.2, label=f"Weibull ({scope})")
        a.plot(x, t["lognormal_pdf"], "--", color=colour, lw=1, label=f"lognormal ({scope})")
    r = j["recurrence"]
    a.set_xlabel("recurrence interval of mainshocks (clock)")
    a.set_ylabel("pdf")
    a.set_title(f"recurrence: COV {fmt(r['cov'], r['cov_err'])}, Weibull k = "
                f"{fmt(r['weibull_k'], r['weibull_k_err'])}", fontsize=10)
    a.legend(fontsize=7)

    sc = read_table(os.path.join(d, "scaling.csv"))
    a = ax[1, 0]
    t = where(sc, "quantity", "length")
    x = centre(t["x_low"], t["x_high"])
    a.loglog(x, t["geo_mean_moment"], "o", ms=4, label="exp(mean ln M)")
    a.loglog(x, t["fit_moment"], "-", lw=1,
             label=f"M ~ L^{j['scaling']['length_exponent']:.3f}")
    a.set_xlabel("rupture length (blocks)")
    a.set_ylabel("moment")
    a.set_title("moment against rupture length", fontsize=10)
    a.legend(fontsize=8)

    st = read_table(os.path.join(d, "spacetime.csv"))
    dens = where(st, "table", "density")
    a = ax[1, 1]
    if len(dens["t_low"]) and (dens["events"] > 0).any():
        # Times with at least 20 events, so a row's pattern is not noise.
        tl = np.array([v for v in np.unique(dens["t_low"])
                       if v > 0 and dens["events"][dens["t_low"] == v].sum() >= 20])
        th = np.array([dens["t_high"][dens["t_low"] == v][0] for v in tl])
        dl = np.unique(dens["d_low"])
        dh = np.array([dens["d_high"][dens["d_low"] == v][0] for v in dl])
        z = np.full((len(tl), len(dl)), np.nan)
        for i, v in enumerate(tl):
            for k, w in enumerate(dl):
                m = (dens["t_low"] == v) & (dens["d_low"] == w)
                if m.any():
                    z[i, k] = dens["density"][m][0]
        mean = np.nanmean(z, axis=1, keepdims=True)
        rel = np.divide(z, mean, out=np.full_like(z, np.nan), where=mean > 0)
        mesh = a.pcolormesh(np.append(dl, dh[-1]), np.append(tl, th[-1]), rel, cmap="RdBu_r",
                            vmin=0, vmax=2, shading="flat")
        a.set_yscale("log")
        fig.colorbar(mesh, ax=a, label="density / mean over distance at that time")
    a.set_xlabel("distance from the coming mainshock's hypocentre (blocks)")
    a.set_ylabel("time before the mainshock")
    a.set_title("Mogi picture: events before mainshocks", fontsize=10)

    b = where(st, "table", "b")
    a = ax[1, 2]
    ok = np.isfinite(b["b"])
    a.errorbar(centre(b["t_low"], b["t_high"])[ok], b["b"][ok], yerr=b["b_err"][ok], fmt="o",
               ms=4, label="events before mainshocks")
    s = j["spacetime"]
    if s["b_all"] is not None:
        a.axhspan(s["b_all"] - s["b_all_err"], s["b_all"] + s["b_all_err"], color="grey",
                  alpha=0.4)
        a.axhline(s["b_all"], color="grey", lw=1, label=f"every event: b = {s['b_all']:.3f}")
    a.set_xscale("log")
    a.set_xlabel("time before the mainshock")
    a.set_ylabel(f"b (Aki, mu >= {s['b_mu_min']:.2f})")
    a.set_title("b before mainshocks", fontsize=10)
    a.legend(fontsize=8)

    bath = j["bath"]
    fig.suptitle(f"{j['input']}: {j['events']} events, {j['mainshocks']['count']} mainshocks "
                 f"({j['mainshocks']['rule']}); Båth Δμ = {fmt(bath['delta_mu'])} "
                 f"(ΔMw = {fmt(bath['delta_mw'])}); moment budget "
                 f"{fmt(j['moment_budget'], digits=4)}", fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.96))
    return fig


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("run_dir")
    p.add_argument("--out", help="image file (default RUN_DIR/seismicity/seismicity.png)")
    args = p.parse_args()
    d = folder_of(args.run_dir)
    inputs = [os.path.join(d, f) for f in FILES]
    # By default into the run folder's seismicity/, under the run folder's lock; never over
    # an input or a run's own file (bkquake_io.save_figure).
    out = args.out or os.path.join(d, "seismicity.png")
    bkquake_io.check_output_or_exit(out, inputs, "plot_seismicity")
    bkquake_io.save_figure(draw(d), out, inputs, "plot_seismicity", dpi=110)
    print(f"written {out}")


if __name__ == "__main__":
    main()
