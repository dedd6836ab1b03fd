/* bench_timing: timed frames (bench_int.h): the samples of a setting at a
 * time gathered over its turns, their medians and quartiles, the settings
 * timed round-robin, frames timed one after another (the cost floor, the
 * cost model), and the cost floor. */
#include "util.h"
#include "bench_int.h"

#include <GL/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "mem.h"
#include "ref_metrics.h"
#include "render.h"

/* The CPU time this process has used, all its threads (NaN: no such
 * clock). With llvmpipe the rasteriser's threads are the process's, so a
 * frame's delta is the work it took, which the machine's other processes
 * barely change; after glFinish those threads are asleep, so their time is
 * up to date. */
static double cpu_now_s(void) {
    struct timespec ts;
    if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0) return NAN;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* A timing's time on the run's axis */
double bench_axis_ms(const bench *b, const timing *t) {
    return b->axis == BENCH_AXIS_GPU ? t->gpu_ms : b->axis == BENCH_AXIS_CPU ? t->cpu_ms : t->wall_ms;
}

static void pass_collect(pass_samples *ps, render *r, int max) {
    const char (*names)[GPU_TIMER_NAME];
    const double *ms;
    int n = render_pass_times(r, true, &names, &ms);
    for (int i = 0; i < n; i++) {
        int k = 0;
        while (k < ps->n && strcmp(ps->name[k], names[i]) != 0) k++;
        if (k == ps->n) {
            if (ps->n >= GPU_TIMER_MARKS) continue;
            memcpy(ps->name[k], names[i], GPU_TIMER_NAME);
            ps->ms[k] = mem_zalloc((size_t)max * sizeof(double));
            ps->count[k] = 0;
            ps->n++;
        }
        if (ps->count[k] < max && ms[i] >= 0) ps->ms[k][ps->count[k]++] = ms[i];
    }
}

void bench_acc_init(timer_acc *a, int max, bool passes) {
    memset(a, 0, sizeof *a);
    a->max = max;
    a->passes = passes;
    a->gpu = mem_zalloc((size_t)max * sizeof *a->gpu);
    a->wall = mem_zalloc((size_t)max * sizeof *a->wall);
    a->cpu = mem_zalloc((size_t)max * sizeof *a->cpu);
}

/* done: the most frames, or at least 3 and the budget spent */
static bool acc_done(const bench *b, const timer_acc *a) {
    return a->n >= a->max || (a->n >= 3 && a->spent > b->o.frame_budget);
}

/* Up to count more timed frames at time t (fewer when done first). */
static void acc_frames(bench *b, timer_acc *a, render *r, const render_target *tg, double t, int count) {
    for (int i = 0; i < count && !acc_done(b, a); i++) {
        double c0 = cpu_now_s(), t0 = clock_now_s();
        render_frame(r, t, tg->fbo, tg->w, tg->h, NULL);
        glFinish();   /* the wall time of the whole frame, deferred rasterisation included */
        double s = clock_now_s() - t0;
        a->cpu[a->n] = (cpu_now_s() - c0) * 1e3;
        a->wall[a->n] = s * 1e3;
        a->gpu[a->n] = render_gpu_ms(r, true);
        a->spent += s;
        if (a->passes) pass_collect(&a->ps, r, a->max);
        a->n++;
    }
}

/* The median, quartiles and spread ((q3 - q1) / median, from 4 samples)
 * of the v[i] >= 0 (numpy's interpolation); v is reordered. */
static void quartiles(double *v, int n, double *med, double *q1, double *q3, double *spread) {
    int k = 0;
    for (int i = 0; i < n; i++)
        if (v[i] >= 0) v[k++] = v[i];
    *med = *q1 = *q3 = *spread = NAN;
    if (k == 0) return;
    qsort(v, (size_t)k, sizeof *v, cmp_double);
    *med = ref_percentile_sorted(v, k, 50);
    *q1 = ref_percentile_sorted(v, k, 25);
    *q3 = ref_percentile_sorted(v, k, 75);
    if (k >= 4 && *med > 0) *spread = (*q3 - *q1) / *med;
}

