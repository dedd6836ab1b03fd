/* bench_measure: one scene's settings measured (bench_int.h): each loaded
 * and warmed up, all timed round-robin, then each measured for error at
 * every time, against the other references (the uncertainty), over the
 * animated sequence, and in the buffers it shows. */
#include "util.h"
#include "strbuf.h"
#include "bench_int.h"

#include <GL/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image_io.h"
#include "mem.h"
#include "ref_metrics.h"
#include "ref_ssim.h"
#include "render.h"

/* Its rows, then loaded and warmed up; false (rows failed) when it cannot be */
static bool slot_open(bench *b, slot *sl, int s, int p, int k) {
    const packset_setting *st = &b->pb[p].settings[k];
    char sc[256];
    memset(sl, 0, sizeof *sl);
    sl->s = s;
    sl->p = p;
    sl->k = k;
    sl->scene = bench_wrapper_path(b, s, p, k, sl->wp, sizeof sl->wp);
    bench_stem(b->scene_abs[s], sc, sizeof sc);
    sl->first_row = b->nrows;
    b->rows = mem_realloc(b->rows, (size_t)(b->nrows + b->o.ntimes) * sizeof *b->rows);
    for (int ti = 0; ti < b->o.ntimes; ti++) {
        row *rw = &b->rows[b->nrows++];
        memset(rw, 0, sizeof *rw);
        rw->scene = s;
        rw->pack = p;
        rw->setting = k;
        rw->ti = ti;
        rw->gpu_ms = rw->wall_ms = rw->first_wall_ms = rw->rmse = rw->psnr = rw->mae = NAN;
        rw->water_rmse = rw->water_psnr = rw->off_rmse = rw->wall_spread = rw->capped_share = NAN;
        rw->p95 = rw->p99 = rw->max_abs = rw->over_share = NAN;
        rw->gpu_q1 = rw->gpu_q3 = rw->wall_q1 = rw->wall_q3 = NAN;
        rw->cpu_ms = rw->cpu_q1 = rw->cpu_q3 = rw->cpu_spread = rw->gpu_spread = NAN;
        rw->water_flip = rw->flip = rw->water_ssim = NAN;
        rw->u_noise_rmse = rw->u_grid_rmse = rw->u_noise_flip = rw->u_grid_flip = NAN;
        rw->seq_water_rmse = rw->seq_water_ssim = rw->temporal_rmse = rw->seq_ref_change = rw->seq_pack_change = NAN;
    }
    bench_progress_set(&b->pr, b->pr.done, true, "%s %s %s: loading", sc, b->o.packs[p], st->name);
    /* no spray: the reference draws none (docs/waves.md), so it is no part of a pack's error or time */
    render_desc rd = { .repo_root = b->root, .pack = b->o.packs[p], .samples = b->o.samples, .no_spray = true };
    sl->r = render_create(&rd);
    bool loaded = render_load(sl->r, sl->scene);
    char err[MSG_MAX] = "";
    bool defines_changed = false;
    if (loaded) {
        int n;
        unif_set *sets = render_uniforms(sl->r, &n);
        if (!packset_apply(sets, n, st, &defines_changed, err, sizeof err))
            for (int ti = 0; ti < b->o.ntimes; ti++)
                bench_first_line(err, b->rows[sl->first_row + ti].note, sizeof b->rows[sl->first_row + ti].note);
        if (defines_changed && !render_rebuild_programs(sl->r)) loaded = false;
    }
    bool have_target = loaded && render_target_create(&sl->tg, b->o.w, b->o.h, true);
    bench_progress_set(&b->pr, b->pr.done + BENCH_LOAD_WEIGHT, false, NULL);
    if (!loaded || !have_target) {
        char why[MSG_MAX];
        bench_first_line(render_messages(sl->r)[0] ? render_messages(sl->r) : "cannot create the framebuffer", why,
                   sizeof why);
        const diag_list *dl = render_diags(sl->r);
        for (int j = 0; j < dl->n; j++)
            if (dl->d[j].severity == DIAG_ERROR) { diag_format(&dl->d[j], why, sizeof why); break; }
        for (int ti = 0; ti < b->o.ntimes; ti++) snprintf(b->rows[sl->first_row + ti].error, sizeof why, "%s", why);
        fprintf(stderr, "%starn bench: %s with %s, setting %s: %s\n", b->pr.tty ? "\n" : "", sc, b->o.packs[p],
                st->name, why);
        b->failures++;
        render_destroy(sl->r);
        sl->r = NULL;
        return false;
    }
    for (int ti = 0; ti < b->o.ntimes; ti++) {
        b->rows[sl->first_row + ti].first_wall_ms = bench_warm_up(b, sl->r, &sl->tg, b->o.times[ti]);
        bench_acc_init(&sl->acc[ti], b->o.frames, true);
    }
    sl->live = true;
    return true;
}

