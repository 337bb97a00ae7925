#!/usr/bin/env -S /usr/bin/python3
"""The events of a lattice run in one figure: the OFC automaton or the Burridge-Knopoff
lattice (model.kind = ofc, bk or bkp with model.rows > 1; event-driven or continuous), from
its catalogue (catalog.csv or catalog.h5, with the row columns trigger_row, first_row,
last_row) and scene.ini:

  left    the magnitude-frequency distribution: the number of events with mu >= mu
          (mu = ln moment), log scale, with the run's Gutenberg-Richter fit (summary.json:
          b over its window) drawn through the data at the window's lower end;
  middle  where the largest events happened: the bounding box (columns first_block ..
          last_block by rows first_row .. last_row) of each of the --largest largest
          events, coloured by mu, its trigger site (x, y) = (trigger, trigger_row) marked;
  third   the triggers of all events: the count per site of the lattice;
  fourth  (a continuous BK run that wrote blocks.csv, output.blocks = true) the stress field:
          the force the springs put on every block, sum over its stencil of k (u_nb - u_j)
          - k_p (u_j - x), in units of its static threshold F0 m_u (failure at 1), from the
          displacements of one row of blocks.csv (--time T: the row nearest T; default the
          last row, the final state). Without blocks.csv (or with part of the lattice in
          it) the panel is left out with a note.

When the run wrote slip maps (output.event_slip = MU: event_slip.csv, one row per site
that slipped, with block = x, row = y and its slip; for OFC the stress it released and its
topplings), a second row of panels draws the maps of the --maps M largest events in that
file (largest total, which is the event's moment): blank where nothing slipped. In a
continuous run the events are the slip episodes (which write no slip maps).

Usage: /usr/bin/python3 analysis/plot_lattice.py RUN_DIR [--out PNG] [--largest K] [--maps M]
       [--time T]
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
    # The fitted line may fall below one event past the data: the axis ends at one event.
    ax.set_ylim(bottom=0.5)
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


def _value(section, key, default=None):
    """A scene value as a float; `auto` (or missing) gives `default`."""
    v = section.get(key, "auto")
    return default if v == "auto" else float(v)


def lattice_springs(scene, nx, ny):
    """(k_p, threshold F0 m_u, stencil [(dx, dy, k)]) of a BK lattice's scene.ini, as
    src/model/coupling.cpp and src/io/settings.cpp compute them: carlson-langer units
    m_u = k_p = F0 = 1, k_c = l^2, k_c_y = l_y^2; thesis units m_u = s_m m_x / N,
    k_p = s_p k_p0 / N, k_c = s_c k_p0 nx, k_c_y = s_c_y k_p0 ny (N = nx ny). range and
    power spread k_c + k_c_y over the disc 0 < r <= R with weights w(r) (k_c dx^2 + k_c_y
    dy^2) / r^2, normalised by the sum of w dx^2 / r^2 over the half disc."""
    model, friction = scene.get("model", {}), scene.get("friction", {})
    n = nx * ny
    if model.get("parameterisation", "carlson-langer") == "thesis":
        k_p0 = _value(model, "caliper_stiffness")
        m_u = _value(model, "s_m", 1.0) * _value(model, "pad_mass") / n
        k_p = _value(model, "s_p", 1.0) * k_p0 / n
        s_c = _value(model, "s_c")
        k_c, k_c_y = s_c * k_p0 * nx, _value(model, "s_c_y", s_c) * k_p0 * ny
        threshold = _value(friction, "f0") * m_u
    else:
        l = _value(model, "l")
        k_p, threshold = 1.0, 1.0
        k_c, k_c_y = l * l, _value(model, "l_y", l) ** 2
    coupling = model.get("coupling", "nearest")
    reach = 1 if coupling == "nearest" else int(model.get("range", "1"))
    if reach == 1:
        return k_p, threshold, [(1, 0, k_c), (0, 1, k_c_y)]
    p = _value(model, "coupling_exponent", 3.0)
    half = [(dx, dy) for dx in range(reach + 1) for dy in range(-reach, reach + 1)
            if 0 < dx * dx + dy * dy <= reach * reach and not (dx == 0 and dy < 0)]
    w = {(dx, dy): (np.hypot(dx, dy) ** -p if coupling == "power" else 1.0) for dx, dy in half}
    norm = sum(w[d] * d[0] ** 2 / (d[0] ** 2 + d[1] ** 2) for d in half)
    return k_p, threshold, [(dx, dy, w[(dx, dy)] * (k_c * dx * dx + k_c_y * dy * dy)
                             / (dx * dx + dy * dy) / norm) for dx, dy in half]


def stress_field(scene, nx, ny, u, pad_x=0.0):
    """The force of the springs on each block in units of its threshold, as a (ny, nx)
    array: sum over the stencil of k (u_nb - u_j) (free edges drop the springs past them,
    periodic ones wrap) minus k_p (u_j - pad_x). u holds the lab-frame displacements row by
    row (site j = y nx + x), as blocks.csv writes them."""
    model = scene.get("model", {})
    k_p, threshold, springs = lattice_springs(scene, nx, ny)
    periodic = (model.get("boundary", "free") == "periodic",
                model.get("boundary_y", "free") == "periodic")
    grid = np.asarray(u, dtype=float).reshape(ny, nx)
    force = -k_p * (grid - pad_x)
    ys, xs = np.mgrid[0:ny, 0:nx]
    for dx, dy, k in springs:
        for sx, sy in ((dx, dy), (-dx, -dy)):
            px, py = xs + sx, ys + sy
            ok = np.ones_like(grid, dtype=bool)
            if periodic[0]:
                px %= nx
            else:
                ok &= (px >= 0) & (px < nx)
            if periodic[1]:
                py %= ny
            else:
                ok &= (py >= 0) & (py < ny)
            partner = grid[np.where(ok, py, 0), np.where(ok, px, 0)]
            force += np.where(ok, k * (partner - grid), 0.0)
    return force / threshold


def block_row(run_dir, n, time):
    """(t, u[0..n-1]) of the row of blocks.csv nearest `time` (None: the last row), or None
    with the reason when blocks.csv is missing or does not hold every block."""
    path = os.path.join(run_dir, "blocks.csv")
    if not os.path.exists(path):
        return None, "no blocks.csv (output.blocks = true writes it)"
    with open(path) as f:
        lines = [line for line in f if line.strip() and not line.startswith("#")]
    if not lines:
        return None, "blocks.csv is empty"
    header, rows = lines[0].strip().split(","), lines[1:]
    if header[1:n + 1] != [f"u{j}" for j in range(n)]:
        return None, ("blocks.csv does not hold every block of the lattice "
                      "(output.block_first, output.block_count)")
    if not rows:
        return None, "blocks.csv holds no rows"
    t = np.array([float(r.split(",", 1)[0]) for r in rows])
    i = len(rows) - 1 if time is None else int(np.argmin(np.abs(t - time)))
    cells = rows[i].strip().split(",")
    return (t[i], np.array(cells[1:n + 1], dtype=float)), None


def pad_position(run_dir, t):
    """The pad's position at time t from timeseries.csv (0 without it: the bk model)."""
    path = os.path.join(run_dir, "timeseries.csv")
    if not os.path.exists(path):
        return 0.0
    ts = bkquake_io.read_csv_columns(path)
    if "pad_x" not in ts or len(ts["t"]) == 0:
        return 0.0
    times = np.asarray(ts["t"], dtype=float)
    return float(np.asarray(ts["pad_x"], dtype=float)[np.argmin(np.abs(times - t))])


