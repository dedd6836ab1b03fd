/* bench_int: the state `tarn bench` shares between its measuring parts
 * (bench.c and the files it names) and its writers (bench_csv.c,
 * bench_json.c, bench_report.c: CSV, JSON, Markdown, plots, the docs
 * section). Private to those files. */
#ifndef TARN_BENCH_INT_H
#define TARN_BENCH_INT_H

#include <stdbool.h>
#include <stdint.h>

#include "bench.h"
#include "bench_ocean.h"
#include "costmodel.h"
#include "gpu_timer.h"
#include "packset.h"
#include "ref_buffers.h"
#include "refcache.h"
#include "ref_metrics.h"
#include "render.h"
#include "strbuf.h"

#define MAX_SCENES BENCH_MAX_SCENES
#define MAX_TIMES BENCH_MAX_TIMES
#define PATH_LEN 2048

/* The Pareto front's time tolerance: two settings whose times differ by
 * less than BENCH_TIME_NOISE of their time (or their median's uncertainty,
 * the frames' (q3 - q1) / median over sqrt(frames), when larger) tie in
 * time. Measured on the 2-core VM: two runs of the same setting differ by
 * up to 15% in wall time on a quiet machine, but under other work by up to
 * 4x (0.39-3.99x over three pairs of runs beside other helpers' work, one
 * of each pair with two busy loops more); the CPU time (BENCH_AXIS_CPU, a
 * CPU rasteriser's axis) moved by 0.62-1.32x (docs/benchmark.md, "Timing
 * on a busy machine"). The error tolerance is each
 * setting's measured uncertainty (the reference's noise and grid bias,
 * bench_uncertainty); BENCH_ERROR_TIE of the error is the fallback where
 * it was not measured (--no-uncertainty). */
#define BENCH_TIME_NOISE 0.2
#define BENCH_ERROR_TIE 0.01

/* The cost model's sweep (bench_cost.c's measure_cost; bench_report.c's cost_md) */
#define COST_SAMPLES 9
extern const int BENCH_COST_MESHES[3];
extern const double BENCH_COST_SCALES[3];

/* The references a run uses besides the one of each frame */
enum {
    REFK_MAIN = 0,   /* the frame's reference (the run's quality) */
    REFK_SEQ,        /* a frame of the animated sequence */
    REFK_NOISE,      /* the same with photon seed 1 (ref_render_desc.seed): another photon sampling */
    REFK_GRID,       /* the same at twice the caustic grid's resolution */
    REFK_FLAT,       /* flat caustics (the sun through the mean plane): a pack's flat lighting */
    REFK_COUNT
};

typedef struct bench_opts {
    const char *scenes[MAX_SCENES];
    int nscenes;
    packset_name packs[PACKSET_MAX];
    int npacks;
    int w, h;
    double times[MAX_TIMES];
    int ntimes;
    int frames, warmup;
    double frame_budget;
    const char *out, *docs;
    int time_axis;               /* 0 auto, else BENCH_AXIS_* */
    refcache_opts ref;
    double heat_max;
    bool images, quiet;
    bool cost_model;             /* fit each pack's a + b·pixels + c·vertices */
    bool uncertainty;            /* measure the reference's noise and grid bias */
    int seq_frames;              /* the animated sequence: frames (0: none) */
    double seq_fps;
    int seq_w, seq_h;
    int rr_chunk;                /* frames a setting is timed before the next one's turn */
    int samples;                 /* MSAA as asked (render_desc.samples) */
    int samples_used;            /* ...and as this GL gives it (1: off) */
    bool spp_matched;            /* ref.spp follows samples_used (no --ref-spp) */
    int ref_photons, ref_caustic_res;   /* the reference's, resolved */
} bench_opts;

typedef struct row {             /* one scene, pack, setting and time */
    int scene, pack, setting, ti;
    bool ok;
    char error[MSG_MAX];
    char note[600];
    int frames;
    double gpu_ms, wall_ms, first_wall_ms;
    double cpu_ms;               /* the process's CPU time a frame (llvmpipe's threads are ours) */
    double gpu_q1, gpu_q3, wall_q1, wall_q3;   /* the timed frames' quartiles */
    double cpu_q1, cpu_q3;
    double water_rmse, water_psnr, off_rmse;   /* over the reference's water pixels / the rest */
    double water_flip, flip, water_ssim;       /* HDR-FLIP mean over water / the frame; SSIM over water */
    long water_px;
    double rmse, psnr, mae, p95, p99, max_abs, over_share;   /* the whole frame */
    double wall_spread;          /* the timed frames' wall time, (p75 - p25) / median */
    double cpu_spread, gpu_spread;   /* the same of their CPU and GPU times */
    double capped_share;         /* water pixels whose refraction march ran out (NaN: not shown) */
    long nan_px, inf_px;
    unsigned gl_error;
    bool has[REF_OUTPUT_COUNT];
    bool irr_flat;               /* irradiance: the pack shows none; its flat lighting measured */
    double comp_median[REF_OUTPUT_COUNT], comp_p95[REF_OUTPUT_COUNT], comp_mean[REF_OUTPUT_COUNT];
    double comp_rel_mean[REF_OUTPUT_COUNT];
    double comp_rel_median[REF_OUTPUT_COUNT];
    /* the first time's row only (NaN elsewhere): how far its water error
     * moves when the reference is another photon sampling / a grid twice as
     * fine */
    double u_noise_rmse, u_grid_rmse, u_noise_flip, u_grid_flip;
    /* the first time's row only (NaN elsewhere): the animated sequence
     * (bench_measure.c's measure_sequence) */
    double seq_water_rmse, seq_water_ssim, temporal_rmse, seq_ref_change, seq_pack_change;
    int seq_frames;
    int npasses;                 /* GPU time per pass (render_pass_times), medians */
    char pass_name[GPU_TIMER_MARKS][GPU_TIMER_NAME];
    double pass_ms[GPU_TIMER_MARKS];
} row;

