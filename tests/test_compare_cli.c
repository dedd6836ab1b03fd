/* `tarn compare A B`: on images this test writes, the JSON and CSV carry the
 * values worked out by hand, the heat map has the documented colours, the
 * reference buffers are compared, and bad input gives the documented exit
 * codes and messages naming the files. Most cases call cmd_compare_io()
 * directly; the last runs $TARN_BIN compare (skipped while main.c does not
 * know the command). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "check.h"
#include "support.h"
#include "cmd.h"
#include "compare.h"
#include "image_io.h"
#include "ref_metrics.h"

static char dir[256];
static char out_buf[65536], err_buf[65536];

/* ---- helpers ----------------------------------------------------------------- */

static const char *path(const char *name) {
    static char p[8][512];
    static int k;
    k = (k + 1) % 8;
    snprintf(p[k], sizeof p[k], "%s/%s", dir, name);
    return p[k];
}

static void slurp(FILE *f, char *buf, size_t len) {
    fflush(f);
    rewind(f);
    size_t n = fread(buf, 1, len - 1, f);
    buf[n] = '\0';
}

/* Runs cmd_compare_io on a space-separated argument line (printf-style);
 * stdout and stderr land in out_buf and err_buf. */
static int compare(const char *fmt, ...) {
    char line[4096];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    char *argv[64];
    int argc = 0;
    for (char *t = strtok(line, " "); t && argc < 64; t = strtok(NULL, " ")) argv[argc++] = t;
    FILE *o = tmpfile(), *e = tmpfile();
    if (!o || !e) { fprintf(stderr, "tmpfile failed\n"); exit(1); }
    int rc = cmd_compare_io(argc, argv, o, e);
    slurp(o, out_buf, sizeof out_buf);
    slurp(e, err_buf, sizeof err_buf);
    fclose(o);
    fclose(e);
    return rc;
}

