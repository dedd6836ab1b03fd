/* ref_ocean: Tessendorf's spectrum ocean in double precision (see
 * ref_ocean.h for the model, the fields and the layout).
 *
 * Sources of the formulas:
 *   - J. Tessendorf, "Simulating Ocean Water", SIGGRAPH 2001 course notes:
 *     the FFT ocean, h~(k, t), the choppy displacement D and the Phillips
 *     spectrum (eq. 40) with its small-wave damping exp(-k^2 l^2) (eq. 41).
 *   - K. Hasselmann et al., "Measurements of wind-wave growth and swell
 *     decay during the Joint North Sea Wave Project (JONSWAP)", 1973: the
 *     fetch-limited spectrum S(omega) with alpha = 0.076 (U^2 / (F g))^0.22,
 *     omega_p = 22 (g^2 / (U F))^(1/3), gamma = 3.3, sigma = 0.07 / 0.09.
 *   - C. J. Horvath, "Empirical directional wave spectra for computer
 *     graphics", DigiPro 2015: the conversion S(omega) -> S(k, theta) with
 *     the dispersion's Jacobian (d omega / dk) / k (sec. 4), Hasselmann's
 *     directional spreading cos^(2s)(theta / 2) with s(omega) and its
 *     normalisation (sec. 5.2.3), the TMA depth factor Phi(omega_h) as
 *     Kitaigorodskii's approximation (sec. 5.1.6).
 *   - L. H. Holthuijsen, "Waves in Oceanic and Coastal Waters" (2007) for
 *     the Pierson-Moskowitz significant wave height Hs = 0.21 U^2 / g the
 *     Phillips constant is matched to (below).
 */
#include "ref_ocean.h"
#include "ref_trace.h"     /* ref_splitmix64 */
#include "strbuf.h"

#include <assert.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"

#define TWO_PI 6.283185307179586476925286766559
#define PI 3.14159265358979323846
#define G 9.81                  /* the same g as ref_waves' REF_GRAVITY */

/* JONSWAP's peak enhancement and its widths below / above the peak */
#define JONSWAP_GAMMA 3.3
#define JONSWAP_SIGMA_LO 0.07
#define JONSWAP_SIGMA_HI 0.09
/* Phillips' small-wave damping length l = PHILLIPS_DAMP * U^2 / g
 * (Tessendorf: "l << L"); at 10 m/s l = 1 cm */
#define PHILLIPS_DAMP 1e-3
/* The Pierson-Moskowitz significant wave height of a fully developed sea,
 * Hs = PM_HS * U^2 / g: the Phillips constant A is chosen so that the
 * spectrum (without its small-wave damping) holds the variance Hs^2 / 16. */
#define PM_HS 0.21
/* The band edge between cascade c and c + 1 lies at BAND_MULT wavenumber
 * steps of the finer cascade (gasgiant/FFT-Ocean's choice, 6 dk_(c+1)),
 * or lower where the coarser grid does not reach that far. */
#define BAND_MULT 6.0
/* frames kept (LRU); each holds every cascade's eight fields */
#define CACHE_SLOTS 4

/* A cache slot is a snapshot (ref_ocean.h): the frame at t while refs > 0. */
typedef struct ref_ocean_snapshot {
    const ref_ocean *o;         /* its ocean (set at creation) */
    double t;
    int valid;
    uint64_t used;              /* LRU stamp */
    atomic_int refs;            /* samplers reading it now */
    double *f[REF_OCEAN_CASCADES_MAX];   /* N * N * 8: A then B a texel */
    /* the same nodes' (Dx, Dz, h) again, packed: a march reads only these
     * (the inversion's map and the height test), and they span 3/8 of the
     * memory of the eight-field texels (the three cascades' 3 MiB do not
     * stay in a core's cache; 1.1 MiB does far better) */
    double *map[REF_OCEAN_CASCADES_MAX]; /* N * N * 3: Dx, Dz, h a texel */
    /* the bounds by region (see cascade_bounds): a max pyramid a cascade,
     * level l holding (slope, chop) of each block of 2^l x 2^l cells,
     * rounded up to float; level 0 is the cells, level log2 N the tile */
    float *pyr[REF_OCEAN_CASCADES_MAX];
    double dlo[2], dhi[2];      /* (Dx, Dz) in [dlo, dhi] everywhere (summed) */
    ref_ocean_bounds bounds;
} frame_slot;

struct ref_ocean {
    ref_ocean_desc d;           /* resolved */
    int n, nc;
    double wind[2];
    double dk[REF_OCEAN_CASCADES_MAX];
    double inv[REF_OCEAN_CASCADES_MAX];     /* N / L_c: texels a metre */
    double band_lo[REF_OCEAN_CASCADES_MAX], band_hi[REF_OCEAN_CASCADES_MAX];
    double *h0[REF_OCEAN_CASCADES_MAX];      /* N * N complex (re, im): h0(k), FFT order */
    double *omega[REF_OCEAN_CASCADES_MAX];   /* N * N */
    /* spectrum constants */
    double phillips_a, phillips_l, phillips_damp;
    double alpha, omega_p;
    /* the FFT's tables */
    double *tw;                 /* N/2 complex: e^{+2 pi i j / N} */
    int *rev;                   /* bit reversal of 0..N-1 */
    ref_ocean_bounds any;
    /* the frame cache */
    pthread_mutex_t mu;
    pthread_cond_t cv;
    atomic_int waiters;
    uint64_t clock;
    frame_slot slot[CACHE_SLOTS];
};

/* ------------------------------------------------------------------ */
/* the desc                                                            */

static const double default_tile[REF_OCEAN_CASCADES_MAX] = { 250.0, 37.0, 5.3 };

