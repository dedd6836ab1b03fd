/* The error metrics (reference/ref_metrics.h) against values worked out by
 * hand: RMSE over all channel values, PSNR = 20 log10(1 / RMSE), the
 * over-threshold share with the per-pixel error max over channels, NaN/Inf
 * and mask counts, percentiles, the heat map's colours, hit-point distances
 * in world units and texels, scalar buffers' absolute and relative error;
 * SSIM (reference/ref_ssim.h) against its closed forms. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "ref_metrics.h"
#include "ref_ssim.h"

#define W 8
#define H 4
#define N (W * H)

/* A w x h x c image, every value v. */
static float *filled(int w, int h, int c, float v) {
    float *p = malloc(sizeof *p * (size_t)(w * h * c));
    for (int i = 0; i < w * h * c; i++) p[i] = v;
    return p;
}

static float *px(float *im, int c, int x, int y) { return im + ((size_t)y * W + (size_t)x) * (size_t)c; }

static void test_identical_images(void) {
    float *a = filled(W, H, 3, 0.25f), *b = filled(W, H, 3, 0.25f);
    ref_fimage fa = { a, W, H, 3 }, fb = { b, W, H, 3 };
    ref_image_metrics m;
    char err[256] = "";
    CHECK(ref_metrics_image(&fa, &fb, NULL, &m, err, sizeof err));
    CHECK_EQ(m.rmse, 0);
    CHECK(isinf(m.psnr_db) && m.psnr_db > 0);
    CHECK(m.mae == 0 && m.max_abs == 0);
    CHECK(m.count.compared == N && m.count.pixels == N);
    CHECK(m.over_threshold == 0 && m.over_threshold_share == 0 && m.differing == 0);
    CHECK(m.threshold == REF_METRICS_THRESHOLD && m.peak == 1.0);
    CHECK(m.count.nan_a == 0 && m.count.nan_b == 0 && m.count.invalid == 0);
    free(a);
    free(b);
}

/* One value off by 0.1 among N pixels x 3 channels: RMSE = 0.1 / sqrt(3N). */
static void test_single_pixel_off(void) {
    float *a = filled(W, H, 4, 0.5f), *b = filled(W, H, 4, 0.5f);
    px(a, 4, 5, 2)[1] = 0.6f;
    px(a, 4, 1, 1)[3] = 0.0f;                  /* alpha: ignored */
    ref_fimage fa = { a, W, H, 4 }, fb = { b, W, H, 4 };
    ref_image_metrics m;
    CHECK(ref_metrics_image(&fa, &fb, NULL, &m, NULL, 0));
    double e = (double)0.6f - 0.5;             /* 0.1 as float arithmetic gives it */
    CHECK_NEAR(e, 0.1, 1e-7);
    CHECK_NEAR(m.rmse, e / sqrt(3.0 * N), 1e-12);
    CHECK_NEAR(m.rmse, 0.1 / sqrt(3.0 * N), 1e-8);
    CHECK_NEAR(m.psnr_db, 20 * log10(1 / m.rmse), 1e-12);
    CHECK_NEAR(m.psnr_db, 20 * log10(sqrt(3.0 * N) / 0.1), 1e-5);   /* 39.82 dB */
    CHECK_NEAR(m.mae, e / (3.0 * N), 1e-12);
    CHECK_NEAR(m.max_abs, e, 1e-12);
    CHECK(m.max_x == 5 && m.max_y == 2 && m.max_c == 1);
    CHECK(m.rmse_c[0] == 0 && m.rmse_c[2] == 0);
    CHECK_NEAR(m.rmse_c[1], e / sqrt((double)N), 1e-12);
    CHECK_NEAR(m.bias[1], e / N, 1e-12);
    CHECK_EQ(m.over_threshold, 1);
    CHECK_NEAR(m.over_threshold_share, 1.0 / N, 1e-15);
    CHECK_EQ(m.differing, 1);
    CHECK(m.pixel_err.median == 0 && m.pixel_err.max == m.max_abs);
    CHECK(m.pixel_err.max_x == 5 && m.pixel_err.max_y == 2);
    /* A higher threshold: nothing over it. */
    ref_metrics_desc d = { .threshold = 0.2 };
    CHECK(ref_metrics_image(&fa, &fb, &d, &m, NULL, 0));
    CHECK(m.over_threshold == 0 && m.over_threshold_share == 0 && m.threshold == 0.2);
    /* PSNR with another peak. */
    d.peak = 2;
    CHECK(ref_metrics_image(&fa, &fb, &d, &m, NULL, 0));
    CHECK_NEAR(m.psnr_db, 20 * log10(2 / m.rmse), 1e-12);
    free(a);
    free(b);
}