def stress_map(ax, field, t):
    """The stress field, the threshold (failure) at the top of the colour scale."""
    im = ax.imshow(field, origin="lower", cmap="viridis", interpolation="nearest",
                   vmin=min(0.0, field.min()), vmax=max(1.0, field.max()))
    ax.set_xlabel("x (column, along strike)")
    ax.set_ylabel("y (row, across strike)")
    ax.set_title(f"spring force / threshold at t = {t:g}", fontsize=9)
    plt.colorbar(im, ax=ax, shrink=0.8)


def title(scene, nx, ny):
    """What the run is: the automaton's alpha, or the BK lattice's coupling and friction."""
    model = scene.get("model", {})
    kind = model.get("kind", "bk")
    if kind == "ofc":
        return f"ofc {nx} x {ny}, alpha = {scene.get('ofc', {}).get('alpha', '?')}"
    coupling = model.get("coupling", "nearest")
    if coupling != "nearest":
        coupling += f" R = {model.get('range', '?')}"
        if model.get("coupling", "") == "power":
            coupling += f" p = {model.get('coupling_exponent', '?')}"
    if model.get("parameterisation", "carlson-langer") == "thesis":
        springs = f"s_c = {model.get('s_c', '?')}"
    else:
        springs = f"l = {model.get('l', '?')}"
    alpha = scene.get("friction", {}).get("alpha")
    friction = f", alpha = {alpha}" if alpha else ""
    drive = scene.get("drive", {}).get("mode", "events")
    return f"{kind} {nx} x {ny}, {coupling}, {springs}{friction}, {drive}"


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
               f"{','.join(SLIP_COLUMNS)}[,topplings])")
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


