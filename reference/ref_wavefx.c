/* ref_wavefx: explosion rings and 3D Perlin wave sets in double precision;
 * see ref_wavefx.h for the formulas. packs/common/waves_fx.glsl is the
 * float twin: the same functions, term for term.
 *
 * Bounds (used to step a ray march safely; they hold at every time).
 *
 * Ring. Write q = k s = sqrt(k^2 r^2 + 1) >= 1 and phi = q - omega tau.
 * The envelope's argument (s - R + W) / W equals 1 + phi / (2 pi), so
 *     h = I0 e^{-b tau} E(phi) sin(phi) / sqrt(q),
 *     E(phi) = 1 - fade(clamp(1 + phi / 2pi, 0, 1)),  0 <= E <= 1.
 * With b >= 0 and tau > 0, e^{-b tau} <= 1, and 1/sqrt(q) <= 1, so
 *     |h| <= |I0|.
 * Gradient: grad h = dh/dq grad q, grad q = k^2 (p - c) / q, and
 * |grad q| = k (k r) / sqrt(k^2 r^2 + 1) < k. With E' = dE/dphi,
 *     dh/dq = I0 e^{-b tau} q^{-1/2} [ (E' - E / (2q)) sin phi + E cos phi ].
 * |a sin + b cos| <= sqrt(a^2 + b^2); E' <= 0 and -E/(2q) <= 0 have one
 * sign, so |E' - E/(2q)| <= max|E'| + 1/2, and max|E'| = max fade' / 2pi =
 * (30/16) / 2pi = 15 / (16 pi) (fade'(x) = 30 x^2 (1-x)^2, largest at 1/2).
 *     |grad h| <= |I0| k sqrt((15/(16 pi) + 1/2)^2 + 1) = 1.27967.. |I0| k.
 *
 * Perlin noise3. n(x) = sum over the 8 corners of w_i(x) (g_i . d_i), with
 * w_i the products of fades (w_i >= 0, sum 1) and d_i = x - corner_i. The
 * hash may pick any of the 12 edge vectors at any corner, so
 *     |n| <= max over x in [0,1]^3 of sum_i w_i max_g |g . d_i|;
 * an exhaustive search (a 65^3 grid, each candidate refined by hill
 * climbing to 1e-7) finds 1.03635 (at (0.3553, 0.4815, 0.5) and its
 * mirror images): PERLIN3_VALUE_BOUND = 1.04. (Sampled noise stays within
 * [-1, 1] in practice; the worst case needs an adversarial hash.)
 * Per axis j, |dn/dx_j| <= sum_i max_g |dw_i/dx_j (g . d_i) + w_i g_j|;
 * the same search puts its maximum at the cell centre, where it is
 * 8 * (15/8)(1/4)(1) / 2 = 15/4 (dw/dx_j = 15/32, g . d = 1 with g_j = 0),
 * so |(dn/dx, dn/dy)| <= 15 sqrt(2) / 4 and |grad n| <= 15 sqrt(3) / 4.
 * Perlin set: octave o adds A_o n(...) with d/du, d/dv of its arguments
 * at most f_o * max(1, 1/stretch) in the (x, y) pair only, so
 *     |h| <= 1.04 sum |A_o|,  |grad h| <= 15 sqrt(2)/4 max(1, 1/stretch) sum |A_o| f_o.
 */
#include "ref_wavefx.h"
#include "ref_hash.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define TWO_PI (2.0 * M_PI)
#define WAVEFX_GRAVITY 9.81                 /* as ref_waves.h's REF_GRAVITY */
#define PERLIN3_VALUE_BOUND 1.04
#define PERLIN3_GRAD_XY_BOUND (15.0 * M_SQRT2 / 4.0)


static int fail(char *err, size_t errlen, const char *fmt, const char *what, double v) {
    if (err && errlen) snprintf(err, errlen, fmt, what, v);
    return -1;
}