/* Per-pixel error is the max over channels (L-infinity): 0.04 in every
 * channel is not over 0.05 (its Euclidean norm 0.069 would be). */
static void test_threshold_share(void) {
    float *a = filled(4, 1, 3, 0), *b = filled(4, 1, 3, 0);
    const float err[4] = { 0.01f, 0.03f, 0.07f, 0.09f };
    for (int x = 0; x < 4; x++) a[3 * x] = err[x];
    ref_fimage fa = { a, 4, 1, 3 }, fb = { b, 4, 1, 3 };
    ref_image_metrics m;
    CHECK(ref_metrics_image(&fa, &fb, NULL, &m, NULL, 0));
    CHECK_EQ(m.over_threshold, 2);
    CHECK_NEAR(m.over_threshold_share, 0.5, 1e-15);
    a[0] = a[1] = a[2] = 0.04f;
    CHECK(ref_metrics_image(&fa, &fb, NULL, &m, NULL, 0));
    CHECK_EQ(m.over_threshold, 2);
    a[2] = 0.06f;
    CHECK(ref_metrics_image(&fa, &fb, NULL, &m, NULL, 0));
    CHECK_EQ(m.over_threshold, 3);
    CHECK_NEAR(m.over_threshold_share, 0.75, 1e-15);
    free(a);
    free(b);
}

/* NaN and Inf: counted per side over all pixels, left out of the stats. */
static void test_nan_and_inf_are_counted_and_left_out(void) {
    float *a = filled(W, H, 4, 0.5f), *b = filled(W, H, 4, 0.5f);
    px(a, 4, 0, 0)[0] = NAN;
    px(a, 4, 1, 0)[2] = NAN;
    px(a, 4, 2, 0)[1] = INFINITY;
    px(a, 4, 3, 0)[3] = NAN;                    /* alpha: not a compared channel */
    px(b, 4, 1, 0)[0] = NAN;                    /* both sides at (1, 0) */
    px(b, 4, 4, 0)[1] = -INFINITY;
    px(a, 4, 7, 3)[0] = 0.7f;                   /* the one real difference */
    ref_fimage fa = { a, W, H, 4 }, fb = { b, W, H, 4 };
    ref_image_metrics m;
    CHECK(ref_metrics_image(&fa, &fb, NULL, &m, NULL, 0));
    CHECK(m.count.nan_a == 2 && m.count.nan_b == 1);
    CHECK(m.count.inf_a == 1 && m.count.inf_b == 1);
    CHECK_EQ(m.count.invalid, 4);                /* (0,0) (1,0) (2,0) (4,0) */
    CHECK_EQ(m.count.compared, N - 4);
    double e = (double)0.7f - 0.5;
    CHECK_NEAR(m.rmse, e / sqrt(3.0 * (N - 4)), 1e-12);
    CHECK(m.max_x == 7 && m.max_y == 3);
    CHECK(isfinite(m.psnr_db));

    /* A mask leaves out (7, 3) and (0, 0): NaN still counted there. */
    unsigned char mask[N];
    memset(mask, 1, sizeof mask);
    mask[3 * W + 7] = 0;
    mask[0] = 0;
    ref_metrics_desc d = { .mask = mask };
    CHECK(ref_metrics_image(&fa, &fb, &d, &m, NULL, 0));
    CHECK_EQ(m.count.masked_out, 2);
    CHECK_EQ(m.count.nan_a, 2);
    CHECK_EQ(m.count.invalid, 3);
    CHECK_EQ(m.count.compared, N - 5);
    CHECK(m.rmse == 0 && isinf(m.psnr_db));

    /* Nothing left to compare: NaN statistics, not zeros. */
    memset(mask, 0, sizeof mask);
    CHECK(ref_metrics_image(&fa, &fb, &d, &m, NULL, 0));
    CHECK(m.count.compared == 0 && m.count.masked_out == N);
    CHECK(isnan(m.rmse) && isnan(m.psnr_db) && isnan(m.over_threshold_share) && isnan(m.pixel_err.median));
    CHECK_EQ(m.max_x, -1);
    free(a);
    free(b);
}

