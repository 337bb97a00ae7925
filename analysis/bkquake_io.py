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


# --- Writing a figure: the folder rule of bkquake's derived outputs (io/run_folder.hpp) ---

# The files a run writes into its folder (io/run_folder.cpp, run_own_files): no plot writes
# over them.
RUN_OWN_FILES = ("scene.ini", "catalog.csv", "catalog.h5", "histogram.csv", "summary.json",
                 "timeseries.csv", "segments.csv", "energy.csv", "energy_samples.csv",
                 "blocks.csv", "event_slip.csv", "checkpoint.bin", "checkpoint.prev.bin",
                 "checkpoint.final.bin", "bkquake.lock")
IMAGE_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg")


def is_run_folder(folder):
    """scene.ini with summary.json or a checkpoint beside it (io/run_folder.cpp)."""
    return os.path.isfile(_path(folder, "scene.ini")) and any(
        os.path.exists(_path(folder, n))
        for n in ("summary.json", "checkpoint.bin", "checkpoint.prev.bin"))


def is_bkquake_folder(folder):
    """A folder a bkquake command wrote and locks while it writes: a run, sweep, stability
    or accuracy folder (scene.ini or sweep.ini in it)."""
    return any(os.path.isfile(_path(folder, n)) for n in ("scene.ini", "sweep.ini"))


class Refused(Exception):
    """An output a script will not write; the message is one line for the user."""


class FolderLock:
    """The lock of a bkquake folder (io/folder_lock.hpp): the file bkquake.lock (host, pid,
    command, start), published with link() so that it exists only when complete, and flock()ed
    while held. A lock whose holder lives is refused naming it; a stale lock of this host (its
    flock gone with its process) is taken over with a warning; one of another host is refused."""

    def __init__(self, folder, command):
        self.folder = folder
        self.path = _path(folder, "bkquake.lock")
        self.command = command
        self.fd = None

    def __enter__(self):
        import datetime
        import fcntl
        import socket
        import sys
        import tempfile
        host = socket.gethostname()
        since = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
        text = (f"bkquake folder lock\nhost {host}\npid {os.getpid()}\n"
                f"command {self.command}\nsince {since}\n").encode()
        for _ in range(5):
            try:
                fd, tmp = tempfile.mkstemp(prefix=".bkquake.lock.tmp-", dir=self.folder)
            except OSError as e:
                raise Refused(f"cannot write to folder '{self.folder}': {e.strerror}")
            os.write(fd, text)
            os.fchmod(fd, 0o644)
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            try:
                os.link(tmp, self.path)
                os.unlink(tmp)
                self.fd = fd
                return self
            except FileExistsError:
                os.unlink(tmp)
                os.close(fd)
            try:
                old = os.open(self.path, os.O_RDWR)
            except FileNotFoundError:
                continue  # released meanwhile
            fields = dict(line.split(" ", 1) for line in
                          os.read(old, 4096).decode(errors="replace").splitlines() if " " in line)
            holder = (f"bkquake {fields.get('command', '?')} (pid {fields.get('pid', '?')} on "
                      f"host {fields.get('host', '?')})")
            try:
                fcntl.flock(old, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError:
                os.close(old)
                raise Refused(f"folder '{self.folder}' is in use by {holder}; try again when it "
                              "is done")
            if fields.get("host", host) != host:
                os.close(old)
                raise Refused(f"folder '{self.folder}' is locked by {holder}; a lock of another "
                              f"host is never taken over: if that command is gone, delete "
                              f"'{self.path}' by hand")
            if os.fstat(old).st_ino != os.stat(self.path).st_ino:
                os.close(old)
                continue  # released and replaced meanwhile
            os.ftruncate(old, 0)
            os.pwrite(old, text, 0)
            print(f"{self.command}: warning: taking over the stale lock of '{self.folder}' left "
                  f"by {holder}, which is gone", file=sys.stderr)
            self.fd = old
            return self
        raise Refused(f"cannot take the lock '{self.path}': it keeps changing")

    def __exit__(self, *exc):
        try:
            if os.fstat(self.fd).st_ino == os.stat(self.path).st_ino:
                os.unlink(self.path)
        except FileNotFoundError:
            pass
        os.close(self.fd)


def check_output(out, inputs, command):
    """Raises Refused unless `out` may take a figure: an image file name, none of `inputs`
    (the files and folders the script read), not a folder, not one of a run's own files."""
    if not out.lower().endswith(IMAGE_SUFFIXES):
        raise Refused(f"output '{out}' is not an image file name; expected one ending in "
                      + ", ".join(IMAGE_SUFFIXES))
    if os.path.isdir(out):
        raise Refused(f"output '{out}' is a folder, expected a file name")
    real = os.path.realpath(out)
    for path in inputs:
        if os.path.realpath(path) == real:
            raise Refused(f"output '{out}' is its input '{path}'; {command} writes nothing over "
                          "its inputs: choose another output")
    folder = os.path.dirname(real)
    if is_run_folder(folder) and os.path.basename(real) in RUN_OWN_FILES:
        raise Refused(f"output '{out}' is the file {os.path.basename(real)} of the run in "
                      f"'{folder}'; {command} writes nothing over a run's own files")


def check_output_or_exit(out, inputs, command):
    """check_output, a refusal printed as one line on stderr with exit status 2: for a script
    to call before it draws."""
    import sys
    try:
        check_output(out, inputs, command)
    except Refused as e:
        print(f"{command}: {e}", file=sys.stderr)
        sys.exit(2)


def save_figure(fig, out, inputs, command, **savefig_args):
    """Writes `fig` to `out` under the rule of every derived output (io/run_folder.hpp,
    DerivedOutput): never over an input or a run's own file (check_output); in a bkquake
    folder (or a subfolder of one, such as a run's seismicity/) under that folder's lock, so never beside a live run; through a temporary file
    renamed over `out`, so only the figure's own earlier version is replaced, whole.
    A refusal is one line on stderr and exit status 2."""
    import sys
    try:
        check_output(out, inputs, command)
        folder = os.path.dirname(os.path.abspath(out))
        base, ext = os.path.splitext(out)
        tmp = f"{base}.tmp-{os.getpid()}{ext}"
        # A derived subfolder (a run's seismicity/) is written under the run folder's lock.
        held = next((f for f in (folder, os.path.dirname(folder)) if is_bkquake_folder(f)), None)
        lock = FolderLock(held, command) if held else None
        if lock:
            lock.__enter__()
        try:
            try:
                fig.savefig(tmp, **savefig_args)
                os.replace(tmp, out)
            except OSError as e:
                raise Refused(f"cannot write '{out}': {e.strerror}")
            finally:
                if os.path.exists(tmp):
                    os.unlink(tmp)
        finally:
            if lock:
                lock.__exit__()
    except Refused as e:
        print(f"{command}: {e}", file=sys.stderr)
        sys.exit(2)
