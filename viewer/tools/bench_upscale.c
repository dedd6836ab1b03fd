/* bench_upscale: what the window's upscaler buys, measured (a tool, not a
 * test: its figures are timings and errors, nothing passes or fails).
 *
 * The window's case: a 960x540 scene area, time running. For each pack
 * and scene, at a few animated instants, the frame is drawn at full
 * resolution (the truth) and at a reduced scale (as the frame budget
 * draws it, render_set_detail included), then brought to 960x540 three
 * ways: the bilinear blit (the window before), the upscaler (sharpened
 * cubic), and the sharp world (upscale_draw_over_world: the reduced
 * frame's water over the world drawn once at full resolution, half a
 * second before the first instant, as the window keeps it); each against
 * the truth: RMSE (linear RGB), SSIM (ref_ssim, luminance) and LDR-FLIP
 * (ref_flip, default viewing). All go through the window's 8-bit sRGB
 * canvas, and the error is computed on the decoded linear values. Then
 * each one's own time per frame (glFinish'd wall time, median of runs),
 * the world-only frame's (what the window pays once when the camera
 * stops, one run) and the reduced frame's own (mean over the instants,
 * each after one frame at the scale: what the window's budget pays at
 * that size, render_set_detail's steps included: natural's photon grid
 * halves at 0.71 of a side, its frame ~40 -> ~65 ms on the lake).
 *
 *   bench_upscale [--pack NAME]... [--scene FILE]... [--scale S]... [--size WxH]
 *                 [--times t1,t2,..] [--sharpness X] [--png DIR]
 *
 * Defaults: the four packs, scenes/lake.glib and scenes/showcase.glib,
 * scales 0.19 (what the 50 ms budget picks on a 2-core llvmpipe machine)
 * and 0.5, 960x540, times 2,2.7,3.4. --png writes truth / bilinear / cubic /
 * world of the first instant for looking at. scripts/live_error.sh
 * measures the window itself. */
#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_ctx.h"
#include "strbuf.h"
#include "image_io.h"
#include "mem.h"
#include "ref_flip.h"
#include "ref_metrics.h"
#include "ref_ssim.h"
#include "render.h"
#include "upscale.h"
#include "util.h"

#define MAX_LIST 8

typedef struct opts {
    const char *packs[MAX_LIST], *scenes[MAX_LIST];
    double scales[MAX_LIST], times[MAX_LIST];
    int npacks, nscenes, nscales, ntimes;
    int w, h;
    float sharpness;
    const char *png_dir;
} opts;

typedef struct errs { double rmse, ssim, flip; } errs;

/* The sum of a case's errors over its instants, per upscaler. */
typedef struct tally { errs bil, edge, over; int n; double frame_ms; } tally;   /* frame_ms: the reduced frames' sum */

static void usage(void) {
    fputs("usage: bench_upscale [--pack NAME]... [--scene FILE]... [--scale S]... [--size WxH]\n"
          "                     [--times t1,t2,..] [--sharpness X] [--png DIR]\n",
          stderr);
    exit(2);
}

static void parse_times(const char *s, opts *o) {
    char buf[256];
    snprintf(buf, sizeof buf, "%s", s);
    for (char *p = strtok(buf, ","); p && o->ntimes < MAX_LIST; p = strtok(NULL, ","))
        o->times[o->ntimes++] = atof(p);
}

static opts parse(int argc, char **argv) {
    opts o = { .w = 960, .h = 540 };
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!v) usage();
        if (!strcmp(a, "--pack") && o.npacks < MAX_LIST) o.packs[o.npacks++] = v;
        else if (!strcmp(a, "--scene") && o.nscenes < MAX_LIST) o.scenes[o.nscenes++] = v;
        else if (!strcmp(a, "--scale") && o.nscales < MAX_LIST) o.scales[o.nscales++] = atof(v);
        else if (!strcmp(a, "--size") && sscanf(v, "%dx%d", &o.w, &o.h) == 2) {}
        else if (!strcmp(a, "--times")) parse_times(v, &o);
        else if (!strcmp(a, "--sharpness")) o.sharpness = (float)atof(v);
        else if (!strcmp(a, "--png")) o.png_dir = v;
        else usage();
        i++;
    }
    static const char *const packs[] = { "basic", "raymarch", "natural", "caustic_tex" };
    if (!o.npacks) for (int i = 0; i < 4; i++) o.packs[o.npacks++] = packs[i];
    if (!o.nscenes) {
        o.scenes[o.nscenes++] = TARN_SOURCE_DIR "/scenes/lake.glib";
        o.scenes[o.nscenes++] = TARN_SOURCE_DIR "/scenes/showcase.glib";
    }
    if (!o.nscales) { o.scales[0] = 0.19; o.scales[1] = 0.5; o.nscales = 2; }
    if (!o.ntimes) { o.times[0] = 2.0; o.times[1] = 2.7; o.times[2] = 3.4; o.ntimes = 3; }
    return o;
}

