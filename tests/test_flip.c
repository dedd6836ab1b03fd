/* ref_flip: LDR-FLIP and HDR-FLIP against the values of the authors' own
 * implementation (../shared/flip-oracle: image pairs and expected.csv from
 * NVlabs flip v1.6), and the paper's properties on synthetic images:
 * identical images give 0, one wrong pixel's error stays near it, every
 * value is in [0, 1], pooling and the mask, exposures, the magma map. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "image_io.h"
#include "ref_flip.h"

#define ORACLE TARN_SOURCE_DIR "/../shared/flip-oracle"

static bool oracle_present(void) {
    struct stat st;
    return stat(ORACLE "/expected.csv", &st) == 0;
}

typedef struct row {
    char ref[64], test[64], kind[8];
    double mean, median, q1, q3, min, max, start, stop;
    int num;
} row;

/* expected.csv: pair,kind,mean,weighted_median,q1,q3,min,max,start,stop,num */
static int read_rows(row *rows, int cap) {
    FILE *f = fopen(ORACLE "/expected.csv", "r");
    if (!f) return -1;
    char line[512];
    int n = 0;
    if (!fgets(line, sizeof line, f)) { fclose(f); return -1; }
    while (n < cap && fgets(line, sizeof line, f)) {
        row *r = &rows[n];
        memset(r, 0, sizeof *r);
        r->start = r->stop = NAN;
        char *fld[11];
        int k = 0;
        line[strcspn(line, "\r\n")] = '\0';
        for (char *p = line; k < 11; k++) {
            fld[k] = p;
            char *c = strchr(p, ',');
            if (!c) { k++; break; }
            *c = '\0';
            p = c + 1;
        }
        if (k < 8) continue;
        char *slash = strchr(fld[0], '/');
        if (!slash) continue;
        *slash = '\0';
        /* a name longer than the row holds is not the oracle's: skip it (the
         * row count is checked) rather than match a truncated name */
        if (snprintf(r->ref, sizeof r->ref, "%s", fld[0]) >= (int)sizeof r->ref ||
            snprintf(r->test, sizeof r->test, "%s", slash + 1) >= (int)sizeof r->test ||
            snprintf(r->kind, sizeof r->kind, "%s", fld[1]) >= (int)sizeof r->kind)
            continue;
        double *v[6] = { &r->mean, &r->median, &r->q1, &r->q3, &r->min, &r->max };
        for (int j = 0; j < 6; j++) *v[j] = atof(fld[2 + j]);
        if (k >= 11 && fld[8][0]) {
            r->start = atof(fld[8]);
            r->stop = atof(fld[9]);
            r->num = atoi(fld[10]);
        }
        n++;
    }
    fclose(f);
    return n;
}

static bool load(const char *name, img *im) {
    char p[512], err[512];
    snprintf(p, sizeof p, "%s/%s", ORACLE, name);
    if (!img_read(p, im, err, sizeof err)) { fprintf(stderr, "%s\n", err); return false; }
    return true;
}

