#!/usr/bin/env python3
"""Where two runs of the same scene part: step by step, how far apart their cloths are and
whether each step converged.

Usage:
  weft simulate SCENE --set PATH=A --out OUT_A
  weft simulate SCENE --set PATH=B --out OUT_B
  scripts/compare-runs.py OUT_A OUT_B [--every N]

For every step (or every N-th, and always the steps where either run did not converge) prints:
the largest distance between the two runs' positions of a node (m), each run's residual and
whether it converged, and (contact scenes) how many nodes are in a contact branch in one run that
they are not in the other. A difference that grows only at the steps one of the runs leaves
unconverged, and decays in between, comes from the solve stopping wherever it stalled; one that
grows steadily through converged steps is the dynamics' own sensitivity.

Standard library only (the .npy reader handles Weft's little-endian float64 arrays).
"""

import argparse
import csv
import math
import os

from npyfile import bad_input, open_npy, read_values


def read_npy(path):
    """(shape, flat tuple of values) of a little-endian float64 C-order .npy file."""
    shape, f = open_npy(path)
    with f:
        count = 1
        for s in shape:
            count *= s
        values = read_values(f, count)
    return shape, values


def read_stats(path):
    rows = list(csv.DictReader(open(path)))
    return {int(r["step"]): (float(r["residual"]), r["converged"] == "1") for r in rows}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("a")
    parser.add_argument("b")
    parser.add_argument("--every", type=int, default=10, help="print every N-th step (default 10)")
    args = parser.parse_args()
    runs = []
    for out in (args.a, args.b):
        for name in ("positions.npy", "stats.csv"):
            if not os.path.exists(os.path.join(out, name)):
                bad_input(f"error: {out}: no {name} (a `weft simulate --out` folder is expected)")
        shape, positions = read_npy(os.path.join(out, "positions.npy"))
        branches = None
        if os.path.exists(os.path.join(out, "contact_branches.npy")):
            branches = read_npy(os.path.join(out, "contact_branches.npy"))[1]
        runs.append((shape, positions, branches, read_stats(os.path.join(out, "stats.csv"))))
    (shape_a, pos_a, br_a, stats_a), (shape_b, pos_b, br_b, stats_b) = runs
    if shape_a != shape_b:
        bad_input(f"error: {args.b}: positions of shape {shape_b}, {args.a} has {shape_a}")
    states, nodes, _ = shape_a
    print("step  max distance (m)  residual A  conv A  residual B  conv B  branch differences")
    unconverged = [0, 0]
    for step in range(1, states):
        base = step * nodes * 3
        distance = 0.0
        for i in range(nodes):
            k = base + 3 * i
            distance = max(distance, math.dist(pos_a[k : k + 3], pos_b[k : k + 3]))
        res_a, conv_a = stats_a[step]
        res_b, conv_b = stats_b[step]
        unconverged[0] += not conv_a
        unconverged[1] += not conv_b
        differ = ""
        if br_a is not None and br_b is not None:
            differ = sum(br_a[step * nodes + i] != br_b[step * nodes + i] for i in range(nodes))
        if step % args.every == 0 or not (conv_a and conv_b):
            print(f"{step:4d}  {distance:16.3e}  {res_a:10.2e}  {int(conv_a):6d}  {res_b:10.2e}"
                  f"  {int(conv_b):6d}  {differ}")
    print(f"unconverged steps: {unconverged[0]} (A), {unconverged[1]} (B)")


if __name__ == "__main__":
    main()
