/* test_ref_ocean: the reference's spectrum ocean (ref_ocean) against
 * independent truth: a direct sum of every wave (no FFT), finite
 * differences of that continuous sum, the spectra's formulas written out
 * again here, the statistics of random amplitudes, and the folding
 * criterion J < 0 against the displaced map itself. */
#include "check.h"
#include "ref_ocean.h"

#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define G 9.81

static ref_ocean *make(ref_ocean_desc d) {
    char err[256];
    ref_ocean *o = ref_ocean_create(&d, err, sizeof err);
    CHECK_MSG(o != NULL, "%s", err);
    return o;
}

static double field(const ref_ocean_sample *s, int q) {
    const double v[8] = { s->h, s->dx, s->dz, s->dxz, s->hx, s->hz, s->dxx, s->dzz };
    return v[q];
}

static const char *fname[8] = { "h", "Dx", "Dz", "Dxz", "hx", "hz", "Dxx", "Dzz" };

/* rms over the nodes of cascade 0..nc-1, per field (summed in quadrature) */
static void field_rms(const ref_ocean *o, double t, double rms[8]) {
    const ref_ocean_desc *d = ref_ocean_get_desc(o);
    size_t nn = (size_t)d->res * d->res;
    double *a = malloc(sizeof(double) * 4 * nn), *b = malloc(sizeof(double) * 4 * nn);
    memset(rms, 0, sizeof(double) * 8);
    for (int c = 0; c < d->cascades; c++) {
        ref_ocean_frame(o, c, t, a, b);
        for (size_t i = 0; i < nn; i++)
            for (int q = 0; q < 4; q++) {
                rms[q] += a[4 * i + q] * a[4 * i + q] / nn;
                rms[4 + q] += b[4 * i + q] * b[4 * i + q] / nn;
            }
    }
    for (int q = 0; q < 8; q++) rms[q] = sqrt(rms[q]);
    free(a);
    free(b);
}

/* Tiles 64, 16, 4 m at N = 64: every node of cascade 0 (integer metres) is
 * a node of the finer ones, so there sample_at is a plain sum of nodes. */
static ref_ocean_desc small_desc(ref_spectrum_kind kind, int cascades) {
    ref_ocean_desc d = { .spectrum = kind, .wind_speed = 7, .wind_angle_deg = 30, .res = 64,
                         .cascades = cascades, .tile = { 64, 16, 4 }, .choppiness = 0.8,
                         .depth = kind == REF_SPECTRUM_TMA ? 6 : 0, .seed = 11 };
    return d;
}

/* FFT frame vs the direct sum at nodes. Rounding: the FFT's error is about
 * eps log2(N) times the field's rms, the direct sum's about eps sqrt(terms)
 * times it (N^2 random-phase terms a cascade, phases up to ~200 rad); both
 * are far below 1e-12 rms. */
static void test_fft_vs_direct(void) {
    ref_spectrum_kind kinds[3] = { REF_SPECTRUM_PHILLIPS, REF_SPECTRUM_JONSWAP, REF_SPECTRUM_TMA };
    double times[3] = { 0.0, 1.7, 123.25 };
    for (int ki = 0; ki < 3; ki++)
        for (int nc = 1; nc <= 3; nc += 2) {
            ref_ocean *o = make(small_desc(kinds[ki], nc));
            if (!o) return;
            for (int ti = 0; ti < 3; ti++) {
                double t = times[ti], rms[8], worst[8] = { 0 };
                field_rms(o, t, rms);
                for (int p = 0; p < 12; p++) {
                    double u = (p * 37) % 64, v = (p * 23 + 5) % 64;
                    if (p == 11) { u = -128 + 3; v = 64 * 5 + 9; }   /* another period */
                    ref_ocean_sample f, s;
                    ref_ocean_sample_at(o, u, v, t, &f);
                    ref_ocean_direct_sum(o, u, v, t, &s);
                    for (int q = 0; q < 8; q++)
                        worst[q] = fmax(worst[q], fabs(field(&f, q) - field(&s, q)) / rms[q]);
                }
                for (int q = 0; q < 8; q++)
                    CHECK_MSG(rms[q] > 0 && worst[q] < 1e-12, "spectrum %d, %d cascades, t %g: %s off by %g rms",
                              kinds[ki], nc, t, fname[q], worst[q]);
            }
            ref_ocean_destroy(o);
        }
}

/* Between nodes: the bilinear blend of the four nodes (one cascade, read
 * from the frame); periodic over the tile. */
