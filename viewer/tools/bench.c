/* bench: `tarn bench`, speed against error (see bench.h, docs/benchmark.md). */
#include "util.h"
#include "bench.h"
#include "bench_ocean.h"
#include "costmodel.h"

#include <GL/gl.h>
#include <dirent.h>
#include <errno.h>
#include <math.h>
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
#include "packset.h"
#include "plot.h"
#include "ref_metrics.h"
#include "refcache.h"
#include "render.h"
#include "scene.h"
#include "ref_buffers.h"
#include "file.h"
#include "mem.h"
#include "strbuf.h"

#define MAX_SCENES BENCH_MAX_SCENES
#define MAX_TIMES BENCH_MAX_TIMES
#define PATH_LEN 2048

/* ---- the run's state ---- */

typedef struct bench_opts {
    const char *scenes[MAX_SCENES];
    int nscenes;
    packset_name packs[PACKSET_MAX];
    int npacks;
    int w, h;
    double times[MAX_TIMES];
    int ntimes;
    int frames, warmup;
    double frame_budget;
    const char *out, *docs;
    int time_axis;               /* 0 auto, 1 gpu, 2 wall */
    refcache_opts ref;
    double heat_max;
    bool images, quiet;
    bool cost_model;             /* fit each pack's a + b·pixels + c·vertices */
    int samples;                 /* MSAA as asked (render_desc.samples) */
    int samples_used;            /* ...and as this GL gives it (1: off) */
    bool spp_matched;            /* ref.spp follows samples_used (no --ref-spp) */
} bench_opts;

typedef struct row {             /* one scene, pack, setting and time */
    int scene, pack, setting, ti;
    bool ok;
    char error[600];
    char note[600];
    int frames;
    double gpu_ms, wall_ms, first_wall_ms;
    double water_rmse, water_psnr, off_rmse;   /* over the reference's water pixels / the rest */
    long water_px;
    double rmse, psnr, mae, p95, p99, max_abs, over_share;   /* the whole frame */
    double wall_spread;          /* the timed frames' wall time, (p75 - p25) / median */
    double capped_share;         /* water pixels whose refraction march ran out (NaN: not shown) */
    long nan_px, inf_px;
    unsigned gl_error;
    bool has[REF_OUTPUT_COUNT];
    double comp_median[REF_OUTPUT_COUNT], comp_p95[REF_OUTPUT_COUNT], comp_mean[REF_OUTPUT_COUNT];
    double comp_rel_mean[REF_OUTPUT_COUNT];
    double comp_rel_median[REF_OUTPUT_COUNT];
    int npasses;                 /* GPU time per pass (render_pass_times), medians */
    char pass_name[GPU_TIMER_MARKS][GPU_TIMER_NAME];
    double pass_ms[GPU_TIMER_MARKS];
} row;

typedef struct summary {         /* one scene, pack and setting, over the times */
    int scene, pack, setting;
    bool ok;
    double gpu_ms, wall_ms, rmse, psnr, p95, over_share;
    double water_rmse, water_psnr, off_rmse;   /* means over the times */
    double wall_spread;                        /* the largest of its rows' */
    double capped_share;                       /* the largest of its rows' (NaN: not shown) */
    /* hit p95 (m), Fresnel MAE, irradiance relative error's median (the
     * mean is ruled by the few points the reference has almost no sun),
     * depth MAE (m) */
    double comp[REF_OUTPUT_COUNT];
    bool has[REF_OUTPUT_COUNT];
    long nan_px;
    bool pareto;
} summary;

typedef struct ref_entry {
    uint64_t key;
    int ti;
    refcache_image im;
    bool tried, ok;
    double weight;               /* progress units: a render, or a read from the cache */
} ref_entry;

typedef struct progress {
    double start, total, done, last_draw;
    bool tty, quiet;
    char what[160];
} progress;

typedef struct bench {
    bench_opts o;
    char root[PATH_LEN];
    char ref_dir[PATH_LEN];      /* the reference cache (ref_cache_dir) */
    char scene_abs[MAX_SCENES][PATH_LEN];
    packset_bench pb[PACKSET_MAX];
    row *rows;
    int nrows;
    summary *sums;
    int nsums;
    ref_entry *refs;
    int nrefs;
    double floor_gpu, floor_wall;
    char gl_renderer[256], gl_version[256], cpu[256];
    int cores;
    bool cpu_raster;
    int axis;                    /* resolved: 1 gpu, 2 wall */
    double seconds;
    char started[64];
    progress pr;
    int failures;
    int refs_rendered, refs_cached;
    /* per pack: its default's cost model on the first scene (measure_cost) */
    cost_model cost[PACKSET_MAX];
    bool has_cost[PACKSET_MAX];
    char cost_note[PACKSET_MAX][200];
    /* the spectrum ocean's passes, when a scene has one (bench_ocean.h) */
    bench_ocean_costs ocean;
    char ocean_scene[256];
} bench;

/* ---- small helpers ---- */

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

static void stem(const char *path, char *out, size_t len) {
    const char *b = strrchr(path, '/');
    b = b ? b + 1 : path;
    size_t n = strlen(b);
    if (n > 5 && strcmp(b + n - 5, ".glib") == 0) n -= 5;
    snprintf(out, len, "%.*s", (int)n, b);
}

static bool write_text(const char *path, const char *text) {
    FILE *f = fopen(path, "w");
    if (!f) return false;
    fputs(text, f);
    return fclose(f) == 0;
}

/* A growing string. */
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
    b->axis = b->o.time_axis ? b->o.time_axis : b->cpu_raster ? 2 : 1;
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
    o->quiet = d->quiet;
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

static ref_entry *find_ref(bench *b, uint64_t key, int ti) {
    for (int i = 0; i < b->nrefs; i++)
        if (b->refs[i].key == key && b->refs[i].ti == ti) return &b->refs[i];
    return NULL;
}

/* Progress weights, roughly seconds on the 2-core machine: a load, and a
 * reference (photons: 35 s for the default 256-cell grid of 36 photons a
 * cell; pixels: 5 s for 480x270 at 1 sample). */
static const double LOAD_WEIGHT = 3;

static double ref_weight(const bench *b) {
    ref_render_desc d = ref_render_resolve(&(ref_render_desc){ .caustic_res = b->o.ref.caustic_res,
                                                                .photons_per_cell = b->o.ref.photons_per_cell,
                                                                .spp = b->o.ref.spp });
    double cr = d.caustic_res / 256.0, rays = b->o.ref.nsamples > 0 ? b->o.ref.nsamples : d.spp * d.spp;
    return 35 * cr * cr * d.photons_per_cell / 36.0 + 5.0 * b->o.w * b->o.h / (480.0 * 270.0) * rays;
}

