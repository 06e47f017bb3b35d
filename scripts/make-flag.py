#!/usr/bin/env python3
"""Writes DiffCloth's "Flag" real-to-sim task (Li et al. 2022, Sec. 6.4, Fig. 11, Appendix B.4) as
a Weft scene, assets/scenes/flag.json, and records its target motion
assets/scenes/targets/flag.npy with `weft simulate`.

From the paper: a flag flapping in the wind, 540 vertices, h = 1/120 s, 100 time steps; its
stretch and bending stiffness, its density and the wind of Eq. 35,
f_ext = 0.5 (sin(w t + phi) + 1) k d^T (k_i a node's inverse distance to the flag centre at the
first time step, d a 3D vector), are fitted (8 DoF: k_stretch, k_bend, rho, phi, w, d) to the
motion of all nodes at every step (loss: the L2 distance, summed over steps). The paper's
motion is a capture (White et al. 2007) that is not public, so here the target is a motion
recorded from this very scene with hidden parameter values (HIDDEN below) by `weft simulate`,
and the task starts away from them (START). Everything else below is chosen here:

- the flag is a 0.78 m x 0.57 m grid of 26 x 19 quads, 27 x 20 = 540 vertices (the paper's
  count; its capture mesh had 1026 triangles, ours has 988), hanging in the vertical XY plane
  (grid rotated 90 degrees about X, so row j = 0 is the top edge) with its centre at
  (0, 1, 0); its left edge (column i = 0, the 20 vertices j * 27) is fixed to the pole (one
  fixed attachment, stiffness 1e4 N/m per vertex, the default);
- Eq. 35 is Weft's wind with `falloff.center` at the flag centre (engine/include/weft/scene/Scene.h,
  struct Wind): node i receives strength * k_i * 0.5 (sin(2 pi frequency t + phase) + 1) *
  direction. Weft's frequency is in Hz (w = 2 pi frequency). d = strength * direction with
  strength fixed at 1e-3 N m as a unit (not a parameter), so the three components of d are the
  task's wind.direction.0..2. An odd number of quads along the flag's height puts no vertex at
  the centre (where k would be unbounded; the loader refuses that);
- gravity -9.8 m/s^2; the Newton forward solver at 1e-6 m/s^2 and a GMRES adjoint at 1e-8 (as
  wind_sysid); the target is recorded at a forward tolerance of 1e-8;
- HIDDEN: stretch 600 N/m, bend 2e-4 N m, density 0.15 kg/m^2 (a light flag fabric), wind
  frequency 1.5 Hz (1.25 gusts in the 0.83 s), phase 0.4 rad, direction (0.6, 0.1, 0.25), i.e.
  d = (6, 1, 2.5) 1e-4 N m: the wind blows the flag out from the pole (+X), lifts it a little
  (+Y) and pushes it out of its plane (+Z);
- START: stretch 1000, bend 5e-4, density 0.2, frequency 1.2, phase 1.0, direction
  (0.45, 0.05, 0.35); BOUNDS: stretch [200, 3000], bend [3e-5, 3e-3], density [0.05, 0.6],
  frequency [0.8, 2.5] Hz, phase [-pi, pi], direction components [-1.5, 1.5] (each box holds
  its hidden value with room; `weft bench applications` starts seeds within a quarter of it);
- the loss is task.loss.trajectory over all vertices and states 1..100 (DiffCloth Eq. 31 with
  squared distances, as Weft's trajectory term is).

As in the paper's 8 parameters, scaling stretch, bend, density and d by one common factor
changes only the pole's attachment springs relative to the rest, so the task's minimum is a
shallow valley along that direction: the motion pins the ratios, not all four values. With the
density held at its hidden value (a subset of 7), the others are identifiable.

Usage: python3 scripts/make-flag.py [--weft BINARY] [SCENE_DIR]
  (SCENE_DIR default: assets/scenes next to scripts/; BINARY default: build/app/weft)
Writes SCENE_DIR/flag.json, then runs
  BINARY simulate SCENE_DIR/flag.json --set <HIDDEN values> --set solver.pd_tolerance=1e-8
         --threads 1 --quiet --out <temporary folder>
and copies its positions.npy to SCENE_DIR/targets/flag.npy (skipped, saying so, when the binary
is missing). Deterministic: the scene is rewritten byte for byte; the target is the binary's
(single-threaded) output. Python 3 standard library only.
"""

import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import functools

import scenefiles

dump = functools.partial(scenefiles.dump, pack_numbers=True)

SCRIPT = "scripts/make-flag.py"
QUADS = (26, 19)      # along the flag's length (X), along its height
SIZE = (0.78, 0.57)   # m
CENTRE = (0.0, 1.0, 0.0)
DT = 1.0 / 120.0
STEPS = 100
WIND_UNIT = 1e-3      # N m: wind.strength, so that d = 1e-3 * direction

