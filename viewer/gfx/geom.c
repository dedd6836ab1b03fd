/* geom.c: meshes for glman's geometry commands (see geom.h). */
#include "geom.h"
#include "file.h"
#include "mem.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GEOM_PI 3.14159265358979323846

/* ---- small vector helpers (double) ---- */

static void v3set(double r[3], double x, double y, double z) { r[0] = x; r[1] = y; r[2] = z; }
static double v3dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void v3cross(double r[3], const double a[3], const double b[3]) {
    double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2], z = a[0] * b[1] - a[1] * b[0];
    v3set(r, x, y, z);
}
static double v3len(const double a[3]) { return sqrt(v3dot(a, a)); }

/* Normalises a in place; false (a untouched) when it has no direction. */
static bool v3normalize(double a[3]) {
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

static void mb_init_prim(mb *b, geom_prim prim) {
    memset(b, 0, sizeof *b);
    b->ok = true;
    b->m.prim = prim;
}

static void mb_init(mb *b, bool lines) { mb_init_prim(b, lines ? GEOM_LINES : GEOM_TRIANGLES); }

static void grow(void **p, size_t elem, int cap) {
    *p = mem_realloc(*p, elem * (size_t)cap);
}

/* Makes room for `nv` more vertices and `ni` more indices. */
static bool mb_reserve(mb *b, long nv, long ni) {
    if (!b->ok) return false;
    long need_v = b->m.nvert + nv, need_i = b->m.nidx + ni;
    if (need_v > INT_MAX / 4 || need_i > INT_MAX / 4) { b->ok = false; return false; }
    if (need_v > b->vcap) {
        int cap = b->vcap ? b->vcap : 64;
        while (cap < need_v) cap = cap > INT_MAX / 8 ? (int)need_v : cap * 2;
        grow((void **)&b->m.pos, 3 * sizeof(float), cap);
        grow((void **)&b->m.nrm, 3 * sizeof(float), cap);
        grow((void **)&b->m.tc, 2 * sizeof(float), cap);
        grow((void **)&b->m.tan, 3 * sizeof(float), cap);
        if (b->with_p) grow((void **)&b->m.tcp, sizeof(float), cap);
        b->vcap = cap;
    }
    if (need_i > b->icap) {
        int cap = b->icap ? b->icap : 64;
        while (cap < need_i) cap = cap > INT_MAX / 8 ? (int)need_i : cap * 2;
        grow((void **)&b->m.idx, sizeof(unsigned), cap);
        b->icap = cap;
    }
    return true;
}

static int mb_vert(mb *b, const double p[3], const double n[3], double u, double v, const double t[3]) {
    if (!mb_reserve(b, 1, 0)) return 0;
    int k = b->m.nvert++;
    for (int c = 0; c < 3; c++) {
        b->m.pos[3 * k + c] = (float)p[c];
        b->m.nrm[3 * k + c] = (float)n[c];
        b->m.tan[3 * k + c] = (float)t[c];
    }
    b->m.tc[2 * k] = (float)u;
    b->m.tc[2 * k + 1] = (float)v;
    if (b->with_p) b->m.tcp[k] = (float)b->p_next;
    return k;
}

static void mb_index(mb *b, int a) {
    if (!mb_reserve(b, 0, 1)) return;
    b->m.idx[b->m.nidx++] = (unsigned)a;
}

static void mb_tri(mb *b, int a, int c, int d) { mb_index(b, a); mb_index(b, c); mb_index(b, d); }
static void mb_line(mb *b, int a, int c) { mb_index(b, a); mb_index(b, c); }

void geom_free(geom_mesh *m) {
    if (!m) return;
    free(m->pos); free(m->nrm); free(m->tc); free(m->tan); free(m->idx);
    free(m->tcp); free(m->part_first);
    memset(m, 0, sizeof *m);
}

/* Any unit vector perpendicular to the unit vector n. */
static void any_perpendicular(double t[3], const double n[3]) {
    double a[3];
    if (fabs(n[0]) < 0.9) v3set(a, 1, 0, 0); else v3set(a, 0, 1, 0);
    double d = v3dot(a, n);
    v3set(t, a[0] - d * n[0], a[1] - d * n[1], a[2] - d * n[2]);
    if (!v3normalize(t)) v3set(t, 1, 0, 0);
}

/* Unit normals (fallback +y) and unit tangents made perpendicular to them
 * (Gram-Schmidt; fallback any perpendicular): never NaN. */
static void fix_frames(geom_mesh *m) {
    for (int k = 0; k < m->nvert; k++) {
        double n[3] = {m->nrm[3 * k], m->nrm[3 * k + 1], m->nrm[3 * k + 2]};
        double t[3] = {m->tan[3 * k], m->tan[3 * k + 1], m->tan[3 * k + 2]};
        if (!v3normalize(n)) v3set(n, 0, 1, 0);
        double d = v3dot(t, n);
        double g[3] = {t[0] - d * n[0], t[1] - d * n[1], t[2] - d * n[2]};
        if (!isfinite(d) || v3len(g) < 1e-6 * (v3len(t) + 1e-30) || !v3normalize(g))
            any_perpendicular(g, n);
        for (int c = 0; c < 3; c++) { m->nrm[3 * k + c] = (float)n[c]; m->tan[3 * k + c] = (float)g[c]; }
    }
}

static bool mb_finish(mb *b, geom_mesh *out) {
    if (!b->ok) {
        geom_free(&b->m);
        memset(out, 0, sizeof *out);
        return false;
    }
    fix_frames(&b->m);
    *out = b->m;
    return true;
}

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
static void grid(mb *b, int nu, int nv, grid_fn f, const void *ctx, int flags) {
    long nvert = (long)(nu + 1) * (nv + 1);
    long nidx = b->m.prim == GEOM_LINES ? 2L * ((long)nu * (nv + 1) + (long)(nu + 1) * nv) : 6L * nu * nv;
    if (!mb_reserve(b, nvert, nidx)) return;
    int base = b->m.nvert;
    for (int j = 0; j <= nv; j++)
        for (int i = 0; i <= nu; i++) {
            double p[3], n[3], t[3], tc[2];
            f(ctx, i, j, p, n, t, tc);
            mb_vert(b, p, n, tc[0], tc[1], t);
        }
#define GV(i, j) (base + (j) * (nu + 1) + (i))
    if (b->m.prim != GEOM_LINES) {
        for (int j = 0; j < nv; j++)
            for (int i = 0; i < nu; i++) {
                int a = GV(i, j), c = GV(i + 1, j), d = GV(i + 1, j + 1), e = GV(i, j + 1);
                if (!(j == 0 && (flags & GRID_COLLAPSED_V0))) mb_tri(b, a, c, d);
                if (!(j == nv - 1 && (flags & GRID_COLLAPSED_V1))) mb_tri(b, a, d, e);
            }
    } else {
        for (int j = 0; j <= nv; j++) {
            if ((j == 0 && (flags & GRID_COLLAPSED_V0)) || (j == nv && (flags & GRID_COLLAPSED_V1)))
                continue;
            for (int i = 0; i < nu; i++) mb_line(b, GV(i, j), GV(i + 1, j));
        }
        for (int i = 0; i <= nu; i++) {
            if (i == nu && (flags & GRID_CLOSED_U)) continue;
            for (int j = 0; j < nv; j++) mb_line(b, GV(i, j), GV(i, j + 1));
        }
    }
#undef GV
}

static int clamp_div(int n, int dflt, int lo, int hi) {
    if (n <= 0) n = dflt;
    if (n < lo) n = lo;
    if (n > hi) n = hi;
    return n;
}

static bool finite_args(int count, ...) {
    va_list ap;
    va_start(ap, count);
    bool ok = true;
    for (int k = 0; k < count; k++) ok = ok && isfinite(va_arg(ap, double));
    va_end(ap);
    return ok;
}

/* sin/cos of 2pi i/n, exact at the seam (i == n gives the same as i == 0). */
static void angle(int i, int n, double *s, double *c) {
    double a = 2.0 * GEOM_PI * (double)(i % n) / (double)n;
    *s = sin(a);
    *c = cos(a);
}

/* ---- quads and boxes ---- */

typedef struct plane_ctx {
    double N[3], U[3], V[3];
    double offset, su, sv;
    int nu, nv;
} plane_ctx;

static void plane_eval(const void *vctx, int i, int j, double p[3], double n[3], double t[3], double tc[2]) {
    const plane_ctx *q = vctx;
    double s = -1.0 + 2.0 * i / q->nu, r = -1.0 + 2.0 * j / q->nv;
    for (int c = 0; c < 3; c++) {
        p[c] = q->offset * q->N[c] + s * q->su * q->U[c] + r * q->sv * q->V[c];
        n[c] = q->N[c];
        t[c] = q->U[c];
    }
    tc[0] = (double)i / q->nu;
    tc[1] = (double)j / q->nv;
}

/* The (N, U, V) frame of each face, U x V = N. */
static void face_frame(plane_ctx *q, int axis, bool negative) {
    static const double frames[6][3][3] = {
        /*  N            U            V  */
        {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},     /* +x: upright seen from +x */
        {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},     /* +y: upright seen from above */
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},      /* +z */
        {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},     /* -x */
        {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},     /* -y: upright seen from below */
        {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},    /* -z */
    };
    const double (*f)[3] = frames[axis + (negative ? 3 : 0)];
    memcpy(q->N, f[0], sizeof q->N);
    memcpy(q->U, f[1], sizeof q->U);
    memcpy(q->V, f[2], sizeof q->V);
}

