/* test_costmodel: the least-squares fit of frame time = a + b·Mpixels +
 * c·kvertices (viewer/tools/costmodel.h) against known models: exact
 * samples give the model back, bounded noise gives a fit whose residual is
 * no larger than the noise, and samples that cannot separate the terms are
 * refused with a reason. */
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "costmodel.h"

/* issue #15's fitted basic pack: 15 ms + 249 ms/Mpx + 1.03 ms/kvertex */
static const cost_model truth = { .a = 15.0, .b = 249.0, .c = 1.03 };

static int sweep(cost_sample *s, double noise) {
    const int sizes[3][2] = { { 240, 135 }, { 480, 270 }, { 960, 540 } };
    const int meshes[3] = { 64, 128, 256 };
    int n = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            s[n].mpixels = sizes[i][0] * sizes[i][1] / 1e6;
            s[n].kvertices = cost_model_grid_kvertices(meshes[j]);
            double exact = cost_model_predict(&truth, s[n].mpixels, s[n].kvertices);
            /* a fixed +-noise pattern, not symmetric in the design */
            double sign = (n * 7 % 3) == 0 ? 1.0 : (n % 2 ? -1.0 : 0.5);
            s[n].ms = exact * (1.0 + noise * sign);
            n++;
        }
    return n;
}

static void test_exact_samples_give_the_model(void) {
    cost_sample s[9];
    int n = sweep(s, 0.0);
    cost_model m;
    char err[256];
    CHECK_MSG(cost_model_fit(s, n, &m, err, sizeof err), "%s", err);
    CHECK_NEAR(m.a, truth.a, 1e-6);
    CHECK_NEAR(m.b, truth.b, 1e-6);
    CHECK_NEAR(m.c, truth.c, 1e-8);
    CHECK_NEAR(m.r2, 1.0, 1e-12);
    CHECK_LT(m.rms_residual, 1e-9);
    CHECK_EQ(m.n, 9);
    CHECK_NEAR(cost_model_predict(&m, 1920 * 1080 / 1e6, cost_model_grid_kvertices(256)),
               15.0 + 249.0 * 2.0736 + 1.03 * 66.049, 1e-6);
}

/* Times off by up to 3%: the fit's residual is within the noise (least
 * squares minimises it: the true model's own residual is an upper bound),
 * and the terms stay near the truth. */
static void test_noisy_samples_fit_within_the_noise(void) {
    cost_sample s[9];
    int n = sweep(s, 0.03);
    cost_model m;
    char err[256];
    CHECK_MSG(cost_model_fit(s, n, &m, err, sizeof err), "%s", err);
    double truth_res = 0;
    for (int i = 0; i < n; i++) {
        double r = s[i].ms - cost_model_predict(&truth, s[i].mpixels, s[i].kvertices);
        truth_res += r * r;
    }
    truth_res = sqrt(truth_res / n);
    fprintf(stderr, "  fit a %.2f b %.1f c %.3f, r2 %.4f, residual %.3f ms (the truth's %.3f)\n", m.a, m.b, m.c, m.r2,
            m.rms_residual, truth_res);
    CHECK_LE(m.rms_residual, truth_res + 1e-9);
    CHECK_GT(m.r2, 0.99);
    CHECK_LT(fabs(m.b - truth.b), 0.1 * truth.b);
}

static void test_samples_that_cannot_separate_the_terms(void) {
    cost_sample s[9];
    int n = sweep(s, 0.0);
    cost_model m;
    char err[256] = "";
    CHECK(!cost_model_fit(s, 3, &m, err, sizeof err));
    CHECK_STR_CONTAINS(err, "at least 4");
    cost_sample one_size[3] = { s[0], s[1], s[2] };   /* one image size, three meshes */
    cost_sample four[4] = { one_size[0], one_size[1], one_size[2], one_size[0] };
    CHECK(!cost_model_fit(four, 4, &m, err, sizeof err));
    CHECK_STR_CONTAINS(err, "two image sizes and two meshes");
    s[4].ms = NAN;
    CHECK(!cost_model_fit(s, n, &m, err, sizeof err));
    CHECK_STR_CONTAINS(err, "sample 5");
    /* collinear: the mesh grows exactly with the image, so pixels and
     * vertices cannot be told apart */
    cost_sample lin[4];
    for (int i = 0; i < 4; i++) lin[i] = (cost_sample){ 0.1 * (i + 1), 10.0 * (i + 1), 5.0 + i };
    CHECK(!cost_model_fit(lin, 4, &m, err, sizeof err));
    CHECK_STR_CONTAINS(err, "do not separate");
}

static void test_grid_vertices(void) {
    CHECK_NEAR(cost_model_grid_kvertices(256), 66.049, 1e-12);
    CHECK_NEAR(cost_model_grid_kvertices(1), 0.004, 1e-12);
}

int main(void) {
    RUN(test_exact_samples_give_the_model);
    RUN(test_noisy_samples_fit_within_the_noise);
    RUN(test_samples_that_cannot_separate_the_terms);
    RUN(test_grid_vertices);
    return check_summary();
}