/* A 1-channel image is grey: it stands for R = G = B. */
static void test_grey_against_rgb(void) {
    float *g = filled(2, 2, 1, 0.5f), *rgb = filled(2, 2, 3, 0.5f);
    rgb[2] = 0.75f;                              /* pixel 0, blue */
    ref_fimage fg = { g, 2, 2, 1 }, fc = { rgb, 2, 2, 3 };
    ref_image_metrics m;
    CHECK(ref_metrics_image(&fg, &fc, NULL, &m, NULL, 0));
    CHECK_EQ(m.channels, 3);
    CHECK_NEAR(m.rmse, 0.25 / sqrt(12.0), 1e-15);
    CHECK_EQ(m.max_c, 2);
    CHECK_NEAR(m.bias[2], -0.25 / 4, 1e-15);
    free(g);
    free(rgb);
}

static void test_size_mismatch_is_an_error(void) {
    float *a = filled(4, 2, 3, 0), *b = filled(2, 4, 3, 0);
    ref_fimage fa = { a, 4, 2, 3 }, fb = { b, 2, 4, 3 };
    ref_image_metrics m;
    ref_point_metrics pm;
    char err[256] = "";
    CHECK(!ref_metrics_image(&fa, &fb, NULL, &m, err, sizeof err));
    CHECK_STR_CONTAINS(err, "A is 4x2, B is 2x4");
    ref_fimage grey = { a, 4, 2, 1 }, fa2 = { a, 4, 2, 3 };
    CHECK(!ref_metrics_points(&grey, &fa2, NULL, &pm, err, sizeof err));
    CHECK_STR_CONTAINS(err, "3 channels");
    ref_fimage empty = { NULL, 0, 0, 0 };
    CHECK(!ref_metrics_image(&empty, &fb, NULL, &m, err, sizeof err));
    CHECK_STR_CONTAINS(err, "A is empty");
    free(a);
    free(b);
}

static void test_percentiles(void) {
    double v[5] = { 5, 1, 4, 2, 3 };
    CHECK_EQ(ref_percentile(v, 5, 50), 3);          /* sorts v */
    CHECK(v[0] == 1 && v[4] == 5);
    CHECK_EQ(ref_percentile_sorted(v, 5, 0), 1);
    CHECK_EQ(ref_percentile_sorted(v, 5, 25), 2);
    CHECK_NEAR(ref_percentile_sorted(v, 5, 95), 4.8, 1e-12);   /* rank 3.8 */
    CHECK_NEAR(ref_percentile_sorted(v, 5, 99), 4.96, 1e-12);
    CHECK_EQ(ref_percentile_sorted(v, 5, 100), 5);
    CHECK_EQ(ref_percentile_sorted(v, 5, 150), 5);   /* clamped */
    double two[2] = { 2, 1 };
    CHECK_NEAR(ref_percentile(two, 2, 50), 1.5, 1e-15);
    double one = 7;
    CHECK_EQ(ref_percentile(&one, 1, 95), 7);
    CHECK(isnan(ref_percentile(NULL, 0, 50)));
    /* 0..99: p99 at rank 98.01 */
    double h[100];
    for (int i = 0; i < 100; i++) h[i] = 99 - i;
    CHECK_NEAR(ref_percentile(h, 100, 99), 98.01, 1e-12);
    CHECK_NEAR(ref_percentile_sorted(h, 100, 50), 49.5, 1e-12);
}

