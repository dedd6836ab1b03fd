/* The tarn program as a user runs it: help texts, exit codes, and headless
 * rendering with DISPLAY unset, checked against what the scene says. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "check.h"
#include "support.h"
#include "exr_header.h"
#include "image_io.h"

static const char *bin, *src;
static char dir[256];

static void test_help_lists_every_command(void) {
    char cmd[1024], out[8192];
    snprintf(cmd, sizeof cmd, "%s --help 2>&1", bin);
    CHECK_EQ(run_command(cmd, out, sizeof out), 0);
    CHECK_STR_CONTAINS(out, "view FILE.glib");
    CHECK_STR_CONTAINS(out, "render FILE.glib");
    CHECK_STR_CONTAINS(out, "validate");
    const char *cmds[] = { "view", "render", "validate" };
    for (int i = 0; i < 3; i++) {
        snprintf(cmd, sizeof cmd, "%s %s --help 2>&1", bin, cmds[i]);
        CHECK_EQ(run_command(cmd, out, sizeof out), 0);
        CHECK_STR_CONTAINS(out, "usage: tarn");
    }
    snprintf(cmd, sizeof cmd, "%s render --help 2>&1", bin);
    run_command(cmd, out, sizeof out);
    CHECK_STR_CONTAINS(out, "--size WxH");
    CHECK_STR_CONTAINS(out, "--frames N");
    CHECK_STR_CONTAINS(out, "--time SECONDS");
}

static void test_bad_usage_exits_2(void) {
    char cmd[1024], out[8192];
    snprintf(cmd, sizeof cmd, "%s frobnicate 2>&1", bin);
    CHECK_EQ(run_command(cmd, out, sizeof out), 2);
    CHECK_STR_CONTAINS(out, "unknown command 'frobnicate'");
    snprintf(cmd, sizeof cmd, "%s render %s/scenes/pond.glib 2>&1", bin, src);
    CHECK_EQ(run_command(cmd, out, sizeof out), 2);
    CHECK_STR_CONTAINS(out, "-o OUT");
    snprintf(cmd, sizeof cmd, "%s render x.glib -o x.png --size 12by3 2>&1", bin);
    CHECK_EQ(run_command(cmd, out, sizeof out), 2);
}

static void test_missing_scene_names_the_file(void) {
    char cmd[1024], out[8192];
    snprintf(cmd, sizeof cmd, "env -u DISPLAY %s render %s/nope.glib -o %s/nope.png 2>&1", bin, dir, dir);
    CHECK_EQ(run_command(cmd, out, sizeof out), 1);
    CHECK_STR_CONTAINS(out, "nope.glib");
}

/* A frame that would take more than a quarter of the machine's memory is
 * refused with the reason, before any drawing (issue #30: WindowSize 16000
 * 16000 took 4.4 GB and 10.7 s a frame). */
static void test_huge_frame_is_refused(void) {
    char cmd[1024], out[8192], glib[512];
    snprintf(glib, sizeof glib, "%s/huge.glib", dir);
    FILE *f = fopen(glib, "w");
    if (!f) { CHECK_NE(f, NULL); return; }
    fputs("##OpenGL GLIB\nWindowSize 16384 16384\nOrtho -1 1 -1 1\nQuadXY 0 1 1 1\n", f);
    fclose(f);
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    if ((double)pages * page / 4 > 16384.0 * 16384.0 * 36) SKIP("this machine has room for a 16384^2 frame");
    snprintf(cmd, sizeof cmd, "env -u DISPLAY %s render %s -o %s/huge.png 2>&1", bin, glib, dir);
    int rc = run_command(cmd, out, sizeof out);
    if (rc == 3) SKIP("no OpenGL");
    CHECK_MSG(rc == 2, "%s", out);
    CHECK_STR_CONTAINS(out, "huge.glib: 16384x16384 needs about");
    CHECK_STR_CONTAINS(out, "ask for less");
}

/* The default scene, headless: the top rows see the sky above the far
 * shore, so they are the glib's Background (0.55 0.72 0.90); the middle is
 * water, which is not. Two renders at the same time are identical. */
