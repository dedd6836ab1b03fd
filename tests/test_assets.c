/* test_assets: the generated textures (viewer/gfx/assets.c): the same bytes
 * every time, tileable where they must tile, cube faces that follow the GL
 * spec's face table, texels that are the world model's values, caustics
 * with mean 1, and `tarn assets` writing all of it. Small resolutions keep
 * each case well under a second or two. */
#define _XOPEN_SOURCE 700       /* nftw(), to remove the temporary directory */
#include "check.h"
#include "assets.h"
#include "cli.h"
#include "cmd.h"
#include "image_io.h"

#include <ftw.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char root[64];

static ref_world *lake(void) {
    static ref_world w;
    static bool done;
    if (!done) {
        ref_world_desc d;
        ref_world_desc_lake(&d);
        ref_world_init(&w, &d);
        done = true;
    }
    return &w;
}

static float *fbuf(int res, int ch) { return calloc((size_t)res * res * ch, sizeof(float)); }

/* Mean absolute jump across the wrap (last column to column 0, last row
 * to row 0) against the mean jump between interior neighbours, channel c
 * of ch: a tileable image jumps no more at its edges than inside. */
static void wrap_vs_inside(const float *px, int res, int ch, int c, double *edge, double *inside) {
    double e = 0, in = 0;
    long ne = 0, ni = 0;
    for (int j = 0; j < res; j++)
        for (int i = 0; i < res; i++) {
            double v = px[((size_t)j * res + i) * ch + c];
            double right = px[((size_t)j * res + (i + 1) % res) * ch + c];
            double up = px[((size_t)((j + 1) % res) * res + i) * ch + c];
            if (i == res - 1) { e += fabs(right - v); ne++; } else { in += fabs(right - v); ni++; }
            if (j == res - 1) { e += fabs(up - v); ne++; } else { in += fabs(up - v); ni++; }
        }
    *edge = e / ne;
    *inside = in / ni;
}

static void check_tiles(const float *px, int res, int ch, int c, const char *what) {
    double e, in;
    wrap_vs_inside(px, res, ch, c, &e, &in);
    CHECK_MSG(in > 0, "%s: flat", what);
    CHECK_MSG(e <= 1.5 * in, "%s channel %d: jumps %.4f at the wrap, %.4f inside", what, c, e, in);
}

static void test_determinism(void) {
    enum { R = 24 };
    const ref_world *w = lake();
    float *a = fbuf(R, 3), *b = fbuf(R, 3);
    CHECK(assets_bake_albedo(w, R, a) && assets_bake_albedo(w, R, b));
    CHECK_EQ(memcmp(a, b, sizeof(float) * R * R * 3), 0);
    CHECK(assets_bake_terrain_normal(w, R, a) && assets_bake_terrain_normal(w, R, b));
    CHECK_EQ(memcmp(a, b, sizeof(float) * R * R * 3), 0);
    for (int f = 0; f < ASSETS_FACES; f++) {
        CHECK(assets_bake_sky_face(w, f, R, a) && assets_bake_sky_face(w, f, R, b));
        CHECK_EQ(memcmp(a, b, sizeof(float) * R * R * 3), 0);
    }
    CHECK(assets_bake_water_normal(R, a) && assets_bake_water_normal(R, b));
    CHECK_EQ(memcmp(a, b, sizeof(float) * R * R * 3), 0);
    CHECK(assets_bake_foam(R, a) && assets_bake_foam(R, b));
    CHECK_EQ(memcmp(a, b, sizeof(float) * R * R * 3), 0);
    char err[256];
    CHECK(assets_bake_caustics(R, a, err, sizeof err) && assets_bake_caustics(R, b, err, sizeof err));
    CHECK_EQ(memcmp(a, b, sizeof(float) * R * R), 0);
    free(a);
    free(b);
}

