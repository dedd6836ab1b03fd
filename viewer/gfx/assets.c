/* assets.c: the generated textures (assets.h). Everything here is a pure
 * function of its inputs: fixed seeds and fixed summation orders (the
 * photons are traced in a fixed set of chunks, added in chunk order,
 * whatever the number of threads), so the same bytes come out every run. */
#include "assets.h"
#include "strbuf.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "exit_code.h"
#include "glib.h"
#include "image_io.h"
#include "mem.h"
#include "noise.h"
#include "ref_trace.h"
#include "scene.h"
#include "vec3.h"
#include "file.h"

#define PI 3.14159265358979323846

static bool res_ok(int res) { return res >= 1 && res <= ASSETS_MAX_RES; }

/* ------------------------------------------------------------------ */
/* encodings                                                           */

static void put_normal(float *px, const double n[3]) {
    px[0] = (float)(0.5 + 0.5 * n[0]);
    px[1] = (float)(0.5 + 0.5 * n[2]);
    px[2] = (float)(0.5 + 0.5 * n[1]);
}

/* ------------------------------------------------------------------ */
/* terrain and sky                                                     */

static double world_coord(const ref_world *w, int i, int res) {
    double h = w->d.half_size;
    return -h + (i + 0.5) * (2.0 * h / res);
}

bool assets_bake_albedo(const ref_world *w, int res, float *rgb) {
    if (!w || !rgb || !res_ok(res))
        return false;
    for (int j = 0; j < res; j++)
        for (int i = 0; i < res; i++) {
            double c[3];
            ref_terrain_albedo(w, world_coord(w, i, res), world_coord(w, j, res), c);
            float *px = rgb + ((size_t)j * res + i) * 3;
            for (int k = 0; k < 3; k++)
                px[k] = (float)c[k];
        }
    return true;
}

bool assets_bake_terrain_normal(const ref_world *w, int res, float *rgb) {
    if (!w || !rgb || !res_ok(res))
        return false;
    for (int j = 0; j < res; j++)
        for (int i = 0; i < res; i++) {
            double n[3];
            ref_terrain_normal_at(w, world_coord(w, i, res), world_coord(w, j, res), n);
            put_normal(rgb + ((size_t)j * res + i) * 3, n);
        }
    return true;
}

const char *assets_face_name(int face) {
    static const char *const names[ASSETS_FACES] = { "px", "nx", "py", "ny", "pz", "nz" };
    return face >= 0 && face < ASSETS_FACES ? names[face] : "?";
}

void assets_face_dir(int face, double s, double t, double dir[3]) {
    double sc = 2.0 * s - 1.0, tc = 2.0 * t - 1.0;
    switch (face) {
    case ASSETS_FACE_PX: dir[0] = 1;   dir[1] = -tc; dir[2] = -sc; break;
    case ASSETS_FACE_NX: dir[0] = -1;  dir[1] = -tc; dir[2] = sc;  break;
    case ASSETS_FACE_PY: dir[0] = sc;  dir[1] = 1;   dir[2] = tc;  break;
    case ASSETS_FACE_NY: dir[0] = sc;  dir[1] = -1;  dir[2] = -tc; break;
    case ASSETS_FACE_PZ: dir[0] = sc;  dir[1] = -tc; dir[2] = 1;   break;
    default:             dir[0] = -sc; dir[1] = -tc; dir[2] = -1;  break;
    }
    vec3_normalize(dir);
}

bool assets_bake_sky_face(const ref_world *w, int face, int res, float *rgb) {
    if (!w || !rgb || !res_ok(res) || face < 0 || face >= ASSETS_FACES)
        return false;
    for (int j = 0; j < res; j++)
        for (int i = 0; i < res; i++) {
            double d[3], c[3];
            assets_face_dir(face, (i + 0.5) / res, (j + 0.5) / res, d);
            ref_sky_radiance(w, d, c);
            float *px = rgb + ((size_t)j * res + i) * 3;
            for (int k = 0; k < 3; k++)
                px[k] = (float)c[k];
        }
    return true;
}

