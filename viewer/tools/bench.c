/* bench: `tarn bench`, speed against error (see bench.h, docs/benchmark.md):
 * the command. The desc resolved into a run's options, the machine, the
 * run in order, and the helpers every part uses (bench_int.h). The parts:
 * bench_progress.c (the progress bar), bench_refs.c (the references),
 * bench_timing.c (timed frames, the cost floor), bench_error.c (a frame's
 * error), bench_measure.c (a scene's settings), bench_cost.c (the cost
 * model), bench_summary.c (the summaries), and the writers (bench_csv.c,
 * bench_json.c, bench_report.c). */
#include "util.h"
#include "strbuf.h"
#include "bench_int.h"

#include <GL/gl.h>
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
#include "render.h"
#include "file.h"
#include "mem.h"

/* the median of v (NAN when empty: "not measured") */
double bench_median(double *v, int n) { return n <= 0 ? NAN : median_double(v, (size_t)n); }

/* snprintf for paths: a path too long for its buffer is cut (and then
 * not found), never overflowed. */
void bench_fmt(char *out, size_t len, const char *f, ...) {
    va_list ap;
    va_start(ap, f);
    vsnprintf(out, len, f, ap);
    va_end(ap);
}

/* mkdir -p, quietly: a folder that cannot be made shows up as a file
 * that cannot be written, with its path. */
bool bench_mkdirs(const char *dir) { return file_mkdir_p(dir, NULL, 0); }

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

/* Writes text to path and frees it. */
bool bench_write_strbuf(const char *path, strbuf *text) {
    bool ok = text->s && bench_write_text(path, text->s);
    free(text->s);
    text->s = NULL;
    return ok;
}

void bench_first_line(const char *text, char *out, size_t len) {
    size_t n = strcspn(text, "\n");
    snprintf(out, len, "%.*s", (int)n, text);
}

const char *bench_setting_name(const bench *b, int pack, int setting) { return b->pb[pack].settings[setting].name; }

/* /proc/loadavg's three figures (NaN where it cannot be read) */
static void loadavg(double out[3]) {
    out[0] = out[1] = out[2] = NAN;
    FILE *f = fopen("/proc/loadavg", "r");
    if (!f) return;
    if (fscanf(f, "%lf %lf %lf", &out[0], &out[1], &out[2]) != 3) out[0] = out[1] = out[2] = NAN;
    fclose(f);
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
            bench_fmt(alt, sizeof alt, "%s/%s", b->root, p);
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
    char err[MSG_MAX] = "";
    for (int p = 0; p < b->o.npacks; p++) {
        err[0] = '\0';
        if (!packset_bench_load(b->root, b->o.packs[p], &b->pb[p], err, sizeof err)) fputs(err, stderr);
    }
    if (!bench_mkdirs(b->o.out)) {
        fprintf(stderr, "tarn bench: cannot create %s: %s\n", b->o.out, strerror(errno));
        for (int p = 0; p < b->o.npacks; p++) packset_bench_free(&b->pb[p]);
        free(b);
        return TARN_EXIT_INPUT;
    }
    char sdir[PATH_LEN + 16];
    snprintf(sdir, sizeof sdir, "%s/scenes", b->o.out);
    bench_mkdirs(sdir);
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
    bench_prepare_refs(b);

    /* progress weights: a frame is 1; a reference, a load, the floor */
    int nsettings = 0;
    for (int p = 0; p < b->o.npacks; p++) nsettings += b->pb[p].n;
    double per_time = 0.5 * b->o.warmup + b->o.frame_budget + 0.3 + 1.0 /* FLIP */;
    double per_setting = BENCH_LOAD_WEIGHT + (b->o.uncertainty ? 2.0 : 0) + 0.1 * b->o.seq_frames;
    b->pr.total = bench_ref_total_weight(b) + 2 +
                  (double)b->o.nscenes * nsettings * (per_setting + per_time * b->o.ntimes);
    if (!b->o.quiet)
        fprintf(stderr, "tarn bench: %d scene(s) x %d pack(s), %d setting(s), %d time(s) at %dx%d on %s\n",
                b->o.nscenes, b->o.npacks, nsettings, b->o.ntimes, b->o.w, b->o.h, b->gl_renderer);
    bench_progress_set(&b->pr, 0, true, "cost floor");
    if (!bench_measure_floor(b)) {
        fprintf(stderr, "tarn bench: the cost floor could not be measured\n");
        b->failures++;
    }
    bench_progress_set(&b->pr, 2, true, NULL);
    for (int s = 0; s < b->o.nscenes; s++) bench_measure_scene(b, s, per_time);
    for (int p = 0; p < b->o.npacks && b->o.cost_model; p++) bench_measure_cost(b, p);
    if (b->o.cost_model) bench_measure_ocean(b);
    loadavg(b->load_after);
    b->seconds = clock_now_s() - t_start;
    bench_progress_set(&b->pr, b->pr.total, true, "done");
    if (b->pr.tty && !b->o.quiet) fputc('\n', stderr);

    bench_summarise(b);
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
