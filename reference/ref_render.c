/* ref_render: the CPU ground-truth renderer (see ref_render.h and
 * docs/reference.md, "The renderer"). */
#include "ref_render.h"
#include "mem.h"
#include "strbuf.h"
#include "util.h"
#include "vec3.h"

#include <math.h>
#include <stdbool.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define PI 3.14159265358979323846

/* defaults, in one place */
#define DEFAULT_WIDTH 640
#define DEFAULT_HEIGHT 360
#define DEFAULT_FOV 50.0
#define DEFAULT_CAUSTIC_RES 256
#define DEFAULT_PHOTONS_PER_CELL 36
#define DEFAULT_MAX_DEPTH 5
#define DEFAULT_T_TOL 1e-9
#define RAY_T_MAX REF_WORLD_HORIZON   /* the GL world's land ends there too */

#define MAX_THREADS 256
#define MAX_CAUSTIC_BYTES (8.0 * (1 << 30))   /* the photon grids: one per thread and the result */
#define MAX_SPP 16
#define PHOTON_CHUNK_ROWS 8      /* strata rows per photon work item (fixed: the
                                    flux is summed chunk by chunk in order) */
#define PHOTON_T_TOL 1e-6         /* a photon's landing point to 1 um: cells are cm */
#define REGION_SAMPLES 257       /* samples per side to find the underwater floor */
#define PIXEL_PHOTON_COST 5.0    /* a pixel costs about this many photons (progress) */

static void set3(double v[3], double x) { v[0] = v[1] = v[2] = x; }

/* ------------------------------------------------------------------ */
/* desc and camera                                                     */

ref_render_desc ref_render_resolve(const ref_render_desc *din) {
    ref_render_desc d;
    memset(&d, 0, sizeof d);
    if (din) d = *din;
    ref_camera *c = &d.camera;
    if (c->width <= 0) c->width = DEFAULT_WIDTH;
    if (c->height <= 0) c->height = DEFAULT_HEIGHT;
    if (!(c->fov_deg > 0)) c->fov_deg = DEFAULT_FOV;
    if (c->up[0] == 0 && c->up[1] == 0 && c->up[2] == 0) c->up[1] = 1;
    if (d.threads <= 0) {
        long n = sysconf(_SC_NPROCESSORS_ONLN);
        d.threads = n > 0 ? (int)n : 1;
    }
    if (d.threads > MAX_THREADS) d.threads = MAX_THREADS;
    if (d.spp <= 0) d.spp = 1;
    if (d.caustic_res <= 0) d.caustic_res = DEFAULT_CAUSTIC_RES;
    if (d.photons_per_cell <= 0) d.photons_per_cell = DEFAULT_PHOTONS_PER_CELL;
    if (d.max_depth <= 0) d.max_depth = DEFAULT_MAX_DEPTH;
    if (!(d.t_tol > 0)) d.t_tol = DEFAULT_T_TOL;
    return d;
}

void ref_camera_ray(const ref_camera *cam, double px, double py, double o[3], double d[3]) {
    double f[3] = { cam->center[0] - cam->eye[0], cam->center[1] - cam->eye[1],
                    cam->center[2] - cam->eye[2] };
    vec3_normalize(f);
    double r[3], u[3];
    vec3_cross(f, cam->up, r);
    vec3_normalize(r);
    vec3_cross(r, f, u);
    double th = tan(0.5 * cam->fov_deg * PI / 180.0);
    double sy = (1.0 - 2.0 * py / cam->height) * th;
    double sx = (2.0 * px / cam->width - 1.0) * th * ((double)cam->width / cam->height);
    for (int i = 0; i < 3; i++) {
        o[i] = cam->eye[i];
        d[i] = f[i] + sx * r[i] + sy * u[i];
    }
    vec3_normalize(d);
}

/* ------------------------------------------------------------------ */
/* the render context                                                  */

typedef struct rctx {
    const ref_world *w;
    ref_render_desc d;          /* resolved */
    double level, n_air, n_water, t0;   /* t0 = 1 - R(normal incidence) */
    ref_terrain ter;
    ref_trace_opts opts;        /* t_tol, t_max */
    const ref_caustics *grid;   /* NULL: flat sun everywhere */
    ref_waves_ctx waves;        /* the waves at the render's time: the ocean's
                                   frame looked up once for every ray */
    int eye_in_water;

    /* work distribution */
    pthread_mutex_t mu;
    pthread_cond_t cv;
    int next_item, items, items_done, chunks_added, workers_done;
    int nthreads;

    /* photons */
    const ref_caustics_plan *plan;
    double *flux;               /* the total, nx*nz*3 */
    ref_caustics_stats *stats;

    ref_render_result *out;
} rctx;

static double ter_height(const void *user, double x, double z) {
    return ref_terrain_height(user, x, z);
}

static void ter_gradient(const void *user, double x, double z, double g[2]) {
    ref_terrain_gradient(user, x, z, g);
}