int ref_ocean_desc_resolve(ref_ocean_desc *d, char *err, size_t errlen) {
    if (err && errlen) err[0] = '\0';
    if (d->spectrum < REF_SPECTRUM_NONE || d->spectrum > REF_SPECTRUM_TMA) {
        msg_set(err, errlen, "ocean: unknown spectrum %d", (int)d->spectrum);
        return -1;
    }
    double nums[] = { d->wind_speed, d->wind_angle_deg, d->fetch, d->depth, d->spreading,
                      d->choppiness, d->amplitude, d->tile[0], d->tile[1], d->tile[2] };
    for (size_t i = 0; i < sizeof nums / sizeof nums[0]; i++)
        if (!isfinite(nums[i])) { msg_set(err, errlen, "ocean: a parameter is not finite"); return -1; }
    if (d->wind_speed < 0 || d->fetch < 0 || d->depth < 0 || d->spreading < 0 ||
        d->choppiness < 0 || d->amplitude < 0) {
        msg_set(err, errlen, "ocean: wind speed, fetch, depth, spreading, choppiness and "
                "amplitude must be >= 0");
        return -1;
    }
    if (d->wind_speed == 0) d->wind_speed = 10.0;
    if (d->fetch == 0) d->fetch = 100e3;
    if (d->spreading == 0 && d->spectrum == REF_SPECTRUM_PHILLIPS) d->spreading = 2.0;
    if (d->amplitude == 0) d->amplitude = 1.0;
    if (d->res == 0) d->res = 128;
    if (d->cascades == 0) d->cascades = 1;
    if (d->res < REF_OCEAN_RES_MIN || d->res > REF_OCEAN_RES_MAX || (d->res & (d->res - 1))) {
        msg_set(err, errlen, "ocean: res %d is not a power of two in %d..%d", d->res,
                REF_OCEAN_RES_MIN, REF_OCEAN_RES_MAX);
        return -1;
    }
    if (d->cascades < 1 || d->cascades > REF_OCEAN_CASCADES_MAX) {
        msg_set(err, errlen, "ocean: cascades %d out of range 1..%d", d->cascades,
                REF_OCEAN_CASCADES_MAX);
        return -1;
    }
    for (int c = 0; c < REF_OCEAN_CASCADES_MAX; c++) {
        if (d->tile[c] < 0) { msg_set(err, errlen, "ocean: tile %d is negative", c); return -1; }
        if (c >= d->cascades) { d->tile[c] = 0; continue; }
        if (d->tile[c] == 0)   /* the default, scaled like the tile before it */
            d->tile[c] = c == 0 ? default_tile[0] : d->tile[c - 1] * default_tile[c] / default_tile[c - 1];
        if (c > 0 && !(d->tile[c] < d->tile[c - 1])) {
            msg_set(err, errlen, "ocean: tiles must decrease (tile %d = %g, tile %d = %g)", c - 1,
                    d->tile[c - 1], c, d->tile[c]);
            return -1;
        }
    }
    return 0;
}

/* ------------------------------------------------------------------ */
/* spectra                                                             */

static double dispersion(const ref_ocean *o, double k) {
    return o->d.depth > 0 ? sqrt(G * k * tanh(k * o->d.depth)) : sqrt(G * k);
}

/* d omega / dk */
static double dispersion_d(const ref_ocean *o, double k, double w) {
    if (w <= 0) return 0;
    if (o->d.depth <= 0) return G / (2.0 * w);
    double kh = k * o->d.depth, th = tanh(kh), ch = cosh(kh);
    double sech2 = isfinite(ch) ? 1.0 / (ch * ch) : 0.0;
    return G * (th + kh * sech2) / (2.0 * w);
}

/* JONSWAP S(omega) (Hasselmann 1973), m^2 s */
static double jonswap_omega(const ref_ocean *o, double w) {
    if (w <= 0) return 0;
    double wp = o->omega_p, sigma = w <= wp ? JONSWAP_SIGMA_LO : JONSWAP_SIGMA_HI;
    double r = exp(-(w - wp) * (w - wp) / (2.0 * sigma * sigma * wp * wp));
    double q = wp / w, q4 = q * q * q * q;
    return o->alpha * G * G / pow(w, 5) * exp(-1.25 * q4) * pow(JONSWAP_GAMMA, r);
}

/* Kitaigorodskii's depth factor, Horvath 2015's approximation in
 * omega_h = omega sqrt(depth / g) */
static double tma_phi(double w, double depth) {
    double wh = w * sqrt(depth / G);
    if (wh <= 1.0) return 0.5 * wh * wh;
    if (wh < 2.0) return 1.0 - 0.5 * (2.0 - wh) * (2.0 - wh);
    return 1.0;
}

/* Hasselmann's spreading exponent s(omega) (Horvath 2015 eq. 41) */
static double hasselmann_s(const ref_ocean *o, double w) {
    double wp = o->omega_p, r = w / wp;
    if (w <= wp) return 6.97 * pow(r, 4.06);
    double mu = -2.33 - 1.45 * (o->d.wind_speed * wp / G - 1.17);
    return 9.77 * pow(r, mu);
}

/* log of the normalisation of cos^(2s)(theta / 2) over (-pi, pi]:
 * 2^(2s - 1) Gamma(s + 1)^2 / (pi Gamma(2s + 1)) */
static double log_norm_half(double s) {
    return (2.0 * s - 1.0) * log(2.0) + 2.0 * lgamma(s + 1.0) - log(PI) - lgamma(2.0 * s + 1.0);
}

/* log of the normalisation of cos^(2s)(theta) over |theta| < pi/2 (0 elsewhere):
 * Gamma(s + 1) / (sqrt(pi) Gamma(s + 1/2)) */
static double log_norm_pos(double s) {
    return lgamma(s + 1.0) - 0.5 * log(PI) - lgamma(s + 0.5);
}

/* The radial part of S at |k| (m^4 rad^-1: S(k, theta) = radial * D(theta))
 * and the spreading's exponent for that k. */
static double radial_part(const ref_ocean *o, double k, double *s_out) {
    double amp2 = o->d.amplitude * o->d.amplitude;
    *s_out = o->d.spreading;
    if (k <= 0) return 0;
    if (o->d.spectrum == REF_SPECTRUM_PHILLIPS) {
        double kl = k * o->phillips_l, k2 = k * k;
        return amp2 * o->phillips_a * exp(-1.0 / (kl * kl)) / (k2 * k2) *
               exp(-k2 * o->phillips_damp * o->phillips_damp);
    }
    double w = dispersion(o, k);
    double s = jonswap_omega(o, w);
    if (o->d.spectrum == REF_SPECTRUM_TMA && o->d.depth > 0) s *= tma_phi(w, o->d.depth);
    if (o->d.spreading == 0) *s_out = hasselmann_s(o, w);
    return amp2 * s * dispersion_d(o, k, w) / k;
}

