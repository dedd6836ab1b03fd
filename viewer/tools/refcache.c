/* refcache: cached reference renders (see refcache.h). */
#include "refcache.h"
#include "strbuf.h"
#include "util.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "image_io.h"
#include "mem.h"
#include "ref_metrics.h"
#include "glib.h"
#include "scene.h"
#include "ref_buffers.h"
#include "render.h"

typedef struct loaded {
    ref_world_desc wd;
    scene_camera cam;
} loaded;


/* The world of a scene. Its Pack is not read: a pack draws the world, it
 * does not describe it (docs/packs/contract.md). */
static bool load(const char *scene, loaded *l, char *err, int errlen) {
    bool has_world = false;
    memset(l, 0, sizeof *l);
    glib_options opt = { 0 };
    glib_scene *g = glib_load_opts(scene, &opt);
    if (g->nerrors > 0) {
        int len = 0;
        for (int i = 0; i < g->ndiags && len < errlen - 1; i++)
            if (g->diags[i].severity == DIAG_ERROR)
                len += snprintf(err + len, (size_t)(errlen - len), "%s:%d: error: %s\n",
                                g->diags[i].file, g->diags[i].line, g->diags[i].text);
        glib_free(g);
        return false;
    }
    scene_from_glib(g, &l->wd, &l->cam, &has_world, NULL);   /* repairs are warnings the renderer says */
    glib_free(g);
    if (!has_world) {
        snprintf(err, (size_t)errlen, "%s describes no world (no Sun, Water, Terrain, Wave... or Object commands)",
                 scene);
        return false;
    }
    return true;
}

static ref_render_desc make_desc(const loaded *l, const ref_world *world, int w, int h, double t,
                                 const refcache_view *view, const refcache_opts *o) {
    ref_render_desc d;
    memset(&d, 0, sizeof d);
    d.world = world;
    for (int k = 0; k < 3; k++) {
        d.camera.eye[k] = view ? view->eye[k] : l->cam.eye[k];
        d.camera.center[k] = view ? view->center[k] : l->cam.center[k];
        d.camera.up[k] = view ? view->up[k] : l->cam.up[k];
    }
    d.camera.fov_deg = l->cam.fov_deg;
    d.camera.width = w;
    d.camera.height = h;
    d.time = t;
    if (o) {
        d.spp = o->nsamples > 0 ? 0 : o->spp;   /* positions replace the grid */
        d.nsamples = o->nsamples;
        if (o->nsamples > 0 && o->nsamples <= REF_MAX_SAMPLES)
            memcpy(d.samples, o->samples, (size_t)o->nsamples * sizeof d.samples[0]);
        d.caustic_res = o->caustic_res;
        d.photons_per_cell = o->photons_per_cell;
        d.seed = o->seed;
        d.threads = o->threads;
        d.caustics = o->flat_caustics ? REF_CAUSTICS_FLAT : REF_CAUSTICS_PHOTONS;
    }
    return d;
}

static uint64_t key_of(const loaded *l, const ref_render_desc *d) {
    ref_world_desc wd = l->wd;
    wd.water_mesh_res = 0;   /* GL only: the reference has the exact surface and terrain */
    wd.terrain_res = 0;
    memset(&wd.flow, 0, sizeof wd.flow);     /* GL only: the reference draws neither (ref_scene.h) */
    memset(&wd.spray, 0, sizeof wd.spray);
    uint64_t h = HASH_FNV1A_BASIS;
    h = hash_fnv1a(h, &wd, sizeof wd);
    ref_render_desc r = ref_render_resolve(d);
    h = hash_fnv1a(h, r.camera.eye, sizeof r.camera.eye);
    h = hash_fnv1a(h, r.camera.center, sizeof r.camera.center);
    h = hash_fnv1a(h, r.camera.up, sizeof r.camera.up);
    h = hash_fnv1a(h, &r.camera.fov_deg, sizeof r.camera.fov_deg);
    int ints[] = { r.camera.width, r.camera.height, r.spp, r.caustics, r.caustic_res, r.photons_per_cell,
                   r.max_depth, r.radiance_n2,
                   2 /* file layout and world model version: 2, a scaled lake's detail and colours scale */ };
    h = hash_fnv1a(h, ints, sizeof ints);
    h = hash_fnv1a(h, &r.time, sizeof r.time);
    h = hash_fnv1a(h, &r.t_tol, sizeof r.t_tol);
    if (r.nsamples > 0 && r.nsamples <= REF_MAX_SAMPLES) {   /* absent: the keys of the grid as before */
        h = hash_fnv1a(h, &r.nsamples, sizeof r.nsamples);
        h = hash_fnv1a(h, r.samples, (size_t)r.nsamples * sizeof r.samples[0]);
    }
    if (r.seed != 0 && r.caustics == REF_CAUSTICS_PHOTONS)   /* absent: seed 0's keys as before */
        h = hash_fnv1a(h, &r.seed, sizeof r.seed);
    return h;
}

