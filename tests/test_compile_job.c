/* test_compile_job: a save's shaders compiled off the window's frame
 * (viewer/ui/compile_job.h), on a worker thread with its own headless
 * context: a job says ready (the moving frames' code made) and then done;
 * one started with wait_for_shown does not make the still frame's code
 * before the window says it has shown the change (compile_job_shown) or
 * COMPILE_JOB_SHOWN_WAIT_S has passed, so the window's first frame of the
 * change does not share the cores with that compile; one for a paused
 * window (still) draws only the change's first frame before its ready,
 * then the sharp frame's code with the water as a grid before the deferred
 * water's (a cancelled one ends after it), and every frame by its end;
 * one for a window whose clock runs
 * (defer_still) makes the still frame only when the window asks. */
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "compile_job.h"
#include "gl_ctx.h"
#include "gl_support.h"
#include "render.h"
#include "util.h"

/* What a run does as soon as the job is ready. */
typedef enum { AT_READY_NOTHING, AT_READY_SHOWN, AT_READY_CANCEL } at_ready_do;

/* Runs a job on r; at_ready: compile_job_shown or compile_job_cancel as
 * soon as it is ready, or nothing. Gives the times from start to ready and
 * from ready to done. */
static void run_job_on(compile_job *j, render *r, bool wait, at_ready_do at_ready, bool still, double *ready_s,
                       double *done_after_s, int *frames_at_ready, int *frames_in_all) {
    render *const scenes[1] = { r };
    compile_job_desc d = { .scenes = scenes, .n = 1, .w = 96, .h = 54, .t = 2.0,
                           .view = render_default_view(r), .wait_for_shown = wait, .still = still };
    double t0 = clock_now_s(), ready_at = 0, secs;
    CHECK(compile_job_start(j, &d));
    CHECK(!compile_job_start(j, &d));   /* one job at a time */
    CHECK(compile_job_compiling(j));    /* its LLVM takes a core from now on */
    if (still) CHECK_MSG(!compile_job_still_ready(j), "a job just started said its sharp frame made");
    for (;;) {
        if (!ready_at && compile_job_ready(j, &secs)) {
            ready_at = clock_now_s();
            /* waiting for the window's first frame (the reload's, drawn
             * small as the job resumes after it) still counts */
            CHECK(compile_job_compiling(j));
            if (at_ready == AT_READY_SHOWN) compile_job_shown(j);
            if (at_ready == AT_READY_CANCEL) {
                compile_job_cancel(j);
                CHECK_MSG(compile_job_wait_done(j, 5.0), "a cancelled job did not end");
            }
        }
        if (compile_job_done(j, &secs)) break;
        CHECK_MSG(clock_now_s() - t0 < 120, "the job never ended");
        if (clock_now_s() - t0 >= 120) break;
        clock_sleep_s(0.002);
    }
    double done_at = clock_now_s();
    CHECK(!compile_job_compiling(j));
    CHECK_MSG(ready_at > 0, "the job ended without saying ready");
    if (!ready_at) ready_at = done_at;
    *ready_s = ready_at - t0;
    *done_after_s = done_at - ready_at;
    compile_job_frames(j, frames_at_ready, frames_in_all);
}

static void run_job(render *r, bool wait, bool shown_at_ready, bool still, double *ready_s, double *done_after_s,
                    int *frames_at_ready, int *frames_in_all) {
    compile_job *j = compile_job_create();
    run_job_on(j, r, wait, shown_at_ready ? AT_READY_SHOWN : AT_READY_NOTHING, still, ready_s, done_after_s,
               frames_at_ready, frames_in_all);
    compile_job_destroy(j);
}

static void run(render *r, bool wait, bool shown_at_ready, double *ready_s, double *done_after_s) {
    int at_ready, in_all;
    run_job(r, wait, shown_at_ready, false, ready_s, done_after_s, &at_ready, &in_all);
}

