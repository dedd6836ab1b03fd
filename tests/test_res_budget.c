/* test_res_budget: the windows' frame budget controller (ui/res_budget)
 * fed synthetic frame times from a cost model ms = a + b * pixels (the
 * shape the issue fitted for every pack): the scale converges to the size
 * whose frame costs the budget, a fixed cost above the budget stays at the
 * floor, and a still picture gets one full-resolution frame and then none. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "res_budget.h"
#include "util.h"

/* A frame at scale s of a w x h window under the model, ms. */
static double model_ms(double a, double b_per_mpix, double s, int w, int h) {
    int iw, ih;
    res_budget_size(s, w, h, &iw, &ih);
    return a + b_per_mpix * (double)iw * ih / 1e6;
}

/* Moving frames (a new key each) at 60 Hz of clock; returns the last scale. */
static double run_moving(res_budget *rb, double a, double bm, int frames, double *t, uint64_t *key, double *last_ms) {
    double s = 1.0;
    for (int i = 0; i < frames; i++) {
        (*key)++;
        CHECK(res_budget_plan(rb, *key, *t, *last_ms, false, &s));
        *last_ms = model_ms(a, bm, s, 960, 540);
        *t += *last_ms / 1e3;
    }
    return s;
}

/* The lake's basic pack at 960x540 before the speed-ups: 15 + 249/Mpix. */
static void test_converges_to_the_budget(void) {
    res_budget rb;
    res_budget_init(&rb, 50);
    double t = 0, last = 0;
    uint64_t key = 0;
    double s = run_moving(&rb, 15, 249, 40, &t, &key, &last);
    double ms = model_ms(15, 249, s, 960, 540);
    CHECK_LT(s, 1.0);
    CHECK_LE(ms, 50 + 1e-9);   /* within the budget: it aims below it by the dead band */
    CHECK_GE(ms, 50 / (1 + RES_BUDGET_DEADBAND) * (1 - RES_BUDGET_DEADBAND) - 2);   /* and not needlessly small */
    /* 40 more frames: it stays (no hunting) */
    double s2 = run_moving(&rb, 15, 249, 40, &t, &key, &last);
    CHECK_NEAR(s2, s, 0.05);
}

/* The first frame, before any measure, is drawn at RES_BUDGET_FIRST of a
 * side (a window's first picture sooner); with the budget off, full. */
static void test_first_frame_is_reduced(void) {
    res_budget rb;
    double s;
    res_budget_init(&rb, 50);
    CHECK(res_budget_plan(&rb, 1, 0.0, 0, false, &s));
    CHECK_EQ(s, RES_BUDGET_FIRST);
    res_budget_init(&rb, 0);
    CHECK(res_budget_plan(&rb, 1, 0.0, 0, false, &s));
    CHECK_EQ(s, 1.0);
}

/* A cheap scene is never reduced: the scale stays 1. */
static void test_cheap_scene_stays_full(void) {
    res_budget rb;
    res_budget_init(&rb, 50);
    double t = 0, last = 0;
    uint64_t key = 0;
    CHECK_NEAR(run_moving(&rb, 2, 20, 30, &t, &key, &last), 1.0, 1e-12);
    /* its moving frames are full-resolution, yet the picture is not still
     * (the window keeps drawing it while a save compiles) until its key has
     * stayed the same for the settle time */
    CHECK(rb.full_done);
    CHECK(!res_budget_settled(&rb, t));
    double s;
    t += RES_BUDGET_SETTLE_S / 2;
    CHECK(!res_budget_plan(&rb, key, t, last, false, &s));
    CHECK(!res_budget_settled(&rb, t));
    t += RES_BUDGET_SETTLE_S;
    CHECK(!res_budget_plan(&rb, key, t, 5, false, &s));
    CHECK(res_budget_settled(&rb, t));
}

/* natural's photon pass: 257 ms whatever the size. The floor, not below. */
static void test_fixed_cost_over_budget_stays_at_the_floor(void) {
    res_budget rb;
    res_budget_init(&rb, 50);
    double t = 0, last = 0;
    uint64_t key = 0;
    CHECK_NEAR(run_moving(&rb, 257, 444, 30, &t, &key, &last), RES_BUDGET_FLOOR, 1e-12);
    int iw, ih;
    res_budget_size(RES_BUDGET_FLOOR, 960, 540, &iw, &ih);
    CHECK(iw == 120 && ih == 68);
}

