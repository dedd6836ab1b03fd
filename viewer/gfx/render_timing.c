/* render_timing: the GPU time of a frame, of each pass and (with draw
 * timing on) of each drawing command, by marks in the frame's timer. */
#include "util.h"
#include "render_internal.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <stdio.h>

void render_timing_mark_pass(render *r, const glib_cmd *c) {
    char name[GPU_TIMER_NAME];
    int n = snprintf(name, sizeof name, "%s:%d", c->nnum ? "pass" : "screen", c->line);
    for (int k = 0; k < c->nnum && n < (int)sizeof name - 4; k++) n += snprintf(name + n, sizeof name - (size_t)n, " %d", (int)c->num[k]);
    gpu_timer_mark(&r->timer, name);
}

/* A mark that times what was drawn before it: a CPU rasteriser (llvmpipe)
 * bins draws and rasterises them at a later flush, and resolves a
 * timestamp query there too, so without the finishes a draw's pixels fell
 * in a later draw's interval (the water's under the World before it). */
void render_timing_mark_now(render *r, const char *name) {
    glFinish();
    gpu_timer_mark(&r->timer, name);
    glFinish();
}

void render_set_draw_timing(render *r, bool on) { r->draw_timing = on; }

double render_gpu_ms(render *r, bool wait) {
    gpu_timer_collect(&r->timer, wait);
    return r->timer.frame_ms;
}

int render_pass_times(render *r, bool wait, const char (**names)[GPU_TIMER_NAME], const double **ms) {
    gpu_timer_collect(&r->timer, wait);
    *names = (const char (*)[GPU_TIMER_NAME])r->timer.pass_names;
    *ms = r->timer.pass_ms;
    return r->timer.npasses;
}

void render_pass_summary(render *r, char *out, int len) {
    const char (*names)[GPU_TIMER_NAME];
    const double *ms;
    int n = render_pass_times(r, false, &names, &ms), used = 0;
    if (len > 0) out[0] = '\0';
    for (int i = 0; i < n && used < len - 40; i++)
        used += snprintf(out + used, (size_t)(len - used), "%s%s %.2f ms", i ? "\n" : "", names[i], ms[i]);
}
