/* test_wavefx: the explosion ring and the 3D Perlin wave sets of
 * reference/ref_wavefx.c against independent truth: the formulas written
 * out here (with their own copy of the lowbias32 hash), central finite
 * differences, the front's speed measured by scanning, the decay measured
 * at one phase, correlation lengths measured by sampling, and the bounds
 * over many random samples. */
#include "check.h"
#include "ref_wavefx.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#define TWO_PI (2.0 * M_PI)

static double lcg01(uint64_t *s) {
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) * 0x1.0p-53;
}

static uint32_t my_hash(uint32_t x) {       /* lowbias32, written out again */
    x ^= x >> 16; x *= 0x7feb352dU; x ^= x >> 15; x *= 0x846ca68bU; x ^= x >> 16;
    return x;
}

static ref_explosion_desc ring(double i0, double omega, double k, double decay) {
    ref_explosion_desc e = { { 1.5, -2.0 }, 0.75, i0, omega, k, decay };
    char err[200];
    int rc = ref_explosion_resolve(&e, err, sizeof err);
    CHECK_MSG(rc == 0, "%s", err);
    return e;
}

/* ---------------------------------------------------------------- ring */

static void test_ring_defaults_and_errors(void) {
    ref_explosion_desc e = { { 0, 0 }, 0, 1, 0, 0, 0 };
    char err[200];
    CHECK_EQ(ref_explosion_resolve(&e, err, sizeof err), 0);
    CHECK_NEAR(e.k, TWO_PI, 1e-15);
    CHECK_NEAR(e.omega, sqrt(9.81 * TWO_PI), 1e-12);
    CHECK_EQ(e.decay, 0);
    struct { ref_explosion_desc d; const char *word; } bad[] = {
        { { { NAN, 0 }, 0, 1, 0, 0, 0 }, "center" },
        { { { 0, INFINITY }, 0, 1, 0, 0, 0 }, "center" },
        { { { 0, 0 }, NAN, 1, 0, 0, 0 }, "start" },
        { { { 0, 0 }, 0, INFINITY, 0, 0, 0 }, "I0" },
        { { { 0, 0 }, 0, 1, 0, -1, 0 }, "k" },
        { { { 0, 0 }, 0, 1, -2, 0, 0 }, "omega" },
        { { { 0, 0 }, 0, 1, 0, 0, -0.1 }, "decay" },
        { { { 0, 0 }, 0, 1, 0, 0, NAN }, "decay" },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        err[0] = 0;
        CHECK_EQ(ref_explosion_resolve(&bad[i].d, err, sizeof err), -1);
        CHECK_STR_CONTAINS(err, bad[i].word);
    }
    CHECK_EQ(ref_explosion_resolve(&bad[4].d, NULL, 0), -1);   /* no buffer: still an error */
}

static void test_ring_flat_before_and_at_start(void) {
    ref_explosion_desc e = ring(0.4, 0, 0, 0.2);
    uint64_t s = 1;
    for (int n = 0; n < 2000; n++) {
        double u = -20 + 40 * lcg01(&s), v = -20 + 40 * lcg01(&s);
        if (n % 10 == 0) { u = e.center[0]; v = e.center[1]; }
        double taus[] = { -5.0, -1e-9, 0.0, 1e-12, 1e-6, 0.99 / e.omega };
        for (int i = 0; i < 6; i++) {
            double g[2] = { 9, 9 };
            double h = ref_explosion_height(&e, u, v, e.start + taus[i], g);
            CHECK(h == 0.0 && g[0] == 0.0 && g[1] == 0.0);
        }
    }
    /* and it does rise afterwards */
    CHECK_GT(fabs(ref_explosion_height(&e, e.center[0], e.center[1], e.start + 1.0, NULL)), 1e-3);
}

