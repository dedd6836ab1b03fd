/* test_cli_reference: `tarn reference` end to end (cmd_reference called
 * directly): the files it writes, their channels, 32-bit float precision
 * of the buffers against an in-memory render of the same scene, NaN where
 * a buffer has no value, --msaa's standard positions without a GL, and
 * usage errors. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "cli.h"
#include "cmd.h"
#include "exr_header.h"
#include "image_io.h"
#include "ref_render.h"
#include "scene.h"

#ifndef TARN_SOURCE_DIR
#define TARN_SOURCE_DIR "."
#endif

static char tmpdir[256];

static const char *tmp_path(const char *name) {
    static char buf[4][512];
    static int k;
    k = (k + 1) % 4;
    snprintf(buf[k], sizeof buf[k], "%s/%s", tmpdir, name);
    return buf[k];
}

static int run(int argc, const char **argv) { return cmd_reference(argc, (char **)argv); }

static const char *lake(void) { return TARN_SOURCE_DIR "/scenes/lake.glib"; }

/* The lake as the command lines below render it (32x18, t = 1.5 s, 4
 * photons a cell, a 48^2 caustic grid), in memory: at n subpixel positions
 * (n 0: the pixel centre). */
static void lake_in_memory(const double (*at)[2], int n, ref_render_result *r) {
    ref_world_desc wd;
    scene_camera cam;
    bool has_world;
    char err[2048];
    CHECK(scene_load(lake(), NULL, &wd, &cam, &has_world, err, sizeof err) || !strstr(err, ": error:"));
    ref_world w;
    ref_world_init(&w, &wd);
    ref_render_desc d = { .world = &w, .time = 1.5, .threads = 1, .photons_per_cell = 4, .caustic_res = 48,
                          .nsamples = n };
    for (int i = 0; i < n; i++) memcpy(d.samples[i], at[i], sizeof d.samples[i]);
    memset(r, 0, sizeof *r);
    memcpy(d.camera.eye, cam.eye, sizeof cam.eye);
    memcpy(d.camera.center, cam.center, sizeof cam.center);
    memcpy(d.camera.up, cam.up, sizeof cam.up);
    d.camera.fov_deg = cam.fov_deg;
    d.camera.width = 32;
    d.camera.height = 18;
    CHECK_EQ(ref_render(&d, r, err, sizeof err), 0);
}

static void test_writes_everything(void) {
    if (access(lake(), R_OK) != 0) SKIP("no %s", lake());
    const char *out = tmp_path("ref.exr");
    const char *argv[] = { lake(), "-o", out, "--size", "32x18", "--time", "1.5", "--threads", "2",
                           "--photons", "4", "--caustic-res", "48", "--quiet" };
    CHECK_EQ(run((int)(sizeof argv / sizeof *argv), argv), TARN_EXIT_OK);

    /* the same render in memory */
    ref_render_result r;
    lake_in_memory(NULL, 0, &r);
    if (!r.color) return;
    char err[2048];

    struct { const char *name; int channels; const double *ref; } files[] = {
        { "ref.exr", 3, r.color },
        { "ref.refract_hit.exr", 4, r.refract_hit },
        { "ref.reflect.exr", 4, r.reflect },
        { "ref.fresnel.exr", 1, r.fresnel },
        { "ref.depth.exr", 1, r.depth },
        { "ref.irradiance.exr", 3, r.irradiance },
        { "ref.surface.exr", 3, r.surface },
        { "ref.mask.exr", 1, NULL },
        { "ref.png", 3, NULL },
    };
    for (size_t f = 0; f < sizeof files / sizeof *files; f++) {
        img im;
        CHECK_MSG(img_read(tmp_path(files[f].name), &im, err, sizeof err), "%s", err);
        if (!im.px) continue;
        if (strstr(files[f].name, ".exr"))   /* every EXR is 32-bit float, not half */
            CHECK_MSG(exr_pixel_type(tmp_path(files[f].name)) == EXR_TYPE_FLOAT, "%s: pixel type %d, want float",
                      files[f].name, exr_pixel_type(tmp_path(files[f].name)));
        CHECK(im.w == 32 && im.h == 18 && im.channels == files[f].channels);
        size_t n = (size_t)32 * 18 * im.channels;
        for (size_t i = 0; files[f].ref && i < n; i++) {
            double want = files[f].ref[i], got = im.px[i];
            if (isnan(want)) { CHECK(isnan(got)); continue; }
            if (isinf(want)) { CHECK_EQ(got, want); continue; }
            /* float: 24 bits, so 6e-8 relative (half would be 5e-4) */
            CHECK_MSG(fabs(got - want) <= 6e-8 * fabs(want) + 1e-30, "%s[%zu] = %.9g, want %.9g",
                      files[f].name, i, got, want);
        }
        if (strcmp(files[f].name, "ref.mask.exr") == 0)
            for (size_t i = 0; i < n; i++) CHECK_EQ(im.px[i], r.mask[i]);
        if (strcmp(files[f].name, "ref.png") == 0)   /* sRGB-encoded 8 bits */
            for (size_t i = 0; i < n; i++) {
                double v = r.color[i] > 1 ? 1 : r.color[i];
                double s = v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
                CHECK_NEAR(im.px[i], s, 0.5 / 255 + 1e-6);
            }
        img_free(&im);
    }
    ref_render_free(&r);
}

