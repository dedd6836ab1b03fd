/* The wave set exists twice: packs/common/waves.glsl (float, on the GPU)
 * and reference/ref_waves.c (double). This renders displaced positions and
 * both normals on llvmpipe into a float target and compares them with the
 * C version on a grid of rest points.
 *
 * Tolerance 1e-4 (metres for positions, unit-vector components for
 * normals): float32 phases k.x + w t reach ~100 rad here, so rounding alone
 * gives errors ~1e-5; 1e-4 leaves a 10x margin, while any wrong term of
 * the formulas (amplitudes 0.02..0.3) shows at 1e-3 or more. */
#include <GL/gl.h>
#include <GL/glext.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "support.h"
#include "gl_ctx.h"
#include "gl_support.h"
#include "ref_waves.h"
#include "render.h"
#include "shader_src.h"

#define N 48              /* grid of N x N rest points */
#define EXTENT 9.0        /* over [-EXTENT, EXTENT]^2 */
#define TIME 3.7
#define TOL 1e-4


static GLuint compile(GLenum type, const char *name, const shader_define *defs, int ndefs) {
    char path[512];
    snprintf(path, sizeof path, "%s/%s", scratch_dir, name);
    return gl_test_compile(type, path, defs, ndefs);
}

static GLuint program(bool approx) {
    shader_define def = { "WAVES_APPROX_NORMAL", "1" };
    GLuint vs = compile(GL_VERTEX_SHADER, "grid.vert", NULL, 0);
    GLuint fs = compile(GL_FRAGMENT_SHADER, "grid.frag", &def, approx ? 1 : 0);
    return gl_test_link(vs, fs);
}


/* Draws mode 0 (position) or 1 (normal) for every grid point; returns RGBA. */
static void draw(GLuint p, int mode, const ref_waves *w, float *out) {
    render_target t;
    render_target_create(&t, N, N, true);
    glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
    glViewport(0, 0, N, N);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(p);
    gl_test_upload_waves(p, w);
    glUniform1f(glGetUniformLocation(p, "uTime"), (float)TIME);
    glUniform1f(glGetUniformLocation(p, "uExtent"), (float)EXTENT);
    glUniform1i(glGetUniformLocation(p, "uMode"), mode);
    glRectf(-1, -1, 1, 1);
    glUseProgram(0);
    render_target_read(&t, out);   /* row 0 = top = the last GL row */
    render_target_destroy(&t);
}

/* The rest point of pixel (i, j) (j from the top), as grid.frag computes it. */
static void rest_point(int i, int j, double *u, double *v) {
    int gl_row = N - 1 - j;
    *u = -EXTENT + (i + 0.5) * 2 * EXTENT / N;
    *v = -EXTENT + (gl_row + 0.5) * 2 * EXTENT / N;
}

static void compare(const ref_waves *w, bool approx) {
    GLuint p = program(approx);
    CHECK_NE(p, 0);
    if (!p) return;
    static float pos[N * N * 4], nrm[N * N * 4];
    draw(p, 0, w, pos);
    draw(p, 1, w, nrm);
    double worst_p = 0, worst_n = 0;
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            double u, v;
            rest_point(i, j, &u, &v);
            ref_waves_point pt;
            ref_waves_eval(w, u, v, TIME, &pt);
            const double *want_n = approx ? pt.normal_approx : pt.normal;
            for (int k = 0; k < 3; k++) {
                double dp = fabs(pos[(j * N + i) * 4 + k] - pt.pos[k]);
                double dn = fabs(nrm[(j * N + i) * 4 + k] - want_n[k]);
                if (dp > worst_p) worst_p = dp;
                if (dn > worst_n) worst_n = dn;
            }
        }
    fprintf(stderr, "  %s normal: worst position error %.3g, normal error %.3g\n",
            approx ? "approximate" : "exact", worst_p, worst_n);
    CHECK_LE(worst_p, TOL);
    CHECK_LE(worst_n, TOL);
    glDeleteProgram(p);
}

static void test_lake_waves_match_reference(void) {
    ref_waves w;
    ref_waves_desc d = ref_waves_default();
    CHECK_EQ(ref_waves_init(&w, &d, NULL, 0), 0);
    compare(&w, false);
}

static void test_approximate_normal_matches_reference(void) {
    ref_waves w;
    ref_waves_desc d = ref_waves_default();
    CHECK_EQ(ref_waves_init(&w, &d, NULL, 0), 0);
    compare(&w, true);
}

/* Steepness 0: Gerstner waves are plain sines on both sides. */
static void test_zero_steepness_matches(void) {
    ref_waves w;
    ref_waves_desc d = ref_waves_default();
    d.steepness = 0;
    CHECK_EQ(ref_waves_init(&w, &d, NULL, 0), 0);
    compare(&w, false);
}

int main(void) {
    char err[512];
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    if (!ctx) { fprintf(stderr, "skip: %s\n", err); return 77; }
    if (!scratch_create("waves")) return 1;
    scratch_write("grid.vert", "#version 330 compatibility\nout vec2 vNdc;\n"
                            "void main() { vNdc = gl_Vertex.xy; gl_Position = gl_Vertex; }\n");
    scratch_write("grid.frag",
               "#version 330 compatibility\n#include \"waves.glsl\"\n"
               "uniform float uTime;\nuniform float uExtent;\nuniform int uMode;\n"
               "out vec4 c;\n"
               "void main() {\n"
               "  vec2 rest = -uExtent + (gl_FragCoord.xy) * 2.0 * uExtent / 48.0;\n"
               "  vec3 pos, n;\n"
               "  wavesEval(rest, uTime, pos, n);\n"
               "  c = uMode == 0 ? vec4(pos, 1.0) : vec4(n, 1.0);\n"
               "}\n");
    RUN(test_lake_waves_match_reference);
    RUN(test_approximate_normal_matches_reference);
    RUN(test_zero_steepness_matches);
    gl_ctx_destroy(ctx);
    scratch_remove();
    return check_summary();
}