static void test_colormap_endpoints(void) {
    float c[3];
    ref_colormap_inferno(0, c);
    CHECK(c[0] == 0 && c[1] == 0);
    CHECK_NEAR(c[2], 4 / 255.0, 1e-7);
    ref_colormap_inferno(1, c);
    CHECK_NEAR(c[0], 252 / 255.0, 1e-7);
    CHECK_NEAR(c[1], 1.0, 1e-7);
    CHECK_NEAR(c[2], 164 / 255.0, 1e-7);
    ref_colormap_inferno(-3, c);
    CHECK_NEAR(c[2], 4 / 255.0, 1e-7);
    ref_colormap_inferno(NAN, c);
    CHECK_NEAR(c[2], 4 / 255.0, 1e-7);
    ref_colormap_inferno(7, c);
    CHECK_NEAR(c[0], 252 / 255.0, 1e-7);
    /* Entry 128 exactly (#bc3754), and halfway to entry 129 (#bd3853). */
    ref_colormap_inferno(128 / 255.0, c);
    CHECK_NEAR(c[0], 0xbc / 255.0, 1e-6);
    CHECK_NEAR(c[1], 0x37 / 255.0, 1e-6);
    CHECK_NEAR(c[2], 0x54 / 255.0, 1e-6);
    ref_colormap_inferno(128.5 / 255.0, c);
    CHECK_NEAR(c[0], 0xbc / 255.0 + 0.5 / 255.0, 1e-6);
    CHECK_NEAR(c[2], 0x54 / 255.0 - 0.5 / 255.0, 1e-6);
    /* Perceptual ramp: luminance (of the linear values) rises monotonically. */
    double prev = -1;
    int mono = 1;
    for (int i = 0; i <= 255; i++) {
        ref_colormap_inferno(i / 255.0, c);
        double y = 0.2126 * ref_srgb_to_linear(c[0]) + 0.7152 * ref_srgb_to_linear(c[1]) +
                   0.0722 * ref_srgb_to_linear(c[2]);
        if (y < prev - 1e-6) mono = 0;
        prev = y;
    }
    CHECK(mono);
}

static void test_heatmap_colours_and_scale(void) {
    /* 0, half the scale, the scale, NaN, masked out, twice the scale. */
    float f[6] = { 0, 0.05f, 0.1f, NAN, -1, 0.2f }, rgb[18], c[3];
    double s = ref_heatmap(f, 6, 1, 0.1, rgb);
    CHECK_EQ(s, 0.1);
    CHECK(rgb[0] == 0 && rgb[1] == 0);
    CHECK_NEAR(rgb[2], 4 / 255.0, 1e-7);
    ref_colormap_inferno(0.5, c);
    CHECK_NEAR(rgb[3], c[0], 1e-6);
    CHECK_NEAR(rgb[5], c[2], 1e-6);
    CHECK_NEAR(rgb[6], 252 / 255.0, 1e-6);
    CHECK_NEAR(rgb[8], 164 / 255.0, 1e-6);
    CHECK(rgb[9] == 0 && rgb[10] == 1 && rgb[11] == 1);       /* NaN: cyan */
    CHECK(rgb[12] == 0.5f && rgb[13] == 0.5f && rgb[14] == 0.5f); /* masked: grey */
    CHECK_NEAR(rgb[15], 252 / 255.0, 1e-6);                    /* clamped */

    /* Automatic scale: the 99th percentile of the compared values. */
    float g[101];
    for (int i = 0; i < 100; i++) g[i] = (float)i;
    g[100] = NAN;                                              /* not a value */
    CHECK_NEAR(ref_heatmap_auto_scale(g, 101), 98.01, 1e-9);
    float grgb[303];
    CHECK_NEAR(ref_heatmap(g, 101, 1, 0, grgb), 98.01, 1e-9);
    CHECK_NEAR(grgb[3 * 99 + 0], 252 / 255.0, 1e-6);          /* 99 > 98.01: top */
    /* 99% zeros: the max; all zero: 1. */
    float z[200] = {0};
    z[17] = 5;
    CHECK_EQ(ref_heatmap_auto_scale(z, 200), 5);
    z[17] = 0;
    CHECK_EQ(ref_heatmap_auto_scale(z, 200), 1);
    z[0] = -1;
    CHECK_EQ(ref_heatmap_auto_scale(z, 1), 1);
}