static void test_ring_formula(void) {
    /* the header's formula written out with r and s */
    ref_explosion_desc e = ring(0.3, 2.5, 3.0, 0.1);
    uint64_t s = 7;
    for (int n = 0; n < 5000; n++) {
        double u = -15 + 30 * lcg01(&s), v = -15 + 30 * lcg01(&s), t = e.start + 12 * lcg01(&s);
        double tau = t - e.start, r = hypot(u - e.center[0], v - e.center[1]);
        double ss = sqrt(r * r + 1 / (e.k * e.k)), R = e.omega / e.k * tau, W = TWO_PI / e.k;
        double x = (ss - R + W) / W;
        x = x < 0 ? 0 : x > 1 ? 1 : x;
        double E = 1 - x * x * x * (10 - 15 * x + 6 * x * x);
        double want = e.i0 * exp(-e.decay * tau) * E * sin(e.k * ss - e.omega * tau) / sqrt(e.k * ss);
        CHECK_NEAR(ref_explosion_height(&e, u, v, t, NULL), want, 1e-12);
    }
}

static void test_ring_centre_smooth(void) {
    ref_explosion_desc e = ring(0.5, 0, 0, 0.05);
    for (double tau = 0.5; tau < 8; tau += 0.37) {
        double t = e.start + tau, g[2];
        double h0 = ref_explosion_height(&e, e.center[0], e.center[1], t, g);
        CHECK(isfinite(h0));
        CHECK(g[0] == 0.0 && g[1] == 0.0);
        /* no cone: h(r) - h(0) is O(r^2) in every direction */
        for (int d = 0; d < 8; d++) {
            double a = d * M_PI / 4, eps = 1e-4;
            double h1 = ref_explosion_height(&e, e.center[0] + eps * cos(a), e.center[1] + eps * sin(a), t, NULL);
            double h2 = ref_explosion_height(&e, e.center[0] + 2 * eps * cos(a), e.center[1] + 2 * eps * sin(a), t, NULL);
            CHECK_LT(fabs(h1 - h0), 1e-6);
            /* quadratic: the step at 2 eps is 4 times that at eps */
            if (fabs(h1 - h0) > 1e-12) CHECK_NEAR((h2 - h0) / (h1 - h0), 4.0, 1e-3);
        }
    }
}

static double fd_check_ring(const ref_explosion_desc *e, double u, double v, double t) {
    double g[2], hs = 1e-5;
    ref_explosion_height(e, u, v, t, g);
    double fx = (ref_explosion_height(e, u + hs, v, t, NULL) - ref_explosion_height(e, u - hs, v, t, NULL)) / (2 * hs);
    double fz = (ref_explosion_height(e, u, v + hs, t, NULL) - ref_explosion_height(e, u, v - hs, t, NULL)) / (2 * hs);
    return fmax(fabs(fx - g[0]), fabs(fz - g[1]));
}

static void test_ring_gradient_fd(void) {
    ref_explosion_desc e = ring(0.3, 0, 0, 0.1);
    uint64_t s = 11;
    double worst = 0;
    for (int n = 0; n < 20000; n++) {
        double tau = 0.2 + 10 * lcg01(&s), t = e.start + tau;
        double R = e.omega / e.k * tau, W = TWO_PI / e.k;
        double r, a = TWO_PI * lcg01(&s);
        switch (n % 4) {
        case 0: r = 15 * lcg01(&s); break;                      /* anywhere */
        case 1: r = 1e-3 * lcg01(&s); break;                    /* at the centre */
        case 2: r = fmax(0, R - W * 1.2 + 1.4 * W * lcg01(&s)); break;   /* across the front */
        default: r = 0.3 * lcg01(&s); break;
        }
        double d = fd_check_ring(&e, e.center[0] + r * cos(a), e.center[1] + r * sin(a), t);
        if (d > worst) worst = d;
    }
    fprintf(stderr, "  ring: worst |analytic - FD| gradient %.3g\n", worst);
    CHECK_LT(worst, 2e-7);
}

/* The outermost r where h != 0 (scanning inwards in steps of dr) and the
 * outermost crest (local maximum of h) behind it. */