/* Keys of every reference the run needs; renders or reads each once. */
static void prepare_refs(bench *b) {
    const char *dir = b->ref_dir;
    for (int s = 0; s < b->o.nscenes; s++)
        for (int p = 0; p < b->o.npacks; p++)
            for (int k = 0; k < b->pb[p].n; k++) {
                char wp[PATH_LEN], err[2048] = "";
                const char *scene = wrapper_path(b, s, p, k, wp, sizeof wp);
                if (scene != b->scene_abs[s] && !packset_write_wrapper(&b->pb[p].settings[k], b->scene_abs[s], scene,
                                                                        err, sizeof err))
                    continue;
                for (int ti = 0; ti < b->o.ntimes; ti++) {
                    uint64_t key;
                    if (!refcache_key(scene, b->o.w, b->o.h, b->o.times[ti], &b->o.ref, &key, err, sizeof err))
                        continue;
                    if (find_ref(b, key, ti)) continue;
                    char named[PATH_LEN], sc[256];
                    stem(b->scene_abs[s], sc, sizeof sc);
                    fmt(named, sizeof named, "%s/%s.glib", dir, sc);
                    bool cached = refcache_cached(dir, scene, named, b->o.w, b->o.h, b->o.times[ti], &b->o.ref);
                    b->refs = mem_realloc(b->refs, (size_t)(b->nrefs + 1) * sizeof *b->refs);
                    ref_entry *e = &b->refs[b->nrefs++];
                    memset(e, 0, sizeof *e);
                    e->key = key;
                    e->ti = ti;
                    e->weight = cached ? 0.2 : ref_weight(b);
                }
            }
}

static double ref_total_weight(bench *b) {
    double w = 0;
    for (int i = 0; i < b->nrefs; i++) w += b->refs[i].weight;
    return w;
}

/* The reference for (scene path, pack, time), rendered on first use. */
static ref_entry *get_ref(bench *b, int s, const char *scene, int ti) {
    uint64_t key;
    char err[2048] = "";
    if (!refcache_key(scene, b->o.w, b->o.h, b->o.times[ti], &b->o.ref, &key, err, sizeof err)) return NULL;
    ref_entry *e = find_ref(b, key, ti);
    if (!e) return NULL;
    if (e->tried) return e->ok ? e : NULL;
    e->tried = true;
    const char *dir = b->ref_dir;
    char sc[256];
    stem(b->scene_abs[s], sc, sizeof sc);
    ref_progress_ctx pc = { &b->pr, b->pr.done, e->weight };
    progress_set(&b->pr, b->pr.done, true, "reference %s t=%g", sc, b->o.times[ti]);
    /* the stem names the scene, not the wrapper: settings that share a world share the file */
    char named[PATH_LEN];
    fmt(named, sizeof named, "%s/%s.glib", dir, sc);
    e->ok = refcache_get(dir, scene, named, b->o.w, b->o.h, b->o.times[ti], NULL, &b->o.ref,
                               on_ref_progress, &pc, &e->im, err, sizeof err);
    progress_set(&b->pr, pc.base + e->weight, true, NULL);
    if (e->ok && e->im.from_cache) b->refs_cached++;
    else if (e->ok) b->refs_rendered++;
    if (!e->ok) {
        fprintf(stderr, "%starn bench: %s\n", b->pr.tty ? "\n" : "", err);
        b->failures++;
        return NULL;
    }
    return e;
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

typedef struct timing { double gpu_ms, wall_ms, first_wall_ms, wall_spread; int frames; } timing;

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

/* Warm-up frames, then timed frames at the fixed time t: medians (and,
 * with rw, the median GPU time of each pass). */
static timing time_frames(bench *b, render *r, const render_target *tg, double t, row *rw) {
    timing out = { NAN, NAN, NAN, NAN, 0 };
    for (int i = 0; i < b->o.warmup; i++) {
        double t0 = clock_now_s();
        render_frame(r, t, tg->fbo, tg->w, tg->h, NULL);
        glFinish();
        if (i == 0) out.first_wall_ms = (clock_now_s() - t0) * 1e3;
        render_gpu_ms(r, true);
    }
    int max = b->o.frames;
    double *gpu = mem_zalloc((size_t)max * sizeof *gpu), *wall = mem_zalloc((size_t)max * sizeof *wall);
    double start = clock_now_s();
    int n = 0;
    pass_samples ps;
    memset(&ps, 0, sizeof ps);
    while (n < max) {
        double t0 = clock_now_s();
        render_frame(r, t, tg->fbo, tg->w, tg->h, NULL);
        glFinish();   /* the wall time of the whole frame, deferred rasterisation included */
        wall[n] = (clock_now_s() - t0) * 1e3;
        gpu[n] = render_gpu_ms(r, true);
        if (rw) pass_collect(&ps, r, max);
        n++;
        if (n >= 3 && clock_now_s() - start > b->o.frame_budget) break;
    }
    out.frames = n;
    out.wall_ms = median(wall, n);   /* sorts wall */
    if (n >= 4 && out.wall_ms > 0) out.wall_spread = (wall[(3 * n) / 4] - wall[n / 4]) / out.wall_ms;
    int ng = 0;
    for (int i = 0; i < n; i++)
        if (gpu[i] >= 0) gpu[ng++] = gpu[i];
    out.gpu_ms = ng ? median(gpu, ng) : NAN;
    if (rw) {
        rw->npasses = ps.n;
        for (int k = 0; k < ps.n; k++) {
            memcpy(rw->pass_name[k], ps.name[k], GPU_TIMER_NAME);
            rw->pass_ms[k] = ps.count[k] ? median(ps.ms[k], ps.count[k]) : NAN;
        }
    }
    for (int k = 0; k < ps.n; k++) free(ps.ms[k]);
    free(gpu);
    free(wall);
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

static void measure_setting(bench *b, int s, int p, int k, double weight_each_time) {
    const packset_setting *st = &b->pb[p].settings[k];
    char wp[PATH_LEN], sc[256];
    const char *scene = wrapper_path(b, s, p, k, wp, sizeof wp);
    stem(b->scene_abs[s], sc, sizeof sc);
    int first_row = b->nrows;
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
    }
    double base = b->pr.done;
    progress_set(&b->pr, base, true, "%s %s %s: loading", sc, b->o.packs[p], st->name);
    render_desc rd = { .repo_root = b->root, .pack = b->o.packs[p], .samples = b->o.samples };
    render *r = render_create(&rd);
    bool loaded = render_load(r, scene);
    char err[4096] = "";
    bool defines_changed = false;
    if (loaded) {
        int n;
        unif_set *sets = render_uniforms(r, &n);
        if (!packset_apply(sets, n, st, &defines_changed, err, sizeof err))
            for (int ti = 0; ti < b->o.ntimes; ti++)
                first_line(err, b->rows[first_row + ti].note, sizeof b->rows[first_row + ti].note);
        if (defines_changed && !render_rebuild_programs(r)) loaded = false;
    }
    render_target tg;
    bool have_target = loaded && render_target_create(&tg, b->o.w, b->o.h, true);
    if (!loaded || !have_target) {
        char why[600];
        first_line(render_messages(r)[0] ? render_messages(r) : "cannot create the framebuffer", why, sizeof why);
        const diag_list *dl = render_diags(r);
        for (int j = 0; j < dl->n; j++)
            if (dl->d[j].severity == DIAG_ERROR) { diag_format(&dl->d[j], why, sizeof why); break; }
        for (int ti = 0; ti < b->o.ntimes; ti++) snprintf(b->rows[first_row + ti].error, sizeof why, "%s", why);
        fprintf(stderr, "%starn bench: %s with %s, setting %s: %s\n", b->pr.tty ? "\n" : "", sc, b->o.packs[p],
                st->name, why);
        b->failures++;
        render_destroy(r);
        progress_set(&b->pr, base + LOAD_WEIGHT + weight_each_time * b->o.ntimes, true, NULL);
        return;
    }
    progress_set(&b->pr, base + LOAD_WEIGHT, false, NULL);
    float *rgba = mem_alloc((size_t)b->o.w * b->o.h * 4 * sizeof *rgba);
    for (int ti = 0; ti < b->o.ntimes; ti++) {
        row *rw = &b->rows[first_row + ti];
        double t = b->o.times[ti];
        progress_set(&b->pr, b->pr.done, true, "%s %s %s t=%g", sc, b->o.packs[p], st->name, t);
        while (glGetError() != GL_NO_ERROR) {}
        timing tm = time_frames(b, r, &tg, t, rw);
        rw->frames = tm.frames;
        rw->gpu_ms = tm.gpu_ms;
        rw->wall_ms = tm.wall_ms;
        rw->first_wall_ms = tm.first_wall_ms;
        rw->wall_spread = tm.wall_spread;
        render_target_read(&tg, rgba);
        GLenum ge = glGetError();
        if (ge != GL_NO_ERROR) rw->gl_error = ge;
        rw->ok = true;
        ref_entry *ref = get_ref(b, s, scene, ti);
        if (ref) {
            ref_fimage A = { rgba, b->o.w, b->o.h, 4 }, B = { ref->im.color, b->o.w, b->o.h, 3 };
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
        } else {
            snprintf(rw->note, sizeof rw->note, "no reference");
            long n = (long)b->o.w * b->o.h;
            for (long i = 0; i < n; i++)
                for (int c = 0; c < 3; c++) {
                    if (isnan(rgba[i * 4 + c])) { rw->nan_px++; break; }
                    if (isinf(rgba[i * 4 + c])) { rw->inf_px++; break; }
                }
        }
        if (b->o.images) write_images(b, rw, rgba, ref);
        progress_set(&b->pr, base + LOAD_WEIGHT + weight_each_time * (ti + 1), false, NULL);
    }
    /* the buffers the pack shows: its bench.txt `buffer` lines, else TARN_OUTPUT */
    if (rgba) measure_buffers(b, r, &tg, s, p, scene, first_row, rgba);
    free(rgba);
    render_target_destroy(&tg);
    render_destroy(r);
}

/* ---- the cost model ---- */

/* The sweep a pack's cost model is fitted from: its default setting on the
 * first scene at three image sizes (half, the run's, 1.5x a side) and
 * three water grids: 9 timed frames, medians as the run's. */
static const int COST_MESHES[] = { 64, 128, 256 };
static const double COST_SCALES[] = { 0.5, 1.0, 1.5 };
#define COST_SAMPLES 9

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
    render_desc rd = { .repo_root = b->root, .pack = b->o.packs[p], .samples = b->o.samples };
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
                                  b->axis == 1 ? tm.gpu_ms : tm.wall_ms };
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

