#!/usr/bin/env -S /usr/bin/python3
"""The events of a lattice run (the OFC automaton with model.rows > 1) in one figure, from
its catalogue (catalog.csv or catalog.h5, with the row columns trigger_row, first_row,
last_row) and scene.ini:

  left    the magnitude-frequency distribution: the number of events with mu >= mu
          (mu = ln moment), log scale, with the run's Gutenberg-Richter fit (summary.json:
          b over its window) drawn through the data at the window's lower end;
  middle  where the largest events happened: the bounding box (columns first_block ..
          last_block by rows first_row .. last_row) of each of the --largest largest
          events, coloured by mu, its trigger site (x, y) = (trigger, trigger_row) marked;
  right   the triggers of all events: the count per site of the lattice.

When the run wrote slip maps (output.event_slip = MU: event_slip.csv, one row per site
that toppled, with block = x, row = y, the stress it released and its topplings), a second
row of panels draws the maps of the --maps M largest events in that file (largest total
release, which is the event's moment): the stress each site released, blank where none
toppled.

Usage: /usr/bin/python3 analysis/plot_lattice.py RUN_DIR [--out PNG] [--largest K] [--maps M]
Writes RUN_DIR/lattice.png by default. A folder that is not a lattice run (no scene.ini or
catalogue, or a catalogue without the row columns: a chain or a single row) is refused
with a one-line message (exit 2).
Needs numpy and matplotlib (and h5py for catalog.h5): use Debian's /usr/bin/python3.
"""

import argparse
import os
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

import bkquake_io  # noqa: E402

COMMAND = "plot_lattice.py"
ROW_COLUMNS = ("trigger_row", "first_row", "last_row")


def refuse(message):
    print(f"{COMMAND}: {message}", file=sys.stderr)
    sys.exit(2)


def lattice_shape(run_dir, cat):
    """(nx, ny): model.blocks and model.rows of scene.ini."""
    model = bkquake_io.load_scene(run_dir).get("model", {})
    try:
        return int(model["blocks"]), int(model["rows"])
    except (KeyError, ValueError):
        refuse(f"{run_dir}/scene.ini names no model.blocks and model.rows")


def magnitude_frequency(ax, mu, summary):
    """N(>= mu) against mu, log scale, and the run's fitted law through the data."""
    s = np.sort(mu)[::-1]
    n = np.arange(1, len(s) + 1)
    ax.semilogy(s, n, ".", ms=2, color="tab:blue", label=f"{len(s)} events")
    fit = bkquake_io.fit_window(summary)
    if fit:
        b, lo, hi = fit
        n_lo = np.count_nonzero(mu >= lo)
        x = np.linspace(lo, hi, 50)
        ax.semilogy(x, n_lo * np.exp(-b * (x - lo)), "-", color="tab:red",
                    label=f"b = {b:.3f} on [{lo:.2f}, {hi:.2f}]")
    ax.set_xlabel(r"magnitude $\mu = \ln M$")
    ax.set_ylabel(r"events with magnitude $\geq \mu$")
    ax.legend(fontsize=8)


def largest_boxes(ax, cat, nx, ny, k):
    """The bounding boxes of the k largest events, coloured by magnitude."""
    mu = np.asarray(cat["magnitude"], dtype=float)
    order = np.argsort(mu)[::-1][:k][::-1]  # the largest drawn last, on top
    norm = matplotlib.colors.Normalize(vmin=mu[order].min(), vmax=mu[order].max())
    cmap = plt.get_cmap("viridis")
    for i in order:
        x0, x1 = float(cat["first_block"][i]), float(cat["last_block"][i])
        y0, y1 = float(cat["first_row"][i]), float(cat["last_row"][i])
        colour = cmap(norm(mu[i]))
        ax.add_patch(Rectangle((x0 - 0.5, y0 - 0.5), x1 - x0 + 1, y1 - y0 + 1, fill=False,
                               edgecolor=colour, lw=1.2))
        ax.plot(float(cat["trigger"][i]), float(cat["trigger_row"][i]), "x", color=colour, ms=5)
    ax.set_xlim(-0.5, nx - 0.5)
    ax.set_ylim(-0.5, ny - 0.5)
    ax.set_aspect("equal")
    ax.set_xlabel("x (column, along strike)")
    ax.set_ylabel("y (row, across strike)")
    ax.set_title(f"the {len(order)} largest events: box and trigger", fontsize=9)
    plt.colorbar(matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap), ax=ax, label=r"$\mu$",
                 shrink=0.8)


def trigger_map(ax, cat, nx, ny):
    """Events per trigger site."""
    x = np.asarray(cat["trigger"], dtype=int)
    y = np.asarray(cat["trigger_row"], dtype=int)
    counts = np.zeros((ny, nx))
    np.add.at(counts, (y, x), 1)
    im = ax.imshow(counts, origin="lower", cmap="magma", interpolation="nearest")
    ax.set_xlabel("x (column, along strike)")
    ax.set_ylabel("y (row, across strike)")
    ax.set_title("events per trigger site", fontsize=9)
    plt.colorbar(im, ax=ax, shrink=0.8)


SLIP_COLUMNS = ("event", "block", "row", "slip")