typedef struct summary {         /* one scene, pack and setting, over the times */
    int scene, pack, setting;
    bool ok;
    double gpu_ms, wall_ms, cpu_ms, rmse, psnr, p95, over_share;
    double wall_q1, wall_q3, gpu_q1, gpu_q3, cpu_q1, cpu_q3;   /* medians over the times of the rows' quartiles */
    double water_rmse, water_psnr, off_rmse;   /* means over the times */
    double water_flip, flip, water_ssim;       /* means over the times */
    double wall_spread, cpu_spread, gpu_spread;   /* the largest of its rows' */
    int frames;                                /* the fewest timed frames of its rows */
    double capped_share;                       /* the largest of its rows' (NaN: not shown) */
    /* hit p95 (m), Fresnel MAE, irradiance relative error's median (the
     * mean is ruled by the few points the reference has almost no sun),
     * depth MAE (m) */
    double comp[REF_OUTPUT_COUNT];
    bool has[REF_OUTPUT_COUNT];
    bool irr_flat;
    /* uncertainty of the water RMSE and water FLIP: noise, grid bias, and
     * both in quadrature (NaN: not measured) */
    double u_noise_rmse, u_grid_rmse, u_rmse, u_noise_flip, u_grid_flip, u_flip;
    /* the animated sequence (NaN: not measured): water RMSE, mean over the
     * instants; the temporal error, RMS over water of the pack's frame-to-
     * frame change minus the reference's; the RMS of each's change */
    double seq_water_rmse, seq_water_ssim, temporal_rmse, seq_ref_change, seq_pack_change;
    int seq_frames;
    long nan_px;
    bool pareto;                 /* on the front of time against water RMSE */
    bool pareto_flip;            /* ...against water FLIP */
} summary;

typedef struct ref_entry {
    uint64_t key;
    int kind;                    /* REFK_* of whoever asked first */
    refcache_image im;
    bool tried, ok;
    double weight;               /* progress units: a render, or a read from the cache */
} ref_entry;

typedef struct progress {
    double start, total, done, last_draw;
    bool tty, quiet;
    char what[160];
} progress;

typedef struct bench {
    bench_opts o;
    char root[PATH_LEN];
    char ref_dir[PATH_LEN];      /* the reference cache (ref_cache_dir) */
    char scene_abs[MAX_SCENES][PATH_LEN];
    packset_bench pb[PACKSET_MAX];
    row *rows;
    int nrows;
    summary *sums;
    int nsums;
    ref_entry *refs;
    int nrefs;
    double floor_gpu, floor_wall, floor_cpu;
    char gl_renderer[256], gl_version[256], cpu[256];
    int cores;
    bool cpu_raster;
    int axis;                    /* resolved: BENCH_AXIS_* */
    double seconds;
    char started[64];
    double load_before[3], load_after[3];   /* /proc/loadavg: 1, 5, 15 min (NaN: unknown) */
    double seconds_timing, seconds_flip, seconds_seq;   /* where the run's time went */
    progress pr;
    int failures;
    int refs_rendered, refs_cached;              /* the frames' references */
    int extra_rendered[REFK_COUNT], extra_cached[REFK_COUNT];   /* the others, by kind */
    /* per pack: its default's cost model on the first scene (measure_cost) */
    cost_model cost[PACKSET_MAX];
    bool has_cost[PACKSET_MAX];
    char cost_note[PACKSET_MAX][200];
    /* the spectrum ocean's passes, when a scene has one (bench_ocean.h) */
    bench_ocean_costs ocean;
    char ocean_scene[256];
} bench;

/* Progress weights, roughly seconds on the 2-core machine: a load, and a
 * reference (photons: 35 s for the default 256-cell grid of 36 photons a
 * cell; pixels: 5 s for 480x270 at 1 sample; bench_refs.c). */
#define BENCH_LOAD_WEIGHT 3.0

/* A setting's timed frames at one time: medians, quartiles, spreads */
typedef struct timing {
    double gpu_ms, wall_ms, first_wall_ms, wall_spread, gpu_q1, gpu_q3, wall_q1, wall_q3;
    double cpu_ms, cpu_q1, cpu_q3, cpu_spread, gpu_spread;
    int frames;
} timing;