/* The Pareto front's tolerances: two settings whose times differ by less
 * than BENCH_TIME_NOISE of their time (or their frames' spread, when
 * larger), and whose errors differ by less than BENCH_ERROR_TIE of their
 * error, tie (neither takes the other off the front). Measured on the
 * 2-core VM: two runs of the same setting differ by up to 15% in wall
 * time, never in error. */
#define BENCH_TIME_NOISE 0.2
#define BENCH_ERROR_TIE 0.01

static double axis_time(const bench *b, const summary *s) { return b->axis == 1 ? s->gpu_ms : s->wall_ms; }

static void summarise(bench *b) {
    b->sums = mem_zalloc((size_t)(b->nrows > 0 ? b->nrows : 1) * sizeof *b->sums);
    for (int i = 0; i < b->nrows; i++) {
        const row *r0 = &b->rows[i];
        if (r0->ti != 0) continue;
        summary *s = &b->sums[b->nsums++];
        s->scene = r0->scene;
        s->pack = r0->pack;
        s->setting = r0->setting;
        double gpu[MAX_TIMES], wall[MAX_TIMES];
        int ng = 0, nw = 0, ne = 0;
        double rmse = 0, psnr = 0, p95 = 0, share = 0, wrmse = 0, wpsnr = 0, off = 0;
        s->capped_share = NAN;
        int nw_err = 0;
        s->wall_spread = 0;
        double comp[REF_OUTPUT_COUNT] = { 0 };
        int ncomp[REF_OUTPUT_COUNT] = { 0 };
        s->ok = true;
        for (int j = i; j < b->nrows && j < i + b->o.ntimes; j++) {
            const row *r = &b->rows[j];
            s->ok &= r->ok;
            s->nan_px += r->nan_px + r->inf_px;
            if (isfinite(r->gpu_ms)) gpu[ng++] = r->gpu_ms;
            if (isfinite(r->wall_ms)) wall[nw++] = r->wall_ms;
            if (isfinite(r->wall_spread) && r->wall_spread > s->wall_spread) s->wall_spread = r->wall_spread;
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
                }
        }
        s->gpu_ms = median(gpu, ng);
        s->wall_ms = median(wall, nw);
        s->rmse = ne ? rmse / ne : NAN;
        s->water_rmse = nw_err ? wrmse / nw_err : NAN;
        s->water_psnr = nw_err ? wpsnr / nw_err : NAN;
        s->off_rmse = nw_err ? off / nw_err : NAN;
        s->psnr = ne ? psnr / ne : NAN;
        s->p95 = ne ? p95 / ne : NAN;
        s->over_share = ne ? share / ne : NAN;
        for (int m = 1; m < REF_OUTPUT_COUNT; m++) {
            s->has[m] = ncomp[m] > 0;
            s->comp[m] = ncomp[m] ? comp[m] / ncomp[m] : NAN;
        }
    }
    /* the Pareto front of each scene, over every pack */
    for (int sc = 0; sc < b->o.nscenes; sc++) {
        double x[1024], y[1024], dx[1024], dy[1024];
        bool on[1024];
        int idx[1024], n = 0;
        for (int i = 0; i < b->nsums && n < 1024; i++) {
            const summary *si = &b->sums[i];
            if (si->scene != sc) continue;
            x[n] = si->ok ? axis_time(b, si) : NAN;
            y[n] = isfinite(si->water_rmse) ? si->water_rmse : si->rmse;
            /* what a second run could move: the time by its frames' spread
             * (at least BENCH_TIME_NOISE: runs on a shared machine differ
             * more than frames within one run), the error by BENCH_ERROR_TIE
             * (it is deterministic; this is the precision it is read to) */
            dx[n] = x[n] * fmax(BENCH_TIME_NOISE, isfinite(si->wall_spread) ? si->wall_spread : 0);
            dy[n] = fmax(y[n] * BENCH_ERROR_TIE, 1e-5);
            idx[n++] = i;
        }
        plot_pareto_ties(x, y, dx, dy, n, on);
        for (int i = 0; i < n; i++) b->sums[idx[i]].pareto = on[i];
    }
}

