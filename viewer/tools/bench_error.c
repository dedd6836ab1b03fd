/* bench_error: a frame's error against its reference (bench_int.h): over
 * the water and off it, the buffers a pack shows (TARN_OUTPUT), the
 * irradiance of flat lighting, SSIM, HDR-FLIP in parallel, and the images
 * of it all. */
#include "util.h"
#include "strbuf.h"
#include "bench_int.h"

#include <GL/gl.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image_io.h"
#include "mem.h"
#include "ref_flip.h"
#include "ref_metrics.h"
#include "ref_ssim.h"
#include "render.h"

static unif_entry *find_output_define(render *r, unif_set **owner) {
    int n;
    unif_set *sets = render_uniforms(r, &n);
    for (int i = 0; i < n; i++) {
        unif_entry *e = unif_find(&sets[i], BENCH_OUTPUT_DEFINE);
        if (e && e->is_define) {
            if (owner) *owner = &sets[i];
            return e;
        }
    }
    return NULL;
}

/* Sets TARN_OUTPUT in every Program that has it; true when any has it. */
static bool set_output(render *r, int mode) {
    int n;
    bool any = false;
    unif_set *sets = render_uniforms(r, &n);
    for (int i = 0; i < n; i++) {
        unif_entry *e = unif_find(&sets[i], BENCH_OUTPUT_DEFINE);
        if (!e || !e->is_define) continue;
        unif_set_component(e, 0, mode);
        any = true;
    }
    if (any) render_rebuild_programs(r);
    return any;
}

void bench_write_images(bench *b, const row *rw, const float *rgba, const ref_entry *ref) {
    char dir[PATH_LEN], path[PATH_LEN + 256], sc[256], err[512];
    snprintf(dir, sizeof dir, "%s/img", b->o.out);
    if (!bench_mkdirs(dir)) return;
    bench_stem(b->scene_abs[rw->scene], sc, sizeof sc);
    int w = b->o.w, h = b->o.h;
    img im;
    if (!img_alloc(&im, w, h, 3)) return;
    for (long i = 0; i < (long)w * h; i++)
        for (int k = 0; k < 3; k++) {
            float v = rgba[i * 4 + k];
            im.px[i * 3 + k] = !(v > 0) ? 0.0f : v >= 1 ? 1.0f : (float)ref_linear_to_srgb(v);
        }
    bench_fmt(path, sizeof path, "%s/%s.%s.%s.t%g.png", dir, sc, b->o.packs[rw->pack],
             b->pb[rw->pack].settings[rw->setting].name, b->o.times[rw->ti]);
    img_write(path, &im, err, sizeof err);
    if (ref) {
        float *field = mem_alloc((size_t)w * h * sizeof *field);
        ref_fimage A = { rgba, w, h, 4 }, B = { ref->im.color, w, h, 3 };
        if (ref_metrics_error_field(&A, &B, REF_ERR_COLOR, NULL, field, err, sizeof err)) {
            ref_heatmap(field, w, h, b->o.heat_max, im.px);
            bench_fmt(path, sizeof path, "%s/%s.%s.%s.t%g.heat.png", dir, sc, b->o.packs[rw->pack],
                     b->pb[rw->pack].settings[rw->setting].name, b->o.times[rw->ti]);
            img_write(path, &im, err, sizeof err);
        }
        free(field);
    }
    img_free(&im);
}

/* The colour error over the reference's water pixels and over the rest:
 * what the bench ranks by (the water technique), and what tells whether
 * the world around it agrees (it should, nearly: one world on both sides). */
void bench_measure_water(bench *b, row *rw, const ref_fimage *A, const ref_fimage *B, const float *classes) {
    long n = (long)b->o.w * b->o.h;
    unsigned char *m = mem_alloc((size_t)n);
    char err[MSG_MAX];
    ref_image_metrics r;
    for (int water = 1; water >= 0; water--) {
        ref_mask_water(classes, n, water, NULL, m);
        ref_metrics_desc d = { .mask = m };
        if (!ref_metrics_image(A, B, &d, &r, err, sizeof err) || r.count.compared == 0) continue;
        if (water) {
            rw->water_rmse = r.rmse;
            rw->water_psnr = r.psnr_db;
            rw->water_px = r.count.compared;
        } else {
            rw->off_rmse = r.rmse;
        }
    }
    free(m);
}

