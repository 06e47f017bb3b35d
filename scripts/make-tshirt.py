#!/usr/bin/env python3
"""Writes DiffCloth's "T-shirt" system identification task (Li et al. 2022, Sec. 6.1, Fig. 7,
Appendix B.1; Weft issue 7) as a garment mesh and a Weft task scene.

From the paper: a T-shirt hangs in a synthetic sinusoidal wind, each node receiving
0.5 (sin(w t + phi) + 1) d; its stretch stiffness and the wind (phi, w and the 3D vector d: 6
DoF in all, Appendix B.1, Table 2) are identified from a recorded motion of the shirt; the loss
is the distance between the simulated and the recorded node positions summed over the steps
(Eq. 31); h = 1/90 s, 250 steps; 4278 DoFs (1426 vertices); self-collision between the front
and back layers under the wind is what sets the task apart from the Wind example (Sec. 6.1).
The paper's shirt (tshirt1000-tri.obj of the DiffCloth release) is not used: Weft's assets are
its own. Everything below is chosen here, since the paper gives no garment geometry, hold,
material or parameter values.

The garment (assets/meshes/tshirt.obj, and tshirt-coarse.obj for the tests), made here:
- Two identical flat panels, front and back, each a T-shirt outline in the XY plane (metres, +Y
  up, the hem at y = 0, centred on x = 0): a body WIDTH wide; side seams from the hem to the
  armpits at ARMPIT; a vertical armhole up to the shoulder points (x = +-WIDTH/2, y = SHOULDER);
  shoulder seams rising from there to the neck points (x = +-NECK_WIDTH/2, y = NECK); between
  them the neckline, a half-cosine NECK_DEPTH deep; and short sleeves: quadrilaterals from the
  armhole to a cuff CUFF_WIDTH wide, SLEEVE_LENGTH along an axis SLEEVE_DROP_DEG below the
  horizontal, the cuff square to the axis.
- Each panel is meshed by structured patches so that the two panels' nodes face each other
  exactly (Weft's self-collision is node-node, so facing nodes are what keeps the layers apart):
  the body in columns (three runs: side to neck point, across the neck, neck point to side; the
  shoulder runs with an even count, so that a column lies at each shoulder seam's middle) and
  rows (hem to armpit uniformly, then armpit to the shoulder line or neckline, each column
  stretched to its own top), each sleeve as a bilinear grid on its armhole's rows; every quad
  split along alternating diagonals (checkerboard), so the mesh has no handedness. EDGE sets
  the spacing of every run (each run gets round(length / EDGE) intervals).
- Sewing: the back panel reuses the front panel's vertices along the seams (welded: one vertex,
  not two coincident ones): shoulder seams (neck point to shoulder point) continued along the
  sleeves' top edges to the cuffs, underarm seams (cuff to armpit) and side seams (armpit to
  hem). The result is one manifold with boundary and four openings: neck, hem and two cuffs
  (the script checks the orientation, that every edge lies in two triangles except the
  openings', and the Euler characteristic 2 - 4 = -2 of a sphere with four holes).
- In 3D the seams lie in the plane z = 0 and every other vertex of the front panel at
  z = +GAP/2, of the back panel at z = -GAP/2 (outward normals +Z and -Z): the shirt lies flat
  with its layers GAP apart, more than the self-collision reach (1.5 times its radius), so no
  pair touches at rest.
- Vertex order: the hanger's 18 vertices first (below), then the rest of the front panel (body
  row by row from the hem, then the right sleeve (+X), then the left), then the back panel's
  own vertices in the same order. Both meshes thus hold the hanger at vertices 0..17, and the
  tests swap in the coarse mesh with `--set cloths.0.mesh.file=../meshes/tshirt-coarse.obj`
  alone.
- tshirt.obj: EDGE = 0.023 m, 1448 vertices (the paper's 1426); tshirt-coarse.obj: EDGE_COARSE
  = 0.07 m, 176 vertices, the same shirt for the tests' reduced size.

The scene (assets/scenes/tshirt.json):
- The shirt hangs on a hanger: one fixed attachment (1e4 N/m per vertex, the default) holding
  on each shoulder seam the neck point, the middle and the shoulder point (vertices 0..5, in
  z = 0), and the front and back vertices one row below each (6..11 at +GAP/2, 12..17 at
  -GAP/2): a hanger as thick as the gap, inside the shirt. Held by the seam alone, each layer
  hangs towards the plane of its seams under its own weight: without any wind the layers come
  within contact reach in 7 steps and stick from step 10 (tried, task mesh), and the torso then
  rests in stick-slip contact on itself, where small parameter changes flip contacts and the
  loss jumps. The hem hangs at HEM_HEIGHT; no obstacle, no floor.
- Material: density 0.15 kg/m^2 (cotton jersey), stretch the parameter (HIDDEN 300 N/m, as
  sphere_sysid: the forward contact solve converges slowly on stiff cloth, README "Contact"),
  bend 1e-3 N m: stiffer than jersey, because with 1e-4 the hanging shirt's compressed regions
  (below the hanger, at the neckline, the sleeves) buckle and the step equations have several
  solutions: runs 1e-4 relative apart in one parameter landed on different ones (a node 3 mm
  apart, in no contact; coarse mesh, tried with a 3 cm gap), which makes the loss jump. With
  1e-3 the second differences of the motion under such probes (coarse mesh, 60 steps) are below
  1e-8 m for four of the six parameters and a jump of 1.3e-5 m at one step for the other two,
  and near the hidden values a 0.7 mm jump of one node was seen: rarer and smaller, not gone.
  Self-collision radius SELF_RADIUS, friction 0.3 (as the other self-colliding scenes).
- Wind: Weft's sinusoidal wind, every node receiving strength * area_i * 0.5 (sin(2 pi
  frequency t + phase) + 1) * direction, with strength fixed at 1 N/m^2 as a unit (not a
  parameter), so d = direction in N/m^2 (per unit area where the paper's d is per node: the
  same model on a mesh of near-uniform area). Weft's frequency is in Hz (w = 2 pi frequency).
  The 6 DoF: stretch, phase, frequency, direction.0..2.
- HIDDEN (what the target is recorded with): stretch 300 N/m, phase 1.0 rad, frequency 1.5 Hz
  (4.2 gusts in the 2.8 s), d = (0.4, 0.6, 0.5) N/m^2: gusts that swing the shirt on its hanger
  (+Z, a third of its weight), lift it (+Y) and push it sideways (+X). The layers touch only
  because of the wind (without it no pair comes within reach in 90 steps of the coarse mesh).
  The hanger fixes a line along X, so only the Z part swings the shirt; X and Y only deform it
  in its plane and show little in the motion: a 2% error costs 40 to 80 times less loss in d_x
  or d_y than in the frequency (coarse mesh, 45 steps). Hence the large lift: at the tests'
  reduced size L-BFGS-B needed about 70 evaluations to bring d_y = 0.3 within 2%, about 40 for
  0.6. START: stretch 500, phase 0.3, frequency 1.2, d = (0.2, 0.3,
  0.8). BOUNDS: stretch [100, 2000] N/m, phase [-pi, pi], frequency [0.4, 3] Hz, direction
  components [-1.5, 1.5] N/m^2 (each holds its hidden value with room; `weft bench
  applications` starts seeds within a quarter of each box around START).
- Loss: task.loss.trajectory over all vertices and states 1..250 (Eq. 31 with squared
  distances, as Weft's trajectory term is) against targets/tshirt.npy. That target is recorded
  at build time (CMake target weft_task_targets in app/CMakeLists.txt: 8.7 MB, so not
  committed) by `weft simulate assets/scenes/tshirt.json --set <HIDDEN> --threads 1`.
- Solver: Newton-PCG to 1e-4 m/s^2 with up to 500 solves per step and DiffCloth's PD contact
  solve (the default), GMRES adjoint at 1e-6 with the direct fallback (as sphere_sysid). The PD
  contact solve stops unconverged on 148 of the 250 steps at START. The semismooth Newton
  contact solve (solver.contact "newton", continued by the PD iteration where it stalls)
  converges on 233 of them in the same time, but it is not used, because its result is not a
  continuous function of the parameters. The layers' step equations can have several
  solutions, and Newton's non-monotone steps pick among them by rounding. Measured 2026-12-03
  on the coarse shirt (36 steps, forward to 1e-8): two runs at most 5e-9 apart in each parameter
  matched to 5e-13 m up to step 32, and then both converged at step 33 to solutions 1.9 mm
  apart. `weft gradcheck` there gave finite differences of 1.04 and -0.94 against adjoint
  values of 0.0043 and 0.0057 (d_x, d_z), where the PD solve's agreed to 4e-7 and 1e-5. The
  reduced L-BFGS-B test stopped at 25 evaluations with the loss at 5.8e-4, where PD's reached
  1.6e-9. On the full task L-BFGS-B from `weft bench applications` seed 1 went 432.5 -> 227.3
  in 10 evaluations with PD and 430.7 -> 227.7 with Newton.

Usage: python3 scripts/make-tshirt.py [ASSET_DIR]   (default: assets/ next to scripts/)
Writes ASSET_DIR/meshes/tshirt.obj, ASSET_DIR/meshes/tshirt-coarse.obj and
ASSET_DIR/scenes/tshirt.json. Deterministic (fixed vertex order and number formatting):
re-running reproduces the files byte for byte. Python 3 standard library only.
"""

