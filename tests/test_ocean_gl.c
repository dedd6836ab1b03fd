/* The spectrum ocean on the GPU (viewer/gfx/render_ocean.c, packs/common/
 * ocean_*.frag, waves_ocean.glsl) against its double-precision twin
 * (reference/ref_ocean.c, ref_waves.c).
 *
 * (a) The frame's textures against ref_ocean_frame, N = 64 and 256, 1 and
 *     3 cascades, at two times, each of the eight fields: the largest
 *     error over the texels divided by the field's rms. Bound: a float32
 *     radix-2 FFT's error grows at worst as log2 N * eps * sqrt(N^2) * rms
 *     (log2 N stages, each adding eps of the running sum, the sum of N^2
 *     terms): eps = 2^-23 gives 4.6e-5 at N = 64 and 2.4e-4 at N = 256;
 *     that is the bound, plus the phase w t rounded in float (w t reaches
 *     ~100 rad at t = 3.7: 4e-6 relative a term, far under it). The
 *     measured figures are printed (a few 1e-6 .. 1e-5: rounding errors
 *     add as a random walk, sqrt(log2 N) eps, not log2 N eps N).
 * (b) Through waves.glsl (wavesEval and wavesHeightAt) against ref_waves
 *     on a world with an ocean.
 * (c) A world without an ocean creates nothing and runs no pass.
 * Plus a plane wave through the passes (one nonzero texel: the transform's
 * index order and sign, exactly), and the passes' cost per size. */
#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "support.h"
#include "gl_support.h"
#include "ref_ocean.h"
#include "ref_waves.h"
#include "render_ocean.h"
#include "render_world.h"
#include "shader_src.h"

static bool make_ocean(gpu_ocean *o, int cascades, int n, const float *tile, float lambda, const float *h0,
                       const float *omega) {
    diag_list log = { 0 };
    memset(o, 0, sizeof *o);
    bool ok = ocean_create(o, cascades, n, tile, lambda, h0, omega, gl_test_sources(), &log, NULL);
    diag_print(&log, stderr);
    diag_list_free(&log);
    return ok;
}

/* One wave vector (m, n) of cascade 1 of 2 (FFT order) holds h0 = a, the
 * rest nothing, w = 0: every output texel is that one term times
 * e^{2 pi i (m x + n z) / N}, in each of the four complex spectra. */