/* After the camera stops: the reduced frame stays for the settle time, then
 * one frame at full resolution, then nothing is drawn while it stays still;
 * a change draws reduced again at once, from what the full frame cost. */
/* A budget of 50 ms after 20 moving frames of a 15 + 249 ms-per-megapixel
 * scene: the scale they settled at. */
static double moving_picture(res_budget *rb, double *t, uint64_t *key, double *last) {
    res_budget_init(rb, 50);
    *t = *last = 0;
    *key = 0;
    return run_moving(rb, 15, 249, 20, t, key, last);
}

static void test_still_picture_returns_to_full(void) {
    res_budget rb;
    double t, last, s;
    uint64_t key;
    double moving = moving_picture(&rb, &t, &key, &last);
    CHECK_LT(moving, 1.0);
    t += 0.01;
    CHECK(!res_budget_plan(&rb, key, t, last, false, &s));   /* settling: keep the reduced frame */
    CHECK_NEAR(s, moving, 1e-12);
    t += RES_BUDGET_SETTLE_S;
    CHECK(res_budget_plan(&rb, key, t, 5, false, &s));
    CHECK_EQ(s, 1.0);
    last = model_ms(15, 249, 1.0, 960, 540);
    for (int i = 0; i < 10; i++) {
        t += 0.005;
        CHECK(!res_budget_plan(&rb, key, t, i == 0 ? last : 5, false, &s));
        CHECK_EQ(s, 1.0);
    }
    CHECK(res_budget_plan(&rb, key + 1, t, 5, false, &s));
    CHECK(s < 1.0 && s >= RES_BUDGET_FLOOR);
    /* one step from the full frame's time: the fixed cost leaves it a little over */
    CHECK_LE(model_ms(15, 249, s, 960, 540), 50 * 1.3);
}

/* A held full frame (a compile job making its code) waits past the settle
 * time, the reduced frame shown and nothing drawn; full_held says so (the
 * window sleeps on it); a screenshot is still full; the release draws it. */
static void test_full_frame_held(void) {
    res_budget rb;
    double t, last, s;
    uint64_t key;
    double moving = moving_picture(&rb, &t, &key, &last);
    res_budget_hold_full(&rb, true);
    t += 0.01;
    CHECK(!res_budget_plan(&rb, key, t, last, false, &s));
    CHECK(!res_budget_full_held(&rb, t));                      /* settling: not due yet */
    for (int i = 0; i < 5; i++) {
        t += RES_BUDGET_SETTLE_S;
        CHECK(!res_budget_plan(&rb, key, t, 5, false, &s));   /* held: the reduced frame stays */
        CHECK_NEAR(s, moving, 1e-12);
        CHECK(res_budget_full_held(&rb, t));
        CHECK(!res_budget_settled(&rb, t));
    }
    CHECK(res_budget_plan(&rb, key + 1, t, 5, false, &s));    /* a change draws, reduced */
    CHECK_LT(s, 1.0);
    CHECK(!res_budget_full_held(&rb, t));
    t += RES_BUDGET_SETTLE_S;
    CHECK(res_budget_plan(&rb, key + 1, t, 5, true, &s));     /* a screenshot: full */
    CHECK_EQ(s, 1.0);
    CHECK(res_budget_plan(&rb, key + 2, t, 5, false, &s));
    t += RES_BUDGET_SETTLE_S;
    CHECK(!res_budget_plan(&rb, key + 2, t, 5, false, &s));
    res_budget_hold_full(&rb, false);                           /* the job's end */
    CHECK(!res_budget_full_held(&rb, t));
    CHECK(res_budget_plan(&rb, key + 2, t, 5, false, &s));
    CHECK_EQ(s, 1.0);
    CHECK(res_budget_settled(&rb, t));
}