/* ---- writing ---- */

static void json_num(strbuf *o, double v) {
    if (isnan(v)) strbuf_printf(o, "null");
    else if (isinf(v)) strbuf_printf(o, v > 0 ? "\"inf\"" : "\"-inf\"");
    else strbuf_printf(o, "%.9g", v);
}

static void json_str(strbuf *o, const char *s) {
    strbuf_printf(o, "\"");
    for (const unsigned char *c = (const unsigned char *)s; *c; c++) {
        if (*c == '"' || *c == '\\') strbuf_printf(o, "\\%c", *c);
        else if (*c < 0x20) strbuf_printf(o, "\\u%04x", *c);
        else strbuf_printf(o, "%c", *c);
    }
    strbuf_printf(o, "\"");
}

static void csv_num(strbuf *o, double v) {
    if (isnan(v)) strbuf_printf(o, ",");
    else if (isinf(v)) strbuf_printf(o, ",%s", v > 0 ? "inf" : "-inf");
    else strbuf_printf(o, ",%.9g", v);
}

static void csv_str(strbuf *o, const char *s, bool first) {
    strbuf_printf(o, first ? "\"" : ",\"");
    for (const char *c = s; *c; c++) strbuf_printf(o, *c == '"' ? "\"\"" : "%c", *c);
    strbuf_printf(o, "\"");
}


static bool write_csv(bench *b, const char *path) {
    strbuf o = { 0 };
    strbuf_printf(&o, "scene,pack,setting,time_s,width,height,frames,gpu_ms,wall_ms,first_frame_wall_ms,"
                  "floor_gpu_ms,floor_wall_ms,x_floor_gpu,x_floor_wall,water_rmse,water_psnr_db,water_pixels,"
                  "off_water_rmse,march_capped_share,rmse,psnr_db,mae,error_p95,error_p99,"
                  "max_abs,over_threshold_share,nan_pixels,inf_pixels,gl_error");
    for (int m = 1; m < REF_OUTPUT_COUNT; m++)
        strbuf_printf(&o, ",%s.median,%s.p95,%s.mean,%s.rel_mean,%s.rel_median", ref_buffer_for_output(m)->name, ref_buffer_for_output(m)->name,
                  ref_buffer_for_output(m)->name, ref_buffer_for_output(m)->name, ref_buffer_for_output(m)->name);
    strbuf_printf(&o, ",error,note\n");
    for (int i = 0; i < b->nrows; i++) {
        const row *r = &b->rows[i];
        char sc[256];
        stem(b->scene_abs[r->scene], sc, sizeof sc);
        csv_str(&o, sc, true);
        csv_str(&o, b->o.packs[r->pack], false);
        csv_str(&o, b->pb[r->pack].settings[r->setting].name, false);
        csv_num(&o, b->o.times[r->ti]);
        strbuf_printf(&o, ",%d,%d,%d", b->o.w, b->o.h, r->frames);
        csv_num(&o, r->gpu_ms);
        csv_num(&o, r->wall_ms);
        csv_num(&o, r->first_wall_ms);
        csv_num(&o, b->floor_gpu);
        csv_num(&o, b->floor_wall);
        csv_num(&o, r->gpu_ms / b->floor_gpu);
        csv_num(&o, r->wall_ms / b->floor_wall);
        csv_num(&o, r->water_rmse);
        csv_num(&o, r->water_psnr);
        strbuf_printf(&o, ",%ld", r->water_px);
        csv_num(&o, r->off_rmse);
        csv_num(&o, r->capped_share);
        csv_num(&o, r->rmse);
        csv_num(&o, r->psnr);
        csv_num(&o, r->mae);
        csv_num(&o, r->p95);
        csv_num(&o, r->p99);
        csv_num(&o, r->max_abs);
        csv_num(&o, r->over_share);
        strbuf_printf(&o, ",%ld,%ld,%u", r->nan_px, r->inf_px, r->gl_error);
        for (int m = 1; m < REF_OUTPUT_COUNT; m++) {
            csv_num(&o, r->has[m] ? r->comp_median[m] : NAN);
            csv_num(&o, r->has[m] ? r->comp_p95[m] : NAN);
            csv_num(&o, r->has[m] ? r->comp_mean[m] : NAN);
            csv_num(&o, r->has[m] ? r->comp_rel_mean[m] : NAN);
            csv_num(&o, r->has[m] ? r->comp_rel_median[m] : NAN);
        }
        csv_str(&o, r->error, false);
        csv_str(&o, r->note, false);
        strbuf_printf(&o, "\n");
    }
    bool ok = o.s && write_text(path, o.s);
    free(o.s);
    return ok;
}

/* One row per pass: scene, pack, setting, time, pass, its median GPU time. */
static bool write_passes_csv(bench *b, const char *path) {
    strbuf o = { 0 };
    strbuf_printf(&o, "scene,pack,setting,time_s,pass,gpu_ms\n");
    for (int i = 0; i < b->nrows; i++) {
        const row *r = &b->rows[i];
        char sc[256];
        stem(b->scene_abs[r->scene], sc, sizeof sc);
        for (int k = 0; k < r->npasses; k++) {
            csv_str(&o, sc, true);
            csv_str(&o, b->o.packs[r->pack], false);
            csv_str(&o, b->pb[r->pack].settings[r->setting].name, false);
            csv_num(&o, b->o.times[r->ti]);
            csv_str(&o, r->pass_name[k], false);
            csv_num(&o, r->pass_ms[k]);
            strbuf_printf(&o, "\n");
        }
    }
    bool ok = o.s && write_text(path, o.s);
    free(o.s);
    return ok;
}

