/* test_ref_waves: the reference's wave set (sum of sines, Gerstner, noise)
 * against independent formulas written out here, finite differences, the
 * loop-free bound of GPU Gems 1 ch. 1 and the Newton inversion. */
#include "check.h"
#include "ref_waves.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#define TWO_PI (2.0 * M_PI)

static int init(ref_waves *w, const ref_waves_desc *d) {
    char err[256];
    int rc = ref_waves_init(w, d, err, sizeof err);
    CHECK_MSG(rc == 0, "%s", err);
    return rc;
}

static double dist3(const double a[3], const double b[3]) {
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* deterministic sample points */
static double lcg01(uint64_t *s) {
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) * 0x1.0p-53;
}

static void test_defaults_and_errors(void) {
    ref_waves w;
    if (init(&w, NULL)) return;                          /* all zero: flat calm water at 0 */
    double p[3];
    ref_waves_displace(&w, 3.0, -7.0, 12.0, p);
    CHECK(p[0] == 3.0 && p[1] == 0.0 && p[2] == -7.0);
    CHECK_EQ(ref_waves_height(&w, 1.0, 2.0, 3.0), 0.0);
    ref_waves_point pt;
    ref_waves_eval(&w, 1.0, 2.0, 0.0, &pt);
    CHECK(pt.normal[0] == 0.0 && pt.normal[1] == 1.0 && pt.normal[2] == 0.0);
    CHECK_EQ(w.height_bound, 0.0);

    ref_waves_desc d = ref_waves_default();
    if (init(&w, &d)) return;
    CHECK_NEAR(w.q_sum, d.steepness, 1e-15);            /* sum Q_i w_i A_i = Q */
    CHECK(w.ngerstner == d.gerstner_count && w.nsine == d.sine_count);
    CHECK_EQ(w.noctaves, d.noise.octaves);
    /* zero speed became the deep-water phase speed */
    CHECK_NEAR(w.desc.gerstner[0].speed, sqrt(REF_GRAVITY * d.gerstner[0].wavelength / TWO_PI), 1e-15);
    CHECK_GT(w.world_slope_bound, w.slope_bound);

    /* zero noise fields take the defaults */
    ref_waves_desc dn;
    memset(&dn, 0, sizeof dn);
    dn.noise.amplitude = 0.1;
    if (init(&w, &dn)) return;
    CHECK(w.desc.noise.cell == REF_NOISE_DEFAULT_CELL && w.desc.noise.octaves == REF_NOISE_DEFAULT_OCTAVES);
    CHECK(w.desc.noise.period == REF_NOISE_DEFAULT_PERIOD && w.desc.noise.gain == REF_NOISE_DEFAULT_GAIN);

    /* bad input is an error value with a message */
    char err[256];
    ref_waves_desc bad = d;
    bad.sine_count = REF_WAVES_MAX + 1;
    CHECK_EQ(ref_waves_init(&w, &bad, err, sizeof err), -1);
    CHECK_STR_CONTAINS(err, "sine_count");
    bad = d;
    bad.steepness = -0.1;
    CHECK_EQ(ref_waves_init(&w, &bad, err, sizeof err), -1);
    CHECK_STR_CONTAINS(err, "steepness");
    bad = d;
    bad.gerstner[1].amplitude = NAN;
    CHECK_EQ(ref_waves_init(&w, &bad, err, sizeof err), -1);
    CHECK_STR_CONTAINS(err, "Gerstner wave 1");
    bad = d;
    bad.noise.octaves = 99;
    CHECK_EQ(ref_waves_init(&w, &bad, err, sizeof err), -1);
    CHECK_STR_CONTAINS(err, "octaves");

    /* an inactive wave (A = 0) is skipped and not counted in N */
    ref_waves_desc dz;
    memset(&dz, 0, sizeof dz);
    dz.steepness = 0.5;
    dz.gerstner_count = 2;
    dz.gerstner[0] = (ref_wave_desc){ .angle_deg = 10, .wavelength = 4, .amplitude = 0.1 };
    dz.gerstner[1] = (ref_wave_desc){ .angle_deg = 80, .wavelength = 3, .amplitude = 0.0 };
    if (init(&w, &dz)) return;
    CHECK_EQ(w.ngerstner, 1);
    CHECK_NEAR(w.q_sum, 0.5, 1e-15);
}

/* The wave set of a test: Gerstner and sine waves in several directions. */
static ref_waves_desc four_waves(double q, int gerstner) {
    ref_waves_desc d;
    memset(&d, 0, sizeof d);
    ref_wave_desc ws[4] = {
        { .angle_deg = 20.0, .wavelength = 9.0, .amplitude = 0.10 },
        { .angle_deg = -35.0, .wavelength = 5.3, .amplitude = 0.06, .phase = 1.0 },
        { .angle_deg = 75.0, .wavelength = 3.1, .amplitude = 0.035, .phase = 2.0, .speed = 1.7 },
        { .angle_deg = 140.0, .wavelength = 1.7, .amplitude = 0.018, .phase = 4.0 },
    };
    if (gerstner) {
        d.gerstner_count = 4;
        memcpy(d.gerstner, ws, sizeof ws);
    } else {
        d.sine_count = 4;
        memcpy(d.sine, ws, sizeof ws);
    }
    d.steepness = q;
    d.level = 0.25;
    return d;
}

/* GPU Gems 1 eq. 9 written out independently (y up; the chapter's y is our z):
 * P = (x + sum Q_i A_i D.x cos(w_i D.(x,z) + phi_i t),
 *      level + sum A_i sin(...),
 *      z + sum Q_i A_i D.z cos(...)),
 * w_i = 2 pi / L_i, phi_i = S_i w_i (S_i = sqrt(g L / 2 pi) when 0),
 * Q_i = Q / (w_i A_i N). */
