#!/usr/bin/env python3
"""Prints how many pixels of a PNG's outermost rows and columns differ from the background colour
(given as 0-255 RGB), and how many pixels differ anywhere. 8-bit RGB or RGBA PNGs (what sortlast
writes), read by scripts/png8.py, so the tests need no imaging package.
Usage: png_border.py IMAGE.png R G B"""
import os
import sys

# The PNG reader shared with the benchmark scripts.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from png8 import read_png  # noqa: E402


w, h, bpp, rows = read_png(sys.argv[1])
bg = [int(v) for v in sys.argv[2:5]]
differs = lambda x, y: any(abs(rows[y][x * bpp + k] - bg[k]) > 1 for k in range(3))
border = {(x, y) for x in range(w) for y in (0, h - 1)} | {(x, y) for y in range(h) for x in (0, w - 1)}
print(f"border_pixels_not_background={sum(differs(x, y) for x, y in border)} "
      f"pixels_not_background={sum(differs(x, y) for x in range(w) for y in range(h))} width={w} height={h}")