static char *read_file(const char *p) {
    FILE *f = fopen(p, "rb");
    if (!f) return NULL;
    static char buf[65536];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

/* The number (or "inf" string, or null = NaN) after "key": in json, after
 * "section": { when section is given. found = 0 when the key is absent. */
static double jnum(const char *json, const char *section, const char *key, int *found) {
    char pat[128];
    if (found) *found = 0;
    if (!json) return NAN;
    if (section) {
        snprintf(pat, sizeof pat, "\"%s\": {", section);
        json = strstr(json, pat);
        if (!json) return NAN;
    }
    snprintf(pat, sizeof pat, "\"%s\": ", key);
    const char *p = strstr(json, pat);
    if (!p) return NAN;
    if (found) *found = 1;
    p += strlen(pat);
    if (strncmp(p, "\"inf\"", 5) == 0) return INFINITY;
    if (strncmp(p, "null", 4) == 0) return NAN;
    if (strncmp(p, "true", 4) == 0) return 1;
    if (strncmp(p, "false", 5) == 0) return 0;
    return strtod(p, NULL);
}

/* A minimal JSON validator: true when s is one well-formed value. */
static const char *jv_value(const char *s);
static const char *jv_ws(const char *s) { while (*s == ' ' || *s == '\n' || *s == '\t' || *s == '\r') s++; return s; }
static const char *jv_string(const char *s) {
    if (*s != '"') return NULL;
    for (s++; *s && *s != '"'; s++) {
        if ((unsigned char)*s < 0x20) return NULL;
        if (*s == '\\') { s++; if (!*s) return NULL; }
    }
    return *s == '"' ? s + 1 : NULL;
}
static const char *jv_value(const char *s) {
    s = jv_ws(s);
    if (*s == '{' || *s == '[') {
        char close = *s == '{' ? '}' : ']';
        s = jv_ws(s + 1);
        if (*s == close) return s + 1;
        for (;;) {
            if (close == '}') {
                if (!(s = jv_string(jv_ws(s)))) return NULL;
                s = jv_ws(s);
                if (*s++ != ':') return NULL;
            }
            if (!(s = jv_value(s))) return NULL;
            s = jv_ws(s);
            if (*s == ',') { s++; continue; }
            return *s == close ? s + 1 : NULL;
        }
    }
    if (*s == '"') return jv_string(s);
    if (!strncmp(s, "true", 4) || !strncmp(s, "null", 4)) return s + 4;
    if (!strncmp(s, "false", 5)) return s + 5;
    char *end;
    strtod(s, &end);
    return end != s && (*s == '-' || (*s >= '0' && *s <= '9')) ? end : NULL;
}
static int json_valid(const char *s) {
    const char *e = s ? jv_value(s) : NULL;
    return e && *jv_ws(e) == '\0';
}

/* Writes a w x h x c image whose every value is v. */
static img make(int w, int h, int c, float v) {
    img im;
    if (!img_alloc(&im, w, h, c)) { fprintf(stderr, "img_alloc failed\n"); exit(1); }
    for (long i = 0; i < (long)w * h * c; i++) im.px[i] = v;
    return im;
}

static void save(const char *p, img *im) {
    char err[512];
    if (!img_write(p, im, err, sizeof err)) fprintf(stderr, "img_write: %s\n", err);
    img_free(im);
}

static float *at(img *im, int x, int y) { return im->px + ((size_t)y * im->w + x) * im->channels; }

/* ---- cases ---------------------------------------------------------------------- */

/* 16x8, one value off by 0.1 (G at (5, 3)) and one NaN pixel in A:
 * RMSE over the 127 compared pixels x 3 channels = 0.1 / sqrt(381). */
static void test_json_has_the_hand_computed_values(void) {
    img a = make(16, 8, 3, 0.5f), b = make(16, 8, 3, 0.5f);
    at(&a, 5, 3)[1] = 0.6f;
    at(&a, 0, 0)[0] = NAN;
    save(path("a.tif"), &a);                    /* 32-bit float: exact */
    save(path("b.tif"), &b);
    int rc = compare("%s %s --json %s", path("a.tif"), path("b.tif"), path("m.json"));
    CHECK_MSG(rc == 0, "%s", err_buf);
    CHECK_STR_CONTAINS(out_buf, "RMSE");
    CHECK_STR_CONTAINS(out_buf, "PSNR");
    CHECK_STR_CONTAINS(out_buf, "NaN pixels in A");
    char *j = read_file(path("m.json"));
    CHECK(j && json_valid(j));
    double e = (double)0.6f - 0.5, rmse = e / sqrt(381.0);
    CHECK_NEAR(jnum(j, NULL, "rmse", NULL), rmse, 1e-9);
    CHECK_NEAR(jnum(j, NULL, "psnr_db", NULL), 20 * log10(1 / rmse), 1e-6);
    CHECK_NEAR(jnum(j, NULL, "max_abs", NULL), e, 1e-9);
    CHECK_EQ(jnum(j, NULL, "max_at_x", NULL), 5);
    CHECK_EQ(jnum(j, NULL, "max_at_y", NULL), 3);
    CHECK_EQ(jnum(j, NULL, "max_at_channel", NULL), 1);
    CHECK_NEAR(jnum(j, NULL, "mae", NULL), e / 381, 1e-9);
    CHECK_NEAR(jnum(j, NULL, "over_threshold_share", NULL), 1.0 / 127, 1e-9);
    CHECK_EQ(jnum(j, NULL, "threshold", NULL), 0.05);
    CHECK_EQ(jnum(j, NULL, "nan_pixels_a", NULL), 1);
    CHECK_EQ(jnum(j, NULL, "nan_pixels_b", NULL), 0);
    CHECK_EQ(jnum(j, NULL, "compared_pixels", NULL), 127);
    CHECK_EQ(jnum(j, NULL, "width", NULL), 16);
    CHECK_EQ(jnum(j, NULL, "height", NULL), 8);
    CHECK_EQ(jnum(j, NULL, "a_srgb_decoded", NULL), 0);
    int found;
    jnum(j, NULL, "heatmap", &found);
    CHECK(found);                               /* null without --out: keys are stable */
    /* FLIP (HDR: TIFF is linear) beside RMSE; SSIM needs 11x11: null */
    CHECK_STR_CONTAINS(j, "\"flip_kind\": \"HDR\"");
    double fm = jnum(j, NULL, "flip_mean", NULL);
    CHECK(fm > 0 && fm < 1);
    CHECK_GE(jnum(j, NULL, "flip_max", NULL), jnum(j, NULL, "flip_weighted_median", NULL));
    CHECK_GE(jnum(j, NULL, "flip_exposures", NULL), 2);
    CHECK(isnan(jnum(j, NULL, "ssim", &found)) && found);
    jnum(j, NULL, "flip_map", &found);
    CHECK(found);
    CHECK_STR_CONTAINS(out_buf, "FLIP, whole frame, mean");
    CHECK_STR_CONTAINS(out_buf, "at least 11x11");

    /* --threshold moves the share. */
    rc = compare("%s %s --threshold 0.2 --json %s", path("a.tif"), path("b.tif"), path("m.json"));
    CHECK_EQ(rc, 0);
    j = read_file(path("m.json"));
    CHECK_EQ(jnum(j, NULL, "over_threshold_share", NULL), 0);
    CHECK_EQ(jnum(j, NULL, "threshold", NULL), 0.2);
}

static void test_identical_images_psnr_inf(void) {
    img a = make(4, 4, 4, 0.3f), b = make(4, 4, 4, 0.3f);
    save(path("i1.exr"), &a);
    save(path("i2.exr"), &b);
    int rc = compare("%s %s --json %s --csv %s", path("i1.exr"), path("i2.exr"), path("i.json"), path("i.csv"));
    CHECK_MSG(rc == 0, "%s", err_buf);
    CHECK_STR_CONTAINS(out_buf, "inf");
    char *j = read_file(path("i.json"));
    CHECK(j && json_valid(j));
    CHECK_STR_CONTAINS(j, "\"psnr_db\": \"inf\"");
    CHECK_EQ(jnum(j, NULL, "rmse", NULL), 0);
    CHECK_EQ(jnum(j, NULL, "differing_pixels", NULL), 0);
    char *c = read_file(path("i.csv"));
    CHECK_STR_CONTAINS(c, ",inf,");
}

/* --csv -: a header row and a value row on stdout, the table on stderr. */
static void test_csv_to_stdout(void) {
    int rc = compare("%s %s --csv -", path("a.tif"), path("b.tif"));
    CHECK_MSG(rc == 0, "%s", err_buf);
    CHECK_STR_CONTAINS(err_buf, "RMSE");
    char *nl = strchr(out_buf, '\n');
    CHECK(nl && strchr(nl + 1, '\n') && *(strchr(nl + 1, '\n') + 1) == '\0');
    if (!nl) return;
    *nl = '\0';
    /* Find the rmse column. */
    int col = -1, k = 0;
    static char header[sizeof out_buf];
    memcpy(header, out_buf, sizeof header);
    for (char *t = strtok(header, ","); t; t = strtok(NULL, ","), k++)
        if (strcmp(t, "rmse") == 0) col = k;
    CHECK_GE(col, 0);
    CHECK_STR_CONTAINS(out_buf, "nan_pixels_a");
    CHECK_STR_CONTAINS(out_buf, "over_threshold_share");
    const char *v = nl + 1;
    for (k = 0; k < col && v; k++) {
        v = strchr(v, ',');
        if (v) v++;
    }
    CHECK(v && fabs(strtod(v, NULL) - ((double)0.6f - 0.5) / sqrt(381.0)) < 1e-9);
    CHECK_EQ(compare("%s %s --csv - --json -", path("a.tif"), path("b.tif")), 2);
}

/* PNG values are sRGB: 128/255 decodes to 0.2158605; --linear keeps it. */
static void test_png_is_srgb_decoded(void) {
    double lin = ref_srgb_to_linear(128 / 255.0);
    img a = make(8, 8, 3, 128 / 255.0f), b = make(8, 8, 3, (float)lin);
    save(path("s.png"), &a);
    save(path("s.tif"), &b);
    int rc = compare("%s %s --json %s", path("s.png"), path("s.tif"), path("s.json"));
    CHECK_MSG(rc == 0, "%s", err_buf);
    char *j = read_file(path("s.json"));
    CHECK_EQ(jnum(j, NULL, "a_srgb_decoded", NULL), 1);
    CHECK_EQ(jnum(j, NULL, "b_srgb_decoded", NULL), 0);
    CHECK_LT(jnum(j, NULL, "rmse", NULL), 1e-6);
    rc = compare("%s %s --linear --json %s", path("s.png"), path("s.tif"), path("s.json"));
    CHECK_EQ(rc, 0);
    j = read_file(path("s.json"));
    CHECK_EQ(jnum(j, NULL, "a_srgb_decoded", NULL), 0);
    CHECK_NEAR(jnum(j, NULL, "rmse", NULL), 128 / 255.0 - lin, 1e-6);
    CHECK(compare_is_srgb_path("x/y.PNG") && compare_is_srgb_path("a.jpeg"));
    CHECK(!compare_is_srgb_path("a.exr") && !compare_is_srgb_path("a.png/x") && !compare_is_srgb_path("noext"));
}

/* The heat map: inferno from black (no error) to pale yellow (--max), cyan
 * for NaN, grey outside the mask. */
static void test_heatmap_png(void) {
    img a = make(4, 2, 3, 0.5f), b = make(4, 2, 3, 0.5f);
    at(&a, 1, 0)[0] = 0.55f;                    /* half the scale */
    at(&a, 2, 0)[2] = 0.75f;                    /* over the scale */
    at(&b, 3, 0)[1] = NAN;
    at(&a, 0, 1)[0] = 0.9f;                     /* masked out */
    img mask = make(4, 2, 1, 1.0f);
    at(&mask, 0, 1)[0] = 0;
    save(path("h1.tif"), &a);
    save(path("h2.tif"), &b);
    save(path("mask.png"), &mask);
    int rc = compare("%s %s --out %s --max 0.1 --mask %s --json %s", path("h1.tif"), path("h2.tif"),
                     path("heat.png"), path("mask.png"), path("h.json"));
    CHECK_MSG(rc == 0, "%s", err_buf);
    char *j = read_file(path("h.json"));
    CHECK_EQ(jnum(j, NULL, "heatmap_scale", NULL), 0.1);
    CHECK_EQ(jnum(j, NULL, "masked_pixels", NULL), 1);
    CHECK_EQ(jnum(j, NULL, "nan_pixels_b", NULL), 1);
    CHECK_NEAR(jnum(j, NULL, "max_abs", NULL), 0.25, 1e-7);   /* not the masked 0.4 */
    img h;
    char err[512];
    CHECK_MSG(img_read(path("heat.png"), &h, err, sizeof err), "%s", err);
    if (!h.px) return;
    CHECK(h.w == 4 && h.h == 2 && h.channels == 3);
    float *p = at(&h, 0, 0);                    /* no error: inferno(0) = (0, 0, 4) */
    CHECK(p[0] == 0 && p[1] == 0 && fabsf(p[2] - 4 / 255.0f) < 1e-6f);
    float c[3];
    ref_colormap_inferno((double)(0.55f - 0.5f) / 0.1, c);
    p = at(&h, 1, 0);
    for (int k = 0; k < 3; k++) CHECK_LE(fabsf(p[k] - c[k]), 0.6f / 255);
    p = at(&h, 2, 0);                           /* clamped: (252, 255, 164) */
    CHECK(fabsf(p[0] - 252 / 255.0f) < 1e-6f && p[1] == 1 && fabsf(p[2] - 164 / 255.0f) < 1e-6f);
    p = at(&h, 3, 0);
    CHECK(p[0] == 0 && p[1] == 1 && p[2] == 1);   /* NaN: cyan */
    p = at(&h, 0, 1);
    CHECK(fabsf(p[0] - 0.5f) < 1 / 255.0f && p[0] == p[1] && p[1] == p[2]);   /* masked: grey */
    img_free(&h);
    /* Automatic scale: the 99th percentile of the per-pixel error. */
    rc = compare("%s %s --out %s --json %s", path("h1.tif"), path("h2.tif"), path("heat.png"), path("h.json"));
    CHECK_EQ(rc, 0);
    j = read_file(path("h.json"));
    /* 7 compared (the NaN pixel is not): 0 x4, 0.05, 0.25, 0.4 (unmasked
     * now); p99 at rank 0.99 * 6 = 5.94. */
    double e4 = (double)0.9f - 0.5;
    CHECK_NEAR(jnum(j, NULL, "heatmap_scale", NULL), 0.25 + 0.94 * (e4 - 0.25), 1e-6);
}

/* --buffers: X.refract_hit.exr (world units, texels), X.fresnel.exr; a
 * buffer on one side only is named and not compared. */
static void test_buffers(void) {
    mkdir(path("ra"), 0755);
    mkdir(path("rb"), 0755);
    img a = make(8, 4, 3, 0.25f), b = make(8, 4, 3, 0.25f);
    save(path("ra/x.exr"), &a);
    save(path("rb/x.exr"), &b);
    a = make(8, 4, 3, 2.0f);
    b = make(8, 4, 3, 2.0f);
    at(&a, 6, 1)[0] = 2.5f;                     /* 0.5 world units */
    at(&a, 2, 2)[1] = 1.875f;                   /* 0.125 */
    at(&a, 0, 0)[0] = NAN;                      /* a miss on one side */
    save(path("ra/x.refract_hit.exr"), &a);
    save(path("rb/x.refract_hit.exr"), &b);
    a = make(8, 4, 1, 0.5f);
    b = make(8, 4, 1, 0.5f);
    at(&a, 7, 3)[0] = 0.25f;
    save(path("ra/x.fresnel.exr"), &a);
    save(path("rb/x.fresnel.exr"), &b);
    a = make(8, 4, 1, 1.0f);
    save(path("ra/x.depth.exr"), &a);
    /* reflect: xyz + flag; flag 2 (REF_REFLECT_SKY) means xyz is a direction. */
    a = make(8, 4, 4, 1.0f);
    b = make(8, 4, 4, 1.0f);
    float *p = at(&a, 3, 0);
    p[0] = 0; p[1] = 1; p[2] = 0; p[3] = 2;     /* a direction in A: left out */
    p = at(&a, 4, 0);
    p[0] = 1.25f; p[3] = 3;                     /* met water instead of terrain */
    save(path("ra/x.reflect.exr"), &a);
    save(path("rb/x.reflect.exr"), &b);
    int rc = compare("%s %s --buffers --texel 0.25 --json %s --csv %s --out %s", path("ra/x.exr"),
                     path("rb/x.exr"), path("buf.json"), path("buf.csv"), path("bheat.png"));
    CHECK_MSG(rc == 0, "%s", err_buf);
    CHECK_STR_CONTAINS(err_buf, "depth");
    CHECK_STR_CONTAINS(err_buf, "ra/x.depth.exr");
    CHECK_STR_CONTAINS(err_buf, "not compared");
    CHECK_STR_CONTAINS(out_buf, "buffer refract_hit");
    CHECK_STR_CONTAINS(out_buf, "texels");
    char *j = read_file(path("buf.json"));
    CHECK_MSG(j && json_valid(j), "%s", j ? j : "(no file)");
    CHECK_EQ(jnum(j, NULL, "rmse", NULL), 0);
    CHECK_EQ(jnum(j, "refract_hit", "dist_max", NULL), 0.5);
    CHECK_EQ(jnum(j, "refract_hit", "dist_max_at_x", NULL), 6);
    CHECK_EQ(jnum(j, "refract_hit", "dist_max_at_y", NULL), 1);
    CHECK_NEAR(jnum(j, "refract_hit", "dist_mean", NULL), 0.625 / 31, 1e-9);
    CHECK_EQ(jnum(j, "refract_hit", "dist_median", NULL), 0);
    CHECK_EQ(jnum(j, "refract_hit", "texel_max", NULL), 2);
    CHECK_EQ(jnum(j, "refract_hit", "texel_size", NULL), 0.25);
    CHECK_EQ(jnum(j, "refract_hit", "nan_pixels_a", NULL), 1);
    CHECK_EQ(jnum(j, "refract_hit", "compared_pixels", NULL), 31);
    CHECK_EQ(jnum(j, "fresnel", "abs_max", NULL), 0.25);
    CHECK_EQ(jnum(j, "fresnel", "abs_max_at_x", NULL), 7);
    CHECK_EQ(jnum(j, "fresnel", "rel_max", NULL), 0.5);
    CHECK_NEAR(jnum(j, "fresnel", "bias", NULL), -0.25 / 32, 1e-12);
    CHECK(!strstr(j, "\"depth\""));
    int found;
    CHECK(isnan(jnum(j, "refract_hit", "flag_mismatch_pixels", &found)) && found);
    CHECK_EQ(jnum(j, "reflect", "direction_pixels", NULL), 1);
    CHECK_EQ(jnum(j, "reflect", "flag_mismatch_pixels", NULL), 2);
    CHECK_EQ(jnum(j, "reflect", "masked_pixels", NULL), 1);
    CHECK_EQ(jnum(j, "reflect", "compared_pixels", NULL), 31);
    CHECK_EQ(jnum(j, "reflect", "dist_max", NULL), 0.25);
    struct stat st;
    CHECK_EQ(stat(path("bheat.refract_hit.png"), &st), 0);
    CHECK_EQ(stat(path("bheat.fresnel.png"), &st), 0);
    char *c = read_file(path("buf.csv"));
    CHECK_STR_CONTAINS(c, "refract_hit.dist_max");
    CHECK_STR_CONTAINS(c, "fresnel.rel_p95");
    /* Nothing beside A or B: said, and still a comparison. */
    rc = compare("%s %s --buffers", path("a.tif"), path("b.tif"));
    CHECK_EQ(rc, 0);
    CHECK_STR_CONTAINS(err_buf, "no buffers");
}

/* 10x4 with B's class mask beside it (B.mask.exr, as `tarn reference`
 * writes): the left 4 columns water, the rest land. A is off by 0.2 on
 * the water only and by 0.05 in one channel of one land pixel, so the
 * water RMSE is 0.2, the off-water one 0.05 / sqrt(24 x 3) and the whole
 * frame mixes both. The water figures lead the table. */
static void test_water_first_from_the_reference_mask(void) {
    img a = make(10, 4, 3, 0.5f), b = make(10, 4, 3, 0.5f), m = make(10, 4, 1, 2.0f);   /* REF_MASK_TERRAIN */
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 4; x++) {
            at(&m, x, y)[0] = 1.0f;                                                       /* REF_MASK_WATER */
            for (int c = 0; c < 3; c++) at(&a, x, y)[c] = 0.7f;
        }
    at(&a, 9, 3)[0] = 0.55f;
    save(path("wa.tif"), &a);
    save(path("wb.exr"), &b);
    save(path("wb.mask.exr"), &m);
    int rc = compare("%s %s --json %s", path("wa.tif"), path("wb.exr"), path("w.json"));
    CHECK_MSG(rc == 0, "%s", err_buf);
    char *j = read_file(path("w.json"));
    CHECK(j && json_valid(j));
    double ew = (double)0.7f - 0.5, el = (double)0.55f - 0.5;
    CHECK_NEAR(jnum(j, NULL, "water_rmse", NULL), ew, 1e-6);
    CHECK_EQ(jnum(j, NULL, "water_pixels", NULL), 16);
    CHECK_NEAR(jnum(j, NULL, "off_water_rmse", NULL), el / sqrt(24.0 * 3), 1e-6);
    CHECK_EQ(jnum(j, NULL, "off_water_pixels", NULL), 24);
    CHECK_GT(jnum(j, NULL, "water_flip_mean", NULL), jnum(j, NULL, "off_water_flip_mean", NULL));
    int fnd;
    CHECK(isnan(jnum(j, NULL, "water_ssim", &fnd)) && fnd);     /* 10x4: smaller than SSIM's window */
    CHECK_NEAR(jnum(j, NULL, "rmse", NULL), sqrt((16 * 3 * ew * ew + el * el) / (40.0 * 3)), 1e-6);
    const char *water = strstr(out_buf, "water RMSE"), *whole = strstr(out_buf, "RMSE, whole frame");
    CHECK(water && whole && water < whole);
    /* without a mask beside B: the whole frame, and a note saying why */
    rc = compare("%s %s", path("wa.tif"), path("wa.tif"));
    CHECK_EQ(rc, 0);
    CHECK_STR_CONTAINS(out_buf, "water-only error");
    CHECK_STR_CONTAINS(out_buf, "FLIP, whole frame, mean");
}

