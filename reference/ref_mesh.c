/* ref_mesh: OBJ triangles in the world and a BVH over them (ref_mesh.h). */
#include "ref_mesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"
#include "obj.h"
#include "strbuf.h"

#define PI 3.14159265358979323846

typedef struct bvh_node {
    double lo[3], hi[3];
    int first;          /* leaf: first entry of order[]; inner: the left child (right = first + 1) */
    int count;          /* leaf: triangles (> 0); inner: 0 */
} bvh_node;

struct ref_mesh {
    int ntri;
    double *tri;        /* 9 a triangle */
    double *nrm;        /* 3 a triangle */
    int *order;         /* triangle indices, leaf by leaf */
    bvh_node *node;
    int nnodes;
};

/* ---- building ---- */

static void tri_bounds(const double *t, double lo[3], double hi[3]) {
    for (int a = 0; a < 3; a++) {
        lo[a] = fmin(t[a], fmin(t[3 + a], t[6 + a]));
        hi[a] = fmax(t[a], fmax(t[3 + a], t[6 + a]));
    }
}

static double centroid(const ref_mesh *m, int i, int axis) {
    const double *t = m->tri + (size_t)i * 9;
    return (t[axis] + t[3 + axis] + t[6 + axis]) / 3.0;
}


/* Partial sort by centroid: quickselect so order[lo..mid) <= order[mid..hi). */
static void select_median(const ref_mesh *m, int *ord, int n, int k, int axis) {
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        double pivot = centroid(m, ord[(lo + hi) / 2], axis);
        int i = lo, j = hi;
        while (i <= j) {
            while (centroid(m, ord[i], axis) < pivot) i++;
            while (centroid(m, ord[j], axis) > pivot) j--;
            if (i <= j) { int s = ord[i]; ord[i] = ord[j]; ord[j] = s; i++; j--; }
        }
        if (k <= j) hi = j;
        else if (k >= i) lo = i;
        else return;
    }
}

/* Builds the node at index `at` over order[first .. first + n); returns the
 * next free node index. Boxes are widened by a hair so that a hit on a
 * triangle lying in a box's face is never culled by rounding. */
static int build(ref_mesh *m, int at, int first, int n, int next) {
    bvh_node *nd = &m->node[at];
    for (int a = 0; a < 3; a++) { nd->lo[a] = INFINITY; nd->hi[a] = -INFINITY; }
    double clo[3] = { INFINITY, INFINITY, INFINITY }, chi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (int k = 0; k < n; k++) {
        double lo[3], hi[3];
        int i = m->order[first + k];
        tri_bounds(m->tri + (size_t)i * 9, lo, hi);
        for (int a = 0; a < 3; a++) {
            nd->lo[a] = fmin(nd->lo[a], lo[a]);
            nd->hi[a] = fmax(nd->hi[a], hi[a]);
            double c = centroid(m, i, a);
            clo[a] = fmin(clo[a], c);
            chi[a] = fmax(chi[a], c);
        }
    }
    for (int a = 0; a < 3; a++) {
        double pad = 1e-9 * (1.0 + fabs(nd->lo[a]) + fabs(nd->hi[a]));
        nd->lo[a] -= pad;
        nd->hi[a] += pad;
    }
    int axis = 0;
    for (int a = 1; a < 3; a++)
        if (chi[a] - clo[a] > chi[axis] - clo[axis]) axis = a;
    if (n <= REF_MESH_LEAF || !(chi[axis] > clo[axis])) {
        nd->first = first;
        nd->count = n;
        return next;
    }
    int half = n / 2;
    select_median(m, m->order + first, n, half, axis);
    nd->first = next;
    nd->count = 0;
    next += 2;
    next = build(m, nd->first, first, half, next);
    return build(m, m->node[at].first + 1, first + half, n - half, next);
}

static ref_mesh *finish(double *tri, int ntri) {
    ref_mesh *m = mem_zalloc(sizeof *m);
    m->ntri = ntri;
    m->tri = tri;
    m->nrm = mem_alloc((size_t)ntri * 3 * sizeof *m->nrm);
    m->order = mem_alloc((size_t)ntri * sizeof *m->order);
    for (int i = 0; i < ntri; i++) {
        const double *t = tri + (size_t)i * 9;
        double e1[3], e2[3], *n = m->nrm + (size_t)i * 3;
        for (int a = 0; a < 3; a++) { e1[a] = t[3 + a] - t[a]; e2[a] = t[6 + a] - t[a]; }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (l > 0) for (int a = 0; a < 3; a++) n[a] /= l;
        else n[0] = 0, n[1] = 1, n[2] = 0;   /* a degenerate triangle: never hit (det 0) */
        m->order[i] = i;
    }
    m->node = mem_alloc((size_t)(2 * ntri) * sizeof *m->node);   /* a binary tree of <= ntri leaves */
    m->nnodes = build(m, 0, 0, ntri, 1);
    return m;
}

