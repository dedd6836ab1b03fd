#!/usr/bin/env python3
"""png_compare: are two screenshots the same picture right of column X0?

    png_compare.py A.png B.png [X0]
prints the largest channel difference and how many pixels differ; exits 0
when none does, 1 otherwise. The standard library only (png_probe's
decoder)."""
import os
import struct
import sys
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import png_probe  # noqa: E402


def load(path):
    data = open(path, "rb").read()
    idat = b""
    for kind, body in png_probe.chunks(data):
        if kind == b"IHDR":
            w, h, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
    bpp = {0: 1, 2: 3, 4: 2, 6: 4}[colour]
    return w, h, bpp, png_probe.unfilter(zlib.decompress(idat), w, h, bpp)


def main(argv):
    x0 = int(argv[3]) if len(argv) > 3 else 0
    wa, ha, ba, ra = load(argv[1])
    wb, hb, bb, rb = load(argv[2])
    if (wa, ha) != (wb, hb):
        print("sizes differ: %dx%d and %dx%d" % (wa, ha, wb, hb))
        return 1
    worst, differ = 0, 0
    for y in range(ha):
        for x in range(x0, wa):
            d = max(abs(ra[y][x * ba + c] - rb[y][x * bb + c]) for c in range(min(ba, bb, 3)))
            worst = max(worst, d)
            differ += d > 0
    print("columns %d..%d: max difference %d, %d pixels differ" % (x0, wa - 1, worst, differ))
    return 0 if differ == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
