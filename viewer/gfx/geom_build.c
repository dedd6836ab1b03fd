/* geom_build.c: the mesh builder and grids the geometry files share (geom_build.h). */
#include "geom_build.h"
#include "mem.h"

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

/* ---- mesh builder ---- */

void mb_init_prim(mb *b, geom_prim prim) {
    memset(b, 0, sizeof *b);
    b->ok = true;
    b->m.prim = prim;
}

void mb_init(mb *b, bool lines) { mb_init_prim(b, lines ? GEOM_LINES : GEOM_TRIANGLES); }

void geom_grow(void **p, size_t elem, int cap) {
    *p = mem_realloc(*p, elem * (size_t)cap);
}

bool mb_reserve(mb *b, long nv, long ni) {
    if (!b->ok) return false;
    long need_v = b->m.nvert + nv, need_i = b->m.nidx + ni;
    if (need_v > INT_MAX / 4 || need_i > INT_MAX / 4) { b->ok = false; return false; }
    if (need_v > b->vcap) {
        int cap = b->vcap ? b->vcap : 64;
        while (cap < need_v) cap = cap > INT_MAX / 8 ? (int)need_v : cap * 2;
        geom_grow((void **)&b->m.pos, 3 * sizeof(float), cap);
        geom_grow((void **)&b->m.nrm, 3 * sizeof(float), cap);
        geom_grow((void **)&b->m.tc, 2 * sizeof(float), cap);
        geom_grow((void **)&b->m.tan, 3 * sizeof(float), cap);
        if (b->with_p) geom_grow((void **)&b->m.tcp, sizeof(float), cap);
        b->vcap = cap;
    }
    if (need_i > b->icap) {
        int cap = b->icap ? b->icap : 64;
        while (cap < need_i) cap = cap > INT_MAX / 8 ? (int)need_i : cap * 2;
        geom_grow((void **)&b->m.idx, sizeof(unsigned), cap);
        b->icap = cap;
    }
    return true;
}

int mb_vert(mb *b, const double p[3], const double n[3], double u, double v, const double t[3]) {
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

void mb_index(mb *b, int a) {
    if (!mb_reserve(b, 0, 1)) return;
    b->m.idx[b->m.nidx++] = (unsigned)a;
}

void mb_tri(mb *b, int a, int c, int d) { mb_index(b, a); mb_index(b, c); mb_index(b, d); }
void mb_line(mb *b, int a, int c) { mb_index(b, a); mb_index(b, c); }

void geom_free(geom_mesh *m) {
    if (!m) return;
    free(m->pos); free(m->nrm); free(m->tc); free(m->tan); free(m->idx);
    free(m->tcp); free(m->part_first);
    memset(m, 0, sizeof *m);
}

void geom_any_perpendicular(double t[3], const double n[3]) {
    double a[3];
    if (fabs(n[0]) < 0.9) v3set(a, 1, 0, 0); else v3set(a, 0, 1, 0);
    double d = vec3_dot(a, n);
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
        double d = vec3_dot(t, n);
        double g[3] = {t[0] - d * n[0], t[1] - d * n[1], t[2] - d * n[2]};
        if (!isfinite(d) || v3len(g) < 1e-6 * (v3len(t) + 1e-30) || !v3normalize(g))
            geom_any_perpendicular(g, n);
        for (int c = 0; c < 3; c++) { m->nrm[3 * k + c] = (float)n[c]; m->tan[3 * k + c] = (float)g[c]; }
    }
}

bool mb_finish(mb *b, geom_mesh *out) {
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

void geom_grid(mb *b, int nu, int nv, grid_fn f, const void *ctx, int flags) {
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

int geom_clamp_div(int n, int dflt, int lo, int hi) {
    if (n <= 0) n = dflt;
    if (n < lo) n = lo;
    if (n > hi) n = hi;
    return n;
}

bool geom_finite_args(int count, ...) {
    va_list ap;
    va_start(ap, count);
    bool ok = true;
    for (int k = 0; k < count; k++) ok = ok && isfinite(va_arg(ap, double));
    va_end(ap);
    return ok;
}

void geom_angle(int i, int n, double *s, double *c) {
    double a = 2.0 * GEOM_PI * (double)(i % n) / (double)n;
    *s = sin(a);
    *c = cos(a);
}