static void front_and_crest(const ref_explosion_desc *e, double t, double rmax, double dr, double *front, double *crest) {
    double r = rmax;
    while (r > 0 && ref_explosion_height(e, e->center[0] + r, e->center[1], t, NULL) == 0.0) r -= dr;
    *front = r;
    double prev = ref_explosion_height(e, e->center[0] + r, e->center[1], t, NULL);
    for (;;) {
        r -= dr;
        double h = ref_explosion_height(e, e->center[0] + r, e->center[1], t, NULL);
        double next = ref_explosion_height(e, e->center[0] + r - dr, e->center[1], t, NULL);
        if (h > prev && h >= next && h > 0) { *crest = r; return; }
        prev = h;
        if (r <= 0) { *crest = -1; return; }
    }
}

static void test_ring_speed(void) {
    double ks[] = { 0, 2.0, 5.0 }, omegas[] = { 0, 3.0, 4.0 };
    for (int i = 0; i < 3; i++) {
        ref_explosion_desc e = ring(1.0, omegas[i], ks[i], 0.0);
        double c = e.omega / e.k, t1 = e.start + 8.0, t2 = e.start + 14.0;
        double f1, f2, c1, c2;
        front_and_crest(&e, t1, c * 8 + 5, 1e-4, &f1, &c1);
        front_and_crest(&e, t2, c * 14 + 5, 1e-4, &f2, &c2);
        double vf = (f2 - f1) / (t2 - t1), vc = (c2 - c1) / (t2 - t1);
        fprintf(stderr, "  omega/k %.5g: front %.5g m/s, crest %.5g m/s\n", c, vf, vc);
        CHECK_LT(fabs(vf - c), 2e-3 * c);
        CHECK_LT(fabs(vc - c), 2e-3 * c);
        /* the front is where s reaches R = (omega / k) tau */
        CHECK_NEAR(sqrt(f1 * f1 + 1 / (e.k * e.k)), c * 8.0, 2e-4);
    }
}

static void test_ring_decay(void) {
    ref_explosion_desc e = ring(0.6, 0, 0, 0.3);
    double r = 2.0, q = sqrt(e.k * e.k * r * r + 1);
    /* at phase -pi/2 - 40 pi, then 5 periods later: the same phase */
    double tau1 = (q + M_PI / 2 + 40 * M_PI) / e.omega, tau2 = tau1 + 5 * TWO_PI / e.omega;
    CHECK_GT(e.omega / e.k * tau1 - r, 2 * TWO_PI / e.k);     /* far behind the front */
    double h1 = ref_explosion_height(&e, e.center[0] + r, e.center[1], e.start + tau1, NULL);
    double h2 = ref_explosion_height(&e, e.center[0], e.center[1] + r, e.start + tau2, NULL);
    CHECK_NEAR(h2 / h1, exp(-e.decay * (tau2 - tau1)), 1e-9);
    CHECK_NEAR(h1, -e.i0 * exp(-e.decay * tau1) / sqrt(q), 1e-9);
    /* spreading: amplitude ~ 1/sqrt(k s) */
    double r2 = 4.0, q2 = sqrt(e.k * e.k * r2 * r2 + 1);
    double tau3 = (q2 + M_PI / 2 + 40 * M_PI) / e.omega;
    double h3 = ref_explosion_height(&e, e.center[0] - r2, e.center[1], e.start + tau3, NULL);
    CHECK_NEAR(h3 / exp(-e.decay * tau3), h1 / exp(-e.decay * tau1) * sqrt(q / q2), 1e-9);
}

static void test_ring_bounds(void) {
    uint64_t s = 3;
    for (int set = 0; set < 20; set++) {
        ref_explosion_desc e = ring((lcg01(&s) - 0.5) * 2, set % 3 ? 0 : 0.5 + 8 * lcg01(&s),
                                    set % 2 ? 0 : 0.5 + 10 * lcg01(&s), set % 4 ? 0 : lcg01(&s));
        double hb, sb, hmax = 0, smax = 0;
        ref_explosion_bounds(&e, &hb, &sb);
        for (int n = 0; n < 20000; n++) {
            double u = e.center[0] + (lcg01(&s) - 0.5) * 12, v = e.center[1] + (lcg01(&s) - 0.5) * 12;
            double t = e.start - 1 + 20 * lcg01(&s), g[2];
            double h = ref_explosion_height(&e, u, v, t, g);
            hmax = fmax(hmax, fabs(h));
            smax = fmax(smax, hypot(g[0], g[1]));
        }
        CHECK_MSG(hmax <= hb && smax <= sb, "set %d: |h| %g <= %g, slope %g <= %g", set, hmax, hb, smax, sb);
        if (e.decay == 0)     /* with decay the largest values are only early on */
            CHECK_MSG(hmax > 0.3 * hb && smax > 0.3 * sb, "set %d: bounds loose: %g / %g, %g / %g", set, hmax, hb, smax, sb);
    }
}