/* The directional factor at angle theta from the wind, for exponent s. */
static double spreading(const ref_ocean *o, double theta, double s, double lognorm) {
    if (o->d.spectrum == REF_SPECTRUM_PHILLIPS) return pow(fabs(cos(theta)), s);
    if (o->d.spreading == 0) {
        double c = fabs(cos(0.5 * theta));
        return c > 0 ? exp(lognorm + 2.0 * s * log(c)) : 0.0;
    }
    double c = cos(theta);
    return c > 0 ? exp(lognorm + 2.0 * s * log(c)) : 0.0;
}

static double spreading_lognorm(const ref_ocean *o, double s) {
    if (o->d.spectrum == REF_SPECTRUM_PHILLIPS) return 0.0;
    return o->d.spreading == 0 ? log_norm_half(s) : log_norm_pos(s);
}

double ref_ocean_spectrum(const ref_ocean *o, double kx, double kz) {
    double k = hypot(kx, kz), s;
    double r = radial_part(o, k, &s);
    if (r == 0) return 0;
    double theta = atan2(kz, kx) - atan2(o->wind[1], o->wind[0]);
    return r * spreading(o, theta, s, spreading_lognorm(o, s));
}

/* ------------------------------------------------------------------ */
/* the FFT                                                             */

/* In-place radix-2 transform of n complex values at stride `stride`
 * complex elements, `count` interleaved vectors (vector j starts at j):
 * X(x) = sum_k Z(k) e^{+2 pi i k x / n}, no scaling. With count = N and
 * stride = N this transforms every column of a row-major N x N array at
 * once (the inner loop runs along contiguous rows). */
static void fft_inverse(const ref_ocean *o, double *z, int n, int stride, int count, int vstride) {
    for (int i = 0; i < n; i++) {
        int j = o->rev[i];
        if (j <= i) continue;
        for (int v = 0; v < count; v++) {
            double *a = z + 2 * ((size_t)i * stride + (size_t)v * vstride);
            double *b = z + 2 * ((size_t)j * stride + (size_t)v * vstride);
            double t0 = a[0], t1 = a[1];
            a[0] = b[0]; a[1] = b[1];
            b[0] = t0; b[1] = t1;
        }
    }
    for (int len = 2; len <= n; len <<= 1) {
        int half = len >> 1, step = n / len;
        for (int i = 0; i < n; i += len)
            for (int j = 0; j < half; j++) {
                double wr = o->tw[2 * (j * step)], wi = o->tw[2 * (j * step) + 1];
                double *p = z + 2 * (size_t)(i + j) * stride;
                double *q = z + 2 * (size_t)(i + j + half) * stride;
                for (int v = 0; v < count; v++) {
                    double *a = p + 2 * (size_t)v * vstride, *b = q + 2 * (size_t)v * vstride;
                    double br = b[0] * wr - b[1] * wi, bi = b[0] * wi + b[1] * wr;
                    b[0] = a[0] - br; b[1] = a[1] - bi;
                    a[0] += br; a[1] += bi;
                }
            }
    }
}

/* 2D inverse DFT of an N x N row-major complex array (row n, m fastest) */
static void fft2_inverse(const ref_ocean *o, double *z) {
    int n = o->n;
    for (int r = 0; r < n; r++) fft_inverse(o, z + 2 * (size_t)r * n, n, 1, 1, 0);
    fft_inverse(o, z, n, n, n, 1);
}

/* ------------------------------------------------------------------ */
/* creation                                                            */

static int signed_index(int m, int n) { return m < n / 2 ? m : m - n; }

/* two unit Gaussians from (seed, cascade, m, n), Box-Muller on splitmix64 */
static void gauss2(uint32_t seed, int c, int m, int n, double *g0, double *g1) {
    uint64_t st = (uint64_t)seed * 0x9E3779B97F4A7C15ull ^
                  ((uint64_t)c << 48 | (uint64_t)m << 24 | (uint64_t)n);
    double u1 = ((double)(ref_splitmix64(&st) >> 11) + 1.0) * 0x1.0p-53;   /* (0, 1] */
    double u2 = (double)(ref_splitmix64(&st) >> 11) * 0x1.0p-53;
    double r = sqrt(-2.0 * log(u1));
    *g0 = r * cos(TWO_PI * u2);
    *g1 = r * sin(TWO_PI * u2);
}