static void test_render_headless_is_deterministic_and_follows_scene(void) {
    char cmd[2048], out[8192], a[512], b[512];
    snprintf(a, sizeof a, "%s/pond-a.png", dir);
    snprintf(b, sizeof b, "%s/pond-b.png", dir);
    snprintf(cmd, sizeof cmd, "env -u DISPLAY -u WAYLAND_DISPLAY %s render %s/scenes/pond.glib -o %s "
             "--size 160x90 --time 3.5 2>&1", bin, src, a);
    int rc = run_command(cmd, out, sizeof out);
    if (rc == 3) SKIP("no OpenGL: %s", out);
    CHECK_MSG(rc == 0, "%s", out);
    CHECK_STR_CONTAINS(out, "wrote");
    snprintf(cmd, sizeof cmd, "env -u DISPLAY %s render %s/scenes/pond.glib -o %s --size 160x90 --time 3.5 --quiet 2>&1",
             bin, src, b);
    CHECK_EQ(run_command(cmd, out, sizeof out), 0);
    img ia, ib;
    char err[512];
    memset(&ia, 0, sizeof ia);
    memset(&ib, 0, sizeof ib);
    CHECK_MSG(img_read(a, &ia, err, sizeof err), "%s", err);
    CHECK_MSG(img_read(b, &ib, err, sizeof err), "%s", err);
    if (!ia.px || !ib.px) return;
    CHECK(ia.w == 160 && ia.h == 90);
    CHECK_EQ(memcmp(ia.px, ib.px, sizeof(float) * ia.w * ia.h * ia.channels), 0);
    const float *top = ia.px;   /* row 0 = top */
    CHECK_NEAR(top[0], 0.55, 1.0 / 255);
    CHECK_NEAR(top[1], 0.72, 1.0 / 255);
    CHECK_NEAR(top[2], 0.90, 1.0 / 255);
    const float *mid = ia.px + ((size_t)60 * ia.w + 80) * ia.channels;
    CHECK_GT(fabsf(mid[0] - 0.55f) + fabsf(mid[1] - 0.72f) + fabsf(mid[2] - 0.90f), 0.05f);
    img_free(&ia);
    img_free(&ib);
}

/* --frames N with %d writes every frame; time moves the waves. */
static void test_frames_write_every_frame(void) {
    char cmd[2048], out[8192], p0[512], p2[512];
    snprintf(cmd, sizeof cmd, "env -u DISPLAY %s render %s/scenes/pond.glib -o %s/f%%d.exr --size 64x36 --frames 3 2>&1",
             bin, src, dir);
    int rc = run_command(cmd, out, sizeof out);
    if (rc == 3) SKIP("no OpenGL");
    CHECK_MSG(rc == 0, "%s", out);
    CHECK_STR_CONTAINS(out, "median GPU time");
    snprintf(p0, sizeof p0, "%s/f0000.exr", dir);
    snprintf(p2, sizeof p2, "%s/f0002.exr", dir);
    CHECK_EQ(access(p0, R_OK), 0);
    CHECK_EQ(access(p2, R_OK), 0);
    /* 32-bit float, as the help says: half would quantise what a float
     * target holds (hit points: 4-8 mm at the lake's coordinates) */
    CHECK_MSG(exr_pixel_type(p0) == EXR_TYPE_FLOAT, "%s: pixel type %d, want float (2)", p0, exr_pixel_type(p0));
    img i0, i2;
    char err[256];
    memset(&i0, 0, sizeof i0);
    memset(&i2, 0, sizeof i2);
    if (img_read(p0, &i0, err, sizeof err) && img_read(p2, &i2, err, sizeof err))
        CHECK_NE(memcmp(i0.px, i2.px, sizeof(float) * i0.w * i0.h * i0.channels), 0);
    img_free(&i0);
    img_free(&i2);
}

/* --passes lists the world's height map and each drawing command by its
 * glib line (the lake: World and WaterSurface), and timing them (a finish
 * around each mark) changes no pixel. */