static void test_error_field(void) {
    float a[4 * 3] = { 0.5f, 0.5f, 0.5f,  0.5f, 0.75f, 0.5f,  NAN, 0, 0,  1, 1, 1 };
    float b[4 * 3] = { 0.5f, 0.5f, 0.5f,  0.5f, 0.5f, 0.25f,  0, 0, 0,   0, 0, 0 };
    unsigned char mask[4] = { 1, 1, 1, 0 };
    ref_fimage fa = { a, 2, 2, 3 }, fb = { b, 2, 2, 3 };
    ref_metrics_desc d = { .mask = mask };
    float f[4];
    CHECK(ref_metrics_error_field(&fa, &fb, REF_ERR_COLOR, &d, f, NULL, 0));
    CHECK(f[0] == 0 && f[1] == 0.25f && isnan(f[2]) && f[3] == -1);
    CHECK(ref_metrics_error_field(&fa, &fb, REF_ERR_POINT, &d, f, NULL, 0));
    CHECK_NEAR(f[1], sqrt(0.25 * 0.25 * 2), 1e-7);
}

/* Hit points: Euclidean distance in world units, and / texel size. */
static void test_hit_point_distance_and_texels(void) {
    float *a = filled(W, H, 3, 1.0f), *b = filled(W, H, 3, 1.0f);
    float *p = px(a, 3, 3, 1);
    p[0] += 3; p[2] += 4;                       /* 5 world units */
    p = px(a, 3, 6, 2);
    p[1] -= 2;                                  /* 2 world units */
    ref_fimage fa = { a, W, H, 3 }, fb = { b, W, H, 3 };
    ref_metrics_desc d = { .texel_size = 0.25 };
    ref_point_metrics m;
    CHECK(ref_metrics_points(&fa, &fb, &d, &m, NULL, 0));
    CHECK_EQ(m.count.compared, N);
    CHECK_NEAR(m.world.max, 5, 1e-12);
    CHECK(m.world.max_x == 3 && m.world.max_y == 1);
    CHECK_NEAR(m.world.mean, 7.0 / N, 1e-12);
    CHECK_NEAR(m.world.rms, sqrt(29.0 / N), 1e-12);
    CHECK_EQ(m.world.median, 0);
    /* sorted: 30 zeros, 2, 5; p95 at rank 0.95 * 31 = 29.45 -> 0.45 * 2 */
    CHECK_NEAR(m.world.p95, 0.9, 1e-12);
    CHECK_NEAR(m.world.p99, 2 + 0.69 * 3, 1e-12);   /* rank 30.69 */
    CHECK_EQ(m.texel_size, 0.25);
    CHECK_NEAR(m.texels.max, 20, 1e-12);
    CHECK_NEAR(m.texels.mean, 28.0 / N, 1e-12);
    CHECK_NEAR(m.texels.p95, 3.6, 1e-12);
    /* Without a texel size there are no texel statistics; a miss (NaN in
     * both) is counted and left out. */
    px(a, 3, 0, 0)[0] = NAN;
    px(b, 3, 0, 0)[1] = NAN;
    d.texel_size = 0;
    d.threshold = 3;
    CHECK(ref_metrics_points(&fa, &fb, &d, &m, NULL, 0));
    CHECK(m.texels.n == 0 && isnan(m.texels.max));
    CHECK(m.count.nan_a == 1 && m.count.nan_b == 1 && m.count.invalid == 1 && m.count.compared == N - 1);
    CHECK_EQ(m.over_threshold, 1);
    CHECK_NEAR(m.over_threshold_share, 1.0 / (N - 1), 1e-15);
    free(a);
    free(b);
}

