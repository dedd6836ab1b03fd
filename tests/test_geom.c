/* test_geom: meshes for the geometry commands (viewer/gfx/geom.h).
 *
 * Truth is geometric: points on a sphere are at distance r, a closed mesh
 * encloses the volume of its solid (divergence theorem, which also checks
 * that triangles wind outward), normals agree with the faces, tangents
 * follow +u of the texture coordinates, and the teapot has Newell's
 * proportions (3.15 tall, body 4 across, handle to spout -3 .. 3.43). */
#include "check.h"
#include "geom.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PI 3.14159265358979323846

static char tmpdir[256];

/* ---- helpers ---- */

static const float *P(const geom_mesh *m, unsigned k) { return m->pos + 3 * k; }
static const float *N(const geom_mesh *m, unsigned k) { return m->nrm + 3 * k; }
static const float *T(const geom_mesh *m, unsigned k) { return m->tan + 3 * k; }

static double dot3(const float *a, const float *b) { return (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2]; }
static double len3(const float *a) { return sqrt(dot3(a, a)); }

static void face_normal(const geom_mesh *m, const unsigned *t, double out[3]) {
    const float *a = P(m, t[0]), *b = P(m, t[1]), *c = P(m, t[2]);
    double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    out[0] = e1[1] * e2[2] - e1[2] * e2[1];
    out[1] = e1[2] * e2[0] - e1[0] * e2[2];
    out[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

/* Finite, unit normals and tangents, tangent perpendicular, indices valid. */
static void check_sane(const geom_mesh *m, const char *what) {
    CHECK_MSG(m->nvert > 0 && m->nidx > 0 && m->pos && m->nrm && m->tc && m->tan && m->idx, "%s empty", what);
    CHECK_MSG(m->nidx % ((m->prim == GEOM_LINES) ? 2 : 3) == 0, "%s: %d indices", what, m->nidx);
    int bad = 0;
    for (int k = 0; k < m->nvert; k++) {
        for (int c = 0; c < 3; c++)
            bad += !isfinite(m->pos[3 * k + c]) || !isfinite(m->nrm[3 * k + c]) || !isfinite(m->tan[3 * k + c]);
        bad += !isfinite(m->tc[2 * k]) || !isfinite(m->tc[2 * k + 1]);
        bad += fabs(len3(N(m, k)) - 1) > 1e-5;
        bad += fabs(len3(T(m, k)) - 1) > 1e-5;
        bad += fabs(dot3(N(m, k), T(m, k))) > 1e-5;
    }
    CHECK_MSG(bad == 0, "%s: %d bad vertex values (NaN, not unit, tangent not perpendicular)", what, bad);
    int badidx = 0;
    for (int i = 0; i < m->nidx; i++) badidx += m->idx[i] >= (unsigned)m->nvert;
    CHECK_MSG(badidx == 0, "%s: %d indices out of range", what, badidx);
}

/* Every non-degenerate triangle faces the way its vertex normals say, and
 * its texture +u (along = 0) or +v (along = 1: the sphere's) runs along the
 * vertex tangents. */
static void check_winding_and_tangent_along(const geom_mesh *m, const char *what, int along) {
    int wrong_side = 0, wrong_tan = 0, counted = 0;
    for (int f = 0; f + 2 < m->nidx; f += 3) {
        const unsigned *t = m->idx + f;
        double fn[3];
        face_normal(m, t, fn);
        double area2 = sqrt(fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2]);
        if (area2 < 1e-9) continue;
        counted++;
        double sum = 0;
        for (int c = 0; c < 3; c++) sum += (fn[0] * N(m, t[c])[0] + fn[1] * N(m, t[c])[1] + fn[2] * N(m, t[c])[2]) / area2;
        wrong_side += sum <= 0;
        /* dP/du of the triangle from its texture coordinates */
        const float *a = P(m, t[0]), *b = P(m, t[1]), *c = P(m, t[2]);
        const float *ta = m->tc + 2 * t[0], *tb = m->tc + 2 * t[1], *tcc = m->tc + 2 * t[2];
        double du1 = tb[0] - ta[0], dv1 = tb[1] - ta[1], du2 = tcc[0] - ta[0], dv2 = tcc[1] - ta[1];
        double det = du1 * dv2 - du2 * dv1;
        if (fabs(det) < 1e-12) continue;
        double dpdu[3];
        for (int k = 0; k < 3; k++)
            dpdu[k] = along ? ((c[k] - a[k]) * du1 - (b[k] - a[k]) * du2) / det
                            : ((b[k] - a[k]) * dv2 - (c[k] - a[k]) * dv1) / det;
        double s = 0;
        for (int v = 0; v < 3; v++) s += dpdu[0] * T(m, t[v])[0] + dpdu[1] * T(m, t[v])[1] + dpdu[2] * T(m, t[v])[2];
        wrong_tan += s <= 0;
    }
    CHECK_MSG(counted > 0, "%s: no triangles", what);
    CHECK_MSG(wrong_side == 0, "%s: %d of %d triangles wind against their normals", what, wrong_side, counted);
    CHECK_MSG(wrong_tan == 0, "%s: %d of %d triangles have tangents against +%c", what, wrong_tan, counted,
              along ? 'v' : 'u');
}

static void check_winding_and_tangents(const geom_mesh *m, const char *what) {
    check_winding_and_tangent_along(m, what, 0);
}

/* Signed volume (divergence theorem): positive when triangles wind outward. */
static double volume(const geom_mesh *m) {
    double v = 0;
    for (int f = 0; f + 2 < m->nidx; f += 3) {
        const float *a = P(m, m->idx[f]), *b = P(m, m->idx[f + 1]), *c = P(m, m->idx[f + 2]);
        v += (a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) - a[1] * ((double)b[0] * c[2] - (double)b[2] * c[0]) +
              a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0])) / 6.0;
    }
    return v;
}

static void bbox(const geom_mesh *m, double lo[3], double hi[3]) {
    for (int c = 0; c < 3; c++) { lo[c] = 1e30; hi[c] = -1e30; }
    for (int k = 0; k < m->nvert; k++)
        for (int c = 0; c < 3; c++) {
            if (m->pos[3 * k + c] < lo[c]) lo[c] = m->pos[3 * k + c];
            if (m->pos[3 * k + c] > hi[c]) hi[c] = m->pos[3 * k + c];
        }
}

static int count_distinct(const geom_mesh *m, int axis) {
    float *seen = malloc(sizeof *seen * (size_t)m->nvert);
    int n = 0;
    for (int k = 0; k < m->nvert; k++) {
        float v = m->pos[3 * k + axis];
        int found = 0;
        for (int i = 0; i < n && !found; i++) found = fabsf(seen[i] - v) < 1e-6f;
        if (!found) seen[n++] = v;
    }
    free(seen);
    return n;
}

/* ---- quads ---- */