static void test_bilinear_periodic(void) {
    ref_ocean *o = make(small_desc(REF_SPECTRUM_JONSWAP, 1));
    if (!o) return;
    int N = 64;
    double L = 64, tx = L / N, t = 3.5;
    double *a = malloc(sizeof(double) * 4 * N * N), *b = malloc(sizeof(double) * 4 * N * N);
    ref_ocean_frame(o, 0, t, a, b);
    double rms[8];
    field_rms(o, t, rms);
    uint64_t st = 99;
    for (int p = 0; p < 200; p++) {
        st = st * 6364136223846793005ULL + 1442695040888963407ULL;
        double u = (double)(st >> 11) * 0x1.0p-53 * 3 * L - L;
        st = st * 6364136223846793005ULL + 1442695040888963407ULL;
        double v = (double)(st >> 11) * 0x1.0p-53 * 3 * L - L;
        double fu = u / tx, fv = v / tx;
        int i = (int)floor(fu), j = (int)floor(fv);
        double x = fu - i, z = fv - j;
        int i0 = ((i % N) + N) % N, j0 = ((j % N) + N) % N, i1 = (i0 + 1) % N, j1 = (j0 + 1) % N;
        ref_ocean_sample s, s2;
        ref_ocean_sample_at(o, u, v, t, &s);
        ref_ocean_sample_at(o, u + L, v - 2 * L, t, &s2);
        for (int q = 0; q < 8; q++) {
            const double *F = q < 4 ? a : b;
            int c = q & 3;
            double want = (1 - x) * (1 - z) * F[4 * (j0 * N + i0) + c] + x * (1 - z) * F[4 * (j0 * N + i1) + c] +
                          (1 - x) * z * F[4 * (j1 * N + i0) + c] + x * z * F[4 * (j1 * N + i1) + c];
            /* the blend's weights from (u, v) differ by rounding of u / texel */
            CHECK_MSG(fabs(field(&s, q) - want) <= 1e-12 * rms[q], "%s at (%g, %g): %g vs %g", fname[q], u, v,
                      field(&s, q), want);
            CHECK_MSG(fabs(field(&s2, q) - field(&s, q)) <= 1e-11 * rms[q], "%s not periodic", fname[q]);
        }
    }
    free(a);
    free(b);
    ref_ocean_destroy(o);
}

/* The slope and D-derivative fields are the derivatives of h, Dx, Dz:
 * central differences of the continuous direct sum with step e = 1e-4
 * texel: truncation (k e)^2 / 6 < 2e-8 of the derivative's scale at the
 * Nyquist wavenumber, rounding 1e-14 rms / e; 1e-6 of the rms covers both. */
static void test_derivatives_fd(void) {
    ref_spectrum_kind kinds[2] = { REF_SPECTRUM_PHILLIPS, REF_SPECTRUM_JONSWAP };
    for (int ki = 0; ki < 2; ki++) {
        ref_ocean *o = make(small_desc(kinds[ki], 3));
        if (!o) return;
        double t = 2.25, rms[8];
        field_rms(o, t, rms);
        double e = 1e-4 * 4.0 / 64;
        for (int p = 0; p < 4; p++) {
            double u = 3.3 + 7.1 * p, v = -2.9 + 4.3 * p;
            ref_ocean_sample c, up, um, vp, vm;
            ref_ocean_direct_sum(o, u, v, t, &c);
            ref_ocean_direct_sum(o, u + e, v, t, &up);
            ref_ocean_direct_sum(o, u - e, v, t, &um);
            ref_ocean_direct_sum(o, u, v + e, t, &vp);
            ref_ocean_direct_sum(o, u, v - e, t, &vm);
            double fd[5][2] = {
                { (up.h - um.h) / (2 * e), c.hx },
                { (vp.h - vm.h) / (2 * e), c.hz },
                { (up.dx - um.dx) / (2 * e), c.dxx },
                { (vp.dx - vm.dx) / (2 * e), c.dxz },
                { (vp.dz - vm.dz) / (2 * e), c.dzz },
            };
            double scale[5] = { rms[4], rms[5], rms[6], rms[3], rms[7] };
            for (int q = 0; q < 5; q++)
                CHECK_MSG(fabs(fd[q][0] - fd[q][1]) <= 1e-6 * scale[q], "spectrum %d derivative %d: fd %g field %g",
                          kinds[ki], q, fd[q][0], fd[q][1]);
            double dzdu = (up.dz - um.dz) / (2 * e);
            CHECK_LE(fabs(dzdu - c.dxz), 1e-6 * rms[3]);    /* d(Dz)/du = d(Dx)/dv */
        }
        ref_ocean_destroy(o);
    }
}

/* JONSWAP S(omega), written out again (Hasselmann 1973) */
static double jonswap(double w, double U, double F) {
    double alpha = 0.076 * pow(U * U / (F * G), 0.22), wp = 22 * cbrt(G * G / (U * F));
    double sigma = w <= wp ? 0.07 : 0.09;
    double r = exp(-(w - wp) * (w - wp) / (2 * sigma * sigma * wp * wp));
    return alpha * G * G / pow(w, 5) * exp(-1.25 * pow(wp / w, 4)) * pow(3.3, r);
}

/* int S(k, theta) k dtheta at |k| (trapezoid on 4096 angles: spectrally
 * accurate for the smooth spreadings) */
static double ring(const ref_ocean *o, double k) {
    double s = 0;
    for (int j = 0; j < 4096; j++) {
        double th = 2 * M_PI * j / 4096;
        s += ref_ocean_spectrum(o, k * cos(th), k * sin(th));
    }
    return s * 2 * M_PI / 4096 * k;
}

