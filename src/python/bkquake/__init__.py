"""bkquake from Python: run a scene in-process, read any run folder, fit its catalogue.

    import bkquake
    run = bkquake.run("data/scenes/carlson-langer.ini", set={"run.events": 20000})
    run.catalog          # the event catalogue (a pandas DataFrame, or a dict of numpy arrays)
    run.summary["b_mle"]
    run.fit(mu_min=-3, mu_max=1)["fit"]["b_mle"]
    bkquake.load("runs/default").histogram

Everything here calls what the command line calls (the compiled part, bkquake._bkquake, is a
thin pybind11 layer over the same C++ functions): a scene is checked by the same
declarations with the same messages, `run` writes the same folder as `bkquake run`, `load`
reads catalogues through the same readers, `Run.fit` is `bkquake fit`.
"""

import collections.abc
import json
import os
import shutil
import stat
import tempfile
import warnings
import weakref

import numpy as np

from . import _bkquake

__version__ = _bkquake.__version__
git_revision = _bkquake.git_revision

__all__ = ["Scene", "Run", "run", "load", "read_catalog", "parameter_table"]


def parameter_table():
    """Every scene key's declaration: key, type, default, allowed, units, doc."""
    return {p.key: p for p in _bkquake.parameter_table()}


def _assignments(set):
    """`set` as (key, value) pairs: a mapping, or --set's "section.key=value" as one string or
    a list of them."""
    if set is None:
        return []
    if isinstance(set, collections.abc.Mapping):
        return list(set.items())
    if isinstance(set, (str, bytes)):
        set = [set]
    if not isinstance(set, collections.abc.Iterable):
        raise TypeError(
            f"bkquake: set: expected a mapping {{'section.key': value}} or 'section.key=value' "
            f"strings, got {type(set).__name__}"
        )
    pairs = []
    for item in set:
        if not isinstance(item, str) or "=" not in item:
            raise ValueError(
                f"bkquake: set: expected 'section.key=value' as --set takes it, got {item!r}"
            )
        key, value = item.split("=", 1)
        pairs.append((key.strip(), value))
    return pairs


def _check_key(key):
    """A key as a scene key must look: a str without '=' (which would split it into a key
    and a value, and change another key than the one named)."""
    if not isinstance(key, str):
        raise TypeError(f"bkquake: scene keys are 'section.key' strings, got {key!r}")
    if "=" in key:
        raise ValueError(
            f"unknown key {key!r} (set): a key has no '='; give the value separately, "
            f"{{'section.key': value}}"
        )
    return key


def _plain_file(path, what):
    """`path` when it is (or links to) a plain file; ValueError for a device, a FIFO, a
    socket, whose reading would never end or never begin (the readers' own check)."""
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        return path
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        why = "it is a device"
    elif stat.S_ISFIFO(mode):
        why = "it is a FIFO (a pipe)"
    elif stat.S_ISSOCK(mode):
        why = "it is a socket"
    else:
        return path  # a plain file, or a folder (which open() refuses in its words)
    raise ValueError(f"cannot read {what} '{path}': {why}, expected a file")


def _text(value):
    """A Python value as scene text: bools as true/false, floats shortest round-trip."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    return str(value)


class Scene(collections.abc.MutableMapping):
    """A scene: every key of the parameter table, validated by its declaration.

    Scene() is the built-in default; Scene("file.ini") reads a scene file; Scene({...}) or
    Scene("file.ini", {...}) applies overrides as `--set` does. A bad key or value raises
    ValueError with the command line's one-line message, e.g.
    Scene({"friction.alfa": 2}) -> ValueError: unknown key 'friction.alfa' (--set); did you
    mean 'friction.alpha'?  Keys read as typed values (float, int, bool, str); setting one
    checks its type and range at once, and the checks across keys run when the scene is
    built and again when it is run.
    """

    def __init__(self, mapping_or_path=None, overrides=None):
        pairs = _assignments(overrides)
        if isinstance(mapping_or_path, Scene):
            self._core = mapping_or_path._core.copy()
        elif isinstance(mapping_or_path, (str, os.PathLike)):
            self._core = _bkquake.SceneCore.from_file(os.fspath(mapping_or_path))
        elif mapping_or_path is None or isinstance(mapping_or_path, collections.abc.Mapping):
            self._core = _bkquake.SceneCore()
            pairs = _assignments(mapping_or_path) + pairs
        else:
            raise TypeError(
                f"bkquake.Scene: expected a mapping, a path or None, got {type(mapping_or_path).__name__}"
            )
        for key, value in pairs:
            self._core.apply_override(f"{_check_key(key)}={_text(value)}")
        self.checked()

    def checked(self):
        """The scene as a run takes it (keys that do not apply dropped, with a warning);
        ValueError with bkquake run's message where the combination is refused."""
        core, notes = self._core.checked()
        for note in notes:
            warnings.warn(note, stacklevel=3)
        scene = Scene.__new__(Scene)
        scene._core = core
        return scene

    def __getitem__(self, key):
        return self._core.get(key)

    def __setitem__(self, key, value):
        self._core.apply_override(f"{_check_key(key)}={_text(value)}")

    def __delitem__(self, key):
        """Resets the key to its default."""
        self._core.apply_override(f"{key}={parameter_table()[key].default}")

    def __iter__(self):
        return iter(p.key for p in _bkquake.parameter_table())

    def __len__(self):
        return len(_bkquake.parameter_table())

    def __eq__(self, other):
        return isinstance(other, Scene) and self._core == other._core

    def given(self):
        """The keys set explicitly (by the file or an override), with their values."""
        return {k: self[k] for k in self if self._core.is_set(k)}

    def applies(self, key):
        """False for a key this scene does not use (e.g. a damping ratio for the plain chain)."""
        return self._core.applies(key)

    def to_ini(self):
        """The scene as a commented INI file (what bkquake writes as scene.ini)."""
        return self._core.to_ini()

    @property
    def origin(self):
        return self._core.origin

    def __repr__(self):
        return f"bkquake.Scene({self._core.origin!r}, {self.given()!r})"