bool geom_quad(geom_mesh *m, int axis, float offset, float size, int n1, int n2, bool wire) {
    if (!m) return false;
    memset(m, 0, sizeof *m);
    if (axis < 0 || axis > 2 || !finite_args(2, (double)offset, (double)size)) return false;
    plane_ctx q;
    face_frame(&q, axis, false);
    q.offset = offset;
    q.su = q.sv = fabs((double)size);
    n1 = clamp_div(n1, 1, 1, GEOM_MAX_DIV);
    n2 = clamp_div(n2, 1, 1, GEOM_MAX_DIV);
    /* the glib's counts are along (x,y), (x,z), (y,z); U of QuadYZ is z */
    q.nu = axis == 0 ? n2 : n1;
    q.nv = axis == 0 ? n1 : n2;
    mb b;
    mb_init(&b, wire);
    grid(&b, q.nu, q.nv, plane_eval, &q, 0);
    return mb_finish(&b, m);
}

/* Moves vertex v of each per-vertex array to remap[v]. */
static void permute_floats(float **a, int per, const int *remap, int nvert) {
    if (!*a) return;
    float *out = mem_alloc((size_t)nvert * per * sizeof(float));
    for (int v = 0; v < nvert; v++) memcpy(out + (size_t)remap[v] * per, *a + (size_t)v * per, per * sizeof(float));
    free(*a);
    *a = out;
}

bool geom_grid_bands(geom_mesh *m, int nu, int nv, int band) {
    if (!m || m->prim != GEOM_TRIANGLES || m->part_first || nu < 1 || nv < 1 || band < 1 ||
        (long)m->nidx != 6L * nu * nv || (long)m->nvert != (long)(nu + 1) * (nv + 1))
        return false;
    unsigned *idx = mem_alloc((size_t)m->nidx * sizeof(unsigned));
    int n = 0;
    for (int b0 = 0; b0 < nu; b0 += band)
        for (int j = 0; j < nv; j++)
            for (int i = b0; i < b0 + band && i < nu; i++, n += 6)
                memcpy(idx + n, m->idx + 6L * ((long)j * nu + i), 6 * sizeof(unsigned));
    int *remap = mem_alloc((size_t)m->nvert * sizeof(int)), next = 0;
    for (int v = 0; v < m->nvert; v++) remap[v] = -1;
    for (int k = 0; k < n; k++) {
        if (remap[idx[k]] < 0) remap[idx[k]] = next++;
        idx[k] = (unsigned)remap[idx[k]];
    }
    for (int v = 0; v < m->nvert; v++)   /* none in a whole grid; kept for safety */
        if (remap[v] < 0) remap[v] = next++;
    permute_floats(&m->pos, 3, remap, m->nvert);
    permute_floats(&m->nrm, 3, remap, m->nvert);
    permute_floats(&m->tan, 3, remap, m->nvert);
    permute_floats(&m->tc, 2, remap, m->nvert);
    permute_floats(&m->tcp, 1, remap, m->nvert);
    free(remap);
    free(m->idx);
    m->idx = idx;
    return true;
}

bool geom_box(geom_mesh *m, float dx, float dy, float dz, bool wire) {
    if (!m) return false;
    memset(m, 0, sizeof *m);
    if (!finite_args(3, (double)dx, (double)dy, (double)dz)) return false;
    double half[3] = {fabs((double)dx) / 2, fabs((double)dy) / 2, fabs((double)dz) / 2};
    mb b;
    mb_init(&b, wire);
    for (int f = 0; f < 6; f++) {
        plane_ctx q;
        face_frame(&q, f % 3, f >= 3);
        int an = f % 3, au = 0, av = 0;
        for (int c = 0; c < 3; c++) {
            if (q.U[c] != 0) au = c;
            if (q.V[c] != 0) av = c;
        }
        q.offset = half[an];
        q.su = half[au];
        q.sv = half[av];
        q.nu = q.nv = 1;
        grid(&b, 1, 1, plane_eval, &q, 0);
    }
    return mb_finish(&b, m);
}

/* ---- sphere ---- */

typedef struct round_ctx {
    double r, r2, h;
    int nu, nv;
} round_ctx;

static void sphere_eval(const void *vctx, int i, int j, double p[3], double n[3], double t[3], double tc[2]) {
    const round_ctx *q = vctx;
    double sa, ca, sp, cp;
    /* The course's sphere (Bailey's MjbSphere / OsuSphere): s = (lng + pi) /
     * 2pi with the point at (cos lng, ., -sin lng): the seam (s = 0 and 1)
     * at -x, s = 0.25 at +z (towards glman's default camera), s = 0.5 at +x,
     * s increasing eastwards seen from outside. As tarn's longitude from +z
     * towards +x that is lon = 2pi s - pi/2: sin lon = -cos a, cos lon = sin a,
     * exact at the quarter turns. */
    angle(i, q->nu, &sa, &ca);
    double st = -ca, ct = sa;
    if (j == 0) { sp = -1; cp = 0; }
    else if (j == q->nv) { sp = 1; cp = 0; }
    else {
        double lat = -GEOM_PI / 2 + GEOM_PI * j / q->nv;
        sp = sin(lat);
        cp = cos(lat);
    }
    v3set(n, st * cp, sp, ct * cp);
    v3set(p, q->r * n[0], q->r * n[1], q->r * n[2]);
    v3set(t, -st * sp, cp, -ct * sp);   /* d/d(latitude): towards the north pole, as glman's */
    tc[0] = (double)i / q->nu;
    tc[1] = (double)j / q->nv;
}

