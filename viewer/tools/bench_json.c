/* bench_json: `tarn bench`'s bench.json (bench_int.h): the machine, the
 * run, the cost floor, a summary per scene, pack and setting, a row per
 * time with its buffers and passes, and the cost models; one function a
 * section. */
#include "bench_int.h"
#include "datafmt.h"

#include <math.h>
#include <stdlib.h>

#include "ref_flip.h"


/* `, "key": number` */
static void json_key_num(strbuf *o, const char *key, double v) {
    strbuf_printf(o, ", \"%s\": ", key);
    json_put_num(o, v);
}

typedef struct json_field { const char *k; double v; } json_field;

static void json_fields(strbuf *o, const json_field *f, size_t n) {
    for (size_t k = 0; k < n; k++) json_key_num(o, f[k].k, f[k].v);
}

/* `[a, b, c]` */
static void json_nums3(strbuf *o, const double v[3]) {
    strbuf_printf(o, "[");
    for (int k = 0; k < 3; k++) {
        strbuf_printf(o, k ? ", " : "");
        json_put_num(o, v[k]);
    }
    strbuf_printf(o, "]");
}

static void json_machine(strbuf *o, const bench *b) {
    strbuf_printf(o, "  \"machine\": {\"cpu\": ");
    json_put_str(o, b->cpu);
    strbuf_printf(o, ", \"cores\": %d, \"gl_renderer\": ", b->cores);
    json_put_str(o, b->gl_renderer);
    strbuf_printf(o, ", \"gl_version\": ");
    json_put_str(o, b->gl_version);
    strbuf_printf(o, ", \"cpu_rasteriser\": %s},\n", b->cpu_raster ? "true" : "false");
}

/* The run: its times, frames, references, load, where its time went, the
 * sequence and the reference's quality. */
static void json_run(strbuf *o, const bench *b) {
    strbuf_printf(o, "  \"run\": {\"started\": \"%s\", \"seconds\": %.1f, \"width\": %d, \"height\": %d, \"times\": [",
              b->started, b->seconds, b->o.w, b->o.h);
    for (int i = 0; i < b->o.ntimes; i++) strbuf_printf(o, "%s%.9g", i ? ", " : "", b->o.times[i]);
    strbuf_printf(o, "], \"max_frames\": %d, \"frame_budget_s\": %g, \"warmup\": %d, \"time_axis\": \"%s\", "
                  "\"references_rendered\": %d, \"references_cached\": %d, ",
              b->o.frames, b->o.frame_budget, b->o.warmup, bench_axis_name(b), b->refs_rendered,
              b->refs_cached);
    static const char *const kinds[REFK_COUNT] = { "frame", "sequence", "noise", "grid", "flat" };
    strbuf_printf(o, "\"other_references\": {");
    for (int k = 1; k < REFK_COUNT; k++)
        strbuf_printf(o, "%s\"%s\": {\"rendered\": %d, \"cached\": %d}", k > 1 ? ", " : "", kinds[k],
                      b->extra_rendered[k], b->extra_cached[k]);
    strbuf_printf(o, "}, \"timing\": \"round-robin\", \"round_robin_frames\": %d, \"load_before\": ",
                  b->o.rr_chunk);
    json_nums3(o, b->load_before);
    strbuf_printf(o, ", \"load_after\": ");
    json_nums3(o, b->load_after);
    strbuf_printf(o, ", \"seconds_timing\": %.1f, \"seconds_flip\": %.1f, \"seconds_sequence\": %.1f, "
                  "\"flip\": \"HDR\", \"flip_ppd\": %.4f, \"sequence\": {\"frames\": %d, \"fps\": %g, "
                  "\"width\": %d, \"height\": %d, \"start_s\": %.9g}, \"uncertainty\": %s, "
                  "\"reference_photons\": %d, \"reference_caustic_res\": %d, \"reference_seed\": %llu, "
                  "\"noise_reference_seed\": %llu},\n",
                  b->seconds_timing, b->seconds_flip, b->seconds_seq, REF_FLIP_PPD, b->o.seq_frames, b->o.seq_fps,
                  b->o.seq_w, b->o.seq_h, b->o.times[0], b->o.uncertainty ? "true" : "false", b->o.ref_photons,
                  b->o.ref_caustic_res, (unsigned long long)b->o.ref.seed, (unsigned long long)b->o.ref.seed + 1);
}

/* MSAA, and the reference's samples a pixel */
static void json_sampling(strbuf *o, const bench *b) {
    strbuf_printf(o, "  \"msaa\": %d, \"reference_spp\": %d, \"reference_positions\": [", b->o.samples_used,
                  b->o.ref.spp);
    for (int k = 0; k < b->o.ref.nsamples; k++)
        strbuf_printf(o, "%s[%.9g, %.9g]", k ? ", " : "", b->o.ref.samples[k][0], b->o.ref.samples[k][1]);
    strbuf_printf(o, "],\n");
}