bool refcache_key(const char *scene, int w, int h, double t, const refcache_opts *o, uint64_t *key, char *err,
                  int errlen) {
    loaded l;
    if (!load(scene, &l, err, errlen)) return false;
    ref_world world;
    ref_world_init(&world, &l.wd);
    ref_render_desc d = make_desc(&l, &world, w, h, t, NULL, o);
    *key = key_of(&l, &d);
    ref_world_release(&world);
    return true;
}

static void stem_of(const char *dir, const char *scene, int w, int h, double t, uint64_t key, char *out,
                    size_t len) {
    const char *base = strrchr(scene, '/');
    base = base ? base + 1 : scene;
    size_t bl = strlen(base);
    if (bl > 5 && strcmp(base + bl - 5, ".glib") == 0) bl -= 5;
    snprintf(out, len, "%s/%.*s-%dx%d-t%g-%016" PRIx64, dir, (int)bl, base, w, h, t, key);
}

/* The buffers the cache keeps (ref_buffers.h gives their files and
 * channels): what bench and the hard cases measure. */
static const ref_buffer_id cached[] = {
    REF_BUF_COLOR, REF_BUF_REFRACT_HIT, REF_BUF_FRESNEL, REF_BUF_DEPTH, REF_BUF_IRRADIANCE, REF_BUF_MASK,
};
enum { NBUFS = sizeof cached / sizeof cached[0] };

static float **slot(refcache_image *im, int i) {
    float **s[NBUFS] = { &im->color, &im->refract_hit, &im->fresnel, &im->depth, &im->irradiance, &im->mask };
    return s[i];
}

void refcache_free(refcache_image *im) {
    for (int i = 0; i < NBUFS; i++) free(*slot(im, i));
    memset(im, 0, sizeof *im);
}

static bool read_cached(const char *stem, int w, int h, refcache_image *out) {
    for (int i = 0; i < NBUFS; i++) {
        char path[1200], err[256];
        snprintf(path, sizeof path, "%s%s", stem, ref_buffers[cached[i]].suffix);
        img im;
        if (!img_read(path, &im, err, sizeof err)) return false;
        if (im.w != w || im.h != h || im.d != 1 || im.channels != ref_buffers[cached[i]].channels) {
            img_free(&im);
            return false;
        }
        *slot(out, i) = im.px;   /* the img's pixels, taken over */
    }
    return true;
}

/* A linear value as an sRGB display value in 0..1 (NaN: 0). */
static float display(float v) {
    if (!(v > 0)) return 0.0f;
    return v >= 1 ? 1.0f : (float)ref_linear_to_srgb(v);
}

static bool write_buf(const char *path, const float *px, int w, int h, int c, bool srgb, char *err, int errlen) {
    img im;
    if (!img_alloc(&im, w, h, c)) {
        snprintf(err, (size_t)errlen, "%s: out of memory", path);
        return false;
    }
    size_t n = (size_t)w * h * c;
    for (size_t i = 0; i < n; i++) im.px[i] = srgb ? display(px[i]) : px[i];
    bool ok = srgb ? img_write(path, &im, err, errlen) : img_write_float(path, &im, err, errlen);
    img_free(&im);
    return ok;
}

static float *to_float(const double *src, size_t n) {
    float *f = mem_alloc((n ? n : 1) * sizeof *f);
    for (size_t i = 0; i < n; i++) f[i] = (float)src[i];
    return f;
}

static bool mkdirs(const char *dir) {
    char path[1024];
    snprintf(path, sizeof path, "%s", dir);
    for (char *p = path + 1; *p; p++) {
        if (*p != '/') continue;
        *p = '\0';
        if (mkdir(path, 0755) != 0 && errno != EEXIST) return false;
        *p = '/';
    }
    return mkdir(path, 0755) == 0 || errno == EEXIST;
}

