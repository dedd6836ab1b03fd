/* app: the window app loop shared by `tarn view` and `tarn compare-view`
 * (see app.h). */
#include "app.h"
#include "strbuf.h"

#include <GL/gl.h>
#include <GLFW/glfw3.h>
#include <assert.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "compile_job.h"
#include "file_cache.h"
#include "path.h"
#include "exit_code.h"
#include "fd_wake.h"
#include "file.h"
#include "frame_meter.h"
#include "mem.h"
#include "res_budget.h"
#include "session.h"
#include "sheet_job.h"
#include "util.h"
#include "watch.h"

#include <math.h>
#include <poll.h>

struct app {
    app_desc d;                  /* defaults filled in */
    gl_ctx *ctx;
    GLFWwindow *win;
    panel *panel;
    watch *watch;
    app_state s;
    double last_wall;
    frame_meter meter;
    int shots;
    bool shot_pending;           /* P/F12 pressed: shoot once this frame is drawn */
    char toast[1200];
    double toast_until;          /* glfwGetTime() when the toast goes */
    bool toast_drawn;            /* the last frame drew it (a still window sleeps until it goes) */
    double rec_drawn_at;         /* glfwGetTime() when the REC label was last drawn */
    render *const *scenes;
    int nscenes;
    int unwatched;               /* dependencies skipped: their directory is missing */
    double next_retry;           /* glfwGetTime() when to look for them again */
    view_script_ctx *sc;         /* while a script step runs */
    char cause[512];             /* why this reload: "water.frag changed" ("" for R) */
    int script_scene;
    session_rec *rec;            /* recording, or NULL */
    int recordings;              /* Shift+R's file names so far */
    bool bare_frame;             /* a script's screenshot: no toast, no REC label */
    int fit_w, fit_h;            /* app_fit_window's scene area (0: none asked for) */
    long frames;                 /* drawn so far */
    /* the frame budget (res_budget.h) */
    res_budget budget;
    float budget_ms;             /* the panel's slider */
    double last_frame_ms;        /* the previous frame's wall time; 0: not a fair measure */
    bool frame_fair;             /* this frame did no reload, no second draw: its time measures the scene */
    bool sharp_world;            /* app_sharp_world */
    unsigned long generation;    /* reloads, rebuilds, pack switches: a new picture each */
    bool shooting;               /* this frame is a screenshot's: full resolution */
    bool client_busy;            /* app_desc.between_frames has work left */
    bool primed;                 /* the start-up compile job was asked for (or could not be) */
    bool key_shot;               /* ... asked for by P/F12 or the panel: shot after it is drawn */
    int drawn_w, drawn_h, area_w, area_h;   /* the internal size last drawn, of the scene area */
    int orbit_left;              /* the script's `orbit ... N`: frames still to turn */
    float orbit_dx, orbit_dy;
    bool stamp;                  /* the script's `stamp on`: time the first frame after a reload */
    bool stamp_pending;
    bool stamp_full_pending;     /* a paused picture's full frame after the reload is yet to come (stamp_full) */
    double stamp_seen;           /* glfwGetTime() when that reload began */
    double stamp_after_until;    /* then, until this glfwGetTime(), the frames after it (0: not timing) */
    double gap_after_max;        /* ... their longest gap */
    long frames_after;
    /* sleeping while the picture is still (issue #30: a still window burnt
     * 0.75 of a core drawing the same frame) */
    bool woken;                  /* an input or window event came since the last frame */
    fd_wake *file_wake;          /* wakes it when the file watcher has news (a save) */
    bool keep_awake;             /* a client asked for the next frame (app_keep_awake) */
    bool slept;                  /* this frame follows a sleep: its dt measures nothing */
    double slow_s;               /* the script's `slow MS`: each frame lasts at least this (input tests) */
    sheet_job sheet;             /* a hand-in sheet being made (a slider's right-click menu) */
    int sheets;                  /* made so far: the next one's number */
    bool help;                   /* F1 or ?: the keys and the mouse, over the scene */
    bool script_play;            /* the script's `play 1`: its clock runs as a user's does */
    /* a save's shaders compiled off the frame (compile_job.h) */
    compile_job *cjob;
    file_cache *files;           /* every file the scenes read; the watcher refreshes what changed */
    bool compiling;              /* a job runs for the change last seen */
    bool ready_seen;             /* ... and has made the moving frames' code (latched until the frame reloads) */
    bool reloaded_early;         /* ... and the window shows the change: the job makes the still frame's code */
    bool job_waits_shown;        /* ... once this frame is on screen (compile_job_desc.wait_for_shown) */
    bool priming;                /* ... or to load the scenes in the job's renders before any change */
    bool compile_ended;          /* ... and has ended: reload on this frame */
    bool still_dropped;          /* ... without the still frame's code (a newer change came) */
    bool changed_again;          /* a file changed while it ran */
    int compile_restarts;        /* jobs started again for such changes, since the last reload */
    double change_seen;          /* glfwGetTime() when the change being compiled was seen (0: none) */
    double contend_until;        /* glfwGetTime() until which frames stay smaller after a job's ready */
    double last_swap, gap_max;   /* the longest the window was awake without a new frame since
                                  * then: swap to swap, or from waking after a sleep (a still
                                  * window sleeps; input wakes it at once). The stamp says it */
    double compile_s;            /* how long the last job ran */
    bool compiled_off_frame;     /* during hooks.reload: the job compiled what it loads */
    bool deferred_held;          /* the water drawn as a grid until the job makes its deferred code (deferred_due) */
    bool judge_job;              /* this frame reloaded after a job: did the job help? */
    bool job_futile;             /* no: saves compile on the frame from now on */
    long frames_meanwhile;       /* frames swapped since the change was seen */
};

/* ---- watching ---- */

static bool dir_exists(const char *path) {
    char *dir = path_dir(path);
    bool is = file_is_dir(dir);
    free(dir);
    return is;
}

/* Every scene's dependencies (the watcher merges duplicates); the caller
 * frees the array, not the paths. */
static const char **all_deps(const app *a, int *n) {
    const char **all = NULL;
    *n = 0;
    for (int i = 0; i < a->nscenes; i++) {
        const char *const *paths;
        int k = render_deps(a->scenes[i], &paths);
        all = mem_realloc(all, (size_t)(*n + k + 1) * sizeof *all);
        for (int j = 0; j < k; j++) all[(*n)++] = paths[j];
    }
    return all;
}

static int count_missing_dirs(const char **paths, int n) {
    int missing = 0;
    for (int i = 0; i < n; i++) missing += !dir_exists(paths[i]);
    return missing;
}

void app_rewatch(app *a) {
    if (!a->watch) return;
    int n;
    const char **all = all_deps(a, &n);
    char err[MSG_MAX];
    a->unwatched = 0;
    if (!all || !watch_set_files(a->watch, all, n, err, sizeof err)) {
        /* one path in a missing directory fails the whole set: watch the rest */
        int nok = 0;
        for (int i = 0; all && i < n; i++)
            if (dir_exists(all[i])) all[nok++] = all[i];
        a->unwatched = n - nok;
        if (!all || !watch_set_files(a->watch, all, nok, err, sizeof err))
            fprintf(stderr, "%s: watching files: %s\n", a->d.name, err);
    }
    a->next_retry = glfwGetTime() + APP_RETRY_S;
    free(all);
}

/* A change starts waiting for its new frame now (unless one already
 * waits): the stamp's times and frame gap count from here. */