/* The target's 8-bit sRGB pixels (bottom-left w x h), decoded to linear
 * RGB, row 0 = top. */
static void read_linear(const render_target *t, int w, int h, float *rgb) {
    unsigned char *b = mem_alloc((size_t)w * h * 4);
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, b);
    float lut[256];
    for (int i = 0; i < 256; i++) lut[i] = (float)ref_srgb_to_linear(i / 255.0);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 3; c++)
                rgb[((size_t)(h - 1 - y) * w + x) * 3 + c] = lut[b[((size_t)y * w + x) * 4 + c]];
    free(b);
}

static errs measure(const float *test, const float *truth, int w, int h) {
    ref_fimage a = { test, w, h, 3 }, b = { truth, w, h, 3 };
    double s = 0;
    size_t n = (size_t)w * h * 3;
    for (size_t i = 0; i < n; i++) s += (double)(test[i] - truth[i]) * (test[i] - truth[i]);
    errs e = { .rmse = sqrt(s / (double)n), .ssim = NAN, .flip = NAN };
    char err[MSG_MAX];
    ref_ssim_result sr;
    if (ref_ssim(&a, &b, NULL, NULL, &sr, err, sizeof err)) e.ssim = sr.mean;
    ref_flip_result fr;
    if (ref_flip_mean(&a, &b, NULL, NULL, &fr, err, sizeof err)) e.flip = fr.mean;
    return e;
}

static void add(errs *sum, errs e) {
    sum->rmse += e.rmse;
    sum->ssim += e.ssim;
    sum->flip += e.flip;
}

static void write_png(const opts *o, const char *name, const float *rgb) {
    if (!o->png_dir) return;
    img im = { 0 };
    if (!img_alloc(&im, o->w, o->h, 3)) return;
    /* back to sRGB values: img_write stores what it is given */
    for (size_t i = 0; i < (size_t)o->w * o->h * 3; i++) im.px[i] = (float)ref_linear_to_srgb(rgb[i]);
    char path[1024], err[256];
    snprintf(path, sizeof path, "%s/%s.png", o->png_dir, name);
    if (!img_write(path, &im, err, sizeof err)) fprintf(stderr, "%s\n", err);
    img_free(&im);
}

typedef struct rig {
    render_target truth_tg, canvas, out;
    render_target full;         /* the world alone at full resolution (the sharp world) */
    upscaler *bil, *edge;
    float *truth, *test;
} rig;