ref_ocean *ref_ocean_create(const ref_ocean_desc *desc, char *err, size_t errlen) {
    ref_ocean_desc d = *desc;
    if (ref_ocean_desc_resolve(&d, err, errlen) != 0) return NULL;
    if (d.spectrum == REF_SPECTRUM_NONE) {
        msg_set(err, errlen, "ocean: no spectrum");
        return NULL;
    }
    ref_ocean *o = mem_zalloc(sizeof *o);
    o->d = d;
    int N = o->n = d.res;
    o->nc = d.cascades;
    double wa = d.wind_angle_deg * (PI / 180.0);
    o->wind[0] = cos(wa);
    o->wind[1] = sin(wa);
    double U = d.wind_speed;
    /* Phillips: A matched to the Pierson-Moskowitz variance (Hs / 4)^2 with
     * Hs = 0.21 U^2 / g: the undamped spectrum integrates to
     * A (L^2 / 2) int |cos|^s dtheta, L = U^2 / g, and
     * int_0^2pi |cos|^s = 2 sqrt(pi) Gamma((s+1)/2) / Gamma(s/2 + 1) */
    o->phillips_l = U * U / G;
    o->phillips_damp = PHILLIPS_DAMP * o->phillips_l;
    double ang = 2.0 * sqrt(PI) * exp(lgamma(0.5 * (d.spreading + 1.0)) - lgamma(0.5 * d.spreading + 1.0));
    o->phillips_a = PM_HS * PM_HS / (8.0 * ang);
    o->alpha = 0.076 * pow(U * U / (d.fetch * G), 0.22);
    o->omega_p = 22.0 * cbrt(G * G / (U * d.fetch));

    /* bands: [lo_c, hi_c); hi of the last = its Nyquist radius */
    for (int c = 0; c < o->nc; c++) {
        o->dk[c] = TWO_PI / d.tile[c];
        o->inv[c] = N / d.tile[c];
    }
    o->band_lo[0] = 0.0;
    for (int c = 0; c + 1 < o->nc; c++) {
        double e = fmin(BAND_MULT * o->dk[c + 1], (N / 2 - 1) * o->dk[c]);
        o->band_hi[c] = e;
        o->band_lo[c + 1] = e;
    }
    o->band_hi[o->nc - 1] = (N / 2) * o->dk[o->nc - 1];

    o->tw = mem_alloc(sizeof(double) * (size_t)N);
    for (int j = 0; j < N / 2; j++) {
        o->tw[2 * j] = cos(TWO_PI * j / N);
        o->tw[2 * j + 1] = sin(TWO_PI * j / N);
    }
    o->rev = mem_alloc(sizeof(int) * (size_t)N);
    int bits = 0;
    while ((1 << bits) < N) bits++;
    for (int i = 0; i < N; i++) {
        int r = 0;
        for (int b = 0; b < bits; b++) if (i & (1 << b)) r |= 1 << (bits - 1 - b);
        o->rev[i] = r;
    }

    /* h0(k) = (xi_r + i xi_i) sqrt(S(-k) dk^2 / 4): see the header */
    o->any = (ref_ocean_bounds){ 0, 0, 0 };
    for (int c = 0; c < o->nc; c++) {
        double *h0 = o->h0[c] = mem_zalloc((size_t)N * N * 2 * sizeof(double));
        double *om = o->omega[c] = mem_zalloc((size_t)N * N * sizeof(double));
        double dk = o->dk[c], hsum = 0, ssum = 0, csum = 0;
        for (int n = 0; n < N; n++)
            for (int m = 0; m < N; m++) {
                size_t i = (size_t)n * N + m;
                double kx = signed_index(m, N) * dk, kz = signed_index(n, N) * dk, k = hypot(kx, kz);
                om[i] = dispersion(o, k);
                if (m == N / 2 || n == N / 2 || k == 0 || k < o->band_lo[c] || k >= o->band_hi[c])
                    continue;
                double g0, g1;
                gauss2(d.seed, c, m, n, &g0, &g1);
                double a = sqrt(ref_ocean_spectrum(o, -kx, -kz) * dk * dk / 4.0);
                h0[2 * i] = g0 * a;
                h0[2 * i + 1] = g1 * a;
                /* |h~(k)| <= |h0(k)| + |h0(-k)|: each |h0| counted twice over k */
                double m0 = 2.0 * hypot(h0[2 * i], h0[2 * i + 1]);
                hsum += m0;
                ssum += k * m0;
                csum += k * m0 * d.choppiness;
            }
        o->any.height += hsum;
        o->any.slope += ssum;
        o->any.chop += csum;
    }
    for (int s = 0; s < CACHE_SLOTS; s++) o->slot[s].o = o;
    pthread_mutex_init(&o->mu, NULL);
    pthread_cond_init(&o->cv, NULL);
    return o;
}

void ref_ocean_destroy(ref_ocean *o) {
    if (!o) return;
    for (int c = 0; c < REF_OCEAN_CASCADES_MAX; c++) {
        free(o->h0[c]);
        free(o->omega[c]);
        for (int s = 0; s < CACHE_SLOTS; s++) {
            assert(atomic_load(&o->slot[s].refs) == 0);   /* a snapshot outlived its ocean */
            free(o->slot[s].f[c]);
            free(o->slot[s].map[c]);
            free(o->slot[s].pyr[c]);
        }
    }
    free(o->tw);
    free(o->rev);
    pthread_mutex_destroy(&o->mu);
    pthread_cond_destroy(&o->cv);
    free(o);
}

const ref_ocean_desc *ref_ocean_get_desc(const ref_ocean *o) { return &o->d; }

void ref_ocean_bounds_any(const ref_ocean *o, ref_ocean_bounds *b) { *b = o->any; }

double ref_ocean_min_wavelength(const ref_ocean *o) {
    return 2.0 * o->d.tile[o->nc - 1] / o->n;
}

/* ------------------------------------------------------------------ */
/* frames                                                              */

/* h~(k, t) of texel i (negative index j) */
static void htilde(const ref_ocean *o, int c, size_t i, size_t j, double t, double out[2]) {
    const double *h0 = o->h0[c];
    double w = o->omega[c][i] * t, cw = cos(w), sw = sin(w);
    double ar = h0[2 * i], ai = h0[2 * i + 1];
    double br = h0[2 * j], bi = -h0[2 * j + 1];            /* conj(h0(-k)) */
    out[0] = ar * cw - ai * sw + br * cw + bi * sw;
    out[1] = ar * sw + ai * cw + bi * cw - br * sw;
}

/* The eight spectra of one texel, as four complex numbers packing two real
 * fields each (Z = A~ + i B~; A~, B~ Hermitian, so ifft(Z) = a + i b):
 * (h, Dx), (Dz, Dxz), (hx, hz), (Dxx, Dzz). */
static void texel_spectra(const ref_ocean *o, int c, int m, int n, double t, double z[4][2]) {
    int N = o->n;
    double dk = o->dk[c], lam = o->d.choppiness;
    double kx = signed_index(m, N) * dk, kz = signed_index(n, N) * dk, k = hypot(kx, kz);
    memset(z, 0, sizeof(double) * 8);
    if (k == 0 || m == N / 2 || n == N / 2) return;
    size_t i = (size_t)n * N + m, j = (size_t)((N - n) % N) * N + (size_t)((N - m) % N);
    double h[2];
    htilde(o, c, i, j, t, h);
    /* i * h */
    double ih[2] = { -h[1], h[0] };
    double dx[2] = { lam * kx / k * ih[0], lam * kx / k * ih[1] };     /* Dx~ = i lam kx/k h~ */
    double dz[2] = { lam * kz / k * ih[0], lam * kz / k * ih[1] };
    double dxz[2] = { -lam * kx * kz / k * h[0], -lam * kx * kz / k * h[1] };
    double hx[2] = { kx * ih[0], kx * ih[1] }, hz[2] = { kz * ih[0], kz * ih[1] };
    double dxx[2] = { -lam * kx * kx / k * h[0], -lam * kx * kx / k * h[1] };
    double dzz[2] = { -lam * kz * kz / k * h[0], -lam * kz * kz / k * h[1] };
    /* A + iB = (Ar - Bi) + i (Ai + Br) */
    z[0][0] = h[0] - dx[1];   z[0][1] = h[1] + dx[0];
    z[1][0] = dz[0] - dxz[1]; z[1][1] = dz[1] + dxz[0];
    z[2][0] = hx[0] - hz[1];  z[2][1] = hx[1] + hz[0];
    z[3][0] = dxx[0] - dzz[1]; z[3][1] = dxx[1] + dzz[0];
}

