/* test_ref_trace: rays against water and terrain, Beer-Lambert, photon
 * tracing — against closed forms computed here (sin/asin geometry, ray-plane
 * intersection) and dense brute-force searches. */
#include "check.h"
#include "ref_trace.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define DEG (M_PI / 180.0)
#define N_W REF_N_WATER

static double lcg01(uint64_t *s) {
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) * 0x1.0p-53;
}

static int init_waves(ref_waves *w, const ref_waves_desc *d) {
    char err[256];
    int rc = ref_waves_init(w, d, err, sizeof err);
    CHECK_MSG(rc == 0, "%s", err);
    return rc;
}

/* ---- terrains ---------------------------------------------------------- */

typedef struct plane { double a, b, c; } plane;       /* y = a + b x + c z */
static double plane_h(const void *u, double x, double z) {
    const plane *p = u;
    return p->a + p->b * x + p->c * z;
}

static double sine_floor_h(const void *u, double x, double z) {
    (void)u;
    return -2.0 + 0.3 * sin(1.7 * x) * cos(1.3 * z) + 0.1 * sin(4.1 * x + 2.3 * z);
}
/* |grad| <= 0.3 sqrt(1.7^2 + 1.3^2) + 0.1 sqrt(4.1^2 + 2.3^2) */
static double sine_floor_lip(void) { return 0.3 * hypot(1.7, 1.3) + 0.1 * hypot(4.1, 2.3); }

/* ---- brute force: first sign change of g on a fine grid, then bisection */

typedef double (*gfn)(const void *ctx, double t);

static int brute_first_root(gfn g, const void *ctx, double t0, double t1, double dt, double *root) {
    double a = t0, ga = g(ctx, a);
    for (double b = t0 + dt; a < t1; a = b, b += dt) {
        if (b > t1) b = t1;
        double gb = g(ctx, b);
        if ((ga > 0.0) != (gb > 0.0) || gb == 0.0) {
            double lo = a, hi = b, glo = ga;
            for (int i = 0; i < 200 && hi - lo > 1e-14; i++) {
                double m = 0.5 * (lo + hi), gm = g(ctx, m);
                if ((gm > 0.0) == (glo > 0.0)) { lo = m; glo = gm; } else hi = m;
            }
            *root = 0.5 * (lo + hi);
            return 1;
        }
        ga = gb;
        if (b >= t1) break;
    }
    return 0;
}

typedef struct ray_ctx {
    const double *o, *d;
    const ref_waves *w;
    double time;
    ref_height_fn h;
} ray_ctx;

static double g_water(const void *vc, double t) {
    const ray_ctx *c = vc;
    double x = c->o[0] + t * c->d[0], z = c->o[2] + t * c->d[2];
    return c->o[1] + t * c->d[1] - ref_waves_height(c->w, x, z, c->time);
}

static double g_terrain(const void *vc, double t) {
    const ray_ctx *c = vc;
    double x = c->o[0] + t * c->d[0], z = c->o[2] + t * c->d[2];
    return c->o[1] + t * c->d[1] - c->h(NULL, x, z);
}

/* ---- flat water, flat floor: closed-form Snell -------------------------- */

/* Camera above flat water (y = L) over a flat floor (y = F): the ray at
 * angle th from the vertical, azimuth ph, meets the water after
 * (o.y - L) / cos th, bends to tt = asin(sin th / n) and meets the floor a
 * horizontal (L - F) tan tt further along the azimuth. Asserted to 1e-9
 * (the traces refine t to 1e-9; on planes they land to rounding). */
