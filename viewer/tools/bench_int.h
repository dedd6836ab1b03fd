/* bench_int: the state `tarn bench` shares between its measuring half
 * (bench.c) and its writers (bench_report.c: CSV, JSON, Markdown, plots,
 * the docs section). Private to those two files. */
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

/* The cost model's sweep (bench.c's measure_cost; bench_report.c's cost_md) */
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
    char error[600];
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
     * (bench.c's measure_sequence) */
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

/* helpers both halves use (bench.c) */
void bench_stem(const char *path, char *out, size_t len);
bool bench_write_text(const char *path, const char *text);
double bench_axis_time(const bench *b, const summary *s);
double bench_axis_floor(const bench *b);           /* the cost floor's time on the axis */
double bench_axis_spread(const bench *b, const summary *s);   /* its frames' (q3 - q1) / median */
const char *bench_axis_name(const bench *b);       /* "gpu", "wall" or "cpu" */
const char *bench_setting_name(const bench *b, int pack, int setting);

/* the writers (bench_report.c): bench.csv, passes.csv, bench.json,
 * report.md, the plots, and --docs. False when a file could not be
 * written. The Markdown report goes to md too (for stdout). */
bool bench_write_results(bench *b, strbuf *md);

#endif