static void make_terrain(const ref_world *w, ref_terrain *t) {
    memset(t, 0, sizeof *t);
    t->height = ter_height;
    t->gradient = ter_gradient;
    t->user = w;
    t->lipschitz = w->terrain_slope_bound > 0 ? w->terrain_slope_bound : 1e-9;
    const ref_world_desc *s = &w->d;
    switch (s->terrain) {
    case REF_TERRAIN_LAKE: {
        double det = 0;
        for (int i = 0; i < REF_TERRAIN_DETAIL; i++) det += fabs(w->detail_a[i]);
        t->bounded = 1;
        t->ymin = s->water_level - s->depth - det - 1e-9;
        t->ymax = s->water_level + s->shore_height + det + 1e-9;
        break;
    }
    case REF_TERRAIN_POOL:   /* the floor to the deck */
        t->bounded = 1;
        t->ymin = s->water_level - s->depth - 1e-9 * (1.0 + fabs(s->depth));
        t->ymax = s->water_level + s->shore_height + 1e-9 * (1.0 + fabs(s->shore_height));
        break;
    case REF_TERRAIN_SLOPE:
        break;   /* a plane: unbounded */
    default: {   /* a plane: pad the slab so a ray is clipped to just above it */
        double y = s->water_level - s->depth, pad = 1e-9 * (1.0 + fabs(y));
        t->bounded = 1;
        t->ymin = y - pad;
        t->ymax = y + pad;
        break;
    }
    }
}

/* Ambient light under water at height y: ambient (1 - R(0)) exp(-sigma depth). */
static void ambient_under(const rctx *c, double y, double a[3]) {
    double depth = c->level - y;
    if (depth < 0) depth = 0;
    for (int i = 0; i < 3; i++)
        a[i] = c->w->ambient[i] * c->t0 * exp(-c->w->d.absorption[i] * depth);
}

void ref_render_flat_sun(const ref_world *w, const double p[3], const double n[3], double e[3]) {
    const double *sun = w->d.sun_dir;
    double down[3] = { -sun[0], -sun[1], -sun[2] }, up[3] = { 0, 1, 0 }, ts[3];
    double level = w->d.water_level;
    set3(e, 0);
    if (!(sun[1] > 0)) return;
    if (!ref_refract(down, up, REF_N_AIR, w->d.ior, ts)) return;
    double cos_s = sun[1], cos_t = -ts[1];
    double R = ref_fresnel(cos_s, REF_N_AIR, w->d.ior);
    double c = -vec3_dot(n, ts);
    if (c <= 0) return;
    double depth = level - p[1];
    if (depth < 0) depth = 0;
    for (int i = 0; i < 3; i++)
        e[i] = w->d.sun_irradiance[i] * (1 - R) * cos_s / cos_t * c *
               exp(-w->d.absorption[i] * depth / cos_t);
}

static void caustic_lookup(const ref_caustics *g, const ref_world *w, double x, double z,
                           double e[3]) {
    if (!g || !g->irradiance || !(x >= g->x0 && x <= g->x1 && z >= g->z0 && z <= g->z1)) {
        double p[3] = { x, ref_terrain_height(w, x, z), z }, n[3];
        ref_terrain_normal_at(w, x, z, n);
        ref_render_flat_sun(w, p, n, e);
        return;
    }
    double dx = (g->x1 - g->x0) / g->nx, dz = (g->z1 - g->z0) / g->nz;
    double fx = (x - g->x0) / dx - 0.5, fz = (z - g->z0) / dz - 0.5;
    if (fx < 0) fx = 0;
    if (fz < 0) fz = 0;
    if (fx > g->nx - 1) fx = g->nx - 1;
    if (fz > g->nz - 1) fz = g->nz - 1;
    int i0 = (int)fx, j0 = (int)fz;
    int i1 = i0 + 1 < g->nx ? i0 + 1 : i0, j1 = j0 + 1 < g->nz ? j0 + 1 : j0;
    double a = fx - i0, b = fz - j0;
    const double *v00 = g->irradiance + ((size_t)j0 * g->nx + i0) * 3;
    const double *v10 = g->irradiance + ((size_t)j0 * g->nx + i1) * 3;
    const double *v01 = g->irradiance + ((size_t)j1 * g->nx + i0) * 3;
    const double *v11 = g->irradiance + ((size_t)j1 * g->nx + i1) * 3;
    for (int k = 0; k < 3; k++) {
        double v = (1 - b) * ((1 - a) * v00[k] + a * v10[k]) + b * ((1 - a) * v01[k] + a * v11[k]);
        e[k] = w->d.sun_irradiance[k] * v;
    }
}

void ref_render_caustic_at(const ref_render_result *r, const ref_world *w, double x, double z,
                           double e[3]) {
    caustic_lookup(r && r->have_caustics ? &r->caustics : NULL, w, x, z, e);
}

