"""Shared fixtures of the Python module's tests (run by ctest as PythonModule, with
PYTHONPATH at build/python and BKQUAKE_BINARY naming the program)."""

import os
import subprocess

import pytest

SOURCE_DIR = os.environ.get(
    "BKQUAKE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", "..")
)
BINARY = os.environ.get("BKQUAKE_BINARY", os.path.join(SOURCE_DIR, "build", "bkquake"))

# A small event run of the built-in default (the Carlson-Langer reference).
SMALL = {"run.events": 400, "run.transient_events": 50, "model.blocks": 40}


def cli(*args, check=True):
    """Runs the bkquake program; returns the CompletedProcess (text output)."""
    r = subprocess.run([BINARY, *args], capture_output=True, text=True)
    if check and r.returncode != 0:
        raise AssertionError(f"bkquake {' '.join(args)} exited {r.returncode}: {r.stderr}")
    return r


def set_args(overrides):
    out = []
    for k, v in overrides.items():
        out += ["--set", f"{k}={v}"]
    return out


@pytest.fixture(scope="session")
def cli_run(tmp_path_factory):
    """The small run made by the command line, once per session."""
    d = tmp_path_factory.mktemp("cli") / "run"
    cli("run", *set_args(SMALL), "--out", str(d), "--quiet")
    return d
