/* bench_msaa_cells: what multisampling costs a rasteriser per triangle
 * size (a tool, not a test: its figures are timings, nothing passes or
 * fails).
 *
 * Why it is here: `tarn render`'s default 4x MSAA costs 3.4-4.4 times a
 * single-sample animated frame on llvmpipe, where the water is drawn as
 * its grid (docs/benchmark.md). A CPU rasteriser shades blocks of pixels,
 * and every triangle touching a block pays for all of it; with 4 samples a
 * pixel a small triangle covers more pixels' samples than their centres,
 * so a fine grid is shaded more often. This draws a screen of cells of
 * C x C pixels (two triangles each) with a shader of fixed cost, depth
 * tested, at 1 and at N samples, and prints the wall time per draw (the
 * best of a few, glFinish'd) and the fragment shader invocations the GL
 * counts (GL_ARB_pipeline_statistics_query; "-" where the GL has none).
 * A cell of the full screen is one triangle pair: the shader's own cost.
 *
 *   bench_msaa_cells [--size WxH] [--samples N] [--loop K]
 *
 * Defaults: 960x540, 4 samples, 100 iterations of the shader's loop. */
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES
#endif
#include <GL/gl.h>
#include <GL/glext.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "gl_ctx.h"

static const char *vs_src =
    "#version 330\n"
    "uniform vec2 cells;\n"
    "void main() {\n"
    "    int q = gl_VertexID / 6, k = gl_VertexID % 6;\n"
    "    ivec2 o[6] = ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(0, 1), ivec2(1, 0), ivec2(1, 1), ivec2(0, 1));\n"
    "    vec2 cell = vec2(q % int(cells.x), q / int(cells.x));\n"
    "    gl_Position = vec4((cell + vec2(o[k])) / cells * 2.0 - 1.0, 0.5, 1.0);\n"
    "}\n";

/* a fixed amount of arithmetic a fragment, its result kept */
static const char *fs_src =
    "#version 330\n"
    "uniform int n;\n"
    "out vec4 colour;\n"
    "void main() {\n"
    "    vec2 p = gl_FragCoord.xy * 0.01;\n"
    "    float a = 0.0;\n"
    "    for (int i = 0; i < n; i++) a += sin(p.x + a) * cos(p.y - a);\n"
    "    colour = vec4(a, 0.0, 0.0, 1.0);\n"
    "}\n";

static double now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

static GLuint stage(GLenum type, const char *src) {
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    return s;
}

static GLuint program(void) {
    GLuint p = glCreateProgram();
    glAttachShader(p, stage(GL_VERTEX_SHADER, vs_src));
    glAttachShader(p, stage(GL_FRAGMENT_SHADER, fs_src));
    glLinkProgram(p);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048];
        glGetProgramInfoLog(p, sizeof log, NULL, log);
        fprintf(stderr, "bench_msaa_cells: the program does not link: %s\n", log);
        exit(1);
    }
    return p;
}

/* A colour and depth framebuffer of w x h at `samples` (1: single-sample). */
static GLuint framebuffer(int w, int h, int samples, GLuint rb[2]) {
    GLuint fb;
    glGenFramebuffers(1, &fb);
    glBindFramebuffer(GL_FRAMEBUFFER, fb);
    glGenRenderbuffers(2, rb);
    const GLenum formats[2] = { GL_RGBA16F, GL_DEPTH_COMPONENT24 };
    const GLenum points[2] = { GL_COLOR_ATTACHMENT0, GL_DEPTH_ATTACHMENT };
    for (int k = 0; k < 2; k++) {
        glBindRenderbuffer(GL_RENDERBUFFER, rb[k]);
        if (samples > 1) glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, formats[k], w, h);
        else glRenderbufferStorage(GL_RENDERBUFFER, formats[k], w, h);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, points[k], GL_RENDERBUFFER, rb[k]);
    }
    return fb;
}

/* The best of 4 glFinish'd draws of cells of `cell` pixels, and the
 * invocations counted in the last (-1: not counted). */
static double time_draw(GLuint prg, int w, int h, int cell, long long *invocations) {
    int cx = cell > 0 ? w / cell : 1, cy = cell > 0 ? h / cell : 1;
    glUniform2f(glGetUniformLocation(prg, "cells"), (float)cx, (float)cy);
    GLsizei nv = cx * cy * 6;
    bool stats = strstr((const char *)glGetString(GL_EXTENSIONS), "GL_ARB_pipeline_statistics_query") != NULL;
    GLuint q = 0;
    if (stats) glGenQueries(1, &q);
    double best = 1e300;
    for (int r = 0; r < 5; r++) {   /* the first compiles the shader's variant */
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glFinish();
        if (stats) glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, q);
        double t0 = now_ms();
        glDrawArrays(GL_TRIANGLES, 0, nv);
        glFinish();
        double t = now_ms() - t0;
        if (stats) glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
        if (r > 0 && t < best) best = t;
    }
    *invocations = -1;
    if (stats) {
        GLuint64 n = 0;
        glGetQueryObjectui64v(q, GL_QUERY_RESULT, &n);
        *invocations = (long long)n;
        glDeleteQueries(1, &q);
    }
    return best;
}

int main(int argc, char **argv) {
    int w = 960, h = 540, samples = 4, loop = 100;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--size") == 0 && i + 1 < argc && sscanf(argv[i + 1], "%dx%d", &w, &h) == 2) i++;
        else if (strcmp(argv[i], "--samples") == 0 && i + 1 < argc) samples = atoi(argv[++i]);
        else if (strcmp(argv[i], "--loop") == 0 && i + 1 < argc) loop = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_msaa_cells [--size WxH] [--samples N] [--loop K]\n");
            return 2;
        }
    }
    if (w < 16 || h < 16 || samples < 2 || loop < 1) {
        fprintf(stderr, "bench_msaa_cells: --size at least 16x16, --samples at least 2, --loop at least 1\n");
        return 2;
    }
    char err[512];
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    if (!ctx) { fprintf(stderr, "bench_msaa_cells: %s\n", err); return 3; }
    printf("bench_msaa_cells: %dx%d, %s, a shader loop of %d, depth tested\n", w, h,
           (const char *)glGetString(GL_RENDERER), loop);
    printf("| cell | 1 sample, ms | %d samples, ms | ratio | invocations, 1 / %d |\n|---|---:|---:|---:|---|\n",
           samples, samples);
    GLuint vao, prg = program();
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glUseProgram(prg);
    glUniform1i(glGetUniformLocation(prg, "n"), loop);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glViewport(0, 0, w, h);
    const int cells[] = { 1, 2, 4, 8, 16, 0 };   /* 0: the whole screen */
    for (size_t c = 0; c < sizeof cells / sizeof *cells; c++) {
        double ms[2];
        long long inv[2];
        for (int k = 0; k < 2; k++) {
            GLuint rb[2], fb = framebuffer(w, h, k ? samples : 1, rb);
            ms[k] = time_draw(prg, w, h, cells[c], &inv[k]);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            glDeleteFramebuffers(1, &fb);
            glDeleteRenderbuffers(2, rb);
        }
        char cell[32], counts[64] = "-";
        if (cells[c]) snprintf(cell, sizeof cell, "%d px", cells[c]);
        else snprintf(cell, sizeof cell, "the screen");
        if (inv[0] >= 0) snprintf(counts, sizeof counts, "%lld / %lld", inv[0], inv[1]);
        printf("| %s | %.1f | %.1f | %.2fx | %s |\n", cell, ms[0], ms[1], ms[1] / ms[0], counts);
    }
    gl_ctx_destroy(ctx);
    return 0;
}