/* Medians and quartiles of the wall, GPU and CPU times, the passes'
 * medians into rw (may be NULL); frees the samples. */
static timing acc_finish(timer_acc *a, row *rw) {
    timing out = { .frames = a->n };
    int n = a->n;
    quartiles(a->wall, n, &out.wall_ms, &out.wall_q1, &out.wall_q3, &out.wall_spread);
    quartiles(a->gpu, n, &out.gpu_ms, &out.gpu_q1, &out.gpu_q3, &out.gpu_spread);
    quartiles(a->cpu, n, &out.cpu_ms, &out.cpu_q1, &out.cpu_q3, &out.cpu_spread);
    out.first_wall_ms = NAN;
    if (rw && a->passes) {
        rw->npasses = a->ps.n;
        for (int k = 0; k < a->ps.n; k++) {
            memcpy(rw->pass_name[k], a->ps.name[k], GPU_TIMER_NAME);
            rw->pass_ms[k] = a->ps.count[k] ? bench_median(a->ps.ms[k], a->ps.count[k]) : NAN;
        }
    }
    for (int k = 0; k < a->ps.n; k++) free(a->ps.ms[k]);
    free(a->gpu);
    free(a->wall);
    free(a->cpu);
    memset(a, 0, sizeof *a);
    return out;
}

/* Untimed frames first (the first one's wall time returned). */
double bench_warm_up(bench *b, render *r, const render_target *tg, double t) {
    double first = NAN;
    for (int i = 0; i < b->o.warmup; i++) {
        double t0 = clock_now_s();
        render_frame(r, t, tg->fbo, tg->w, tg->h, NULL);
        glFinish();
        if (i == 0) first = (clock_now_s() - t0) * 1e3;
        render_gpu_ms(r, true);
    }
    return first;
}

/* Warm-up frames, then timed frames at the fixed time t, one after
 * another (the floor and the cost model; settings are timed round-robin). */
timing bench_time_frames(bench *b, render *r, const render_target *tg, double t, row *rw) {
    double first = bench_warm_up(b, r, tg, t);
    timer_acc a;
    bench_acc_init(&a, b->o.frames, rw != NULL);
    acc_frames(b, &a, r, tg, t, b->o.frames);
    timing out = acc_finish(&a, rw);
    out.first_wall_ms = first;
    return out;
}

/* One turn of a setting at time t: an untimed frame, then up to count
 * timed ones. The untimed frame takes the cost of coming back after the
 * other settings' turns (their textures and programs evicted this one's
 * from the caches): timed, it was half the frames at 2 a turn, and the
 * median fell between cold and warm frames (raymarch's CPU time at 96x54:
 * quartiles 30 and 55 ms about a median of 32). */
static void acc_turn(bench *b, timer_acc *a, render *r, const render_target *tg, double t, int count) {
    if (acc_done(b, a)) return;
    render_frame(r, t, tg->fbo, tg->w, tg->h, NULL);
    glFinish();
    render_gpu_ms(r, true);   /* its GPU time is not a timed frame's */
    acc_frames(b, a, r, tg, t, count);
}

/* Round-robin: every live setting and time in turn gets rr_chunk timed
 * frames (after an untimed one, acc_turn), turn after turn, until each has
 * its frames (or its budget): a load that comes and goes falls on every
 * setting alike, not on the ones that happened to run then. */