static void test_passes_lists_each_draw(void) {
    char cmd[2048], out[8192], a[512], b[512];
    snprintf(a, sizeof a, "%s/passes_on.exr", dir);
    snprintf(b, sizeof b, "%s/passes_off.exr", dir);
    snprintf(cmd, sizeof cmd,
             "env -u DISPLAY %s render %s/scenes/lake.glib --pack basic -o %s --size 64x36 --frames 2 --passes 2>&1",
             bin, src, a);
    int rc = run_command(cmd, out, sizeof out);
    if (rc == 3) SKIP("no OpenGL");
    CHECK_MSG(rc == 0, "%s", out);
    CHECK_STR_CONTAINS(out, "per pass:");
    CHECK_STR_CONTAINS(out, "world height");
    CHECK_STR_CONTAINS(out, "  World:");
    CHECK_STR_CONTAINS(out, "  WaterSurface:");
    snprintf(cmd, sizeof cmd, "env -u DISPLAY %s render %s/scenes/lake.glib --pack basic -o %s --size 64x36 --frames 2 2>&1",
             bin, src, b);
    rc = run_command(cmd, out, sizeof out);
    CHECK_MSG(rc == 0, "%s", out);
    CHECK_EQ(strstr(out, "per pass:"), NULL);
    img ia, ib;
    char err[256];
    memset(&ia, 0, sizeof ia);
    memset(&ib, 0, sizeof ib);
    CHECK(img_read(a, &ia, err, sizeof err) && img_read(b, &ib, err, sizeof err));
    CHECK(ia.w == ib.w && ia.h == ib.h && ia.channels == ib.channels);
    if (ia.px && ib.px && ia.w == ib.w && ia.h == ib.h && ia.channels == ib.channels)
        CHECK_EQ(memcmp(ia.px, ib.px, sizeof(float) * ia.w * ia.h * ia.channels), 0);
    img_free(&ia);
    img_free(&ib);
}

/* --detail D draws as the window's reduced frame at D does (natural's
 * photon grid and targets, the meshes coarser): --detail 1 is the full
 * frame bit for bit, 0.25 another picture; out of (0, 1] a usage error. */
static void test_detail_draws_as_a_reduced_frame(void) {
    char cmd[2048], out[8192], path[3][512];
    const char *detail[3] = { "", "--detail 1", "--detail 0.25" };
    img im[3];
    char err[256];
    memset(im, 0, sizeof im);
    for (int i = 0; i < 3; i++) {
        snprintf(path[i], sizeof path[i], "%s/detail%d.exr", dir, i);
        snprintf(cmd, sizeof cmd, "env -u DISPLAY %s render %s/scenes/lake.glib --pack natural -o %s --size 96x54 "
                 "--time 2 --msaa 1 --quiet %s 2>&1", bin, src, path[i], detail[i]);
        int rc = run_command(cmd, out, sizeof out);
        if (rc == 3) SKIP("no OpenGL");
        CHECK_MSG(rc == 0, "%s", out);
        CHECK_MSG(img_read(path[i], &im[i], err, sizeof err), "%s", err);
    }
    size_t n = (size_t)96 * 54 * im[0].channels;
    if (im[0].px && im[1].px && im[2].px && im[1].w == 96 && im[2].w == 96) {
        CHECK_EQ(memcmp(im[0].px, im[1].px, n * sizeof(float)), 0);
        size_t differ = 0;
        for (size_t k = 0; k < n; k++) differ += im[0].px[k] != im[2].px[k];
        CHECK_MSG(differ > 0, "--detail 0.25 drew the full frame's pixels");
    }
    for (int i = 0; i < 3; i++) img_free(&im[i]);
    const char *bad[2] = { "0", "1.5" };
    for (int i = 0; i < 2; i++) {
        snprintf(cmd, sizeof cmd, "env -u DISPLAY %s render %s/scenes/lake.glib -o %s --detail %s 2>&1", bin, src,
                 path[0], bad[i]);
        CHECK_EQ(run_command(cmd, out, sizeof out), 2);
        CHECK_STR_CONTAINS(out, "--detail");
    }
}

/* The pond rendered at 160x90 with Floor.uSandColor=1,0,0: the floor seen
 * through the water near the bottom (pixel 80, 80) is red. */
static void check_floor_red(const char *png, const char *what) {
    img im;
    char err[256];
    memset(&im, 0, sizeof im);
    CHECK_MSG(img_read(png, &im, err, sizeof err), "%s", err);
    if (im.px) {
        const float *p = im.px + ((size_t)80 * im.w + 80) * im.channels;
        CHECK_MSG(p[0] > p[1] + 0.1f && p[0] > p[2] + 0.1f, "%spixel %g %g %g", what, p[0], p[1], p[2]);
    }
    img_free(&im);
}

/* --set does what the panel does: the sand colour set to pure red makes a
 * floor pixel red-dominant; a name the scene lacks is an error naming it. */