/* A cheap moving picture (its frames full-resolution) while a full frame
 * is held: drawn just below (RES_BUDGET_HELD_MAX, whose code the job has
 * made), the controller's own scale still 1 (the window asks the job for
 * the full frame's code on it); the release draws it full again. */
static void test_held_caps_moving_frames(void) {
    res_budget rb;
    res_budget_init(&rb, 50);
    double t = 0, s;
    uint64_t key = 0;
    for (int i = 0; i < 12; i++, t += 0.01) res_budget_plan(&rb, ++key, t, i ? 5 : 0, false, &s);
    CHECK_EQ(s, 1.0);                                           /* 5 ms frames: full */
    res_budget_hold_full(&rb, true);
    for (int i = 0; i < 4; i++, t += 0.01) {
        CHECK(res_budget_plan(&rb, ++key, t, 5, false, &s));
        CHECK_EQ(s, RES_BUDGET_HELD_MAX);
        CHECK_EQ(rb.scale, 1.0);
    }
    res_budget_hold_full(&rb, false);
    CHECK(res_budget_plan(&rb, ++key, t, 5, false, &s));
    CHECK_EQ(s, 1.0);
}

/* A screenshot (force_full) of a moving picture is drawn at full size; with
 * the budget off every changed frame is full and a still one is kept. */
static void test_force_full_and_off(void) {
    res_budget rb;
    res_budget_init(&rb, 50);
    double t = 0, last = 0, s;
    uint64_t key = 0;
    run_moving(&rb, 15, 249, 20, &t, &key, &last);
    CHECK(res_budget_plan(&rb, ++key, t, last, true, &s));
    CHECK_EQ(s, 1.0);
    CHECK(!res_budget_plan(&rb, key, t + 0.001, 500, true, &s));   /* drawn already */
    res_budget_init(&rb, 0);
    for (int i = 0; i < 5; i++) {
        CHECK(res_budget_plan(&rb, ++key, t, 500, false, &s));
        CHECK_EQ(s, 1.0);
    }
    CHECK(!res_budget_plan(&rb, key, t, 500, false, &s));
}

/* Noisy times (+-30%) around a cost: it settles within the deadband's
 * reach and never leaves [floor, 1]. */
static void test_noise_stays_bounded(void) {
    res_budget rb;
    res_budget_init(&rb, 50);
    double t = 0, s = 1, last = 0;
    unsigned seed = 12345;
    for (int i = 0; i < 500; i++) {
        CHECK(res_budget_plan(&rb, (uint64_t)i, t, last, false, &s));
        CHECK(s >= RES_BUDGET_FLOOR && s <= 1.0);
        seed = seed * 1103515245u + 12345u;
        double noise = 0.7 + 0.6 * ((seed >> 16) & 0x7fff) / 32767.0;
        last = model_ms(27, 713, s, 960, 540) * noise;
        t += last / 1e3;
    }
    double ms = model_ms(27, 713, s, 960, 540);
    CHECK(ms > 20 && ms < 90);
}

/* The window animating: the first frame at a new size pays once for what
 * later frames at that size keep (the world's layers, world_layers.h), so
 * it costs much more than they do. Sized by that frame, the picture would
 * shrink, pay again at the new size and hunt, frame after frame; the
 * controller leaves the first frame at a size out and settles. */
static void test_first_frame_at_a_size_is_not_a_measure(void) {
    res_budget rb;
    res_budget_init(&rb, 50);
    double t = 0, s = 1, last = 0, prev = -1;
    int changes = 0;
    for (int i = 0; i < 120; i++) {
        CHECK(res_budget_plan(&rb, (uint64_t)i + 1, t, last, false, &s));
        bool fresh = s != prev;
        if (i >= 60 && fresh) changes++;
        last = model_ms(10, 100, s, 960, 540) + (fresh ? model_ms(30, 300, s, 960, 540) : 0);
        prev = s;
        t += last / 1e3;
    }
    CHECK_MSG(changes <= 1, "%d new sizes in the last 60 frames, want at most 1", changes);
    CHECK_LE(model_ms(10, 100, s, 960, 540), 50 + 1e-9);
    CHECK_MSG(model_ms(10, 100, s, 960, 540) >= 50 / (1 + RES_BUDGET_DEADBAND) * (1 - RES_BUDGET_DEADBAND) - 2 || s == 1.0,
              "settled at %.3f of a side, %.1f ms a frame", s, model_ms(10, 100, s, 960, 540));
}

