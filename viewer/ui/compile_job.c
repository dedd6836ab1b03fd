/* compile_job: a save's shaders compiled off the frame (see compile_job.h). */
#include "compile_job.h"
#include "strbuf.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

#include "gl_ctx.h"
#include "glib.h"
#include "mem.h"
#include "unif.h"
#include "util.h"

/* One Define's value as the window has it. */
typedef struct job_define {
    char program[UNIF_NAME_MAX], name[UNIF_NAME_MAX];
    float value[UNIF_MAX_COMPONENTS];
} job_define;

/* What the worker needs of one of the window's scenes, copied. */
typedef struct job_scene {
    char glib[GLIB_PATH_MAX], root[GLIB_PATH_MAX], pack[GLIB_NAME_MAX];
    render_desc desc;            /* its strings point into this struct */
    bool srgb;                   /* a world: the window draws it into an sRGB canvas */
    job_define *defines;
    int ndefines;
} job_scene;

struct compile_job {
    pthread_mutex_t mu;
    pthread_cond_t cv;
    pthread_t th;
    bool thread;                 /* the worker was started */
    bool request;                /* under mu: a job is waiting for the worker */
    bool busy;                   /* under mu: a job was started and has not been taken as done */
    bool done;                   /* under mu: the worker finished it */
    bool ready;                  /* under mu: the reduced frames' code is made (the window may reload) */
    bool ready_taken;            /* under mu: compile_job_ready said so */
    bool deferred_ready;         /* under mu: the deferred water's code is made too (compile_job_deferred_ready) */
    bool still_ready;            /* under mu: a still job's full frame is made with the grid (compile_job_still_ready) */
    double ready_seconds;        /* under mu: how long that took */
    bool wait_for_shown;         /* under mu: the job waits for shown after its ready */
    bool still;                  /* compile_job_desc.still: only the first frame before the ready */
    bool defer_still;            /* under mu: compile_job_desc.defer_still */
    int still_answer;            /* under mu: 0 none yet, 1 want_still, -1 drop_still */
    bool still_waits;            /* under mu: the worker waits for that answer */
    int frames_at_ready, frames_in_all;   /* under mu: the frames the last job drew (compile_job_frames) */
    int frames_at_still;         /* under mu: ... before its still_ready (compile_job_frames_at_still) */
    int frames_drawn;            /* the worker's own: this job's so far */
    bool shown;                  /* under mu: compile_job_shown since the job started */
    bool quit;                   /* under mu: destroy asked the worker to end */
    bool cancel;                 /* under mu: this job's work is old (compile_job_cancel): it ends at its next step */
    double seconds;              /* under mu: how long it ran */
    /* the job: written by compile_job_start while no job runs, read by the worker */
    job_scene scenes[COMPILE_JOB_MAX_SCENES];
    int nscenes, w, h;
    double t;
    render_view view;
    void (*wake)(void *user);    /* compile_job_desc.wake */
    void *wake_user;
    /* the worker's own: its context and the renders it keeps between jobs,
     * so that a job reloads as the window does (the world, the once-drawn
     * passes and the unchanged programs kept) instead of loading afresh */
    gl_ctx *ctx;
    render *kept[COMPILE_JOB_MAX_SCENES];
    job_scene kept_as[COMPILE_JOB_MAX_SCENES];   /* (no defines: only the keys) */
};

static bool env_true(const char *name) {
    const char *v = getenv(name);
    return v && (strcmp(v, "1") == 0 || strcasecmp(v, "true") == 0 || strcasecmp(v, "yes") == 0);
}

bool compile_job_useful(void) {
    const char *on_frame = getenv("TARN_COMPILE_ON_FRAME");
    if (on_frame && on_frame[0]) return false;
    return !env_true("MESA_SHADER_CACHE_DISABLE") && !env_true("MESA_GLSL_CACHE_DISABLE");
}

bool compile_job_helped(double first_frame_s, double job_s, double budget_ms) {
    double limit = COMPILE_JOB_SLOW_S, budgets = 4e-3 * budget_ms;
    if (!(first_frame_s > (budgets > limit ? budgets : limit))) return true;
    return first_frame_s < 0.5 * job_s;
}

