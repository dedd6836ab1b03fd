/* test_ref_render: the CPU reference renderer against independent truth:
 * closed-form Snell, Fresnel and path length over flat water, total
 * internal reflection from below, the shading composition in closed form,
 * flat-water caustic irradiance within the Monte-Carlo bound (for two
 * photon seeds, which differ by noise alone and agree on a mean), bitwise
 * determinism across thread counts, exact sky pixels, finite images of the
 * lake, wavy-water hits that obey Snell at the exact surface, and
 * subsamples at given positions (MSAA's) as the rays of a finer image. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "ref_render.h"

#define PI 3.14159265358979323846
#define N_WATER 1.333

/* a max that keeps NaN (fmax would drop it) */
static double worse(double worst, double e) { return isnan(e) || e > worst ? e : worst; }

static double dot3(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void normalize3(double v[3]) {
    double l = sqrt(dot3(v, v));
    for (int i = 0; i < 3; i++) v[i] /= l;
}

/* The camera ray written out again (gluLookAt + gluPerspective): forward
 * f, right r = f x up, true up u = r x f; pixel centre (i + .5, j + .5). */
static void camera_ray(const ref_camera *c, int i, int j, double d[3]) {
    double f[3], r[3], u[3];
    for (int k = 0; k < 3; k++) f[k] = c->center[k] - c->eye[k];
    normalize3(f);
    r[0] = f[1] * c->up[2] - f[2] * c->up[1];
    r[1] = f[2] * c->up[0] - f[0] * c->up[2];
    r[2] = f[0] * c->up[1] - f[1] * c->up[0];
    normalize3(r);
    u[0] = r[1] * f[2] - r[2] * f[1];
    u[1] = r[2] * f[0] - r[0] * f[2];
    u[2] = r[0] * f[1] - r[1] * f[0];
    double t = tan(c->fov_deg * PI / 360.0), aspect = (double)c->width / c->height;
    double x = ((i + 0.5) / c->width * 2 - 1) * t * aspect, y = (1 - (j + 0.5) / c->height * 2) * t;
    for (int k = 0; k < 3; k++) d[k] = f[k] + x * r[k] + y * u[k];
    normalize3(d);
}

/* Fresnel by the sine and tangent laws (independent of ref_fresnel). */
static double fresnel_laws(double ti, double tt) {
    double rs = sin(ti - tt) / sin(ti + tt), rp = tan(ti - tt) / tan(ti + tt);
    return 0.5 * (rs * rs + rp * rp);
}

/* Flat water at y = 0 over a flat floor y = -depth, no objects. */
static void flat_world(ref_world *w, double depth) {
    ref_world_desc d;
    memset(&d, 0, sizeof d);
    d.terrain = REF_TERRAIN_FLAT;
    d.depth = depth;
    ref_world_init(w, &d);
}

static void lake_world(ref_world *w) {
    ref_world_desc d;
    ref_world_desc_lake(&d);
    ref_world_init(w, &d);
}

static int render(const ref_render_desc *d, ref_render_result *r) {
    char err[256] = "";
    int rc = ref_render(d, r, err, sizeof err);
    if (rc != 0) fprintf(stderr, "ref_render: %s\n", err);
    return rc;
}

/* ---- flat water, camera above --------------------------------------- */

static void test_flat_snell(void) {
    ref_world w;
    const double D = 2.0;
    flat_world(&w, D);
    ref_render_desc d = { .world = &w, .caustics = REF_CAUSTICS_FLAT, .threads = 2 };
    d.camera = (ref_camera){ { 0.3, 1.5, 4.0 }, { 0.0, -1.0, 0.0 }, { 0, 1, 0 }, 60, 48, 32 };
    ref_render_result r;
    CHECK_EQ(render(&d, &r), 0);
    if (!r.color) return;
    double err_hit = 0, err_fres = 0, err_laws = 0, err_depth = 0;
    int n = 0;
    for (int j = 0; j < r.height; j++)
        for (int i = 0; i < r.width; i++) {
            size_t p = (size_t)j * r.width + i;
            double dir[3];
            camera_ray(&d.camera, i, j, dir);
            if (!(dir[1] < -1e-3)) { CHECK_EQ(r.mask[p], REF_MASK_SKY); continue; }
            CHECK_EQ(r.mask[p], REF_MASK_WATER);
            const double *e = d.camera.eye;
            double tw = e[1] / -dir[1];
            double s[3] = { e[0] + tw * dir[0], 0.0, e[2] + tw * dir[2] };
            double sin_i = hypot(dir[0], dir[2]), cos_i = -dir[1];
            double sin_t = sin_i / N_WATER, cos_t = sqrt(1 - sin_t * sin_t);
            double run = D * sin_t / cos_t;
            double hit[3] = { s[0] + run * dir[0] / sin_i, -D, s[2] + run * dir[2] / sin_i };
            for (int k = 0; k < 3; k++) {
                err_hit = worse(err_hit, fabs(r.refract_hit[p * 4 + k] - hit[k]));
                err_hit = worse(err_hit, fabs(r.surface[p * 3 + k] - s[k]));
            }
            err_fres = worse(err_fres, fabs(r.fresnel[p] - ref_fresnel(cos_i, 1.0, N_WATER)));
            if (sin_i > 0.02)
                err_laws = worse(err_laws, fabs(r.fresnel[p] - fresnel_laws(asin(sin_i), asin(sin_t))));
            err_depth = worse(err_depth, fabs(r.depth[p] - D / cos_t));
            /* the reflection goes to the sky along the mirrored ray */
            CHECK_EQ(r.reflect[p * 4 + 3], REF_REFLECT_SKY);
            CHECK_NEAR(r.reflect[p * 4 + 1], -dir[1], 1e-12);
            n++;
        }
    fprintf(stderr, "  %d water pixels: hit %.2g, Fresnel %.2g (laws %.2g), depth %.2g\n", n, err_hit,
            err_fres, err_laws, err_depth);
    CHECK_GT(n, r.width * r.height / 2);
    CHECK_LE(err_hit, 1e-9);
    CHECK_LE(err_fres, 1e-12);
    CHECK_LE(err_laws, 1e-12);
    CHECK_LE(err_depth, 1e-9);
    ref_render_free(&r);
}

/* The colour of a flat-water pixel written out: R sky(reflected) + (1 - R)
 * exp(-sigma s) albedo (E_flat / pi + ambient (1 - R0) exp(-sigma D)). */
static void test_flat_color(void) {
    ref_world w;
    const double D = 1.5;
    flat_world(&w, D);
    ref_render_desc d = { .world = &w, .caustics = REF_CAUSTICS_FLAT, .threads = 1 };
    d.camera = (ref_camera){ { -0.5, 2.0, 3.0 }, { 0.5, -1.0, -1.0 }, { 0, 1, 0 }, 50, 24, 16 };
    ref_render_result r;
    CHECK_EQ(render(&d, &r), 0);
    if (!r.color) return;
    const double *sun = w.d.sun_dir, *sig = w.d.absorption;
    double cos_s = sun[1], sin_ts = sqrt(1 - cos_s * cos_s) / N_WATER, cos_ts = sqrt(1 - sin_ts * sin_ts);
    double Rs = fresnel_laws(acos(cos_s), asin(sin_ts));
    double R0 = pow((N_WATER - 1) / (N_WATER + 1), 2);
    double worst = 0;
    int n = 0;
    for (size_t p = 0; p < (size_t)r.width * r.height; p++) {
        if (r.mask[p] != REF_MASK_WATER) continue;
        const double *hit = r.refract_hit + p * 4;
        double dir[3];
        camera_ray(&d.camera, (int)(p % r.width), (int)(p / r.width), dir);
        double refl[3] = { dir[0], -dir[1], dir[2] }, sky[3], alb[3];
        ref_sky_radiance(&w, refl, sky);
        ref_terrain_albedo(&w, hit[0], hit[2], alb);
        double R = r.fresnel[p], s = r.depth[p];
        for (int k = 0; k < 3; k++) {
            /* E on the floor: E_sun cos_s (1 - R_s), attenuated over D / cos_ts */
            double E = w.d.sun_irradiance[k] * cos_s * (1 - Rs) * exp(-sig[k] * D / cos_ts);
            double amb = w.ambient[k] * (1 - R0) * exp(-sig[k] * D);
            double floor = alb[k] * (E / PI + amb);
            double want = R * sky[k] + (1 - R) * exp(-sig[k] * s) * floor;
            worst = worse(worst, fabs(r.color[p * 3 + k] - want) / want);
            CHECK_NEAR(r.irradiance[p * 3 + k], E, 1e-12 * E);
        }
        n++;
    }
    fprintf(stderr, "  %d pixels, colour relative error %.2g\n", n, worst);
    CHECK_GT(n, 100);
    CHECK_LE(worst, 1e-12);
    ref_render_free(&r);
}

/* ---- camera under water ------------------------------------------------ */

static void test_tir_from_below(void) {
    ref_world w;
    flat_world(&w, 5.0);
    ref_render_desc d = { .world = &w, .caustics = REF_CAUSTICS_FLAT, .threads = 2 };
    /* looking up at 45 degrees with a 90 degree field: 0..90 degrees from the zenith */
    d.camera = (ref_camera){ { 0.0, -1.0, 0.0 }, { 0.0, 0.0, -1.0 }, { 0, 1, 0 }, 90, 32, 32 };
    ref_render_result r;
    CHECK_EQ(render(&d, &r), 0);
    if (!r.color) return;
    double crit = asin(1.0 / N_WATER) * 180 / PI;   /* 48.61 */
    int tir = 0, through = 0;
    for (int j = 0; j < r.height; j++)
        for (int i = 0; i < r.width; i++) {
            size_t p = (size_t)j * r.width + i;
            double dir[3];
            camera_ray(&d.camera, i, j, dir);
            if (dir[1] <= 1e-3) continue;
            CHECK_EQ(r.mask[p], REF_MASK_WATER);
            double theta = acos(dir[1]) * 180 / PI;
            CHECK_NEAR(r.depth[p], 1.0 / dir[1], 1e-9);          /* eye to surface, in water */
            if (theta > crit + 0.01) {
                CHECK_EQ(r.fresnel[p], 1.0);
                CHECK(isnan(r.refract_hit[p * 4]) && r.refract_hit[p * 4 + 3] == REF_MASK_SKY);
                CHECK_EQ(r.reflect[p * 4 + 3], REF_REFLECT_POINT);   /* down to the floor */
                CHECK_NEAR(r.reflect[p * 4 + 1], -5.0, 1e-9);
                tir++;
            } else if (theta < crit - 0.01) {
                CHECK_LT(r.fresnel[p], 1.0);
                CHECK_NEAR(r.fresnel[p], ref_fresnel(dir[1], N_WATER, 1.0), 1e-12);
                double st = N_WATER * sin(acos(dir[1]));
                CHECK_NEAR(r.fresnel[p], fresnel_laws(acos(dir[1]), asin(st)), 1e-12);
                through++;
            }
        }
    fprintf(stderr, "  %d pixels beyond the critical angle, %d inside it\n", tir, through);
    CHECK(tir > 100 && through > 100);
    ref_render_free(&r);
}

/* ---- caustics over flat water ------------------------------------------ */

/* Flat water at y = 0 over a flat floor 2.5 m down, a grid of 8 cells of
 * 1024 photons (k = 32 strata a side), with the given photon seed. */
static int flat_caustics(ref_world *w, uint64_t seed, ref_render_result *r) {
    ref_world_desc wd;
    memset(&wd, 0, sizeof wd);
    wd.terrain = REF_TERRAIN_FLAT;
    wd.depth = 2.5;
    wd.half_size = 6;
    ref_world_init(w, &wd);
    ref_render_desc d = { .world = w, .threads = 2, .caustic_res = 8, .photons_per_cell = 1024, .seed = seed };
    d.camera = (ref_camera){ { 0.5, 2.0, 3.0 }, { 0.0, -2.5, 0.0 }, { 0, 1, 0 }, 60, 32, 24 };
    return render(&d, r);
}

/* The irradiance at every water pixel against the closed form E cos(theta_s)
 * (1 - R) exp(-sigma D / cos(theta_t)); the worst relative error, or -1
 * when a pixel is not water or its hit is off the floor. */
static double flat_caustics_error(const ref_world *w, const ref_render_result *r) {
    const double *sun = w->d.sun_dir;
    double cos_s = sun[1], sin_ts = sqrt(1 - cos_s * cos_s) / N_WATER, cos_ts = sqrt(1 - sin_ts * sin_ts);
    double Rs = fresnel_laws(acos(cos_s), asin(sin_ts));
    double worst = 0;
    for (size_t p = 0; p < (size_t)r->width * r->height; p++) {
        if (r->mask[p] != REF_MASK_WATER || isnan(r->irradiance[p * 3])) return -1;
        const double *hit = r->refract_hit + p * 4;
        if (!(fabs(hit[0]) < 6 && fabs(hit[2]) < 6)) return -1;
        for (int c = 0; c < 3; c++) {
            double want = w->d.sun_irradiance[c] * cos_s * (1 - Rs) * exp(-w->d.absorption[c] * 2.5 / cos_ts);
            worst = worse(worst, fabs(r->irradiance[p * 3 + c] / want - 1));
        }
    }
    return worst;
}

static void test_flat_caustics(void) {
    ref_world w;
    ref_render_result r;
    CHECK_EQ(flat_caustics(&w, 0, &r), 0);
    if (!r.color) return;
    CHECK(r.have_caustics);
    /* k = 32 strata a side per cell: the count's sd is at most sqrt(k+1) of
       k^2 photons (docs/reference.md), 0.56%; bound 5 sd = 2.8% */
    const double k = 32, bound = 5 * sqrt(k + 1) / (k * k);
    double worst = flat_caustics_error(&w, &r);
    fprintf(stderr, "  %d pixels, %ld photons: worst relative error %.2g (bound %.3g)\n", r.width * r.height,
            r.caustics.stats.photons, worst, bound);
    CHECK_GE(worst, 0);
    CHECK_LE(worst, bound);
    ref_render_free(&r);
}

/* ---- photon seeds ----------------------------------------------------------- */

#define SAME(a, b, n) (memcmp((a), (b), (n) * sizeof *(a)) == 0)

/* ref_render_desc.seed: another seed is another sampling of the same
 * strata. Over flat water each seed meets the closed form within the
 * Monte-Carlo bound of test_flat_caustics, the two grids differ (photons
 * near a cell's edge land on either side), and one seed twice is the same
 * render bit for bit. */
static void test_seed_flat(void) {
    ref_world w;
    ref_render_result a, b, c;
    CHECK_EQ(flat_caustics(&w, 0, &a), 0);
    CHECK_EQ(flat_caustics(&w, 1, &b), 0);
    CHECK_EQ(flat_caustics(&w, 1, &c), 0);
    if (!a.color || !b.color || !c.color) return;
    size_t n = (size_t)a.width * a.height, cells = (size_t)a.caustics.nx * a.caustics.nz;
    CHECK(b.caustics.nx == a.caustics.nx && b.caustics.nz == a.caustics.nz);
    CHECK_EQ(b.caustics.stats.photons, a.caustics.stats.photons);   /* the same strata */
    CHECK(!SAME(a.caustics.irradiance, b.caustics.irradiance, cells * 3));
    CHECK(SAME(b.caustics.irradiance, c.caustics.irradiance, cells * 3));
    CHECK(SAME(b.color, c.color, n * 3));
    CHECK(SAME(b.irradiance, c.irradiance, n * 3));
    const double k = 32, bound = 5 * sqrt(k + 1) / (k * k);
    double e0 = flat_caustics_error(&w, &a), e1 = flat_caustics_error(&w, &b);
    fprintf(stderr, "  seed 0: worst relative error %.2g, seed 1: %.2g (bound %.3g)\n", e0, e1, bound);
    CHECK(e1 >= 0 && e1 <= bound);
    ref_render_free(&a);
    ref_render_free(&b);
    ref_render_free(&c);
}

/* Over the lake's waves (focused caustics) two seeds differ cell by cell
 * by photon noise, and agree on the mean over the wet cells: the mean of
 * the per-cell differences within 5 standard errors of it (the cells taken
 * as independent; stratified jitter makes neighbours anti-correlated, which
 * only narrows the mean's spread). A seed that moved the mean would be a
 * bias, not another sampling. */
static void test_seed_lake(void) {
    ref_world w;
    lake_world(&w);
    ref_render_desc d = { .world = &w, .threads = 2, .time = 2.0, .caustic_res = 48, .photons_per_cell = 16 };
    d.camera = (ref_camera){ { 0.0, 3.0, 14.0 }, { 0.0, -0.5, 0.0 }, { 0, 1, 0 }, 50, 32, 18 };
    ref_render_desc d7 = d;
    d7.seed = 7;
    ref_render_result a, b;
    CHECK_EQ(render(&d, &a), 0);
    CHECK_EQ(render(&d7, &b), 0);
    if (!a.color || !b.color) return;
    CHECK(a.have_caustics && b.have_caustics);
    CHECK(a.caustics.nx == b.caustics.nx && a.caustics.nz == b.caustics.nz);
    size_t cells = (size_t)a.caustics.nx * a.caustics.nz;
    double sum_a = 0, sum_d = 0, sq_d = 0, sq_rel = 0;
    long m = 0;
    for (size_t i = 0; i < cells; i++) {
        double ea = a.caustics.irradiance[i * 3 + 1], eb = b.caustics.irradiance[i * 3 + 1];
        if (!(ea > 0) || !(eb > 0)) continue;   /* dry, or beyond the photons */
        sum_a += ea;
        sum_d += ea - eb;
        sq_d += (ea - eb) * (ea - eb);
        sq_rel += (ea - eb) * (ea - eb) / (0.25 * (ea + eb) * (ea + eb));
        m++;
    }
    CHECK_GT(m, 100);
    if (m <= 100) return;
    double mean_a = sum_a / m, mean_d = sum_d / m;
    double sd_d = sqrt(fmax(0, sq_d / m - mean_d * mean_d)), se = sd_d / sqrt((double)m);
    double rms_rel = sqrt(sq_rel / m);
    fprintf(stderr, "  %ld wet cells: rms relative difference %.3f; mean %.5g, seeds differ on it by %.3g "
            "(standard error %.3g)\n", m, rms_rel, mean_a, mean_d, se);
    /* k = 4: at most sqrt(5)/16 = 14% a cell unfocused, two seeds sqrt(2)
       times that; focusing raises it: noise, but neither none nor garbage */
    CHECK(rms_rel > 0.01 && rms_rel < 0.6);
    CHECK_LE(fabs(mean_d), 5 * se);
    ref_render_free(&a);
    ref_render_free(&b);
}

/* ---- the lake ------------------------------------------------------------- */

static ref_render_desc lake_desc(const ref_world *w, int threads, double t) {
    ref_render_desc d = { .world = w, .threads = threads, .time = t, .caustic_res = 48,
                          .photons_per_cell = 16 };
    d.camera = (ref_camera){ { 0.0, 3.0, 14.0 }, { 0.0, -0.5, 0.0 }, { 0, 1, 0 }, 50, 64, 36 };
    return d;
}

static void test_deterministic(void) {
    ref_world w;
    lake_world(&w);
    ref_render_desc d1 = lake_desc(&w, 1, 2.0), d2 = lake_desc(&w, 2, 2.0), d3 = lake_desc(&w, 3, 2.0);
    ref_render_result a, b, c;
    CHECK_EQ(render(&d1, &a), 0);
    CHECK_EQ(render(&d2, &b), 0);
    CHECK_EQ(render(&d3, &c), 0);
    if (!a.color || !b.color || !c.color) return;
    size_t n = (size_t)a.width * a.height;
    const ref_render_result *o[2] = { &b, &c };
    for (int k = 0; k < 2; k++) {
        CHECK(SAME(a.color, o[k]->color, n * 3));
        CHECK(SAME(a.mask, o[k]->mask, n));
        CHECK(SAME(a.surface, o[k]->surface, n * 3));
        CHECK(SAME(a.refract_hit, o[k]->refract_hit, n * 4));
        CHECK(SAME(a.reflect, o[k]->reflect, n * 4));
        CHECK(SAME(a.fresnel, o[k]->fresnel, n));
        CHECK(SAME(a.depth, o[k]->depth, n));
        CHECK(SAME(a.irradiance, o[k]->irradiance, n * 3));
        CHECK(a.caustics.nx == o[k]->caustics.nx && a.caustics.nz == o[k]->caustics.nz);
        CHECK(SAME(a.caustics.irradiance, o[k]->caustics.irradiance,
                   (size_t)a.caustics.nx * a.caustics.nz * 3));
        CHECK_EQ(a.caustics.stats.flux_in_grid[1], o[k]->caustics.stats.flux_in_grid[1]);
    }
    CHECK(a.threads == 1 && b.threads == 2 && c.threads == 3);
    ref_render_free(&a);
    ref_render_free(&b);
    ref_render_free(&c);
}

static void test_lake_finite(void) {
    ref_world w;
    lake_world(&w);
    const double times[] = { 0.0, 3.7, 11.25 };
    for (int t = 0; t < 3; t++) {
        ref_render_desc d = lake_desc(&w, 2, times[t]);
        if (t == 2) d.spp = 2;
        ref_render_result r;
        CHECK_EQ(render(&d, &r), 0);
        if (!r.color) return;
        int bad = 0, kinds[4] = { 0 };
        for (size_t p = 0; p < (size_t)r.width * r.height; p++) {
            for (int k = 0; k < 3; k++) bad += !isfinite(r.color[p * 3 + k]) || r.color[p * 3 + k] < 0;
            kinds[r.mask[p]]++;
        }
        CHECK_MSG(bad == 0, "t = %g: %d non-finite or negative values", times[t], bad);
        CHECK(kinds[0] > 0 && kinds[1] > 0 && kinds[2] > 0 && kinds[3] > 0);   /* it sees it all */
        /* energy: the photons' flux splits into reflected and transmitted */
        const ref_caustics_stats *s = &r.caustics.stats;
        CHECK_NEAR(s->flux_reflected + s->flux_transmitted,
                   s->flux_emitted * (double)s->hit_water / (double)s->photons, 1e-9 * s->flux_emitted);
        ref_render_free(&r);
    }
}

/* ---- explicit subsample positions ---------------------------------- */

/* GL's standard 4x MSAA positions, turned from GL's y up into the image's
 * y down: (0.375, 0.125) ... become (0.375, 0.875) ... */
static const double ROTATED4[4][2] = { { 0.375, 0.875 }, { 0.875, 0.625 }, { 0.125, 0.375 }, { 0.625, 0.125 } };

/* One position at the pixel centre is the 1-spp render, bit for bit (the
 * same rays in the same order), buffers and all. */
static void test_positions_centre_is_spp1(void) {
    ref_world w;
    lake_world(&w);
    ref_render_desc d1 = lake_desc(&w, 2, 2.0), dp = d1;
    dp.nsamples = 1;
    dp.samples[0][0] = dp.samples[0][1] = 0.5;
    ref_render_result a, b;
    CHECK_EQ(render(&d1, &a), 0);
    CHECK_EQ(render(&dp, &b), 0);
    size_t n = (size_t)a.width * a.height;
    CHECK_EQ(b.nsamples, 1);
    CHECK(SAME(a.color, b.color, n * 3));
    CHECK(SAME(a.mask, b.mask, n));
    CHECK(SAME(a.refract_hit, b.refract_hit, n * 4));
    CHECK(SAME(a.fresnel, b.fresnel, n));
    ref_render_free(&a);
    ref_render_free(&b);
}

/* Positions on a 1/4-pixel lattice against independent truth: pixel
 * (i, j)'s subsample at ((a + 0.5) / 4, (b + 0.5) / 4) is the same camera
 * ray as the centre of pixel (4i + a, 4j + b) of the 1-spp image 4x the
 * size (ref_camera_ray scales px / w; a factor 4 is exact in binary), so
 * the rotated 4x pattern is the mean of those four centre pixels.
 * Tolerance 1e-12: the same rays give the same radiance; only the sum's
 * order differs. The pattern's mirror (y up taken as y down) is checked to
 * differ, so the test sees which way y runs; and the spp grid is its cell
 * centres given as positions, bit for bit. */
static double lattice_error(const ref_render_result *r, const ref_render_result *big, const double pos[][2],
                            int np) {
    double worst = 0;
    for (int j = 0; j < r->height; j++)
        for (int i = 0; i < r->width; i++)
            for (int c = 0; c < 3; c++) {
                double sum = 0;
                for (int k = 0; k < np; k++) {
                    int x = 4 * i + (int)(pos[k][0] * 4), y = 4 * j + (int)(pos[k][1] * 4);
                    sum += big->color[((size_t)y * big->width + x) * 3 + c];
                }
                worst = worse(worst, fabs(r->color[((size_t)j * r->width + i) * 3 + c] - sum / np));
            }
    return worst;
}

static void test_positions_are_subpixel_rays(void) {
    ref_world w;
    lake_world(&w);
    ref_render_desc d = lake_desc(&w, 2, 2.0), big = d, grid = d, mirror = d;
    d.camera.width = big.camera.width / 4;   /* 16 x 9, and 64 x 36 the lattice */
    d.camera.height = big.camera.height / 4;
    grid.camera = mirror.camera = d.camera;
    d.nsamples = mirror.nsamples = 4;
    for (int k = 0; k < 4; k++) {
        d.samples[k][0] = mirror.samples[k][0] = ROTATED4[k][0];
        d.samples[k][1] = ROTATED4[k][1];
        mirror.samples[k][1] = 1 - ROTATED4[k][1];
    }
    grid.spp = 2;
    ref_render_result r, b, g, m;
    CHECK_EQ(render(&d, &r), 0);
    CHECK_EQ(render(&big, &b), 0);
    CHECK_EQ(render(&grid, &g), 0);
    CHECK_EQ(render(&mirror, &m), 0);
    double e = lattice_error(&r, &b, ROTATED4, 4);
    CHECK_MSG(e < 1e-12, "rotated 4x: worst %g off the mean of the 4x image's pixels", e);
    double em = lattice_error(&m, &b, ROTATED4, 4);
    CHECK_MSG(em > 1e-3, "the mirrored pattern is as close (%g): the scene has no edge to tell", em);
    /* the spp grid is the same as its cell centres given as positions, in
       its order (row by row), bit for bit */
    ref_render_desc gp = grid;
    gp.spp = 0;
    gp.nsamples = 4;
    for (int k = 0; k < 4; k++) {
        gp.samples[k][0] = 0.25 + 0.5 * (k % 2);
        gp.samples[k][1] = 0.25 + 0.5 * (k / 2);
    }
    ref_render_result q;
    CHECK_EQ(render(&gp, &q), 0);
    CHECK(SAME(q.color, g.color, (size_t)g.width * g.height * 3));
    ref_render_free(&q);
    /* the centre ray's buffers do not depend on the subsamples */
    size_t n = (size_t)r.width * r.height;
    CHECK(SAME(r.mask, g.mask, n));
    CHECK(SAME(r.fresnel, g.fresnel, n));
    ref_render_free(&r);
    ref_render_free(&b);
    ref_render_free(&g);
    ref_render_free(&m);
}

/* Wavy water: every refraction hit lies on the terrain, along the Snell
 * direction at the exact surface normal from a point on the surface. */
static void test_lake_snell(void) {
    ref_world w;
    lake_world(&w);
    ref_render_desc d = lake_desc(&w, 2, 4.5);
    d.caustics = REF_CAUSTICS_FLAT;
    ref_render_result r;
    CHECK_EQ(render(&d, &r), 0);
    if (!r.color) return;
    double worst_surf = 0, worst_dir = 0, worst_floor = 0;
    int n = 0, nter = 0, nobj = 0;
    for (int j = 0; j < r.height; j++)
        for (int i = 0; i < r.width; i++) {
            size_t p = (size_t)j * r.width + i;
            if (r.mask[p] != REF_MASK_WATER) continue;
            const double *s = r.surface + p * 3, *h = r.refract_hit + p * 4;
            ref_waves_point wp;
            CHECK_EQ(ref_waves_at(&w.waves, s[0], s[2], d.time, NULL, &wp), 0);
            worst_surf = worse(worst_surf, fabs(wp.pos[1] - s[1]));
            if (isnan(h[0])) continue;
            double dir[3], t[3], seg[3];
            camera_ray(&d.camera, i, j, dir);
            CHECK(ref_refract(dir, wp.normal, 1.0, N_WATER, t));
            for (int k = 0; k < 3; k++) seg[k] = h[k] - s[k];
            double len = sqrt(dot3(seg, seg));
            /* the floor hit is within t_tol = 1e-9 of the crossing along the ray */
            for (int k = 0; k < 3; k++)
                worst_dir = worse(worst_dir, fabs(seg[k] / len - t[k]) / (1e-12 + 2e-9 / len));
            CHECK_NEAR(len, r.depth[p], 1e-9);
            if (h[3] == REF_MASK_TERRAIN) {
                worst_floor = worse(worst_floor, fabs(h[1] - ref_terrain_height(&w, h[0], h[2])));
                nter++;
            } else {   /* an object: the segment ends on its surface */
                double to, no[3];
                CHECK_EQ(h[3], REF_MASK_OBJECT);
                CHECK_GE(ref_objects_hit(&w, s, t, 0.0, len + 1e-6, &to, no), 0);
                CHECK_NEAR(to, len, 1e-9);
                nobj++;
            }
            n++;
        }
    fprintf(stderr, "  %d pixels (%d terrain, %d objects): surface %.2g, direction %.2g of the bound, on the terrain %.2g\n",
            n, nter, nobj, worst_surf, worst_dir, worst_floor);
    CHECK(n > 200 && nter > 0 && nobj > 0);
    CHECK_LE(worst_surf, 1e-9);
    CHECK_LE(worst_dir, 1.0);      /* in units of the bound 2e-9 / len + 1e-12 */
    CHECK_LE(worst_floor, 1e-12);
    ref_render_free(&r);
}

static void test_sky_exact(void) {
    ref_world w;
    lake_world(&w);
    ref_render_desc d = { .world = &w, .threads = 2, .caustics = REF_CAUSTICS_FLAT };
    d.camera = (ref_camera){ { 1.0, 2.0, 13.0 }, { 0.0, 2.5, 0.0 }, { 0, 1, 0 }, 70, 40, 30 };
    ref_render_result r;
    CHECK_EQ(render(&d, &r), 0);
    if (!r.color) return;
    int n = 0;
    for (int j = 0; j < r.height; j++)
        for (int i = 0; i < r.width; i++) {
            size_t p = (size_t)j * r.width + i;
            if (r.mask[p] != REF_MASK_SKY) continue;
            double o[3], dir[3], want[3], mine[3];
            ref_camera_ray(&d.camera, i + 0.5, j + 0.5, o, dir);
            camera_ray(&d.camera, i, j, mine);
            for (int k = 0; k < 3; k++) CHECK_NEAR(dir[k], mine[k], 1e-14);
            ref_sky_radiance(&w, dir, want);
            CHECK_EQ(memcmp(want, r.color + p * 3, sizeof want), 0);
            CHECK(isnan(r.fresnel[p]) && isnan(r.depth[p]) && r.reflect[p * 4 + 3] == REF_REFLECT_NONE);
            n++;
        }
    fprintf(stderr, "  %d sky pixels\n", n);
    CHECK_GT(n, 300);
    ref_render_free(&r);
}

/* Luminance of an albedo. */
static double luma(const double c[3]) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

/* The spread of the terrain's albedo (luminance, max - min) over one tile
 * period (1 m: a light and a dark tile) on the floor near (x0, z0). */
static double albedo_spread(const ref_world *w, double x0, double z0) {
    double lo = 1e9, hi = -1e9;
    for (int j = 0; j < 40; j++)
        for (int i = 0; i < 40; i++) {
            double c[3];
            ref_terrain_albedo(w, x0 + (i + 0.5) / 40.0, z0 + (j + 0.5) / 40.0, c);
            lo = fmin(lo, luma(c));
            hi = fmax(hi, luma(c));
        }
    return hi - lo;
}

/* The pool (scenes/pool.glib's world) exists so that an error in the
 * refraction hit shows as a colour error: its floor must have strong
 * contrast over a tile period where the lake's has almost none; its floor
 * is flat at -depth, its deck at +shore, its gradient is the height's and
 * within the bound the tracer marches with. */
static void test_pool_contrast(void) {
    ref_world_desc d;
    memset(&d, 0, sizeof d);
    d.terrain = REF_TERRAIN_POOL;
    d.depth = 1.5;
    d.shore_height = 0.4;
    ref_world pool, lake;
    ref_world_init(&pool, &d);
    lake_world(&lake);
    double sp = albedo_spread(&pool, -2.3, 1.1), sl = albedo_spread(&lake, -2.3, 1.1);
    fprintf(stderr, "  albedo spread over 1 m: pool %.3f, lake %.3f\n", sp, sl);
    CHECK_MSG(sp > 0.4, "pool albedo spread %.3f (want > 0.4)", sp);
    CHECK_MSG(sl < 0.1, "lake albedo spread %.3f (the pool is the high-contrast one)", sl);
    CHECK_NEAR(ref_terrain_height(&pool, 0.3, -2.0), -1.5, 1e-12);
    CHECK_NEAR(ref_terrain_height(&pool, 11.0, -11.0), 0.4, 1e-12);
    double worst = 0, gmax = 0;
    for (int k = 0; k < 2000; k++) {
        double x = -12 + 24 * ((k * 37) % 2000) / 2000.0, z = -12 + 24 * ((k * 91) % 2000) / 2000.0;
        double g[2], e = 1e-6;
        ref_terrain_gradient(&pool, x, z, g);
        double fx = (ref_terrain_height(&pool, x + e, z) - ref_terrain_height(&pool, x - e, z)) / (2 * e);
        double fz = (ref_terrain_height(&pool, x, z + e) - ref_terrain_height(&pool, x, z - e)) / (2 * e);
        worst = fmax(worst, fmax(fabs(fx - g[0]), fabs(fz - g[1])));
        gmax = fmax(gmax, hypot(g[0], g[1]));
    }
    CHECK_MSG(worst < 1e-5, "pool gradient off its height's by %g", worst);
    CHECK_MSG(gmax > 0.5 && gmax <= pool.terrain_slope_bound,
              "pool slope %g against its bound %g", gmax, pool.terrain_slope_bound);
}

static void test_bad_input(void) {
    ref_world w;
    flat_world(&w, 1.0);
    ref_render_result r;
    char err[256] = "";
    ref_render_desc d = { 0 };
    CHECK_EQ(ref_render(&d, &r, err, sizeof err), -1);
    CHECK_STR_CONTAINS(err, "no world");
    d.world = &w;
    d.camera = (ref_camera){ { 0, 1, 0 }, { 0, 1, 0 }, { 0, 1, 0 }, 50, 8, 8 };
    CHECK_EQ(ref_render(&d, &r, err, sizeof err), -1);
    CHECK_STR_CONTAINS(err, "eye equals");
    d.camera.center[1] = 5;
    CHECK_EQ(ref_render(&d, &r, err, sizeof err), -1);
    CHECK_STR_CONTAINS(err, "up lies along");
    d.camera.center[2] = 1;
    d.spp = 100;
    CHECK_EQ(ref_render(&d, &r, err, sizeof err), -1);
    CHECK_EQ(r.color, NULL);
    /* photon grids past the memory budget: refused before any is allocated */
    d.spp = 1;
    d.nsamples = 1;
    d.samples[0][1] = 1.0;   /* a position must lie in the pixel, [0, 1) */
    CHECK_EQ(ref_render(&d, &r, err, sizeof err), -1);
    CHECK_STR_CONTAINS(err, "outside the pixel");
    d.nsamples = REF_MAX_SAMPLES + 1;
    CHECK_EQ(ref_render(&d, &r, err, sizeof err), -1);
    d.nsamples = 0;
    d.caustic_res = 8192;
    d.threads = 64;
    CHECK_EQ(ref_render(&d, &r, err, sizeof err), -1);
    CHECK_STR_CONTAINS(err, "a 8192 x 8192 caustic grid on 64 threads needs 99 GiB");
    CHECK_EQ(r.color, NULL);
    ref_render_desc z = ref_render_resolve(NULL);
    CHECK(z.camera.width == 640 && z.camera.height == 360 && z.camera.fov_deg == 50);
    CHECK(z.spp == 1 && z.threads >= 1 && z.max_depth == 5 && z.t_tol == 1e-9);
}

int main(void) {
    RUN(test_flat_snell);
    RUN(test_flat_color);
    RUN(test_tir_from_below);
    RUN(test_flat_caustics);
    RUN(test_seed_flat);
    RUN(test_seed_lake);
    RUN(test_deterministic);
    RUN(test_lake_finite);
    RUN(test_positions_centre_is_spp1);
    RUN(test_positions_are_subpixel_rays);
    RUN(test_lake_snell);
    RUN(test_sky_exact);
    RUN(test_pool_contrast);
    RUN(test_bad_input);
    return check_summary();
}
