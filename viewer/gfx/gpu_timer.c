#include "gpu_timer.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <stdio.h>
#include <string.h>

void gpu_timer_init(gpu_timer *t) {
    memset(t, 0, sizeof *t);
    glGenQueries(2 * (GPU_TIMER_MARKS + 1), &t->q[0][0]);
    t->frame_ms = -1;
}

void gpu_timer_free(gpu_timer *t) {
    glDeleteQueries(2 * (GPU_TIMER_MARKS + 1), &t->q[0][0]);
    memset(t, 0, sizeof *t);
}

static void read_slot(gpu_timer *t, int s) {
    GLuint64 stamp[GPU_TIMER_MARKS + 1] = {0};
    int n = t->nmarks[s];
    for (int i = 0; i <= n; i++) glGetQueryObjectui64v(t->q[s][i], GL_QUERY_RESULT, &stamp[i]);
    t->frame_ms = stamp[n] >= stamp[0] ? (double)(stamp[n] - stamp[0]) / 1e6 : -1;
    t->npasses = n;
    for (int i = 0; i < n; i++) {
        t->pass_ms[i] = stamp[i + 1] >= stamp[i] ? (double)(stamp[i + 1] - stamp[i]) / 1e6 : -1;
        memcpy(t->pass_names[i], t->names[s][i], GPU_TIMER_NAME);
    }
    t->pending[s] = false;
}

void gpu_timer_collect(gpu_timer *t, bool wait) {
    for (int k = 1; k <= 2; k++) {   /* the older slot first, so the newest wins */
        int s = (t->slot + k) % 2;
        if (!t->pending[s]) continue;
        GLint ready = 0;
        if (!wait) glGetQueryObjectiv(t->q[s][t->nmarks[s]], GL_QUERY_RESULT_AVAILABLE, &ready);
        if (wait || ready) read_slot(t, s);
    }
}

void gpu_timer_begin_frame(gpu_timer *t) {
    if (t->pending[t->slot]) read_slot(t, t->slot);   /* two frames behind: done by now */
    t->nmarks[t->slot] = 0;
    gpu_timer_mark(t, "screen");
}

void gpu_timer_mark(gpu_timer *t, const char *pass_name) {
    int s = t->slot, n = t->nmarks[s];
    if (n >= GPU_TIMER_MARKS) return;   /* more passes than marks: the rest add to the last */
    glQueryCounter(t->q[s][n], GL_TIMESTAMP);
    snprintf(t->names[s][n], GPU_TIMER_NAME, "%s", pass_name);
    t->nmarks[s] = n + 1;
}

void gpu_timer_end_frame(gpu_timer *t) {
    int s = t->slot;
    glQueryCounter(t->q[s][t->nmarks[s]], GL_TIMESTAMP);
    t->pending[s] = true;
    t->slot = 1 - s;
    gpu_timer_collect(t, false);
}