/* Scalar buffers: |a - b| and |a - b| / max(|b|, 1e-3), B the reference. */
static void test_scalar_abs_and_relative(void) {
    float a[4] = { 1.25f, 1.75f, 0.0005f, 0.5f };
    float b[4] = { 1.0f, 2.0f, 0.0f, 0.5f };
    ref_fimage fa = { a, 2, 2, 1 }, fb = { b, 2, 2, 1 };
    ref_scalar_metrics m;
    CHECK(ref_metrics_scalar(&fa, &fb, NULL, &m, NULL, 0));
    double e2 = (double)0.0005f;
    CHECK(m.channels == 1 && m.abs.n == 4 && m.rel_floor == REF_METRICS_REL_FLOOR);
    CHECK_NEAR(m.abs.max, 0.25, 1e-15);
    CHECK(m.abs.max_x == 0 && m.abs.max_y == 0);   /* the first of the two 0.25s */
    CHECK_NEAR(m.abs.mean, (0.5 + e2) / 4, 1e-12);
    CHECK_NEAR(m.abs.rms, sqrt((0.125 + e2 * e2) / 4), 1e-12);
    CHECK_NEAR(m.bias, (0.25 - 0.25 + e2) / 4, 1e-12);
    /* relative: 0.25, 0.125, 0.5 (floor), 0 */
    CHECK_NEAR(m.rel.max, e2 / 1e-3, 1e-9);
    CHECK_NEAR(m.rel.mean, (0.25 + 0.125 + e2 / 1e-3) / 4, 1e-9);
    CHECK_NEAR(m.rel.median, (0.125 + 0.25) / 2, 1e-12);
    /* Three channels against one: the one is broadcast. */
    float c3[12] = { 1, 1, 1,  2, 2, 2.5f,  0, 0, 0,  0.5f, 0.5f, 0.5f };
    ref_fimage f3 = { c3, 2, 2, 3 };
    CHECK(ref_metrics_scalar(&f3, &fb, NULL, &m, NULL, 0));
    CHECK(m.channels == 3 && m.abs.n == 12);
    CHECK_NEAR(m.abs.max, 0.5, 1e-15);
    CHECK(m.abs.max_x == 1 && m.abs.max_y == 0 && m.abs.max_c == 2);
}

static void test_srgb(void) {
    CHECK_EQ(ref_srgb_to_linear(0), 0);
    CHECK_NEAR(ref_srgb_to_linear(1), 1, 1e-15);
    CHECK_NEAR(ref_srgb_to_linear(0.5), 0.21404114048223255, 1e-12);
    CHECK_NEAR(ref_srgb_to_linear(0.04), 0.04 / 12.92, 1e-15);
    for (int i = 0; i <= 255; i++) {
        double c = i / 255.0;
        CHECK_NEAR(ref_linear_to_srgb(ref_srgb_to_linear(c)), c, 1e-12);
    }
}

/* ---- SSIM --------------------------------------------------------------------- */

#define SW 24
#define SH 20
#define SC1 (0.01 * 0.01)
#define SC2 (0.03 * 0.03)

/* A linear image whose display (sRGB-encoded luminance) value is v(x, y):
 * grey, so the luminance is the grey value itself. */
static float *grey_display(double (*v)(int x, int y, double p), double p) {
    float *im = malloc(sizeof *im * SW * SH * 3);
    for (int y = 0; y < SH; y++)
        for (int x = 0; x < SW; x++)
            for (int c = 0; c < 3; c++) im[(y * SW + x) * 3 + c] = (float)ref_srgb_to_linear(v(x, y, p));
    return im;
}