def _columns(pairs):
    return {name: array for name, array in pairs}


def _frame(columns):
    """A pandas DataFrame of the columns when pandas is installed, else the dict itself."""
    try:
        import pandas as pd
    except ImportError:
        return columns
    return pd.DataFrame(columns, copy=False)


class Run:
    """A run folder (scene.ini, catalog.csv or catalog.h5, histogram.csv, summary.json).

    Files are read when first asked for: `columns` (the catalogue as a dict of numpy
    arrays, integer columns as int64), `catalog` (the same as a pandas DataFrame when
    pandas is installed), `histogram`, `summary` (a dict), `scene` (a Scene); `fit()` is
    `bkquake fit` on the catalogue.
    """

    def __init__(self, path, _tmp=None):
        self.path = os.fspath(path)
        # The temporary folder the run went into, removed with this object.
        self._tmp = weakref.finalize(self, shutil.rmtree, _tmp, True) if _tmp else None
        self._columns = None
        self._catalog = None
        if not os.path.isdir(self.path):
            raise FileNotFoundError(f"{self.path}: not a folder")

    def _file(self, name):
        return os.path.join(self.path, name)

    @property
    def catalog_file(self):
        """The catalogue's path (catalog.csv, else catalog.h5), or None."""
        for name in ("catalog.csv", "catalog.h5"):
            if os.path.exists(self._file(name)):
                return self._file(name)
        return None

    @property
    def columns(self):
        """The catalogue as {column: numpy array} in the file's column order."""
        if self._columns is None:
            f = self.catalog_file
            if f is None:
                raise FileNotFoundError(
                    f"{self.path}: no catalog.csv or catalog.h5 (output.catalog = none?)"
                )
            self._columns = _columns(_bkquake.read_catalog(f))
        return self._columns

    @property
    def catalog(self):
        """The catalogue: a pandas DataFrame when pandas is installed, else `columns`."""
        if self._catalog is None:
            self._catalog = _frame(self.columns)
        return self._catalog

    @property
    def histogram(self):
        """histogram.csv (mu_low, mu_high, count, D, R, D_rate, R_rate), as `catalog` is."""
        return _frame(_columns(_bkquake.read_histogram(self._file("histogram.csv"))))

    def table(self, name):
        """Any other numeric CSV of the folder (timeseries.csv, segments.csv, spectrum.csv,
        energy.csv, ...) by name, every column float64, as `catalog` is."""
        return _frame(_columns(_bkquake.read_table(self._file(name))))

    @property
    def summary(self):
        """summary.json as a dict ({} when there is none)."""
        try:
            with open(_plain_file(self._file("summary.json"), "summary")) as f:
                return json.load(f)
        except FileNotFoundError:
            return {}

    @property
    def scene(self):
        """The run's effective scene (scene.ini)."""
        path = self._file("scene.ini")
        scene = Scene.__new__(Scene)
        scene._core = _bkquake.read_run_scene(path)
        # Keys this bkquake does not know are skipped (a folder of another version stays
        # readable), but never silently: bkquake run refuses them.
        for key in _bkquake.unknown_scene_keys(path):
            warnings.warn(
                f"unknown key '{key}' (in {path}) skipped: bkquake run refuses it; written by "
                f"another bkquake version, or edited?",
                stacklevel=2,
            )
        return scene

    def fit(self, mu_min=None, mu_max=None, bin_width=None, measure="moment", x_min=None,
            x_max=None):
        """`bkquake fit` on the catalogue: the dict its --json writes. "fit" holds b_mle,
        its errors (b_mle_err: Shi & Bolt; b_mle_boot_err: block bootstrap), the window,
        why it ends (mu_max_reason), warnings about a given window, ... Its
        "catalog_events" is the catalogue's size (also "events", as in the JSON),
        "n_in_window" the events the window holds. mu_min, mu_max: the fit window (None:
        automatic); bin_width: None for the run's stats.bin_width; measure: moment, or
        blocks, topplings, area, duration: then "tau" holds the power-law fit of that size
        (value, err, x_min, x_max, p, the likelihood-ratio tests; "catalog_events" and
        "n_in_range"), on [x_min, x_max] when given (None: chosen from the data)."""
        f = self.catalog_file
        if f is None:
            raise FileNotFoundError(f"{self.path}: no catalogue to fit")
        if bin_width is None and os.path.exists(self._file("scene.ini")):
            bin_width = self.scene["stats.bin_width"]
        with tempfile.TemporaryDirectory(prefix="bkquake-fit-") as tmp:
            out = os.path.join(tmp, "fit.json")
            _bkquake.fit_catalog(f, out, mu_min, mu_max, bin_width, measure, x_min, x_max)
            with open(out) as j:
                result = json.load(j)
        # The catalogue's size under a name that cannot be read as the window's count.
        for part in ("fit", "tau"):
            if isinstance(result.get(part), dict) and "events" in result[part]:
                result[part]["catalog_events"] = result[part]["events"]
        return result

    def spectrum(self, signal="pad_position", segment=None, start=None, end=None,
                 window="hann", peaks=6, f_min=0.0, out=None):
        """`bkquake spectrum` of a continuous run: the amplitude spectrum of `signal`
        (pad_position, pad_velocity, pad_friction, block:J) over the last half of
        `segment` (a row of segments.csv), the span [start, end] or the whole run, as a
        dict: frequency and amplitude arrays, peaks [(frequency, amplitude)], natural
        frequencies, the linear modes of steady sliding; writes spectrum.csv (or `out`)."""
        return _bkquake.spectrum(self.path, signal, segment, start, end, window, peaks, f_min,
                                 os.fspath(out) if out is not None else "")

    def __repr__(self):
        return f"bkquake.Run({self.path!r})"