static void gems_eq9(const ref_waves_desc *d, int gerstner, double x, double z, double t, double P[3]) {
    const ref_wave_desc *ws = gerstner ? d->gerstner : d->sine;
    int n = gerstner ? d->gerstner_count : d->sine_count;
    P[0] = x; P[1] = d->level; P[2] = z;
    for (int i = 0; i < n; i++) {
        double a = ws[i].angle_deg * M_PI / 180.0, Dx = cos(a), Dz = sin(a);
        double w = TWO_PI / ws[i].wavelength, A = ws[i].amplitude;
        double S = ws[i].speed != 0.0 ? ws[i].speed : sqrt(REF_GRAVITY * ws[i].wavelength / TWO_PI);
        double th = w * (Dx * x + Dz * z) + S * w * t + ws[i].phase;
        double Qi = gerstner ? d->steepness / (w * A * n) : 0.0;
        P[0] += Qi * A * Dx * cos(th);
        P[1] += A * sin(th);
        P[2] += Qi * A * Dz * cos(th);
    }
}

static void test_gerstner_matches_gems_eq9(void) {
    ref_waves_desc d = four_waves(0.8, 1);
    ref_waves w;
    if (init(&w, &d)) return;
    uint64_t s = 1;
    double worst = 0.0;
    for (int i = 0; i < 2000; i++) {
        double u = 200.0 * lcg01(&s) - 100.0, v = 200.0 * lcg01(&s) - 100.0, t = 30.0 * lcg01(&s);
        double P[3], Q[3];
        ref_waves_displace(&w, u, v, t, P);
        gems_eq9(&d, 1, u, v, t, Q);
        worst = fmax(worst, dist3(P, Q));
    }
    CHECK_MSG(worst <= 1e-12, "max |P - eq9| = %g", worst);
}

/* Q = 0 turns Gerstner waves into the sum of sines: same positions and
 * normals (to 1e-12), and both equal the sum of sines written out. */
static void test_gerstner_q0_is_sum_of_sines(void) {
    ref_waves_desc dg = four_waves(0.0, 1), ds = four_waves(0.0, 0);
    ref_waves wg, ws;
    if (init(&wg, &dg) || init(&ws, &ds)) return;
    uint64_t s = 2;
    double worst_p = 0.0, worst_n = 0.0, worst_ind = 0.0;
    for (int i = 0; i < 2000; i++) {
        double u = 200.0 * lcg01(&s) - 100.0, v = 200.0 * lcg01(&s) - 100.0, t = 30.0 * lcg01(&s);
        ref_waves_point a, b;
        ref_waves_eval(&wg, u, v, t, &a);
        ref_waves_eval(&ws, u, v, t, &b);
        worst_p = fmax(worst_p, dist3(a.pos, b.pos));
        worst_n = fmax(worst_n, dist3(a.normal, b.normal));
        double P[3];
        gems_eq9(&ds, 0, u, v, t, P);
        worst_ind = fmax(worst_ind, dist3(b.pos, P));
        /* the sum of sines moves nothing sideways */
        CHECK(a.pos[0] == u && a.pos[2] == v);
    }
    CHECK_MSG(worst_p <= 1e-12, "max |P_gerstner - P_sines| = %g", worst_p);
    CHECK_MSG(worst_n <= 1e-12, "max |N_gerstner - N_sines| = %g", worst_n);
    CHECK_MSG(worst_ind <= 1e-12, "max |P_sines - written out| = %g", worst_ind);
}

/* Central differences of P(u, v) against the analytic dP/du, dP/dv and the
 * exact normal, on the full default set (Gerstner + sines + noise).
 * Central differences err by h^2/6 |P'''| plus rounding eps |P| / h: with
 * h = 1e-4, |P'''| < ~10 here (largest k^3 A is ~1.1 for the sines, the
 * finest noise octave a few) and |P| <= ~150, both are below 1e-8; we assert
 * 1e-7. The order is checked too: halving h divides the error by ~4. */
static void test_normals_vs_finite_differences(void) {
    ref_waves_desc d = ref_waves_default();
    ref_waves w;
    if (init(&w, &d)) return;
    const double h = 1e-4;
    uint64_t s = 3;
    double worst_b = 0.0, worst_t = 0.0, worst_n = 0.0, e_h = 0.0, e_h2 = 0.0;
    for (int i = 0; i < 3000; i++) {
        double u = 200.0 * lcg01(&s) - 100.0, v = 200.0 * lcg01(&s) - 100.0, t = 20.0 * lcg01(&s);
        ref_waves_point p;
        ref_waves_eval(&w, u, v, t, &p);
        double pu1[3], pu0[3], pv1[3], pv0[3], B[3], T[3];
        ref_waves_displace(&w, u + h, v, t, pu1);
        ref_waves_displace(&w, u - h, v, t, pu0);
        ref_waves_displace(&w, u, v + h, t, pv1);
        ref_waves_displace(&w, u, v - h, t, pv0);
        for (int k = 0; k < 3; k++) {
            B[k] = (pu1[k] - pu0[k]) / (2 * h);
            T[k] = (pv1[k] - pv0[k]) / (2 * h);
        }
        worst_b = fmax(worst_b, dist3(B, p.dpdu));
        worst_t = fmax(worst_t, dist3(T, p.dpdv));
        double n[3] = { T[1] * B[2] - T[2] * B[1], T[2] * B[0] - T[0] * B[2], T[0] * B[1] - T[1] * B[0] };
        double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int k = 0; k < 3; k++) n[k] /= l;
        worst_n = fmax(worst_n, dist3(n, p.normal));
        CHECK_GT(p.normal[1], 0.0);
        /* Jacobian = the horizontal cross product of the differences */
        CHECK_NEAR(p.jacobian, B[0] * T[2] - B[2] * T[0], 1e-7);
        if (i < 300) {   /* convergence order with larger steps (truncation dominates) */
            double H = 2e-2;
            for (int pass = 0; pass < 2; pass++, H *= 0.5) {
                double a[3], b[3];
                ref_waves_displace(&w, u + H, v, t, a);
                ref_waves_displace(&w, u - H, v, t, b);
                double e = 0.0;
                for (int k = 0; k < 3; k++) e += fabs((a[k] - b[k]) / (2 * H) - p.dpdu[k]);
                if (pass == 0) e_h += e; else e_h2 += e;
            }
        }
    }
    CHECK_MSG(worst_b <= 1e-7, "max |dP/du - FD| = %g", worst_b);
    CHECK_MSG(worst_t <= 1e-7, "max |dP/dv - FD| = %g", worst_t);
    CHECK_MSG(worst_n <= 1e-7, "max |N - N_FD| = %g", worst_n);
    double order = log2(e_h / e_h2);
    CHECK_MSG(order > 1.8 && order < 2.2, "observed order %g", order);
    fprintf(stderr, "  max |B - FD| %.3g, |T - FD| %.3g, |N - N_FD| %.3g (h = 1e-4); order %.3f\n",
            worst_b, worst_t, worst_n, order);
}