/* S(k) k dtheta integrated over the ring is S(omega) d omega / dk when the
 * spreading integrates to 1 and the Jacobian is right; JONSWAP's maximum
 * at omega_p; TMA -> JONSWAP with depth; Phillips' A and |cos|^2. */
static void test_spectra(void) {
    double U = 9, F = 50e3, wp = 22 * cbrt(G * G / (U * F));
    for (int sp = 0; sp < 2; sp++) {
        ref_ocean *o = make((ref_ocean_desc){ .spectrum = REF_SPECTRUM_JONSWAP, .wind_speed = U, .fetch = F,
                                              .wind_angle_deg = 40, .spreading = sp ? 4.0 : 0.0 });
        if (!o) return;
        double best = 0, wbest = 0;
        for (int i = 1; i <= 400; i++) {
            /* off omega_p itself, where Hasselmann's s jumps (6.97 / 9.77)
             * and the ring's points would straddle it by rounding */
            double w = wp * (0.5 + (i + 0.5) * 0.005), k = w * w / G;
            double sw = ring(o, k) / (G / (2 * w));         /* S(omega) = E(k) / (d omega / dk) */
            CHECK_MSG(fabs(sw - jonswap(w, U, F)) <= 1e-9 * jonswap(wp, U, F), "spreading %d, omega %g: %g vs %g",
                      sp, w, sw, jonswap(w, U, F));
            if (sw > best) { best = sw; wbest = w; }
        }
        CHECK_MSG(fabs(wbest - wp) <= 0.005 * wp, "JONSWAP peak at %g, omega_p %g", wbest, wp);
        /* downwind holds the energy */
        double k = wp * wp / G, a = 40 * M_PI / 180;
        CHECK_GT(ref_ocean_spectrum(o, k * cos(a), k * sin(a)), 10 * ref_ocean_spectrum(o, -k * cos(a), -k * sin(a)));
        ref_ocean_destroy(o);
    }
    /* TMA: the depth factor -> 1 and tanh -> 1 as the depth grows */
    ref_ocean *j = make((ref_ocean_desc){ .spectrum = REF_SPECTRUM_JONSWAP, .wind_speed = U, .fetch = F });
    ref_ocean *deep = make((ref_ocean_desc){ .spectrum = REF_SPECTRUM_TMA, .wind_speed = U, .fetch = F, .depth = 1e4 });
    ref_ocean *shallow = make((ref_ocean_desc){ .spectrum = REF_SPECTRUM_TMA, .wind_speed = U, .fetch = F, .depth = 3 });
    if (!j || !deep || !shallow) return;
    for (int i = 1; i <= 20; i++) {
        double k = 0.02 * i * i;
        double sj = ref_ocean_spectrum(j, k, 0), sd = ref_ocean_spectrum(deep, k, 0);
        CHECK_MSG(fabs(sd - sj) <= 1e-9 * sj, "TMA deep %g vs JONSWAP %g at k %g", sd, sj, k);
        /* TMA written out: JONSWAP(omega) Phi(omega sqrt(h / g)) (d omega / dk) / k
         * with omega = sqrt(g k tanh(k h)) */
        double h = 3, th = tanh(k * h), w = sqrt(G * k * th), wh = w * sqrt(h / G);
        double phi = wh <= 1 ? 0.5 * wh * wh : wh < 2 ? 1 - 0.5 * (2 - wh) * (2 - wh) : 1;
        double dwdk = G * (th + k * h * (1 - th * th)) / (2 * w);
        double want = jonswap(w, U, F) * phi * dwdk;
        /* Hasselmann's s(omega) falls below 1 far from the peak (both
         * sides), where the ring's trapezoid rule meets the |theta - pi|^(2s)
         * kink: an error O(h^(2s+1)), 1e-4 at most here */
        double tol = 1e-4;
        CHECK_MSG(fabs(ring(shallow, k) - want) <= tol * want, "TMA at k %g: %g vs %g", k,
                  ring(shallow, k), want);
    }
    ref_ocean_destroy(j);
    ref_ocean_destroy(deep);
    ref_ocean_destroy(shallow);
    /* Phillips: A exp(-1/(kL)^2) / k^4 |k^.w^|^2 exp(-k^2 l^2), A = 0.21^2 / (8 pi),
     * so the ring holds A exp(-1/(kL)^2) exp(-k^2 l^2) pi / k^3 */
    ref_ocean *p = make((ref_ocean_desc){ .spectrum = REF_SPECTRUM_PHILLIPS, .wind_speed = U });
    if (!p) return;
    double L = U * U / G, l = 1e-3 * L, A = 0.21 * 0.21 / (8 * M_PI);
    for (int i = 1; i <= 20; i++) {
        double k = 0.05 * i * i;
        double want = A * exp(-1 / (k * L * k * L)) * exp(-k * k * l * l) * M_PI / (k * k * k);
        CHECK_NEAR(ring(p, k), want, 1e-12 * want);
    }
    ref_ocean_destroy(p);
}