static void test_quad(void) {
    const char *names[3] = {"QuadYZ", "QuadXZ", "QuadXY"};
    for (int axis = 0; axis < 3; axis++) {
        geom_mesh m;
        CHECK(geom_quad(&m, axis, 0.7f, 2.5f, 3, 5, false));
        check_sane(&m, names[axis]);
        check_winding_and_tangents(&m, names[axis]);
        CHECK(!(m.prim == GEOM_LINES) && m.nvert == 4 * 6 && m.nidx == 6 * 15);
        double lo[3], hi[3];
        bbox(&m, lo, hi);
        for (int c = 0; c < 3; c++) {
            if (c == axis) { CHECK_NEAR(lo[c], 0.7, 1e-6); CHECK_NEAR(hi[c], 0.7, 1e-6); }
            else { CHECK_NEAR(lo[c], -2.5, 1e-6); CHECK_NEAR(hi[c], 2.5, 1e-6); }
        }
        for (int k = 0; k < m.nvert; k++) {
            for (int c = 0; c < 3; c++) CHECK_EQ(m.nrm[3 * k + c], (c == axis ? 1.0f : 0.0f));
            CHECK(m.tc[2 * k] >= 0 && m.tc[2 * k] <= 1 && m.tc[2 * k + 1] >= 0 && m.tc[2 * k + 1] <= 1);
        }
        /* the glib's counts: QuadXY nx ny, QuadXZ nx nz, QuadYZ ny nz */
        int first = axis == 0 ? 1 : 0, second = axis == 2 ? 1 : 2;
        CHECK_MSG(count_distinct(&m, first) == 4 && count_distinct(&m, second) == 6,
                  "%s: %d x %d distinct", names[axis], count_distinct(&m, first), count_distinct(&m, second));
        geom_free(&m);
        CHECK(m.pos == NULL && m.nvert == 0);

        /* wire: grid lines, each along one axis */
        CHECK(geom_quad(&m, axis, 0.7f, 2.5f, 3, 5, true));
        CHECK((m.prim == GEOM_LINES) && m.nidx == 2 * (3 * 6 + 4 * 5));
        int diag = 0;
        for (int i = 0; i + 1 < m.nidx; i += 2) {
            const float *a = P(&m, m.idx[i]), *b = P(&m, m.idx[i + 1]);
            int moved = (a[0] != b[0]) + (a[1] != b[1]) + (a[2] != b[2]);
            diag += moved != 1;
        }
        CHECK_EQ(diag, 0);
        check_sane(&m, "wire quad");
        geom_free(&m);
    }
    /* QuadXZ seen from above is upright: +u along +x, +v along -z */
    geom_mesh m;
    CHECK(geom_quad(&m, 1, 0, 1, 1, 1, false));
    for (int k = 0; k < m.nvert; k++) {
        CHECK_NEAR(m.tc[2 * k], (m.pos[3 * k] + 1) / 2, 1e-6);
        CHECK_NEAR(m.tc[2 * k + 1], (1 - m.pos[3 * k + 2]) / 2, 1e-6);
    }
    geom_free(&m);

    /* robustness: negative size, zero size, silly counts, NaN, bad axis */
    CHECK(geom_quad(&m, 2, 0, -3, 2, 2, false));
    double lo[3], hi[3];
    bbox(&m, lo, hi);
    CHECK_NEAR(lo[0], -3, 1e-6); CHECK_NEAR(hi[0], 3, 1e-6);
    geom_free(&m);
    CHECK(geom_quad(&m, 2, 0, 0, 2, 2, false));
    check_sane(&m, "zero quad");
    geom_free(&m);
    CHECK(geom_quad(&m, 1, 0, 1, 0, -7, false));
    CHECK(m.nvert == 4 && m.nidx == 6);
    geom_free(&m);
    CHECK(geom_quad(&m, 1, 0, 1, 100000000, 1, false));
    CHECK_EQ(m.nvert, (GEOM_MAX_DIV + 1) * 2);
    geom_free(&m);
    CHECK(!geom_quad(&m, 1, NAN, 1, 2, 2, false));
    CHECK(m.pos == NULL && m.nvert == 0);
    CHECK(!geom_quad(&m, 1, 0, INFINITY, 2, 2, false));
    CHECK(!geom_quad(&m, 3, 0, 1, 2, 2, false));
    CHECK(!geom_quad(NULL, 1, 0, 1, 2, 2, false));
    geom_free(&m);
    geom_free(NULL);
}

/* ---- sphere ---- */

/* A triangle as its corners' (position, texture coordinate), rotated so
 * the smallest corner comes first: the same triangle with the same winding
 * gives the same key whatever the vertex numbers and corner order. */
typedef struct tri_key { float c[3][5]; } tri_key;

static int cmp_corner(const float *a, const float *b) {
    for (int k = 0; k < 5; k++)
        if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
    return 0;
}

static int cmp_tri(const void *a, const void *b) {
    const tri_key *x = a, *y = b;
    for (int c = 0; c < 3; c++) {
        int d = cmp_corner(x->c[c], y->c[c]);
        if (d) return d;
    }
    return 0;
}

static tri_key *tri_keys(const geom_mesh *m) {
    int n = m->nidx / 3;
    tri_key *t = malloc((size_t)n * sizeof *t);
    for (int i = 0; i < n; i++) {
        float c[3][5];
        for (int k = 0; k < 3; k++) {
            unsigned v = m->idx[i * 3 + k];
            memcpy(c[k], m->pos + 3 * v, 3 * sizeof(float));
            memcpy(c[k] + 3, m->tc + 2 * v, 2 * sizeof(float));
        }
        int first = 0;
        for (int k = 1; k < 3; k++)
            if (cmp_corner(c[k], c[first]) < 0) first = k;
        for (int k = 0; k < 3; k++) memcpy(t[i].c[k], c[(first + k) % 3], sizeof c[0]);
    }
    qsort(t, (size_t)n, sizeof *t, cmp_tri);
    return t;
}

/* geom_grid_bands: the same triangles, wound the same way, their vertices
 * numbered by first use, in bands (a band's rows are consecutive). */
static void test_grid_bands(void) {
    geom_mesh a, b;
    CHECK(geom_quad(&a, 1, 0.5f, 3.0f, 70, 9, false));
    CHECK(geom_quad(&b, 1, 0.5f, 3.0f, 70, 9, false));
    CHECK(geom_grid_bands(&b, 70, 9, 32));
    CHECK(a.nidx == b.nidx && a.nvert == b.nvert);
    tri_key *ka = tri_keys(&a), *kb = tri_keys(&b);
    CHECK_EQ(memcmp(ka, kb, (size_t)(a.nidx / 3) * sizeof *ka), 0);
    free(ka);
    free(kb);
    unsigned next = 0;
    bool first_use = true;
    for (int k = 0; k < b.nidx; k++) {
        if (b.idx[k] > next) first_use = false;
        if (b.idx[k] == next) next++;
    }
    CHECK(first_use && next == (unsigned)b.nvert);
    /* the first band, 32 cells by 9 rows, uses 33 x 10 vertices and no more */
    unsigned most = 0;
    for (int k = 0; k < 6 * 32 * 9; k++) most = b.idx[k] > most ? b.idx[k] : most;
    CHECK_EQ(most, 33 * 10 - 1);
    check_winding_and_tangents(&b, "banded quad");
    geom_free(&b);
    /* not a grid of that size: refused, untouched */
    CHECK(!geom_grid_bands(&a, 71, 9, 32));
    CHECK(!geom_grid_bands(&a, 70, 9, 0));
    geom_free(&a);
    CHECK(geom_sphere(&a, 1, 8, 4, false));
    CHECK(!geom_grid_bands(&a, 8, 4, 32));
    geom_free(&a);
}