/* A buffer the pack wrote (TARN_OUTPUT = mode) against the reference's, over
 * the pixels where the reference sees water first. */
static void compare_buffer(bench *b, row *rw, int mode, const float *rgba, const ref_entry *ref) {
    int w = b->o.w, h = b->o.h;
    long n = (long)w * h;
    unsigned char *mask = mem_alloc((size_t)n);
    for (long i = 0; i < n; i++) mask[i] = ref->im.mask[i] == REF_MASK_WATER;
    ref_metrics_desc d = { .mask = mask };
    ref_fimage A = { rgba, w, h, 4 };
    char err[MSG_MAX];
    if (mode == REF_OUTPUT_REFRACT_HIT) {
        /* a truncated march is never silent: the contract's alpha of the
         * refraction-hit buffer is BENCH_MARCH_CAPPED where it ran out */
        long water = 0, capped = 0;
        for (long i = 0; i < n; i++)
            if (mask[i]) { water++; capped += rgba[i * 4 + 3] == BENCH_MARCH_CAPPED; }
        rw->capped_share = water ? (double)capped / (double)water : NAN;
        ref_fimage B = { ref->im.refract_hit, w, h, 4 };
        ref_fimage A3 = A;
        ref_point_metrics m;
        /* the pack's alpha is not a flag: compare xyz only */
        float *xyz = mem_alloc((size_t)n * 3 * sizeof *xyz);
        float *bxyz = mem_alloc((size_t)n * 3 * sizeof *bxyz);
        for (long i = 0; i < n; i++)
            for (int k = 0; k < 3; k++) {
                xyz[i * 3 + k] = rgba[i * 4 + k];
                bxyz[i * 3 + k] = ref->im.refract_hit[i * 4 + k];
            }
        A3 = (ref_fimage){ xyz, w, h, 3 };
        B = (ref_fimage){ bxyz, w, h, 3 };
        if (ref_metrics_points(&A3, &B, &d, &m, err, sizeof err)) {
            rw->has[mode] = true;
            rw->comp_median[mode] = m.world.median;
            rw->comp_p95[mode] = m.world.p95;
            rw->comp_mean[mode] = m.world.mean;
            rw->comp_rel_mean[mode] = NAN;
            rw->comp_rel_median[mode] = NAN;
        }
        free(xyz);
        free(bxyz);
    } else {
        const float *src = mode == REF_OUTPUT_FRESNEL ? ref->im.fresnel
                           : mode == REF_OUTPUT_IRRADIANCE ? ref->im.irradiance : ref->im.depth;
        int ch = mode == REF_OUTPUT_IRRADIANCE ? 3 : 1;
        /* the pack's side: R (or RGB) of its output */
        float *a = mem_alloc((size_t)n * ch * sizeof *a);
        for (long i = 0; i < n; i++)
            for (int k = 0; k < ch; k++) a[i * ch + k] = rgba[i * 4 + k];
        ref_fimage A1 = { a, w, h, ch }, B = { src, w, h, ch };
        ref_scalar_metrics m;
        if (ref_metrics_scalar(&A1, &B, &d, &m, err, sizeof err)) {
            rw->has[mode] = true;
            rw->comp_median[mode] = m.abs.median;
            rw->comp_p95[mode] = m.abs.p95;
            rw->comp_mean[mode] = m.abs.mean;
            rw->comp_rel_mean[mode] = m.rel.mean;
            rw->comp_rel_median[mode] = m.rel.median;
        }
        free(a);
    }
    free(mask);
}

