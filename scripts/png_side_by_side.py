#!/usr/bin/env python3
"""Puts PNGs of the same height side by side, over black, into one RGB PNG: the smoothing
benchmark's round | anisotropic images. 8-bit RGB or RGBA input (what sortlast writes), read and
written by scripts/png8.py, so the benchmark needs no imaging package.
Usage: png_side_by_side.py OUT.png IN.png..."""
import sys

from png8 import read_png, write_png


def rgb_over_black(path):
    """The image's rows as RGB over black: RGB times alpha (sortlast's colours are premultiplied
    already, so this only zeroes what an unpremultiplied writer left under alpha 0)."""
    w, h, bpp, rows = read_png(path)
    if bpp == 4:
        rows = [bytearray(v for x in range(w) for v in (r[4 * x] * r[4 * x + 3] // 255,
                r[4 * x + 1] * r[4 * x + 3] // 255, r[4 * x + 2] * r[4 * x + 3] // 255)) for r in rows]
    return w, h, rows


images = [rgb_over_black(p) for p in sys.argv[2:]]
height = images[0][1]
assert all(h == height for _, h, _ in images), "images differ in height"
write_png(sys.argv[1], sum(w for w, _, _ in images), height,
          [b"".join(bytes(rows[y]) for _, _, rows in images) for y in range(height)])