static void test_sphere(void) {
    const float r = 1.7f;
    geom_mesh m;
    CHECK(geom_sphere(&m, r, 24, 12, false));
    check_sane(&m, "sphere");
    check_winding_and_tangent_along(&m, "sphere", 1);
    int off = 0, offn = 0, offt = 0, offtc = 0;
    for (int k = 0; k < m.nvert; k++) {
        const float *p = P(&m, k), *n = N(&m, k), *t = T(&m, k);
        off += fabs(len3(p) - r) > 1e-6 * r;
        for (int c = 0; c < 3; c++) offn += fabs(n[c] - p[c] / r) > 1e-6;
        /* Tangent = d/d(latitude), towards the north pole (glman's): the
         * unit y - (y.n) n, where defined */
        double north[3] = {-n[1] * n[0], 1 - n[1] * n[1], -n[1] * n[2]};
        double l = sqrt(north[0] * north[0] + north[1] * north[1] + north[2] * north[2]);
        if (l > 1e-3) offt += fabs(t[0] - north[0] / l) > 1e-5 || fabs(t[1] - north[1] / l) > 1e-5 ||
                              fabs(t[2] - north[2] / l) > 1e-5;
        /* tc as the course's OsuSphere: s = (lng + pi) / 2pi where the point
         * is (cos lng, ., -sin lng) cos lat; t = latitude 0..1 */
        double v = asin(fmax(-1, fmin(1, p[1] / r))) / PI + 0.5;
        offtc += fabs(m.tc[2 * k + 1] - v) > 1e-5;
        if (l > 1e-3) {
            double u = (atan2(-p[2], p[0]) + PI) / (2 * PI);
            if (u >= 1) u -= 1;
            double du = fabs(m.tc[2 * k] - u);
            offtc += du > 1e-5 && fabs(du - 1) > 1e-5;   /* the seam is 0 and 1 */
        }
    }
    CHECK_MSG(off == 0 && offn == 0, "%d positions off the sphere, %d normals not pos/r", off, offn);
    CHECK_MSG(offt == 0, "%d tangents not d/d(latitude) (towards the north pole)", offt);
    CHECK_MSG(offtc == 0, "%d texture coordinates off", offtc);
    /* Where a world map lands (issue #27: the date line faced the camera):
     * on the equator, s = 0.25 faces glman's default camera (+z), s = 0.5
     * is at +x, the seam (s = 0 and 1) at -x, away from the camera's centre;
     * s increases eastwards seen from outside: from the front (+z, y up)
     * the next meridian east is to the right (+x). */
    int at_z = 0, at_x = 0, seam = 0, east = 0;
    for (int k = 0; k < m.nvert; k++) {
        const float *p = P(&m, k), *t = T(&m, k);
        if (fabs(p[1]) > 1e-6) continue;              /* the equator (12 stacks: one ring) */
        float s0 = m.tc[2 * k];
        if (fabs(p[2] - r) < 1e-5) at_z += fabs(s0 - 0.25) < 1e-6;
        if (fabs(p[0] - r) < 1e-5) at_x += fabs(s0 - 0.5) < 1e-6;
        if (fabs(p[0] + r) < 1e-5) seam += s0 == 0 || s0 == 1;
        /* east at this point: north (the Tangent) x outward normal... seen
         * from outside, east = cross(north, n) */
        const float *n = N(&m, k);
        double e[3] = {t[1] * n[2] - t[2] * n[1], t[2] * n[0] - t[0] * n[2], t[0] * n[1] - t[1] * n[0]};
        if (fabs(p[2] - r) < 1e-5) east += e[0] > 0.99;   /* at the front, east is +x: to the right */
    }
    CHECK_MSG(at_z >= 1 && at_x >= 1 && seam >= 1 && east >= 1,
              "s = 0.25 at +z: %d, s = 0.5 at +x: %d, seam at -x: %d, east is +x at the front: %d",
              at_z, at_x, seam, east);
    /* s increasing along the equator goes east: from s = 0.25 (+z) to a
     * slightly larger s lands at x > 0 */
    int east_s = 0, west_s = 0;
    for (int k = 0; k < m.nvert; k++) {
        const float *p = P(&m, k);
        if (fabs(p[1]) > 1e-6) continue;
        float s0 = m.tc[2 * k];
        if (s0 > 0.25f && s0 < 0.4f && p[2] > 0) east_s += p[0] > 0, west_s += p[0] <= 0;
    }
    CHECK_MSG(east_s > 0 && west_s == 0, "s past 0.25: %d east of the front, %d west", east_s, west_s);
    double vol = volume(&m), exact = 4.0 / 3.0 * PI * r * r * r;
    CHECK_MSG(vol > 0.95 * exact && vol < exact, "volume %g of %g", vol, exact);
    geom_free(&m);

    /* finer -> closer */
    CHECK(geom_sphere(&m, 1, 256, 128, false));
    CHECK_NEAR(volume(&m), 4.0 / 3.0 * PI, 2e-3);
    geom_free(&m);

    CHECK(geom_sphere(&m, r, 24, 12, true));
    CHECK((m.prim == GEOM_LINES));
    check_sane(&m, "wire sphere");
    int zero = 0;
    for (int i = 0; i + 1 < m.nidx; i += 2) {
        const float *a = P(&m, m.idx[i]), *b = P(&m, m.idx[i + 1]);
        zero += a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
    }
    CHECK_MSG(zero == 0, "%d zero-length wire lines", zero);
    geom_free(&m);

    CHECK(geom_sphere(&m, 0, 0, 0, false));     /* defaults, zero radius: no NaN */
    check_sane(&m, "zero sphere");
    geom_free(&m);
    CHECK(geom_sphere(&m, -2, 1, 1, false));    /* minimums; |r| */
    check_sane(&m, "tiny sphere");
    CHECK_NEAR(len3(P(&m, 0)), 2, 1e-6);
    geom_free(&m);
    CHECK(!geom_sphere(&m, NAN, 8, 8, false));
    CHECK_EQ(m.nvert, 0);
}

/* ---- torus ---- */

static void test_torus(void) {
    const double R = 2.0, r = 0.5;
    geom_mesh m;
    CHECK(geom_torus(&m, (float)R, (float)r, 24, 48, false));
    check_sane(&m, "torus");
    check_winding_and_tangents(&m, "torus");
    int off = 0, offn = 0;
    for (int k = 0; k < m.nvert; k++) {
        const float *p = P(&m, k), *n = N(&m, k);
        double rho = sqrt((double)p[0] * p[0] + (double)p[1] * p[1]);
        double d = sqrt((rho - R) * (rho - R) + (double)p[2] * p[2]);    /* in the xy plane, about z */
        off += fabs(d - r) > 1e-5;
        /* normal = from the tube's centre circle to the point */
        double cx = p[0] / rho * R, cy = p[1] / rho * R;
        double want[3] = {(p[0] - cx) / r, (p[1] - cy) / r, p[2] / r};
        for (int c = 0; c < 3; c++) offn += fabs(n[c] - want[c]) > 1e-5;
    }
    CHECK_MSG(off == 0 && offn == 0, "%d points off the tube, %d normals off", off, offn);
    double vol = volume(&m), exact = 2 * PI * PI * R * r * r;
    CHECK_MSG(vol > 0.97 * exact && vol < 1.0 * exact, "volume %g of %g", vol, exact);
    geom_free(&m);
    CHECK(geom_torus(&m, 1, 2, 3, 3, true));    /* self-intersecting, wire, minimum: still sane */
    check_sane(&m, "odd torus");
    geom_free(&m);
    CHECK(geom_torus(&m, 0, 0, 0, 0, false));
    check_sane(&m, "zero torus");
    geom_free(&m);
}

/* ---- box ---- */

static void test_box(void) {
    geom_mesh m;
    CHECK(geom_box(&m, 2, 3, 4, false));
    check_sane(&m, "box");
    check_winding_and_tangents(&m, "box");
    CHECK(m.nvert == 24 && m.nidx == 36);
    int faces[6] = {0};     /* +x +y +z -x -y -z */
    const double half[3] = {1, 1.5, 2};
    int off = 0;
    for (int k = 0; k < m.nvert; k++) {
        const float *n = N(&m, k), *p = P(&m, k);
        int axis = -1, nonzero = 0;
        for (int c = 0; c < 3; c++) if (n[c] != 0) { axis = c; nonzero++; }
        CHECK(nonzero == 1 && (n[axis] == 1 || n[axis] == -1));
        if (nonzero != 1) continue;
        faces[axis + (n[axis] < 0 ? 3 : 0)]++;
        off += fabs(p[axis] - n[axis] * half[axis]) > 1e-6;    /* on its face */
        for (int c = 0; c < 3; c++) off += fabs(fabs(p[c]) - half[c]) > 1e-6;   /* corners */
    }
    for (int f = 0; f < 6; f++) CHECK_MSG(faces[f] == 4, "face %d has %d vertices", f, faces[f]);
    CHECK_EQ(off, 0);
    CHECK_NEAR(volume(&m), 24.0, 1e-5);
    geom_free(&m);

    CHECK(geom_box(&m, 2, 3, 4, true));
    CHECK((m.prim == GEOM_LINES) && m.nidx == 2 * 24);         /* 4 edges a face */
    for (int i = 0; i + 1 < m.nidx; i += 2) {
        const float *a = P(&m, m.idx[i]), *b = P(&m, m.idx[i + 1]);
        double d = sqrt(((double)a[0] - b[0]) * (a[0] - b[0]) + ((double)a[1] - b[1]) * (a[1] - b[1]) +
                        ((double)a[2] - b[2]) * (a[2] - b[2]));
        CHECK(fabs(d - 2) < 1e-6 || fabs(d - 3) < 1e-6 || fabs(d - 4) < 1e-6);
    }
    geom_free(&m);
    CHECK(geom_box(&m, -1, 0, 1, false));       /* flat, negative: finite */
    check_sane(&m, "flat box");
    geom_free(&m);
}

