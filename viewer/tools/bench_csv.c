/* bench_csv: `tarn bench`'s tables for spreadsheets (bench_int.h):
 * bench.csv, a row per scene, pack, setting and time with every figure,
 * and passes.csv, a row per pass of each. */
#include "bench_int.h"
#include "datafmt.h"

#include <math.h>
#include <stdlib.h>

/* A number after a comma: empty when not measured (NaN). */
static void csv_num(strbuf *o, double v) {
    strbuf_puts(o, ",");
    csv_put_num(o, v);
}

/* A name, quoted (a spreadsheet keeps "1e3" a name), after a comma but the first. */
static void csv_str(strbuf *o, const char *s, bool first) {
    if (!first) strbuf_puts(o, ",");
    csv_put_str(o, s, true);
}

/* The first columns of a row: scene, pack, setting, time. */
static void csv_setting(strbuf *o, const bench *b, const row *r) {
    char sc[256];
    bench_stem(b->scene_abs[r->scene], sc, sizeof sc);
    csv_str(o, sc, true);
    csv_str(o, b->o.packs[r->pack], false);
    csv_str(o, b->pb[r->pack].settings[r->setting].name, false);
    csv_num(o, b->o.times[r->ti]);
}

static void csv_header(strbuf *o) {
    strbuf_printf(o, "scene,pack,setting,time_s,width,height,frames,gpu_ms,wall_ms,first_frame_wall_ms,"
                  "floor_gpu_ms,floor_wall_ms,x_floor_gpu,x_floor_wall,water_rmse,water_psnr_db,water_pixels,"
                  "off_water_rmse,march_capped_share,rmse,psnr_db,mae,error_p95,error_p99,"
                  "max_abs,over_threshold_share,nan_pixels,inf_pixels,gl_error,"
                  "water_flip,flip,water_ssim,gpu_q1_ms,gpu_q3_ms,wall_q1_ms,wall_q3_ms,"
                  "cpu_ms,cpu_q1_ms,cpu_q3_ms,floor_cpu_ms,x_floor_cpu,gpu_spread,wall_spread,cpu_spread,"
                  "water_rmse_u_noise,water_rmse_u_grid,water_flip_u_noise,water_flip_u_grid,"
                  "seq_frames,seq_water_rmse,seq_water_ssim,temporal_rmse,seq_ref_change_rms,seq_pack_change_rms,"
                  "irradiance_flat");
    for (int m = 1; m < REF_OUTPUT_COUNT; m++) {
        const char *n = ref_buffer_for_output(m)->name;
        strbuf_printf(o, ",%s.median,%s.p95,%s.mean,%s.rel_mean,%s.rel_median", n, n, n, n, n);
    }
    strbuf_printf(o, ",error,note\n");
}

/* From the frame count to the whole frame's error. */
static void csv_time_and_error(strbuf *o, const bench *b, const row *r) {
    strbuf_printf(o, ",%d,%d,%d", b->o.w, b->o.h, r->frames);
    const double before_px[] = {
        r->gpu_ms, r->wall_ms, r->first_wall_ms, b->floor_gpu, b->floor_wall,
        r->gpu_ms / b->floor_gpu, r->wall_ms / b->floor_wall, r->water_rmse, r->water_psnr,
    };
    for (size_t k = 0; k < sizeof before_px / sizeof before_px[0]; k++) csv_num(o, before_px[k]);
    strbuf_printf(o, ",%ld", r->water_px);
    const double after_px[] = {
        r->off_rmse, r->capped_share, r->rmse, r->psnr, r->mae, r->p95, r->p99, r->max_abs, r->over_share,
    };
    for (size_t k = 0; k < sizeof after_px / sizeof after_px[0]; k++) csv_num(o, after_px[k]);
    strbuf_printf(o, ",%ld,%ld,%u", r->nan_px, r->inf_px, r->gl_error);
}

/* FLIP and SSIM, the quartiles, the CPU time, the spreads, the uncertainty,
 * the sequence, and each buffer's error. */
static void csv_more(strbuf *o, const bench *b, const row *r) {
    const double more[] = {
        r->water_flip, r->flip, r->water_ssim, r->gpu_q1, r->gpu_q3, r->wall_q1, r->wall_q3,
        r->cpu_ms, r->cpu_q1, r->cpu_q3, b->floor_cpu, r->cpu_ms / b->floor_cpu,
        r->gpu_spread, r->wall_spread, r->cpu_spread,
        r->u_noise_rmse, r->u_grid_rmse, r->u_noise_flip, r->u_grid_flip,
    };
    for (size_t k = 0; k < sizeof more / sizeof more[0]; k++) csv_num(o, more[k]);
    strbuf_printf(o, ",%d", r->seq_frames);
    const double seq[] = {
        r->seq_water_rmse, r->seq_water_ssim, r->temporal_rmse, r->seq_ref_change, r->seq_pack_change,
    };
    for (size_t k = 0; k < sizeof seq / sizeof seq[0]; k++) csv_num(o, seq[k]);
    strbuf_printf(o, ",%d", r->irr_flat ? 1 : 0);
    for (int m = 1; m < REF_OUTPUT_COUNT; m++) {
        csv_num(o, r->has[m] ? r->comp_median[m] : NAN);
        csv_num(o, r->has[m] ? r->comp_p95[m] : NAN);
        csv_num(o, r->has[m] ? r->comp_mean[m] : NAN);
        csv_num(o, r->has[m] ? r->comp_rel_mean[m] : NAN);
        csv_num(o, r->has[m] ? r->comp_rel_median[m] : NAN);
    }
}

bool bench_write_csv(bench *b, const char *path) {
    strbuf o = { 0 };
    csv_header(&o);
    for (int i = 0; i < b->nrows; i++) {
        const row *r = &b->rows[i];
        csv_setting(&o, b, r);
        csv_time_and_error(&o, b, r);
        csv_more(&o, b, r);
        csv_str(&o, r->error, false);
        csv_str(&o, r->note, false);
        strbuf_printf(&o, "\n");
    }
    return bench_write_strbuf(path, &o);
}

/* One row per pass: scene, pack, setting, time, pass, its median GPU time. */
bool bench_write_passes_csv(bench *b, const char *path) {
    strbuf o = { 0 };
    strbuf_printf(&o, "scene,pack,setting,time_s,pass,gpu_ms\n");
    for (int i = 0; i < b->nrows; i++) {
        const row *r = &b->rows[i];
        for (int k = 0; k < r->npasses; k++) {
            csv_setting(&o, b, r);
            csv_str(&o, r->pass_name[k], false);
            csv_num(&o, r->pass_ms[k]);
            strbuf_printf(&o, "\n");
        }
    }
    return bench_write_strbuf(path, &o);
}