static void change_wait_starts(app *a) {
    if (a->change_seen > 0) return;
    a->change_seen = glfwGetTime();
    a->gap_max = 0;
    a->frames_meanwhile = 0;
}

static void reload(app *a) {
    change_wait_starts(a);   /* R, a reload on the frame: the wait is the reload's */
    a->stamp_pending = a->stamp;
    a->stamp_seen = a->change_seen;
    a->change_seen = 0;
    a->d.reload(a->d.user, a);
    app_picture_changed(a);
    a->frame_fair = false;   /* the reload's own time is not the scene's */
    a->cause[0] = '\0';
    app_rewatch(a);
}

/* Any thread: a sleeping window's glfwWaitEventsTimeout returns. */
static void post_wake(void *user) {
    (void)user;
    glfwPostEmptyEvent();
}

/* Compiles the scenes as they are on disk now, off the frame, into
 * Mesa's shader cache (compile_job.h); false when that cannot help or
 * cannot start (reload on the frame then). */
static bool start_compile(app *a, bool prime) {
    if (!compile_job_useful() || a->job_futile || a->drawn_w <= 0) return false;
    if (!a->cjob) a->cjob = compile_job_create();
    compile_job_desc d = { .scenes = a->scenes, .n = a->nscenes, .w = a->drawn_w, .h = a->drawn_h,
                           .t = a->s.t, .view = orbit_view(&a->s.cam),
                           .wait_for_shown = !prime && a->budget_ms > 0,   /* early_wanted's reload */
                           .still = a->s.paused,
                           .defer_still = !prime && a->budget_ms > 0 && !a->s.paused,
                           .wake = post_wake };
    if (!compile_job_start(a->cjob, &d)) return false;
    a->compiling = true;
    a->priming = prime;
    a->compile_ended = a->ready_seen = false;
    if (!prime) change_wait_starts(a);
    return true;
}

/* Has the running compile job ended (latched until the frame takes it)? */
static bool compile_finished(app *a) {
    if (a->compiling && !a->compile_ended && compile_job_done(a->cjob, &a->compile_s)) a->compile_ended = true;
    return a->compile_ended;
}

/* The frame that reloaded after a job took frame_s: where the job did
 * not help (compile_job_helped), it only delays the new frame, so later
 * saves compile on the frame, as without it. */
static void judge_compile_job(app *a, double frame_s) {
    a->judge_job = false;
    if (compile_job_helped(frame_s, a->compile_s, a->budget_ms)) return;
    a->job_futile = true;
    fprintf(stderr, "%s: compiling off the frame did not help this scene (the first frame of the new build "
            "still took %.2f s, the job %.2f s): saves compile on the frame from now on\n", a->d.name, frame_s,
            a->compile_s);
}

/* The reload after a job: it finds the programs and the variants its first
 * frames need in Mesa's cache. */
static void reload_compiled(app *a) {
    a->compiled_off_frame = true;
    /* the water as a grid until the job has made its deferred code too
     * (compile_job_deferred_ready): the first frames need one front end */
    if (!compile_job_deferred_ready(a->cjob)) {
        for (int i = 0; i < a->nscenes; i++) render_set_deferred_water(a->scenes[i], false);
        a->deferred_held = true;
        res_budget_costlier(&a->budget, APP_GRID_WATER_COST);
    }
    reload(a);
    a->compiled_off_frame = false;
    a->judge_job = true;   /* this frame says whether the job made the first draw cheap */
}

/* Does the window show the change as soon as the job has made the code of
 * the frames drawn while the picture changes (compile_job_ready), holding
 * the still picture's full frame until the job has made its code too? Not
 * for a start-up job (nothing to show), while a newer change waits (the
 * job's end compiles it first), or without a budget (every frame full). */
static bool early_wanted(const app *a) {
    return a->compiling && !a->priming && !a->reloaded_early && !a->changed_again && a->budget_ms > 0;
}

/* Has the running job made the moving frames' code (latched until the
 * frame reloads)? Asked before compile_finished: the job's end answers
 * it too. */
static bool compile_readied(app *a) {
    if (!a->ready_seen && early_wanted(a) && compile_job_ready(a->cjob, &a->compile_s)) a->ready_seen = true;
    return a->ready_seen;
}

/* Does a save's job compile now, on the cores the window draws on? Its
 * reduced frames' code before the window shows the change, the deferred
 * water's and the still frame's after it (made beside moving frames at
 * full size, as a cheap scene asks for it, the frames took 62-71 ms,
 * basic on the lake): whenever it is not waiting for the window's still
 * answer (compile_job_compiling). */
static bool job_contends(const app *a) {
    return a->compiling && !a->priming && compile_job_compiling(a->cjob);
}

static void reload_early(app *a) {
    a->ready_seen = false;
    a->reloaded_early = true;
    a->job_waits_shown = true;   /* until this frame is on screen (compile_job_shown) */
    res_budget_hold_full(&a->budget, true);
    a->compile_restarts = 0;
    reload_compiled(a);
}

/* The window shows the change and the job waits to make the still
 * picture's code (compile_job_desc.defer_still): ask for it once that
 * frame is due (held: the picture stood still), or once the moving frames
 * would be full-resolution ones too (a cheap scene; until then they stay
 * just below, res_budget_hold_full); let it go where the window draws
 * other scenes now. */
static void still_due(app *a, double now) {
    if (!a->compiling || !a->reloaded_early) return;
    if (!(res_budget_full_held(&a->budget, now) || a->budget.scale >= 1 || a->budget_ms <= 0)) return;
    if (compile_job_draws(a->cjob, a->scenes, a->nscenes)) {
        compile_job_want_still(a->cjob);
        return;
    }
    /* another pack since (a switch compiles on the frame): not the old one's */
    compile_job_drop_still(a->cjob);
    a->still_dropped = true;
}

/* A paused window's full frame once the job has made its code with the
 * water as a grid (compile_job_still_ready), not at the job's end: the
 * deferred water's code, which the job makes after it, took another
 * second of natural's on a slow 2-core machine. That frame draws the
 * grid (deferred_held) until the deferred code is made. */
static void still_ready_due(app *a) {
    if (!a->compiling || !a->reloaded_early || !a->s.paused || !a->budget.hold_full) return;
    if (compile_job_still_ready(a->cjob)) res_budget_hold_full(&a->budget, false);
}

/* The water deferred again once the job has made that code too (or has
 * ended, or none runs). */
static void deferred_due(app *a) {
    if (!a->deferred_held || (a->compiling && !compile_job_deferred_ready(a->cjob))) return;
    for (int i = 0; i < a->nscenes; i++) render_set_deferred_water(a->scenes[i], true);
    a->deferred_held = false;
}

/* The job ended: the reload finds its programs in the cache (already
 * done at its ready, unless a change came meanwhile). A file that changed
 * while it ran is compiled again first (twice at most, so that a stream of
 * saves still shows one). */
static void compile_ended(app *a) {
    bool primed = a->priming, shown = a->reloaded_early, again = a->changed_again, dropped = a->still_dropped;
    a->compiling = a->compile_ended = a->priming = a->reloaded_early = a->still_dropped = false;
    res_budget_hold_full(&a->budget, false);
    if (primed && a->d.verbose)
        fprintf(stderr, "%s: the compile job has the scene loaded (%.2f s, off the frame)\n", a->d.name, a->compile_s);
    if (primed && !again) return;   /* the job's renders hold the scenes: nothing changed */
    if (shown && !again && !dropped && a->d.verbose)
        fprintf(stderr, "%s: the compile job made the still picture's frame too (%.2f s in all)\n", a->d.name,
                a->compile_s);
    if (shown && !again) return;    /* on screen since the job's ready */
    if (again && a->compile_restarts < 2) {
        a->changed_again = false;
        a->compile_restarts++;
        if (start_compile(a, false)) return;
    }
    a->changed_again = false;
    a->compile_restarts = 0;
    reload_compiled(a);
}

