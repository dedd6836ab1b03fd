/* ref_trace: ray casting against water and terrain, attenuation, photons
 * (see ref_trace.h). */
#include "ref_trace.h"
#include "mem.h"
#include "strbuf.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DEFAULT_T_MAX 1e4
#define DEFAULT_T_TOL 1e-9
#define DEFAULT_MAX_STEPS 1000000
#define TERRAIN_DEFAULT_STEP 0.01
#define TERRAIN_DEFAULT_MIN_STEP 1e-5
#define TERRAIN_FD_STEP 6e-6
#define BRENT_MAX_IT 200

typedef struct trace_params {
    double t_min, t_max, t_tol, min_step;
    int max_steps;
} trace_params;

static trace_params resolve_opts(const ref_trace_opts *o) {
    trace_params p;
    p.t_min = o ? o->t_min : 0.0;
    p.t_max = o && o->t_max > 0.0 ? o->t_max : DEFAULT_T_MAX;
    p.t_tol = o && o->t_tol > 0.0 ? o->t_tol : DEFAULT_T_TOL;
    p.min_step = o && o->min_step > 0.0 ? o->min_step : 0.0;   /* per-surface default */
    p.max_steps = o && o->max_steps > 0 ? o->max_steps : DEFAULT_MAX_STEPS;
    return p;
}

/* ------------------------------------------------------------------ */
/* Brent's root finder on a bracket [a, b] with f(a) f(b) < 0          */

typedef double (*root_fn)(void *ctx, double t);

