#!/usr/bin/env python3
"""Which bending hinge holds a stalled contact step's residual.

Usage:
  WEFT_CONTACT_TRACE=a-b weft simulate SCENE --threads 1 --out OUT 2> TRACE
  scripts/trace-stall-hinges.py TRACE OUT

For every traced step of the Newton contact solve, the trace ends with the nodes holding the
largest shares of the step's residual ("residual at node i: share s, ..."). This script reads them
with OUT/stats.csv (each step's residual and whether it converged), OUT/positions.npy and
OUT/rest.obj, and reports for each unconverged step:
  - the share of the residual on its four largest nodes;
  - the bending hinge (two triangles sharing an edge) holding at least three of those four nodes,
    if there is one, and its curvature ratio |e| / |e_rest| ("flat" for a hinge flat at rest, whose
    projection is zero and energy quadratic), where e = sum_k cot_k x_k is the
    hinge's cotangent-weighted curvature vector (BendingConstraint.cpp builds the same weights).
The projection e -> |e_rest| e / |e| has the Hessian eigenvalue 1 - |e_rest| / |e| across e, so a
ratio well below 1 is a curved hinge pressed flat, where the bending energy is strongly concave.

Standard library only (the .npy reader handles Weft's little-endian float64 arrays).
"""

import csv
import math
import re
import sys

from npyfile import bad_input, open_npy, read_values


def read_positions(path, frame):
    (frames, nodes, _), f = open_npy(path)
    with f:
        if not 0 <= frame < frames:
            bad_input(f"error: {path}: no frame {frame} (it has {frames})")
        f.seek(frame * nodes * 3 * 8, 1)
        values = read_values(f, nodes * 3)
    return [values[3 * i : 3 * i + 3] for i in range(nodes)]


def read_obj(path):
    vertices, faces = [], []
    for line in open(path):
        t = line.split()
        if t and t[0] == "v":
            vertices.append(tuple(float(a) for a in t[1:4]))
        elif t and t[0] == "f":
            faces.append([int(a.split("/")[0]) - 1 for a in t[1:4]])
    return vertices, faces


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    return math.sqrt(dot(a, a))


def cotangent(apex, p, q):
    u, v = sub(p, apex), sub(q, apex)
    return dot(u, v) / norm(cross(u, v))


def hinges(vertices, faces):
    """(nodes, cotangent weights, |e_rest|) per interior edge, as BendingConstraint builds them."""
    edges = {}
    for index, face in enumerate(faces):
        for k in range(3):
            edges.setdefault(tuple(sorted((face[k], face[(k + 1) % 3]))), []).append(index)
    out = []
    for (a, b), adjacent in edges.items():
        if len(adjacent) != 2:
            continue
        c, d = ([v for v in faces[f] if v not in (a, b)][0] for f in adjacent)
        x0, x1, x2, x3 = (vertices[i] for i in (a, b, c, d))
        c00, c01 = cotangent(x0, x1, x2), cotangent(x1, x0, x2)
        c10, c11 = cotangent(x0, x1, x3), cotangent(x1, x0, x3)
        weights = (c01 + c11, c00 + c10, -(c00 + c01), -(c10 + c11))
        nodes = (a, b, c, d)
        rest = norm(curvature(nodes, weights, vertices))
        # As BendingConstraint: below 1e-8 edge lengths the hinge is flat (projection 0).
        out.append((nodes, weights, rest if rest > 1e-8 * norm(sub(x1, x0)) else 0.0))
    return out


def curvature(nodes, weights, x):
    return tuple(sum(w * x[n][i] for n, w in zip(nodes, weights)) for i in range(3))


def main():
    if len(sys.argv) != 3:
        bad_input(__doc__)
    trace, out = sys.argv[1], sys.argv[2]
    vertices, faces = read_obj(out + "/rest.obj")
    all_hinges = hinges(vertices, faces)
    by_node = {}
    for h in all_hinges:
        for n in h[0]:
            by_node.setdefault(n, []).append(h)
    stats = {int(r["step"]): r for r in csv.DictReader(open(out + "/stats.csv"))}

    steps, current = {}, None
    for line in open(trace):
        m = re.match(r"step (\d+): newton contact solve", line)
        if m:
            current = int(m.group(1))
            steps[current] = []
            continue
        m = re.match(r"\s+residual at node (\d+): share ([\d.eE+-]+)", line)
        if m and current is not None:
            steps[current].append((int(m.group(1)), float(m.group(2))))

    unconverged = on_hinge = on_flat = 0
    ratios = []
    print("step,residual,top4_share,hinge,ratio")
    for step, nodes in sorted(steps.items()):
        row = stats.get(step)
        if not nodes or row is None or row["converged"] == "1":
            continue
        unconverged += 1
        top = [n for n, _ in nodes[:4]]
        share = sum(s for _, s in nodes[:4])
        x = read_positions(out + "/positions.npy", step)
        best = None
        for h in {h for n in top for h in by_node.get(n, [])}:
            shared = len(set(top) & set(h[0]))
            if shared >= 3 and (best is None or shared > best[0]):
                best = (shared, h)
        if best is None:
            print(f"{step},{row['residual']},{share:.3f},,")
            continue
        nodes_, weights, rest = best[1]
        name = "-".join(map(str, nodes_))
        if rest == 0.0:
            on_flat += 1
            print(f"{step},{row['residual']},{share:.3f},{name},flat")
            continue
        ratio = norm(curvature(nodes_, weights, x)) / rest
        on_hinge += 1
        ratios.append(ratio)
        print(f"{step},{row['residual']},{share:.3f},{name},{ratio:.3f}")
    ratios.sort()
    median = ratios[len(ratios) // 2] if ratios else float("nan")
    print(
        f"# {unconverged} traced unconverged steps; on one hinge curved at rest: {on_hinge} "
        f"(|e|/|e_rest|: median {median:.3f}, below 0.3: {sum(r < 0.3 for r in ratios)}, "
        f"below 0.5: {sum(r < 0.5 for r in ratios)}, above 1: {sum(r > 1 for r in ratios)}); "
        f"on one hinge flat at rest: {on_flat}",
        file=sys.stderr,
    )


if __name__ == "__main__":
    main()
