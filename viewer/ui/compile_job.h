/* compile_job: a save's shaders compiled off the window's frame (issue #30).
 *
 * On Mesa's llvmpipe the GLSL front end runs in glLinkProgram and the LLVM
 * compile of a fragment shader's variant at the first draw that uses it:
 * 0.6-1.2 s for a pack's water shader, on the thread that draws the
 * window, which froze for as long. Mesa keeps both results in its on-disk
 * shader cache, keyed by the shader's text and the draw state, not by the
 * context. So before a save's reload, a compile job loads the same scene
 * into a render of its own, on a worker thread with a headless context of
 * its own, and draws frames as the window would (the same pack, MSAA,
 * Define values and target format, reduced and full detail); the window keeps drawing with
 * the last good programs meanwhile. Once the reduced frames' code is made
 * (compile_job_ready) the window reloads, finding the stages and variants
 * in the cache, and shows the change while the job makes the still
 * picture's full-resolution frame (another variant for each target of
 * the scene's own size: 0.15-0.25 s more for a pack's water), which the
 * window holds back until the job ends (res_budget_hold_full); with the
 * clock running, only once the window asks for it (defer_still); a
 * paused window (still) gets that frame's code with the water as a grid
 * first, before the deferred water's (compile_job_still_ready).
 *
 * The job's render shares nothing with the window's: no GL object, no
 * state; it reads the files as they are when it runs. What it compiles is
 * thrown away with its context; its messages too (the window's reload
 * reports them). Without Mesa's cache (MESA_SHADER_CACHE_DISABLE) it buys
 * nothing: compile_job_useful() says so and the window reloads at once.
 * Nor does it for a scene whose first draw after the reload is still slow
 * (the window's context making code the job's did not; app.c notices and
 * compiles on the frame from then on).
 *
 *     compile_job *j = compile_job_create();
 *     compile_job_start(j, &(compile_job_desc){ scenes, n, w, h, t, view });
 *     ... each frame: if (compile_job_ready(j, &s)) reload now (the moving
 *         picture's code is made); hold the still picture's full frame until
 *         compile_job_done(j, &s) (its code is made then), with defer_still
 *         asking for it by compile_job_want_still once it is due ...
 *     compile_job_destroy(j);                 stops a running job at its next step
 */
#ifndef TARN_COMPILE_JOB_H
#define TARN_COMPILE_JOB_H

#include <stdbool.h>

#include "render.h"

#define COMPILE_JOB_MAX_SCENES 4

typedef struct compile_job compile_job;

typedef struct compile_job_desc {
    render *const *scenes;       /* what the window draws: read by compile_job_start, on its thread */
    int n;                       /* at most COMPILE_JOB_MAX_SCENES are warmed */
    int w, h;                    /* the size the window draws them at (0: 256 x 144) */
    double t;                    /* the clock */
    render_view view;
    /* after its ready, wait (at most COMPILE_JOB_SHOWN_WAIT_S) for
     * compile_job_shown before making the still frame's code: the window's
     * first frame of the change, drawn meanwhile on the cores the job's
     * compile would take, cost 75-100 ms instead of 35-45 (basic, lake) */
    bool wait_for_shown;
    /* the window's clock is paused: until something else changes it draws
     * the change's first frame and then the still picture's full one, none
     * like the later frames of a moving picture (the world's cache copied,
     * its layers built and composited), so the job makes those after its
     * ready instead of before (a save's first new frame 18-45 ms sooner on
     * the lake); with the clock running they come first only where the
     * world's programs changed (render_world_programs_hash) */
    bool still;
    /* the window's clock runs: its frames are reduced ones for as long as
     * it does, and the still picture's full frame comes only once it
     * stops, so after its ready the job waits for compile_job_want_still
     * before making that frame's code (or ends without it at
     * compile_job_drop_still) instead of making it at once on a core the
     * window's next frames draw on (they took 160-190 ms, natural on the
     * lake, against the 50 ms budget) */
    bool defer_still;
    /* called on the job's thread at its ready and at its end (NULL: none):
     * a window asleep while the job compiles (glfwWaitEventsTimeout) looks
     * at once instead of at its next poll */
    void (*wake)(void *user);
    void *wake_user;
} compile_job_desc;

compile_job *compile_job_create(void);
/* NULL is fine. A running job stops at its next step (a scene's load or
 * one frame under way ends first), then the thread is joined. */
void compile_job_destroy(compile_job *j);

/* Copies what it needs of d's scenes (path, desc, Define values, whether
 * a world draws in sRGB) and starts the worker. False (nothing started)
 * while a job runs or when no thread can be made. */
bool compile_job_start(compile_job *j, const compile_job_desc *d);