import math
import os
import sys
import functools

import scenefiles

dump = functools.partial(scenefiles.dump, pack_numbers=True)

SCRIPT = "scripts/make-tshirt.py"
# The garment, metres (hem at y = 0).
WIDTH = 0.5             # body width (chest 1 m round)
ARMPIT = 0.42           # side seam length, hem to armpit
SHOULDER = 0.62         # height of the shoulder points (armhole 0.2 m)
NECK = 0.66             # height of the neck points (shoulder seams rise 4 cm)
NECK_WIDTH = 0.18       # between the neck points
NECK_DEPTH = 0.07       # the neckline's dip below the neck points
SLEEVE_LENGTH = 0.2     # along the sleeve axis, armhole centre to cuff centre
SLEEVE_DROP_DEG = 35.0  # the sleeve axis below the horizontal
CUFF_WIDTH = 0.16
GAP = 0.012             # between the layers at rest
EDGE = 0.023            # the task mesh's spacing
EDGE_COARSE = 0.07      # the tests' reduced mesh
# The scene.
HEM_HEIGHT = 0.8
SELF_RADIUS = 0.004
DT = 1.0 / 90.0
STEPS = 250
WIND_UNIT = 1.0         # N/m^2: wind.strength, so that d = direction

HIDDEN = {
    "cloths.0.material.stretch": 300.0,
    "wind.phase": 1.0,
    "wind.frequency": 1.5,
    "wind.direction.0": 0.4,
    "wind.direction.1": 0.6,
    "wind.direction.2": 0.5,
}
START = {
    "cloths.0.material.stretch": 500.0,
    "wind.phase": 0.3,
    "wind.frequency": 1.2,
    "wind.direction.0": 0.2,
    "wind.direction.1": 0.3,
    "wind.direction.2": 0.8,
}
BOUNDS = {
    "cloths.0.material.stretch": [100.0, 2000.0],
    "wind.phase": [-round(math.pi, 6), round(math.pi, 6)],
    "wind.frequency": [0.4, 3.0],
    "wind.direction.0": [-1.5, 1.5],
    "wind.direction.1": [-1.5, 1.5],
    "wind.direction.2": [-1.5, 1.5],
}
PARAMETERS = list(START)