static void test_plane_wave_through_the_passes(void) {
    enum { NR = 64, C = 2 };
    static float h0[C * NR * NR * 4], omega[C * NR * NR];
    memset(h0, 0, sizeof h0);
    memset(omega, 0, sizeof omega);
    int m = 5, n = NR - 3;                       /* k = 2 pi (5, -3) / L */
    double ar = 0.3, ai = -0.2, lambda = 0.7, L = 20;
    size_t at = (size_t)NR * NR + (size_t)n * NR + m;
    h0[at * 4 + 0] = (float)ar;
    h0[at * 4 + 1] = (float)ai;
    float tile[C] = { 50.0f, (float)L };
    gpu_ocean o;
    CHECK(make_ocean(&o, C, NR, tile, (float)lambda, h0, omega));
    ocean_update(&o, 1.0, NULL);
    static float a[NR * NR * 4], b[NR * NR * 4];
    ocean_read(&o, 1, a, b);
    /* the spectra of the one term, as ocean_spectrum.frag makes them */
    double kx = 2 * M_PI * 5 / L, kz = 2 * M_PI * -3 / L, kl = hypot(kx, kz);
    double H[2] = { ar, ai }, iH[2] = { -ai, ar };
    double f[8][2];   /* h, Dx, Dz, Dxz, hx, hz, Dxx, Dzz spectra */
    for (int k = 0; k < 2; k++) {
        f[0][k] = H[k];
        f[1][k] = lambda * kx / kl * iH[k];
        f[2][k] = lambda * kz / kl * iH[k];
        f[3][k] = -lambda * kx * kz / kl * H[k];
        f[4][k] = kx * iH[k];
        f[5][k] = kz * iH[k];
        f[6][k] = -lambda * kx * kx / kl * H[k];
        f[7][k] = -lambda * kz * kz / kl * H[k];
    }
    /* Z = X + i Y pairs: (h, Dx) (Dz, Dxz) (hx, hz) (Dxx, Dzz) */
    double worst = 0, scale = 0;
    for (int z = 0; z < NR; z++)
        for (int x = 0; x < NR; x++) {
            double ph = 2 * M_PI * (double)(m * x + n * z) / NR, e[2] = { cos(ph), sin(ph) };
            for (int zi = 0; zi < 4; zi++) {
                const double *X = f[2 * zi], *Y = f[2 * zi + 1];
                double Z[2] = { X[0] - Y[1], X[1] + Y[0] };
                double want[2] = { Z[0] * e[0] - Z[1] * e[1], Z[0] * e[1] + Z[1] * e[0] };
                const float *got = (zi < 2 ? a : b) + ((size_t)z * NR + x) * 4 + (zi % 2) * 2;
                for (int k = 0; k < 2; k++) {
                    double d = fabs(got[k] - want[k]);
                    if (d > worst) worst = d;
                    if (fabs(want[k]) > scale) scale = fabs(want[k]);
                }
            }
        }
    fprintf(stderr, "  plane wave: worst error %.3g of amplitude %.3g\n", worst, scale);
    CHECK_GT(scale, 0.1);
    CHECK_LE(worst, 1e-5 * scale);
    /* cascade 0 holds nothing: all zero */
    ocean_read(&o, 0, a, b);
    double any = 0;
    for (int i = 0; i < NR * NR * 4; i++) any = fmax(any, fmax(fabs(a[i]), fabs(b[i])));
    CHECK_EQ(any, 0);
    ocean_free(&o);
}


/* ---- (a) the frame against the reference ---- */

static ref_ocean *reference_ocean(int n, int cascades, double chop) {
    ref_ocean_desc d = { .spectrum = REF_SPECTRUM_JONSWAP, .wind_speed = 12, .wind_angle_deg = 30,
                         .choppiness = chop, .res = n, .cascades = cascades, .seed = 7 };
    char err[256];
    ref_ocean *o = ref_ocean_create(&d, err, sizeof err);
    if (!o) fprintf(stderr, "ref_ocean_create: %s\n", err);
    return o;
}

static bool gpu_from(gpu_ocean *g, const ref_ocean *ro) {
    diag_list log = { 0 };
    memset(g, 0, sizeof *g);
    bool ok = ocean_create_from(g, ro, gl_test_sources(), &log, NULL);
    diag_print(&log, stderr);
    diag_list_free(&log);
    return ok;
}

/* The worst error over the texels of each field, relative to the field's
 * rms; returns the largest of the eight. */
static double frame_error(const gpu_ocean *g, const ref_ocean *ro, int c, double t) {
    static const char *const names[8] = { "h", "Dx", "Dz", "Dxz", "hx", "hz", "Dxx", "Dzz" };
    int n = g->res;
    size_t nn = (size_t)n * n;
    float *a = malloc(nn * 4 * sizeof *a), *b = malloc(nn * 4 * sizeof *b);
    double *ra = malloc(nn * 4 * sizeof *ra), *rb = malloc(nn * 4 * sizeof *rb);
    ocean_read(g, c, a, b);
    ref_ocean_frame(ro, c, t, ra, rb);
    double worst_rel = 0;
    char line[512];
    int len = snprintf(line, sizeof line, "  N %d cascade %d t %.1f: max err / rms", n, c, t);
    for (int q = 0; q < 8; q++) {
        const float *got = q < 4 ? a : b;
        const double *want = q < 4 ? ra : rb;
        double sum2 = 0, worst = 0;
        for (size_t i = 0; i < nn; i++) {
            double w = want[i * 4 + q % 4];
            sum2 += w * w;
            double d = fabs(got[i * 4 + q % 4] - w);
            if (!(d <= worst)) worst = d;   /* NaN counts */
        }
        double rms = sqrt(sum2 / (double)nn), rel = rms > 0 ? worst / rms : worst;
        CHECK_GT(rms, 0);
        if (!(rel <= worst_rel)) worst_rel = rel;
        len += snprintf(line + len, sizeof line - (size_t)len, " %s %.2g", names[q], rel);
    }
    fprintf(stderr, "%s\n", line);
    free(a); free(b); free(ra); free(rb);
    return worst_rel;
}

