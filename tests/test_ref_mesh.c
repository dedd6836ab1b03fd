/* ref_mesh: the OBJ reader, placing, and rays through the BVH against the
 * truth of testing every triangle (the same Moller-Trumbore, so the same t
 * to the bit), closed forms on a cube, the shipped models' winding (a ray
 * from outside meets a facet that faces it), and bad files. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "ref_mesh.h"
#include "ref_scene.h"

static uint64_t rng = 0x243f6a8885a308d3ull;

static double urand(void) {   /* xorshift64*, [0, 1) */
    rng ^= rng >> 12;
    rng ^= rng << 25;
    rng ^= rng >> 27;
    return (double)((rng * 0x2545f4914f6cdd1dull) >> 11) * 0x1.0p-53;
}

static void unit_dir(double d[3]) {
    double z = 2 * urand() - 1, a = 2 * M_PI * urand(), r = sqrt(1 - z * z);
    d[0] = r * cos(a);
    d[1] = z;
    d[2] = r * sin(a);
}

static char tmpdir[] = "/tmp/tarn-test-mesh-XXXXXX";

static const char *write_obj(const char *name, const char *text) {
    static char path[256];
    snprintf(path, sizeof path, "%s/%s", tmpdir, name);
    FILE *f = fopen(path, "w");
    CHECK_NE(f, NULL);
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    return path;
}

/* A unit cube [-0.5, 0.5]^3 in quads, wound counter-clockwise from outside. */
static const char cube_obj[] =
    "# cube\nv -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
    "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 5 8 4\nf 2 3 7 6\nf 4 8 7 3\nf 1/1 2/2/2 6//6 -4\n";

static void test_cube_closed_forms(void) {
    char err[256] = "";
    ref_mesh *m = ref_mesh_load(write_obj("cube.obj", cube_obj), NULL, err, sizeof err);
    CHECK_MSG(m != NULL, "%s", err);
    if (!m) return;
    CHECK_EQ(ref_mesh_count(m), 12);
    double o[3] = { 0.1, 0.2, 5 }, d[3] = { 0, 0, -1 }, t, n[3];
    CHECK(ref_mesh_hit(m, o, d, 0, 1e9, &t, n));
    CHECK_EQ(t, 4.5);                       /* the +z face, exactly */
    CHECK(n[0] == 0 && n[1] == 0 && n[2] == 1);
    CHECK(!ref_mesh_hit(m, o, d, 0, 4.4, &t, n));   /* tmax before it */
    CHECK(ref_mesh_hit(m, o, d, 4.6, 1e9, &t, n));  /* tmin past it: the back face */
    CHECK(t == 5.5 && n[2] == -1);
    double lo[3], hi[3];
    ref_mesh_bounds(m, lo, hi);
    CHECK(lo[0] == -0.5 && hi[1] == 0.5);
    ref_mesh_free(m);

    /* placed: turned 90 degrees about +y (x goes to -z), scaled 2, moved */
    ref_mesh_place pl = { { 10, 1, -3 }, 90, 2 };
    m = ref_mesh_load(write_obj("cube.obj", cube_obj), &pl, err, sizeof err);
    CHECK_NE(m, NULL);
    if (!m) return;
    ref_mesh_bounds(m, lo, hi);
    CHECK_NEAR(lo[0], 9, 1e-12);
    CHECK_NEAR(hi[0], 11, 1e-12);
    CHECK_NEAR(lo[1], 0, 1e-12);
    CHECK_NEAR(hi[2], -2, 1e-12);
    double o2[3] = { 10, 1, 10 }, d2[3] = { 0, 0, -1 };
    CHECK(ref_mesh_hit(m, o2, d2, 0, 1e9, &t, n));
    CHECK_NEAR(t, 12, 1e-12);
    CHECK_NEAR(n[2], 1, 1e-12);
    ref_mesh_free(m);
}

/* Random rays at the mesh: hit or miss and t the same as every triangle
 * gives; half the rays aimed at a random triangle's inside, so most hit. */
