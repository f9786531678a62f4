#!/usr/bin/env python3
"""Puts PNGs of the same height side by side, over black, into one RGB PNG: the smoothing
benchmark's round | anisotropic images. 8-bit RGB or RGBA input (what sortlast writes); a plain
decoder and encoder (zlib), so the benchmark needs no imaging package (the decoder is
tests/mpi/png_border.py's, which runs as a script and cannot be imported).
Usage: png_side_by_side.py OUT.png IN.png..."""
import struct
import sys
import zlib


def read_png(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path}: not a PNG"
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            w, h, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and colour in (2, 6) and interlace == 0, f"{path}: 8-bit RGB(A) only"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    bpp = 3 if colour == 2 else 4
    raw, stride, rows, prev = zlib.decompress(idat), w * bpp, [], bytearray(w * bpp)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    # Over black: RGB times alpha (sortlast's colours are premultiplied already, so this only
    # zeroes what an unpremultiplied writer left under alpha 0).
    if bpp == 4:
        rows = [bytearray(v for x in range(w) for v in (r[4 * x] * r[4 * x + 3] // 255,
                r[4 * x + 1] * r[4 * x + 3] // 255, r[4 * x + 2] * r[4 * x + 3] // 255)) for r in rows]
    return w, h, rows


def write_png(path, w, h, rows):
    chunk = lambda kind, body: (struct.pack(">I", len(body)) + kind + body +
                                struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF))
    raw = b"".join(b"\x00" + bytes(r) for r in rows)
    with open(path, "wb") as out:
        out.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
                  chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


images = [read_png(p) for p in sys.argv[2:]]
height = images[0][1]
assert all(h == height for _, h, _ in images), "images differ in height"
write_png(sys.argv[1], sum(w for w, _, _ in images), height,
          [b"".join(bytes(rows[y]) for _, _, rows in images) for y in range(height)])