/* Fills f (N * N * 8: h, Dx, Dz, Dxz, hx, hz, Dxx, Dzz a texel). */
static void compute_cascade(const ref_ocean *o, int c, double t, double *f) {
    int N = o->n;
    size_t nn = (size_t)N * N;
    double *z = mem_alloc(sizeof(double) * 2 * nn * 4);
    for (int n = 0; n < N; n++)
        for (int m = 0; m < N; m++) {
            double s[4][2];
            texel_spectra(o, c, m, n, t, s);
            size_t i = (size_t)n * N + m;
            for (int p = 0; p < 4; p++) {
                z[2 * (p * nn + i)] = s[p][0];
                z[2 * (p * nn + i) + 1] = s[p][1];
            }
        }
    for (int p = 0; p < 4; p++) fft2_inverse(o, z + 2 * p * nn);
    /* A = (h, Dx, Dz, Dxz), B = (hx, hz, Dxx, Dzz) */
    static const int src[8][2] = { {0, 0}, {0, 1}, {1, 0}, {1, 1}, {2, 0}, {2, 1}, {3, 0}, {3, 1} };
    for (size_t i = 0; i < nn; i++)
        for (int q = 0; q < 8; q++) f[8 * i + q] = z[2 * (src[q][0] * nn + i) + src[q][1]];
    free(z);
}

/* The bounds of the bilinear fields, exact per cell and per cascade.
 *
 * In a cell (x, z in [0, 1]^2 across it) the bilinear interpolant of a
 * field q with node values q00, q10, q01, q11 has the derivatives
 *
 *     dq/du = ((1 - z) (q10 - q00) + z (q11 - q01)) / texel     (affine in z, free of x)
 *     dq/dv = ((1 - x) (q01 - q00) + x (q11 - q10)) / texel     (affine in x, free of z)
 *
 * so the gradient of h, and the 2 x 2 derivative A = d(Dx, Dz)/d(u, v) of
 * the sideways map, are bi-affine in (x, z): A(x, z) = sum_ab w_ab(x, z)
 * A_ab, with the bilinear weights w_ab >= 0 (summing to 1) and the corner
 * matrices A_ab = [dq/du at z = b | dq/dv at x = a] (q = Dx, Dz; the du
 * column of both rows from the same edge z = b, the dv column from x = a).
 * (Check: sum_a w_ab = (1 - z) or z, so column 1 of sum w_ab A_ab is
 * (1 - z) du_0 + z du_1.) A norm is convex, so over the cell
 *
 *     |grad h(x, z)| <= max_ab |grad h_ab|,   ||A(x, z)||_2 <= max_ab ||A_ab||_2,
 *
 * and both are attained (at the corner): the cell's exact maxima. For h the
 * four corner gradients are all the pairs (du at z = 0 or 1, dv at x = 0 or
 * 1), so its max is hypot(max |du|, max |dv|). The spectral norm of
 * [a b; c d] is (hypot(a + d, b - c) + hypot(a - d, b + c)) / 2.
 *
 * The interpolant is continuous and C1 inside cells, so on a convex set B
 * of rest points (a segment between two points of B crosses finitely many
 * cells) h is Lipschitz with the largest cell |grad h| of the cells meeting
 * B, and D with the largest cell ||A||_2: |D(p) - D(q)| <= C |p - q|. Over
 * the cascades these add (A = sum_c A_c: ||A|| <= sum ||A_c||), and then
 * the sideways map F(p) = p + D(p) has |F(p) - F(q)| >= (1 - C) |p - q|
 * (the smallest singular value of I + A is >= 1 - ||A||), which is what
 * ref_waves' world-slope bounds are built on (ref_waves.c, world_slope_box).
 *
 * (The bound before this one took the Frobenius norm of the matrix of the
 * entries' maxima over the cell, and ||A||_2 <= ||(max |a_ij|)||_2 <=
 * Frobenius; the corners' spectral norm is the least of the three.)
 *
 * Besides the frame's bounds this fills the cascade's pyramid (frame_slot:
 * level 0 the cells' (slope, chop), each level above the max of the 2 x 2
 * blocks below it) and the per-cascade range of (Dx, Dz) over the nodes
 * (a bilinear value lies between its cell's nodes). */
static size_t pyr_size(int n) {
    size_t s = 0;
    for (int m = n; m >= 1; m >>= 1) s += (size_t)m * m;
    return s;
}

/* x rounded up to a float (the pyramid's values are bounds) */
static float float_up(double x) {
    float f = (float)x;
    return (double)f < x ? nextafterf(f, INFINITY) : f;
}

/* The spectral norm of [a b; c d]. */
static double spectral2(double a, double b, double c, double d) {
    return 0.5 * (hypot(a + d, b - c) + hypot(a - d, b + c));
}

