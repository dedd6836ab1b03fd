/* geom_soccerball.c: glman's Soccerball, the truncated icosahedron on a
 * sphere, one part a face (geom.h). */
#include "geom_build.h"
#include "mem.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- Soccerball: the truncated icosahedron on a sphere ---- */

#define BALL_SUB 4   /* each fan triangle of a face cut in 4 x 4, so the face bulges with the sphere */

/* The icosahedron (edge 2): its 12 vertices, 20 faces wound outward. */
static int icosahedron(double v[12][3], int f[20][3]) {
    const double g = (1 + sqrt(5.0)) / 2;
    int k = 0;
    for (int a = -1; a <= 1; a += 2)
        for (int b = -1; b <= 1; b += 2) {
            v3set(v[k++], 0, a, b * g);
            v3set(v[k++], a, b * g, 0);
            v3set(v[k++], b * g, 0, a);
        }
    int nf = 0;
    for (int i = 0; i < 12; i++)
        for (int j = i + 1; j < 12; j++)
            for (int l = j + 1; l < 12; l++) {
                double d1[3], d2[3], d3[3];
                for (int c = 0; c < 3; c++) { d1[c] = v[j][c] - v[i][c]; d2[c] = v[l][c] - v[i][c]; d3[c] = v[l][c] - v[j][c]; }
                if (fabs(v3len(d1) - 2) > 1e-9 || fabs(v3len(d2) - 2) > 1e-9 || fabs(v3len(d3) - 2) > 1e-9 || nf >= 20)
                    continue;
                double cr[3], ctr[3] = {v[i][0] + v[j][0] + v[l][0], v[i][1] + v[j][1] + v[l][1],
                                         v[i][2] + v[j][2] + v[l][2]};
                v3cross(cr, d1, d2);
                bool out = vec3_dot(cr, ctr) > 0;
                f[nf][0] = i;
                f[nf][1] = out ? j : l;
                f[nf][2] = out ? l : j;
                nf++;
            }
    return nf;
}

/* The point a third of the way from a to b. */
static void third(double r[3], const double a[3], const double b[3]) {
    for (int c = 0; c < 3; c++) r[c] = a[c] + (b[c] - a[c]) / 3;
}

/* A unit vector towards the north pole (+y) in the plane normal to n. */
static void north_of(double t[3], const double n[3]) {
    v3set(t, -n[0] * n[1], 1 - n[1] * n[1], -n[2] * n[1]);
    if (!v3normalize(t)) geom_any_perpendicular(t, n);
}

/* One flat face (corners cw[0..nc-1], wound outward) as part of the mesh:
 * fans from its centre, subdivided, pushed out to radius r. */
static void ball_face(mb *b, const double (*cw)[3], int nc, double r) {
    double o[3] = {0, 0, 0};
    for (int k = 0; k < nc; k++)
        for (int c = 0; c < 3; c++) o[c] += cw[k][c] / nc;
    double d0[3] = {cw[0][0] - o[0], cw[0][1] - o[1], cw[0][2] - o[2]};
    double radius = v3len(d0), fn[3] = {o[0], o[1], o[2]}, e1[3], e2[3];
    v3normalize(fn);
    north_of(e2, fn);               /* t runs up the face, s across */
    v3cross(e1, e2, fn);
    for (int k = 0; k < nc; k++) {
        const double *a = cw[k], *c2 = cw[(k + 1) % nc];
        int base = b->m.nvert;
        for (int i = 0; i <= BALL_SUB; i++)
            for (int j = 0; j <= i; j++) {
                double q[3], d[3];
                for (int c = 0; c < 3; c++) {
                    q[c] = o[c] + (a[c] - o[c]) * i / BALL_SUB + (c2[c] - a[c]) * j / BALL_SUB;
                    d[c] = q[c] - o[c];
                }
                double n[3] = {q[0], q[1], q[2]}, p[3], t[3];
                v3normalize(n);
                v3set(p, r * n[0], r * n[1], r * n[2]);
                north_of(t, n);
                b->p_next = v3len(d) / radius;
                mb_vert(b, p, n, 0.5 + 0.5 * vec3_dot(d, e1) / radius, 0.5 + 0.5 * vec3_dot(d, e2) / radius, t);
            }
#define BV(i, j) (base + (i) * ((i) + 1) / 2 + (j))
        for (int i = 0; i < BALL_SUB; i++)
            for (int j = 0; j <= i; j++) {
                mb_tri(b, BV(i, j), BV(i + 1, j), BV(i + 1, j + 1));
                if (j < i) mb_tri(b, BV(i, j), BV(i + 1, j + 1), BV(i, j + 1));
            }
#undef BV
    }
}

/* The 5 points a third of the way from vertex i to its neighbours, in
 * order around it (counter-clockwise seen from outside). */
static void pentagon(const double v[12][3], int i, double out[5][3]) {
    double n[3] = {v[i][0], v[i][1], v[i][2]}, e1[3], e2[3], ang[5];
    v3normalize(n);
    geom_any_perpendicular(e1, n);
    v3cross(e2, n, e1);
    int k = 0;
    for (int j = 0; j < 12 && k < 5; j++) {
        double d[3] = {v[j][0] - v[i][0], v[j][1] - v[i][1], v[j][2] - v[i][2]};
        if (j == i || fabs(v3len(d) - 2) > 1e-9) continue;
        third(out[k], v[i], v[j]);
        ang[k++] = atan2(vec3_dot(d, e2), vec3_dot(d, e1));
    }
    for (int a = 1; a < 5; a++)     /* insertion sort by angle */
        for (int c = a; c > 0 && ang[c] < ang[c - 1]; c--) {
            double t = ang[c]; ang[c] = ang[c - 1]; ang[c - 1] = t;
            double tmp[3];
            memcpy(tmp, out[c], sizeof tmp);
            memcpy(out[c], out[c - 1], sizeof tmp);
            memcpy(out[c - 1], tmp, sizeof tmp);
        }
}

static bool ball_parts(mb *b, int face, int **first) {
    if (face == 0) {
        *first = mem_alloc(sizeof **first * 33);
    }
    (*first)[face] = b->m.nidx;
    return true;
}

bool geom_soccerball(geom_mesh *m, float r) {
    if (!m) return false;
    memset(m, 0, sizeof *m);
    if (!geom_finite_args(1, (double)r)) return false;
    double v[12][3];
    int f[20][3];
    if (icosahedron(v, f) != 20) return false;
    mb b;
    mb_init(&b, false);
    b.with_p = true;
    int *first = NULL;
    double rr = fabs((double)r);
    for (int i = 0; i < 12 && ball_parts(&b, i, &first); i++) {   /* FaceIndex 0-11: pentagons */
        double pent[5][3];
        pentagon(v, i, pent);
        ball_face(&b, (const double (*)[3])pent, 5, rr);
    }
    for (int t = 0; t < 20 && b.ok && ball_parts(&b, 12 + t, &first); t++) {   /* 12-31: hexagons */
        const double *a = v[f[t][0]], *c = v[f[t][1]], *d = v[f[t][2]];
        double hex[6][3];
        third(hex[0], a, c); third(hex[1], c, a);
        third(hex[2], c, d); third(hex[3], d, c);
        third(hex[4], d, a); third(hex[5], a, d);
        ball_face(&b, (const double (*)[3])hex, 6, rr);
    }
    if (first) first[32] = b.m.nidx;
    if (!mb_finish(&b, m)) { free(first); return false; }
    m->part_first = first;
    m->nparts = 32;
    return true;
}