/* ------------------------------------------------------------------ */
/* water normal map and foam                                           */

enum { RIPPLE_OCTAVES = 4, RIPPLE_BASE_PERIODS = 4 };
#define RIPPLE_SEED 0x77617465u            /* "wate" */
#define RIPPLE_RMS_SLOPE 0.25

/* Ripple height at tile coordinates (u, v) in [0, 1): periodic in both. */
static double ripple(double u, double v) {
    double h = 0, amp = 1;
    int per = RIPPLE_BASE_PERIODS;
    for (int o = 0; o < RIPPLE_OCTAVES; o++) {
        h += amp * noise_perlin2(u * per, v * per, per, RIPPLE_SEED + (unsigned)o) / per;
        amp *= 0.6;
        per *= 2;
    }
    return h;
}

bool assets_bake_water_normal(int res, float *rgb) {
    if (!rgb || !res_ok(res))
        return false;
    size_t n = (size_t)res * res;
    double *g = mem_alloc(n * 2 * sizeof *g);
    /* gradient by central differences of the continuous (periodic) noise */
    double e = 0.25 / res, sum2 = 0;
    for (int j = 0; j < res; j++)
        for (int i = 0; i < res; i++) {
            double u = (i + 0.5) / res, v = (j + 0.5) / res;
            double gu = (ripple(u + e, v) - ripple(u - e, v)) / (2 * e);
            double gv = (ripple(u, v + e) - ripple(u, v - e)) / (2 * e);
            g[2 * ((size_t)j * res + i)] = gu;
            g[2 * ((size_t)j * res + i) + 1] = gv;
            sum2 += gu * gu + gv * gv;
        }
    double scale = sum2 > 0 ? RIPPLE_RMS_SLOPE / sqrt(sum2 / (double)n) : 0;
    for (size_t k = 0; k < n; k++) {
        double nv[3] = { -scale * g[2 * k], 1.0, -scale * g[2 * k + 1] };
        vec3_normalize(nv);
        put_normal(rgb + k * 3, nv);
    }
    free(g);
    return true;
}

enum { FOAM_DISCS = 40 };
#define FOAM_SEED 0x666f616d666f616dull     /* "foamfoam" */

static double rand01(uint64_t *s) {
    return (double)(ref_splitmix64(s) >> 11) / 9007199254740992.0;
}

/* Distance along one axis on the unit torus. */
static double wrap_d(double a) {
    a = fabs(a);
    a -= floor(a);
    return a > 0.5 ? 1.0 - a : a;
}

bool assets_bake_foam(int res, float *rgb) {
    if (!rgb || !res_ok(res))
        return false;
    double disc[2][FOAM_DISCS][3];
    uint64_t s = FOAM_SEED;
    for (int c = 0; c < 2; c++)
        for (int k = 0; k < FOAM_DISCS; k++) {
            disc[c][k][0] = rand01(&s);
            disc[c][k][1] = rand01(&s);
            disc[c][k][2] = 0.02 + 0.04 * rand01(&s);
        }
    double aa = 1.0 / res;                  /* one texel of soft edge */
    for (int j = 0; j < res; j++)
        for (int i = 0; i < res; i++) {
            double u = (i + 0.5) / res, v = (j + 0.5) / res, m[2] = { 0, 0 };
            for (int c = 0; c < 2; c++)
                for (int k = 0; k < FOAM_DISCS; k++) {
                    double dx = wrap_d(u - disc[c][k][0]), dy = wrap_d(v - disc[c][k][1]);
                    double a = 0.5 - (sqrt(dx * dx + dy * dy) - disc[c][k][2]) / aa;
                    a = a < 0 ? 0 : a > 1 ? 1 : a;
                    if (a > m[c])
                        m[c] = a;
                }
            float *px = rgb + ((size_t)j * res + i) * 3;
            px[0] = (float)m[0];
            px[1] = 0.0f;
            px[2] = (float)m[1];
        }
    return true;
}