/* ------------------------------------------------------------------ */
/* paths                                                               */

typedef struct first_hit {
    int kind;           /* REF_MASK_*; SKY = met nothing */
    double t;           /* distance (INFINITY when nothing) */
    double pos[3];      /* NaN when nothing */
    double e_sun[3];    /* terrain/object: the sun irradiance its shading used */
} first_hit;

typedef struct path_info {
    first_hit first;            /* the primary ray */
    int water;                  /* it met the water surface first */
    double fresnel;
    double refl_dir[3];         /* the reflected direction */
    first_hit refl, refr;       /* what its reflected and refracted rays met */
} path_info;

static void no_hit(first_hit *fh) {
    fh->kind = REF_MASK_SKY;
    fh->t = INFINITY;
    set3(fh->pos, NAN);
    set3(fh->e_sun, NAN);
}

/* The smallest t > 0 at which a ray leaving the surface point p is on the
 * side it is going to (above: y > H), so the water march does not find the
 * crossing it starts on. */
static double leave_surface(const rctx *c, const double p[3], const double d[3], int above) {
    double t = 1e-10 * (1.0 + fabs(p[0]) + fabs(p[1]) + fabs(p[2]));
    for (int k = 0; k < 48; k++, t *= 2) {
        double h = ref_waves_ctx_height(&c->waves, p[0] + t * d[0], p[2] + t * d[2]);
        if (isnan(h)) break;
        double f = p[1] + t * d[1] - h;
        if (above ? f > 0 : f < 0) break;
    }
    return t;
}

/* Radiance arriving at o from direction -d, for a ray in air or water,
 * after a path of length `path` from the eye. on_surface: o is on the
 * water surface (the ray leaves it). fh (may be NULL) gets what this ray
 * met first; pi (primary rays only) gets the water interaction's details. */
static void trace_path(const rctx *c, const double o[3], const double d[3], int on_surface,
                       int in_water, int depth, double path, double L[3], first_hit *fh, path_info *pi) {
    const ref_world *w = c->w;
    ref_trace_opts wo = c->opts;
    wo.t_min = on_surface ? leave_surface(c, o, d, !in_water) : 0.0;
    ref_water_hit wh;
    int wat = ref_trace_water_ctx(&c->waves, o, d, &wo, &wh);
    double tbest = wat ? wh.t : RAY_T_MAX;
    int kind = wat ? REF_MASK_WATER : REF_MASK_SKY;

    ref_trace_opts to = c->opts;
    to.t_min = 0.0;
    to.t_max = tbest;
    ref_terrain_hit th;
    if (ref_trace_terrain(&c->ter, o, d, &to, &th) && th.t < tbest) {
        tbest = th.t;
        kind = REF_MASK_TERRAIN;
    }
    double tob, nob[3];
    int ob = ref_objects_hit(w, o, d, 0.0, tbest, &tob, nob);
    if (ob >= 0 && tob < tbest) {
        tbest = tob;
        kind = REF_MASK_OBJECT;
    }

    first_hit me;
    no_hit(&me);
    if (pi) {
        pi->water = 0;
        pi->fresnel = NAN;
        no_hit(&pi->refl);
        no_hit(&pi->refr);
    }
    if (kind == REF_MASK_SKY) {
        if (in_water) set3(L, 0.0);              /* absorbed on an endless path */
        else ref_sky_radiance(w, d, L);
        if (fh) *fh = me;
        return;
    }
    me.kind = kind;
    me.t = tbest;
    int seg_water = kind == REF_MASK_WATER ? wh.from_below : in_water;
    double Lh[3];
    if (kind == REF_MASK_WATER) {
        const ref_waves_point *s = &wh.surf;
        memcpy(me.pos, s->pos, sizeof me.pos);
        int below = wh.from_below;
        double n1 = below ? c->n_water : c->n_air, n2 = below ? c->n_air : c->n_water;
        double cos_i = fabs(vec3_dot(d, s->normal));
        double R = ref_fresnel(cos_i, n1, n2);
        double rdir[3], tdir[3];
        ref_reflect(d, s->normal, rdir);
        vec3_normalize(rdir);
        int tir = !ref_refract(d, s->normal, n1, n2, tdir);
        if (pi) {
            pi->water = 1;
            pi->fresnel = R;
            memcpy(pi->refl_dir, rdir, sizeof rdir);
        }
        if (depth + 1 > c->d.max_depth) {
            set3(Lh, 0.0);
        } else {
            double Lr[3], Lt[3] = { 0, 0, 0 };
            trace_path(c, s->pos, rdir, 1, below, depth + 1, path + tbest, Lr, pi ? &pi->refl : NULL, NULL);
            if (!tir && R < 1.0)
                trace_path(c, s->pos, tdir, 1, !below, depth + 1, path + tbest, Lt, pi ? &pi->refr : NULL, NULL);
            double k = c->d.radiance_n2 ? (n1 / n2) * (n1 / n2) : 1.0;
            for (int i = 0; i < 3; i++) Lh[i] = R * Lr[i] + (1.0 - R) * k * Lt[i];
        }
    } else {
        double n[3], albedo[3];
        if (kind == REF_MASK_TERRAIN) {
            memcpy(me.pos, th.pos, sizeof me.pos);
            memcpy(n, th.normal, sizeof n);
            ref_terrain_albedo(w, th.pos[0], th.pos[2], albedo);
        } else {
            for (int i = 0; i < 3; i++) me.pos[i] = o[i] + tbest * d[i];
            memcpy(n, nob, sizeof n);
            memcpy(albedo, w->d.objects[ob].albedo, sizeof albedo);
        }
        if (seg_water) {
            double a[3];
            if (kind == REF_MASK_TERRAIN) caustic_lookup(c->grid, w, me.pos[0], me.pos[2], me.e_sun);
            else ref_render_flat_sun(w, me.pos, n, me.e_sun);
            ambient_under(c, me.pos[1], a);
            for (int i = 0; i < 3; i++) Lh[i] = albedo[i] * (me.e_sun[i] / PI + a[i]);
        } else {
            double cl = vec3_dot(n, w->d.sun_dir);
            if (cl < 0) cl = 0;
            for (int i = 0; i < 3; i++) me.e_sun[i] = w->d.sun_irradiance[i] * cl;
            ref_shade_lambert(w, albedo, n, 1.0, Lh);
            /* Haze: the air path from the eye (a mirror camera's eye in
             * GL: the same length over flat water) */
            ref_haze(w, path + tbest, Lh);
        }
    }
    if (seg_water) {
        double tr[3];
        ref_beer_lambert(w->d.absorption, tbest, tr);
        for (int i = 0; i < 3; i++) L[i] = tr[i] * Lh[i];
    } else {
        memcpy(L, Lh, sizeof Lh);
    }
    if (fh) *fh = me;
}