static int bvh_against_brute(const ref_mesh *m, int nrays) {
    double lo[3], hi[3], c[3], r = 0;
    ref_mesh_bounds(m, lo, hi);
    for (int a = 0; a < 3; a++) {
        c[a] = 0.5 * (lo[a] + hi[a]);
        r += (hi[a] - lo[a]) * (hi[a] - lo[a]);
    }
    r = sqrt(r);
    int hits = 0, bad = 0;
    for (int k = 0; k < nrays; k++) {
        double o[3], d[3];
        unit_dir(d);
        for (int a = 0; a < 3; a++) o[a] = c[a] + 1.5 * r * (2 * urand() - 1);
        if (k % 2 == 0) {   /* aim at a point inside a random triangle */
            const double *t = ref_mesh_triangle(m, (int)(urand() * ref_mesh_count(m)));
            double u = urand(), v = urand();
            if (u + v > 1) u = 1 - u, v = 1 - v;
            double l = 0;
            for (int a = 0; a < 3; a++) {
                d[a] = t[a] + u * (t[3 + a] - t[a]) + v * (t[6 + a] - t[a]) - o[a];
                l += d[a] * d[a];
            }
            l = sqrt(l);
            for (int a = 0; a < 3; a++) d[a] /= l;
        }
        double tb, tf, nb[3], nf[3];
        bool hb = ref_mesh_hit(m, o, d, 1e-9, 1e9, &tb, nb), hf = ref_mesh_hit_brute(m, o, d, 1e-9, 1e9, &tf, nf);
        if (hb != hf || (hb && tb != tf)) {
            if (bad++ < 5)
                fprintf(stderr, "  ray %d: bvh %d t=%.17g, brute %d t=%.17g\n", k, hb, hb ? tb : 0, hf, hf ? tf : 0);
        }
        hits += hf;
    }
    CHECK_EQ(bad, 0);
    return hits;
}

static void test_bvh_equals_brute_force(void) {
    /* a soup of 2000 random triangles: overlapping, thin, every orientation */
    int n = 2000;
    double *tri = malloc((size_t)n * 9 * sizeof *tri);
    for (int i = 0; i < n; i++) {
        double c[3] = { 20 * urand() - 10, 20 * urand() - 10, 20 * urand() - 10 };
        for (int k = 0; k < 3; k++)
            for (int a = 0; a < 3; a++) tri[i * 9 + k * 3 + a] = c[a] + 1.5 * (2 * urand() - 1);
    }
    ref_mesh *m = ref_mesh_from_triangles(tri, n);
    free(tri);
    CHECK_NE(m, NULL);
    if (m) {
        int hits = bvh_against_brute(m, 20000);
        fprintf(stderr, "  soup: %d of 20000 rays hit\n", hits);
        CHECK_GT(hits, 8000);
        ref_mesh_free(m);
    }
    /* the shipped models, placed as scenes/harbour.glib has them */
    const char *models[] = { "boat", "rock", "pier" };
    for (int i = 0; i < 3; i++) {
        char path[512], err[256];
        snprintf(path, sizeof path, "%s/data/models/%s.obj", TARN_SOURCE_DIR, models[i]);
        ref_mesh_place pl = { { 6.2, 0.1, -0.8 }, 25, 1.3 };
        m = ref_mesh_load(path, &pl, err, sizeof err);
        CHECK_MSG(m != NULL, "%s", err);
        if (!m) continue;
        int hits = bvh_against_brute(m, 20000);
        fprintf(stderr, "  %s: %d triangles, %d of 20000 rays hit\n", models[i], ref_mesh_count(m), hits);
        CHECK_GT(hits, 8000);
        ref_mesh_free(m);
    }
}

/* The models are wound counter-clockwise from outside: a ray from far
 * outside meets first a facet whose normal faces it (what both renderers
 * shade; a flipped facet would be lit from behind). */
