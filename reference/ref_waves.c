/* ref_waves: sum of sines, Gerstner and noise waves in double precision
 * (see ref_waves.h; the float twin is packs/common/waves.glsl). */
#include "ref_waves.h"
#include "ref_hash.h"
#include "strbuf.h"
#include "vec3.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#define TWO_PI 6.283185307179586476925286766559

/* The bound |grad n| <= 7.4 of one octave of the gradient noise below (unit
 * gradients, quintic fade): each partial is a convex blend of
 * (1-s) g.x + s g'.x + fade'(f) (v' - v), |.| <= 1 + 1.875 * 2 sqrt(1.25)
 * < 5.2, so the norm is below 5.2 sqrt 2 < 7.4. Its value is below
 * sqrt(2)/2 (the classic bound for 2D gradient noise); 0.75 leaves room. */
#define NOISE_GRAD_BOUND 7.4
#define NOISE_VALUE_BOUND 0.75

/* ------------------------------------------------------------------ */
/* defaults, in one place                                              */

ref_waves_desc ref_waves_default(void) {
    ref_waves_desc d;
    memset(&d, 0, sizeof d);
    d.level = 0.0;
    d.steepness = 0.6;
    d.gerstner_count = 4;
    d.gerstner[0] = (ref_wave_desc){ .angle_deg = 20.0,  .wavelength = 9.0, .amplitude = 0.10 };
    d.gerstner[1] = (ref_wave_desc){ .angle_deg = -15.0, .wavelength = 5.3, .amplitude = 0.06, .phase = 1.0 };
    d.gerstner[2] = (ref_wave_desc){ .angle_deg = 50.0,  .wavelength = 3.1, .amplitude = 0.035, .phase = 2.0 };
    d.gerstner[3] = (ref_wave_desc){ .angle_deg = 95.0,  .wavelength = 1.7, .amplitude = 0.018, .phase = 4.0 };
    d.sine_count = 2;
    d.sine[0] = (ref_wave_desc){ .angle_deg = 160.0, .wavelength = 2.3, .amplitude = 0.012 };
    d.sine[1] = (ref_wave_desc){ .angle_deg = 70.0,  .wavelength = 1.1, .amplitude = 0.006, .phase = 0.5 };
    d.noise = (ref_noise_desc){ .amplitude = 0.01, .cell = 2.0, .octaves = 3, .period = 32,
                                .gain = 0.5, .angle_deg = 30.0, .seed = 1 };
    return d;
}

static double deep_water_speed(double wavelength) {
    return sqrt(REF_GRAVITY * wavelength / TWO_PI);
}

static int wave_finite(const ref_wave_desc *w) {
    return isfinite(w->angle_deg) && isfinite(w->wavelength) && isfinite(w->amplitude) &&
           isfinite(w->speed) && isfinite(w->phase);
}

static int wave_active(const ref_wave_desc *w) {
    return w->wavelength > 0.0 && w->amplitude != 0.0;
}

static ref_wave_comp make_comp(const ref_wave_desc *wd) {
    ref_wave_comp c;
    double a = wd->angle_deg * (TWO_PI / 360.0);
    c.dir[0] = cos(a);
    c.dir[1] = sin(a);
    c.k = TWO_PI / wd->wavelength;
    c.amp = wd->amplitude;
    c.omega = wd->speed * c.k;
    c.phase = wd->phase;
    c.qa = 0.0;
    return c;
}


/* The bounds every model adds to as it is set up: the height's and the
 * slope's (in the parameter domain), and the smallest feature. */
typedef struct bounds {
    double height, slope, lmin;
} bounds;

static void bounds_add(bounds *b, double height, double slope, double feature) {
    b->height += height;
    b->slope += slope;
    if (feature < b->lmin) b->lmin = feature;
}

/* The sine and Gerstner sets' counts and values, the steepness, the level. */
static int check_waves(const ref_waves_desc *d, char *err, size_t errlen) {
    if (d->sine_count < 0 || d->sine_count > REF_WAVES_MAX) {
        msg_set(err, errlen, "sine_count %d out of range 0..%d", d->sine_count, REF_WAVES_MAX);
        return -1;
    }
    if (d->gerstner_count < 0 || d->gerstner_count > REF_WAVES_MAX) {
        msg_set(err, errlen, "gerstner_count %d out of range 0..%d", d->gerstner_count, REF_WAVES_MAX);
        return -1;
    }
    if (!isfinite(d->steepness) || d->steepness < 0.0) {
        msg_set(err, errlen, "steepness Q must be finite and >= 0 (got %g)", d->steepness);
        return -1;
    }
    if (!isfinite(d->level)) {
        msg_set(err, errlen, "level must be finite");
        return -1;
    }
    for (int i = 0; i < d->sine_count; i++)
        if (!wave_finite(&d->sine[i])) { msg_set(err, errlen, "sine wave %d has a non-finite value", i); return -1; }
    for (int i = 0; i < d->gerstner_count; i++)
        if (!wave_finite(&d->gerstner[i])) { msg_set(err, errlen, "Gerstner wave %d has a non-finite value", i); return -1; }
    return 0;
}

/* The noise's defaults (zero means default) filled in, then checked. */
static int resolve_noise(ref_noise_desc *nd, char *err, size_t errlen) {
    if (nd->cell == 0.0) nd->cell = REF_NOISE_DEFAULT_CELL;
    if (nd->octaves == 0) nd->octaves = REF_NOISE_DEFAULT_OCTAVES;
    if (nd->period == 0) nd->period = REF_NOISE_DEFAULT_PERIOD;
    if (nd->gain == 0.0) nd->gain = REF_NOISE_DEFAULT_GAIN;
    if (nd->speed == 0.0) nd->speed = deep_water_speed(2.0 * nd->cell);
    if (!isfinite(nd->amplitude) || !isfinite(nd->cell) || !isfinite(nd->gain) ||
        !isfinite(nd->angle_deg) || !isfinite(nd->speed) || nd->cell < 0.0) {
        msg_set(err, errlen, "noise parameters must be finite, cell > 0");
        return -1;
    }
    if (nd->octaves < 0 || nd->octaves > REF_NOISE_OCTAVES_MAX) {
        msg_set(err, errlen, "noise octaves %d out of range 1..%d", nd->octaves, REF_NOISE_OCTAVES_MAX);
        return -1;
    }
    if (nd->period < 0 || nd->period > (1 << 16)) {
        msg_set(err, errlen, "noise period %d out of range 1..65536", nd->period);
        return -1;
    }
    return 0;
}