/* Every pair of expected.csv: our pooled values against the authors'. */
static void test_oracle(void) {
    if (!oracle_present()) SKIP("no %s (the FLIP oracle sits beside the repository)", ORACLE);
    row rows[32];
    int n = read_rows(rows, 32);
    CHECK_GE(n, 8);
    for (int i = 0; i < n; i++) {
        const row *r = &rows[i];
        img a = {0}, b = {0};
        if (!load(r->test, &a) || !load(r->ref, &b)) { CHECK(!"oracle image readable"); continue; }
        bool hdr = strcmp(r->kind, "HDR") == 0;
        ref_fimage ft = { a.px, a.w, a.h, a.channels }, fr = { b.px, b.w, b.h, b.channels };
        ref_flip_desc d = { .hdr = hdr, .srgb = !hdr };
        ref_flip_result res;
        char err[256];
        bool ok = ref_flip_mean(&ft, &fr, NULL, &d, &res, err, sizeof err);
        CHECK_MSG(ok, "%s", err);
        fprintf(stderr, "  %s/%s %s: mean %.6f (theirs %.6f, %+.1e)  median %.6f (%.6f)  q1 %.6f (%.6f)  "
                "q3 %.6f (%.6f)  min %.6f (%.6f)  max %.6f (%.6f)",
                r->ref, r->test, r->kind, res.mean, r->mean, res.mean - r->mean, res.weighted_median, r->median,
                res.q1, r->q1, res.q3, r->q3, res.min, r->min, res.max, r->max);
        if (hdr) fprintf(stderr, "  exposures %.4f..%.4f x%d (theirs %.4f..%.4f x%d)", res.start_exposure,
                         res.stop_exposure, res.num_exposures, r->start, r->stop, r->num);
        fputc('\n', stderr);
        CHECK_NEAR(res.mean, r->mean, 1e-4);
        CHECK_NEAR(res.weighted_median, r->median, 2e-3);
        CHECK_NEAR(res.q1, r->q1, 2e-3);
        CHECK_NEAR(res.q3, r->q3, 2e-3);
        CHECK_NEAR(res.min, r->min, 1e-4);
        CHECK_NEAR(res.max, r->max, 1e-3);
        CHECK_EQ(res.pooled, (long)a.w * a.h);
        if (hdr) {
            CHECK_NEAR(res.start_exposure, r->start, 6e-5);
            CHECK_NEAR(res.stop_exposure, r->stop, 6e-5);
            CHECK_EQ(res.num_exposures, r->num);
        }
        img_free(&a);
        img_free(&b);
    }
}

/* ---- synthetic images --------------------------------------------------------- */

#define W 48
#define H 40

/* A textured test card: smooth colour gradients and a few edges. */
static void card(float *px, int ch) {
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float *p = px + (y * W + x) * ch;
            p[0] = (float)x / (W - 1);
            p[1] = (float)y / (H - 1);
            p[2] = ((x / 8 + y / 8) % 2) ? 0.8f : 0.2f;
            for (int c = 3; c < ch; c++) p[c] = 1;
        }
}

static void test_identical_is_zero(void) {
    static float a[W * H * 3], map[W * H];
    card(a, 3);
    ref_fimage fa = { a, W, H, 3 };
    for (int hdr = 0; hdr < 2; hdr++) {
        ref_flip_desc d = { .hdr = hdr };
        ref_flip_result r;
        char err[256];
        CHECK(ref_flip_map(&fa, &fa, &d, map, NULL, &r, err, sizeof err));
        for (int i = 0; i < W * H; i++) CHECK_EQ(map[i], 0);
        CHECK(r.mean == 0 && r.max == 0 && r.min == 0);
        CHECK_EQ(r.weighted_median, 0);
        CHECK_EQ(r.pooled, W * H);
    }
}

/* One wrong pixel: the error is largest there and zero beyond the reach
 * of the filters (the colour filter's radius plus the feature filter's). */
static void test_single_pixel_is_local(void) {
    static float a[W * H * 3], b[W * H * 3], map[W * H];
    for (int i = 0; i < W * H * 3; i++) a[i] = b[i] = 0.5f;
    int cx = 24, cy = 20;
    for (int c = 0; c < 3; c++) a[(cy * W + cx) * 3 + c] = 1.0f;
    ref_fimage fa = { a, W, H, 3 }, fb = { b, W, H, 3 };
    ref_flip_desc d = {0};
    char err[256];
    CHECK(ref_flip_map(&fa, &fb, &d, map, NULL, NULL, err, sizeof err));
    /* at 67 ppd: colour radius ceil(3 sqrt(0.04 / 2 pi^2) 67.02) = 10 */
    float peak = map[cy * W + cx];
    CHECK_GT(peak, 0.05f);
    int reach = 10;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float v = map[y * W + x];
            CHECK_LE(v, peak);
            if (abs(x - cx) > reach || abs(y - cy) > reach) CHECK_MSG(v == 0, "(%d, %d) = %g", x, y, v);
        }
    /* symmetric about the pixel */
    for (int k = 1; k < 6; k++) {
        CHECK_NEAR(map[cy * W + cx + k], map[cy * W + cx - k], 1e-6);
        CHECK_NEAR(map[(cy + k) * W + cx], map[(cy - k) * W + cx], 1e-6);
        CHECK_NEAR(map[cy * W + cx + k], map[(cy + k) * W + cx], 1e-6);
    }
}

