/* test_image: the OpenImageIO bridge (viewer/gfx/image_io.h).
 *
 * Truth comes from outside the bridge: BMP files written byte by byte here,
 * the 8-bit rounding rule, and half-float precision. */
#include "check.h"
#include "image_io.h"

#include <stdint.h>
#include <stdlib.h>
#include <unistd.h>

static char tmpdir[256];

static const char *tmp_path(const char *name) {
    static char buf[4][512];
    static int next;
    char *p = buf[next++ % 4];
    snprintf(p, sizeof buf[0], "%s/%s", tmpdir, name);
    return p;
}

static float clamp01(float v) { return v < 0.f ? 0.f : v > 1.f ? 1.f : v; }

/* A pattern with a distinct value per texel and channel, some out of 0..1. */
static float pattern(int x, int y, int c) {
    return -0.25f + (float)((x * 37 + y * 101 + c * 59) % 151) / 100.0f;
}

static void fill_pattern(img *im) {
    for (int y = 0; y < im->h; y++)
        for (int x = 0; x < im->w; x++)
            for (int c = 0; c < im->channels; c++)
                im->px[(y * im->w + x) * im->channels + c] = pattern(x, y, c);
}

static void le16(unsigned char *p, unsigned v) { p[0] = v & 255; p[1] = (v >> 8) & 255; }
static void le32(unsigned char *p, uint32_t v) {
    p[0] = v & 255; p[1] = (v >> 8) & 255; p[2] = (v >> 16) & 255; p[3] = (v >> 24) & 255;
}

/* Writes a 24-bit BI_RGB BMP; rgb is w*h*3 bytes in top-down order.
 * height_sign < 0 stores a top-down file (negative height). */
static int write_bmp24(const char *path, int w, int h, const unsigned char *rgb, int height_sign) {
    int stride = (w * 3 + 3) & ~3;
    uint32_t size = 54u + (uint32_t)(stride * h);
    unsigned char hdr[54] = {0};
    hdr[0] = 'B'; hdr[1] = 'M';
    le32(hdr + 2, size);
    le32(hdr + 10, 54);                 /* pixel data offset */
    le32(hdr + 14, 40);                 /* BITMAPINFOHEADER */
    le32(hdr + 18, (uint32_t)w);
    le32(hdr + 22, (uint32_t)(height_sign < 0 ? -h : h));
    le16(hdr + 26, 1);                  /* planes */
    le16(hdr + 28, 24);                 /* bits per pixel */
    le32(hdr + 30, 0);                  /* BI_RGB */
    le32(hdr + 34, (uint32_t)(stride * h));
    le32(hdr + 38, 2835); le32(hdr + 42, 2835);
    FILE *f = fopen(path, "wb");
    if (!f) return 0;
    fwrite(hdr, 1, 54, f);
    unsigned char *row = calloc(1, (size_t)stride);
    for (int i = 0; i < h; i++) {
        int y = height_sign < 0 ? i : h - 1 - i;    /* bottom-up unless negative */
        for (int x = 0; x < w; x++) {
            const unsigned char *p = rgb + (y * w + x) * 3;
            row[x * 3 + 0] = p[2]; row[x * 3 + 1] = p[1]; row[x * 3 + 2] = p[0];
        }
        fwrite(row, 1, (size_t)stride, f);
    }
    free(row);
    return fclose(f) == 0;
}

static void test_alloc_free_flip(void) {
    img im;
    CHECK(img_alloc(&im, 3, 4, 2));
    CHECK(im.w == 3 && im.h == 4 && im.d == 1 && im.channels == 2 && im.px);
    for (int i = 0; i < 3 * 4 * 2; i++) CHECK_EQ(im.px[i], 0.0f);
    for (int y = 0; y < 4; y++)
        for (int i = 0; i < 6; i++) im.px[y * 6 + i] = (float)(y * 10 + i);
    img_flip_rows(&im);
    for (int y = 0; y < 4; y++)
        for (int i = 0; i < 6; i++) CHECK_EQ(im.px[y * 6 + i], (float)((3 - y) * 10 + i));
    img_free(&im);
    CHECK(im.px == NULL && im.w == 0);
    img_free(&im);                        /* twice is harmless */

    CHECK(!img_alloc(&im, 0, 4, 3));
    CHECK(!img_alloc(&im, 20000, 4, 3));
    CHECK(img_alloc(&im, 16384, 1, 1));    /* the largest side */
    img_free(&im);
    CHECK(!img_alloc(&im, 16385, 1, 1));
    CHECK(!img_alloc(&im, 4, 4, 0));
    CHECK_EQ(im.px, NULL);
}

