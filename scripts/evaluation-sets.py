#!/usr/bin/env python3
"""The `--set` options that put a scene at the parameter values of one optimiser evaluation.

`weft optimize` and `weft bench applications` store the parameter values of every evaluation,
one row per evaluation: `loss.csv` in an optimize run's folder (`evaluation,steps,wall_s,loss,
<paths>`), `runs/parameters/<task>_<method>_<seed>.csv` in a comparison's (`evaluation,<paths>`).
This prints one evaluation's row as `--set PATH=VALUE` options, so it can be run again:

  weft simulate assets/scenes/sock.json --threads 1 \\
      $(scripts/evaluation-sets.py out/sock/runs/parameters/sock_lbfgsb_1.csv 21) --out out/best

Values are printed as stored (17 significant digits), so the run is the evaluation's own.
Standard library only.
"""

import csv
import sys


NOT_PATHS = {"evaluation", "steps", "wall_s", "loss"}


def fail(message):
    print(message, file=sys.stderr)
    sys.exit(2)


def main():
    if len(sys.argv) != 3:
        fail("usage: scripts/evaluation-sets.py PARAMETERS.csv EVALUATION")
    path, wanted = sys.argv[1], sys.argv[2]
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        fail(f"error: {path}: {e.strerror}")
    if not rows or not rows[0] or rows[0][0] != "evaluation":
        fail(f"error: {path}: header: expected 'evaluation,<path>,...'")
    header = rows[0]
    for line, row in enumerate(rows[1:], start=2):
        if row and row[0] == wanted:
            if len(row) != len(header):
                fail(f"error: {path}: line {line}: {len(row)} values, header has {len(header)}")
            print(" ".join(f"--set {k}={v}" for k, v in zip(header, row) if k not in NOT_PATHS))
            return
    fail(f"error: {path}: evaluation {wanted}: no such row")


if __name__ == "__main__":
    main()
