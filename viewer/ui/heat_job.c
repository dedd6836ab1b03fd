/* heat_job: compare-view's heat maps on a worker thread (see heat_job.h). */
#include "heat_job.h"
#include "strbuf.h"

#include <assert.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ref_flip.h"
#include "mem.h"
#include "ref_metrics.h"

struct heat_job {
    pthread_mutex_t mu;
    pthread_t th;
    bool joinable;               /* a thread was started and not joined yet */
    bool pending;                /* a job was started and heat_job_poll/wait has not said it ended */
    heat_job_kind kind;          /* the job started last */
    bool done;                   /* under mu: the worker finished it */
    bool orphaned;               /* under mu: destroyed while a reference ran; the worker frees */
    double progress;             /* under mu */
    /* the reference: its inputs, then its result */
    char scene[4096];
    int w, h;
    double t;
    refcache_view view;
    refcache_opts opts;
    refcache_image ref;
    bool ref_ok;
    char err[MSG_MAX];
    /* the maps: their inputs (rgba copied, against borrowed), then the result */
    float *rgba[HEAT_JOB_MAX_PACKS];
    float *field[HEAT_JOB_MAX_PACKS];
    const refcache_image *against;
    double heat_max;
    heat_metric metric;
    heat_maps maps;
};

heat_job *heat_job_create(void) {
    heat_job *j = mem_zalloc(sizeof *j);
    pthread_mutex_init(&j->mu, NULL);
    return j;
}

static void join(heat_job *j) {
    if (!j->joinable) return;
    pthread_join(j->th, NULL);
    j->joinable = false;
}

static void free_job(heat_job *j) {
    refcache_free(&j->ref);
    for (int i = 0; i < HEAT_JOB_MAX_PACKS; i++) {
        free(j->rgba[i]);
        free(j->field[i]);
        free(j->maps.map[i].rgb);
    }
    pthread_mutex_destroy(&j->mu);
    free(j);
}

void heat_job_destroy(heat_job *j) {
    if (!j) return;
    /* a window closed during a reference of half a minute closes now: the
     * reference owns its inputs, so its worker is left to finish and free
     * the job (maps borrow the caller's reference: they are waited for) */
    pthread_mutex_lock(&j->mu);
    bool orphan = j->joinable && !j->done && j->kind == HEAT_JOB_REFERENCE;
    j->orphaned = orphan;
    pthread_mutex_unlock(&j->mu);
    if (orphan) {
        pthread_detach(j->th);
        return;
    }
    join(j);
    free_job(j);
}

/* ---- the worker ---- */

static void set_progress(void *user, double f) {   /* called on the reference's threads */
    heat_job *j = user;
    pthread_mutex_lock(&j->mu);
    j->progress = f;
    pthread_mutex_unlock(&j->mu);
}

static void run_reference(heat_job *j) {
    refcache_free(&j->ref);
    j->err[0] = '\0';
    j->ref_ok = refcache_get(NULL, j->scene, NULL, j->w, j->h, j->t, &j->view, &j->opts, set_progress, j, &j->ref,
                             j->err, (int)sizeof j->err);
}

/* HDR-FLIP of pack i (linear values, the exposures chosen from the
 * reference as the bench does) into its field; its means over the water
 * (the whole frame when the reference has none) and the frame. */
static bool flip_field(heat_job *j, int i, const ref_fimage *A, const ref_fimage *B, bool have_water,
                       const unsigned char *water) {
    heat_map *m = &j->maps.map[i];
    ref_flip_desc d = { .hdr = true };
    ref_flip_result all;
    char err[MSG_MAX];
    if (!ref_flip_map(A, B, &d, j->field[i], NULL, &all, err, sizeof err)) return false;
    m->frame_flip = all.mean;
    ref_flip_result wet = all;
    if (have_water) ref_flip_pool(j->field[i], A->w, A->h, water, &wet);
    m->flip = wet.mean;
    return true;
}

/* Pack i's field and metrics against the reference; its automatic scale. */
static double map_one(heat_job *j, int i) {
    heat_map *m = &j->maps.map[i];
    int w = j->maps.w, h = j->maps.h;
    size_t n = (size_t)w * h;
    m->ok = false;
    if (!j->rgba[i]) return 0;
    j->field[i] = mem_realloc(j->field[i], n * sizeof *j->field[i]);
    ref_fimage A = { j->rgba[i], w, h, 4 }, B = { j->against->color, w, h, 3 };
    ref_image_metrics all, water_m;
    char err[MSG_MAX];
    if (!ref_metrics_error_field(&A, &B, REF_ERR_COLOR, NULL, j->field[i], err, sizeof err) ||
        !ref_metrics_image(&A, &B, NULL, &all, err, sizeof err))
        return 0;
    /* water first: the error of the water technique, where the reference
     * sees water (the rest of the frame is one world) */
    unsigned char *water = mem_alloc(n);
    ref_mask_water(j->against->mask, (long)n, 1, NULL, water);
    ref_metrics_desc wd = { .mask = water };
    bool have_water = ref_metrics_image(&A, &B, &wd, &water_m, err, sizeof err) && water_m.count.compared > 0;
    m->frame_rmse = all.rmse;
    m->rmse = have_water ? water_m.rmse : all.rmse;
    m->psnr = have_water ? water_m.psnr_db : all.psnr_db;
    m->flip = m->frame_flip = NAN;
    if (j->maps.metric == HEAT_METRIC_FLIP) {
        bool ok = flip_field(j, i, &A, &B, have_water, water);
        free(water);
        m->ok = ok;
        return ok ? 1 : 0;   /* FLIP is in [0, 1]: one scale for all */
    }
    free(water);
    m->ok = true;
    /* a pack with no error has no scale of its own (the automatic one
     * would say 1, the whole range, and wash out the others' maps) */
    float most = 0;
    for (size_t k = 0; k < n; k++)
        if (j->field[i][k] > most) most = j->field[i][k];
    return most > 0 ? ref_heatmap_auto_scale(j->field[i], (long)n) : 0;
}

