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

void bench_summarise(bench *b) {
    b->sums = mem_zalloc((size_t)(b->nrows > 0 ? b->nrows : 1) * sizeof *b->sums);
    for (int i = 0; i < b->nrows; i++) {
        const row *r0 = &b->rows[i];
        if (r0->ti != 0) continue;
        summary *s = &b->sums[b->nsums++];
        s->scene = r0->scene;
        s->pack = r0->pack;
        s->setting = r0->setting;
        double gpu[MAX_TIMES], wall[MAX_TIMES], cpu[MAX_TIMES], q[6][MAX_TIMES];
        double wflip[MAX_TIMES], flip[MAX_TIMES], wssim[MAX_TIMES];
        int ng = 0, nw = 0, nc = 0, ne = 0, nq = 0, nt = 0;
        double rmse = 0, psnr = 0, p95 = 0, share = 0, wrmse = 0, wpsnr = 0, off = 0;
        s->capped_share = NAN;
        int nw_err = 0;
        s->wall_spread = s->cpu_spread = s->gpu_spread = 0;
        double comp[REF_OUTPUT_COUNT] = { 0 };
        int ncomp[REF_OUTPUT_COUNT] = { 0 };
        s->ok = true;
        for (int j = i; j < b->nrows && j < i + b->o.ntimes; j++) {
            const row *r = &b->rows[j];
            s->ok &= r->ok;
            if (r->frames > 0 && (s->frames == 0 || r->frames < s->frames)) s->frames = r->frames;
            s->nan_px += r->nan_px + r->inf_px;
            if (isfinite(r->gpu_ms)) gpu[ng++] = r->gpu_ms;
            if (isfinite(r->wall_ms)) wall[nw++] = r->wall_ms;
            if (isfinite(r->cpu_ms)) cpu[nc++] = r->cpu_ms;
            if (isfinite(r->wall_ms)) {
                q[0][nq] = r->wall_q1;
                q[1][nq] = r->wall_q3;
                q[2][nq] = r->gpu_q1;
                q[3][nq] = r->gpu_q3;
                q[4][nq] = r->cpu_q1;
                q[5][nq] = r->cpu_q3;
                nq++;
            }
            wflip[nt] = r->water_flip;
            flip[nt] = r->flip;
            wssim[nt++] = r->water_ssim;
            if (isfinite(r->wall_spread) && r->wall_spread > s->wall_spread) s->wall_spread = r->wall_spread;
            if (isfinite(r->cpu_spread) && r->cpu_spread > s->cpu_spread) s->cpu_spread = r->cpu_spread;
            if (isfinite(r->gpu_spread) && r->gpu_spread > s->gpu_spread) s->gpu_spread = r->gpu_spread;
            if (isfinite(r->capped_share) && !(r->capped_share <= s->capped_share)) s->capped_share = r->capped_share;
            if (isfinite(r->water_rmse)) {
                wrmse += r->water_rmse;
                wpsnr += isfinite(r->water_psnr) ? r->water_psnr : 99;
                off += isfinite(r->off_rmse) ? r->off_rmse : 0;
                nw_err++;
            }
            if (isfinite(r->rmse)) {
                rmse += r->rmse;
                psnr += isfinite(r->psnr) ? r->psnr : 99;
                p95 += r->p95;
                share += r->over_share;
                ne++;
            }
            for (int m = 1; m < REF_OUTPUT_COUNT; m++)
                if (r->has[m]) {
                    comp[m] += m == REF_OUTPUT_REFRACT_HIT ? r->comp_p95[m]
                               : m == REF_OUTPUT_IRRADIANCE ? r->comp_rel_median[m] : r->comp_mean[m];
                    ncomp[m]++;
                    if (m == REF_OUTPUT_IRRADIANCE) s->irr_flat |= r->irr_flat;
                }
        }
        s->gpu_ms = bench_median(gpu, ng);
        s->wall_ms = bench_median(wall, nw);
        s->cpu_ms = bench_median(cpu, nc);
        s->wall_q1 = bench_median(q[0], nq);
        s->wall_q3 = bench_median(q[1], nq);
        int kq[6] = { 0 };
        for (int m = 2; m < 6; m++)
            for (int j = 0; j < nq; j++)
                if (isfinite(q[m][j])) q[m][kq[m]++] = q[m][j];
        s->gpu_q1 = bench_median(q[2], kq[2]);
        s->gpu_q3 = bench_median(q[3], kq[3]);
        s->cpu_q1 = bench_median(q[4], kq[4]);
        s->cpu_q3 = bench_median(q[5], kq[5]);
        s->rmse = ne ? rmse / ne : NAN;
        s->water_rmse = nw_err ? wrmse / nw_err : NAN;
        s->water_psnr = nw_err ? wpsnr / nw_err : NAN;
        s->off_rmse = nw_err ? off / nw_err : NAN;
        s->water_flip = mean_of(wflip, nt);
        s->flip = mean_of(flip, nt);
        s->water_ssim = mean_of(wssim, nt);
        s->psnr = ne ? psnr / ne : NAN;
        s->p95 = ne ? p95 / ne : NAN;
        s->over_share = ne ? share / ne : NAN;
        for (int m = 1; m < REF_OUTPUT_COUNT; m++) {
            s->has[m] = ncomp[m] > 0;
            s->comp[m] = ncomp[m] ? comp[m] / ncomp[m] : NAN;
        }
        /* the uncertainty and the sequence: the first time's row */
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
    /* the Pareto fronts of each scene, over every pack: time against the
     * water RMSE, and against the water FLIP */
    for (int sc = 0; sc < b->o.nscenes; sc++)
        for (int metric = 0; metric < 2; metric++) {
            double x[1024], y[1024], dx[1024], dy[1024];
            bool on[1024];
            int idx[1024], n = 0;
            for (int i = 0; i < b->nsums && n < 1024; i++) {
                const summary *si = &b->sums[i];
                if (si->scene != sc) continue;
                x[n] = si->ok ? bench_axis_time(b, si) : NAN;
                double u = metric == 0 ? si->u_rmse : si->u_flip;
                y[n] = metric == 0 ? (isfinite(si->water_rmse) ? si->water_rmse : si->rmse)
                                   : (isfinite(si->water_flip) ? si->water_flip : si->flip);
                /* what a second run could move: the time by its median's
                 * own uncertainty, the frames' spread over sqrt(frames)
                 * (for normal noise the median's standard error is 0.93
                 * IQR / sqrt(n)), at least BENCH_TIME_NOISE: runs on a
                 * shared machine differ more than frames within one run.
                 * (The frames' spread itself, as until issue 26, let one
                 * noisy setting tie in time with, and so take off the
                 * front, settings up to 6.7 times faster: raymarch iter-20,
                 * 27.6 ms of CPU, spread 0.88, took basic mesh-64, 4.1 ms,
                 * off.) What another
                 * reference could move: the error by its measured
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
}