static void frame_matches(int n, int cascades) {
    ref_ocean *ro = reference_ocean(n, cascades, 0.8);
    CHECK_NE(ro, NULL);
    if (!ro) return;
    gpu_ocean g;
    CHECK(gpu_from(&g, ro));
    int lg = 0;
    while ((1 << lg) < n) lg++;
    double bound = lg * 0x1p-23 * n;   /* log2 N eps sqrt(N^2) */
    static const double times[2] = { 0.0, 3.7 };
    for (int k = 0; k < 2; k++) {
        ocean_update(&g, times[k], NULL);
        for (int c = 0; c < cascades; c++) CHECK_LE(frame_error(&g, ro, c, times[k]), bound);
    }
    fprintf(stderr, "  bound log2 N eps N = %.2g\n", bound);
    ocean_free(&g);
    ref_ocean_destroy(ro);
}

static void test_frame_64_one_cascade(void) { frame_matches(64, 1); }
static void test_frame_64_three_cascades(void) { frame_matches(64, 3); }
static void test_frame_256_one_cascade(void) { frame_matches(256, 1); }
static void test_frame_256_three_cascades(void) { frame_matches(256, 3); }

/* A frame's passes run once a time: a still frame (the same t again) runs
 * none, a new time runs them again, at every N. (What they cost is `tarn
 * bench`'s to measure, tools/bench_ocean.c: timing is no test's.) */
static void test_still_frame_runs_no_pass(void) {
    static const int sizes[2] = { 64, 512 };
    for (int s = 0; s < 2; s++) {
        ref_ocean *ro = reference_ocean(sizes[s], 3, 0.8);
        if (!ro) { CHECK(0); return; }
        gpu_ocean g;
        CHECK(gpu_from(&g, ro));
        CHECK(ocean_update(&g, 1.0, NULL));
        int frames = g.frames;
        CHECK(!ocean_update(&g, 1.0, NULL));
        CHECK_EQ(g.frames, frames);
        CHECK(ocean_update(&g, 1.5, NULL));
        CHECK_EQ(g.frames, frames + 1);
        ocean_free(&g);
        ref_ocean_destroy(ro);
    }
}

/* ---- (b) through waves.glsl, against ref_waves ---- */

#define GRID 48            /* GRID x GRID rest points (and world points) */
#define EXTENT 30.0        /* over [-EXTENT, EXTENT]^2: the finest tiles many times, the middle one in part */
#define WTIME 2.0

static GLuint compile(GLenum type, const char *name) {
    char path[512];
    snprintf(path, sizeof path, "%s/%s", scratch_dir, name);
    return gl_test_compile(type, path, NULL, 0);
}

/* eval_only: just wavesEval (the cost measurement: llvmpipe runs every
 * branch of an if on a uniform) */
