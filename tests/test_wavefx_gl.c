/* The explosion rings and Perlin wave sets exist twice:
 * packs/common/waves_fx.glsl (float, on the GPU) and reference/ref_wavefx.c
 * (double). This renders wavesExplosions, wavesPerlin and wavesPerlin3 on
 * llvmpipe into a float target for a grid of points at several times (before
 * the start, exactly at it, just after it, and later; one ring's centre is
 * a pixel centre, so r = 0 exactly) and compares height and gradient with
 * the C functions, which get the same float inputs.
 *
 * Tolerances (waves_fx.glsl's precision note): the ring's phase
 * q - omega tau reaches ~130 rad here, so float rounding of q and omega tau
 * gives up to ~3 * 2^-24 * 130 = 2.3e-5 rad; heights are off by at most
 * |I0| times that (7e-6 m at I0 = 0.3) and slopes by 1.28 |I0| k times it
 * (5e-5 at k = 2 pi), plus llvmpipe's sin/cos error (~1e-6 relative after
 * range reduction). Perlin lattice coordinates are < 60 cells here: the
 * fraction inside a cell is off by ~60 * 2^-23 = 7e-6 cells, worth
 * 3.75 sqrt(2) * 7e-6 = 4e-5 of A_o in height and more in slope (f_o up
 * to 8 / m). So: heights within 5e-5 m, gradients within 5e-4, and
 * wavesPerlin3 (same float lattice coordinates on both sides) within 1e-5;
 * a wrong term (amplitudes 0.1..0.3, slopes ~1) shows at 1e-2 or more. */
#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "support.h"
#include "gl_ctx.h"
#include "gl_support.h"
#include "ref_wavefx.h"
#include "render.h"
#include "shader_src.h"

#define N 48              /* grid of N x N points */
#define EXTENT 9.0        /* rest points over [-EXTENT, EXTENT]^2 */
#define TOL_H 5e-5
#define TOL_G 5e-4
#define TOL_P3 1e-5

static GLuint compile(GLenum type, const char *name) {
    char path[512];
    snprintf(path, sizeof path, "%s/%s", scratch_dir, name);
    return gl_test_compile(type, path, NULL, 0);
}

static GLuint program(void) {
    GLuint vs = compile(GL_VERTEX_SHADER, "grid.vert");
    GLuint fs = compile(GL_FRAGMENT_SHADER, "grid.frag");
    return gl_test_link(vs, fs);
}

static void upload(GLuint p, const ref_explosion_desc *e, int n, const ref_perlin_desc *pd) {
    ref_waves_uniform u[REF_WAVEFX_UNIFORMS_MAX];
    int k = ref_wavefx_uniforms(e, n, pd, u, REF_WAVEFX_UNIFORMS_MAX);
    for (int i = 0; i < k; i++) {
        GLint loc = glGetUniformLocation(p, u[i].name);
        if (loc < 0) { fprintf(stderr, "  (uniform %s unused)\n", u[i].name); continue; }
        if (u[i].is_int) glUniform1i(loc, u[i].i);
        else if (u[i].is_uint) glUniform1uiv(loc, u[i].count, u[i].u);
        else if (u[i].comps == 4) glUniform4fv(loc, u[i].count, u[i].v);
        else if (u[i].comps == 3) glUniform3fv(loc, u[i].count, u[i].v);
        else glUniform1fv(loc, u[i].count, u[i].v);
    }
}

/* Draws mode 0 (rings), 1 (Perlin set) or 2 (raw noise3) at time / z;
 * returns RGBA rows from the top. */
static void draw(GLuint p, int mode, float t, uint32_t seed, float *out) {
    render_target rt;
    render_target_create(&rt, N, N, true);
    glBindFramebuffer(GL_FRAMEBUFFER, rt.fbo);
    glViewport(0, 0, N, N);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(p);
    glUniform1i(glGetUniformLocation(p, "uMode"), mode);
    glUniform1f(glGetUniformLocation(p, "uTime"), t);
    glUniform1f(glGetUniformLocation(p, "uExtent"), (float)EXTENT);
    glUniform1ui(glGetUniformLocation(p, "uSeed"), seed);
    glRectf(-1, -1, 1, 1);
    glUseProgram(0);
    render_target_read(&rt, out);
    render_target_destroy(&rt);
}