/* The energy: the random amplitudes hold sum S dk^2 on the grid within
 * their statistics (each 2 |h0|^2 term is S dk^2 chi^2_2 / 2: mean S dk^2,
 * sd S dk^2, so the sum's sd is sqrt(sum (S dk^2)^2)); the grid sum is a
 * midpoint rule of the integral (33 steps a peak wavenumber here: within
 * 2%); the nodes' mean of h^2 is the variance plus cross terms of zero
 * mean and about the same sd (Parseval). */
static void test_energy(void) {
    ref_spectrum_kind kinds[3] = { REF_SPECTRUM_PHILLIPS, REF_SPECTRUM_JONSWAP, REF_SPECTRUM_TMA };
    for (int ki = 0; ki < 3; ki++) {
        int N = 256;
        double Lt = kinds[ki] == REF_SPECTRUM_PHILLIPS ? 800 : 2000;
        ref_ocean *o = make((ref_ocean_desc){ .spectrum = kinds[ki], .wind_speed = 10, .res = N, .tile = { Lt },
                                              .depth = kinds[ki] == REF_SPECTRUM_TMA ? 20 : 0, .seed = 5 });
        if (!o) return;
        double dk = 2 * M_PI / Lt, sum = 0, sum2 = 0;
        for (int n = 0; n < N; n++)
            for (int m = 0; m < N; m++) {
                if (m == N / 2 || n == N / 2) continue;
                double kx = (m < N / 2 ? m : m - N) * dk, kz = (n < N / 2 ? n : n - N) * dk, k = hypot(kx, kz);
                if (k == 0 || k >= N / 2 * dk) continue;
                double e = ref_ocean_spectrum(o, kx, kz) * dk * dk;
                sum += e;
                sum2 += e * e;
            }
        double sd = sqrt(sum2), var = ref_ocean_variance(o), cont = ref_ocean_spectrum_variance(o);
        CHECK_MSG(fabs(var - sum) <= 5 * sd, "spectrum %d: variance %g, expected %g +- %g", kinds[ki], var, sum, sd);
        CHECK_MSG(fabs(sum - cont) <= 0.02 * cont, "spectrum %d: grid %g, integral %g", kinds[ki], sum, cont);
        CHECK_MSG(sd < 0.05 * sum, "spectrum %d: too few modes for the test (sd %g of %g)", kinds[ki], sd, sum);
        double *a = malloc(sizeof(double) * 4 * N * N), *b = malloc(sizeof(double) * 4 * N * N);
        for (int ti = 0; ti < 2; ti++) {
            ref_ocean_frame(o, 0, ti * 7.5, a, b);
            double m2 = 0, mean = 0;
            for (int i = 0; i < N * N; i++) { m2 += a[4 * i] * a[4 * i]; mean += a[4 * i]; }
            m2 /= N * N;
            mean /= N * N;
            CHECK_LT(fabs(mean), 1e-12 * sqrt(m2));           /* no k = 0 term */
            CHECK_MSG(fabs(m2 - var) <= 6 * sd, "spectrum %d: mean h^2 %g, variance %g +- %g", kinds[ki], m2, var, sd);
        }
        free(a);
        free(b);
        ref_ocean_destroy(o);
    }
    /* Phillips' sea state: Hs = 4 sqrt(variance) near the Pierson-Moskowitz
     * 0.21 U^2 / g (the damping and the bands take a little) */
    ref_ocean *o = make((ref_ocean_desc){ .spectrum = REF_SPECTRUM_PHILLIPS, .wind_speed = 10, .res = 256,
                                          .cascades = 3, .tile = { 1000, 100, 10 } });
    if (!o) return;
    double hs = 4 * sqrt(ref_ocean_spectrum_variance(o));
    CHECK_MSG(hs > 0.8 * 0.21 * 100 / G && hs < 1.0 * 0.21 * 100 / G, "Phillips Hs %g", hs);
    ref_ocean_destroy(o);
}

/* A strongly choppy sea folds: nodes with J = (1 + Dxx)(1 + Dzz) - Dxz^2 < 0,
 * and there the continuous displaced map x + Dx, z + Dz really reverses
 * orientation (its finite-difference Jacobian is negative). */