static GLuint eval_program(bool eval_only) {
    scratch_write("grid.vert", "#version 330 compatibility\nvoid main() { gl_Position = gl_Vertex; }\n");
    char text[1024];
    snprintf(text, sizeof text,
             "#version 330 compatibility\n%s#include \"waves.glsl\"\n"
             "uniform float uTime;\nuniform float uExtent;\nuniform int uMode;\nuniform float uGrid;\n"
             "out vec4 c;\n"
             "void main() {\n"
             "  vec2 p = -uExtent + gl_FragCoord.xy * 2.0 * uExtent / uGrid;\n"
             "  vec3 pos, n;\n"
             "#ifdef EVAL_ONLY\n"
             "  wavesEval(p, uTime, pos, n); c = vec4(pos + n, 1.0);\n"
             "#else\n"
             "  if (uMode == 0) { wavesEval(p, uTime, pos, n); c = vec4(pos, 1.0); }\n"
             "  else if (uMode == 1) { wavesEval(p, uTime, pos, n); c = vec4(n, 1.0); }\n"
             "  else c = vec4(wavesRestPoint(p, uTime), wavesHeightAt(p, uTime), 1.0);\n"
             "#endif\n"
             "}\n", eval_only ? "#define EVAL_ONLY 1\n" : "");
    scratch_write("grid.frag", text);
    GLuint vs = compile(GL_VERTEX_SHADER, "grid.vert"), fs = compile(GL_FRAGMENT_SHADER, "grid.frag");
    return gl_test_link(vs, fs);
}


/* mode 0 positions, 1 normals, 2 (rest point, height) over world points; GL rows (row 0 at the bottom) */
static void draw_modes(GLuint p, const ref_waves *w, float out[3][GRID * GRID * 4]) {
    GLuint tex, fbo;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, GRID, GRID, 0, GL_RGBA, GL_FLOAT, NULL);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    glViewport(0, 0, GRID, GRID);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(p);
    gl_test_upload_waves(p, w);
    ocean_upload(p);   /* the ocean's samplers at their units */
    glUniform1f(glGetUniformLocation(p, "uTime"), (float)WTIME);
    glUniform1f(glGetUniformLocation(p, "uExtent"), (float)EXTENT);
    glUniform1f(glGetUniformLocation(p, "uGrid"), (float)GRID);
    for (int m = 0; m < 3; m++) {
        glUniform1i(glGetUniformLocation(p, "uMode"), m);
        glRectf(-1, -1, 1, 1);
        glReadPixels(0, 0, GRID, GRID, GL_RGBA, GL_FLOAT, out[m]);
    }
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
}

static double cell_coord(int i) { return -EXTENT + (i + 0.5) * 2 * EXTENT / GRID; }

/* The tolerances, in metres for positions and heights and unit-vector
 * components for normals, from the float error sources: the frame's
 * fields are off by <= 1.5e-5 of their rms (part (a)); the bilinear
 * weights by fract(p0 / L) N rounded (2^-24 * 30 / 5.3 * 128 texels
 * = 4e-5 texel, times a texel's change of a field: under 1e-5 m here);
 * the Gerstner wave's and the rings' phases by ~1e-5 rad (see
 * test_waves_gl, waves_fx.glsl). 2e-4 leaves a margin of ~10 over the
 * sum, while a missing model or a wrong sign shows at 1e-2 or more
 * (ocean heights ~0.3 m, slopes ~0.2). The height over a world point
 * adds the inversion: the GPU's 4 Newton steps (with the fields' own
 * Jacobian, not the bilinear map's derivative) against the reference's
 * 1e-12; checked at 2e-4 m like the rest point (measured: a few 1e-6 m
 * for the positions and heights, 1e-5 for normals and rest points). */
#define TOL_POS 2e-4
#define TOL_NRM 2e-4
#define TOL_WORLD 2e-4