/* Subsample k of n in the pixel (x right, y down, in [0, 1)): the desc's
 * positions, or the N x N grid's cell centres. */
static void subsample(const ref_render_desc *d, int k, double *sx, double *sy) {
    if (d->nsamples > 0) {
        *sx = d->samples[k][0];
        *sy = d->samples[k][1];
        return;
    }
    int n = d->spp;
    *sx = (k % n + 0.5) / n;
    *sy = (k / n + 0.5) / n;
}

static void render_pixel(const rctx *c, int px, int py) {
    ref_render_result *r = c->out;
    const ref_camera *cam = &c->d.camera;
    int ns = c->d.nsamples > 0 ? c->d.nsamples : c->d.spp * c->d.spp;
    double acc[3] = { 0, 0, 0 }, o[3], d[3], L[3];
    path_info pi;
    bool have_centre = false;
    for (int k = 0; k < ns; k++) {
        double sx, sy;
        subsample(&c->d, k, &sx, &sy);
        bool centre = !have_centre && sx == 0.5 && sy == 0.5;
        have_centre |= centre;
        ref_camera_ray(cam, px + sx, py + sy, o, d);
        trace_path(c, o, d, 0, c->eye_in_water, 0, 0.0, L, centre ? &pi.first : NULL, centre ? &pi : NULL);
        for (int i = 0; i < 3; i++) acc[i] += L[i];
    }
    if (!have_centre) {   /* the buffers come from the pixel centre */
        ref_camera_ray(cam, px + 0.5, py + 0.5, o, d);
        trace_path(c, o, d, 0, c->eye_in_water, 0, 0.0, L, &pi.first, &pi);
    }
    size_t i = (size_t)py * r->width + px;
    for (int k = 0; k < 3; k++) r->color[i * 3 + k] = acc[k] / ns;
    r->mask[i] = (unsigned char)pi.first.kind;

    double *surf = r->surface + i * 3, *rh = r->refract_hit + i * 4, *rf = r->reflect + i * 4;
    double *ir = r->irradiance + i * 3;
    set3(surf, NAN);
    set3(rh, NAN);
    rh[3] = REF_MASK_SKY;
    set3(ir, NAN);
    set3(rf, NAN);
    rf[3] = REF_REFLECT_NONE;
    r->fresnel[i] = NAN;
    r->depth[i] = NAN;
    if (c->eye_in_water) r->depth[i] = pi.first.t;   /* the eye's segment in water */
    if (!pi.water) return;
    memcpy(surf, pi.first.pos, 3 * sizeof *surf);
    r->fresnel[i] = pi.fresnel;
    if (pi.refr.kind != REF_MASK_SKY) {
        memcpy(rh, pi.refr.pos, 3 * sizeof *rh);
        rh[3] = pi.refr.kind;
        if (pi.refr.kind != REF_MASK_WATER) memcpy(ir, pi.refr.e_sun, 3 * sizeof *ir);
    }
    if (!c->eye_in_water) r->depth[i] = pi.refr.t;   /* the refracted segment (INFINITY: endless) */
    if (pi.refl.kind == REF_MASK_SKY) {
        memcpy(rf, pi.refl_dir, 3 * sizeof *rf);
        rf[3] = REF_REFLECT_SKY;
    } else {
        memcpy(rf, pi.refl.pos, 3 * sizeof *rf);
        rf[3] = pi.refl.kind == REF_MASK_WATER ? REF_REFLECT_WATER : REF_REFLECT_POINT;
    }
}