static bool write_json(bench *b, const char *path) {
    strbuf o = { 0 };
    strbuf_printf(&o, "{\n  \"machine\": {\"cpu\": ");
    json_str(&o, b->cpu);
    strbuf_printf(&o, ", \"cores\": %d, \"gl_renderer\": ", b->cores);
    json_str(&o, b->gl_renderer);
    strbuf_printf(&o, ", \"gl_version\": ");
    json_str(&o, b->gl_version);
    strbuf_printf(&o, ", \"cpu_rasteriser\": %s},\n", b->cpu_raster ? "true" : "false");
    strbuf_printf(&o, "  \"run\": {\"started\": \"%s\", \"seconds\": %.1f, \"width\": %d, \"height\": %d, \"times\": [",
              b->started, b->seconds, b->o.w, b->o.h);
    for (int i = 0; i < b->o.ntimes; i++) strbuf_printf(&o, "%s%.9g", i ? ", " : "", b->o.times[i]);
    strbuf_printf(&o, "], \"max_frames\": %d, \"frame_budget_s\": %g, \"warmup\": %d, \"time_axis\": \"%s\", "
                  "\"references_rendered\": %d, \"references_cached\": %d},\n",
              b->o.frames, b->o.frame_budget, b->o.warmup, b->axis == 1 ? "gpu" : "wall", b->refs_rendered,
              b->refs_cached);
    strbuf_printf(&o, "  \"msaa\": %d, \"reference_spp\": %d, \"reference_positions\": [", b->o.samples_used,
                  b->o.ref.spp);
    for (int k = 0; k < b->o.ref.nsamples; k++)
        strbuf_printf(&o, "%s[%.9g, %.9g]", k ? ", " : "", b->o.ref.samples[k][0], b->o.ref.samples[k][1]);
    strbuf_printf(&o, "],\n");
    strbuf_printf(&o, "  \"floor\": {\"gpu_ms\": ");
    json_num(&o, b->floor_gpu);
    strbuf_printf(&o, ", \"wall_ms\": ");
    json_num(&o, b->floor_wall);
    strbuf_printf(&o, "},\n  \"summary\": [\n");
    for (int i = 0; i < b->nsums; i++) {
        const summary *s = &b->sums[i];
        char sc[256];
        stem(b->scene_abs[s->scene], sc, sizeof sc);
        strbuf_printf(&o, "    {\"scene\": ");
        json_str(&o, sc);
        strbuf_printf(&o, ", \"pack\": ");
        json_str(&o, b->o.packs[s->pack]);
        strbuf_printf(&o, ", \"setting\": ");
        json_str(&o, b->pb[s->pack].settings[s->setting].name);
        strbuf_printf(&o, ", \"ok\": %s, \"gpu_ms\": ", s->ok ? "true" : "false");
        json_num(&o, s->gpu_ms);
        strbuf_printf(&o, ", \"wall_ms\": ");
        json_num(&o, s->wall_ms);
        strbuf_printf(&o, ", \"x_floor_gpu\": ");
        json_num(&o, s->gpu_ms / b->floor_gpu);
        strbuf_printf(&o, ", \"x_floor_wall\": ");
        json_num(&o, s->wall_ms / b->floor_wall);
        strbuf_printf(&o, ", \"water_rmse\": ");
        json_num(&o, s->water_rmse);
        strbuf_printf(&o, ", \"water_psnr_db\": ");
        json_num(&o, s->water_psnr);
        strbuf_printf(&o, ", \"off_water_rmse\": ");
        json_num(&o, s->off_rmse);
        strbuf_printf(&o, ", \"march_capped_share\": ");
        json_num(&o, s->capped_share);
        strbuf_printf(&o, ", \"rmse\": ");
        json_num(&o, s->rmse);
        strbuf_printf(&o, ", \"psnr_db\": ");
        json_num(&o, s->psnr);
        strbuf_printf(&o, ", \"error_p95\": ");
        json_num(&o, s->p95);
        strbuf_printf(&o, ", \"over_threshold_share\": ");
        json_num(&o, s->over_share);
        strbuf_printf(&o, ", \"refract_hit_p95_m\": ");
        json_num(&o, s->has[1] ? s->comp[1] : NAN);
        strbuf_printf(&o, ", \"fresnel_mae\": ");
        json_num(&o, s->has[2] ? s->comp[2] : NAN);
        strbuf_printf(&o, ", \"irradiance_rel_median\": ");
        json_num(&o, s->has[3] ? s->comp[3] : NAN);
        strbuf_printf(&o, ", \"depth_mae\": ");
        json_num(&o, s->has[4] ? s->comp[4] : NAN);
        strbuf_printf(&o, ", \"nonfinite_pixels\": %ld, \"pareto\": %s}%s\n", s->nan_px, s->pareto ? "true" : "false",
                  i + 1 < b->nsums ? "," : "");
    }
    strbuf_printf(&o, "  ],\n  \"rows\": [\n");
    for (int i = 0; i < b->nrows; i++) {
        const row *r = &b->rows[i];
        char sc[256];
        stem(b->scene_abs[r->scene], sc, sizeof sc);
        strbuf_printf(&o, "    {\"scene\": ");
        json_str(&o, sc);
        strbuf_printf(&o, ", \"pack\": ");
        json_str(&o, b->o.packs[r->pack]);
        strbuf_printf(&o, ", \"setting\": ");
        json_str(&o, b->pb[r->pack].settings[r->setting].name);
        strbuf_printf(&o, ", \"time_s\": %.9g, \"ok\": %s, \"frames\": %d, \"gpu_ms\": ", b->o.times[r->ti],
                  r->ok ? "true" : "false", r->frames);
        json_num(&o, r->gpu_ms);
        strbuf_printf(&o, ", \"wall_ms\": ");
        json_num(&o, r->wall_ms);
        strbuf_printf(&o, ", \"first_frame_wall_ms\": ");
        json_num(&o, r->first_wall_ms);
        strbuf_printf(&o, ", \"water_rmse\": ");
        json_num(&o, r->water_rmse);
        strbuf_printf(&o, ", \"water_psnr_db\": ");
        json_num(&o, r->water_psnr);
        strbuf_printf(&o, ", \"water_pixels\": %ld", r->water_px);
        strbuf_printf(&o, ", \"off_water_rmse\": ");
        json_num(&o, r->off_rmse);
        strbuf_printf(&o, ", \"march_capped_share\": ");
        json_num(&o, r->capped_share);
        strbuf_printf(&o, ", \"rmse\": ");
        json_num(&o, r->rmse);
        strbuf_printf(&o, ", \"psnr_db\": ");
        json_num(&o, r->psnr);
        strbuf_printf(&o, ", \"mae\": ");
        json_num(&o, r->mae);
        strbuf_printf(&o, ", \"error_p95\": ");
        json_num(&o, r->p95);
        strbuf_printf(&o, ", \"error_p99\": ");
        json_num(&o, r->p99);
        strbuf_printf(&o, ", \"max_abs\": ");
        json_num(&o, r->max_abs);
        strbuf_printf(&o, ", \"over_threshold_share\": ");
        json_num(&o, r->over_share);
        strbuf_printf(&o, ", \"nan_pixels\": %ld, \"inf_pixels\": %ld, \"gl_error\": %u, \"buffers\": {", r->nan_px,
                  r->inf_px, r->gl_error);
        bool first = true;
        for (int m = 1; m < REF_OUTPUT_COUNT; m++) {
            if (!r->has[m]) continue;
            strbuf_printf(&o, "%s\"%s\": {\"median\": ", first ? "" : ", ", ref_buffer_for_output(m)->name);
            json_num(&o, r->comp_median[m]);
            strbuf_printf(&o, ", \"p95\": ");
            json_num(&o, r->comp_p95[m]);
            strbuf_printf(&o, ", \"mean\": ");
            json_num(&o, r->comp_mean[m]);
            strbuf_printf(&o, ", \"rel_mean\": ");
            json_num(&o, r->comp_rel_mean[m]);
            strbuf_printf(&o, ", \"rel_median\": ");
            json_num(&o, r->comp_rel_median[m]);
            strbuf_printf(&o, "}");
            first = false;
        }
        strbuf_printf(&o, "}, \"passes\": [");
        for (int k = 0; k < r->npasses; k++) {
            strbuf_printf(&o, "%s{\"pass\": ", k ? ", " : "");
            json_str(&o, r->pass_name[k]);
            strbuf_printf(&o, ", \"gpu_ms\": ");
            json_num(&o, r->pass_ms[k]);
            strbuf_printf(&o, "}");
        }
        strbuf_printf(&o, "], \"error\": ");
        json_str(&o, r->error);
        strbuf_printf(&o, ", \"note\": ");
        json_str(&o, r->note);
        strbuf_printf(&o, "}%s\n", i + 1 < b->nrows ? "," : "");
    }
    strbuf_printf(&o, "  ],\n  \"cost_models\": [");
    int nc = 0;
    for (int p = 0; p < b->o.npacks; p++) {
        if (!b->has_cost[p]) continue;
        const cost_model *m = &b->cost[p];
        strbuf_printf(&o, "%s\n    {\"pack\": ", nc++ ? "," : "");
        json_str(&o, b->o.packs[p]);
        strbuf_printf(&o, ", \"a_ms\": %.6g, \"b_ms_per_mpixel\": %.6g, \"c_ms_per_kvertex\": %.6g, \"r2\": %.6g, "
                      "\"residual_ms\": %.6g, \"samples\": %d}", m->a, m->b, m->c, m->r2, m->rms_residual, m->n);
    }
    strbuf_printf(&o, "%s]\n}\n", nc ? "\n  " : "");
    bool ok = o.s && write_text(path, o.s);
    free(o.s);
    return ok;
}