static void test_bad_args(void) {
    float px[3 * 16];
    char err[256] = "";
    CHECK(!assets_bake_albedo(NULL, 4, px));
    CHECK(!assets_bake_albedo(lake(), 0, px));
    CHECK(!assets_bake_sky_face(lake(), 6, 4, px));
    CHECK(!assets_bake_sky_face(lake(), -1, 4, px));
    CHECK(!assets_bake_water_normal(ASSETS_MAX_RES + 1, px));
    CHECK(!assets_bake_foam(4, NULL));
    CHECK(!assets_bake_caustics(2, px, err, sizeof err));
    CHECK_STR_CONTAINS(err, "caustics: resolution 2 is outside 4..1024");
    CHECK(strcmp(assets_face_name(ASSETS_FACE_NZ), "nz") == 0 && strcmp(assets_face_name(6), "?") == 0);
}

static void test_albedo_and_normal_texels(void) {
    enum { R = 40 };
    const ref_world *w = lake();
    float *a = fbuf(R, 3), *n = fbuf(R, 3);
    CHECK(assets_bake_albedo(w, R, a) && assets_bake_terrain_normal(w, R, n));
    double h = w->d.half_size;
    static const int ij[][2] = { { 0, 0 }, { 39, 0 }, { 0, 39 }, { 20, 20 }, { 7, 31 }, { 33, 12 } };
    for (size_t k = 0; k < sizeof ij / sizeof ij[0]; k++) {
        int i = ij[k][0], j = ij[k][1];
        double x = -h + (i + 0.5) * 2 * h / R, z = -h + (j + 0.5) * 2 * h / R;
        double c[3], nn[3];
        ref_terrain_albedo(w, x, z, c);
        ref_terrain_normal_at(w, x, z, nn);
        const float *pa = a + ((size_t)j * R + i) * 3, *pn = n + ((size_t)j * R + i) * 3;
        for (int q = 0; q < 3; q++)
            CHECK_NEAR(pa[q], c[q], 1e-6);
        /* decode n = (2 rgb - 1).xzy */
        CHECK_NEAR(2 * pn[0] - 1, nn[0], 1e-6);
        CHECK_NEAR(2 * pn[1] - 1, nn[2], 1e-6);
        CHECK_NEAR(2 * pn[2] - 1, nn[1], 1e-6);
    }
    free(a);
    free(n);
}

/* The GL spec's face selection (OpenGL 4.6, table 8.19), written out
 * independently: direction -> face, s, t. */
static void gl_select(const double d[3], int *face, double *s, double *t) {
    double ax = fabs(d[0]), ay = fabs(d[1]), az = fabs(d[2]), sc, tc, ma;
    if (ax >= ay && ax >= az) {
        ma = ax;
        if (d[0] > 0) { *face = 0; sc = -d[2]; tc = -d[1]; }
        else          { *face = 1; sc = d[2];  tc = -d[1]; }
    } else if (ay >= az) {
        ma = ay;
        if (d[1] > 0) { *face = 2; sc = d[0]; tc = d[2]; }
        else          { *face = 3; sc = d[0]; tc = -d[2]; }
    } else {
        ma = az;
        if (d[2] > 0) { *face = 4; sc = d[0];  tc = -d[1]; }
        else          { *face = 5; sc = -d[0]; tc = -d[1]; }
    }
    *s = 0.5 * (sc / ma + 1);
    *t = 0.5 * (tc / ma + 1);
}

