/* test_frame_meter: the window's frame-time meter (ui/frame_meter) with
 * synthetic frame times: true figures from the first second, whatever the
 * first frame did. */
#include "check.h"
#include "frame_meter.h"

static void test_empty_reads_zero(void) {
    frame_meter m = { 0 };
    CHECK_EQ(frame_meter_ms(&m), 0);
    CHECK_EQ(frame_meter_fps(&m), 0);
    frame_meter_add(&m, 0);               /* no time passed: not a frame */
    frame_meter_add(&m, -1);
    CHECK_EQ(m.n, 0);
}

/* The case: a tiny first frame, then 2 fps. A 0.9/0.1 average of
 * 1/dt read ~100 fps here for a long time. */
static void test_first_frame_spike_then_slow_frames(void) {
    frame_meter m = { 0 };
    frame_meter_add(&m, 0.001);
    frame_meter_add(&m, 0.5);
    CHECK_LT(frame_meter_fps(&m), 5);       /* already the right order after 0.5 s */
    frame_meter_add(&m, 0.5);
    CHECK_NEAR(frame_meter_fps(&m), 2.0, 1e-9);
    CHECK_NEAR(frame_meter_ms(&m), 500.0, 1e-9);
    for (int i = 0; i < 10; i++) frame_meter_add(&m, 0.5);
    CHECK_NEAR(frame_meter_fps(&m), 2.0, 1e-9);
}

/* A slow first frame (compiling shaders) is forgotten once a second of
 * frames follows it. */
static void test_slow_first_frame_is_forgotten(void) {
    frame_meter m = { 0 };
    frame_meter_add(&m, 3.0);
    CHECK_NEAR(frame_meter_ms(&m), 3000.0, 1e-9);
    for (int i = 0; i < 70; i++) frame_meter_add(&m, 1.0 / 60);
    CHECK_NEAR(frame_meter_fps(&m), 60.0, 1e-6);
}

/* Slower than the window: the last frame alone. */
static void test_one_frame_slower_than_the_window(void) {
    frame_meter m = { 0 };
    for (int i = 0; i < 100; i++) frame_meter_add(&m, 0.01);
    frame_meter_add(&m, 5.0);
    CHECK_NEAR(frame_meter_fps(&m), 0.2, 1e-9);
}

/* Fast frames overflow the ring: still the mean of what it keeps. */
static void test_fast_frames_fill_the_ring(void) {
    frame_meter m = { 0 };
    for (int i = 0; i < 3 * FRAME_METER_MAX; i++) frame_meter_add(&m, 0.001);
    CHECK_EQ(m.n, FRAME_METER_MAX);
    CHECK_NEAR(frame_meter_ms(&m), 1.0, 1e-9);
    CHECK_NEAR(frame_meter_fps(&m), 1000.0, 1e-6);
}

/* A change of rate shows within the window, not minutes later. */
static void test_follows_a_change_within_a_second(void) {
    frame_meter m = { 0 };
    for (int i = 0; i < 200; i++) frame_meter_add(&m, 0.005);
    for (int i = 0; i < 3; i++) frame_meter_add(&m, 0.4);   /* 1.2 s of slow frames */
    CHECK_NEAR(frame_meter_ms(&m), 400.0, 1e-9);
}

int main(void) {
    RUN(test_empty_reads_zero);
    RUN(test_first_frame_spike_then_slow_frames);
    RUN(test_slow_first_frame_is_forgotten);
    RUN(test_one_frame_slower_than_the_window);
    RUN(test_fast_frames_fill_the_ring);
    RUN(test_follows_a_change_within_a_second);
    return check_summary();
}
