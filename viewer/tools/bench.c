/* bench: `tarn bench`, speed against error (see bench.h, docs/benchmark.md).
 * This file measures; bench_report.c writes the results. */
#include "util.h"
#include "bench_int.h"

#include <GL/gl.h>
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "exit_code.h"
#include "gl_ctx.h"
#include "image_io.h"
#include "plot.h"
#include "ref_flip.h"
#include "ref_metrics.h"
#include "ref_ssim.h"
#include "render.h"
#include "scene.h"
#include "file.h"
#include "mem.h"


/* the median of v (NAN when empty: "not measured") */
static double median(double *v, int n) { return n <= 0 ? NAN : median_double(v, (size_t)n); }

/* snprintf for paths: a path too long for its buffer is cut (and then
 * not found), never overflowed. */
static void fmt(char *out, size_t len, const char *f, ...) {
    va_list ap;
    va_start(ap, f);
    vsnprintf(out, len, f, ap);
    va_end(ap);
}

/* mkdir -p, quietly: a folder that cannot be made shows up as a file
 * that cannot be written, with its path. */
static bool mkdirs(const char *dir) { return file_mkdir_p(dir, NULL, 0); }

static bool is_file(const char *p) {
    struct stat st;
    return stat(p, &st) == 0 && S_ISREG(st.st_mode);
}

void bench_stem(const char *path, char *out, size_t len) {
    const char *b = strrchr(path, '/');
    b = b ? b + 1 : path;
    size_t n = strlen(b);
    if (n > 5 && strcmp(b + n - 5, ".glib") == 0) n -= 5;
    snprintf(out, len, "%.*s", (int)n, b);
}

bool bench_write_text(const char *path, const char *text) {
    FILE *f = fopen(path, "w");
    if (!f) return false;
    fputs(text, f);
    return fclose(f) == 0;
}

#define stem bench_stem
#define write_text bench_write_text

const char *bench_setting_name(const bench *b, int pack, int setting) { return b->pb[pack].settings[setting].name; }

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

/* /proc/loadavg's three figures (NaN where it cannot be read) */
static void loadavg(double out[3]) {
    out[0] = out[1] = out[2] = NAN;
    FILE *f = fopen("/proc/loadavg", "r");
    if (!f) return;
    if (fscanf(f, "%lf %lf %lf", &out[0], &out[1], &out[2]) != 3) out[0] = out[1] = out[2] = NAN;
    fclose(f);
}

/* ---- the progress bar ---- */

static void fmt_dur(double s, char *buf, size_t n) {
    if (s < 60) snprintf(buf, n, "%.0f s", s);
    else snprintf(buf, n, "%d:%02d", (int)(s / 60), (int)fmod(s, 60));
}

static void progress_draw(progress *p, bool force) {
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

static void progress_set(progress *p, double done, bool force, const char *fmt, ...) {
    p->done = done;
    if (fmt) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(p->what, sizeof p->what, fmt, ap);
        va_end(ap);
    }
    progress_draw(p, force);
}

typedef struct ref_progress_ctx { progress *p; double base, weight; } ref_progress_ctx;

static void on_ref_progress(void *user, double f) {
    ref_progress_ctx *c = user;
    c->p->done = c->base + f * c->weight;
    progress_draw(c->p, false);
}

/* ---- the machine ---- */

static void machine(bench *b) {
    snprintf(b->cpu, sizeof b->cpu, "unknown CPU");
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (f) {
        char line[512];
        while (fgets(line, sizeof line, f)) {
            if (strncmp(line, "model name", 10) != 0) continue;
            char *colon = strchr(line, ':');
            if (!colon) continue;
            colon++;
            while (*colon == ' ') colon++;
            colon[strcspn(colon, "\n")] = '\0';
            snprintf(b->cpu, sizeof b->cpu, "%s", colon);
            break;
        }
        fclose(f);
    }
    b->cores = (int)sysconf(_SC_NPROCESSORS_ONLN);
    const char *r = (const char *)glGetString(GL_RENDERER), *v = (const char *)glGetString(GL_VERSION);
    snprintf(b->gl_renderer, sizeof b->gl_renderer, "%s", r ? r : "?");
    snprintf(b->gl_version, sizeof b->gl_version, "%s", v ? v : "?");
    b->cpu_raster = strstr(b->gl_renderer, "llvmpipe") || strstr(b->gl_renderer, "softpipe") ||
                    strstr(b->gl_renderer, "SwiftShader") || strstr(b->gl_renderer, "lavapipe");
    b->axis = b->o.time_axis ? b->o.time_axis : b->cpu_raster ? BENCH_AXIS_CPU : BENCH_AXIS_GPU;
    time_t now = time(NULL);
    struct tm tmv;
    gmtime_r(&now, &tmv);
    strftime(b->started, sizeof b->started, "%Y-%m-%d %H:%M UTC", &tmv);
}

/* ---- the desc, resolved ---- */

/* A desc the run cannot use (no such scene or pack): the reason in why,
 * for the command line to show with its usage. */
static int unusable(char *why, size_t whylen, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, whylen, fmt, ap);
    va_end(ap);
    return TARN_EXIT_USAGE;
}

/* The defaults, in one place (zero in the desc means these). */
static void fill_opts(bench_opts *o, const bench_desc *d) {
    for (int i = 0; i < d->nscenes && i < MAX_SCENES; i++) o->scenes[o->nscenes++] = d->scenes[i];
    o->w = d->width > 0 ? d->width : 480;
    o->h = d->height > 0 ? d->height : 270;
    if (d->ntimes > 0) {
        for (int i = 0; i < d->ntimes && i < MAX_TIMES; i++) o->times[o->ntimes++] = d->times[i];
    } else {
        o->times[0] = 1.0;
        o->times[1] = 4.0;
        o->ntimes = 2;
    }
    o->frames = d->frames > 0 ? d->frames : 30;
    o->warmup = d->warmup_set ? d->warmup : 1;
    o->frame_budget = d->frame_budget_set ? d->frame_budget : 1.5;
    o->out = d->out ? d->out : "out/bench";
    o->docs = d->docs;
    o->time_axis = d->time_axis;
    o->ref = d->ref;
    o->samples = d->samples;
    o->heat_max = d->heat_max > 0 ? d->heat_max : 0.25;
    o->images = !d->no_images;
    o->cost_model = !d->no_cost_model;
    o->uncertainty = !d->no_uncertainty;
    o->seq_frames = d->no_sequence ? 0 : d->seq_frames > 0 ? d->seq_frames : 8;
    if (o->seq_frames == 1) o->seq_frames = 2;   /* a change needs two frames */
    o->seq_fps = d->seq_fps > 0 ? d->seq_fps : 30;
    o->seq_w = d->seq_width > 0 ? d->seq_width : o->w / 2 < 32 ? 32 : o->w / 2;
    o->seq_h = d->seq_height > 0 ? d->seq_height : o->h / 2 < 18 ? 18 : o->h / 2;
    o->rr_chunk = d->rr_chunk > 0 ? d->rr_chunk : 2;
    o->quiet = d->quiet;
    ref_render_desc rd = ref_render_resolve(&(ref_render_desc){ .caustic_res = d->ref.caustic_res,
                                                                 .photons_per_cell = d->ref.photons_per_cell });
    o->ref_photons = rd.photons_per_cell;
    o->ref_caustic_res = rd.caustic_res;
}

/* The reference is subsampled as the frames are multisampled, at the
 * positions the GL samples (unless --ref-spp asks for a grid), so
 * anti-aliased edges meet edges anti-aliased alike and the error stays
 * comparable (needs the GL context). */
static void match_reference(bench_opts *o) {
    o->samples_used = render_samples_on_this_gl(o->samples);
    o->spp_matched = o->ref.spp <= 0;
    if (o->spp_matched) refcache_match_msaa(&o->ref, o->samples_used);
    else o->ref.nsamples = 0;   /* --ref-spp: the ordered grid */
}

/* Where the references are cached: --ref-cache, else $XDG_CACHE_HOME/tarn/ref
 * (shared by every output folder: the same frame is the same reference),
 * else, with no home to cache in, the output folder's ref/. */
static void ref_cache_dir(bench *b, const bench_desc *d) {
    char cache[PATH_LEN - 8];
    if (d->ref_cache) snprintf(b->ref_dir, sizeof b->ref_dir, "%s", d->ref_cache);
    else if (tarn_cache_dir(cache, sizeof cache)) snprintf(b->ref_dir, sizeof b->ref_dir, "%s/ref", cache);
    else snprintf(b->ref_dir, sizeof b->ref_dir, "%s/ref", b->o.out);
}