static void test_folding(void) {
    ref_ocean_desc d = small_desc(REF_SPECTRUM_JONSWAP, 1);
    d.choppiness = 4;
    d.wind_speed = 15;
    d.amplitude = 1.5;
    ref_ocean *o = make(d);
    if (!o) return;
    int N = 64;
    double tx = 64.0 / N, t = 1.0;
    double *a = malloc(sizeof(double) * 4 * N * N), *b = malloc(sizeof(double) * 4 * N * N);
    ref_ocean_frame(o, 0, t, a, b);
    int folds = 0, checked = 0, flat1d = 0;
    for (int i = 0; i < N * N && checked < 20; i++) {
        double dxx = b[4 * i + 2], dzz = b[4 * i + 3], dxz = a[4 * i + 3];
        double J = (1 + dxx) * (1 + dzz) - dxz * dxz;
        if (J >= 0) continue;
        folds++;
        if (i % 3) continue;                 /* a spread of them */
        checked++;
        double u = (i % N) * tx, v = (i / N) * tx, e = 1e-5;
        ref_ocean_sample up, um, vp, vm;
        ref_ocean_direct_sum(o, u + e, v, t, &up);
        ref_ocean_direct_sum(o, u - e, v, t, &um);
        ref_ocean_direct_sum(o, u, v + e, t, &vp);
        ref_ocean_direct_sum(o, u, v - e, t, &vm);
        double xu = (2 * e + up.dx - um.dx) / (2 * e), xv = (vp.dx - vm.dx) / (2 * e);
        double zu = (up.dz - um.dz) / (2 * e), zv = (2 * e + vp.dz - vm.dz) / (2 * e);
        double Jfd = xu * zv - xv * zu;
        CHECK_MSG(Jfd < 0 && fabs(Jfd - J) < 1e-5 * (1 + fabs(J)), "node %d: J %g, fd %g", i, J, Jfd);
        if (1 + dxx < 0) {                   /* along u alone: x(u + e) < x(u - e) */
            flat1d++;
            CHECK_LT(u + e + up.dx, u - e + um.dx);
        }
    }
    CHECK_MSG(folds > 0 && checked > 0, "no fold found (%d)", folds);
    ref_ocean_bounds bd;
    ref_ocean_bounds_at(o, t, &bd);
    CHECK_GE(bd.chop, 1);
    free(a);
    free(b);
    ref_ocean_destroy(o);
}

/* The frame's bounds hold at random points and are not loose; the any-time
 * bounds hold the frame's. */
static void test_bounds(void) {
    ref_ocean *o = make(small_desc(REF_SPECTRUM_PHILLIPS, 3));
    if (!o) return;
    double t = 0.75;
    ref_ocean_bounds b, any;
    ref_ocean_bounds_at(o, t, &b);
    ref_ocean_bounds_any(o, &any);
    CHECK(b.height <= any.height && b.slope <= any.slope && b.chop <= any.chop);
    double hmax = 0, gmax = 0, e = 1e-6;
    for (int p = 0; p < 20000; p++) {
        double u = fmod(p * 0.6180339887 * 13.1, 64), v = fmod(p * 0.41421356 * 7.3, 64);
        ref_ocean_sample s, su, sv;
        ref_ocean_sample_at(o, u, v, t, &s);
        ref_ocean_sample_at(o, u + e, v, t, &su);
        ref_ocean_sample_at(o, u, v + e, t, &sv);
        hmax = fmax(hmax, fabs(s.h));
        gmax = fmax(gmax, hypot(su.h - s.h, sv.h - s.h) / e);
    }
    CHECK_MSG(hmax <= b.height && hmax > 0.3 * b.height, "height %g, bound %g", hmax, b.height);
    CHECK_MSG(gmax <= b.slope * (1 + 1e-6) && gmax > 0.2 * b.slope, "slope %g, bound %g", gmax, b.slope);
    CHECK_EQ(ref_ocean_min_wavelength(o), 2 * 4.0 / 64);
    ref_ocean_destroy(o);
}

/* The spectral norm of [a b; c d], by the eigenvalues of M^T M. */
static double norm2(const double m[4]) {
    double p = m[0] * m[0] + m[2] * m[2], q = m[1] * m[1] + m[3] * m[3], r = m[0] * m[1] + m[2] * m[3];
    return sqrt(0.5 * (p + q) + sqrt(0.25 * (p - q) * (p - q) + r * r));
}

/* The chop bound is the exact max of the bilinear map's derivative's
 * spectral norm (one cascade: attained just inside a cell's corner), and
 * at random points and times, in random boxes, the derivative and the
 * bilinear height's gradient (finite differences inside a cell) stay
 * within the frame's and the box's bounds; the displacement within its
 * range. */