/* FLIP and SSIM on display images: identical PNGs give FLIP 0 (LDR) and
 * SSIM 1, the FLIP map is magma's black (0, 0, 4); a changed square gives
 * FLIP > 0 there only and SSIM < 1; --flip-map greys what --mask leaves out. */
static void test_flip_and_ssim(void) {
    img a = make(32, 24, 3, 0.5f), b = make(32, 24, 3, 0.5f);
    save(path("fa.png"), &a);
    save(path("fb.png"), &b);
    int rc = compare("%s %s --json %s --flip-map %s", path("fa.png"), path("fb.png"), path("f.json"), path("flip.png"));
    CHECK_MSG(rc == 0, "%s", err_buf);
    char *j = read_file(path("f.json"));
    CHECK(j && json_valid(j));
    CHECK_STR_CONTAINS(j, "\"flip_kind\": \"LDR\"");
    CHECK_EQ(jnum(j, NULL, "flip_mean", NULL), 0);
    CHECK_EQ(jnum(j, NULL, "flip_max", NULL), 0);
    CHECK_NEAR(jnum(j, NULL, "flip_ppd", NULL), 67.0206, 1e-3);
    CHECK_NEAR(jnum(j, NULL, "ssim", NULL), 1, 1e-9);
    CHECK(isnan(jnum(j, NULL, "flip_start_exposure", NULL)));
    CHECK_STR_CONTAINS(j, path("flip.png"));
    img m;
    char e[512];
    CHECK(img_read(path("flip.png"), &m, e, sizeof e));
    CHECK(m.w == 32 && m.h == 24 && m.channels >= 3);
    CHECK(m.px[0] == 0 && m.px[1] == 0 && fabsf(m.px[2] - 4 / 255.0f) < 1e-6f);
    img_free(&m);

    a = make(32, 24, 3, 0.5f);
    for (int y = 8; y < 12; y++)
        for (int x = 4; x < 8; x++) at(&a, x, y)[0] = 0.9f;
    save(path("fa.png"), &a);
    img mk = make(32, 24, 1, 1.0f);
    for (int y = 0; y < 24; y++)
        for (int x = 16; x < 32; x++) at(&mk, x, y)[0] = 0;       /* the right half out */
    save(path("fmask.png"), &mk);
    rc = compare("%s %s --json %s --flip-map %s --mask %s", path("fa.png"), path("fb.png"), path("f.json"),
                 path("flip.png"), path("fmask.png"));
    CHECK_MSG(rc == 0, "%s", err_buf);
    j = read_file(path("f.json"));
    double fm = jnum(j, NULL, "flip_mean", NULL), ss = jnum(j, NULL, "ssim", NULL);
    CHECK(fm > 0 && fm < 1);
    CHECK(ss < 1 && ss > 0);
    CHECK_EQ(jnum(j, NULL, "flip_min", NULL), 0);               /* far from the square */
    CHECK_GT(jnum(j, NULL, "flip_max", NULL), 0.3);
    CHECK(img_read(path("flip.png"), &m, e, sizeof e));
    CHECK(fabsf(at(&m, 20, 10)[0] - 0.5f) < 0.01f && fabsf(at(&m, 20, 10)[1] - 0.5f) < 0.01f);   /* masked: grey */
    CHECK_GT(at(&m, 5, 9)[0], 0.3f);                              /* the square: bright */
    img_free(&m);
    /* without the mask the mean pools twice the pixels, and the little
     * error the filters spread into the right half */
    rc = compare("%s %s --json %s", path("fa.png"), path("fb.png"), path("f.json"));
    j = read_file(path("f.json"));
    double all = jnum(j, NULL, "flip_mean", NULL);
    CHECK(all > fm / 2 && all < fm * 0.6);
    rc = compare("%s %s --flip-map %s/no/such/dir.png", path("fa.png"), path("fb.png"), dir);
    CHECK_EQ(rc, 1);
    CHECK_STR_CONTAINS(err_buf, "FLIP map");
}