bool geom_sphere(geom_mesh *m, float r, int slices, int stacks, bool wire) {
    if (!m) return false;
    memset(m, 0, sizeof *m);
    if (!finite_args(1, (double)r)) return false;
    round_ctx q = {fabs((double)r), 0, 0, clamp_div(slices, 32, 3, GEOM_MAX_DIV),
                   clamp_div(stacks, 16, 2, GEOM_MAX_DIV)};
    mb b;
    mb_init(&b, wire);
    grid(&b, q.nu, q.nv, sphere_eval, &q, GRID_CLOSED_U | GRID_COLLAPSED_V0 | GRID_COLLAPSED_V1);
    return mb_finish(&b, m);
}

/* ---- torus ---- */

static void torus_eval(const void *vctx, int i, int j, double p[3], double n[3], double t[3], double tc[2]) {
    const round_ctx *q = vctx;     /* r: major, r2: minor; nu rings, nv sides */
    double st, ct, sp, cp;
    angle(i, q->nu, &st, &ct);
    angle(j, q->nv, &sp, &cp);
    double rho = q->r + q->r2 * cp;
    v3set(p, rho * ct, rho * st, q->r2 * sp);
    v3set(n, cp * ct, cp * st, sp);
    v3set(t, -st, ct, 0);
    tc[0] = (double)i / q->nu;
    tc[1] = (double)j / q->nv;
}

bool geom_torus(geom_mesh *m, float r_major, float r_minor, int sides, int rings, bool wire) {
    if (!m) return false;
    memset(m, 0, sizeof *m);
    if (!finite_args(2, (double)r_major, (double)r_minor)) return false;
    round_ctx q = {fabs((double)r_major), fabs((double)r_minor), 0,
                   clamp_div(rings, 32, 3, GEOM_MAX_DIV), clamp_div(sides, 16, 3, GEOM_MAX_DIV)};
    mb b;
    mb_init(&b, wire);
    grid(&b, q.nu, q.nv, torus_eval, &q, GRID_CLOSED_U);
    return mb_finish(&b, m);
}

/* ---- cylinder and cone ---- */

/* r: base radius, r2: top radius (cylinder r, cone 0), h: height */
static void side_eval(const void *vctx, int i, int j, double p[3], double n[3], double t[3], double tc[2]) {
    const round_ctx *q = vctx;
    double st, ct;
    angle(i, q->nu, &st, &ct);
    double f = (double)j / q->nv;
    double rho = j == q->nv ? q->r2 : q->r + (q->r2 - q->r) * f;
    double y = j == q->nv ? q->h / 2 : -q->h / 2 + q->h * f;
    v3set(p, rho * st, y, rho * ct);
    /* the slant normal: (h sin, r_base - r_top, h cos) */
    v3set(n, q->h * st, q->r - q->r2, q->h * ct);
    if (!v3normalize(n)) v3set(n, 0, 1, 0);
    v3set(t, ct, 0, -st);
    tc[0] = (double)i / q->nu;
    tc[1] = f;
}

/* A disc at height y, facing +y (top) or -y; fan of `slices` triangles. */
static void disc(mb *b, double y, double r, int slices, bool top) {
    if (!mb_reserve(b, slices + 1, 3L * slices)) return;
    double ny = top ? 1 : -1, vs = top ? -1 : 1;     /* v along -z on top, +z below */
    double p[3] = {0, y, 0}, n[3] = {0, ny, 0}, t[3] = {1, 0, 0};
    int centre = mb_vert(b, p, n, 0.5, 0.5, t);
    for (int i = 0; i < slices; i++) {
        double st, ct;
        angle(i, slices, &st, &ct);
        v3set(p, r * st, y, r * ct);
        mb_vert(b, p, n, 0.5 + 0.5 * st, 0.5 + 0.5 * vs * ct, t);
    }
    for (int i = 0; i < slices; i++) {
        int a = centre + 1 + i, c = centre + 1 + (i + 1) % slices;
        if (b->m.prim == GEOM_LINES) mb_line(b, centre, a);
        else if (top) mb_tri(b, centre, a, c);
        else mb_tri(b, centre, c, a);
    }
}

static bool round_solid(geom_mesh *m, float r, float h, int slices, int stacks, bool wire, bool cone) {
    if (!m) return false;
    memset(m, 0, sizeof *m);
    if (!finite_args(2, (double)r, (double)h)) return false;
    double rr = fabs((double)r), hh = fabs((double)h);
    round_ctx q = {rr, cone ? 0 : rr, hh, clamp_div(slices, 32, 3, GEOM_MAX_DIV),
                   clamp_div(stacks, 1, 1, GEOM_MAX_DIV)};
    mb b;
    mb_init(&b, wire);
    grid(&b, q.nu, q.nv, side_eval, &q, GRID_CLOSED_U | (cone ? GRID_COLLAPSED_V1 : 0));
    disc(&b, -hh / 2, rr, q.nu, false);
    if (!cone) disc(&b, hh / 2, rr, q.nu, true);
    return mb_finish(&b, m);
}

bool geom_cylinder(geom_mesh *m, float r, float h, int slices, int stacks, bool wire) {
    return round_solid(m, r, h, slices, stacks, wire, false);
}

bool geom_cone(geom_mesh *m, float r, float h, int slices, int stacks, bool wire) {
    return round_solid(m, r, h, slices, stacks, wire, true);
}

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
    if (!finite_args(1, (double)size)) return false;
    patch_ctx q;
    q.scale = 0.5 * fabs((double)size);
    q.n = clamp_div(grid_n, 10, 1, GEOM_MAX_TEAPOT_GRID);
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
            grid(&b, q.n, q.n, patch_eval, &q, flags);
        }
    }
    return mb_finish(&b, m);
}

/* ---- tangents from texture coordinates (OBJ) ---- */

static void tangents_from_tc(geom_mesh *m) {
    double *acc = mem_zalloc((size_t)m->nvert * 3 * sizeof *acc);
    for (int f = 0; f + 2 < m->nidx; f += 3) {
        unsigned i0 = m->idx[f], i1 = m->idx[f + 1], i2 = m->idx[f + 2];
        const float *p0 = m->pos + 3 * i0, *p1 = m->pos + 3 * i1, *p2 = m->pos + 3 * i2;
        const float *t0 = m->tc + 2 * i0, *t1 = m->tc + 2 * i1, *t2 = m->tc + 2 * i2;
        double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        double du1 = t1[0] - t0[0], dv1 = t1[1] - t0[1], du2 = t2[0] - t0[0], dv2 = t2[1] - t0[1];
        double det = du1 * dv2 - du2 * dv1;
        if (!(fabs(det) > 1e-20)) continue;
        double t[3] = {(e1[0] * dv2 - e2[0] * dv1) / det, (e1[1] * dv2 - e2[1] * dv1) / det,
                       (e1[2] * dv2 - e2[2] * dv1) / det};
        double cr[3];
        v3cross(cr, e1, e2);
        double area = v3len(cr);
        if (!v3normalize(t) || !isfinite(area)) continue;
        for (int c = 0; c < 3; c++) {
            acc[3 * i0 + c] += area * t[c];
            acc[3 * i1 + c] += area * t[c];
            acc[3 * i2 + c] += area * t[c];
        }
    }
    for (long k = 0; k < 3L * m->nvert; k++) m->tan[k] = (float)acc[k];
    free(acc);
}

/* ---- Wavefront OBJ ---- */