/* ------------------------------------------------------------------ */
/* threads                                                             */

static void stats_add(ref_caustics_stats *a, const ref_caustics_stats *b) {
    a->photons += b->photons;
    a->hit_water += b->hit_water;
    a->hit_dry += b->hit_dry;
    a->hit_floor += b->hit_floor;
    a->in_grid += b->in_grid;
    a->flux_emitted += b->flux_emitted;
    a->flux_reflected += b->flux_reflected;
    a->flux_transmitted += b->flux_transmitted;
    for (int i = 0; i < 3; i++) a->flux_in_grid[i] += b->flux_in_grid[i];
}

typedef struct worker {
    rctx *c;
    double *buf;        /* photons: this thread's chunk buffer */
} worker;

static void worker_finish(rctx *c) {
    pthread_mutex_lock(&c->mu);
    c->workers_done++;
    pthread_cond_broadcast(&c->cv);
    pthread_mutex_unlock(&c->mu);
}

/* Photon chunks are handed out in order; each is traced into the thread's
 * own zeroed buffer and added to the total in chunk order, so the sums do
 * not depend on the number of threads. */
static void *photon_worker(void *arg) {
    worker *wk = arg;
    rctx *c = wk->c;
    const ref_caustics_plan *p = c->plan;
    size_t n = (size_t)p->d.nx * p->d.nz * 3;
    for (;;) {
        pthread_mutex_lock(&c->mu);
        int k = c->next_item < c->items ? c->next_item++ : -1;
        pthread_mutex_unlock(&c->mu);
        if (k < 0) break;
        memset(wk->buf, 0, n * sizeof *wk->buf);
        ref_caustics_stats st;
        memset(&st, 0, sizeof st);
        ref_caustics_trace_rows(p, k * PHOTON_CHUNK_ROWS, (k + 1) * PHOTON_CHUNK_ROWS, wk->buf, &st);
        pthread_mutex_lock(&c->mu);
        while (c->chunks_added != k) pthread_cond_wait(&c->cv, &c->mu);
        for (size_t i = 0; i < n; i++) c->flux[i] += wk->buf[i];
        stats_add(c->stats, &st);
        c->chunks_added++;
        c->items_done++;
        pthread_cond_broadcast(&c->cv);
        pthread_mutex_unlock(&c->mu);
    }
    worker_finish(c);
    return NULL;
}

static void *pixel_worker(void *arg) {
    worker *wk = arg;
    rctx *c = wk->c;
    int width = c->out->width;
    for (;;) {
        pthread_mutex_lock(&c->mu);
        int row = c->next_item < c->items ? c->next_item++ : -1;
        pthread_mutex_unlock(&c->mu);
        if (row < 0) break;
        for (int x = 0; x < width; x++) render_pixel(c, x, row);
        pthread_mutex_lock(&c->mu);
        c->items_done++;
        pthread_mutex_unlock(&c->mu);
    }
    worker_finish(c);
    return NULL;
}

/* Runs fn on the threads over items work items; progress goes from f0 to
 * f1 of the whole. */
static void run_phase(rctx *c, void *(*fn)(void *), worker *wk, int items, double f0, double f1) {
    c->next_item = 0;
    c->items = items;
    c->items_done = 0;
    c->chunks_added = 0;
    c->workers_done = 0;
    pthread_t th[MAX_THREADS];
    int started = 0;
    for (int i = 0; i < c->nthreads; i++) {
        if (pthread_create(&th[i], NULL, fn, &wk[i]) != 0) break;
        started++;
    }
    if (started == 0) {   /* no threads to be had: do it here */
        fn(&wk[0]);
        if (c->d.progress) c->d.progress(c->d.progress_user, f1);
        return;
    }
    if (c->d.progress) {
        pthread_mutex_lock(&c->mu);
        while (c->workers_done < started) {
            struct timespec ts;
            clock_gettime(CLOCK_REALTIME, &ts);
            ts.tv_nsec += 100000000L;
            if (ts.tv_nsec >= 1000000000L) { ts.tv_sec++; ts.tv_nsec -= 1000000000L; }
            pthread_cond_timedwait(&c->cv, &c->mu, &ts);
            double f = items > 0 ? (double)c->items_done / items : 1.0;
            pthread_mutex_unlock(&c->mu);
            c->d.progress(c->d.progress_user, f0 + (f1 - f0) * f);
            pthread_mutex_lock(&c->mu);
        }
        pthread_mutex_unlock(&c->mu);
    }
    for (int i = 0; i < started; i++) pthread_join(th[i], NULL);
}