/* A new change while the last one is on screen and what its job still
 * makes is old: the still frame's code it only waits to make
 * (defer_still), or, on a paused window that shows the change sharp, the
 * deferred water's code for when the clock runs (that job runs longer
 * since the sharp frame comes first: a save 5 s after the last waited for
 * it, caustic_tex's new frame 1.4 -> 1.8 s on a slow 2-core machine). The
 * job ends, and the new change's starts at once instead of after it. */
static void end_old_job(app *a) {
    if (!a->compiling || !a->reloaded_early || a->changed_again) return;
    if (!compile_job_still_waits(a->cjob) && !(a->s.paused && compile_job_still_ready(a->cjob))) return;
    compile_job_cancel(a->cjob);
    a->still_dropped = true;
    if (compile_job_wait_done(a->cjob, COMPILE_JOB_DROP_WAIT_S) && compile_finished(a)) compile_ended(a);
}

/* The files the watcher saw change (watch_changed 0..n-1): compiled off
 * the frame, then reloaded; reloaded now where that cannot help. */
static void reload_changed(app *a, int n) {
    const char **paths = mem_alloc((size_t)n * sizeof *paths);
    for (int i = 0; i < n; i++) paths[i] = watch_changed(a->watch, i);
    char cause[sizeof a->cause];
    view_reload_cause(paths, n, cause, sizeof cause);
    free(paths);
    end_old_job(a);
    if (a->compiling) {   /* the job reads the files when it runs: compile again once it ends */
        a->changed_again = true;
        compile_job_shown(a->cjob);   /* no reload at its ready now: it need not wait for one */
        compile_job_drop_still(a->cjob);   /* nor make the still frame of code now old */
        change_wait_starts(a);   /* (during a priming job: the change's wait starts now) */
        if (strcmp(cause, a->cause) != 0) snprintf(a->cause, sizeof a->cause, "%s", cause);
        return;
    }
    snprintf(a->cause, sizeof a->cause, "%s", cause);
    if (start_compile(a, false)) return;
    reload(a);
}

/* A skipped dependency whose directory has appeared: its file may be
 * there now, and from now it can be watched. */
static bool missing_dir_appeared(app *a) {
    if (a->unwatched == 0 || glfwGetTime() < a->next_retry) return false;
    a->next_retry = glfwGetTime() + APP_RETRY_S;
    int n;
    const char **all = all_deps(a, &n);
    bool appeared = all && count_missing_dirs(all, n) < a->unwatched;
    free(all);
    return appeared;
}

/* ---- actions, input ---- */

void app_toast(app *a, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(a->toast, sizeof a->toast, fmt, ap);
    va_end(ap);
    a->toast_until = glfwGetTime() + APP_TOAST_S;
}

/* The window's image to path; the outcome on screen and on stderr. */
static void shoot(app *a, const char *path) {
    char said[1100];
    view_screenshot(a->win, path, said, sizeof said);
    fprintf(stderr, "%s: %s\n", a->d.name, said);
    app_toast(a, "%s", said);
}

void app_screenshot(app *a) {
    char path[128];
    view_shot_path(a->shots++, path, sizeof path);
    shoot(a, path);
}

static bool toast_showing(const app *a) { return a->toast[0] && glfwGetTime() <= a->toast_until; }

/* When (glfwGetTime()) a still window must draw again though nothing wakes
 * it; INFINITY: never. A toast stands still on screen: a frame shows it
 * and one takes it away once it is due to go (drawing the same frame for
 * its 4 s burnt a core after every start and every setting). While
 * recording, the REC label's seconds go on, a frame a second. While a
 * folder is missing, the frame looks for it every APP_RETRY_S
 * (missing_dir_appeared: the loop spun a core meanwhile). */
static double frame_due_at(const app *a) {
    double due = INFINITY;
    if (toast_showing(a) != a->toast_drawn) due = 0.0;
    else if (a->toast_drawn) due = a->toast_until;
    if (a->rec) due = fmin(due, a->rec_drawn_at + APP_REC_LABEL_S);
    if (a->unwatched > 0) due = fmin(due, a->next_retry);
    return due;
}

/* Over the top of the scene area, above the panel and the scene's labels;
 * not into a screenshot asked for by key. */
static void draw_toast(app *a) {
    a->toast_drawn = false;
    if (a->shooting || a->bare_frame) return;
    int ww, wh;
    glfwGetWindowSize(a->win, &ww, &wh);
    if (a->rec) {
        char label[1200];
        snprintf(label, sizeof label, "REC %.1f s  %s", session_rec_seconds(a->rec, glfwGetTime()),
                 session_rec_path(a->rec));
        panel_label(a->panel, (float)ww - 10.0f, 10.0f, label, true);
        a->rec_drawn_at = glfwGetTime();
    }
    float y = 40.0f, x = (app_scene_x_window(a) + (float)ww) * 0.5f;
    if (a->compiling && !a->priming && !a->reloaded_early) {   /* the last good build is on screen until then */
        char what[700];
        view_compiling_text(a->cause, what, sizeof what);
        panel_toast(a->panel, x, y, what);
        y += 36.0f;
    }
    if (!toast_showing(a)) return;
    panel_toast(a->panel, x, y, a->toast);
    a->toast_drawn = true;
}

/* F1 or ?: what the keys and the mouse do, over the scene's top left (the
 * same words as `tarn view --help`). */
static const char *const HELP_TEXT =
    "mouse   left drag: orbit   right or middle drag: pan   wheel: zoom\n"
    "Space   pause / run time (a paused picture is drawn at full resolution)\n"
    "R       reload the scene and its shaders (a save reloads by itself)\n"
    "P, F12  screenshot (PNG in the current folder)\n"
    "F, Home reset the camera\n"
    "Shift+R start / stop recording a session (tarn record replays it)\n"
    "F1, ?   this help          Esc, Q  quit";

static void draw_help(app *a) {
    if (!a->help || a->key_shot) return;   /* P/F12 shoots the scene, not the help */
    panel_label(a->panel, app_scene_x_window(a) + 12.0f, 12.0f, HELP_TEXT, false);
}

void app_splash(app *a, const char *text) {
    int fw, fh, ww, wh;
    glfwGetFramebufferSize(a->win, &fw, &fh);
    glfwGetWindowSize(a->win, &ww, &wh);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fw, fh);
    glClearColor(0.08f, 0.10f, 0.13f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    panel_begin_frame(a->panel);
    panel_toast(a->panel, (float)ww * 0.5f, (float)wh * 0.45f, text);
    panel_render(a->panel);
    glfwSwapBuffers(a->win);
    glfwPollEvents();
}

/* ---- recording ---- */

