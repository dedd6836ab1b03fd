/* bench_spray: what the spray costs per 1000 particles (issue #29), for
 * docs/benchmark.md's cost model (a tool, not a test: its figures are
 * timings, nothing passes or fails).
 *
 * The world: scenes/waves/spray.glib's (the tiled pool, an explosion ring
 * I0 0.9 m, k 5.2, decay 0.3 born at t = 1 s) under a swell (a wave 8 m
 * long, 0.4 m high), with the spray's threshold at 0 m/s and its rate
 * high, so every dead slot whose candidate point rises emits at once. For each slot count, it times (glFinish'd wall,
 * median of BENCH_SPRAY_FRAMES frames of 1/30 s, after a warm-up second)
 * the update pass (every slot, live or dead: one texel each) and the draw
 * (the live ones, 4 cm droplets seen from scenes/waves/base.glib's camera
 * into a size target, 4 x 4 to 10 x 10 pixel discs), counts the live
 * particles, and fits ms = a + b n by least squares for each.
 *
 *   bench_spray [--size WxH] [--counts n1,n2,..]
 *
 * Defaults: 480x270 and 4096, 16384, 65536, 262144 slots. */
#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_ctx.h"
#include "strbuf.h"
#include "mem.h"
#include "render.h"
#include "render_world.h"
#include "util.h"

#define BENCH_SPRAY_FRAMES 15
#define MAX_COUNTS 8

/* column-major perspective(fov_y, aspect) * lookAt(eye, centre, up y) */
static void view_proj(const float eye[3], const float c[3], double fov_deg, double aspect, float out[16]) {
    double f[3] = { c[0] - eye[0], c[1] - eye[1], c[2] - eye[2] }, l = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int i = 0; i < 3; i++) f[i] /= l;
    double s[3] = { f[1] * 0 - f[2] * 1, f[2] * 0 - f[0] * 0, f[0] * 1 - f[1] * 0 };   /* f x (0,1,0) */
    l = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    for (int i = 0; i < 3; i++) s[i] /= l;
    double u[3] = { s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2], s[0] * f[1] - s[1] * f[0] };
    double V[16] = { s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0, 0, 0, 0, 1 };
    V[12] = -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]);
    V[13] = -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]);
    V[14] = f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2];
    double n = 0.1, fa = 200, t = 1.0 / tan(fov_deg * M_PI / 360);
    double P[16] = { t / aspect, 0, 0, 0, 0, t, 0, 0, 0, 0, (fa + n) / (n - fa), -1, 0, 0, 2 * fa * n / (n - fa), 0 };
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++) {
            double a = 0;
            for (int k = 0; k < 4; k++) a += P[k * 4 + row] * V[col * 4 + k];
            out[col * 4 + row] = (float)a;
        }
}

static void fit(const double *x, const double *y, int n, double *a, double *b) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int i = 0; i < n; i++) { sx += x[i]; sy += y[i]; sxx += x[i] * x[i]; sxy += x[i] * y[i]; }
    *b = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    *a = (sy - *b * sx) / n;
}