static void md_num(strbuf *o, const char *fmt, double v) {
    if (isnan(v)) strbuf_printf(o, " – |");
    else if (isinf(v)) strbuf_printf(o, " ∞ |");
    else {
        strbuf_printf(o, " ");
        strbuf_printf(o, fmt, v);
        strbuf_printf(o, " |");
    }
}

/* The report: machine, run, floor, a table per scene, the plot. plot_dir is
 * how the Markdown names the plots' directory ("" for beside it). */
/* The cost models: a line a pack, and what its default would cost at 1080p. */
static void cost_md(bench *b, strbuf *o) {
    char sc[256];
    stem(b->scene_abs[0], sc, sizeof sc);
    strbuf_printf(o, "**Cost model** (%s, each pack's default; %s ms a frame = a + b·Mpixels + c·kvertices of the "
                  "water grid, least squares over %d frames: %dx%d, %dx%d and %dx%d, each with WaterMesh 64, 128 "
                  "and 256; the last column extrapolates far beyond them, so read it as an order of magnitude):\n\n",
                  sc, b->axis == 1 ? "GPU" : "wall", COST_SAMPLES, (int)lround(b->o.w * COST_SCALES[0]),
                  (int)lround(b->o.h * COST_SCALES[0]), b->o.w, b->o.h, (int)lround(b->o.w * COST_SCALES[2]),
                  (int)lround(b->o.h * COST_SCALES[2]));
    strbuf_printf(o, "| pack | a ms | b ms/Mpixel | c ms/kvertex | R² | residual ms | 1920x1080, mesh 256 |\n"
                  "|---|---:|---:|---:|---:|---:|---:|\n");
    for (int p = 0; p < b->o.npacks; p++) {
        if (!b->has_cost[p]) {
            strbuf_printf(o, "| %s | not fitted: %s | | | | | |\n", b->o.packs[p], b->cost_note[p]);
            continue;
        }
        const cost_model *m = &b->cost[p];
        strbuf_printf(o, "| %s | %.1f | %.1f | %.3f | %.3f | %.1f | %.0f ms |\n", b->o.packs[p], m->a, m->b, m->c,
                      m->r2, m->rms_residual, cost_model_predict(m, 1920 * 1080 / 1e6, cost_model_grid_kvertices(256)));
    }
    strbuf_printf(o, "\n");
}

