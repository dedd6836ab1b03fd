/* The spray (viewer/gfx/render_spray.c, packs/common/spray_*.{frag,vert};
 * issue #29) against closed forms.
 *
 * (a) With emission off (a threshold no surface reaches) no particle ever
 *     lives.
 * (b) Over an explosion ring, particles are emitted where the surface
 *     rises, and each follows x0 + v0 tau - g tau^2 / 2 y exactly (a step
 *     is the parabola's own update, so only float rounding is left: a few
 *     ulps of a position of metres, bound 1e-4 m over 0.1 s; measured
 *     ~6e-8); a particle whose parabola has gone 0.3 m under the water's
 *     highest point (the ring's height bound over the level) 0.5 s later
 *     is gone: removed there.
 * (c) Two runs of the same seed and steps give bit-identical state; another
 *     seed another.
 * (d) A world without a Spray runs no spray pass and builds no state; a
 *     Spray scene runs them, and none with render_desc.no_spray (the bench).
 * (e) Over a spectrum ocean (height from textures of one time) a step
 *     after a jump emits nothing (no other model rises), and played
 *     steps, which read the ocean's upward speed from the last two height
 *     maps, do: spray on its crests. */
#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "support.h"
#include "gl_support.h"
#include "ref_wavefx.h"
#include "render_spray.h"
#include "render_world.h"

/* A flat lake with one explosion ring at the origin from t = 0.2 s. */
static bool ring_world(gpu_world *gw, double threshold, unsigned seed) {
    ref_world_desc desc;
    memset(&desc, 0, sizeof desc);
    desc.waves.explosion_count = 1;
    desc.waves.explosion[0] = (ref_explosion_desc){ .center = { 0, 0 }, .start = 0.2, .i0 = 0.3 };
    desc.half_size = 6;
    desc.spray = (ref_spray_desc){ .on = true, .threshold = threshold, .rate = 4e5, .life = 3, .seed = seed,
                                   .count = 4096 };
    memset(gw, 0, sizeof *gw);
    diag_list log = { 0 };
    bool ok = world_build(gw, &desc, gl_test_sources(), &log, NULL);
    diag_print(&log, stderr);
    diag_list_free(&log);
    return ok && gw->spray.active;
}

static int live(const float *pos, int n) {
    int k = 0;
    for (int i = 0; i < n; i++) k += pos[4 * i + 3] > 0;
    return k;
}

static void test_no_emission_no_particle(void) {
    gpu_world gw;
    CHECK(ring_world(&gw, 1e6, 1));
    int n = gw.spray.res * gw.spray.res;
    float *pos = malloc((size_t)n * 4 * sizeof(float)), *vel = malloc((size_t)n * 4 * sizeof(float));
    int most = 0;
    for (int s = 0; s <= 60; s++) {
        world_update_spray(&gw, 0.2 + s / 30.0, NULL);
        spray_read(&gw.spray, pos, vel);
        int k = live(pos, n);
        if (k > most) most = k;
    }
    CHECK_EQ(most, 0);
    free(pos);
    free(vel);
    world_free(&gw);
}

static void test_parabolas_until_the_water(void) {
    gpu_world gw;
    CHECK(ring_world(&gw, 0.3, 3));
    int n = gw.spray.res * gw.spray.res;
    size_t bytes = (size_t)n * 4 * sizeof(float);
    float *p0 = malloc(bytes), *v0 = malloc(bytes), *p1 = malloc(bytes), *v1 = malloc(bytes);
    double t0 = 0.2 + 24 / 30.0;   /* the ring rises past the threshold from ~0.6 s */
    for (int s = 1; s <= 24; s++) {
        world_update_spray(&gw, 0.2 + s / 30.0, NULL);
        spray_read(&gw.spray, p0, v0);
        if (getenv("SPRAY_DEBUG")) printf("step %d live %d\n", s, live(p0, n));
    }
    double ring_h, ring_slope;
    ref_explosion_desc e = gw.w.waves.explosion[0];
    ref_explosion_bounds(&e, &ring_h, &ring_slope);
    int born = live(p0, n), followed = 0, removed = 0, kept_under = 0;
    double worst = 0, g = SPRAY_GRAVITY;
    /* two looks: after 0.1 s (most still fly: v0 of 0.3-4 m/s stays up
     * 2 v0 / g = 0.06-0.8 s) for the parabolas, after 0.5 s for removal */
    const int until[2] = { 27, 39 };
    double tau = 0;
    for (int look = 0; look < 2; look++) {
        for (int s = look ? until[0] + 1 : 25; s <= until[look]; s++) world_update_spray(&gw, 0.2 + s / 30.0, NULL);
        spray_read(&gw.spray, p1, v1);
        tau = 0.2 + until[look] / 30.0 - t0;
        for (int i = 0; i < n; i++) {
            const float *a = p0 + 4 * i, *va = v0 + 4 * i, *b = p1 + 4 * i;
            if (a[3] <= 0) continue;
            double x = a[0] + va[0] * tau, y = a[1] + va[1] * tau - 0.5 * g * tau * tau, z = a[2] + va[2] * tau;
            bool same = b[3] > 0 && fabs(b[3] - (a[3] - tau)) < 1e-4;   /* the same particle, not a new one */
            if (y < -ring_h - 0.3) {   /* under the water anywhere: must have been removed */
                if (same) kept_under++;
                else removed++;
                continue;
            }
            if (!same || look == 1) continue;   /* fell into the water (or its life ended) on the way */
            double d = sqrt((b[0] - x) * (b[0] - x) + (b[1] - y) * (b[1] - y) + (b[2] - z) * (b[2] - z));
            if (d > worst) worst = d;
            followed++;
        }
    }
    printf("  %d live at t0 %.2f s (ring height bound %.2f m); after 0.1 s %d on their parabolas (worst %.2e m); "
           "after %.2f s %d removed under the water, %d left under it\n",
           born, t0, ring_h, followed, worst, tau, removed, kept_under);
    CHECK_GT(born, 30);
    CHECK_GT(followed, 10);
    CHECK_LT(worst, 1e-4);
    CHECK_GT(removed, 10);
    CHECK_EQ(kept_under, 0);
    free(p0); free(v0); free(p1); free(v1);
    world_free(&gw);
}