/* The chapter's normal (eq. 12) drops the cross terms of cross(B, T): it is
 * exact for a single Gerstner wave (the cross terms cancel) and not for a
 * sum; it equals eq. 12 written out. */
static void test_approx_normal(void) {
    ref_waves_desc d1;
    memset(&d1, 0, sizeof d1);
    d1.gerstner_count = 1;
    d1.gerstner[0] = (ref_wave_desc){ .angle_deg = 33.0, .wavelength = 4.0, .amplitude = 0.2 };
    d1.steepness = 0.9;
    ref_waves w1, w4;
    ref_waves_desc d4 = four_waves(0.9, 1);
    if (init(&w1, &d1) || init(&w4, &d4)) return;
    uint64_t s = 4;
    double worst1 = 0.0, max_angle4 = 0.0, worst_eq12 = 0.0;
    for (int i = 0; i < 2000; i++) {
        double u = 100.0 * lcg01(&s) - 50.0, v = 100.0 * lcg01(&s) - 50.0, t = 10.0 * lcg01(&s);
        ref_waves_point p;
        ref_waves_eval(&w1, u, v, t, &p);
        worst1 = fmax(worst1, dist3(p.normal, p.normal_approx));
        ref_waves_eval(&w4, u, v, t, &p);
        double c = p.normal[0] * p.normal_approx[0] + p.normal[1] * p.normal_approx[1] +
                   p.normal[2] * p.normal_approx[2];
        max_angle4 = fmax(max_angle4, acos(fmin(1.0, c)));
        /* eq. 12: N = (-sum D.x WA C, 1 - sum Q_i WA S, -sum D.z WA C) */
        double n[3] = { 0.0, 1.0, 0.0 };
        for (int k = 0; k < 4; k++) {
            const ref_wave_desc *wd = &d4.gerstner[k];
            double a = wd->angle_deg * M_PI / 180.0, Dx = cos(a), Dz = sin(a);
            double W = TWO_PI / wd->wavelength, A = wd->amplitude;
            double S = wd->speed != 0.0 ? wd->speed : sqrt(REF_GRAVITY * wd->wavelength / TWO_PI);
            double th = W * (Dx * u + Dz * v) + S * W * t + wd->phase;
            double Qi = d4.steepness / (W * A * 4);
            n[0] -= Dx * W * A * cos(th);
            n[1] -= Qi * W * A * sin(th);
            n[2] -= Dz * W * A * cos(th);
        }
        double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int k = 0; k < 3; k++) n[k] /= l;
        worst_eq12 = fmax(worst_eq12, dist3(n, p.normal_approx));
    }
    CHECK_MSG(worst1 <= 1e-12, "single wave: |N - N_approx| = %g", worst1);
    CHECK_MSG(worst_eq12 <= 1e-12, "|N_approx - eq. 12| = %g", worst_eq12);
    CHECK_MSG(max_angle4 > 1e-3, "four waves: approx normal error only %g rad", max_angle4);
}

/* Minimum of the horizontal map's Jacobian over a dense grid (spacing
 * L_min / 24 over a 40 x 40 area) at a few times. */
static double min_jacobian(const ref_waves *w) {
    double m = INFINITY;
    double step = w->min_wavelength / 24.0;
    int n = (int)(40.0 / step);
    for (int ti = 0; ti < 3; ti++)
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                ref_waves_point p;
                ref_waves_eval(w, -20.0 + i * step, -20.0 + j * step, 1.3 * ti, &p);
                if (p.jacobian < m) m = p.jacobian;
            }
    return m;
}

/* Loop-free while sum Q_i w_i A_i = Q <= 1: the Jacobian of (u,v) -> (x,z)
 * is I - sum c_i D_i D_i^T with |c_i| <= Q_i w_i A_i, so its eigenvalues are
 * >= 1 - Q and det >= (1 - Q)^2 > 0; asserted on the grid (to 1e-12). At
 * Q = 1 the bound is 0 and is reached where all crests meet (parallel waves
 * at one crest). Above 1 the surface folds (det < 0 somewhere). */