/* Pixel (i, j from the top) -> its GL column and row. */
static int gl_row(int j) { return N - 1 - j; }
/* The rest point of a pixel, as grid.frag computes it (exact in float). */
static double rest(int c) { return -EXTENT + (c + 0.5) * 2 * EXTENT / N; }
/* The noise3 lattice point of a pixel: (c - 24) / 4, exact. */
static double lat(int c) { return (c - 24) * 0.25; }

static const ref_explosion_desc *g_rings;
static int g_nrings;
static const ref_perlin_desc *g_perlin;

static double eval(int mode, double x, double z, double t, uint32_t seed, double g[3]) {
    g[0] = g[1] = g[2] = 0.0;
    if (mode == 0) {
        double h = 0;
        for (int r = 0; r < g_nrings; r++) {
            double gr[2];
            h += ref_explosion_height(&g_rings[r], x, z, t, gr);
            g[0] += gr[0]; g[1] += gr[1];
        }
        return h;
    }
    if (mode == 1) return ref_perlin_height(g_perlin, x, z, t, g);
    return ref_perlin3(x, z, t, seed, g);
}

/* Worst height and gradient differences over the grid. */
static void compare(GLuint p, int mode, float t, uint32_t seed, double *wh, double *wg, double *hmax) {
    static float img[N * N * 4];
    draw(p, mode, t, seed, img);
    *wh = *wg = *hmax = 0;
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            int row = gl_row(j);
            double x = mode == 2 ? lat(i) : rest(i), z = mode == 2 ? lat(row) : rest(row);
            double g[3];
            double h = eval(mode, x, z, (double)t, seed, g);
            const float *px = &img[(j * N + i) * 4];
            *hmax = fmax(*hmax, fabs(h));
            *wh = fmax(*wh, fabs(px[0] - h));
            for (int k = 0; k < (mode == 2 ? 3 : 2); k++) *wg = fmax(*wg, fabs(px[1 + k] - g[k]));
        }
}

static GLuint g_prog;

static void test_rings_match_reference(void) {
    ref_explosion_desc e[3] = {
        { { -9 + 0.1875 + 0.375 * 28, -9 + 0.1875 + 0.375 * 18 }, 0.75, 0.3, 0, 0, 0.15 },  /* centre on a pixel */
        { { -3.1, 4.2 }, 1.5, -0.2, 3.0, 2.5, 0 },
        { { 2.0, 2.0 }, 0.0, 0.0, 0, 0, 0 },                                              /* I0 = 0: none */
    };
    for (int i = 0; i < 3; i++) CHECK_EQ(ref_explosion_resolve(&e[i], NULL, 0), 0);
    g_rings = e; g_nrings = 3;
    glUseProgram(g_prog);
    upload(g_prog, e, 3, NULL);
    float times[] = { 0.25f, 0.75f, 0.751f, 0.75f + 1.0f / 7.85f + 0.05f, 1.5f, 2.0f, 4.0f, 6.25f };
    for (int k = 0; k < 8; k++) {
        double wh, wg, hmax;
        compare(g_prog, 0, times[k], 0, &wh, &wg, &hmax);
        fprintf(stderr, "  rings t = %.4f: max |h| %.3g, worst height error %.3g, gradient error %.3g\n",
                times[k], hmax, wh, wg);
        CHECK_LE(wh, TOL_H);
        CHECK_LE(wg, TOL_G);
        if (k >= 4) CHECK_GT(hmax, 0.02);       /* something to compare */
    }
    /* exactly at r = 0, later: finite, gradient 0 on both sides */
    static float img[N * N * 4];
    draw(g_prog, 0, 3.0f, 0, img);
    const float *c = &img[((N - 1 - 18) * N + 28) * 4];
    double g[3];
    double h = eval(0, e[0].center[0], e[0].center[1], 3.0, 0, g);
    CHECK(isfinite(c[0]) && fabs(c[0] - h) <= TOL_H);
    CHECK(fabs(c[1] - g[0]) <= TOL_G && fabs(c[2] - g[1]) <= TOL_G);
}

