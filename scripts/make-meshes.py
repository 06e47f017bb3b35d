#!/usr/bin/env python3
"""Writes the obstacle meshes Weft's scenes use to assets/meshes/*.obj.

The meshes are made here rather than downloaded so that their provenance is this file: every
OBJ says in its header which function and parameters made it. Output is deterministic (fixed
vertex order, fixed number formatting), so re-running the script reproduces the committed files
byte for byte. Python 3 standard library only.

Contact against a mesh obstacle signs distances by angle-weighted pseudo-normals, which is
exact only for a closed, consistently oriented surface (engine/weft/contact/MeshShape.h). So
every mesh here is closed and outward-oriented, including the "open" shapes: the bowl and the
pyramid are solids with the cavity carved out of their top, the cavity being outside the solid. The script checks
both properties (every edge shared by exactly two triangles in opposite directions; positive
enclosed volume) before writing.

Usage: python3 scripts/make-meshes.py [OUTPUT_DIR]   (default: assets/meshes next to scripts/)
"""

import math
import os
import sys

SCRIPT = "scripts/make-meshes.py"


def revolve(profile, segments, phase_deg=0.0, scale_z=1.0):
    """Closed surface of revolution about +Y.

    `profile` is a list of (radius, y) from one pole (radius 0) to the other (radius 0); the
    points in between become rings of `segments` vertices. Returns (vertices, triangles) with
    triangles oriented outward.
    """
    assert profile[0][0] == 0.0 and profile[-1][0] == 0.0, "profile must start and end on the axis"
    vertices = [(0.0, profile[0][1], 0.0)]
    rings = []
    for radius, y in profile[1:-1]:
        ring = []
        for s in range(segments):
            a = math.radians(phase_deg) + 2.0 * math.pi * s / segments
            ring.append(len(vertices))
            vertices.append((radius * math.cos(a), y, scale_z * radius * math.sin(a)))
        rings.append(ring)
    vertices.append((0.0, profile[-1][1], 0.0))
    return orient_outward(vertices, close_rings(rings, 0, len(vertices) - 1, segments))


def sweep(centreline, half_widths, half_heights, segments, cap_rings):
    """Closed tube along a planar centreline in the YZ plane (a leg bending into a foot).

    Cross-sections are ellipses with semi-axis `half_widths[i]` along X and `half_heights[i]`
    along the in-plane normal. The start is closed by a flat cap (a centre vertex), the end by a
    half-ellipsoid of `cap_rings` rings, so the toe is round.
    """
    n = len(centreline)
    frames = []
    for i in range(n):
        a = centreline[max(i - 1, 0)]
        b = centreline[min(i + 1, n - 1)]
        ty, tz = b[0] - a[0], b[1] - a[1]
        length = math.hypot(ty, tz)
        ty, tz = ty / length, tz / length
        frames.append(((ty, tz), (-tz, ty)))  # tangent and in-plane normal, both (y, z)
    vertices = [(0.0, centreline[0][0], centreline[0][1])]
    rings = []

    def add_ring(y, z, normal, w, h):
        ring = []
        for s in range(segments):
            a = 2.0 * math.pi * s / segments
            ring.append(len(vertices))
            vertices.append((w * math.cos(a), y + h * math.sin(a) * normal[0], z + h * math.sin(a) * normal[1]))
        rings.append(ring)

    for i, (y, z) in enumerate(centreline):
        add_ring(y, z, frames[i][1], half_widths[i], half_heights[i])
    # Toe: rings shrinking along the last tangent like a half ellipsoid whose third semi-axis is
    # the mean of the last section's two.
    (ty, tz), normal = frames[-1]
    y0, z0 = centreline[-1]
    w, h = half_widths[-1], half_heights[-1]
    reach = 0.5 * (w + h)
    for k in range(1, cap_rings):
        angle = 0.5 * math.pi * k / cap_rings
        along, shrink = reach * math.sin(angle), math.cos(angle)
        add_ring(y0 + along * ty, z0 + along * tz, normal, w * shrink, h * shrink)
    vertices.append((0.0, y0 + reach * ty, z0 + reach * tz))
    return orient_outward(vertices, close_rings(rings, 0, len(vertices) - 1, segments))