static void test_cube_faces(void) {
    enum { R = 9 };             /* odd: texel (4, 4) is the face's centre */
    static const double axis[6][3] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 },
                                       { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 } };
    const ref_world *w = lake();
    float *px = fbuf(R, 3);
    for (int f = 0; f < ASSETS_FACES; f++) {
        CHECK(assets_bake_sky_face(w, f, R, px));
        double c[3];
        ref_sky_radiance(w, axis[f], c);
        const float *mid = px + ((size_t)(R / 2) * R + R / 2) * 3;
        for (int k = 0; k < 3; k++)
            CHECK_MSG(fabs(mid[k] - c[k]) <= 1e-6 * (1 + c[k]), "face %s centre channel %d: %g, want %g",
                      assets_face_name(f), k, mid[k], c[k]);
        /* every texel looks where GL's table says that texel is */
        for (int j = 0; j < R; j++)
            for (int i = 0; i < R; i++) {
                double s = (i + 0.5) / R, t = (j + 0.5) / R, d[3], s2, t2, rad[3];
                int f2;
                assets_face_dir(f, s, t, d);
                CHECK_NEAR(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 1.0, 1e-12);
                gl_select(d, &f2, &s2, &t2);
                CHECK_MSG(f2 == f && fabs(s2 - s) < 1e-12 && fabs(t2 - t) < 1e-12,
                          "face %d texel (%d, %d) looks at face %d (%g, %g)", f, i, j, f2, s2, t2);
                ref_sky_radiance(w, d, rad);
                CHECK_NEAR(px[((size_t)j * R + i) * 3], rad[0], 1e-6 * (1 + rad[0]));
            }
    }
    /* row 0 (the top of the file) of a side face looks up: brighter sky,
     * not the ground */
    CHECK(assets_bake_sky_face(w, ASSETS_FACE_PZ, R, px));
    CHECK_GT(px[2], px[((size_t)(R - 1) * R) * 3 + 2]);
    free(px);
}

static void test_tileable(void) {
    enum { R = 64 };
    float *px = fbuf(R, 3);
    CHECK(assets_bake_water_normal(R, px));
    for (int c = 0; c < 3; c++)
        check_tiles(px, R, 3, c, "water normal");
    /* the normals are unit and point up */
    for (int k = 0; k < R * R; k++) {
        double n[3] = { 2 * px[3 * k] - 1, 2 * px[3 * k + 2] - 1, 2 * px[3 * k + 1] - 1 };
        CHECK_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-5);
        CHECK_GT(n[1], 0.5);
    }
    CHECK(assets_bake_foam(R, px));
    check_tiles(px, R, 3, 0, "foam red");
    check_tiles(px, R, 3, 2, "foam blue");
    double red = 0, blue = 0, green = 0;
    for (int k = 0; k < R * R; k++) {
        red += px[3 * k];
        green += px[3 * k + 1];
        blue += px[3 * k + 2];
    }
    CHECK(green == 0 && red > 0.05 * R * R && blue > 0.05 * R * R && red < 0.6 * R * R);

    /* the check is not vacuous: three quarters of a periodic tile,
     * stretched over the whole, do not tile */
    float *cut = fbuf(R, 3);
    CHECK(assets_bake_water_normal(R, px));
    for (int j = 0; j < R; j++)
        for (int i = 0; i < R; i++)
            cut[((size_t)j * R + i) * 3] = px[((size_t)j * R + (i * 3 / 4)) * 3];
    double e, in;
    wrap_vs_inside(cut, R, 3, 0, &e, &in);
    CHECK_MSG(e > 1.5 * in, "a cut tile: %.4f at the wrap, %.4f inside", e, in);
    free(cut);
    free(px);
}

static void test_caustics(void) {
    enum { R = 32 };
    float *c = fbuf(R, 1);
    char err[256] = "";
    CHECK_MSG(assets_bake_caustics(R, c, err, sizeof err), "%s", err);
    double sum = 0, sum2 = 0, mx = 0, mn = 1e30;
    for (int k = 0; k < R * R; k++) {
        sum += c[k];
        sum2 += (double)c[k] * c[k];
        mx = c[k] > mx ? c[k] : mx;
        mn = c[k] < mn ? c[k] : mn;
    }
    double mean = sum / (R * R), sd = sqrt(sum2 / (R * R) - mean * mean);
    CHECK_NEAR(mean, 1.0, 1e-6);
    CHECK_MSG(sd > 0.3 && mx > 2.5 && mn < 0.6 && mn >= 0, "sd %g max %g min %g", sd, mx, mn);
    check_tiles(c, R, 1, 0, "caustics");
    free(c);
}

