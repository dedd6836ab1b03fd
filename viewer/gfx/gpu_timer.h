/* gpu_timer: GPU time per frame and per pass from GL timestamp queries.
 * Two frames in flight: results are read a frame late without stalling
 * (or at once, waiting, for benchmarks). A pass starts at each mark; the
 * frame's first pass is "screen" until a RenderToTexture begins another.
 * (GL_TIMESTAMP rather than GL_TIME_ELAPSED: llvmpipe's elapsed queries were
 * wrong across framebuffer switches; on llvmpipe timestamps are taken when
 * commands are queued, so only wall time after glFinish means anything
 * there.) */
#ifndef TARN_GPU_TIMER_H
#define TARN_GPU_TIMER_H

#include <stdbool.h>

#define GPU_TIMER_MARKS 32
#define GPU_TIMER_NAME 48

typedef struct gpu_timer {
    unsigned q[2][GPU_TIMER_MARKS + 1];
    char names[2][GPU_TIMER_MARKS][GPU_TIMER_NAME];
    int nmarks[2];
    bool pending[2];
    int slot;
    /* the last completed frame */
    double frame_ms;                          /* -1 until one is known */
    int npasses;
    double pass_ms[GPU_TIMER_MARKS];
    char pass_names[GPU_TIMER_MARKS][GPU_TIMER_NAME];
} gpu_timer;

void gpu_timer_init(gpu_timer *t);
void gpu_timer_free(gpu_timer *t);
void gpu_timer_begin_frame(gpu_timer *t);
void gpu_timer_mark(gpu_timer *t, const char *pass_name);
void gpu_timer_end_frame(gpu_timer *t);
/* Reads finished frames; wait: block for the latest. */
void gpu_timer_collect(gpu_timer *t, bool wait);

#endif
