"""Executes the example notebooks of this folder with nbclient (Debian python3-nbclient,
python3-ipykernel) and writes the executed copies (with their figures) to --out. A cell that
raises fails the run: ctest runs this with --small as the test Notebooks.

    PYTHONPATH=build/python /usr/bin/python3 analysis/notebooks/execute.py [--small] [--out DIR] [NOTEBOOK...]

--small: BKQUAKE_NOTEBOOK_SMALL=1, which each notebook reads to run at reduced size.
"""

import argparse
import os
import sys
from pathlib import Path

import nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError

HERE = Path(__file__).resolve().parent


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("notebooks", nargs="*", type=Path)
    ap.add_argument("--small", action="store_true", help="run at reduced size")
    ap.add_argument("--out", type=Path, default=Path("build/notebooks"))
    ap.add_argument("--timeout", type=int, default=600, help="seconds a cell may take")
    args = ap.parse_args()
    if args.small:
        os.environ["BKQUAKE_NOTEBOOK_SMALL"] = "1"
    os.environ.setdefault("BKQUAKE_SOURCE_DIR", str(HERE.parents[1]))
    os.environ.setdefault("MPLBACKEND", "agg")
    os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # a debugger note per kernel
    # The kernel runs in the notebooks' folder: a relative PYTHONPATH (build/python) is
    # made absolute from here.
    paths = os.environ.get("PYTHONPATH", "").split(os.pathsep)
    os.environ["PYTHONPATH"] = os.pathsep.join(os.path.abspath(p) for p in paths if p)
    args.out.mkdir(parents=True, exist_ok=True)
    failed = []
    for path in args.notebooks or sorted(HERE.glob("*.ipynb")):
        nb = nbformat.read(path, as_version=4)
        client = NotebookClient(nb, timeout=args.timeout, kernel_name="python3",
                                resources={"metadata": {"path": str(path.resolve().parent)}})
        try:
            client.execute()
            status = "ok"
        except CellExecutionError as e:
            status = "FAILED"
            failed.append(path.name)
            print(f"{path.name}: {e}", file=sys.stderr)
        out = args.out / path.name
        nbformat.write(nb, out)
        print(f"{path.name}: {status} -> {out}")
    if failed:
        sys.exit(f"notebooks failed: {', '.join(failed)}")


if __name__ == "__main__":
    main()