static void report_md(bench *b, strbuf *o, const char *plot_prefix) {
    strbuf_printf(o, "Measured %s by `tarn bench` in %.0f s (%d:%02d; references: %d rendered, %d read from "
                 "the cache).\n\n",
              b->started, b->seconds, (int)(b->seconds / 60), (int)fmod(b->seconds, 60), b->refs_rendered,
              b->refs_cached);
    strbuf_printf(o, "| machine | |\n|---|---|\n| CPU | %s (%d cores online) |\n| GL renderer | %s |\n"
                 "| GL version | %s |\n\n",
              b->cpu, b->cores, b->gl_renderer, b->gl_version);
    strbuf_printf(o, "Images %dx%d at t =", b->o.w, b->o.h);
    for (int i = 0; i < b->o.ntimes; i++) strbuf_printf(o, "%s %g", i ? "," : "", b->o.times[i]);
    strbuf_printf(o, " s; per setting and time %d warm-up frame(s), then up to %d timed frames (at least 3, "
                 "stopping after %.3g s); medians. Error: the mean over the times of the colour error against "
                 "the CPU reference of the same frame (linear RGB), first over the pixels where the reference "
                 "sees water (what ranks the techniques and decides the Pareto front), then off the water "
                 "and over the whole frame. Settings whose times agree within their run-to-run noise "
                 "(%.0f%%, or their frames' spread) and whose water errors agree within %.0f%% tie: both "
                 "stay on the front.\n\n",
              b->o.warmup, b->o.frames, b->o.frame_budget, 100 * BENCH_TIME_NOISE, 100 * BENCH_ERROR_TIE);
    char aa[32] = "off";
    if (b->o.samples_used > 1) snprintf(aa, sizeof aa, "MSAA %dx", b->o.samples_used);
    char subs[96];
    refcache_describe_samples(&b->o.ref, subs, (int)sizeof subs);
    strbuf_printf(o, "Anti-aliasing: %s; the reference takes %s%s. Per-pixel "
                 "buffers (hit point, Fresnel, irradiance, depth) are drawn without MSAA and compared with the "
                 "reference's pixel-centre buffers.\n\n",
              aa, subs, b->o.spp_matched ? ", to match" : " (--ref-spp)");
    if (b->cpu_raster)
        strbuf_printf(o, "**%s is a CPU rasteriser**: its GPU timestamps are taken when commands are issued, "
                     "not when pixels are drawn, so the GPU column is not meaningful here. The wall time "
                     "(after `glFinish`) is what the plot and the Pareto front use.\n\n",
                  b->gl_renderer);
    strbuf_printf(o, "Cost floor (a full-screen pass with one texture fetch): %.3f ms GPU, %.3f ms wall. "
                 "\"× floor\" is a setting's %s time over the floor's.\n\n",
              b->floor_gpu, b->floor_wall, b->axis == 1 ? "GPU" : "wall");
    for (int sc = 0; sc < b->o.nscenes; sc++) {
        char st[256];
        stem(b->scene_abs[sc], st, sizeof st);
        strbuf_printf(o, "### %s\n\n", st);
        strbuf_printf(o, "| pack | setting | GPU ms | wall ms | × floor | water RMSE | water PSNR dB | off-water RMSE | "
                     "frame RMSE | p95 error | > 0.05 | hit p95 m | march capped | Fresnel MAE | irradiance rel. median | "
                     "depth MAE m | Pareto |\n"
                     "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|:-:|\n");
        for (int i = 0; i < b->nsums; i++) {
            const summary *s = &b->sums[i];
            if (s->scene != sc) continue;
            strbuf_printf(o, "| %s | %s |", b->o.packs[s->pack], b->pb[s->pack].settings[s->setting].name);
            if (!s->ok) {
                const row *r = NULL;
                for (int j = 0; j < b->nrows; j++)
                    if (b->rows[j].scene == sc && b->rows[j].pack == s->pack && b->rows[j].setting == s->setting)
                        r = &b->rows[j];
                strbuf_printf(o, " failed: %s | | | | | | | | | | | | | | | |\n", r && r->error[0] ? r->error : "?");
                continue;
            }
            md_num(o, "%.2f", s->gpu_ms);
            md_num(o, "%.1f", s->wall_ms);
            md_num(o, "%.1f", axis_time(b, s) / (b->axis == 1 ? b->floor_gpu : b->floor_wall));
            md_num(o, "%.4f", s->water_rmse);
            md_num(o, "%.1f", s->water_psnr);
            md_num(o, "%.4f", s->off_rmse);
            md_num(o, "%.4f", s->rmse);
            md_num(o, "%.4f", s->p95);
            md_num(o, "%.1f%%", 100 * s->over_share);
            md_num(o, "%.3f", s->has[1] ? s->comp[1] : NAN);
            md_num(o, "%.1f%%", 100 * s->capped_share);
            md_num(o, "%.4f", s->has[2] ? s->comp[2] : NAN);
            md_num(o, "%.3f", s->has[3] ? s->comp[3] : NAN);
            md_num(o, "%.3f", s->has[4] ? s->comp[4] : NAN);
            strbuf_printf(o, " %s |\n", s->pareto ? "●" : "");
            if (s->nan_px) strbuf_printf(o, "| | ⚠ %ld non-finite pixels | | | | | | | | | | | | | | | |\n", s->nan_px);
        }
        strbuf_printf(o, "\nGPU time per pass (median, first time; `pass:LINE units` is the glib line of the "
                     "RenderToTexture that begins it, `screen:LINE` what is drawn to the screen):\n\n");
        for (int i = 0; i < b->nrows; i++) {
            const row *r = &b->rows[i];
            if (r->scene != sc || r->ti != 0 || !r->npasses) continue;
            strbuf_printf(o, "- %s / %s:", b->o.packs[r->pack], b->pb[r->pack].settings[r->setting].name);
            for (int k = 0; k < r->npasses; k++)
                strbuf_printf(o, "%s `%s` %.2f ms", k ? "," : "", r->pass_name[k], r->pass_ms[k]);
            strbuf_printf(o, "\n");
        }
        strbuf_printf(o, "\n![speed against error, %s](%splot-%s.png)\n\n", st, plot_prefix, st);
    }
    if (b->o.cost_model) {
        cost_md(b, o);
        bench_ocean_md(&b->ocean, b->ocean_scene, o);
    }
    strbuf_printf(o, "– : not measured: the pack shows no such buffer (a `buffer` line in its bench.txt, or "
                 "`Define %s`; docs/benchmark.md).\n",
              BENCH_OUTPUT_DEFINE);
}

static bool write_plot(bench *b, int sc, const char *path) {
    plot_series series[PACKSET_MAX];
    plot_point *pts = mem_zalloc((size_t)(b->nsums > 0 ? b->nsums : 1) * sizeof *pts);
    int np = 0, ns = 0;
    for (int p = 0; p < b->o.npacks; p++) {
        plot_series *se = &series[ns];
        se->name = b->o.packs[p];
        if (b->pb[p].has_colour) memcpy(se->rgb, b->pb[p].colour, sizeof se->rgb);
        else packset_palette(p, se->rgb);
        se->pts = pts + np;
        se->n = 0;
        for (int i = 0; i < b->nsums; i++) {
            const summary *s = &b->sums[i];
            if (s->scene != sc || s->pack != p || !s->ok) continue;
            double e = isfinite(s->water_rmse) ? s->water_rmse : s->rmse;
            pts[np++] = (plot_point){ axis_time(b, s), e, b->pb[p].settings[s->setting].name, s->pareto };
            se->n++;
        }
        ns++;
    }
    char st[256], title[512], sub[512], floor[64];
    stem(b->scene_abs[sc], st, sizeof st);
    snprintf(title, sizeof title, "%s %dx%d: speed against error", st, b->o.w, b->o.h);
    snprintf(sub, sizeof sub, "%.60s", b->gl_renderer);
    snprintf(floor, sizeof floor, "floor %.3g ms", b->axis == 1 ? b->floor_gpu : b->floor_wall);
    plot_chart c = { .title = title, .subtitle = sub,
                     .xlabel = b->axis == 1 ? "GPU time per frame, ms (log)" : "wall time per frame, ms (log)",
                     .ylabel = "water RMSE vs reference (log)", .series = series, .nseries = ns,
                     .floor_x = b->axis == 1 ? b->floor_gpu : b->floor_wall, .floor_label = floor };
    img im;
    bool ok = plot_speed_error(&c, &im);
    char err[512];
    if (ok) ok = img_write(path, &im, err, sizeof err);
    img_free(&im);
    free(pts);
    return ok;
}

/* text with what lies between the markers replaced by content (or, when
 * text has no such markers, with a section `heading` holding them added at
 * its end). A new string. */
static char *replace_section(const char *text, const char *begin, const char *end, const char *heading,
                             const char *content) {
    strbuf o = { 0 };
    const char *bp = strstr(text, begin), *ep = bp ? strstr(bp, end) : NULL;
    if (bp && ep) strbuf_printf(&o, "%.*s%s\n%s%s", (int)(bp - text), text, begin, content, ep);
    else strbuf_printf(&o, "%s\n%s\n\n%s\n%s%s\n", text, heading, begin, content, end);
    return o.s;
}


/* The hard-case bounds of every pack (bounds.txt, else the built-in table),
 * a row per scenes/hard case, with the reasons where a pack has none. */
