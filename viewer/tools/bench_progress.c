/* bench_progress: `tarn bench`'s progress bar on stderr (bench_int.h): a
 * bar with the elapsed time and an estimate of what is left on a terminal,
 * a line now and then elsewhere. */
#include "util.h"
#include "bench_int.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>

static void fmt_dur(double s, char *buf, size_t n) {
    if (s < 60) snprintf(buf, n, "%.0f s", s);
    else snprintf(buf, n, "%d:%02d", (int)(s / 60), (int)fmod(s, 60));
}

void bench_progress_draw(progress *p, bool force) {
    if (p->quiet) return;
    double t = clock_now_s();
    if (!force && t - p->last_draw < 0.2) return;
    p->last_draw = t;
    double f = p->total > 0 ? p->done / p->total : 0;
    if (f > 1) f = 1;
    char el[32], eta[48] = "";
    fmt_dur(t - p->start, el, sizeof el);
    if (f > 0.02 && f < 1) {
        char e[32];
        fmt_dur((t - p->start) * (1 - f) / f, e, sizeof e);
        snprintf(eta, sizeof eta, " ETA %s", e);
    }
    if (p->tty) {
        enum { WIDTH = 28 };
        char bar[WIDTH + 1];
        int fill = (int)(f * WIDTH + 0.5);
        for (int i = 0; i < WIDTH; i++) bar[i] = i < fill ? '#' : '.';
        bar[WIDTH] = '\0';
        fprintf(stderr, "\r[%s] %3.0f%% %s%s  %s\033[K", bar, 100 * f, el, eta, p->what);
    } else if (force) {
        fprintf(stderr, "bench: %3.0f%% %s%s  %s\n", 100 * f, el, eta, p->what);
    }
    fflush(stderr);
}

void bench_progress_set(progress *p, double done, bool force, const char *fmt, ...) {
    p->done = done;
    if (fmt) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(p->what, sizeof p->what, fmt, ap);
        va_end(ap);
    }
    bench_progress_draw(p, force);
}