/* Every entry's values, to return to between buffers. */
static float *snapshot(render *r, bool restore, float *snap) {
    int n;
    unif_set *sets = render_uniforms(r, &n);
    size_t total = 0;
    for (int i = 0; i < n; i++) total += (size_t)sets[i].n;
    if (!restore) snap = mem_alloc((total ? total : 1) * UNIF_MAX_COMPONENTS * sizeof *snap);
    size_t k = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < sets[i].n; j++, k++) {
            float *v = sets[i].entries[j].value, *sv = snap + k * UNIF_MAX_COMPONENTS;
            memcpy(restore ? v : sv, restore ? sv : v, UNIF_MAX_COMPONENTS * sizeof *v);
        }
    return snap;
}

void bench_measure_buffers(bench *b, render *r, const render_target *tg, int s, int p, const char *scene,
                            int first_row, float *rgba) {
    const packset_bench *pb = &b->pb[p];
    unif_entry *out_def = find_output_define(r, NULL);
    float *snap = NULL;
    char sc[256];
    bench_stem(b->scene_abs[s], sc, sizeof sc);
    for (int mode = 1; mode < REF_OUTPUT_COUNT; mode++) {
        const packset_buffer *spec = NULL;
        for (int i = 0; i < pb->nbuffers; i++)
            if (strcmp(pb->buffers[i].name, ref_buffer_for_output(mode)->name) == 0) spec = &pb->buffers[i];
        bool via_define = !spec && out_def && out_def->min <= mode && out_def->max >= mode;
        if (!spec && !via_define) continue;
        if (!snap) snap = snapshot(r, false, NULL);
        else snapshot(r, true, snap);
        bench_progress_set(&b->pr, b->pr.done, true, "%s %s: buffer %s", sc, b->o.packs[p], ref_buffer_for_output(mode)->name);
        if (spec) {
            int n;
            unif_set *sets = render_uniforms(r, &n);
            char err[MSG_MAX] = "";
            bool changed;
            if (!packset_apply(sets, n, &spec->how, &changed, err, sizeof err))
                fprintf(stderr, "%starn bench: %s: buffer %s: %s", b->pr.tty ? "\n" : "", pb->path, spec->name, err);
            render_rebuild_programs(r);
        } else {
            set_output(r, mode);
        }
        /* a buffer's pixel is the pixel centre's, as the reference's: a
         * resolve would average hit points across an edge */
        render_set_samples(r, 1);
        for (int ti = 0; ti < b->o.ntimes; ti++) {
            ref_entry *ref = bench_get_ref(b, s, scene, ti);
            if (!ref) continue;
            render_frame(r, b->o.times[ti], tg->fbo, tg->w, tg->h, NULL);
            render_target_read(tg, rgba);
            compare_buffer(b, &b->rows[first_row + ti], mode, rgba, ref);
        }
        render_set_samples(r, b->o.samples);
    }
    free(snap);
}

/* ---- FLIP, in parallel: HDR-FLIP costs about 1 s a 480x270 frame on one
 * core, and the GL is idle while it runs ---- */

typedef struct flip_queue {
    flip_job *jobs;
    int n, next;
    pthread_mutex_t mu;
} flip_queue;

/* One map, pooled per region (ref_flip_map once, ref_flip_pool per mask). */
static void flip_job_run(flip_job *j) {
    long n = (long)j->w * j->h;
    j->water = j->frame = NAN;
    float *map = mem_alloc((size_t)n * sizeof *map);
    unsigned char *m = mem_alloc((size_t)n);
    ref_fimage A = { j->test, j->w, j->h, 4 }, B = { j->ref, j->w, j->h, 3 };
    ref_flip_desc d = { .hdr = true };
    ref_flip_result info;
    char err[MSG_MAX];
    if (ref_flip_map(&A, &B, &d, map, NULL, &info, err, sizeof err)) {
        ref_flip_result r = info;
        ref_mask_water(j->classes, n, 1, NULL, m);
        ref_flip_pool(map, j->w, j->h, m, &r);
        j->water = r.mean;
        ref_flip_pool(map, j->w, j->h, NULL, &r);
        j->frame = r.mean;
    }
    free(m);
    free(map);
}