static void record_start(app *a, const char *path) {
    render *r = a->scenes[0];
    int n, w, h;
    unif_set *sets = render_uniforms(r, &n);
    glfwGetFramebufferSize(a->win, &w, &h);
    w -= app_scene_x(w);
    /* before the first frame the window may not have its fitted size yet */
    if (a->frames == 0 && a->fit_w > 0) { w = a->fit_w; h = a->fit_h; }
    /* the pack drawing it now: --pack, or one picked in the panel since */
    const char *pack = render_has_world(r) && render_pack(r)[0] ? render_pack(r) : a->d.pack;
    session_header hd = { .scene = render_scene_path(r), .pack = pack, .width = w, .height = h,
                          .time_s = a->s.t };
    char err[MSG_MAX];
    a->rec = session_rec_start(path, &hd, sets, n, &a->s.cam, a->s.paused, glfwGetTime(), err, sizeof err);
    if (!a->rec) {
        fprintf(stderr, "%s: not recording: %s\n", a->d.name, err);
        app_toast(a, "not recording: %s", err);
        return;
    }
    fprintf(stderr, "%s: recording to %s\n", a->d.name, path);
    app_toast(a, "recording to %s (Shift+R stops)", path);
}

void app_record_pack(app *a, const char *pack) {
    if (a->rec) session_rec_pack(a->rec, pack, glfwGetTime());
}

void app_record_setting(app *a, const char *setting) {
    if (a->rec) session_rec_setting(a->rec, setting, glfwGetTime());
}

static void record_stop(app *a) {
    char path[1024], err[1200];
    snprintf(path, sizeof path, "%s", session_rec_path(a->rec));
    double secs = session_rec_seconds(a->rec, glfwGetTime());
    int n;
    bool ok = session_rec_stop(a->rec, glfwGetTime(), &n, err, sizeof err);
    a->rec = NULL;
    if (!ok) {
        fprintf(stderr, "%s: recording: %s\n", a->d.name, err);
        app_toast(a, "recording failed: %s", err);
        return;
    }
    fprintf(stderr, "%s: recorded %d events in %.1f s to %s; `tarn record %s -o out.mp4` makes the video\n",
            a->d.name, n, secs, path, path);
    app_toast(a, "recorded %.1f s to %s", secs, path);
}

static void record_toggle(app *a) {
    if (a->rec) { record_stop(a); return; }
    char path[128];
    view_shot_path(a->recordings++, path, sizeof path);
    snprintf(strrchr(path, '.'), sizeof path - (size_t)(strrchr(path, '.') - path), ".session");
    record_start(a, path);
}

/* A hand-in sheet of one slider from min to max, the other values as the
 * window has them (issue #27): `tarn sheet` in a child, the window live. */
static bool start_sheet(app *a, const char *program, const char *uniform, double min, double max) {
    if (!a->scenes || a->nscenes < 1) return false;
    render *r = a->scenes[0];
    char out[160], stamp[128], err[512];
    view_shot_path(a->sheets++, stamp, sizeof stamp);   /* tarn-DATE-N.png */
    snprintf(out, sizeof out, "tarn-sheet-%s", stamp + 5);
    int n;
    const unif_set *sets = render_uniforms(r, &n);
    sheet_job_desc d = { .scene = render_scene_path(r), .pack = render_has_world(r) ? render_pack(r) : NULL,
                         .program = program, .uniform = uniform, .min = min, .max = max, .time_s = a->s.t,
                         .sets = sets, .nsets = n, .out = out };
    bool ok = sheet_job_start(&a->sheet, &d, err, sizeof err);
    if (ok) app_toast(a, "making a hand-in sheet of %s into %s ...", a->sheet.what, out);
    else app_toast(a, "no sheet: %s", err);
    fprintf(stderr, "%s: %s%s\n", a->d.name, ok ? "making a hand-in sheet of " : "no sheet: ", ok ? a->sheet.what : err);
    return ok;
}

/* The sheet's end, said once; true when it ended now. */
static bool sheet_ended(app *a, bool wait) {
    int rc = sheet_job_poll(&a->sheet, wait);
    if (rc < 0) return false;
    if (rc == 0) app_toast(a, "sheet written: %s", a->sheet.out);
    else app_toast(a, "the sheet of %s failed (tarn sheet exited %d): see the terminal", a->sheet.what, rc);
    fprintf(stderr, "%s: %s %s\n", a->d.name, rc == 0 ? "sheet written:" : "sheet failed:", a->sheet.out);
    return true;
}

static void apply_common(app *a, const panel_actions *c) {
    if (c->sheet) start_sheet(a, c->sheet_program, c->sheet_uniform, c->sheet_min, c->sheet_max);
    if (c->reload) reload(a);
    if (c->toggle_pause) a->s.paused = !a->s.paused;
    /* the button's frame was drawn before the panel said so: the next one,
     * drawn at full resolution, is shot */
    if (c->screenshot) a->shot_pending = true;
    if (a->key_shot) app_screenshot(a);
}

/* Any event wakes a sleeping window; the panel's own callbacks (ImGui's
 * backend, installed after these) chain to them. */
static void wake(GLFWwindow *w) {
    app *a = glfwGetWindowUserPointer(w);
    if (a) a->woken = true;
}
static void on_cursor(GLFWwindow *w, double x, double y) { (void)x; (void)y; wake(w); }
static void on_char(GLFWwindow *w, unsigned c) {
    wake(w);
    app *a = glfwGetWindowUserPointer(w);
    if (a && c == '?' && a->panel && !panel_wants_keyboard(a->panel)) a->help = !a->help;
}
static void on_size(GLFWwindow *w, int x, int y) { (void)x; (void)y; wake(w); }
static void on_focus(GLFWwindow *w, int f) { (void)f; wake(w); }
static void on_enter(GLFWwindow *w, int e) { (void)e; wake(w); }
static void on_refresh(GLFWwindow *w) { wake(w); }

static void on_scroll(GLFWwindow *w, double dx, double dy) {
    app *a = glfwGetWindowUserPointer(w);
    a->woken = true;
    if (!a->panel || !panel_wants_mouse(a->panel)) a->s.mouse.scroll += dy;
}

/* Where a press happened, now: by the next frame (a second away on a slow
 * scene) the cursor may be elsewhere. */
static void on_button(GLFWwindow *w, int button, int action, int mods) {
    app *a = glfwGetWindowUserPointer(w);
    a->woken = true;
    if (action != GLFW_PRESS) return;
    int which = button == GLFW_MOUSE_BUTTON_LEFT ? VIEW_MOUSE_LEFT
              : button == GLFW_MOUSE_BUTTON_RIGHT || button == GLFW_MOUSE_BUTTON_MIDDLE ? VIEW_MOUSE_PAN : 0;
    double x, y;
    glfwGetCursorPos(w, &x, &y);
    if (which) view_mouse_press(&a->s.mouse, which, x, y);
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods) {
    app *a = glfwGetWindowUserPointer(w);
    a->woken = true;
    if (action != GLFW_PRESS || !a->panel || panel_wants_keyboard(a->panel)) return;
    switch (key) {
    case GLFW_KEY_ESCAPE: case GLFW_KEY_Q: glfwSetWindowShouldClose(w, 1); break;
    case GLFW_KEY_R:
        if ((mods & GLFW_MOD_SHIFT) && a->d.recordable && a->scenes) record_toggle(a);
        else reload(a);
        break;
    case GLFW_KEY_SPACE: a->s.paused = !a->s.paused; break;
    /* not now: between swap and draw the back buffer holds no frame */
    case GLFW_KEY_P: case GLFW_KEY_F12: a->shot_pending = true; break;
    case GLFW_KEY_HOME: case GLFW_KEY_F: a->s.cam = a->s.cam_home; break;
    case GLFW_KEY_F1: a->help = !a->help; break;
    default:
        if (a->d.key) a->d.key(a->d.user, a, key);
        break;
    }
}

