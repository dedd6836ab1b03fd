/* geom_teapot.c: the Newell teapot as glutSolidTeapot places it (geom.h). */
#include "geom_build.h"

#include <math.h>
#include <string.h>

/* ---- the Newell teapot ---- */

/* Martin Newell's teapot (1975, public domain) as 10 bicubic Bezier
 * patches of one quadrant (rim, body, lid, bottom) or one half (handle,
 * spout), z up; mirrored in x and y they make the 32 patches. */
static const float teapot_cp[][3] = {
    {1.4f, 0.0f, 2.4f}, {1.4f, -0.784f, 2.4f}, {0.784f, -1.4f, 2.4f}, {0.0f, -1.4f, 2.4f},
    {1.3375f, 0.0f, 2.53125f}, {1.3375f, -0.749f, 2.53125f}, {0.749f, -1.3375f, 2.53125f},
    {0.0f, -1.3375f, 2.53125f}, {1.4375f, 0.0f, 2.53125f}, {1.4375f, -0.805f, 2.53125f},
    {0.805f, -1.4375f, 2.53125f}, {0.0f, -1.4375f, 2.53125f}, {1.5f, 0.0f, 2.4f},
    {1.5f, -0.84f, 2.4f}, {0.84f, -1.5f, 2.4f}, {0.0f, -1.5f, 2.4f}, {1.75f, 0.0f, 1.875f},
    {1.75f, -0.98f, 1.875f}, {0.98f, -1.75f, 1.875f}, {0.0f, -1.75f, 1.875f},
    {2.0f, 0.0f, 1.35f}, {2.0f, -1.12f, 1.35f}, {1.12f, -2.0f, 1.35f}, {0.0f, -2.0f, 1.35f},
    {2.0f, 0.0f, 0.9f}, {2.0f, -1.12f, 0.9f}, {1.12f, -2.0f, 0.9f}, {0.0f, -2.0f, 0.9f},
    {2.0f, 0.0f, 0.45f}, {2.0f, -1.12f, 0.45f}, {1.12f, -2.0f, 0.45f}, {0.0f, -2.0f, 0.45f},
    {1.5f, 0.0f, 0.225f}, {1.5f, -0.84f, 0.225f}, {0.84f, -1.5f, 0.225f},
    {0.0f, -1.5f, 0.225f}, {1.5f, 0.0f, 0.15f}, {1.5f, -0.84f, 0.15f}, {0.84f, -1.5f, 0.15f},
    {0.0f, -1.5f, 0.15f}, {0.0f, 0.0f, 3.15f}, {0.0f, 0.0f, 3.15f}, {0.0f, 0.0f, 3.15f},
    {0.8f, 0.0f, 3.15f}, {0.8f, -0.45f, 3.15f}, {0.45f, -0.8f, 3.15f}, {0.0f, -0.8f, 3.15f},
    {0.0f, 0.0f, 2.85f}, {0.2f, 0.0f, 2.7f}, {0.2f, -0.112f, 2.7f}, {0.112f, -0.2f, 2.7f},
    {0.0f, -0.2f, 2.7f}, {0.4f, 0.0f, 2.55f}, {0.4f, -0.224f, 2.55f}, {0.224f, -0.4f, 2.55f},
    {0.0f, -0.4f, 2.55f}, {1.3f, 0.0f, 2.55f}, {1.3f, -0.728f, 2.55f}, {0.728f, -1.3f, 2.55f},
    {0.0f, -1.3f, 2.55f}, {1.3f, 0.0f, 2.4f}, {1.3f, -0.728f, 2.4f}, {0.728f, -1.3f, 2.4f},
    {0.0f, -1.3f, 2.4f}, {0.0f, 0.0f, 0.0f}, {0.0f, -1.425f, 0.0f}, {0.798f, -1.425f, 0.0f},
    {1.425f, -0.798f, 0.0f}, {1.425f, 0.0f, 0.0f}, {0.0f, -1.5f, 0.075f},
    {0.84f, -1.5f, 0.075f}, {1.5f, -0.84f, 0.075f}, {1.5f, 0.0f, 0.075f},
    {-1.6f, 0.0f, 2.025f}, {-1.6f, -0.3f, 2.025f}, {-1.5f, -0.3f, 2.25f}, {-1.5f, 0.0f, 2.25f},
    {-2.3f, 0.0f, 2.025f}, {-2.3f, -0.3f, 2.025f}, {-2.5f, -0.3f, 2.25f}, {-2.5f, 0.0f, 2.25f},
    {-2.7f, 0.0f, 2.025f}, {-2.7f, -0.3f, 2.025f}, {-3.0f, -0.3f, 2.25f}, {-3.0f, 0.0f, 2.25f},
    {-2.7f, 0.0f, 1.8f}, {-2.7f, -0.3f, 1.8f}, {-3.0f, -0.3f, 1.8f}, {-3.0f, 0.0f, 1.8f},
    {-2.7f, 0.0f, 1.575f}, {-2.7f, -0.3f, 1.575f}, {-3.0f, -0.3f, 1.35f}, {-3.0f, 0.0f, 1.35f},
    {-2.5f, 0.0f, 1.125f}, {-2.5f, -0.3f, 1.125f}, {-2.65f, -0.3f, 0.9375f},
    {-2.65f, 0.0f, 0.9375f}, {-2.0f, 0.0f, 0.9f}, {-2.0f, -0.3f, 0.9f}, {-1.9f, -0.3f, 0.6f},
    {-1.9f, 0.0f, 0.6f}, {1.7f, 0.0f, 1.425f}, {1.7f, -0.66f, 1.425f}, {1.7f, -0.66f, 0.6f},
    {1.7f, 0.0f, 0.6f}, {2.6f, 0.0f, 1.425f}, {2.6f, -0.66f, 1.425f}, {3.1f, -0.66f, 0.825f},
    {3.1f, 0.0f, 0.825f}, {2.3f, 0.0f, 2.1f}, {2.3f, -0.25f, 2.1f}, {2.4f, -0.25f, 2.025f},
    {2.4f, 0.0f, 2.025f}, {2.7f, 0.0f, 2.4f}, {2.7f, -0.25f, 2.4f}, {3.3f, -0.25f, 2.4f},
    {3.3f, 0.0f, 2.4f}, {2.8f, 0.0f, 2.475f}, {2.8f, -0.25f, 2.475f},
    {3.525f, -0.25f, 2.49375f}, {3.525f, 0.0f, 2.49375f}, {2.9f, 0.0f, 2.475f},
    {2.9f, -0.15f, 2.475f}, {3.45f, -0.15f, 2.5125f}, {3.45f, 0.0f, 2.5125f},
    {2.8f, 0.0f, 2.4f}, {2.8f, -0.15f, 2.4f}, {3.2f, -0.15f, 2.4f}, {3.2f, 0.0f, 2.4f},
};

