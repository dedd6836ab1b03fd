/* bench_refs: the reference frames a `tarn bench` run needs (bench_int.h):
 * each kind's options (REFK_*), registered up front for the progress bar,
 * then rendered or read from the cache on first use. */
#include "bench_int.h"
#include "strbuf.h"

#include <stdio.h>
#include <string.h>

#include "mem.h"

const char *bench_wrapper_path(bench *b, int s, int p, int k, char *out, size_t len) {
    const packset_setting *st = &b->pb[p].settings[k];
    char lines[4096];
    if (packset_scene_lines(st, lines, sizeof lines) == 0) return b->scene_abs[s];
    char sc[256];
    bench_stem(b->scene_abs[s], sc, sizeof sc);
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
    char err[MSG_MAX] = "";
    if (!refcache_key(scene, w, h, t, &o, &key, err, sizeof err) || find_ref(b, key)) return;
    char named[PATH_LEN], sc[256];
    bench_stem(b->scene_abs[s], sc, sizeof sc);
    bench_fmt(named, sizeof named, "%s/%s.glib", b->ref_dir, sc);
    bool cached = refcache_cached(b->ref_dir, scene, named, w, h, t, &o);
    b->refs = mem_realloc(b->refs, (size_t)(b->nrefs + 1) * sizeof *b->refs);
    ref_entry *e = &b->refs[b->nrefs++];
    memset(e, 0, sizeof *e);
    e->key = key;
    e->kind = kind;
    e->weight = cached ? 0.2 : ref_weight(b, &o, w, h);
}

double bench_seq_time(const bench *b, int i) { return b->o.times[0] + i / b->o.seq_fps; }

/* Keys of every reference the run needs; renders or reads each once. */
void bench_prepare_refs(bench *b) {
    for (int s = 0; s < b->o.nscenes; s++)
        for (int p = 0; p < b->o.npacks; p++)
            for (int k = 0; k < b->pb[p].n; k++) {
                char wp[PATH_LEN], err[2048] = "";
                const char *scene = bench_wrapper_path(b, s, p, k, wp, sizeof wp);
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
                    want_ref(b, s, scene, REFK_SEQ, b->o.seq_w, b->o.seq_h, bench_seq_time(b, i));
            }
}

double bench_ref_total_weight(bench *b) {
    double w = 0;
    for (int i = 0; i < b->nrefs; i++) w += b->refs[i].weight;
    return w;
}

typedef struct ref_progress_ctx { progress *p; double base, weight; } ref_progress_ctx;

static void on_ref_progress(void *user, double f) {
    ref_progress_ctx *c = user;
    c->p->done = c->base + f * c->weight;
    bench_progress_draw(c->p, false);
}

/* A reference of the scene (a setting's wrapper) of the given kind, size
 * and time, rendered (or read from the cache) on first use. */
ref_entry *bench_get_ref_at(bench *b, int s, const char *scene, int kind, int w, int h, double t) {
    refcache_opts o = ref_opts(b, kind);
    uint64_t key;
    char err[MSG_MAX] = "";
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
    bench_stem(b->scene_abs[s], sc, sizeof sc);
    static const char *const what[REFK_COUNT] = { "reference", "sequence reference", "noise reference",
                                                  "grid reference", "flat-lighting reference" };
    ref_progress_ctx pc = { &b->pr, b->pr.done, e->weight };
    bench_progress_set(&b->pr, b->pr.done, true, "%s %s t=%g", what[kind], sc, t);
    /* the stem names the scene, not the wrapper: settings that share a world share the file */
    char named[PATH_LEN];
    bench_fmt(named, sizeof named, "%s/%s.glib", dir, sc);
    e->ok = refcache_get(dir, scene, named, w, h, t, NULL, &o, on_ref_progress, &pc, &e->im, err, sizeof err);
    bench_progress_set(&b->pr, pc.base + e->weight, true, NULL);
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

ref_entry *bench_get_ref(bench *b, int s, const char *scene, int ti) {
    return bench_get_ref_at(b, s, scene, REFK_MAIN, b->o.w, b->o.h, b->o.times[ti]);
}