static void test_bounds_regions(void) {
    ref_ocean_desc d1 = small_desc(REF_SPECTRUM_JONSWAP, 1);
    d1.choppiness = 1.2;
    ref_ocean *o1 = make(d1);
    ref_ocean *o3 = make(small_desc(REF_SPECTRUM_PHILLIPS, 3));
    if (!o1 || !o3) return;
    /* one cascade: the max over every cell's four inner corners is the bound */
    const ref_ocean_snapshot *s1 = ref_ocean_snapshot_acquire(o1, 1.5);
    ref_ocean_bounds b1;
    ref_ocean_snapshot_bounds(s1, &b1);
    double cmax = 0, e = 1e-9;
    for (int j = 0; j < 64; j++)
        for (int i = 0; i < 64; i++)
            for (int k = 0; k < 4; k++) {
                double dd[2], jac[4];
                ref_ocean_snapshot_map(s1, i + ((k & 1) ? 1 - e : e), j + ((k & 2) ? 1 - e : e), dd, jac, NULL);
                cmax = fmax(cmax, norm2(jac));
            }
    CHECK_MSG(cmax <= b1.chop && cmax > b1.chop * (1 - 1e-7), "corner max %.12g, chop %.12g", cmax, b1.chop);
    ref_ocean_snapshot_release(s1);

    uint64_t st = 5;
    int bad = 0, n = 0;
    double worst_g = 0, worst_c = 0, worst_bg = 0, worst_bc = 0;
    for (int k = 0; k < 12; k++) {
        double t = 0.37 + 2.9 * k;
        const ref_ocean_snapshot *s = ref_ocean_snapshot_acquire(o3, t);
        ref_ocean_bounds b;
        ref_ocean_snapshot_bounds(s, &b);
        double lo[2], hi[2];
        ref_ocean_snapshot_disp_range(s, lo, hi);
        for (int r = 0; r < 40; r++) {
            st = st * 6364136223846793005ull + 1442695040888963407ull;
            double u0 = (double)(st >> 11) * 0x1.0p-53 * 200 - 100;
            st = st * 6364136223846793005ull + 1442695040888963407ull;
            double v0 = (double)(st >> 11) * 0x1.0p-53 * 200 - 100;
            double w = 0.05 * pow(400.0, (r % 8) / 7.0);   /* boxes 5 cm .. 20 m */
            double bs, bc;
            ref_ocean_snapshot_box_bounds(s, u0, v0, u0 + w, v0 + 0.7 * w, &bs, &bc);
            bad += !(bs <= b.slope * (1 + 1e-6) && bc <= b.chop * (1 + 1e-6));
            for (int p = 0; p < 50; p++) {
                st = st * 6364136223846793005ull + 1442695040888963407ull;
                double u = u0 + w * (double)(st >> 11) * 0x1.0p-53;
                st = st * 6364136223846793005ull + 1442695040888963407ull;
                double v = v0 + 0.7 * w * (double)(st >> 11) * 0x1.0p-53;
                double dd[2], jac[4], h0;
                ref_ocean_snapshot_map(s, u, v, dd, jac, &h0);
                /* one-sided differences, a step well inside the finest texel */
                double h = 1e-7, su = ref_ocean_snapshot_height(s, u + h, v), sv = ref_ocean_snapshot_height(s, u, v + h);
                double g = hypot(su - h0, sv - h0) / h, c = norm2(jac);
                worst_g = fmax(worst_g, g / b.slope);
                worst_c = fmax(worst_c, c / b.chop);
                worst_bg = fmax(worst_bg, g / bs);
                worst_bc = fmax(worst_bc, c / bc);
                bad += !(dd[0] >= lo[0] - 1e-12 && dd[0] <= hi[0] + 1e-12 && dd[1] >= lo[1] - 1e-12 &&
                         dd[1] <= hi[1] + 1e-12);
                n++;
            }
        }
        ref_ocean_snapshot_release(s);
    }
    CHECK_MSG(bad == 0, "%d of %d outside", bad, n);
    /* the gradient by differences: to 1e-6 of the bound (their rounding) */
    CHECK_MSG(worst_g <= 1 + 1e-6 && worst_c <= 1 && worst_bg <= 1 + 1e-6 && worst_bc <= 1,
              "|grad h| / bound %.9g, ||A|| / chop %.9g, in boxes %.9g %.9g", worst_g, worst_c, worst_bg, worst_bc);
    /* and the boxes' bounds are not loose: the sampled maxima reach a fair part */
    CHECK_MSG(worst_bg > 0.5 && worst_bc > 0.5, "in boxes %g %g", worst_bg, worst_bc);
    ref_ocean_destroy(o1);
    ref_ocean_destroy(o3);
}

