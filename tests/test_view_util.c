/* test_view_util: what the windows share that needs no window: pass names
 * as the panel shows them, why a reload happened. */
#include <math.h>

#include "check.h"
#include "support.h"
#include "view_script.h"
#include "sheet_job.h"
#include "compile_job.h"
#include "view_util.h"

static void test_pass_names_read_as_the_glib(void) {
    char out[96];
    view_pass_name("pass:65 10", out, sizeof out);
    CHECK_STR_EQ(out, "RenderToTexture 10 (line 65)");
    view_pass_name("pass:21 8 9", out, sizeof out);
    CHECK_STR_EQ(out, "RenderToTexture 8 9 (line 21)");
    view_pass_name("screen:24", out, sizeof out);
    CHECK_STR_EQ(out, "to the screen (line 24)");
    view_pass_name("screen", out, sizeof out);      /* before any command */
    CHECK_STR_EQ(out, "screen");
    view_pass_name("pass:7 1 2 3 4 5 6 7 8", out, 12);   /* cut, never overrun */
    CHECK_EQ(strlen(out), 11);
}

/* A script is read whole, up to its line limit: a huge file is refused, not
 * held in memory. */
static void test_script_line_limit(void) {
    if (!scratch_create("script")) {
        CHECK(false);
        return;
    }
    const char *path = scratch_path("s.txt");
    char err[512] = "";
    for (int n = VIEW_SCRIPT_MAX_LINES; n <= VIEW_SCRIPT_MAX_LINES + 1; n++) {
        FILE *f = fopen(path, "w");
        CHECK_NE(f, NULL);
        if (!f) break;
        for (int i = 0; i < n; i++) fputs("frames 1\n", f);
        fclose(f);
        view_script *s = view_script_load(path, err, sizeof err);
        CHECK_MSG((s != NULL) == (n == VIEW_SCRIPT_MAX_LINES), "%d lines: %s", n, err);
        view_script_free(s);
    }
    CHECK_STR_CONTAINS(err, "more than 65536 lines");
    scratch_remove();
}

/* A script of text, written to the scratch folder and loaded (NULL, a
 * failed check, when it does not load). */
static view_script *script_of(const char *text) {
    char err[512] = "";
    scratch_write("s.txt", text);
    view_script *s = view_script_load(scratch_path("s.txt"), err, sizeof err);
    CHECK_MSG(s != NULL, "%s", err);
    return s;
}

/* `advance DT N`: N frames, each a new instant DT after the one before,
 * then the next line on the frame the last one showed (a benchmark grabs
 * it): the time each frame is drawn at is what the step before it left.
 * `frames N`: N frames, then the next line. */
static void test_script_frames_and_advance_count_frames(void) {
    if (!scratch_create("advance")) {
        CHECK(false);
        return;
    }
    view_script *s = script_of("time 1\nadvance 0.25 3\nquit\n");
    double t = 0;
    view_script_ctx c = { .time_s = &t };
    const double drawn_at[] = { 1.25, 1.5, 1.75 };
    for (int frame = 0; s && frame < 3; frame++) {
        CHECK_EQ(view_script_step(s, &c), VIEW_SCRIPT_CONTINUE);   /* the step before frame + 1 */
        CHECK_MSG(fabs(t - drawn_at[frame]) < 1e-12, "frame %d drawn at %g, not %g", frame + 1, t, drawn_at[frame]);
    }
    if (s) CHECK_EQ(view_script_step(s, &c), VIEW_SCRIPT_DONE);    /* after the third: the next line */
    CHECK(fabs(t - 1.75) < 1e-12);
    view_script_free(s);
    /* `frames N` likewise: N frames drawn as things are, then the next line
     * on the Nth (until 2026-12-07 it let N + 1 pass) */
    s = script_of("time 1\nframes 2\ntime 2\nquit\n");
    for (int frame = 0; s && frame < 2; frame++) {
        CHECK_EQ(view_script_step(s, &c), VIEW_SCRIPT_CONTINUE);
        CHECK_MSG(t == 1, "frame %d drawn at %g, not 1", frame + 1, t);
    }
    if (s) CHECK_EQ(view_script_step(s, &c), VIEW_SCRIPT_DONE);     /* after the second: time 2, quit */
    CHECK(t == 2);
    view_script_free(s);
    /* a count that is no whole number of frames, or no step: said, not run */
    const char *bad[] = { "advance 0.1 0\n", "advance 0.1\n", "advance x 3\n", "advance 0.1 2.5\n" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        s = script_of(bad[i]);
        t = 0;
        if (s) CHECK_MSG(view_script_step(s, &c) == VIEW_SCRIPT_FAILED, "%s", bad[i]);
        view_script_free(s);
    }
    scratch_remove();
}