static void test_flat_refraction_closed_form(void) {
    ref_waves_desc wd;
    memset(&wd, 0, sizeof wd);
    wd.level = 0.5;
    ref_waves w;
    if (init_waves(&w, &wd)) return;
    const double L = 0.5, F = -3.0;
    plane pl = { F, 0.0, 0.0 };
    ref_terrain floors[2] = {
        { .height = plane_h, .user = &pl },                  /* no bound: fixed steps */
        { .height = plane_h, .user = &pl, .lipschitz = 1.0 }, /* Lipschitz steps */
    };
    double worst = 0.0, worst_w = 0.0, worst_r = 0.0, worst_path = 0.0;
    for (int fi = 0; fi < 2; fi++)
        for (int it = 0; it <= 85; it += 5)
            for (int ip = 0; ip < 360; ip += 40) {
                double th = it * DEG, ph = ip * DEG;
                double o[3] = { 1.0, 4.0, -2.0 };
                double d[3] = { sin(th) * cos(ph), -cos(th), sin(th) * sin(ph) };
                ref_refraction r;
                if (!ref_trace_refraction(&w, 0.0, 1.0, N_W, &floors[fi], o, d, NULL, &r)) {
                    CHECK_MSG(0, "no water hit at %d deg", it);
                    continue;
                }
                double tw = (o[1] - L) / cos(th);
                double pw[3] = { o[0] + tw * d[0], L, o[2] + tw * d[2] };
                double tt = asin(sin(th) / N_W);
                double along = (L - F) * tan(tt);
                double pf[3] = { pw[0] + along * cos(ph), F, pw[2] + along * sin(ph) };
                double rs = it ? pow(sin(th - tt) / sin(th + tt), 2) : pow((N_W - 1) / (N_W + 1), 2);
                double rp = it ? pow(tan(th - tt) / tan(th + tt), 2) : rs;
                CHECK(!r.water.from_below && !r.tir && r.floor.hit);
                for (int k = 0; k < 3; k++) {
                    worst_w = fmax(worst_w, fabs(r.water.surf.pos[k] - pw[k]));
                    worst = fmax(worst, fabs(r.floor.pos[k] - pf[k]));
                }
                worst_r = fmax(worst_r, fabs(r.fresnel - 0.5 * (rs + rp)));
                worst_path = fmax(worst_path, fabs(r.water_path - (L - F) / cos(tt)));
            }
    CHECK_MSG(worst_w <= 1e-9, "water hit error %g", worst_w);
    CHECK_MSG(worst <= 1e-9, "floor hit error %g", worst);
    CHECK_MSG(worst_r <= 1e-12, "Fresnel error %g", worst_r);
    CHECK_MSG(worst_path <= 1e-9, "water path error %g", worst_path);
    fprintf(stderr, "  max error: water hit %.3g, floor hit %.3g, Fresnel %.3g\n", worst_w, worst, worst_r);

    /* camera under water looking up: leaves at asin(n sin th) below the
     * critical angle, total internal reflection beyond it */
    for (int it = 0; it < 80; it += 4) {
        double th = it * DEG;
        double o[3] = { 0.0, -1.0, 0.0 };
        double d[3] = { sin(th), cos(th), 0.0 };
        ref_refraction r;
        if (!ref_trace_refraction(&w, 0.0, 1.0, N_W, NULL, o, d, NULL, &r)) { CHECK(0); continue; }
        CHECK(r.water.from_below);
        CHECK_NEAR(r.water.t, (L + 1.0) / cos(th), 1e-9);
        CHECK_NEAR(r.water_path, (L + 1.0) / cos(th), 1e-9);
        if (N_W * sin(th) < 1.0) {
            double tt = asin(N_W * sin(th));
            CHECK(!r.tir);
            CHECK_NEAR(r.refract_dir[0], sin(tt), 1e-12);
            CHECK_NEAR(r.refract_dir[1], cos(tt), 1e-12);
            CHECK_LT(r.fresnel, 1.0);
        } else {
            CHECK(r.tir);
            CHECK_EQ(r.fresnel, 1.0);
            CHECK_NEAR(r.reflect_dir[1], -cos(th), 1e-12);
        }
    }
}

/* ---- wavy water vs brute force ------------------------------------------ */

/* Rays from above (10..80 deg from vertical) and from below against the
 * default wave set: the hit lies on the surface, and its t equals the first
 * sign change of y(t) - H(x(t), z(t)) found by stepping 1e-4 and bisecting
 * to 1e-14, within 1e-9 (the refinement tolerance). */