static void test_loop_free_up_to_q1(void) {
    double qs[] = { 0.3, 0.7, 0.95, 1.0 };
    for (int k = 0; k < 4; k++) {
        ref_waves_desc d = four_waves(qs[k], 1);
        ref_waves w;
        if (init(&w, &d)) return;
        CHECK_NEAR(w.q_sum, qs[k], 1e-15);
        double m = min_jacobian(&w);
        double bound = (1.0 - qs[k]) * (1.0 - qs[k]);
        CHECK_MSG(m >= bound - 1e-12, "Q = %g: min det %g < (1-Q)^2 = %g", qs[k], m, bound);
        if (qs[k] < 1.0) CHECK_GT(m, 0.0);
    }
    /* parallel waves at Q = 1 touch 0 at the common crest, fold above */
    ref_waves_desc dp;
    memset(&dp, 0, sizeof dp);
    dp.gerstner_count = 2;
    dp.gerstner[0] = (ref_wave_desc){ .angle_deg = 0.0, .wavelength = 4.0, .amplitude = 0.2 };
    dp.gerstner[1] = (ref_wave_desc){ .angle_deg = 0.0, .wavelength = 2.0, .amplitude = 0.05, .phase = -M_PI / 2 };
    dp.steepness = 1.0;
    ref_waves w;
    if (init(&w, &dp)) return;
    /* both crests at k u = pi/2 (mod 2 pi) at t = 0: u = 1 */
    ref_waves_point p;
    ref_waves_eval(&w, 1.0, 0.0, 0.0, &p);
    CHECK_NEAR(p.jacobian, 0.0, 1e-12);
    CHECK_GE(min_jacobian(&w), -1e-12);
    /* x(u) along the wave is monotone (no loop) at Q = 1 ... */
    double prev = -INFINITY;
    int monotone = 1;
    for (int i = 0; i <= 4000; i++) {
        double P[3];
        ref_waves_displace(&w, -2.0 + i * 1e-3, 0.0, 0.0, P);
        if (P[0] < prev) monotone = 0;
        prev = P[0];
    }
    CHECK(monotone);
    /* ... and loops above it */
    dp.steepness = 1.2;
    if (init(&w, &dp)) return;
    ref_waves_eval(&w, 1.0, 0.0, 0.0, &p);
    CHECK_NEAR(p.jacobian, 1.0 - 1.2, 1e-12);
    prev = -INFINITY;
    monotone = 1;
    for (int i = 0; i <= 4000; i++) {
        double P[3];
        ref_waves_displace(&w, -2.0 + i * 1e-3, 0.0, 0.0, P);
        if (P[0] < prev) monotone = 0;
        prev = P[0];
    }
    CHECK(!monotone);
    /* the four-direction set folds too once Q is well above 1 */
    ref_waves_desc d = four_waves(1.8, 1);
    if (init(&w, &d)) return;
    CHECK_LT(min_jacobian(&w), 0.0);
}

/* Newton at a world point recovers the parametric point: take (u, v), map
 * it to P, ask for the surface over (P.x, P.z): same (u, v) to 1e-10, same
 * height to 1e-12, residual within the 1e-12 * max(1, |x|, |z|) target. */
static void test_newton_inversion(void) {
    double qs[] = { 0.6, 0.95, 0.999 };
    for (int k = 0; k < 3; k++) {
        ref_waves_desc d = ref_waves_default();
        d.steepness = qs[k];
        ref_waves w;
        if (init(&w, &d)) return;
        uint64_t s = 5 + k;
        double worst_uv = 0.0, worst_h = 0.0;
        int max_it = 0, fails = 0;
        for (int i = 0; i < 5000; i++) {
            double u = 400.0 * lcg01(&s) - 200.0, v = 400.0 * lcg01(&s) - 200.0, t = 50.0 * lcg01(&s);
            double P[3];
            ref_waves_displace(&w, u, v, t, P);
            ref_waves_point q;
            if (ref_waves_at(&w, P[0], P[2], t, NULL, &q) != 0) fails++;
            worst_uv = fmax(worst_uv, fmax(fabs(q.param[0] - u), fabs(q.param[1] - v)));
            worst_h = fmax(worst_h, fabs(q.pos[1] - P[1]));
            CHECK_LE(q.residual, 1e-12 * fmax(1.0, fmax(fabs(P[0]), fabs(P[2]))));
            if (q.iterations > max_it) max_it = q.iterations;
        }
        CHECK_MSG(fails == 0, "Q = %g: %d failures", qs[k], fails);
        /* the residual target is 1e-12 * max(1, |x|, |z|) (<= 2e-10 here,
         * |x|, |z| <= ~200), and the map's smallest singular value 1 - Q
         * bounds how far that moves (u, v): 2e-10 / (1 - Q); the height
         * moves by at most slope_bound times that. The polishing Newton
         * step after convergence takes the residual to rounding level, so
         * for Q <= 0.95 we also assert 1e-12 absolute (actual: ~1e-13). */
        CHECK_MSG(worst_uv <= 200e-12 / (1.0 - qs[k]), "Q = %g: |uv error| = %g", qs[k], worst_uv);
        CHECK_MSG(worst_h <= 200e-12 / (1.0 - qs[k]) * w.slope_bound, "Q = %g: |h error| = %g", qs[k], worst_h);
        if (qs[k] <= 0.95) {
            CHECK_MSG(worst_uv <= 1e-12, "Q = %g: |uv error| = %g", qs[k], worst_uv);
            CHECK_MSG(worst_h <= 1e-12, "Q = %g: |h error| = %g", qs[k], worst_h);
        }
        if (qs[k] <= 0.95) CHECK_MSG(max_it <= 12, "Q = %g: %d iterations", qs[k], max_it);
        fprintf(stderr, "  Q = %g: max |uv err| %.3g, |h err| %.3g, max iterations %d\n",
                qs[k], worst_uv, worst_h, max_it);
    }
    /* a warm start near the answer converges at once */
    ref_waves_desc d = ref_waves_default();
    ref_waves w;
    if (init(&w, &d)) return;
    double P[3];
    ref_waves_displace(&w, 3.0, 4.0, 1.0, P);
    double guess[2] = { 3.0 + 1e-6, 4.0 - 1e-6 };
    ref_waves_point q;
    CHECK_EQ(ref_waves_at(&w, P[0], P[2], 1.0, guess, &q), 0);
    CHECK_LE(q.iterations, 2);
    CHECK_NEAR(ref_waves_height(&w, P[0], P[2], 1.0), P[1], 1e-12);
}

/* The noise tiles with period * cell, is C1 across lattice lines, and its
 * gradient matches central differences (h = 1e-5, tolerance 1e-7). */