static double flat(int x, int y, double p) { (void)x; (void)y; return p; }
/* a checkerboard 0.5 +- 0.2, raised by p */
static double checker(int x, int y, double p) { return 0.5 + ((x + y) % 2 ? 0.2 : -0.2) + p; }
static double ramp(int x, int y, double p) { return (0.3 + 0.02 * x + 0.01 * y) * (1 - p) + p * ((x * 7 + y * 3) % 5) / 5.0; }

static void test_ssim_identical_is_one(void) {
    float *a = grey_display(ramp, 0.3), *m = malloc(sizeof *m * SW * SH);
    ref_fimage fa = { a, SW, SH, 3 };
    ref_ssim_result r;
    char err[256];
    for (int pc = 0; pc < 2; pc++) {
        ref_ssim_desc d = { .per_channel = pc };
        CHECK(ref_ssim(&fa, &fa, &d, m, &r, err, sizeof err));
        CHECK_NEAR(r.mean, 1, 1e-12);
        CHECK_NEAR(r.min, 1, 1e-12);
        /* only centres whose 11x11 window is inside: (SW - 10) x (SH - 10) */
        CHECK(r.pooled == (SW - 10) * (SH - 10) && r.border == SW * SH - r.pooled && r.invalid == 0);
        CHECK(isnan(m[0]) && isnan(m[4 * SW + 4]) && !isnan(m[5 * SW + 5]) && isnan(m[5 * SW + SW - 5]));
    }
    free(a);
    free(m);
}

/* Flat images of display values p and q: no variance, so SSIM is the
 * luminance term (2pq + C1) / (p^2 + q^2 + C1). */
static void test_ssim_flat_closed_form(void) {
    double p = 0.5, q = 0.7;
    float *a = grey_display(flat, p), *b = grey_display(flat, q);
    ref_fimage fa = { a, SW, SH, 3 }, fb = { b, SW, SH, 3 };
    ref_ssim_result r;
    char err[256];
    CHECK(ref_ssim(&fa, &fb, NULL, NULL, &r, err, sizeof err));
    CHECK_NEAR(r.mean, (2 * p * q + SC1) / (p * p + q * q + SC1), 1e-6);
    free(a);
    free(b);
}

/* A checkerboard and the same raised by a constant d: equal variances and
 * a covariance equal to them, so the contrast-structure term is 1 and
 * SSIM = (2 mu (mu + d) + C1) / (mu^2 + (mu + d)^2 + C1), mu the window's
 * weighted mean: 0.5 -+ 0.2 s^2 by the centre's parity, s = sum over k of
 * (-1)^k g_k with g the normalised 1D Gaussian (sd 1.5). */
static void test_ssim_offset_closed_form(void) {
    double dd = 0.1;
    float *a = grey_display(checker, 0), *b = grey_display(checker, dd), *m = malloc(sizeof *m * SW * SH);
    ref_fimage fa = { a, SW, SH, 3 }, fb = { b, SW, SH, 3 };
    double g[11], gs = 0, s = 0;
    for (int k = -5; k <= 5; k++) gs += g[k + 5] = exp(-k * k / (2 * 1.5 * 1.5));
    for (int k = -5; k <= 5; k++) s += (k % 2 ? -1 : 1) * g[k + 5] / gs;
    ref_ssim_result r;
    char err[256];
    CHECK(ref_ssim(&fa, &fb, NULL, m, &r, err, sizeof err));
    double sum = 0;
    for (int y = 5; y < SH - 5; y++)
        for (int x = 5; x < SW - 5; x++) {
            double mu = 0.5 + ((x + y) % 2 ? 0.2 : -0.2) * s * s;
            double want = (2 * mu * (mu + dd) + SC1) / (mu * mu + (mu + dd) * (mu + dd) + SC1);
            CHECK_NEAR(m[y * SW + x], want, 2e-6);
            sum += want;
        }
    CHECK_NEAR(r.mean, sum / r.pooled, 2e-6);
    CHECK_LT(r.mean, 1);
    free(a);
    free(b);
    free(m);
}