def intervals(length, edge):
    return max(1, int(round(length / edge)))


def runs(points, edge, even):
    """Coordinates from points[0] to points[-1] through every listed point, each run between
    consecutive points split into round(length / edge) equal intervals, an even number for the
    runs flagged in `even` (so that a vertex lies at the run's middle)."""
    out = [points[0]]
    for a, b, pair in zip(points[:-1], points[1:], even):
        n = 2 * intervals(b - a, 2 * edge) if pair else intervals(b - a, edge)
        out += [a + (b - a) * k / n for k in range(1, n + 1)]
    return out


def top(x):
    """Height of the body panel's top edge at x: the shoulder seams and the neckline."""
    half = 0.5 * NECK_WIDTH
    if abs(x) <= half:
        return NECK - NECK_DEPTH * math.cos(math.pi * x / NECK_WIDTH)
    return NECK + (SHOULDER - NECK) * (abs(x) - half) / (0.5 * WIDTH - half)


def panel(edge):
    """One flat panel: points {key: (x, y)}, quads (4 keys counter-clockwise seen from +Z), the
    set of seam keys, and the hanger's keys: on each shoulder seam the neck point, the middle and
    the shoulder point, ordered by x."""
    # The shoulder runs have a vertex at their middle: the hanger's (see tshirt()).
    xs = runs([-0.5 * WIDTH, -0.5 * NECK_WIDTH, 0.5 * NECK_WIDTH, 0.5 * WIDTH], edge, [True, False, True])
    lower = intervals(ARMPIT, edge)               # rows hem -> armpit
    upper = intervals(SHOULDER - ARMPIT, edge)    # rows armpit -> top (the armhole's intervals)
    rows = lower + upper
    points, quads, seams = {}, [], set()
    columns = len(xs) - 1
    neck = [i for i, x in enumerate(xs) if abs(abs(x) - 0.5 * NECK_WIDTH) < 1e-12]
    hanger = [("body", i, lower + upper) for i in (0, neck[0] // 2, neck[0], neck[1],
                                                   (neck[1] + columns) // 2, columns)]
    for j in range(rows + 1):
        for i, x in enumerate(xs):
            if j <= lower:
                y = ARMPIT * j / lower
            else:
                y = ARMPIT + (top(x) - ARMPIT) * (j - lower) / upper
            key = ("body", i, j)
            points[key] = (x, y)
            side = i in (0, columns)
            if (side and j <= lower) or (j == rows and abs(x) >= 0.5 * NECK_WIDTH - 1e-12):
                seams.add(key)
    for j in range(rows):
        for i in range(columns):
            quads.append((("body", i, j), ("body", i + 1, j), ("body", i + 1, j + 1), ("body", i, j + 1)))
    along = intervals(SLEEVE_LENGTH, edge)
    drop = math.radians(SLEEVE_DROP_DEG)
    for name, sign in (("right", 1.0), ("left", -1.0)):
        side = columns if sign > 0 else 0
        armhole = [("body", side, lower + r) for r in range(upper + 1)]  # armpit -> shoulder point
        centre = (sign * 0.5 * WIDTH, 0.5 * (ARMPIT + SHOULDER))
        axis = (sign * math.cos(drop), -math.sin(drop))
        normal = (sign * math.sin(drop), math.cos(drop))  # across the cuff, towards the top seam
        cuff_centre = (centre[0] + SLEEVE_LENGTH * axis[0], centre[1] + SLEEVE_LENGTH * axis[1])
        for r in range(upper + 1):
            a = points[armhole[r]]
            t = -0.5 + r / upper
            b = (cuff_centre[0] + t * CUFF_WIDTH * normal[0], cuff_centre[1] + t * CUFF_WIDTH * normal[1])
            for k in range(1, along + 1):
                s = k / along
                key = (name, k, r)
                points[key] = ((1 - s) * a[0] + s * b[0], (1 - s) * a[1] + s * b[1])
                if r in (0, upper):
                    seams.add(key)  # underarm seam (r = 0), shoulder seam on the sleeve (r = upper)

        def at(k, r):
            return armhole[r] if k == 0 else (name, k, r)

        for r in range(upper):
            for k in range(along):
                q = (at(k, r), at(k + 1, r), at(k + 1, r + 1), at(k, r + 1))
                # Counter-clockwise seen from +Z: on the left sleeve k runs towards -X.
                quads.append(q if sign > 0 else (q[1], q[0], q[3], q[2]))
    return points, quads, seams, hanger


def split(quads, points):
    """Two triangles per quad along alternating diagonals (by the quad's lower-left corner's
    parity), orientation kept."""
    triangles = []
    for q in quads:
        a, b, c, d = q
        parity = (q[0][1] + q[0][2]) % 2
        if parity == 0:
            triangles += [(a, b, c), (a, c, d)]
        else:
            triangles += [(a, b, d), (b, c, d)]
    return triangles


def tshirt(edge):
    """Vertices (x, y, z), triangles (vertex indices), and the hanger's vertex indices."""
    points, quads, seams, hanger = panel(edge)
    # The hanger's vertices first, so that the task and the coarse mesh hold the same indices:
    # the six seam vertices (0..5), then the front (6..11) and back (12..17) vertices one row
    # below them (the clips). Then the rest of the front panel row by row, then the back's.
    clips = [("body", key[1], key[2] - 1) for key in hanger]
    rest = sorted((key for key in points if key not in hanger and key not in clips),
                  key=lambda key: ({"body": 0, "right": 1, "left": 2}[key[0]], key[2], key[1]))
    front, back, vertices = {}, {}, []

    def add(key, layer, index):
        z = 0.0 if key in seams else 0.5 * GAP * layer
        index[key] = len(vertices)
        vertices.append((points[key][0], points[key][1], z))

    for key in hanger:
        add(key, 0, front)
        back[key] = front[key]
    for key in clips:
        add(key, 1, front)
    for key in clips:
        add(key, -1, back)
    for key in rest:
        add(key, 1, front)
    for key in rest:
        if key in seams:
            back[key] = front[key]
        else:
            add(key, -1, back)
    triangles = []
    for tri in split(quads, points):
        triangles.append(tuple(front[k] for k in tri))
    for tri in split(quads, points):
        triangles.append(tuple(back[k] for k in reversed(tri)))  # the back faces -Z
    return vertices, triangles, [front[k] for k in hanger + clips] + [back[k] for k in clips]


def check_mesh(name, vertices, triangles):
    """Consistently oriented manifold with boundary: every edge in one triangle per direction,
    interior edges in two, no degenerate triangle, every vertex used, four boundary loops (neck,
    hem, cuffs) and Euler characteristic -2."""
    directed = set()
    for tri in triangles:
        scenefiles.require_nondegenerate(name, vertices, tri)
        for k in range(3):
            edge = (tri[k], tri[(k + 1) % 3])
            if edge in directed:
                raise SystemExit(f"{name}: edge {edge} used twice in one direction")
            directed.add(edge)
    boundary = {e for e in directed if (e[1], e[0]) not in directed}
    following = {}
    for a, b in boundary:
        if a in following:
            raise SystemExit(f"{name}: vertex {a} starts two boundary edges (not a manifold)")
        following[a] = b
    loops, seen = 0, set()
    for start in following:
        if start in seen:
            continue
        loops += 1
        v = start
        while v not in seen:
            seen.add(v)
            v = following[v]
    if {i for tri in triangles for i in tri} != set(range(len(vertices))):
        raise SystemExit(f"{name}: vertices in no triangle")
    edges = len({frozenset(e) for e in directed})
    euler = len(vertices) - edges + len(triangles)
    if loops != 4 or euler != -2:
        raise SystemExit(f"{name}: {loops} openings and Euler characteristic {euler}, expected 4 and -2")
    return loops


def fmt(x):
    s = "%.6f" % x
    return "0.000000" if s == "-0.000000" else s


def write_obj(path, edge, vertices, triangles, hanger):
    with open(path, "w", newline="\n") as f:
        f.write("# Weft T-shirt, written by %s (see its docstring); do not edit by hand.\n" % SCRIPT)
        f.write("# Front and back panels sewn (welded) along the shoulder, sleeve-top, underarm and side seams;\n")
        f.write("# openings at the neck, hem and cuffs. Metres, +Y up, hem at y = 0, seams in z = 0, layers %g m apart.\n" % GAP)
        f.write("# Body %g m wide, shoulder points at %g m, neck points at %g m, sleeves %g m at %g deg; edge %g m.\n"
                % (WIDTH, SHOULDER, NECK, SLEEVE_LENGTH, SLEEVE_DROP_DEG, edge))
        f.write("# %d vertices, %d triangles; shoulder seams (the hanger): vertices %s (1-based).\n"
                % (len(vertices), len(triangles), " ".join(str(i + 1) for i in hanger)))
        for v in vertices:
            f.write("v %s %s %s\n" % tuple(fmt(c) for c in v))
        for t in triangles:
            f.write("f %d %d %d\n" % tuple(i + 1 for i in t))


def hidden_overrides():
    return ["%s=%r" % (k, v) for k, v in HIDDEN.items()]


def scene(vertex_count, hanger):
    description = (
        "DiffCloth's T-shirt system identification (Li et al. 2022, Sec. 6.1, Fig. 7, Appendix "
        "B.1): a %d-vertex T-shirt on a hanger (vertices 0..17: three points of each shoulder "
        "seam and the front and back vertices below them) in a sinusoidal "
        "wind, every node receiving strength * area * 0.5 (sin(2 pi frequency t + phase) + 1) * "
        "direction with strength 1 N/m^2, so d = direction; its stretch stiffness, the wind's "
        "phase, frequency and d (6 DoF) are to be identified from a recorded motion (trajectory "
        "loss over all vertices and steps, Eq. 31 squared), with self-collision between its front "
        "and back layers. The target targets/tshirt.npy is the motion of hidden values (%s), "
        "recorded at build time (target weft_task_targets in app/CMakeLists.txt) by: weft "
        "simulate assets/scenes/tshirt.json %s --threads 1, then copying positions.npy. h = 1/90 "
        "s, 250 steps, the wind model, the 6 parameters, the loss and the vertex count (the "
        "paper's 1426) are the paper's; the garment (../meshes/tshirt.obj: front and back panels "
        "sewn at the shoulder, underarm and side seams, made by %s, not the paper's mesh; "
        "../meshes/tshirt-coarse.obj is the same shirt at 176 vertices for tests), hanger, "
        "material (bend 1e-3 N m so that the hanging shirt bends rather than buckles), "
        "self-collision radius, hidden and starting values and bounds were chosen here. Written "
        "by %s (see its docstring); do not edit by hand."
        % (vertex_count, ", ".join("%s %g" % kv for kv in HIDDEN.items()),
           " ".join("--set " + o for o in hidden_overrides()), SCRIPT, SCRIPT))
    return {
        "name": "tshirt",
        "description": description,
        "time": {"dt": DT, "steps": STEPS},
        "gravity": [0, -9.8, 0],
        "solver": {
            "method": "newton", "pd_iterations": 500, "pd_tolerance": 1e-4,
            "backward": {"method": "gmres", "tolerance": 1e-6, "max_iterations": 200,
                         "fallback": "direct"},
        },
        "cloths": [{
            "mesh": {"file": "../meshes/tshirt.obj", "transform": {"translate": [0, HEM_HEIGHT, 0]}},
            "material": {"density": 0.15, "stretch": START["cloths.0.material.stretch"], "bend": 0.001},
            "attachments": [{"vertices": hanger, "kind": "fixed"}],
            "self_collision": {"radius": SELF_RADIUS, "friction": 0.3},
        }],
        "wind": {
            "direction": [START["wind.direction.%d" % i] for i in range(3)],
            "strength": WIND_UNIT,
            "frequency": START["wind.frequency"],
            "phase": START["wind.phase"],
        },
        "task": {
            "loss": {"trajectory": {"target": "targets/tshirt.npy"}},
            "parameters": PARAMETERS,
            "bounds": BOUNDS,
        },
    }


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "assets")
    os.makedirs(os.path.join(out, "meshes"), exist_ok=True)
    os.makedirs(os.path.join(out, "scenes"), exist_ok=True)
    for name, edge in (("tshirt", EDGE), ("tshirt-coarse", EDGE_COARSE)):
        vertices, triangles, hanger = tshirt(edge)
        check_mesh(name, vertices, triangles)
        write_obj(os.path.join(out, "meshes", name + ".obj"), edge, vertices, triangles, hanger)
        print("wrote %s.obj (%d vertices, %d triangles, hanger %d vertices)"
              % (name, len(vertices), len(triangles), len(hanger)))
        if name == "tshirt":
            doc = scene(len(vertices), hanger)
    with open(os.path.join(out, "scenes", "tshirt.json"), "w") as f:
        f.write(dump(doc) + "\n")
    print("wrote tshirt.json (%d parameters)" % len(PARAMETERS))


if __name__ == "__main__":
    main()
