"""A small RGB raster for benchmark figures, written as PNG with zlib alone (no plotting library
is among Weft's dependencies): lines, circles and polylines in data coordinates."""

import struct
import zlib

import numpy as _np


class Canvas:
    def __init__(self, width, height, background=(255, 255, 255)):
        self.width, self.height = width, height
        self.pixels = _np.empty((height, width, 3), dtype=_np.uint8)
        self.pixels[:] = background

    def dot(self, x, y, color, radius=1.0):
        r = int(_np.ceil(radius))
        xi, yi = int(round(x)), int(round(y))
        for dy in range(-r, r + 1):
            for dx in range(-r, r + 1):
                if dx * dx + dy * dy <= radius * radius + 0.25:
                    px, py = xi + dx, yi + dy
                    if 0 <= px < self.width and 0 <= py < self.height:
                        self.pixels[py, px] = color

    def line(self, x0, y0, x1, y1, color, width=1.0):
        n = int(max(abs(x1 - x0), abs(y1 - y0)) * 2) + 1
        for s in _np.linspace(0.0, 1.0, n + 1):
            self.dot(x0 + s * (x1 - x0), y0 + s * (y1 - y0), color, width / 2)

    def polyline(self, xs, ys, color, width=1.0):
        for k in range(len(xs) - 1):
            self.line(xs[k], ys[k], xs[k + 1], ys[k + 1], color, width)

    def circle(self, cx, cy, radius, color, width=1.0):
        n = max(16, int(radius * 8))
        t = _np.linspace(0, 2 * _np.pi, n + 1)
        self.polyline(cx + radius * _np.cos(t), cy + radius * _np.sin(t), color, width)

    def save(self, path):
        raw = b"".join(b"\x00" + self.pixels[y].tobytes() for y in range(self.height))

        def chunk(kind, data):
            body = kind + data
            return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

        header = struct.pack(">IIBBBBB", self.width, self.height, 8, 2, 0, 0, 0)
        with open(path, "wb") as f:
            f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header)
                    + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


class Axes:
    """A panel of a canvas mapping data (u, v) to pixels, v up."""

    def __init__(self, canvas, left, top, width, height, u_range, v_range, log_u=False):
        self.canvas, self.left, self.top, self.width, self.height = canvas, left, top, width, height
        self.u_range, self.v_range, self.log_u = u_range, v_range, log_u

    def _u(self, u):
        lo, hi = self.u_range
        if self.log_u:
            u, lo, hi = _np.log10(u), _np.log10(lo), _np.log10(hi)
        return self.left + (u - lo) / (hi - lo) * self.width

    def _v(self, v):
        lo, hi = self.v_range
        return self.top + self.height - (v - lo) / (hi - lo) * self.height

    def frame(self, color=(160, 160, 160)):
        c, l, t, w, h = self.canvas, self.left, self.top, self.width, self.height
        c.polyline([l, l + w, l + w, l, l], [t, t, t + h, t + h, t], color)

    def polyline(self, us, vs, color, width=1.5):
        self.canvas.polyline([self._u(u) for u in us], [self._v(v) for v in vs], color, width)

    def dot(self, u, v, color, radius=3.0):
        self.canvas.dot(self._u(u), self._v(v), color, radius)

    def circle(self, u, v, radius, color):
        scale = self.width / (self.u_range[1] - self.u_range[0])
        self.canvas.circle(self._u(u), self._v(v), radius * scale, color, 1.5)
