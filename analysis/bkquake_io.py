"""Small loader for bkquake run folders.

A run folder holds scene.ini (the effective scene), catalog.csv or catalog.h5 (one row per
event; output.catalog = csv | hdf5, none writes neither),
histogram.csv (mu_low,mu_high,count,D,R,D_rate,R_rate) and summary.json. These helpers
read them into plain Python/numpy structures; column names come from the header lines,
so the loaders follow the schema rather than a fixed column order.

Needs numpy, and h5py for catalog.h5: use Debian's /usr/bin/python3 with python3-numpy and
python3-h5py (the python3 first on PATH may lack them). When the bkquake Python module is
importable (PYTHONPATH=build/python after ./run.sh, or installed with cmake --install),
catalogues and histograms are read through it: its C++ reader is about ten times faster,
needs no h5py, and keeps the integer columns (event, trigger, blocks, first_block,
last_block, count, R) as int64; without it every column is float64.
"""

import configparser
import json
import os

import numpy as np

try:
    import bkquake as _bkquake  # the compiled reader, when built (see the module docstring)
except ImportError:
    _bkquake = None


def _path(run_dir, name):
    return os.path.join(run_dir, name)


def read_csv_columns(path):
    """Reads a headed numeric CSV into a dict name -> numpy array (float64)."""
    with open(path) as f:
        header = f.readline().strip().split(",")
    if not header or header == [""]:
        raise ValueError(f"{path}: empty file, expected a header line")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    if data.size == 0:
        return {name: np.empty(0) for name in header}
    if data.shape[1] != len(header):
        raise ValueError(f"{path}: {data.shape[1]} columns, header names {len(header)}")
    return {name: data[:, i] for i, name in enumerate(header)}


def read_catalog_file(path):
    """One catalogue file (catalog.csv or catalog.h5) as a dict of arrays, as load_catalog."""
    if _bkquake is not None:
        return _bkquake.read_catalog(path)
    with open(path, "rb") as f:
        hdf5 = f.read(8) == b"\x89HDF\r\n\x1a\n"
    return read_h5_columns(path) if hdf5 else read_csv_columns(path)


def load_histogram(run_dir):
    """histogram.csv as a dict of arrays (mu_low, mu_high, count, D, R, D_rate, R_rate)."""
    if _bkquake is not None:
        h = _bkquake.load(run_dir).histogram
        return {name: np.asarray(h[name]) for name in h}
    return read_csv_columns(_path(run_dir, "histogram.csv"))


def read_h5_columns(path):
    """catalog.h5's table as a dict name -> numpy array (float64), in the table's column
    order: the same arrays read_csv_columns gives for the same run's catalog.csv."""
    import h5py  # only catalog.h5 needs it

    try:
        f = h5py.File(path, "r")
    except OSError:
        # A run killed while writing leaves the file marked as being written; it is
        # consistent and opens as HDF5's single-writer mode's reader.
        f = h5py.File(path, "r", swmr=True)
    with f:
        table = f["catalog"][:]
    return {name: table[name].astype(np.float64) for name in table.dtype.names}


def load_catalog(run_dir):
    """The run's catalogue (catalog.csv, else catalog.h5) as a dict of arrays, one entry per
    column; the same arrays for both formats (through the bkquake module when it is there:
    integer columns as int64; else all float64)."""
    if _bkquake is not None:
        run = _bkquake.load(run_dir)
        if run.catalog_file is not None:
            return dict(run.columns)
    csv = _path(run_dir, "catalog.csv")
    if os.path.exists(csv):
        return read_csv_columns(csv)
    h5 = _path(run_dir, "catalog.h5")
    if os.path.exists(h5):
        return read_h5_columns(h5)
    raise FileNotFoundError(f"{run_dir}: no catalog.csv or catalog.h5 (output.catalog = none?)")


def load_summary(run_dir):
    """summary.json as a dict ({} when the file is missing)."""
    p = _path(run_dir, "summary.json")
    if not os.path.exists(p):
        return {}
    with open(p) as f:
        return json.load(f)


def load_scene(run_dir):
    """scene.ini as {section: {key: value-string}} ({} when the file is missing)."""
    p = _path(run_dir, "scene.ini")
    if not os.path.exists(p):
        return {}
    cp = configparser.ConfigParser(inline_comment_prefixes=(";", "#"), interpolation=None)
    with open(p) as f:
        text = f.read()
    # Keys written before the first [section] (provenance) go to a pseudo-section.
    cp.read_string("[_top]\n" + text)
    return {s: dict(cp[s]) for s in cp.sections()}


def fit_window(summary):
    """(b, mu_min, mu_max) of the Gutenberg-Richter fit recorded in summary.json, or None.

    Accepts the run summary ("b_mle" + "fit_window": {mu_min, mu_max}) and the summary of
    `bkquake merge` ("b_mle", "mu_min", "mu_max", "fit": {...}). None also when the run
    found no acceptable window ("b_mle": null; see no_fit_reason).
    """
    b = summary.get("b_mle")
    if b is None and isinstance(summary.get("fit"), dict):
        b = summary["fit"].get("b_mle")
    window = summary.get("fit_window") or summary.get("fit") or summary
    lo, hi = window.get("mu_min"), window.get("mu_max")
    if b is None or lo is None or hi is None:
        return None
    return float(b), float(lo), float(hi)


def no_fit_reason(summary):
    """Why summary.json has no b ("fit_error" of a run, no_b_reason of a merge), or None."""
    fit = summary.get("fit") if isinstance(summary.get("fit"), dict) else {}
    return summary.get("fit_error") or fit.get("no_b_reason")


class WrongFolder(Exception):
    """A folder that is not the kind a script reads; the message is one line for the user."""


def require_files(run_dir, names, what):
    """Raises WrongFolder unless run_dir is a folder holding every file in names."""
    if not os.path.isdir(run_dir):
        raise WrongFolder(f"{run_dir}: not a folder")
    missing = [n for n in names if not os.path.exists(_path(run_dir, n))]
    if missing:
        summary = load_summary(run_dir)
        mode = summary.get("mode")
        kind = f" (a {mode} run)" if mode else ""
        if summary.get("status") == "interrupted":  # summary.json of a run stopped by a signal
            kind = f" (an interrupted {mode or ''} run: bkquake run ... --resume finishes it)"
        raise WrongFolder(f"{run_dir}{kind} has no {', '.join(missing)}: {what}")


def label(run_dir, scene=None):
    """A legend label: alpha and N from scene.ini when present, else the folder name."""
    scene = load_scene(run_dir) if scene is None else scene
    parts = []
    alpha = scene.get("friction", {}).get("alpha")
    blocks = scene.get("model", {}).get("blocks")
    if alpha is not None:
        parts.append(f"alpha = {alpha}")
    if blocks is not None:
        parts.append(f"N = {blocks}")
    name = os.path.basename(os.path.normpath(run_dir))
    return f"{name}: " + ", ".join(parts) if parts else name