/* The active sines and Gerstner waves as components (a wave's speed 0:
 * deep water's). */
static void add_waves(ref_waves *w, ref_waves_desc *d, bounds *b) {
    for (int i = 0; i < d->sine_count; i++) {
        ref_wave_desc *wd = &d->sine[i];
        if (!wave_active(wd)) continue;
        if (wd->speed == 0.0) wd->speed = deep_water_speed(wd->wavelength);
        ref_wave_comp c = make_comp(wd);
        w->sine[w->nsine++] = c;
        bounds_add(b, fabs(c.amp), c.k * fabs(c.amp), wd->wavelength);
    }
    int ng = 0;
    for (int i = 0; i < d->gerstner_count; i++) ng += wave_active(&d->gerstner[i]);
    for (int i = 0; i < d->gerstner_count; i++) {
        ref_wave_desc *wd = &d->gerstner[i];
        if (!wave_active(wd)) continue;
        if (wd->speed == 0.0) wd->speed = deep_water_speed(wd->wavelength);
        ref_wave_comp c = make_comp(wd);
        /* Q_i = Q / (k_i A_i N): the horizontal amplitude Q_i A_i = Q / (k_i N). */
        c.qa = d->steepness / (c.k * ng);
        if (c.amp < 0.0) c.qa = -c.qa;      /* keeps Q_i >= 0 for a negative A */
        w->gerstner[w->ngerstner++] = c;
        w->q_sum += fabs(c.qa) * c.k;       /* Q_i k_i |A_i| = Q / N */
        bounds_add(b, fabs(c.amp), c.k * fabs(c.amp), wd->wavelength);
    }
}

/* The noise's octaves, each twice as fine and gain times as high as the
 * one before, turned by REF_NOISE_TURN. */
static void add_noise(ref_waves *w, const ref_noise_desc *nd, bounds *b) {
    if (nd->amplitude == 0.0) return;
    w->noctaves = nd->octaves;
    double amp = nd->amplitude, scale = 1.0;
    for (int o = 0; o < nd->octaves; o++) {
        ref_noise_octave *oc = &w->octave[o];
        double ang = nd->angle_deg * (TWO_PI / 360.0) + o * REF_NOISE_TURN;
        double spd = nd->speed / sqrt(scale);
        oc->freq = scale / nd->cell;
        oc->amp = amp;
        oc->drift[0] = spd * cos(ang);
        oc->drift[1] = spd * sin(ang);
        oc->period = nd->period * scale;
        oc->seed = ref_hash32(nd->seed + (uint32_t)o * 0x9E3779B9U);
        b->height += fabs(amp) * NOISE_VALUE_BOUND;
        b->slope += fabs(amp) * oc->freq * NOISE_GRAD_BOUND;
        amp *= nd->gain;
        scale *= 2.0;
    }
    double finest = nd->cell / (scale * 0.5);
    if (finest < b->lmin) b->lmin = finest;
}

/* The explosion rings with i0 != 0 and the Perlin set (height only),
 * resolved and checked. */
static int add_wave_fx(ref_waves *w, ref_waves_desc *d, bounds *b, char *err, size_t errlen) {
    if (d->explosion_count < 0 || d->explosion_count > REF_EXPLOSIONS_MAX) {
        msg_set(err, errlen, "explosion_count %d out of range 0..%d", d->explosion_count, REF_EXPLOSIONS_MAX);
        return -1;
    }
    for (int i = 0; i < d->explosion_count; i++) {
        if (ref_explosion_resolve(&d->explosion[i], err, errlen) != 0) return -1;
        if (d->explosion[i].i0 == 0.0) continue;
        ref_explosion_desc *e = &w->explosion[w->nexplosions++];
        *e = d->explosion[i];
        double eh, es;
        ref_explosion_bounds(e, &eh, &es);
        bounds_add(b, eh, es, TWO_PI / e->k);
    }
    if (ref_perlin_resolve(&d->perlin, err, errlen) != 0) return -1;
    if (d->perlin.amplitude != 0.0) {
        w->has_perlin = 1;
        w->perlin = d->perlin;
        double ph, ps;
        ref_perlin_bounds(&w->perlin, &ph, &ps);
        /* the finest octave's lattice cell (2^(octaves-1) finer than cell) */
        bounds_add(b, ph, ps, d->perlin.cell / ldexp(1.0, d->perlin.octaves - 1));
    }
    return 0;
}

/* The spectrum ocean, if any: the one part that holds memory. */
static int add_ocean(ref_waves *w, ref_waves_desc *d, bounds *b, char *err, size_t errlen) {
    if (d->ocean.spectrum == REF_SPECTRUM_NONE) return 0;
    w->ocean = ref_ocean_create(&d->ocean, err, errlen);
    if (!w->ocean) return -1;
    d->ocean = *ref_ocean_get_desc(w->ocean);
    ref_ocean_bounds_any(w->ocean, &w->ocean_any);
    bounds_add(b, w->ocean_any.height, w->ocean_any.slope, ref_ocean_min_wavelength(w->ocean));
    return 0;
}