static void test_noise(void) {
    ref_waves_desc d;
    memset(&d, 0, sizeof d);
    d.noise = (ref_noise_desc){ .amplitude = 0.3, .cell = 2.0, .octaves = 4, .period = 8,
                                .angle_deg = 30.0, .seed = 77 };
    ref_waves w;
    if (init(&w, &d)) return;
    double tile = 8 * 2.0;
    uint64_t s = 9;
    double worst_tile = 0.0, worst_grad = 0.0, maxabs = 0.0, maxgrad = 0.0;
    for (int i = 0; i < 3000; i++) {
        double u = 100.0 * lcg01(&s) - 50.0, v = 100.0 * lcg01(&s) - 50.0, t = 7.0 * lcg01(&s);
        double g[2], g1[2];
        double n = ref_waves_noise(&w, u, v, t, g);
        worst_tile = fmax(worst_tile, fabs(ref_waves_noise(&w, u + tile, v, t, NULL) - n));
        worst_tile = fmax(worst_tile, fabs(ref_waves_noise(&w, u, v - 3 * tile, t, NULL) - n));
        const double h = 1e-5;
        double fx = (ref_waves_noise(&w, u + h, v, t, NULL) - ref_waves_noise(&w, u - h, v, t, NULL)) / (2 * h);
        double fz = (ref_waves_noise(&w, u, v + h, t, NULL) - ref_waves_noise(&w, u, v - h, t, NULL)) / (2 * h);
        worst_grad = fmax(worst_grad, fmax(fabs(fx - g[0]), fabs(fz - g[1])));
        maxabs = fmax(maxabs, fabs(n));
        maxgrad = fmax(maxgrad, hypot(g[0], g[1]));
        (void)g1;
    }
    CHECK_MSG(worst_tile <= 1e-9, "tile mismatch %g", worst_tile);
    CHECK_MSG(worst_grad <= 1e-7, "noise gradient vs FD %g", worst_grad);
    CHECK_LE(maxabs, w.height_bound);
    CHECK_LE(maxgrad, w.slope_bound);
    CHECK_GT(maxabs, 0.05);                         /* it is not flat */
    /* across a lattice line of octave 0 (u = 4.0 is a multiple of cell at
     * t = 0 since the drift moves the lattice with time) */
    double ga[2], gb[2];
    double na = ref_waves_noise(&w, 4.0 - 1e-9, 1.3, 0.0, ga);
    double nb = ref_waves_noise(&w, 4.0 + 1e-9, 1.3, 0.0, gb);
    CHECK_NEAR(na, nb, 1e-8);
    CHECK_NEAR(ga[0], gb[0], 1e-6);
    CHECK_NEAR(ga[1], gb[1], 1e-6);
    /* deterministic, and the seed matters */
    double n1 = ref_waves_noise(&w, 1.234, 5.678, 0.5, NULL);
    d.noise.seed = 78;
    ref_waves w2;
    if (init(&w2, &d)) return;
    CHECK_EQ(ref_waves_noise(&w, 1.234, 5.678, 0.5, NULL), n1);
    CHECK_GT(fabs(ref_waves_noise(&w2, 1.234, 5.678, 0.5, NULL) - n1), 1e-6);
}

static void test_uniforms(void) {
    ref_waves_desc d = ref_waves_default();
    d.noise.seed = 0xdeadbeefU;
    ref_waves w;
    if (init(&w, &d)) return;
    ref_waves_uniform u[REF_WAVES_UNIFORMS_MAX];
    int n = ref_waves_uniforms(&w, u, REF_WAVES_UNIFORMS_MAX);
    /* 32 of the waves, ref_wavefx's 7 (rings and Perlin set), the ocean's 3 */
    CHECK_EQ(n, 32 + 7 + 3);
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++) CHECK(strcmp(u[i].name, u[j].name) != 0);
    int seen = 0;
    for (int i = 0; i < n; i++) {
        if (!strcmp(u[i].name, "uGerstnerLength")) {
            seen++;
            CHECK(u[i].count == REF_WAVES_MAX && !u[i].is_int);
            CHECK_EQ(u[i].v[1], (float)d.gerstner[1].wavelength);
        }
        if (!strcmp(u[i].name, "uGerstnerSpeed")) {
            seen++;
            CHECK_EQ(u[i].v[0], (float)sqrt(REF_GRAVITY * d.gerstner[0].wavelength / TWO_PI));
        }
        if (!strcmp(u[i].name, "uSineCount")) { seen++; CHECK(u[i].is_int && u[i].i == d.sine_count); }
        if (!strcmp(u[i].name, "uNoiseSeed")) { seen++; CHECK(u[i].is_int && (uint32_t)u[i].i == 0xdeadbeefU); }
        if (!strcmp(u[i].name, "uSteepness")) { seen++; CHECK_EQ(u[i].v[0], (float)d.steepness); }
        if (!strcmp(u[i].name, "uWaveGerst")) {   /* (k D.x, k D.z, omega, phase) of the second */
            seen++;
            double k = TWO_PI / d.gerstner[1].wavelength, a = d.gerstner[1].angle_deg * TWO_PI / 360.0;
            double omega = sqrt(REF_GRAVITY * d.gerstner[1].wavelength / TWO_PI) * k;
            CHECK(u[i].comps == 4 && u[i].count == REF_WAVES_MAX);
            CHECK_NEAR(u[i].v[4], k * cos(a), 1e-5);
            CHECK_NEAR(u[i].v[5], k * sin(a), 1e-5);
            CHECK_NEAR(u[i].v[6], omega, 1e-5);
            CHECK_EQ(u[i].v[7], (float)d.gerstner[1].phase);
        }
        if (!strcmp(u[i].name, "uWaveGerstAmp")) {   /* (A, Q_i A_i D.x, Q_i A_i D.z), Q_i A_i = Q / (k N) */
            seen++;
            double k = TWO_PI / d.gerstner[0].wavelength, a = d.gerstner[0].angle_deg * TWO_PI / 360.0;
            double qa = d.steepness / (k * w.ngerstner);
            CHECK_EQ(u[i].comps, 3);
            CHECK_EQ(u[i].v[0], (float)d.gerstner[0].amplitude);
            CHECK_NEAR(u[i].v[1], qa * cos(a), 1e-6);
            CHECK_NEAR(u[i].v[2], qa * sin(a), 1e-6);
        }
        if (!strcmp(u[i].name, "uWaveNoiseSeed")) { seen++; CHECK(u[i].is_uint && u[i].u[0] == w.octave[0].seed); }
    }
    CHECK_EQ(seen, 8);
    CHECK_EQ(ref_waves_uniforms(&w, u, 3), 3);
}