int ref_explosion_resolve(ref_explosion_desc *e, char *err, size_t errlen) {
    const double vals[] = { e->center[0], e->center[1], e->start, e->i0, e->omega, e->k, e->decay };
    const char *names[] = { "center x", "center z", "start", "I0", "omega", "k", "decay" };
    for (int i = 0; i < 7; i++)
        if (!isfinite(vals[i])) return fail(err, errlen, "explosion: %s is not finite (%g)", names[i], vals[i]);
    if (e->k < 0) return fail(err, errlen, "explosion: %s must be positive (%g)", "k", e->k);
    if (e->omega < 0) return fail(err, errlen, "explosion: %s must be positive (%g)", "omega", e->omega);
    if (e->decay < 0) return fail(err, errlen, "explosion: %s must not be negative (%g)", "decay", e->decay);
    if (e->k == 0) e->k = TWO_PI;                               /* a 1 m wavelength */
    if (e->omega == 0) e->omega = sqrt(WAVEFX_GRAVITY * e->k);  /* deep water */
    return 0;
}

int ref_perlin_resolve(ref_perlin_desc *p, char *err, size_t errlen) {
    const double vals[] = { p->amplitude, p->cell, p->gain, p->stretch, p->angle_deg, p->rate };
    const char *names[] = { "amplitude", "cell", "gain", "stretch", "angle", "rate" };
    for (int i = 0; i < 6; i++)
        if (!isfinite(vals[i])) return fail(err, errlen, "perlin: %s is not finite (%g)", names[i], vals[i]);
    if (p->cell < 0) return fail(err, errlen, "perlin: %s must be positive (%g)", "cell", p->cell);
    if (p->stretch < 0) return fail(err, errlen, "perlin: %s must be positive (%g)", "stretch", p->stretch);
    if (p->octaves < 0 || p->octaves > REF_PERLIN_OCTAVES_MAX) {
        if (err && errlen)
            snprintf(err, errlen, "perlin: octaves must be 1..%d (%d)", REF_PERLIN_OCTAVES_MAX, p->octaves);
        return -1;
    }
    if (p->cell == 0) p->cell = 4.0;
    if (p->octaves == 0) p->octaves = 4;
    if (p->gain == 0) p->gain = 0.5;
    if (p->stretch == 0) p->stretch = 1.0;
    if (p->rate == 0) p->rate = 0.5;
    return 0;
}

static double fade(double x) { return x * x * x * (x * (x * 6.0 - 15.0) + 10.0); }
static double dfade(double x) { return 30.0 * x * x * (x - 1.0) * (x - 1.0); }

double ref_explosion_height(const ref_explosion_desc *e, double u, double v, double t, double grad[2]) {
    if (grad) grad[0] = grad[1] = 0.0;
    double tau = t - e->start;
    if (tau <= 0.0 || e->i0 == 0.0) return 0.0;
    double du = u - e->center[0], dv = v - e->center[1];
    double k = e->k;
    double q = sqrt(k * k * (du * du + dv * dv) + 1.0);    /* k s >= 1 */
    double phi = q - e->omega * tau;
    double x = 1.0 + phi / TWO_PI;                          /* (s - R + W) / W */
    if (x >= 1.0) return 0.0;                               /* beyond the front: E = 0 */
    double E = 1.0, dE = 0.0;
    if (x > 0.0) { E = 1.0 - fade(x); dE = -dfade(x) / TWO_PI; }
    double amp = e->i0 * exp(-e->decay * tau) / sqrt(q);
    double sn = sin(phi), cs = cos(phi);
    if (grad) {
        double dhdq = amp * ((dE - E / (2.0 * q)) * sn + E * cs);
        double g = dhdq * k * k / q;                       /* grad q = k^2 (p - c) / q */
        grad[0] = g * du;
        grad[1] = g * dv;
    }
    return amp * E * sn;
}