ref_mesh *ref_mesh_from_triangles(const double *tri, int ntri) {
    if (!tri || ntri < 1 || ntri > REF_MESH_MAX_TRIANGLES) return NULL;
    double *copy = mem_alloc((size_t)ntri * 9 * sizeof *copy);
    memcpy(copy, tri, (size_t)ntri * 9 * sizeof *copy);
    return finish(copy, ntri);
}

/* ---- OBJ (base/obj.h reads it) ---- */

static void place_point(const ref_mesh_place *p, const double in[3], double out[3]) {
    double s = p && p->scale != 0 ? p->scale : 1.0, a = p ? p->rot_y_deg * PI / 180.0 : 0.0;
    double c = cos(a), sn = sin(a);
    double x = in[0] * c + in[2] * sn, z = -in[0] * sn + in[2] * c;   /* about +y, anticlockwise from above */
    out[0] = s * x + (p ? p->pos[0] : 0);
    out[1] = s * in[1] + (p ? p->pos[1] : 0);
    out[2] = s * z + (p ? p->pos[2] : 0);
}

ref_mesh *ref_mesh_from_obj(const obj_data *d, const char *name, const ref_mesh_place *place, char *err,
                            size_t errlen) {
    if (!d || d->ntri == 0) {
        msg_set(err, errlen, "%s: no triangles (no `f` lines)", name ? name : "(null)");
        return NULL;
    }
    if (d->ntri > REF_MESH_MAX_TRIANGLES) {   /* obj_parse was told the limit: a caller's own data */
        msg_set(err, errlen, "%s: more than %d triangles", name ? name : "(null)", REF_MESH_MAX_TRIANGLES);
        return NULL;
    }
    double *v = mem_alloc((size_t)(d->nv > 0 ? d->nv : 1) * 3 * sizeof *v);
    for (int i = 0; i < d->nv; i++) place_point(place, d->v + (size_t)i * 3, v + (size_t)i * 3);
    double *tri = mem_alloc((size_t)d->ntri * 9 * sizeof *tri);
    int ntri = 0;
    for (int f = 0; f < d->nface; f++) {   /* polygons fanned from their first corner */
        const obj_corner *c = d->corner + d->face_first[f];
        int n = d->face_first[f + 1] - d->face_first[f];
        for (int k = 1; k + 1 < n; k++) {
            double *t = tri + (size_t)ntri++ * 9;
            memcpy(t, v + (size_t)c[0].v * 3, 3 * sizeof *t);
            memcpy(t + 3, v + (size_t)c[k].v * 3, 3 * sizeof *t);
            memcpy(t + 6, v + (size_t)c[k + 1].v * 3, 3 * sizeof *t);
        }
    }
    free(v);
    return finish(tri, ntri);
}

/* What the reference reads of an OBJ: positions alone, its triangle bound. */
static const obj_opts mesh_obj_opts = { .max_triangles = REF_MESH_MAX_TRIANGLES, .positions_only = true };

static ref_mesh *mesh_from_parsed(bool parsed, obj_data *d, const char *name, const ref_mesh_place *place,
                                  char *err, size_t errlen) {
    if (!parsed) return NULL;
    ref_mesh *m = ref_mesh_from_obj(d, name, place, err, errlen);
    obj_free(d);
    return m;
}

ref_mesh *ref_mesh_load(const char *path, const ref_mesh_place *place, char *err, size_t errlen) {
    obj_data d;
    return mesh_from_parsed(obj_read(&d, path, &mesh_obj_opts, err, errlen), &d, path, place, err, errlen);
}

ref_mesh *ref_mesh_parse(const char *text, size_t len, const char *name, const ref_mesh_place *place, char *err,
                         size_t errlen) {
    obj_data d;
    return mesh_from_parsed(obj_parse(&d, text, len, name, &mesh_obj_opts, err, errlen), &d, name, place, err,
                            errlen);
}

void ref_mesh_free(ref_mesh *m) {
    if (!m) return;
    free(m->tri);
    free(m->nrm);
    free(m->order);
    free(m->node);
    free(m);
}

int ref_mesh_count(const ref_mesh *m) { return m ? m->ntri : 0; }
const double *ref_mesh_triangle(const ref_mesh *m, int i) { return m->tri + (size_t)i * 9; }
const double *ref_mesh_normal(const ref_mesh *m, int i) { return m->nrm + (size_t)i * 3; }

void ref_mesh_bounds(const ref_mesh *m, double lo[3], double hi[3]) {
    for (int a = 0; a < 3; a++) { lo[a] = INFINITY; hi[a] = -INFINITY; }
    for (int i = 0; m && i < m->ntri; i++) {
        double l[3], h[3];
        tri_bounds(m->tri + (size_t)i * 9, l, h);
        for (int a = 0; a < 3; a++) { lo[a] = fmin(lo[a], l[a]); hi[a] = fmax(hi[a], h[a]); }
    }
}