static void test_waves_with_an_ocean_match_reference(void) {
    ref_waves_desc d;
    memset(&d, 0, sizeof d);
    d.gerstner_count = 1;
    d.gerstner[0] = (ref_wave_desc){ .angle_deg = 60, .wavelength = 9, .amplitude = 0.08 };
    d.steepness = 0.3;
    d.ocean = (ref_ocean_desc){ .spectrum = REF_SPECTRUM_JONSWAP, .wind_speed = 7, .wind_angle_deg = 20,
                                .choppiness = 0.6, .res = 128, .cascades = 3, .seed = 11 };
    d.explosion_count = 1;
    d.explosion[0] = (ref_explosion_desc){ .center = { 3, -4 }, .start = 0.5, .i0 = 0.05, .k = 3, .decay = 0.2 };
    d.perlin = (ref_perlin_desc){ .amplitude = 0.03, .cell = 3, .octaves = 3, .angle_deg = 45, .seed = 5 };
    ref_waves w;
    char err[256];
    if (ref_waves_init(&w, &d, err, sizeof err) != 0) { CHECK_MSG(0, "%s", err); return; }
    CHECK_NE(w.ocean, NULL);
    gpu_ocean g;
    CHECK(gpu_from(&g, w.ocean));
    CHECK(ocean_update(&g, WTIME, NULL));
    GLuint p = eval_program(false);
    CHECK_NE(p, 0);
    if (!p) { ocean_free(&g); ref_waves_release(&w); return; }
    static float out[3][GRID * GRID * 4];
    draw_modes(p, &w, out);
    double wp = 0, wn = 0, wh = 0, wr = 0, amp = 0;
    int failed = 0;
    for (int j = 0; j < GRID; j++)
        for (int i = 0; i < GRID; i++) {
            double u = cell_coord(i), v = cell_coord(j);
            const float *P = out[0] + (j * GRID + i) * 4, *Nr = out[1] + (j * GRID + i) * 4, *R = out[2] + (j * GRID + i) * 4;
            ref_waves_point pt;
            ref_waves_eval(&w, u, v, WTIME, &pt);
            amp = fmax(amp, fabs(pt.pos[1]));
            for (int k = 0; k < 3; k++) {
                wp = fmax(wp, fabs(P[k] - pt.pos[k]));
                wn = fmax(wn, fabs(Nr[k] - pt.normal[k]));
            }
            double uv[2], hh;
            if (ref_waves_rest_point(&w, u, v, WTIME, NULL, uv, &hh) != 0) { failed++; continue; }   /* folded */
            wr = fmax(wr, hypot(R[0] - uv[0], R[1] - uv[1]));
            wh = fmax(wh, fabs(R[2] - hh));
        }
    fprintf(stderr, "  ocean + Gerstner + ring + Perlin (heights to %.2f m): position %.3g m, normal %.3g, "
            "rest point %.3g m, height over a world point %.3g m (%d folded points skipped)\n",
            amp, wp, wn, wr, wh, failed);
    CHECK_GT(amp, 0.1);
    CHECK_LE(wp, TOL_POS);
    CHECK_LE(wn, TOL_NRM);
    CHECK_LE(wr, TOL_WORLD);
    CHECK_LE(wh, TOL_WORLD);
    CHECK_LT(failed, GRID * GRID / 50);
    glDeleteProgram(p);
    ocean_free(&g);
    ref_waves_release(&w);
}

/* The models are compiled in only where the world has them (waves.glsl:
 * WAVES_MODELS and WAVES_HAS_*, set by render_world): llvmpipe runs a
 * loop's body even when its uniform count is 0 (measured here before the
 * gate: wavesEval over 960x540 cost ~120 ms with or without an ocean), so
 * a program built for a world without an ocean must not contain the
 * ocean's code at all: its samplers are then inactive. Without
 * WAVES_MODELS (a test, `tarn validate`), every model is in. */