def read_catalog(path):
    """One catalogue file (catalog.csv or catalog.h5, any name) as {column: numpy array}."""
    return _columns(_bkquake.read_catalog(os.fspath(path)))


def load(path):
    """The run folder at `path` as a Run (files are read when first asked for)."""
    return Run(path)


def run(scene=None, set=None, out=None, progress=True, resume=False, force=False):
    """Runs a scene in this process, as `bkquake run` does, and returns its Run.

    scene: a Scene, a scene file's path, a mapping of overrides, or None (the built-in
    default); set: overrides applied after it ({"run.events": 20000}, or --set's
    "run.events=20000" as a string or a list of them); out: the run folder (None: a temporary
    one, removed with the returned Run); resume, force: as --resume, --force; progress: the
    progress line on the terminal (stderr).

    Ctrl-C (SIGINT) stops the run after the current event with a checkpoint and raises
    KeyboardInterrupt naming the folder; run(..., out=that folder, resume=True) continues it.
    A temporary folder is then kept (the message says so): remove it when done.
    """
    s = Scene(scene)  # a copy: the caller's Scene is not changed by `set`
    for key, value in _assignments(set):
        s[key] = value
    checked = s.checked()
    tmp = None
    if out is None:
        tmp = tempfile.mkdtemp(prefix="bkquake-run-")
        out = tmp
    try:
        status = _bkquake.run_scene(checked._core, os.fspath(out), resume, force, not progress)
    except BaseException:
        if tmp:
            shutil.rmtree(tmp, ignore_errors=True)
        raise
    if status != 0:
        # A temporary folder is kept: it holds the checkpoint the message names.
        raise KeyboardInterrupt(
            f"bkquake.run stopped by a signal (exit status {status}); the checkpoint in "
            f"{os.fspath(out)} continues it with out={os.fspath(out)!r}, resume=True"
            + (" (a temporary folder, kept: remove it when done)" if tmp else "")
        )
    return Run(out, _tmp=tmp)