static void test_set_changes_uniforms(void) {
    char cmd[2048], out[8192], a[512];
    snprintf(a, sizeof a, "%s/set.png", dir);
    snprintf(cmd, sizeof cmd, "env -u DISPLAY %s render %s/scenes/pond.glib -o %s --size 160x90 --quiet "
             "--set Floor.uSandColor=1,0,0 --set Water.uClarity=1 --set SPECULAR=0 2>&1", bin, src, a);
    int rc = run_command(cmd, out, sizeof out);
    if (rc == 3) SKIP("no OpenGL");
    CHECK_MSG(rc == 0, "%s", out);
    check_floor_red(a, "");
    snprintf(cmd, sizeof cmd, "env -u DISPLAY %s render %s/scenes/pond.glib -o %s --size 32x18 --quiet "
             "--set Water.uNope=1 2>&1", bin, src, a);
    CHECK_EQ(run_command(cmd, out, sizeof out), 1);
    CHECK_STR_CONTAINS(out, "no entry 'uNope' in Water");
}

/* Every --set is applied, however many: 69 harmless ones before the one
 * that turns the sand red (a fixed array of 64 once dropped the 65th on). */
static void test_many_sets_all_applied(void) {
    char cmd[8192], out[8192], a[512];
    snprintf(a, sizeof a, "%s/sets.png", dir);
    int n = snprintf(cmd, sizeof cmd, "env -u DISPLAY %s render %s/scenes/pond.glib -o %s --size 160x90 --quiet",
                     bin, src, a);
    for (int i = 0; i < 69; i++) n += snprintf(cmd + n, sizeof cmd - (size_t)n, " --set Water.uClarity=1");
    snprintf(cmd + n, sizeof cmd - (size_t)n, " --set Floor.uSandColor=1,0,0 2>&1");
    int rc = run_command(cmd, out, sizeof out);
    if (rc == 3) SKIP("no OpenGL");
    CHECK_MSG(rc == 0, "%s", out);
    check_floor_red(a, "the 70th --set was lost: ");
}

/* No arguments and no display: the default scene (the showcase pool, drawn
 * by the pack it names) goes to out/default.png at its WindowSize, the same
 * picture as `render scenes/showcase.glib` (issue #30: `tarn` and `tarn
 * view` of the same scene drew different packs). */
static void test_no_arguments_renders_default_scene(void) {
    char cmd[2048], out[8192], png[512], same[512];
    snprintf(cmd, sizeof cmd, "cd %s && env -u DISPLAY -u WAYLAND_DISPLAY %s 2>&1", dir, bin);
    int rc = run_command(cmd, out, sizeof out);
    if (rc == 3) SKIP("no OpenGL");
    CHECK_MSG(rc == 0, "%s", out);
    CHECK_STR_CONTAINS(out, "out/default.png");
    CHECK_STR_CONTAINS(out, "scenes/showcase.glib, pack natural");
    snprintf(png, sizeof png, "%s/out/default.png", dir);
    snprintf(same, sizeof same, "%s/showcase.png", dir);
    snprintf(cmd, sizeof cmd, "env -u DISPLAY %s render %s/scenes/showcase.glib --time 2 -o %s --quiet 2>&1",
             bin, src, same);
    CHECK_MSG(run_command(cmd, out, sizeof out) == 0, "%s", out);
    img a, b;
    char err[512];
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    CHECK_MSG(img_read(png, &a, err, sizeof err), "%s", err);
    CHECK_MSG(img_read(same, &b, err, sizeof err), "%s", err);
    CHECK(a.w == 960 && a.h == 540);
    CHECK(a.w == b.w && a.h == b.h && a.px && b.px &&
          a.channels == b.channels && memcmp(a.px, b.px, (size_t)a.w * a.h * a.channels * sizeof *a.px) == 0);
    img_free(&a);
    img_free(&b);
}

int main(void) {
    bin = getenv("TARN_BIN");
    src = getenv("TARN_SOURCE_DIR");
    if (!bin || !src) { fprintf(stderr, "run through ctest (TARN_BIN, TARN_SOURCE_DIR)\n"); return 1; }
    snprintf(dir, sizeof dir, "/tmp/tarn-test-cli-XXXXXX");
    if (!mkdtemp(dir)) return 1;
    RUN(test_help_lists_every_command);
    RUN(test_bad_usage_exits_2);
    RUN(test_missing_scene_names_the_file);
    RUN(test_huge_frame_is_refused);
    RUN(test_render_headless_is_deterministic_and_follows_scene);
    RUN(test_frames_write_every_frame);
    RUN(test_passes_lists_each_draw);
    RUN(test_detail_draws_as_a_reduced_frame);
    RUN(test_set_changes_uniforms);
    RUN(test_many_sets_all_applied);
    RUN(test_no_arguments_renders_default_scene);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
    return check_summary();
}