static void test_png_round_trip(void) {
    const char *path = tmp_path("rt.png");
    for (int ch = 1; ch <= 4; ch++) {
        img im, back;
        CHECK(img_alloc(&im, 7, 5, ch));
        fill_pattern(&im);
        if (ch == 4) im.px[3] = 0.0f;      /* alpha 0 must not destroy colour */
        char err[512] = "";
        CHECK_MSG(img_write(path, &im, err, sizeof err), "%s", err);
        CHECK_MSG(img_read(path, &back, err, sizeof err), "%s", err);
        CHECK(back.w == 7 && back.h == 5 && back.d == 1 && back.channels == ch);
        if (back.px && back.channels == ch && back.w == 7 && back.h == 5) {
            double worst = 0;
            for (int i = 0; i < 7 * 5 * ch; i++) {
                double e = fabs(back.px[i] - clamp01(im.px[i]));
                if (e > worst) worst = e;
                /* stored as round(v * 255): back on the 1/255 grid */
                CHECK_NEAR(back.px[i] * 255.0, floor(back.px[i] * 255.0 + 0.5), 1e-3);
            }
            CHECK_MSG(worst <= 0.5 / 255.0 + 1e-6, "worst %g with %d channels", worst, ch);
        }
        img_free(&im);
        img_free(&back);
    }
}

static void test_exr_round_trip(void) {
    const char *path = tmp_path("rt.exr");
    img im, back;
    CHECK(img_alloc(&im, 6, 4, 4));
    for (int i = 0; i < 6 * 4 * 4; i++)
        im.px[i] = (float)((i % 2 ? 1 : -1) * pow(1.37, (double)(i % 29) - 8.0));
    im.px[5] = 0.0f; im.px[6] = 1000.25f; im.px[7] = -0.0001f;
    char err[512] = "";
    CHECK_MSG(img_write(path, &im, err, sizeof err), "%s", err);
    CHECK_MSG(img_read(path, &back, err, sizeof err), "%s", err);
    CHECK(back.w == 6 && back.h == 4 && back.channels == 4 && back.d == 1);
    if (back.px && back.w == 6 && back.h == 4 && back.channels == 4)
        for (int i = 0; i < 6 * 4 * 4; i++) /* half: 11 significant bits */
            CHECK_NEAR(back.px[i], im.px[i], fabs(im.px[i]) * (1.0 / 2048.0) + 1e-7);
    img_free(&im);
    img_free(&back);
}