/* ---- the frame budget ---- */

void app_picture_changed(app *a) { a->generation++; }

void app_sharp_world(app *a, bool on) { a->sharp_world = on; }

/* Does any scene's picture move with the clock (render_reads_clock)? A
 * glman scene without Timer does not: its picture is still while the
 * clock runs, drawn once at full resolution, and the window sleeps. */
static bool scenes_read_clock(const app *a) {
    for (int i = 0; i < a->nscenes; i++)
        if (render_reads_clock(a->scenes[i])) return true;
    return false;
}

/* with_time: the clock and the reloads count too */
static uint64_t picture_key(app *a, int w, int h, bool with_time) {
    uint64_t k = HASH_FNV1A_BASIS;
    k = hash_fnv1a(k, &a->s.cam, sizeof a->s.cam);
    if (with_time && scenes_read_clock(a)) k = hash_fnv1a(k, &a->s.t, sizeof a->s.t);
    if (with_time) k = hash_fnv1a(k, &a->generation, sizeof a->generation);
    int size[2] = { w, h };
    k = hash_fnv1a(k, size, sizeof size);
    /* every slider, checkbox and colour of every scene: what the panel,
     * a script or a preset changes */
    for (int i = 0; i < a->nscenes; i++) {
        int n;
        unif_set *sets = render_uniforms(a->scenes[i], &n);
        for (int j = 0; j < n; j++)
            for (int e = 0; e < sets[j].n; e++)
                k = hash_fnv1a(k, sets[j].entries[e].value, sizeof sets[j].entries[e].value);
    }
    return k;
}

uint64_t app_picture_key(app *a, int w, int h) { return picture_key(a, w, h, true); }
uint64_t app_picture_key_timeless(app *a, int w, int h) { return picture_key(a, w, h, false); }

bool app_budget_plan(app *a, uint64_t key, bool force_full, double *scale) {
    a->budget.budget_ms = a->budget_ms;
    /* the picture but its clock: the camera, the sliders, a reload, the area */
    uint64_t view = hash_fnv1a(picture_key(a, a->area_w, a->area_h, false), &a->generation, sizeof a->generation);
    res_budget_view(&a->budget, view);
    return res_budget_plan(&a->budget, key, glfwGetTime(), a->last_frame_ms, force_full || a->shooting, scale);
}

void app_budget_drawn(app *a, int iw, int ih, int w, int h) {
    a->drawn_w = iw;
    a->drawn_h = ih;
    a->area_w = w;
    a->area_h = h;
}

float *app_budget_ms(app *a) { return &a->budget_ms; }

void app_budget_text(const app *a, char *out, int len) {
    double pct = a->area_w > 0 ? 100.0 * a->drawn_w / a->area_w : 100;
    if (a->budget_ms <= 0)
        snprintf(out, (size_t)len, "%dx%d (%.0f%%) of %dx%d, no budget", a->drawn_w, a->drawn_h, pct, a->area_w,
                 a->area_h);
    else
        snprintf(out, (size_t)len, "%dx%d (%.0f%%) of %dx%d, budget %.3g ms", a->drawn_w, a->drawn_h, pct,
                 a->area_w, a->area_h, a->budget_ms);
}

/* The first frame after a reload is on screen (the script's `stamp on`):
 * when, on the wall clock a benchmark compares with a file's save. */
static void stamp_swap(app *a) {
    a->stamp_pending = false;
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    fprintf(stderr, "%s: stamp: first frame after the reload swapped at %.6f (%.1f ms after the reload began; "
            "longest frame gap meanwhile %.1f ms, %ld frames before it)\n", a->d.name,
            (double)ts.tv_sec + ts.tv_nsec * 1e-9, (glfwGetTime() - a->stamp_seen) * 1e3, a->gap_max * 1e3,
            a->frames_meanwhile - 1);
    a->stamp_full_pending = a->s.paused;
    a->stamp_after_until = glfwGetTime() + APP_STAMP_AFTER_S;
    a->gap_after_max = 0;
    a->frames_after = 0;
}

/* A paused picture's first full-resolution frame after the reload is on
 * screen (the stamped first frame may be a reduced one): when the change
 * is seen sharp (scripts/save_bench.sh). */
static void stamp_full(app *a) {
    if (!a->stamp_full_pending || a->drawn_w < a->area_w || a->drawn_h < a->area_h) return;
    a->stamp_full_pending = false;
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    fprintf(stderr, "%s: stamp: full frame after the reload swapped at %.6f (%.1f ms after the reload began)\n",
            a->d.name, (double)ts.tv_sec + ts.tv_nsec * 1e-9, (glfwGetTime() - a->stamp_seen) * 1e3);
}

/* The frames in the APP_STAMP_AFTER_S after the stamped one: what the
 * compile job still does then (a save's still-picture code) must leave
 * them within the budget too (issue #30: no frame gap longer than it). */
static void stamp_after(app *a, double gap, double swapped) {
    if (a->stamp_after_until <= 0) return;
    if (swapped <= a->stamp_after_until) {
        a->gap_after_max = fmax(a->gap_after_max, gap);
        a->frames_after++;
        return;
    }
    a->stamp_after_until = 0;
    fprintf(stderr, "%s: stamp: in the %.1f s after that frame, longest frame gap %.1f ms over %ld frames\n",
            a->d.name, APP_STAMP_AFTER_S, a->gap_after_max * 1e3, a->frames_after);
}

/* ---- the loop ---- */

/* A press since the last frame that landed on the panel as drawn then
 * (over the scene, where the panel floats on it, ui_right cannot say). */
static bool pressed_on_panel(const app *a) {
    return a->s.mouse.pressed && panel_contains(a->panel, a->s.mouse.press_x, a->s.mouse.press_y);
}