int ref_waves_init(ref_waves *w, const ref_waves_desc *desc, char *err, size_t errlen) {
    ref_waves_desc d;
    if (desc) d = *desc;
    else memset(&d, 0, sizeof d);
    memset(w, 0, sizeof *w);
    if (err && errlen) err[0] = '\0';
    if (check_waves(&d, err, errlen) != 0 || resolve_noise(&d.noise, err, errlen) != 0) return -1;
    bounds b = { 0.0, 0.0, INFINITY };
    add_waves(w, &d, &b);
    add_noise(w, &d.noise, &b);
    if (add_wave_fx(w, &d, &b, err, errlen) != 0) return -1;
    w->fixed_height = b.height;
    w->fixed_slope = b.slope;
    if (add_ocean(w, &d, &b, err, errlen) != 0) return -1;
    w->desc = d;
    w->height_bound = b.height;
    w->slope_bound = b.slope;
    w->fold_bound = w->q_sum + w->ocean_any.chop;
    w->world_slope_bound = w->fold_bound < 1.0 ? b.slope / (1.0 - w->fold_bound) : INFINITY;
    w->min_wavelength = isfinite(b.lmin) ? b.lmin : 1.0;
    return 0;
}

void ref_waves_release(ref_waves *w) {
    if (!w) return;
    ref_ocean_destroy(w->ocean);
    w->ocean = NULL;
}

/* The bounds with the ocean's frame bounds ob (NULL: no ocean). */
static void bounds_with(const ref_waves *w, const ref_ocean_bounds *ob, double *height, double *slope,
                        double *world_slope) {
    double h = w->height_bound, s = w->slope_bound, fold = w->fold_bound;
    if (ob) {
        h = w->fixed_height + ob->height;
        s = w->fixed_slope + ob->slope;
        fold = w->q_sum + ob->chop;
    }
    if (height) *height = h;
    if (slope) *slope = s;
    /* grad H = J^-T grad h, and J = I + (Gerstner's and the ocean's
     * sideways derivatives) has smallest singular value >= 1 - fold */
    if (world_slope) *world_slope = fold < 1.0 ? s / (1.0 - fold) : INFINITY;
}

void ref_waves_bounds_at(const ref_waves *w, double t, double *height, double *slope, double *world_slope) {
    ref_ocean_bounds b;
    if (w->ocean) ref_ocean_bounds_at(w->ocean, t, &b);
    bounds_with(w, w->ocean ? &b : NULL, height, slope, world_slope);
}

void ref_waves_ctx_begin(ref_waves_ctx *c, const ref_waves *w, double t) {
    c->w = w;
    c->t = t;
    c->ocean = w->ocean ? ref_ocean_snapshot_acquire(w->ocean, t) : NULL;
    ref_ocean_bounds b;
    if (c->ocean) ref_ocean_snapshot_bounds(c->ocean, &b);
    bounds_with(w, c->ocean ? &b : NULL, &c->height, &c->slope, &c->world_slope);
    c->fold = w->q_sum + (c->ocean ? b.chop : w->ocean_any.chop);
    /* the sideways displacement's range: Gerstner's |Dx| <= sum |Q_i A_i D.x|,
     * the ocean's between its nodes' extremes */
    double g[2] = { 0.0, 0.0 };
    for (int i = 0; i < w->ngerstner; i++)
        for (int q = 0; q < 2; q++) g[q] += fabs(w->gerstner[i].qa * w->gerstner[i].dir[q]);
    double lo[2] = { 0.0, 0.0 }, hi[2] = { 0.0, 0.0 };
    if (c->ocean) ref_ocean_snapshot_disp_range(c->ocean, lo, hi);
    for (int q = 0; q < 2; q++) {
        c->disp_lo[q] = lo[q] - g[q];
        c->disp_hi[q] = hi[q] + g[q];
    }
}

/* Why the box's bound holds. Let X be a world point of the box W =
 * [x0, x1] x [z0, z1] and p any rest point of it: p + D(p) = X, D the
 * whole sideways displacement, which lies in [disp_lo, disp_hi] per axis.
 * So p lies in the box B = [x0 - hi_x, x1 - lo_x] x [z0 - hi_z, z1 - lo_z],
 * convex. Over B, h is Lipschitz with S = fixed_slope + the ocean's box
 * slope, and D with C = q_sum + the ocean's box chop (ref_ocean.c,
 * cascade_bounds: a Gerstner wave's derivative -Q_i A_i k_i sin D D^T has
 * norm <= Q_i k_i |A_i|, and the noise, sines, rings and Perlin set do not
 * move points sideways). When C < 1, for p, q in B
 *     |F(p) - F(q)| >= |p - q| - |D(p) - D(q)| >= (1 - C) |p - q|,
 * F(p) = p + D(p): so X has exactly one rest point (all of them lie in B,
 * and two in B would be equal), the height over X is H(X) = h(p), and for
 * X, X' in W with rest points p, p'
 *     |H(X) - H(X')| = |h(p) - h(p')| <= S |p - p'| <= S / (1 - C) |X - X'|.
 * This needs C < 1 over B only: the sea may fold elsewhere. (The frame's
 * world_slope is the same with B the whole plane.) */
/* S and C over the rest box [u0, u1] x [v0, v1] */
static void rest_box(const ref_waves_ctx *c, double u0, double v0, double u1, double v1, double *s, double *fold) {
    double os, oc;
    ref_ocean_snapshot_box_bounds(c->ocean, u0, v0, u1, v1, &os, &oc);
    *s = c->w->fixed_slope + os;
    *fold = c->w->q_sum + oc;
}

double ref_waves_ctx_world_slope_box(const ref_waves_ctx *c, double x0, double z0, double x1, double z1) {
    if (!c->ocean) return c->world_slope;
    double s, fold;
    rest_box(c, x0 - c->disp_hi[0], z0 - c->disp_hi[1], x1 - c->disp_lo[0], z1 - c->disp_lo[1], &s, &fold);
    double ws = fold < 1.0 ? s / (1.0 - fold) : INFINITY;
    return ws < c->world_slope ? ws : c->world_slope;
}