static void test_waits_for_the_window(void) {
    if (!compile_job_useful()) SKIP("Mesa's shader cache is off: the window compiles on the frame");
    render *r = render_create(&(render_desc){ .pack = "basic" });
    CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/scenes/lake.glib"), "%s", render_messages(r));
    double ready, after;
    run(r, false, false, &ready, &after);   /* fills Mesa's cache: the runs below find it */
    printf("no wait: ready after %.2f s, done %.2f s later\n", ready, after);
    run(r, true, false, &ready, &after);
    printf("waiting, never shown: ready after %.2f s, done %.2f s later\n", ready, after);
    CHECK_MSG(after >= COMPILE_JOB_SHOWN_WAIT_S * 0.95, "the still frame's code was made %.3f s after ready, "
              "before the window could show the change", after);
    run(r, true, true, &ready, &after);
    printf("waiting, shown at ready: ready after %.2f s, done %.2f s later\n", ready, after);
    render_destroy(r);
}

/* A paused window draws the change's first frame and then the full one:
 * the job makes the moving picture's later frames (the world copied from
 * its cache, its layers) after its ready, not before. */
static void test_still_window_first_frame_first(void) {
    if (!compile_job_useful()) SKIP("Mesa's shader cache is off: the window compiles on the frame");
    render *r = render_create(&(render_desc){ .pack = "basic" });
    CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/scenes/lake.glib"), "%s", render_messages(r));
    double ready, after;
    int moving_ready, moving_all, still_ready, still_all;
    run_job(r, false, false, false, &ready, &after, &moving_ready, &moving_all);
    run_job(r, false, false, true, &ready, &after, &still_ready, &still_all);
    printf("frames at ready / in all: moving %d / %d, still %d / %d\n", moving_ready, moving_all, still_ready,
           still_all);
    CHECK_MSG(moving_ready == 4 && moving_all == 6, "a moving picture's job: %d frames at ready, %d in all "
              "(4 moving frames, one with the water deferred, then the still one)", moving_ready, moving_all);
    CHECK_MSG(still_ready == 1 && still_all == 7, "a still window's job: %d frames at ready, %d in all (the "
              "change's first frame, then the 3 others, the still one as a grid, one deferred and the still one "
              "deferred)", still_ready, still_all);
    render_destroy(r);
}

/* A paused window's sharp frame: the job makes its code with the water as
 * a grid before the deferred water's (compile_job_still_ready after the 3
 * moving frames and that one, the deferred ones after it); a cancelled job
 * ends at its next step, and the next runs whole. */
static void test_still_window_sharp_frame_first(void) {
    if (!compile_job_useful()) SKIP("Mesa's shader cache is off: the window compiles on the frame");
    render *r = render_create(&(render_desc){ .pack = "basic" });
    CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/scenes/lake.glib"), "%s", render_messages(r));
    compile_job *j = compile_job_create();
    for (int round = 0; round < 3; round++) {
        /* round 1 cancels while the job waits for the change's first frame */
        double ready, after;
        int at_ready, in_all;
        run_job_on(j, r, true, round == 1 ? AT_READY_CANCEL : AT_READY_SHOWN, true, &ready, &after, &at_ready,
                   &in_all);
        int at_still = compile_job_frames_at_still(j);
        if (round == 1) {
            CHECK_MSG(in_all == 1 && at_still == 0, "cancelled at its ready: %d frames in all, %d before the "
                      "sharp one (1 and 0)", in_all, at_still);
            continue;
        }
        CHECK_MSG(at_still == 5 && in_all == 7, "round %d: the sharp frame's code after %d frames (the first, 3 "
                  "moving, the sharp one: 5), %d in all (7)", round, at_still, in_all);
    }
    compile_job_destroy(j);
    render_destroy(r);
}

/* With the clock running, the moving picture's later frames draw only the
 * world's code anew: before the ready where the world's programs are new
 * (the job's first load), after it where the reload kept them (a save of a
 * pack's shader). */
static void test_moving_picture_world_kept(void) {
    if (!compile_job_useful()) SKIP("Mesa's shader cache is off: the window compiles on the frame");
    render *r = render_create(&(render_desc){ .pack = "basic" });
    CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/scenes/lake.glib"), "%s", render_messages(r));
    compile_job *j = compile_job_create();
    double ready, after;
    int first_ready, first_all, again_ready, again_all;
    run_job_on(j, r, false, AT_READY_NOTHING, false, &ready, &after, &first_ready, &first_all);
    run_job_on(j, r, false, AT_READY_NOTHING, false, &ready, &after, &again_ready, &again_all);
    printf("frames at ready / in all: the job's first load %d / %d, a reload that kept the world %d / %d\n",
           first_ready, first_all, again_ready, again_all);
    CHECK_MSG(first_ready == 4 && first_all == 6, "the world's programs new: %d frames at ready, %d in all",
              first_ready, first_all);
    CHECK_MSG(again_ready == 1 && again_all == 6, "the world's programs kept: %d frames at ready, %d in all",
              again_ready, again_all);
    compile_job_destroy(j);
    render_destroy(r);
}