typedef struct obj_ctx {
    const char *path;
    char *err;
    int errlen;
    int line;
    bool failed;
    double *v, *vt, *vn;        /* 3, 2, 3 a record */
    int nv, nvt, nvn, capv, capvt, capvn;
    double *acc;                /* area-weighted normal sum per position (capv) */
    /* mesh vertices: the (v, vt, vn) corner each came from */
    int *corner_v, *corner_n, ncorner_cap;
    /* open-addressing table: (v, vt, vn) -> mesh vertex */
    int *hkey, *hval;
    size_t hcap, hcount;
    mb b;
    /* ObjPatch: every face's corners in the file's order, and their count
     * if all faces have the same (else -1) */
    bool keep_polys;
    unsigned *poly;
    int npoly, poly_cap, face_n;
} obj_ctx;

static bool obj_error(obj_ctx *o, const char *fmt, ...) {
    if (o->failed) return false;
    o->failed = true;
    if (o->err && o->errlen > 0) {
        char msg[256];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg, sizeof msg, fmt, ap);
        va_end(ap);
        if (o->line > 0) snprintf(o->err, (size_t)o->errlen, "%s:%d: %s", o->path, o->line, msg);
        else snprintf(o->err, (size_t)o->errlen, "%s: %s", o->path, msg);
    }
    return false;
}

/* A token shown in a message: printable, short. */
static void show_token(char *dst, size_t n, const char *tok) {
    size_t k = 0;
    for (; tok[k] && k + 4 < n && k < 24; k++) {
        unsigned char c = (unsigned char)tok[k];
        dst[k] = (c >= 32 && c < 127) ? (char)c : '?';
    }
    if (tok[k]) { dst[k++] = '.'; dst[k++] = '.'; dst[k++] = '.'; }
    dst[k] = 0;
}

static bool parse_double(obj_ctx *o, const char *tok, double *out) {
    char *end;
    errno = 0;
    double d = strtod(tok, &end);
    if (end == tok || *end || !isfinite(d) || (errno == ERANGE && fabs(d) > 1.0)) {
        char shown[32];
        show_token(shown, sizeof shown, tok);
        return obj_error(o, "bad number '%s'", shown);
    }
    *out = d;
    return true;
}

static bool push_record(obj_ctx *o, double **arr, int *count, int *cap, int width,
                        char **tok, int ntok, int need_min, int need_max, const char *what) {
    if (ntok < need_min || ntok > need_max) {
        if (need_min == need_max)
            return obj_error(o, "'%s' needs %d numbers, got %d", what, need_min, ntok);
        return obj_error(o, "'%s' needs %d to %d numbers, got %d", what, need_min, need_max, ntok);
    }
    if (*count >= *cap) {
        if (*cap > INT_MAX / 4) return obj_error(o, "too many '%s' records", what);
        int ncap = *cap ? *cap * 2 : 256;
        grow((void **)arr, (size_t)width * sizeof(double), ncap);
        if (arr == &o->v)       /* the normal sums follow the positions */
            grow((void **)&o->acc, 3 * sizeof(double), ncap);
        *cap = ncap;
    }
    double *r = *arr + (size_t)*count * width;
    for (int c = 0; c < width; c++) r[c] = 0;
    for (int c = 0; c < ntok && c < width; c++)
        if (!parse_double(o, tok[c], &r[c])) return false;
    for (int c = width; c < ntok; c++) {   /* w, or vertex colours: checked, not kept */
        double ignored;
        if (!parse_double(o, tok[c], &ignored)) return false;
    }
    if (arr == &o->v) for (int c = 0; c < 3; c++) o->acc[3 * (size_t)*count + c] = 0;
    (*count)++;
    return true;
}

/* One index of a corner: 1-based, negative from the end; -1 when absent. */
static bool parse_index(obj_ctx *o, const char *s, size_t len, int count, const char *what, int *out) {
    char buf[32];
    if (len == 0 || len >= sizeof buf) {
        if (len == 0) return obj_error(o, "empty %s index", what);
        return obj_error(o, "bad %s index", what);
    }
    memcpy(buf, s, len);
    buf[len] = 0;
    char *end;
    errno = 0;
    long k = strtol(buf, &end, 10);
    if (end == buf || *end || errno == ERANGE) {
        char shown[32];
        show_token(shown, sizeof shown, buf);
        return obj_error(o, "bad %s index '%s'", what, shown);
    }
    if (k == 0) return obj_error(o, "%s index 0 (OBJ indices start at 1)", what);
    long r = k > 0 ? k - 1 : (long)count + k;
    if (r < 0 || r >= count)
        return obj_error(o, "%s index %ld out of range (%d defined so far)", what, k, count);
    *out = (int)r;
    return true;
}

static uint64_t corner_hash(int v, int t, int n) {
    uint64_t h = (uint64_t)(uint32_t)v * 0x9E3779B97F4A7C15ULL;
    h ^= (uint64_t)(uint32_t)t * 0xC2B2AE3D27D4EB4FULL + (h << 6) + (h >> 2);
    h ^= (uint64_t)(uint32_t)n * 0x165667B19E3779F9ULL + (h << 6) + (h >> 2);
    return h ^ (h >> 29);
}

static void table_grow(obj_ctx *o) {
    size_t ncap = o->hcap ? o->hcap * 2 : 1024;
    int *nk = mem_alloc(ncap * 3 * sizeof *nk), *nv = mem_alloc(ncap * sizeof *nv);
    for (size_t s = 0; s < ncap; s++) nv[s] = -1;
    for (size_t s = 0; s < o->hcap; s++) {
        if (o->hval[s] < 0) continue;
        int *k = o->hkey + 3 * s;
        size_t at = corner_hash(k[0], k[1], k[2]) & (ncap - 1);
        while (nv[at] >= 0) at = (at + 1) & (ncap - 1);
        memcpy(nk + 3 * at, k, 3 * sizeof *k);
        nv[at] = o->hval[s];
    }
    free(o->hkey); free(o->hval);
    o->hkey = nk; o->hval = nv; o->hcap = ncap;
}

/* The mesh vertex of a corner, made on first use. */
static int corner_vertex(obj_ctx *o, int v, int t, int n) {
    if ((o->hcount + 1) * 2 > o->hcap) table_grow(o);
    size_t at = corner_hash(v, t, n) & (o->hcap - 1);
    while (o->hval[at] >= 0) {
        const int *k = o->hkey + 3 * at;
        if (k[0] == v && k[1] == t && k[2] == n) return o->hval[at];
        at = (at + 1) & (o->hcap - 1);
    }
    const double *p = o->v + 3 * (size_t)v;
    double nn[3] = {0, 0, 0}, tan[3] = {0, 0, 0};
    if (n >= 0) memcpy(nn, o->vn + 3 * (size_t)n, sizeof nn);
    double u = t >= 0 ? o->vt[2 * (size_t)t] : 0, w = t >= 0 ? o->vt[2 * (size_t)t + 1] : 0;
    int k = mb_vert(&o->b, p, nn, u, w, tan);
    if (!o->b.ok) { obj_error(o, "too many vertices"); return -1; }
    if (k >= o->ncorner_cap) {
        int ncap = o->ncorner_cap ? o->ncorner_cap * 2 : 1024;
        grow((void **)&o->corner_v, sizeof(int), ncap);
        grow((void **)&o->corner_n, sizeof(int), ncap);
        o->ncorner_cap = ncap;
    }
    o->corner_v[k] = v;
    o->corner_n[k] = n;
    o->hkey[3 * at] = v; o->hkey[3 * at + 1] = t; o->hkey[3 * at + 2] = n;
    o->hval[at] = k;
    o->hcount++;
    return k;
}

