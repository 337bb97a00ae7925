#!/usr/bin/env python3
"""The OFC size-distribution exponent tau against alpha and lattice size.

Runs `bkquake run` with model.kind = ofc for each (alpha, L) on an L x L lattice with open
(free) edges, reads the catalogue and fits P(s) ~ s^-tau to the avalanche sizes s (the
`topplings` column; OFC 1992 count topplings, i.e. the energy released in units of the
threshold) by least squares on a log-binned histogram over 10 <= s <= L^2 / 10, below the
finite-size cutoff. The recorded events are split in halves: the two halves' tau show
whether the run is stationary and how far the fit moves with the sample. Each run is also
fitted by maximum likelihood (`bkquake fit RUN --measure topplings`: x_min by the KS
distance, the block-bootstrap error, the goodness-of-fit p; the tau_mle* columns).

Writes ofc_exponent.csv and ofc_exponent.png into --out (default: the current folder).
  /usr/bin/python3 analysis/ofc_exponent.py [--bkquake build/bkquake] [--sizes L ...]
      [--events N] [--quick] [--out DIR]
"""

import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import bkquake_io  # noqa: E402


def fit_tau(s, s_min, s_max):
    """Slope of log P(s) on log-spaced bins in [s_min, s_max] (P per unit s)."""
    edges = np.unique(np.round(np.logspace(np.log10(s_min), np.log10(s_max), 16)))
    counts, _ = np.histogram(s, bins=edges)
    widths = np.diff(edges)
    centres = np.sqrt(edges[:-1] * edges[1:])
    keep = counts > 0
    if keep.sum() < 4:
        return float("nan")
    p = counts[keep] / widths[keep] / len(s)
    slope, _ = np.polyfit(np.log(centres[keep]), np.log(p), 1)
    return -slope


def run_case(bkquake, alpha, L, events, transient, work):
    out = os.path.join(work, f"a{alpha}-L{L}")
    cmd = [bkquake, "run", "--quiet", "--force", "--out", out,
           "--set", "model.kind=ofc", "--set", f"model.blocks={L}", "--set", f"model.rows={L}",
           "--set", f"ofc.alpha={alpha}", "--set", f"run.events={events}",
           "--set", f"run.transient_events={transient}", "--set", "run.seed=1"]
    subprocess.run(cmd, check=True)
    cat = bkquake_io.load_catalog(out)
    s = np.asarray(cat["topplings"], dtype=float)
    fit_json = os.path.join(work, f"a{alpha}-L{L}.json")
    subprocess.run([bkquake, "fit", out, "--measure", "topplings", "--json", fit_json],
                   check=True, stdout=subprocess.DEVNULL)
    with open(fit_json) as f:
        tau = json.load(f)["tau"]
    return s, tau


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bkquake", default=os.path.join(ROOT, "build", "bkquake"))
    ap.add_argument("--quick", action="store_true", help="small runs (a smoke test)")
    ap.add_argument("--out", default=".",
                    help="folder for ofc_exponent.csv and ofc_exponent.png (default: here)")
    ap.add_argument("--sizes", type=int, nargs="+", default=[32, 64, 128],
                    help="lattice sides L")
    ap.add_argument("--events", type=int, default=500000, help="recorded events per run")
    args = ap.parse_args()
    args.csv = os.path.join(args.out, "ofc_exponent.csv")
    args.plot = os.path.join(args.out, "ofc_exponent.png")

    alphas = [0.25, 0.2, 0.15, 0.1]
    sizes = [16, 32] if args.quick else args.sizes
    rows = []
    dists = {}
    with tempfile.TemporaryDirectory() as work:
        for L in sizes:
            for alpha in alphas:
                # Events scale with the sites; the transient is about 2000 drive units per
                # site at L = 128 (Lise 2002: t_tr ~ L^1.3), checked by the halves' taus.
                events = 20000 if args.quick else args.events
                transient = (20000 if args.quick else int(40 * L * L))
                s, mle = run_case(args.bkquake, alpha, L, events, transient, work)
                s_max = max(L * L / 10.0, 30.0)
                half = len(s) // 2
                tau = fit_tau(s, 10, s_max)
                tau1, tau2 = fit_tau(s[:half], 10, s_max), fit_tau(s[half:], 10, s_max)
                rows.append({"alpha": alpha, "L": L, "events": len(s), "transient": transient,
                             "tau": round(tau, 3), "tau_first_half": round(tau1, 3),
                             "tau_second_half": round(tau2, 3),
                             "tau_mle": round(mle["value"], 3) if mle["ok"] else "",
                             "tau_mle_err": round(mle["err"], 3) if mle["ok"] else "",
                             "tau_mle_x_min": mle["x_min"] if mle["ok"] else "",
                             "tau_mle_p": mle["p"] if mle["ok"] else "",
                             "mean_topplings": round(float(np.mean(s)), 3),
                             "largest": int(s.max())})
                dists[(alpha, L)] = s
                print(rows[-1], flush=True)

    os.makedirs(args.out, exist_ok=True)
    with open(args.csv, "w", newline="") as f:
        f.write("# OFC size-distribution exponent tau (P(s) ~ s^-tau, s = topplings), open edges;\n")
        f.write("# tau*: least squares on 10 <= s <= L^2/10; tau_mle*: bkquake fit --measure topplings\n")
        f.write("# made by analysis/ofc_exponent.py " + " ".join(sys.argv[1:]) + "\n")
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    L = sizes[-1]
    for alpha in alphas:
        s = dists[(alpha, L)]
        edges = np.unique(np.round(np.logspace(0, np.log10(s.max() + 1), 30)))
        counts, _ = np.histogram(s, bins=edges)
        keep = counts > 0
        p = counts[keep] / np.diff(edges)[keep] / len(s)
        ax1.loglog(np.sqrt(edges[:-1] * edges[1:])[keep], p, "o-", ms=3, label=f"alpha = {alpha}")
    ax1.set_xlabel("avalanche size s (topplings)")
    ax1.set_ylabel("P(s)")
    ax1.set_title(f"OFC {L} x {L}, open edges")
    ax1.legend()
    for Lk in sizes:
        taus = [r["tau"] for r in rows if r["L"] == Lk]
        ax2.plot(alphas, taus, "o-", label=f"L = {Lk}")
    ax2.axhline(1.8, color="gray", ls="--", label="Lise & Paczuski 2001: tau -> 1.8")
    ax2.set_xlabel("alpha")
    ax2.set_ylabel("tau (fit 10 <= s <= L^2/10)")
    ax2.legend()
    fig.tight_layout()
    fig.savefig(args.plot, dpi=110)
    print("wrote", args.csv, "and", args.plot)


if __name__ == "__main__":
    main()