/* A cost step: natural's targets double at 0.354 of a side, and a frame
 * just over it costs half as much again as one just under (the lake in
 * the window, llvmpipe: 37 against 58 ms). Growing from under the step by
 * the time left crossed it, two frames over the aim shrank it back, and
 * the size went back and forth every few frames, a third of them over the
 * budget. A size found over the aim is a ceiling for RES_BUDGET_CEILING_S:
 * growth stops short of it (halfway, then closer), so the size settles
 * under the step and tries it again only once the ceiling lapses. */
static double step_ms(double s) {
    int iw, ih;
    res_budget_size(s, 960, 540, &iw, &ih);
    return 15 + 390 * (double)iw * ih / 1e6 + (s >= 0.354 ? 18 : 0);
}

static void test_cost_step_settles_under_it(void) {
    res_budget rb;
    res_budget_init(&rb, 50);
    double t = 0, s = 1, last = 0, prev = -1, least = 1;
    int changes = 0, over = 0;
    unsigned seed = 777;
    for (int i = 0; i < 400; i++) {
        CHECK(res_budget_plan(&rb, (uint64_t)i + 1, t, last, false, &s));
        seed = seed * 1103515245u + 12345u;
        last = step_ms(s) * (0.85 + 0.3 * ((seed >> 16) & 0x7fff) / 32767.0);   /* the machine's noise, +-15% */
        if (i >= 100) {
            changes += s != prev;
            over += step_ms(s) > 50;
            least = fmin(least, s);
        }
        prev = s;
        t += last / 1e3;
    }
    /* 300 frames of ~40 ms, 12 s: without the ceiling 59 new sizes and 75
     * frames over the budget */
    CHECK_MSG(changes <= 10, "%d new sizes in 300 frames, want at most 10", changes);
    CHECK_MSG(over <= 8, "%d frames over the budget in 300, want at most 8", over);
    CHECK_MSG(step_ms(least) >= 30, "down to %.3f of a side, %.1f ms a frame", least, step_ms(least));
    /* the camera moved (another picture, other costs): the ceiling is
     * forgotten and the next frames under the aim grow past it */
    double under;
    res_budget_view(&rb, 42);
    for (int i = 0; i < 6; i++) CHECK(res_budget_plan(&rb, (uint64_t)1000 + i, t, 20, false, &under));
    CHECK_MSG(under > 0.37, "after the camera moved: %.3f of a side", under);
}

/* One slow frame (the machine's noise) keeps the size; two in a row over
 * the aim shrink it; one quick one does not grow it. */
static void test_one_frame_is_noise(void) {
    res_budget rb;
    res_budget_init(&rb, 50);
    double t = 0, last = 0;
    uint64_t key = 0;
    double s = run_moving(&rb, 15, 249, 40, &t, &key, &last), s1;
    double steady = model_ms(15, 249, s, 960, 540);
    CHECK(res_budget_plan(&rb, ++key, t, 1.4 * steady, false, &s1));   /* one slow frame */
    CHECK(res_budget_plan(&rb, ++key, t, steady, false, &s1));
    CHECK(res_budget_plan(&rb, ++key, t, steady, false, &s1));
    CHECK_EQ(s1, s);
    CHECK(res_budget_plan(&rb, ++key, t, 0.5 * steady, false, &s1));   /* one quick frame */
    CHECK(res_budget_plan(&rb, ++key, t, steady, false, &s1));
    CHECK(res_budget_plan(&rb, ++key, t, steady, false, &s1));
    CHECK_EQ(s1, s);
    CHECK(res_budget_plan(&rb, ++key, t, 1.4 * steady, false, &s1));   /* two: the scene got heavier */
    CHECK(res_budget_plan(&rb, ++key, t, 1.4 * steady, false, &s1));
    CHECK_LT(s1, s);
    /* and lighter again: a size that held before the shrink is no ceiling
     * (test_cost_step_settles_under_it), so it grows back */
    double s2 = s1;
    for (int i = 0; i < 12; i++) {
        CHECK(res_budget_plan(&rb, ++key, t, model_ms(15, 249, s2, 960, 540), false, &s2));
        t += 0.04;
    }
    CHECK_MSG(s2 > s1 && model_ms(15, 249, s2, 960, 540) >= 50 / (1 + RES_BUDGET_DEADBAND) * (1 - RES_BUDGET_DEADBAND),
              "after the noise: %.3f of a side, %.1f ms a frame", s2, model_ms(15, 249, s2, 960, 540));
}