/* --seed N: the same strata sampled anew, so the floor's irradiance (the
 * caustics) differs from seed 0's (ref.exr, test_writes_everything), and
 * the pixels that see no water floor (the sky, dry land) are NaN in both. */
static void test_seed(void) {
    if (access(lake(), R_OK) != 0) SKIP("no %s", lake());
    const char *argv[] = { lake(), "-o", tmp_path("seed3.exr"), "--size", "32x18", "--time", "1.5",
                           "--threads", "2", "--photons", "4", "--caustic-res", "48", "--seed", "3", "--quiet" };
    CHECK_EQ(run((int)(sizeof argv / sizeof *argv), argv), TARN_EXIT_OK);
    img a = { 0 }, b = { 0 };
    char err[2048];
    CHECK_MSG(img_read(tmp_path("ref.irradiance.exr"), &a, err, sizeof err), "%s", err);
    CHECK_MSG(img_read(tmp_path("seed3.irradiance.exr"), &b, err, sizeof err), "%s", err);
    if (a.px && b.px && a.w == b.w && a.h == b.h && a.channels == b.channels) {
        int differ = 0, finite = 0;
        for (size_t i = 0; i < (size_t)a.w * a.h * a.channels; i++) {
            if (isnan(a.px[i])) { CHECK(isnan(b.px[i])); continue; }
            finite++;
            differ += a.px[i] != b.px[i];
        }
        fprintf(stderr, "  seed 3 against seed 0: %d of %d irradiance values differ\n", differ, finite);
        CHECK(finite > 0 && differ > 0);
    }
    img_free(&a);
    img_free(&b);
    const char *bad[] = { "s.glib", "-o", "x.exr", "--seed", "-1" };
    CHECK_EQ(run(5, bad), TARN_EXIT_USAGE);
    CHECK_STR_CONTAINS(cmd_reference_usage(), "--seed N");
}

/* --msaa 4 with no GL to ask (libglvnd pointed at no vendor): the
 * standard 4x positions, GL's (0.375, 0.125), (0.875, 0.375), (0.125,
 * 0.625), (0.625, 0.875) with y turned down, written out here as the
 * truth; the image is the in-memory render at them (float precision). A
 * count with no standard positions and no GL is refused; --spp with it is
 * bad usage. */