/* ------------------------------------------------------------------ */
/* caustics                                                            */

/* The wave patch: a TILE x TILE square; every wave vector is 2 pi (m, n) /
 * TILE with whole m, n, so the surface, and the light it focuses on a flat
 * floor, repeat with the tile. */
#define CAUSTIC_TILE 4.0
#define CAUSTIC_DEPTH 2.5
enum { CAUSTIC_PHOTONS_PER_CELL = 64, CAUSTIC_CHUNKS = 8, CAUSTIC_MIN_RES = ASSETS_MIN_SIZE,
       CAUSTIC_MAX_RES = ASSETS_MAX_SIZE };

static const struct { int m, n; double amp, phase; } caustic_waves[] = {
    { 2, 1, 0.040, 0.3 }, { -1, 2, 0.036, 1.9 }, { 3, -1, 0.024, 4.1 },
    { 1, 3, 0.022, 2.6 }, { -3, -2, 0.016, 5.3 }, { 4, 3, 0.010, 0.8 },
};

static void caustic_waves_desc(ref_waves_desc *d) {
    memset(d, 0, sizeof *d);
    d->sine_count = (int)(sizeof caustic_waves / sizeof caustic_waves[0]);
    for (int i = 0; i < d->sine_count; i++) {
        double m = caustic_waves[i].m, n = caustic_waves[i].n;
        ref_wave_desc *w = &d->sine[i];
        w->angle_deg = atan2(n, m) * 180.0 / PI;
        w->wavelength = CAUSTIC_TILE / sqrt(m * m + n * n);
        w->amplitude = caustic_waves[i].amp;
        w->phase = caustic_waves[i].phase;
    }
}

typedef struct caustic_job {
    const ref_caustics_plan *plan;
    double *flux[CAUSTIC_CHUNKS];           /* one buffer per chunk of rows */
    int ncells;
    int next;                               /* the next chunk to trace */
    pthread_mutex_t lock;
} caustic_job;

static void *caustic_worker(void *arg) {
    caustic_job *job = arg;
    const ref_caustics_plan *p = job->plan;
    for (;;) {
        pthread_mutex_lock(&job->lock);
        int c = job->next++;
        pthread_mutex_unlock(&job->lock);
        if (c >= CAUSTIC_CHUNKS)
            return NULL;
        int r0 = (int)((long)p->mz * c / CAUSTIC_CHUNKS);
        int r1 = (int)((long)p->mz * (c + 1) / CAUSTIC_CHUNKS);
        ref_caustics_trace_rows(p, r0, r1, job->flux[c], NULL);
    }
}

static int thread_count(void) {
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > 16 ? 16 : (int)n;
}

