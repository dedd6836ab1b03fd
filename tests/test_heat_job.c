/* test_heat_job: compare-view's heat maps on a worker thread. The maps of
 * images whose error is known (a constant offset in one channel) against a
 * made-up reference: the error field, the metrics and the colours follow
 * in closed form; and the reference of a real scene computed on the
 * worker while this thread goes on polling. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "heat_job.h"
#include "ref_flip.h"
#include "ref_metrics.h"
#include "ref_render.h"

#define W 8
#define H 4
#define N (W * H)

static float ref_color[N * 3], ref_mask[N];
static float pack_off[N * 4], pack_same[N * 4];

/* The reference: grey 0.5; the top half water, the bottom half terrain.
 * Pack "off" is 0.1 brighter in red over the water, 0.3 over the terrain;
 * pack "same" is the reference. */
static refcache_image make_inputs(void) {
    for (int i = 0; i < N; i++) {
        bool water = i < N / 2;
        ref_mask[i] = water ? REF_MASK_WATER : REF_MASK_TERRAIN;
        for (int c = 0; c < 3; c++) ref_color[i * 3 + c] = 0.5f;
        for (int c = 0; c < 4; c++) pack_same[i * 4 + c] = pack_off[i * 4 + c] = c < 3 ? 0.5f : 1.0f;
        pack_off[i * 4] += water ? 0.1f : 0.3f;
    }
    refcache_image ref;
    memset(&ref, 0, sizeof ref);
    ref.w = W;
    ref.h = H;
    ref.color = ref_color;
    ref.mask = ref_mask;
    return ref;
}

static void check_rgb(const float *rgb, double t) {
    float want[3];
    ref_colormap_inferno(t, want);
    for (int c = 0; c < 3; c++) CHECK_NEAR(rgb[c], want[c], 1e-6);
}

static void test_maps_of_a_known_error(void) {
    refcache_image ref = make_inputs();
    heat_job *j = heat_job_create();
    const float *rgba[3] = { pack_off, NULL, pack_same };
    CHECK(heat_job_start_maps(j, rgba, 3, W, H, &ref, 0.6));
    CHECK_EQ(heat_job_wait(j), HEAT_JOB_MAPS);
    CHECK_EQ(heat_job_poll(j), HEAT_JOB_NONE);   /* said once */
    const heat_maps *m = heat_job_maps(j);
    CHECK(m->n == 3 && m->w == W && m->h == H);
    CHECK_NEAR(m->scale, 0.6, 1e-12);
    CHECK(m->map[0].ok && !m->map[1].ok && m->map[2].ok);
    /* RMSE over the three colour channels: one channel off by e gives e / sqrt 3 */
    CHECK_NEAR(m->map[0].rmse, 0.1 / sqrt(3.0), 1e-6);
    CHECK_NEAR(m->map[0].frame_rmse, sqrt((0.01 + 0.09) / 2 / 3), 1e-6);
    CHECK_NEAR(m->map[2].rmse, 0.0, 1e-12);
    /* colours: e / scale through inferno; water pixels first, terrain last */
    check_rgb(m->map[0].rgb, 0.1 / 0.6);
    check_rgb(m->map[0].rgb + (N - 1) * 3, 0.3 / 0.6);
    check_rgb(m->map[2].rgb, 0.0);
    heat_job_destroy(j);
}

/* No fixed scale: the largest pack's own (its 99th percentile, 0.3). */
static void test_automatic_scale_is_the_largest(void) {
    refcache_image ref = make_inputs();
    heat_job *j = heat_job_create();
    const float *rgba[2] = { pack_same, pack_off };
    CHECK(heat_job_start_maps(j, rgba, 2, W, H, &ref, 0));
    CHECK(!heat_job_start_maps(j, rgba, 2, W, H, &ref, 0));   /* one job at a time */
    CHECK_EQ(heat_job_wait(j), HEAT_JOB_MAPS);
    const heat_maps *m = heat_job_maps(j);
    CHECK_NEAR(m->scale, 0.3, 1e-6);
    check_rgb(m->map[1].rgb + (N - 1) * 3, 1.0);
    heat_job_destroy(j);
}

