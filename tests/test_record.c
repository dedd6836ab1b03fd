/* test_record: `tarn record` as a user runs it, headless. A session moves
 * the grey scene's slider (tests/data/window: the quad's colour is uGrey *
 * uTint while uOn) and then unticks uOn; the PNG frames are those values,
 * exactly, on either side of each event's time, and a second replay gives
 * the same bytes; a Define event rebuilds. On the pond, the replay's
 * frames are `tarn render`'s at the session's simulated time, which stops
 * while paused. Without ffmpeg the frames become PNGs with a message; a
 * bad session line is named by file:line and the rest still plays. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "image_io.h"
#include "support.h"

static const char *bin, *src;

/* The session of these tests: 1 s; frames at 10 fps are t = 0, 0.1, ... 0.9. */
static void write_session(const char *name, const char *extra) {
    char text[2048];
    snprintf(text, sizeof text,
             "tarn-session 1\n"
             "scene %s/tests/data/window/scene.glib\n"
             "pack -\n"
             "size 32 24\n"
             "time 0\n"
             "t=0.000 camera 0 0 0 3 0 0\n"
             "t=0.500 slider Flat uGrey 0.75\n"
             "t=0.800 checkbox Flat uOn 0\n"
             "%s"
             "t=1.000 end\n",
             src, extra);
    scratch_write(name, text);
}

static int tarn(const char *args, char *out, size_t outlen) {
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "cd %s && env -u DISPLAY %s %s 2>&1", scratch_dir, bin, args);
    int rc = run_command(cmd, out, outlen);
    fputs(out, stderr);
    return rc;
}

static bool read_frame(const char *dir, int i, img *im) {
    char path[600], err[512];
    snprintf(path, sizeof path, "%s/%s/frame-%05d.png", scratch_dir, dir, i);
    return img_read(path, im, err, sizeof err);
}

/* The grey level of the frame's centre, 0..255. */
static int centre_grey(const img *im) {
    const float *p = &im->px[((im->h / 2) * im->w + im->w / 2) * im->channels];
    return (int)(p[0] * 255.0f + 0.5f);
}

static void test_replay_is_deterministic_and_follows_the_events(void) {
    write_session("s.session", "");
    char out[8192];
    CHECK_EQ(tarn("record s.session -o a/ --fps 10 --size 40x30", out, sizeof out), 0);
    CHECK_STR_CONTAINS(out, "10 frames, 40x30, 10 fps");
    CHECK_EQ(tarn("record s.session -o b/ --fps 10 --size 40x30", out, sizeof out), 0);
    /* uGrey 0.25 (the glib's default) before t=0.5, 0.75 until t=0.8, then uOn off: 0 */
    const int want[10] = { 64, 64, 64, 64, 64, 191, 191, 191, 0, 0 };
    for (int i = 0; i < 10; i++) {
        img a = {0}, b = {0};
        CHECK(read_frame("a", i, &a) && read_frame("b", i, &b));
        if (!a.px || !b.px) { img_free(&a); img_free(&b); return; }
        CHECK(a.w == 40 && a.h == 30);
        CHECK_MSG(centre_grey(&a) == want[i], "frame %d: grey %d, want %d", i, centre_grey(&a), want[i]);
        CHECK_MSG(a.w == b.w && a.h == b.h && memcmp(a.px, b.px, sizeof(float) * (size_t)(a.w * a.h * a.channels)) == 0,
                  "frame %d differs between two replays", i);
        img_free(&a);
        img_free(&b);
    }
    img extra = {0};
    CHECK(!read_frame("a", 10, &extra));   /* 1 s at 10 fps: 10 frames */
    img_free(&extra);
}

/* The header's size is the default; the fps sets where events fall. */
static void test_session_size_and_fps(void) {
    write_session("s.session", "");
    char out[8192];
    CHECK_EQ(tarn("record s.session -o c/ --fps 4", out, sizeof out), 0);
    CHECK_STR_CONTAINS(out, "4 frames, 32x24, 4 fps");
    const int want[4] = { 64, 64, 191, 191 };   /* t = 0, 0.25, 0.5, 0.75 */
    for (int i = 0; i < 4; i++) {
        img a = {0};
        CHECK(read_frame("c", i, &a));
        if (a.px) CHECK(a.w == 32 && a.h == 24 && centre_grey(&a) == want[i]);
        img_free(&a);
    }
}