static void test_determinism_and_errors(void) {
    ref_ocean_desc d = small_desc(REF_SPECTRUM_JONSWAP, 2);
    ref_ocean *a = make(d), *b = make(d);
    d.seed = 12;
    ref_ocean *c = make(d);
    if (!a || !b || !c) return;
    size_t nn = 64 * 64;
    float *h0a = malloc(16 * nn), *h0b = malloc(16 * nn), *wa = malloc(4 * nn), *wb = malloc(4 * nn);
    for (int k = 0; k < 2; k++) {
        ref_ocean_gpu_spectrum(a, k, h0a, wa);
        ref_ocean_gpu_spectrum(b, k, h0b, wb);
        CHECK(memcmp(h0a, h0b, 16 * nn) == 0 && memcmp(wa, wb, 4 * nn) == 0);
        ref_ocean_gpu_spectrum(c, k, h0b, wb);
        CHECK(memcmp(h0a, h0b, 16 * nn) != 0 && memcmp(wa, wb, 4 * nn) == 0);
        /* the GL's pair: texel (m, n) holds conj(h0(-k)) next to h0(k) */
        int m = 5, n = 60, mi = 64 - m, ni = 64 - n;
        CHECK(h0a[4 * (n * 64 + m) + 2] == h0a[4 * (ni * 64 + mi)] &&
              h0a[4 * (n * 64 + m) + 3] == -h0a[4 * (ni * 64 + mi) + 1]);
        CHECK(h0a[4 * (32 * 64 + 3)] == 0 && h0a[4 * (3 * 64 + 32) + 1] == 0);   /* Nyquist */
        CHECK_LT(fabs(wa[n * 64 + m] - sqrt(G * hypot(m, 64 - n) * 2 * M_PI / (k ? 16 : 64))), 1e-5);
    }
    free(h0a); free(h0b); free(wa); free(wb);
    ref_ocean_destroy(a);
    ref_ocean_destroy(b);
    ref_ocean_destroy(c);
    /* a fixed number from seed 11: the same on every machine */
    ref_ocean *e = make(small_desc(REF_SPECTRUM_PHILLIPS, 1));
    ref_ocean_sample s;
    ref_ocean_sample_at(e, 0, 0, 0, &s);
    ref_ocean_sample s2;
    ref_ocean *e2 = make(small_desc(REF_SPECTRUM_PHILLIPS, 1));
    ref_ocean_sample_at(e2, 0, 0, 0, &s2);
    CHECK(s.h == s2.h && s.dx == s2.dx);
    ref_ocean_destroy(e);
    ref_ocean_destroy(e2);

    char err[256];
    ref_ocean_desc bad = small_desc(REF_SPECTRUM_JONSWAP, 1);
    bad.res = 100;
    CHECK_EQ(ref_ocean_create(&bad, err, sizeof err), NULL);
    CHECK_STR_CONTAINS(err, "power of two");
    bad = small_desc(REF_SPECTRUM_JONSWAP, 4);
    CHECK_EQ(ref_ocean_create(&bad, err, sizeof err), NULL);
    CHECK_STR_CONTAINS(err, "cascades");
    bad = small_desc(REF_SPECTRUM_JONSWAP, 1);
    bad.wind_speed = -3;
    CHECK_EQ(ref_ocean_create(&bad, err, sizeof err), NULL);
    CHECK_STR_CONTAINS(err, "wind");
    bad = small_desc(REF_SPECTRUM_JONSWAP, 2);
    bad.tile[1] = 100;
    CHECK_EQ(ref_ocean_create(&bad, err, sizeof err), NULL);
    CHECK_STR_CONTAINS(err, "decrease");
    bad = (ref_ocean_desc){ 0 };
    CHECK_EQ(ref_ocean_create(&bad, err, sizeof err), NULL);
    bad = (ref_ocean_desc){ .spectrum = REF_SPECTRUM_JONSWAP, .choppiness = NAN };
    CHECK_EQ(ref_ocean_create(&bad, err, sizeof err), NULL);
    /* defaults, in one place */
    ref_ocean_desc def = { .spectrum = REF_SPECTRUM_PHILLIPS, .cascades = 3 };
    CHECK_EQ(ref_ocean_desc_resolve(&def, err, sizeof err), 0);
    CHECK(def.res == 128 && def.wind_speed == 10 && def.fetch == 100e3 && def.spreading == 2 && def.amplitude == 1);
    CHECK(def.tile[0] == 250 && def.tile[1] == 37 && def.tile[2] == 5.3);
    ref_ocean_desc one = { .spectrum = REF_SPECTRUM_JONSWAP, .cascades = 3, .tile = { 500 } };
    CHECK_EQ(ref_ocean_desc_resolve(&one, err, sizeof err), 0);
    CHECK_NEAR(one.tile[1], 74, 1e-12);
    CHECK_NEAR(one.tile[2], 10.6, 1e-12);
    CHECK_EQ(one.spreading, 0);
}

/* Threads sampling more distinct times than the cache holds get what one
 * thread gets. */
typedef struct job { const ref_ocean *o; double out[6]; } job;

static void *sampler(void *arg) {
    job *j = arg;
    for (int r = 0; r < 3; r++)
        for (int i = 0; i < 6; i++) {
            ref_ocean_sample s;
            ref_ocean_sample_at(j->o, 1.3 * i, 2.1, 0.5 * i, &s);
            j->out[i] = s.h + s.dxx;
        }
    return NULL;
}

static void test_threads(void) {
    ref_ocean *o = make(small_desc(REF_SPECTRUM_JONSWAP, 3));
    if (!o) return;
    double want[6];
    for (int i = 0; i < 6; i++) {
        ref_ocean_sample s;
        ref_ocean_direct_sum(o, 1.3 * i, 2.1, 0.5 * i, &s);
        ref_ocean_sample_at(o, 1.3 * i, 2.1, 0.5 * i, &s);
        want[i] = s.h + s.dxx;
    }
    pthread_t th[4];
    job jobs[4];
    for (int k = 0; k < 4; k++) { jobs[k].o = o; pthread_create(&th[k], NULL, sampler, &jobs[k]); }
    for (int k = 0; k < 4; k++) pthread_join(th[k], NULL);
    for (int k = 0; k < 4; k++)
        for (int i = 0; i < 6; i++) CHECK_EQ(jobs[k].out[i], want[i]);
    ref_ocean_destroy(o);
}