/* A gentle spectrum ocean (lambda 1, not folding at t) through the wave
 * set: the inversion converges, heights and positions are the ocean's
 * fields at the rest point, the normal is the continuous surface's. */
static ref_waves_desc ocean_desc(double wind, double lambda) {
    ref_waves_desc d;
    memset(&d, 0, sizeof d);
    d.level = 0.5;
    d.ocean = (ref_ocean_desc){ .spectrum = REF_SPECTRUM_JONSWAP, .wind_speed = wind, .fetch = 20e3,
                                .choppiness = lambda, .res = 64, .cascades = 2, .tile = { 64, 8 }, .seed = 3 };
    return d;
}

static void test_ocean(void) {
    ref_waves_desc d = ocean_desc(6, 1);
    d.gerstner_count = 1;
    d.gerstner[0] = (ref_wave_desc){ .angle_deg = 10, .wavelength = 7, .amplitude = 0.05 };
    d.steepness = 0.2;
    ref_waves w;
    if (init(&w, &d)) return;
    CHECK_NE(w.ocean, NULL);
    double t = 1.25, hb, sb, wsb;
    ref_waves_bounds_at(&w, t, &hb, &sb, &wsb);
    CHECK_MSG(isfinite(wsb) && hb <= w.height_bound && sb <= w.slope_bound, "bounds %g %g %g", hb, sb, wsb);
    CHECK_LE(w.min_wavelength, 2 * 8.0 / 64);
    uint64_t st = 7;
    double worst_r = 0, worst_h = 0;
    for (int i = 0; i < 300; i++) {
        double x = 200 * lcg01(&st) - 100, z = 200 * lcg01(&st) - 100;
        ref_waves_point p;
        int rc = ref_waves_at(&w, x, z, t, NULL, &p);
        CHECK_EQ(rc, 0);
        worst_r = fmax(worst_r, p.residual / fmax(1, fmax(fabs(x), fabs(z))));
        /* the rest point's own fields: Gerstner plus ocean, written out */
        ref_ocean_sample s;
        ref_ocean_sample_at(w.ocean, p.param[0], p.param[1], t, &s);
        const ref_wave_comp *g = &w.gerstner[0];
        double th = g->k * (g->dir[0] * p.param[0] + g->dir[1] * p.param[1]) + g->omega * t + g->phase;
        double px = p.param[0] + g->qa * g->dir[0] * cos(th) + s.dx;
        double pz = p.param[1] + g->qa * g->dir[1] * cos(th) + s.dz;
        double py = d.level + g->amp * sin(th) + s.h;
        CHECK(fabs(px - x) <= 1e-11 * fmax(1, fabs(x)) && fabs(pz - z) <= 1e-11 * fmax(1, fabs(z)));
        worst_h = fmax(worst_h, fabs(ref_waves_height(&w, x, z, t) - py));
        CHECK_LT(fabs(p.pos[1] - py), 1e-14 * 10);
    }
    /* a residual of 1e-12 moves the height by at most slope / (1 - fold) times it */
    CHECK_MSG(worst_r <= 1e-12, "residual %g", worst_r);
    CHECK_MSG(worst_h <= 1e-12 * 100 * wsb + 1e-14, "height %g", worst_h);
    ref_waves_release(&w);

    /* normals at nodes (integer metres are nodes of both cascades) against
     * central differences of the continuous displaced surface (the direct
     * sum; e = 1e-5: truncation (k e)^2, rounding 1e-15 / e: < 1e-7) */
    ref_waves_desc od = ocean_desc(6, 1);
    if (init(&w, &od)) return;
    for (int i = 0; i < 10; i++) {
        double u = (i * 7) % 64 - 20, v = (i * 13) % 64 + 3, e = 1e-5;
        ref_waves_point p;
        ref_waves_eval(&w, u, v, t, &p);
        ref_ocean_sample a, b, c2, dd;
        ref_ocean_direct_sum(w.ocean, u + e, v, t, &a);
        ref_ocean_direct_sum(w.ocean, u - e, v, t, &b);
        ref_ocean_direct_sum(w.ocean, u, v + e, t, &c2);
        ref_ocean_direct_sum(w.ocean, u, v - e, t, &dd);
        double B[3] = { (2 * e + a.dx - b.dx) / (2 * e), (a.h - b.h) / (2 * e), (a.dz - b.dz) / (2 * e) };
        double T[3] = { (c2.dx - dd.dx) / (2 * e), (c2.h - dd.h) / (2 * e), (2 * e + c2.dz - dd.dz) / (2 * e) };
        double n[3] = { T[1] * B[2] - T[2] * B[1], T[2] * B[0] - T[0] * B[2], T[0] * B[1] - T[1] * B[0] };
        double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int k = 0; k < 3; k++) CHECK_MSG(fabs(n[k] / l - p.normal[k]) < 1e-7, "normal %d: %g vs %g", k, n[k] / l, p.normal[k]);
        CHECK_GT(p.jacobian, 0);
    }
    ref_waves_uniform un[REF_WAVES_UNIFORMS_MAX];
    int nu = ref_waves_uniforms(&w, un, REF_WAVES_UNIFORMS_MAX), seen = 0;
    for (int i = 0; i < nu; i++) {
        if (!strcmp(un[i].name, "uOceanN")) { seen++; CHECK(un[i].is_int && un[i].i == 2); }
        if (!strcmp(un[i].name, "uOceanRes")) { seen++; CHECK(un[i].is_int && un[i].i == 64); }
        if (!strcmp(un[i].name, "uOceanTile")) {
            seen++;
            CHECK(!un[i].is_int && un[i].count == REF_OCEAN_CASCADES_MAX && un[i].v[0] == 64 && un[i].v[1] == 8 && un[i].v[2] == 0);
        }
    }
    CHECK_EQ(seen, 3);
    ref_waves_release(&w);
    ref_waves_release(&w);                 /* twice: safe */
    ref_waves zero;
    memset(&zero, 0, sizeof zero);
    ref_waves_release(&zero);

    /* a bad ocean is an error and holds nothing */
    od.ocean.res = 100;
    char err[256];
    CHECK(ref_waves_init(&w, &od, err, sizeof err) == -1 && w.ocean == NULL);
    CHECK_STR_CONTAINS(err, "power of two");
}