def signed_volume(vertices, triangles):
    total = 0.0
    for a, b, c in triangles:
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = vertices[a], vertices[b], vertices[c]
        total += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)
    return total / 6.0


def close_rings(rings, first, last, segments):
    """Triangles of a closed body of revolution: a fan from vertex `first` to the first ring,
    quads between neighbouring rings, and a fan from the last ring to vertex `last`."""
    triangles = []
    for s in range(segments):
        t = (s + 1) % segments
        triangles.append((first, rings[0][t], rings[0][s]))
        for r in range(len(rings) - 1):
            a, b = rings[r], rings[r + 1]
            triangles.append((a[s], a[t], b[t]))
            triangles.append((a[s], b[t], b[s]))
        triangles.append((last, rings[-1][s], rings[-1][t]))
    return triangles


def orient_outward(vertices, triangles):
    """Flips every triangle when the construction came out inward (negative volume)."""
    if signed_volume(vertices, triangles) < 0.0:
        triangles = [(a, c, b) for a, b, c in triangles]
    return vertices, triangles


def check_closed(name, vertices, triangles):
    """Every directed edge once and its reverse once: closed, manifold, consistently oriented."""
    directed = {}
    for tri in triangles:
        for k in range(3):
            edge = (tri[k], tri[(k + 1) % 3])
            directed[edge] = directed.get(edge, 0) + 1
    for (a, b), count in directed.items():
        if count != 1 or directed.get((b, a)) != 1:
            raise SystemExit(f"{name}: edge {a}-{b} is not shared by exactly two consistently oriented triangles")
    if signed_volume(vertices, triangles) <= 0.0:
        raise SystemExit(f"{name}: encloses no positive volume")


def bowl():
    # A hemispherical bowl (DiffCloth Fig. 5 shows a napkin falling into one): a cavity of
    # radius 0.3 m, rim at y = 0, bottom at y = -0.3, in a round solid of radius 0.4 m and depth
    # 0.4 m (flat outside bottom). Thick walls for the reason given at pyramid().
    inner, outer, depth, rings, segments = 0.3, 0.4, 0.4, 16, 48
    profile = [(0.0, -inner)]
    for k in range(1, rings + 1):
        theta = 0.5 * math.pi * k / rings
        profile.append((inner * math.sin(theta), -inner * math.cos(theta)))
    profile += [(outer, 0.0), (outer, -depth), (0.0, -depth)]
    params = (f"cavity radius {inner} m, {rings} rings, {segments} segments, rim at y = 0; "
              f"solid radius {outer} m, bottom at y = -{depth} m")
    return revolve(profile, segments), params


def pyramid():
    # Liang et al. 2019's ablation scene (Sec. 4.1, Fig. 2) crumples a cloth inside an
    # upside-down square pyramid; no dimensions are given. Ours: a square block (1.4 m wide,
    # top at y = 0, 0.9 m deep) with the pyramid carved out of its top: opening 0.8 m x 0.8 m,
    # apex 0.6 m below it. The walls are thick on purpose: distances are signed by the nearest
    # surface, so a node pushed past the middle of a thin wall would be sent out the far side.
    # A surface of revolution with 4 segments is exactly a square pyramid; the cavity faces are
    # split into bands only to keep triangles from being needle-thin.
    half, depth, outer_half, bottom, bands = 0.4, 0.6, 0.7, 0.9, 8
    corner, outer_corner = half * math.sqrt(2.0), outer_half * math.sqrt(2.0)
    profile = [(0.0, -depth)]
    for k in range(1, bands + 1):
        profile.append((corner * k / bands, -depth + depth * k / bands))
    profile += [(outer_corner, 0.0), (outer_corner, -bottom), (0.0, -bottom)]
    params = (f"cavity: opening {2 * half} m square at y = 0, apex at y = -{depth} m, {bands} bands per face; "
              f"block {2 * outer_half} m square from y = -{bottom} m to 0")
    return revolve(profile, 4, phase_deg=45.0), params