/* Every value is in [0, 1], for extreme pairs too. Flat black against
 * flat white has no features, so its error is the same everywhere: the
 * colour term alone, remap(HyAB(black, white)^0.7) = remap(100^0.7). */
static void test_range(void) {
    static float a[W * H * 3], b[W * H * 3], map[W * H];
    unsigned s = 12345;
    for (int i = 0; i < W * H * 3; i++) {
        s = s * 1103515245u + 12345u;
        a[i] = (float)((s >> 8) & 0xffff) / 65535.0f;
        s = s * 1103515245u + 12345u;
        b[i] = (float)((s >> 8) & 0xffff) / 65535.0f * 4.0f - 1.0f;    /* out of range too */
    }
    ref_fimage fa = { a, W, H, 3 }, fb = { b, W, H, 3 };
    char err[256];
    for (int hdr = 0; hdr < 2; hdr++) {
        ref_flip_desc d = { .hdr = hdr };
        CHECK(ref_flip_map(&fa, &fb, &d, map, NULL, NULL, err, sizeof err));
        for (int i = 0; i < W * H; i++) CHECK(map[i] >= 0 && map[i] <= 1);
    }
    for (int i = 0; i < W * H * 3; i++) { a[i] = 0; b[i] = 1; }
    ref_flip_result r;
    ref_flip_desc d = {0};
    CHECK(ref_flip_map(&fa, &fb, &d, map, NULL, &r, err, sizeof err));
    CHECK_EQ(r.min, r.max);
    /* cmax = HyAB(green, blue)^0.7, from the CIELAB of sRGB green (87.735,
     * -86.183, 83.179) and blue (32.303, 79.197, -107.864), Hunt-adjusted;
     * 100^0.7 is above the knee 0.4 cmax: 0.95 + the rest scaled to 0.05 */
    double ga = 0.87735 * -86.183, gb = 0.87735 * 83.179, ba = 0.32303 * 79.197, bb = 0.32303 * -107.864;
    double cmax = pow(87.735 - 32.303 + hypot(ga - ba, gb - bb), 0.7), e = pow(100.0, 0.7);
    CHECK_GT(e, 0.4 * cmax);
    CHECK_NEAR(r.min, 0.95 + (e - 0.4 * cmax) / (0.6 * cmax) * 0.05, 1e-4);
}

/* The mask pools over its pixels only; NaN inputs are left out and
 * counted; the weighted quantiles follow their definition. */