/* ObjPatch: the face's corners as they are (vis: mesh vertex, position). */
static bool keep_polygon(obj_ctx *o, const int *vis, int ntok) {
    if (o->npoly > INT_MAX / 4 - ntok) return obj_error(o, "too many faces");
    if (o->npoly + ntok > o->poly_cap) {
        int cap = o->poly_cap ? o->poly_cap : 256;
        while (cap < o->npoly + ntok) cap *= 2;
        grow((void **)&o->poly, sizeof *o->poly, cap);
        o->poly_cap = cap;
    }
    for (int c = 0; c < ntok; c++) o->poly[o->npoly++] = (unsigned)vis[2 * c];
    o->face_n = o->face_n == 0 ? ntok : o->face_n == ntok ? ntok : -1;
    return true;
}

static bool parse_face(obj_ctx *o, char **tok, int ntok) {
    if (ntok < 3) return obj_error(o, "a face needs at least 3 vertices, got %d", ntok);
    double area[3] = {0, 0, 0};
    int *vis = mem_alloc((size_t)ntok * 2 * sizeof *vis);
    for (int c = 0; c < ntok; c++) {
        const char *s = tok[c];
        const char *s1 = strchr(s, '/');
        const char *s2 = s1 ? strchr(s1 + 1, '/') : NULL;
        if (s2 && strchr(s2 + 1, '/')) {
            char shown[32];
            show_token(shown, sizeof shown, s);
            free(vis);
            return obj_error(o, "bad face vertex '%s' (v, v/vt, v//vn or v/vt/vn)", shown);
        }
        int vi, ti = -1, ni = -1;
        size_t lv = s1 ? (size_t)(s1 - s) : strlen(s);
        if (!parse_index(o, s, lv, o->nv, "vertex", &vi)) { free(vis); return false; }
        if (s1) {
            size_t lt = s2 ? (size_t)(s2 - s1 - 1) : strlen(s1 + 1);
            if (lt > 0 && !parse_index(o, s1 + 1, lt, o->nvt, "texture coordinate", &ti)) {
                free(vis);
                return false;
            }
        }
        if (s2 && s2[1] && !parse_index(o, s2 + 1, strlen(s2 + 1), o->nvn, "normal", &ni)) {
            free(vis);
            return false;
        }
        int k = corner_vertex(o, vi, ti, ni);
        if (k < 0) { free(vis); return false; }
        vis[2 * c] = k;
        vis[2 * c + 1] = vi;
    }
    if (o->keep_polys && !keep_polygon(o, vis, ntok)) { free(vis); return false; }
    /* fan triangles, and the polygon's area vector (sum of the fan's) */
    for (int c = 1; c + 1 < ntok; c++) {
        mb_tri(&o->b, vis[0], vis[2 * c], vis[2 * c + 2]);
        const double *p0 = o->v + 3 * (size_t)vis[1], *p1 = o->v + 3 * (size_t)vis[2 * c + 1],
                     *p2 = o->v + 3 * (size_t)vis[2 * c + 3];
        double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]}, cr[3];
        v3cross(cr, e1, e2);
        for (int k = 0; k < 3; k++) area[k] += cr[k];
    }
    /* every corner's position gets the whole polygon's area vector */
    for (int c = 0; c < ntok; c++) {
        bool seen = false;      /* a position used twice in one polygon counts once */
        for (int d = 0; d < c; d++) seen = seen || vis[2 * d + 1] == vis[2 * c + 1];
        if (seen) continue;
        for (int k = 0; k < 3; k++) o->acc[3 * (size_t)vis[2 * c + 1] + k] += area[k];
    }
    free(vis);
    if (!o->b.ok) return obj_error(o, "too many faces");
    return true;
}

static bool is_ignored_statement(const char *kw) {
    static const char *const ignored[] = {
        "o", "g", "s", "mg", "usemtl", "mtllib", "l", "p", "vp", "cstype", "deg", "bmat",
        "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv", "sp", "end", "con",
        "lod", "bevel", "c_interp", "d_interp", "usemap", "maplib", "shadow_obj",
        "trace_obj", "ctech", "stech", "call", "csh"};
    for (size_t k = 0; k < sizeof ignored / sizeof ignored[0]; k++)
        if (!strcmp(kw, ignored[k])) return true;
    return false;
}

#define OBJ_MAX_TOKENS_PREALLOC 64

static bool parse_statement(obj_ctx *o, char *text) {
    char *hash = strchr(text, '#');
    if (hash) *hash = 0;
    /* split on whitespace; a face may have many corners */
    int ntok = 0, cap = OBJ_MAX_TOKENS_PREALLOC;
    char *stack_tok[OBJ_MAX_TOKENS_PREALLOC];
    char **tok = stack_tok;
    for (char *s = text;;) {
        while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\v' || *s == '\f') s++;
        if (!*s) break;
        if (ntok == cap) {
            char **bigger = mem_alloc(sizeof *bigger * (size_t)cap * 2);
            memcpy(bigger, tok, sizeof *tok * (size_t)ntok);
            if (tok != stack_tok) free(tok);
            tok = bigger;
            cap *= 2;
        }
        tok[ntok++] = s;
        while (*s && *s != ' ' && *s != '\t' && *s != '\r' && *s != '\v' && *s != '\f') s++;
        if (*s) *s++ = 0;
    }
    bool ok = true;
    if (ntok > 0) {
        const char *kw = tok[0];
        char **args = tok + 1;
        int nargs = ntok - 1;
        if (!strcmp(kw, "v"))
            ok = push_record(o, &o->v, &o->nv, &o->capv, 3, args, nargs, 3, 7, "v");
        else if (!strcmp(kw, "vt"))
            ok = push_record(o, &o->vt, &o->nvt, &o->capvt, 2, args, nargs, 1, 3, "vt");
        else if (!strcmp(kw, "vn"))
            ok = push_record(o, &o->vn, &o->nvn, &o->capvn, 3, args, nargs, 3, 3, "vn");
        else if (!strcmp(kw, "f") || !strcmp(kw, "fo"))
            ok = parse_face(o, args, nargs);
        else if (!is_ignored_statement(kw)) {
            char shown[32];
            show_token(shown, sizeof shown, kw);
            ok = obj_error(o, "unknown statement '%s'", shown);
        }
    }
    if (tok != stack_tok) free(tok);
    return ok;
}

/* The OBJ text (a BOM dropped, CRLF as LF), or NULL with the error set:
 * binary (a NUL byte), a directory, too large. */
static char *read_file(obj_ctx *o, size_t *len) {
    file_text_opts opts = { .max_bytes = GEOM_OBJ_MAX_FILE_BYTES, .strip_bom = true, .crlf_to_lf = true,
                            .reject_nul = true };
    char why[256];
    char *text = file_read_text(o->path, &opts, len, why, sizeof why);
    if (!text) obj_error(o, "%s", why);
    return text;
}

/* What the OBJ variants need beyond the mesh: each mesh vertex's OBJ
 * position (edges are shared by position, not by split corner), and for
 * ObjPatch the faces as written. Owned by the caller when given. */
typedef struct obj_extra {
    int *pos_of;                /* nvert entries */
    bool keep_polys;
    unsigned *poly;
    int npoly, face_n;
} obj_extra;

static bool obj_load(geom_mesh *m, const char *path, char *err, int errlen, obj_extra *x);

bool geom_obj_load(geom_mesh *m, const char *path, char *err, int errlen) {
    return obj_load(m, path, err, errlen, NULL);
}