void ref_explosion_bounds(const ref_explosion_desc *e, double *height, double *slope) {
    double a = fabs(e->i0);
    double c = 15.0 / (16.0 * M_PI) + 0.5;
    if (height) *height = a;
    if (slope) *slope = a * e->k * sqrt(c * c + 1.0);
}

/* Perlin's 12 cube-edge gradients, in his order. */
static const double edge_grad[12][3] = {
    { 1, 1, 0 }, { -1, 1, 0 }, { 1, -1, 0 }, { -1, -1, 0 },
    { 1, 0, 1 }, { -1, 0, 1 }, { 1, 0, -1 }, { -1, 0, -1 },
    { 0, 1, 1 }, { 0, -1, 1 }, { 0, 1, -1 }, { 0, -1, -1 },
};

double ref_perlin3(double x, double y, double z, uint32_t seed, double grad[3]) {
    double fl[3] = { floor(x), floor(y), floor(z) };
    double f[3] = { x - fl[0], y - fl[1], z - fl[2] };
    uint32_t il[3];
    double w[3][2], dw[3][2];                              /* weight of corner bit 0 / 1 along an axis */
    for (int j = 0; j < 3; j++) {
        il[j] = (uint32_t)(int32_t)fl[j];
        double s = fade(f[j]), ds = dfade(f[j]);
        w[j][0] = 1.0 - s; w[j][1] = s;
        dw[j][0] = -ds;    dw[j][1] = ds;
    }
    double n = 0.0, g[3] = { 0, 0, 0 };
    for (int c = 0; c < 8; c++) {
        int b0 = c & 1, b1 = (c >> 1) & 1, b2 = (c >> 2) & 1;
        uint32_t h = ref_hash32(il[0] + (uint32_t)b0 + ref_hash32(il[1] + (uint32_t)b1 + ref_hash32(il[2] + (uint32_t)b2 + seed)));
        const double *gv = edge_grad[h % 12u];
        double d0 = f[0] - b0, d1 = f[1] - b1, d2 = f[2] - b2;
        double val = gv[0] * d0 + gv[1] * d1 + gv[2] * d2;
        double wx = w[0][b0], wy = w[1][b1], wz = w[2][b2];
        double wc = wx * wy * wz;
        n += wc * val;
        g[0] += dw[0][b0] * wy * wz * val + wc * gv[0];
        g[1] += wx * dw[1][b1] * wz * val + wc * gv[1];
        g[2] += wx * wy * dw[2][b2] * val + wc * gv[2];
    }
    if (grad) { grad[0] = g[0]; grad[1] = g[1]; grad[2] = g[2]; }
    return n;
}

/* Octave o's seed, frequency (1/m), time rate (lattice units/s) and amplitude. */
static uint32_t octave_seed(uint32_t seed, int o) { return ref_hash32(seed + (uint32_t)o * 0x9E3779B9U); }

double ref_perlin_height(const ref_perlin_desc *p, double u, double v, double t, double grad[2]) {
    if (grad) grad[0] = grad[1] = 0.0;
    if (p->amplitude == 0.0) return 0.0;
    double ang = p->angle_deg * (M_PI / 180.0);
    double ca = cos(ang), sa = sin(ang);
    double a = u * ca + v * sa;                 /* along the wind */
    double c = -u * sa + v * ca;                /* across it */
    double inv_stretch = 1.0 / p->stretch;
    double h = 0.0, ga = 0.0, gc = 0.0;
    double f = 1.0 / p->cell, amp = p->amplitude, rate = p->rate;
    for (int o = 0; o < p->octaves; o++) {
        double g3[3];
        double n = ref_perlin3(a * f, c * f * inv_stretch, t * rate, octave_seed(p->seed, o), g3);
        h += amp * n;
        ga += amp * f * g3[0];
        gc += amp * f * inv_stretch * g3[1];
        f *= 2.0;
        amp *= p->gain;
        rate *= M_SQRT2;
    }
    if (grad) {
        grad[0] = ga * ca - gc * sa;
        grad[1] = ga * sa + gc * ca;
    }
    return h;
}