def slip_map(ax, event, released, topplings, automaton):
    """One event's map: each site's slip (the automaton: the stress it released)."""
    im = ax.imshow(released, origin="lower", cmap="viridis", interpolation="nearest")
    sites = int(np.count_nonzero(~np.isnan(released)))
    mu = np.log(np.nansum(released))
    counted = f", {int(topplings.sum())} topplings" if automaton else ""
    ax.set_title(f"event {event}: mu = {mu:.2f}, {sites} sites{counted}", fontsize=9)
    ax.set_xlabel("x (column, along strike)")
    ax.set_ylabel("y (row, across strike)")
    plt.colorbar(im, ax=ax, shrink=0.8, label="stress released" if automaton else "slip")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("run", help="run folder of a lattice (model.rows > 1: ofc, bk or bkp)")
    ap.add_argument("--out", help="PNG file (default RUN_DIR/lattice.png)")
    ap.add_argument("--largest", type=int, default=20,
                    help="how many of the largest events to map (default 20)")
    ap.add_argument("--maps", type=int, default=3,
                    help="how many of the largest events' slip maps to draw, when the run "
                         "wrote event_slip.csv (default 3)")
    ap.add_argument("--time", type=float,
                    help="continuous BK runs: the time of the stress field's row of blocks.csv "
                         "(default the last row)")
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
    scene = bkquake_io.load_scene(args.run)
    out = args.out or os.path.join(args.run, "lattice.png")
    inputs = [args.run]
    bkquake_io.check_output_or_exit(out, inputs, COMMAND)

    stress = None
    continuous = scene.get("drive", {}).get("mode") == "continuous"
    if continuous and scene.get("model", {}).get("kind", "bk") != "ofc":
        row, why = block_row(args.run, nx * ny, args.time)
        if row is None:
            print(f"{COMMAND}: no stress field: {why}")
        else:
            t, u = row
            stress = (stress_field(scene, nx, ny, u, pad_position(args.run, t)), t)
    elif args.time is not None:
        refuse(f"--time = {args.time:g}: the stress field is drawn for continuous BK runs only")

    slips = load_slip_maps(args.run)
    maps = largest_maps(slips, nx, ny, args.maps) if slips is not None else []
    panels = 4 if stress else 3
    if maps:
        # Top: the catalogue's panels; bottom: one panel per slip map.
        n = len(maps)
        automaton = "topplings" in slips
        fig = plt.figure(figsize=(max(5 * panels, 5 * n), 8.8), dpi=100)
        grid = fig.add_gridspec(2, panels * n)
        axes = [fig.add_subplot(grid[0, i * n:(i + 1) * n]) for i in range(panels)]
        for i, (event, released, topplings) in enumerate(maps):
            slip_map(fig.add_subplot(grid[1, panels * i:panels * (i + 1)]), event, released,
                     topplings, automaton)
    else:
        fig, axes = plt.subplots(1, panels, figsize=(5 * panels, 4.4), dpi=100)
    magnitude_frequency(axes[0], np.asarray(cat["magnitude"], dtype=float),
                        bkquake_io.load_summary(args.run))
    name = os.path.basename(os.path.normpath(args.run))
    axes[0].set_title(f"{name}: {title(scene, nx, ny)}", fontsize=8)
    largest_boxes(axes[1], cat, nx, ny, args.largest)
    trigger_map(axes[2], cat, nx, ny)
    if stress:
        stress_map(axes[3], *stress)
    fig.tight_layout()
    bkquake_io.save_figure(fig, out, inputs, COMMAND, dpi=110)
    print(out)


if __name__ == "__main__":
    main()