/* A folding sea (chop >= 1): ref_waves_eval stays finite everywhere; over
 * a world point ref_waves_height gives a finite height (one of the
 * surface's sheets there, rc 0) or NaN exactly when the inversion fails
 * (rc -1: no unique rest point found). */
/* The fast path a march takes: a prepared context (ref_waves_ctx) gives
 * the plain queries' numbers bit for bit, and the tracked inversion (its
 * start predicted from the last point, as a march steps) reaches the plain
 * inversion's rest point and height to its tolerance, in fewer iterations
 * than from the world point. */
static void test_ctx_fast_path(void) {
    ref_waves_desc d = ocean_desc(6, 1);
    d.gerstner_count = 1;
    d.gerstner[0] = (ref_wave_desc){ .angle_deg = 10, .wavelength = 7, .amplitude = 0.05 };
    d.steepness = 0.2;
    d.sine_count = 1;
    d.sine[0] = (ref_wave_desc){ .angle_deg = 70, .wavelength = 3, .amplitude = 0.02 };
    ref_waves w;
    if (init(&w, &d)) return;
    double t = 1.25, hb, sb, wsb;
    ref_waves_bounds_at(&w, t, &hb, &sb, &wsb);
    ref_waves_ctx c;
    ref_waves_ctx_begin(&c, &w, t);
    CHECK(c.ocean != NULL && c.height == hb && c.slope == sb && c.world_slope == wsb);
    ref_waves_track tr = { 0 };
    uint64_t st = 11;
    int bad = 0;
    double worst_uv = 0, worst_h = 0;
    for (int i = 0; i < 400; i++) {
        /* a march: small steps along a line, and now and then a jump */
        double x = -30 + 0.037 * i + (i % 50 == 0 ? 5 * lcg01(&st) : 0), z = 12 - 0.021 * i;
        ref_waves_point p, q;
        memset(&p, 0, sizeof p);   /* the struct's tail padding too: memcmp below */
        memset(&q, 0, sizeof q);
        bad += ref_waves_at(&w, x, z, t, NULL, &p) != ref_waves_ctx_at(&c, x, z, NULL, &q);
        bad += memcmp(&p, &q, sizeof p) != 0;
        double uv0[2], uv1[2], uv2[2], h0, h1, h2;
        ref_waves_rest_point(&w, x, z, t, NULL, uv0, &h0);
        ref_waves_ctx_rest_point(&c, x, z, NULL, uv1, &h1);
        bad += uv0[0] != uv1[0] || uv0[1] != uv1[1] || h0 != h1;
        bad += ref_waves_height(&w, x, z, t) != ref_waves_ctx_height(&c, x, z) || h0 != ref_waves_ctx_height(&c, x, z);
        bad += ref_waves_ctx_track(&c, x, z, &tr, uv2, &h2) != 0;
        worst_uv = fmax(worst_uv, hypot(uv2[0] - uv0[0], uv2[1] - uv0[1]));
        worst_h = fmax(worst_h, fabs(h2 - h0));
    }
    CHECK_MSG(bad == 0, "%d disagreements", bad);
    /* both inversions stop at |residual| <= 1e-12 max(1, |x|, |z|), 3e-11 here;
     * rest points then differ by at most twice that / (1 - fold) */
    CHECK_MSG(worst_uv < 1e-9 && worst_h < 1e-9, "rest points %g m, heights %g m apart", worst_uv, worst_h);
    ref_waves_ctx_end(&c);
    CHECK_EQ(c.ocean, NULL);
    ref_waves_release(&w);

    /* without an ocean a context holds nothing and changes nothing */
    ref_waves_desc lake = ref_waves_default();
    if (init(&w, &lake)) return;
    ref_waves_ctx_begin(&c, &w, 3.0);
    CHECK(c.ocean == NULL && c.world_slope == w.world_slope_bound);
    CHECK_EQ(ref_waves_ctx_height(&c, 1.5, -2.25), ref_waves_height(&w, 1.5, -2.25, 3.0));
    ref_waves_ctx_end(&c);
    ref_waves_release(&w);
}

/* The world-slope bounds by region hold: over random world boxes and
 * discs about a point (its rest point given), at random times, the height
 * over the world changes by at most bound * distance between any two
 * points of them (ocean.glib's sea at N = 64, and with a Gerstner wave
 * too); and the sideways map's smallest singular value (the bilinear map's
 * exact derivative) stays >= 1 - fold. */