/* Waits (at most 120 s) for the job's end; its frames in all. */
static int frames_at_end(compile_job *j) {
    double t0 = clock_now_s(), secs;
    while (!compile_job_done(j, &secs)) {
        if (clock_now_s() - t0 >= 120) {
            CHECK_MSG(false, "the job never ended");
            return -1;
        }
        clock_sleep_s(0.002);
    }
    int at_ready, in_all;
    compile_job_frames(j, &at_ready, &in_all);
    return in_all;
}

/* One defer_still job on r up to its wait for the window's answer; false
 * (checked) when it does not get there. */
static bool job_waiting_for_still(compile_job *j, render *r) {
    render *const scenes[1] = { r };
    compile_job_desc d = { .scenes = scenes, .n = 1, .w = 96, .h = 54, .t = 2.0, .view = render_default_view(r),
                           .defer_still = true };
    CHECK(compile_job_start(j, &d));
    double t0 = clock_now_s(), secs;
    while (!compile_job_still_waits(j) && clock_now_s() - t0 < 120) clock_sleep_s(0.002);
    CHECK_MSG(compile_job_still_waits(j), "the job never waited for the still frame's answer");
    CHECK_MSG(!compile_job_compiling(j), "waiting for the still frame's answer, yet said to compile");
    CHECK_MSG(compile_job_ready(j, &secs), "waiting for the still frame's answer, yet not ready");
    clock_sleep_s(0.2);
    CHECK_MSG(!compile_job_done(j, &secs), "a defer_still job ended before the window answered");
    return compile_job_still_waits(j);
}

/* With the clock running the window needs the still picture's frame only
 * once it stops: the job waits for the window to ask (want_still: all 6
 * frames) or to let it go (drop_still, a newer change: the 4 moving ones
 * with the water as a grid, one deferred). */
static void test_still_frame_when_asked(void) {
    if (!compile_job_useful()) SKIP("Mesa's shader cache is off: the window compiles on the frame");
    render *r = render_create(&(render_desc){ .pack = "basic" });
    CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/scenes/lake.glib"), "%s", render_messages(r));
    compile_job *j = compile_job_create();
    if (job_waiting_for_still(j, r)) {
        /* the deferred water's code is made before the still frame's wait:
         * an animating window turns to it without the job's end */
        CHECK(compile_job_deferred_ready(j));
        compile_job_want_still(j);
        CHECK_MSG(compile_job_compiling(j), "asked for the still frame, yet not said to compile");
        int n = frames_at_end(j);
        CHECK_MSG(n == 6, "asked for the still frame: %d frames in all (4 moving, 1 deferred, then the still "
                  "one)", n);
    }
    if (job_waiting_for_still(j, r)) {
        compile_job_drop_still(j);
        int n = frames_at_end(j);
        CHECK_MSG(n == 5, "let go without the still frame: %d frames in all (the 4 moving ones as a grid, "
                  "one deferred)", n);
    }
    /* the window's scenes as the job has them, until a pack switch */
    render *const scenes[1] = { r };
    CHECK(compile_job_draws(j, scenes, 1));
    render_set_pack(r, "raymarch");
    CHECK_MSG(!compile_job_draws(j, scenes, 1), "another pack, yet the job draws the scene as it is");
    render_set_pack(r, "basic");
    CHECK(compile_job_draws(j, scenes, 1));
    CHECK(!compile_job_draws(j, scenes, 0));
    compile_job_want_still(j);   /* no job: nothing to answer, the next starts afresh */
    CHECK(job_waiting_for_still(j, r));
    compile_job_destroy(j);   /* while it waits: ends at once */
    render_destroy(r);
}

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    RUN(test_waits_for_the_window);
    RUN(test_still_window_first_frame_first);
    RUN(test_still_window_sharp_frame_first);
    RUN(test_moving_picture_world_kept);
    RUN(test_still_frame_when_asked);
    gl_ctx_destroy(ctx);
    return check_summary();
}
