/* bench: `tarn bench [SCENE...] [options]`, speed against error. For every
 * pack present (or those named) and every setting its packs/NAME/bench.txt
 * declares (packset.h), at fixed simulated times: the median GPU time,
 * wall time and process CPU time per frame, and the error against the CPU reference of the same
 * frame (refcache.h, reference/ref_metrics.h, ref_flip.h, ref_ssim.h):
 * RMSE, HDR-FLIP and SSIM over the reference's water pixels first, and hit
 * point, Fresnel, irradiance and depth where the pack exposes them
 * (`Define TARN_OUTPUT`; a pack without an irradiance buffer is measured as
 * the flat lighting it draws). Settings are timed interleaved (round-robin,
 * a few frames each turn) with the machine's load recorded; each setting is
 * also measured over a short animated sequence (mean and temporal error),
 * and the reference's own noise and grid bias give each error figure its
 * uncertainty, which decides ties on the Pareto fronts. The cost floor (a
 * full-screen pass with one texture fetch) is measured in the same run.
 * Writes CSV, JSON, a Markdown report and speed-against-RMSE and
 * speed-against-FLIP plots per scene; with --docs, the report section of
 * docs/benchmark.md. See docs/benchmark.md. The command is bench.c, the
 * measuring bench_measure.c (with bench_timing.c, bench_error.c,
 * bench_refs.c, bench_cost.c), the writers bench_csv.c, bench_json.c and
 * bench_report.c (their shared state: bench_int.h). */
#ifndef TARN_BENCH_H
#define TARN_BENCH_H

#include <stdbool.h>
#include <stddef.h>

#include "packset.h"
#include "refcache.h"

#define BENCH_MAX_SCENES 16
#define BENCH_MAX_TIMES 16

/* The time the plots and the Pareto fronts rank by. auto (0): the GPU
 * timer's on a GPU, the process's CPU time on a CPU rasteriser (llvmpipe's
 * threads are the process's, so its CPU time is the work done, which other
 * processes' load barely moves; its GL timer and the wall time are wall
 * clocks, which a busy machine stretches). */
enum { BENCH_AXIS_AUTO = 0, BENCH_AXIS_GPU = 1, BENCH_AXIS_WALL = 2, BENCH_AXIS_CPU = 3 };

/* What to measure. Zero means default in every field but the two whose
 * zero is a real value (warmup, frame_budget: say so with *_set). */
typedef struct bench_desc {
    const char *scenes[BENCH_MAX_SCENES];  /* a path, or relative to root */
    int nscenes;                           /* 0: scenes/lake.glib */
    const char *packs[PACKSET_MAX];
    int npacks;                            /* 0: every pack under root */
    const char *root;                      /* NULL: tarn_root() */
    int width, height;                     /* 0: 480x270 */
    double times[BENCH_MAX_TIMES];
    int ntimes;                            /* 0: 1 s and 4 s */
    int frames;                            /* timed frames a time; 0: 30 */
    int warmup;                            /* untimed frames first (default 1) */
    bool warmup_set;
    double frame_budget;                   /* seconds a time (default 1.5) */
    bool frame_budget_set;
    const char *out;                       /* NULL: out/bench */
    const char *ref_cache;                 /* NULL: $XDG_CACHE_HOME/tarn/ref */
    const char *docs;                      /* NULL: no docs section */
    int time_axis;                         /* 0 auto, else BENCH_AXIS_* */
    refcache_opts ref;                     /* the references' quality; ref.spp 0: matched to the
                                              MSAA (refcache_match_msaa: the GL's positions) */
    int samples;                           /* MSAA of the packs (render_desc.samples): 0 default, 1 off */
    double heat_max;                       /* 0: 0.25 */
    bool no_images, quiet;
    bool no_cost_model;                    /* skip the cost model's sweep (costmodel.h) */
    bool no_uncertainty;                   /* skip the reference's noise and grid-bias references */
    int seq_frames;                        /* the animated sequence's frames (0: 8) */
    bool no_sequence;                      /* ...none */
    double seq_fps;                        /* 0: 30 */
    int seq_width, seq_height;             /* 0: half the run's size a side (at least 32x18) */
    int rr_chunk;                          /* frames each setting is timed in its turn (0: 2) */
} bench_desc;

/* Measures and writes. Exit codes: 0 ok, 1 a scene, pack or output failed
 * (the rest is still measured and written), 2 the desc names a root,
 * scene or pack that is not there (the reason in why), 3 no OpenGL. */
int bench_run(const bench_desc *d, char *why, size_t whylen);

/* The `Define` a pack declares to expose its per-pixel buffers; what each
 * of its values writes is reference/ref_buffers.h's ref_output. */
#define BENCH_OUTPUT_DEFINE "TARN_OUTPUT"

/* The alpha a pack writes in its refraction-hit buffer where its march ran
 * out of steps before it found the ground (raymarch's MARCH_CAP); bench
 * reports the share of water pixels so. */
#define BENCH_MARCH_CAPPED 2.0f

#endif
