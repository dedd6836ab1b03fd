/* geom_obj.c: Wavefront OBJ meshes (Obj, WireObj, ObjAdj, ObjPatch; geom.h):
 * the file read by tarn's one OBJ reader (base/obj.h), then made a mesh
 * here: one vertex per distinct (v, vt, vn) corner, polygons fanned,
 * missing normals from the faces around, tangents from the texture
 * coordinates. */
#include "geom_build.h"
#include "mem.h"
#include "obj.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- tangents from texture coordinates (OBJ) ---- */

/* A sum of area-weighted directions as floats (made unit later, mb_finish):
 * one too large or too small for a float is scaled first, keeping its
 * direction (an OBJ in light years, or in nanometres). */
static void store_direction(float out[3], const double a[3]) {
    double big = fmax(fabs(a[0]), fmax(fabs(a[1]), fabs(a[2])));
    double s = big > 1e30 || (big > 0 && big < 1e-30) ? big : 1;
    for (int c = 0; c < 3; c++) out[c] = (float)(a[c] / s);
}

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
    for (int k = 0; k < m->nvert; k++) store_direction(m->tan + 3 * k, acc + 3 * k);
    free(acc);
}

/* ---- the mesh of an OBJ ---- */

typedef struct obj_build {
    const obj_data *d;
    double *acc;                /* area-weighted normal sum per position */
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
} obj_build;

static uint64_t corner_hash(int v, int t, int n) {
    uint64_t h = (uint64_t)(uint32_t)v * 0x9E3779B97F4A7C15ULL;
    h ^= (uint64_t)(uint32_t)t * 0xC2B2AE3D27D4EB4FULL + (h << 6) + (h >> 2);
    h ^= (uint64_t)(uint32_t)n * 0x165667B19E3779F9ULL + (h << 6) + (h >> 2);
    return h ^ (h >> 29);
}