/* A save's job takes one of two cores (res_budget_contend): frames cost
 * twice the model's. The picture shrinks at once to RES_BUDGET_CONTENDED
 * of a side, the controller brings the doubled frames within the budget,
 * and at the job's end the size from before comes back at once, the last
 * contended frame's time not taken as a measure of it. */
static void test_contended_shrinks_and_comes_back(void) {
    res_budget rb;
    res_budget_init(&rb, 50);
    double t = 0, last = 0, s;
    uint64_t key = 0;
    double calm = run_moving(&rb, 15, 249, 40, &t, &key, &last);
    CHECK_LT(calm, 1.0);
    res_budget_contend(&rb, true);
    double worst_late = 0;
    for (int i = 0; i < 20; i++) {
        CHECK(res_budget_plan(&rb, ++key, t, last, false, &s));
        if (i == 0) CHECK_NEAR(s, calm * RES_BUDGET_CONTENDED, 1e-12);
        last = 2 * model_ms(15, 249, s, 960, 540);
        if (i >= 10) worst_late = fmax(worst_late, last);
        t += last / 1e3;
    }
    CHECK_MSG(worst_late <= 50 + 1e-9, "contended frames settle at %.1f ms, budget 50", worst_late);
    res_budget_contend(&rb, false);
    CHECK(res_budget_plan(&rb, ++key, t, last, false, &s));
    CHECK_EQ(s, calm);
    last = model_ms(15, 249, s, 960, 540);   /* a new size's first frame: no measure either */
    CHECK(res_budget_plan(&rb, ++key, t, 3 * last, false, &s));
    CHECK_EQ(s, calm);
    /* contending twice changes nothing; ending twice neither */
    res_budget_contend(&rb, true);
    res_budget_contend(&rb, true);
    CHECK_NEAR(rb.scale, calm * RES_BUDGET_CONTENDED, 1e-12);
    res_budget_contend(&rb, false);
    res_budget_contend(&rb, false);
    CHECK_EQ(rb.scale, calm);
}

/* A costlier path for a while (the window's water drawn as a grid after a
 * save, res_budget_costlier): the picture shrinks at once by 1/sqrt(cost)
 * of a side, so frames whose cost is in their pixels stay within the
 * budget from the first; the floor holds; no change for a cost of 1 or
 * less or with the budget off; the calm size comes back at the
 * contention's end. */
static void test_costlier_path_shrinks_at_once(void) {
    res_budget rb;
    res_budget_init(&rb, 50);
    double t = 0, last = 0, s;
    uint64_t key = 0;
    double calm = run_moving(&rb, 0, 249, 40, &t, &key, &last);
    CHECK_LT(calm, 1.0);
    CHECK_LE(last, 50 + 1e-9);
    res_budget_costlier(&rb, 1.5);
    CHECK_NEAR(rb.scale, calm / sqrt(1.5), 1e-12);
    for (int i = 0; i < 10; i++) {
        CHECK(res_budget_plan(&rb, ++key, t, last, false, &s));
        last = 1.5 * model_ms(0, 249, s, 960, 540);
        CHECK_MSG(last <= 50 * 1.01, "frame %d of the costlier path: %.1f ms, budget 50", i, last);
        t += last / 1e3;
    }
    /* without it, the first frames at the old size are over the budget */
    CHECK_GT(1.5 * model_ms(0, 249, calm, 960, 540), 50);
    double before = rb.scale;
    res_budget_costlier(&rb, 1.0);
    res_budget_costlier(&rb, 0.5);
    CHECK_EQ(rb.scale, before);
    res_budget_costlier(&rb, 1e6);
    CHECK_EQ(rb.scale, RES_BUDGET_FLOOR);
    /* under contention: the calm size back at its end */
    res_budget_init(&rb, 50);
    calm = run_moving(&rb, 15, 249, 40, &t, &key, &last);
    res_budget_contend(&rb, true);
    res_budget_costlier(&rb, 1.35);
    CHECK_NEAR(rb.scale, calm * RES_BUDGET_CONTENDED / sqrt(1.35), 1e-12);
    res_budget_contend(&rb, false);
    CHECK_EQ(rb.scale, calm);
    res_budget_init(&rb, 0);
    res_budget_costlier(&rb, 2);
    CHECK_EQ(rb.scale, 1.0);
}