/* Collects this frame's GPU time per pass into per-name sample lists. */
typedef struct pass_samples {
    int n;
    char name[GPU_TIMER_MARKS][GPU_TIMER_NAME];
    double *ms[GPU_TIMER_MARKS];
    int count[GPU_TIMER_MARKS];
} pass_samples;

/* The timed frames of one setting at one time, gathered over its turns
 * (round-robin: a few frames a turn, bench_time_round_robin). */
typedef struct timer_acc {
    int max, n;
    double spent;                /* seconds of timed frames so far */
    double *gpu, *wall, *cpu;
    bool passes;
    pass_samples ps;
} timer_acc;

/* One frame's HDR-FLIP against its reference, run in parallel (bench_run_flip_jobs) */
typedef struct flip_job {
    const float *test;           /* 4 channels (RGBA) */
    const float *ref;            /* 3 */
    const float *classes;        /* the reference's REF_MASK_* */
    int w, h;
    double water, frame;         /* out: the mean over water, over the frame (NaN: failed) */
} flip_job;

/* One setting, kept alive while its scene is timed (bench_measure.c) */
typedef struct slot {
    int s, p, k;
    char wp[PATH_LEN];
    const char *scene;           /* the scene or its wrapper (wp) */
    render *r;
    render_target tg;
    bool live;
    int first_row;
    timer_acc acc[MAX_TIMES];
} slot;

/* helpers every part uses (bench.c) */
void bench_stem(const char *path, char *out, size_t len);
bool bench_write_text(const char *path, const char *text);
bool bench_write_strbuf(const char *path, strbuf *text);   /* and frees text */
const char *bench_setting_name(const bench *b, int pack, int setting);

/* the time axis (bench_summary.c) */
double bench_axis_time(const bench *b, const summary *s);
double bench_axis_floor(const bench *b);           /* the cost floor's time on the axis */
double bench_axis_spread(const bench *b, const summary *s);   /* its frames' (q3 - q1) / median */
const char *bench_axis_name(const bench *b);       /* "gpu", "wall" or "cpu" */

/* the measuring, part by part */
/* bench.c */
double bench_median(double *v, int n);
void bench_fmt(char *out, size_t len, const char *f, ...);
bool bench_mkdirs(const char *dir);
void bench_first_line(const char *text, char *out, size_t len);

/* bench_progress.c */
void bench_progress_draw(progress *p, bool force);
void bench_progress_set(progress *p, double done, bool force, const char *fmt, ...);

/* bench_refs.c */
const char *bench_wrapper_path(bench *b, int s, int p, int k, char *out, size_t len);
double bench_seq_time(const bench *b, int i);
void bench_prepare_refs(bench *b);
double bench_ref_total_weight(bench *b);
ref_entry *bench_get_ref_at(bench *b, int s, const char *scene, int kind, int w, int h, double t);
ref_entry *bench_get_ref(bench *b, int s, const char *scene, int ti);

/* bench_timing.c */
double bench_axis_ms(const bench *b, const timing *t);
void bench_acc_init(timer_acc *a, int max, bool passes);
double bench_warm_up(bench *b, render *r, const render_target *tg, double t);
timing bench_time_frames(bench *b, render *r, const render_target *tg, double t, row *rw);
void bench_time_round_robin(bench *b, slot *sl, int n, double weight_each_time);
bool bench_measure_floor(bench *b);

/* bench_error.c */
void bench_write_images(bench *b, const row *rw, const float *rgba, const ref_entry *ref);
void bench_measure_water(bench *b, row *rw, const ref_fimage *A, const ref_fimage *B, const float *classes);
void bench_measure_buffers(bench *b, render *r, const render_target *tg, int s, int p, const char *scene,
                           int first_row, float *rgba);
void bench_run_flip_jobs(bench *b, flip_job *jobs, int n);
double bench_water_ssim(const float *rgba, const refcache_image *ref, int w, int h);
double bench_water_rmse_of(const float *rgba, const refcache_image *ref, int w, int h);
void bench_measure_flat_irradiance(bench *b, row *rw, const ref_entry *flat, const ref_entry *ref);

/* bench_measure.c */
void bench_measure_scene(bench *b, int s, double weight_each_time);

/* bench_cost.c */
void bench_measure_cost(bench *b, int p);
void bench_measure_ocean(bench *b);

/* bench_summary.c */
void bench_summarise(bench *b);

/* the writers: bench.csv and passes.csv (bench_csv.c), bench.json
 * (bench_json.c); report.md, the plots, and --docs (bench_report.c), which
 * writes them all. False when a file could not be written. The Markdown
 * report goes to md too (for stdout). */
bool bench_write_csv(bench *b, const char *path);
bool bench_write_passes_csv(bench *b, const char *path);
bool bench_write_json(bench *b, const char *path);
bool bench_write_results(bench *b, strbuf *md);

#endif
