/* geom_build: what the geometry files (geom_*.c) share, private to them:
 * double vectors, the mesh builder (mb: vertices with their frames,
 * indices, growing as needed; mb_finish makes the frames unit and
 * perpendicular), parametric grids, and the argument checks. */
#ifndef TARN_GEOM_BUILD_H
#define TARN_GEOM_BUILD_H

#include <math.h>
#include <stdbool.h>
#include <stddef.h>

#include "geom.h"
#include "vec3.h"   /* vec3_dot */

#define GEOM_PI 3.14159265358979323846

/* ---- small vector helpers (double; base/vec3.h has the dot product) ---- */

static inline void v3set(double r[3], double x, double y, double z) { r[0] = x; r[1] = y; r[2] = z; }
static inline void v3cross(double r[3], const double a[3], const double b[3]) {
    double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2], z = a[0] * b[1] - a[1] * b[0];
    v3set(r, x, y, z);
}
static inline double v3len(const double a[3]) { return sqrt(vec3_dot(a, a)); }

/* Normalises a in place; false (a untouched) when it has no direction. */
static inline bool v3normalize(double a[3]) {
    double l = v3len(a);
    if (!(l > 1e-30) || !isfinite(l)) return false;
    a[0] /= l; a[1] /= l; a[2] /= l;
    return true;
}

/* ---- mesh builder ---- */

typedef struct mb {
    geom_mesh m;
    int vcap, icap;
    bool ok;
    bool with_p;                /* the mesh has tcp: mb_vert stores p_next */
    double p_next;
} mb;

void mb_init_prim(mb *b, geom_prim prim);
void mb_init(mb *b, bool lines);          /* GEOM_LINES or GEOM_TRIANGLES */
void geom_grow(void **p, size_t elem, int cap);
/* Makes room for `nv` more vertices and `ni` more indices; false (and the
 * builder failed) past the limits. */
bool mb_reserve(mb *b, long nv, long ni);
int mb_vert(mb *b, const double p[3], const double n[3], double u, double v, const double t[3]);
void mb_index(mb *b, int a);
void mb_tri(mb *b, int a, int c, int d);
void mb_line(mb *b, int a, int c);
/* Any unit vector perpendicular to the unit vector n. */
void geom_any_perpendicular(double t[3], const double n[3]);
/* The mesh, frames fixed, in out; false and out empty when the builder failed. */
bool mb_finish(mb *b, geom_mesh *out);

/* ---- parametric grids ---- */

typedef void (*grid_fn)(const void *ctx, int i, int j, double p[3], double n[3], double t[3],
                        double tc[2]);

enum {
    GRID_CLOSED_U = 1,      /* column nu repeats column 0 (a seam): no second wire line */
    GRID_COLLAPSED_V0 = 2,  /* row 0 is one point (a pole): no degenerate triangles */
    GRID_COLLAPSED_V1 = 4   /* row nv is one point */
};

/* (nu+1) x (nv+1) vertices; f must make dP/du x dP/dv point along the
 * normal so that the triangles wind counter-clockwise from outside. */
void geom_grid(mb *b, int nu, int nv, grid_fn f, const void *ctx, int flags);

/* n, or dflt when n <= 0, clamped to [lo, hi]. */
int geom_clamp_div(int n, int dflt, int lo, int hi);
/* Are all `count` double arguments finite? */
bool geom_finite_args(int count, ...);
/* sin/cos of 2pi i/n, exact at the seam (i == n gives the same as i == 0). */
void geom_angle(int i, int n, double *s, double *c);

#endif