static void frame(app *a, bool scripted) {
    double now = glfwGetTime(), dt = now - a->last_wall;
    a->last_wall = now;
    a->last_frame_ms = a->frame_fair ? dt * 1e3 : 0;
    a->frame_fair = true;
    a->key_shot = a->shot_pending;
    a->shooting = a->key_shot || a->bare_frame;
    a->shot_pending = false;
    if (a->shooting) a->frame_fair = false;
    if (a->orbit_left > 0 && !a->bare_frame) {   /* a screenshot's frame shows the camera as it is */
        orbit_rotate(&a->s.cam, a->orbit_dx, a->orbit_dy);
        a->orbit_left--;
    }
    if (a->slept) a->frame_fair = false;    /* the sleep is not the frame's time */
    else frame_meter_add(&a->meter, dt);
    a->slept = false;
    a->s.frame_ms = frame_meter_ms(&a->meter);
    a->s.fps = frame_meter_fps(&a->meter);
    if (!a->s.paused && (!scripted || a->script_play)) a->s.t += dt;
    bool contended = job_contends(a);   /* (the reload's frame, at the job's ready, too) */
    if (compile_readied(a)) reload_early(a);
    if (compile_finished(a)) compile_ended(a);
    still_ready_due(a);
    deferred_due(a);
    still_due(a, now);
    int changed = a->watch ? watch_poll(a->watch, 0) : 0;
    fd_wake_rearm(a->file_wake);   /* its news are read: wake at the next */
    if (changed > 0) reload_changed(a, changed);
    else if (a->watch && missing_dir_appeared(a)) {
        snprintf(a->cause, sizeof a->cause, "a missing folder appeared");
        reload(a);
    }
    /* a save's job compiles on a core this frame draws on: the frame
     * shrinks for as long (res_budget_contend), from the frame that
     * started it to APP_CONTEND_TAIL_S after the reload at its ready */
    if (contended && a->reloaded_early) a->contend_until = glfwGetTime() + APP_CONTEND_TAIL_S;
    res_budget_contend(&a->budget, contended || job_contends(a) || glfwGetTime() < a->contend_until);
    /* A smaller frame reads the larger frame's World layers: while a job
     * compiles, and, where the client shows the world from a full-size
     * frame of its own (the view's sharp world), as the budget's size
     * moves. Rebuilt at each new size they cost the first frame there 2-6
     * times a frame (the lake on llvmpipe: 70-170 ms against 25-45), and
     * the size came back to the larger one every half second (natural:
     * 40 frames in 2.3 s instead of 1.75 s). Read from larger layers, a
     * reduced frame's world is their nearest texels: compare-view, which
     * enlarges its frames whole, showed that (10-25% more RMSE) */
    bool keep = (a->sharp_world && a->budget.budget_ms > 0) || a->budget.contended || a->budget.hold_full;
    for (int i = 0; i < a->nscenes; i++) render_keep_world_layers(a->scenes[i], keep);
    sheet_ended(a, false);
    a->s.mouse.ui_right = app_scene_x_window(a);   /* presses left of it are the panel's */
    if (a->d.mouse) a->d.mouse(a->d.user, a);
    else view_mouse_update(&a->s.mouse, a->win, panel_wants_mouse(a->panel) || pressed_on_panel(a), &a->s.cam);
    a->d.draw(a->d.user, a);
    panel_actions common;
    memset(&common, 0, sizeof common);
    panel_begin_frame(a->panel);
    a->d.panel(a->d.user, a, &common);
    draw_toast(a);
    draw_help(a);
    panel_render(a->panel);
    if (a->d.apply) a->d.apply(a->d.user, a);
    apply_common(a, &common);
    a->frames++;
    if (a->rec) {
        int n;
        unif_set *sets = render_uniforms(a->scenes[0], &n);
        session_rec_frame(a->rec, sets, n, &a->s.cam, a->s.paused, glfwGetTime());
    }
}

/* The frame budget's script actions (app.h); VIEW_SCRIPT_DONE: not one of them. */
static view_script_status budget_action(app *a, const char *cmd, char *rest, const char *file, int line) {
    char word[32] = "";
    if (strcmp(cmd, "orbit") == 0) {   /* DX DY [N]: a turn now and on each of the next N-1 frames */
        float dx = 0, dy = 0;
        int n = 1;
        if (sscanf(rest, "%f %f %d", &dx, &dy, &n) < 2 || n < 1) {
            fprintf(stderr, "%s:%d: orbit wants DYAW DPITCH (radians) and optionally FRAMES\n", file, line);
            return VIEW_SCRIPT_FAILED;
        }
        orbit_rotate(&a->s.cam, dx, dy);
        a->orbit_left = n - 1;
        a->orbit_dx = dx;
        a->orbit_dy = dy;
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "slow") == 0) {   /* MS: frames of at least MS, as a slow GPU draws them */
        double ms;
        if (sscanf(rest, "%lf", &ms) != 1 || !(ms >= 0) || ms > 10000) {
            fprintf(stderr, "%s:%d: slow wants milliseconds a frame at least, 0 (off) to 10000\n", file, line);
            return VIEW_SCRIPT_FAILED;
        }
        a->slow_s = ms / 1e3;
        fprintf(stderr, "%s: slow %.0f ms a frame\n", a->d.name, ms);
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "sheet") == 0) {   /* PROGRAM.NAME: the slider's menu item, then wait for it */
        char program[UNIF_NAME_MAX] = "", name[UNIF_NAME_MAX] = "";
        const unif_entry *e = NULL;
        if (sscanf(rest, "%63[^.].%63s", program, name) == 2 && a->scenes) {
            int n;
            unif_set *sets = render_uniforms(a->scenes[0], &n);
            for (int i = 0; i < n && !e; i++)
                if (strcmp(sets[i].program, program) == 0) e = unif_find(&sets[i], name);
        }
        if (!e || !(e->min < e->max)) {
            fprintf(stderr, "%s:%d: sheet wants PROGRAM.NAME of a slider\n", file, line);
            return VIEW_SCRIPT_FAILED;
        }
        if (!start_sheet(a, program, name, e->min, e->max)) return VIEW_SCRIPT_FAILED;
        sheet_ended(a, true);
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "help") == 0) {   /* 1 | 0: the key help overlay, as F1 */
        a->help = atoi(rest) != 0;
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "budget") == 0) {
        double ms;
        if (sscanf(rest, "%lf", &ms) != 1 || !(ms >= 0) || ms > RES_BUDGET_MAX_MS) {
            fprintf(stderr, "%s:%d: budget wants milliseconds, 0 (off) to %.0f\n", file, line, RES_BUDGET_MAX_MS);
            return VIEW_SCRIPT_FAILED;
        }
        a->budget_ms = (float)ms;
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "resolution") == 0 || strcmp(cmd, "expect-resolution") == 0) {
        char text[160];
        app_budget_text(a, text, sizeof text);
        sscanf(rest, "%31s", word);
        bool full = a->drawn_w == a->area_w && a->drawn_h == a->area_h;
        bool ok = cmd[0] == 'r' || (strcmp(word, "full") == 0 ? full : strcmp(word, "reduced") == 0 ? !full : false);
        fprintf(stderr, "%s: resolution %s%s\n", a->d.name, text, ok ? "" : " (FAILED: want full or reduced)");
        return ok ? VIEW_SCRIPT_CONTINUE : VIEW_SCRIPT_FAILED;
    }
    if (strcmp(cmd, "grab") == 0) {   /* the scene area as this frame showed it, and its time */
        char path[1024] = "", said[1100];
        sscanf(rest, "%1023s", path);
        int w, h;
        glfwGetFramebufferSize(a->win, &w, &h);
        int x0 = app_scene_x(w);
        bool ok = path[0] && view_screenshot_area(x0, 0, w - x0, h, path, said, sizeof said);
        fprintf(stderr, "%s: grab %s at t=%.9g, drawn at %dx%d of %dx%d\n", a->d.name, ok ? path : said, a->s.t,
                a->drawn_w, a->drawn_h, a->area_w, a->area_h);
        return ok ? VIEW_SCRIPT_CONTINUE : VIEW_SCRIPT_FAILED;
    }
    if (strcmp(cmd, "clock") == 0) {   /* for benchmarks: frames so far and the wall clock */
        fprintf(stderr, "%s: clock %ld frames %.3f ms\n", a->d.name, a->frames, glfwGetTime() * 1e3);
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "play") == 0) {   /* 1 | 0: the clock runs on the wall clock, as without a script */
        a->script_play = atoi(rest) != 0;
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "stamp") == 0) {
        sscanf(rest, "%31s", word);
        a->stamp = strcmp(word, "off") != 0;
        fprintf(stderr, "%s: stamp %s\n", a->d.name, a->stamp ? "on" : "off");   /* a benchmark saves after this */
        return VIEW_SCRIPT_CONTINUE;
    }
    return VIEW_SCRIPT_DONE;
}