bool refcache_cached(const char *dir, const char *scene, const char *name, int w, int h, double t,
                     const refcache_opts *o) {
    if (!dir) return false;
    uint64_t key;
    char err[MSG_MAX];
    if (!refcache_key(scene, w, h, t, o, &key, err, sizeof err)) return false;
    char stem[1100], path[1200];
    stem_of(dir, name ? name : scene, w, h, t, key, stem, sizeof stem);
    for (int i = 0; i < NBUFS; i++) {
        struct stat st;
        snprintf(path, sizeof path, "%s%s", stem, ref_buffers[cached[i]].suffix);
        if (stat(path, &st) != 0) return false;
    }
    return true;
}

bool refcache_get(const char *dir, const char *scene, const char *name, int w, int h, double t,
                  const refcache_view *view, const refcache_opts *o, ref_progress_fn progress, void *user,
                  refcache_image *out, char *err, int errlen) {
    memset(out, 0, sizeof *out);
    loaded l;
    if (!load(scene, &l, err, errlen)) return false;
    ref_world world;
    ref_world_init(&world, &l.wd);
    ref_render_desc d = make_desc(&l, &world, w, h, t, view, o);
    d.progress = progress;
    d.progress_user = user;
    uint64_t key = key_of(&l, &d);
    out->w = w;
    out->h = h;
    if (dir) {
        stem_of(dir, name ? name : scene, w, h, t, key, out->stem, sizeof out->stem);
        if (read_cached(out->stem, w, h, out)) {
            out->from_cache = true;
            ref_world_release(&world);
            return true;
        }
        for (int i = 0; i < NBUFS; i++) {   /* a partial or stale set: render again */
            free(*slot(out, i));
            *slot(out, i) = NULL;
        }
    }
    ref_render_result r;
    char rerr[512] = "";
    int rrc = ref_render(&d, &r, rerr, sizeof rerr);
    ref_world_release(&world);
    if (rrc != 0) {
        snprintf(err, (size_t)errlen, "reference of %s: %s", scene, rerr);
        return false;
    }
    size_t n = (size_t)w * h;
    for (int i = 0; i < NBUFS; i++)
        if (cached[i] != REF_BUF_MASK)
            *slot(out, i) = to_float(ref_buffer_data(&r, cached[i]), n * (size_t)ref_buffers[cached[i]].channels);
    out->mask = mem_alloc(n * sizeof *out->mask);
    for (size_t i = 0; i < n; i++) out->mask[i] = (float)r.mask[i];
    out->seconds = r.seconds_photons + r.seconds_pixels;
    ref_render_free(&r);
    if (dir) {
        if (!mkdirs(dir)) {
            snprintf(err, (size_t)errlen, "cannot create %s: %s", dir, strerror(errno));
            return true;   /* the image is good; only the cache failed */
        }
        char path[1200];
        for (int i = 0; i < NBUFS; i++) {
            snprintf(path, sizeof path, "%s%s", out->stem, ref_buffers[cached[i]].suffix);
            if (!write_buf(path, *slot(out, i), w, h, ref_buffers[cached[i]].channels, false, err, errlen)) return true;
        }
        snprintf(path, sizeof path, "%s.png", out->stem);
        write_buf(path, out->color, w, h, 3, true, err, errlen);
    }
    return true;
}

void refcache_match_msaa(refcache_opts *o, int samples) {
    o->nsamples = 0;
    o->spp = render_ref_spp(samples);
    if (samples <= 1) return;
    int n = render_ref_positions(samples, o->samples, REF_MAX_SAMPLES);
    if (n <= 0) n = render_ref_standard_positions(samples, o->samples, REF_MAX_SAMPLES);
    if (n <= 0) return;
    o->nsamples = n;
    o->spp = 1;   /* not used: the positions replace the grid */
}

void refcache_describe_samples(const refcache_opts *o, char *buf, int len) {
    if (o->nsamples > 0) snprintf(buf, (size_t)len, "%d subsamples per pixel at the GL's MSAA sample positions",
                                   o->nsamples);
    else snprintf(buf, (size_t)len, "%d x %d subsamples per pixel", o->spp > 0 ? o->spp : 1, o->spp > 0 ? o->spp : 1);
}