static void test_perlin_set_matches_reference(void) {
    ref_perlin_desc pd = { 0.2, 2.0, 5, 0.5, 2.0, 30.0, 0.6, 99 };
    CHECK_EQ(ref_perlin_resolve(&pd, NULL, 0), 0);
    g_perlin = &pd;
    glUseProgram(g_prog);
    upload(g_prog, NULL, 0, &pd);
    float times[] = { 0.0f, 0.5f, 3.7f, 12.0f };
    for (int k = 0; k < 4; k++) {
        double wh, wg, hmax;
        compare(g_prog, 1, times[k], 0, &wh, &wg, &hmax);
        fprintf(stderr, "  perlin set t = %.2f: max |h| %.3g, worst height error %.3g, gradient error %.3g\n",
                times[k], hmax, wh, wg);
        CHECK_LE(wh, TOL_H);
        CHECK_LE(wg, TOL_G);
        CHECK_GT(hmax, 0.05);
    }
}

static void test_perlin3_matches_reference(void) {
    float zs[] = { -2.0f, 0.3f, 7.625f };
    uint32_t seeds[] = { 0u, 12345u, 0xdeadbeefu };
    for (int k = 0; k < 3; k++) {
        double wh, wg, hmax;
        compare(g_prog, 2, zs[k], seeds[k], &wh, &wg, &hmax);
        fprintf(stderr, "  perlin3 z = %.3f seed %u: max |n| %.3g, worst value error %.3g, gradient error %.3g\n",
                zs[k], seeds[k], hmax, wh, wg);
        CHECK_LE(wh, TOL_P3);
        CHECK_LE(wg, 10 * TOL_P3);
    }
}

/* No rings and no Perlin set: both sums are exactly 0. */
static void test_nothing_is_zero(void) {
    glUseProgram(g_prog);
    upload(g_prog, NULL, 0, NULL);
    static float img[N * N * 4];
    for (int mode = 0; mode < 2; mode++) {
        draw(g_prog, mode, 2.0f, 0, img);
        int nonzero = 0;
        for (int i = 0; i < N * N * 4; i += 4)
            if (img[i] != 0 || img[i + 1] != 0 || img[i + 2] != 0) nonzero++;
        CHECK_EQ(nonzero, 0);
    }
}

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    if (!scratch_create("wavefx")) return 1;
    scratch_write("grid.vert", "#version 330 compatibility\n"
                               "void main() { gl_Position = gl_Vertex; }\n");
    scratch_write("grid.frag",
                  "#version 330 compatibility\n#include \"waves_fx.glsl\"\n"
                  "uniform float uTime;\nuniform float uExtent;\nuniform int uMode;\nuniform uint uSeed;\n"
                  "out vec4 c;\n"
                  "void main() {\n"
                  "  vec2 rest = -uExtent + gl_FragCoord.xy * 2.0 * uExtent / 48.0;\n"
                  "  vec2 g; vec3 g3; float h;\n"
                  "  if (uMode == 0) { h = wavesExplosions(rest, uTime, g); c = vec4(h, g, 0.0); }\n"
                  "  else if (uMode == 1) { h = wavesPerlin(rest, uTime, g); c = vec4(h, g, 0.0); }\n"
                  "  else { h = wavesPerlin3(vec3((gl_FragCoord.xy - 24.5) * 0.25, uTime), uSeed, g3);\n"
                  "         c = vec4(h, g3); }\n"
                  "}\n");
    g_prog = program();
    CHECK_NE(g_prog, 0);
    if (g_prog) {
        RUN(test_rings_match_reference);
        RUN(test_perlin_set_matches_reference);
        RUN(test_perlin3_matches_reference);
        RUN(test_nothing_is_zero);
        glDeleteProgram(g_prog);
    }
    gl_ctx_destroy(ctx);
    scratch_remove();
    return check_summary();
}