/* The app's own script actions, then the client's: `window W H` resizes
 * the window, as a user's drag would (what follows the window is tested). */
static view_script_status script_action(void *user, const char *cmd, char *rest, const char *file, int line) {
    app *a = user;
    if (strcmp(cmd, "window") == 0) {
        int w, h;
        if (sscanf(rest, "%d %d", &w, &h) != 2 || w <= 0 || h <= 0) {
            fprintf(stderr, "%s:%d: window wants a width and a height in pixels\n", file, line);
            return VIEW_SCRIPT_FAILED;
        }
        glfwSetWindowSize(a->win, w, h);
        return VIEW_SCRIPT_CONTINUE;
    }
    view_script_status st = budget_action(a, cmd, rest, file, line);
    if (st != VIEW_SCRIPT_DONE) return st;
    if (a->d.script_action) return a->d.script_action(a->d.user, cmd, rest, file, line);
    fprintf(stderr, "%s:%d: unknown script action '%s'\n", file, line, cmd);
    return VIEW_SCRIPT_FAILED;
}

/* One script step after a frame; returns the exit code it calls for. */
static int script_step(app *a, view_script *script) {
    view_script_ctx sc = { .r = a->scenes[a->script_scene], .time_s = &a->s.t, .cam = &a->s.cam,
                           .paused = &a->s.paused, .custom = script_action, .user = a };
    a->sc = &sc;
    view_script_status st = view_script_step(script, &sc);
    a->sc = NULL;
    if (st == VIEW_SCRIPT_SCREENSHOT) {
        /* the frame as it is now, drawn again with what the step changed;
         * without the toast of an earlier shot, which is not the scene's */
        a->bare_frame = true;
        frame(a, true);
        a->bare_frame = false;
        a->shooting = false;
        shoot(a, view_script_arg(script));
    }
    if (st == VIEW_SCRIPT_RELOAD) reload(a);
    if (st == VIEW_SCRIPT_REBUILD) render_rebuild_programs(a->scenes[a->script_scene]);
    if (st == VIEW_SCRIPT_DONE || st == VIEW_SCRIPT_FAILED) glfwSetWindowShouldClose(a->win, 1);
    return st == VIEW_SCRIPT_FAILED ? TARN_EXIT_INPUT : TARN_EXIT_OK;
}

static void start_watching(app *a) {
    char err[MSG_MAX];
    a->watch = watch_create(err, sizeof err);
    if (!a->watch) fprintf(stderr, "%s: hot reload is off: %s\n", a->d.name, err);
    else {
        watch_use_cache(a->watch, a->files);   /* a save is read once: the reload finds it in memory */
        a->file_wake = fd_wake_start(watch_fd(a->watch), post_wake, NULL);
    }
    app_rewatch(a);
}

void app_keep_awake(app *a) { a->keep_awake = true; }

/* Nothing to draw: the full-resolution frame of a still picture is on the
 * screen (res_budget), the clock is stopped or moves nothing, no script or
 * orbit drives frames, no toast is fading, no client asked for frames, no
 * folder is being looked for. (The clock advances with the frames: a
 * window asleep over a picture that reads it froze its animation, glman's
 * Timer scenes as soon as they drew at full size.) */
static bool idle(const app *a, const view_script *script) {
    bool clock_moves = !a->s.paused && scenes_read_clock(a);
    /* a script's `wait` sleeps as a user's still window does, so that
     * what it times (scripts/save_bench.sh) is what a user meets */
    bool script_waits = !script || view_script_waiting(script);
    return script_waits && !a->client_busy && a->budget.full_done && !clock_moves && !a->compiling && a->orbit_left == 0 &&
           !a->shot_pending && !a->stamp_pending && glfwGetTime() < frame_due_at(a);
}

/* Has a watched file something to say (without taking it: frame() does)? */
static bool files_pending(const app *a) {
    if (!a->watch) return false;
    if (watch_timeout_ms(a->watch) == 0) return true;
    struct pollfd p = { .fd = watch_fd(a->watch), .events = POLLIN };
    return p.fd >= 0 && poll(&p, 1, 0) > 0;
}

/* How long a still window sleeps at most: APP_IDLE_WAIT_S, or until a
 * save that is settling is due (watch_timeout_ms: the watcher has read its
 * events, so its fd wakes no one; it waits out the writer's quiet), the
 * script's wait ends or a frame is due (frame_due_at). */
static double idle_wait_s(const app *a, const view_script *script) {
    double s = fmin(APP_IDLE_WAIT_S, fmax(frame_due_at(a) - glfwGetTime() + 0.001, 0.0));
    if (view_script_waiting(script)) s = fmin(s, view_script_wait_left_s(script) + 0.001);   /* its next line */
    int ms = a->watch ? watch_timeout_ms(a->watch) : -1;
    if (ms >= 0 && ms / 1000.0 < s) s = ms / 1000.0;
    return s;
}

/* Waits for input, a window event or a file change while the picture is
 * still; returns whether a frame is due. A save wakes the wait (fd_wake:
 * the watcher's fd is not GLFW's to wait on); its timeout (idle_wait_s)
 * bounds how late anything else is seen. */
static bool wait_for_work(app *a, const view_script *script) {
    /* a client's ask holds for the frame after the one it was made in: it
     * asks again in each frame that wants another (compare-view while its
     * heat job runs, whose result a frame picks up). Those frames come at
     * the idle poll's rate, not as fast as they draw: the job is on the
     * same cores */
    bool asked = a->keep_awake;
    a->keep_awake = false;
    if (asked && idle(a, script)) {
        glfwWaitEventsTimeout(APP_CLIENT_POLL_S);
        return true;
    }
    double now = glfwGetTime();
    still_due(a, now);
    still_ready_due(a);   /* a paused picture's full frame, woken by the job: drawn now */
    if (a->compiling && !compile_readied(a) && !compile_finished(a) && (!script || view_script_waiting(script)) &&
        (res_budget_settled(&a->budget, now) || res_budget_full_held(&a->budget, now))) {
        /* a still picture while a job compiles (the last good build's full
         * frame, or the change's reduced one while the job makes the full
         * frame's code): no frames to draw (the cores are the compiler's),
         * only the job's end to see; a script's `wait` too, so a benchmark
         * meets what a user does. A moving one (the clock, a drag) keeps
         * drawing, full-resolution or not */
        glfwWaitEventsTimeout(APP_COMPILE_POLL_S);
        if (!a->woken && !compile_readied(a) && !compile_finished(a) && !files_pending(a)) return false;
        a->slept = true;
        return true;
    }
    if (!idle(a, script)) {
        glfwPollEvents();
        return true;
    }
    glfwWaitEventsTimeout(idle_wait_s(a, script));
    bool sheet = a->sheet.pid > 0 && sheet_ended(a, false);   /* its toast wants frames */
    if (!a->woken && !sheet && !files_pending(a) && idle(a, script)) return false;
    a->slept = true;
    return true;
}