static void table_grow(obj_build *o) {
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
static int corner_vertex(obj_build *o, int v, int t, int n) {
    if ((o->hcount + 1) * 2 > o->hcap) table_grow(o);
    size_t at = corner_hash(v, t, n) & (o->hcap - 1);
    while (o->hval[at] >= 0) {
        const int *k = o->hkey + 3 * at;
        if (k[0] == v && k[1] == t && k[2] == n) return o->hval[at];
        at = (at + 1) & (o->hcap - 1);
    }
    const obj_data *d = o->d;
    const double *p = d->v + 3 * (size_t)v;
    double nn[3] = {0, 0, 0}, tan[3] = {0, 0, 0};
    if (n >= 0) memcpy(nn, d->vn + 3 * (size_t)n, sizeof nn);
    double u = t >= 0 ? d->vt[2 * (size_t)t] : 0, w = t >= 0 ? d->vt[2 * (size_t)t + 1] : 0;
    int k = mb_vert(&o->b, p, nn, u, w, tan);
    if (!o->b.ok) return -1;
    if (k >= o->ncorner_cap) {
        int ncap = o->ncorner_cap ? o->ncorner_cap * 2 : 1024;
        geom_grow((void **)&o->corner_v, sizeof(int), ncap);
        geom_grow((void **)&o->corner_n, sizeof(int), ncap);
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
static void keep_polygon(obj_build *o, const int *vis, int ntok) {
    if (o->npoly + ntok > o->poly_cap) {   /* obj_parse's limits keep this in int */
        int cap = o->poly_cap ? o->poly_cap : 256;
        while (cap < o->npoly + ntok) cap *= 2;
        geom_grow((void **)&o->poly, sizeof *o->poly, cap);
        o->poly_cap = cap;
    }
    for (int c = 0; c < ntok; c++) o->poly[o->npoly++] = (unsigned)vis[2 * c];
    o->face_n = o->face_n == 0 ? ntok : o->face_n == ntok ? ntok : -1;
}

/* One face: its corners' vertices, its fan, its area on its positions. */
static bool add_face(obj_build *o, const obj_corner *corner, int ntok) {
    const obj_data *d = o->d;
    double area[3] = {0, 0, 0};
    int *vis = mem_alloc((size_t)ntok * 2 * sizeof *vis);
    for (int c = 0; c < ntok; c++) {
        int k = corner_vertex(o, corner[c].v, corner[c].vt, corner[c].vn);
        if (k < 0) { free(vis); return false; }
        vis[2 * c] = k;
        vis[2 * c + 1] = corner[c].v;
    }
    if (o->keep_polys) keep_polygon(o, vis, ntok);
    /* fan triangles, and the polygon's area vector (sum of the fan's) */
    for (int c = 1; c + 1 < ntok; c++) {
        mb_tri(&o->b, vis[0], vis[2 * c], vis[2 * c + 2]);
        const double *p0 = d->v + 3 * (size_t)vis[1], *p1 = d->v + 3 * (size_t)vis[2 * c + 1],
                     *p2 = d->v + 3 * (size_t)vis[2 * c + 3];
        double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]}, cr[3];
        v3cross(cr, e1, e2);
        for (int k = 0; k < 3; k++) area[k] += cr[k];
    }
    /* every corner's position gets the whole polygon's area vector */
    for (int c = 0; c < ntok; c++) {
        bool seen = false;      /* a position used twice in one polygon counts once */
        for (int e = 0; e < c; e++) seen = seen || vis[2 * e + 1] == vis[2 * c + 1];
        if (seen) continue;
        for (int k = 0; k < 3; k++) o->acc[3 * (size_t)vis[2 * c + 1] + k] += area[k];
    }
    free(vis);
    return o->b.ok;
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

static bool build_fail(geom_mesh *m, char *err, int errlen, const char *name, const char *why) {
    if (err && errlen > 0) snprintf(err, (size_t)errlen, "%s: %s", name ? name : "(null)", why);
    memset(m, 0, sizeof *m);
    return false;
}

static bool fits_float(const double *a, long n) {
    for (long i = 0; i < n; i++)
        if (!(fabs(a[i]) <= FLT_MAX)) return false;
    return true;
}

static bool obj_mesh(geom_mesh *m, const obj_data *d, const char *name, char *err, int errlen, obj_extra *x) {
    memset(m, 0, sizeof *m);
    if (d->nface == 0) return build_fail(m, err, errlen, name, "no faces");
    if (!fits_float(d->v, 3L * d->nv) || !fits_float(d->vt, 2L * d->nvt) || !fits_float(d->vn, 3L * d->nvn))
        return build_fail(m, err, errlen, name, "a number too large for a float (at most 3.4e38)");
    obj_build o;
    memset(&o, 0, sizeof o);
    o.d = d;
    o.keep_polys = x && x->keep_polys;
    o.acc = mem_zalloc((size_t)d->nv * 3 * sizeof *o.acc);
    mb_init(&o.b, false);
    bool ok = true;
    for (int f = 0; f < d->nface && ok; f++)
        ok = add_face(&o, d->corner + d->face_first[f], d->face_first[f + 1] - d->face_first[f]);
    if (ok) {
        /* normals: given ones as they are; the others from the faces around */
        for (int k = 0; k < o.b.m.nvert; k++) {
            float *n = o.b.m.nrm + 3 * k;
            double given[3] = {n[0], n[1], n[2]};
            if (o.corner_n[k] >= 0 && v3normalize(given)) continue;
            store_direction(n, o.acc + 3 * (size_t)o.corner_v[k]);
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
    free(o.acc); free(o.poly);
    free(o.corner_v); free(o.corner_n); free(o.hkey); free(o.hval);
    if (!ok) {
        o.b.ok = false;
        mb_finish(&o.b, m);
        return build_fail(m, err, errlen, name, "too many vertices or faces for one mesh");
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

/* WireObj: each edge of the triangles once, as GL_LINES. */
static void to_wire(geom_mesh *m, obj_extra *x) {
    int n = 0;
    edge_rec *e = sorted_edges(m, x->pos_of, &n);
    unsigned *idx = mem_alloc(sizeof *idx * (size_t)(2 * (n > 0 ? n : 1)));
    int k = 0;
    for (int i = 0; i < n; i++) {
        if (i > 0 && e[i].a == e[i - 1].a && e[i].b == e[i - 1].b) continue;   /* drawn once */
        idx[k++] = e[i].va;
        idx[k++] = e[i].vb;
    }
    free(e);
    free(m->idx);
    m->idx = idx;
    m->nidx = k;
    m->prim = GEOM_LINES;
}

/* ObjAdj: the triangles with their neighbours' far corners. */
static void to_adjacency(geom_mesh *m, obj_extra *x) {
    int n = 0, ntri = m->nidx / 3;
    edge_rec *e = sorted_edges(m, x->pos_of, &n);
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
    free(m->idx);
    m->idx = idx;
    m->nidx = 6 * ntri;
    m->prim = GEOM_TRIANGLES_ADJACENCY;
}

#define GEOM_MAX_PATCH 32   /* GL's least GL_MAX_PATCH_VERTICES */

/* ObjPatch: each face one patch when all have the same corners, else triangles. */
static void to_patches(geom_mesh *m, obj_extra *x) {
    m->prim = GEOM_PATCHES;
    m->patch_size = 3;
    if (x->face_n >= 3 && x->face_n <= GEOM_MAX_PATCH && x->poly) {   /* each face one patch */
        free(m->idx);
        m->idx = x->poly;
        m->nidx = x->npoly;
        m->patch_size = x->face_n;
        x->poly = NULL;
    }
}

bool geom_obj_mesh(geom_mesh *m, const obj_data *d, geom_prim prim, const char *name, char *err, int errlen) {
    if (!m) return false;
    memset(m, 0, sizeof *m);
    if (err && errlen > 0) err[0] = 0;
    if (!d || (prim != GEOM_TRIANGLES && prim != GEOM_LINES && prim != GEOM_TRIANGLES_ADJACENCY &&
               prim != GEOM_PATCHES))
        return build_fail(m, err, errlen, name, "no OBJ, or a primitive an OBJ is not drawn as");
    obj_extra x = {.keep_polys = prim == GEOM_PATCHES};
    if (!obj_mesh(m, d, name, err, errlen, prim == GEOM_TRIANGLES ? NULL : &x)) return false;
    if (prim == GEOM_LINES) to_wire(m, &x);
    else if (prim == GEOM_TRIANGLES_ADJACENCY) to_adjacency(m, &x);
    else if (prim == GEOM_PATCHES) to_patches(m, &x);
    free(x.pos_of);
    free(x.poly);
    return true;
}

bool geom_obj_read(geom_mesh *m, struct file_cache *files, const char *path, geom_prim prim, char *err,
                   int errlen) {
    if (!m) return false;
    memset(m, 0, sizeof *m);
    obj_data d;
    obj_opts o = { .max_abs = FLT_MAX,   /* the mesh is floats: a larger number is refused at its line */
                   .files = files };
    if (!obj_read(&d, path, &o, errlen > 0 ? err : NULL, errlen > 0 ? (size_t)errlen : 0)) return false;
    bool ok = geom_obj_mesh(m, &d, prim, path, err, errlen);
    obj_free(&d);
    return ok;
}

bool geom_obj_load(geom_mesh *m, const char *path, char *err, int errlen) {
    return geom_obj_read(m, NULL, path, GEOM_TRIANGLES, err, errlen);
}

bool geom_obj_load_wire(geom_mesh *m, const char *path, char *err, int errlen) {
    return geom_obj_read(m, NULL, path, GEOM_LINES, err, errlen);
}

bool geom_obj_load_adjacency(geom_mesh *m, const char *path, char *err, int errlen) {
    return geom_obj_read(m, NULL, path, GEOM_TRIANGLES_ADJACENCY, err, errlen);
}

bool geom_obj_load_patches(geom_mesh *m, const char *path, char *err, int errlen) {
    return geom_obj_read(m, NULL, path, GEOM_PATCHES, err, errlen);
}
