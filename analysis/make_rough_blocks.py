#!/usr/bin/env -S /usr/bin/python3
"""A per-block rate-and-state file (rsf.blocks) for an asperity pattern with rough D_c.

    analysis/make_rough_blocks.py --nx NX [--ny NY] [--period P] [--width W] [--a A] [--b B]
                                  [--dc DC] [--rough R] [--seed S] > FILE.csv

The pattern is rsf.pattern = asperities' (blocks with x mod P < W and y mod P < W take a, b,
the others, the barriers, b and a swapped); every block's D_c is DC times a factor drawn
uniformly from [1 - R, 1 + R] with the given seed. A uniform pattern from a uniform start keeps
blocks in equivalent places in step in the continuous integration (they fail together as one
event); the rough D_c breaks that symmetry, as any heterogeneity in nature does.

Runs with Debian's python3 (/usr/bin/python3, with python3-numpy).
"""

import argparse
import sys

import numpy as np


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--nx", type=int, required=True, help="blocks along strike")
    p.add_argument("--ny", type=int, default=1, help="rows (1: a chain)")
    p.add_argument("--period", type=int, default=10, help="rsf.pattern_period")
    p.add_argument("--width", type=int, default=5, help="rsf.pattern_width")
    p.add_argument("--a", type=float, default=0.01, help="the asperities' a")
    p.add_argument("--b", type=float, default=0.025, help="the asperities' b")
    p.add_argument("--dc", type=float, default=1e-5, help="D_c [m] before the roughness")
    p.add_argument("--rough", type=float, default=0.05, help="relative spread of D_c, [0, 1)")
    p.add_argument("--seed", type=int, default=1, help="random seed")
    args = p.parse_args()
    if not (0 <= args.rough < 1):
        sys.exit(f"make_rough_blocks: --rough {args.rough}: allowed [0, 1)")
    if args.nx < 1 or args.ny < 1 or args.width < 1 or args.period < args.width:
        sys.exit("make_rough_blocks: allowed --nx, --ny >= 1 and 1 <= --width <= --period")
    rng = np.random.default_rng(args.seed)
    out = sys.stdout
    out.write(
        f"# {args.nx} x {args.ny} blocks: asperities (a = {args.a}, b = {args.b}) of width "
        f"{args.width} in every {args.period}, barriers with a and b swapped; D_c = {args.dc} m "
        f"times U[1 - {args.rough}, 1 + {args.rough}] (seed {args.seed});\n"
        "# made by analysis/make_rough_blocks.py " + " ".join(sys.argv[1:]) + "\n"
    )
    out.write("block,a,b,dc\n")
    for j in range(args.nx * args.ny):
        x, y = j % args.nx, j // args.nx
        asperity = x % args.period < args.width and y % args.period < args.width
        a, b = (args.a, args.b) if asperity else (args.b, args.a)
        dc = args.dc * (1 + args.rough * (2 * rng.random() - 1))
        out.write(f"{j},{a},{b},{dc:.6e}\n")


if __name__ == "__main__":
    main()