/* ------------------------------------------------------------------ */
/* caustics                                                            */

/* The caustic grid's region: the part of the world square where the
 * terrain can be under the water (h < level + wave height bound), found on
 * a REGION_SAMPLES^2 lattice and widened by one lattice step. 0 = none. */
static int caustic_region(const ref_world *w, double time, double box[4]) {
    double hs = w->d.half_size, sp = 2 * hs / (REGION_SAMPLES - 1), hb;
    ref_waves_bounds_at(&w->waves, time, &hb, NULL, NULL);   /* the frame's */
    double top = w->d.water_level + hb;
    double x0 = INFINITY, x1 = -INFINITY, z0 = INFINITY, z1 = -INFINITY;
    for (int j = 0; j < REGION_SAMPLES; j++)
        for (int i = 0; i < REGION_SAMPLES; i++) {
            double x = -hs + i * sp, z = -hs + j * sp;
            if (ref_terrain_height(w, x, z) < top) {
                x0 = fmin(x0, x); x1 = fmax(x1, x);
                z0 = fmin(z0, z); z1 = fmax(z1, z);
            }
        }
    if (!(x1 >= x0)) return 0;
    box[0] = fmax(-hs, x0 - sp);
    box[1] = fmin(hs, x1 + sp);
    box[2] = fmax(-hs, z0 - sp);
    box[3] = fmin(hs, z1 + sp);
    return box[1] > box[0] && box[3] > box[2];
}

/* The emission margin around the grid's flat-water preimage. A photon
 * meeting the floor at X (depth D under the highest wave) left the flat
 * path by at most D tan(half the largest surface tilt, at most 45 degrees),
 * plus the waves' height seen along the sun; X lies dist(X) inside the
 * grid's edge, so the margin must cover D tan - dist(X) over the grid (on
 * the REGION_SAMPLES lattice, plus a lattice step), plus two cells. Where
 * the grid's edge is dry land (the lake) this is far smaller than
 * ref_caustics' automatic margin, which assumes the deepest water at the
 * edge. */
static double photon_margin(const ref_world *w, double time, const double box[4], double cell) {
    const double *sun = w->d.sun_dir;
    double hs = w->d.half_size, sp = 2 * hs / (REGION_SAMPLES - 1), hb, wsb;
    ref_waves_bounds_at(&w->waves, time, &hb, NULL, &wsb);   /* the frame's */
    double top = w->d.water_level + hb;
    double tilt = atan(isfinite(wsb) ? wsb : 10.0), tn = tan(fmin(0.5 * tilt, PI / 4));
    double need = 0;
    for (int j = 0; j < REGION_SAMPLES; j++)
        for (int i = 0; i < REGION_SAMPLES; i++) {
            double x = -hs + i * sp, z = -hs + j * sp;
            if (x < box[0] || x > box[1] || z < box[2] || z > box[3]) continue;
            double dist = fmin(fmin(x - box[0], box[1] - x), fmin(z - box[2], box[3] - z));
            double depth = top - ref_terrain_height(w, x, z);
            if (depth > 0) need = fmax(need, depth * tn - dist);
        }
    return 2 * cell + hb * (2 + hypot(sun[0], sun[2]) / sun[1]) + need +
           (need > 0 ? sp : 0);
}

/* The photon tracer's seed for a render's: 0 stays 0 (ref_caustics' fixed
 * default, so a render without a seed is the one it always was); any other
 * seed is scrambled by splitmix64 so that seeds 1, 2, 3 give unrelated
 * per-stratum streams (the tracer xors the seed with the stratum index times
 * an odd constant: nearby raw seeds would give nearby states). */
static uint64_t photon_seed(uint64_t seed) {
    if (seed == 0) return 0;
    uint64_t s = seed;
    uint64_t m = ref_splitmix64(&s);
    return m ? m : 1;   /* 0 would mean the default again */
}

/* Plans the photons and allocates the grid; 0 (r->have_caustics says
 * whether there are photons to trace) or -1. */
