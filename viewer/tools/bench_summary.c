/* bench_summary: `tarn bench`'s summaries (bench_int.h): a scene, pack and
 * setting over its times, each on the run's time axis, and the Pareto
 * fronts of time against water RMSE and against water FLIP. */
#include "util.h"
#include "bench_int.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"
#include "plot.h"

double bench_axis_time(const bench *b, const summary *s) {
    return b->axis == BENCH_AXIS_GPU ? s->gpu_ms : b->axis == BENCH_AXIS_CPU ? s->cpu_ms : s->wall_ms;
}

double bench_axis_floor(const bench *b) {
    return b->axis == BENCH_AXIS_GPU ? b->floor_gpu : b->axis == BENCH_AXIS_CPU ? b->floor_cpu : b->floor_wall;
}

double bench_axis_spread(const bench *b, const summary *s) {
    return b->axis == BENCH_AXIS_GPU ? s->gpu_spread : b->axis == BENCH_AXIS_CPU ? s->cpu_spread : s->wall_spread;
}

const char *bench_axis_name(const bench *b) {
    return b->axis == BENCH_AXIS_GPU ? "gpu" : b->axis == BENCH_AXIS_CPU ? "cpu" : "wall";
}

static double mean_of(const double *v, int n) {
    double sum = 0;
    int k = 0;
    for (int i = 0; i < n; i++)
        if (isfinite(v[i])) { sum += v[i]; k++; }
    return k ? sum / k : NAN;
}

/* A setting's rows over its times, gathered for their medians and means. */
typedef struct gathered {
    double gpu[MAX_TIMES], wall[MAX_TIMES], cpu[MAX_TIMES], q[6][MAX_TIMES];
    double wflip[MAX_TIMES], flip[MAX_TIMES], wssim[MAX_TIMES];
    int ng, nw, nc, ne, nq, nt, nw_err;
    double rmse, psnr, p95, share, wrmse, wpsnr, off;
    double comp[REF_OUTPUT_COUNT];
    int ncomp[REF_OUTPUT_COUNT];
} gathered;

/* One time's row into g, and into s what is the worst or the least over
 * the times (ok, frames, bad pixels, spreads, the capped share). */
static void gather_row(const row *r, gathered *g, summary *s) {
    s->ok &= r->ok;
    if (r->frames > 0 && (s->frames == 0 || r->frames < s->frames)) s->frames = r->frames;
    s->nan_px += r->nan_px + r->inf_px;
    if (isfinite(r->gpu_ms)) g->gpu[g->ng++] = r->gpu_ms;
    if (isfinite(r->wall_ms)) g->wall[g->nw++] = r->wall_ms;
    if (isfinite(r->cpu_ms)) g->cpu[g->nc++] = r->cpu_ms;
    if (isfinite(r->wall_ms)) {
        const double qs[6] = { r->wall_q1, r->wall_q3, r->gpu_q1, r->gpu_q3, r->cpu_q1, r->cpu_q3 };
        for (int m = 0; m < 6; m++) g->q[m][g->nq] = qs[m];
        g->nq++;
    }
    g->wflip[g->nt] = r->water_flip;
    g->flip[g->nt] = r->flip;
    g->wssim[g->nt++] = r->water_ssim;
    if (isfinite(r->wall_spread) && r->wall_spread > s->wall_spread) s->wall_spread = r->wall_spread;
    if (isfinite(r->cpu_spread) && r->cpu_spread > s->cpu_spread) s->cpu_spread = r->cpu_spread;
    if (isfinite(r->gpu_spread) && r->gpu_spread > s->gpu_spread) s->gpu_spread = r->gpu_spread;
    if (isfinite(r->capped_share) && !(r->capped_share <= s->capped_share)) s->capped_share = r->capped_share;
    if (isfinite(r->water_rmse)) {
        g->wrmse += r->water_rmse;
        g->wpsnr += isfinite(r->water_psnr) ? r->water_psnr : 99;
        g->off += isfinite(r->off_rmse) ? r->off_rmse : 0;
        g->nw_err++;
    }
    if (isfinite(r->rmse)) {
        g->rmse += r->rmse;
        g->psnr += isfinite(r->psnr) ? r->psnr : 99;
        g->p95 += r->p95;
        g->share += r->over_share;
        g->ne++;
    }
    for (int m = 1; m < REF_OUTPUT_COUNT; m++)
        if (r->has[m]) {
            g->comp[m] += m == REF_OUTPUT_REFRACT_HIT ? r->comp_p95[m]
                          : m == REF_OUTPUT_IRRADIANCE ? r->comp_rel_median[m] : r->comp_mean[m];
            g->ncomp[m]++;
            if (m == REF_OUTPUT_IRRADIANCE) s->irr_flat |= r->irr_flat;
        }
}

/* The times' medians (and their quartiles' medians, over the finite ones). */
static void finish_times(gathered *g, summary *s) {
    s->gpu_ms = bench_median(g->gpu, g->ng);
    s->wall_ms = bench_median(g->wall, g->nw);
    s->cpu_ms = bench_median(g->cpu, g->nc);
    s->wall_q1 = bench_median(g->q[0], g->nq);
    s->wall_q3 = bench_median(g->q[1], g->nq);
    int kq[6] = { 0 };
    for (int m = 2; m < 6; m++)
        for (int j = 0; j < g->nq; j++)
            if (isfinite(g->q[m][j])) g->q[m][kq[m]++] = g->q[m][j];
    s->gpu_q1 = bench_median(g->q[2], kq[2]);
    s->gpu_q3 = bench_median(g->q[3], kq[3]);
    s->cpu_q1 = bench_median(g->q[4], kq[4]);
    s->cpu_q3 = bench_median(g->q[5], kq[5]);
}