/* End to end on the FLIP oracle (../shared/flip-oracle): `tarn compare`
 * gives the authors' mean for an LDR and an HDR pair, and leads with the
 * water (ref.mask.exr is beside ref.exr and ref.png). */
static void test_flip_oracle_through_compare(void) {
    const char *o = TARN_SOURCE_DIR "/../shared/flip-oracle";
    struct stat st;
    if (stat(o, &st) != 0) SKIP("no %s", o);
    int rc = compare("%s/natural.png %s/ref.png --json %s", o, o, path("o.json"));
    CHECK_MSG(rc == 0, "%s", err_buf);
    char *j = read_file(path("o.json"));
    CHECK_STR_CONTAINS(j, "\"flip_kind\": \"LDR\"");
    CHECK_NEAR(jnum(j, NULL, "flip_mean", NULL), 0.050793, 1e-4);
    double w = jnum(j, NULL, "water_flip_mean", NULL), ow = jnum(j, NULL, "off_water_flip_mean", NULL);
    CHECK(w > ow && ow >= 0);
    CHECK_LT(jnum(j, NULL, "water_ssim", NULL), jnum(j, NULL, "off_water_ssim", NULL));
    rc = compare("%s/caustic_tex.exr %s/ref.exr --json %s", o, o, path("o.json"));
    CHECK_MSG(rc == 0, "%s", err_buf);
    j = read_file(path("o.json"));
    CHECK_STR_CONTAINS(j, "\"flip_kind\": \"HDR\"");
    CHECK_NEAR(jnum(j, NULL, "flip_mean", NULL), 0.135878, 1e-4);
    CHECK_NEAR(jnum(j, NULL, "flip_start_exposure", NULL), 1.4344, 1e-4);
    CHECK_NEAR(jnum(j, NULL, "flip_stop_exposure", NULL), 2.3352, 1e-4);
    CHECK_EQ(jnum(j, NULL, "flip_exposures", NULL), 2);
    const char *wf = strstr(out_buf, "water FLIP, mean"), *ff = strstr(out_buf, "FLIP, whole frame");
    CHECK(wf && ff && wf < ff);
}