static int plan_caustics(rctx *c, worker *wk, char *err, size_t errlen) {
    const ref_world *w = c->w;
    ref_render_result *r = c->out;
    double box[4];
    if (!(w->d.sun_dir[1] > 1e-6) || !caustic_region(w, c->d.time, box)) return 0;   /* flat sun: zero or everywhere */
    double ex = box[1] - box[0], ez = box[3] - box[2];
    double cell = fmax(ex, ez) / c->d.caustic_res;
    int nx = (int)ceil(ex / cell - 1e-9), nz = (int)ceil(ez / cell - 1e-9);
    if (nx < 1) nx = 1;
    if (nz < 1) nz = 1;

    ref_caustics_desc cd;
    memset(&cd, 0, sizeof cd);
    cd.waves = &w->waves;
    cd.time = c->d.time;
    memcpy(cd.sun_dir, w->d.sun_dir, sizeof cd.sun_dir);
    cd.sun_irradiance = 1.0;
    cd.n_air = c->n_air;
    cd.n_water = c->n_water;
    cd.floor = &c->ter;
    memcpy(cd.sigma, w->d.absorption, sizeof cd.sigma);
    cd.x0 = box[0];
    cd.z0 = box[2];
    cd.x1 = box[0] + nx * cell;
    cd.z1 = box[2] + nz * cell;
    cd.nx = nx;
    cd.nz = nz;
    cd.photons_per_cell = c->d.photons_per_cell;
    cd.seed = photon_seed(c->d.seed);
    cd.margin = photon_margin(w, c->d.time, box, cell);
    cd.opts.t_tol = PHOTON_T_TOL;

    ref_caustics *g = &r->caustics;
    if (ref_caustics_plan_init(&cd, &g->plan, err, errlen) != 0) return -1;
    size_t n = (size_t)nx * nz;
    g->nx = nx; g->nz = nz;
    g->x0 = cd.x0; g->z0 = cd.z0; g->x1 = cd.x1; g->z1 = cd.z1;
    g->irradiance = mem_zalloc(n * 3 * sizeof *g->irradiance);
    g->area = mem_zalloc(n * sizeof *g->area);
    for (int i = 0; i < c->nthreads; i++) wk[i].buf = mem_alloc(n * 3 * sizeof *wk[i].buf);
    r->have_caustics = 1;
    return 0;
}

/* Traces the planned photons on every thread; irradiance = flux / area. */
static void trace_caustics(rctx *c, worker *wk, double f1) {
    ref_caustics *g = &c->out->caustics;
    size_t n = (size_t)g->nx * g->nz;
    c->plan = &g->plan;
    c->flux = g->irradiance;
    c->stats = &g->stats;
    int chunks = (g->plan.mz + PHOTON_CHUNK_ROWS - 1) / PHOTON_CHUNK_ROWS;
    run_phase(c, photon_worker, wk, chunks, 0.0, f1);
    ref_caustics_cell_areas(&g->plan, g->area);
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) g->irradiance[i * 3 + k] /= g->area[i];
    c->grid = g;
    g->plan.d.floor = NULL;   /* it pointed into this render's context */
}

/* ------------------------------------------------------------------ */
/* the renderer                                                        */

void ref_render_free(ref_render_result *r) {
    if (!r) return;
    free(r->color);
    free(r->mask);
    free(r->surface);
    free(r->refract_hit);
    free(r->reflect);
    free(r->fresnel);
    free(r->depth);
    free(r->irradiance);
    ref_caustics_free(&r->caustics);
    memset(r, 0, sizeof *r);
}

static int check_desc(const ref_render_desc *d, char *err, size_t errlen) {
    const ref_camera *c = &d->camera;
    if (!d->world) { msg_set(err, errlen, "reference: no world"); return -1; }
    if (c->width > 16384 || c->height > 16384 || (long)c->width * c->height > (1L << 26)) {
        msg_set(err, errlen, "reference: image size %dx%d out of range", c->width, c->height);
        return -1;
    }
    if (d->spp > MAX_SPP) {
        msg_set(err, errlen, "reference: %d x %d subsamples per pixel (at most %d x %d)", d->spp,
                d->spp, MAX_SPP, MAX_SPP);
        return -1;
    }
    if (d->nsamples < 0 || d->nsamples > REF_MAX_SAMPLES) {
        msg_set(err, errlen, "reference: %d subsample positions (at most %d)", d->nsamples, REF_MAX_SAMPLES);
        return -1;
    }
    for (int k = 0; k < d->nsamples; k++)
        if (!(d->samples[k][0] >= 0 && d->samples[k][0] < 1 && d->samples[k][1] >= 0 && d->samples[k][1] < 1)) {
            msg_set(err, errlen, "reference: subsample position %d (%g, %g) is outside the pixel [0, 1)^2", k,
                    d->samples[k][0], d->samples[k][1]);
            return -1;
        }
    if (d->caustic_res > 8192 || d->photons_per_cell > 1 << 20 || d->max_depth > 64) {
        msg_set(err, errlen, "reference: caustic_res, photons_per_cell or max_depth out of range");
        return -1;
    }
    if (d->caustics != REF_CAUSTICS_PHOTONS && d->caustics != REF_CAUSTICS_FLAT) {
        msg_set(err, errlen, "reference: unknown caustics mode %d", d->caustics);
        return -1;
    }
    /* at most caustic_res^2 cells, 3 doubles each per thread, plus the
     * irradiance and area of the result */
    double grid = (double)d->caustic_res * d->caustic_res * 3 * sizeof(double) * (d->threads + 2);
    if (d->caustics == REF_CAUSTICS_PHOTONS && grid > MAX_CAUSTIC_BYTES) {
        msg_set(err, errlen, "reference: a %d x %d caustic grid on %d threads needs %.0f GiB (at most %.0f); "
                "lower the caustic resolution or the threads", d->caustic_res, d->caustic_res, d->threads,
                grid / (1 << 30), MAX_CAUSTIC_BYTES / (1 << 30));
        return -1;
    }
    double f[3] = { c->center[0] - c->eye[0], c->center[1] - c->eye[1], c->center[2] - c->eye[2] }, s[3];
    for (int i = 0; i < 3; i++)
        if (!isfinite(c->eye[i]) || !isfinite(c->center[i]) || !isfinite(c->up[i])) {
            msg_set(err, errlen, "reference: camera has a non-finite number");
            return -1;
        }
    if (vec3_normalize(f) == 0) { msg_set(err, errlen, "reference: camera eye equals its centre"); return -1; }
    vec3_cross(f, c->up, s);
    if (sqrt(vec3_dot(s, s)) < 1e-9 * sqrt(vec3_dot(c->up, c->up))) {
        msg_set(err, errlen, "reference: camera up lies along the line of sight");
        return -1;
    }
    if (!(c->fov_deg < 179.0)) { msg_set(err, errlen, "reference: field of view %g out of range", c->fov_deg); return -1; }
    return 0;
}