compile_job *compile_job_create(void) {
    compile_job *j = mem_zalloc(sizeof *j);
    pthread_mutex_init(&j->mu, NULL);
    pthread_cond_init(&j->cv, NULL);
    return j;
}

static void free_scenes(compile_job *j) {
    for (int i = 0; i < j->nscenes; i++) free(j->scenes[i].defines);
    j->nscenes = 0;
}

void compile_job_destroy(compile_job *j) {
    if (!j) return;
    if (j->thread) {
        pthread_mutex_lock(&j->mu);
        j->quit = true;
        pthread_cond_signal(&j->cv);
        pthread_mutex_unlock(&j->mu);
        pthread_join(j->th, NULL);
    }
    free_scenes(j);
    pthread_cond_destroy(&j->cv);
    pthread_mutex_destroy(&j->mu);
    free(j);
}

/* The Define entries of r's programs: they change the text compiled. */
static void copy_defines(render *r, job_scene *s) {
    int nsets;
    unif_set *sets = render_uniforms(r, &nsets);
    for (int i = 0; i < nsets; i++)
        for (int k = 0; k < sets[i].n; k++) {
            const unif_entry *e = &sets[i].entries[k];
            if (!e->is_define) continue;
            s->defines = mem_realloc(s->defines, (size_t)(s->ndefines + 1) * sizeof *s->defines);
            job_define *d = &s->defines[s->ndefines++];
            snprintf(d->program, sizeof d->program, "%s", sets[i].program);
            snprintf(d->name, sizeof d->name, "%s", e->name);
            memcpy(d->value, e->value, sizeof d->value);
        }
}

/* What says which scene r draws (same_scene's keys), into s. */
static void copy_keys(render *r, job_scene *s) {
    render_desc d = render_desc_of(r);
    snprintf(s->glib, sizeof s->glib, "%s", render_scene_path(r));
    snprintf(s->root, sizeof s->root, "%s", d.repo_root);
    snprintf(s->pack, sizeof s->pack, "%s", d.pack ? d.pack : "");
    s->desc = d;
    s->desc.repo_root = s->root;
    s->desc.pack = s->pack[0] ? s->pack : NULL;
}

static void copy_scene(render *r, job_scene *s) {
    memset(s, 0, sizeof *s);
    copy_keys(r, s);
    s->srgb = render_has_world(r);
    copy_defines(r, s);
}

/* The window's Define values on the job's fresh load; true when one
 * differs from the glib's default (the programs must be built again). */
static bool apply_defines(render *r, const job_scene *s) {
    int nsets;
    unif_set *sets = render_uniforms(r, &nsets);
    bool changed = false;
    for (int i = 0; i < s->ndefines; i++)
        for (int k = 0; k < nsets; k++) {
            if (strcmp(sets[k].program, s->defines[i].program) != 0) continue;
            unif_entry *e = unif_find(&sets[k], s->defines[i].name);
            if (!e || !e->is_define || memcmp(e->value, s->defines[i].value, sizeof e->value) == 0) continue;
            memcpy(e->value, s->defines[i].value, sizeof e->value);
            changed = true;
        }
    return changed;
}

/* Under mu: the window closes (destroy) or the job's work is old (cancel). */
static bool stopping(const compile_job *j) { return j->quit || j->cancel; }

/* The window is closing or the job is cancelled: what the job has not
 * begun is left undone (a load or a frame under way runs to its end; GL
 * has no way to stop one). */

static bool quitting(compile_job *j) {
    pthread_mutex_lock(&j->mu);
    bool q = stopping(j);
    pthread_mutex_unlock(&j->mu);
    return q;
}

/* The detail of the reduced frames the job draws: any below 1 has the
 * same draw states (side_off_pow2), so the cheap one. */
#define COMPILE_JOB_REDUCED_DETAIL 0.25