int main(int argc, char **argv) {
    int w = 480, h = 270, counts[MAX_COUNTS] = { 4096, 16384, 65536, 262144 }, ncounts = 4;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--size") == 0 && i + 1 < argc) {
            if (sscanf(argv[++i], "%dx%d", &w, &h) != 2) return 2;
        } else if (strcmp(argv[i], "--counts") == 0 && i + 1 < argc) {
            ncounts = 0;
            for (char *p = argv[++i]; *p && ncounts < MAX_COUNTS;) {
                counts[ncounts++] = (int)strtol(p, &p, 10);
                if (*p == ',') p++;
            }
        } else {
            fputs("usage: bench_spray [--size WxH] [--counts n1,n2,..]\n", stderr);
            return 2;
        }
    }
    char err[MSG_MAX];
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    if (!ctx) { fprintf(stderr, "bench_spray: %s\n", err); return 3; }
    char common[4096];
    snprintf(common, sizeof common, "%s/packs/common", tarn_root());
    const char *inc[1] = { common };
    render_target tg;
    if (!render_target_create(&tg, w, h, true)) return 3;
    const float eye[3] = { 0, 3.2f, 6.5f }, centre[3] = { 0, -1.2f, -1.5f };
    float vp[16];
    view_proj(eye, centre, 50, (double)w / h, vp);
    double n_slots[MAX_COUNTS], n_live[MAX_COUNTS], up_ms[MAX_COUNTS], draw_ms[MAX_COUNTS];
    printf("spray cost at %dx%d (median of %d frames, glFinish'd wall time):\n\n", w, h, BENCH_SPRAY_FRAMES);
    printf("| slots | live | update ms | draw ms |\n|---|---|---|---|\n");
    for (int c = 0; c < ncounts; c++) {
        ref_world_desc desc;
        memset(&desc, 0, sizeof desc);
        desc.terrain = REF_TERRAIN_POOL;
        desc.depth = 1.5;
        desc.shore_height = 0.4;
        desc.waves.gerstner_count = 1;   /* a swell: half the square rises at up to 1.1 m/s */
        desc.waves.gerstner[0] = (ref_wave_desc){ .angle_deg = 20, .wavelength = 8, .amplitude = 0.4 };
        desc.waves.explosion_count = 1;
        desc.waves.explosion[0] = (ref_explosion_desc){ .center = { 0, -1 }, .start = 1.0, .i0 = 0.9, .k = 5.2, .decay = 0.3 };
        desc.spray = (ref_spray_desc){ .on = true, .threshold = 0, .rate = 1e9, .life = 2, .size = 0.04, .seed = 1,
                                       .count = counts[c] };
        gpu_world gw;
        memset(&gw, 0, sizeof gw);
        diag_list log = { 0 };
        if (!world_build(&gw, &desc, &(prog_sources){ .include_dirs = inc, .ninclude_dirs = 1, .common_dir = common },
                         &log, NULL)) {
            char *text = log.n ? diag_list_format(&log, 0) : NULL;
            fprintf(stderr, "bench_spray: %s\n", text ? text : "the world does not build");
            free(text);
            diag_list_free(&log);
            return 1;
        }
        diag_list_free(&log);
        for (int s = 0; s <= 30; s++) world_update_spray(&gw, 1.0 + s / 30.0, NULL);   /* warm: a second */
        glFinish();
        double u[BENCH_SPRAY_FRAMES], d[BENCH_SPRAY_FRAMES];
        for (int i = 0; i < BENCH_SPRAY_FRAMES; i++) {
            double t0 = clock_now_s();
            world_update_spray(&gw, 2.0 + (i + 1) / 30.0, NULL);
            glFinish();
            u[i] = (clock_now_s() - t0) * 1e3;
            glBindFramebuffer(GL_FRAMEBUFFER, tg.fbo);
            glViewport(0, 0, w, h);
            glClearColor(0, 0, 0, 0);
            glClearDepth(1);
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            glFinish();
            t0 = clock_now_s();
            world_draw_spray(&gw, vp, eye, w, h);
            glFinish();
            d[i] = (clock_now_s() - t0) * 1e3;
        }
        int res = gw.spray.res;
        float *pos = mem_alloc((size_t)res * res * 4 * sizeof(float)), *vel = mem_alloc((size_t)res * res * 4 * sizeof(float));
        spray_read(&gw.spray, pos, vel);
        int live = 0;
        for (int i = 0; i < res * res; i++) live += pos[4 * i + 3] > 0;
        free(pos);
        free(vel);
        n_slots[c] = counts[c];
        n_live[c] = live;
        up_ms[c] = median_double(u, BENCH_SPRAY_FRAMES);
        draw_ms[c] = median_double(d, BENCH_SPRAY_FRAMES);
        printf("| %d | %d | %.3f | %.3f |\n", counts[c], live, up_ms[c], draw_ms[c]);
        world_free(&gw);
    }
    double a, b;
    fit(n_slots, up_ms, ncounts, &a, &b);
    printf("\nupdate: %.3f ms + %.4f ms per 1000 slots\n", a, b * 1000);
    fit(n_live, draw_ms, ncounts, &a, &b);
    printf("draw:   %.3f ms + %.4f ms per 1000 live particles\n", a, b * 1000);
    render_target_destroy(&tg);
    gl_ctx_destroy(ctx);
    return 0;
}