/* Control point indices, 4 rows of 4; u runs along a row, v across rows. */
static const unsigned char teapot_patch[10][16] = {
    {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15},                 /* rim */
    {12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27},       /* body */
    {24, 25, 26, 27, 28, 29, 30, 31, 32, 33, 34, 35, 36, 37, 38, 39},
    {40, 41, 42, 40, 43, 44, 45, 46, 47, 47, 47, 47, 48, 49, 50, 51},       /* lid */
    {48, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59, 60, 61, 62, 63},
    {64, 64, 64, 64, 65, 66, 67, 68, 69, 70, 71, 72, 39, 38, 37, 36},       /* bottom */
    {73, 74, 75, 76, 77, 78, 79, 80, 81, 82, 83, 84, 85, 86, 87, 88},       /* handle */
    {85, 86, 87, 88, 89, 90, 91, 92, 93, 94, 95, 96, 97, 98, 99, 100},
    {101, 102, 103, 104, 105, 106, 107, 108, 109, 110, 111, 112, 113, 114, 115, 116}, /* spout */
    {113, 114, 115, 116, 117, 118, 119, 120, 121, 122, 123, 124, 125, 126, 127, 128},
};
#define TEAPOT_QUADRANT_PATCHES 6   /* the first 6 mirror 4 ways, the rest 2 */

typedef struct patch_ctx {
    double cp[4][4][3];     /* [row (v)][column (u)] */
    double scale;
    int n;
} patch_ctx;