/* Is the worker's render i one of this scene (then a job reloads it)? */
static bool same_scene(const job_scene *a, const job_scene *b) {
    return strcmp(a->glib, b->glib) == 0 && strcmp(a->root, b->root) == 0 && strcmp(a->pack, b->pack) == 0 &&
           a->desc.samples == b->desc.samples && a->desc.verbose == b->desc.verbose &&
           a->desc.no_spray == b->desc.no_spray;
}

/* A canvas for the job's frames: an eighth of the window's side (a
 * canvas's size changes no variant but for a power-of-two side, which
 * side_off_pow2 keeps away), sRGB where the window's is. */
static bool job_canvas(const compile_job *j, const job_scene *s, render_target *t, int *w, int *h) {
    memset(t, 0, sizeof *t);
    *w = side_off_pow2((j->w + 7) / 8, j->w);
    *h = side_off_pow2((j->h + 7) / 8, j->h);
    return s->srgb ? render_target_create_srgb(t, *w, *h) : render_target_create(t, *w, *h, false);
}

/* The frames the window draws while its picture changes (no side a power
 * of two there: side_off_pow2): the frame after the reload, the same again
 * (the static world copied from its cache), then with the clock running
 * (the world's layers built, then composited). */
static const double warm_dt[] = { 0, 0, 0.04, 0.08 };
#define WARM_FRAMES ((int)(sizeof warm_dt / sizeof warm_dt[0]))

/* Loads (or reloads) scene i as the window would: every changed stage
 * compiled (the GLSL front end), into Mesa's cache. True when the world's
 * own programs are new (a first load, or their texts changed). */
static bool job_load(compile_job *j, int i) {
    const job_scene *s = &j->scenes[i];
    unsigned long long world_before = j->kept[i] ? render_world_programs_hash(j->kept[i]) : 0;
    if (j->kept[i] && !same_scene(&j->kept_as[i], s)) {
        render_destroy(j->kept[i]);
        j->kept[i] = NULL;
    }
    if (!j->kept[i]) {
        j->kept[i] = render_create(&s->desc);
        j->kept_as[i] = *s;
        j->kept_as[i].defines = NULL;
        j->kept_as[i].ndefines = 0;
        render_load(j->kept[i], s->glib);   /* its errors are the window's reload's to report */
    }
    else render_load(j->kept[i], NULL);
    if (apply_defines(j->kept[i], s)) render_rebuild_programs(j->kept[i]);
    return render_world_programs_hash(j->kept[i]) != world_before;
}

/* Draws warm_dt's frames [from, to) of scene i as the window would:
 * every variant those draws need made (the LLVM compile), into Mesa's
 * cache. deferred: the water drawn deferred (render_set_deferred_water),
 * as the window draws it once compile_job_deferred_ready, else as a grid,
 * as it draws the first frames after a reload (their code made first: one
 * GLSL front end of the water's text, not two). Pixels do not matter. */
static void warm_moving(compile_job *j, int i, int from, int to, bool deferred) {
    if (from >= to) return;
    const job_scene *s = &j->scenes[i];
    render *r = j->kept[i];
    render_target t;
    int w, h;
    bool made = job_canvas(j, s, &t, &w, &h);
    if (made && r && render_has_scene(r)) {
        if (s->srgb) glEnable(GL_FRAMEBUFFER_SRGB);
        render_set_detail(r, COMPILE_JOB_REDUCED_DETAIL);
        render_set_deferred_water(r, deferred);
        for (int k = from; k < to && !quitting(j); k++) {
            render_frame_at(r, j->t + warm_dt[k], t.fbo, 0, 0, w, h, &j->view);
            j->frames_drawn++;
        }
        glDisable(GL_FRAMEBUFFER_SRGB);
        glFinish();
    }
    if (made) render_target_destroy(&t);
}

/* The still picture's full-resolution frame, where the targets and the
 * world's height map have the scene's sizes: its variants too, with the
 * water deferred or (deferred false) as a grid. */