static int resolve(bench *b, const bench_desc *d, char *why, size_t whylen) {
    bench_opts *o = &b->o;
    fill_opts(o, d);
    ref_cache_dir(b, d);
    if (d->root && !realpath(d->root, b->root)) return unusable(why, whylen, "--root: no directory '%s'", d->root);
    if (!o->nscenes) {
        /* the lake, the pool, whose tiled floor turns an error in the
         * refraction hit into a colour error (the lake's floor hides it),
         * and the open sea */
        static char lake[4096], pool[4096], ocean[4096];
        snprintf(lake, sizeof lake, "%s/scenes/lake.glib", tarn_root());
        snprintf(pool, sizeof pool, "%s/scenes/pool.glib", tarn_root());
        snprintf(ocean, sizeof ocean, "%s/scenes/ocean.glib", tarn_root());
        o->scenes[o->nscenes++] = lake;
        o->scenes[o->nscenes++] = pool;
        o->scenes[o->nscenes++] = ocean;   /* open sea: the spectrum ocean to the horizon */
    }
    for (int s = 0; s < o->nscenes; s++) {
        char alt[PATH_LEN];
        const char *p = o->scenes[s];
        if (!is_file(p)) {
            fmt(alt, sizeof alt, "%s/%s", b->root, p);
            if (!is_file(alt)) return unusable(why, whylen, "no scene '%s'", p);
            p = alt;
        }
        if (!realpath(p, b->scene_abs[s])) return unusable(why, whylen, "cannot resolve '%s'", p);
    }
    packset_name all[PACKSET_MAX];
    int nall = packset_list(b->root, all, PACKSET_MAX);
    char list[PACKSET_MAX * PACKSET_NAME_MAX] = "";
    for (int i = 0; i < nall; i++) {
        strcat(list, i ? ", " : "");
        strcat(list, all[i]);
    }
    for (int i = 0; i < d->npacks; i++) {
        const char *p = d->packs[i];
        if (!packset_exists(b->root, p))
            return unusable(why, whylen, "no pack '%s' (no %s/packs/%s/pack.glib); the packs are: %s", p, b->root,
                            p, nall ? list : "none");
        if (o->npacks >= PACKSET_MAX) return unusable(why, whylen, "at most %d packs", PACKSET_MAX);
        snprintf(o->packs[o->npacks++], PACKSET_NAME_MAX, "%s", p);
    }
    if (!d->npacks)
        for (int i = 0; i < nall; i++) memcpy(o->packs[o->npacks++], all[i], sizeof all[i]);
    if (!o->npacks) return unusable(why, whylen, "no packs in %s/packs", b->root);
    return 0;
}

/* ---- references ---- */

static const char *wrapper_path(bench *b, int s, int p, int k, char *out, size_t len) {
    const packset_setting *st = &b->pb[p].settings[k];
    char lines[4096];
    if (packset_scene_lines(st, lines, sizeof lines) == 0) return b->scene_abs[s];
    char sc[256];
    stem(b->scene_abs[s], sc, sizeof sc);
    snprintf(out, len, "%s/scenes/%s.%s.%s.glib", b->o.out, sc, b->o.packs[p], st->name);
    return out;
}

static ref_entry *find_ref(bench *b, uint64_t key) {
    for (int i = 0; i < b->nrefs; i++)
        if (b->refs[i].key == key) return &b->refs[i];
    return NULL;
}

/* The reference's options for each kind of reference (REFK_*). The noise
 * reference is the run's with another photon seed: the same strata, grid
 * and count, other random numbers, so it differs from the run's by photon
 * noise alone; the grid reference halves the caustic cells, photons a cell
 * as the run's. */
static refcache_opts ref_opts(const bench *b, int kind) {
    refcache_opts o = b->o.ref;
    if (kind == REFK_NOISE) {
        o.seed = b->o.ref.seed + 1;
    } else if (kind == REFK_GRID) {
        o.caustic_res = 2 * b->o.ref_caustic_res;
        o.photons_per_cell = b->o.ref_photons;
    } else if (kind == REFK_FLAT) {
        o.flat_caustics = true;
    }
    return o;
}

/* Progress weights, roughly seconds on the 2-core machine: a load, and a
 * reference (photons: 35 s for the default 256-cell grid of 36 photons a
 * cell; pixels: 5 s for 480x270 at 1 sample). */
static const double LOAD_WEIGHT = 3;

static double ref_weight(const bench *b, const refcache_opts *o, int w, int h) {
    ref_render_desc d = ref_render_resolve(&(ref_render_desc){ .caustic_res = o->caustic_res,
                                                                .photons_per_cell = o->photons_per_cell,
                                                                .spp = o->spp });
    double cr = d.caustic_res / 256.0, rays = o->nsamples > 0 ? o->nsamples : d.spp * d.spp;
    double photons = o->flat_caustics ? 0 : 35 * cr * cr * d.photons_per_cell / 36.0;
    (void)b;
    return photons + 5.0 * w * h / (480.0 * 270.0) * rays;
}

/* A reference the run will need, registered for the progress bar's total
 * (it is rendered or read on first use, get_ref). */
static void want_ref(bench *b, int s, const char *scene, int kind, int w, int h, double t) {
    refcache_opts o = ref_opts(b, kind);
    uint64_t key;
    char err[2048] = "";
    if (!refcache_key(scene, w, h, t, &o, &key, err, sizeof err) || find_ref(b, key)) return;
    char named[PATH_LEN], sc[256];
    stem(b->scene_abs[s], sc, sizeof sc);
    fmt(named, sizeof named, "%s/%s.glib", b->ref_dir, sc);
    bool cached = refcache_cached(b->ref_dir, scene, named, w, h, t, &o);
    b->refs = mem_realloc(b->refs, (size_t)(b->nrefs + 1) * sizeof *b->refs);
    ref_entry *e = &b->refs[b->nrefs++];
    memset(e, 0, sizeof *e);
    e->key = key;
    e->kind = kind;
    e->weight = cached ? 0.2 : ref_weight(b, &o, w, h);
}

static double seq_time(const bench *b, int i) { return b->o.times[0] + i / b->o.seq_fps; }

/* Keys of every reference the run needs; renders or reads each once. */
static void prepare_refs(bench *b) {
    for (int s = 0; s < b->o.nscenes; s++)
        for (int p = 0; p < b->o.npacks; p++)
            for (int k = 0; k < b->pb[p].n; k++) {
                char wp[PATH_LEN], err[2048] = "";
                const char *scene = wrapper_path(b, s, p, k, wp, sizeof wp);
                if (scene != b->scene_abs[s] && !packset_write_wrapper(&b->pb[p].settings[k], b->scene_abs[s], scene,
                                                                        err, sizeof err))
                    continue;
                for (int ti = 0; ti < b->o.ntimes; ti++) {
                    want_ref(b, s, scene, REFK_MAIN, b->o.w, b->o.h, b->o.times[ti]);
                    want_ref(b, s, scene, REFK_FLAT, b->o.w, b->o.h, b->o.times[ti]);
                }
                if (b->o.uncertainty) {
                    want_ref(b, s, scene, REFK_NOISE, b->o.w, b->o.h, b->o.times[0]);
                    want_ref(b, s, scene, REFK_GRID, b->o.w, b->o.h, b->o.times[0]);
                }
                for (int i = 0; i < b->o.seq_frames; i++)
                    want_ref(b, s, scene, REFK_SEQ, b->o.seq_w, b->o.seq_h, seq_time(b, i));
            }
}

static double ref_total_weight(bench *b) {
    double w = 0;
    for (int i = 0; i < b->nrefs; i++) w += b->refs[i].weight;
    return w;
}

/* A reference of the scene (a setting's wrapper) of the given kind, size
 * and time, rendered (or read from the cache) on first use. */
static ref_entry *get_ref_at(bench *b, int s, const char *scene, int kind, int w, int h, double t) {
    refcache_opts o = ref_opts(b, kind);
    uint64_t key;
    char err[2048] = "";
    if (!refcache_key(scene, w, h, t, &o, &key, err, sizeof err)) return NULL;
    ref_entry *e = find_ref(b, key);
    if (!e) {   /* not foreseen: add it */
        want_ref(b, s, scene, kind, w, h, t);
        if (!(e = find_ref(b, key))) return NULL;
    }
    if (e->tried) return e->ok ? e : NULL;
    e->tried = true;
    const char *dir = b->ref_dir;
    char sc[256];
    stem(b->scene_abs[s], sc, sizeof sc);
    static const char *const what[REFK_COUNT] = { "reference", "sequence reference", "noise reference",
                                                  "grid reference", "flat-lighting reference" };
    ref_progress_ctx pc = { &b->pr, b->pr.done, e->weight };
    progress_set(&b->pr, b->pr.done, true, "%s %s t=%g", what[kind], sc, t);
    /* the stem names the scene, not the wrapper: settings that share a world share the file */
    char named[PATH_LEN];
    fmt(named, sizeof named, "%s/%s.glib", dir, sc);
    e->ok = refcache_get(dir, scene, named, w, h, t, NULL, &o, on_ref_progress, &pc, &e->im, err, sizeof err);
    progress_set(&b->pr, pc.base + e->weight, true, NULL);
    if (e->ok) {
        bool main = e->kind == REFK_MAIN;
        if (e->im.from_cache) main ? b->refs_cached++ : b->extra_cached[e->kind]++;
        else main ? b->refs_rendered++ : b->extra_rendered[e->kind]++;
    }
    if (!e->ok) {
        fprintf(stderr, "%starn bench: %s\n", b->pr.tty ? "\n" : "", err);
        b->failures++;
        return NULL;
    }
    return e;
}

