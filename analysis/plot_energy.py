#!/usr/bin/python3
"""Energy diagnostics of a continuous run (output.energy, output.status; seed 004 §4.3).

Six panels from a run folder: (a) the mechanical energy E(t) from the sliding equilibrium
and its windowed mean (energy_samples.csv, energy.csv); (b) the spectrogram of E in dB
(seed 004 Fig. 11b); (c) the rate of relative change tau_E of the mean energy, with the
settle time of summary.json; (d) the braking force N_b and its windowed mean (Fig. 12);
(e) the limit cycle, pad velocity against pad position over the last part of the run
(Fig. 10); (f) the node status, blocks stuck / sliding forward / backward (Fig. 13; needs
output.status = true).

Usage: /usr/bin/python3 analysis/plot_energy.py RUN_DIR [--out FILE.png] [--tail FRACTION]
Needs numpy and matplotlib: use Debian's /usr/bin/python3 (python3-numpy,
python3-matplotlib); the python3 first on PATH may lack them.
"""

import argparse
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import bkquake_io  # noqa: E402


def columns(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {name: data[:, i] for i, name in enumerate(header)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run")
    ap.add_argument("--out", default=None)
    ap.add_argument("--tail", type=float, default=0.2,
                    help="fraction of the run at its end drawn as the limit cycle")
    args = ap.parse_args()
    out = args.out or os.path.join(args.run, "energy.png")
    inputs = [os.path.join(args.run, n)
              for n in ("energy_samples.csv", "energy.csv", "timeseries.csv", "summary.json")]
    bkquake_io.check_output_or_exit(out, inputs, "plot_energy.py")
    s = columns(os.path.join(args.run, "energy_samples.csv"))
    w = columns(os.path.join(args.run, "energy.csv"))
    ts = columns(os.path.join(args.run, "timeseries.csv"))
    with open(os.path.join(args.run, "summary.json")) as f:
        summary = json.load(f)

    fig, ax = plt.subplots(3, 2, figsize=(12, 10))
    a = ax[0, 0]
    a.plot(s["t"], s["energy"], lw=0.5, label="E")
    a.plot(w["t"], w["energy_mean"], "o-", ms=2, label="windowed mean Ē")
    a.set_yscale("log")
    a.set_xlabel("t")
    a.set_ylabel("energy from the sliding equilibrium")
    a.legend(fontsize=8)
    a.set_title("(a) mechanical energy", fontsize=10)

    a = ax[0, 1]
    dt = np.median(np.diff(s["t"]))
    nfft = int(min(1024, max(64, 2 ** np.floor(np.log2(len(s["t"]) / 16)))))
    a.specgram(s["energy"] - np.mean(s["energy"]), NFFT=nfft, Fs=1.0 / dt, noverlap=nfft // 2,
               cmap="viridis", scale="dB")
    a.set_ylim(0, min(1.0, 0.5 / dt))
    a.set_xlabel("t")
    a.set_ylabel("frequency")
    a.set_title("(b) spectrogram of E (dB)", fontsize=10)

    a = ax[1, 0]
    a.plot(w["t"], w["tau_energy"], "o-", ms=2)
    a.axhline(0, color="k", lw=0.8)
    settle = summary.get("energy_settle_time")
    if settle is not None:
        a.axvline(settle, color="tab:red", ls="--", label=f"settled at t = {settle:g}")
        a.legend(fontsize=8)
    a.set_xlabel("t (window centre)")
    a.set_ylabel("τ_E = Ē_t / Ē")
    a.set_title("(c) rate of relative change of Ē", fontsize=10)

    a = ax[1, 1]
    a.plot(s["t"], s["braking_force"], lw=0.5, label="N_b = k_p0 x + c_p x'")
    a.plot(w["t"], w["braking_mean"], "o-", ms=2, label="windowed mean")
    a.set_xlabel("t")
    a.set_ylabel("braking force")
    a.legend(fontsize=8)
    a.set_title("(d) effective braking force", fontsize=10)

    a = ax[2, 0]
    keep = ts["t"] >= ts["t"][-1] * (1 - args.tail)
    a.plot(ts["pad_x"][keep], ts["pad_v"][keep], lw=0.5)
    a.set_xlabel("pad position x")
    a.set_ylabel("pad velocity x'")
    a.set_title(f"(e) limit cycle, last {100 * args.tail:g} % of the run", fontsize=10)

    a = ax[2, 1]
    if "stuck" in ts:
        a.plot(ts["t"], ts["stuck"], lw=0.6, label="stuck")
        a.plot(ts["t"], ts["slip_forward"], lw=0.6, label="sliding forward")
        a.plot(ts["t"], ts["slip_backward"], lw=0.6, label="sliding backward")
        a.legend(fontsize=8)
    else:
        a.text(0.5, 0.5, "no node status (output.status = false)", ha="center",
               transform=a.transAxes)
    a.set_xlabel("t")
    a.set_ylabel("blocks")
    a.set_title("(f) node status", fontsize=10)
    fig.tight_layout()
    bkquake_io.save_figure(fig, out, inputs, "plot_energy.py", dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