static void test_models_compiled_in_only_when_present(void) {
    struct { const char *defines; bool ocean, ring; } cases[] = {
        { "", true, true },
        { "#define WAVES_MODELS\n#define WAVES_HAS_GERSTNER\n", false, false },
        { "#define WAVES_MODELS\n#define WAVES_HAS_OCEAN\n", true, false },
        { "#define WAVES_MODELS\n#define WAVES_HAS_EXPLOSION\n", false, true },
    };
    for (int k = 0; k < 4; k++) {
        char text[1024];
        snprintf(text, sizeof text,
                 "#version 330 compatibility\n%s#include \"waves.glsl\"\nuniform float uTime;\nout vec4 c;\n"
                 "void main() { vec3 pos, n; wavesEval(gl_FragCoord.xy, uTime, pos, n); c = vec4(pos + n, 1.0); }\n",
                 cases[k].defines);
        scratch_write("gate.frag", text);
        scratch_write("gate.vert", "#version 330 compatibility\nvoid main() { gl_Position = gl_Vertex; }\n");
        GLuint vs = compile(GL_VERTEX_SHADER, "gate.vert"), fs = compile(GL_FRAGMENT_SHADER, "gate.frag");
        CHECK(vs && fs);
        if (!vs || !fs) return;
        GLuint p = glCreateProgram();
        glAttachShader(p, vs);
        glAttachShader(p, fs);
        glLinkProgram(p);
        glDeleteShader(vs);
        glDeleteShader(fs);
        GLint ok = 0;
        glGetProgramiv(p, GL_LINK_STATUS, &ok);
        CHECK(ok);
        CHECK_MSG((glGetUniformLocation(p, "uOceanA") >= 0) == cases[k].ocean, "case %d: uOceanA", k);
        CHECK_MSG((glGetUniformLocation(p, "uExplosion") >= 0) == cases[k].ring, "case %d: uExplosion", k);
        glDeleteProgram(p);
    }
}

/* ---- (c) a world without an ocean pays nothing ---- */

static void test_no_ocean_no_pass(void) {
    render *r = render_create(&(render_desc){ .pack = "basic" });
    CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/scenes/lake.glib"), "%s", render_messages(r));
    render_target tg;
    CHECK(render_target_create(&tg, 64, 36, true));
    render_frame(r, 1.0, tg.fbo, 64, 36, NULL);
    render_frame(r, 2.0, tg.fbo, 64, 36, NULL);
    CHECK(!gl_test_has_pass(r, "ocean"));
    render_target_destroy(&tg);
    render_destroy(r);
    /* the world module itself: no ocean, no texture, no program */
    ref_world_desc desc;
    memset(&desc, 0, sizeof desc);
    gpu_world gw;
    gl_test_world_build(&gw, &desc);
    CHECK(gw.active);
    CHECK(!gw.ocean.active && gw.ocean.tex[0][0] == 0 && gw.ocean.h0_tex == 0 && gw.ocean.progs[0].gl == 0);
    CHECK(!world_update_ocean(&gw, 1.0, NULL));
    world_free(&gw);
}

/* And one with an ocean computes it once a time and names its passes. */
static void test_ocean_world_runs_its_passes(void) {
    ref_world_desc desc;
    memset(&desc, 0, sizeof desc);
    desc.waves.ocean = (ref_ocean_desc){ .spectrum = REF_SPECTRUM_PHILLIPS, .res = 64, .cascades = 2, .choppiness = 0.5 };
    gpu_world gw;
    CHECK(gl_test_world_build(&gw, &desc));
    CHECK(gw.ocean.active && gw.ocean.cascades == 2 && gw.ocean.res == 64);
    gpu_timer timer;
    gpu_timer_init(&timer);
    gpu_timer_begin_frame(&timer);
    CHECK(world_update_ocean(&gw, 1.0, &timer));
    CHECK(!world_update_ocean(&gw, 1.0, &timer));   /* held already */
    gpu_timer_end_frame(&timer);
    gpu_timer_collect(&timer, true);
    bool spectrum = false, fft = false;
    for (int i = 0; i < timer.npasses; i++) {
        spectrum |= strcmp(timer.pass_names[i], "ocean spectrum") == 0;
        fft |= strcmp(timer.pass_names[i], "ocean fft") == 0;
    }
    CHECK(spectrum && fft);
    CHECK_EQ(gw.ocean.frames, 1);
    gpu_timer_free(&timer);
    world_free(&gw);
}

/* ---- (d) folding foam and the filtered normal ---- */