static ref_entry *get_ref(bench *b, int s, const char *scene, int ti) {
    return get_ref_at(b, s, scene, REFK_MAIN, b->o.w, b->o.h, b->o.times[ti]);
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

typedef struct timing {
    double gpu_ms, wall_ms, first_wall_ms, wall_spread, gpu_q1, gpu_q3, wall_q1, wall_q3;
    double cpu_ms, cpu_q1, cpu_q3, cpu_spread, gpu_spread;
    int frames;
} timing;

/* A timing's time on the run's axis */
static double axis_ms(const bench *b, const timing *t) {
    return b->axis == BENCH_AXIS_GPU ? t->gpu_ms : b->axis == BENCH_AXIS_CPU ? t->cpu_ms : t->wall_ms;
}

/* Collects this frame's GPU time per pass into per-name sample lists. */
typedef struct pass_samples {
    int n;
    char name[GPU_TIMER_MARKS][GPU_TIMER_NAME];
    double *ms[GPU_TIMER_MARKS];
    int count[GPU_TIMER_MARKS];
} pass_samples;

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

/* The timed frames of one setting at one time, gathered over its turns
 * (round-robin: a few frames a turn, bench_time_round). */
typedef struct timer_acc {
    int max, n;
    double spent;                /* seconds of timed frames so far */
    double *gpu, *wall, *cpu;
    bool passes;
    pass_samples ps;
} timer_acc;

static void acc_init(timer_acc *a, int max, bool passes) {
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
            rw->pass_ms[k] = a->ps.count[k] ? median(a->ps.ms[k], a->ps.count[k]) : NAN;
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
static double warm_up(bench *b, render *r, const render_target *tg, double t) {
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
static timing time_frames(bench *b, render *r, const render_target *tg, double t, row *rw) {
    double first = warm_up(b, r, tg, t);
    timer_acc a;
    acc_init(&a, b->o.frames, rw != NULL);
    acc_frames(b, &a, r, tg, t, b->o.frames);
    timing out = acc_finish(&a, rw);
    out.first_wall_ms = first;
    return out;
}

static bool measure_floor(bench *b) {
    char dir[PATH_LEN], path[PATH_LEN + 32];
    snprintf(dir, sizeof dir, "%s/floor", b->o.out);
    if (!mkdirs(dir)) return false;
    snprintf(path, sizeof path, "%s/floor.vert", dir);
    bool ok = write_text(path, floor_vert);
    snprintf(path, sizeof path, "%s/floor.frag", dir);
    ok = ok && write_text(path, floor_frag);
    snprintf(path, sizeof path, "%s/floor.glib", dir);
    ok = ok && write_text(path, floor_glib);
    if (!ok) return false;
    render_desc rd = { .repo_root = b->root, .samples = b->o.samples };
    render *r = render_create(&rd);
    ok = render_load(r, path);
    if (!ok) fprintf(stderr, "%s", render_messages(r));
    render_target tg;
    if (ok && render_target_create(&tg, b->o.w, b->o.h, true)) {
        timing tm = time_frames(b, r, &tg, 0.0, NULL);
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

/* ---- one setting ---- */

static unif_entry *find_output_define(render *r, unif_set **owner) {
    int n;
    unif_set *sets = render_uniforms(r, &n);
    for (int i = 0; i < n; i++) {
        unif_entry *e = unif_find(&sets[i], BENCH_OUTPUT_DEFINE);
        if (e && e->is_define) {
            if (owner) *owner = &sets[i];
            return e;
        }
    }
    return NULL;
}

/* Sets TARN_OUTPUT in every Program that has it; true when any has it. */
static bool set_output(render *r, int mode) {
    int n;
    bool any = false;
    unif_set *sets = render_uniforms(r, &n);
    for (int i = 0; i < n; i++) {
        unif_entry *e = unif_find(&sets[i], BENCH_OUTPUT_DEFINE);
        if (!e || !e->is_define) continue;
        unif_set_component(e, 0, mode);
        any = true;
    }
    if (any) render_rebuild_programs(r);
    return any;
}

static void write_images(bench *b, const row *rw, const float *rgba, const ref_entry *ref) {
    char dir[PATH_LEN], path[PATH_LEN + 256], sc[256], err[512];
    snprintf(dir, sizeof dir, "%s/img", b->o.out);
    if (!mkdirs(dir)) return;
    stem(b->scene_abs[rw->scene], sc, sizeof sc);
    int w = b->o.w, h = b->o.h;
    img im;
    if (!img_alloc(&im, w, h, 3)) return;
    for (long i = 0; i < (long)w * h; i++)
        for (int k = 0; k < 3; k++) {
            float v = rgba[i * 4 + k];
            im.px[i * 3 + k] = !(v > 0) ? 0.0f : v >= 1 ? 1.0f : (float)ref_linear_to_srgb(v);
        }
    fmt(path, sizeof path, "%s/%s.%s.%s.t%g.png", dir, sc, b->o.packs[rw->pack],
             b->pb[rw->pack].settings[rw->setting].name, b->o.times[rw->ti]);
    img_write(path, &im, err, sizeof err);
    if (ref) {
        float *field = mem_alloc((size_t)w * h * sizeof *field);
        ref_fimage A = { rgba, w, h, 4 }, B = { ref->im.color, w, h, 3 };
        if (ref_metrics_error_field(&A, &B, REF_ERR_COLOR, NULL, field, err, sizeof err)) {
            ref_heatmap(field, w, h, b->o.heat_max, im.px);
            fmt(path, sizeof path, "%s/%s.%s.%s.t%g.heat.png", dir, sc, b->o.packs[rw->pack],
                     b->pb[rw->pack].settings[rw->setting].name, b->o.times[rw->ti]);
            img_write(path, &im, err, sizeof err);
        }
        free(field);
    }
    img_free(&im);
}

/* The colour error over the reference's water pixels and over the rest:
 * what the bench ranks by (the water technique), and what tells whether
 * the world around it agrees (it should, nearly: one world on both sides). */
static void measure_water(bench *b, row *rw, const ref_fimage *A, const ref_fimage *B, const float *classes) {
    long n = (long)b->o.w * b->o.h;
    unsigned char *m = mem_alloc((size_t)n);
    char err[256];
    ref_image_metrics r;
    for (int water = 1; water >= 0; water--) {
        ref_mask_water(classes, n, water, NULL, m);
        ref_metrics_desc d = { .mask = m };
        if (!ref_metrics_image(A, B, &d, &r, err, sizeof err) || r.count.compared == 0) continue;
        if (water) {
            rw->water_rmse = r.rmse;
            rw->water_psnr = r.psnr_db;
            rw->water_px = r.count.compared;
        } else {
            rw->off_rmse = r.rmse;
        }
    }
    free(m);
}

/* A buffer the pack wrote (TARN_OUTPUT = mode) against the reference's, over
 * the pixels where the reference sees water first. */
static void compare_buffer(bench *b, row *rw, int mode, const float *rgba, const ref_entry *ref) {
    int w = b->o.w, h = b->o.h;
    long n = (long)w * h;
    unsigned char *mask = mem_alloc((size_t)n);
    for (long i = 0; i < n; i++) mask[i] = ref->im.mask[i] == REF_MASK_WATER;
    ref_metrics_desc d = { .mask = mask };
    ref_fimage A = { rgba, w, h, 4 };
    char err[256];
    if (mode == REF_OUTPUT_REFRACT_HIT) {
        /* a truncated march is never silent: the contract's alpha of the
         * refraction-hit buffer is BENCH_MARCH_CAPPED where it ran out */
        long water = 0, capped = 0;
        for (long i = 0; i < n; i++)
            if (mask[i]) { water++; capped += rgba[i * 4 + 3] == BENCH_MARCH_CAPPED; }
        rw->capped_share = water ? (double)capped / (double)water : NAN;
        ref_fimage B = { ref->im.refract_hit, w, h, 4 };
        ref_fimage A3 = A;
        ref_point_metrics m;
        /* the pack's alpha is not a flag: compare xyz only */
        float *xyz = mem_alloc((size_t)n * 3 * sizeof *xyz);
        float *bxyz = mem_alloc((size_t)n * 3 * sizeof *bxyz);
        for (long i = 0; i < n; i++)
            for (int k = 0; k < 3; k++) {
                xyz[i * 3 + k] = rgba[i * 4 + k];
                bxyz[i * 3 + k] = ref->im.refract_hit[i * 4 + k];
            }
        A3 = (ref_fimage){ xyz, w, h, 3 };
        B = (ref_fimage){ bxyz, w, h, 3 };
        if (ref_metrics_points(&A3, &B, &d, &m, err, sizeof err)) {
            rw->has[mode] = true;
            rw->comp_median[mode] = m.world.median;
            rw->comp_p95[mode] = m.world.p95;
            rw->comp_mean[mode] = m.world.mean;
            rw->comp_rel_mean[mode] = NAN;
            rw->comp_rel_median[mode] = NAN;
        }
        free(xyz);
        free(bxyz);
    } else {
        const float *src = mode == REF_OUTPUT_FRESNEL ? ref->im.fresnel
                           : mode == REF_OUTPUT_IRRADIANCE ? ref->im.irradiance : ref->im.depth;
        int ch = mode == REF_OUTPUT_IRRADIANCE ? 3 : 1;
        /* the pack's side: R (or RGB) of its output */
        float *a = mem_alloc((size_t)n * ch * sizeof *a);
        for (long i = 0; i < n; i++)
            for (int k = 0; k < ch; k++) a[i * ch + k] = rgba[i * 4 + k];
        ref_fimage A1 = { a, w, h, ch }, B = { src, w, h, ch };
        ref_scalar_metrics m;
        if (ref_metrics_scalar(&A1, &B, &d, &m, err, sizeof err)) {
            rw->has[mode] = true;
            rw->comp_median[mode] = m.abs.median;
            rw->comp_p95[mode] = m.abs.p95;
            rw->comp_mean[mode] = m.abs.mean;
            rw->comp_rel_mean[mode] = m.rel.mean;
            rw->comp_rel_median[mode] = m.rel.median;
        }
        free(a);
    }
    free(mask);
}

/* Every entry's values, to return to between buffers. */
static float *snapshot(render *r, bool restore, float *snap) {
    int n;
    unif_set *sets = render_uniforms(r, &n);
    size_t total = 0;
    for (int i = 0; i < n; i++) total += (size_t)sets[i].n;
    if (!restore) snap = mem_alloc((total ? total : 1) * UNIF_MAX_COMPONENTS * sizeof *snap);
    size_t k = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < sets[i].n; j++, k++) {
            float *v = sets[i].entries[j].value, *sv = snap + k * UNIF_MAX_COMPONENTS;
            memcpy(restore ? v : sv, restore ? sv : v, UNIF_MAX_COMPONENTS * sizeof *v);
        }
    return snap;
}

static void measure_buffers(bench *b, render *r, const render_target *tg, int s, int p, const char *scene,
                            int first_row, float *rgba) {
    const packset_bench *pb = &b->pb[p];
    unif_entry *out_def = find_output_define(r, NULL);
    float *snap = NULL;
    char sc[256];
    stem(b->scene_abs[s], sc, sizeof sc);
    for (int mode = 1; mode < REF_OUTPUT_COUNT; mode++) {
        const packset_buffer *spec = NULL;
        for (int i = 0; i < pb->nbuffers; i++)
            if (strcmp(pb->buffers[i].name, ref_buffer_for_output(mode)->name) == 0) spec = &pb->buffers[i];
        bool via_define = !spec && out_def && out_def->min <= mode && out_def->max >= mode;
        if (!spec && !via_define) continue;
        if (!snap) snap = snapshot(r, false, NULL);
        else snapshot(r, true, snap);
        progress_set(&b->pr, b->pr.done, true, "%s %s: buffer %s", sc, b->o.packs[p], ref_buffer_for_output(mode)->name);
        if (spec) {
            int n;
            unif_set *sets = render_uniforms(r, &n);
            char err[1024] = "";
            bool changed;
            if (!packset_apply(sets, n, &spec->how, &changed, err, sizeof err))
                fprintf(stderr, "%starn bench: %s: buffer %s: %s", b->pr.tty ? "\n" : "", pb->path, spec->name, err);
            render_rebuild_programs(r);
        } else {
            set_output(r, mode);
        }
        /* a buffer's pixel is the pixel centre's, as the reference's: a
         * resolve would average hit points across an edge */
        render_set_samples(r, 1);
        for (int ti = 0; ti < b->o.ntimes; ti++) {
            ref_entry *ref = get_ref(b, s, scene, ti);
            if (!ref) continue;
            render_frame(r, b->o.times[ti], tg->fbo, tg->w, tg->h, NULL);
            render_target_read(tg, rgba);
            compare_buffer(b, &b->rows[first_row + ti], mode, rgba, ref);
        }
        render_set_samples(r, b->o.samples);
    }
    free(snap);
}

static void first_line(const char *text, char *out, size_t len) {
    size_t n = strcspn(text, "\n");
    snprintf(out, len, "%.*s", (int)n, text);
}

/* ---- FLIP, in parallel: HDR-FLIP costs about 1 s a 480x270 frame on one
 * core, and the GL is idle while it runs ---- */

typedef struct flip_job {
    const float *test;           /* 4 channels (RGBA) */
    const float *ref;            /* 3 */
    const float *classes;        /* the reference's REF_MASK_* */
    int w, h;
    double water, frame;         /* out: the mean over water, over the frame (NaN: failed) */
} flip_job;

typedef struct flip_queue {
    flip_job *jobs;
    int n, next;
    pthread_mutex_t mu;
} flip_queue;

/* One map, pooled per region (ref_flip_map once, ref_flip_pool per mask). */
static void flip_job_run(flip_job *j) {
    long n = (long)j->w * j->h;
    j->water = j->frame = NAN;
    float *map = mem_alloc((size_t)n * sizeof *map);
    unsigned char *m = mem_alloc((size_t)n);
    ref_fimage A = { j->test, j->w, j->h, 4 }, B = { j->ref, j->w, j->h, 3 };
    ref_flip_desc d = { .hdr = true };
    ref_flip_result info;
    char err[256];
    if (ref_flip_map(&A, &B, &d, map, NULL, &info, err, sizeof err)) {
        ref_flip_result r = info;
        ref_mask_water(j->classes, n, 1, NULL, m);
        ref_flip_pool(map, j->w, j->h, m, &r);
        j->water = r.mean;
        ref_flip_pool(map, j->w, j->h, NULL, &r);
        j->frame = r.mean;
    }
    free(m);
    free(map);
}

static void *flip_worker(void *arg) {
    flip_queue *q = arg;
    for (;;) {
        pthread_mutex_lock(&q->mu);
        int i = q->next++;
        pthread_mutex_unlock(&q->mu);
        if (i >= q->n) return NULL;
        flip_job_run(&q->jobs[i]);
    }
}

static void run_flip_jobs(bench *b, flip_job *jobs, int n) {
    if (n <= 0) return;
    double t0 = clock_now_s();
    flip_queue q = { .jobs = jobs, .n = n };
    pthread_mutex_init(&q.mu, NULL);
    int nt = b->cores > 1 ? b->cores : 1;
    if (nt > n) nt = n;
    pthread_t th[64];
    int started = 0;
    for (int i = 1; i < nt && i < 64; i++)
        if (pthread_create(&th[started], NULL, flip_worker, &q) == 0) started++;
    flip_worker(&q);
    for (int i = 0; i < started; i++) pthread_join(th[i], NULL);
    pthread_mutex_destroy(&q.mu);
    b->seconds_flip += clock_now_s() - t0;
}

/* SSIM over the reference's water (the luminance plane, ref_ssim.h) */
static double water_ssim(const float *rgba, const refcache_image *ref, int w, int h) {
    long n = (long)w * h;
    unsigned char *m = mem_alloc((size_t)n);
    ref_mask_water(ref->mask, n, 1, NULL, m);
    ref_fimage A = { rgba, w, h, 4 }, B = { ref->color, w, h, 3 };
    ref_ssim_desc d = { .mask = m };
    ref_ssim_result r;
    char err[256];
    double v = ref_ssim(&A, &B, &d, NULL, &r, err, sizeof err) ? r.mean : NAN;
    free(m);
    return v;
}

/* The water RMSE of a frame against a reference (NaN: none compared) */
static double water_rmse_of(const float *rgba, const refcache_image *ref, int w, int h) {
    long n = (long)w * h;
    unsigned char *m = mem_alloc((size_t)n);
    ref_mask_water(ref->mask, n, 1, NULL, m);
    ref_fimage A = { rgba, w, h, 4 }, B = { ref->color, w, h, 3 };
    ref_metrics_desc d = { .mask = m };
    ref_image_metrics r;
    char err[256];
    double v = ref_metrics_image(&A, &B, &d, &r, err, sizeof err) && r.count.compared ? r.rmse : NAN;
    free(m);
    return v;
}

/* Irradiance where the pack shows none: it lights the floor as the world
 * does, by the sun through the flat mean surface (world.glsl's
 * worldSunBelow, the reference's ref_render_flat_sun), so its irradiance
 * at the reference's hit points is the flat-caustics reference's. */
static void measure_flat_irradiance(bench *b, row *rw, const ref_entry *flat, const ref_entry *ref) {
    int w = b->o.w, h = b->o.h;
    long n = (long)w * h;
    unsigned char *mask = mem_alloc((size_t)n);
    for (long i = 0; i < n; i++) mask[i] = ref->im.mask[i] == REF_MASK_WATER;
    ref_metrics_desc d = { .mask = mask };
    ref_fimage A = { flat->im.irradiance, w, h, 3 }, B = { ref->im.irradiance, w, h, 3 };
    ref_scalar_metrics m;
    char err[256];
    int mode = REF_OUTPUT_IRRADIANCE;
    if (ref_metrics_scalar(&A, &B, &d, &m, err, sizeof err)) {
        rw->has[mode] = true;
        rw->irr_flat = true;
        rw->comp_median[mode] = m.abs.median;
        rw->comp_p95[mode] = m.abs.p95;
        rw->comp_mean[mode] = m.abs.mean;
        rw->comp_rel_mean[mode] = m.rel.mean;
        rw->comp_rel_median[mode] = m.rel.median;
    }
    free(mask);
}

/* ---- one setting, kept alive while its scene is timed ---- */

typedef struct slot {
    int s, p, k;
    char wp[PATH_LEN];
    const char *scene;           /* the scene or its wrapper (wp) */
    render *r;
    render_target tg;
    bool live;
    int first_row;
    timer_acc acc[MAX_TIMES];
} slot;

/* Its rows, then loaded and warmed up; false (rows failed) when it cannot be */
static bool slot_open(bench *b, slot *sl, int s, int p, int k) {
    const packset_setting *st = &b->pb[p].settings[k];
    char sc[256];
    memset(sl, 0, sizeof *sl);
    sl->s = s;
    sl->p = p;
    sl->k = k;
    sl->scene = wrapper_path(b, s, p, k, sl->wp, sizeof sl->wp);
    stem(b->scene_abs[s], sc, sizeof sc);
    sl->first_row = b->nrows;
    b->rows = mem_realloc(b->rows, (size_t)(b->nrows + b->o.ntimes) * sizeof *b->rows);
    for (int ti = 0; ti < b->o.ntimes; ti++) {
        row *rw = &b->rows[b->nrows++];
        memset(rw, 0, sizeof *rw);
        rw->scene = s;
        rw->pack = p;
        rw->setting = k;
        rw->ti = ti;
        rw->gpu_ms = rw->wall_ms = rw->first_wall_ms = rw->rmse = rw->psnr = rw->mae = NAN;
        rw->water_rmse = rw->water_psnr = rw->off_rmse = rw->wall_spread = rw->capped_share = NAN;
        rw->p95 = rw->p99 = rw->max_abs = rw->over_share = NAN;
        rw->gpu_q1 = rw->gpu_q3 = rw->wall_q1 = rw->wall_q3 = NAN;
        rw->cpu_ms = rw->cpu_q1 = rw->cpu_q3 = rw->cpu_spread = rw->gpu_spread = NAN;
        rw->water_flip = rw->flip = rw->water_ssim = NAN;
        rw->u_noise_rmse = rw->u_grid_rmse = rw->u_noise_flip = rw->u_grid_flip = NAN;
        rw->seq_water_rmse = rw->seq_water_ssim = rw->temporal_rmse = rw->seq_ref_change = rw->seq_pack_change = NAN;
    }
    progress_set(&b->pr, b->pr.done, true, "%s %s %s: loading", sc, b->o.packs[p], st->name);
    /* no spray: the reference draws none (docs/waves.md), so it is no part of a pack's error or time */
    render_desc rd = { .repo_root = b->root, .pack = b->o.packs[p], .samples = b->o.samples, .no_spray = true };
    sl->r = render_create(&rd);
    bool loaded = render_load(sl->r, sl->scene);
    char err[4096] = "";
    bool defines_changed = false;
    if (loaded) {
        int n;
        unif_set *sets = render_uniforms(sl->r, &n);
        if (!packset_apply(sets, n, st, &defines_changed, err, sizeof err))
            for (int ti = 0; ti < b->o.ntimes; ti++)
                first_line(err, b->rows[sl->first_row + ti].note, sizeof b->rows[sl->first_row + ti].note);
        if (defines_changed && !render_rebuild_programs(sl->r)) loaded = false;
    }
    bool have_target = loaded && render_target_create(&sl->tg, b->o.w, b->o.h, true);
    progress_set(&b->pr, b->pr.done + LOAD_WEIGHT, false, NULL);
    if (!loaded || !have_target) {
        char why[600];
        first_line(render_messages(sl->r)[0] ? render_messages(sl->r) : "cannot create the framebuffer", why,
                   sizeof why);
        const diag_list *dl = render_diags(sl->r);
        for (int j = 0; j < dl->n; j++)
            if (dl->d[j].severity == DIAG_ERROR) { diag_format(&dl->d[j], why, sizeof why); break; }
        for (int ti = 0; ti < b->o.ntimes; ti++) snprintf(b->rows[sl->first_row + ti].error, sizeof why, "%s", why);
        fprintf(stderr, "%starn bench: %s with %s, setting %s: %s\n", b->pr.tty ? "\n" : "", sc, b->o.packs[p],
                st->name, why);
        b->failures++;
        render_destroy(sl->r);
        sl->r = NULL;
        return false;
    }
    for (int ti = 0; ti < b->o.ntimes; ti++) {
        b->rows[sl->first_row + ti].first_wall_ms = warm_up(b, sl->r, &sl->tg, b->o.times[ti]);
        acc_init(&sl->acc[ti], b->o.frames, true);
    }
    sl->live = true;
    return true;
}

static void slot_close(slot *sl) {
    if (!sl->r) return;
    if (sl->live) render_target_destroy(&sl->tg);
    render_destroy(sl->r);
    sl->r = NULL;
    sl->live = false;
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
static void time_round_robin(bench *b, slot *sl, int n, double weight_each_time) {
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
        progress_set(&b->pr, base + (want > 0 ? total * spent / want : total), false, NULL);
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
    progress_set(&b->pr, base + total, false, NULL);
    b->seconds_timing += clock_now_s() - t0;
}

/* The error over the animated sequence: seq_frames frames from the first
 * time at seq_fps, at the sequence's size, each against the reference of
 * its instant: the water RMSE and SSIM, means over the instants, and the
 * temporal error: the RMS over the water (water in both frames) of the
 * pack's frame-to-frame change minus the reference's, (P[i+1] - P[i]) -
 * (R[i+1] - R[i]). A pack whose glints or march steps jump between frames
 * where the reference's change is smooth scores worse there. With images,
 * a strip of |that| per pixel (max over R, G, B), one panel a pair. */
typedef struct seq_result { double water_rmse, water_ssim, temporal, ref_change, pack_change; int frames; } seq_result;

static seq_result measure_sequence(bench *b, slot *sl) {
    seq_result out = { NAN, NAN, NAN, NAN, NAN, 0 };
    int nf = b->o.seq_frames, w = b->o.seq_w, h = b->o.seq_h;
    if (nf < 2) return out;
    double t0 = clock_now_s();
    render_target tg;
    if (!render_target_create(&tg, w, h, true)) return out;
    long n = (long)w * h;
    float *prev = mem_alloc((size_t)n * 4 * sizeof *prev), *cur = mem_alloc((size_t)n * 4 * sizeof *cur);
    const refcache_image *rprev = NULL;
    double sum_rmse = 0, sum_ssim = 0, sq = 0, sq_ref = 0, sq_pack = 0;
    long cnt = 0;
    int n_rmse = 0, n_ssim = 0, got = 0;
    img strip = { 0 };
    bool images = b->o.images && img_alloc(&strip, w * (nf - 1), h, 3);
    float *field = images ? mem_alloc((size_t)n * sizeof *field) : NULL;
    float *rgb = images ? mem_alloc((size_t)n * 3 * sizeof *rgb) : NULL;
    for (int i = 0; i < nf; i++) {
        double t = seq_time(b, i);
        ref_entry *re = get_ref_at(b, sl->s, sl->scene, REFK_SEQ, w, h, t);
        render_frame(sl->r, t, tg.fbo, w, h, NULL);
        render_target_read(&tg, cur);
        if (!re) { rprev = NULL; continue; }
        const refcache_image *R = &re->im;
        got++;
        double e = water_rmse_of(cur, R, w, h), ss = water_ssim(cur, R, w, h);
        if (isfinite(e)) { sum_rmse += e; n_rmse++; }
        if (isfinite(ss)) { sum_ssim += ss; n_ssim++; }
        if (rprev) {
            for (long px = 0; px < n; px++) {
                bool water = R->mask[px] == REF_MASK_WATER && rprev->mask[px] == REF_MASK_WATER;
                float worst = NAN;
                if (water) {
                    worst = 0;
                    for (int c = 0; c < 3; c++) {
                        double dp = (double)cur[px * 4 + c] - prev[px * 4 + c];
                        double dr = (double)R->color[px * 3 + c] - rprev->color[px * 3 + c];
                        if (!isfinite(dp) || !isfinite(dr)) { worst = NAN; break; }
                        sq += (dp - dr) * (dp - dr);
                        sq_ref += dr * dr;
                        sq_pack += dp * dp;
                        cnt++;
                        if (fabs(dp - dr) > worst) worst = (float)fabs(dp - dr);
                    }
                }
                if (field) field[px] = water ? worst : -1.0f;
            }
            if (images) {
                ref_heatmap(field, w, h, b->o.heat_max / 4, rgb);
                for (int y = 0; y < h; y++)
                    memcpy(strip.px + ((size_t)y * strip.w + (size_t)(i - 1) * w) * 3, rgb + (size_t)y * w * 3,
                           (size_t)w * 3 * sizeof *rgb);
            }
        }
        rprev = R;
        float *tmp = prev;
        prev = cur;
        cur = tmp;
    }
    out.frames = got;
    out.water_rmse = n_rmse ? sum_rmse / n_rmse : NAN;
    out.water_ssim = n_ssim ? sum_ssim / n_ssim : NAN;
    if (cnt) {
        out.temporal = sqrt(sq / cnt);
        out.ref_change = sqrt(sq_ref / cnt);
        out.pack_change = sqrt(sq_pack / cnt);
    }
    if (images && cnt) {
        char dir[PATH_LEN], path[PATH_LEN + 256], sc[256], err[512];
        snprintf(dir, sizeof dir, "%s/img", b->o.out);
        stem(b->scene_abs[sl->s], sc, sizeof sc);
        fmt(path, sizeof path, "%s/%s.%s.%s.temporal.png", dir, sc, b->o.packs[sl->p],
            bench_setting_name(b, sl->p, sl->k));
        if (mkdirs(dir)) img_write(path, &strip, err, sizeof err);
    }
    if (images) img_free(&strip);
    free(field);
    free(rgb);
    free(prev);
    free(cur);
    render_target_destroy(&tg);
    b->seconds_seq += clock_now_s() - t0;
    return out;
}

/* The error of a setting: at each time the frame against the reference
 * (RMSE, and HDR-FLIP with SSIM over the water), its buffers, the
 * irradiance of flat lighting where it shows none, its uncertainty (the
 * first time against the noise and grid references), the sequence. */
static void slot_measure(bench *b, slot *sl) {
    int w = b->o.w, h = b->o.h, nt = b->o.ntimes;
    long n = (long)w * h;
    char sc[256];
    stem(b->scene_abs[sl->s], sc, sizeof sc);
    const char *name = bench_setting_name(b, sl->p, sl->k);
    float *frames = mem_alloc((size_t)nt * n * 4 * sizeof *frames);
    flip_job jobs[MAX_TIMES + 2];
    int nj = 0, job_of[MAX_TIMES];
    ref_entry *refs[MAX_TIMES];
    for (int ti = 0; ti < nt; ti++) {
        row *rw = &b->rows[sl->first_row + ti];
        float *rgba = frames + (size_t)ti * n * 4;
        double t = b->o.times[ti];
        progress_set(&b->pr, b->pr.done, true, "%s %s %s t=%g: error", sc, b->o.packs[sl->p], name, t);
        while (glGetError() != GL_NO_ERROR) {}
        render_frame(sl->r, t, sl->tg.fbo, w, h, NULL);
        render_target_read(&sl->tg, rgba);
        GLenum ge = glGetError();
        if (ge != GL_NO_ERROR) rw->gl_error = ge;
        rw->ok = true;
        ref_entry *ref = refs[ti] = get_ref(b, sl->s, sl->scene, ti);
        job_of[ti] = -1;
        if (ref) {
            ref_fimage A = { rgba, w, h, 4 }, B = { ref->im.color, w, h, 3 };
            ref_image_metrics m;
            char merr[256];
            measure_water(b, rw, &A, &B, ref->im.mask);
            if (ref_metrics_image(&A, &B, NULL, &m, merr, sizeof merr)) {
                rw->rmse = m.rmse;
                rw->psnr = m.psnr_db;
                rw->mae = m.mae;
                rw->p95 = m.pixel_err.p95;
                rw->p99 = m.pixel_err.p99;
                rw->max_abs = m.max_abs;
                rw->over_share = m.over_threshold_share;
                rw->nan_px = m.count.nan_a;
                rw->inf_px = m.count.inf_a;
            }
            rw->water_ssim = water_ssim(rgba, &ref->im, w, h);
            job_of[ti] = nj;
            jobs[nj++] = (flip_job){ rgba, ref->im.color, ref->im.mask, w, h, NAN, NAN };
        } else {
            snprintf(rw->note, sizeof rw->note, "no reference");
            for (long i = 0; i < n; i++)
                for (int c = 0; c < 3; c++) {
                    if (isnan(rgba[i * 4 + c])) { rw->nan_px++; break; }
                    if (isinf(rgba[i * 4 + c])) { rw->inf_px++; break; }
                }
        }
        if (b->o.images) write_images(b, rw, rgba, ref);
    }
    /* the uncertainty: the first time's frame against the other references */
    ref_entry *alt[2] = { NULL, NULL };
    int alt_job[2] = { -1, -1 };
    if (b->o.uncertainty && refs[0]) {
        alt[0] = get_ref_at(b, sl->s, sl->scene, REFK_NOISE, w, h, b->o.times[0]);
        alt[1] = get_ref_at(b, sl->s, sl->scene, REFK_GRID, w, h, b->o.times[0]);
        for (int k = 0; k < 2; k++)
            if (alt[k]) {
                alt_job[k] = nj;
                /* the water is the default reference's, as for the figure it qualifies */
                jobs[nj++] = (flip_job){ frames, alt[k]->im.color, refs[0]->im.mask, w, h, NAN, NAN };
            }
    }
    progress_set(&b->pr, b->pr.done, true, "%s %s %s: FLIP x%d", sc, b->o.packs[sl->p], name, nj);
    run_flip_jobs(b, jobs, nj);
    for (int ti = 0; ti < nt; ti++)
        if (job_of[ti] >= 0) {
            b->rows[sl->first_row + ti].water_flip = jobs[job_of[ti]].water;
            b->rows[sl->first_row + ti].flip = jobs[job_of[ti]].frame;
        }
    row *r0 = &b->rows[sl->first_row];
    for (int k = 0; k < 2; k++) {
        if (!alt[k]) continue;
        /* the alternative reference's water mask is the same (the caustics
         * differ, not the geometry): the default's is used for both */
        refcache_image im = alt[k]->im;
        im.mask = refs[0]->im.mask;
        double e = water_rmse_of(frames, &im, w, h);
        double du = fabs(e - r0->water_rmse), df = fabs(jobs[alt_job[k]].water - r0->water_flip);
        if (k == 0) { r0->u_noise_rmse = du; r0->u_noise_flip = df; }
        else { r0->u_grid_rmse = du; r0->u_grid_flip = df; }
    }
    /* the sequence, while the programs are the setting's own (the buffers change them) */
    if (b->o.seq_frames >= 2) {
        progress_set(&b->pr, b->pr.done, true, "%s %s %s: sequence", sc, b->o.packs[sl->p], name);
        seq_result q = measure_sequence(b, sl);
        r0->seq_frames = q.frames;
        r0->seq_water_rmse = q.water_rmse;
        r0->seq_water_ssim = q.water_ssim;
        r0->temporal_rmse = q.temporal;
        r0->seq_ref_change = q.ref_change;
        r0->seq_pack_change = q.pack_change;
    }
    /* the buffers the pack shows: its bench.txt `buffer` lines, else TARN_OUTPUT */
    measure_buffers(b, sl->r, &sl->tg, sl->s, sl->p, sl->scene, sl->first_row, frames);
    for (int ti = 0; ti < nt; ti++) {
        row *rw = &b->rows[sl->first_row + ti];
        if (rw->has[REF_OUTPUT_IRRADIANCE] || !refs[ti]) continue;
        ref_entry *flat = get_ref_at(b, sl->s, sl->scene, REFK_FLAT, w, h, b->o.times[ti]);
        if (flat) measure_flat_irradiance(b, rw, flat, refs[ti]);
    }
    free(frames);
}

/* Every setting of a scene: loaded and warmed up, timed round-robin, then
 * measured for error one by one. */
static void measure_scene(bench *b, int s, double weight_each_time) {
    int n = 0;
    for (int p = 0; p < b->o.npacks; p++) n += b->pb[p].n;
    slot *sl = mem_zalloc((size_t)(n ? n : 1) * sizeof *sl);
    int i = 0;
    for (int p = 0; p < b->o.npacks; p++)
        for (int k = 0; k < b->pb[p].n; k++) slot_open(b, &sl[i++], s, p, k);
    time_round_robin(b, sl, n, weight_each_time);
    for (i = 0; i < n; i++) {
        if (sl[i].live) slot_measure(b, &sl[i]);
        slot_close(&sl[i]);
    }
    free(sl);
}

/* ---- the cost model ---- */

/* The sweep a pack's cost model is fitted from: its default setting on the
 * first scene at three image sizes (half, the run's, 1.5x a side) and
 * three water grids: 9 timed frames, medians as the run's. */
const int BENCH_COST_MESHES[3] = { 64, 128, 256 };
const double BENCH_COST_SCALES[3] = { 0.5, 1.0, 1.5 };
#define COST_MESHES BENCH_COST_MESHES
#define COST_SCALES BENCH_COST_SCALES

/* One mesh: a wrapper glib adding `WaterMesh m` to the scene, loaded once
 * and timed at each size. Returns the samples added, -1 with why on a
 * failed load. */
static int cost_mesh(bench *b, int p, int m, cost_sample *out, char *why, size_t whylen) {
    char sc[256], path[PATH_LEN + 300];
    stem(b->scene_abs[0], sc, sizeof sc);
    packset_assign as = { .program = "scene", .name = "WaterMesh", .value = { (float)m }, .nvalue = 1 };
    packset_setting st = { .assign = &as, .nassign = 1 };
    snprintf(st.name, sizeof st.name, "cost-mesh-%d", m);
    snprintf(path, sizeof path, "%s/scenes/%s.%s.cost-mesh-%d.glib", b->o.out, sc, b->o.packs[p], m);
    char err[1024] = "";
    if (!packset_write_wrapper(&st, b->scene_abs[0], path, err, sizeof err)) {
        snprintf(why, whylen, "%s", err);
        return -1;
    }
    /* no spray: the reference draws none (docs/waves.md), so it is no part of a pack's error or time */
    render_desc rd = { .repo_root = b->root, .pack = b->o.packs[p], .samples = b->o.samples, .no_spray = true };
    render *r = render_create(&rd);
    if (!render_load(r, path)) {
        first_line(render_messages(r), why, whylen);
        render_destroy(r);
        return -1;
    }
    int n = 0;
    for (size_t i = 0; i < sizeof COST_SCALES / sizeof COST_SCALES[0]; i++) {
        int w = (int)lround(b->o.w * COST_SCALES[i]), h = (int)lround(b->o.h * COST_SCALES[i]);
        render_target tg;
        if (w < 1 || h < 1 || !render_target_create(&tg, w, h, true)) continue;
        timing tm = time_frames(b, r, &tg, b->o.times[0], NULL);
        render_target_destroy(&tg);
        out[n++] = (cost_sample){ (double)w * h / 1e6, cost_model_grid_kvertices(m),
                                  axis_ms(b, &tm) };
    }
    render_destroy(r);
    return n;
}

static void measure_cost(bench *b, int p) {
    char sc[256];
    stem(b->scene_abs[0], sc, sizeof sc);
    progress_set(&b->pr, b->pr.done, true, "%s %s: cost model", sc, b->o.packs[p]);
    cost_sample samples[COST_SAMPLES];
    int n = 0;
    for (size_t k = 0; k < sizeof COST_MESHES / sizeof COST_MESHES[0]; k++) {
        int got = cost_mesh(b, p, COST_MESHES[k], samples + n, b->cost_note[p], sizeof b->cost_note[p]);
        if (got < 0) return;
        n += got;
    }
    b->has_cost[p] = cost_model_fit(samples, n, &b->cost[p], b->cost_note[p], sizeof b->cost_note[p]);
}

/* The ocean's FFT passes at every size, with the first scene that has an
 * ocean: its cost grows with N^2 log N, whatever the pack draws. */
static void measure_ocean(bench *b) {
    for (int s = 0; s < b->o.nscenes; s++) {
        ref_world_desc w;
        if (!scene_load(b->scene_abs[s], NULL, &w, NULL, NULL, NULL, 0) || w.waves.ocean.spectrum == REF_SPECTRUM_NONE)
            continue;
        stem(b->scene_abs[s], b->ocean_scene, sizeof b->ocean_scene);
        progress_set(&b->pr, b->pr.done, true, "%s: the ocean's FFT passes", b->ocean_scene);
        if (!bench_ocean_measure(&w.waves.ocean, &b->ocean)) b->failures++;
        return;
    }
}

/* ---- summaries ---- */

double bench_axis_time(const bench *b, const summary *s) {
    return b->axis == BENCH_AXIS_GPU ? s->gpu_ms : b->axis == BENCH_AXIS_CPU ? s->cpu_ms : s->wall_ms;
}

double bench_axis_floor(const bench *b) {
    return b->axis == BENCH_AXIS_GPU ? b->floor_gpu : b->axis == BENCH_AXIS_CPU ? b->floor_cpu : b->floor_wall;
}

double bench_axis_spread(const bench *b, const summary *s) {
    return b->axis == BENCH_AXIS_GPU ? s->gpu_spread : b->axis == BENCH_AXIS_CPU ? s->cpu_spread : s->wall_spread;
}

const char *bench_axis_name(const bench *b) {
    return b->axis == BENCH_AXIS_GPU ? "gpu" : b->axis == BENCH_AXIS_CPU ? "cpu" : "wall";
}

static double mean_of(const double *v, int n) {
    double sum = 0;
    int k = 0;
    for (int i = 0; i < n; i++)
        if (isfinite(v[i])) { sum += v[i]; k++; }
    return k ? sum / k : NAN;
}

static void summarise(bench *b) {
    b->sums = mem_zalloc((size_t)(b->nrows > 0 ? b->nrows : 1) * sizeof *b->sums);
    for (int i = 0; i < b->nrows; i++) {
        const row *r0 = &b->rows[i];
        if (r0->ti != 0) continue;
        summary *s = &b->sums[b->nsums++];
        s->scene = r0->scene;
        s->pack = r0->pack;
        s->setting = r0->setting;
        double gpu[MAX_TIMES], wall[MAX_TIMES], cpu[MAX_TIMES], q[6][MAX_TIMES];
        double wflip[MAX_TIMES], flip[MAX_TIMES], wssim[MAX_TIMES];
        int ng = 0, nw = 0, nc = 0, ne = 0, nq = 0, nt = 0;
        double rmse = 0, psnr = 0, p95 = 0, share = 0, wrmse = 0, wpsnr = 0, off = 0;
        s->capped_share = NAN;
        int nw_err = 0;
        s->wall_spread = s->cpu_spread = s->gpu_spread = 0;
        double comp[REF_OUTPUT_COUNT] = { 0 };
        int ncomp[REF_OUTPUT_COUNT] = { 0 };
        s->ok = true;
        for (int j = i; j < b->nrows && j < i + b->o.ntimes; j++) {
            const row *r = &b->rows[j];
            s->ok &= r->ok;
            if (r->frames > 0 && (s->frames == 0 || r->frames < s->frames)) s->frames = r->frames;
            s->nan_px += r->nan_px + r->inf_px;
            if (isfinite(r->gpu_ms)) gpu[ng++] = r->gpu_ms;
            if (isfinite(r->wall_ms)) wall[nw++] = r->wall_ms;
            if (isfinite(r->cpu_ms)) cpu[nc++] = r->cpu_ms;
            if (isfinite(r->wall_ms)) {
                q[0][nq] = r->wall_q1;
                q[1][nq] = r->wall_q3;
                q[2][nq] = r->gpu_q1;
                q[3][nq] = r->gpu_q3;
                q[4][nq] = r->cpu_q1;
                q[5][nq] = r->cpu_q3;
                nq++;
            }
            wflip[nt] = r->water_flip;
            flip[nt] = r->flip;
            wssim[nt++] = r->water_ssim;
            if (isfinite(r->wall_spread) && r->wall_spread > s->wall_spread) s->wall_spread = r->wall_spread;
            if (isfinite(r->cpu_spread) && r->cpu_spread > s->cpu_spread) s->cpu_spread = r->cpu_spread;
            if (isfinite(r->gpu_spread) && r->gpu_spread > s->gpu_spread) s->gpu_spread = r->gpu_spread;
            if (isfinite(r->capped_share) && !(r->capped_share <= s->capped_share)) s->capped_share = r->capped_share;
            if (isfinite(r->water_rmse)) {
                wrmse += r->water_rmse;
                wpsnr += isfinite(r->water_psnr) ? r->water_psnr : 99;
                off += isfinite(r->off_rmse) ? r->off_rmse : 0;
                nw_err++;
            }
            if (isfinite(r->rmse)) {
                rmse += r->rmse;
                psnr += isfinite(r->psnr) ? r->psnr : 99;
                p95 += r->p95;
                share += r->over_share;
                ne++;
            }
            for (int m = 1; m < REF_OUTPUT_COUNT; m++)
                if (r->has[m]) {
                    comp[m] += m == REF_OUTPUT_REFRACT_HIT ? r->comp_p95[m]
                               : m == REF_OUTPUT_IRRADIANCE ? r->comp_rel_median[m] : r->comp_mean[m];
                    ncomp[m]++;
                    if (m == REF_OUTPUT_IRRADIANCE) s->irr_flat |= r->irr_flat;
                }
        }
        s->gpu_ms = median(gpu, ng);
        s->wall_ms = median(wall, nw);
        s->cpu_ms = median(cpu, nc);
        s->wall_q1 = median(q[0], nq);
        s->wall_q3 = median(q[1], nq);
        int kq[6] = { 0 };
        for (int m = 2; m < 6; m++)
            for (int j = 0; j < nq; j++)
                if (isfinite(q[m][j])) q[m][kq[m]++] = q[m][j];
        s->gpu_q1 = median(q[2], kq[2]);
        s->gpu_q3 = median(q[3], kq[3]);
        s->cpu_q1 = median(q[4], kq[4]);
        s->cpu_q3 = median(q[5], kq[5]);
        s->rmse = ne ? rmse / ne : NAN;
        s->water_rmse = nw_err ? wrmse / nw_err : NAN;
        s->water_psnr = nw_err ? wpsnr / nw_err : NAN;
        s->off_rmse = nw_err ? off / nw_err : NAN;
        s->water_flip = mean_of(wflip, nt);
        s->flip = mean_of(flip, nt);
        s->water_ssim = mean_of(wssim, nt);
        s->psnr = ne ? psnr / ne : NAN;
        s->p95 = ne ? p95 / ne : NAN;
        s->over_share = ne ? share / ne : NAN;
        for (int m = 1; m < REF_OUTPUT_COUNT; m++) {
            s->has[m] = ncomp[m] > 0;
            s->comp[m] = ncomp[m] ? comp[m] / ncomp[m] : NAN;
        }
        /* the uncertainty and the sequence: the first time's row */
        s->u_noise_rmse = r0->u_noise_rmse;
        s->u_grid_rmse = r0->u_grid_rmse;
        s->u_noise_flip = r0->u_noise_flip;
        s->u_grid_flip = r0->u_grid_flip;
        s->u_rmse = hypot(r0->u_noise_rmse, r0->u_grid_rmse);
        s->u_flip = hypot(r0->u_noise_flip, r0->u_grid_flip);
        s->seq_frames = r0->seq_frames;
        s->seq_water_rmse = r0->seq_water_rmse;
        s->seq_water_ssim = r0->seq_water_ssim;
        s->temporal_rmse = r0->temporal_rmse;
        s->seq_ref_change = r0->seq_ref_change;
        s->seq_pack_change = r0->seq_pack_change;
    }
    /* the Pareto fronts of each scene, over every pack: time against the
     * water RMSE, and against the water FLIP */
    for (int sc = 0; sc < b->o.nscenes; sc++)
        for (int metric = 0; metric < 2; metric++) {
            double x[1024], y[1024], dx[1024], dy[1024];
            bool on[1024];
            int idx[1024], n = 0;
            for (int i = 0; i < b->nsums && n < 1024; i++) {
                const summary *si = &b->sums[i];
                if (si->scene != sc) continue;
                x[n] = si->ok ? bench_axis_time(b, si) : NAN;
                double u = metric == 0 ? si->u_rmse : si->u_flip;
                y[n] = metric == 0 ? (isfinite(si->water_rmse) ? si->water_rmse : si->rmse)
                                   : (isfinite(si->water_flip) ? si->water_flip : si->flip);
                /* what a second run could move: the time by its median's
                 * own uncertainty, the frames' spread over sqrt(frames)
                 * (for normal noise the median's standard error is 0.93
                 * IQR / sqrt(n)), at least BENCH_TIME_NOISE: runs on a
                 * shared machine differ more than frames within one run.
                 * (The frames' spread itself, as until issue 26, let one
                 * noisy setting tie in time with, and so take off the
                 * front, settings up to 6.7 times faster: raymarch iter-20,
                 * 27.6 ms of CPU, spread 0.88, took basic mesh-64, 4.1 ms,
                 * off.) What another
                 * reference could move: the error by its measured
                 * uncertainty (BENCH_ERROR_TIE of it where not measured) */
                double spread = bench_axis_spread(b, si);
                double se = isfinite(spread) && si->frames > 0 ? spread / sqrt((double)si->frames) : 0;
                dx[n] = x[n] * fmax(BENCH_TIME_NOISE, se);
                dy[n] = fmax(isfinite(u) ? u : y[n] * BENCH_ERROR_TIE, 1e-5);
                idx[n++] = i;
            }
            plot_pareto_combined(x, y, dx, dy, n, on);
            for (int i = 0; i < n; i++) {
                if (metric == 0) b->sums[idx[i]].pareto = on[i];
                else b->sums[idx[i]].pareto_flip = on[i];
            }
        }
}

/* ---- the command ---- */

int bench_run(const bench_desc *d, char *why, size_t whylen) {
    bench *b = mem_zalloc(sizeof *b);
    snprintf(b->root, sizeof b->root, "%s", tarn_root());
    int rc = resolve(b, d, why, whylen);
    if (rc != 0) {
        free(b);
        return rc;
    }
    double t_start = clock_now_s();
    loadavg(b->load_before);
    char err[4096] = "";
    for (int p = 0; p < b->o.npacks; p++) {
        err[0] = '\0';
        if (!packset_bench_load(b->root, b->o.packs[p], &b->pb[p], err, sizeof err)) fputs(err, stderr);
    }
    if (!mkdirs(b->o.out)) {
        fprintf(stderr, "tarn bench: cannot create %s: %s\n", b->o.out, strerror(errno));
        for (int p = 0; p < b->o.npacks; p++) packset_bench_free(&b->pb[p]);
        free(b);
        return TARN_EXIT_INPUT;
    }
    char sdir[PATH_LEN + 16];
    snprintf(sdir, sizeof sdir, "%s/scenes", b->o.out);
    mkdirs(sdir);
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    if (!ctx) {
        fprintf(stderr, "tarn bench: %s\n", err);
        for (int p = 0; p < b->o.npacks; p++) packset_bench_free(&b->pb[p]);
        free(b);
        return TARN_EXIT_NO_GL;
    }
    machine(b);
    match_reference(&b->o);
    b->pr = (progress){ .start = t_start, .tty = isatty(STDERR_FILENO), .quiet = b->o.quiet };
    prepare_refs(b);

    /* progress weights: a frame is 1; a reference, a load, the floor */
    int nsettings = 0;
    for (int p = 0; p < b->o.npacks; p++) nsettings += b->pb[p].n;
    double per_time = 0.5 * b->o.warmup + b->o.frame_budget + 0.3 + 1.0 /* FLIP */;
    double per_setting = LOAD_WEIGHT + (b->o.uncertainty ? 2.0 : 0) + 0.1 * b->o.seq_frames;
    b->pr.total = ref_total_weight(b) + 2 +
                  (double)b->o.nscenes * nsettings * (per_setting + per_time * b->o.ntimes);
    if (!b->o.quiet)
        fprintf(stderr, "tarn bench: %d scene(s) x %d pack(s), %d setting(s), %d time(s) at %dx%d on %s\n",
                b->o.nscenes, b->o.npacks, nsettings, b->o.ntimes, b->o.w, b->o.h, b->gl_renderer);
    progress_set(&b->pr, 0, true, "cost floor");
    if (!measure_floor(b)) {
        fprintf(stderr, "tarn bench: the cost floor could not be measured\n");
        b->failures++;
    }
    progress_set(&b->pr, 2, true, NULL);
    for (int s = 0; s < b->o.nscenes; s++) measure_scene(b, s, per_time);
    for (int p = 0; p < b->o.npacks && b->o.cost_model; p++) measure_cost(b, p);
    if (b->o.cost_model) measure_ocean(b);
    loadavg(b->load_after);
    b->seconds = clock_now_s() - t_start;
    progress_set(&b->pr, b->pr.total, true, "done");
    if (b->pr.tty && !b->o.quiet) fputc('\n', stderr);

    summarise(b);
    strbuf md = { 0 };
    bool ok = bench_write_results(b, &md);
    if (!ok) b->failures++;
    if (!b->o.quiet) {
        fputs(md.s ? md.s : "", stdout);
        printf("\ntarn bench: %d rows in %.1f s; results in %s (bench.csv, bench.json, report.md, plot-*.png)\n",
               b->nrows, b->seconds, b->o.out);
    }
    free(md.s);
    rc = b->failures ? TARN_EXIT_INPUT : TARN_EXIT_OK;
    for (int i = 0; i < b->nrefs; i++) refcache_free(&b->refs[i].im);
    free(b->refs);
    free(b->rows);
    free(b->sums);
    for (int p = 0; p < b->o.npacks; p++) packset_bench_free(&b->pb[p]);
    gl_ctx_destroy(ctx);
    free(b);
    return rc;
}