/* Why the bound near a rest point holds. Let the frame's fold be < 1, so
 * F(p) = p + D(p) is one to one (ref_waves_ctx_world_slope_box's proof with
 * B the plane) and every world point has exactly one rest point. uv is X0's
 * rest point to the inversion's tolerance: |F(uv) - X0| <= pad. Let X be
 * within reach of X0, so within l = reach + pad of F(uv), and let D be Lipschitz with C < 1 on the box B of
 * half-width l / (1 - C) about uv. Then G(p) = X - D(p) maps the ball K of
 * radius l / (1 - C) about uv (inside B) into itself,
 *     |G(p) - uv| = |X - F(uv) - (D(p) - D(uv))| <= l + C |p - uv| <= l / (1 - C),
 * and is a contraction there, so X's rest point lies in K. So for X, X'
 * near X0 the rest points p, p' lie in B, and as in the box's proof
 * |H(X) - H(X')| <= S |p - p'| <= S / (1 - C) |X - X'|, S h's Lipschitz
 * bound on B. The first C is the frame's fold (valid everywhere); the box
 * it gives has its own C1 <= C, and the smaller box of half-width
 * l / (1 - C1) (inside the first, so C1 holds on it) gives C2; the bound
 * takes the least S and C of the boxes that hold the last ball. */
double ref_waves_ctx_world_slope_near(const ref_waves_ctx *c, double x, double z, const double uv[2],
                                      double reach) {
    if (!c->ocean) return c->world_slope;
    if (!(c->fold < 1.0) || !isfinite(uv[0]) || !isfinite(uv[1]) || !(reach >= 0.0))
        return ref_waves_ctx_world_slope_box(c, x - reach, z - reach, x + reach, z + reach);
    /* the inversion stops within 1e-12 max(1, |x|, |z|); the pad covers
     * that and the rounding of the caller's reach */
    double pad = 1e-9 * (1.0 + fabs(x) + fabs(z));
    /* the box's bound holds too (it is the better one when the reach is
     * long: its region grows with the displacement's range, not as
     * reach / (1 - C)): the better of the two */
    double wb = ref_waves_ctx_world_slope_box(c, x - reach - pad, z - reach - pad, x + reach + pad, z + reach + pad);
    double l = reach + pad, C = c->fold, S = INFINITY;
    for (int k = 0; k < (reach == 0.0 ? 1 : 2); k++) {   /* a point's box is a cell or two: once */
        double r = l / (1.0 - C), s1, c1;
        rest_box(c, uv[0] - r, uv[1] - r, uv[0] + r, uv[1] + r, &s1, &c1);
        if (s1 < S) S = s1;
        if (c1 < C) C = c1;
    }
    double ws = S / (1.0 - C);
    return ws < wb ? ws : wb;
}

void ref_waves_ctx_end(ref_waves_ctx *c) {
    if (c->ocean) ref_ocean_snapshot_release(c->ocean);
    c->ocean = NULL;
}

/* ------------------------------------------------------------------ */
/* evaluation                                                          */

static double fade(double x) { return x * x * x * (x * (x * 6.0 - 15.0) + 10.0); }
static double dfade(double x) { double m = x * (x - 1.0); return 30.0 * m * m; }

static double wrap_cell(double i, double period) { return i - period * floor(i / period); }

static void lattice_grad(uint32_t seed, double i, double j, double g[2]) {
    uint32_t h = ref_hash32((uint32_t)i + ref_hash32((uint32_t)j + seed));
    double a = (double)(h >> 8) * (TWO_PI / 16777216.0);
    g[0] = cos(a);
    g[1] = sin(a);
}

/* One octave of tileable gradient noise at lattice coordinates (px, pz):
 * value, and its gradient in lattice units. */
static double noise_octave(const ref_noise_octave *oc, double px, double pz, double dn[2]) {
    double fx = floor(px), fz = floor(pz);
    double x = px - fx, z = pz - fz;
    double i0 = wrap_cell(fx, oc->period), i1 = wrap_cell(fx + 1.0, oc->period);
    double j0 = wrap_cell(fz, oc->period), j1 = wrap_cell(fz + 1.0, oc->period);
    double ga[2], gb[2], gc[2], gd[2];
    lattice_grad(oc->seed, i0, j0, ga);
    lattice_grad(oc->seed, i1, j0, gb);
    lattice_grad(oc->seed, i0, j1, gc);
    lattice_grad(oc->seed, i1, j1, gd);
    double va = ga[0] * x + ga[1] * z;
    double vb = gb[0] * (x - 1.0) + gb[1] * z;
    double vc = gc[0] * x + gc[1] * (z - 1.0);
    double vd = gd[0] * (x - 1.0) + gd[1] * (z - 1.0);
    double ux = fade(x), uz = fade(z), dux = dfade(x), duz = dfade(z);
    double e = va - vb - vc + vd;
    double n = va + ux * (vb - va) + uz * (vc - va) + ux * uz * e;
    dn[0] = ga[0] + ux * (gb[0] - ga[0]) + uz * (gc[0] - ga[0]) +
            ux * uz * (ga[0] - gb[0] - gc[0] + gd[0]) + dux * (vb - va + uz * e);
    dn[1] = ga[1] + ux * (gb[1] - ga[1]) + uz * (gc[1] - ga[1]) +
            ux * uz * (ga[1] - gb[1] - gc[1] + gd[1]) + duz * (vc - va + ux * e);
    return n;
}