bool assets_bake_caustics(int res, float *out, char *err, int errlen) {
    if (err && errlen > 0)
        err[0] = '\0';
    if (!out || res < CAUSTIC_MIN_RES || res > CAUSTIC_MAX_RES) {
        if (err && errlen > 0)
            snprintf(err, (size_t)errlen, "caustics: resolution %d is outside %d..%d", res,
                     CAUSTIC_MIN_RES, CAUSTIC_MAX_RES);
        return false;
    }
    ref_waves_desc wd;
    caustic_waves_desc(&wd);
    ref_waves waves;
    char why[MSG_MAX];
    if (ref_waves_init(&waves, &wd, why, sizeof why) != 0) {
        if (err && errlen > 0)
            snprintf(err, (size_t)errlen, "caustics: %s", why);
        return false;
    }
    ref_caustics_desc d = {
        .waves = &waves, .sun_dir = { 0, 1, 0 }, .sun_irradiance = 1,
        .floor_y = -CAUSTIC_DEPTH, .x0 = 0, .z0 = 0, .x1 = CAUSTIC_TILE, .z1 = CAUSTIC_TILE,
        .nx = res, .nz = res, .photons_per_cell = CAUSTIC_PHOTONS_PER_CELL,
    };
    ref_caustics_plan plan;
    if (ref_caustics_plan_init(&d, &plan, why, sizeof why) != 0) {
        if (err && errlen > 0)
            snprintf(err, (size_t)errlen, "%s", why);
        ref_waves_release(&waves);
        return false;
    }
    /* Rows are cut into a fixed number of chunks, each summed into its own
     * buffer and the buffers added in chunk order: the result does not
     * depend on how many threads ran. */
    caustic_job job = { .plan = &plan, .ncells = res * res };
    pthread_mutex_init(&job.lock, NULL);
    bool ok = true;
    for (int c = 0; c < CAUSTIC_CHUNKS; c++)
        job.flux[c] = mem_zalloc((size_t)job.ncells * 3 * sizeof(double));
    int nt = thread_count();
    pthread_t th[16];
    int started = 0;
    for (int t = 0; t < nt; t++)
        started += pthread_create(&th[started], NULL, caustic_worker, &job) == 0;
    if (started == 0)
        caustic_worker(&job);
    for (int t = 0; t < started; t++)
        pthread_join(th[t], NULL);
    /* the floor is flat: every cell has the same area, so flux over
     * the mean flux is irradiance over the mean irradiance */
    double *sum = job.flux[0], total = 0;
    for (int c = 1; c < CAUSTIC_CHUNKS; c++)
        for (int k = 0; k < job.ncells * 3; k++)
            sum[k] += job.flux[c][k];
    for (int k = 0; k < job.ncells; k++)
        total += sum[3 * k];
    double mean = total / job.ncells;
    if (!(mean > 0)) {
        ok = false;
        if (err && errlen > 0)
            snprintf(err, (size_t)errlen, "caustics: no light reached the floor");
    }
    for (int k = 0; ok && k < job.ncells; k++)
        out[k] = (float)(sum[3 * k] / mean);
    for (int c = 0; c < CAUSTIC_CHUNKS; c++)
        free(job.flux[c]);
    pthread_mutex_destroy(&job.lock);
    ref_waves_release(&waves);
    return ok;
}

/* ------------------------------------------------------------------ */
/* tarn assets                                                         */


typedef struct out_dir {
    const char *dir;
    int nwritten;
    bool failed;
} out_dir;

/* Writes res x res x 3 floats (GL order) as DIR/name (EXR as 32-bit
 * float, exactly the baked values); flip: 2D textures (files are top row
 * first), not cube faces. */
static void save(out_dir *o, const char *name, const float *rgb, int res, bool flip, double scale) {
    if (o->failed)
        return;
    char path[1200], err[512];
    snprintf(path, sizeof path, "%s/%s", o->dir, name);
    img im;
    if (!img_alloc(&im, res, res, 3)) {
        fprintf(stderr, "tarn assets: %s: out of memory\n", path);
        o->failed = true;
        return;
    }
    for (size_t k = 0; k < (size_t)res * res * 3; k++)
        im.px[k] = (float)(rgb[k] * scale);
    if (flip)
        img_flip_rows(&im);
    size_t len = strlen(name);
    bool exr = len > 4 && strcmp(name + len - 4, ".exr") == 0;
    if (!(exr ? img_write_float : img_write)(path, &im, err, sizeof err)) {
        fprintf(stderr, "tarn assets: %s\n", err);
        o->failed = true;
    } else {
        printf("tarn assets: wrote %s (%dx%d)\n", path, res, res);
        o->nwritten++;
    }
    img_free(&im);
}