/* The errors' means over the times that measured them. */
static void finish_errors(const gathered *g, summary *s) {
    s->rmse = g->ne ? g->rmse / g->ne : NAN;
    s->water_rmse = g->nw_err ? g->wrmse / g->nw_err : NAN;
    s->water_psnr = g->nw_err ? g->wpsnr / g->nw_err : NAN;
    s->off_rmse = g->nw_err ? g->off / g->nw_err : NAN;
    s->water_flip = mean_of(g->wflip, g->nt);
    s->flip = mean_of(g->flip, g->nt);
    s->water_ssim = mean_of(g->wssim, g->nt);
    s->psnr = g->ne ? g->psnr / g->ne : NAN;
    s->p95 = g->ne ? g->p95 / g->ne : NAN;
    s->over_share = g->ne ? g->share / g->ne : NAN;
    for (int m = 1; m < REF_OUTPUT_COUNT; m++) {
        s->has[m] = g->ncomp[m] > 0;
        s->comp[m] = g->ncomp[m] ? g->comp[m] / g->ncomp[m] : NAN;
    }
}

/* The uncertainty and the sequence: measured at the first time only. */
static void copy_first_time(const row *r0, summary *s) {
    s->u_noise_rmse = r0->u_noise_rmse;
    s->u_grid_rmse = r0->u_grid_rmse;
    s->u_noise_flip = r0->u_noise_flip;
    s->u_grid_flip = r0->u_grid_flip;
    s->u_rmse = hypot(r0->u_noise_rmse, r0->u_grid_rmse);
    s->u_flip = hypot(r0->u_noise_flip, r0->u_grid_flip);
    s->seq_frames = r0->seq_frames;
    s->seq_water_rmse = r0->seq_water_rmse;
    s->seq_water_ssim = r0->seq_water_ssim;
    s->temporal_rmse = r0->temporal_rmse;
    s->seq_ref_change = r0->seq_ref_change;
    s->seq_pack_change = r0->seq_pack_change;
}

/* The setting whose first time's row is rows[i], over its times. */
static void summarise_setting(const bench *b, int i, summary *s) {
    const row *r0 = &b->rows[i];
    s->scene = r0->scene;
    s->pack = r0->pack;
    s->setting = r0->setting;
    s->capped_share = NAN;
    s->wall_spread = s->cpu_spread = s->gpu_spread = 0;
    s->ok = true;
    gathered g = { .ng = 0 };
    for (int j = i; j < b->nrows && j < i + b->o.ntimes; j++) gather_row(&b->rows[j], &g, s);
    finish_times(&g, s);
    finish_errors(&g, s);
    copy_first_time(r0, s);
}

/* The Pareto front of one scene, over every pack: time against the water
 * RMSE (metric 0), or against the water FLIP (1). */
static void mark_front(bench *b, int sc, int metric) {
    /* zeroed: GCC cannot see the loop fill them before the call */
    double x[1024] = { 0 }, y[1024] = { 0 }, dx[1024] = { 0 }, dy[1024] = { 0 };
    bool on[1024];
    int idx[1024], n = 0;
    for (int i = 0; i < b->nsums && n < 1024; i++) {
        const summary *si = &b->sums[i];
        if (si->scene != sc) continue;
        x[n] = si->ok ? bench_axis_time(b, si) : NAN;
        double u = metric == 0 ? si->u_rmse : si->u_flip;
        y[n] = metric == 0 ? (isfinite(si->water_rmse) ? si->water_rmse : si->rmse)
                           : (isfinite(si->water_flip) ? si->water_flip : si->flip);
        /* what a second run could move: the time by its median's own
         * uncertainty, the frames' spread over sqrt(frames) (for normal
         * noise the median's standard error is 0.93 IQR / sqrt(n)), at
         * least BENCH_TIME_NOISE: runs on a shared machine differ more
         * than frames within one run. (The frames' spread itself, as until
         * issue 26, let one noisy setting tie in time with, and so take off
         * the front, settings up to 6.7 times faster: raymarch iter-20,
         * 27.6 ms of CPU, spread 0.88, took basic mesh-64, 4.1 ms, off.)
         * What another reference could move: the error by its measured
         * uncertainty (BENCH_ERROR_TIE of it where not measured) */
        double spread = bench_axis_spread(b, si);
        double se = isfinite(spread) && si->frames > 0 ? spread / sqrt((double)si->frames) : 0;
        dx[n] = x[n] * fmax(BENCH_TIME_NOISE, se);
        dy[n] = fmax(isfinite(u) ? u : y[n] * BENCH_ERROR_TIE, 1e-5);
        idx[n++] = i;
    }
    plot_pareto_combined(x, y, dx, dy, n, on);
    for (int i = 0; i < n; i++) {
        if (metric == 0) b->sums[idx[i]].pareto = on[i];
        else b->sums[idx[i]].pareto_flip = on[i];
    }
}

void bench_summarise(bench *b) {
    b->sums = mem_zalloc((size_t)(b->nrows > 0 ? b->nrows : 1) * sizeof *b->sums);
    for (int i = 0; i < b->nrows; i++)
        if (b->rows[i].ti == 0) summarise_setting(b, i, &b->sums[b->nsums++]);
    for (int sc = 0; sc < b->o.nscenes; sc++)
        for (int metric = 0; metric < 2; metric++) mark_front(b, sc, metric);
}