static void run_maps(heat_job *j) {
    double scale = 0;
    for (int i = 0; i < j->maps.n; i++) {
        double s = map_one(j, i);
        if (s > scale) scale = s;
    }
    if (j->maps.metric == HEAT_METRIC_FLIP) scale = 1;
    else if (j->heat_max > 0) scale = j->heat_max;
    else if (scale <= 0) scale = 1;   /* no error anywhere */
    j->maps.scale = scale;
    size_t n = (size_t)j->maps.w * j->maps.h;
    for (int i = 0; i < j->maps.n; i++) {
        heat_map *m = &j->maps.map[i];
        if (!m->ok) continue;
        m->rgb = mem_realloc(m->rgb, n * 3 * sizeof *m->rgb);
        if (j->maps.metric == HEAT_METRIC_FLIP) ref_flip_colorize(j->field[i], j->maps.w, j->maps.h, NULL, m->rgb);
        else ref_heatmap(j->field[i], j->maps.w, j->maps.h, scale, m->rgb);
    }
}

static void *worker(void *arg) {
    heat_job *j = arg;
    if (j->kind == HEAT_JOB_REFERENCE) run_reference(j);
    else run_maps(j);
    pthread_mutex_lock(&j->mu);
    j->done = true;
    bool orphaned = j->orphaned;
    pthread_mutex_unlock(&j->mu);
    if (orphaned) free_job(j);
    return NULL;
}

static bool start(heat_job *j, heat_job_kind kind) {
    j->kind = kind;
    j->done = false;
    j->progress = 0;
    j->pending = true;
    if (pthread_create(&j->th, NULL, worker, j) != 0) worker(j);   /* no thread: do it here */
    else j->joinable = true;
    return true;
}

/* ---- the caller's side ---- */

bool heat_job_busy(heat_job *j) { return heat_job_running(j) != HEAT_JOB_NONE; }

heat_job_kind heat_job_running(heat_job *j) {
    if (!j->pending) return HEAT_JOB_NONE;
    pthread_mutex_lock(&j->mu);
    bool done = j->done;
    pthread_mutex_unlock(&j->mu);
    return done ? HEAT_JOB_NONE : j->kind;
}

double heat_job_progress(heat_job *j) {
    pthread_mutex_lock(&j->mu);
    double f = j->progress;
    pthread_mutex_unlock(&j->mu);
    return f;
}

heat_job_kind heat_job_poll(heat_job *j) {
    if (!j->pending) return HEAT_JOB_NONE;
    pthread_mutex_lock(&j->mu);
    bool done = j->done;
    pthread_mutex_unlock(&j->mu);
    if (!done) return HEAT_JOB_NONE;
    return heat_job_wait(j);
}

heat_job_kind heat_job_wait(heat_job *j) {
    if (!j->pending) return HEAT_JOB_NONE;
    join(j);
    j->pending = false;
    return j->kind;
}

bool heat_job_start_reference(heat_job *j, const char *scene, int w, int h, double t, const refcache_view *view,
                              const refcache_opts *o) {
    if (j->pending) return false;   /* running, or finished and not polled yet */
    snprintf(j->scene, sizeof j->scene, "%s", scene);
    j->w = w;
    j->h = h;
    j->t = t;
    j->view = *view;
    j->opts = *o;
    return start(j, HEAT_JOB_REFERENCE);
}

bool heat_job_start_maps(heat_job *j, const float *const *rgba, int n, int w, int h, const refcache_image *ref,
                         double heat_max) {
    assert(n >= 0 && n <= HEAT_JOB_MAX_PACKS && ref && ref->w == w && ref->h == h);
    if (j->pending) return false;
    size_t bytes = (size_t)w * h * 4 * sizeof(float);
    for (int i = 0; i < HEAT_JOB_MAX_PACKS; i++) {
        if (i < n && rgba[i]) {
            j->rgba[i] = mem_realloc(j->rgba[i], bytes);
            memcpy(j->rgba[i], rgba[i], bytes);
        } else {
            free(j->rgba[i]);
            j->rgba[i] = NULL;
        }
        j->maps.map[i].ok = false;
    }
    j->maps.n = n;
    j->maps.w = w;
    j->maps.h = h;
    j->against = ref;
    j->heat_max = heat_max;
    j->maps.metric = j->metric;
    return start(j, HEAT_JOB_MAPS);
}

bool heat_job_take_reference(heat_job *j, refcache_image *out, char *err, int errlen) {
    if (!j->ref_ok) {
        snprintf(err, (size_t)errlen, "%s", j->err[0] ? j->err : "no reference");
        return false;
    }
    *out = j->ref;
    memset(&j->ref, 0, sizeof j->ref);
    j->ref_ok = false;
    return true;
}

const heat_maps *heat_job_maps(const heat_job *j) { return &j->maps; }

void heat_job_set_metric(heat_job *j, heat_metric m) { j->metric = m; }