static void test_water_vs_brute_force(void) {
    ref_waves_desc wd = ref_waves_default();
    ref_waves w;
    if (init_waves(&w, &wd)) return;
    /* the surface lies below level + sum |A| + sum of noise octave
     * amplitudes (gradient noise stays within +-sqrt(2)/2 < 1) */
    double top = wd.level + wd.noise.amplitude * (1.0 + 0.5 + 0.25);
    for (int i = 0; i < wd.sine_count; i++) top += fabs(wd.sine[i].amplitude);
    for (int i = 0; i < wd.gerstner_count; i++) top += fabs(wd.gerstner[i].amplitude);
    CHECK(wd.noise.octaves == 3 && wd.noise.gain == 0.5);
    uint64_t s = 11;
    double worst_t = 0.0, worst_on = 0.0;
    int n = 0, evals = 0;
    for (int i = 0; i < 60; i++) {
        int below = i % 5 == 4;
        double th = (10.0 + 70.0 * lcg01(&s)) * DEG, ph = 2 * M_PI * lcg01(&s);
        double time = 10.0 * lcg01(&s);
        double o[3] = { 40.0 * lcg01(&s) - 20.0, below ? -0.7 : 2.0, 40.0 * lcg01(&s) - 20.0 };
        double d[3] = { sin(th) * cos(ph), below ? cos(th) : -cos(th), sin(th) * sin(ph) };
        if (below) { d[0] *= 0.5; d[2] *= 0.5; double l = sqrt(d[0]*d[0]+d[1]*d[1]+d[2]*d[2]); for (int k = 0; k < 3; k++) d[k] /= l; }
        ref_water_hit hit;
        if (!ref_trace_water(&w, time, o, d, NULL, &hit)) { CHECK_MSG(0, "ray %d missed", i); continue; }
        CHECK_EQ(hit.from_below, below);
        evals += hit.evals;
        /* on the surface, and the parametric point maps to it */
        double P[3];
        ref_waves_displace(&w, hit.surf.param[0], hit.surf.param[1], time, P);
        for (int k = 0; k < 3; k++) worst_on = fmax(worst_on, fabs(P[k] - hit.surf.pos[k]));
        double ray_y = o[1] + hit.t * d[1];
        worst_on = fmax(worst_on, fabs(ray_y - hit.surf.pos[1]));
        ray_ctx c = { .o = o, .d = d, .w = &w, .time = time };
        double t_bf;
        double t_start = below ? 0.0 : (o[1] - top) / -d[1];   /* no water above top */
        if (!brute_first_root(g_water, &c, t_start, hit.t + 1.0, 1e-4, &t_bf)) { CHECK(0); continue; }
        worst_t = fmax(worst_t, fabs(t_bf - hit.t));
        n++;
    }
    CHECK_MSG(worst_t <= 1e-9, "|t - t_brute| = %g", worst_t);
    CHECK_MSG(worst_on <= 1e-9, "hit off the surface by %g", worst_on);
    fprintf(stderr, "  %d rays: max |t - t_brute| %.3g, off-surface %.3g, %.1f evaluations per ray\n",
            n, worst_t, worst_on, (double)evals / (n ? n : 1));

    /* a ray above the slab going up, and one parallel above it, miss */
    double o[3] = { 0.0, 2.0, 0.0 }, up[3] = { 0.0, 1.0, 0.0 }, side[3] = { 1.0, 0.0, 0.0 };
    ref_water_hit hit;
    CHECK(!ref_trace_water(&w, 0.0, o, up, NULL, &hit));
    CHECK(!ref_trace_water(&w, 0.0, o, side, NULL, &hit));
    /* t_max bounds the search */
    double down[3] = { 0.0, -1.0, 0.0 };
    ref_trace_opts opts = { .t_max = 1.0 };
    CHECK(!ref_trace_water(&w, 0.0, o, down, &opts, &hit));
}

/* ---- the spectrum ocean's fast path --------------------------------------- */

/* A march over the spectrum ocean (scenes/ocean.glib's sea at 64^2 a
 * cascade, one Gerstner wave on top in the folding case): ref_trace_water
 * and ref_trace_water_ctx (one frame lookup for every ray) give the same
 * hit bit for bit, and both give the hits the reference gave before the
 * fast path (a snapshot of the frame, packed nodes, the march's predicted
 * Newton starts: commit c31aa40, printed to 17 digits): t within the
 * refinement tolerance (1e-9), the surface within what that moves it (y by
 * |f'| <= 1 times it, the normal by the curvature times it). The march's
 * steps are Lipschitz steps from the bounds of the region each crosses
 * (ref_waves_ctx_world_slope_near; before, the frame's: then the evals
 * were 682 167 107 107 119 113 and, where the frame's bound is infinite
 * since Q + chop >= 1, the least steps' 16840 10009 8903 8740 8037 7224):
 * the counts now are recorded. */
typedef struct recorded_hit {
    double t, y, nx;
    int evals;
} recorded_hit;