int ref_render(const ref_render_desc *din, ref_render_result *out, char *err, size_t errlen) {
    memset(out, 0, sizeof *out);
    ref_render_desc d = ref_render_resolve(din);
    if (check_desc(&d, err, errlen) != 0) return -1;

    rctx *c = mem_zalloc(sizeof *c);
    worker *wk = mem_zalloc((size_t)d.threads * sizeof *wk);
    c->w = d.world;
    c->d = d;
    c->level = d.world->d.water_level;
    c->n_air = REF_N_AIR;
    c->n_water = d.world->d.ior;
    c->t0 = 1.0 - ref_fresnel(1.0, c->n_air, c->n_water);
    make_terrain(d.world, &c->ter);
    c->opts.t_tol = d.t_tol;
    c->opts.t_max = RAY_T_MAX;
    c->nthreads = d.threads;
    c->out = out;
    pthread_mutex_init(&c->mu, NULL);
    pthread_cond_init(&c->cv, NULL);
    for (int i = 0; i < d.threads; i++) wk[i].c = c;
    ref_waves_ctx_begin(&c->waves, &d.world->waves, d.time);

    int w = d.camera.width, h = d.camera.height;
    size_t np = (size_t)w * h;
    out->width = w;
    out->height = h;
    out->spp = d.spp;
    out->nsamples = d.nsamples;
    out->threads = d.threads;
    out->color = mem_alloc(np * 3 * sizeof *out->color);
    out->mask = mem_alloc(np);
    out->surface = mem_alloc(np * 3 * sizeof *out->surface);
    out->refract_hit = mem_alloc(np * 4 * sizeof *out->refract_hit);
    out->reflect = mem_alloc(np * 4 * sizeof *out->reflect);
    out->fresnel = mem_alloc(np * sizeof *out->fresnel);
    out->depth = mem_alloc(np * sizeof *out->depth);
    out->irradiance = mem_alloc(np * 3 * sizeof *out->irradiance);
    int rc = 0;

    double eh = ref_waves_ctx_height(&c->waves, d.camera.eye[0], d.camera.eye[2]);
    c->eye_in_water = d.camera.eye[1] - eh < 0;

    if (rc == 0 && d.caustics == REF_CAUSTICS_PHOTONS) rc = plan_caustics(c, wk, err, errlen);
    /* progress weights: a photon is one unit, a pixel ray PIXEL_PHOTON_COST */
    int rays = d.nsamples > 0 ? d.nsamples + 1 : d.spp * d.spp + (d.spp % 2 == 0);
    double pixel_work = (double)np * rays * PIXEL_PHOTON_COST;
    double photon_work = out->have_caustics ? (double)out->caustics.plan.mx * out->caustics.plan.mz : 0.0;
    double f1 = photon_work / (photon_work + pixel_work);
    if (rc == 0 && out->have_caustics) {
        double t0 = clock_now_s();
        trace_caustics(c, wk, f1);
        out->seconds_photons = clock_now_s() - t0;
    }
    if (rc == 0) {
        double t0 = clock_now_s();
        run_phase(c, pixel_worker, wk, h, f1, 1.0);
        out->seconds_pixels = clock_now_s() - t0;
        if (d.progress) d.progress(d.progress_user, 1.0);
    }

    for (int i = 0; i < d.threads; i++) free(wk[i].buf);
    ref_waves_ctx_end(&c->waves);
    pthread_cond_destroy(&c->cv);
    pthread_mutex_destroy(&c->mu);
    free(wk);
    free(c);
    if (rc != 0) ref_render_free(out);
    return rc;
}
