/* test_noise: glman's built-in noise textures (viewer/gfx/noise.h). */
#include "check.h"
#include "noise.h"

#include <math.h>
#include <stdlib.h>

/* A deterministic sample sequence of the test's own (not the module's). */
static double test_rand(unsigned *s) {
    *s = *s * 1664525u + 1013904223u;
    return (double)(*s >> 8) / 16777216.0;
}

/* Each channel's standard deviation against glman's own textures' (issue
 * 14, measured on noise2d.064.tex / noise3d.064.tex). The tolerance is
 * +-20%: glman's figures are rounded measurements of one random texture,
 * and what a shader's look depends on is the size of each octave, not its
 * third digit. (The amplitudes were 0.5 / 2^c bounds before issue 14.) */
static void check_range_and_mean(const float *rgba, size_t n, const char *what, const double *std_want) {
    for (int c = 0; c < 4; c++) {
        double sum = 0, sq = 0, lo = 1e9, hi = -1e9;
        for (size_t t = 0; t < n; t++) {
            double v = rgba[t * 4 + c];
            sum += v;
            if (v < lo) lo = v;
            if (v > hi) hi = v;
        }
        double mean = sum / n;
        for (size_t t = 0; t < n; t++)
            sq += (rgba[t * 4 + c] - mean) * (rgba[t * 4 + c] - mean);
        double sd = sqrt(sq / n);
        CHECK_MSG(lo >= 0.0 && hi <= 1.0, "%s channel %d spans %g..%g", what, c, lo, hi);
        CHECK_MSG(fabs(mean - 0.5) <= 0.02, "%s channel %d mean %g", what, c, mean);
        CHECK_MSG(fabs(sd - std_want[c]) <= 0.2 * std_want[c], "%s channel %d std %g, glman's %g",
                  what, c, sd, std_want[c]);
    }
}

static const double glman_std_2d[4] = { 0.074, 0.024, 0.014, 0.0070 };
static const double glman_std_3d[4] = { 0.066, 0.032, 0.017, 0.0075 };

static void test_2d_range_mean(void) {
    const int sizes[] = {128, 64, 37, 1};
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
        int res = sizes[k];
        float *t = malloc((size_t)res * res * 4 * sizeof *t);
        CHECK(noise_2d(res, t));
        if (res > 1) check_range_and_mean(t, (size_t)res * res, "2D", glman_std_2d);
        else for (int c = 0; c < 4; c++) CHECK_EQ(t[c], 0.5f);    /* one texel: its mean */
        free(t);
    }
}

static void test_3d_range_mean(void) {
    const int res = 64;         /* glman's size */
    float *t = malloc((size_t)res * res * res * 4 * sizeof *t);
    CHECK(noise_3d(res, t));
    check_range_and_mean(t, (size_t)res * res * res, "3D", glman_std_3d);
    free(t);
}

/* The function itself: f(p + period) == f(p) on every axis, 0 on lattice points. */
static void test_function_periodic(void) {
    unsigned s = 12345;
    double biggest = 0;
    for (int i = 0; i < 2000; i++) {
        int period = 1 + (int)(test_rand(&s) * 40);
        double x = (test_rand(&s) - 0.5) * 200, y = (test_rand(&s) - 0.5) * 200;
        double z = (test_rand(&s) - 0.5) * 200;
        if (i == 0) { x = 0; y = 0.37; z = 0.81; }   /* exactly at 0 vs at the period */
        double f2 = noise_perlin2(x, y, period, 7);
        CHECK_NEAR(noise_perlin2(x + period, y, period, 7), f2, 1e-9);
        CHECK_NEAR(noise_perlin2(x, y + period, period, 7), f2, 1e-9);
        CHECK_NEAR(noise_perlin2(x - 3 * period, y + 2 * period, period, 7), f2, 1e-9);
        double f3 = noise_perlin3(x, y, z, period, 9);
        CHECK_NEAR(noise_perlin3(x + period, y, z, period, 9), f3, 1e-9);
        CHECK_NEAR(noise_perlin3(x, y + period, z, period, 9), f3, 1e-9);
        CHECK_NEAR(noise_perlin3(x, y, z - period, period, 9), f3, 1e-9);
        CHECK(fabs(f2) <= 1.0 + 1e-9 && fabs(f3) <= 1.0 + 1e-9);
        if (fabs(f2) > biggest) biggest = fabs(f2);
        /* gradient noise vanishes on the lattice */
        double li = floor(x), lj = floor(y), lk = floor(z);
        CHECK_NEAR(noise_perlin2(li, lj, period, 7), 0.0, 1e-12);
        CHECK_NEAR(noise_perlin3(li, lj, lk, period, 9), 0.0, 1e-12);
    }
    CHECK_GT(biggest, 0.5);     /* not a constant */
    /* seam continuity: approaching the period from below meets 0 from above */
    CHECK_NEAR(noise_perlin2(4.0 - 1e-7, 0.3, 4, 1), noise_perlin2(1e-7, 0.3, 4, 1), 1e-5);
    /* seeds are independent; period 0 is plain (non-wrapping) noise */
    CHECK(fabs(noise_perlin2(0.5, 0.5, 4, 1) - noise_perlin2(0.5, 0.5, 4, 2)) > 1e-6 ||
          fabs(noise_perlin2(1.5, 0.5, 4, 1) - noise_perlin2(1.5, 0.5, 4, 2)) > 1e-6);
    int differ = 0;
    for (int i = 0; i < 20; i++)
        differ += fabs(noise_perlin2(0.3 + i, 0.6, 0, 3) - noise_perlin2(4.3 + i, 0.6, 0, 3)) > 1e-6;
    CHECK_GT(differ, 10);
    /* absurd input gives a number, not a crash */
    CHECK(isfinite(noise_perlin2(NAN, 1, 4, 0)) && isfinite(noise_perlin3(1e300, -1e300, INFINITY, 0, 0)));
    CHECK(isfinite(noise_perlin2(1e300, 1, 4, 0)));
}