/* ---- cylinder and cone ---- */

static void test_cylinder_cone(void) {
    const double r = 0.8, h = 3.0;
    geom_mesh m;
    CHECK(geom_cylinder(&m, (float)r, (float)h, 64, 4, false));
    check_sane(&m, "cylinder");
    check_winding_and_tangents(&m, "cylinder");
    double lo[3], hi[3];
    bbox(&m, lo, hi);
    CHECK_NEAR(lo[1], -h / 2, 1e-6); CHECK_NEAR(hi[1], h / 2, 1e-6);   /* centred along y */
    CHECK_NEAR(hi[0], r, 1e-6); CHECK_NEAR(lo[2], -r, 1e-6);
    int caps_up = 0, caps_down = 0, side = 0, bad = 0;
    for (int k = 0; k < m.nvert; k++) {
        const float *n = N(&m, k), *p = P(&m, k);
        if (n[1] > 0.999) { caps_up++; bad += fabs(p[1] - h / 2) > 1e-6; }
        else if (n[1] < -0.999) { caps_down++; bad += fabs(p[1] + h / 2) > 1e-6; }
        else {
            side++;
            double rho = sqrt((double)p[0] * p[0] + (double)p[2] * p[2]);
            bad += fabs(n[1]) > 1e-6 || fabs(rho - r) > 1e-6 || fabs(n[0] - p[0] / r) > 1e-5;
        }
    }
    CHECK(caps_up > 0 && caps_down > 0 && side > 0 && bad == 0);
    double exact = PI * r * r * h;
    CHECK_MSG(volume(&m) > 0.99 * exact && volume(&m) <= exact, "cylinder volume %g of %g", volume(&m), exact);
    geom_free(&m);

    CHECK(geom_cone(&m, (float)r, (float)h, 64, 3, false));
    check_sane(&m, "cone");
    check_winding_and_tangents(&m, "cone");
    bbox(&m, lo, hi);
    CHECK_NEAR(lo[1], -h / 2, 1e-6); CHECK_NEAR(hi[1], h / 2, 1e-6);
    bad = 0;
    for (int k = 0; k < m.nvert; k++) {
        const float *n = N(&m, k), *p = P(&m, k);
        if (n[1] < -0.999) continue;       /* base */
        /* side: radius shrinks linearly to the apex, normal slope r/h */
        double rho = sqrt((double)p[0] * p[0] + (double)p[2] * p[2]);
        bad += fabs(rho - r * (h / 2 - p[1]) / h) > 1e-5;
        double nh = sqrt((double)n[0] * n[0] + (double)n[2] * n[2]);
        bad += fabs(n[1] / nh - r / h) > 1e-5;
    }
    CHECK_EQ(bad, 0);
    exact = PI * r * r * h / 3;
    CHECK_MSG(volume(&m) > 0.99 * exact && volume(&m) <= exact, "cone volume %g of %g", volume(&m), exact);
    geom_free(&m);

    CHECK(geom_cone(&m, (float)r, (float)h, 8, 2, true));
    CHECK((m.prim == GEOM_LINES));
    check_sane(&m, "wire cone");
    geom_free(&m);
    CHECK(geom_cylinder(&m, 0, 0, 0, 0, false));
    check_sane(&m, "zero cylinder");
    geom_free(&m);
    CHECK(geom_cone(&m, 0, 0, -1, -1, false));
    check_sane(&m, "zero cone");
    geom_free(&m);
    CHECK(geom_cone(&m, 1, 0, 5, 1, false));    /* flat cone: a disc, normals up and down */
    check_sane(&m, "flat cone");
    geom_free(&m);
    CHECK(!geom_cylinder(&m, 1, NAN, 8, 1, false));
    CHECK(!geom_cone(&m, INFINITY, 1, 8, 1, false));
}

/* ---- teapot ---- */

static void test_teapot(void) {
    const double s = 2.0;
    geom_mesh m;
    CHECK(geom_teapot(&m, (float)s, 12, false));
    check_sane(&m, "teapot");
    check_winding_and_tangents(&m, "teapot");
    /* 32 patches of 13 x 13 vertices */
    CHECK_EQ(m.nvert, 32 * 13 * 13);
    /* Newell's teapot, z up: 3.15 tall, body radius 2 at z 0.9, handle at
     * x = -3, spout tip near x = 3.43; glutSolidTeapot(s) turns it y up,
     * halves it and lowers it by 1.5 */
    double lo[3], hi[3];
    bbox(&m, lo, hi);
    CHECK_NEAR(lo[1], 0.5 * s * (0 - 1.5), 1e-5);
    CHECK_NEAR(hi[1], 0.5 * s * (3.15 - 1.5), 1e-5);
    CHECK_NEAR(lo[2], -0.5 * s * 2.0, 1e-5);
    CHECK_NEAR(hi[2], 0.5 * s * 2.0, 1e-5);
    CHECK_NEAR(lo[0], -0.5 * s * 3.0, 1e-5);
    CHECK_NEAR(hi[0], 0.5 * s * 3.434, 0.01 * s);
    CHECK_NEAR((hi[1] - lo[1]) / (hi[2] - lo[2]), 3.15 / 4.0, 1e-5);

    /* where patches meet, the surface is smooth: coinciding vertices have
     * (nearly) the same normal, mirrored copies included */
    int pairs = 0, kinks = 0;
    for (int a = 0; a < m.nvert; a++)
        for (int b = a + 1; b < m.nvert; b++) {
            const float *pa = P(&m, a), *pb = P(&m, b);
            if (fabs(pa[0] - pb[0]) > 1e-5 || fabs(pa[1] - pb[1]) > 1e-5 || fabs(pa[2] - pb[2]) > 1e-5) continue;
            /* except where the handle's lower end (-2, 0, 0.9), z up, touches the body */
            if (fabs(pa[0] + 0.5 * s * 2) < 1e-5 && fabs(pa[1] - 0.5 * s * (0.9 - 1.5)) < 1e-5 && fabs(pa[2]) < 1e-5)
                continue;
            pairs++;
            kinks += dot3(N(&m, a), N(&m, b)) < 0.99;
        }
    CHECK_GT(pairs, 100);
    CHECK_MSG(kinks == 0, "%d of %d coinciding vertices disagree on the normal", kinks, pairs);
    /* the knob's top faces up, the bottom's centre down */
    int top = 0, bottom = 0;
    for (int k = 0; k < m.nvert; k++) {
        const float *p = P(&m, k), *n = N(&m, k);
        if (fabs(p[0]) < 1e-6 && fabs(p[2]) < 1e-6 && fabs(p[1] - hi[1]) < 1e-6) { top++; CHECK_GT(n[1], 0.999); }
        if (fabs(p[0]) < 1e-6 && fabs(p[2]) < 1e-6 && fabs(p[1] - lo[1]) < 1e-6) { bottom++; CHECK_LT(n[1], -0.999); }
    }
    CHECK(top > 0 && bottom > 0);
    geom_free(&m);

    CHECK(geom_teapot(&m, 1, 0, true));          /* default grid, wire */
    CHECK((m.prim == GEOM_LINES));
    check_sane(&m, "wire teapot");
    CHECK_EQ(m.nvert, 32 * 11 * 11);
    geom_free(&m);
    CHECK(geom_teapot(&m, -1, 100000, false));   /* clamped grid, |size| */
    CHECK_EQ(m.nvert, 32 * (GEOM_MAX_TEAPOT_GRID + 1) * (GEOM_MAX_TEAPOT_GRID + 1));
    geom_free(&m);
    CHECK(geom_teapot(&m, 0, 1, false));
    check_sane(&m, "zero teapot");
    geom_free(&m);
    CHECK(!geom_teapot(&m, NAN, 4, false));
}