static void test_other_formats_round_trip(void) {
    struct { const char *name; int ch; double abs_tol, rel_tol; } fmts[] = {
        {"rt.tif", 4, 0.0, 0.0},            /* 32-bit float: exact */
        {"rt.hdr", 3, 0.0, 1.0 / 128.0},    /* RGBE: 8-bit mantissa on the largest */
        {"rt.bmp", 3, 0.5 / 255.0 + 1e-6, 0.0},
    };
    for (size_t k = 0; k < sizeof fmts / sizeof fmts[0]; k++) {
        img im, back;
        CHECK(img_alloc(&im, 5, 3, fmts[k].ch));
        fill_pattern(&im);
        if (fmts[k].abs_tol > 0 || fmts[k].rel_tol > 0)
            for (int i = 0; i < 5 * 3 * fmts[k].ch; i++) im.px[i] = clamp01(im.px[i]);
        const char *path = tmp_path(fmts[k].name);
        char err[512] = "";
        CHECK_MSG(img_write(path, &im, err, sizeof err), "%s: %s", fmts[k].name, err);
        CHECK_MSG(img_read(path, &back, err, sizeof err), "%s: %s", fmts[k].name, err);
        CHECK_MSG(back.w == 5 && back.h == 3 && back.channels >= fmts[k].ch, "%s", fmts[k].name);
        if (back.px && back.w == 5 && back.h == 3 && back.channels >= fmts[k].ch)
            for (int y = 0; y < 3; y++)
                for (int x = 0; x < 5; x++) {
                    float mx = 0;
                    for (int c = 0; c < fmts[k].ch; c++)
                        mx = fmaxf(mx, fabsf(im.px[(y * 5 + x) * fmts[k].ch + c]));
                    for (int c = 0; c < fmts[k].ch; c++)
                        CHECK_NEAR(back.px[(y * 5 + x) * back.channels + c],
                                   im.px[(y * 5 + x) * fmts[k].ch + c],
                                   fmts[k].abs_tol + fmts[k].rel_tol * mx + 1e-7);
                }
        img_free(&im);
        img_free(&back);
    }

    /* JPEG is lossy: a flat colour comes back close; RGBA drops nothing fatal */
    img im, back;
    CHECK(img_alloc(&im, 16, 16, 3));
    for (int i = 0; i < 16 * 16; i++) { im.px[3 * i] = 0.8f; im.px[3 * i + 1] = 0.4f; im.px[3 * i + 2] = 0.1f; }
    char err[512] = "";
    const char *jpg = tmp_path("rt.jpg");
    CHECK_MSG(img_write(jpg, &im, err, sizeof err), "%s", err);
    CHECK_MSG(img_read(jpg, &back, err, sizeof err), "%s", err);
    if (back.px && back.channels == 3 && back.w == 16 && back.h == 16) {
        CHECK_NEAR(back.px[(8 * 16 + 8) * 3 + 0], 0.8, 0.03);
        CHECK_NEAR(back.px[(8 * 16 + 8) * 3 + 1], 0.4, 0.03);
        CHECK_NEAR(back.px[(8 * 16 + 8) * 3 + 2], 0.1, 0.03);
    } else CHECK_MSG(0, "jpg read back %dx%dx%d", back.w, back.h, back.channels);
    img_free(&im);
    img_free(&back);

    /* .hdr with alpha keeps RGB */
    CHECK(img_alloc(&im, 2, 2, 4));
    for (int i = 0; i < 16; i++) im.px[i] = 0.5f;
    const char *hdr = tmp_path("rgba.hdr");
    CHECK_MSG(img_write(hdr, &im, err, sizeof err), "%s", err);
    CHECK_MSG(img_read(hdr, &back, err, sizeof err), "%s", err);
    CHECK(back.channels == 3 && back.px && fabsf(back.px[0] - 0.5f) < 0.01f);
    img_free(&im);
    img_free(&back);
}

/* 24-bit BMP as glman reads it: bottom-up rows, BGR, rows padded to 4. */
static void test_bmp24_hand_made(void) {
    enum { W = 3, H = 2 };          /* 9 bytes a row: padding exercised */
    const unsigned char rgb[H][W][3] = {
        {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}},        /* top row */
        {{10, 20, 30}, {128, 64, 32}, {255, 255, 255}}, /* bottom row */
    };
    for (int sign = 1; sign >= -1; sign -= 2) {
        const char *path = tmp_path(sign > 0 ? "hand.bmp" : "hand_topdown.bmp");
        CHECK(write_bmp24(path, W, H, &rgb[0][0][0], sign));
        img im;
        char err[512] = "";
        CHECK_MSG(img_read(path, &im, err, sizeof err), "%s", err);
        CHECK(im.w == W && im.h == H && im.d == 1 && im.channels == 3);
        if (im.px && im.w == W && im.h == H && im.channels == 3)
            for (int y = 0; y < H; y++)
                for (int x = 0; x < W; x++)
                    for (int c = 0; c < 3; c++)
                        CHECK_MSG(fabs(im.px[(y * W + x) * 3 + c] - rgb[y][x][c] / 255.0) < 1e-6,
                                  "sign %d pixel (%d,%d).%d = %g, want %d/255", sign, x, y, c,
                                  im.px[(y * W + x) * 3 + c], rgb[y][x][c]);
        /* GL order: after the flip, row 0 is the file's bottom row */
        img_flip_rows(&im);
        if (im.px && im.w == W && im.h == H && im.channels == 3)
            CHECK_NEAR(im.px[0], 10 / 255.0, 1e-6);
        img_free(&im);
    }
}