static void warm_still(compile_job *j, int i, bool deferred) {
    const job_scene *s = &j->scenes[i];
    render *r = j->kept[i];
    render_target t;
    int w, h;
    bool made = job_canvas(j, s, &t, &w, &h);
    if (made && r && render_has_scene(r) && !quitting(j)) {
        if (s->srgb) glEnable(GL_FRAMEBUFFER_SRGB);
        render_set_detail(r, 1);
        render_set_deferred_water(r, deferred);
        render_frame_at(r, j->t, t.fbo, 0, 0, w, h, &j->view);
        j->frames_drawn++;
        glDisable(GL_FRAMEBUFFER_SRGB);
        glFinish();
    }
    if (made) render_target_destroy(&t);
}

/* s seconds from now on pthread_cond_timedwait's clock. */
static struct timespec deadline_in(double s) {
    struct timespec until;
    clock_gettime(CLOCK_REALTIME, &until);
    until.tv_nsec += (long)(s * 1e9);
    until.tv_sec += until.tv_nsec / 1000000000L;
    until.tv_nsec %= 1000000000L;
    return until;
}

/* Under mu: the window's first frame of the change first, alone on the
 * cores (compile_job_desc.wait_for_shown), for at most
 * COMPILE_JOB_SHOWN_WAIT_S. */
static void wait_for_shown(compile_job *j) {
    struct timespec until = deadline_in(COMPILE_JOB_SHOWN_WAIT_S);
    while (j->wait_for_shown && !j->shown && !stopping(j))
        if (pthread_cond_timedwait(&j->cv, &j->mu, &until) != 0) break;   /* timed out: go on */
}

/* Under mu: with defer_still, the window's answer (or the window's
 * closing); true when the still picture's code is wanted. */
static bool still_wanted(compile_job *j) {
    if (!j->defer_still) return true;
    j->still_waits = true;
    while (j->still_answer == 0 && !stopping(j)) pthread_cond_wait(&j->cv, &j->mu);
    j->still_waits = false;
    return j->still_answer > 0 && !stopping(j);
}

/* One job: the scenes asked for, warmed; renders of scenes no longer
 * drawn are let go. */
static void run_job(compile_job *j) {
    j->frames_drawn = 0;
    if (!j->ctx) {
        char err[MSG_MAX] = "";
        j->ctx = gl_ctx_create_headless(err, sizeof err);   /* none: the window compiles on the frame */
        if (!j->ctx) return;
    }
    double t0 = clock_now_s();
    /* The frames the window needs before it can show the change: the
     * first; the clock's too where the world's programs changed (their
     * frames draw only the world's code anew: its cache copied, its layers
     * built and composited), unless the window is paused. */
    int first[COMPILE_JOB_MAX_SCENES] = { 0 };
    for (int i = 0; i < j->nscenes && !quitting(j); i++) {
        first[i] = job_load(j, i) && !j->still ? WARM_FRAMES : 1;
        warm_moving(j, i, 0, first[i], false);
    }
    /* the window can show the change now: its frames while the picture
     * changes find their code (a paused window's first: the others, made
     * next, only once its picture moves again); the still picture's
     * frame, which it draws only once the picture stands still, is made
     * meanwhile */
    pthread_mutex_lock(&j->mu);
    j->ready = true;
    j->ready_seconds = clock_now_s() - t0;
    j->frames_at_ready = j->frames_drawn;
    if (j->wake) j->wake(j->wake_user);   /* a window asleep while it compiles reloads now */
    wait_for_shown(j);
    pthread_mutex_unlock(&j->mu);
    for (int i = 0; i < j->nscenes && !quitting(j); i++) warm_moving(j, i, first[i], WARM_FRAMES, false);
    /* A paused window shows the change reduced, then holds its sharp
     * frame until that frame's code is made. With the water as a grid its
     * code is the reduced frames' (made above) but for the scene's own
     * sizes, so that frame comes first, before the deferred water's
     * front end and LLVM compile (0.95 s of natural's on a slow 2-core
     * machine): the window draws it with the grid it already draws.
     * (Waiting for the window to show it, as for the first frame, made
     * that frame no faster in save_bench: 610-873 ms against 652-764.) */
    if (j->still && !quitting(j)) {
        for (int i = 0; i < j->nscenes && !quitting(j); i++) warm_still(j, i, false);
        pthread_mutex_lock(&j->mu);
        j->still_ready = true;
        j->frames_at_still = j->frames_drawn;
        if (j->wake) j->wake(j->wake_user);
        pthread_mutex_unlock(&j->mu);
    }
    /* then the deferred water's (the window turns to it at
     * compile_job_deferred_ready): one frame, the water's two programs and
     * their variants; the rest of a frame (the world's copy, layers) was
     * made above and draws the same code with the water deferred */
    for (int i = 0; i < j->nscenes && !quitting(j); i++) warm_moving(j, i, 0, 1, true);
    pthread_mutex_lock(&j->mu);
    j->deferred_ready = !j->cancel;   /* cancelled: not made (compile_job_deferred_ready says so at the end) */
    if (j->wake) j->wake(j->wake_user);
    bool still = still_wanted(j);
    pthread_mutex_unlock(&j->mu);
    for (int i = 0; i < j->nscenes && still && !quitting(j); i++) warm_still(j, i, true);
    for (int i = j->nscenes; i < COMPILE_JOB_MAX_SCENES; i++)
        if (j->kept[i]) {
            render_destroy(j->kept[i]);
            j->kept[i] = NULL;
        }
}