static void test_pool(void) {
    float map[10] = { 0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 0.8f, 0.9f, NAN };
    unsigned char mask[10] = { 1, 1, 1, 1, 0, 0, 0, 0, 0, 1 };
    ref_flip_result r;
    ref_flip_pool(map, 10, 1, mask, &r);
    CHECK(r.pooled == 4 && r.invalid == 1 && r.pixels == 10);
    CHECK_NEAR(r.mean, 0.25, 1e-7);
    CHECK_NEAR(r.min, 0.1, 1e-7);
    CHECK_NEAR(r.max, 0.4, 1e-7);
    /* sum 1.0: running sums 0.1 0.3 0.6 1.0: > 0.5 first at 0.3, > 0.25
     * at 0.2, > 0.75 at 0.4 */
    CHECK_NEAR(r.weighted_median, 0.3, 1e-7);
    CHECK_NEAR(r.q1, 0.2, 1e-7);
    CHECK_NEAR(r.q3, 0.4, 1e-7);
    unsigned char none[10] = {0};
    ref_flip_pool(map, 10, 1, none, &r);
    CHECK(r.pooled == 0 && isnan(r.mean) && isnan(r.weighted_median));

    /* a NaN input pixel: NaN in the map, out of the pooled values */
    static float a[W * H * 3], b[W * H * 3], m[W * H];
    card(a, 3);
    card(b, 3);
    a[(5 * W + 5) * 3 + 1] = NAN;
    ref_fimage fa = { a, W, H, 3 }, fb = { b, W, H, 3 };
    char err[256];
    CHECK(ref_flip_map(&fa, &fb, NULL, m, NULL, &r, err, sizeof err));
    CHECK(isnan(m[5 * W + 5]));
    CHECK(r.invalid == 1 && r.pooled == W * H - 1);
    CHECK(isfinite(r.mean));
}

/* A grey (1-channel) image is its channel 0 on R, G and B; RGBA is RGB. */
static void test_channels(void) {
    static float g[W * H], rgb[W * H * 3], rgba[W * H * 4], m1[W * H], m2[W * H], ref[W * H * 3];
    card(rgba, 4);
    card(ref, 3);
    for (int i = 0; i < W * H; i++) {
        g[i] = rgba[i * 4 + 1];
        for (int c = 0; c < 3; c++) rgb[i * 3 + c] = g[i];
    }
    ref_fimage fg = { g, W, H, 1 }, frgb = { rgb, W, H, 3 }, fr = { ref, W, H, 3 }, fa = { rgba, W, H, 4 };
    char err[256];
    CHECK(ref_flip_map(&fg, &fr, NULL, m1, NULL, NULL, err, sizeof err));
    CHECK(ref_flip_map(&frgb, &fr, NULL, m2, NULL, NULL, err, sizeof err));
    for (int i = 0; i < W * H; i++) CHECK_EQ(m1[i], m2[i]);
    CHECK(ref_flip_map(&fa, &fr, NULL, m1, NULL, NULL, err, sizeof err));
    for (int i = 0; i < W * H; i++) CHECK_EQ(m1[i], 0);
}

static void test_errors(void) {
    static float a[W * H * 3], map[W * H];
    ref_fimage fa = { a, W, H, 3 }, fb = { a, W - 1, H, 3 }, fe = { NULL, 0, 0, 3 };
    char err[256] = "";
    CHECK(!ref_flip_map(&fa, &fb, NULL, map, NULL, NULL, err, sizeof err));
    CHECK_STR_CONTAINS(err, "sizes differ: A is 48x40, B is 47x40");
    CHECK(!ref_flip_map(&fe, &fa, NULL, map, NULL, NULL, err, sizeof err));
    CHECK_STR_CONTAINS(err, "A is empty");
    ref_flip_desc d = { .hdr = true, .fixed_exposures = true, .start_exposure = 2, .stop_exposure = 1 };
    CHECK(!ref_flip_map(&fa, &fa, &d, map, NULL, NULL, err, sizeof err));
    CHECK_STR_CONTAINS(err, "bad exposures");
}

/* Exposures: a constant reference has start == stop (Ymax = Ymedian), so
 * 2 exposures; x* maps to 0.85 through ACES; fixed exposures are used as
 * given; the exposure map holds i / (num - 1). */
