#!/usr/bin/env python3
"""How well one gradient predicts the loss and the gradient at a nearby point.

Usage:
  weft optimize SCENE --max-evaluations 1 [--set ...A] --out A
  weft optimize SCENE --max-evaluations 1 [--set ...B] --out B
  scripts/compare-gradients.py A/result.json B/result.json

Each result.json holds the loss, the parameters and the gradient of its one evaluation (the
`initial_parameters`, `initial_loss` and `gradient` of `weft optimize`). Prints the distance
|x_B - x_A| in parameter values, the loss change against the first-order prediction
g_A . (x_B - x_A), and how much the gradient changed: |g_B - g_A| / |g_A| and the cosine between
them. A loss change the prediction matches while the gradient changes by much more than
|x_B - x_A| times a plausible curvature is a gradient that jumps: L-BFGS reads its jumps as
curvature and shortens its steps. Standard library only.
"""

import json
import math
import sys


def fail(message):
    print(message, file=sys.stderr)
    sys.exit(2)


def load(path):
    try:
        with open(path) as f:
            r = json.load(f)
    except OSError as e:
        fail(f"error: {path}: {e.strerror}")
    except json.JSONDecodeError as e:
        fail(f"error: {path}: <json>: {e}")
    for key in ("initial_parameters", "initial_loss", "gradient"):
        if not isinstance(r.get(key), (dict, float, int)) or r.get(key) is None:
            fail(f"error: {path}: {key}: missing (a gradient-based evaluation's result.json?)")
    return r


def main():
    if len(sys.argv) != 3:
        fail("usage: scripts/compare-gradients.py A/result.json B/result.json")
    a, b = load(sys.argv[1]), load(sys.argv[2])
    keys = sorted(a["gradient"])
    if sorted(b["gradient"]) != keys or sorted(a["initial_parameters"]) != keys:
        fail(f"error: {sys.argv[2]}: gradient: not the same parameters as {sys.argv[1]}")
    xa = [a["initial_parameters"][k] for k in keys]
    xb = [b["initial_parameters"][k] for k in keys]
    ga = [a["gradient"][k] for k in keys]
    gb = [b["gradient"][k] for k in keys]
    dx = [q - p for p, q in zip(xa, xb)]
    norm = lambda v: math.sqrt(sum(c * c for c in v))
    dot = lambda u, v: sum(p * q for p, q in zip(u, v))
    dg = [q - p for p, q in zip(ga, gb)]
    print(f"distance |x_B - x_A|          {norm(dx):.4e}")
    print(f"loss A, B                     {a['initial_loss']:.10e}  {b['initial_loss']:.10e}")
    print(f"loss change                   {b['initial_loss'] - a['initial_loss']:.4e}")
    print(f"predicted g_A . (x_B - x_A)   {dot(ga, dx):.4e}")
    print(f"|g_A|, |g_B|                  {norm(ga):.4e}  {norm(gb):.4e}")
    print(f"|g_B - g_A| / |g_A|           {norm(dg) / norm(ga):.4e}")
    print(f"cosine(g_A, g_B)              {dot(ga, gb) / (norm(ga) * norm(gb)):.6f}")
    if norm(dx) > 0:
        print(f"|g_B - g_A| / |x_B - x_A|     {norm(dg) / norm(dx):.4e}  (what L-BFGS reads as curvature)")


if __name__ == "__main__":
    main()