static void bernstein(double t, double b[4], double db[4]) {
    double s = 1 - t;
    b[0] = s * s * s; b[1] = 3 * t * s * s; b[2] = 3 * t * t * s; b[3] = t * t * t;
    db[0] = -3 * s * s; db[1] = 3 * s * s - 6 * t * s; db[2] = 6 * t * s - 3 * t * t; db[3] = 3 * t * t;
}

static void patch_point(const patch_ctx *q, double u, double v, double p[3], double pu[3], double pv[3]) {
    double bu[4], dbu[4], bv[4], dbv[4];
    bernstein(u, bu, dbu);
    bernstein(v, bv, dbv);
    for (int c = 0; c < 3; c++) {
        p[c] = pu[c] = pv[c] = 0;
        for (int a = 0; a < 4; a++)
            for (int k = 0; k < 4; k++) {
                double x = q->cp[a][k][c];
                p[c] += bv[a] * bu[k] * x;
                pu[c] += bv[a] * dbu[k] * x;
                pv[c] += dbv[a] * bu[k] * x;
            }
    }
}

static void patch_eval(const void *vctx, int i, int j, double p[3], double n[3], double t[3], double tc[2]) {
    const patch_ctx *q = vctx;
    double u = (double)i / q->n, v = (double)j / q->n, pu[3], pv[3], zp[3];
    patch_point(q, u, v, zp, pu, pv);
    v3cross(n, pu, pv);
    if (v3len(n) < 1e-9) {
        /* a collapsed edge (the lid's knob, the bottom's centre): take the
         * limit from just inside the patch */
        const double e = 1e-5;
        double pu2[3], pv2[3], p2[3];
        patch_point(q, u < 0.5 ? u + e : u - e, v < 0.5 ? v + e : v - e, p2, pu2, pv2);
        v3cross(n, pu2, pv2);
        if (v3len(pu) < 1e-9) memcpy(pu, pu2, sizeof pu2);
    }
    /* z up -> y up as glutSolidTeapot: rotate -90 about x, scale 0.5, drop 1.5 */
    v3set(p, q->scale * zp[0], q->scale * (zp[2] - 1.5), -q->scale * zp[1]);
    double nn[3] = {n[0], n[2], -n[1]};
    memcpy(n, nn, sizeof nn);
    v3set(t, pu[0], pu[2], -pu[1]);
    tc[0] = u;
    tc[1] = v;
}

static bool row_collapsed(const patch_ctx *q, int row) {
    for (int k = 1; k < 4; k++)
        for (int c = 0; c < 3; c++)
            if (q->cp[row][k][c] != q->cp[row][0][c]) return false;
    return true;
}

bool geom_teapot(geom_mesh *m, float size, int grid_n, bool wire) {
    if (!m) return false;
    memset(m, 0, sizeof *m);
    if (!geom_finite_args(1, (double)size)) return false;
    patch_ctx q;
    q.scale = 0.5 * fabs((double)size);
    q.n = geom_clamp_div(grid_n, 10, 1, GEOM_MAX_TEAPOT_GRID);
    static const double mirror[4][2] = {{1, 1}, {1, -1}, {-1, 1}, {-1, -1}};
    mb b;
    mb_init(&b, wire);
    for (int pi = 0; pi < 10; pi++) {
        int copies = pi < TEAPOT_QUADRANT_PATCHES ? 4 : 2;
        for (int mi = 0; mi < copies; mi++) {
            double sx = mirror[mi][0], sy = mirror[mi][1];
            bool flip = sx * sy < 0;    /* a mirror image: reverse u to keep outward normals */
            for (int a = 0; a < 4; a++)
                for (int k = 0; k < 4; k++) {
                    const float *c = teapot_cp[teapot_patch[pi][4 * a + (flip ? 3 - k : k)]];
                    v3set(q.cp[a][k], sx * c[0], sy * c[1], c[2]);
                }
            int flags = (row_collapsed(&q, 0) ? GRID_COLLAPSED_V0 : 0) |
                        (row_collapsed(&q, 3) ? GRID_COLLAPSED_V1 : 0);
            geom_grid(&b, q.n, q.n, patch_eval, &q, flags);
        }
    }
    return mb_finish(&b, m);
}