/* The Jacobian's coverage, as ocean_foam.frag computes it (floats). */
static float foam_cover(const float *a, const float *b) {
    float J = (1.0f + b[2]) * (1.0f + b[3]) - a[3] * a[3];
    float c = ((float)OCEAN_FOAM_J - J) / (float)OCEAN_FOAM_SOFT;
    return c < 0 ? 0 : c > 1 ? 1 : c;
}

/* Foam appears where J < OCEAN_FOAM_J (the coverage, exactly, on the first
 * frame), then each frame is max(prev exp(-dt / decay), coverage); a still
 * frame changes nothing; a jump backwards or over a second restarts it. */
static void test_foam_from_the_jacobian(void) {
    enum { NR = 64, C = 2 };
    ref_ocean *ro = reference_ocean(NR, C, 1.6);
    if (!ro) { CHECK(0); return; }
    gpu_ocean g;
    CHECK(gpu_from(&g, ro));
    static float a[NR * NR * 4], b[NR * NR * 4], f[NR * NR * 2], prev[C][NR * NR * 2];
    const double times[] = { 1.0, 1.2, 1.2, 1.5, 0.7, 3.0 };
    int resets = 0;
    for (int k = 0; k < (int)(sizeof times / sizeof *times); k++) {
        double t = times[k], dt = k ? t - times[k - 1] : -1;
        bool ran = ocean_update(&g, t, NULL);
        CHECK_EQ(ran, (dt != 0));                         /* a still frame runs nothing */
        bool reset = dt < 0 || dt > OCEAN_FOAM_RESET_DT;
        resets += reset && ran;
        CHECK_EQ(g.foam_resets, resets);
        double keep = reset ? 0 : exp(-(dt > 0 ? dt : 0) / OCEAN_FOAM_DECAY);
        int folded = 0, foamy = 0, decayed = 0;
        double worst = 0;
        for (int c = 0; c < C; c++) {
            ocean_read(&g, c, a, b);
            ocean_read_foam(&g, c, f);
            for (int i = 0; i < NR * NR; i++) {
                float cover = foam_cover(a + 4 * i, b + 4 * i);
                double want = k == 0 ? cover : fmax(prev[c][2 * i] * keep, cover);
                if (!ran) want = prev[c][2 * i];         /* nothing decays twice */
                worst = fmax(worst, fabs(f[2 * i] - want));
                folded += cover > 0;
                foamy += f[2 * i] > 0;
                decayed += f[2 * i] > cover + 1e-6;      /* foam left by an earlier frame */
                CHECK_EQ(f[2 * i + 1], g.slope_var[c]);
            }
            memcpy(prev[c], f, sizeof f);
        }
        printf("  foam t=%.1f (dt %+.1f%s): %d of %d nodes under J = %.2f, %d with foam, %d of them decaying; "
               "worst |foam - expected| %.2g\n", t, dt, reset ? ", restart" : ran ? "" : ", still", folded,
               C * NR * NR, OCEAN_FOAM_J, foamy, decayed, worst);
        CHECK_LE(worst, 1e-5);
        CHECK_GT(folded, 0);
        if (!reset && ran) CHECK_GT(decayed, 0);   /* the foam of earlier crests stays a while */
        if (reset) CHECK_EQ(decayed, 0);
    }
    for (int c = 0; c < C; c++) CHECK_GT(g.slope_var[c], 0);
    ocean_free(&g);
    ref_ocean_destroy(ro);
}

/* wavesNormalFiltered at footprint 0 is wavesNormal; at a footprint of
 * many tiles the ocean's slopes are gone (its normal is straight up) and
 * the slope variance it dropped is the cascades' sum. */