static void json_floor(strbuf *o, const bench *b) {
    strbuf_printf(o, "  \"floor\": {\"gpu_ms\": ");
    json_put_num(o, b->floor_gpu);
    json_key_num(o, "wall_ms", b->floor_wall);
    json_key_num(o, "cpu_ms", b->floor_cpu);
    strbuf_printf(o, "},\n");
}

/* `{"scene": "lake", "pack": "natural", "setting": "default"` */
static void json_setting(strbuf *o, const bench *b, int scene, int pack, int setting) {
    char sc[256];
    bench_stem(b->scene_abs[scene], sc, sizeof sc);
    strbuf_printf(o, "    {\"scene\": ");
    json_put_str(o, sc);
    strbuf_printf(o, ", \"pack\": ");
    json_put_str(o, b->o.packs[pack]);
    strbuf_printf(o, ", \"setting\": ");
    json_put_str(o, b->pb[pack].settings[setting].name);
}

/* One scene, pack and setting over the times. */
static void json_summary(strbuf *o, const bench *b, const summary *s, bool last) {
    json_setting(o, b, s->scene, s->pack, s->setting);
    strbuf_printf(o, ", \"ok\": %s", s->ok ? "true" : "false");
    const json_field fig[] = {
        { "gpu_ms", s->gpu_ms }, { "wall_ms", s->wall_ms }, { "x_floor_gpu", s->gpu_ms / b->floor_gpu },
        { "x_floor_wall", s->wall_ms / b->floor_wall }, { "cpu_ms", s->cpu_ms },
        { "x_floor_cpu", s->cpu_ms / b->floor_cpu }, { "water_rmse", s->water_rmse },
        { "water_psnr_db", s->water_psnr }, { "off_water_rmse", s->off_rmse },
        { "march_capped_share", s->capped_share }, { "rmse", s->rmse }, { "psnr_db", s->psnr },
        { "error_p95", s->p95 }, { "over_threshold_share", s->over_share },
        { "refract_hit_p95_m", s->has[1] ? s->comp[1] : NAN }, { "fresnel_mae", s->has[2] ? s->comp[2] : NAN },
        { "irradiance_rel_median", s->has[3] ? s->comp[3] : NAN }, { "depth_mae", s->has[4] ? s->comp[4] : NAN },
    };
    json_fields(o, fig, sizeof fig / sizeof fig[0]);
    strbuf_printf(o, ", \"irradiance_flat\": %s", s->irr_flat ? "true" : "false");
    const json_field more[] = {
        { "water_flip", s->water_flip }, { "flip", s->flip }, { "water_ssim", s->water_ssim },
        { "water_rmse_u", s->u_rmse }, { "water_rmse_u_noise", s->u_noise_rmse },
        { "water_rmse_u_grid", s->u_grid_rmse }, { "water_flip_u", s->u_flip },
        { "water_flip_u_noise", s->u_noise_flip }, { "water_flip_u_grid", s->u_grid_flip },
        { "gpu_q1_ms", s->gpu_q1 }, { "gpu_q3_ms", s->gpu_q3 }, { "wall_q1_ms", s->wall_q1 },
        { "wall_q3_ms", s->wall_q3 }, { "cpu_q1_ms", s->cpu_q1 }, { "cpu_q3_ms", s->cpu_q3 },
        { "gpu_spread", s->gpu_spread }, { "wall_spread", s->wall_spread }, { "cpu_spread", s->cpu_spread },
        { "seq_water_rmse", s->seq_water_rmse },
        { "seq_water_ssim", s->seq_water_ssim }, { "temporal_rmse", s->temporal_rmse },
        { "seq_ref_change_rms", s->seq_ref_change }, { "seq_pack_change_rms", s->seq_pack_change },
    };
    json_fields(o, more, sizeof more / sizeof more[0]);
    strbuf_printf(o, ", \"seq_frames\": %d", s->seq_frames);
    strbuf_printf(o, ", \"nonfinite_pixels\": %ld, \"pareto\": %s, \"pareto_flip\": %s}%s\n", s->nan_px,
                  s->pareto ? "true" : "false", s->pareto_flip ? "true" : "false", last ? "" : ",");
}

/* The error of each buffer the pack shows */
static void json_buffers(strbuf *o, const row *r) {
    strbuf_printf(o, ", \"buffers\": {");
    bool first = true;
    for (int m = 1; m < REF_OUTPUT_COUNT; m++) {
        if (!r->has[m]) continue;
        strbuf_printf(o, "%s\"%s\": {\"median\": ", first ? "" : ", ", ref_buffer_for_output(m)->name);
        json_put_num(o, r->comp_median[m]);
        json_key_num(o, "p95", r->comp_p95[m]);
        json_key_num(o, "mean", r->comp_mean[m]);
        json_key_num(o, "rel_mean", r->comp_rel_mean[m]);
        json_key_num(o, "rel_median", r->comp_rel_median[m]);
        if (m == REF_OUTPUT_IRRADIANCE) strbuf_printf(o, ", \"flat\": %s", r->irr_flat ? "true" : "false");
        strbuf_printf(o, "}");
        first = false;
    }
    strbuf_printf(o, "}");
}