static void run_state(unsigned seed, float *pos, float *vel) {
    gpu_world gw;
    CHECK(ring_world(&gw, 0.3, seed));
    for (int s = 1; s <= 20; s++) world_update_spray(&gw, 0.2 + s / 30.0, NULL);
    spray_read(&gw.spray, pos, vel);
    world_free(&gw);
}

static void test_same_seed_same_spray(void) {
    size_t bytes = 64 * 64 * 4 * sizeof(float);   /* count 4096: 64^2 */
    float *a = malloc(bytes), *av = malloc(bytes), *b = malloc(bytes), *bv = malloc(bytes);
    run_state(11, a, av);
    run_state(11, b, bv);
    CHECK_GT(live(a, 4096), 0);
    CHECK(memcmp(a, b, bytes) == 0 && memcmp(av, bv, bytes) == 0);
    run_state(12, b, bv);
    CHECK_NE(memcmp(a, b, bytes), 0);
    free(a); free(av); free(b); free(bv);
}

static void test_no_spray_no_pass(void) {
    render *r = render_create(&(render_desc){ .pack = "basic" });
    CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/scenes/lake.glib"), "%s", render_messages(r));
    render_target tg;
    CHECK(render_target_create(&tg, 64, 36, true));
    render_frame(r, 1.0, tg.fbo, 64, 36, NULL);
    render_frame(r, 1.5, tg.fbo, 64, 36, NULL);
    CHECK(!gl_test_has_pass(r, "spray"));
    render_target_destroy(&tg);
    render_destroy(r);
    /* a Spray scene runs its passes, and not with render_desc.no_spray (tarn bench) */
    for (int off = 0; off < 2; off++) {
        r = render_create(&(render_desc){ .no_spray = off == 1 });
        CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/scenes/waves/spray.glib"), "%s", render_messages(r));
        CHECK(render_target_create(&tg, 64, 36, true));
        render_frame(r, 1.8, tg.fbo, 64, 36, NULL);
        CHECK(gl_test_has_pass(r, "spray update") == (off == 0) && gl_test_has_pass(r, "spray draw") == (off == 0));
        render_target_destroy(&tg);
        render_destroy(r);
    }
    ref_world_desc desc;
    memset(&desc, 0, sizeof desc);
    gpu_world gw;
    gl_test_world_build(&gw, &desc);
    CHECK(!gw.spray.active && gw.spray.pos_tex[0] == 0 && gw.spray.progs[0].gl == 0);
    CHECK(!world_update_spray(&gw, 1.0, NULL));
    world_free(&gw);
}

static void test_ocean_crests_throw_spray(void) {
    ref_world_desc desc;
    memset(&desc, 0, sizeof desc);
    desc.terrain = REF_TERRAIN_FLAT;
    desc.depth = 30;
    desc.half_size = 20;
    desc.waves.ocean = (ref_ocean_desc){ .spectrum = REF_SPECTRUM_PHILLIPS, .wind_speed = 12, .res = 64,
                                         .cascades = 1, .choppiness = 1, .seed = 3 };
    desc.spray = (ref_spray_desc){ .on = true, .threshold = 0.3, .rate = 1e6, .life = 3, .seed = 5, .count = 4096 };
    gpu_world gw;
    CHECK(gl_test_world_build(&gw, &desc));
    int n = gw.spray.res * gw.spray.res;
    float *pos = malloc((size_t)n * 4 * sizeof(float)), *vel = malloc((size_t)n * 4 * sizeof(float));
    int first = -1, most = 0;
    for (int s = 0; s <= 20; s++) {   /* as render_frame: ocean, height map, spray */
        double t = 2.0 + s / 30.0;
        world_update_ocean(&gw, t, NULL);
        world_update_height(&gw, t, 1.0);
        world_update_spray(&gw, t, NULL);
        spray_read(&gw.spray, pos, vel);
        int k = live(pos, n);
        if (s == 0) first = k;
        if (k > most) most = k;
    }
    printf("  ocean: %d live after the jump, at most %d over 20 played steps\n", first, most);
    CHECK_EQ(first, 0);
    CHECK_GT(most, 20);
    free(pos);
    free(vel);
    world_free(&gw);
}

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    RUN(test_no_emission_no_particle);
    RUN(test_parabolas_until_the_water);
    RUN(test_same_seed_same_spray);
    RUN(test_no_spray_no_pass);
    RUN(test_ocean_crests_throw_spray);
    gl_ctx_destroy(ctx);
    return check_summary();
}