bool compile_job_busy(compile_job *j);

/* Does a job hold one of the cores the window's frames draw on
 * (res_budget_contend): it runs and does not wait for the window's still
 * answer (defer_still)? Its wait for the window's first frame of the
 * change (wait_for_shown) counts: that frame, the reload's, is the one
 * the job resumes after, and drawn at the calm size it took 50-58 ms
 * (basic, lake) against 21-34 drawn smaller. Any thread; NULL is fine
 * (false). */
bool compile_job_compiling(compile_job *j);

/* True once per job when the code of the frames the window draws while
 * its picture changes is made (or the job ended first), with how long that
 * took: the window reloads then, and shows the change. The job goes on to
 * make the still picture's full-resolution frame (compile_job_done). */
bool compile_job_ready(compile_job *j, double *seconds);

/* The deferred water (render_set_deferred_water) of the job's build has
 * its code made too (or no job runs): the window draws a reload's water
 * as a grid until then, so that the reload at compile_job_ready needs one
 * GLSL front end of the water's text (the grid's), not two (the
 * deferred's shade pass is the same text once more). Any thread; NULL is
 * fine (true). */
bool compile_job_deferred_ready(compile_job *j);

/* A job started with still (a paused window) has made the still
 * picture's full frame with the water as a grid, right after the reduced
 * frames and before the deferred water's code (or no job runs, or it
 * ended): the window may draw its full frame now, with the grid it draws
 * until compile_job_deferred_ready. Any thread; NULL is fine (true). */
bool compile_job_still_ready(compile_job *j);
/* What the running job makes from now on is old (a newer change, after
 * the window showed this one): it ends at its next step, a wait for
 * compile_job_want_still included (a frame under way ends first;
 * compile_job_wait_done waits for that). Its code made so far stays in
 * Mesa's cache. Any thread; NULL is fine. */
void compile_job_cancel(compile_job *j);

/* The window has shown the change (its first frame after the reload at
 * the job's ready is on screen), or will not reload before the job's end:
 * a job started with wait_for_shown goes on. Any thread; NULL is fine. */
#define COMPILE_JOB_SHOWN_WAIT_S 0.5
void compile_job_shown(compile_job *j);
/* A job started with defer_still, once its ready is taken: make the
 * still picture's code now (the window's picture stands still, or its
 * moving frames are to be full-resolution ones), or end without it (a new
 * change makes this job's code old). Is it waiting for either? Any thread;
 * NULL is fine. */
void compile_job_want_still(compile_job *j);
void compile_job_drop_still(compile_job *j);
bool compile_job_still_waits(compile_job *j);
/* Is the job (running or last) one of these scenes, as they are drawn
 * now (file, pack, samples)? Not after a pack switch: its still frame
 * would be the old pack's. Call on the window's thread. */
bool compile_job_draws(compile_job *j, render *const *scenes, int n);
/* Waits at most max_s for the running job's end (compile_job_done then
 * says so): a new change after drop_still starts its own job at once (the
 * worker only has to wake: COMPILE_JOB_DROP_WAIT_S is ample). */
#define COMPILE_JOB_DROP_WAIT_S 0.1
bool compile_job_wait_done(compile_job *j, double max_s);
/* True once after a started job has ended (every frame's code made), with
 * how long it ran; a new job can start from then. */
bool compile_job_done(compile_job *j, double *seconds);
/* The frames the last job that ended drew before its ready and in all,
 * over its scenes (what a still window's job leaves until after its ready
 * shows here: tests). */
void compile_job_frames(compile_job *j, int *at_ready, int *in_all);
/* The frames the last job (running or ended) drew before its
 * compile_job_still_ready: 0 for a job that did not make the sharp frame
 * first (tests). */
int compile_job_frames_at_still(compile_job *j);

/* Does compiling off the frame help here? False when Mesa's shader cache
 * is off (MESA_SHADER_CACHE_DISABLE or MESA_GLSL_CACHE_DISABLE true), or
 * TARN_COMPILE_ON_FRAME is set (the old way, for A/B measurements). */
bool compile_job_useful(void);

/* Did the job make the new build's first draw cheap? The job ran job_s;
 * the window's frame that reloaded after it took first_frame_s. Up to
 * COMPILE_JOB_SLOW_S (or four frame budgets, for a budget above that) it
 * did; above that, when that frame took half the job's time or more, the
 * window's context made most of the code again (as natural's and
 * caustic_tex's water did, 0.8-2.5 s, while reduced sizes could be powers
 * of two) and the job only delayed the new frame. */
#define COMPILE_JOB_SLOW_S 0.25
bool compile_job_helped(double first_frame_s, double job_s, double budget_ms);

#endif