void ref_perlin_bounds(const ref_perlin_desc *p, double *height, double *slope) {
    double hb = 0.0, sb = 0.0, f = 1.0 / p->cell, amp = fabs(p->amplitude);
    double widen = p->stretch < 1.0 ? 1.0 / p->stretch : 1.0;
    if (p->amplitude != 0.0)
        for (int o = 0; o < p->octaves; o++) {
            hb += amp * PERLIN3_VALUE_BOUND;
            sb += amp * f * widen * PERLIN3_GRAD_XY_BOUND;
            f *= 2.0;
            amp *= fabs(p->gain);
        }
    if (height) *height = hb;
    if (slope) *slope = sb;
}

static ref_waves_uniform *unif(ref_waves_uniform *out, int *n, int max, const char *name, int count, int comps) {
    if (*n >= max) return NULL;
    ref_waves_uniform *u = &out[(*n)++];
    memset(u, 0, sizeof *u);
    u->name = name;
    u->count = count;
    u->comps = comps;
    return u;
}

int ref_wavefx_uniforms(const ref_explosion_desc *e, int n, const ref_perlin_desc *p,
                        ref_waves_uniform *out, int max) {
    int w = 0, rings = 0;
    ref_waves_uniform *un = unif(out, &w, max, "uExplosionN", 1, 1);
    ref_waves_uniform *ue = unif(out, &w, max, "uExplosion", REF_EXPLOSIONS_MAX, 4);
    ref_waves_uniform *uw = unif(out, &w, max, "uExplosionWave", REF_EXPLOSIONS_MAX, 4);
    for (int i = 0; e && i < n && rings < REF_EXPLOSIONS_MAX; i++) {
        if (e[i].i0 == 0.0) continue;                   /* no ring: the shader loops over live ones only */
        if (ue) {
            float *v = &ue->v[rings * 4];
            v[0] = (float)e[i].center[0]; v[1] = (float)e[i].center[1];
            v[2] = (float)e[i].start;     v[3] = (float)e[i].i0;
        }
        if (uw) {
            float *v = &uw->v[rings * 4];
            v[0] = (float)e[i].omega; v[1] = (float)e[i].k;
            v[2] = (float)e[i].decay; v[3] = (float)(e[i].k * e[i].k);
        }
        rings++;
    }
    if (un) { un->is_int = 1; un->i = rings; }

    int oct = p && p->amplitude != 0.0 ? p->octaves : 0;
    if (oct > REF_PERLIN_OCTAVES_MAX) oct = REF_PERLIN_OCTAVES_MAX;
    ref_waves_uniform *upn = unif(out, &w, max, "uPerlinN", 1, 1);
    ref_waves_uniform *uo = unif(out, &w, max, "uPerlinOctave", REF_PERLIN_OCTAVES_MAX, 4);
    ref_waves_uniform *uf = unif(out, &w, max, "uPerlinFrame", 1, 4);
    ref_waves_uniform *us = unif(out, &w, max, "uPerlinSeed", REF_PERLIN_OCTAVES_MAX, 1);
    if (upn) { upn->is_int = 1; upn->i = oct; }
    if (us) us->is_uint = 1;
    if (oct > 0) {
        double f = 1.0 / p->cell, amp = p->amplitude, rate = p->rate;
        for (int o = 0; o < oct; o++) {
            if (uo) {
                uo->v[o * 4 + 0] = (float)f;
                uo->v[o * 4 + 1] = (float)rate;
                uo->v[o * 4 + 2] = (float)amp;
            }
            if (us) us->u[o] = octave_seed(p->seed, o);
            f *= 2.0;
            amp *= p->gain;
            rate *= M_SQRT2;
        }
        if (uf) {
            double ang = p->angle_deg * (M_PI / 180.0);
            uf->v[0] = (float)cos(ang);
            uf->v[1] = (float)sin(ang);
            uf->v[2] = (float)(1.0 / p->stretch);
        }
    }
    return w;
}