/* The texture wraps: across the seam (last texel -> first) it changes no
 * more than between any two neighbours inside. */
static void test_texture_tiles(void) {
    const int res = 64;
    float *t = malloc((size_t)res * res * 4 * sizeof *t);
    CHECK(noise_2d(res, t));
    for (int c = 0; c < 4; c++) {
        double inside = 0, seam_x = 0, seam_y = 0;
        for (int y = 0; y < res; y++) {
            for (int x = 0; x + 1 < res; x++)
                inside += fabs(t[(y * res + x + 1) * 4 + c] - t[(y * res + x) * 4 + c]);
            seam_x += fabs(t[(y * res + 0) * 4 + c] - t[(y * res + res - 1) * 4 + c]);
            seam_y += fabs(t[(0 * res + y) * 4 + c] - t[((res - 1) * res + y) * 4 + c]);
        }
        inside /= (double)res * (res - 1);
        seam_x /= res;
        seam_y /= res;
        CHECK_MSG(seam_x <= 1.6 * inside && seam_y <= 1.6 * inside,
                  "channel %d: seam %g / %g vs inside %g", c, seam_x, seam_y, inside);
    }
    free(t);

    const int r3 = 24;
    float *v = malloc((size_t)r3 * r3 * r3 * 4 * sizeof *v);
    CHECK(noise_3d(r3, v));
    double inside = 0, seam = 0;
    for (int z = 0; z < r3; z++)
        for (int y = 0; y < r3; y++) {
            size_t row = ((size_t)z * r3 + y) * r3;
            for (int x = 0; x + 1 < r3; x++) inside += fabs(v[(row + x + 1) * 4] - v[(row + x) * 4]);
            seam += fabs(v[row * 4] - v[(row + r3 - 1) * 4]);
            /* the z seam too */
            size_t first = ((size_t)0 * r3 + y) * r3 + (size_t)z, last = ((size_t)(r3 - 1) * r3 + y) * r3 + (size_t)z;
            seam += fabs(v[first * 4] - v[last * 4]);
        }
    inside /= (double)r3 * r3 * (r3 - 1);
    seam /= 2.0 * r3 * r3;
    CHECK_MSG(seam <= 1.6 * inside, "3D seam %g vs inside %g", seam, inside);
    free(v);
}

/* Each channel is an octave: twice the frequency of the one before. */
static void test_octaves(void) {
    const int res = 256;
    float *t = malloc((size_t)res * res * 4 * sizeof *t);
    CHECK(noise_2d(res, t));
    double wiggle[4];
    for (int c = 0; c < 4; c++) {
        double diff = 0, var = 0;
        for (int y = 0; y < res; y++)
            for (int x = 0; x < res; x++) {
                double v = t[(y * res + x) * 4 + c] - 0.5;
                var += v * v;
                diff += fabs(t[(y * res + (x + 1) % res) * 4 + c] - t[(y * res + x) * 4 + c]);
            }
        wiggle[c] = diff / sqrt(var / res / res) / res / res;   /* change per texel / spread */
    }
    for (int c = 1; c < 4; c++)
        CHECK_MSG(wiggle[c] / wiggle[c - 1] > 1.6 && wiggle[c] / wiggle[c - 1] < 2.4,
                  "channel %d vs %d: frequency ratio %g", c, c - 1, wiggle[c] / wiggle[c - 1]);
    free(t);
}

static void test_deterministic(void) {
    const int res = 48;
    float *a = malloc((size_t)res * res * 4 * sizeof *a), *b = malloc((size_t)res * res * 4 * sizeof *b);
    CHECK(noise_2d(res, a));
    srand(999);   /* the module must not depend on rand() */
    CHECK(noise_2d(res, b));
    CHECK_EQ(memcmp(a, b, (size_t)res * res * 4 * sizeof *a), 0);
    free(a); free(b);
    const int r3 = 16;
    a = malloc((size_t)r3 * r3 * r3 * 4 * sizeof *a);
    b = malloc((size_t)r3 * r3 * r3 * 4 * sizeof *b);
    CHECK(noise_3d(r3, a));
    srand(4);
    CHECK(noise_3d(r3, b));
    CHECK_EQ(memcmp(a, b, (size_t)r3 * r3 * r3 * 4 * sizeof *a), 0);
    free(a); free(b);
}

static void test_bad_args(void) {
    float one[4] = {9, 9, 9, 9};
    CHECK(!noise_2d(0, one));
    CHECK(!noise_2d(-5, one));
    CHECK(!noise_2d(NOISE_2D_MAX_RES + 1, one));
    CHECK(!noise_2d(16, NULL));
    CHECK(!noise_3d(0, one));
    CHECK(!noise_3d(NOISE_3D_MAX_RES + 1, one));
    CHECK(!noise_3d(8, NULL));
    CHECK(one[0] == 9 && one[3] == 9);      /* untouched on failure */
}

int main(void) {
    RUN(test_2d_range_mean);
    RUN(test_3d_range_mean);
    RUN(test_function_periodic);
    RUN(test_texture_tiles);
    RUN(test_octaves);
    RUN(test_deterministic);
    RUN(test_bad_args);
    return check_summary();
}
