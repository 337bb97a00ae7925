"""The bkquake Python module against the command line: the same scene gives the same
catalogue value for value, columns keep their dtypes, scene errors are the CLI's messages,
CSV and HDF5 catalogues read the same, fit is bkquake fit, and Ctrl-C leaves a run that
resumes."""

import json
import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

import bkquake
from conftest import SMALL, cli, set_args

INTEGER_COLUMNS = {"event", "trigger", "blocks", "first_block", "last_block"}


def test_import_names_the_version():
    assert bkquake.__version__
    assert bkquake.git_revision


def test_run_gives_the_cli_catalogue_value_for_value(cli_run, tmp_path):
    run = bkquake.run(set=SMALL, out=tmp_path / "py", progress=False)
    ours, theirs = run.columns, bkquake.load(cli_run).columns
    assert list(ours) == list(theirs)
    assert len(ours["event"]) == SMALL["run.events"]
    for name in ours:
        assert ours[name].dtype == theirs[name].dtype, name
        np.testing.assert_array_equal(ours[name], theirs[name], err_msg=name)
    # The files themselves, byte for byte.
    for name in ("catalog.csv", "histogram.csv"):
        assert (tmp_path / "py" / name).read_bytes() == (cli_run / name).read_bytes(), name


def test_catalogue_columns_have_their_own_dtypes(cli_run):
    columns = bkquake.load(cli_run).columns
    header = (cli_run / "catalog.csv").read_text().splitlines()[0].split(",")
    assert list(columns) == header
    for name, a in columns.items():
        want = np.int64 if name in INTEGER_COLUMNS else np.float64
        assert a.dtype == want, name
    np.testing.assert_array_equal(columns["event"], np.arange(1, SMALL["run.events"] + 1))
    np.testing.assert_allclose(columns["magnitude"], np.log(columns["moment"]), rtol=1e-15)


def test_catalogue_is_a_dataframe_with_pandas(cli_run):
    pd = pytest.importorskip("pandas")
    frame = bkquake.load(cli_run).catalog
    assert isinstance(frame, pd.DataFrame)
    assert frame["blocks"].dtype == np.int64 and frame["moment"].dtype == np.float64
    assert len(frame) == SMALL["run.events"]


def test_histogram_and_summary(cli_run):
    run = bkquake.load(cli_run)
    h = run.histogram
    counts = np.asarray(h["count"])
    assert counts.dtype == np.int64
    assert counts.sum() == SMALL["run.events"]
    s = run.summary
    assert s == json.loads((cli_run / "summary.json").read_text())
    assert s["status"] == "finished"


def test_run_scene_reads_back(cli_run):
    scene = bkquake.load(cli_run).scene
    assert scene["model.blocks"] == SMALL["model.blocks"]
    assert scene["run.events"] == SMALL["run.events"]


def test_fit_is_bkquake_fit(cli_run, tmp_path):
    out = tmp_path / "fit.json"
    cli("fit", str(cli_run / "catalog.csv"), "--mu-min", "-8.6", "--mu-max", "-6", "--json",
        str(out))
    theirs = json.loads(out.read_text())
    ours = bkquake.load(cli_run).fit(mu_min=-8.6, mu_max=-6)
    # Python adds the catalogue's size under a name that cannot be read as the window's.
    assert ours["fit"].pop("catalog_events") == theirs["fit"]["events"]
    assert ours["fit"] == theirs["fit"]
    assert ours["fit"]["mu_min"] == -8.6 and ours["fit"]["b_mle"] > 0
    with pytest.raises(ValueError, match="mu_max must be greater than mu_min"):
        bkquake.load(cli_run).fit(mu_min=1, mu_max=-2)
    with pytest.raises(ValueError, match=r"fit window \[-2, 1\) holds 0 events"):
        bkquake.load(cli_run).fit(mu_min=-2, mu_max=1)