static void test_ocean_fast_path(void) {
    static const recorded_hit want[2][6] = {
        {   /* the ocean alone (not folding: Lipschitz steps) */
            { 44.228549147250128, 0.47735710488689681, -0.091696424290270348, 136 },
            { 27.45527469799374, 0.72947999402743202, -0.025927404548995336, 44 },
            { 22.814130219527208, 0.39575984375719014, 0.086726477768808902, 43 },
            { 20.189199857427759, 0.043614356386600106, 0.056808377724659687, 48 },
            { 17.834376276104408, -0.15245273336780563, -0.020621622162503433, 56 },
            { 15.758781359820649, -0.22947434400370514, 0.068405667761570033, 54 },
        }, {   /* and a Gerstner wave (Q + chop >= 1 over the frame: Lipschitz steps
                  where the region a step reaches does not fold, else steps as if the
                  map's least singular value were REF_TRACE_FOLD_FLOOR: the same hits,
                  with 585 1349 1509 4792 4448 4031 evals at the least step before) */
            { 43.813480539858716, 0.51041580812276965, 0.0043241431451611139, 377 },
            { 27.674229438318289, 0.70339772508203391, -0.046971759460510437, 173 },
            { 22.620382178517119, 0.42636870163967183, -0.018773531819039731, 135 },
            { 20.256786792130455, 0.030369652270811232, 0.1045429386253014, 194 },
            { 17.928736898946202, -0.17442311350193407, -0.034304279954892887, 192 },
            { 15.879413485518068, -0.26185060896046219, -0.0068286174713047664, 176 },
        },
    };
    for (int g = 0; g < 2; g++) {
        ref_waves_desc wd;
        memset(&wd, 0, sizeof wd);
        wd.level = 0.5;
        wd.gerstner_count = g;
        wd.gerstner[0] = (ref_wave_desc){ .angle_deg = 30, .wavelength = 7, .amplitude = 0.05 };
        wd.steepness = 0.3;
        wd.ocean = (ref_ocean_desc){ .spectrum = REF_SPECTRUM_JONSWAP, .wind_speed = 9, .wind_angle_deg = -80,
                                     .choppiness = 1, .res = 64, .seed = 7, .fetch = 100000, .cascades = 3,
                                     .tile = { 160, 37, 5.3 } };
        ref_waves w;
        if (init_waves(&w, &wd)) return;
        ref_waves_ctx wc;
        ref_waves_ctx_begin(&wc, &w, 2.0);
        ref_trace_opts op = { .t_tol = 1e-9 };
        for (int k = 0; k < 6; k++) {
            double o[3] = { 0.3 * k, 4, 12 - k }, d[3] = { -0.05 + 0.03 * k, -0.08 - 0.04 * k, -1 };
            double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            for (int i = 0; i < 3; i++) d[i] /= l;
            ref_water_hit a, b;
            CHECK(ref_trace_water(&w, 2.0, o, d, &op, &a) && ref_trace_water_ctx(&wc, o, d, &op, &b));
            CHECK_EQ(memcmp(&a, &b, sizeof a), 0);
            const recorded_hit *r = &want[g][k];
            CHECK_MSG(fabs(a.t - r->t) <= 1e-9 && fabs(a.surf.pos[1] - r->y) <= 1e-9 &&
                      fabs(a.surf.normal[0] - r->nx) <= 1e-7 && a.evals == r->evals,
                      "case %d ray %d: t %.17g y %.17g nx %.17g evals %d", g, k, a.t, a.surf.pos[1],
                      a.surf.normal[0], a.evals);
        }
        ref_waves_ctx_end(&wc);
        ref_waves_release(&w);
    }
}

/* ---- terrain -------------------------------------------------------------- */

/* Sloped plane y = a + b x + c z: t = (a + b o.x + c o.z - o.y) /
 * (d.y - b d.x - c d.z); asserted to 1e-9, with and without a Lipschitz
 * bound, and the normal (-b, 1, -c)/|.| to 1e-8 (central differences are
 * exact on a plane up to rounding, ~eps |h| / 6e-6). */
static void test_terrain_sloped_plane(void) {
    plane pl = { -1.5, 0.3, -0.2 };
    ref_terrain ters[3] = {
        { .height = plane_h, .user = &pl },
        { .height = plane_h, .user = &pl, .lipschitz = hypot(0.3, 0.2) },
        /* |x|, |z| <= 80 along these rays: |y| <= 1.5 + 0.5 * 80 */
        { .height = plane_h, .user = &pl, .lipschitz = 1.0, .bounded = 1, .ymin = -42.0, .ymax = 42.0 },
    };
    double nl = sqrt(1.0 + 0.09 + 0.04), nwant[3] = { -0.3 / nl, 1.0 / nl, 0.2 / nl };
    uint64_t s = 21;
    double worst = 0.0, worst_n = 0.0;
    for (int i = 0; i < 200; i++) {
        double th = 70.0 * lcg01(&s) * DEG, ph = 2 * M_PI * lcg01(&s);
        double o[3] = { 10.0 * lcg01(&s) - 5.0, 3.0 + 2.0 * lcg01(&s), 10.0 * lcg01(&s) - 5.0 };
        double d[3] = { sin(th) * cos(ph), -cos(th), sin(th) * sin(ph) };
        double t_want = (pl.a + pl.b * o[0] + pl.c * o[2] - o[1]) / (d[1] - pl.b * d[0] - pl.c * d[2]);
        for (int k = 0; k < 3; k++) {
            ref_terrain_hit hit;
            if (!ref_trace_terrain(&ters[k], o, d, NULL, &hit)) {
                CHECK_MSG(t_want < 0.0 || t_want > 1e4, "missed the plane (t %g)", t_want);
                continue;
            }
            CHECK(!hit.inside);
            for (int j = 0; j < 3; j++) {
                worst = fmax(worst, fabs(hit.pos[j] - (o[j] + t_want * d[j])));
                worst_n = fmax(worst_n, fabs(hit.normal[j] - nwant[j]));
            }
        }
    }
    CHECK_MSG(worst <= 1e-9, "plane hit error %g", worst);
    CHECK_MSG(worst_n <= 1e-8, "plane normal error %g", worst_n);
    /* starting under the terrain */
    double o[3] = { 0.0, -5.0, 0.0 }, d[3] = { 0.0, -1.0, 0.0 };
    ref_terrain_hit hit;
    CHECK(ref_trace_terrain(&ters[0], o, d, NULL, &hit) && hit.inside && hit.t == 0.0);
    CHECK(ref_trace_terrain(&ters[2], o, d, NULL, &hit) && hit.inside);
    /* going up and away: no hit */
    double o2[3] = { 0.0, 5.0, 0.0 }, up[3] = { 0.0, 1.0, 0.0 };
    CHECK(!ref_trace_terrain(&ters[1], o2, up, NULL, &hit));
    CHECK(!ref_trace_terrain(&ters[2], o2, up, NULL, &hit));
}

