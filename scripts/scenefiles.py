"""The file writers the asset generators share (make-napkins.py, make-garments.py, make-dress.py,
make-flag.py): one JSON layout and one .npy writer, so that re-running any generator reproduces
the committed scene and target files byte for byte. Python 3 standard library only.
"""

import json
import math
import struct


def write_npy(path, rows):
    """A float64 [len(rows), 3] .npy (format version 1.0)."""
    header = "{'descr': '<f8', 'fortran_order': False, 'shape': (%d, 3), }" % len(rows)
    header += " " * ((64 - (10 + len(header) + 1) % 64) % 64) + "\n"
    with open(path, "wb") as f:
        f.write(b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode("latin1"))
        for row in rows:
            f.write(struct.pack("<3d", *row))


def dump(value, indent=0, pack_numbers=False):
    """JSON with objects one key a line and anything that fits in 100 columns on one line; with
    pack_numbers, longer lists of numbers are packed into lines of at most 100 columns instead of
    one number a line."""
    flat = json.dumps(value)
    if not isinstance(value, (dict, list)) or len(flat) + indent <= 100:
        return flat
    pad = " " * (indent + 2)
    if pack_numbers and isinstance(value, list) and all(isinstance(v, (int, float)) for v in value):
        lines, line = [], ""
        for v in value:
            item = json.dumps(v)
            if line and len(pad) + len(line) + len(item) + 2 > 100:
                lines.append(line + ",")
                line = ""
            line += (", " if line else "") + item
        return "[\n" + "\n".join(pad + l for l in lines + [line]) + "\n" + " " * indent + "]"
    if isinstance(value, list):
        items = [pad + dump(v, indent + 2, pack_numbers) for v in value]
        return "[\n" + ",\n".join(items) + "\n" + " " * indent + "]"
    items = [pad + json.dumps(k) + ": " + dump(v, indent + 2, pack_numbers) for k, v in value.items()]
    return "{\n" + ",\n".join(items) + "\n" + " " * indent + "}"


def require_nondegenerate(name, vertices, tri):
    """Exits naming the mesh when triangle `tri` (three indices into `vertices`) has no area."""
    a, b, c = (vertices[i] for i in tri)
    ab = [b[k] - a[k] for k in range(3)]
    ac = [c[k] - a[k] for k in range(3)]
    cross = (ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2], ab[0] * ac[1] - ab[1] * ac[0])
    if math.sqrt(sum(x * x for x in cross)) < 1e-10:
        raise SystemExit(f"{name}: degenerate triangle {tri}")
