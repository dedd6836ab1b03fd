/* fuzz_obj: libFuzzer target for tarn's one OBJ reader (base/obj.h) and its
 * two users without OpenGL: obj_parse on the bytes (as they are, as the
 * reference reads them with positions_only, and with a small triangle
 * limit), the reference's mesh and its BVH (ref_mesh_from_obj, rays
 * against it and against every triangle), and the viewer's OBJ meshes
 * (geom_obj_mesh, pure C, compiled in: Obj, WireObj, ObjAdj, ObjPatch).
 *
 * Invariants checked beyond "no crash, no sanitizer report, no leak":
 * every index in range, faces of 3 or more corners whose fans add up to
 * ntri, finite numbers, an error message naming the text, the lenient
 * reading accepting what the strict one does with the same faces, the
 * BVH agreeing with brute force, meshes with in-range indices and no NaN.
 *
 * Built with libFuzzer when TARN_FUZZ is on (tests/fuzz/fuzz_build.cmake);
 * in a normal build replay_main.c replays the corpus and the regressions. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geom.h"
#include "obj.h"
#include "ref_mesh.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerInitialize(int *argc, char ***argv) {
    (void)argc; (void)argv;
    return 0;
}

static void check(bool ok, const char *what) {
    if (!ok) { fprintf(stderr, "fuzz_obj: invariant broken: %s\n", what); abort(); }
}

static bool finite_all(const double *a, long n) {
    for (long i = 0; i < n; i++)
        if (!isfinite(a[i])) return false;
    return true;
}

static bool fits_float(const double *a, long n) {
    for (long i = 0; i < n; i++)
        if (!(fabs(a[i]) <= FLT_MAX)) return false;
    return true;
}

static void check_data(const obj_data *d, bool positions_only) {
    check(d->nv >= 0 && d->nvt >= 0 && d->nvn >= 0 && d->nface >= 0 && d->ncorner >= 0, "counts >= 0");
    check(finite_all(d->v, 3L * d->nv) && finite_all(d->vt, 2L * d->nvt) && finite_all(d->vn, 3L * d->nvn),
          "finite numbers");
    if (d->color) check(finite_all(d->color, 3L * d->nv), "finite colours");
    if (d->nface == 0) { check(d->ntri == 0 && d->ncorner == 0, "no face, no corner"); return; }
    check(d->face_first[0] == 0 && d->face_first[d->nface] == d->ncorner, "faces cover the corners");
    long tri = 0;
    for (int f = 0; f < d->nface; f++) {
        int n = d->face_first[f + 1] - d->face_first[f];
        check(n >= 3, "a face has 3 corners or more");
        tri += n - 2;
    }
    check(tri == d->ntri, "ntri is the fans' triangles");
    for (int c = 0; c < d->ncorner; c++) {
        const obj_corner *k = &d->corner[c];
        check(k->v >= 0 && k->v < d->nv, "v index in range");
        check(k->vt >= -1 && k->vt < d->nvt, "vt index in range");
        check(k->vn >= -1 && k->vn < d->nvn, "vn index in range");
        if (positions_only) check(k->vt == -1 && k->vn == -1, "positions only: no vt, vn");
    }
}

static void check_mesh(const geom_mesh *m, geom_prim prim) {
    check(m->prim == prim, "the primitive asked for");
    check(m->nvert > 0 && m->nidx > 0, "a mesh with vertices and indices");
    int per = prim == GEOM_LINES ? 2 : prim == GEOM_TRIANGLES_ADJACENCY ? 6 : prim == GEOM_PATCHES ? m->patch_size : 3;
    check(per >= 2 && m->nidx % per == 0, "whole primitives");
    for (int i = 0; i < m->nidx; i++) check(m->idx[i] < (unsigned)m->nvert, "index in range");
    for (long i = 0; i < 3L * m->nvert; i++)
        check(isfinite(m->pos[i]) && isfinite(m->nrm[i]) && isfinite(m->tan[i]), "finite vertices");
    for (long i = 0; i < 2L * m->nvert; i++) check(isfinite(m->tc[i]), "finite tc");
}

/* How much rounding Moller-Trumbore's t of triangle i can carry, relative
 * to t, for the ray o + t d: the triangle's aspect, |e1| |e2| / |e1 x e2|,
 * over the cosine of the ray with its normal, times how much farther its
 * first corner is from o than the hit (its t is the triple product of
 * o - a with the edges, rounded at that size). ref_mesh.c's box test covers
 * conditions up to 1e5 exactly; INFINITY for a degenerate triangle or a
 * grazing ray. */