/* A sine floor against a brute-force search (step 1e-4, bisection to
 * 1e-14): same first hit to 1e-6 in position, for rays 5..75 deg from the
 * vertical; with a Lipschitz bound and with fixed 0.01 steps. */
static void test_terrain_sine_floor(void) {
    ref_terrain ters[2] = {
        { .height = sine_floor_h, .lipschitz = sine_floor_lip() },
        { .height = sine_floor_h },
    };
    uint64_t s = 31;
    double worst[2] = { 0.0, 0.0 };
    long evals[2] = { 0, 0 };
    int n = 0;
    for (int i = 0; i < 80; i++) {
        double th = (5.0 + 70.0 * lcg01(&s)) * DEG, ph = 2 * M_PI * lcg01(&s);
        double o[3] = { 20.0 * lcg01(&s) - 10.0, 1.0, 20.0 * lcg01(&s) - 10.0 };
        double d[3] = { sin(th) * cos(ph), -cos(th), sin(th) * sin(ph) };
        ray_ctx c = { .o = o, .d = d, .h = sine_floor_h };
        double t_bf;
        if (!brute_first_root(g_terrain, &c, 0.0, 60.0, 1e-4, &t_bf)) { CHECK(0); continue; }
        n++;
        for (int k = 0; k < 2; k++) {
            ref_terrain_hit hit;
            if (!ref_trace_terrain(&ters[k], o, d, NULL, &hit)) { CHECK_MSG(0, "ray %d missed", i); continue; }
            evals[k] += hit.evals;
            for (int j = 0; j < 3; j++) worst[k] = fmax(worst[k], fabs(hit.pos[j] - (o[j] + t_bf * d[j])));
            /* normal: central differences vs the analytic gradient */
            double x = hit.pos[0], z = hit.pos[2];
            double gx = 0.3 * 1.7 * cos(1.7 * x) * cos(1.3 * z) + 0.1 * 4.1 * cos(4.1 * x + 2.3 * z);
            double gz = -0.3 * 1.3 * sin(1.7 * x) * sin(1.3 * z) + 0.1 * 2.3 * cos(4.1 * x + 2.3 * z);
            double l = sqrt(1.0 + gx * gx + gz * gz);
            CHECK_NEAR(hit.normal[0], -gx / l, 1e-8);
            CHECK_NEAR(hit.normal[1], 1.0 / l, 1e-8);
            CHECK_NEAR(hit.normal[2], -gz / l, 1e-8);
        }
    }
    CHECK_MSG(worst[0] <= 1e-6, "Lipschitz march: error %g", worst[0]);
    CHECK_MSG(worst[1] <= 1e-6, "fixed steps: error %g", worst[1]);
    fprintf(stderr, "  %d rays: max error %.3g (Lipschitz, %.0f evals/ray), %.3g (fixed 0.01, %.0f evals/ray)\n",
            n, worst[0], (double)evals[0] / n, worst[1], (double)evals[1] / n);
}

static void test_beer_lambert(void) {
    double sigma[3] = { 0.45, 0.06, 0.02 }, a[3], b[3], c[3];
    ref_beer_lambert(sigma, 2.0, a);
    CHECK_NEAR(a[0], exp(-0.9), 1e-15);
    CHECK_NEAR(a[1], exp(-0.12), 1e-15);
    CHECK_NEAR(a[2], exp(-0.04), 1e-15);
    ref_beer_lambert(sigma, 0.7, b);
    ref_beer_lambert(sigma, 2.7, c);
    for (int k = 0; k < 3; k++) CHECK_NEAR(a[k] * b[k], c[k], 1e-15);   /* segments multiply */
    double zero[3] = { 0, 0, 0 };
    ref_beer_lambert(zero, 100.0, a);
    CHECK(a[0] == 1.0 && a[1] == 1.0 && a[2] == 1.0);
}