static void cascade_bounds(const ref_ocean *o, int c, frame_slot *sl, ref_ocean_bounds *b) {
    int N = o->n;
    const double *f = sl->f[c];
    float *pyr = sl->pyr[c];
    double inv = N / o->d.tile[c], hmax = 0, smax = 0, cmax = 0;
    double lo[2] = { INFINITY, INFINITY }, hi[2] = { -INFINITY, -INFINITY };
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            const double *p00 = f + 8 * ((size_t)j * N + i);
            const double *p10 = f + 8 * ((size_t)j * N + (i + 1) % N);
            const double *p01 = f + 8 * ((size_t)((j + 1) % N) * N + i);
            const double *p11 = f + 8 * ((size_t)((j + 1) % N) * N + (i + 1) % N);
            hmax = fmax(hmax, fabs(p00[0]));
            for (int q = 0; q < 2; q++) {
                lo[q] = fmin(lo[q], p00[1 + q]);
                hi[q] = fmax(hi[q], p00[1 + q]);
            }
            /* du on the edges z = 0, 1 and dv on x = 0, 1, of h, Dx, Dz */
            double du[3][2], dv[3][2];
            for (int q = 0; q < 3; q++) {
                du[q][0] = (p10[q] - p00[q]) * inv;
                du[q][1] = (p11[q] - p01[q]) * inv;
                dv[q][0] = (p01[q] - p00[q]) * inv;
                dv[q][1] = (p11[q] - p10[q]) * inv;
            }
            double sc = hypot(fmax(fabs(du[0][0]), fabs(du[0][1])), fmax(fabs(dv[0][0]), fabs(dv[0][1])));
            double cc = 0;
            for (int zb = 0; zb < 2; zb++)
                for (int xa = 0; xa < 2; xa++)
                    cc = fmax(cc, spectral2(du[1][zb], dv[1][xa], du[2][zb], dv[2][xa]));
            smax = fmax(smax, sc);
            cmax = fmax(cmax, cc);
            pyr[2 * ((size_t)j * N + i)] = float_up(sc);
            pyr[2 * ((size_t)j * N + i) + 1] = float_up(cc);
        }
    /* the levels above: max of 2 x 2 blocks */
    float *below = pyr;
    for (int n = N / 2; n >= 1; n /= 2) {
        float *lev = below + 2 * (size_t)(2 * n) * (2 * n);
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++)
                for (int k = 0; k < 2; k++) {
                    const float *r0 = below + 2 * ((size_t)(2 * j) * (2 * n) + 2 * i) + k;
                    const float *r1 = r0 + 2 * (size_t)(2 * n);
                    lev[2 * ((size_t)j * n + i) + k] = fmaxf(fmaxf(r0[0], r0[2]), fmaxf(r1[0], r1[2]));
                }
        below = lev;
    }
    b->height += hmax;
    b->slope += smax;
    b->chop += cmax;
    for (int q = 0; q < 2; q++) {
        sl->dlo[q] += lo[q];
        sl->dhi[q] += hi[q];
    }
}

/* The slot's arrays for cascade c (allocated on first use); returns f. */
static double *slot_fields(const ref_ocean *o, frame_slot *sl, int c) {
    size_t nn = (size_t)o->n * o->n;
    if (!sl->f[c]) {
        sl->f[c] = mem_alloc(sizeof(double) * 8 * nn);
        sl->map[c] = mem_alloc(sizeof(double) * 3 * nn);
        sl->pyr[c] = mem_alloc(sizeof(float) * 2 * pyr_size(o->n));
    }
    return sl->f[c];
}

/* Copies (Dx, Dz, h) out of the eight-field texels (see frame_slot). */
static void pack_fields(const ref_ocean *o, frame_slot *sl, int c) {
    size_t nn = (size_t)o->n * o->n;
    const double *f = sl->f[c];
    double *m = sl->map[c];
    for (size_t i = 0; i < nn; i++) {
        m[3 * i] = f[8 * i + 1];
        m[3 * i + 1] = f[8 * i + 2];
        m[3 * i + 2] = f[8 * i];
    }
}

/* The slot holding the frame at t, referenced (release with frame_release). */
static frame_slot *frame_acquire(const ref_ocean *oc, double t) {
    ref_ocean *o = (ref_ocean *)oc;   /* the cache is the one mutable part */
    pthread_mutex_lock(&o->mu);
    for (;;) {
        for (int s = 0; s < CACHE_SLOTS; s++) {
            frame_slot *sl = &o->slot[s];
            if (sl->valid && sl->t == t) {
                atomic_fetch_add(&sl->refs, 1);
                sl->used = ++o->clock;
                pthread_mutex_unlock(&o->mu);
                return sl;
            }
        }
        atomic_fetch_add(&o->waiters, 1);
        frame_slot *lru = NULL;
        for (int s = 0; s < CACHE_SLOTS; s++) {
            frame_slot *sl = &o->slot[s];
            if (atomic_load(&sl->refs) != 0) continue;
            if (!lru || !sl->valid || (lru->valid && sl->used < lru->used)) lru = sl;
            if (!sl->valid) break;
        }
        if (!lru) {
            pthread_cond_wait(&o->cv, &o->mu);
            atomic_fetch_sub(&o->waiters, 1);
            continue;
        }
        atomic_fetch_sub(&o->waiters, 1);
        /* computed under the lock: a thread wanting the same t waits for it */
        lru->valid = 0;
        lru->bounds = (ref_ocean_bounds){ 0, 0, 0 };
        lru->dlo[0] = lru->dlo[1] = lru->dhi[0] = lru->dhi[1] = 0;
        for (int c = 0; c < o->nc; c++) {
            compute_cascade(o, c, t, slot_fields(o, lru, c));
            pack_fields(o, lru, c);
            cascade_bounds(o, c, lru, &lru->bounds);
        }
        lru->t = t;
        lru->valid = 1;
        lru->used = ++o->clock;
        atomic_fetch_add(&lru->refs, 1);
        pthread_mutex_unlock(&o->mu);
        return lru;
    }
}

static void frame_release(const ref_ocean *oc, frame_slot *sl) {
    ref_ocean *o = (ref_ocean *)oc;
    if (atomic_fetch_sub(&sl->refs, 1) == 1 && atomic_load(&o->waiters) > 0) {
        pthread_mutex_lock(&o->mu);
        pthread_cond_broadcast(&o->cv);
        pthread_mutex_unlock(&o->mu);
    }
}

void ref_ocean_frame(const ref_ocean *o, int cascade, double t, double *a, double *b) {
    assert(cascade >= 0 && cascade < o->nc);
    frame_slot *sl = frame_acquire(o, t);
    const double *f = sl->f[cascade];
    size_t nn = (size_t)o->n * o->n;
    for (size_t i = 0; i < nn; i++) {
        memcpy(a + 4 * i, f + 8 * i, 4 * sizeof(double));
        memcpy(b + 4 * i, f + 8 * i + 4, 4 * sizeof(double));
    }
    frame_release(o, sl);
}