static void *worker(void *arg) {
    compile_job *j = arg;
    pthread_mutex_lock(&j->mu);
    for (;;) {
        while (!j->request && !j->quit) pthread_cond_wait(&j->cv, &j->mu);
        if (j->quit) break;
        j->request = false;
        pthread_mutex_unlock(&j->mu);
        double t0 = clock_now_s();
        run_job(j);
        pthread_mutex_lock(&j->mu);
        j->done = true;
        j->seconds = clock_now_s() - t0;
        j->frames_in_all = j->frames_drawn;
        if (j->wake) j->wake(j->wake_user);
        pthread_cond_broadcast(&j->cv);   /* compile_job_wait_done */
    }
    pthread_mutex_unlock(&j->mu);
    for (int i = 0; i < COMPILE_JOB_MAX_SCENES; i++) render_destroy(j->kept[i]);
    gl_ctx_destroy(j->ctx);   /* its screen writes what is still queued for Mesa's cache */
    return NULL;
}

bool compile_job_start(compile_job *j, const compile_job_desc *d) {
    if (!j || !d || d->n <= 0 || compile_job_busy(j)) return false;
    free_scenes(j);
    for (int i = 0; i < d->n && i < COMPILE_JOB_MAX_SCENES; i++)
        if (render_has_scene(d->scenes[i])) copy_scene(d->scenes[i], &j->scenes[j->nscenes++]);
    if (j->nscenes == 0) return false;
    j->w = d->w > 0 ? d->w : 256;
    j->h = d->h > 0 ? d->h : 144;
    j->t = d->t;
    j->view = d->view;
    j->wake = d->wake;
    j->wake_user = d->wake_user;
    if (!j->thread) {
        if (pthread_create(&j->th, NULL, worker, j) != 0) return false;
        j->thread = true;
    }
    pthread_mutex_lock(&j->mu);
    j->request = j->busy = true;
    j->done = j->ready = j->ready_taken = j->shown = j->deferred_ready = j->still_ready = j->cancel = false;
    j->frames_at_still = 0;
    j->wait_for_shown = d->wait_for_shown;
    j->still = d->still;
    j->defer_still = d->defer_still;
    j->still_answer = 0;
    pthread_cond_signal(&j->cv);
    pthread_mutex_unlock(&j->mu);
    return true;
}

bool compile_job_busy(compile_job *j) {
    if (!j) return false;
    pthread_mutex_lock(&j->mu);
    bool busy = j->busy;
    pthread_mutex_unlock(&j->mu);
    return busy;
}

void compile_job_shown(compile_job *j) {
    if (!j || !j->thread) return;
    pthread_mutex_lock(&j->mu);
    j->shown = true;
    pthread_cond_broadcast(&j->cv);
    pthread_mutex_unlock(&j->mu);
}