static void test_key_changes_with_any_byte(void) {
    float a[3] = { 1, 2, 3 }, b[3] = { 1, 2, 3.0001f };
    uint64_t ka = hash_fnv1a(HASH_FNV1A_BASIS, a, sizeof a);
    CHECK_EQ(ka, hash_fnv1a(HASH_FNV1A_BASIS, a, sizeof a));
    CHECK_NE(ka, hash_fnv1a(HASH_FNV1A_BASIS, b, sizeof b));
    /* FNV-1a's published vectors (64-bit): "" and "a" */
    CHECK_EQ(hash_fnv1a(HASH_FNV1A_BASIS, "", 0), 0xcbf29ce484222325ull);
    CHECK_EQ(hash_fnv1a(HASH_FNV1A_BASIS, "a", 1), 0xaf63dc4c8601ec8cull);
    int iw, ih;
    res_budget_size(0.5, 961, 541, &iw, &ih);
    CHECK(iw == 481 && ih == 271);
    res_budget_size(1e-6, 961, 541, &iw, &ih);
    CHECK(iw == 1 && ih == 1);
    res_budget_size(0.5, 256, 1024, &iw, &ih);   /* reduced sides off powers of two (side_off_pow2) */
    CHECK(iw == 129 && ih == 513);
    res_budget_size(1.0, 256, 1024, &iw, &ih);   /* the full frame as it is */
    CHECK(iw == 256 && ih == 1024);
    CHECK(side_off_pow2(64, 64) == 64 && side_off_pow2(63, 64) == 63 && side_off_pow2(2, 64) == 2);
    CHECK(side_off_pow2(64, 100) == 65 && side_off_pow2(4, 100) == 5);
    /* a reduced side keeps whether the full one is a power of two */
    CHECK_EQ(side_like_full(379, 1024, 16), 512);   /* 379: nearer 512 than 256 in ratio */
    CHECK_EQ(side_like_full(77, 256, 16), 64);
    CHECK_EQ(side_like_full(95, 256, 32), 128);
    CHECK_EQ(side_like_full(3, 256, 16), 16);        /* the floor */
    CHECK_EQ(side_like_full(3000, 1024, 16), 1024);  /* never above full */
    CHECK_EQ(side_like_full(64, 100, 16), 65);       /* full not one: side_off_pow2 */
    CHECK_EQ(side_like_full(50, 100, 16), 50);
    CHECK_EQ(side_like_full(3, 100, 16), 17);
}

int main(void) {
    RUN(test_converges_to_the_budget);
    RUN(test_first_frame_is_reduced);
    RUN(test_cheap_scene_stays_full);
    RUN(test_fixed_cost_over_budget_stays_at_the_floor);
    RUN(test_still_picture_returns_to_full);
    RUN(test_full_frame_held);
    RUN(test_held_caps_moving_frames);
    RUN(test_force_full_and_off);
    RUN(test_noise_stays_bounded);
    RUN(test_first_frame_at_a_size_is_not_a_measure);
    RUN(test_one_frame_is_noise);
    RUN(test_cost_step_settles_under_it);
    RUN(test_contended_shrinks_and_comes_back);
    RUN(test_costlier_path_shrinks_at_once);
    RUN(test_key_changes_with_any_byte);
    return check_summary();
}