/* A wait after an action (`pause 1`, `set`...) does not sleep before the
 * frame that shows it: the window draws it and a recording notes it then
 * (until 2026-12-07 the window slept through the wait over the old picture
 * and window_record_xvfb's replay could miss the change). A wait alone
 * sleeps at once. */
static void test_script_wait_draws_the_change_first(void) {
    if (!scratch_create("wait")) {
        CHECK(false);
        return;
    }
    view_script *s = script_of("pause 1\nwait 30\nquit\n");
    double t = 0;
    bool paused = false;
    view_script_ctx c = { .time_s = &t, .paused = &paused };
    if (s) {
        CHECK_EQ(view_script_step(s, &c), VIEW_SCRIPT_CONTINUE);
        CHECK(paused);
        CHECK_MSG(!view_script_waiting(s), "the wait sleeps before the frame that shows the pause");
        CHECK_EQ(view_script_wait_left_s(s), 0.0);
        CHECK_EQ(view_script_step(s, &c), VIEW_SCRIPT_CONTINUE);   /* that frame drawn */
        CHECK(view_script_waiting(s));
        CHECK(view_script_wait_left_s(s) > 29);
    }
    view_script_free(s);
    s = script_of("frames 1\nwait 30\nquit\n");
    if (s) {
        CHECK_EQ(view_script_step(s, &c), VIEW_SCRIPT_CONTINUE);   /* frames 1 */
        CHECK(!view_script_waiting(s));
        CHECK_EQ(view_script_step(s, &c), VIEW_SCRIPT_CONTINUE);   /* after it: wait, nothing changed */
        CHECK(view_script_waiting(s));
    }
    view_script_free(s);
    scratch_remove();
}

static void test_reload_cause_names_the_files(void) {
    char out[128];
    const char *one[] = { "/home/s/scenes/water.frag" };
    view_reload_cause(one, 1, out, sizeof out);
    CHECK_MSG(strcmp(out, "water.frag changed") == 0, "%s", out);
    const char *two[] = { "/a/water.frag", "scenes/lake.glib" };
    view_reload_cause(two, 2, out, sizeof out);
    CHECK_MSG(strcmp(out, "water.frag and lake.glib changed") == 0, "%s", out);
    const char *three[] = { "a.frag", "b.frag", "c.glsl" };
    view_reload_cause(three, 3, out, sizeof out);
    CHECK_MSG(strcmp(out, "a.frag, b.frag and c.glsl changed") == 0, "%s", out);
    const char *five[] = { "a.frag", "b.frag", "c.glsl", "d.glsl", "e.glib" };
    view_reload_cause(five, 5, out, sizeof out);
    CHECK_MSG(strcmp(out, "a.frag, b.frag and 3 more changed") == 0, "%s", out);
    view_reload_cause(NULL, 0, out, sizeof out);
    CHECK_EQ(out[0], '\0');
    view_reload_cause(five, 5, out, 9);   /* cut, never overrun */
    CHECK_EQ(strlen(out), 8);
}

/* The reload's line and the "compiling ..." note say what the window does
 * with a save (compile_job.h): off the frame, and for which file. */
/* When the job's work did not reach the window (its first frame after the
 * reload still slow), later saves compile on the frame. */