def test_fit_measure_and_errors(cli_run, tmp_path):
    """fit(measure=...) carries the power law of that size ("tau"), the fit its bootstrap
    error beside Shi & Bolt's, and the catalogue's size apart from the window's count."""
    run = bkquake.load(cli_run)
    res = run.fit(measure="blocks")
    out = tmp_path / "fit.json"
    cli("fit", str(cli_run / "catalog.csv"), "--measure", "blocks", "--json", str(out))
    tau = res["tau"]
    assert {k: v for k, v in tau.items() if k != "catalog_events"} == json.loads(
        out.read_text())["tau"]
    assert tau["catalog_events"] == SMALL["run.events"] and tau["n_in_range"] <= SMALL["run.events"]
    assert tau["measure"] == "blocks" and tau["discrete"] is True
    assert tau["ok"] is False or (tau["value"] > 1 and tau["err"] > 0 and tau["x_min"] >= 1)
    f = res["fit"]
    assert f["events"] == f["catalog_events"] == SMALL["run.events"]
    assert f["n_in_window"] <= f["catalog_events"]
    # A given range for the power law: fitted there; refused for the moment or when empty.
    given = run.fit(measure="blocks", x_min=1, x_max=5)["tau"]
    assert given["x_min"] == 1 and given["x_max"] == 5 and given["x_min_auto"] is False
    with pytest.raises(ValueError, match="x_min = 2: a power law's range"):
        run.fit(x_min=2)
    with pytest.raises(ValueError, match="x_max = 1: allowed: greater than x_min = 3"):
        run.fit(measure="blocks", x_min=3, x_max=1)
    assert "b_mle_boot_err" in f and "mu_max_reason" in f
    assert "tau" not in run.fit()
    with pytest.raises(ValueError, match="expected one of moment, blocks"):
        run.fit(measure="energy")


def cli_error(*overrides):
    """The CLI's one-line message for these --set overrides (without 'bkquake: error: ')."""
    r = cli("run", *sum((["--set", o] for o in overrides), []), "--dump-defaults", check=False)
    assert r.returncode == 2
    line = r.stderr.strip()
    assert "\n" not in line and line.startswith("bkquake: error: ")
    return line[len("bkquake: error: "):]


@pytest.mark.parametrize(
    "key, value, text",
    [
        ("friction.alfa", 2, "2"),
        ("friction.alpha", -1, "-1"),
        ("model.blocks", 2.5, "2.5"),
        ("friction.law", "coulomb", "coulomb"),
        ("model.damping_ratio", 0.1, "0.1"),  # given where it does not apply
    ],
)
def test_scene_errors_are_the_cli_messages(key, value, text):
    want = cli_error(f"{key}={text}")
    with pytest.raises(ValueError) as e:
        bkquake.Scene({key: value})
    assert str(e.value) == want


def test_scene_is_dict_like_and_typed(tmp_path):
    s = bkquake.Scene()
    assert s["model.blocks"] == 100 and isinstance(s["model.blocks"], int)
    assert isinstance(s["friction.alpha"], float)
    assert s["friction.law"] == "clst91"
    assert len(s) == len(list(s)) == len(bkquake.parameter_table())
    s["friction.alpha"] = 3
    assert s["friction.alpha"] == 3.0 and s.given() == {"friction.alpha": 3.0}
    with pytest.raises(ValueError, match="friction.alpha"):
        s["friction.alpha"] = "x"
    del s["friction.alpha"]
    assert s["friction.alpha"] == 2.5
    f = tmp_path / "scene.ini"
    f.write_text("[friction]\nalpha = 2\n")
    from_file = bkquake.Scene(f)
    assert from_file["friction.alpha"] == 2.0
    assert bkquake.Scene(str(f), {"model.blocks": 20})["model.blocks"] == 20
    assert bkquake.Scene(from_file) == from_file and bkquake.Scene(from_file) != s


def test_run_takes_a_scene_a_path_or_none(tmp_path):
    f = tmp_path / "small.ini"
    f.write_text("[model]\nblocks = 40\n[run]\nevents = 400\ntransient_events = 50\n")
    by_path = bkquake.run(str(f), progress=False)
    by_scene = bkquake.run(bkquake.Scene(f), progress=False)
    by_none = bkquake.run(None, set=SMALL, progress=False)
    for other in (by_scene, by_none):
        for name, a in by_path.columns.items():
            np.testing.assert_array_equal(a, other.columns[name], err_msg=name)


def test_run_without_out_uses_a_temporary_folder():
    run = bkquake.run(set=SMALL, progress=False)
    folder = run.path
    assert os.path.isfile(os.path.join(folder, "summary.json"))
    del run
    import gc

    gc.collect()
    assert not os.path.exists(folder)