static void slot_close(slot *sl) {
    if (!sl->r) return;
    if (sl->live) render_target_destroy(&sl->tg);
    render_destroy(sl->r);
    sl->r = NULL;
    sl->live = false;
}

/* The error over the animated sequence: seq_frames frames from the first
 * time at seq_fps, at the sequence's size, each against the reference of
 * its instant: the water RMSE and SSIM, means over the instants, and the
 * temporal error: the RMS over the water (water in both frames) of the
 * pack's frame-to-frame change minus the reference's, (P[i+1] - P[i]) -
 * (R[i+1] - R[i]). A pack whose glints or march steps jump between frames
 * where the reference's change is smooth scores worse there. With images,
 * a strip of |that| per pixel (max over R, G, B), one panel a pair. */
typedef struct seq_result { double water_rmse, water_ssim, temporal, ref_change, pack_change; int frames; } seq_result;

static seq_result measure_sequence(bench *b, slot *sl) {
    seq_result out = { NAN, NAN, NAN, NAN, NAN, 0 };
    int nf = b->o.seq_frames, w = b->o.seq_w, h = b->o.seq_h;
    if (nf < 2) return out;
    double t0 = clock_now_s();
    render_target tg;
    if (!render_target_create(&tg, w, h, true)) return out;
    long n = (long)w * h;
    float *prev = mem_alloc((size_t)n * 4 * sizeof *prev), *cur = mem_alloc((size_t)n * 4 * sizeof *cur);
    const refcache_image *rprev = NULL;
    double sum_rmse = 0, sum_ssim = 0, sq = 0, sq_ref = 0, sq_pack = 0;
    long cnt = 0;
    int n_rmse = 0, n_ssim = 0, got = 0;
    img strip = { 0 };
    bool images = b->o.images && img_alloc(&strip, w * (nf - 1), h, 3);
    float *field = images ? mem_alloc((size_t)n * sizeof *field) : NULL;
    float *rgb = images ? mem_alloc((size_t)n * 3 * sizeof *rgb) : NULL;
    for (int i = 0; i < nf; i++) {
        double t = bench_seq_time(b, i);
        ref_entry *re = bench_get_ref_at(b, sl->s, sl->scene, REFK_SEQ, w, h, t);
        render_frame(sl->r, t, tg.fbo, w, h, NULL);
        render_target_read(&tg, cur);
        if (!re) { rprev = NULL; continue; }
        const refcache_image *R = &re->im;
        got++;
        double e = bench_water_rmse_of(cur, R, w, h), ss = bench_water_ssim(cur, R, w, h);
        if (isfinite(e)) { sum_rmse += e; n_rmse++; }
        if (isfinite(ss)) { sum_ssim += ss; n_ssim++; }
        if (rprev) {
            for (long px = 0; px < n; px++) {
                bool water = R->mask[px] == REF_MASK_WATER && rprev->mask[px] == REF_MASK_WATER;
                float worst = NAN;
                if (water) {
                    worst = 0;
                    for (int c = 0; c < 3; c++) {
                        double dp = (double)cur[px * 4 + c] - prev[px * 4 + c];
                        double dr = (double)R->color[px * 3 + c] - rprev->color[px * 3 + c];
                        if (!isfinite(dp) || !isfinite(dr)) { worst = NAN; break; }
                        sq += (dp - dr) * (dp - dr);
                        sq_ref += dr * dr;
                        sq_pack += dp * dp;
                        cnt++;
                        if (fabs(dp - dr) > worst) worst = (float)fabs(dp - dr);
                    }
                }
                if (field) field[px] = water ? worst : -1.0f;
            }
            if (images) {
                ref_heatmap(field, w, h, b->o.heat_max / 4, rgb);
                for (int y = 0; y < h; y++)
                    memcpy(strip.px + ((size_t)y * strip.w + (size_t)(i - 1) * w) * 3, rgb + (size_t)y * w * 3,
                           (size_t)w * 3 * sizeof *rgb);
            }
        }
        rprev = R;
        float *tmp = prev;
        prev = cur;
        cur = tmp;
    }
    out.frames = got;
    out.water_rmse = n_rmse ? sum_rmse / n_rmse : NAN;
    out.water_ssim = n_ssim ? sum_ssim / n_ssim : NAN;
    if (cnt) {
        out.temporal = sqrt(sq / cnt);
        out.ref_change = sqrt(sq_ref / cnt);
        out.pack_change = sqrt(sq_pack / cnt);
    }
    if (images && cnt) {
        char dir[PATH_LEN], path[PATH_LEN + 256], sc[256], err[512];
        snprintf(dir, sizeof dir, "%s/img", b->o.out);
        bench_stem(b->scene_abs[sl->s], sc, sizeof sc);
        bench_fmt(path, sizeof path, "%s/%s.%s.%s.temporal.png", dir, sc, b->o.packs[sl->p],
            bench_setting_name(b, sl->p, sl->k));
        if (bench_mkdirs(dir)) img_write(path, &strip, err, sizeof err);
    }
    if (images) img_free(&strip);
    free(field);
    free(rgb);
    free(prev);
    free(cur);
    render_target_destroy(&tg);
    b->seconds_seq += clock_now_s() - t0;
    return out;
}

