/* heat_job: compare-view's heat maps computed off the UI thread.
 *
 * The CPU reference of a frame took 34 s at 960x540, and the error maps of
 * every frame a good part of one, all on the thread that draws the window,
 * which froze. A heat_job runs one job at a time on a worker thread
 * (pthreads) and the window polls it once a frame:
 *
 *   reference  refcache_get of the scene at a size, time and camera, with
 *              its progress readable while it runs (heat_job_progress);
 *   maps       each pack's error field against the reference, its water
 *              and whole-frame metrics, and the field coloured (one scale
 *              for all packs), from images the caller read back.
 *
 * GL stays on the caller's thread: it reads the packs' pixels back and
 * uploads the coloured maps; the worker touches no GL and no GLFW.
 *
 *     heat_job *j = heat_job_create();
 *     heat_job_start_reference(j, scene, w, h, t, &view, &opts);
 *     ... each frame: if (heat_job_poll(j) == HEAT_JOB_REFERENCE) heat_job_take_reference(j, &ref, ...);
 *     heat_job_start_maps(j, rgba, n, w, h, &ref, 0);        the pixels are copied
 *     ... if (heat_job_poll(j) == HEAT_JOB_MAPS) heat_job_maps(j) ...
 *     heat_job_destroy(j);                                    waits for a running job
 */
#ifndef TARN_HEAT_JOB_H
#define TARN_HEAT_JOB_H

#include <stdbool.h>

#include "refcache.h"

#define HEAT_JOB_MAX_PACKS 4

typedef struct heat_job heat_job;

typedef enum heat_job_kind { HEAT_JOB_NONE, HEAT_JOB_REFERENCE, HEAT_JOB_MAPS } heat_job_kind;

/* What a map shows (issue #26): the largest of the R, G, B errors in the
 * inferno ramp up to a scale, or HDR-FLIP (reference/ref_flip.h, 0..1, what
 * the eye sees of the difference) in the authors' magma ramp. */
typedef enum heat_metric { HEAT_METRIC_COLOR = 0, HEAT_METRIC_FLIP = 1 } heat_metric;

/* One pack's map: ok false when it was not given or its metrics failed. */
typedef struct heat_map {
    bool ok;
    float *rgb;                  /* w * h * 3 display values, row 0 at the top (owned by the job) */
    double rmse, psnr;           /* over the reference's water pixels (the whole frame when it has none) */
    double frame_rmse;           /* the whole frame */
    double flip, frame_flip;     /* HDR-FLIP means, water and whole frame (HEAT_METRIC_FLIP; else NaN) */
} heat_map;

typedef struct heat_maps {
    int n, w, h;
    heat_metric metric;          /* what the maps show */
    double scale;                /* the colour scale used for every pack (FLIP: 1) */
    heat_map map[HEAT_JOB_MAX_PACKS];
} heat_maps;

heat_job *heat_job_create(void);
void heat_job_destroy(heat_job *j);   /* NULL is fine; waits for a running job */

/* Starts the reference of scene at w x h, time t, seen from view, on the
 * worker. False (nothing started) while a job runs. */
bool heat_job_start_reference(heat_job *j, const char *scene, int w, int h, double t, const refcache_view *view,
                              const refcache_opts *o);
/* Starts the maps of n packs' images (rgba[i]: w * h * 4 floats, row 0 at
 * the top, copied; NULL for a pack not drawn) against ref, which must stay
 * as it is until the job is finished (heat_job_poll or heat_job_wait).
 * heat_max > 0 fixes the scale, else the largest pack's automatic scale. */
bool heat_job_start_maps(heat_job *j, const float *const *rgba, int n, int w, int h, const refcache_image *ref,
                         double heat_max);

/* The metric of the maps started from now on (default HEAT_METRIC_COLOR). */
void heat_job_set_metric(heat_job *j, heat_metric m);

bool heat_job_busy(heat_job *j);
/* What is running: HEAT_JOB_NONE when idle. */
heat_job_kind heat_job_running(heat_job *j);
/* The running reference's progress, 0..1. */
double heat_job_progress(heat_job *j);
/* Once a job has finished: its kind, once (the thread is joined); else
 * HEAT_JOB_NONE. Never blocks. */
heat_job_kind heat_job_poll(heat_job *j);
/* Blocks until the running job finishes; returns its kind as heat_job_poll. */
heat_job_kind heat_job_wait(heat_job *j);

/* After a finished reference: moves it to *out (the caller frees it with
 * refcache_free). False with the reason in err when it failed. */
bool heat_job_take_reference(heat_job *j, refcache_image *out, char *err, int errlen);
/* After finished maps: the results, valid until the next job starts. */
const heat_maps *heat_job_maps(const heat_job *j);

#endif