/* -------------------------------------------------------------- perlin3 */

static const double G12[12][3] = {
    { 1, 1, 0 }, { -1, 1, 0 }, { 1, -1, 0 }, { -1, -1, 0 }, { 1, 0, 1 }, { -1, 0, 1 },
    { 1, 0, -1 }, { -1, 0, -1 }, { 0, 1, 1 }, { 0, -1, 1 }, { 0, 1, -1 }, { 0, -1, -1 },
};

static void test_perlin3_lattice(void) {
    uint64_t s = 5;
    for (int n = 0; n < 3000; n++) {
        int ix = (int)(lcg01(&s) * 2000) - 1000, iy = (int)(lcg01(&s) * 2000) - 1000, iz = (int)(lcg01(&s) * 2000) - 1000;
        uint32_t seed = (uint32_t)(lcg01(&s) * 4294967295.0);
        double g[3];
        double h = ref_perlin3(ix, iy, iz, seed, g);
        CHECK_EQ(h, 0.0);
        /* the gradient there is the corner's edge vector, chosen by the spec's hash */
        uint32_t k = my_hash((uint32_t)ix + my_hash((uint32_t)iy + my_hash((uint32_t)iz + seed))) % 12u;
        CHECK(g[0] == G12[k][0] && g[1] == G12[k][1] && g[2] == G12[k][2]);
    }
}

static void test_perlin3_range_and_gradient(void) {
    uint64_t s = 9;
    double lo = 0, hi = 0, worst = 0, gmax = 0;
    for (int n = 0; n < 200000; n++) {
        double x = (lcg01(&s) - 0.5) * 200, y = (lcg01(&s) - 0.5) * 200, z = (lcg01(&s) - 0.5) * 200;
        uint32_t seed = (uint32_t)n * 2654435761U;
        double g[3];
        double h = ref_perlin3(x, y, z, seed, g);
        lo = fmin(lo, h); hi = fmax(hi, h);
        gmax = fmax(gmax, sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]));
        if (n % 10 == 0) {
            double e = 1e-5, p[3] = { x, y, z }, fd[3];
            for (int j = 0; j < 3; j++) {
                double a[3] = { x, y, z }, b[3] = { x, y, z };
                a[j] += e; b[j] -= e;
                fd[j] = (ref_perlin3(a[0], a[1], a[2], seed, NULL) - ref_perlin3(b[0], b[1], b[2], seed, NULL)) / (2 * e);
                worst = fmax(worst, fabs(fd[j] - g[j]));
            }
            (void)p;
        }
    }
    fprintf(stderr, "  perlin3: range [%.4f, %.4f], max |grad| %.3f, worst FD %.3g\n", lo, hi, gmax, worst);
    CHECK(lo >= -1.0 && hi <= 1.0);
    CHECK(lo < -0.7 && hi > 0.7);
    CHECK_LE(gmax, 15 * sqrt(3.0) / 4);
    CHECK_LT(worst, 1e-7);
}