static bool world_for(const char *scene, ref_world *w) {
    ref_world_desc d;
    if (!scene) {
        ref_world_desc_lake(&d);
    } else {
        glib_scene *g = glib_load(scene);
        glib_print_diags(g, stderr);
        int nerr = g->nerrors;
        diag_list repairs = { 0 };
        scene_camera cam;
        bool has;
        if (!nerr && !scene_from_glib(g, &d, &cam, &has, &repairs)) diag_print(&repairs, stderr);
        diag_list_free(&repairs);
        glib_free(g);
        if (nerr) {
            fprintf(stderr, "tarn assets: %s has errors; nothing written\n", scene);
            return false;
        }
    }
    ref_world_init(w, &d);
    return true;
}

int assets_run(const assets_desc *d) {
    const char *dir = d->dir ? d->dir : "assets", *scene = d->scene;
    int size = d->size;
    if (size && (size < CAUSTIC_MIN_RES || size > CAUSTIC_MAX_RES)) {
        fprintf(stderr, "tarn assets: size %d is out of %d..%d\n", size, CAUSTIC_MIN_RES, CAUSTIC_MAX_RES);
        return TARN_EXIT_USAGE;
    }
    ref_world *w = mem_alloc(sizeof *w);
    if (!world_for(scene, w)) {
        free(w);
        return TARN_EXIT_INPUT;
    }
    char err[MSG_MAX];
    if (!file_mkdir_p(dir, err, sizeof err)) {
        fprintf(stderr, "tarn assets: %s\n", err);
        ref_world_release(w);
        free(w);
        return TARN_EXIT_INPUT;
    }
    int r_terrain = size ? size : w->d.terrain_res;
    int r_sky = size ? size : 256, r_tile = size ? size : 512, r_caustic = size ? size : 256;
    int rmax = r_terrain > r_tile ? r_terrain : r_tile;
    rmax = rmax > r_sky ? rmax : r_sky;
    float *buf = mem_alloc((size_t)rmax * rmax * 3 * sizeof *buf);
    out_dir o = { .dir = dir };
    assets_bake_albedo(w, r_terrain, buf);
    save(&o, "terrain_albedo.png", buf, r_terrain, true, 1.0);
    assets_bake_terrain_normal(w, r_terrain, buf);
    save(&o, "terrain_normal.png", buf, r_terrain, true, 1.0);
    for (int f = 0; f < ASSETS_FACES; f++) {
        char name[32];
        assets_bake_sky_face(w, f, r_sky, buf);
        snprintf(name, sizeof name, "sky_%s.exr", assets_face_name(f));
        save(&o, name, buf, r_sky, false, 1.0);
        snprintf(name, sizeof name, "sky_%s.png", assets_face_name(f));
        save(&o, name, buf, r_sky, false, 1.0);
    }
    assets_bake_water_normal(r_tile, buf);
    save(&o, "water_normal.png", buf, r_tile, true, 1.0);
    assets_bake_foam(r_tile, buf);
    save(&o, "foam.png", buf, r_tile, true, 1.0);
    float *c = mem_alloc((size_t)r_caustic * r_caustic * sizeof *c);
    float *rgb = mem_alloc((size_t)r_caustic * r_caustic * 3 * sizeof *rgb);
    if (!assets_bake_caustics(r_caustic, c, err, sizeof err)) {
        fprintf(stderr, "tarn assets: %s\n", err);
        o.failed = true;
    } else {
        for (size_t k = 0; k < (size_t)r_caustic * r_caustic; k++)
            rgb[3 * k] = rgb[3 * k + 1] = rgb[3 * k + 2] = c[k];
        save(&o, "caustics.exr", rgb, r_caustic, true, 1.0);
        save(&o, "caustics.png", rgb, r_caustic, true, 0.5);   /* mean 0.5 */
    }
    free(c);
    free(rgb);
    free(buf);
    ref_world_release(w);
    free(w);
    return o.failed ? TARN_EXIT_INPUT : TARN_EXIT_OK;
}