static void *flip_worker(void *arg) {
    flip_queue *q = arg;
    for (;;) {
        pthread_mutex_lock(&q->mu);
        int i = q->next++;
        pthread_mutex_unlock(&q->mu);
        if (i >= q->n) return NULL;
        flip_job_run(&q->jobs[i]);
    }
}

void bench_run_flip_jobs(bench *b, flip_job *jobs, int n) {
    if (n <= 0) return;
    double t0 = clock_now_s();
    flip_queue q = { .jobs = jobs, .n = n };
    pthread_mutex_init(&q.mu, NULL);
    int nt = b->cores > 1 ? b->cores : 1;
    if (nt > n) nt = n;
    pthread_t th[64];
    int started = 0;
    for (int i = 1; i < nt && i < 64; i++)
        if (pthread_create(&th[started], NULL, flip_worker, &q) == 0) started++;
    flip_worker(&q);
    for (int i = 0; i < started; i++) pthread_join(th[i], NULL);
    pthread_mutex_destroy(&q.mu);
    b->seconds_flip += clock_now_s() - t0;
}

/* The reference's water as a byte mask (heap), what both water metrics count. */
static unsigned char *water_mask(const refcache_image *ref, long n) {
    unsigned char *m = mem_alloc((size_t)n);
    ref_mask_water(ref->mask, n, 1, NULL, m);
    return m;
}

/* SSIM over the reference's water (the luminance plane, ref_ssim.h) */
double bench_water_ssim(const float *rgba, const refcache_image *ref, int w, int h) {
    long n = (long)w * h;
    unsigned char *m = water_mask(ref, n);
    ref_fimage A = { rgba, w, h, 4 }, B = { ref->color, w, h, 3 };
    ref_ssim_desc d = { .mask = m };
    ref_ssim_result r;
    char err[MSG_MAX];
    double v = ref_ssim(&A, &B, &d, NULL, &r, err, sizeof err) ? r.mean : NAN;
    free(m);
    return v;
}

/* The water RMSE of a frame against a reference (NaN: none compared) */
double bench_water_rmse_of(const float *rgba, const refcache_image *ref, int w, int h) {
    long n = (long)w * h;
    unsigned char *m = water_mask(ref, n);
    ref_fimage A = { rgba, w, h, 4 }, B = { ref->color, w, h, 3 };
    ref_metrics_desc d = { .mask = m };
    ref_image_metrics r;
    char err[MSG_MAX];
    double v = ref_metrics_image(&A, &B, &d, &r, err, sizeof err) && r.count.compared ? r.rmse : NAN;
    free(m);
    return v;
}

/* Irradiance where the pack shows none: it lights the floor as the world
 * does, by the sun through the flat mean surface (world.glsl's
 * worldSunBelow, the reference's ref_render_flat_sun), so its irradiance
 * at the reference's hit points is the flat-caustics reference's. */
void bench_measure_flat_irradiance(bench *b, row *rw, const ref_entry *flat, const ref_entry *ref) {
    int w = b->o.w, h = b->o.h;
    long n = (long)w * h;
    unsigned char *mask = mem_alloc((size_t)n);
    for (long i = 0; i < n; i++) mask[i] = ref->im.mask[i] == REF_MASK_WATER;
    ref_metrics_desc d = { .mask = mask };
    ref_fimage A = { flat->im.irradiance, w, h, 3 }, B = { ref->im.irradiance, w, h, 3 };
    ref_scalar_metrics m;
    char err[MSG_MAX];
    int mode = REF_OUTPUT_IRRADIANCE;
    if (ref_metrics_scalar(&A, &B, &d, &m, err, sizeof err)) {
        rw->has[mode] = true;
        rw->irr_flat = true;
        rw->comp_median[mode] = m.abs.median;
        rw->comp_p95[mode] = m.abs.p95;
        rw->comp_mean[mode] = m.abs.mean;
        rw->comp_rel_mean[mode] = m.rel.mean;
        rw->comp_rel_median[mode] = m.rel.median;
    }
    free(mask);
}