static void test_errors(void) {
    img im = {1, 1, 1, 1, NULL};
    char err[512] = "";
    const char *missing = tmp_path("no_such_file.png");
    CHECK(!img_read(missing, &im, err, sizeof err));
    CHECK_STR_CONTAINS(err, missing);
    CHECK(im.px == NULL && im.w == 0);

    /* text under an image name */
    const char *junk = tmp_path("junk.png");
    FILE *f = fopen(junk, "w");
    fputs("this is not an image\n", f);
    fclose(f);
    err[0] = 0;
    CHECK(!img_read(junk, &im, err, sizeof err));
    CHECK_STR_CONTAINS(err, junk);
    CHECK_EQ(im.px, NULL);

    /* an unknown extension */
    const char *unk = tmp_path("mystery.qqq");
    f = fopen(unk, "w");
    fputs("P?\n", f);
    fclose(f);
    err[0] = 0;
    CHECK(!img_read(unk, &im, err, sizeof err));
    CHECK_STR_CONTAINS(err, unk);

    /* a BMP header claiming an absurd size, with no pixels behind it */
    unsigned char hdr[54] = {'B', 'M'};
    le32(hdr + 2, 54); le32(hdr + 10, 54); le32(hdr + 14, 40);
    le32(hdr + 18, 100000); le32(hdr + 22, 100000);
    le16(hdr + 26, 1); le16(hdr + 28, 24);
    const char *big = tmp_path("huge.bmp");
    f = fopen(big, "wb");
    fwrite(hdr, 1, sizeof hdr, f);
    fclose(f);
    err[0] = 0;
    CHECK(!img_read(big, &im, err, sizeof err));
    CHECK_STR_CONTAINS(err, big);
    CHECK_EQ(im.px, NULL);

    /* a truncated BMP: header fine, pixels cut short */
    const unsigned char rgb[4 * 4 * 3] = {0};
    const char *cut = tmp_path("cut.bmp");
    CHECK(write_bmp24(cut, 4, 4, rgb, 1));
    CHECK_EQ(truncate(cut, 60), 0);
    err[0] = 0;
    bool ok = img_read(cut, &im, err, sizeof err);
    if (!ok) CHECK_STR_CONTAINS(err, cut);
    img_free(&im);

    /* writing: bad image, unknown format, missing directory, volume to png */
    img two;
    CHECK(img_alloc(&two, 2, 2, 3));
    err[0] = 0;
    CHECK(!img_write(tmp_path("out.qqq"), &two, err, sizeof err));
    CHECK_STR_CONTAINS(err, "out.qqq");
    err[0] = 0;
    CHECK(!img_write(tmp_path("no/such/dir/out.png"), &two, err, sizeof err));
    CHECK_STR_CONTAINS(err, "no/such/dir/out.png");
    img empty = {0, 0, 0, 0, NULL};
    err[0] = 0;
    CHECK(!img_write(tmp_path("empty.png"), &empty, err, sizeof err));
    CHECK_STR_CONTAINS(err, "empty.png");
    img vol = {2, 2, 2, 1, NULL};
    float vpx[8] = {0};
    vol.px = vpx;
    err[0] = 0;
    CHECK(!img_write(tmp_path("vol.png"), &vol, err, sizeof err));
    CHECK_STR_CONTAINS(err, "vol.png");
    img_free(&two);

    /* err may be NULL */
    CHECK(!img_read(missing, &im, NULL, 0));
}

int main(void) {
    const char *base = getenv("TMPDIR");
    snprintf(tmpdir, sizeof tmpdir, "%s/tarn_test_image_XXXXXX", base && *base ? base : "/tmp");
    if (!mkdtemp(tmpdir)) { perror("mkdtemp"); return 1; }

    RUN(test_alloc_free_flip);
    RUN(test_png_round_trip);
    RUN(test_exr_round_trip);
    RUN(test_other_formats_round_trip);
    RUN(test_bmp24_hand_made);
    RUN(test_errors);

    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", tmpdir);
    return check_summary();
}