static void test_perlin3_seeds(void) {
    uint64_t s = 13;
    int differ = 0, total = 0;
    for (int n = 0; n < 2000; n++) {
        double x = (lcg01(&s) - 0.5) * 50, y = (lcg01(&s) - 0.5) * 50, z = (lcg01(&s) - 0.5) * 50;
        double a = ref_perlin3(x, y, z, 42, NULL), b = ref_perlin3(x, y, z, 42, NULL);
        CHECK_EQ(a, b);
        double c = ref_perlin3(x, y, z, 43, NULL);
        total++;
        if (fabs(a - c) > 1e-3) differ++;
    }
    CHECK_GT(differ, total * 9 / 10);
    /* a known value written out from the definition at (0.5, 0.25, 0.75), seed 7 */
    double x = 0.5, y = 0.25, z = 0.75, want = 0;
    for (int c = 0; c < 8; c++) {
        int bx = c & 1, by = (c >> 1) & 1, bz = (c >> 2) & 1;
        uint32_t k = my_hash((uint32_t)bx + my_hash((uint32_t)by + my_hash((uint32_t)bz + 7u))) % 12u;
        double fx = x * x * x * (x * (x * 6 - 15) + 10), fy = y * y * y * (y * (y * 6 - 15) + 10), fz = z * z * z * (z * (z * 6 - 15) + 10);
        double w = (bx ? fx : 1 - fx) * (by ? fy : 1 - fy) * (bz ? fz : 1 - fz);
        want += w * (G12[k][0] * (x - bx) + G12[k][1] * (y - by) + G12[k][2] * (z - bz));
    }
    CHECK_NEAR(ref_perlin3(x, y, z, 7, NULL), want, 1e-15);
    /* negative lattice cells: (uint32_t)(int32_t)floor */
    double g[3];
    ref_perlin3(-3.0, -1.0, -7.0, 99, g);
    uint32_t k = my_hash((uint32_t)-3 + my_hash((uint32_t)-1 + my_hash((uint32_t)-7 + 99u))) % 12u;
    CHECK(g[0] == G12[k][0] && g[1] == G12[k][1] && g[2] == G12[k][2]);
}

/* ---------------------------------------------------------- Perlin sets */

static ref_perlin_desc pset(double amp, int oct, double stretch, double angle, uint32_t seed) {
    ref_perlin_desc p = { amp, 3.0, oct, 0.55, stretch, angle, 0.7, seed };
    char err[200];
    int rc = ref_perlin_resolve(&p, err, sizeof err);
    CHECK_MSG(rc == 0, "%s", err);
    return p;
}

static void test_perlin_defaults_and_errors(void) {
    ref_perlin_desc p = { .amplitude = 0.2 };
    char err[200];
    CHECK_EQ(ref_perlin_resolve(&p, err, sizeof err), 0);
    CHECK(p.cell == 4 && p.octaves == 4 && p.gain == 0.5 && p.stretch == 1 && p.rate == 0.5);
    struct { ref_perlin_desc d; const char *word; } bad[] = {
        { { .amplitude = NAN }, "amplitude" },
        { { .amplitude = 1, .cell = -1 }, "cell" },
        { { .amplitude = 1, .stretch = -2 }, "stretch" },
        { { .amplitude = 1, .octaves = 9 }, "octaves" },
        { { .amplitude = 1, .octaves = -1 }, "octaves" },
        { { .amplitude = 1, .angle_deg = INFINITY }, "angle" },
        { { .amplitude = 1, .gain = NAN }, "gain" },
        { { .amplitude = 1, .rate = -INFINITY }, "rate" },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        err[0] = 0;
        CHECK_EQ(ref_perlin_resolve(&bad[i].d, err, sizeof err), -1);
        CHECK_STR_CONTAINS(err, bad[i].word);
    }
    ref_perlin_desc none = { 0 };
    CHECK_EQ(ref_perlin_resolve(&none, err, sizeof err), 0);
    double g[2] = { 1, 1 };
    CHECK(ref_perlin_height(&none, 1, 2, 3, g) == 0.0 && g[0] == 0 && g[1] == 0);
}

