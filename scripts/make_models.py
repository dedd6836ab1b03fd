#!/usr/bin/env python3
"""Writes the world's small models (issue #25) into data/models/: a rowing
boat, a rock and a pier section, as Wavefront OBJ (v and f lines only).

Every model is a closed surface with its triangles wound counter-clockwise
seen from outside (tarn's reference and GL world shade each facet by its
geometric normal, ref_mesh.h), in metres, y up, its origin where a scene's
`Object mesh FILE x y z` puts it: the boat's at its waterline centre, the
rock's at its middle, the pier's at the top of its deck's landward end.
Deterministic (no randomness but a fixed hash), so running it again writes
the same files:  python3 scripts/make_models.py
"""
import math
import os

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "models")


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


class Mesh:
    def __init__(self):
        self.v, self.f = [], []

    def vert(self, p):
        self.v.append(p)
        return len(self.v) - 1

    def tri(self, a, b, c, outward):
        """Triangle of vertex indices a b c, wound so its normal points along outward."""
        pa, pb, pc = self.v[a], self.v[b], self.v[c]
        n = cross(sub(pb, pa), sub(pc, pa))
        if dot(n, n) < 1e-20:
            return          # degenerate: nothing to draw or hit
        self.f.append((a, b, c) if dot(n, outward) >= 0 else (a, c, b))

    def quad(self, a, b, c, d, outward):
        self.tri(a, b, c, outward)
        self.tri(a, c, d, outward)

    def box(self, lo, hi):
        c = [(lo[i] + hi[i]) / 2 for i in range(3)]
        idx = {}
        for i in (0, 1):
            for j in (0, 1):
                for k in (0, 1):
                    idx[i, j, k] = self.vert((hi[0] if i else lo[0], hi[1] if j else lo[1], hi[2] if k else lo[2]))
        for axis in range(3):
            for side in (0, 1):
                corners = []
                for u, w in ((0, 0), (1, 0), (1, 1), (0, 1)):
                    key = [0, 0, 0]
                    key[axis] = side
                    key[(axis + 1) % 3] = u
                    key[(axis + 2) % 3] = w
                    corners.append(idx[tuple(key)])
                out = [0.0, 0.0, 0.0]
                out[axis] = 1.0 if side else -1.0
                self.quad(*corners, outward=tuple(out))
        del c

    def write(self, path, comment):
        with open(path, "w") as f:
            f.write("# %s\n# made by scripts/make_models.py: %d vertices, %d triangles\n"
                    % (comment, len(self.v), len(self.f)))
            for p in self.v:
                f.write("v %.4f %.4f %.4f\n" % p)
            for a, b, c in self.f:
                f.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))
        print("wrote %s (%d triangles)" % (os.path.relpath(path), len(self.f)))