/* ---- photons ---------------------------------------------------------------- */

static void photon_stats(const ref_caustics *c, int ch, double *mean, double *maxdev_rel, double want) {
    double s = 0.0, md = 0.0;
    int n = c->nx * c->nz;
    for (int i = 0; i < n; i++) {
        double e = c->irradiance[i * 3 + ch];
        s += e * c->area[i];
        md = fmax(md, fabs(e / want - 1.0));
    }
    double total_area = 0.0;
    for (int i = 0; i < n; i++) total_area += c->area[i];
    *mean = s / total_area;
    *maxdev_rel = md;
}

/* Flat water, flat floor, sun 35 deg from the zenith: every photon carries
 * E_sun cos(theta) sx sz, loses R(theta) at the surface, and the beam is
 * only translated, so the floor irradiance is E = E_sun cos(theta) (1 -
 * R(theta)) everywhere (R computed here with the sine/tangent laws).
 *
 * What we assert and why: k x k = 1024 jittered strata per cell area. A
 * stratum wholly inside a cell puts exactly one photon in it; only the
 * ~4k strata cut by the cell edges are random, each a Bernoulli(p) with
 * variance p(1-p) <= 1/4, so the count's std is <= sqrt(k + 1) = 5.7
 * photons of 1024 (0.56%), against 1/sqrt(1024) = 3.1% for Poisson counts.
 * Each cell: within 5 such sigmas (2.8%). The mean over the 32 x 32 grid:
 * only the grid's outer edge is random (~4 * 32k strata, std <= 91 photons
 * of 1M): within 5e-4 relative. Energy: emitted = reflected + transmitted
 * to 1e-9 relative (the rounding of sums of ~1e6 terms, N eps ~ 1e-10).
 *
 * With the default margin the strata line up with the cells exactly (the
 * emission region is the floor grid translated, widened by whole cells), so
 * every cell gets exactly k^2 photons and the irradiance is exact to
 * rounding; a margin of 0.3711 breaks the alignment so that the cut strata
 * (and the bound above) are exercised. */
static void test_photons_flat_uniform(void) {
    ref_waves_desc wd;
    memset(&wd, 0, sizeof wd);
    ref_waves w;
    if (init_waves(&w, &wd)) return;
    double th = 35.0 * DEG;
    ref_caustics_desc cd = {
        .waves = &w, .sun_dir = { sin(th), cos(th), 0.0 }, .sun_irradiance = 800.0,
        .floor_y = -2.0, .x0 = 0.0, .z0 = 0.0, .x1 = 8.0, .z1 = 8.0, .nx = 32, .nz = 32,
        .photons_per_cell = 1024,
    };
    double tt = asin(sin(th) / N_W);
    double R = 0.5 * (pow(sin(th - tt) / sin(th + tt), 2) + pow(tan(th - tt) / tan(th + tt), 2));
    double E = 800.0 * cos(th) * (1.0 - R);
    int k = 32;
    double per_cell = 5.0 * sqrt(k + 1.0) / (k * k);
    ref_caustics c;
    char err[256];
    double mean, maxdev;
    /* aligned strata: exact */
    if (ref_caustics_trace(&cd, &c, err, sizeof err) != 0) { CHECK_MSG(0, "%s", err); return; }
    photon_stats(&c, 0, &mean, &maxdev, E);
    CHECK_MSG(fabs(mean / E - 1.0) <= 1e-12, "aligned: mean %g, want %g", mean, E);
    CHECK_MSG(maxdev <= 1e-12, "aligned: worst cell off by %g", maxdev);
    ref_caustics_free(&c);
    /* misaligned strata: the Monte-Carlo bound */
    cd.margin = 0.3711;
    if (ref_caustics_trace(&cd, &c, err, sizeof err) != 0) { CHECK_MSG(0, "%s", err); return; }
    photon_stats(&c, 0, &mean, &maxdev, E);
    CHECK_MSG(fabs(mean / E - 1.0) <= 5e-4, "mean %g, want %g", mean, E);
    CHECK_MSG(maxdev <= per_cell, "worst cell off by %.4f (bound %.4f)", maxdev, per_cell);
    CHECK_NEAR(c.stats.flux_reflected + c.stats.flux_transmitted, c.stats.flux_emitted,
               1e-9 * c.stats.flux_emitted);
    CHECK_EQ(c.stats.hit_water, c.stats.photons);
    CHECK_EQ(c.irradiance[5 * 3 + 0], c.irradiance[5 * 3 + 2]);      /* clear water: grey */
    fprintf(stderr, "  E = %.6g: mean %.6g (rel %.2g), worst cell %.4f (bound %.4f), %ld photons\n",
            E, mean, mean / E - 1.0, maxdev, per_cell, c.stats.photons);
    ref_caustics_free(&c);
}