static void test_compile_job_helped(void) {
    CHECK(compile_job_helped(0.084, 1.10, 50));   /* raymarch on llvmpipe: about a frame */
    CHECK(compile_job_helped(0.37, 0.97, 50));    /* slower, but a third of the job's time */
    CHECK(!compile_job_helped(1.31, 1.25, 50));   /* natural: the window compiled again */
    CHECK(!compile_job_helped(0.55, 1.0, 50));    /* half the job's time or more */
    CHECK(compile_job_helped(0.25, 0.1, 50));     /* the limit itself still counts as help */
    CHECK(!compile_job_helped(0.26, 0.1, 0));     /* the budget off: the same limit */
    CHECK(compile_job_helped(0.7, 0.1, 200));     /* a 200 ms budget: four of them */
    CHECK(!compile_job_helped(0.9, 0.1, 200));
}

static void test_reload_line_and_compiling_text(void) {
    char out[256];
    view_reload_line("tarn", "lake.glib", "water.frag changed", 0.914, out, sizeof out);
    CHECK_MSG(strcmp(out, "tarn: reloaded lake.glib (water.frag changed), compiled off the frame in 0.91 s") == 0,
              "%s", out);
    view_reload_line("tarn", "lake.glib", "", -1, out, sizeof out);   /* R: no cause, compiled on the frame */
    CHECK_MSG(strcmp(out, "tarn: reloaded lake.glib") == 0, "%s", out);
    view_reload_line("tarn", "lake.glib", "water.frag changed", 0.5, out, 20);   /* cut, never overrun */
    CHECK_EQ(strlen(out), 19);
    view_compiling_text("water.frag changed", out, sizeof out);
    CHECK_MSG(strcmp(out, "compiling water.frag ... (the last good build draws meanwhile)") == 0, "%s", out);
    view_compiling_text("", out, sizeof out);
    CHECK_MSG(strncmp(out, "compiling ...", 13) == 0, "%s", out);
}

static orbit home(void) {
    render_view v = { { 0, 2, 10 }, { 0, 0, 0 }, { 0, 1, 0 } };
    return orbit_from_view(v);
}

/* A drag pressed at x = 10 and at x = 110 by the next frame (1 fps): the
 * camera turns by the whole 100 pixels, from the press. */
static void test_drag_runs_from_its_press(void) {
    view_mouse m = { .last_x = 400, .last_y = 300 };   /* the cursor's last frame */
    orbit cam = home(), want = home();
    view_mouse_press(&m, VIEW_MOUSE_LEFT, 10, 20);
    view_mouse_press(&m, VIEW_MOUSE_PAN, 50, 50);       /* a second press keeps the first's place */
    CHECK(m.press_x == 10 && m.press_y == 20);
    view_mouse_input in = { .x = 110, .y = 20, .left = true, .pressed = VIEW_MOUSE_LEFT, .press_x = 10, .press_y = 20 };
    view_mouse_step(&m, &in, false, &cam);
    orbit_rotate(&want, 100, 0);
    CHECK(orbit_equal(&cam, &want));
    /* held on: the next frame's move adds */
    in = (view_mouse_input){ .x = 130, .y = 20, .left = true };
    view_mouse_step(&m, &in, false, &cam);
    orbit_rotate(&want, 20, 0);
    CHECK(orbit_equal(&cam, &want));
    /* released: nothing more */
    in = (view_mouse_input){ .x = 300, .y = 20 };
    view_mouse_step(&m, &in, false, &cam);
    CHECK(orbit_equal(&cam, &want));
    /* a press over the panel is the panel's */
    orbit before = cam;
    in = (view_mouse_input){ .x = 200, .y = 20, .left = true, .pressed = VIEW_MOUSE_LEFT, .press_x = 100, .press_y = 20 };
    view_mouse_step(&m, &in, true, &cam);
    CHECK(orbit_equal(&cam, &before));
}