static bool obj_load(geom_mesh *m, const char *path, char *err, int errlen, obj_extra *x) {
    if (!m) return false;
    memset(m, 0, sizeof *m);
    if (err && errlen > 0) err[0] = 0;
    obj_ctx o;
    memset(&o, 0, sizeof o);
    o.keep_polys = x && x->keep_polys;
    o.path = path ? path : "(null)";
    o.err = err;
    o.errlen = errlen;
    mb_init(&o.b, false);
    if (!path || !*path) {
        obj_error(&o, "no file name");
        return false;
    }
    size_t len = 0;
    char *text = read_file(&o, &len);
    if (!text) return false;

    /* logical lines: a trailing backslash continues the line */
    char *s = text, *end = text + len;
    int lineno = 1;
    while (s < end && !o.failed) {
        o.line = lineno;
        char *out = s, *r = s;
        for (;;) {
            char *nl = memchr(r, '\n', (size_t)(end - r));
            char *stop = nl ? nl : end;
            size_t n = (size_t)(stop - r);
            bool cont = n > 0 && r[n - 1] == '\\';
            if (cont) n--;
            memmove(out, r, n);
            out += n;
            lineno++;
            r = nl ? nl + 1 : end;
            if (cont && nl) { *out++ = ' '; continue; }
            break;
        }
        *out = 0;
        parse_statement(&o, s);
        s = r;
    }
    free(text);

    if (!o.failed && o.b.m.nidx == 0) {
        o.line = 0;
        obj_error(&o, "no faces");
    }
    bool ok = !o.failed;
    if (ok) {
        /* normals: given ones as they are; the others from the faces around */
        for (int k = 0; k < o.b.m.nvert; k++) {
            float *n = o.b.m.nrm + 3 * k;
            double given[3] = {n[0], n[1], n[2]};
            if (o.corner_n[k] >= 0 && v3normalize(given)) continue;
            const double *a = o.acc + 3 * (size_t)o.corner_v[k];
            for (int c = 0; c < 3; c++) n[c] = (float)a[c];
        }
        tangents_from_tc(&o.b.m);
    }
    if (ok && x) {   /* hand over what the variant needs */
        x->pos_of = o.corner_v;
        o.corner_v = NULL;
        x->poly = o.poly;
        x->npoly = o.npoly;
        x->face_n = o.face_n;
        o.poly = NULL;
    }
    free(o.v); free(o.vt); free(o.vn); free(o.acc); free(o.poly);
    free(o.corner_v); free(o.corner_n); free(o.hkey); free(o.hval);
    if (!ok) {
        o.b.ok = false;
        mb_finish(&o.b, m);
        return false;
    }
    return mb_finish(&o.b, m);
}

/* ---- OBJ variants: edges, adjacency, patches ---- */

/* One edge of one triangle: its ends by OBJ position (a < b), the mesh
 * vertices at those ends, and the triangle's corner across from it. */
typedef struct edge_rec {
    int a, b;
    unsigned va, vb, opp;
    int tri, slot;
} edge_rec;

static int edge_cmp(const void *pa, const void *pb) {
    const edge_rec *x = pa, *y = pb;
    if (x->a != y->a) return x->a < y->a ? -1 : 1;
    if (x->b != y->b) return x->b < y->b ? -1 : 1;
    return x->tri < y->tri ? -1 : x->tri > y->tri;
}

/* The 3 edges of every triangle, sorted so shared ones are neighbours. */
static edge_rec *sorted_edges(const geom_mesh *m, const int *pos_of, int *count) {
    int ntri = m->nidx / 3;
    edge_rec *e = mem_alloc(sizeof *e * (size_t)(ntri > 0 ? ntri : 1) * 3);
    for (int t = 0; t < ntri; t++)
        for (int k = 0; k < 3; k++) {
            unsigned v0 = m->idx[3 * t + k], v1 = m->idx[3 * t + (k + 1) % 3], v2 = m->idx[3 * t + (k + 2) % 3];
            int p0 = pos_of[v0], p1 = pos_of[v1];
            edge_rec *r = &e[3 * t + k];
            r->a = p0 < p1 ? p0 : p1;
            r->b = p0 < p1 ? p1 : p0;
            r->va = p0 < p1 ? v0 : v1;
            r->vb = p0 < p1 ? v1 : v0;
            r->opp = v2;
            r->tri = t;
            r->slot = k;
        }
    qsort(e, (size_t)ntri * 3, sizeof *e, edge_cmp);
    *count = ntri * 3;
    return e;
}

bool geom_obj_load_wire(geom_mesh *m, const char *path, char *err, int errlen) {
    obj_extra x = {0};
    if (!obj_load(m, path, err, errlen, &x)) return false;
    int n = 0;
    edge_rec *e = sorted_edges(m, x.pos_of, &n);
    unsigned *idx = mem_alloc(sizeof *idx * (size_t)(2 * (n > 0 ? n : 1)));
    int k = 0;
    for (int i = 0; i < n; i++) {
        if (i > 0 && e[i].a == e[i - 1].a && e[i].b == e[i - 1].b) continue;   /* drawn once */
        idx[k++] = e[i].va;
        idx[k++] = e[i].vb;
    }
    free(e);
    free(x.pos_of);
    free(x.poly);
    free(m->idx);
    m->idx = idx;
    m->nidx = k;
    m->prim = GEOM_LINES;
    return true;
}

bool geom_obj_load_adjacency(geom_mesh *m, const char *path, char *err, int errlen) {
    obj_extra x = {0};
    if (!obj_load(m, path, err, errlen, &x)) return false;
    int n = 0, ntri = m->nidx / 3;
    edge_rec *e = sorted_edges(m, x.pos_of, &n);
    unsigned *idx = mem_alloc(sizeof *idx * (size_t)(6 * (ntri > 0 ? ntri : 1)));
    for (int t = 0; t < ntri; t++)
        for (int k = 0; k < 3; k++) {
            idx[6 * t + 2 * k] = m->idx[3 * t + k];
            idx[6 * t + 2 * k + 1] = m->idx[3 * t + (k + 2) % 3];   /* no neighbour: its own third corner */
        }
    for (int i = 0; i < n;) {
        int j = i + 1;
        while (j < n && e[j].a == e[i].a && e[j].b == e[i].b) j++;
        if (j - i == 2)   /* a manifold edge: each triangle sees the other's far corner */
            for (int s = 0; s < 2; s++) {
                const edge_rec *me = &e[i + s], *other = &e[i + 1 - s];
                idx[6 * me->tri + 2 * me->slot + 1] = other->opp;
            }
        i = j;
    }
    free(e);
    free(x.pos_of);
    free(x.poly);
    free(m->idx);
    m->idx = idx;
    m->nidx = 6 * ntri;
    m->prim = GEOM_TRIANGLES_ADJACENCY;
    return true;
}

#define GEOM_MAX_PATCH 32   /* GL's least GL_MAX_PATCH_VERTICES */

bool geom_obj_load_patches(geom_mesh *m, const char *path, char *err, int errlen) {
    obj_extra x = {.keep_polys = true};
    if (!obj_load(m, path, err, errlen, &x)) return false;
    m->prim = GEOM_PATCHES;
    m->patch_size = 3;
    if (x.face_n >= 3 && x.face_n <= GEOM_MAX_PATCH && x.poly) {   /* each face one patch */
        free(m->idx);
        m->idx = x.poly;
        m->nidx = x.npoly;
        m->patch_size = x.face_n;
        x.poly = NULL;
    }
    free(x.pos_of);
    free(x.poly);
    return true;
}

/* ---- Shp: ESRI shapefiles (the .shp main file) ---- */

static uint32_t shp_be32(const unsigned char *p) {
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}
static uint32_t shp_le32(const unsigned char *p) {
    return (uint32_t)p[3] << 24 | (uint32_t)p[2] << 16 | (uint32_t)p[1] << 8 | p[0];
}
static double shp_le64f(const unsigned char *p) {
    uint64_t u = 0;
    for (int k = 7; k >= 0; k--) u = u << 8 | p[k];
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

static bool shp_fail(char *err, int errlen, const char *path, const char *fmt, ...) {
    if (err && errlen > 0) {
        char msg[256];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg, sizeof msg, fmt, ap);
        va_end(ap);
        snprintf(err, (size_t)errlen, "%s: %s", path, msg);
    }
    return false;
}