static void test_filtered_normal(void) {
    enum { NR = 64, C = 2, G = 32 };
    ref_ocean *ro = reference_ocean(NR, C, 1.0);
    if (!ro) { CHECK(0); return; }
    gpu_ocean g;
    CHECK(gpu_from(&g, ro));
    CHECK(ocean_update(&g, 1.5, NULL));
    scratch_write("filt.vert", "#version 330 compatibility\nvoid main() { gl_Position = gl_Vertex; }\n");
    scratch_write("filt.frag",
                  "#version 330 compatibility\n#include \"waves.glsl\"\n"
                  "uniform float uFoot;\nout vec4 c;\n"
                  "void main() {\n"
                  "  vec2 p = gl_FragCoord.xy * 1.37 - 20.0;\n"
                  "  float lost;\n"
                  "  vec3 nf = wavesNormalFilteredVar(p, 1.5, vec2(uFoot, 0.5 * uFoot), lost);\n"
                  "  vec3 n = uFoot == 0.0 ? wavesNormal(p, 1.5) : vec3(0.0, 1.0, 0.0);\n"
                  "  c = vec4(nf - n, lost);\n"
                  "}\n");
    GLuint vs = compile(GL_VERTEX_SHADER, "filt.vert"), fs = compile(GL_FRAGMENT_SHADER, "filt.frag");
    CHECK(vs && fs);
    if (!vs || !fs) { ocean_free(&g); ref_ocean_destroy(ro); return; }
    GLuint p = glCreateProgram();
    glAttachShader(p, vs);
    glAttachShader(p, fs);
    glLinkProgram(p);
    GLuint tex, fbo;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, G, G, 0, GL_RGBA, GL_FLOAT, NULL);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    glViewport(0, 0, G, G);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(p);
    const ref_ocean_desc *od = ref_ocean_get_desc(ro);
    glUniform1i(glGetUniformLocation(p, "uOceanN"), od->cascades);
    glUniform1i(glGetUniformLocation(p, "uOceanRes"), od->res);
    float tile[C];
    for (int c = 0; c < C; c++) tile[c] = (float)od->tile[c];
    glUniform1fv(glGetUniformLocation(p, "uOceanTile"), C, tile);
    ocean_upload(p);
    ocean_bind(&g);
    static float out[G * G * 4];
    const float feet[2] = { 0.0f, 1e4f };
    for (int k = 0; k < 2; k++) {
        glUniform1f(glGetUniformLocation(p, "uFoot"), feet[k]);
        glRectf(-1, -1, 1, 1);
        glReadPixels(0, 0, G, G, GL_RGBA, GL_FLOAT, out);
        double worst = 0, lost = 0;
        for (int i = 0; i < G * G; i++) {
            for (int j = 0; j < 3; j++) worst = fmax(worst, fabs(out[4 * i + j]));
            lost = fmax(lost, fabs(out[4 * i + 3] - (k ? g.slope_var[0] + g.slope_var[1] : 0.0)));
        }
        printf("  filtered normal, footprint %g m: worst |n - expected| %.2g, |lost variance - expected| %.2g "
               "(sigma^2 %.3g + %.3g)\n", feet[k], worst, lost, g.slope_var[0], g.slope_var[1]);
        CHECK(worst == 0 || (k == 1 && worst <= 1e-6));
        CHECK_LE(lost, 1e-6 * (1 + g.slope_var[0] + g.slope_var[1]));
    }
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    glDeleteProgram(p);
    glDeleteShader(vs);
    glDeleteShader(fs);
    ocean_free(&g);
    ref_ocean_destroy(ro);
}

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    RUN(test_plane_wave_through_the_passes);
    RUN(test_frame_64_one_cascade);
    RUN(test_frame_64_three_cascades);
    RUN(test_frame_256_one_cascade);
    RUN(test_frame_256_three_cascades);
    RUN(test_still_frame_runs_no_pass);
    if (!scratch_create("ocean")) return 1;
    RUN(test_waves_with_an_ocean_match_reference);
    RUN(test_models_compiled_in_only_when_present);
    RUN(test_filtered_normal);
    scratch_remove();
    RUN(test_foam_from_the_jacobian);
    RUN(test_no_ocean_no_pass);
    RUN(test_ocean_world_runs_its_passes);
    gl_ctx_destroy(ctx);
    return check_summary();
}