int app_run(app *a, render *const *scenes, int n) {
    assert(n > 0 && a->d.draw && a->d.panel && a->d.reload);
    a->scenes = scenes;
    a->nscenes = n;
    view_script *script = NULL;
    if (a->d.script) {
        char err[MSG_MAX];
        script = view_script_load(a->d.script, err, sizeof err);
        if (!script) { fprintf(stderr, "tarn: %s\n", err); return TARN_EXIT_USAGE; }
    }
    start_watching(a);
    a->s.t = a->d.time_s;
    a->last_wall = glfwGetTime();
    a->slept = true;   /* the first frame has no frame before it to time ("first frame" on the panel) */
    if (a->d.recordable && a->d.record) record_start(a, a->d.record);
    int rc = TARN_EXIT_OK;
    while (!glfwWindowShouldClose(a->win)) {
        if (!wait_for_work(a, script)) continue;
        a->woken = false;
        double started = glfwGetTime();
        bool after_sleep = a->slept;
        frame(a, script != NULL);
        char lost[1024];
        if (gl_ctx_lost(a->ctx, lost, sizeof lost)) {
            fprintf(stderr, "%s: %s\n", a->d.name, lost);
            rc = TARN_EXIT_NO_GL;
            break;
        }
        if (script && !a->client_busy && script_step(a, script) != TARN_EXIT_OK) rc = TARN_EXIT_INPUT;
        glfwSwapBuffers(a->win);
        double swapped = glfwGetTime();
        double gap = swapped - (after_sleep ? started : a->last_swap);
        if (a->change_seen > 0 || a->stamp_pending) {
            a->gap_max = fmax(a->gap_max, gap);
            a->frames_meanwhile++;
        }
        stamp_after(a, gap, swapped);
        a->last_swap = swapped;
        if (a->judge_job) judge_compile_job(a, swapped - started);
        if (a->job_waits_shown) {
            a->job_waits_shown = false;
            compile_job_shown(a->cjob);
        }
        if (a->stamp_pending) stamp_swap(a);
        stamp_full(a);
        /* the scenes loaded in the job's renders once the window shows
         * them all (after the frame that drew the last one loaded: the job
         * would take the cores its first draw compiles on), so that the
         * first save compiles only what it changed */
        if (!a->primed && !a->client_busy) {
            a->primed = true;
            if (!a->compiling) start_compile(a, true);
        }
        if (a->client_busy) {
            a->client_busy = a->d.between_frames(a->d.user, a);
            a->slept = true;   /* the client's work is not the next frame's time */
        }
        /* input that arrives meanwhile queues, as behind a slow frame */
        for (double left; (left = started + a->slow_s - glfwGetTime()) > 0;)
            clock_sleep_s(left);
    }
    if (a->rec) record_stop(a);
    view_script_free(script);
    return rc;
}

/* ---- creating ---- */

static app_desc with_defaults(const app_desc *d) {
    app_desc r = *d;
    if (!r.name) r.name = "tarn";
    if (r.width <= 0) r.width = 1000;
    if (r.height <= 0) r.height = 700;
    return r;
}

app *app_create(const app_desc *desc) {
    app *a = mem_zalloc(sizeof *a);
    a->d = with_defaults(desc);
    a->client_busy = a->d.between_frames != NULL;
    char err[MSG_MAX];
    a->ctx = gl_ctx_create_window(a->d.width, a->d.height, a->d.name, err, sizeof err);
    if (!a->ctx) {
        fprintf(stderr, "%s: %s\n", a->d.name, err);
        free(a);
        return NULL;
    }
    a->win = gl_ctx_window(a->ctx);
    a->files = file_cache_create();
    res_budget_init(&a->budget, RES_BUDGET_DEFAULT_MS);
    a->budget_ms = (float)RES_BUDGET_DEFAULT_MS;
    glfwSetWindowUserPointer(a->win, a);
    char title[1200];
    if (a->d.scene_path) snprintf(title, sizeof title, "%s — %s", a->d.name, a->d.scene_path);
    else snprintf(title, sizeof title, "%s", a->d.name);
    glfwSetWindowTitle(a->win, title);
    /* ours first: the ImGui backend chains to callbacks installed before it */
    glfwSetScrollCallback(a->win, on_scroll);
    glfwSetCursorPosCallback(a->win, on_cursor);
    glfwSetCharCallback(a->win, on_char);
    glfwSetWindowSizeCallback(a->win, on_size);
    glfwSetWindowFocusCallback(a->win, on_focus);
    glfwSetCursorEnterCallback(a->win, on_enter);
    glfwSetWindowRefreshCallback(a->win, on_refresh);
    glfwSetKeyCallback(a->win, on_key);
    glfwSetMouseButtonCallback(a->win, on_button);
    a->panel = panel_create(a->win, "#version 130");
    a->s.cpu_raster = gl_ctx_cpu_rasteriser();
    return a;
}

void app_destroy(app *a) {
    if (!a) return;
    /* the window goes at once (issue #30: quitting is immediate); a job
     * under way stops at its next step, and its context goes before the
     * window's */
    if (a->win) glfwHideWindow(a->win);
    compile_job_destroy(a->cjob);
    fd_wake_stop(a->file_wake);   /* before the fd it polls goes */
    watch_destroy(a->watch);
    panel_destroy(a->panel);
    gl_ctx_destroy(a->ctx);
    file_cache_destroy(a->files);   /* last: the job's renders read through it */
    free(a);
}

file_cache *app_files(app *a) { return a->files; }

/* ---- small things ---- */

void app_fit_window(app *a, int w, int h) {
    /* no window many times the screen (issue #30: WindowSize 16000 16000
     * opened a 4.4 GB window at 10.7 s a frame): the scene keeps its aspect */
    int mx = 0, my = 0, mw = 0, mh = 0;
    GLFWmonitor *m = glfwGetPrimaryMonitor();
    if (m) glfwGetMonitorWorkarea(m, &mx, &my, &mw, &mh);
    int room_w = mw - APP_PANEL_WIDTH, room_h = mh;
    /* a little past the screen is the window manager's to fit (and what
     * the window tests' 1280x800 screens do); far past it is a mistake */
    if (room_w > 160 && room_h > 120 && (w > 2 * room_w || h > 2 * room_h)) {
        double s = fmin((double)room_w / w, (double)room_h / h);
        int nw = (int)(w * s), nh = (int)(h * s);
        app_toast(a, "WindowSize %dx%d is larger than the screen: the window shows it at %dx%d "
                  "(tarn render --size %dx%d draws the full size)", w, h, nw, nh, w, h);
        fprintf(stderr, "%s: %s\n", a->d.name, a->toast);
        w = nw;
        h = nh;
    }
    a->fit_w = w;
    a->fit_h = h;
    glfwSetWindowSize(a->win, w + APP_PANEL_WIDTH, h);
}

void app_home(app *a, render_view v) { a->s.cam = a->s.cam_home = orbit_from_view(v); }

void app_script_use(app *a, int i) {
    assert(i >= 0 && i < a->nscenes);
    a->script_scene = i;
    if (a->sc) a->sc->r = a->scenes[i];
}

app_state *app_get_state(app *a) { return &a->s; }
const char *app_reload_cause(const app *a) { return a->cause; }
double app_reload_compiled_s(const app *a) { return a->compiled_off_frame ? a->compile_s : -1; }
void *app_window(app *a) { return a->win; }
gl_ctx *app_gl(app *a) { return a->ctx; }
panel *app_panel(app *a) { return a->panel; }

int app_scene_x(int fb_w) { return fb_w > APP_PANEL_WIDTH + 160 ? APP_PANEL_WIDTH : 0; }

float app_scene_x_window(app *a) {
    int ww, wh, fw, fh;
    glfwGetWindowSize(a->win, &ww, &wh);
    glfwGetFramebufferSize(a->win, &fw, &fh);
    return fw > 0 ? (float)app_scene_x(fw) * (float)ww / (float)fw : 0;
}