def boat():
    """A rowing boat 3 m long, 1.1 m in the beam: a thin shell (outer hull,
    inner hull, the gunwale between) and two thwarts. Origin: the waterline
    amidships; the keel 0.22 m below it."""
    m = Mesh()
    L, B, N, M = 3.0, 1.1, 16, 8

    def section(u, inner):
        half = 0.5 * B * max(0.0, 1.0 - abs(u) ** 2.4) ** 0.55
        top = 0.26 + 0.14 * u * u                  # the sheer rises to bow and stern
        keel = -0.22 + 0.30 * abs(u) ** 3          # and the keel towards them
        x = u * L / 2
        if inner:   # inside the outer hull, ending short of the stems (a small deck closes each end)
            ui = 0.9 * u
            half = 0.88 * 0.5 * B * max(0.0, 1.0 - abs(ui) ** 2.4) ** 0.55
            top = 0.26 + 0.14 * ui * ui
            keel = top - (top - (-0.22 + 0.30 * abs(ui) ** 3)) * 0.82
            x = ui * L / 2
        pts = []
        for j in range(M + 1):
            phi = math.pi * j / M
            pts.append((x, top + (keel - top) * math.sin(phi), half * math.cos(phi)))
        return pts

    grid = {}
    for inner in (0, 1):
        for i in range(N + 1):
            u = -1.0 + 2.0 * i / N
            for j, p in enumerate(section(u, inner)):
                grid[inner, i, j] = m.vert(p)
    # a parametric grid wound one way throughout is oriented consistently:
    # the sign is settled once, on the outer hull's bottom amidships (its
    # normal must point down), and the inner hull faces the other way
    def raw_normal(a, b, c):
        return cross(sub(m.v[b], m.v[a]), sub(m.v[c], m.v[a]))
    mid = (grid[0, N // 2, M // 2], grid[0, N // 2 + 1, M // 2], grid[0, N // 2 + 1, M // 2 + 1])
    flip = raw_normal(*mid)[1] > 0
    for inner in (0, 1):
        for i in range(N):
            for j in range(M):
                a, b = grid[inner, i, j], grid[inner, i + 1, j]
                c, d = grid[inner, i + 1, j + 1], grid[inner, i, j + 1]
                if flip != bool(inner):
                    a, b, c, d = d, c, b, a
                for tri in ((a, b, c), (a, c, d)):
                    n = raw_normal(*tri)
                    if dot(n, n) > 1e-20:
                        m.f.append(tri)
    for i in range(N):                          # the gunwale: outer to inner top edges, facing up
        for j in (0, M):
            m.quad(grid[0, i, j], grid[0, i + 1, j], grid[1, i + 1, j], grid[1, i, j], (0.0, 1.0, 0.0))
    for i, sign in ((0, -1.0), (N, 1.0)):       # the inner hull's ends: a bulkhead, a deck to the stem
        cen = m.vert((m.v[grid[1, i, 0]][0], m.v[grid[1, i, 0]][1], 0.0))
        for j in range(M):
            m.tri(cen, grid[1, i, j], grid[1, i, j + 1], (-sign, 0.0, 0.0))
        m.tri(grid[0, i, 0], grid[1, i, 0], grid[1, i, M], (0.0, 1.0, 0.0))
    for x in (-0.45, 0.55):                     # two thwarts (seats)
        m.box((x - 0.12, 0.12, -0.46), (x + 0.12, 0.16, 0.46))
    return m


def hash01(i):
    """A fixed hash of an integer to [0, 1) (lowbias32)."""
    x = i & 0xffffffff
    x ^= x >> 16
    x = (x * 0x7feb352d) & 0xffffffff
    x ^= x >> 15
    x = (x * 0x846ca68b) & 0xffffffff
    x ^= x >> 16
    return x / 4294967296.0


def rock():
    """A boulder about 1.6 m across: an icosahedron subdivided twice, its
    vertices pushed in and out by a smooth bumpy function, squashed to
    0.6 of its height. Origin: its middle."""
    t = (1 + 5 ** 0.5) / 2
    verts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
             (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    verts = [tuple(c / math.sqrt(dot(v, v)) for c in v) for v in verts]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
             (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(2):
        cache, nf = {}, []

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                p = [(verts[a][k] + verts[b][k]) / 2 for k in range(3)]
                n = math.sqrt(dot(p, p))
                verts.append(tuple(c / n for c in p))
                cache[key] = len(verts) - 1
            return cache[key]
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = nf
    m = Mesh()
    for k, v in enumerate(verts):
        bump = 0.18 * math.sin(3.1 * v[0] + 1.3) * math.sin(2.7 * v[2] + 0.4) + 0.10 * math.sin(5.3 * v[1] + 2.0 * v[0])
        r = 0.8 * (1.0 + bump + 0.06 * (hash01(k) - 0.5))
        m.vert((r * v[0], 0.6 * r * v[1], r * v[2]))
    for a, b, c in faces:
        cen = [(m.v[a][k] + m.v[b][k] + m.v[c][k]) / 3 for k in range(3)]
        m.tri(a, b, c, tuple(cen))
    return m


def pier():
    """A pier section 4 m long (along -x from its origin), 1.2 m wide: six
    deck planks 0.06 m thick with gaps between, two stringers under them and
    four posts 2.6 m down. Origin: the top of the deck at its landward end."""
    m = Mesh()
    for k in range(6):                          # planks across the length, gaps of 2 cm
        z0 = -0.6 + k * 0.2 + 0.01
        m.box((-4.0, -0.06, z0), (0.0, 0.0, z0 + 0.18))
    for z in (-0.45, 0.45):                     # stringers under the planks
        m.box((-4.0, -0.22, z - 0.05), (0.0, -0.06, z + 0.05))
    for x in (-0.3, -3.7):                      # posts
        for z in (-0.5, 0.5):
            m.box((x - 0.08, -2.6, z - 0.08), (x + 0.08, -0.06, z + 0.08))
    return m


def main():
    os.makedirs(OUT, exist_ok=True)
    boat().write(os.path.join(OUT, "boat.obj"), "a rowing boat, 3 m, origin at the waterline amidships")
    rock().write(os.path.join(OUT, "rock.obj"), "a boulder about 1.6 m across, origin at its middle")
    pier().write(os.path.join(OUT, "pier.obj"), "a pier section 4 m long along -x, origin at the deck's top, landward end")


if __name__ == "__main__":
    main()