static const char *shp_type_name(int t) {
    switch (t) {
    case 0: return "Null"; case 1: return "Point"; case 3: return "PolyLine"; case 5: return "Polygon";
    case 8: return "MultiPoint"; case 11: return "PointZ"; case 13: return "PolyLineZ";
    case 15: return "PolygonZ"; case 18: return "MultiPointZ"; case 21: return "PointM";
    case 23: return "PolyLineM"; case 25: return "PolygonM"; case 28: return "MultiPointM";
    case 31: return "MultiPatch"; default: return "unknown";
    }
}

static bool shp_lines(int t) { return t == 3 || t == 5 || t == 13 || t == 15 || t == 23 || t == 25; }

bool geom_shp_load(geom_mesh *m, const char *path, char *err, int errlen) {
    if (!m) return false;
    memset(m, 0, sizeof *m);
    if (err && errlen > 0) err[0] = '\0';
    char why[256];
    size_t len = 0;
    unsigned char *f = (unsigned char *)file_read(path, (size_t)GEOM_OBJ_MAX_FILE_BYTES, &len, why, sizeof why);
    if (!f) return shp_fail(err, errlen, path, "%s", why);
    bool ok = false;
    mb b;
    mb_init(&b, true);
    if (len < 100) {
        shp_fail(err, errlen, path, "not a shapefile: %zu bytes, shorter than the 100-byte header", len);
        goto done;
    }
    if (shp_be32(f) != 9994) {
        shp_fail(err, errlen, path, "not a shapefile (.shp): its file code is %u, not 9994", shp_be32(f));
        goto done;
    }
    if (shp_le32(f + 28) != 1000) {
        shp_fail(err, errlen, path, "not a shapefile: version %u, not 1000", shp_le32(f + 28));
        goto done;
    }
    size_t declared = (size_t)shp_be32(f + 24) * 2;
    if (declared > len) {
        shp_fail(err, errlen, path, "truncated: the header says %zu bytes, the file has %zu", declared, len);
        goto done;
    }
    if (declared < 100) declared = len;   /* a writer that left the length 0: read what is there */
    int type = (int)shp_le32(f + 32);
    if (type != 0 && !shp_lines(type)) {
        shp_fail(err, errlen, path, "shape type %d (%s): tarn draws PolyLine and Polygon shapefiles "
                 "(3, 5 and their Z/M variants)", type, shp_type_name(type));
        goto done;
    }
    double box[4];
    for (int k = 0; k < 4; k++) box[k] = shp_le64f(f + 36 + 8 * k);
    double w = box[2] - box[0], h = box[3] - box[1];
    if (!isfinite(w) || !(w > 0)) w = 1;
    if (!isfinite(h) || !(h > 0)) h = 1;
    const double nz[3] = {0, 0, 1}, tx[3] = {1, 0, 0};
    size_t at = 100;
    int rec = 0;
    while (at < declared) {
        rec++;
        if (declared - at < 8) {
            shp_fail(err, errlen, path, "truncated: record %d's header at byte %zu is cut off", rec, at);
            goto done;
        }
        size_t clen = (size_t)shp_be32(f + at + 4) * 2;
        size_t c = at + 8;
        if (clen > declared - c) {
            shp_fail(err, errlen, path, "truncated: record %d (at byte %zu) needs %zu bytes, the file ends %zu bytes on",
                     rec, at, clen, declared - c);
            goto done;
        }
        at = c + clen;
        if (clen < 4) {
            shp_fail(err, errlen, path, "record %d (at byte %zu) has no shape type", rec, c - 8);
            goto done;
        }
        int rt = (int)shp_le32(f + c);
        if (rt == 0) continue;                          /* a null shape: nothing to draw */
        if (!shp_lines(rt)) {
            shp_fail(err, errlen, path, "record %d is shape type %d (%s): tarn draws PolyLine and Polygon shapes",
                     rec, rt, shp_type_name(rt));
            goto done;
        }
        if (clen < 44) {
            shp_fail(err, errlen, path, "record %d (at byte %zu): %zu bytes, too short for a %s",
                     rec, c - 8, clen, shp_type_name(rt));
            goto done;
        }
        uint32_t np = shp_le32(f + c + 36), npt = shp_le32(f + c + 40);
        size_t need = 44 + (size_t)np * 4 + (size_t)npt * 16;
        bool z = rt == 13 || rt == 15;
        if (z) need += 16 + (size_t)npt * 8;
        if (np > clen || npt > clen || need > clen) {
            shp_fail(err, errlen, path, "record %d (at byte %zu): %u parts and %u points need %zu bytes, it has %zu",
                     rec, c - 8, np, npt, need, clen);
            goto done;
        }
        const unsigned char *parts = f + c + 44, *pts = parts + (size_t)np * 4;
        const unsigned char *zs = pts + (size_t)npt * 16 + 16;
        bool closed = rt == 5 || rt == 15 || rt == 25;
        for (uint32_t p = 0; p < np; p++) {
            uint32_t first = shp_le32(parts + 4 * p), end = p + 1 < np ? shp_le32(parts + 4 * (p + 1)) : npt;
            if (first > end || end > npt) {
                shp_fail(err, errlen, path, "record %d: part %u runs from point %u to %u of %u", rec, p, first, end, npt);
                goto done;
            }
            if (!mb_reserve(&b, (long)(end - first), 2L * (end - first + 1))) goto done;
            int v0 = b.m.nvert;
            for (uint32_t i = first; i < end; i++) {
                double x = shp_le64f(pts + 16 * i), y = shp_le64f(pts + 16 * i + 8);
                double pz = z ? shp_le64f(zs + 8 * i) : 0;
                if (!isfinite(x) || !isfinite(y) || !isfinite(pz)) {
                    shp_fail(err, errlen, path, "record %d: point %u is not a finite number", rec, i);
                    goto done;
                }
                double pos[3] = {x, y, pz};
                mb_vert(&b, pos, nz, (x - box[0]) / w, (y - box[1]) / h, tx);
                if (i > first) mb_line(&b, b.m.nvert - 2, b.m.nvert - 1);
            }
            int n = b.m.nvert - v0;
            if (closed && n > 2) {
                const float *a = b.m.pos + 3 * v0, *e = b.m.pos + 3 * (b.m.nvert - 1);
                if (a[0] != e[0] || a[1] != e[1] || a[2] != e[2]) mb_line(&b, b.m.nvert - 1, v0);
            }
        }
    }
    if (b.m.nidx == 0) {
        shp_fail(err, errlen, path, "no line to draw: %d record%s, none with two points", rec, rec == 1 ? "" : "s");
        goto done;
    }
    ok = true;
done:
    free(f);
    if (!ok) {
        b.ok = false;
        if (err && errlen > 0 && !err[0]) shp_fail(err, errlen, path, "too large");
    }
    return mb_finish(&b, m) && ok;
}

/* ---- points given in the glib ---- */