/* Beer-Lambert on the photons: depth D under flat water, the path is
 * D / cos(tt), so each channel is E exp(-sigma_c D / cos tt) (mean to 5e-4
 * as above). */
static void test_photons_beer_lambert(void) {
    ref_waves_desc wd;
    memset(&wd, 0, sizeof wd);
    ref_waves w;
    if (init_waves(&w, &wd)) return;
    double th = 20.0 * DEG;
    ref_caustics_desc cd = {
        .waves = &w, .sun_dir = { 0.0, cos(th), sin(th) }, .floor_y = -3.0,
        .sigma = { 0.45, 0.06, 0.02 },
        .x0 = -2.0, .z0 = -2.0, .x1 = 2.0, .z1 = 2.0, .nx = 16, .nz = 16, .photons_per_cell = 256,
    };
    ref_caustics c;
    char err[256];
    if (ref_caustics_trace(&cd, &c, err, sizeof err) != 0) { CHECK_MSG(0, "%s", err); return; }
    double tt = asin(sin(th) / N_W);
    double E = cos(th) * (1.0 - ref_fresnel(cos(th), 1.0, N_W));
    for (int ch = 0; ch < 3; ch++) {
        double want = E * exp(-cd.sigma[ch] * 3.0 / cos(tt)), mean, maxdev;
        photon_stats(&c, ch, &mean, &maxdev, want);
        CHECK_MSG(fabs(mean / want - 1.0) <= 5e-4, "channel %d: mean %g, want %g", ch, mean, want);
    }
    ref_caustics_free(&c);
}

/* A sloped floor under flat water: the refracted beam (direction t) has
 * irradiance E_perp = E_sun cos(theta) (1 - R) / |t.y| across it, so a floor
 * with normal n_f receives E_perp |t . n_f| per unit of its own area — this
 * checks the heightfield floor and the cell-area accounting. Tolerance as
 * for the flat case, with k^2 = the expected photons per cell. */
static void test_photons_sloped_floor(void) {
    ref_waves_desc wd;
    memset(&wd, 0, sizeof wd);
    ref_waves w;
    if (init_waves(&w, &wd)) return;
    plane pl = { -2.0, 0.2, 0.1 };
    ref_terrain ter = { .height = plane_h, .user = &pl, .lipschitz = hypot(0.2, 0.1) };
    double th = 40.0 * DEG;
    ref_caustics_desc cd = {
        .waves = &w, .sun_dir = { -sin(th) * 0.6, cos(th), sin(th) * 0.8 }, .floor = &ter,
        .x0 = 0.0, .z0 = 0.0, .x1 = 4.0, .z1 = 4.0, .nx = 16, .nz = 16, .photons_per_cell = 1024,
    };
    ref_caustics c;
    char err[256];
    if (ref_caustics_trace(&cd, &c, err, sizeof err) != 0) { CHECK_MSG(0, "%s", err); return; }
    double down[3] = { sin(th) * 0.6, -cos(th), -sin(th) * 0.8 }, up[3] = { 0, 1, 0 }, t[3];
    ref_refract(down, up, 1.0, N_W, t);
    double R = ref_fresnel(cos(th), 1.0, N_W);
    double Eperp = cos(th) * (1.0 - R) / fabs(t[1]);
    double nl = sqrt(1.0 + 0.04 + 0.01), nf[3] = { -0.2 / nl, 1.0 / nl, -0.1 / nl };
    double want = Eperp * fabs(t[0] * nf[0] + t[1] * nf[1] + t[2] * nf[2]);
    double mean, maxdev;
    photon_stats(&c, 0, &mean, &maxdev, want);
    double per_cell_photons = want * c.area[0] / c.plan.photon_flux;
    double k = sqrt(per_cell_photons);
    double bound = 5.0 * sqrt(k + 1.0) / per_cell_photons;
    CHECK_NEAR(c.area[0], 0.25 * 0.25 / nf[1], 1e-12);
    CHECK_MSG(fabs(mean / want - 1.0) <= 5e-4, "mean %g, want %g", mean, want);
    CHECK_MSG(maxdev <= bound, "worst cell %.4f (bound %.4f)", maxdev, bound);
    fprintf(stderr, "  sloped floor: want %.6g, mean %.6g, worst cell %.4f (bound %.4f)\n", want, mean, maxdev, bound);
    ref_caustics_free(&c);
}

/* Waves focus light into caustics (the grid is far from uniform) but do not
 * make or lose energy: the flux deposited over a grid much larger than the
 * depth equals E_sun cos(theta) (1 - R_mean) times its area, R_mean the
 * measured reflected share, up to the flux crossing the grid's edge in
 * either direction (asserted 1%). The result does not depend on how the
 * strata rows are split (for threads): to 1e-12 per cell. */