static void test_models_face_outwards(void) {
    const char *models[] = { "boat", "rock", "pier" };
    for (int i = 0; i < 3; i++) {
        char path[512], err[256];
        snprintf(path, sizeof path, "%s/data/models/%s.obj", TARN_SOURCE_DIR, models[i]);
        ref_mesh *m = ref_mesh_load(path, NULL, err, sizeof err);
        CHECK_MSG(m != NULL, "%s", err);
        if (!m) continue;
        CHECK(ref_mesh_count(m) >= 100 && ref_mesh_count(m) <= 2000);   /* small models */
        int hits = 0, backs = 0;
        for (int k = 0; k < 5000; k++) {
            double o[3], d[3], t, n[3];
            unit_dir(o);
            for (int a = 0; a < 3; a++) o[a] *= 20;
            const double *tr = ref_mesh_triangle(m, (int)(urand() * ref_mesh_count(m)));
            double l = 0;
            for (int a = 0; a < 3; a++) {
                d[a] = (tr[a] + tr[3 + a] + tr[6 + a]) / 3 - o[a];
                l += d[a] * d[a];
            }
            for (int a = 0; a < 3; a++) d[a] /= sqrt(l);
            if (!ref_mesh_hit(m, o, d, 0, 1e9, &t, n)) continue;
            hits++;
            if (n[0] * d[0] + n[1] * d[1] + n[2] * d[2] > 0) backs++;
        }
        fprintf(stderr, "  %s: %d hits from outside, %d on a back face\n", models[i], hits, backs);
        CHECK_GT(hits, 4000);
        CHECK_EQ(backs, 0);
        ref_mesh_free(m);
    }
}

static void test_bad_files(void) {
    char err[256] = "";
    CHECK_EQ(ref_mesh_load(write_obj("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n"), NULL, err, sizeof err), NULL);
    CHECK_STR_CONTAINS(err, "bad.obj:3:");
    CHECK_STR_CONTAINS(err, "does not exist");
    CHECK_EQ(ref_mesh_load(write_obj("bad2.obj", "v 0 0\n"), NULL, err, sizeof err), NULL);
    CHECK_STR_CONTAINS(err, "bad2.obj:1:");
    CHECK_EQ(ref_mesh_load(write_obj("empty.obj", "# nothing\nv 0 0 0\n"), NULL, err, sizeof err), NULL);
    CHECK_STR_CONTAINS(err, "no triangles");
    CHECK_EQ(ref_mesh_load("/nonexistent/x.obj", NULL, err, sizeof err), NULL);
    CHECK_STR_CONTAINS(err, "/nonexistent/x.obj");
    CHECK_EQ(ref_mesh_from_triangles(NULL, 0), NULL);
}

/* A world's mesh object is hit through ref_objects_hit, with its albedo. */
static void test_world_object(void) {
    ref_world_desc d;
    memset(&d, 0, sizeof d);
    d.nobjects = 1;
    d.objects[0].kind = REF_OBJECT_MESH;
    snprintf(d.objects[0].mesh_path, sizeof d.objects[0].mesh_path, "%s", write_obj("cube.obj", cube_obj));
    d.objects[0].center[0] = 3;
    d.objects[0].size[0] = 2;
    ref_world w;
    ref_world_init(&w, &d);
    double o[3] = { 3, 0, 10 }, dir[3] = { 0, 0, -1 }, t, n[3];
    CHECK_EQ(ref_objects_hit(&w, o, dir, 0, 1e9, &t, n), 0);
    CHECK_EQ(t, 9);
    ref_world_release(&w);
}

int main(void) {
    CHECK_NE(mkdtemp(tmpdir), NULL);
    RUN(test_cube_closed_forms);
    RUN(test_bvh_equals_brute_force);
    RUN(test_models_face_outwards);
    RUN(test_bad_files);
    RUN(test_world_object);
    const char *names[] = { "cube.obj", "bad.obj", "bad2.obj", "empty.obj" };
    for (int i = 0; i < 4; i++) {
        char p[256];
        snprintf(p, sizeof p, "%s/%s", tmpdir, names[i]);
        remove(p);
    }
    rmdir(tmpdir);
    return check_summary();
}
