/* frame_meter: the window's frame time, averaged over the last
 * FRAME_METER_WINDOW_S of frames (at least the last frame, when that one
 * alone is slower). A running average of 1/dt starts from its first frame's
 * spike and takes minutes to forget it at 1 fps; a time window shows true
 * figures from the first second. Pure C, no GL: the window feeds it the wall
 * time between frames.
 *
 *     frame_meter m = { 0 };
 *     each frame: frame_meter_add(&m, dt_s);
 *     frame_meter_ms(&m), frame_meter_fps(&m)
 */
#ifndef TARN_FRAME_METER_H
#define TARN_FRAME_METER_H

#define FRAME_METER_WINDOW_S 1.0   /* the span averaged over */
#define FRAME_METER_MAX 512        /* frames kept: at 512+ fps the window is shorter */

typedef struct frame_meter {
    double dt[FRAME_METER_MAX];    /* seconds, a ring; dt[head - 1] is the latest */
    int head, n;
} frame_meter;

/* One frame that took dt_s seconds (<= 0 is ignored: no time passed). */
void frame_meter_add(frame_meter *m, double dt_s);
/* Milliseconds per frame over the recent window; 0 before any frame. */
double frame_meter_ms(const frame_meter *m);
/* Frames per second from frame_meter_ms; 0 before any frame. */
double frame_meter_fps(const frame_meter *m);

#endif