static void bounds_md(bench *b, strbuf *o) {
    char dir[PATH_LEN + 16];
    fmt(dir, sizeof dir, "%s/scenes/hard", b->root);
    char *cases[128];
    int nc = 0;
    DIR *d = opendir(dir);
    struct dirent *e;
    while (d && (e = readdir(d)) && nc < 128) {
        size_t len = strlen(e->d_name);
        if (len > 5 && strcmp(e->d_name + len - 5, ".glib") == 0) cases[nc++] = mem_strndup(e->d_name, len - 5);
    }
    if (d) closedir(d);
    qsort(cases, (size_t)nc, sizeof *cases, cmp_str_ptr);
    packset_name packs[PACKSET_MAX];
    int np = packset_list(b->root, packs, PACKSET_MAX);
    packset_bounds pb[PACKSET_MAX];
    for (int p = 0; p < np; p++) packset_bounds_load(b->root, packs[p], &pb[p], NULL, 0);
    strbuf_printf(o, "RMSE (linear RGB) that tests/test_hard_cases.c allows, 96x54 at t = 1 s: from each pack's "
                 "bounds.txt, else (*in italics*) the built-in table of viewer/scene/packset.c. Written by `tarn bench "
                 "--docs` from the files as they were then.\n\n| case |");
    for (int p = 0; p < np; p++) strbuf_printf(o, " %s |", packs[p]);
    strbuf_printf(o, "\n|---|");
    for (int p = 0; p < np; p++) strbuf_printf(o, "---:|");
    strbuf_printf(o, "\n");
    strbuf notes = { 0 };
    int nnotes = 0;
    for (int c = 0; c < nc; c++) {
        strbuf_printf(o, "| %s |", cases[c]);
        for (int p = 0; p < np; p++) {
            const char *from = NULL;
            const packset_bound *bd = packset_bound_resolve(&pb[p], cases[c], &from);
            bool builtin = from && strcmp(from, "built-in") == 0;
            if (!bd) {
                strbuf_printf(o, " – |");
            } else if (bd->max_rmse >= 0) {
                strbuf_printf(o, builtin ? " *%.3g* |" : " %.3g |", bd->max_rmse);
            } else {
                nnotes++;
                strbuf_printf(o, builtin ? " *none* (%d) |" : " none (%d) |", nnotes);
                strbuf_printf(&notes, "%d. %s, %s: %s\n", nnotes, packs[p], cases[c],
                          bd->why[0] ? bd->why : "(no reason given)");
            }
        }
        strbuf_printf(o, "\n");
    }
    if (notes.s) strbuf_printf(o, "\nWhere a pack holds no bound:\n\n%s", notes.s);
    free(notes.s);
    for (int p = 0; p < np; p++) packset_bounds_free(&pb[p]);
    for (int c = 0; c < nc; c++) free(cases[c]);
}

/* Writes the report and the bounds between their markers in the docs page
 * (adding the sections when the page has no markers), the plots beside it. */
static bool write_docs(bench *b, const char *path) {
    strbuf gen = { 0 };
    char dir[PATH_LEN];
    snprintf(dir, sizeof dir, "%s", path);
    char *slash = strrchr(dir, '/');
    if (slash) *slash = '\0';
    else snprintf(dir, sizeof dir, ".");
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    char prefix[256];
    snprintf(prefix, sizeof prefix, "%.*s-", (int)(strcspn(base, ".")), base);
    report_md(b, &gen, prefix);
    for (int sc = 0; sc < b->o.nscenes; sc++) {
        char st[256], pp[PATH_LEN + 300];
        stem(b->scene_abs[sc], st, sizeof st);
        fmt(pp, sizeof pp, "%s/%splot-%s.png", dir, prefix, st);
        write_plot(b, sc, pp);
    }
    FILE *f = fopen(path, "r");
    char *old = NULL;
    if (f) {
        old = mem_alloc(1 << 20);
        size_t n = fread(old, 1, (1 << 20) - 1, f);
        old[n] = '\0';
        fclose(f);
    }
    strbuf bounds = { 0 };
    bounds_md(b, &bounds);
    char *mid = replace_section(old ? old : "# Benchmark\n", "<!-- bench:begin -->", "<!-- bench:end -->",
                                "## Latest results", gen.s ? gen.s : "");
    char *page = mid ? replace_section(mid, "<!-- bounds:begin -->", "<!-- bounds:end -->", "## Hard-case bounds",
                                       bounds.s ? bounds.s : "")
                     : NULL;
    bool ok = page && write_text(path, page);
    free(page);
    free(mid);
    free(bounds.s);
    free(gen.s);
    free(old);
    return ok;
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
    double per_time = 0.5 * b->o.warmup + b->o.frame_budget + 0.3;
    b->pr.total = ref_total_weight(b) + 2 + (double)b->o.nscenes * nsettings * (LOAD_WEIGHT + per_time * b->o.ntimes);
    if (!b->o.quiet)
        fprintf(stderr, "tarn bench: %d scene(s) x %d pack(s), %d setting(s), %d time(s) at %dx%d on %s\n",
                b->o.nscenes, b->o.npacks, nsettings, b->o.ntimes, b->o.w, b->o.h, b->gl_renderer);
    progress_set(&b->pr, 0, true, "cost floor");
    if (!measure_floor(b)) {
        fprintf(stderr, "tarn bench: the cost floor could not be measured\n");
        b->failures++;
    }
    progress_set(&b->pr, 2, true, NULL);
    for (int s = 0; s < b->o.nscenes; s++)
        for (int p = 0; p < b->o.npacks; p++)
            for (int k = 0; k < b->pb[p].n; k++) measure_setting(b, s, p, k, per_time);
    for (int p = 0; p < b->o.npacks && b->o.cost_model; p++) measure_cost(b, p);
    if (b->o.cost_model) measure_ocean(b);
    b->seconds = clock_now_s() - t_start;
    progress_set(&b->pr, b->pr.total, true, "done");
    if (b->pr.tty && !b->o.quiet) fputc('\n', stderr);

    summarise(b);
    char path[PATH_LEN + 64];
    snprintf(path, sizeof path, "%s/bench.csv", b->o.out);
    bool ok = write_csv(b, path);
    snprintf(path, sizeof path, "%s/passes.csv", b->o.out);
    ok &= write_passes_csv(b, path);
    snprintf(path, sizeof path, "%s/bench.json", b->o.out);
    ok &= write_json(b, path);
    strbuf md = { 0 };
    strbuf_printf(&md, "# tarn bench\n\n");
    report_md(b, &md, "");
    snprintf(path, sizeof path, "%s/report.md", b->o.out);
    ok &= md.s && write_text(path, md.s);
    for (int sc = 0; sc < b->o.nscenes; sc++) {
        char st[256];
        stem(b->scene_abs[sc], st, sizeof st);
        snprintf(path, sizeof path, "%s/plot-%s.png", b->o.out, st);
        ok &= write_plot(b, sc, path);
    }
    if (b->o.docs && !write_docs(b, b->o.docs)) {
        fprintf(stderr, "tarn bench: cannot write %s\n", b->o.docs);
        ok = false;
    }
    if (!ok) {
        fprintf(stderr, "tarn bench: cannot write the results in %s\n", b->o.out);
        b->failures++;
    }
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