double ref_waves_noise(const ref_waves *w, double u, double v, double t, double grad[2]) {
    double h = 0.0, gx = 0.0, gz = 0.0;
    for (int o = 0; o < w->noctaves; o++) {
        const ref_noise_octave *oc = &w->octave[o];
        double dn[2];
        double px = (u - oc->drift[0] * t) * oc->freq;
        double pz = (v - oc->drift[1] * t) * oc->freq;
        h += oc->amp * noise_octave(oc, px, pz, dn);
        gx += oc->amp * oc->freq * dn[0];
        gz += oc->amp * oc->freq * dn[1];
    }
    if (grad) { grad[0] = gx; grad[1] = gz; }
    return h;
}

/* Everything at (u, v): height h and its partials, the Gerstner horizontal
 * displacement D and its Jacobian entries (a = dDx/du, b = dDx/dv = dDz/du,
 * d = dDz/dv). */
typedef struct wave_sums {
    double h, hu, hv;
    double dx, dz;
    double a, b, d;
} wave_sums;

/* What sum_waves works out: h alone (a march's height test), the position
 * (h and D), or the frame (and every derivative). */
enum { SUM_HEIGHT, SUM_POSITION, SUM_FRAME };

static void sum_waves(const ref_waves_ctx *ctx, double u, double v, int what, wave_sums *s) {
    const ref_waves *w = ctx->w;
    double t = ctx->t;
    int derivs = what == SUM_FRAME;
    memset(s, 0, sizeof *s);
    for (int i = 0; i < w->nsine; i++) {
        const ref_wave_comp *c = &w->sine[i];
        double th = c->k * (c->dir[0] * u + c->dir[1] * v) + c->omega * t + c->phase;
        double sn = sin(th);
        s->h += c->amp * sn;
        if (derivs) {
            double kc = c->k * c->amp * cos(th);
            s->hu += kc * c->dir[0];
            s->hv += kc * c->dir[1];
        }
    }
    for (int i = 0; i < w->ngerstner; i++) {
        const ref_wave_comp *c = &w->gerstner[i];
        double th = c->k * (c->dir[0] * u + c->dir[1] * v) + c->omega * t + c->phase;
        double sn = sin(th);
        s->h += c->amp * sn;
        if (what == SUM_HEIGHT) continue;
        double cs = cos(th);
        s->dx += c->qa * c->dir[0] * cs;
        s->dz += c->qa * c->dir[1] * cs;
        if (derivs) {
            double kc = c->k * c->amp * cs;
            double qs = c->qa * c->k * sn;
            s->hu += kc * c->dir[0];
            s->hv += kc * c->dir[1];
            s->a -= qs * c->dir[0] * c->dir[0];
            s->b -= qs * c->dir[0] * c->dir[1];
            s->d -= qs * c->dir[1] * c->dir[1];
        }
    }
    if (w->noctaves) {
        double g[2];
        s->h += ref_waves_noise(w, u, v, t, derivs ? g : NULL);
        if (derivs) { s->hu += g[0]; s->hv += g[1]; }
    }
    for (int i = 0; i < w->nexplosions; i++) {
        double g[2];
        s->h += ref_explosion_height(&w->explosion[i], u, v, t, derivs ? g : NULL);
        if (derivs) { s->hu += g[0]; s->hv += g[1]; }
    }
    if (w->has_perlin) {
        double g[2];
        s->h += ref_perlin_height(&w->perlin, u, v, t, derivs ? g : NULL);
        if (derivs) { s->hu += g[0]; s->hv += g[1]; }
    }
    if (ctx->ocean && what == SUM_HEIGHT) {
        s->h += ref_ocean_snapshot_height(ctx->ocean, u, v);   /* one field, not eight */
    } else if (ctx->ocean) {
        ref_ocean_sample o;
        ref_ocean_snapshot_sample(ctx->ocean, u, v, &o);
        s->h += o.h;
        s->dx += o.dx;
        s->dz += o.dz;
        if (derivs) {
            /* the slope fields, not the bilinear h's own gradient: what the
             * GL shades with (smooth across cells) */
            s->hu += o.hx;
            s->hv += o.hz;
            s->a += o.dxx;
            s->b += o.dxz;
            s->d += o.dzz;
        }
    }
}

void ref_waves_displace(const ref_waves *w, double u, double v, double t, double pos[3]) {
    wave_sums s;
    ref_waves_ctx c;
    ref_waves_ctx_begin(&c, w, t);
    sum_waves(&c, u, v, SUM_POSITION, &s);
    ref_waves_ctx_end(&c);
    pos[0] = u + s.dx;
    pos[1] = w->desc.level + s.h;
    pos[2] = v + s.dz;
}

static void fill_point(const ref_waves *w, double u, double v, const wave_sums *s, ref_waves_point *p) {
    p->param[0] = u;
    p->param[1] = v;
    p->pos[0] = u + s->dx;
    p->pos[1] = w->desc.level + s->h;
    p->pos[2] = v + s->dz;
    /* B = dP/du, T = dP/dv */
    double B[3] = { 1.0 + s->a, s->hu, s->b };
    double T[3] = { s->b, s->hv, 1.0 + s->d };
    memcpy(p->dpdu, B, sizeof B);
    memcpy(p->dpdv, T, sizeof T);
    /* N = T x B (y up) */
    p->normal[0] = T[1] * B[2] - T[2] * B[1];
    p->normal[1] = T[2] * B[0] - T[0] * B[2];
    p->normal[2] = T[0] * B[1] - T[1] * B[0];
    vec3_normalize(p->normal);
    /* chapter eq. 12: (-sum D.x WA C, 1 - sum Q_i WA S, -sum D.z WA C);
     * 1 + a + d = 1 - sum Q_i k A sin since |D| = 1 */
    p->normal_approx[0] = -s->hu;
    p->normal_approx[1] = 1.0 + s->a + s->d;
    p->normal_approx[2] = -s->hv;
    vec3_normalize(p->normal_approx);
    p->jacobian = (1.0 + s->a) * (1.0 + s->d) - s->b * s->b;
}