static void test_photons_waves(void) {
    ref_waves_desc wd = ref_waves_default();
    ref_waves w;
    if (init_waves(&w, &wd)) return;
    double th = 25.0 * DEG;
    ref_caustics_desc cd = {
        .waves = &w, .time = 3.0, .sun_dir = { sin(th), cos(th), 0.0 }, .floor_y = -1.5,
        .x0 = -6.0, .z0 = -6.0, .x1 = 6.0, .z1 = 6.0, .nx = 40, .nz = 40, .photons_per_cell = 16,
    };
    ref_caustics c;
    char err[256];
    if (ref_caustics_trace(&cd, &c, err, sizeof err) != 0) { CHECK_MSG(0, "%s", err); return; }
    double Rm = c.stats.flux_reflected / c.stats.flux_emitted;
    double want = cos(th) * (1.0 - Rm);
    double mean, maxdev;
    photon_stats(&c, 0, &mean, &maxdev, want);
    double lo = INFINITY, hi = 0.0;
    for (int i = 0; i < c.nx * c.nz; i++) {
        lo = fmin(lo, c.irradiance[i * 3]);
        hi = fmax(hi, c.irradiance[i * 3]);
    }
    CHECK_MSG(fabs(mean / want - 1.0) <= 0.01, "mean %g, want %g", mean, want);
    CHECK_MSG(hi > 1.3 * want && lo < 0.8 * want, "no caustics: %g..%g around %g", lo, hi, want);
    CHECK_NEAR(c.stats.flux_reflected + c.stats.flux_transmitted, c.stats.flux_emitted,
               1e-9 * c.stats.flux_emitted);
    fprintf(stderr, "  waves: R_mean %.5f, mean %.5g vs %.5g (rel %.2g), range %.3g..%.3g, %ld photons\n",
            Rm, mean, want, mean / want - 1.0, lo, hi, c.stats.photons);

    /* split rows: same flux */
    size_t n = (size_t)c.nx * c.nz * 3;
    double *a = calloc(n, sizeof *a), *b = calloc(n, sizeof *b);
    if (!a || !b) { free(a); free(b); ref_caustics_free(&c); CHECK(0); return; }
    int mz = c.plan.mz;
    ref_caustics_trace_rows(&c.plan, mz / 3, mz, b, NULL);       /* later rows first */
    ref_caustics_trace_rows(&c.plan, 0, mz / 3, b, NULL);
    double worst = 0.0;
    for (int i = 0; i < c.nx * c.nz; i++) {
        double one = c.irradiance[i * 3] * c.area[i];
        worst = fmax(worst, fabs(one - b[i * 3]) / fmax(1e-300, one));
    }
    CHECK_MSG(worst <= 1e-12, "split rows differ by %g", worst);
    free(a);
    free(b);
    ref_caustics_free(&c);
}

static void test_photons_errors_and_rng(void) {
    ref_waves w;
    if (init_waves(&w, NULL)) return;
    ref_caustics c;
    char err[256];
    ref_caustics_desc cd = { .waves = &w, .x0 = 1.0, .x1 = 0.0, .z1 = 1.0 };
    CHECK_EQ(ref_caustics_trace(&cd, &c, err, sizeof err), -1);
    CHECK_STR_CONTAINS(err, "region");
    ref_caustics_desc cd2 = { .waves = &w, .x1 = 1.0, .z1 = 1.0, .sun_dir = { 1.0, -0.2, 0.0 } };
    CHECK_EQ(ref_caustics_trace(&cd2, &c, err, sizeof err), -1);
    CHECK_STR_CONTAINS(err, "horizon");
    ref_caustics_desc cd3 = { .x1 = 1.0, .z1 = 1.0 };
    CHECK_EQ(ref_caustics_trace(&cd3, &c, err, sizeof err), -1);
    /* splitmix64: the published first outputs for seed 1234567 */
    uint64_t s = 1234567;
    CHECK_EQ(ref_splitmix64(&s), 6457827717110365317ULL);
    CHECK_EQ(ref_splitmix64(&s), 3203168211198807973ULL);
}

int main(void) {
    RUN(test_flat_refraction_closed_form);
    RUN(test_water_vs_brute_force);
    RUN(test_ocean_fast_path);
    RUN(test_terrain_sloped_plane);
    RUN(test_terrain_sine_floor);
    RUN(test_beer_lambert);
    RUN(test_photons_flat_uniform);
    RUN(test_photons_beer_lambert);
    RUN(test_photons_sloped_floor);
    RUN(test_photons_waves);
    RUN(test_photons_errors_and_rng);
    return check_summary();
}