static void test_mismatch_and_missing_files(void) {
    img a = make(16, 8, 3, 0), b = make(8, 16, 3, 0);
    save(path("w.exr"), &a);
    save(path("t.exr"), &b);
    int rc = compare("%s %s", path("w.exr"), path("t.exr"));
    CHECK_EQ(rc, 1);
    CHECK_STR_CONTAINS(err_buf, "w.exr");
    CHECK_STR_CONTAINS(err_buf, "t.exr");
    CHECK_STR_CONTAINS(err_buf, "16x8");
    CHECK_STR_CONTAINS(err_buf, "8x16");
    rc = compare("%s %s", path("nope-a.exr"), path("t.exr"));
    CHECK_EQ(rc, 1);
    CHECK_STR_CONTAINS(err_buf, "nope-a.exr");
    rc = compare("%s %s", path("nope-a.exr"), path("nope-b.png"));
    CHECK_EQ(rc, 1);
    CHECK_STR_CONTAINS(err_buf, "nope-a.exr");
    CHECK_STR_CONTAINS(err_buf, "nope-b.png");
    rc = compare("%s %s --mask %s", path("w.exr"), path("w.exr"), path("t.exr"));
    CHECK_EQ(rc, 1);
    CHECK_STR_CONTAINS(err_buf, "mask");
    rc = compare("%s %s --json %s/no/such/dir.json", path("w.exr"), path("w.exr"), dir);
    CHECK_EQ(rc, 1);
    CHECK_STR_CONTAINS(err_buf, "no/such/dir.json");
}