static void answer_still(compile_job *j, int answer) {
    if (!j || !j->thread) return;
    pthread_mutex_lock(&j->mu);
    if (j->busy && j->still_answer == 0) j->still_answer = answer;
    pthread_cond_broadcast(&j->cv);
    pthread_mutex_unlock(&j->mu);
}

void compile_job_want_still(compile_job *j) { answer_still(j, 1); }

void compile_job_drop_still(compile_job *j) { answer_still(j, -1); }

void compile_job_cancel(compile_job *j) {
    if (!j || !j->thread) return;
    pthread_mutex_lock(&j->mu);
    if (j->busy) j->cancel = true;
    pthread_cond_broadcast(&j->cv);
    pthread_mutex_unlock(&j->mu);
}

bool compile_job_draws(compile_job *j, render *const *scenes, int n) {
    if (!j || n != j->nscenes) return false;
    for (int i = 0; i < n; i++) {
        job_scene now;
        memset(&now, 0, sizeof now);
        copy_keys(scenes[i], &now);
        if (!same_scene(&j->scenes[i], &now)) return false;
    }
    return true;
}

bool compile_job_wait_done(compile_job *j, double max_s) {
    if (!j || !j->thread) return false;
    struct timespec until = deadline_in(max_s);
    pthread_mutex_lock(&j->mu);
    while (j->busy && !j->done)
        if (pthread_cond_timedwait(&j->cv, &j->mu, &until) != 0) break;
    bool done = j->busy && j->done;
    pthread_mutex_unlock(&j->mu);
    return done;
}

bool compile_job_compiling(compile_job *j) {
    if (!j) return false;
    pthread_mutex_lock(&j->mu);
    /* answered, it compiles from this frame on, before the worker wakes */
    bool compiling = j->busy && !j->done && !(j->still_waits && j->still_answer == 0);
    pthread_mutex_unlock(&j->mu);
    return compiling;
}

bool compile_job_still_waits(compile_job *j) {
    if (!j) return false;
    pthread_mutex_lock(&j->mu);
    bool waits = j->still_waits;
    pthread_mutex_unlock(&j->mu);
    return waits;
}

bool compile_job_ready(compile_job *j, double *seconds) {
    if (!j) return false;
    pthread_mutex_lock(&j->mu);
    bool ready = j->busy && !j->ready_taken && (j->ready || j->done);
    if (ready) {
        j->ready_taken = true;
        if (seconds) *seconds = j->ready ? j->ready_seconds : j->seconds;
    }
    pthread_mutex_unlock(&j->mu);
    return ready;
}

int compile_job_frames_at_still(compile_job *j) {
    if (!j) return 0;
    pthread_mutex_lock(&j->mu);
    int n = j->frames_at_still;
    pthread_mutex_unlock(&j->mu);
    return n;
}

void compile_job_frames(compile_job *j, int *at_ready, int *in_all) {
    *at_ready = *in_all = 0;
    if (!j) return;
    pthread_mutex_lock(&j->mu);
    *at_ready = j->frames_at_ready;
    *in_all = j->frames_in_all;
    pthread_mutex_unlock(&j->mu);
}

bool compile_job_deferred_ready(compile_job *j) {
    if (!j) return true;
    pthread_mutex_lock(&j->mu);
    bool ready = !j->busy || j->deferred_ready || j->done;
    pthread_mutex_unlock(&j->mu);
    return ready;
}

bool compile_job_still_ready(compile_job *j) {
    if (!j) return true;
    pthread_mutex_lock(&j->mu);
    bool ready = !j->busy || j->still_ready || j->done;
    pthread_mutex_unlock(&j->mu);
    return ready;
}

bool compile_job_done(compile_job *j, double *seconds) {
    if (!j) return false;
    pthread_mutex_lock(&j->mu);
    bool done = j->busy && j->done;
    if (done) {
        j->busy = j->done = false;
        if (seconds) *seconds = j->seconds;
    }
    pthread_mutex_unlock(&j->mu);
    return done;
}