/* HDR-FLIP maps (issue #26): what ref_flip_map gives the same pair, pooled
 * over the water; the reference's own image scores 0; FLIP's magma ramp;
 * the colour maps' figures are still there. */
static void test_flip_maps(void) {
    refcache_image ref = make_inputs();
    heat_job *j = heat_job_create();
    heat_job_set_metric(j, HEAT_METRIC_FLIP);
    const float *rgba[2] = { pack_off, pack_same };
    CHECK(heat_job_start_maps(j, rgba, 2, W, H, &ref, 0.6));
    CHECK_EQ(heat_job_wait(j), HEAT_JOB_MAPS);
    const heat_maps *m = heat_job_maps(j);
    CHECK(m->metric == HEAT_METRIC_FLIP && m->map[0].ok && m->map[1].ok);
    CHECK_NEAR(m->scale, 1.0, 0);   /* FLIP is in [0, 1]: the fixed scale is not used */
    /* the truth: ref_flip_map of the same pair, HDR, pooled over the top half */
    ref_fimage A = { pack_off, W, H, 4 }, B = { ref_color, W, H, 3 };
    float map[N];
    ref_flip_desc d = { .hdr = true };
    ref_flip_result all, wet;
    CHECK(ref_flip_map(&A, &B, &d, map, NULL, &all, NULL, 0));
    unsigned char water[N];
    for (int i = 0; i < N; i++) water[i] = i < N / 2;
    wet = all;
    ref_flip_pool(map, W, H, water, &wet);
    CHECK_GT(wet.mean, 0.01);   /* a red shift of 0.1 is visible */
    CHECK_NEAR(m->map[0].flip, wet.mean, 1e-6);
    CHECK_NEAR(m->map[0].frame_flip, all.mean, 1e-6);
    CHECK_NEAR(m->map[1].flip, 0.0, 1e-6);
    CHECK_NEAR(m->map[0].rmse, 0.1 / sqrt(3.0), 1e-6);
    float want[3];
    ref_flip_magma(map[0], want);
    for (int c = 0; c < 3; c++) CHECK_NEAR(m->map[0].rgb[c], want[c], 1e-6);
    heat_job_destroy(j);
}

/* The reference of a real scene, computed while this thread polls. */
static void test_reference_on_the_worker(void) {
    const char *root = getenv("TARN_SOURCE_DIR");
    char scene[1024];
    snprintf(scene, sizeof scene, "%s/scenes/lake.glib", root && root[0] ? root : TARN_SOURCE_DIR);
    heat_job *j = heat_job_create();
    refcache_view view = { { 0, 6, 14 }, { 0, 0, 0 }, { 0, 1, 0 } };
    refcache_opts o = { .caustic_res = 16, .photons_per_cell = 2 };
    CHECK(heat_job_start_reference(j, scene, 24, 12, 1.0, &view, &o));
    int polls = 0;
    double last = 0;
    bool monotone = true;
    while (heat_job_poll(j) == HEAT_JOB_NONE) {
        double f = heat_job_progress(j);
        if (f < last || f > 1) monotone = false;
        last = f;
        polls++;
        struct timespec ts = { 0, 2000000 };
        nanosleep(&ts, NULL);
    }
    fprintf(stderr, "  %d polls while the reference ran; progress %.2f\n", polls, last);
    CHECK(monotone);
    refcache_image ref;
    char err[512];
    CHECK_MSG(heat_job_take_reference(j, &ref, err, sizeof err), "%s", err);
    CHECK(ref.w == 24 && ref.h == 12 && ref.color && ref.mask);
    refcache_free(&ref);
    /* a scene that is not there: the reason, no image */
    CHECK(heat_job_start_reference(j, "/nonexistent/none.glib", 8, 8, 0, &view, &o));
    CHECK_EQ(heat_job_wait(j), HEAT_JOB_REFERENCE);
    CHECK(!heat_job_take_reference(j, &ref, err, sizeof err));
    CHECK_NE(err[0], '\0');
    heat_job_destroy(j);
}

int main(void) {
    RUN(test_maps_of_a_known_error);
    RUN(test_automatic_scale_is_the_largest);
    RUN(test_flip_maps);
    RUN(test_reference_on_the_worker);
    return check_summary();
}