static double hit_condition(const ref_mesh *m, int i, const double o[3], const double d[3], double t_hit) {
    if (i < 0) return INFINITY;
    const double *t = ref_mesh_triangle(m, i);
    double e1[3], e2[3], c[3];
    for (int a = 0; a < 3; a++) { e1[a] = t[3 + a] - t[a]; e2[a] = t[6 + a] - t[a]; }
    c[0] = e1[1] * e2[2] - e1[2] * e2[1];
    c[1] = e1[2] * e2[0] - e1[0] * e2[2];
    c[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double lc = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    double l2 = sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
    double ld = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double cosine = fabs(c[0] * d[0] + c[1] * d[1] + c[2] * d[2]) / (lc * ld);
    double sa[3] = { o[0] - t[0], o[1] - t[1], o[2] - t[2] };
    double far = sqrt(sa[0] * sa[0] + sa[1] * sa[1] + sa[2] * sa[2]) / (t_hit * ld);
    double cond = l1 * l2 / lc / cosine * fmax(far, 1.0);
    return isfinite(cond) ? cond : INFINITY;
}

/* The triangle brute force hits at t: the first whose own t it is. */
static int triangle_at(const ref_mesh *m, const double o[3], const double d[3], double t) {
    for (int i = 0; i < ref_mesh_count(m); i++) {
        ref_mesh *one = ref_mesh_from_triangles(ref_mesh_triangle(m, i), 1);
        double ti, n[3];
        bool hit = ref_mesh_hit_brute(one, o, d, 1e-9, 1e30, &ti, n);
        ref_mesh_free(one);
        if (hit && ti == t) return i;
    }
    return -1;
}

/* Rays from a few places at the mesh: the BVH and every triangle agree
 * exactly where the nearest hit is well conditioned (ref_mesh.h promises
 * it); on a sliver or a grazing ray the BVH may skip a triangle whose t
 * rounding put before its box, so there it is only never nearer than brute
 * force (it tests a subset). For a mesh within 1e9 of the origin (world
 * meshes are metres; far beyond, a ray through a unit triangle is not
 * defined to a unit). */
static void check_rays(const ref_mesh *m) {
    double lo[3], hi[3];
    ref_mesh_bounds(m, lo, hi);
    for (int a = 0; a < 3; a++)
        if (!(fabs(lo[a]) <= 1e9 && fabs(hi[a]) <= 1e9)) return;
    for (int r = 0; r < 8; r++) {
        double o[3], d[3];
        const double *t = ref_mesh_triangle(m, (r * 7919) % ref_mesh_count(m));
        for (int a = 0; a < 3; a++) {
            double c = (t[a] + t[3 + a] + t[6 + a]) / 3;
            o[a] = (r & (1 << a)) ? hi[a] + 1 : lo[a] - 1;
            d[a] = c - o[a];
        }
        double tb = 0, tf = 0, nb[3], nf[3];
        bool hb = ref_mesh_hit(m, o, d, 1e-9, 1e30, &tb, nb), hf = ref_mesh_hit_brute(m, o, d, 1e-9, 1e30, &tf, nf);
        if (!isfinite(o[0] + o[1] + o[2] + d[0] + d[1] + d[2])) continue;   /* huge coordinates overflow */
        check(!hb || (hf && tb >= tf), "the BVH is never nearer than every triangle");
        if (!(hb == hf && (!hb || tb == tf)))   /* a difference is allowed on an ill-conditioned hit only */
            check(hit_condition(m, triangle_at(m, o, d, tf), o, d, tf) > 1e5, "BVH and brute force agree");
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    const char *text = (const char *)data;
    char err[512];
    obj_data d, lenient, small;
    bool ok = obj_parse(&d, text, size, "fuzz.obj", NULL, err, sizeof err);
    if (ok) check_data(&d, false);
    else check(!strncmp(err, "fuzz.obj:", 9) && d.nv == 0 && d.v == NULL, "an error names the text, d empty");

    obj_opts po = { .positions_only = true, .max_triangles = 1 << 12 };
    bool lok = obj_parse(&lenient, text, size, "fuzz.obj", &po, err, sizeof err);
    if (lok) check_data(&lenient, true);
    if (ok && d.ntri <= po.max_triangles)
        check(lok && lenient.nface == d.nface && lenient.nv == d.nv, "positions only reads what the full reading does");

    obj_opts so = { .max_triangles = 3 };
    bool sok = obj_parse(&small, text, size, "fuzz.obj", &so, err, sizeof err);
    check(!sok || small.ntri <= 3, "the triangle limit holds");
    if (ok) check(sok == (d.ntri <= 3), "the triangle limit is the only difference");
    obj_free(&small);

    if (lok && lenient.ntri > 0) {
        ref_mesh_place pl = { { 1, -2, 3 }, 30, 2 };
        ref_mesh *m = ref_mesh_from_obj(&lenient, "fuzz.obj", &pl, err, sizeof err);
        check(m != NULL && ref_mesh_count(m) == lenient.ntri, "a mesh of every triangle");
        if (m) check_rays(m);
        ref_mesh_free(m);
    }
    obj_free(&lenient);

    bool floats = ok && fits_float(d.v, 3L * d.nv) && fits_float(d.vt, 2L * d.nvt) && fits_float(d.vn, 3L * d.nvn);
    static const geom_prim prims[] = { GEOM_TRIANGLES, GEOM_LINES, GEOM_TRIANGLES_ADJACENCY, GEOM_PATCHES };
    for (int k = 0; k < 4; k++) {
        geom_mesh m;
        bool gok = geom_obj_mesh(&m, ok ? &d : NULL, prims[k], "fuzz.obj", err, sizeof err);
        check(gok == (floats && d.nface > 0), "a mesh for every OBJ with faces and float-sized numbers");
        if (gok) check_mesh(&m, prims[k]);
        else check(m.pos == NULL && m.idx == NULL && !strncmp(err, "fuzz.obj: ", 10), "a failed mesh is empty, named");
        geom_free(&m);
    }
    obj_free(&d);
    return 0;
}