/* ---- rays ---- */

/* Moller-Trumbore: t of the ray against triangle i, or NAN. */
static double tri_hit(const ref_mesh *m, int i, const double o[3], const double d[3]) {
    const double *a = m->tri + (size_t)i * 9;
    double e1[3], e2[3], s[3], p[3], q[3];
    for (int k = 0; k < 3; k++) { e1[k] = a[3 + k] - a[k]; e2[k] = a[6 + k] - a[k]; s[k] = o[k] - a[k]; }
    p[0] = d[1] * e2[2] - d[2] * e2[1];
    p[1] = d[2] * e2[0] - d[0] * e2[2];
    p[2] = d[0] * e2[1] - d[1] * e2[0];
    double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (fabs(det) < 1e-300) return NAN;
    double inv = 1.0 / det, u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) * inv;
    if (u < 0.0 || u > 1.0) return NAN;
    q[0] = s[1] * e1[2] - s[2] * e1[1];
    q[1] = s[2] * e1[0] - s[0] * e1[2];
    q[2] = s[0] * e1[1] - s[1] * e1[0];
    double v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) * inv;
    if (v < 0.0 || u + v > 1.0) return NAN;
    return (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * inv;
}

/* Does the ray meet the box within (tmin, tmax)? Conservatively: each
 * axis's interval is widened at both ends by BOX_T_REL of its t, so that no
 * box is culled whose triangles Moller-Trumbore puts inside (tmin, tmax).
 * Two roundings must be covered: the slab's own, at most gamma(3) of its t
 * (Pharr, Jakob and Humphreys, PBR 3rd ed. 3.9.2; a far-off ray at a mesh,
 * found by fuzz_obj), and tri_hit's, which puts a hit a few ulps of t
 * before the exact one; the box's padding in space cannot cover that for a
 * far ray, where one ulp of t is more than the padding (a ray from 4e8 away
 * through a triangle's corner on the box's face, found by fuzz_obj). The
 * error of tri_hit's t is about 8 eps times the triangle's aspect over the
 * cosine of the ray with its normal, times its first corner's distance
 * from the origin over the hit's (ref_mesh.h); 1e-9 covers that up to 1e5
 * and costs a box whose entry is within 1e-9 of the best t, a near tie. */
#define BOX_T_REL 1e-9
static bool box_hit(const bvh_node *nd, const double o[3], const double d[3], double tmin, double tmax) {
    double t0 = tmin, t1 = tmax;
    for (int a = 0; a < 3; a++) {
        if (d[a] == 0.0) {
            if (o[a] < nd->lo[a] || o[a] > nd->hi[a]) return false;
            continue;
        }
        double ta = (nd->lo[a] - o[a]) / d[a], tb = (nd->hi[a] - o[a]) / d[a];
        if (ta > tb) { double s = ta; ta = tb; tb = s; }
        ta -= fabs(ta) * BOX_T_REL;
        tb += fabs(tb) * BOX_T_REL;
        if (ta > t0) t0 = ta;
        if (tb < t1) t1 = tb;
        if (t0 > t1) return false;
    }
    return true;
}

bool ref_mesh_hit(const ref_mesh *m, const double o[3], const double d[3], double tmin, double tmax,
                  double *t, double n[3]) {
    if (!m) return false;
    int stack[128], sp = 0, best = -1;
    double best_t = tmax;
    stack[sp++] = 0;
    while (sp > 0) {
        const bvh_node *nd = &m->node[stack[--sp]];
        if (!box_hit(nd, o, d, tmin, best_t)) continue;
        if (nd->count > 0) {
            for (int k = 0; k < nd->count; k++) {
                int i = m->order[nd->first + k];
                double ti = tri_hit(m, i, o, d);
                if (ti > tmin && ti < best_t) { best_t = ti; best = i; }
            }
        } else if (sp + 2 <= (int)(sizeof stack / sizeof stack[0])) {
            stack[sp++] = nd->first + 1;
            stack[sp++] = nd->first;
        }
    }
    if (best < 0) return false;
    *t = best_t;
    memcpy(n, m->nrm + (size_t)best * 3, 3 * sizeof *n);
    return true;
}

bool ref_mesh_hit_brute(const ref_mesh *m, const double o[3], const double d[3], double tmin,
                        double tmax, double *t, double n[3]) {
    int best = -1;
    double best_t = tmax;
    for (int i = 0; m && i < m->ntri; i++) {
        double ti = tri_hit(m, i, o, d);
        if (ti > tmin && ti < best_t) { best_t = ti; best = i; }
    }
    if (best < 0) return false;
    *t = best_t;
    memcpy(n, m->nrm + (size_t)best * 3, 3 * sizeof *n);
    return true;
}