/* ---- OBJ ---- */

static const char *write_file(const char *name, const char *text, size_t len) {
    static char path[4][512];
    static int next;
    char *p = path[next++ % 4];
    snprintf(p, sizeof path[0], "%s/%s", tmpdir, name);
    FILE *f = fopen(p, "wb");
    if (f) { fwrite(text, 1, len, f); fclose(f); }
    return p;
}

static const char *write_text(const char *name, const char *text) { return write_file(name, text, strlen(text)); }

/* The triangle with corners at these positions, or -1. */
static int find_tri(const geom_mesh *m, const float a[3], const float b[3], const float c[3]) {
    for (int f = 0; f + 2 < m->nidx; f += 3)
        for (int rot = 0; rot < 3; rot++) {
            const float *p0 = P(m, m->idx[f + rot]), *p1 = P(m, m->idx[f + (rot + 1) % 3]),
                        *p2 = P(m, m->idx[f + (rot + 2) % 3]);
            if (!memcmp(p0, a, 12) && !memcmp(p1, b, 12) && !memcmp(p2, c, 12)) return f;
        }
    return -1;
}

static void test_obj_face_forms(void) {
    const char *good =
        "# four squares, one per face form, plus negative indices\n"
        "mtllib none.mtl\n"
        "o squares\n"
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
        "vn 0 0 1\n"
        "g a\nusemtl x\ns 1\n"
        "f 1 2 3 4\n"                               /* v: fan-triangulated quad */
        "v 0 0 1 0.5 0.25 0.125\r\n"               /* x y z r g b, CRLF */
        "v 1 0 1\nv 1 1 1\nv 0 1 1\n"
        "f 5/1 6/2 7/3\n"                          /* v/vt */
        "f 5//1 7//1 8//1   # a comment after\n"   /* v//vn */
        "v 0 0 2\nv 1 0 2\nv 1 1 2\nv 0 1 2\n"
        "f 9/1/1 10/2/1 \\\n 11/3/1 12/4/1\n"      /* v/vt/vn, continued line */
        "v 0 0 3\nv 1 0 3\nv 1 1 3\nv 0 1 3\n"
        "f -4/-4 -3/-3 -2/-2 -1/-1\n";             /* negative: the last four */
    const char *path = write_text("forms.obj", good);
    geom_mesh m;
    char err[512] = "";
    CHECK_MSG(geom_obj_load(&m, path, err, sizeof err), "%s", err);
    check_sane(&m, "obj forms");
    check_winding_and_tangents(&m, "obj forms");
    CHECK_MSG(!(m.prim == GEOM_LINES) && m.nidx == 3 * (2 + 1 + 1 + 2 + 2), "%d indices", m.nidx);
    for (int z = 0; z <= 3; z++) {
        float a[3] = {0, 0, (float)z}, b[3] = {1, 0, (float)z}, c[3] = {1, 1, (float)z}, d[3] = {0, 1, (float)z};
        int t1 = find_tri(&m, a, b, c);
        CHECK_MSG(t1 >= 0, "square %d: first triangle missing", z);
        /* the v//vn face is a single triangle (5 7 8): a c d */
        CHECK_MSG(find_tri(&m, a, c, d) >= 0, "square %d: fan triangle from corner 0 missing", z);
        if (z == 1) CHECK_GE(find_tri(&m, a, b, c), 0);
        if (t1 < 0) continue;
        for (int k = 0; k < 3; k++) {
            unsigned v = m.idx[t1 + k];
            /* every square faces +z: given or computed normals alike */
            CHECK_NEAR(m.nrm[3 * v + 2], 1.0, 1e-6);
            /* texture: where given, u = x and v = y; else (0, 0) */
            if (z != 0) {
                CHECK_NEAR(m.tc[2 * v], m.pos[3 * v], 1e-6);
                CHECK_NEAR(m.tc[2 * v + 1], m.pos[3 * v + 1], 1e-6);
                CHECK_NEAR(m.tan[3 * v], 1.0, 1e-6);    /* +u is +x */
            } else {
                CHECK(m.tc[2 * v] == 0 && m.tc[2 * v + 1] == 0);
            }
        }
    }
    geom_free(&m);
    CHECK_EQ(m.pos, NULL);
}

/* Corners without vn get the area-weighted normal of the faces around. */
static void test_obj_computed_normals(void) {
    /* a 2x2 floor (area 4, +z) and a 1x2 wall (area 2, +x) sharing the edge
     * x = 1, z = 0; on that edge the normal is (2, 0, 4) normalised */
    const char *path = write_text("roof.obj",
        "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
        "v 1 -1 -1\nv 1 1 -1\n"
        "f 1 2 3 4\n"
        "f 2 5 6 3\n");
    geom_mesh m;
    char err[512] = "";
    CHECK_MSG(geom_obj_load(&m, path, err, sizeof err), "%s", err);
    check_sane(&m, "roof");
    int edge = 0;
    for (int k = 0; k < m.nvert; k++) {
        const float *p = P(&m, k), *n = N(&m, k);
        if (p[0] == 1 && p[2] == 0) {
            edge++;
            CHECK_NEAR(n[0], 2 / sqrt(20.0), 1e-6);
            CHECK_NEAR(n[1], 0, 1e-6);
            CHECK_NEAR(n[2], 4 / sqrt(20.0), 1e-6);
        } else if (p[2] == 0) {
            CHECK_NEAR(n[2], 1, 1e-6);
        } else {
            CHECK_NEAR(n[0], 1, 1e-6);
        }
    }
    CHECK_EQ(edge, 2);       /* shared: one vertex per position */
    CHECK_EQ(m.nvert, 6);
    geom_free(&m);

    /* a degenerate face and a zero vn: still no NaN */
    path = write_text("degenerate.obj", "v 0 0 0\nv 0 0 0\nv 0 0 0\nvn 0 0 0\nf 1//1 2//1 3//1\n");
    CHECK_MSG(geom_obj_load(&m, path, err, sizeof err), "%s", err);
    check_sane(&m, "degenerate obj");
    geom_free(&m);
}

static void expect_obj_error(const char *name, const char *text, int line, const char *phrase) {
    const char *path = write_text(name, text);
    geom_mesh m;
    char err[512] = "";
    CHECK_MSG(!geom_obj_load(&m, path, err, sizeof err), "%s loaded", name);
    CHECK(m.nvert == 0 && m.pos == NULL && m.idx == NULL);
    char want[600];
    if (line > 0) snprintf(want, sizeof want, "%s:%d: ", path, line);
    else snprintf(want, sizeof want, "%s: ", path);
    CHECK_STR_CONTAINS(err, want);
    if (phrase) CHECK_STR_CONTAINS(err, phrase);
}