void ref_waves_ctx_eval(const ref_waves_ctx *c, double u, double v, ref_waves_point *out) {
    wave_sums s;
    sum_waves(c, u, v, SUM_FRAME, &s);
    fill_point(c->w, u, v, &s, out);
    out->residual = 0.0;
    out->iterations = 0;
}

void ref_waves_eval(const ref_waves *w, double u, double v, double t, ref_waves_point *out) {
    ref_waves_ctx c;
    ref_waves_ctx_begin(&c, w, t);
    ref_waves_ctx_eval(&c, u, v, out);
    ref_waves_ctx_end(&c);
}

/* ------------------------------------------------------------------ */
/* inversion: the undisplaced point under a world (x, z)               */

/* A point of the inversion: the rest point (u, v), the horizontal residual
 * F = (u + Dx - x, v + Dz - z) there, r = |F|, J = dF/d(u, v) = (dx/du,
 * dx/dv, dz/du, dz/dv) when it was asked for, and the ocean's height at
 * (u, v) (0 without one), which its map gives for free. */
typedef struct newton_pt {
    double u, v, F[2], r, J[4], ocean_h;
} newton_pt;

/* Fills p at (u, v) for the world point (x, z). Only the Gerstner waves and
 * the ocean move points sideways, so only they are summed. The ocean's part
 * of J is the exact derivative of its bilinear map in the cell
 * (ref_ocean_sample_map), so Newton converges as fast as on the Gerstner
 * waves. */
static void horiz_residual(const ref_waves_ctx *ctx, double u, double v, double x, double z,
                           int want_j, newton_pt *p) {
    const ref_waves *w = ctx->w;
    double t = ctx->t;
    double dx = 0.0, dz = 0.0, a = 0.0, b = 0.0, d = 0.0;
    for (int i = 0; i < w->ngerstner; i++) {
        const ref_wave_comp *c = &w->gerstner[i];
        double th = c->k * (c->dir[0] * u + c->dir[1] * v) + c->omega * t + c->phase;
        double cs = cos(th);
        dx += c->qa * c->dir[0] * cs;
        dz += c->qa * c->dir[1] * cs;
        if (want_j) {
            double qs = c->qa * c->k * sin(th);
            a -= qs * c->dir[0] * c->dir[0];
            b -= qs * c->dir[0] * c->dir[1];
            d -= qs * c->dir[1] * c->dir[1];
        }
    }
    double c = b;   /* dDz/du: = dDx/dv for Gerstner waves, not for the bilinear ocean */
    p->ocean_h = 0.0;
    if (ctx->ocean) {
        double D[2], jo[4];
        ref_ocean_snapshot_map(ctx->ocean, u, v, D, want_j ? jo : NULL, &p->ocean_h);
        dx += D[0];
        dz += D[1];
        if (want_j) { a += jo[0]; b += jo[1]; c += jo[2]; d += jo[3]; }
    }
    p->u = u;
    p->v = v;
    p->F[0] = u + dx - x;
    p->F[1] = v + dz - z;
    if (want_j) { p->J[0] = 1.0 + a; p->J[1] = b; p->J[2] = c; p->J[3] = 1.0 + d; }
    p->r = sqrt(p->F[0] * p->F[0] + p->F[1] * p->F[1]);   /* no overflow at these scales; hypot is slow */
}

/* The Newton step -J^-1 F at p; 0 when J is (nearly) singular. */
static int newton_step(const newton_pt *p, double *du, double *dv) {
    const double *J = p->J;
    double det = J[0] * J[3] - J[1] * J[2];
    if (!(fabs(det) > 1e-14)) return 0;
    *du = -( J[3] * p->F[0] - J[1] * p->F[1]) / det;
    *dv = -(-J[2] * p->F[0] + J[0] * p->F[1]) / det;
    return 1;
}

#define NEWTON_MAX_IT 50
#define NEWTON_MAX_HALVINGS 40
#define FIXED_POINT_MAX_IT 2000

/* Solves P_xz(u, v) = (x, z) from guess (NULL: (x, z)) into *p (its J is
 * the last Newton iterate's: the map's derivative near the solution). */
static int invert(const ref_waves_ctx *c, double x, double z, const double guess[2],
                  newton_pt *p, int *iterations) {
    double tol = 1e-12 * fmax(1.0, fmax(fabs(x), fabs(z)));
    int it = 0, ok = 0;
    horiz_residual(c, guess ? guess[0] : x, guess ? guess[1] : z, x, z, 1, p);
    if (!isfinite(p->r)) horiz_residual(c, x, z, x, z, 1, p);

    /* damped Newton: backtrack until |F| decreases */
    while (p->r > tol && it < NEWTON_MAX_IT) {
        it++;
        double du, dv;
        if (!newton_step(p, &du, &dv)) { du = -p->F[0]; dv = -p->F[1]; }   /* singular: a fixed-point step */
        double lam = 1.0;
        newton_pt n;
        int accepted = 0;
        for (int k = 0; k < NEWTON_MAX_HALVINGS; k++, lam *= 0.5) {
            horiz_residual(c, p->u + lam * du, p->v + lam * dv, x, z, 1, &n);
            if (n.r < p->r) { accepted = 1; break; }
        }
        if (!accepted) break;
        *p = n;
    }
    ok = p->r <= tol;
    /* polish: Newton converges quadratically, so one more step from a
     * residual at the tolerance lands at rounding level */
    double du, dv;
    if (ok && p->r > 0.0 && newton_step(p, &du, &dv)) {
        newton_pt n;
        horiz_residual(c, p->u + du, p->v + dv, x, z, 0, &n);
        if (n.r < p->r) { memcpy(n.J, p->J, sizeof n.J); *p = n; }
    }

    /* fallback: relaxed fixed point (u, v) <- (u, v) - alpha F; alpha = 1 is
     * the contraction (x, z) - D(u, v) when Q < 1, smaller alphas help when
     * it is not */
    if (!ok) {
        double alpha = 1.0;
        for (int k = 0; k < FIXED_POINT_MAX_IT && p->r > tol; k++) {
            it++;
            newton_pt n;
            horiz_residual(c, p->u - alpha * p->F[0], p->v - alpha * p->F[1], x, z, 0, &n);
            if (n.r < p->r) {
                memcpy(n.J, p->J, sizeof n.J);
                *p = n;
            } else {
                alpha *= 0.5;
                if (alpha < 1e-6) break;
            }
        }
        ok = p->r <= tol;
    }
    *iterations = it;
    return ok ? 0 : -1;
}