static void test_perlin_set_formula_and_gradient(void) {
    ref_perlin_desc p = pset(0.25, 5, 2.5, 35.0, 1234);
    uint64_t s = 17;
    double th = 35.0 * M_PI / 180, worst = 0;
    for (int n = 0; n < 5000; n++) {
        double u = (lcg01(&s) - 0.5) * 60, v = (lcg01(&s) - 0.5) * 60, t = 30 * lcg01(&s);
        double a = u * cos(th) + v * sin(th), c = -u * sin(th) + v * cos(th), want = 0;
        for (int o = 0; o < 5; o++) {
            double f = pow(2, o) / 3.0;
            want += 0.25 * pow(0.55, o) *
                    ref_perlin3(a * f, c * f / 2.5, t * 0.7 * sqrt(pow(2, o)), my_hash(1234u + (uint32_t)o * 0x9E3779B9U), NULL);
        }
        double g[2];
        CHECK_NEAR(ref_perlin_height(&p, u, v, t, g), want, 1e-12);
        double e = 1e-5;
        double fx = (ref_perlin_height(&p, u + e, v, t, NULL) - ref_perlin_height(&p, u - e, v, t, NULL)) / (2 * e);
        double fz = (ref_perlin_height(&p, u, v + e, t, NULL) - ref_perlin_height(&p, u, v - e, t, NULL)) / (2 * e);
        worst = fmax(worst, fmax(fabs(fx - g[0]), fabs(fz - g[1])));
    }
    fprintf(stderr, "  perlin set: worst |analytic - FD| gradient %.3g\n", worst);
    CHECK_LT(worst, 1e-7);
}

/* The lag at which the normalised autocorrelation along dir first drops
 * below 1/2, over many base points (one octave). */
static double corr_half(const ref_perlin_desc *p, double dx, double dz) {
    double lag = 0.0, step = 0.02;
    for (;;) {
        lag += step;
        uint64_t s = 21;
        double num = 0, den = 0;
        for (int n = 0; n < 6000; n++) {
            double u = (lcg01(&s) - 0.5) * 400, v = (lcg01(&s) - 0.5) * 400, t = 50 * lcg01(&s);
            double a = ref_perlin_height(p, u, v, t, NULL), b = ref_perlin_height(p, u + lag * dx, v + lag * dz, t, NULL);
            num += a * b;
            den += 0.5 * (a * a + b * b);
        }
        if (num / den < 0.5 || lag > 100) return lag;
    }
}

static void test_perlin_stretch_direction(void) {
    double angle = 30.0, th = angle * M_PI / 180, stretch = 3.0;
    ref_perlin_desc p = pset(1.0, 1, stretch, angle, 77);
    double along = corr_half(&p, cos(th), sin(th));
    double across = corr_half(&p, -sin(th), cos(th));
    fprintf(stderr, "  stretch %.1f: half-correlation length along the wind %.3f m, across %.3f m (ratio %.3f)\n",
            stretch, along, across, across / along);
    CHECK_LT(fabs(across / along - stretch), 0.1 * stretch);
    ref_perlin_desc iso = pset(1.0, 1, 1.0, angle, 77);
    double a1 = corr_half(&iso, cos(th), sin(th)), c1 = corr_half(&iso, -sin(th), cos(th));
    CHECK_LT(fabs(c1 / a1 - 1.0), 0.1);
    CHECK_LT(fabs(a1 - along), 0.1 * a1);      /* along the wind: unstretched */
}

static void test_perlin_bounds(void) {
    uint64_t s = 23;
    for (int set = 0; set < 12; set++) {
        ref_perlin_desc p = pset(0.1 + lcg01(&s), 1 + set % 8, 0.4 + 3 * lcg01(&s), 360 * lcg01(&s), (uint32_t)set);
        double hb, sb, hmax = 0, smax = 0;
        ref_perlin_bounds(&p, &hb, &sb);
        for (int n = 0; n < 20000; n++) {
            double g[2];
            double h = ref_perlin_height(&p, (lcg01(&s) - 0.5) * 100, (lcg01(&s) - 0.5) * 100, 100 * lcg01(&s), g);
            hmax = fmax(hmax, fabs(h));
            smax = fmax(smax, hypot(g[0], g[1]));
        }
        CHECK_MSG(hmax <= hb && smax <= sb, "set %d: |h| %g <= %g, slope %g <= %g", set, hmax, hb, smax, sb);
        CHECK_MSG(hmax > 0.2 * hb && smax > 0.1 * sb, "set %d: bounds loose: %g / %g, %g / %g", set, hmax, hb, smax, sb);
    }
}