static void test_obj_errors(void) {
    const char *tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    char buf[600];
    snprintf(buf, sizeof buf, "%s# ok so far\nf 0 1 2\n", tri);
    expect_obj_error("zero.obj", buf, 5, "index 0");
    snprintf(buf, sizeof buf, "%sf 1 2 4\n", tri);
    expect_obj_error("range.obj", buf, 4, "out of range");
    snprintf(buf, sizeof buf, "%sf -1 -2 -4\n", tri);
    expect_obj_error("negrange.obj", buf, 4, "out of range");
    snprintf(buf, sizeof buf, "%svt 0 0\nf 1/2 2/1 3/1\n", tri);
    expect_obj_error("vtrange.obj", buf, 5, "out of range");
    snprintf(buf, sizeof buf, "%sf 1//1 2//1 3//1\n", tri);
    expect_obj_error("vnrange.obj", buf, 4, "out of range");
    snprintf(buf, sizeof buf, "%sf 1 2 99999999999999999999999\n", tri);
    expect_obj_error("hugeidx.obj", buf, 4, NULL);
    snprintf(buf, sizeof buf, "%sf 1 2 3x\n", tri);
    expect_obj_error("badidx.obj", buf, 4, NULL);
    snprintf(buf, sizeof buf, "%sf 1/1/1/1 2 3\n", tri);
    expect_obj_error("form.obj", buf, 4, NULL);
    snprintf(buf, sizeof buf, "%sf 1 2\n", tri);
    expect_obj_error("short.obj", buf, 4, NULL);
    expect_obj_error("badnum.obj", "v 0 0 0\nv 1 zero 0\n", 2, "bad number");
    expect_obj_error("nan.obj", "v nan 0 0\n", 1, "bad number");
    expect_obj_error("fewnums.obj", "v 1 2\n", 1, NULL);
    expect_obj_error("vn2.obj", "vn 1 2\n", 1, NULL);
    expect_obj_error("junk.obj", "v 0 0 0\nthis is not obj at all\n", 2, "unknown");
    expect_obj_error("nofaces.obj", "v 0 0 0\nv 1 0 0\n", 0, "no faces");
    expect_obj_error("empty.obj", "", 0, "no faces");

    /* binary junk: random bytes with NULs */
    unsigned char junk[512];
    unsigned s = 77;
    for (size_t i = 0; i < sizeof junk; i++) { s = s * 1103515245u + 12345u; junk[i] = (unsigned char)(s >> 16); }
    const char *path = write_file("binary.obj", (const char *)junk, sizeof junk);
    geom_mesh m;
    char err[512] = "";
    CHECK(!geom_obj_load(&m, path, err, sizeof err));
    snprintf(buf, sizeof buf, "%s:", path);
    CHECK_STR_CONTAINS(err, buf);
    CHECK_EQ(m.nvert, 0);

    /* missing file */
    snprintf(buf, sizeof buf, "%s/missing.obj", tmpdir);
    err[0] = 0;
    CHECK(!geom_obj_load(&m, buf, err, sizeof err));
    CHECK_STR_CONTAINS(err, buf);
    CHECK(!geom_obj_load(&m, buf, NULL, 0));     /* err may be NULL */
    CHECK(!geom_obj_load(&m, NULL, err, sizeof err));

    /* a long polygon and a long junk token: no overflow */
    char *big = malloc(40000);
    size_t n = 0;
    for (int i = 0; i < 300; i++) n += (size_t)snprintf(big + n, 40000 - n, "v %d %d 0\n", i % 2, i);
    n += (size_t)snprintf(big + n, 40000 - n, "f");
    for (int i = 1; i <= 300; i++) n += (size_t)snprintf(big + n, 40000 - n, " %d", i);
    n += (size_t)snprintf(big + n, 40000 - n, "\n");
    path = write_text("long.obj", big);
    CHECK_MSG(geom_obj_load(&m, path, err, sizeof err), "%s", err);
    CHECK_EQ(m.nidx, 3 * 298);
    geom_free(&m);
    memset(big, 'x', 30000);
    big[30000] = 0;
    path = write_text("longjunk.obj", big);
    err[0] = 0;
    CHECK(!geom_obj_load(&m, path, err, sizeof err));
    snprintf(buf, sizeof buf, "%s:1:", path);
    CHECK_STR_CONTAINS(err, buf);
    free(big);
}

/* ---- glman's other geometry ---- */

/* A closed tetrahedron: each triangle's adjacency corners are all the one
 * vertex it lacks (its three neighbours share that far corner). */
