/* `tarn render`: draws a glib without any display through EGL and writes
 * the image through OpenImageIO. Deterministic for a fixed --time. */
#include <GL/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "util.h"
#include "cli.h"
#include "gl_ctx.h"
#include "image_io.h"
#include "packset.h"
#include "ref_metrics.h"
#include "render.h"

const char *cli_default_scene(void) {
    static char path[4096];
    snprintf(path, sizeof path, "%s/scenes/pond.glib", tarn_root());
    return path;
}

static bool wants_float(const char *path) {
    const char *dot = strrchr(path, '.');
    return dot && (strcmp(dot, ".exr") == 0 || strcmp(dot, ".hdr") == 0 || strcmp(dot, ".tif") == 0);
}

/* A scene with a world is lit in linear radiance (as the reference): float
 * files keep it linear, 8-bit ones get the sRGB encoding a display expects
 * (like the reference's PNG). A plain glman scene is written as drawn. */
static bool write_target(const render_target *t, const char *path, bool encode_srgb, char *err, int errlen) {
    img im;
    memset(&im, 0, sizeof im);
    if (!img_alloc(&im, t->w, t->h, 4)) { snprintf(err, errlen, "out of memory"); return false; }
    bool ok = render_target_read(t, im.px);
    if (!ok) snprintf(err, errlen, "reading the framebuffer failed");
    if (ok && encode_srgb && !wants_float(path))
        for (long i = 0; i < (long)t->w * t->h; i++)
            for (int k = 0; k < 3; k++) im.px[i * 4 + k] = (float)ref_linear_to_srgb(im.px[i * 4 + k]);
    /* 32-bit float .exr, as the help says and as the reference writes: a
     * half's 11 bits quantise hit-point buffers to 4-8 mm at the lake's
     * coordinates, coarser than the errors worth measuring */
    if (ok) ok = img_write_float(path, &im, err, errlen);
    img_free(&im);
    return ok;
}

/* out with its first "%d" replaced by the frame number (frame < 0: as is). */
static void frame_path(char *path, size_t len, const char *out, int frame) {
    const char *pct = frame >= 0 ? strstr(out, "%d") : NULL;
    if (!pct) { snprintf(path, len, "%s", out); return; }
    snprintf(path, len, "%.*s%04d%s", (int)(pct - out), out, frame, pct + 2);
}

static double now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* --set: what moving a slider or ticking a Define would do, written as
 * bench.txt assignments (PROGRAM.NAME=V, or NAME=V for every Program). */
static bool apply_sets(render *r, const cli_render_desc *d) {
    if (d->nsets == 0) return true;
    char text[4096] = "cli";
    size_t n = strlen(text);
    for (int i = 0; i < d->nsets && n < sizeof text; i++) {
        const char *eq = strchr(d->sets[i], '='), *dot = strchr(d->sets[i], '.');
        bool bare = !dot || (eq && dot > eq);
        n += (size_t)snprintf(text + n, sizeof text - n, " %s%s", bare ? "*." : "", d->sets[i]);
    }
    packset_bench b;
    char err[2048] = "";
    bool ok = packset_bench_parse(text, "--set", &b, err, sizeof err) && b.n > 0;
    bool defines = false;
    int nsets;
    unif_set *sets = render_uniforms(r, &nsets);
    if (ok) ok = packset_apply(sets, nsets, &b.settings[0], &defines, err, sizeof err);
    if (defines) render_rebuild_programs(r);
    if (err[0]) fprintf(stderr, "tarn: --set: %s\n", err);
    packset_bench_free(&b);
    return ok;
}

int cli_render(const cli_render_desc *d) {
    char err[1024];
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    if (!ctx) { fprintf(stderr, "tarn: %s\n", err); return TARN_EXIT_NO_GL; }
    render_desc rd = { .pack = d->pack };
    render *r = render_create(&rd);
    bool ok = render_load(r, d->glib);
    if (render_messages(r)[0]) fputs(render_messages(r), stderr);
    if (!apply_sets(r, d)) ok = false;
    int w = d->width, h = d->height;
    if (w <= 0 || h <= 0) render_window_size(r, &w, &h);
    render_target t;
    bool linear_scene = render_has_world(r);
    if (!render_target_create(&t, w, h, wants_float(d->out) || linear_scene)) {
        fprintf(stderr, "tarn: cannot create a %dx%d framebuffer\n", w, h);
        render_destroy(r);
        gl_ctx_destroy(ctx);
        return TARN_EXIT_NO_GL;
    }
    int frames = d->frames > 0 ? d->frames : 1;
    double *ms = calloc((size_t)frames, sizeof *ms);
    double *wall = calloc((size_t)frames, sizeof *wall);
    bool per_frame = strstr(d->out, "%d") != NULL;
    int rc = ok ? TARN_EXIT_OK : TARN_EXIT_INPUT;
    for (int f = 0; f < frames; f++) {
        double t0 = now_ms();
        render_frame(r, d->time_s + f / 60.0, t.fbo, w, h, NULL);
        glFinish();   /* wall time of the whole frame, including deferred rasterisation */
        if (gl_ctx_lost(ctx, err, sizeof err)) {   /* a GPU reset: nothing drawn can be trusted */
            fprintf(stderr, "tarn: %s\n", err);
            rc = TARN_EXIT_NO_GL;
            break;
        }
        if (wall) wall[f] = now_ms() - t0;
        if (ms) ms[f] = render_gpu_ms(r, true);
        if (per_frame || f == frames - 1) {
            char path[2048];
            frame_path(path, sizeof path, d->out, per_frame ? f : -1);
            if (!write_target(&t, path, linear_scene, err, sizeof err)) {
                fprintf(stderr, "tarn: %s\n", err);
                rc = TARN_EXIT_INPUT;
                break;
            }
            if (!d->quiet && (!per_frame || f == frames - 1))
                printf("tarn: wrote %s (%dx%d, t=%.3f s)\n", path, w, h, d->time_s + f / 60.0);
        }
    }
    if (ms && wall && !d->quiet && rc != TARN_EXIT_NO_GL) {
        qsort(ms, (size_t)frames, sizeof *ms, cmp_double);
        qsort(wall, (size_t)frames, sizeof *wall, cmp_double);
        printf("tarn: %d frame(s) at %dx%d: median GPU time %.3f ms, wall %.3f ms, on %s\n", frames, w, h,
               ms[frames / 2], wall[frames / 2], gl_ctx_describe(ctx));
    }
    free(ms);
    free(wall);
    render_target_destroy(&t);
    render_destroy(r);
    gl_ctx_destroy(ctx);
    return rc;
}
