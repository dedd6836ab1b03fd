#!/usr/bin/env python3
"""png_probe: what the window tests need to know of a screenshot, with the
standard library only (no PIL on the test machines).

    png_probe.py FILE [X Y]...
    png_probe.py FILE hash X0
prints "size W H", "alpha_min A" (255 when the PNG has no alpha channel)
and "pixel X Y R G B A" per point asked for (top-left origin); with
`hash X0`, "hash HEX", a digest of the pixels at x >= X0 (the scene area
right of the panel, to compare two screenshots' scenes). 8-bit
greyscale, RGB, grey+alpha and RGBA, not interlaced: what img_write writes.
"""
import hashlib
import struct
import sys
import zlib


def chunks(data):
    pos = 8
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        yield kind, data[pos + 8:pos + 8 + n]
        pos += 12 + n


def paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    return a if pa <= pb and pa <= pc else b if pb <= pc else c


def unfilter(raw, w, h, bpp):
    stride = w * bpp
    rows, prev, pos = [], bytearray(stride), 0
    for _ in range(h):
        kind, row = raw[pos], bytearray(raw[pos + 1:pos + 1 + stride])
        pos += 1 + stride
        for i in range(stride):
            a = row[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            row[i] = (row[i] + (0, a, b, (a + b) // 2, paeth(a, b, c))[kind]) & 255
        rows.append(row)
        prev = row
    return rows


def main(argv):
    data = open(argv[1], "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit("%s: not a PNG" % argv[1])
    idat = b""
    for kind, body in chunks(data):
        if kind == b"IHDR":
            w, h, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
    bpp = {0: 1, 2: 3, 4: 2, 6: 4}.get(colour)
    if depth != 8 or interlace or bpp is None:
        sys.exit("%s: depth %d colour type %d interlace %d not handled" % (argv[1], depth, colour, interlace))
    rows = unfilter(zlib.decompress(idat), w, h, bpp)
    print("size %d %d" % (w, h))
    alpha = 255 if bpp in (1, 3) else min(min(r[bpp - 1::bpp]) for r in rows)
    print("alpha_min %d" % alpha)
    if len(argv) == 4 and argv[2] == "hash":
        x0 = int(argv[3]) * bpp
        print("hash " + hashlib.sha256(b"".join(bytes(r[x0:]) for r in rows)).hexdigest())
        return
    for x, y in zip(argv[2::2], argv[3::2]):
        x, y = int(x), int(y)
        px = list(rows[y][x * bpp:(x + 1) * bpp])
        rgba = px * 3 + [255] if bpp == 1 else [px[0]] * 3 + [px[1]] if bpp == 2 else px + [255] * (4 - bpp)
        print("pixel %d %d %d %d %d %d" % (x, y, *rgba[:4]))


if __name__ == "__main__":
    main(sys.argv)