HIDDEN = {
    "cloths.0.material.stretch": 600.0,
    "cloths.0.material.bend": 2e-4,
    "cloths.0.material.density": 0.15,
    "wind.phase": 0.4,
    "wind.frequency": 1.5,
    "wind.direction.0": 0.6,
    "wind.direction.1": 0.1,
    "wind.direction.2": 0.25,
}
START = {
    "cloths.0.material.stretch": 1000.0,
    "cloths.0.material.bend": 5e-4,
    "cloths.0.material.density": 0.2,
    "wind.phase": 1.0,
    "wind.frequency": 1.2,
    "wind.direction.0": 0.45,
    "wind.direction.1": 0.05,
    "wind.direction.2": 0.35,
}
BOUNDS = {
    "cloths.0.material.stretch": [200.0, 3000.0],
    "cloths.0.material.bend": [3e-5, 3e-3],
    "cloths.0.material.density": [0.05, 0.6],
    "wind.phase": [-round(math.pi, 6), round(math.pi, 6)],
    "wind.frequency": [0.8, 2.5],
    "wind.direction.0": [-1.5, 1.5],
    "wind.direction.1": [-1.5, 1.5],
    "wind.direction.2": [-1.5, 1.5],
}
PARAMETERS = list(START)


def hidden_overrides():
    return ["%s=%r" % (k, v) for k, v in HIDDEN.items()]


def scene():
    columns = QUADS[0] + 1
    pole = [j * columns for j in range(QUADS[1] + 1)]
    description = (
        "DiffCloth's Flag (Li et al. 2022, Sec. 6.4, Fig. 11, Appendix B.4, Eq. 35): a flag fixed "
        "along its left edge flaps in a wind whose force on node i is 0.5 (sin(2 pi frequency t "
        "+ phase) + 1) k_i d, k_i the node's inverse distance to the flag centre (wind.falloff) "
        "and d = strength * direction; stretch, bend, density, phase, frequency and d (8 DoF) "
        "are fitted to a recorded motion. The paper's capture is not public: targets/flag.npy "
        "was recorded from this scene with hidden values (%s) by: weft simulate "
        "assets/scenes/flag.json %s --set solver.pd_tolerance=1e-8 --threads 1, then copying "
        "positions.npy. The vertex count (540), h = 1/120 s, 100 steps, the wind model, the "
        "parameters and the loss are the paper's; size, placement, pole, hidden and starting "
        "values and bounds were chosen here. Written by %s (see its docstring); do not edit by "
        "hand."
        % (", ".join("%s %g" % kv for kv in HIDDEN.items()),
           " ".join("--set " + o for o in hidden_overrides()), SCRIPT))
    wind = {
        "direction": [START["wind.direction.%d" % i] for i in range(3)],
        "strength": WIND_UNIT,
        "frequency": START["wind.frequency"],
        "phase": START["wind.phase"],
        "falloff": {"center": list(CENTRE)},
    }
    return {
        "name": "flag",
        "description": description,
        "time": {"dt": DT, "steps": STEPS},
        "gravity": [0, -9.8, 0],
        "solver": {
            "method": "newton", "pd_iterations": 500, "pd_tolerance": 1e-6,
            "backward": {"method": "gmres", "tolerance": 1e-8, "max_iterations": 200,
                         "fallback": "direct"},
        },
        "cloths": [{
            "mesh": {"grid": {"size": list(SIZE), "resolution": list(QUADS)},
                     "transform": {"rotate_deg": [90, 0, 0], "translate": list(CENTRE)}},
            "material": {"density": START["cloths.0.material.density"],
                         "stretch": START["cloths.0.material.stretch"],
                         "bend": START["cloths.0.material.bend"]},
            "attachments": [{"vertices": pole, "kind": "fixed"}],
        }],
        "wind": wind,
        "task": {
            "loss": {"trajectory": {"target": "targets/flag.npy"}},
            "parameters": PARAMETERS,
            "bounds": BOUNDS,
        },
    }


def main():
    args = sys.argv[1:]
    here = os.path.dirname(os.path.abspath(__file__))
    weft = os.path.join(here, "..", "build", "app", "weft")
    if len(args) >= 2 and args[0] == "--weft":
        weft, args = args[1], args[2:]
    out = args[0] if args else os.path.join(here, "..", "assets", "scenes")
    os.makedirs(os.path.join(out, "targets"), exist_ok=True)
    path = os.path.join(out, "flag.json")
    with open(path, "w") as f:
        f.write(dump(scene()) + "\n")
    print("wrote %s (%d parameters)" % (path, len(PARAMETERS)))
    if not os.access(weft, os.X_OK):
        print("%s not found: targets/flag.npy not recorded (pass --weft BINARY)" % weft)
        return
    with tempfile.TemporaryDirectory() as tmp:
        run = os.path.join(tmp, "run")
        command = [weft, "simulate", path, "--out", run, "--threads", "1", "--quiet",
                   "--set", "solver.pd_tolerance=1e-8"]
        for o in hidden_overrides():
            command += ["--set", o]
        subprocess.run(command, check=True)
        shutil.copyfile(os.path.join(run, "positions.npy"),
                        os.path.join(out, "targets", "flag.npy"))
    print("recorded targets/flag.npy with %s" % weft)


if __name__ == "__main__":
    main()