/* At 2 fps the cursor moves onto the panel and presses within one frame:
 * ImGui, which has not had a frame since, does not want the mouse yet. The
 * press is left of the panel's edge, so it is the panel's: the camera
 * stays, for the whole drag (issue #30). */
static void test_press_on_panel_never_reaches_camera(void) {
    view_mouse m = { .last_x = 600, .last_y = 300, .ui_right = 320 };
    orbit cam = home(), before = home();
    view_mouse_press(&m, VIEW_MOUSE_LEFT, 150, 200);
    view_mouse_input in = { .x = 180, .y = 200, .left = true, .pressed = VIEW_MOUSE_LEFT, .press_x = 150, .press_y = 200 };
    view_mouse_step(&m, &in, false, &cam);   /* ImGui's answer is a frame old: false */
    CHECK(orbit_equal(&cam, &before));
    in = (view_mouse_input){ .x = 500, .y = 260, .left = true };   /* dragged out over the scene, held */
    view_mouse_step(&m, &in, false, &cam);
    CHECK(orbit_equal(&cam, &before));
    /* the same press right of the edge is the camera's */
    view_mouse_input up = { .x = 500, .y = 260 };
    view_mouse_step(&m, &up, false, &cam);
    in = (view_mouse_input){ .x = 520, .y = 260, .left = true, .pressed = VIEW_MOUSE_LEFT, .press_x = 420, .press_y = 260 };
    view_mouse_step(&m, &in, false, &cam);
    CHECK(!orbit_equal(&cam, &before));
}

/* The window's hand-in sheet (issue #27) is `tarn sheet` with the slider
 * varied over its range and every value not at its default as a --set. */
static void test_sheet_command_line(void) {
    unif_entry e[3] = { { .name = "uOpacity", .widget = UNIF_WIDGET_SLIDER, .ncomp = 1, .min = 0, .max = 1 },
                        { .name = "uTint", .widget = UNIF_WIDGET_COLOR, .ncomp = 3 },
                        { .name = "uGlow", .widget = UNIF_WIDGET_SLIDER, .ncomp = 1, .min = 0, .max = 2 } };
    e[0].value[0] = 0.8f;                                   /* varied: no --set */
    e[1].value[0] = 1; e[1].value[1] = 0.5f; e[1].value[2] = 0.25f;   /* changed: --set */
    e[2].value[0] = e[2].def[0] = 1;                        /* at its default: none */
    unif_set set = { .program = "Water", .entries = e, .n = 3 };
    sheet_job_desc d = { .tarn = "tarn", .scene = "/p/lake.glib", .pack = "natural", .program = "Water",
                         .uniform = "uOpacity", .min = 0, .max = 1, .time_s = 2.5, .sets = &set, .nsets = 1,
                         .out = "s.png" };
    char *argv[32], text[2048], line[2048] = "";
    int argc = sheet_job_argv(&d, argv, 32, text, sizeof text);
    for (int i = 0; i < argc; i++) snprintf(line + strlen(line), sizeof line - strlen(line), "%s%s", i ? " " : "", argv[i]);
    CHECK_MSG(strcmp(line, "tarn sheet /p/lake.glib --vary Water.uOpacity=0:1:5 --time 2.5 --pack natural "
                           "--set Water.uTint=1,0.5,0.25 --quiet -o s.png") == 0, "%s", line);
    CHECK_EQ(argv[argc], NULL);
    CHECK_EQ(sheet_job_argv(&d, argv, 8, text, sizeof text), -1);   /* does not fit: said, not cut */
}

int main(void) {
    RUN(test_drag_runs_from_its_press);
    RUN(test_press_on_panel_never_reaches_camera);
    RUN(test_pass_names_read_as_the_glib);
    RUN(test_script_line_limit);
    RUN(test_script_frames_and_advance_count_frames);
    RUN(test_script_wait_draws_the_change_first);
    RUN(test_reload_cause_names_the_files);
    RUN(test_reload_line_and_compiling_text);
    RUN(test_compile_job_helped);
    RUN(test_sheet_command_line);
    return check_summary();
}