const ref_ocean_snapshot *ref_ocean_snapshot_acquire(const ref_ocean *o, double t) {
    return frame_acquire(o, t);
}

void ref_ocean_snapshot_release(const ref_ocean_snapshot *s) {
    frame_release(s->o, (frame_slot *)s);   /* only its count changes */
}

void ref_ocean_snapshot_bounds(const ref_ocean_snapshot *s, ref_ocean_bounds *b) { *b = s->bounds; }

void ref_ocean_snapshot_disp_range(const ref_ocean_snapshot *s, double lo[2], double hi[2]) {
    for (int q = 0; q < 2; q++) {
        lo[q] = s->dlo[q];
        hi[q] = s->dhi[q];
    }
}

/* The cells a box [a, b] of texel coordinates meets, along one axis: the
 * first one wrapped into [0, N) and how many more. 0 when it spans the
 * tile (or is not finite). */
static int cell_span(double a, double b, long N, long *i0, long *di) {
    if (!(b - a < (double)(N - 1)) || !(fabs(a) < 0x1p52) || !(fabs(b) < 0x1p52)) return 0;
    double fa = floor(a), fb = floor(b);
    *i0 = (long)fa & (N - 1);
    *di = (long)(fb - fa);
    return 1;
}

void ref_ocean_snapshot_box_bounds(const ref_ocean_snapshot *s, double u0, double v0, double u1, double v1,
                                   double *slope, double *chop) {
    const ref_ocean *o = s->o;
    long N = o->n;
    double sl = 0, ch = 0;
    for (int c = 0; c < o->nc; c++) {
        const float *pyr = s->pyr[c];
        double inv = o->inv[c];
        long i0, di, j0, dj;
        if (!cell_span(u0 * inv, u1 * inv, N, &i0, &di) || !cell_span(v0 * inv, v1 * inv, N, &j0, &dj)) {
            /* the whole tile: the top level */
            const float *top = pyr + 2 * (pyr_size((int)N) - 1);
            sl += top[0];
            ch += top[1];
            continue;
        }
        /* the finest level whose blocks cover the cells in 2 x 2 of them */
        long n = N, l = 0;
        const float *lev = pyr;
        while (((i0 + di) >> l) - (i0 >> l) > 1 || ((j0 + dj) >> l) - (j0 >> l) > 1) {
            lev += 2 * (size_t)n * n;
            n >>= 1;
            l++;
        }
        long m = n - 1, ia = i0 >> l, ib = ((i0 + di) >> l) & m, ja = j0 >> l, jb = ((j0 + dj) >> l) & m;
        const float *e[4] = { lev + 2 * (ja * n + ia), lev + 2 * (ja * n + ib), lev + 2 * (jb * n + ia),
                              lev + 2 * (jb * n + ib) };
        float a = fmaxf(fmaxf(e[0][0], e[1][0]), fmaxf(e[2][0], e[3][0]));
        float b = fmaxf(fmaxf(e[0][1], e[1][1]), fmaxf(e[2][1], e[3][1]));
        sl += a;
        ch += b;
    }
    *slope = sl;
    *chop = ch;
}

/* Where (u, v) lies in cascade c's periodic grid: the node indices of its
 * cell (row-major, m fastest) and its place (x, z) in [0, 1)^2 there. */
typedef struct cell_pos {
    long i00, i10, i01, i11;
    double x, z;
} cell_pos;

/* floor(x) for |x| < 2^62 (cell_at's range): libm's is a call without
 * SSE4.1, and this runs a dozen times an inversion step */
static inline double floor_fast(double x) {
    double i = (double)(long)x;   /* rounds towards zero: exact in range */
    return i > x ? i - 1.0 : i;
}

static inline void cell_at(const ref_ocean *o, int c, double u, double v, cell_pos *p) {
    long N = o->n, mask = N - 1;
    double fu = u * o->inv[c], fv = v * o->inv[c], iu = floor_fast(fu), iv = floor_fast(fv);
    p->x = fu - iu;
    p->z = fv - iv;
    /* N is a power of two: the mask wraps negative nodes too (two's
     * complement); |u| / texel stays far below 2^62 */
    long i0 = (long)iu & mask, j0 = (long)iv & mask, i1 = (i0 + 1) & mask, j1 = (j0 + 1) & mask;
    p->i00 = j0 * N + i0;
    p->i10 = j0 * N + i1;
    p->i01 = j1 * N + i0;
    p->i11 = j1 * N + i1;
}

void ref_ocean_snapshot_sample(const ref_ocean_snapshot *s, double u, double v, ref_ocean_sample *out) {
    const ref_ocean *o = s->o;
    double acc[8] = { 0 };
    for (int c = 0; c < o->nc; c++) {
        cell_pos p;
        cell_at(o, c, u, v, &p);
        const double *f = s->f[c];
        const double *p00 = f + 8 * p.i00, *p10 = f + 8 * p.i10, *p01 = f + 8 * p.i01, *p11 = f + 8 * p.i11;
        double x = p.x, z = p.z;
        double w00 = (1 - x) * (1 - z), w10 = x * (1 - z), w01 = (1 - x) * z, w11 = x * z;
        for (int q = 0; q < 8; q++) acc[q] += w00 * p00[q] + w10 * p10[q] + w01 * p01[q] + w11 * p11[q];
    }
    out->h = acc[0]; out->dx = acc[1]; out->dz = acc[2]; out->dxz = acc[3];
    out->hx = acc[4]; out->hz = acc[5]; out->dxx = acc[6]; out->dzz = acc[7];
}

double ref_ocean_snapshot_height(const ref_ocean_snapshot *s, double u, double v) {
    const ref_ocean *o = s->o;
    double h = 0;
    for (int c = 0; c < o->nc; c++) {
        cell_pos p;
        cell_at(o, c, u, v, &p);
        const double *m = s->map[c] + 2;
        double x = p.x, z = p.z;
        double w00 = (1 - x) * (1 - z), w10 = x * (1 - z), w01 = (1 - x) * z, w11 = x * z;
        h += w00 * m[3 * p.i00] + w10 * m[3 * p.i10] + w01 * m[3 * p.i01] + w11 * m[3 * p.i11];
    }
    return h;
}