static void test_usage(void) {
    CHECK_EQ(compare("--help"), 0);
    const char *opts[] = { "--out", "--threshold", "--max", "--json", "--csv", "--buffers", "--texel",
                           "--mask", "--linear", "--flip-map", "FLIP", "SSIM", "exit codes" };
    for (int i = 0; i < (int)(sizeof opts / sizeof opts[0]); i++) CHECK_STR_CONTAINS(out_buf, opts[i]);
    CHECK_EQ(compare(""), 2);
    CHECK_STR_CONTAINS(err_buf, "usage: tarn compare");
    CHECK_EQ(compare("a.exr"), 2);
    CHECK_EQ(compare("a.exr b.exr c.exr"), 2);
    CHECK_EQ(compare("a.exr b.exr --frob"), 2);
    CHECK_STR_CONTAINS(err_buf, "unknown option '--frob'");
    CHECK_EQ(compare("a.exr b.exr --threshold 0"), 2);
    CHECK_EQ(compare("a.exr b.exr --threshold abc"), 2);
    CHECK_EQ(compare("a.exr b.exr --max -1"), 2);
    CHECK_EQ(compare("a.exr b.exr --texel"), 2);
    CHECK_EQ(compare("a.exr b.exr --json"), 2);
    CHECK_EQ(compare("a.exr b.exr --flip-map"), 2);
    CHECK_STR_CONTAINS(err_buf, "--flip-map wants a file name");
}