static void test_no_ffmpeg_writes_pngs_and_says_so(void) {
    write_session("s.session", "");
    char out[8192], full[2048];
    snprintf(full, sizeof full,
             "cd %s && env -u DISPLAY TARN_FFMPEG=/nonexistent/ffmpeg %s record s.session -o take.mp4 --fps 10 2>&1",
             scratch_dir, bin);
    CHECK_EQ(run_command(full, out, sizeof out), 0);
    fputs(out, stderr);
    CHECK_STR_CONTAINS(out, "apt-get install ffmpeg");
    CHECK_STR_CONTAINS(out, "take-frames/");
    img a = {0};
    CHECK(read_frame("take-frames", 9, &a));
    if (a.px) CHECK_EQ(centre_grey(&a), 0);
    img_free(&a);
}

static void test_bad_lines_are_named_and_the_rest_plays(void) {
    write_session("bad.session", "t=0.900 slider Flat\nt=0.850 slider Flat uNope 1\n");
    char out[8192];
    CHECK_EQ(tarn("record bad.session -o d/ --fps 10", out, sizeof out), 1);
    CHECK_STR_CONTAINS(out, "bad.session:9: error: slider: expected PROGRAM NAME");
    CHECK_STR_CONTAINS(out, "bad.session:10: no uniform 'uNope'");   /* the scene lacks it */
    img a = {0};
    CHECK(read_frame("d", 5, &a));
    if (a.px) CHECK_EQ(centre_grey(&a), 191);
    img_free(&a);

    scratch_write("glib.session", "##OpenGL GLIB\nWindowSize 32 24\n");
    CHECK_EQ(tarn("record glib.session -o e/", out, sizeof out), 1);
    CHECK_STR_CONTAINS(out, "glib.session:2: error: not a tarn session");
    scratch_write("noscene.session", "tarn-session 1\nscene nope.glib\nt=1 end\n");
    CHECK_EQ(tarn("record noscene.session -o e/", out, sizeof out), 1);
    CHECK_STR_CONTAINS(out, "nope.glib");
}

/* A Define event rebuilds the program: the frame after it is drawn with
 * the new #define (LEVEL is the grey level, 0.25 -> 0.75). */
static void test_define_event_rebuilds(void) {
    scratch_write("level.vert", "#version 330 compatibility\n"
                                "void main() { gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; }\n");
    scratch_write("level.frag", "#version 330 compatibility\nout vec4 c;\n"
                                "void main() { c = vec4(vec3(LEVEL), 1.); }\n");
    scratch_write("level.glib", "##OpenGL GLIB\nWindowSize 16 12\nOrtho -1 1 -1 1\n"
                                "Define LEVEL <0. 0.25 1.>\nVertex level.vert\nFragment level.frag\n"
                                "Program Level\nQuadXY 0 1 1 1\n");
    scratch_write("level.session", "tarn-session 1\nscene level.glib\n"
                                   "t=0.5 define Level LEVEL 0.75\nt=1 end\n");
    char out[8192];
    CHECK_EQ(tarn("record level.session -o lv/ --fps 4", out, sizeof out), 0);
    const int want[4] = { 64, 64, 191, 191 };
    for (int i = 0; i < 4; i++) {
        img a = {0};
        CHECK(read_frame("lv", i, &a));
        if (a.px) CHECK_MSG(centre_grey(&a) == want[i], "frame %d: grey %d", i, centre_grey(&a));
        img_free(&a);
    }
}

/* The largest difference of two frames' RGB, 0..1 (1 when they cannot be read or differ in size). */
static float rgb_diff(const img *a, const img *b) {
    if (!a->px || !b->px || a->w != b->w || a->h != b->h) return 1;
    float worst = 0;
    for (long i = 0; i < (long)a->w * a->h; i++)
        for (int k = 0; k < 3; k++) {
            float d = fabsf(a->px[i * a->channels + k] - b->px[i * b->channels + k]);
            if (d > worst) worst = d;
        }
    return worst;
}