void ref_ocean_snapshot_map(const ref_ocean_snapshot *s, double u, double v, double d[2], double jac[4],
                            double *height) {
    const ref_ocean *o = s->o;
    double h = 0;
    d[0] = d[1] = 0;
    if (jac) jac[0] = jac[1] = jac[2] = jac[3] = 0;
    for (int c = 0; c < o->nc; c++) {
        cell_pos p;
        cell_at(o, c, u, v, &p);
        const double *m = s->map[c];
        double x = p.x, z = p.z, inv = o->inv[c];
        double w00 = (1 - x) * (1 - z), w10 = x * (1 - z), w01 = (1 - x) * z, w11 = x * z;
        for (int q = 0; q < 2; q++) {
            double a = m[3 * p.i00 + q], b = m[3 * p.i10 + q], e = m[3 * p.i01 + q], g = m[3 * p.i11 + q];
            d[q] += w00 * a + w10 * b + w01 * e + w11 * g;
            if (jac) {
                jac[2 * q] += ((1 - z) * (b - a) + z * (g - e)) * inv;
                jac[2 * q + 1] += ((1 - x) * (e - a) + x * (g - b)) * inv;
            }
        }
        h += w00 * m[3 * p.i00 + 2] + w10 * m[3 * p.i10 + 2] + w01 * m[3 * p.i01 + 2] + w11 * m[3 * p.i11 + 2];
    }
    if (height) *height = h;
}

void ref_ocean_bounds_at(const ref_ocean *o, double t, ref_ocean_bounds *b) {
    const ref_ocean_snapshot *s = ref_ocean_snapshot_acquire(o, t);
    ref_ocean_snapshot_bounds(s, b);
    ref_ocean_snapshot_release(s);
}

void ref_ocean_sample_at(const ref_ocean *o, double u, double v, double t, ref_ocean_sample *out) {
    const ref_ocean_snapshot *s = ref_ocean_snapshot_acquire(o, t);
    ref_ocean_snapshot_sample(s, u, v, out);
    ref_ocean_snapshot_release(s);
}

void ref_ocean_sample_map(const ref_ocean *o, double u, double v, double t, double d[2], double jac[4]) {
    const ref_ocean_snapshot *s = ref_ocean_snapshot_acquire(o, t);
    ref_ocean_snapshot_map(s, u, v, d, jac, NULL);
    ref_ocean_snapshot_release(s);
}

void ref_ocean_direct_sum(const ref_ocean *o, double u, double v, double t, ref_ocean_sample *s) {
    int N = o->n;
    double acc[8] = { 0 };
    for (int c = 0; c < o->nc; c++)
        for (int n = 0; n < N; n++)
            for (int m = 0; m < N; m++) {
                double z[4][2];
                texel_spectra(o, c, m, n, t, z);
                double kx = signed_index(m, N) * o->dk[c], kz = signed_index(n, N) * o->dk[c];
                double ph = kx * u + kz * v, cp = cos(ph), sp = sin(ph);
                for (int p = 0; p < 4; p++) {
                    acc[2 * p] += z[p][0] * cp - z[p][1] * sp;       /* Re(Z e^{i ph}) */
                    acc[2 * p + 1] += z[p][0] * sp + z[p][1] * cp;   /* Im */
                }
            }
    s->h = acc[0]; s->dx = acc[1]; s->dz = acc[2]; s->dxz = acc[3];
    s->hx = acc[4]; s->hz = acc[5]; s->dxx = acc[6]; s->dzz = acc[7];
}

void ref_ocean_gpu_spectrum(const ref_ocean *o, int cascade, float *h0, float *omega) {
    assert(cascade >= 0 && cascade < o->nc);
    int N = o->n;
    const double *src = o->h0[cascade];
    for (int n = 0; n < N; n++)
        for (int m = 0; m < N; m++) {
            size_t i = (size_t)n * N + m, j = (size_t)((N - n) % N) * N + (size_t)((N - m) % N);
            h0[4 * i] = (float)src[2 * i];
            h0[4 * i + 1] = (float)src[2 * i + 1];
            h0[4 * i + 2] = (float)src[2 * j];
            h0[4 * i + 3] = (float)-src[2 * j + 1];
            omega[i] = (float)o->omega[cascade][i];
        }
}

double ref_ocean_variance(const ref_ocean *o) {
    double v = 0;
    size_t nn = (size_t)o->n * o->n;
    for (int c = 0; c < o->nc; c++)
        for (size_t i = 0; i < nn; i++) {
            double a = o->h0[c][2 * i], b = o->h0[c][2 * i + 1];
            v += 2.0 * (a * a + b * b);     /* |h0(k)|^2 + |h0(-k)|^2 summed over k */
        }
    return v;
}

/* int S over the annulus lo <= |k| < hi: composite Simpson in ln k, the
 * periodic trapezoid rule in theta (spectrally accurate for the smooth
 * spreadings; cos^(2s) clipped at +-pi/2 has a kink of order 2s). */
#define VAR_RADIAL 2000
#define VAR_ANGULAR 720

static double band_integral(const ref_ocean *o, double lo, double hi) {
    if (!(hi > lo)) return 0;
    double a = log(lo > 0 ? lo : 1e-7 * hi), b = log(hi), h = (b - a) / VAR_RADIAL;
    double wind = atan2(o->wind[1], o->wind[0]), sum = 0;
    for (int i = 0; i <= VAR_RADIAL; i++) {
        double k = exp(a + i * h), s;
        double r = radial_part(o, k, &s);
        double ring = 0;
        if (r > 0) {
            double ln = spreading_lognorm(o, s);
            for (int j = 0; j < VAR_ANGULAR; j++)
                ring += spreading(o, TWO_PI * j / VAR_ANGULAR - wind, s, ln);
            ring *= TWO_PI / VAR_ANGULAR * r * k * k;   /* k dk = k^2 d(ln k) */
        }
        double wgt = (i == 0 || i == VAR_RADIAL) ? 1.0 : (i & 1) ? 4.0 : 2.0;
        sum += wgt * ring;
    }
    return sum * h / 3.0;
}

double ref_ocean_spectrum_variance(const ref_ocean *o) {
    double v = 0;
    for (int c = 0; c < o->nc; c++) v += band_integral(o, o->band_lo[c], o->band_hi[c]);
    return v;
}