void bench_time_round_robin(bench *b, slot *sl, int n, double weight_each_time) {
    double t0 = clock_now_s(), base = b->pr.done;
    double total = weight_each_time * b->o.ntimes * n;
    for (bool more = true; more;) {
        more = false;
        for (int i = 0; i < n; i++) {
            if (!sl[i].live) continue;
            for (int ti = 0; ti < b->o.ntimes; ti++) {
                timer_acc *a = &sl[i].acc[ti];
                if (acc_done(b, a)) continue;
                acc_turn(b, a, sl[i].r, &sl[i].tg, b->o.times[ti], b->o.rr_chunk);
                more |= !acc_done(b, a);
            }
        }
        /* progress: the share of the budget spent, roughly */
        double spent = 0, want = 0;
        for (int i = 0; i < n; i++)
            for (int ti = 0; ti < b->o.ntimes && sl[i].live; ti++) {
                spent += sl[i].acc[ti].n >= sl[i].acc[ti].max ? b->o.frame_budget
                                                               : fmin(sl[i].acc[ti].spent, b->o.frame_budget);
                want += b->o.frame_budget;
            }
        bench_progress_set(&b->pr, base + (want > 0 ? total * spent / want : total), false, NULL);
    }
    for (int i = 0; i < n; i++) {
        if (!sl[i].live) continue;
        for (int ti = 0; ti < b->o.ntimes; ti++) {
            row *rw = &b->rows[sl[i].first_row + ti];
            timing tm = acc_finish(&sl[i].acc[ti], rw);
            rw->frames = tm.frames;
            rw->gpu_ms = tm.gpu_ms;
            rw->wall_ms = tm.wall_ms;
            rw->wall_spread = tm.wall_spread;
            rw->gpu_q1 = tm.gpu_q1;
            rw->gpu_q3 = tm.gpu_q3;
            rw->wall_q1 = tm.wall_q1;
            rw->wall_q3 = tm.wall_q3;
            rw->cpu_ms = tm.cpu_ms;
            rw->cpu_q1 = tm.cpu_q1;
            rw->cpu_q3 = tm.cpu_q3;
            rw->cpu_spread = tm.cpu_spread;
            rw->gpu_spread = tm.gpu_spread;
        }
    }
    bench_progress_set(&b->pr, base + total, false, NULL);
    b->seconds_timing += clock_now_s() - t0;
}

/* ---- the cost floor: a full-screen pass with one texture fetch ---- */

static const char *floor_glib =
    "##OpenGL GLIB\n"
    "# tarn bench's cost floor: one full-screen pass, one texture fetch a pixel.\n"
    "# Every pack's time is also given as a multiple of this one's.\n"
    "Ortho -1 1 -1 1\n"
    "Noise2D 64\n"
    "Vertex   floor.vert\n"
    "Fragment floor.frag\n"
    "Program  Floor  Noise2 2\n"
    "QuadXY 0 1 1 1\n";
static const char *floor_vert =
    "#version 330 compatibility\n"
    "out vec2 vUv;\n"
    "void main() {\n"
    "    vUv = gl_Vertex.xy * 0.5 + 0.5;\n"
    "    gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;\n"
    "}\n";
static const char *floor_frag =
    "#version 330 compatibility\n"
    "uniform sampler2D Noise2;\n"
    "in vec2 vUv;\n"
    "out vec4 fragColor;\n"
    "void main() { fragColor = vec4(texture(Noise2, vUv).rgb, 1.0); }\n";

bool bench_measure_floor(bench *b) {
    char dir[PATH_LEN], path[PATH_LEN + 32];
    snprintf(dir, sizeof dir, "%s/floor", b->o.out);
    if (!bench_mkdirs(dir)) return false;
    snprintf(path, sizeof path, "%s/floor.vert", dir);
    bool ok = bench_write_text(path, floor_vert);
    snprintf(path, sizeof path, "%s/floor.frag", dir);
    ok = ok && bench_write_text(path, floor_frag);
    snprintf(path, sizeof path, "%s/floor.glib", dir);
    ok = ok && bench_write_text(path, floor_glib);
    if (!ok) return false;
    render_desc rd = { .repo_root = b->root, .samples = b->o.samples };
    render *r = render_create(&rd);
    ok = render_load(r, path);
    if (!ok) fprintf(stderr, "%s", render_messages(r));
    render_target tg;
    if (ok && render_target_create(&tg, b->o.w, b->o.h, true)) {
        timing tm = bench_time_frames(b, r, &tg, 0.0, NULL);
        b->floor_gpu = tm.gpu_ms;
        b->floor_wall = tm.wall_ms;
        b->floor_cpu = tm.cpu_ms;
        render_target_destroy(&tg);
    } else {
        ok = false;
    }
    render_destroy(r);
    return ok;
}