/* One instant of one case: the truth, the reduced frame, both upscales. */
static void one_instant(const opts *o, rig *g, render *r, double t, double scale, tally *tl, const char *tag) {
    int w = o->w, h = o->h, rw, rh;
    glEnable(GL_FRAMEBUFFER_SRGB);
    render_set_detail(r, 1.0);
    render_frame_at(r, t, g->truth_tg.fbo, 0, 0, w, h, NULL);
    read_linear(&g->truth_tg, w, h, g->truth);
    rw = (int)lround(scale * w);
    rh = (int)lround(scale * h);
    render_set_detail(r, scale);
    /* the truth's full detail resized the targets: a first reduced frame
     * draws them again, which the window's steady frames do not */
    render_frame_at(r, t - 0.05, g->canvas.fbo, 0, 0, rw, rh, NULL);
    glFinish();
    double f0 = clock_now_s();
    render_frame_at(r, t, g->canvas.fbo, 0, 0, rw, rh, NULL);
    glFinish();
    tl->frame_ms += (clock_now_s() - f0) * 1e3;
    upscaler *ups[2] = { g->bil, g->edge };
    for (int k = 0; k < 3; k++) {
        glEnable(GL_FRAMEBUFFER_SRGB);
        if (k < 2) upscale_draw(ups[k], g->canvas.color, rw, rh, g->out.fbo, (upscale_rect){ 0, 0, w, h });
        else {
            int sw, sh;
            unsigned snap = render_world_snapshot(r, &sw, &sh);
            if (!upscale_draw_over_world(g->bil, g->canvas.color, snap, rw, rh, g->full.color, g->out.fbo,
                                         (upscale_rect){ 0, 0, w, h }))
                upscale_draw(g->bil, g->canvas.color, rw, rh, g->out.fbo, (upscale_rect){ 0, 0, w, h });
        }
        read_linear(&g->out, w, h, g->test);
        add(k == 0 ? &tl->bil : k == 1 ? &tl->edge : &tl->over, measure(g->test, g->truth, w, h));
        if (tl->n == 0) {
            static const char *const tags[3] = { "bilinear", "cubic", "world" };
            char name[300];
            snprintf(name, sizeof name, "%.256s-%s", tag, tags[k]);
            write_png(o, name, g->test);
        }
    }
    if (tl->n == 0) {
        char name[300];
        snprintf(name, sizeof name, "%.256s-truth", tag);
        write_png(o, name, g->truth);
    }
    tl->n++;
}

static const char *base_name(const char *path) {
    const char *s = strrchr(path, '/');
    return s ? s + 1 : path;
}

static void run_case(const opts *o, rig *g, const char *scene, const char *pack) {
    render *r = render_create(&(render_desc){ .pack = pack });
    if (!render_load(r, scene)) {
        fprintf(stderr, "%s with %s: %s", scene, pack, render_messages(r));
        render_destroy(r);
        return;
    }
    render_set_world_snapshot(r, true);
    for (int s = 0; s < o->nscales; s++) {
        /* the world the window keeps: drawn once, half a second before the
         * first instant (after a reduced frame, as in the window, whose
         * height map it keeps) */
        double t0 = o->times[0] - 0.5;
        int rw = (int)lround(o->scales[s] * o->w), rh = (int)lround(o->scales[s] * o->h);
        render_set_detail(r, o->scales[s]);
        render_frame_at(r, t0, g->canvas.fbo, 0, 0, rw, rh, NULL);
        glEnable(GL_FRAMEBUFFER_SRGB);
        glFinish();
        double w0 = clock_now_s();
        render_frame_world_at(r, t0, g->full.fbo, 0, 0, o->w, o->h, NULL);
        glFinish();
        double world_ms = (clock_now_s() - w0) * 1e3;
        tally tl = { 0 };
        char tag[256];
        snprintf(tag, sizeof tag, "%.*s-%s-%.2f", (int)strcspn(base_name(scene), "."), base_name(scene), pack,
                 o->scales[s]);
        for (int i = 0; i < o->ntimes; i++) one_instant(o, g, r, o->times[i], o->scales[s], &tl, tag);
        double n = tl.n ? tl.n : 1;
        printf("| %s | %s | %dx%d | %.4f | %.4f | %.4f | %.0f%% | %.4f | %.4f | %.4f | %.4f | %.4f | %.4f | %.0f%% | %.0f | %.1f |\n",
               base_name(scene), pack, rw, rh, tl.bil.rmse / n, tl.edge.rmse / n, tl.over.rmse / n,
               100 * (1 - tl.over.rmse / tl.bil.rmse), tl.bil.ssim / n, tl.edge.ssim / n, tl.over.ssim / n,
               tl.bil.flip / n, tl.edge.flip / n, tl.over.flip / n, 100 * (1 - tl.over.flip / tl.bil.flip), world_ms, tl.frame_ms / n);
        fflush(stdout);
    }
    render_destroy(r);
}

static int cmp_ms(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* One enlargement of the canvas's rw x rh into w x h: by u, or the sharp
 * world's over g->full when over (the truth target stands in for the
 * snapshot: the cost does not depend on what the texels hold). */
