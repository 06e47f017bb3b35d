#!/usr/bin/env python3
"""Writes DiffCloth's "Dress" inverse-design task (Li et al. 2022, Sec. 6.3, Fig. 1, Appendix B.3)
as a Weft scene: assets/meshes/dress.obj (the skirt) and assets/scenes/dress.json.

From the paper: a twirl dress spins; its density d and bending stiffness k_bend (2 DoF) are to
be chosen so that the cone it forms at the last of 125 steps of h = 1/120 s has a 100 degree apex
angle; the loss is Eq. 34, L = sum_{p in P} (h_p - h)^2 over the points P on the bottom of the
dress, h_p their height (y) and h the height the hem reaches at the target apex angle. The paper's
dress has no obstacle (DiffCloth's code: primitiveConfig NONE) and is held at the waist by points
that turn about the vertical axis through the dress's middle. Everything else below is chosen
here, since the paper gives no dress mesh (its 3634-vertex garment is not public), size,
material or spin rate:

- the dress is a skirt (the paper's dress has a bodice too, which the task does not need: only
  the skirt flares) of RINGS rings from waist to hem, slant length SKIRT_LENGTH, waist radius
  WAIST_RADIUS (a 75 cm waist). It is cut as a circle-like skirt whose material would form a
  cone of half-angle FLARE_HALF_ANGLE_DEG when fully opened, and hangs at rest in PLEATS pleats
  around a cone of half-angle REST_HALF_ANGLE_DEG: each ring has 2 PLEATS vertices alternating
  between an outer and an inner radius, the pleat depth growing from zero at the waist so that
  each ring's zig-zag is as long as that ring's polygon on the flared cone (pleat_depth). Opening
  the pleats is what lets the spinning skirt flare without stretching its hem: a plain cone
  would have to stretch around the hem to widen, so its flare is set by the stretch stiffness
  instead of the two design parameters (tried: its hem only bounced on its hoop stiffness). The
  quads are split along alternating diagonals (checkerboard), so the mesh has no handedness
  that the spin could favour. 16 pleats x 9 rings = 288 vertices (the paper's dress has 3634);
- the waist ring (vertices 0..2 PLEATS - 1) is one handle attachment (stiffness 1e4 N/m per
  vertex, the default) turning about +Y through the waist centre at SPIN_DEG_PER_S from the
  first step. DiffCloth's public code turns its waist points 0.02 rad per step of 1/120 s
  (137.5 deg/s) on a dress of other units; at 360 deg/s a pendulum hung from our waist settles
  at a half-angle of about 58 degrees, so the 50 degrees of the target lie within reach and the
  bending stiffness decides how far the pleats open;
- the skirt starts at rest in its rest shape with the waist at WAIST_HEIGHT, gravity
  -9.8 m/s^2, no wind, no obstacle and no self-collision (the pleats open outwards and do not
  touch; self-contact would only add cost), stretch STRETCH N/m (fixed: not a task parameter);
- the hemline loss (task.loss.hemline) on the hem ring: the cone's apex is taken at the waist
  (apex_height = WAIST_HEIGHT) with the skirt's slant length (SKIRT_LENGTH), so the target
  height is WAIST_HEIGHT - SKIRT_LENGTH cos(50 deg) = 0.6915 m. Eq. 34 looks at the last frame
  only; here the term covers the last quarter second (HEM_STATES, states 95..125), because the
  suddenly spun skirt still breathes in and out at 125 steps (a period of about 0.4 s): at the
  last state alone the loss and its gradient follow the phase of that oscillation, and from
  the starting dress L-BFGS-B's first step went the wrong way (tried). Weft's hemline term is
  also the mean of Eq. 34's squares over the hem, not their sum (engine/weft/diff/HemlineLoss.h);
- the task starts from a light, stiff dress (density START_DENSITY, bend START_BEND) whose
  pleats barely open (apex about 70 degrees at the end), and bounds both parameters
  (DENSITY_BOUNDS, BEND_BOUNDS). `weft landscape` over the two shows a valley along a constant
  bend-to-density ratio (about 2.2e-3 m^3/s^2: e.g. density 0.3 kg/m^2 with bend 6.5e-4 N m),
  since gravity and the spin's inertia both scale with density: as in the paper, the two
  parameters are not independently determined by one apex angle. On the soft side (bend below
  about 3e-4 N m at density 0.3) pleats snap open at once and the loss jumps.

Usage: python3 scripts/make-dress.py [ASSETS_DIR]   (default: assets/ next to scripts/)
Writes ASSETS_DIR/meshes/dress.obj and ASSETS_DIR/scenes/dress.json. Deterministic (fixed vertex
order and number formatting): re-running reproduces the committed files byte for byte. Python 3
standard library only.
"""