/* ---- the program ------------------------------------------------------------------ */

static void test_tarn_compare_program(void) {
    const char *bin = getenv("TARN_BIN");
    if (!bin) SKIP("TARN_BIN is not set (run through ctest)");
    char cmd[2048];
    static char out[65536];
    snprintf(cmd, sizeof cmd, "%s compare --help 2>&1", bin);
    int rc = run_command(cmd, out, sizeof out);
    if (rc == 2 && strstr(out, "unknown command")) SKIP("tarn has no compare command yet (main.c)");
    CHECK_EQ(rc, 0);
    CHECK_STR_CONTAINS(out, "--buffers");
    snprintf(cmd, sizeof cmd, "%s compare %s %s --json - 2>/dev/null", bin, path("a.tif"), path("b.tif"));
    CHECK_EQ(run_command(cmd, out, sizeof out), 0);
    CHECK(json_valid(out));
    CHECK_NEAR(jnum(out, NULL, "rmse", NULL), ((double)0.6f - 0.5) / sqrt(381.0), 1e-9);
    snprintf(cmd, sizeof cmd, "%s compare %s %s 2>&1", bin, path("w.exr"), path("t.exr"));
    CHECK_EQ(run_command(cmd, out, sizeof out), 1);
    CHECK_STR_CONTAINS(out, "16x8");
    snprintf(cmd, sizeof cmd, "%s compare %s %s 2>&1", bin, path("missing.exr"), path("t.exr"));
    CHECK_EQ(run_command(cmd, out, sizeof out), 1);
    CHECK_STR_CONTAINS(out, "missing.exr");
    snprintf(cmd, sizeof cmd, "%s compare %s 2>&1", bin, path("t.exr"));
    CHECK_EQ(run_command(cmd, out, sizeof out), 2);
}

int main(void) {
    snprintf(dir, sizeof dir, "/tmp/tarn-test-compare-XXXXXX");
    if (!mkdtemp(dir)) return 1;
    RUN(test_json_has_the_hand_computed_values);
    RUN(test_identical_images_psnr_inf);
    RUN(test_csv_to_stdout);
    RUN(test_png_is_srgb_decoded);
    RUN(test_heatmap_png);
    RUN(test_buffers);
    RUN(test_water_first_from_the_reference_mask);
    RUN(test_flip_and_ssim);
    RUN(test_flip_oracle_through_compare);
    RUN(test_mismatch_and_missing_files);
    RUN(test_usage);
    RUN(test_tarn_compare_program);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
    return check_summary();
}
