/* noise.c: tileable Perlin gradient noise for glman's noise textures. */
#include "noise.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#define NOISE_OCTAVES 4
#define NOISE_SEED 0x7a726eu    /* fixed: the texture never changes */

/* A well-mixed 32-bit integer hash (lowbias32). */
static uint32_t hash32(uint32_t x) {
    x ^= x >> 16; x *= 0x7feb352dU;
    x ^= x >> 15; x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

static uint32_t lattice_hash(int64_t i, int64_t j, int64_t k, int period, unsigned seed) {
    if (period > 0) {           /* wrap the lattice: this is what makes it tile */
        i %= period; if (i < 0) i += period;
        j %= period; if (j < 0) j += period;
        k %= period; if (k < 0) k += period;
    }
    uint32_t h = hash32(seed ^ 0x9e3779b9U);
    h = hash32(h ^ (uint32_t)i);
    h = hash32(h ^ (uint32_t)j);
    return hash32(h ^ (uint32_t)k);
}

/* Brings a coordinate into the range where its floor fits an integer:
 * exactly (fmod) for periodic noise; far-away coordinates give 0 otherwise. */
static bool reduce(double *x, int period) {
    if (!isfinite(*x)) return false;
    if (period > 0) *x = fmod(*x, (double)period);
    return fabs(*x) < 1e15;
}

static double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }
static double lerp(double a, double b, double t) { return a + (b - a) * t; }

/* 2D: 16 unit gradients evenly around the circle. */
static double grad2(uint32_t h, double dx, double dy) {
    static const double c[16] = {
        1.0, 0.92387953, 0.70710678, 0.38268343, 0.0, -0.38268343, -0.70710678, -0.92387953,
        -1.0, -0.92387953, -0.70710678, -0.38268343, 0.0, 0.38268343, 0.70710678, 0.92387953};
    unsigned k = h & 15u;
    return c[k] * dx + c[(k + 12u) & 15u] * dy;     /* (cos, sin) */
}

/* 3D: Perlin's 12 cube-edge directions, unit length. */
static double grad3(uint32_t h, double dx, double dy, double dz) {
    static const signed char g[12][3] = {
        {1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1}, {-1, 0, 1},
        {1, 0, -1}, {-1, 0, -1}, {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}};
    const signed char *v = g[h % 12u];
    return (v[0] * dx + v[1] * dy + v[2] * dz) * 0.70710678118654752;
}

double noise_perlin2(double x, double y, int period, unsigned seed) {
    if (!reduce(&x, period) || !reduce(&y, period)) return 0.0;
    double fx0 = floor(x), fy0 = floor(y);
    int64_t i = (int64_t)fx0, j = (int64_t)fy0;
    double dx = x - fx0, dy = y - fy0;
    double n00 = grad2(lattice_hash(i, j, 0, period, seed), dx, dy);
    double n10 = grad2(lattice_hash(i + 1, j, 0, period, seed), dx - 1.0, dy);
    double n01 = grad2(lattice_hash(i, j + 1, 0, period, seed), dx, dy - 1.0);
    double n11 = grad2(lattice_hash(i + 1, j + 1, 0, period, seed), dx - 1.0, dy - 1.0);
    double u = fade(dx), v = fade(dy);
    /* max of 2D Perlin noise with unit gradients is sqrt(2)/2: scale to ~1 */
    return lerp(lerp(n00, n10, u), lerp(n01, n11, u), v) * 1.41421356237309505;
}

double noise_perlin3(double x, double y, double z, int period, unsigned seed) {
    if (!reduce(&x, period) || !reduce(&y, period) || !reduce(&z, period)) return 0.0;
    double fx0 = floor(x), fy0 = floor(y), fz0 = floor(z);
    int64_t i = (int64_t)fx0, j = (int64_t)fy0, k = (int64_t)fz0;
    double dx = x - fx0, dy = y - fy0, dz = z - fz0;
    double n[2][2][2];
    for (int c = 0; c < 2; c++)
        for (int b = 0; b < 2; b++)
            for (int a = 0; a < 2; a++)
                n[c][b][a] = grad3(lattice_hash(i + a, j + b, k + c, period, seed),
                                   dx - a, dy - b, dz - c);
    double u = fade(dx), v = fade(dy), w = fade(dz);
    double z0 = lerp(lerp(n[0][0][0], n[0][0][1], u), lerp(n[0][1][0], n[0][1][1], u), v);
    double z1 = lerp(lerp(n[1][0][0], n[1][0][1], u), lerp(n[1][1][0], n[1][1][1], u), v);
    /* unit gradients: the bound is sqrt(3)/2; scale to ~1 */
    return lerp(z0, z1, w) * 1.15470053837925153;
}

/* Centres each channel on 0.5 (mean exactly 0.5) and scales it to the
 * standard deviation glman's own textures have per channel (noise.h), so
 * a glman shader's thresholds and sums look as they did in glman. */
static void normalise(float *rgba, size_t ntexels, const double std_want[NOISE_OCTAVES]) {
    for (int c = 0; c < NOISE_OCTAVES; c++) {
        double sum = 0.0, sq = 0.0;
        for (size_t t = 0; t < ntexels; t++) sum += rgba[t * 4 + c];
        double mean = sum / (double)ntexels;
        for (size_t t = 0; t < ntexels; t++) {
            double e = rgba[t * 4 + c] - mean;
            sq += e * e;
        }
        double sd = sqrt(sq / (double)ntexels);
        double scale = sd > 1e-12 ? std_want[c] / sd : 0.0;
        for (size_t t = 0; t < ntexels; t++) {
            double v = 0.5 + (rgba[t * 4 + c] - mean) * scale;
            rgba[t * 4 + c] = (float)(v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v);
        }
    }
}

/* Measured on glman's noise2d.064.tex / noise3d.064.tex (docs/glman.md) */
static const double std_2d[NOISE_OCTAVES] = { 0.074, 0.024, 0.014, 0.0070 };
static const double std_3d[NOISE_OCTAVES] = { 0.066, 0.032, 0.017, 0.0075 };

bool noise_2d(int res, float *rgba) {
    if (!rgba || res < 1 || res > NOISE_2D_MAX_RES) return false;
    for (int c = 0; c < NOISE_OCTAVES; c++) {
        int period = NOISE_BASE_PERIODS << c;
        double step = (double)period / res;
        for (int y = 0; y < res; y++)
            for (int x = 0; x < res; x++)
                rgba[((size_t)y * res + x) * 4 + c] = (float)noise_perlin2(
                    (x + 0.5) * step, (y + 0.5) * step, period, NOISE_SEED + (unsigned)c);
    }
    normalise(rgba, (size_t)res * res, std_2d);
    return true;
}

bool noise_3d(int res, float *rgba) {
    if (!rgba || res < 1 || res > NOISE_3D_MAX_RES) return false;
    for (int c = 0; c < NOISE_OCTAVES; c++) {
        int period = NOISE_BASE_PERIODS << c;
        double step = (double)period / res;
        for (int z = 0; z < res; z++)
            for (int y = 0; y < res; y++)
                for (int x = 0; x < res; x++)
                    rgba[(((size_t)z * res + y) * res + x) * 4 + c] = (float)noise_perlin3(
                        (x + 0.5) * step, (y + 0.5) * step, (z + 0.5) * step, period,
                        NOISE_SEED + 101u + (unsigned)c);
    }
    normalise(rgba, (size_t)res * res * res, std_3d);
    return true;
}