import json
import math
import os
import sys
import functools

import scenefiles

dump = functools.partial(scenefiles.dump, pack_numbers=True)

SCRIPT = "scripts/make-dress.py"
PLEATS = 16            # pleats around the skirt: 2 PLEATS vertices a ring
RINGS = 9              # rings from waist (0) to hem (RINGS - 1)
WAIST_RADIUS = 0.12    # m
SKIRT_LENGTH = 0.48    # m, slant length waist -> hem
REST_HALF_ANGLE_DEG = 30.0   # the hanging (pleated) skirt's mean cone
FLARE_HALF_ANGLE_DEG = 65.0  # the cone the skirt's material makes with its pleats opened
WAIST_HEIGHT = 1.0     # m
SPIN_DEG_PER_S = 360.0
STRETCH = 1000.0       # N/m
START_DENSITY = 0.15   # kg/m^2
START_BEND = 1.5e-3    # N m
DENSITY_BOUNDS = [0.05, 1.0]
BEND_BOUNDS = [1e-4, 5e-3]
TARGET_APEX_DEG = 100.0
HEM_STATES = list(range(95, 126))  # the last quarter second (see the docstring)
DT = 1.0 / 120.0
STEPS = 125


def pleat_depth(mean_radius, flared_radius):
    """Half-depth a of a ring of 2 PLEATS vertices alternating between radii r + a and r - a
    (r = mean_radius) whose 2 PLEATS edges are as long as those of the same ring laid out
    without pleats on the flared cone, at radius `flared_radius` (so a = 0 where the two radii
    agree, as at the waist)."""
    c = math.cos(math.pi / PLEATS)
    excess = 2.0 * (1.0 - c) * (flared_radius ** 2 - mean_radius ** 2)  # e^2 - 2 r^2 (1 - c)
    return math.sqrt(max(0.0, excess) / (2.0 * (1.0 + c)))


def skirt():
    """Vertices (waist at the origin, hanging along -Y) and outward-facing triangles."""
    rest, flare = math.radians(REST_HALF_ANGLE_DEG), math.radians(FLARE_HALF_ANGLE_DEG)
    segments = 2 * PLEATS
    vertices = []
    for k in range(RINGS):
        s = SKIRT_LENGTH * k / (RINGS - 1)
        r, y = WAIST_RADIUS + s * math.sin(rest), -s * math.cos(rest)
        a = pleat_depth(r, WAIST_RADIUS + s * math.sin(flare))
        for j in range(segments):
            t = 2.0 * math.pi * j / segments
            rj = r + a if j % 2 == 0 else r - a
            vertices.append((rj * math.cos(t), y, rj * math.sin(t)))
    triangles = []
    for k in range(RINGS - 1):
        for j in range(segments):
            a00, a01 = k * segments + j, k * segments + (j + 1) % segments
            a10, a11 = a00 + segments, a01 + segments
            # (a00, a01, a10) faces outwards: around the ring is +theta, down the skirt outwards.
            if (j + k) % 2 == 0:
                triangles += [(a00, a01, a11), (a00, a11, a10)]
            else:
                triangles += [(a00, a01, a10), (a01, a11, a10)]
    return vertices, triangles


def fmt(x):
    s = "%.9f" % x
    return "0.000000000" if s == "-0.000000000" else s