static void test_exposures(void) {
    static float a[W * H * 3], b[W * H * 3], map[W * H], emap[W * H];
    for (int i = 0; i < W * H * 3; i++) a[i] = 0.25f;
    ref_fimage fa = { a, W, H, 3 };
    double start, stop;
    ref_flip_exposures(&fa, &start, &stop);
    CHECK_NEAR(start, stop, 1e-9);
    /* x* = 0.25 * 2^start maps to 0.85 */
    double x = 0.25 * pow(2.0, start) * 0.6;
    CHECK_NEAR(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.85, 1e-6);
    for (int i = 0; i < W * H * 3; i++) a[i] = 0;
    ref_flip_exposures(&fa, &start, &stop);
    CHECK(start == 0 && stop == 0);

    card(a, 3);
    card(b, 3);
    for (int i = 0; i < W * H * 3; i++) b[i] *= 1.5f;
    ref_fimage ft = { b, W, H, 3 };
    fa = (ref_fimage){ a, W, H, 3 };
    ref_flip_desc d = { .hdr = true, .fixed_exposures = true, .start_exposure = -3, .stop_exposure = 1 };
    ref_flip_result r;
    char err[256];
    CHECK(ref_flip_map(&ft, &fa, &d, map, emap, &r, err, sizeof err));
    CHECK(r.num_exposures == 4 && r.start_exposure == -3 && r.stop_exposure == 1);
    for (int i = 0; i < W * H; i++) {
        float k = emap[i] * 3;
        CHECK(fabsf(k - roundf(k)) < 1e-6f && emap[i] >= 0 && emap[i] <= 1);
    }
    d.num_exposures = 7;
    CHECK(ref_flip_map(&ft, &fa, &d, map, emap, &r, err, sizeof err));
    CHECK_EQ(r.num_exposures, 7);
}

/* Magma: its endpoints, entries by round(255 t), clamping, and the
 * colouring of masked and NaN pixels. */
static void test_magma(void) {
    float c[3];
    ref_flip_magma(0, c);
    CHECK_NEAR(c[0], 0, 1e-6); CHECK_NEAR(c[1], 0, 1e-6); CHECK_NEAR(c[2], 4 / 255.0, 1e-6);
    ref_flip_magma(1, c);
    CHECK_NEAR(c[0], 252 / 255.0, 1e-6); CHECK_NEAR(c[1], 253 / 255.0, 1e-6); CHECK_NEAR(c[2], 191 / 255.0, 1e-6);
    float d[3];
    ref_flip_magma(2, d);
    CHECK(d[0] == c[0] && d[1] == c[1] && d[2] == c[2]);
    ref_flip_magma(NAN, d);
    CHECK_NEAR(d[2], 4 / 255.0, 1e-6);
    /* entries 128 and 64: t = 0.5 and t = 0.25 (and 0.2505: nearest) */
    ref_flip_magma(0.5, c);
    CHECK_NEAR(c[0], 0xb7 / 255.0, 1e-6); CHECK_NEAR(c[1], 0x37 / 255.0, 1e-6); CHECK_NEAR(c[2], 0x79 / 255.0, 1e-6);
    ref_flip_magma(0.2505, c);
    CHECK_NEAR(c[0], 0x51 / 255.0, 1e-6); CHECK_NEAR(c[1], 0x12 / 255.0, 1e-6); CHECK_NEAR(c[2], 0x7c / 255.0, 1e-6);
    float map[3] = { 0.5f, NAN, 1.0f }, rgb[9];
    unsigned char mask[3] = { 0, 1, 1 };
    ref_flip_colorize(map, 3, 1, mask, rgb);
    CHECK(rgb[0] == 0.5f && rgb[1] == 0.5f && rgb[2] == 0.5f);
    CHECK(rgb[3] == 0 && rgb[4] == 1 && rgb[5] == 1);
    CHECK_NEAR(rgb[6], 252 / 255.0, 1e-6);
}

int main(void) {
    RUN(test_oracle);
    RUN(test_identical_is_zero);
    RUN(test_single_pixel_is_local);
    RUN(test_range);
    RUN(test_pool);
    RUN(test_channels);
    RUN(test_errors);
    RUN(test_exposures);
    RUN(test_magma);
    return check_summary();
}
