"""Reading Weft's .npy outputs (positions.npy, contact_branches.npy, ...) without numpy: they
are little-endian float64 arrays in C order. Shared by the analysis scripts beside it, with the
way they refuse bad input (bad_input: `error: <file>: <what>` on stderr, exit 2, as weft does)."""

import ast
import struct
import sys


def bad_input(message):
    """Prints `message` to stderr and exits with status 2 (bad input, as weft does)."""
    print(message, file=sys.stderr)
    sys.exit(2)


def open_npy(path):
    """(shape, file positioned at the first value) of a little-endian float64 C-order .npy."""
    try:
        f = open(path, "rb")
    except OSError as e:
        bad_input(f"error: {path}: {e.strerror}")
    if f.read(6) != b"\x93NUMPY":
        bad_input(f"error: {path}: not a .npy file")
    major = f.read(2)[0]
    length = struct.unpack("<H" if major == 1 else "<I", f.read(2 if major == 1 else 4))[0]
    header = ast.literal_eval(f.read(length).decode("latin1"))
    if header["descr"] != "<f8" or header["fortran_order"]:
        bad_input(f"error: {path}: expected little-endian float64 in C order")
    return header["shape"], f


def read_values(f, count):
    """The next `count` float64 values of an open .npy file."""
    return struct.unpack(f"<{count}d", f.read(count * 8))