/* The snapshot (the fast path a march takes: one lookup, packed nodes)
 * against the per-call queries and against the bilinear interpolation of
 * ref_ocean_frame's nodes written out here: the same numbers bit for bit
 * where the formulas are the same, to rounding against the written-out
 * one; and a held snapshot stays put while other times push the cache's
 * slots round. */
static void test_snapshot(void) {
    ref_ocean *o = make(small_desc(REF_SPECTRUM_JONSWAP, 3));
    if (!o) return;
    const ref_ocean_desc *d = ref_ocean_get_desc(o);
    int N = d->res;
    size_t nn = (size_t)N * N;
    double t = 1.25, *a[3], *b = malloc(sizeof(double) * 4 * nn);
    for (int c = 0; c < d->cascades; c++) {
        a[c] = malloc(sizeof(double) * 4 * nn);
        ref_ocean_frame(o, c, t, a[c], b);
    }
    const ref_ocean_snapshot *snap = ref_ocean_snapshot_acquire(o, t);
    ref_ocean_bounds b0, b1;
    ref_ocean_bounds_at(o, t, &b0);
    ref_ocean_snapshot_bounds(snap, &b1);
    CHECK(b0.height == b1.height && b0.slope == b1.slope && b0.chop == b1.chop);
    int bad = 0;
    for (int p = 0; p < 3000; p++) {
        /* far and negative points too: the nodes wrap */
        double u = (p * 0.6180339887 - 900) * 1.7, v = (p * 0.41421356 - 600) * 2.3;
        ref_ocean_sample s, fs;
        ref_ocean_sample_at(o, u, v, t, &s);
        ref_ocean_snapshot_sample(snap, u, v, &fs);
        double dm[2], jm[4], dp[2], jp[4], hm;
        ref_ocean_snapshot_map(snap, u, v, dm, jm, &hm);
        ref_ocean_sample_map(o, u, v, t, dp, jp);
        bad += memcmp(&s, &fs, sizeof s) != 0;
        bad += dm[0] != s.dx || dm[1] != s.dz || hm != s.h;
        bad += ref_ocean_snapshot_height(snap, u, v) != s.h;
        bad += memcmp(jm, jp, sizeof jm) != 0;
        /* the bilinear interpolant of the nodes, and its derivative, by hand */
        double want[3] = { 0, 0, 0 }, wj[4] = { 0, 0, 0, 0 };
        for (int c = 0; c < d->cascades; c++) {
            double texel = d->tile[c] / N, fu = u / texel, fv = v / texel;
            double x = fu - floor(fu), z = fv - floor(fv);
            long i0 = ((long)floor(fu) % N + N) % N, j0 = ((long)floor(fv) % N + N) % N;
            long i1 = (i0 + 1) % N, j1 = (j0 + 1) % N;
            for (int q = 0; q < 3; q++) {
                double n00 = a[c][4 * (j0 * N + i0) + q], n10 = a[c][4 * (j0 * N + i1) + q];
                double n01 = a[c][4 * (j1 * N + i0) + q], n11 = a[c][4 * (j1 * N + i1) + q];
                want[q] += (1 - z) * ((1 - x) * n00 + x * n10) + z * ((1 - x) * n01 + x * n11);
                if (q == 0) continue;
                wj[2 * (q - 1)] += ((1 - z) * (n10 - n00) + z * (n11 - n01)) / texel;
                wj[2 * (q - 1) + 1] += ((1 - x) * (n01 - n00) + x * (n11 - n10)) / texel;
            }
        }
        double tol = 1e-12 * (1 + b0.height);
        bad += !(fabs(hm - want[0]) < tol && fabs(dm[0] - want[1]) < tol && fabs(dm[1] - want[2]) < tol);
        for (int k = 0; k < 4; k++) bad += !(fabs(jm[k] - wj[k]) < 1e-10 * (1 + b0.chop));
    }
    CHECK_MSG(bad == 0, "%d disagreements", bad);
    /* more times than the cache has slots: the held frame is not evicted */
    ref_ocean_sample before, after;
    ref_ocean_snapshot_sample(snap, 3.3, -7.1, &before);
    for (int k = 1; k <= 6; k++) {
        ref_ocean_sample s;
        ref_ocean_sample_at(o, 3.3, -7.1, t + k, &s);
    }
    ref_ocean_snapshot_sample(snap, 3.3, -7.1, &after);
    CHECK_EQ(memcmp(&before, &after, sizeof before), 0);
    ref_ocean_snapshot_release(snap);
    for (int c = 0; c < d->cascades; c++) free(a[c]);
    free(b);
    ref_ocean_destroy(o);
}

int main(void) {
    RUN(test_fft_vs_direct);
    RUN(test_bilinear_periodic);
    RUN(test_derivatives_fd);
    RUN(test_spectra);
    RUN(test_energy);
    RUN(test_folding);
    RUN(test_bounds);
    RUN(test_bounds_regions);
    RUN(test_determinism_and_errors);
    RUN(test_threads);
    RUN(test_snapshot);
    return check_summary();
}