/* The error of a setting: at each time the frame against the reference
 * (RMSE, and HDR-FLIP with SSIM over the water), its buffers, the
 * irradiance of flat lighting where it shows none, its uncertainty (the
 * first time against the noise and grid references), the sequence. */
static void slot_measure(bench *b, slot *sl) {
    int w = b->o.w, h = b->o.h, nt = b->o.ntimes;
    long n = (long)w * h;
    char sc[256];
    bench_stem(b->scene_abs[sl->s], sc, sizeof sc);
    const char *name = bench_setting_name(b, sl->p, sl->k);
    float *frames = mem_alloc((size_t)nt * n * 4 * sizeof *frames);
    flip_job jobs[MAX_TIMES + 2];
    int nj = 0, job_of[MAX_TIMES];
    ref_entry *refs[MAX_TIMES];
    for (int ti = 0; ti < nt; ti++) {
        row *rw = &b->rows[sl->first_row + ti];
        float *rgba = frames + (size_t)ti * n * 4;
        double t = b->o.times[ti];
        bench_progress_set(&b->pr, b->pr.done, true, "%s %s %s t=%g: error", sc, b->o.packs[sl->p], name, t);
        while (glGetError() != GL_NO_ERROR) {}
        render_frame(sl->r, t, sl->tg.fbo, w, h, NULL);
        render_target_read(&sl->tg, rgba);
        GLenum ge = glGetError();
        if (ge != GL_NO_ERROR) rw->gl_error = ge;
        rw->ok = true;
        ref_entry *ref = refs[ti] = bench_get_ref(b, sl->s, sl->scene, ti);
        job_of[ti] = -1;
        if (ref) {
            ref_fimage A = { rgba, w, h, 4 }, B = { ref->im.color, w, h, 3 };
            ref_image_metrics m;
            char merr[256];
            bench_measure_water(b, rw, &A, &B, ref->im.mask);
            if (ref_metrics_image(&A, &B, NULL, &m, merr, sizeof merr)) {
                rw->rmse = m.rmse;
                rw->psnr = m.psnr_db;
                rw->mae = m.mae;
                rw->p95 = m.pixel_err.p95;
                rw->p99 = m.pixel_err.p99;
                rw->max_abs = m.max_abs;
                rw->over_share = m.over_threshold_share;
                rw->nan_px = m.count.nan_a;
                rw->inf_px = m.count.inf_a;
            }
            rw->water_ssim = bench_water_ssim(rgba, &ref->im, w, h);
            job_of[ti] = nj;
            jobs[nj++] = (flip_job){ rgba, ref->im.color, ref->im.mask, w, h, NAN, NAN };
        } else {
            snprintf(rw->note, sizeof rw->note, "no reference");
            for (long i = 0; i < n; i++)
                for (int c = 0; c < 3; c++) {
                    if (isnan(rgba[i * 4 + c])) { rw->nan_px++; break; }
                    if (isinf(rgba[i * 4 + c])) { rw->inf_px++; break; }
                }
        }
        if (b->o.images) bench_write_images(b, rw, rgba, ref);
    }
    /* the uncertainty: the first time's frame against the other references */
    ref_entry *alt[2] = { NULL, NULL };
    int alt_job[2] = { -1, -1 };
    if (b->o.uncertainty && refs[0]) {
        alt[0] = bench_get_ref_at(b, sl->s, sl->scene, REFK_NOISE, w, h, b->o.times[0]);
        alt[1] = bench_get_ref_at(b, sl->s, sl->scene, REFK_GRID, w, h, b->o.times[0]);
        for (int k = 0; k < 2; k++)
            if (alt[k]) {
                alt_job[k] = nj;
                /* the water is the default reference's, as for the figure it qualifies */
                jobs[nj++] = (flip_job){ frames, alt[k]->im.color, refs[0]->im.mask, w, h, NAN, NAN };
            }
    }
    bench_progress_set(&b->pr, b->pr.done, true, "%s %s %s: FLIP x%d", sc, b->o.packs[sl->p], name, nj);
    bench_run_flip_jobs(b, jobs, nj);
    for (int ti = 0; ti < nt; ti++)
        if (job_of[ti] >= 0) {
            b->rows[sl->first_row + ti].water_flip = jobs[job_of[ti]].water;
            b->rows[sl->first_row + ti].flip = jobs[job_of[ti]].frame;
        }
    row *r0 = &b->rows[sl->first_row];
    for (int k = 0; k < 2; k++) {
        if (!alt[k]) continue;
        /* the alternative reference's water mask is the same (the caustics
         * differ, not the geometry): the default's is used for both */
        refcache_image im = alt[k]->im;
        im.mask = refs[0]->im.mask;
        double e = bench_water_rmse_of(frames, &im, w, h);
        double du = fabs(e - r0->water_rmse), df = fabs(jobs[alt_job[k]].water - r0->water_flip);
        if (k == 0) { r0->u_noise_rmse = du; r0->u_noise_flip = df; }
        else { r0->u_grid_rmse = du; r0->u_grid_flip = df; }
    }
    /* the sequence, while the programs are the setting's own (the buffers change them) */
    if (b->o.seq_frames >= 2) {
        bench_progress_set(&b->pr, b->pr.done, true, "%s %s %s: sequence", sc, b->o.packs[sl->p], name);
        seq_result q = measure_sequence(b, sl);
        r0->seq_frames = q.frames;
        r0->seq_water_rmse = q.water_rmse;
        r0->seq_water_ssim = q.water_ssim;
        r0->temporal_rmse = q.temporal;
        r0->seq_ref_change = q.ref_change;
        r0->seq_pack_change = q.pack_change;
    }
    /* the buffers the pack shows: its bench.txt `buffer` lines, else TARN_OUTPUT */
    bench_measure_buffers(b, sl->r, &sl->tg, sl->s, sl->p, sl->scene, sl->first_row, frames);
    for (int ti = 0; ti < nt; ti++) {
        row *rw = &b->rows[sl->first_row + ti];
        if (rw->has[REF_OUTPUT_IRRADIANCE] || !refs[ti]) continue;
        ref_entry *flat = bench_get_ref_at(b, sl->s, sl->scene, REFK_FLAT, w, h, b->o.times[ti]);
        if (flat) bench_measure_flat_irradiance(b, rw, flat, refs[ti]);
    }
    free(frames);
}

/* Every setting of a scene: loaded and warmed up, timed round-robin, then
 * measured for error one by one. */
void bench_measure_scene(bench *b, int s, double weight_each_time) {
    int n = 0;
    for (int p = 0; p < b->o.npacks; p++) n += b->pb[p].n;
    slot *sl = mem_zalloc((size_t)(n ? n : 1) * sizeof *sl);
    int i = 0;
    for (int p = 0; p < b->o.npacks; p++)
        for (int k = 0; k < b->pb[p].n; k++) slot_open(b, &sl[i++], s, p, k);
    bench_time_round_robin(b, sl, n, weight_each_time);
    for (i = 0; i < n; i++) {
        if (sl[i].live) slot_measure(b, &sl[i]);
        slot_close(&sl[i]);
    }
    free(sl);
}