bool geom_points(geom_mesh *m, const float *xyz, int n, geom_prim prim) {
    if (!m) return false;
    memset(m, 0, sizeof *m);
    if (!xyz || n < 1 || n > (1 << 20)) return false;
    for (int k = 0; k < 3 * n; k++)
        if (!isfinite(xyz[k])) return false;
    double nrm[3] = {0, 0, 1};
    if (n >= 3) {   /* the winding's normal: a triangle faces where it winds CCW */
        double e1[3], e2[3];
        for (int c = 0; c < 3; c++) { e1[c] = xyz[3 + c] - xyz[c]; e2[c] = xyz[6 + c] - xyz[c]; }
        v3cross(nrm, e1, e2);
        if (!v3normalize(nrm)) v3set(nrm, 0, 0, 1);
    }
    mb b;
    mb_init_prim(&b, prim);
    double t[3];
    any_perpendicular(t, nrm);
    for (int k = 0; k < n; k++) {
        double p[3] = {xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]};
        mb_index(&b, mb_vert(&b, p, nrm, p[0], p[1], t));
    }
    return mb_finish(&b, m);
}

/* ---- DiskXY, QuadBox, PointCloud ---- */

bool geom_disk_xy(geom_mesh *m, int slices) {
    if (!m) return false;
    memset(m, 0, sizeof *m);
    slices = clamp_div(slices, 64, 3, GEOM_MAX_DIV);
    mb b;
    mb_init(&b, false);
    const double n[3] = {0, 0, 1}, t[3] = {1, 0, 0}, o[3] = {0, 0, 0};
    int centre = mb_vert(&b, o, n, 0.5, 0.5, t);
    for (int i = 0; i <= slices; i++) {
        double s, c;
        angle(i, slices, &s, &c);
        double p[3] = {c, s, 0};
        mb_vert(&b, p, n, 0.5 + 0.5 * c, 0.5 + 0.5 * s, t);
    }
    for (int i = 0; i < slices; i++) mb_tri(&b, centre, centre + 1 + i, centre + 2 + i);
    return mb_finish(&b, m);
}

bool geom_quad_box(geom_mesh *m, int n) {
    if (!m) return false;
    memset(m, 0, sizeof *m);
    n = clamp_div(n, 10, 1, GEOM_MAX_DIV);
    mb b;
    mb_init(&b, false);
    b.with_p = true;
    const double nz[3] = {0, 0, 1}, tx[3] = {1, 0, 0};
    for (int k = 0; k < n; k++) {   /* from z = -1 up: back to front seen from +z, for blending */
        double z = n == 1 ? 0 : -1 + 2.0 * k / (n - 1);
        b.p_next = (z + 1) / 2;
        int v0 = b.m.nvert;
        for (int j = 0; j < 2; j++)
            for (int i = 0; i < 2; i++) {
                double p[3] = {2.0 * i - 1, 2.0 * j - 1, z};
                mb_vert(&b, p, nz, i, j, tx);
            }
        mb_tri(&b, v0, v0 + 1, v0 + 3);
        mb_tri(&b, v0, v0 + 3, v0 + 2);
    }
    return mb_finish(&b, m);
}

#define GEOM_MAX_POINTS (1L << 24)

bool geom_point_cloud(geom_mesh *m, int nx, int ny, int nz, bool jitter) {
    if (!m) return false;
    memset(m, 0, sizeof *m);
    nx = clamp_div(nx, 10, 1, GEOM_MAX_DIV);
    ny = clamp_div(ny, 10, 1, GEOM_MAX_DIV);
    nz = clamp_div(nz, 10, 1, GEOM_MAX_DIV);
    if ((long)nx * ny * nz > GEOM_MAX_POINTS) return false;
    mb b;
    mb_init_prim(&b, GEOM_POINTS);
    b.with_p = true;
    uint64_t rng = 0x2545F4914F6CDD1DULL;   /* a fixed seed: the same cloud on every load */
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++) {
                double f[3] = {0.5, 0.5, 0.5};
                for (int c = 0; jitter && c < 3; c++) {   /* xorshift64: a place in the cell */
                    rng ^= rng << 13; rng ^= rng >> 7; rng ^= rng << 17;
                    f[c] = (double)(rng >> 11) / 9007199254740992.0;
                }
                double u[3] = {(i + f[0]) / nx, (j + f[1]) / ny, (k + f[2]) / nz};
                double p[3] = {2 * u[0] - 1, 2 * u[1] - 1, 2 * u[2] - 1}, n[3] = {p[0], p[1], p[2]}, t[3];
                if (!v3normalize(n)) v3set(n, 0, 0, 1);
                any_perpendicular(t, n);
                b.p_next = u[2];
                mb_index(&b, mb_vert(&b, p, n, u[0], u[1], t));
            }
    return mb_finish(&b, m);
}

/* ---- Xarrow: a surface of revolution about +x ---- */

typedef struct lathe_ctx {
    double x0, r0, x1, r1;      /* one segment of the profile */
    int slices;
    int rows;                   /* rings along the segment */
} lathe_ctx;

static void lathe_eval(const void *vctx, int i, int j, double p[3], double n[3], double t[3], double tc[2]) {
    const lathe_ctx *q = vctx;
    double s, c;
    angle(i, q->slices, &s, &c);
    double f = (double)j / q->rows;
    double x = j == q->rows ? q->x1 : q->x0 + (q->x1 - q->x0) * f, r = j == q->rows ? q->r1 : q->r0 + (q->r1 - q->r0) * f;
    double dx = q->x1 - q->x0, dr = q->r1 - q->r0;
    v3set(p, x, r * c, r * s);
    v3set(n, -dr, dx * c, dx * s);   /* the profile's normal (-dr, dx) turned about x */
    v3set(t, 0, -s, c);
    tc[0] = (double)i / q->slices;
    tc[1] = x;
}

bool geom_xarrow(geom_mesh *m, int slices) {
    if (!m) return false;
    memset(m, 0, sizeof *m);
    /* base disk, shaft, the head's back, the head's cone: (x, r) */
    static const double prof[5][2] = {{0, 0}, {0, 0.02}, {0.8, 0.02}, {0.8, 0.06}, {1, 0}};
    mb b;
    mb_init(&b, false);
    for (int k = 0; k < 4; k++) {
        int n = clamp_div(slices, 100, 3, GEOM_MAX_DIV);
        /* glman's arrow has n segments along its length (issue 27: a vertex
         * shader bends `Xarrow 200` along a helix): the shaft and the head's
         * cone get rings in proportion to their length, n over 0..1 */
        double len = prof[k + 1][0] - prof[k][0];
        int rows = len > 0 ? (int)lround(n * len) : 1;
        lathe_ctx q = {prof[k][0], prof[k][1], prof[k + 1][0], prof[k + 1][1], n, rows < 1 ? 1 : rows};
        int flags = GRID_CLOSED_U | (q.r0 == 0 ? GRID_COLLAPSED_V0 : 0) | (q.r1 == 0 ? GRID_COLLAPSED_V1 : 0);
        grid(&b, q.slices, q.rows, lathe_eval, &q, flags);
    }
    return mb_finish(&b, m);
}

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
                bool out = v3dot(cr, ctr) > 0;
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
    if (!v3normalize(t)) any_perpendicular(t, n);
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
                mb_vert(b, p, n, 0.5 + 0.5 * v3dot(d, e1) / radius, 0.5 + 0.5 * v3dot(d, e2) / radius, t);
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
    any_perpendicular(e1, n);
    v3cross(e2, n, e1);
    int k = 0;
    for (int j = 0; j < 12 && k < 5; j++) {
        double d[3] = {v[j][0] - v[i][0], v[j][1] - v[i][1], v[j][2] - v[i][2]};
        if (j == i || fabs(v3len(d) - 2) > 1e-9) continue;
        third(out[k], v[i], v[j]);
        ang[k++] = atan2(v3dot(d, e2), v3dot(d, e1));
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
    if (!finite_args(1, (double)r)) return false;
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