def test_csv_and_hdf5_catalogues_read_the_same(cli_run, tmp_path):
    h5 = tmp_path / "h5"
    r = cli("run", *set_args({**SMALL, "output.catalog": "hdf5"}), "--out", str(h5), "--quiet",
            check=False)
    if r.returncode == 2 and "without HDF5" in r.stderr:
        pytest.skip("this bkquake was built without HDF5")
    assert r.returncode == 0, r.stderr
    a, b = bkquake.load(cli_run).columns, bkquake.load(h5).columns
    assert list(a) == list(b)
    one_file = bkquake.read_catalog(h5 / "catalog.h5")
    assert all(np.array_equal(one_file[k], b[k]) for k in b)
    for name in a:
        assert a[name].dtype == b[name].dtype, name
        np.testing.assert_array_equal(a[name], b[name], err_msg=name)


def test_load_errors_name_the_file(tmp_path):
    (tmp_path / "catalog.csv").write_text("event,moment\n1,0.5\n2,abc\n")
    with pytest.raises(ValueError, match=r"catalog.csv line 3: column 'moment': expected a number"):
        bkquake.load(tmp_path).columns
    (tmp_path / "catalog.csv").write_text("event,moment\n1,0.5,3\n")
    with pytest.raises(ValueError, match="line 2: expected 2 fields, got 3"):
        bkquake.load(tmp_path).columns
    with pytest.raises(FileNotFoundError):
        bkquake.load(tmp_path / "nothing")


def interrupted_run(out, resume):
    """bkquake.run of a long scene in a child process, stopped by SIGINT once the run has
    written a checkpoint (which it does only inside its loop, where its stop handler is
    installed); returns the child's stdout."""
    checkpoint = out / "checkpoint.bin"

    def stamp():  # a new checkpoint is renamed into place: a new inode
        try:
            st = checkpoint.stat()
            return st.st_ino, st.st_mtime_ns
        except FileNotFoundError:
            return None

    before = stamp()
    script = textwrap.dedent(
        f"""
        import bkquake
        try:
            bkquake.run(set={LONG!r}, out={str(out)!r}, progress=False, resume={resume})
        except KeyboardInterrupt as e:
            print("KeyboardInterrupt:", e)
            raise SystemExit(7)
        """
    )
    p = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True)
    while stamp() in (None, before):
        assert p.poll() is None, "the run ended before it was interrupted"
        time.sleep(0.01)
    p.send_signal(signal.SIGINT)
    stdout, _ = p.communicate(timeout=120)
    assert p.returncode == 7, stdout
    assert "KeyboardInterrupt" in stdout
    return stdout


# Far more events than a test waits for, with a checkpoint every 100 of them.
LONG = {"model.blocks": 40, "run.events": 10**9, "run.transient_events": 0,
        "run.checkpoint_events": 100}


def test_ctrl_c_raises_keyboard_interrupt_and_leaves_a_resumable_folder(tmp_path):
    out = tmp_path / "long"
    interrupted_run(out, resume=False)
    first = json.loads((out / "summary.json").read_text())
    assert first["status"] == "interrupted"
    assert first["events"] >= 100
    # The folder continues with resume=True (and stops again on the next Ctrl-C).
    stdout = interrupted_run(out, resume=True)
    second = json.loads((out / "summary.json").read_text())
    assert second["status"] == "interrupted"
    assert second["events"] > first["events"]
    assert len(bkquake.load(out).columns["event"]) == second["events"]


def python_call(code, timeout=60, env=None):
    """Runs `code` in a child interpreter with this module (a reader that hangs fails the
    test after `timeout` seconds instead of stalling the suite); returns the CompletedProcess."""
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True,
                          text=True, timeout=timeout, env=env)


READ_OR_REFUSE = """
import sys, bkquake
try:
    {call}
except ValueError as e:
    print("ValueError:", e)
    sys.exit(0 if str(e) else 5)
sys.exit(3)
"""