static void json_passes(strbuf *o, const row *r) {
    strbuf_printf(o, ", \"passes\": [");
    for (int k = 0; k < r->npasses; k++) {
        strbuf_printf(o, "%s{\"pass\": ", k ? ", " : "");
        json_put_str(o, r->pass_name[k]);
        json_key_num(o, "gpu_ms", r->pass_ms[k]);
        strbuf_printf(o, "}");
    }
    strbuf_printf(o, "]");
}

/* One scene, pack, setting and time. */
static void json_row(strbuf *o, const bench *b, const row *r, bool last) {
    json_setting(o, b, r->scene, r->pack, r->setting);
    strbuf_printf(o, ", \"time_s\": %.9g, \"ok\": %s, \"frames\": %d", b->o.times[r->ti],
                  r->ok ? "true" : "false", r->frames);
    const json_field fig[] = {
        { "gpu_ms", r->gpu_ms }, { "wall_ms", r->wall_ms }, { "first_frame_wall_ms", r->first_wall_ms },
        { "water_rmse", r->water_rmse }, { "water_psnr_db", r->water_psnr },
    };
    json_fields(o, fig, sizeof fig / sizeof fig[0]);
    strbuf_printf(o, ", \"water_pixels\": %ld", r->water_px);
    const json_field more[] = {
        { "off_water_rmse", r->off_rmse }, { "march_capped_share", r->capped_share }, { "rmse", r->rmse },
        { "psnr_db", r->psnr }, { "mae", r->mae }, { "error_p95", r->p95 }, { "error_p99", r->p99 },
        { "max_abs", r->max_abs }, { "over_threshold_share", r->over_share },
        { "water_flip", r->water_flip }, { "flip", r->flip }, { "water_ssim", r->water_ssim },
        { "gpu_q1_ms", r->gpu_q1 }, { "gpu_q3_ms", r->gpu_q3 }, { "wall_q1_ms", r->wall_q1 },
        { "wall_q3_ms", r->wall_q3 }, { "cpu_ms", r->cpu_ms }, { "cpu_q1_ms", r->cpu_q1 },
        { "cpu_q3_ms", r->cpu_q3 }, { "water_rmse_u_noise", r->u_noise_rmse },
        { "water_rmse_u_grid", r->u_grid_rmse }, { "water_flip_u_noise", r->u_noise_flip },
        { "water_flip_u_grid", r->u_grid_flip },
    };
    json_fields(o, more, sizeof more / sizeof more[0]);
    strbuf_printf(o, ", \"nan_pixels\": %ld, \"inf_pixels\": %ld, \"gl_error\": %u", r->nan_px, r->inf_px,
                  r->gl_error);
    json_buffers(o, r);
    json_passes(o, r);
    strbuf_printf(o, ", \"error\": ");
    json_put_str(o, r->error);
    strbuf_printf(o, ", \"note\": ");
    json_put_str(o, r->note);
    strbuf_printf(o, "}%s\n", last ? "" : ",");
}

/* Each pack's a + b·pixels + c·vertices (measure_cost) */
static void json_cost_models(strbuf *o, const bench *b) {
    strbuf_printf(o, "  \"cost_models\": [");
    int nc = 0;
    for (int p = 0; p < b->o.npacks; p++) {
        if (!b->has_cost[p]) continue;
        const cost_model *m = &b->cost[p];
        strbuf_printf(o, "%s\n    {\"pack\": ", nc++ ? "," : "");
        json_put_str(o, b->o.packs[p]);
        strbuf_printf(o, ", \"a_ms\": %.6g, \"b_ms_per_mpixel\": %.6g, \"c_ms_per_kvertex\": %.6g, \"r2\": %.6g, "
                      "\"residual_ms\": %.6g, \"samples\": %d}", m->a, m->b, m->c, m->r2, m->rms_residual, m->n);
    }
    strbuf_printf(o, "%s]\n", nc ? "\n  " : "");
}

bool bench_write_json(bench *b, const char *path) {
    strbuf o = { 0 };
    strbuf_printf(&o, "{\n");
    json_machine(&o, b);
    json_run(&o, b);
    json_sampling(&o, b);
    json_floor(&o, b);
    strbuf_printf(&o, "  \"summary\": [\n");
    for (int i = 0; i < b->nsums; i++) json_summary(&o, b, &b->sums[i], i + 1 == b->nsums);
    strbuf_printf(&o, "  ],\n  \"rows\": [\n");
    for (int i = 0; i < b->nrows; i++) json_row(&o, b, &b->rows[i], i + 1 == b->nrows);
    strbuf_printf(&o, "  ],\n");
    json_cost_models(&o, b);
    strbuf_printf(&o, "}\n");
    return bench_write_strbuf(path, &o);
}