def write_obj(path, vertices, triangles):
    with open(path, "w") as f:
        f.write("# Weft dress skirt, written by %s (see its docstring); do not edit by hand.\n" % SCRIPT)
        f.write("# Pleated skirt, metres, waist ring at y = 0 (vertices 1..%d), hem ring last "
                "(vertices %d..%d);\n" % (2 * PLEATS, (RINGS - 1) * 2 * PLEATS + 1, RINGS * 2 * PLEATS))
        f.write("# %d rings x %d pleats, waist radius %g m, slant length %g m, hanging half-angle "
                "%g deg, material half-angle %g deg.\n" % (RINGS, PLEATS, WAIST_RADIUS, SKIRT_LENGTH,
                                                          REST_HALF_ANGLE_DEG, FLARE_HALF_ANGLE_DEG))
        for v in vertices:
            f.write("v %s %s %s\n" % tuple(fmt(c) for c in v))
        for t in triangles:
            f.write("f %d %d %d\n" % tuple(i + 1 for i in t))


def scene():
    hem = list(range((RINGS - 1) * 2 * PLEATS, RINGS * 2 * PLEATS))
    target = WAIST_HEIGHT - SKIRT_LENGTH * math.cos(math.radians(TARGET_APEX_DEG / 2.0))
    description = (
        "DiffCloth's Dress (Li et al. 2022, Sec. 6.3, Fig. 1, Appendix B.3, Eq. 34): a skirt "
        "whose waist turns at %g deg/s; density and bending stiffness (2 DoF) are to make the "
        "hem reach the height (%.4f m) of a %g degree cone at the end of %d steps of 1/120 s. "
        "The task, the parameters, h and the step count are the paper's; the skirt mesh "
        "(../meshes/dress.obj: %d rings of %d pleats hanging around a %g degree half-angle cone, "
        "waist radius %g m, slant %g m), spin rate, stretch (%g N/m), the loss over the last "
        "quarter second (states %d..%d, where the paper takes the last state), starting values "
        "and bounds were chosen here. Written by %s (see its docstring); do not edit by hand."
        % (SPIN_DEG_PER_S, target, TARGET_APEX_DEG, STEPS, RINGS, PLEATS, REST_HALF_ANGLE_DEG,
           WAIST_RADIUS, SKIRT_LENGTH, STRETCH, HEM_STATES[0], HEM_STATES[-1], SCRIPT))
    return {
        "name": "dress",
        "description": description,
        "time": {"dt": DT, "steps": STEPS},
        "gravity": [0, -9.8, 0],
        "solver": {
            "method": "newton", "pd_iterations": 500, "pd_tolerance": 1e-6,
            "backward": {"method": "gmres", "tolerance": 1e-8, "max_iterations": 200,
                         "fallback": "direct"},
        },
        "cloths": [{
            "mesh": {"file": "../meshes/dress.obj",
                     "transform": {"translate": [0, WAIST_HEIGHT, 0]}},
            "material": {"density": START_DENSITY, "stretch": STRETCH, "bend": START_BEND},
            "attachments": [{
                "vertices": list(range(2 * PLEATS)), "kind": "handle",
                "trajectory": {"rotate": {"center": [0, WAIST_HEIGHT, 0], "axis": [0, 1, 0],
                                          "degrees_per_second": SPIN_DEG_PER_S}},
            }],
        }],
        "task": {
            "loss": {"hemline": {"vertices": hem, "steps": HEM_STATES, "apex_angle_deg": TARGET_APEX_DEG,
                                 "apex_height": WAIST_HEIGHT, "slant_length": SKIRT_LENGTH}},
            "parameters": ["cloths.0.material.density", "cloths.0.material.bend"],
            "bounds": {"cloths.0.material.density": DENSITY_BOUNDS,
                       "cloths.0.material.bend": BEND_BOUNDS},
        },
    }


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "assets")
    os.makedirs(os.path.join(out, "meshes"), exist_ok=True)
    os.makedirs(os.path.join(out, "scenes"), exist_ok=True)
    vertices, triangles = skirt()
    write_obj(os.path.join(out, "meshes", "dress.obj"), vertices, triangles)
    with open(os.path.join(out, "scenes", "dress.json"), "w") as f:
        f.write(dump(scene()) + "\n")
    print("wrote dress.obj (%d vertices, %d triangles) and dress.json"
          % (len(vertices), len(triangles)))


if __name__ == "__main__":
    main()
