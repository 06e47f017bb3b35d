#!/usr/bin/env python3
"""Writes DiffCloth's "Flying Napkin" task (Li et al. 2022, Sec. 5.2, Fig. 4) as Weft scenes.

The paper: "we simulate a piece of cloth with time-invariant external forces applied to each
node. The goal is to design the force at each node to pull the center of the cloth to a target
position in the end", with 4x4, 5x5, 7x7 and 10x10 nodes, so 48, 75, 147 and 300 variables.
That much is the paper's; everything else below was chosen here, since the paper gives no
sizes, material, time step, target or gravity for this task:

- a 0.5 m square cloth of k x k nodes ((k-1) x (k-1) quads), horizontal at a height of 1 m,
  density 0.2 kg/m^2, stretch 400 N/m, bend 0.001 N m (the wind_sysid material), gravity on
  (the napkin has to be flown against it: every other scene of the paper has gravity);
- 50 steps of 0.01 s (h = 1/100 s, 0.5 s of flight), Newton-PCG forward solver at 1e-6 m/s^2,
  GMRES adjoint at 1e-8 (as wind_sysid);
- one `forces` entry per node, starting at zero, each component bounded to +-4 m g, with m the
  lumped mass of an interior node (0.2 kg/m^2 * (0.5 / (k-1))^2 m^2): a uniform field of about
  1.2 m g per node lifts the napkin onto the target, so the box holds solutions with room;
- a final-frame loss (task.loss.final) on the centre node for odd k, on the four central nodes
  for even k (a k x k grid with k even has no centre node), each pulled to its rest position
  moved by (0.25, 0.25, 0) m: L = sum_i |x_N,i - (X_i + d)|^2 in m^2. With zero forces the
  napkin falls 1.2 m in 0.5 s, so the loss starts at about 2.2 m^2 per loss node.

Usage: python3 scripts/make-napkins.py [SCENE_DIR]   (default: assets/scenes next to scripts/)
Writes SCENE_DIR/napkin_KxK.json and SCENE_DIR/targets/napkin_KxK.npy for K in 4, 5, 7, 10.
Deterministic (fixed formatting): re-running reproduces the committed files byte for byte.
Python 3 standard library only.
"""

import json
import os
import sys

from scenefiles import dump, write_npy

SCRIPT = "scripts/make-napkins.py"
SIZES = (4, 5, 7, 10)
EXTENT = 0.5  # m
HEIGHT = 1.0  # m
DENSITY = 0.2  # kg/m^2
GRAVITY = 9.8  # m/s^2
OFFSET = (0.25, 0.25, 0.0)  # m, where the centre has to go
STEPS = 50
DT = 0.01
FORCE_BOUND_WEIGHTS = 4.0  # the force box, in interior-node weights


def centre_nodes(k):
    """Global indices of the centre node (odd k) or the four central nodes (even k)."""
    if k % 2 == 1:
        c = k // 2
        return [c * k + c]
    a, b = k // 2 - 1, k // 2
    return [j * k + i for j in (a, b) for i in (a, b)]


def rest_positions(k):
    """Vertex (i, j) at index j k + i, as engine/weft/mesh/GridMesh.cpp lays out a grid."""
    q = k - 1
    return [(-0.5 * EXTENT + EXTENT * i / q, HEIGHT, -0.5 * EXTENT + EXTENT * j / q)
            for j in range(k) for i in range(k)]


def scene(k):
    name = "napkin_%dx%d" % (k, k)
    node_mass = DENSITY * (EXTENT / (k - 1)) ** 2
    bound = round(FORCE_BOUND_WEIGHTS * node_mass * GRAVITY, 6)
    nodes = k * k
    parameters = ["cloths.0.forces.%d.force.%d" % (j, c) for j in range(nodes) for c in range(3)]
    centre = centre_nodes(k)
    description = (
        "DiffCloth's Flying Napkin (Li et al. 2022, Sec. 5.2, Fig. 4), %dx%d nodes: constant "
        "forces on every node (%d parameters, one forces entry per node) are to bring the "
        "napkin's centre (%s) to its rest position moved by (%g, %g, %g) m at the last of %d "
        "steps. The node count and the task are the paper's; size, material, time step, gravity, "
        "target and the force box (+-%g N per component, 4 interior-node weights) were chosen "
        "here. Written by %s (see its docstring); do not edit by hand."
        % (k, k, 3 * nodes, "node %d" % centre[0] if len(centre) == 1 else
           "the four central nodes " + ", ".join(map(str, centre)),
           OFFSET[0], OFFSET[1], OFFSET[2], STEPS, bound, SCRIPT))
    return name, {
        "name": name,
        "description": description,
        "time": {"dt": DT, "steps": STEPS},
        "gravity": [0, -GRAVITY, 0],
        "solver": {
            "method": "newton", "pd_iterations": 500, "pd_tolerance": 1e-6,
            "backward": {"method": "gmres", "tolerance": 1e-8, "max_iterations": 200,
                         "fallback": "direct"},
        },
        "cloths": [{
            "mesh": {"grid": {"size": [EXTENT, EXTENT], "resolution": [k - 1, k - 1]},
                     "transform": {"translate": [0, HEIGHT, 0]}},
            "material": {"density": DENSITY, "stretch": 400.0, "bend": 0.001},
            "forces": [{"vertices": [j], "force": [0.0, 0.0, 0.0]} for j in range(nodes)],
        }],
        "task": {
            "loss": {"final": {"target": "targets/%s.npy" % name, "vertices": centre}},
            "parameters": parameters,
            "bounds": {p: [-bound, bound] for p in parameters},
        },
    }


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "assets", "scenes")
    os.makedirs(os.path.join(out, "targets"), exist_ok=True)
    for k in SIZES:
        name, doc = scene(k)
        target = [(x + OFFSET[0], y + OFFSET[1], z + OFFSET[2]) for x, y, z in rest_positions(k)]
        write_npy(os.path.join(out, "targets", name + ".npy"), target)
        with open(os.path.join(out, name + ".json"), "w") as f:
            f.write(dump(doc) + "\n")
        print("wrote %s (%d parameters)" % (name, 3 * k * k))


if __name__ == "__main__":
    main()