static void test_obj_variants(void) {
    const char *tet = write_text("tet.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                 "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n");
    geom_mesh m;
    char err[256];
    CHECK_MSG(geom_obj_load_adjacency(&m, tet, err, sizeof err), "%s", err);
    CHECK(m.prim == GEOM_TRIANGLES_ADJACENCY && m.nidx == 4 * 6);
    for (int t = 0; t < 4 && m.nidx == 24; t++) {
        const unsigned *a = m.idx + 6 * t;
        double sum[3] = {0, 0, 0};   /* the lacking vertex is 1,1,1 minus the other three (as positions sum) */
        for (int k = 0; k < 3; k++)
            for (int c = 0; c < 3; c++) sum[c] += P(&m, a[2 * k])[c];
        for (int k = 0; k < 3; k++) {
            const float *q = P(&m, a[2 * k + 1]);
            CHECK_MSG(fabs(q[0] + sum[0] - 1) < 1e-6 && fabs(q[1] + sum[1] - 1) < 1e-6 && fabs(q[2] + sum[2] - 1) < 1e-6,
                      "triangle %d edge %d: adjacent corner (%g %g %g) is not the vertex it lacks", t, k, q[0], q[1], q[2]);
        }
    }
    geom_free(&m);
    /* an open mesh (one triangle): no neighbour, the corner across is its own */
    const char *tri = write_text("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    CHECK(geom_obj_load_adjacency(&m, tri, err, sizeof err));
    CHECK(m.nidx == 6 && m.idx[1] == m.idx[4] && m.idx[3] == m.idx[0] && m.idx[5] == m.idx[2]);
    geom_free(&m);

    CHECK_MSG(geom_obj_load_wire(&m, tet, err, sizeof err), "%s", err);   /* 6 edges, each once */
    CHECK(m.prim == GEOM_LINES && m.nidx == 2 * 6);
    check_sane(&m, "wire obj");
    geom_free(&m);

    /* patches: quads stay quads (patch_size 4, the file's corner order) */
    const char *quads = write_text("quads.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
                                   "f 1 2 3 4\nf 2 5 6 3\n");
    CHECK_MSG(geom_obj_load_patches(&m, quads, err, sizeof err), "%s", err);
    CHECK(m.prim == GEOM_PATCHES && m.patch_size == 4 && m.nidx == 8);
    if (m.nidx == 8) CHECK(P(&m, m.idx[2])[0] == 1 && P(&m, m.idx[2])[1] == 1 && P(&m, m.idx[6])[0] == 2);
    geom_free(&m);
    const char *mixed = write_text("mixed.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n"
                                   "f 1 2 3 4\nf 2 5 3\n");
    CHECK(geom_obj_load_patches(&m, mixed, err, sizeof err));
    CHECK(m.prim == GEOM_PATCHES && m.patch_size == 3 && m.nidx == 9);   /* fanned: 2 + 1 triangles */
    geom_free(&m);
    CHECK(!geom_obj_load_adjacency(&m, "/nonexistent/x.obj", err, sizeof err) && m.pos == NULL);
}

static void test_points_disk_box(void) {
    geom_mesh m;
    const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    CHECK(geom_points(&m, tri, 3, GEOM_TRIANGLES));
    CHECK(m.nidx == 3 && fabs(N(&m, 0)[2] - 1) < 1e-6);   /* counter-clockwise seen from +z */
    check_sane(&m, "Triangles");
    geom_free(&m);
    const float adj[12] = {0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0};
    CHECK(geom_points(&m, adj, 4, GEOM_LINES_ADJACENCY) && m.prim == GEOM_LINES_ADJACENCY && m.nidx == 4);
    geom_free(&m);
    const float bad[3] = {NAN, 0, 0};
    CHECK(!geom_points(&m, bad, 1, GEOM_POINTS));

    CHECK(geom_disk_xy(&m, 0));   /* area pi, unit radius, z = 0, facing +z */
    check_sane(&m, "disk");
    check_winding_and_tangents(&m, "disk");
    double area = 0, rmax = 0;
    for (int f = 0; f < m.nidx; f += 3) {
        double fn[3];
        face_normal(&m, m.idx + f, fn);
        area += fn[2] / 2;
    }
    for (int k = 0; k < m.nvert; k++) {
        rmax = fmax(rmax, hypot(P(&m, k)[0], P(&m, k)[1]));
        CHECK_EQ(P(&m, k)[2], 0);
    }
    CHECK_MSG(area > 0.99 * PI && area < PI && fabs(rmax - 1) < 1e-6, "disk area %g, radius %g", area, rmax);
    geom_free(&m);

    CHECK(geom_quad_box(&m, 5));   /* 5 quads, z = -1 .. 1 back to front, p = (z + 1) / 2 */
    check_sane(&m, "QuadBox");
    CHECK(m.tcp != NULL && m.nidx == 5 * 6 && m.nvert == 5 * 4);
    for (int k = 0; m.tcp && k < m.nvert; k++) {
        const float *p = P(&m, k);
        CHECK(fabs(m.tcp[k] - (p[2] + 1) / 2) < 1e-6 && fabs(m.tc[2 * k] - (p[0] + 1) / 2) < 1e-6 &&
              fabs(m.tc[2 * k + 1] - (p[1] + 1) / 2) < 1e-6);
    }
    CHECK(P(&m, 0)[2] == -1 && P(&m, m.nvert - 1)[2] == 1);
    geom_free(&m);
}

static void test_clouds_and_arrow(void) {
    geom_mesh m, j;
    CHECK(geom_point_cloud(&m, 4, 3, 2, false));
    CHECK(m.prim == GEOM_POINTS && m.nvert == 24 && m.nidx == 24 && m.tcp);
    CHECK(fabs(P(&m, 0)[0] + 0.75) < 1e-6 && fabs(P(&m, 0)[1] + 2.0 / 3) < 1e-6 && fabs(P(&m, 0)[2] + 0.5) < 1e-6);
    CHECK(geom_point_cloud(&j, 4, 3, 2, true));
    int moved = 0, outside = 0;
    for (int k = 0; k < j.nvert && j.nvert == m.nvert; k++)
        for (int c = 0; c < 3; c++) {
            double cell = 2.0 / (c == 0 ? 4 : c == 1 ? 3 : 2);   /* each point stays in its own cell */
            moved += fabs(P(&j, k)[c] - P(&m, k)[c]) > 1e-6;
            outside += fabs(P(&j, k)[c] - P(&m, k)[c]) > cell / 2 + 1e-6;
        }
    CHECK_MSG(moved > 30 && outside == 0, "jitter: %d coordinates moved, %d left their cell", moved, outside);
    geom_free(&j);
    CHECK(geom_point_cloud(&j, 4, 3, 2, true));   /* the same cloud every time */
    geom_mesh j2;
    CHECK(geom_point_cloud(&j2, 4, 3, 2, true));
    CHECK_EQ(memcmp(j.pos, j2.pos, sizeof(float) * 3 * 24), 0);
    geom_free(&j);
    geom_free(&j2);
    geom_free(&m);
    CHECK(!geom_point_cloud(&m, 2048, 2048, 2048, false));

    CHECK(geom_xarrow(&m, 0));   /* closed: its volume is the shaft's and the head's */
    check_sane(&m, "Xarrow");
    check_winding_and_tangents(&m, "Xarrow");
    double lo[3], hi[3];
    bbox(&m, lo, hi);
    CHECK(fabs(lo[0]) < 1e-6 && fabs(hi[0] - 1) < 1e-6 && hi[1] <= 0.0600001 && lo[2] >= -0.0600001);
    double vol = volume(&m), exact = PI * (0.02 * 0.02 * 0.8 + 0.06 * 0.06 * 0.2 / 3);
    CHECK_MSG(vol > 0.99 * exact && vol < exact, "arrow volume %g of %g", vol, exact);
    geom_free(&m);
    /* issue 27: `Xarrow 200` has 200 segments along its length (a vertex
     * shader bends it): the shaft's vertices sit at 160 distinct x in 0..0.8 */
    CHECK(geom_xarrow(&m, 200));
    int distinct = 0;
    double xs[1024];
    for (int k = 0; k < m.nvert && distinct < 1024; k++) {
        double x = P(&m, k)[0];
        bool seen = false;
        for (int q = 0; q < distinct && !seen; q++) seen = fabs(xs[q] - x) < 1e-6;
        if (!seen && x > 1e-6 && x < 0.8 - 1e-6) xs[distinct++] = x;
    }
    CHECK_MSG(distinct == 159, "the shaft has %d inner rings, want 159 (160 segments over 0..0.8)", distinct);
    check_sane(&m, "Xarrow 200");
    geom_free(&m);
}

/* The soccer ball: 32 faces on the sphere, pentagons at the icosahedron's
 * vertices (their centres 63.4 degrees apart, cos = 1/sqrt 5), every face
 * with p from 0 at its centre to 1 at its corners. */
static void test_soccerball(void) {
    const float r = 1.5f;
    geom_mesh m;
    CHECK(geom_soccerball(&m, r));
    check_sane(&m, "Soccerball");
    CHECK(m.nparts == 32 && m.part_first && m.tcp);
    if (m.nparts != 32 || !m.part_first || !m.tcp) { geom_free(&m); return; }
    CHECK(m.part_first[0] == 0 && m.part_first[32] == m.nidx);
    int off = 0, north = 0;
    for (int k = 0; k < m.nvert; k++) {
        off += fabs(len3(P(&m, k)) - r) > 1e-5 || fabs(dot3(N(&m, k), P(&m, k)) - r) > 1e-5;
        double nn[3] = {-N(&m, k)[1] * N(&m, k)[0], 1 - N(&m, k)[1] * N(&m, k)[1], -N(&m, k)[1] * N(&m, k)[2]};
        double l = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
        if (l > 1e-3) north += (nn[0] * T(&m, k)[0] + nn[1] * T(&m, k)[1] + nn[2] * T(&m, k)[2]) / l < 0.9999;
    }
    CHECK_MSG(off == 0 && north == 0, "%d vertices off the sphere, %d tangents not towards the pole", off, north);
    double centre[32][3];
    for (int f = 0; f < 32; f++) {
        int tris = (m.part_first[f + 1] - m.part_first[f]) / 3;
        CHECK_MSG(tris == (f < 12 ? 5 : 6) * 16, "face %d has %d triangles", f, tris);
        double pmin = 1, pmax = 0, smin = 1, smax = 0, c[3] = {0, 0, 0};
        for (int i = m.part_first[f]; i < m.part_first[f + 1]; i++) {
            unsigned v = m.idx[i];
            pmin = fmin(pmin, m.tcp[v]);
            pmax = fmax(pmax, m.tcp[v]);
            smin = fmin(smin, fmin(m.tc[2 * v], m.tc[2 * v + 1]));
            smax = fmax(smax, fmax(m.tc[2 * v], m.tc[2 * v + 1]));
            for (int k = 0; k < 3; k++) c[k] += P(&m, v)[k];
        }
        CHECK_MSG(pmin < 1e-6 && fabs(pmax - 1) < 1e-5 && smin >= -1e-6 && smax <= 1 + 1e-6,
                  "face %d: p %g..%g, s/t %g..%g", f, pmin, pmax, smin, smax);
        double l = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        for (int k = 0; k < 3; k++) centre[f][k] = c[k] / l;
    }
    int bad = 0;
    for (int a = 0; a < 12; a++)
        for (int b = a + 1; b < 12; b++) {
            double d = centre[a][0] * centre[b][0] + centre[a][1] * centre[b][1] + centre[a][2] * centre[b][2];
            bad += fabs(fabs(d) - 1 / sqrt(5.0)) > 1e-3 && fabs(d + 1) > 1e-3;
        }
    CHECK_MSG(bad == 0, "%d pentagon pairs not at the icosahedron's angles", bad);
    double vol = volume(&m), exact = 4.0 / 3.0 * PI * r * r * r;
    CHECK_MSG(vol > 0.97 * exact && vol < exact, "volume %g of %g (outward winding)", vol, exact);
    geom_free(&m);
    CHECK(!geom_soccerball(&m, NAN));
}

/* ---- Shp: ESRI shapefiles ---- */

typedef struct shp_buf { unsigned char b[4096]; size_t n; } shp_buf;

static void shp_be(shp_buf *f, size_t at, unsigned v) {
    f->b[at] = (unsigned char)(v >> 24); f->b[at + 1] = (unsigned char)(v >> 16);
    f->b[at + 2] = (unsigned char)(v >> 8); f->b[at + 3] = (unsigned char)v;
}
static void shp_le(shp_buf *f, size_t at, unsigned v) {
    for (int k = 0; k < 4; k++) f->b[at + k] = (unsigned char)(v >> (8 * k));
}
static void shp_dbl(shp_buf *f, size_t at, double d) {
    unsigned long long u;
    memcpy(&u, &d, sizeof u);
    for (int k = 0; k < 8; k++) f->b[at + k] = (unsigned char)(u >> (8 * k));
}

/* Appends a PolyLine (3) or Polygon (5) record: nparts parts starting at
 * first[], npts points xy[]. */
static void shp_record(shp_buf *f, int type, int nparts, const int *first, int npts, const double *xy) {
    size_t at = f->n, c = at + 8;
    size_t clen = 44 + 4 * (size_t)nparts + 16 * (size_t)npts;
    static int recno = 0;
    shp_be(f, at, (unsigned)++recno);
    shp_be(f, at + 4, (unsigned)(clen / 2));
    shp_le(f, c, (unsigned)type);
    for (int k = 0; k < 4; k++) shp_dbl(f, c + 4 + 8 * k, 0);   /* the record's box: unread */
    shp_le(f, c + 36, (unsigned)nparts);
    shp_le(f, c + 40, (unsigned)npts);
    for (int p = 0; p < nparts; p++) shp_le(f, c + 44 + 4 * (size_t)p, (unsigned)first[p]);
    for (int i = 0; i < 2 * npts; i++) shp_dbl(f, c + 44 + 4 * (size_t)nparts + 8 * (size_t)i, xy[i]);
    f->n = c + clen;
}

static void shp_header(shp_buf *f, int type, double x0, double y0, double x1, double y1) {
    memset(f->b, 0, 100);
    shp_be(f, 0, 9994);
    shp_be(f, 24, (unsigned)(f->n / 2));
    shp_le(f, 28, 1000);
    shp_le(f, 32, (unsigned)type);
    shp_dbl(f, 36, x0); shp_dbl(f, 44, y0); shp_dbl(f, 52, x1); shp_dbl(f, 60, y1);
}

static const char *shp_write(const char *name, const shp_buf *f, size_t n) {
    static char path[512];
    snprintf(path, sizeof path, "%s/%s", tmpdir, name);
    FILE *fp = fopen(path, "wb");
    if (!fp) { perror(path); exit(1); }
    fwrite(f->b, 1, n, fp);
    fclose(fp);
    return path;
}

/* Two polylines (the second of two parts) and a polygon of two rings, one
 * written closed and one not: each part a line strip, the open ring closed. */
static void test_shp(void) {
    shp_buf f;
    memset(&f, 0, sizeof f);
    f.n = 100;
    const int f1[] = {0};
    const double l1[] = {0, 0, 1, 0, 1, 1};
    shp_record(&f, 3, 1, f1, 3, l1);
    const int f2[] = {0, 2};
    const double l2[] = {2, 0, 3, 0, 2, 1, 3, 1, 4, 1};
    shp_record(&f, 3, 2, f2, 5, l2);
    const int f3[] = {0, 4};
    const double g[] = {0, 2, 1, 2, 1, 3, 0, 2, 5, 5, 6, 5, 6, 6};
    shp_record(&f, 5, 2, f3, 7, g);
    shp_header(&f, 3, 0, 0, 6, 6);
    const char *path = shp_write("map.shp", &f, f.n);
    geom_mesh m;
    char err[512] = "";
    CHECK_MSG(geom_shp_load(&m, path, err, sizeof err), "%s", err);
    check_sane(&m, "shapefile");
    CHECK((m.prim == GEOM_LINES));
    const double want[] = {0, 0, 1, 0, 1, 1, 2, 0, 3, 0, 2, 1, 3, 1, 4, 1, 0, 2, 1, 2, 1, 3, 0, 2, 5, 5, 6, 5, 6, 6};
    CHECK_MSG(m.nvert == 15, "%d vertices, want 15", m.nvert);
    int off = 0;
    for (int k = 0; k < m.nvert && k < 15; k++) {
        off += P(&m, k)[0] != want[2 * k] || P(&m, k)[1] != want[2 * k + 1] || P(&m, k)[2] != 0;
        off += m.tc[2 * k] != (float)(want[2 * k] / 6) || m.tc[2 * k + 1] != (float)(want[2 * k + 1] / 6);
        off += N(&m, k)[2] != 1;
    }
    CHECK_MSG(off == 0, "%d vertices off (x, y on z = 0; tc over the box; normal +z)", off);
    /* segments: 2 + (1 + 2) + (3 + 2, and the open ring's closing one) */
    const unsigned seg[] = {0, 1, 1, 2, 3, 4, 5, 6, 6, 7, 8, 9, 9, 10, 10, 11, 12, 13, 13, 14, 14, 12};
    CHECK_MSG(m.nidx == 22, "%d indices, want 22", m.nidx);
    CHECK(m.nidx == 22 && memcmp(m.idx, seg, sizeof seg) == 0);
    geom_free(&m);

    /* truncated: the header promises more than there is */
    path = shp_write("cut.shp", &f, f.n - 20);
    CHECK(!geom_shp_load(&m, path, err, sizeof err));
    CHECK_MSG(strstr(err, path) && strstr(err, "truncated"), "%s", err);
    CHECK_EQ(m.nvert, 0);
    /* a record cut short, the header's length matching the cut */
    shp_buf g2 = f;
    g2.n = f.n - 20;
    shp_header(&g2, 3, 0, 0, 6, 6);
    path = shp_write("cut2.shp", &g2, g2.n);
    CHECK(!geom_shp_load(&m, path, err, sizeof err));
    CHECK_MSG(strstr(err, path) && strstr(err, "record 3"), "%s", err);
    /* missing; not a shapefile; points */
    char missing[512];
    snprintf(missing, sizeof missing, "%s/no_such_map.shp", tmpdir);
    CHECK(!geom_shp_load(&m, missing, err, sizeof err));
    CHECK_MSG(strstr(err, missing) != NULL, "%s", err);
    shp_buf t;
    memset(&t, 0, sizeof t);
    memset(t.b, 'x', 200);
    path = shp_write("text.shp", &t, 200);
    CHECK(!geom_shp_load(&m, path, err, sizeof err));
    CHECK_MSG(strstr(err, path) && strstr(err, "not a shapefile"), "%s", err);
    shp_buf pt;
    memset(&pt, 0, sizeof pt);
    pt.n = 100;
    shp_header(&pt, 1, 0, 0, 1, 1);
    path = shp_write("points.shp", &pt, pt.n);
    CHECK(!geom_shp_load(&m, path, err, sizeof err));
    CHECK_MSG(strstr(err, "Point"), "%s", err);
}

int main(void) {
    const char *base = getenv("TMPDIR");
    snprintf(tmpdir, sizeof tmpdir, "%s/tarn_test_geom_XXXXXX", base && *base ? base : "/tmp");
    if (!mkdtemp(tmpdir)) { perror("mkdtemp"); return 1; }

    RUN(test_quad);
    RUN(test_grid_bands);
    RUN(test_sphere);
    RUN(test_torus);
    RUN(test_box);
    RUN(test_cylinder_cone);
    RUN(test_teapot);
    RUN(test_obj_face_forms);
    RUN(test_obj_computed_normals);
    RUN(test_obj_errors);
    RUN(test_obj_variants);
    RUN(test_points_disk_box);
    RUN(test_clouds_and_arrow);
    RUN(test_soccerball);
    RUN(test_shp);

    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", tmpdir);
    return check_summary();
}