static int rm_entry(const char *path, const struct stat *sb, int flag, struct FTW *ftw) {
    (void)sb; (void)flag; (void)ftw;
    return remove(path);
}

static bool read_file(const char *path, char **buf, long *len) {
    FILE *f = fopen(path, "rb");
    if (!f)
        return false;
    fseek(f, 0, SEEK_END);
    *len = ftell(f);
    fseek(f, 0, SEEK_SET);
    *buf = malloc((size_t)*len + 1);
    bool ok = fread(*buf, 1, (size_t)*len, f) == (size_t)*len;
    fclose(f);
    return ok;
}

static const char *const files[] = {
    "terrain_albedo.png", "terrain_normal.png", "sky_px.exr", "sky_nx.exr", "sky_py.exr",
    "sky_ny.exr", "sky_pz.exr", "sky_nz.exr", "sky_px.png", "sky_nx.png", "sky_py.png",
    "sky_ny.png", "sky_pz.png", "sky_nz.png", "water_normal.png", "foam.png", "caustics.exr",
    "caustics.png",
};

static int run_cli(int argc, const char *const *argv) {
    fflush(stdout);
    return cmd_assets(argc, (char **)argv);
}

static void test_cli(void) {
    enum { R = 16 };
    char a[128], b[128];
    snprintf(a, sizeof a, "%s/one/deeper", root);
    snprintf(b, sizeof b, "%s/two", root);
    const char *args_a[] = { "--out", a, "--size", "16" };
    const char *args_b[] = { "--size", "16", "-o", b, TARN_SOURCE_DIR "/scenes/lake.glib" };
    CHECK_EQ(run_cli(4, args_a), TARN_EXIT_OK);
    CHECK_EQ(run_cli(5, args_b), TARN_EXIT_OK);
    /* the same bytes twice, and the lake glib's world is the default one */
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        char pa[256], pb[256], *ba = NULL, *bb = NULL;
        long la = 0, lb = 0;
        snprintf(pa, sizeof pa, "%s/%s", a, files[i]);
        snprintf(pb, sizeof pb, "%s/%s", b, files[i]);
        bool ra = read_file(pa, &ba, &la), rb = read_file(pb, &bb, &lb);
        CHECK_MSG(ra && rb, "%s", files[i]);
        /* PNGs byte for byte; EXRs by their pixels: OpenEXR's threaded
         * compression may lay the same pixels out differently under load */
        bool same = ra && rb && la == lb && la > 0 && memcmp(ba, bb, (size_t)la) == 0;
        if (!same && ra && rb && strstr(files[i], ".exr")) {
            img ia, ib;
            char e1[256], e2[256];
            memset(&ia, 0, sizeof ia);
            memset(&ib, 0, sizeof ib);
            same = img_read(pa, &ia, e1, sizeof e1) && img_read(pb, &ib, e2, sizeof e2) && ia.w == ib.w &&
                   ia.h == ib.h && ia.channels == ib.channels &&
                   memcmp(ia.px, ib.px, sizeof(float) * (size_t)ia.w * ia.h * ia.channels) == 0;
            img_free(&ia);
            img_free(&ib);
        }
        CHECK_MSG(same, "%s differs between runs", files[i]);
        free(ba);
        free(bb);
    }
    /* what the files hold: 2D files top row first (t = 1 at the top), the
     * caustics at half their value in the PNG, cube faces unflipped */
    char path[256], err[512];
    img im;
    float *buf = fbuf(R, 3);
    snprintf(path, sizeof path, "%s/terrain_albedo.png", a);
    CHECK_MSG(img_read(path, &im, err, sizeof err), "%s", err);
    CHECK(assets_bake_albedo(lake(), R, buf));
    if (im.px && im.w == R && im.h == R && im.channels == 3)
        for (int j = 0; j < R; j++)
            for (int i = 0; i < R; i++)
                CHECK_NEAR(im.px[((size_t)(R - 1 - j) * R + i) * 3 + 1],
                           buf[((size_t)j * R + i) * 3 + 1], 0.5 / 255 + 1e-6);
    img_free(&im);
    snprintf(path, sizeof path, "%s/sky_py.exr", a);
    CHECK_MSG(img_read(path, &im, err, sizeof err), "%s", err);
    CHECK(assets_bake_sky_face(lake(), ASSETS_FACE_PY, R, buf));
    if (im.px && im.w == R && im.h == R)
        for (int k = 0; k < R * R * 3; k++)
            CHECK_EQ(im.px[k], buf[k]);                  /* 32-bit floats: exact */
    img_free(&im);
    float *c = fbuf(R, 1);
    CHECK(assets_bake_caustics(R, c, err, sizeof err));
    snprintf(path, sizeof path, "%s/caustics.png", a);
    CHECK_MSG(img_read(path, &im, err, sizeof err), "%s", err);
    if (im.px && im.w == R && im.h == R)
        for (int j = 0; j < R; j++)
            for (int i = 0; i < R; i++) {
                double want = 0.5 * c[j * R + i];
                CHECK_NEAR(im.px[((size_t)(R - 1 - j) * R + i) * 3], want > 1 ? 1 : want, 0.5 / 255 + 1e-6);
            }
    img_free(&im);
    snprintf(path, sizeof path, "%s/caustics.exr", a);
    CHECK_MSG(img_read(path, &im, err, sizeof err), "%s", err);
    if (im.px && im.w == R && im.h == R) {
        double sum = 0;
        for (int k = 0; k < R * R; k++) {
            sum += im.px[3 * k];
            CHECK_EQ(im.px[3 * k], c[(R - 1 - k / R) * R + k % R]);   /* exact, flipped */
        }
        CHECK_NEAR(sum / (R * R), 1.0, 1e-6);
    }
    img_free(&im);
    free(c);
    free(buf);

    /* usage and input errors */
    const char *help[] = { "--help" }, *bad[] = { "--frobnicate" }, *badsize[] = { "--size", "2" };
    CHECK_EQ(run_cli(1, help), TARN_EXIT_OK);
    CHECK_EQ(run_cli(1, bad), TARN_EXIT_USAGE);
    CHECK_EQ(run_cli(2, badsize), TARN_EXIT_USAGE);
    char scene[128];
    snprintf(scene, sizeof scene, "%s/bad.glib", root);
    FILE *f = fopen(scene, "w");
    fputs("##OpenGL GLIB\nSun 0 0 0\n", f);
    fclose(f);
    char out3[128];
    snprintf(out3, sizeof out3, "%s/three", root);
    const char *args_bad[] = { "--out", out3, scene };
    CHECK_EQ(run_cli(3, args_bad), TARN_EXIT_INPUT);
    CHECK_NE(access(out3, F_OK), 0);                 /* nothing written */
    const char *args_file[] = { "--out", scene, "--size", "8" };   /* a file, not a directory */
    CHECK_EQ(run_cli(4, args_file), TARN_EXIT_INPUT);
}

int main(void) {
    snprintf(root, sizeof root, "/tmp/test_assets_XXXXXX");
    if (!mkdtemp(root)) {
        perror("mkdtemp");
        return 1;
    }
    RUN(test_determinism);
    RUN(test_bad_args);
    RUN(test_albedo_and_normal_texels);
    RUN(test_cube_faces);
    RUN(test_tileable);
    RUN(test_caustics);
    RUN(test_cli);
    nftw(root, rm_entry, 16, FTW_DEPTH | FTW_PHYS);
    return check_summary();
}