def head():
    # A stylised head on a neck for the hat tasks (DiffCloth Sec. 6.2, 6.5): an ellipsoidal
    # skull (0.17 m wide, 0.22 m tall, 15% deeper front to back) on a 0.05 m neck, base at y = 0.
    a, b, centre, segments, rings = 0.085, 0.11, 0.22, 48, 28
    profile = [(0.0, centre + b)]
    last = math.radians(145.0)
    for k in range(1, rings + 1):
        phi = last * k / rings
        profile.append((a * math.sin(phi), centre + b * math.cos(phi)))
    profile += [(0.05, 0.10), (0.05, 0.05), (0.05, 0.0), (0.0, 0.0)]
    params = (f"skull semi-axes {a} m (x), {b} m (y), {a * 1.15:.4f} m (z) centred at y = {centre} m; "
              f"neck radius 0.05 m down to y = 0; {segments} segments")
    return revolve(profile, segments, scale_z=1.15), params


def foot():
    # A synthetic foot and lower leg for the sock task (DiffCloth Sec. 6.2, Fig. 10): a tube
    # down the leg (y from 0.45 m to 0.15 m), a quarter bend of radius 0.08 m at the ankle, and
    # the foot along +Z to a rounded toe. Sections are ellipses: leg 0.05 m round, foot 0.045 m
    # wide and 0.035 m high. The top of the leg is closed flat.
    segments = 32
    centreline, widths, heights = [], [], []
    for k in range(7):  # leg
        centreline.append((0.45 - 0.3 * k / 6, 0.0))
    for k in range(1, 9):  # ankle bend about (y, z) = (0.15, 0.08)
        angle = 0.5 * math.pi * k / 8
        centreline.append((0.15 - 0.08 * math.sin(angle), 0.08 - 0.08 * math.cos(angle)))
    for k in range(1, 7):  # foot
        centreline.append((0.07, 0.08 + 0.14 * k / 6))
    for y, z in centreline:
        along = max(0.0, min(1.0, (0.15 - y) / 0.08 if z < 0.08 else 1.0))  # 0 on the leg, 1 on the foot
        widths.append(0.05 + (0.045 - 0.05) * along)
        heights.append(0.05 + (0.035 - 0.05) * along)
    params = "leg radius 0.05 m from y = 0.45 m to 0.15 m, ankle bend radius 0.08 m, foot 0.045 x 0.035 m to z = 0.22 m plus toe cap"
    return sweep(centreline, widths, heights, segments, cap_rings=6), params


def write_obj(path, name, purpose, params, vertices, triangles):
    with open(path, "w", newline="\n") as out:
        out.write(f"# {name}.obj: {purpose}\n")
        out.write(f"# Generated by {SCRIPT} ({name}()); do not edit, re-run the script instead.\n")
        out.write(f"# Parameters: {params}\n")
        out.write("# Units: metres, +Y up. Closed and outward-oriented (checked by the script).\n")
        out.write(f"# {len(vertices)} vertices, {len(triangles)} triangles.\n")
        for x, y, z in vertices:
            out.write(f"v {x:.6f} {y:.6f} {z:.6f}\n".replace("-0.000000", "0.000000"))
        for a, b, c in triangles:
            out.write(f"f {a + 1} {b + 1} {c + 1}\n")


MESHES = [
    ("bowl", bowl, "hemispherical bowl for the napkin-in-a-bowl scene (DiffCloth Fig. 5)"),
    ("pyramid", pyramid, "upside-down square pyramid for the crumple scene (Liang et al. 2019, Sec. 4.1)"),
    ("head", head, "stylised head and neck for the hat tasks (DiffCloth Sec. 6.2, 6.5)"),
    ("foot", foot, "foot and lower leg for the sock task (DiffCloth Sec. 6.2)"),
]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "assets", "meshes")
    os.makedirs(out_dir, exist_ok=True)
    for name, build, purpose in MESHES:
        (vertices, triangles), params = build()
        check_closed(name, vertices, triangles)
        path = os.path.join(out_dir, name + ".obj")
        write_obj(path, name, purpose, params, vertices, triangles)
        print(f"{os.path.normpath(path)}: {len(vertices)} vertices, {len(triangles)} triangles, "
              f"volume {signed_volume(vertices, triangles):.5f} m^3")


if __name__ == "__main__":
    main()