static void upscale_once(upscaler *u, rig *g, bool over, int rw, int rh, int w, int h) {
    upscale_rect rect = { 0, 0, w, h };
    if (!over || !upscale_draw_over_world(u, g->canvas.color, g->truth_tg.color, rw, rh, g->full.color, g->out.fbo, rect))
        upscale_draw(u, g->canvas.color, rw, rh, g->out.fbo, rect);
}

/* The upscaler's own time into w x h from rw x rh: median of 15 runs of 4
 * draws each, each run ended by glFinish. */
static double time_upscale(upscaler *u, rig *g, bool over, int rw, int rh, int w, int h) {
    double runs[15];
    glEnable(GL_FRAMEBUFFER_SRGB);
    upscale_once(u, g, over, rw, rh, w, h);
    glFinish();
    for (int i = 0; i < 15; i++) {
        double t0 = clock_now_s();
        for (int k = 0; k < 4; k++) upscale_once(u, g, over, rw, rh, w, h);
        glFinish();
        runs[i] = (clock_now_s() - t0) * 1e3 / 4;
    }
    qsort(runs, 15, sizeof runs[0], cmp_ms);
    return runs[7];
}

static void timings(const opts *o, rig *g) {
    printf("\nupscaler's own time per frame into %dx%d (ms, median):\n\n", o->w, o->h);
    printf("| from | bilinear blit | cubic | sharp world |\n|---|---|---|---|\n");
    for (int s = 0; s < o->nscales; s++) {
        int rw = (int)lround(o->scales[s] * o->w), rh = (int)lround(o->scales[s] * o->h);
        printf("| %dx%d | %.2f | %.2f | %.2f |\n", rw, rh, time_upscale(g->bil, g, false, rw, rh, o->w, o->h),
               time_upscale(g->edge, g, false, rw, rh, o->w, o->h), time_upscale(g->bil, g, true, rw, rh, o->w, o->h));
    }
}

int main(int argc, char **argv) {
    opts o = parse(argc, argv);
    char err[MSG_MAX];
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    if (!ctx) { fprintf(stderr, "bench_upscale: no OpenGL: %s\n", err); return 3; }
    printf("renderer: %s\n", (const char *)glGetString(GL_RENDERER));
    rig g = { 0 };
    const char *uerr = NULL;
    g.bil = upscale_create(&(upscale_desc){ .filter = UPSCALE_BILINEAR }, NULL);
    g.edge = upscale_create(&(upscale_desc){ .sharpness = o.sharpness }, &uerr);
    if (uerr) fprintf(stderr, "%s\n", uerr);
    if (!render_target_create_srgb(&g.truth_tg, o.w, o.h) || !render_target_create_srgb(&g.canvas, o.w, o.h) ||
        !render_target_create_srgb(&g.out, o.w, o.h) || !render_target_create_srgb(&g.full, o.w, o.h)) {
        fprintf(stderr, "bench_upscale: no %dx%d targets\n", o.w, o.h);
        return 1;
    }
    g.truth = mem_alloc((size_t)o.w * o.h * 3 * sizeof(float));
    g.test = mem_alloc((size_t)o.w * o.h * 3 * sizeof(float));
    timings(&o, &g);
    printf("\nerror against the full-resolution frame (mean of %d instants; FLIP at %.0f px/degree):\n\n", o.ntimes,
           REF_FLIP_PPD);
    printf("| scene | pack | drawn at | RMSE bilinear | RMSE cubic | RMSE sharp world | RMSE cut | SSIM bilinear | "
           "SSIM cubic | SSIM sharp world | FLIP bilinear | FLIP cubic | FLIP sharp world | FLIP cut | world frame ms | "
           "reduced frame ms |\n"
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int s = 0; s < o.nscenes; s++)
        for (int p = 0; p < o.npacks; p++) run_case(&o, &g, o.scenes[s], o.packs[p]);
    free(g.truth);
    free(g.test);
    render_target_destroy(&g.truth_tg);
    render_target_destroy(&g.canvas);
    render_target_destroy(&g.out);
    render_target_destroy(&g.full);
    upscale_destroy(g.bil);
    upscale_destroy(g.edge);
    gl_ctx_destroy(ctx);
    return 0;
}