/* Independent truth for the replay's camera, clock and colour encoding:
 * the pond (a world, sRGB-encoded) from the glib's LookAt is `tarn render`
 * at the simulated time. The session starts at 2 s and pauses from 0.25 to
 * 0.75 s, so at 4 fps the clock reads 2, 2.25, 2.25, 2.25, 2.5: the paused
 * frames are one image, the first and last are tarn render's at 2 and 2.5. */
static void test_clock_and_pause_match_tarn_render(void) {
    char text[1024], out[8192], args[1200];
    snprintf(text, sizeof text,
             "tarn-session 1\nscene %s/scenes/pond.glib\ntime 2\nt=0.25 pause 1\nt=0.75 pause 0\nt=1.25 end\n", src);
    scratch_write("pond.session", text);
    CHECK_EQ(tarn("record pond.session -o pond/ --size 48x27 --fps 4", out, sizeof out), 0);
    img f[5], r[2];
    memset(f, 0, sizeof f);
    memset(r, 0, sizeof r);
    for (int i = 0; i < 5; i++) CHECK(read_frame("pond", i, &f[i]));
    const char *times[2] = { "2", "2.5" };
    for (int i = 0; i < 2; i++) {
        snprintf(args, sizeof args, "render %s/scenes/pond.glib --time %s --size 48x27 -o r%d.png --quiet", src,
                 times[i], i);
        CHECK_EQ(tarn(args, out, sizeof out), 0);
        char path[600], err[512];
        snprintf(path, sizeof path, "%s/r%d.png", scratch_dir, i);
        CHECK(img_read(path, &r[i], err, sizeof err));
    }
    CHECK_MSG(rgb_diff(&f[0], &r[0]) == 0, "frame 0 is not tarn render at 2 s (by %g)", rgb_diff(&f[0], &r[0]));
    CHECK_MSG(rgb_diff(&f[4], &r[1]) == 0, "frame 4 is not tarn render at 2.5 s (by %g)", rgb_diff(&f[4], &r[1]));
    CHECK(rgb_diff(&f[1], &f[2]) == 0 && rgb_diff(&f[2], &f[3]) == 0);   /* paused */
    CHECK(rgb_diff(&f[0], &f[1]) > 0 && rgb_diff(&f[3], &f[4]) > 0);     /* the water moves */
    for (int i = 0; i < 5; i++) img_free(&f[i]);
    img_free(&r[0]);
    img_free(&r[1]);
}

static void test_usage(void) {
    char out[8192];
    CHECK_EQ(tarn("record", out, sizeof out), 2);
    CHECK_EQ(tarn("record s.session", out, sizeof out), 2);
    CHECK_STR_CONTAINS(out, "-o out.mp4");
    CHECK_EQ(tarn("record s.session -o x/ --fps 0", out, sizeof out), 2);
    CHECK_EQ(tarn("record s.session -o x/ --fps 2.5", out, sizeof out), 2);
    CHECK_EQ(tarn("record s.session -o video", out, sizeof out), 2);   /* ffmpeg could not tell the format */
    CHECK_STR_CONTAINS(out, "extension");
    CHECK_EQ(tarn("record --help", out, sizeof out), 0);
    CHECK_STR_CONTAINS(out, "usage: tarn record SESSION");
}

int main(void) {
    bin = getenv("TARN_BIN");
    src = getenv("TARN_SOURCE_DIR");
    if (!bin || !src) { fprintf(stderr, "skip: TARN_BIN and TARN_SOURCE_DIR unset (run through ctest)\n"); return 77; }
    if (!scratch_create("record")) return 1;
    write_session("s.session", "");
    char out[8192];
    if (tarn("record s.session -o probe/ --fps 1", out, sizeof out) == 3) {
        fprintf(stderr, "skip: no OpenGL here\n");
        scratch_remove();
        return 77;
    }
    RUN(test_replay_is_deterministic_and_follows_the_events);
    RUN(test_session_size_and_fps);
    RUN(test_no_ffmpeg_writes_pngs_and_says_so);
    RUN(test_bad_lines_are_named_and_the_rest_plays);
    RUN(test_define_event_rebuilds);
    RUN(test_clock_and_pause_match_tarn_render);
    RUN(test_usage);
    scratch_remove();
    return check_summary();
}