static void test_msaa_without_gl(void) {
    if (access(lake(), R_OK) != 0) SKIP("no %s", lake());
    setenv("__EGL_VENDOR_LIBRARY_FILENAMES", "/nonexistent/tarn-test-no-vendor.json", 1);
    const char *out = tmp_path("msaa.exr");
    const char *argv[] = { lake(), "-o", out, "--size", "32x18", "--time", "1.5", "--photons", "4",
                           "--caustic-res", "48", "--msaa", "4", "--quiet" };
    CHECK_EQ(run((int)(sizeof argv / sizeof *argv), argv), TARN_EXIT_OK);
    const char *three[] = { lake(), "-o", tmp_path("m3.exr"), "--size", "8x8", "--msaa", "3", "--quiet" };
    CHECK_EQ(run((int)(sizeof three / sizeof *three), three), TARN_EXIT_INPUT);
    unsetenv("__EGL_VENDOR_LIBRARY_FILENAMES");
    const char *both[] = { lake(), "-o", tmp_path("b.exr"), "--msaa", "4", "--spp", "2" };
    CHECK_EQ(run((int)(sizeof both / sizeof *both), both), TARN_EXIT_USAGE);

    const double at[4][2] = { { 0.375, 0.875 }, { 0.875, 0.625 }, { 0.125, 0.375 }, { 0.625, 0.125 } };
    ref_render_result r;
    lake_in_memory(at, 4, &r);
    char err[2048];
    img im;
    CHECK_MSG(img_read(out, &im, err, sizeof err), "%s", err);
    if (r.color && im.px) {
        CHECK(im.w == 32 && im.h == 18 && im.channels == 3);
        int off = 0;
        for (size_t i = 0; i < (size_t)32 * 18 * 3; i++)   /* float: 6e-8 relative, as above */
            off += !(fabs(im.px[i] - r.color[i]) <= 6e-8 * fabs(r.color[i]) + 1e-30);
        CHECK_MSG(off == 0, "%d values differ from the render at the standard 4x positions", off);
    }
    img_free(&im);
    ref_render_free(&r);
}

static void test_usage(void) {
    const char *no_out[] = { "scene.glib" };
    CHECK_EQ(run(1, no_out), TARN_EXIT_USAGE);
    const char *no_scene[] = { "-o", "x.exr" };
    CHECK_EQ(run(2, no_scene), TARN_EXIT_USAGE);
    const char *png[] = { "s.glib", "-o", "x.png" };
    CHECK_EQ(run(3, png), TARN_EXIT_USAGE);
    const char *size[] = { "s.glib", "-o", "x.exr", "--size", "64" };
    CHECK_EQ(run(5, size), TARN_EXIT_USAGE);
    const char *spp[] = { "s.glib", "-o", "x.exr", "--spp", "0" };
    CHECK_EQ(run(5, spp), TARN_EXIT_USAGE);
    const char *unknown[] = { "s.glib", "-o", "x.exr", "--frobnicate" };
    CHECK_EQ(run(4, unknown), TARN_EXIT_USAGE);
    CHECK_STR_CONTAINS(cmd_reference_usage(), "--threads");
    CHECK_STR_CONTAINS(cmd_reference_usage(), "refract_hit.exr");
}

static void test_input_errors(void) {
    const char *missing[] = { tmp_path("nope.glib"), "-o", tmp_path("x.exr"), "--quiet" };
    CHECK_EQ(run(4, missing), TARN_EXIT_INPUT);
    /* a glman scene with no world commands: nothing to render */
    const char *glib = tmp_path("noworld.glib");
    FILE *f = fopen(glib, "w");
    CHECK_NE(f, NULL);
    if (!f) return;
    fputs("##OpenGL GLIB\nLookAt 0 2 5  0 0 0  0 1 0\n", f);
    fclose(f);
    const char *noworld[] = { glib, "-o", tmp_path("x.exr"), "--quiet" };
    CHECK_EQ(run(4, noworld), TARN_EXIT_INPUT);
    /* an output that cannot be written */
    if (access(lake(), R_OK) == 0) {
        const char *bad[] = { lake(), "-o", tmp_path("no/such/dir/x.exr"), "--size", "8x4",
                              "--flat-caustics", "--quiet" };
        CHECK_EQ(run(7, bad), TARN_EXIT_INPUT);
    }
}

int main(void) {
    snprintf(tmpdir, sizeof tmpdir, "/tmp/tarn_cli_reference_XXXXXX");
    if (!mkdtemp(tmpdir)) { perror("mkdtemp"); return 1; }
    RUN(test_writes_everything);
    RUN(test_seed);
    RUN(test_msaa_without_gl);
    RUN(test_usage);
    RUN(test_input_errors);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", tmpdir);
    return check_summary();
}