/* The height at the rest point p: every wave's but the ocean's summed, and
 * the ocean's from the inversion's own sample (the same number as
 * sum_waves' SUM_HEIGHT, added in the same order). */
static double height_at(const ref_waves_ctx *c, const newton_pt *p) {
    wave_sums s;
    ref_waves_ctx rest = *c;
    rest.ocean = NULL;
    sum_waves(&rest, p->u, p->v, SUM_HEIGHT, &s);
    return c->w->desc.level + (s.h + p->ocean_h);
}

int ref_waves_ctx_at(const ref_waves_ctx *c, double x, double z, const double guess[2],
                     ref_waves_point *out) {
    newton_pt p;
    int it;
    int rc = invert(c, x, z, guess, &p, &it);
    wave_sums s;
    sum_waves(c, p.u, p.v, SUM_FRAME, &s);
    fill_point(c->w, p.u, p.v, &s, out);
    out->residual = p.r;
    out->iterations = it;
    return rc;
}

int ref_waves_ctx_rest_point(const ref_waves_ctx *c, double x, double z, const double guess[2],
                             double uv[2], double *height) {
    newton_pt p;
    int it;
    int rc = invert(c, x, z, guess, &p, &it);
    uv[0] = p.u;
    uv[1] = p.v;
    if (height) *height = height_at(c, &p);
    return rc;
}

int ref_waves_ctx_track(const ref_waves_ctx *c, double x, double z, ref_waves_track *tr,
                        double uv[2], double *height) {
    double guess[2];
    if (tr->valid) {
        /* one Newton step from the last rest point, without sampling: its
         * residual for (x, z) is its own (at rounding level) plus the move */
        newton_pt last = { .u = tr->uv[0], .v = tr->uv[1], .F = { tr->x - x, tr->z - z } };
        memcpy(last.J, tr->jac, sizeof last.J);
        double du, dv;
        if (!newton_step(&last, &du, &dv)) { du = x - tr->x; dv = z - tr->z; }
        guess[0] = last.u + du;
        guess[1] = last.v + dv;
    }
    newton_pt p;
    int it;
    int rc = invert(c, x, z, tr->valid ? guess : NULL, &p, &it);
    uv[0] = p.u;
    uv[1] = p.v;
    if (height) *height = height_at(c, &p);
    /* kept after a failed inversion too (a fold): its best point is still
     * the nearest start the next query has */
    *tr = (ref_waves_track){ .valid = isfinite(p.u) && isfinite(p.v), .x = x, .z = z, .uv = { p.u, p.v } };
    memcpy(tr->jac, p.J, sizeof tr->jac);
    return rc;
}

double ref_waves_ctx_height(const ref_waves_ctx *c, double x, double z) {
    double uv[2], h;
    if (ref_waves_ctx_rest_point(c, x, z, NULL, uv, &h) != 0) return NAN;
    return h;
}

int ref_waves_at(const ref_waves *w, double x, double z, double t,
                 const double guess[2], ref_waves_point *out) {
    ref_waves_ctx c;
    ref_waves_ctx_begin(&c, w, t);
    int rc = ref_waves_ctx_at(&c, x, z, guess, out);
    ref_waves_ctx_end(&c);
    return rc;
}

int ref_waves_rest_point(const ref_waves *w, double x, double z, double t,
                         const double guess[2], double uv[2], double *height) {
    ref_waves_ctx c;
    ref_waves_ctx_begin(&c, w, t);
    int rc = ref_waves_ctx_rest_point(&c, x, z, guess, uv, height);
    ref_waves_ctx_end(&c);
    return rc;
}

double ref_waves_height(const ref_waves *w, double x, double z, double t) {
    ref_waves_ctx c;
    ref_waves_ctx_begin(&c, w, t);
    double h = ref_waves_ctx_height(&c, x, z);
    ref_waves_ctx_end(&c);
    return h;
}

/* ------------------------------------------------------------------ */
/* the GLSL uniforms                                                   */

static void put_scalar(ref_waves_uniform *u, const char *name, int is_int, double v) {
    memset(u, 0, sizeof *u);
    u->name = name;
    u->is_int = is_int;
    u->count = 1;
    u->comps = 1;
    if (is_int) u->i = (int)v;
    else u->v[0] = (float)v;
}

static void put_array(ref_waves_uniform *u, const char *name, const ref_wave_desc *w, int n, int field) {
    memset(u, 0, sizeof *u);
    u->name = name;
    u->count = REF_WAVES_MAX;
    u->comps = 1;
    for (int i = 0; i < n; i++) {
        double x = field == 0 ? w[i].angle_deg : field == 1 ? w[i].wavelength :
                   field == 2 ? w[i].amplitude : field == 3 ? w[i].speed : w[i].phase;
        u->v[i] = (float)x;
    }
}

static void put_vectors(ref_waves_uniform *u, const char *name, int comps) {
    memset(u, 0, sizeof *u);
    u->name = name;
    u->count = REF_WAVES_MAX;
    u->comps = comps;
}

/* One wave's (k D.x, k D.z, omega, phase). */
static void put_wave(float *v, const ref_wave_comp *c) {
    v[0] = (float)(c->k * c->dir[0]);
    v[1] = (float)(c->k * c->dir[1]);
    v[2] = (float)c->omega;
    v[3] = (float)c->phase;
}

