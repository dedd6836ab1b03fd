/* frame_meter: frame time over a recent window (see frame_meter.h). */
#include "frame_meter.h"

void frame_meter_add(frame_meter *m, double dt_s) {
    if (!(dt_s > 0)) return;
    m->dt[m->head] = dt_s;
    m->head = (m->head + 1) % FRAME_METER_MAX;
    if (m->n < FRAME_METER_MAX) m->n++;
}

double frame_meter_ms(const frame_meter *m) {
    double sum = 0;
    int k = 0;
    /* newest first until the window is covered: the last frame always counts */
    while (k < m->n && (k == 0 || sum < FRAME_METER_WINDOW_S)) {
        int i = (m->head - 1 - k + FRAME_METER_MAX) % FRAME_METER_MAX;
        sum += m->dt[i];
        k++;
    }
    return k ? sum / k * 1e3 : 0;
}

double frame_meter_fps(const frame_meter *m) {
    double ms = frame_meter_ms(m);
    return ms > 0 ? 1e3 / ms : 0;
}