def load_slip_maps(run_dir):
    """event_slip.csv's columns as arrays, or None when the run wrote none; a file without
    the lattice's columns (event, block, row, slip) is refused."""
    path = os.path.join(run_dir, "event_slip.csv")
    if not os.path.isfile(path):
        return None
    try:
        cols = bkquake_io.read_csv_columns(path)
    except ValueError as e:
        refuse(str(e))
    missing = [c for c in SLIP_COLUMNS if c not in cols]
    if missing:
        refuse(f"{path} has no {', '.join(missing)} column (expected a lattice's slip maps: "
               f"{','.join(SLIP_COLUMNS)},topplings)")
    return cols


def largest_maps(slips, nx, ny, k):
    """[(event, released, topplings)] of the k events of largest total release in the
    slip-map columns, largest first: released[y, x] the stress site (x, y) released (nan
    where it did not topple), topplings[y, x] its topplings (0 where none; all 0 when the
    file has no topplings column)."""
    events = np.asarray(slips["event"], dtype=np.int64)
    if len(events) == 0:
        return []
    ids, inverse = np.unique(events, return_inverse=True)
    total = np.bincount(inverse, weights=np.asarray(slips["slip"], dtype=float))
    out = []
    for e in ids[np.argsort(total, kind="stable")[::-1][:k]]:
        m = events == e
        x = np.asarray(slips["block"], dtype=np.int64)[m]
        y = np.asarray(slips["row"], dtype=np.int64)[m]
        released = np.full((ny, nx), np.nan)
        released[y, x] = np.asarray(slips["slip"], dtype=float)[m]
        topplings = np.zeros((ny, nx), dtype=np.int64)
        if "topplings" in slips:
            topplings[y, x] = np.asarray(slips["topplings"], dtype=np.int64)[m]
        out.append((int(e), released, topplings))
    return out


def slip_map(ax, event, released, topplings):
    """One event's map: the stress each site released."""
    im = ax.imshow(released, origin="lower", cmap="viridis", interpolation="nearest")
    sites = int(np.count_nonzero(~np.isnan(released)))
    mu = np.log(np.nansum(released))
    ax.set_title(f"event {event}: mu = {mu:.2f}, {sites} sites, {int(topplings.sum())} "
                 "topplings", fontsize=9)
    ax.set_xlabel("x (column, along strike)")
    ax.set_ylabel("y (row, across strike)")
    plt.colorbar(im, ax=ax, shrink=0.8, label="stress released")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("run", help="run folder of a lattice (model.kind = ofc, model.rows > 1)")
    ap.add_argument("--out", help="PNG file (default RUN_DIR/lattice.png)")
    ap.add_argument("--largest", type=int, default=20,
                    help="how many of the largest events to map (default 20)")
    ap.add_argument("--maps", type=int, default=3,
                    help="how many of the largest events' slip maps to draw, when the run "
                         "wrote event_slip.csv (default 3)")
    args = ap.parse_args()
    if args.largest < 1:
        refuse(f"--largest = {args.largest}: expected at least 1")
    if args.maps < 1:
        refuse(f"--maps = {args.maps}: expected at least 1")
    try:
        bkquake_io.require_files(args.run, ["scene.ini"], "a lattice run folder is expected")
        cat = bkquake_io.load_catalog(args.run)
    except (bkquake_io.WrongFolder, FileNotFoundError) as e:
        refuse(str(e))
    missing = [c for c in ROW_COLUMNS if c not in cat]
    if missing:
        refuse(f"{args.run}: the catalogue has no {', '.join(missing)} (a chain or a single "
               "row, not a lattice of model.rows > 1)")
    if len(cat["magnitude"]) == 0:
        refuse(f"{args.run}: the catalogue holds no events")
    nx, ny = lattice_shape(args.run, cat)
    slips = load_slip_maps(args.run)
    maps = largest_maps(slips, nx, ny, args.maps) if slips is not None else []
    out = args.out or os.path.join(args.run, "lattice.png")
    inputs = [args.run]
    bkquake_io.check_output_or_exit(out, inputs, COMMAND)

    if maps:
        # Top: the catalogue's three panels; bottom: one panel per slip map.
        n = len(maps)
        fig = plt.figure(figsize=(max(15, 5 * n), 8.8), dpi=100)
        grid = fig.add_gridspec(2, 3 * n)
        axes = [fig.add_subplot(grid[0, i * n:(i + 1) * n]) for i in range(3)]
        for i, (event, released, topplings) in enumerate(maps):
            slip_map(fig.add_subplot(grid[1, 3 * i:3 * (i + 1)]), event, released, topplings)
    else:
        fig, axes = plt.subplots(1, 3, figsize=(15, 4.4), dpi=100)
    magnitude_frequency(axes[0], np.asarray(cat["magnitude"], dtype=float),
                        bkquake_io.load_summary(args.run))
    alpha = bkquake_io.load_scene(args.run).get("ofc", {}).get("alpha", "?")
    name = os.path.basename(os.path.normpath(args.run))
    axes[0].set_title(f"{name}: {nx} x {ny} sites, alpha = {alpha}", fontsize=9)
    largest_boxes(axes[1], cat, nx, ny, args.largest)
    trigger_map(axes[2], cat, nx, ny)
    fig.tight_layout()
    bkquake_io.save_figure(fig, out, inputs, COMMAND, dpi=110)
    print(out)


if __name__ == "__main__":
    main()