/* ------------------------------------------------------------ uniforms */

static const ref_waves_uniform *find(const ref_waves_uniform *u, int n, const char *name) {
    for (int i = 0; i < n; i++)
        if (strcmp(u[i].name, name) == 0) return &u[i];
    return NULL;
}

static void test_uniforms(void) {
    ref_explosion_desc e[3] = { ring(0.5, 0, 0, 0.1), ring(0, 0, 0, 0), ring(-0.2, 3, 2, 0) };
    ref_perlin_desc p = pset(0.3, 3, 2.0, 90.0, 5);
    ref_waves_uniform u[REF_WAVEFX_UNIFORMS_MAX];
    int n = ref_wavefx_uniforms(e, 3, &p, u, REF_WAVEFX_UNIFORMS_MAX);
    CHECK(n > 0 && n <= REF_WAVEFX_UNIFORMS_MAX);
    const ref_waves_uniform *en = find(u, n, "uExplosionN"), *ex = find(u, n, "uExplosion"),
                            *ew = find(u, n, "uExplosionWave"), *pn = find(u, n, "uPerlinN"),
                            *po = find(u, n, "uPerlinOctave"), *pf = find(u, n, "uPerlinFrame"),
                            *ps = find(u, n, "uPerlinSeed");
    CHECK(en && ex && ew && pn && po && pf && ps);
    if (!(en && ex && ew && pn && po && pf && ps)) return;
    CHECK(en->is_int && en->i == 2);                      /* the I0 = 0 ring is left out */
    CHECK(ex->comps == 4 && ex->count == REF_EXPLOSIONS_MAX && ex->count <= REF_UNIFORM_ARRAY_MAX);
    CHECK(ex->v[4 + 3] == -0.2f && ew->v[4 + 0] == 3.0f && ew->v[4 + 1] == 2.0f && ew->v[4 + 3] == 4.0f);
    CHECK(pn->is_int && pn->i == 3);
    CHECK(ps->is_uint && ps->count == REF_PERLIN_OCTAVES_MAX && ps->u[2] == my_hash(5u + 2u * 0x9E3779B9U));
    CHECK_NEAR(po->v[4 * 2 + 0], 4.0 / 3.0, 1e-6);
    CHECK_NEAR(po->v[4 * 2 + 1], 0.7 * 2.0, 1e-6);
    CHECK_NEAR(po->v[4 * 2 + 2], 0.3 * 0.55 * 0.55, 1e-7);
    CHECK_NEAR(pf->v[0], 0.0, 1e-7);
    CHECK_NEAR(pf->v[1], 1.0, 1e-7);
    CHECK_NEAR(pf->v[2], 0.5, 1e-7);
    /* nothing: both counts 0 */
    n = ref_wavefx_uniforms(NULL, 0, NULL, u, REF_WAVEFX_UNIFORMS_MAX);
    CHECK(find(u, n, "uExplosionN")->i == 0 && find(u, n, "uPerlinN")->i == 0);
    /* a short array: no more than max */
    CHECK_EQ(ref_wavefx_uniforms(e, 3, &p, u, 2), 2);
}

int main(void) {
    RUN(test_ring_defaults_and_errors);
    RUN(test_ring_flat_before_and_at_start);
    RUN(test_ring_formula);
    RUN(test_ring_centre_smooth);
    RUN(test_ring_gradient_fd);
    RUN(test_ring_speed);
    RUN(test_ring_decay);
    RUN(test_ring_bounds);
    RUN(test_perlin3_lattice);
    RUN(test_perlin3_range_and_gradient);
    RUN(test_perlin3_seeds);
    RUN(test_perlin_defaults_and_errors);
    RUN(test_perlin_set_formula_and_gradient);
    RUN(test_perlin_stretch_direction);
    RUN(test_perlin_bounds);
    RUN(test_uniforms);
    return check_summary();
}
