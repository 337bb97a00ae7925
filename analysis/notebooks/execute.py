"""Executes the example notebooks of this folder with nbclient (Debian python3-nbclient,
python3-ipykernel) and writes the executed copies (with their figures) to --out. A cell that
raises fails the run, and so does a cell that makes a figure (plt.subplots, plt.figure)
without an image among its outputs, or whose outputs, executed or committed (and the
documentation's page of them), show a path under /tmp/: ctest runs this with --small as
the test Notebooks.

    PYTHONPATH=build/python /usr/bin/python3 analysis/notebooks/execute.py [--small] [--out DIR]
        [--in-place] [--docs DIR] [NOTEBOOK...]

--small: BKQUAKE_NOTEBOOK_SMALL=1, which each notebook reads to run at reduced size.
--in-place: writes the executed notebooks over the sources (their committed outputs).
--docs DIR: also writes each executed notebook as DIR/NAME.md with its figures as
DIR/img/NAME_K.png, the pages of the documentation site (docs/notebooks/).

The kernel draws with matplotlib's inline backend (matplotlib_inline, from Debian
python3-ipykernel's dependencies), so each figure is a PNG output of the cell that made it.
"""

import argparse
import base64
import os
import re
import sys
from pathlib import Path

import nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError

HERE = Path(__file__).resolve().parent


FIGURE = re.compile(r"plt\.(subplots|figure)\(")


def figure_cells_without_image(nb):
    """The indices of the code cells that make a figure and show no image."""
    missing = []
    for k, cell in enumerate(nb.cells):
        if cell.cell_type != "code" or not FIGURE.search(cell.source):
            continue
        if not any("image/png" in o.get("data", {}) for o in cell.get("outputs", [])):
            missing.append(k)
    return missing


def output_text(cell):
    """Everything a code cell's outputs show as text (streams, values, tables, errors)."""
    parts = []
    for o in cell.get("outputs", []):
        parts.append(o.get("text", ""))
        parts.extend(v for k, v in o.get("data", {}).items() if k.startswith("text/"))
        parts.extend(o.get("traceback", []))
    return "\n".join(p if isinstance(p, str) else "".join(p) for p in parts)


def cells_showing_tmp(nb):
    """The indices of the code cells whose outputs show a path under /tmp/ (a scratch folder
    of one machine and one run: a notebook names its runs relative to its working folder)."""
    return [k for k, cell in enumerate(nb.cells)
            if cell.cell_type == "code" and "/tmp/" in output_text(cell)]


def to_markdown(nb, name, folder, small):
    """The executed notebook as a markdown page: its markdown cells as they are, its code in
    python blocks, its printed and returned values in text blocks (tables as HTML), its
    figures as PNG files beside the page. Returns the page's path."""
    (folder / "img").mkdir(parents=True, exist_ok=True)
    parts = [f"<!-- Made by analysis/notebooks/execute.py --docs from analysis/notebooks/"
             f"{name}.ipynb; edit the notebook, not this page. -->"]
    note = (f"*The notebook `analysis/notebooks/{name}.ipynb` as executed"
            + (" at reduced size (`execute.py --small`)" if small else "") + ".*")
    figures = 0
    for cell in nb.cells:
        if cell.cell_type == "markdown":
            parts.append(cell.source)
            if note:  # below the notebook's title
                parts.append(note)
                note = None
            continue
        if cell.cell_type != "code":
            continue
        parts.append("```python\n" + cell.source + "\n```")
        for o in cell.get("outputs", []):
            data = o.get("data", {})
            if o.get("output_type") == "stream":
                parts.append("```text\n" + o.get("text", "").rstrip("\n") + "\n```")
            elif "image/png" in data:
                figures += 1
                png = f"{name}_{figures}.png"
                (folder / "img" / png).write_bytes(base64.b64decode(data["image/png"]))
                parts.append(f"![figure {figures} of {name}](img/{png})")
            elif "text/html" in data:
                parts.append(data["text/html"].strip())
            elif "text/plain" in data:
                parts.append("```text\n" + data["text/plain"].rstrip("\n") + "\n```")
    page = folder / f"{name}.md"
    page.write_text("\n\n".join(parts) + "\n", encoding="utf-8")
    return page


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("notebooks", nargs="*", type=Path)
    ap.add_argument("--small", action="store_true", help="run at reduced size")
    ap.add_argument("--out", type=Path, default=Path("build/notebooks"))
    ap.add_argument("--timeout", type=int, default=600, help="seconds a cell may take")
    ap.add_argument("--in-place", action="store_true", help="write the outputs into the sources")
    ap.add_argument("--docs", type=Path, help="write markdown pages and figures into DIR")
    args = ap.parse_args()
    if args.small:
        os.environ["BKQUAKE_NOTEBOOK_SMALL"] = "1"
    os.environ.setdefault("BKQUAKE_SOURCE_DIR", str(HERE.parents[1]))
    # Inline: figures become the cells' image/png outputs (agg would draw them nowhere).
    os.environ["MPLBACKEND"] = "module://matplotlib_inline.backend_inline"
    os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # a debugger note per kernel
    # The kernel runs in the notebooks' folder: a relative PYTHONPATH (build/python) is
    # made absolute from here.
    paths = os.environ.get("PYTHONPATH", "").split(os.pathsep)
    os.environ["PYTHONPATH"] = os.pathsep.join(os.path.abspath(p) for p in paths if p)
    args.out.mkdir(parents=True, exist_ok=True)
    failed = []
    for path in args.notebooks or sorted(HERE.glob("*.ipynb")):
        nb = nbformat.read(path, as_version=4)
        # The committed outputs and the documentation's page of them, as they are now (unless
        # this run rewrites them).
        page = HERE.parents[1] / "docs" / "notebooks" / f"{path.stem}.md"
        for k in ([] if args.in_place else cells_showing_tmp(nb)):
            failed.append(path.name)
            print(f"{path.name}: the committed outputs of cell {k} show a /tmp/ path",
                  file=sys.stderr)
        if not args.docs and page.exists() and "/tmp/" in page.read_text(encoding="utf-8"):
            failed.append(path.name)
            print(f"{path.name}: {page} shows a /tmp/ path", file=sys.stderr)
        client = NotebookClient(nb, timeout=args.timeout, kernel_name="python3",
                                resources={"metadata": {"path": str(path.resolve().parent)}})
        try:
            client.execute()
            status = "ok"
            for k in figure_cells_without_image(nb):
                status = "FAILED"
                print(f"{path.name}: cell {k} makes a figure but has no image output",
                      file=sys.stderr)
            for k in cells_showing_tmp(nb):
                status = "FAILED"
                print(f"{path.name}: cell {k} shows a /tmp/ path in its outputs",
                      file=sys.stderr)
            if status != "ok":
                failed.append(path.name)
        except CellExecutionError as e:
            status = "FAILED"
            failed.append(path.name)
            print(f"{path.name}: {e}", file=sys.stderr)
        out = args.out / path.name
        nbformat.write(nb, out)
        print(f"{path.name}: {status} -> {out}")
        if status == "ok" and args.in_place:
            nbformat.write(nb, path)
            print(f"{path.name}: outputs written into {path}")
        if status == "ok" and args.docs:
            print(f"{path.name}: page {to_markdown(nb, path.stem, args.docs, args.small)}")
    if failed:
        sys.exit(f"notebooks failed: {', '.join(dict.fromkeys(failed))}")


if __name__ == "__main__":
    main()