/* uWave*: the resolved waves (waves.glsl's wavesSums, wavesNoise and
 * wavesRestPoint read these); returns how many were put. */
static int put_resolved(const ref_waves *w, ref_waves_uniform *all) {
    int n = 0;
    put_scalar(&all[n++], "uWaveSineN", 1, w->nsine);
    ref_waves_uniform *sine = &all[n++], *sine_amp = &all[n++];
    put_vectors(sine, "uWaveSine", 4);
    put_vectors(sine_amp, "uWaveSineAmp", 1);
    for (int i = 0; i < w->nsine; i++) {
        put_wave(sine->v + 4 * i, &w->sine[i]);
        sine_amp->v[i] = (float)w->sine[i].amp;
    }
    put_scalar(&all[n++], "uWaveGerstN", 1, w->ngerstner);
    ref_waves_uniform *gerst = &all[n++], *gerst_amp = &all[n++];
    put_vectors(gerst, "uWaveGerst", 4);
    put_vectors(gerst_amp, "uWaveGerstAmp", 3);
    for (int i = 0; i < w->ngerstner; i++) {
        const ref_wave_comp *c = &w->gerstner[i];
        put_wave(gerst->v + 4 * i, c);
        gerst_amp->v[3 * i] = (float)c->amp;
        gerst_amp->v[3 * i + 1] = (float)(c->qa * c->dir[0]);
        gerst_amp->v[3 * i + 2] = (float)(c->qa * c->dir[1]);
    }
    put_scalar(&all[n++], "uWaveNoiseN", 1, w->noctaves);
    ref_waves_uniform *noise = &all[n++], *period = &all[n++], *seed = &all[n++];
    put_vectors(noise, "uWaveNoise", 4);
    put_vectors(period, "uWaveNoisePeriod", 1);
    put_vectors(seed, "uWaveNoiseSeed", 1);
    seed->is_uint = 1;
    for (int o = 0; o < w->noctaves; o++) {
        const ref_noise_octave *oc = &w->octave[o];
        noise->v[4 * o] = (float)oc->freq;
        noise->v[4 * o + 1] = (float)(oc->freq * oc->drift[0]);
        noise->v[4 * o + 2] = (float)(oc->freq * oc->drift[1]);
        noise->v[4 * o + 3] = (float)oc->amp;
        period->v[o] = (float)oc->period;
        seed->u[o] = oc->seed;
    }
    return n;
}

int ref_waves_uniforms(const ref_waves *w, ref_waves_uniform *out, int max) {
    ref_waves_uniform all[REF_WAVES_UNIFORMS_MAX];
    const ref_waves_desc *d = &w->desc;
    int n = 0;
    put_scalar(&all[n++], "uWaterLevel", 0, d->level);
    put_scalar(&all[n++], "uSteepness", 0, d->steepness);
    put_scalar(&all[n++], "uSineCount", 1, d->sine_count);
    put_array(&all[n++], "uSineAngle", d->sine, d->sine_count, 0);
    put_array(&all[n++], "uSineLength", d->sine, d->sine_count, 1);
    put_array(&all[n++], "uSineAmp", d->sine, d->sine_count, 2);
    put_array(&all[n++], "uSineSpeed", d->sine, d->sine_count, 3);
    put_array(&all[n++], "uSinePhase", d->sine, d->sine_count, 4);
    put_scalar(&all[n++], "uGerstnerCount", 1, d->gerstner_count);
    put_array(&all[n++], "uGerstnerAngle", d->gerstner, d->gerstner_count, 0);
    put_array(&all[n++], "uGerstnerLength", d->gerstner, d->gerstner_count, 1);
    put_array(&all[n++], "uGerstnerAmp", d->gerstner, d->gerstner_count, 2);
    put_array(&all[n++], "uGerstnerSpeed", d->gerstner, d->gerstner_count, 3);
    put_array(&all[n++], "uGerstnerPhase", d->gerstner, d->gerstner_count, 4);
    put_scalar(&all[n++], "uNoiseAmp", 0, d->noise.amplitude);
    put_scalar(&all[n++], "uNoiseCell", 0, d->noise.cell);
    put_scalar(&all[n++], "uNoiseOctaves", 1, d->noise.octaves);
    put_scalar(&all[n++], "uNoisePeriod", 1, d->noise.period);
    put_scalar(&all[n++], "uNoiseGain", 0, d->noise.gain);
    put_scalar(&all[n++], "uNoiseAngle", 0, d->noise.angle_deg);
    put_scalar(&all[n++], "uNoiseSpeed", 0, d->noise.speed);
    /* the seed's 32 bits travel as an int; the GLSL reads uint(uNoiseSeed) */
    put_scalar(&all[n++], "uNoiseSeed", 1, 0.0);
    int32_t seed_bits;
    memcpy(&seed_bits, &d->noise.seed, sizeof seed_bits);
    all[n - 1].i = seed_bits;
    n += put_resolved(w, all + n);
    n += ref_wavefx_uniforms(w->explosion, w->nexplosions, w->has_perlin ? &w->perlin : NULL, all + n,
                             REF_WAVEFX_UNIFORMS_MAX);
    put_scalar(&all[n++], "uOceanN", 1, w->ocean ? w->desc.ocean.cascades : 0);
    put_scalar(&all[n++], "uOceanRes", 1, w->ocean ? w->desc.ocean.res : 0);
    ref_waves_uniform *tile = &all[n++];
    memset(tile, 0, sizeof *tile);
    tile->name = "uOceanTile";
    tile->count = REF_OCEAN_CASCADES_MAX;
    tile->comps = 1;
    for (int c = 0; w->ocean && c < w->desc.ocean.cascades; c++) tile->v[c] = (float)w->desc.ocean.tile[c];
    int k = n < max ? n : max;
    memcpy(out, all, (size_t)k * sizeof *out);
    return k;
}