static void test_world_slope_regions(void) {
    double worst = 0, worst_sv = 0, ratio_box = 0, ratio_near = 0;
    int n = 0;
    for (int g = 0; g < 2; g++) {
        ref_waves_desc d;
        memset(&d, 0, sizeof d);
        d.level = 0.5;
        d.ocean = (ref_ocean_desc){ .spectrum = REF_SPECTRUM_JONSWAP, .wind_speed = 9, .wind_angle_deg = -80,
                                    .choppiness = 1, .res = 64, .seed = 7, .fetch = 100000, .cascades = 3,
                                    .tile = { 160, 37, 5.3 } };
        d.gerstner_count = g;
        d.gerstner[0] = (ref_wave_desc){ .angle_deg = 30, .wavelength = 7, .amplitude = 0.05 };
        d.steepness = 0.15;
        ref_waves w;
        if (init(&w, &d)) return;
        uint64_t st = 17 + g;
        for (int k = 0; k < 6; k++) {
            ref_waves_ctx c;
            ref_waves_ctx_begin(&c, &w, 0.4 + 1.7 * k);
            CHECK(c.fold < 1 && isfinite(c.world_slope));
            for (int r = 0; r < 12; r++) {
                double x0 = 100 * lcg01(&st) - 50, z0 = 100 * lcg01(&st) - 50;
                double reach = 0.02 * pow(250.0, (r % 6) / 5.0);   /* 2 cm .. 5 m */
                double uv[2], h0;
                CHECK_EQ(ref_waves_ctx_rest_point(&c, x0, z0, NULL, uv, &h0), 0);
                double bn = ref_waves_ctx_world_slope_near(&c, x0, z0, uv, reach);
                double bb = ref_waves_ctx_world_slope_box(&c, x0 - reach, z0 - reach, x0 + reach, z0 + reach);
                CHECK(bn <= bb && bb <= c.world_slope);
                for (int p = 0; p < 40; p++) {
                    /* a pair in the disc (for the box, in the square) */
                    double a = 2 * M_PI * lcg01(&st), q = reach * sqrt(lcg01(&st));
                    double x1 = x0 + q * cos(a), z1 = z0 + q * sin(a);
                    double x2 = x0 + reach * (2 * lcg01(&st) - 1), z2 = z0 + reach * (2 * lcg01(&st) - 1);
                    double h1 = ref_waves_ctx_height(&c, x1, z1), h2 = ref_waves_ctx_height(&c, x2, z2);
                    double e = 1e-9;   /* the inversions' tolerance, times the slope */
                    double rn = fabs(h1 - h0) / (bn * hypot(x1 - x0, z1 - z0) + e);
                    double rb = fabs(h2 - h1) / (bb * hypot(x2 - x1, z2 - z1) + e);
                    worst = fmax(worst, fmax(rn, rb));
                    ratio_near = fmax(ratio_near, fabs(h1 - h0) / (bn * hypot(x1 - x0, z1 - z0) + 1e-300));
                    ratio_box = fmax(ratio_box, fabs(h2 - h1) / (bb * hypot(x2 - x1, z2 - z1) + 1e-300));
                    if (g == 0) {   /* J = I + the ocean's bilinear derivative */
                        double u1[2], dd[2], jac[4];
                        ref_waves_ctx_rest_point(&c, x1, z1, NULL, u1, NULL);
                        ref_ocean_snapshot_map(c.ocean, u1[0], u1[1], dd, jac, NULL);
                        double J[4] = { 1 + jac[0], jac[1], jac[2], 1 + jac[3] };
                        double P = J[0] * J[0] + J[2] * J[2], Q = J[1] * J[1] + J[3] * J[3], R = J[0] * J[1] + J[2] * J[3];
                        double smin = sqrt(fmax(0, 0.5 * (P + Q) - sqrt(0.25 * (P - Q) * (P - Q) + R * R)));
                        worst_sv = fmax(worst_sv, (1 - c.fold) / smin);
                    }
                    n++;
                }
            }
            ref_waves_ctx_end(&c);
        }
        ref_waves_release(&w);
    }
    CHECK_MSG(worst <= 1 && worst_sv <= 1, "%d pairs: |dH| / (bound |dX|) up to %g, (1 - fold) / sigma_min %g",
              n, worst, worst_sv);
    /* not loose by much: the pairs reach a fair part of the bounds */
    CHECK_MSG(ratio_near > 0.2 && ratio_box > 0.1, "near %g, box %g", ratio_near, ratio_box);
    printf("  world slope regions: %d pairs, |dH| / (bound |dX|) max: near %.3f, box %.3f; (1 - fold) / sigma_min max %.3f\n",
           n, ratio_near, ratio_box, worst_sv);
}

static void test_ocean_folding(void) {
    ref_waves_desc d = ocean_desc(15, 5);
    d.ocean.amplitude = 1.5;
    ref_waves w;
    if (init(&w, &d)) return;
    double t = 0.5, wsb;
    ref_waves_bounds_at(&w, t, NULL, NULL, &wsb);
    CHECK(isinf(wsb) && isinf(w.world_slope_bound));
    uint64_t st = 3;
    int nan = 0, folds = 0;
    for (int i = 0; i < 400; i++) {
        double x = 128 * lcg01(&st), z = 128 * lcg01(&st);
        ref_waves_point p;
        ref_waves_eval(&w, x, z, t, &p);
        for (int k = 0; k < 3; k++) CHECK(isfinite(p.pos[k]) && isfinite(p.normal[k]));
        folds += p.jacobian < 0;
        double h = ref_waves_height(&w, x, z, t), uv[2], h2;
        int rc = ref_waves_rest_point(&w, x, z, t, NULL, uv, &h2);
        if (isnan(h)) { nan++; CHECK_EQ(rc, -1); }
        else CHECK(rc == 0 && isfinite(h) && h == h2);
    }
    CHECK_MSG(folds > 0, "no fold at this setting");
    (void)nan;
    ref_waves_release(&w);
}

int main(void) {
    RUN(test_defaults_and_errors);
    RUN(test_gerstner_matches_gems_eq9);
    RUN(test_gerstner_q0_is_sum_of_sines);
    RUN(test_normals_vs_finite_differences);
    RUN(test_approx_normal);
    RUN(test_loop_free_up_to_q1);
    RUN(test_newton_inversion);
    RUN(test_noise);
    RUN(test_uniforms);
    RUN(test_ocean);
    RUN(test_ocean_folding);
    RUN(test_world_slope_regions);
    RUN(test_ctx_fast_path);
    return check_summary();
}