/* SSIM(a, b) == SSIM(b, a), per pixel; the mask pools its own centres;
 * a NaN leaves out the centres whose window touches it. */
static void test_ssim_symmetry_mask_nan(void) {
    float *a = grey_display(ramp, 0.2), *b = grey_display(ramp, 0.6);
    float *m1 = malloc(sizeof *m1 * SW * SH), *m2 = malloc(sizeof *m2 * SW * SH);
    ref_fimage fa = { a, SW, SH, 3 }, fb = { b, SW, SH, 3 };
    ref_ssim_result r1, r2;
    char err[256];
    CHECK(ref_ssim(&fa, &fb, NULL, m1, &r1, err, sizeof err));
    CHECK(ref_ssim(&fb, &fa, NULL, m2, &r2, err, sizeof err));
    CHECK_NEAR(r1.mean, r2.mean, 1e-12);
    for (int i = 0; i < SW * SH; i++) CHECK((isnan(m1[i]) && isnan(m2[i])) || fabsf(m1[i] - m2[i]) <= 1e-7f);
    CHECK(r1.mean < 1 && r1.mean > -1);

    unsigned char mask[SW * SH] = {0};
    mask[7 * SW + 9] = mask[8 * SW + 12] = 1;
    mask[0] = 1;                                   /* on the border: not pooled */
    ref_ssim_desc d = { .mask = mask };
    CHECK(ref_ssim(&fa, &fb, &d, NULL, &r2, err, sizeof err));
    CHECK(r2.pooled == 2 && r2.border == 1);
    CHECK_NEAR(r2.mean, (m1[7 * SW + 9] + m1[8 * SW + 12]) / 2.0, 1e-7);

    a[(10 * SW + 10) * 3 + 1] = NAN;
    CHECK(ref_ssim(&fa, &fb, NULL, m1, &r2, err, sizeof err));
    /* centres x 5..15, y 5..14 (the last row inside is SH - 6 = 14) */
    CHECK_EQ(r2.invalid, 11 * 10);
    CHECK(isnan(m1[10 * SW + 10]) && isnan(m1[14 * SW + 15]) && !isnan(m1[14 * SW + 16]) && !isnan(m1[10 * SW + 4 + 12]));
    CHECK_EQ(r2.pooled + r2.invalid, r1.pooled);

    ref_fimage small = { a, 10, 10, 3 };
    CHECK(!ref_ssim(&small, &small, NULL, NULL, &r2, err, sizeof err));
    CHECK_STR_CONTAINS(err, "at least 11x11");
    ref_fimage other = { b, SW - 1, SH, 3 };
    CHECK(!ref_ssim(&fa, &other, NULL, NULL, &r2, err, sizeof err));
    CHECK_STR_CONTAINS(err, "sizes differ");
    free(a);
    free(b);
    free(m1);
    free(m2);
}

int main(void) {
    RUN(test_identical_images);
    RUN(test_single_pixel_off);
    RUN(test_threshold_share);
    RUN(test_nan_and_inf_are_counted_and_left_out);
    RUN(test_grey_against_rgb);
    RUN(test_size_mismatch_is_an_error);
    RUN(test_percentiles);
    RUN(test_colormap_endpoints);
    RUN(test_heatmap_colours_and_scale);
    RUN(test_error_field);
    RUN(test_hit_point_distance_and_texels);
    RUN(test_scalar_abs_and_relative);
    RUN(test_srgb);
    RUN(test_ssim_identical_is_one);
    RUN(test_ssim_flat_closed_form);
    RUN(test_ssim_offset_closed_form);
    RUN(test_ssim_symmetry_mask_nan);
    return check_summary();
}