@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom"])
def test_readers_refuse_devices_at_once(device, cli_run, tmp_path):
    r = python_call(READ_OR_REFUSE.format(call=f"bkquake.read_catalog({device!r})"))
    assert r.returncode == 0, r.stdout + r.stderr
    assert "device" in r.stdout
    # Through a link in a run folder: the catalogue, the histogram, any table, the summary.
    d = tmp_path / "linked"
    d.mkdir()
    for name in ("catalog.csv", "histogram.csv", "timeseries.csv", "summary.json"):
        (d / name).symlink_to(device)
    for call in ("bkquake.load(d).columns", "bkquake.load(d).histogram",
                 "bkquake.load(d).table('timeseries.csv')", "bkquake.load(d).summary"):
        r = python_call(f"d = {str(d)!r}\n" + READ_OR_REFUSE.format(call=call))
        assert r.returncode == 0, call + ": " + r.stdout + r.stderr


def test_readers_refuse_a_fifo_at_once(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    r = python_call(READ_OR_REFUSE.format(call=f"bkquake.read_catalog({str(fifo)!r})"))
    assert r.returncode == 0, r.stdout + r.stderr
    assert "FIFO" in r.stdout


def test_random_bytes_raise_a_value_error_that_says_why(tmp_path):
    rng = np.random.default_rng(37)
    for k in range(20):
        f = tmp_path / f"garbage{k}.csv"
        f.write_bytes(rng.integers(0, 256, size=int(rng.integers(1, 4000)), dtype=np.uint8)
                      .tobytes())
        with pytest.raises(ValueError) as e:
            bkquake.read_catalog(f)
        message = str(e.value)
        assert message, f"empty message for {f}"
        assert not any(ord(c) < 32 or 127 <= ord(c) < 160 for c in message), message


def test_ctrl_c_without_out_keeps_the_folder_it_names(tmp_path):
    env = {**os.environ, "TMPDIR": str(tmp_path)}
    script = textwrap.dedent(
        f"""
        import bkquake
        try:
            bkquake.run(set={LONG!r}, progress=False)
        except KeyboardInterrupt as e:
            print(e)
            raise SystemExit(7)
        """
    )
    p = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True,
                         env=env)
    deadline = time.time() + 120
    while not list(tmp_path.glob("bkquake-run-*/checkpoint.bin")):
        assert p.poll() is None, "the run ended before it was interrupted"
        assert time.time() < deadline
        time.sleep(0.01)
    p.send_signal(signal.SIGINT)
    stdout, _ = p.communicate(timeout=120)
    assert p.returncode == 7, stdout
    folder = stdout.split("the checkpoint in ")[1].split(" continues it")[0]
    assert "kept" in stdout
    assert os.path.isfile(os.path.join(folder, "checkpoint.bin")), stdout
    assert bkquake.load(folder).summary["status"] == "interrupted"


def test_unknown_key_in_scene_ini_is_not_ignored_silently(cli_run, tmp_path):
    d = tmp_path / "edited"
    d.mkdir()
    for name in ("catalog.csv", "histogram.csv", "summary.json", "scene.ini"):
        (d / name).write_bytes((cli_run / name).read_bytes())
    with open(d / "scene.ini", "a") as f:
        f.write("\n[friction]\nalfa = 2\n")
    r = cli("run", str(d / "scene.ini"), "--out", str(tmp_path / "o"), check=False)
    assert r.returncode == 2 and "friction.alfa" in r.stderr
    run = bkquake.load(d)
    with pytest.warns(UserWarning, match=r"unknown key 'friction.alfa'"):
        run.scene
    with pytest.warns(UserWarning, match=r"unknown key 'friction.alfa'"):
        run.fit()


def test_set_takes_a_mapping_or_set_strings_and_refuses_a_key_with_equals():
    as_dict = bkquake.Scene(None, {"model.blocks": 40, "run.events": 400})
    assert bkquake.Scene(None, "model.blocks=40")["model.blocks"] == 40
    as_list = bkquake.Scene(None, ["model.blocks=40", "run.events=400"])
    assert as_list == as_dict
    with pytest.raises(ValueError, match=r"unknown key 'run.events=5' \(set\)"):
        bkquake.Scene({"run.events=5": 7})
    with pytest.raises(ValueError, match=r"unknown key 'run.events=5' \(set\)"):
        bkquake.run(set={"run.events=5": 7}, progress=False)
    with pytest.raises(ValueError, match=r"expected 'section.key=value'"):
        bkquake.run(set=["run.events"], progress=False)
    with pytest.raises(TypeError, match=r"set: expected a mapping"):
        bkquake.run(set=5, progress=False)
