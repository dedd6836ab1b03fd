/* geom_shapes.c: glman's solids and primitives: QuadXY/XZ/YZ (and the grid
 * reordered into bands), Box, Sphere, Torus, Cylinder, Cone, Triangles and
 * glBegin's points, DiskXY, QuadBox, PointCloud, JitterCloud, Xarrow (geom.h). */
#include "geom_build.h"
#include "mem.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

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
    if (axis < 0 || axis > 2 || !geom_finite_args(2, (double)offset, (double)size)) return false;
    plane_ctx q;
    face_frame(&q, axis, false);
    q.offset = offset;
    q.su = q.sv = fabs((double)size);
    n1 = geom_clamp_div(n1, 1, 1, GEOM_MAX_DIV);
    n2 = geom_clamp_div(n2, 1, 1, GEOM_MAX_DIV);
    /* the glib's counts are along (x,y), (x,z), (y,z); U of QuadYZ is z */
    q.nu = axis == 0 ? n2 : n1;
    q.nv = axis == 0 ? n1 : n2;
    mb b;
    mb_init(&b, wire);
    geom_grid(&b, q.nu, q.nv, plane_eval, &q, 0);
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
    if (!geom_finite_args(3, (double)dx, (double)dy, (double)dz)) return false;
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
        geom_grid(&b, 1, 1, plane_eval, &q, 0);
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
    geom_angle(i, q->nu, &sa, &ca);
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
    if (!geom_finite_args(1, (double)r)) return false;
    round_ctx q = {fabs((double)r), 0, 0, geom_clamp_div(slices, 32, 3, GEOM_MAX_DIV),
                   geom_clamp_div(stacks, 16, 2, GEOM_MAX_DIV)};
    mb b;
    mb_init(&b, wire);
    geom_grid(&b, q.nu, q.nv, sphere_eval, &q, GRID_CLOSED_U | GRID_COLLAPSED_V0 | GRID_COLLAPSED_V1);
    return mb_finish(&b, m);
}

/* ---- torus ---- */

static void torus_eval(const void *vctx, int i, int j, double p[3], double n[3], double t[3], double tc[2]) {
    const round_ctx *q = vctx;     /* r: major, r2: minor; nu rings, nv sides */
    double st, ct, sp, cp;
    geom_angle(i, q->nu, &st, &ct);
    geom_angle(j, q->nv, &sp, &cp);
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
    if (!geom_finite_args(2, (double)r_major, (double)r_minor)) return false;
    round_ctx q = {fabs((double)r_major), fabs((double)r_minor), 0,
                   geom_clamp_div(rings, 32, 3, GEOM_MAX_DIV), geom_clamp_div(sides, 16, 3, GEOM_MAX_DIV)};
    mb b;
    mb_init(&b, wire);
    geom_grid(&b, q.nu, q.nv, torus_eval, &q, GRID_CLOSED_U);
    return mb_finish(&b, m);
}

/* ---- cylinder and cone ---- */

/* r: base radius, r2: top radius (cylinder r, cone 0), h: height */
static void side_eval(const void *vctx, int i, int j, double p[3], double n[3], double t[3], double tc[2]) {
    const round_ctx *q = vctx;
    double st, ct;
    geom_angle(i, q->nu, &st, &ct);
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
        geom_angle(i, slices, &st, &ct);
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
    if (!geom_finite_args(2, (double)r, (double)h)) return false;
    double rr = fabs((double)r), hh = fabs((double)h);
    round_ctx q = {rr, cone ? 0 : rr, hh, geom_clamp_div(slices, 32, 3, GEOM_MAX_DIV),
                   geom_clamp_div(stacks, 1, 1, GEOM_MAX_DIV)};
    mb b;
    mb_init(&b, wire);
    geom_grid(&b, q.nu, q.nv, side_eval, &q, GRID_CLOSED_U | (cone ? GRID_COLLAPSED_V1 : 0));
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
    geom_any_perpendicular(t, nrm);
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
    slices = geom_clamp_div(slices, 64, 3, GEOM_MAX_DIV);
    mb b;
    mb_init(&b, false);
    const double n[3] = {0, 0, 1}, t[3] = {1, 0, 0}, o[3] = {0, 0, 0};
    int centre = mb_vert(&b, o, n, 0.5, 0.5, t);
    for (int i = 0; i <= slices; i++) {
        double s, c;
        geom_angle(i, slices, &s, &c);
        double p[3] = {c, s, 0};
        mb_vert(&b, p, n, 0.5 + 0.5 * c, 0.5 + 0.5 * s, t);
    }
    for (int i = 0; i < slices; i++) mb_tri(&b, centre, centre + 1 + i, centre + 2 + i);
    return mb_finish(&b, m);
}

bool geom_quad_box(geom_mesh *m, int n) {
    if (!m) return false;
    memset(m, 0, sizeof *m);
    n = geom_clamp_div(n, 10, 1, GEOM_MAX_DIV);
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
    nx = geom_clamp_div(nx, 10, 1, GEOM_MAX_DIV);
    ny = geom_clamp_div(ny, 10, 1, GEOM_MAX_DIV);
    nz = geom_clamp_div(nz, 10, 1, GEOM_MAX_DIV);
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
                geom_any_perpendicular(t, n);
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
    geom_angle(i, q->slices, &s, &c);
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
        int n = geom_clamp_div(slices, 100, 3, GEOM_MAX_DIV);
        /* glman's arrow has n segments along its length (issue 27: a vertex
         * shader bends `Xarrow 200` along a helix): the shaft and the head's
         * cone get rings in proportion to their length, n over 0..1 */
        double len = prof[k + 1][0] - prof[k][0];
        int rows = len > 0 ? (int)lround(n * len) : 1;
        lathe_ctx q = {prof[k][0], prof[k][1], prof[k + 1][0], prof[k + 1][1], n, rows < 1 ? 1 : rows};
        int flags = GRID_CLOSED_U | (q.r0 == 0 ? GRID_COLLAPSED_V0 : 0) | (q.r1 == 0 ? GRID_COLLAPSED_V1 : 0);
        geom_grid(&b, q.slices, q.rows, lathe_eval, &q, flags);
    }
    return mb_finish(&b, m);
}
