"""Reading a catalogue into Python: bkquake.load (the C++ reader) against the pure-Python
loader analysis/bkquake_io.py, each in a fresh interpreter; prints the time of the read and
the peak memory it added (ru_maxrss after the read minus before it), beside the size of the
arrays it returns.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_load.py RUN_DIR
    PYTHONPATH=build/python /usr/bin/python3 bench/python_load.py --make runs/load-1e6

--make first runs the built-in default with run.events = 1e6 (catalog.csv about 100 MB)
into RUN_DIR with the program in build/.
"""

import argparse
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

CHILD = r"""
import resource, sys, time
sys.path.insert(0, {analysis!r})
import numpy as np
import bkquake, bkquake_io
try:
    import pandas
except ImportError:
    pass
def peak():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
before = peak()
t0, c0 = time.perf_counter(), time.process_time()
{read}
seconds, cpu = time.perf_counter() - t0, time.process_time() - c0
arrays = sum(np.asarray(a).nbytes for a in columns.values())
print(seconds, cpu, peak() - before, arrays, len(columns), len(next(iter(columns.values()))))
"""

READERS = {
    "bkquake.load(dir).columns": "columns = bkquake.load({d!r}).columns",
    "bkquake.load(dir).catalog (pandas)": (
        "frame = bkquake.load({d!r}).catalog\ncolumns = {{k: frame[k].to_numpy() for k in frame}}"
    ),
    # Without the module, as analysis/bkquake_io.py read catalogues before it existed.
    "bkquake_io.load_catalog(dir), no module": (
        "bkquake_io._bkquake = None\ncolumns = bkquake_io.load_catalog({d!r})"
    ),
}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run_dir")
    ap.add_argument("--make", action="store_true", help="make a 1e6-event run there first")
    ap.add_argument("--events", type=int, default=10**6)
    args = ap.parse_args()
    d = os.path.abspath(args.run_dir)
    if args.make:
        subprocess.run(
            [os.path.join(ROOT, "build", "bkquake"), "run", "--set", f"run.events={args.events}",
             "--out", d, "--force", "--quiet"],
            check=True,
        )
    size = os.path.getsize(os.path.join(d, "catalog.csv"))
    print(f"catalogue {d}/catalog.csv: {size / 1e6:.0f} MB")
    print(f"{'reader':42s} {'rows':>8s} {'wall s':>7s} {'CPU s':>6s} {'peak MB':>8s} "
          f"{'arrays MB':>9s} {'peak/arrays':>11s}")
    for name, read in READERS.items():
        code = CHILD.format(analysis=os.path.join(ROOT, "analysis"), read=read.format(d=d))
        r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
        if r.returncode != 0:
            print(f"{name:42s} failed: {r.stderr.strip().splitlines()[-1]}")
            continue
        seconds, cpu, peak, arrays, ncols, rows = r.stdout.split("\n")[-2].split()
        peak, arrays = float(peak), float(arrays)
        print(f"{name:42s} {int(rows):8d} {float(seconds):7.2f} {float(cpu):6.2f} "
              f"{peak / 1e6:8.0f} {arrays / 1e6:9.0f} {peak / arrays:11.2f}")


if __name__ == "__main__":
    main()