static double brent_root(root_fn f, void *ctx, double a, double b, double fa, double fb,
                         double tol, int *evals) {
    double c = a, fc = fa, d = b - a, e = d;
    for (int it = 0; it < BRENT_MAX_IT; it++) {
        if ((fb > 0.0 && fc > 0.0) || (fb < 0.0 && fc < 0.0)) {
            c = a; fc = fa; d = e = b - a;
        }
        if (fabs(fc) < fabs(fb)) {
            a = b; b = c; c = a;
            fa = fb; fb = fc; fc = fa;
        }
        double tol1 = 2.0 * DBL_EPSILON * fabs(b) + 0.5 * tol;
        double xm = 0.5 * (c - b);
        if (fabs(xm) <= tol1 || fb == 0.0) return b;
        if (fabs(e) >= tol1 && fabs(fa) > fabs(fb)) {
            double p, q, r, s = fb / fa;
            if (a == c) {
                p = 2.0 * xm * s;
                q = 1.0 - s;
            } else {
                q = fa / fc;
                r = fb / fc;
                p = s * (2.0 * xm * q * (q - r) - (b - a) * (r - 1.0));
                q = (q - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if (p > 0.0) q = -q;
            p = fabs(p);
            double m1 = 3.0 * xm * q - fabs(tol1 * q), m2 = fabs(e * q);
            if (2.0 * p < (m1 < m2 ? m1 : m2)) {
                e = d;
                d = p / q;
            } else {
                d = xm; e = d;
            }
        } else {
            d = xm; e = d;
        }
        a = b; fa = fb;
        b += fabs(d) > tol1 ? d : copysign(tol1, xm);
        fb = f(ctx, b);
        (*evals)++;
    }
    return b;
}

/* Clips t to the slab lo <= y <= hi; returns 0 when the segment misses it. */
static int clip_slab(double oy, double dy, double lo, double hi, double *ta, double *tb) {
    if (dy == 0.0) return oy >= lo && oy <= hi;
    double t1 = (lo - oy) / dy, t2 = (hi - oy) / dy;
    if (t1 > t2) { double s = t1; t1 = t2; t2 = s; }
    if (t1 > *ta) *ta = t1;
    if (t2 < *tb) *tb = t2;
    return *ta <= *tb;
}

/* ------------------------------------------------------------------ */
/* water                                                               */

typedef struct water_ctx {
    const ref_waves_ctx *wc;
    const double *o, *d;
    ref_waves_track track;      /* the last sample's rest point: the next one's start */
    int rc;                     /* the last sample's inversion: 0 when it converged */
    double seg_t0, seg_t1, seg_lip;   /* |f'| <= seg_lip on [seg_t0, seg_t1] (regional_step) */
} water_ctx;

/* f(t) = y(t) - H(x(t), z(t)): > 0 above the water */
static double water_f(void *vctx, double t) {
    water_ctx *c = vctx;
    double x = c->o[0] + t * c->d[0], z = c->o[2] + t * c->d[2];
    double uv[2], h;
    c->rc = ref_waves_ctx_track(c->wc, x, z, &c->track, uv, &h);
    return c->o[1] + t * c->d[1] - h;
}

/* The longest step from t (where |f| = af) that the world-slope bound of
 * the region it crosses allows. Any dt with dt <= af / L(dt), L(dt) =
 * |d.y| + (a world-slope bound over the ray's (x, z) on [t, t + dt]) |d.xz|
 * a Lipschitz bound of f there, cannot step over a crossing: |f| > 0 on
 * [t, t + dt). With the most hopeful reach, cand = af / L(0) (the bound at
 * the point), dt = min(cand, af / L(cand)) is such a dt (the bound over
 * [t, t + dt] is at most the one over [t, t + cand]), and at least the
 * frame's step af / L(everywhere). The bounds are those of the world points
 * within a distance of the ray's point at t, from its rest point (the last
 * sample's, when its inversion converged: ref_waves_ctx_world_slope_near).
 * 0 where none is known (the region may fold, or f is not a number). */
static double regional_step(water_ctx *c, double t, double af, double dh) {
    const double *o = c->o, *d = c->d;
    if (!(af >= 0.0)) return 0.0;
    if (t >= c->seg_t0 && t < c->seg_t1) {          /* the segment's bound still holds */
        double dt = af / c->seg_lip;
        if (t + dt <= c->seg_t1) return dt;
    }
    double x = o[0] + t * d[0], z = o[2] + t * d[2], ay = fabs(d[1]);
    const double *uv = c->track.valid && c->rc == 0 ? c->track.uv : (const double[2]){ NAN, NAN };
    double l0 = ay + ref_waves_ctx_world_slope_near(c->wc, x, z, uv, 0.0) * dh;
    if (!(l0 > 0.0) || !isfinite(l0)) return 0.0;
    double cand = af / l0;
    double l1 = ay + ref_waves_ctx_world_slope_near(c->wc, x, z, uv, cand * dh) * dh;
    if (!(l1 > 0.0) || !isfinite(l1)) return 0.0;
    c->seg_t0 = t;
    c->seg_t1 = t + cand;
    c->seg_lip = l1;
    double dt = af / l1;
    return dt < cand ? dt : cand;
}

int ref_trace_water(const ref_waves *w, double time, const double o[3], const double d[3],
                    const ref_trace_opts *opts, ref_water_hit *hit) {
    ref_waves_ctx wc;
    ref_waves_ctx_begin(&wc, w, time);
    int rc = ref_trace_water_ctx(&wc, o, d, opts, hit);
    ref_waves_ctx_end(&wc);
    return rc;
}

int ref_trace_water_ctx(const ref_waves_ctx *wc, const double o[3], const double d[3],
                        const ref_trace_opts *opts, ref_water_hit *hit) {
    trace_params tp = resolve_opts(opts);
    memset(hit, 0, sizeof *hit);
    const ref_waves *w = wc->w;
    /* the frame's own bounds (an ocean's any-time bounds are far looser) */
    double level = w->desc.level, hb = wc->height, wsb = wc->world_slope;
    double pad = 1e-7 * (1.0 + fabs(level) + hb);
    double ta = tp.t_min, tb = tp.t_max;
    if (!clip_slab(o[1], d[1], level - hb - pad, level + hb + pad, &ta, &tb)) return 0;

    double dlen = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double dh = hypot(d[0], d[2]);
    double lip = fabs(d[1]) + wsb * dh;   /* |f'(t)| <= lip */
    /* with an ocean, each step takes the bound of the region it goes
     * through (regional_step), which may be finite where the frame's is
     * not (the sea folds somewhere else) */
    int regional = wc->ocean != NULL && dh > 0.0;
    /* min_wavelength is at most the finest ocean cascade's 2 texels, so the
     * least step is a 64th of its texel. Where the sideways maps may fold
     * (Gerstner Q + the ocean's chop >= 1 over the region a step reaches,
     * or over the frame without an ocean) the world slope is unbounded and
     * the march goes at this least step: it then finds every crossing of
     * the surface whose sign change spans more than one step (a fold
     * thinner than 1/64 texel along the ray may be stepped over), and
     * where the inversion fails (NaN height: the surface is not a height
     * field there) the sign test is false and the march goes on. */
    double min_step = (tp.min_step > 0.0 ? tp.min_step : w->min_wavelength / 128.0) / dlen;
    /* Where the sea folds, the height over a world point is not one number
     * and no Lipschitz bound holds; marching at min_step there took minutes
     * a ray (scenes/hard/ocean_fold.glib: over 5 min for 96x54). So there
     * the march steps as if the sideways map's smallest singular value were
     * REF_TRACE_FOLD_FLOOR: a fold narrower than the surface's height
     * change over such a step may be stepped over. A folding sea is the
     * reference's own limit: it draws one sheet where several lie. */
    double lip_fold = fabs(d[1]) + wc->slope / REF_TRACE_FOLD_FLOOR * dh;

    water_ctx c = { .wc = wc, .o = o, .d = d, .seg_t0 = INFINITY, .seg_t1 = -INFINITY };
    double t = ta, ft = water_f(&c, t);
    int evals = 1, found = 0;
    double tr = t;
    if (ft == 0.0) {
        found = 1;
    } else {
        for (int step = 0; step < tp.max_steps && t < tb; step++) {
            double dt = isfinite(lip) && lip > 0.0 ? fabs(ft) / lip : min_step;
            if (regional) {
                double dr = regional_step(&c, t, fabs(ft), dh);
                if (dr > dt) dt = dr;
            }
            if (!isfinite(lip) && isfinite(ft) && lip_fold > 0.0 && fabs(ft) / lip_fold > dt)
                dt = fabs(ft) / lip_fold;           /* the sea folds: see lip_fold */
            if (!(dt >= min_step)) dt = min_step;   /* and where f is NaN (a fold) */
            double tn = t + dt < tb ? t + dt : tb;
            double fn = water_f(&c, tn);
            evals++;
            if (fn == 0.0) { tr = tn; found = 1; break; }
            if ((fn > 0.0) != (ft > 0.0)) {
                tr = brent_root(water_f, &c, t, tn, ft, fn, tp.t_tol, &evals);
                found = 1;
                break;
            }
            t = tn; ft = fn;
        }
    }
    hit->evals = evals;
    if (!found) return 0;
    hit->hit = 1;
    hit->t = tr;
    hit->from_below = ft < 0.0;
    double x = o[0] + tr * d[0], z = o[2] + tr * d[2];
    ref_waves_ctx_at(wc, x, z, c.track.valid ? c.track.uv : NULL, &hit->surf);
    return 1;
}

/* ------------------------------------------------------------------ */
/* terrain                                                             */

typedef struct terrain_ctx {
    const ref_terrain *ter;
    const double *o, *d;
} terrain_ctx;

static double terrain_g(void *vctx, double t) {
    terrain_ctx *c = vctx;
    double x = c->o[0] + t * c->d[0], z = c->o[2] + t * c->d[2];
    return c->o[1] + t * c->d[1] - c->ter->height(c->ter->user, x, z);
}

void ref_terrain_normal(const ref_terrain *ter, double x, double z, double n[3]) {
    double g[2];
    if (ter->gradient) {
        ter->gradient(ter->user, x, z, g);
    } else {
        /* ~ cbrt(eps * scale): balances truncation h^2 |h'''| / 6 against
         * rounding eps |x| |h'| / h */
        double h = TERRAIN_FD_STEP * cbrt(fmax(1.0, fmax(fabs(x), fabs(z))));
        g[0] = (ter->height(ter->user, x + h, z) - ter->height(ter->user, x - h, z)) / (2.0 * h);
        g[1] = (ter->height(ter->user, x, z + h) - ter->height(ter->user, x, z - h)) / (2.0 * h);
    }
    double l = sqrt(1.0 + g[0] * g[0] + g[1] * g[1]);
    n[0] = -g[0] / l;
    n[1] = 1.0 / l;
    n[2] = -g[1] / l;
}

static void terrain_fill(const ref_terrain *ter, const double o[3], const double d[3], double t,
                         ref_terrain_hit *hit) {
    hit->hit = 1;
    hit->t = t;
    hit->pos[0] = o[0] + t * d[0];
    hit->pos[2] = o[2] + t * d[2];
    hit->pos[1] = ter->height(ter->user, hit->pos[0], hit->pos[2]);
    ref_terrain_normal(ter, hit->pos[0], hit->pos[2], hit->normal);
}

int ref_trace_terrain(const ref_terrain *ter, const double o[3], const double d[3],
                      const ref_trace_opts *opts, ref_terrain_hit *hit) {
    trace_params tp = resolve_opts(opts);
    memset(hit, 0, sizeof *hit);
    terrain_ctx c = { .ter = ter, .o = o, .d = d };
    double ta = tp.t_min, tb = tp.t_max;
    double dlen = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);

    if (ter->bounded) {
        double y0 = o[1] + ta * d[1];
        if (y0 < ter->ymin) {                 /* starts below every point of it */
            hit->inside = 1;
            terrain_fill(ter, o, d, ta, hit);
            return 1;
        }
        if (!clip_slab(o[1], d[1], ter->ymin, ter->ymax, &ta, &tb)) return 0;
    }
    double t = ta, gt = terrain_g(&c, t);
    int evals = 1;
    if (gt < 0.0 && t == tp.t_min) {
        hit->inside = 1;
        hit->evals = evals;
        terrain_fill(ter, o, d, t, hit);
        return 1;
    }
    double lip = 0.0, fixed = (ter->step > 0.0 ? ter->step : TERRAIN_DEFAULT_STEP) / dlen;
    double min_step = (ter->min_step > 0.0 ? ter->min_step : TERRAIN_DEFAULT_MIN_STEP) / dlen;
    if (ter->lipschitz > 0.0) lip = fabs(d[1]) + ter->lipschitz * hypot(d[0], d[2]);
    if (ter->lipschitz == 0.0 && fabs(d[0]) + fabs(d[2]) == 0.0) lip = fabs(d[1]);  /* vertical ray */

    int found = 0;
    double tr = t;
    if (gt == 0.0) found = 1;
    for (int step = 0; !found && step < tp.max_steps && t < tb; step++) {
        double dt = lip > 0.0 ? fabs(gt) / lip : fixed;
        if (lip > 0.0 && dt < min_step) dt = min_step;
        double tn = t + dt < tb ? t + dt : tb;
        double gn = terrain_g(&c, tn);
        evals++;
        if (gn == 0.0) { tr = tn; found = 1; break; }
        if ((gn > 0.0) != (gt > 0.0)) {
            tr = brent_root(terrain_g, &c, t, tn, gt, gn, tp.t_tol, &evals);
            found = 1;
            break;
        }
        t = tn; gt = gn;
    }
    hit->evals = evals;
    if (!found) return 0;
    terrain_fill(ter, o, d, tr, hit);
    return 1;
}

/* ------------------------------------------------------------------ */
/* attenuation, refraction                                             */

void ref_beer_lambert(const double sigma[3], double distance, double trans[3]) {
    for (int c = 0; c < 3; c++) trans[c] = exp(-sigma[c] * distance);
}

int ref_trace_refraction(const ref_waves *w, double time, double n_air, double n_water,
                         const ref_terrain *ter, const double o[3], const double d[3],
                         const ref_trace_opts *opts, ref_refraction *out) {
    memset(out, 0, sizeof *out);
    out->water_path = INFINITY;
    if (!ref_trace_water(w, time, o, d, opts, &out->water)) return 0;
    const ref_waves_point *s = &out->water.surf;
    int below = out->water.from_below;
    out->n1 = below ? n_water : n_air;
    out->n2 = below ? n_air : n_water;
    double dn = d[0] * s->normal[0] + d[1] * s->normal[1] + d[2] * s->normal[2];
    out->cos_i = fabs(dn);
    out->fresnel = ref_fresnel(out->cos_i, out->n1, out->n2);
    ref_reflect(d, s->normal, out->reflect_dir);
    out->tir = !ref_refract(d, s->normal, out->n1, out->n2, out->refract_dir);
    if (below) out->water_path = out->water.t - (opts ? opts->t_min : 0.0);
    if (!out->tir && ter) {
        ref_trace_opts o2 = opts ? *opts : (ref_trace_opts){ 0 };
        o2.t_min = 0.0;
        if (o2.t_max > 0.0) o2.t_max -= out->water.t;
        if (ref_trace_terrain(ter, s->pos, out->refract_dir, &o2, &out->floor) && !below)
            out->water_path = out->floor.t;
    }
    return 1;
}

/* ------------------------------------------------------------------ */
/* photons                                                             */

uint64_t ref_splitmix64(uint64_t *state) {
    uint64_t z = (*state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

static double rand01(uint64_t *s) { return (double)(ref_splitmix64(s) >> 11) * 0x1.0p-53; }

static double floor_height(const ref_caustics_desc *d, double x, double z) {
    return d->floor ? d->floor->height(d->floor->user, x, z) : d->floor_y;
}

int ref_caustics_plan_init(const ref_caustics_desc *din, ref_caustics_plan *p, char *err, size_t errlen) {
    memset(p, 0, sizeof *p);
    ref_caustics_desc d = *din;
    if (!d.waves) { msg_set(err, errlen, "caustics: no wave set"); return -1; }
    if (!(d.x1 > d.x0) || !(d.z1 > d.z0)) {
        msg_set(err, errlen, "caustics: empty floor region [%g, %g] x [%g, %g]", d.x0, d.x1, d.z0, d.z1);
        return -1;
    }
    if (d.floor && !d.floor->height) { msg_set(err, errlen, "caustics: floor without a height function"); return -1; }
    if (d.nx == 0) d.nx = 64;
    if (d.nz == 0) d.nz = 64;
    if (d.nx < 0 || d.nz < 0 || (long)d.nx * d.nz > (1L << 26)) {
        msg_set(err, errlen, "caustics: grid %d x %d out of range", d.nx, d.nz);
        return -1;
    }
    if (d.photons_per_cell == 0) d.photons_per_cell = 256;
    if (d.photons_per_cell < 0) { msg_set(err, errlen, "caustics: photons_per_cell < 0"); return -1; }
    if (d.sun_irradiance == 0.0) d.sun_irradiance = 1.0;
    if (d.n_air == 0.0) d.n_air = REF_N_AIR;
    if (d.n_water == 0.0) d.n_water = REF_N_WATER;
    if (d.seed == 0) d.seed = 0x7a726e2d63617573ULL;   /* "tarn-caus"-ish */

    double sl = sqrt(d.sun_dir[0] * d.sun_dir[0] + d.sun_dir[1] * d.sun_dir[1] + d.sun_dir[2] * d.sun_dir[2]);
    if (sl == 0.0) { p->sun[0] = 0.0; p->sun[1] = 1.0; p->sun[2] = 0.0; }
    else for (int i = 0; i < 3; i++) p->sun[i] = d.sun_dir[i] / sl;
    if (!(p->sun[1] > 1e-6)) { msg_set(err, errlen, "caustics: the sun is below the horizon"); return -1; }

    const ref_waves *w = d.waves;
    double level = w->desc.level;
    p->cell_dx = (d.x1 - d.x0) / d.nx;
    p->cell_dz = (d.z1 - d.z0) / d.nz;
    double hb_t, wsb_t;        /* the frame's bounds */
    ref_waves_bounds_at(w, d.time, &hb_t, NULL, &wsb_t);
    p->emit_y = level + hb_t + 1e-3 * (1.0 + hb_t);

    /* floor height range (bounds, or samples at the cell corners) */
    double ylo, yhi;
    if (!d.floor) {
        ylo = yhi = d.floor_y;
    } else if (d.floor->bounded) {
        ylo = d.floor->ymin; yhi = d.floor->ymax;
    } else {
        ylo = INFINITY; yhi = -INFINITY;
        for (int j = 0; j <= d.nz; j++)
            for (int i = 0; i <= d.nx; i++) {
                double y = floor_height(&d, d.x0 + i * p->cell_dx, d.z0 + j * p->cell_dz);
                if (y < ylo) ylo = y;
                if (y > yhi) yhi = y;
            }
    }
    if (yhi > level) yhi = level;
    if (ylo > level) ylo = level;

    /* the flat-water preimage: floor point X came from the emission point
     * X - t_h (level - y_f) / |t_y| + s_h (emit_y - level) / s_y */
    double down[3] = { -p->sun[0], -p->sun[1], -p->sun[2] }, tdir[3];
    double up[3] = { 0.0, 1.0, 0.0 };
    ref_refract(down, up, d.n_air, d.n_water, tdir);
    double ox_lo = INFINITY, ox_hi = -INFINITY, oz_lo = INFINITY, oz_hi = -INFINITY;
    for (int k = 0; k < 2; k++) {
        double yf = k ? yhi : ylo;
        double ox = -tdir[0] * (level - yf) / -tdir[1] + p->sun[0] * (p->emit_y - level) / p->sun[1];
        double oz = -tdir[2] * (level - yf) / -tdir[1] + p->sun[2] * (p->emit_y - level) / p->sun[1];
        ox_lo = fmin(ox_lo, ox); ox_hi = fmax(ox_hi, ox);
        oz_lo = fmin(oz_lo, oz); oz_hi = fmax(oz_hi, oz);
    }
    double margin = d.margin;
    if (margin == 0.0) {
        /* two cells, the waves' height seen along the sun, and the sideways
         * drift of rays bent by tilted normals (half the tilt, at most 45
         * degrees) over the depth */
        double tilt = atan(isfinite(wsb_t) ? wsb_t : 10.0);
        margin = 2.0 * fmax(p->cell_dx, p->cell_dz) +
                 hb_t * (2.0 + hypot(p->sun[0], p->sun[2]) / p->sun[1]) +
                 (level - ylo) * tan(fmin(0.5 * tilt, M_PI / 4.0));
    }
    double ex1, ez1;
    p->ex0 = d.x0 + ox_lo - margin;
    ex1 = d.x1 + ox_hi + margin;
    p->ez0 = d.z0 + oz_lo - margin;
    ez1 = d.z1 + oz_hi + margin;

    int k = (int)lround(sqrt((double)d.photons_per_cell));
    if (k < 1) k = 1;
    double mxd = ceil((ex1 - p->ex0) / (p->cell_dx / k));
    double mzd = ceil((ez1 - p->ez0) / (p->cell_dz / k));
    if (mxd * mzd > 4e9) { msg_set(err, errlen, "caustics: too many photons (%g)", mxd * mzd); return -1; }
    p->mx = (int)mxd;
    p->mz = (int)mzd;
    p->sx = (ex1 - p->ex0) / p->mx;
    p->sz = (ez1 - p->ez0) / p->mz;
    p->photon_flux = d.sun_irradiance * p->sun[1] * p->sx * p->sz;
    p->d = d;
    return 0;
}

void ref_caustics_trace_rows(const ref_caustics_plan *p, int row0, int row1,
                             double *flux, ref_caustics_stats *st) {
    const ref_caustics_desc *d = &p->d;
    const ref_waves *w = d->waves;
    ref_caustics_stats s;
    memset(&s, 0, sizeof s);
    double down[3] = { -p->sun[0], -p->sun[1], -p->sun[2] };
    ref_trace_opts wopts = d->opts;
    double level = w->desc.level;
    if (row0 < 0) row0 = 0;
    if (row1 > p->mz) row1 = p->mz;
    ref_waves_ctx wc;   /* the frame, looked up once for all these photons */
    ref_waves_ctx_begin(&wc, w, d->time);

    for (int j = row0; j < row1; j++) {
        for (int i = 0; i < p->mx; i++) {
            uint64_t rng = d->seed ^ ((uint64_t)j * (uint64_t)p->mx + (uint64_t)i) * 0xD1B54A32D192ED03ULL;
            ref_splitmix64(&rng);
            double o[3];
            o[0] = p->ex0 + (i + rand01(&rng)) * p->sx;
            o[1] = p->emit_y;
            o[2] = p->ez0 + (j + rand01(&rng)) * p->sz;
            double phi = p->photon_flux;
            s.photons++;
            s.flux_emitted += phi;

            ref_water_hit wh;
            if (!ref_trace_water_ctx(&wc, o, down, &wopts, &wh)) continue;

            /* dry land before the water: the sun lights it directly */
            if (d->floor && (!d->floor->bounded || d->floor->ymax > level - w->height_bound)) {
                ref_trace_opts dry = wopts;
                dry.t_max = wh.t;
                ref_terrain_hit th;
                if (ref_trace_terrain(d->floor, o, down, &dry, &th)) {
                    s.hit_dry++;
                    double fx = (th.pos[0] - d->x0) / p->cell_dx, fz = (th.pos[2] - d->z0) / p->cell_dz;
                    if (fx >= 0.0 && fz >= 0.0 && fx < d->nx && fz < d->nz) {
                        size_t cell = (size_t)((int)fz * d->nx + (int)fx) * 3;
                        for (int ch = 0; ch < 3; ch++) {
                            flux[cell + ch] += phi;
                            s.flux_in_grid[ch] += phi;
                        }
                        s.in_grid++;
                    }
                    continue;
                }
            }
            s.hit_water++;
            const double *nrm = wh.surf.normal;
            double cos_i = -(down[0] * nrm[0] + down[1] * nrm[1] + down[2] * nrm[2]);
            double R = ref_fresnel(cos_i, d->n_air, d->n_water);
            s.flux_reflected += phi * R;
            s.flux_transmitted += phi * (1.0 - R);
            double tdir[3];
            if (!ref_refract(down, nrm, d->n_air, d->n_water, tdir)) continue;   /* cannot happen from air */

            double pos[3], dist;
            if (d->floor) {
                ref_trace_opts fo = wopts;
                fo.t_min = 0.0;
                ref_terrain_hit th;
                if (!ref_trace_terrain(d->floor, wh.surf.pos, tdir, &fo, &th)) continue;
                memcpy(pos, th.pos, sizeof pos);
                dist = th.t;
            } else {
                if (!(tdir[1] < 0.0) || wh.surf.pos[1] < d->floor_y) continue;
                dist = (d->floor_y - wh.surf.pos[1]) / tdir[1];
                pos[0] = wh.surf.pos[0] + dist * tdir[0];
                pos[1] = d->floor_y;
                pos[2] = wh.surf.pos[2] + dist * tdir[2];
            }
            s.hit_floor++;
            double fx = (pos[0] - d->x0) / p->cell_dx, fz = (pos[2] - d->z0) / p->cell_dz;
            if (!(fx >= 0.0 && fz >= 0.0 && fx < d->nx && fz < d->nz)) continue;
            size_t cell = (size_t)((int)fz * d->nx + (int)fx) * 3;
            double tr[3];
            ref_beer_lambert(d->sigma, dist, tr);
            for (int ch = 0; ch < 3; ch++) {
                double e = phi * (1.0 - R) * tr[ch];
                flux[cell + ch] += e;
                s.flux_in_grid[ch] += e;
            }
            s.in_grid++;
        }
    }
    ref_waves_ctx_end(&wc);
    if (st) {
        st->photons += s.photons;
        st->hit_water += s.hit_water;
        st->hit_dry += s.hit_dry;
        st->hit_floor += s.hit_floor;
        st->in_grid += s.in_grid;
        st->flux_emitted += s.flux_emitted;
        st->flux_reflected += s.flux_reflected;
        st->flux_transmitted += s.flux_transmitted;
        for (int ch = 0; ch < 3; ch++) st->flux_in_grid[ch] += s.flux_in_grid[ch];
    }
}

void ref_caustics_cell_areas(const ref_caustics_plan *p, double *area) {
    const ref_caustics_desc *d = &p->d;
    double flat = p->cell_dx * p->cell_dz;
    for (int j = 0; j < d->nz; j++)
        for (int i = 0; i < d->nx; i++) {
            if (!d->floor) { area[j * d->nx + i] = flat; continue; }
            double a = 0.0;
            for (int b = 0; b < 4; b++)
                for (int c = 0; c < 4; c++) {
                    double x = d->x0 + (i + (c + 0.5) / 4.0) * p->cell_dx;
                    double z = d->z0 + (j + (b + 0.5) / 4.0) * p->cell_dz;
                    double n[3];
                    ref_terrain_normal(d->floor, x, z, n);
                    a += 1.0 / n[1];            /* sqrt(1 + |grad h|^2) */
                }
            area[j * d->nx + i] = a * flat / 16.0;
        }
}

int ref_caustics_trace(const ref_caustics_desc *d, ref_caustics *out, char *err, size_t errlen) {
    memset(out, 0, sizeof *out);
    if (ref_caustics_plan_init(d, &out->plan, err, errlen) != 0) return -1;
    const ref_caustics_plan *p = &out->plan;
    int nx = p->d.nx, nz = p->d.nz;
    out->nx = nx; out->nz = nz;
    out->x0 = p->d.x0; out->z0 = p->d.z0; out->x1 = p->d.x1; out->z1 = p->d.z1;
    out->irradiance = mem_zalloc((size_t)nx * nz * 3 * sizeof *out->irradiance);
    out->area = mem_zalloc((size_t)nx * nz * sizeof *out->area);
    ref_caustics_trace_rows(p, 0, p->mz, out->irradiance, &out->stats);
    ref_caustics_cell_areas(p, out->area);
    for (size_t c = 0; c < (size_t)nx * nz; c++)
        for (int ch = 0; ch < 3; ch++) out->irradiance[c * 3 + ch] /= out->area[c];
    return 0;
}

void ref_caustics_free(ref_caustics *c) {
    free(c->irradiance);
    free(c->area);
    c->irradiance = NULL;
    c->area = NULL;
}
