/* ref_waves: the water surface of the reference, in double precision.
 *
 * The wave set is the one packs/common/waves.glsl evaluates in float, with
 * the same parameters and the same formulas (one definition each side):
 *
 *   - sum of sines (height only):   h += A sin(k D.(u,v) + omega t + phase)
 *   - Gerstner waves (GPU Gems 1 ch. 1, eq. 9), parametric:
 *         x += Q_i A D.x cos(theta), z += Q_i A D.z cos(theta), h += A sin(theta)
 *     with Q_i = Q / (k_i A_i N), N the number of active Gerstner waves, so
 *     that sum Q_i k_i A_i = Q (the surface is loop-free while Q <= 1);
 *   - noise waves (height only): octaves of tileable 2D gradient noise
 *     (quintic fade, so C2), each drifting with its own velocity;
 *   - explosion rings and a 3D Perlin set (height only; ref_wavefx.h);
 *   - a spectrum ocean (ref_ocean.h): height, slopes and Tessendorf's
 *     sideways displacement, added like the Gerstner waves' (its Jacobian
 *     too). Where it folds (the map's Jacobian <= 0) the height over a
 *     world point is not unique: the inversion may fail (-1, NaN height)
 *     and world-space slope bounds are infinite.
 *
 * Coordinates: y is up, the mean water plane is y = level; (u, v) are the
 * undisplaced (rest) coordinates (x0, z0) of a surface point and P(u, v, t)
 * its displaced position. k = 2 pi / L is the chapter's frequency w; the
 * phase speed S gives omega = S k (the chapter's phi = S w).
 *
 * ref_waves_desc is a desc where zero means default (ref_waves_init fills
 * the defaults, in one place); the all-zero desc is calm flat water at y = 0.
 * ref_waves_default() is the lake's wave set. ref_waves is the resolved,
 * read-only form every query takes: all queries are pure and thread-safe.
 */
#ifndef TARN_REF_WAVES_H
#define TARN_REF_WAVES_H

#include <stddef.h>
#include <stdint.h>

#include "ref_ocean.h"
#include "ref_uniform.h"
#include "ref_wavefx.h"

#define REF_WAVES_MAX 8            /* sines, and Gerstner waves, each */
#define REF_NOISE_OCTAVES_MAX 8
#define REF_GRAVITY 9.81           /* for the deep-water phase speed */
#define REF_NOISE_TURN 0.5         /* radians the drift turns per noise octave */

/* Defaults for zero fields (the GLSL applies the same ones). */
#define REF_NOISE_DEFAULT_CELL 4.0
#define REF_NOISE_DEFAULT_OCTAVES 4
#define REF_NOISE_DEFAULT_PERIOD 16
#define REF_NOISE_DEFAULT_GAIN 0.5

typedef struct ref_wave_desc {
    double angle_deg;   /* direction of travel, degrees from +x towards +z */
    double wavelength;  /* L, world units; a wave with L <= 0 or A == 0 is inactive */
    double amplitude;   /* A */
    double speed;       /* phase speed S; 0 = deep water, sqrt(g L / 2 pi) */
    double phase;       /* phase offset, radians */
} ref_wave_desc;

typedef struct ref_noise_desc {
    double amplitude;   /* of octave 0; 0 = no noise */
    double cell;        /* world size of a lattice cell at octave 0 (0 = 4) */
    int octaves;        /* 0 = 4; octave o has frequency 2^o / cell */
    int period;         /* lattice cells per tile at octave 0 (0 = 16); the
                           noise repeats every period * cell in x and z */
    double gain;        /* amplitude ratio between octaves (0 = 0.5) */
    double angle_deg;   /* drift direction of octave 0; octave o turns by o * REF_NOISE_TURN */
    double speed;       /* drift speed of octave 0 (0 = deep-water speed for
                           wavelength 2 * cell); octave o drifts at speed / sqrt(2^o) */
    uint32_t seed;
} ref_noise_desc;

typedef struct ref_waves_desc {
    int sine_count;
    ref_wave_desc sine[REF_WAVES_MAX];
    int gerstner_count;
    ref_wave_desc gerstner[REF_WAVES_MAX];
    double steepness;   /* Q = sum Q_i k_i A_i; 0 = the Gerstner waves are plain sines */
    double level;       /* mean water height */
    ref_noise_desc noise;
    ref_ocean_desc ocean;          /* spectrum NONE (0): no ocean */
    int explosion_count;
    ref_explosion_desc explosion[REF_EXPLOSIONS_MAX];   /* i0 = 0: no ring */
    ref_perlin_desc perlin;        /* amplitude 0: no Perlin set */
} ref_waves_desc;

typedef struct ref_wave_comp {   /* one active wave, resolved */
    double dir[2];      /* unit (D.x, D.z) */
    double k;           /* 2 pi / L */
    double amp;         /* A */
    double omega;       /* S k */
    double phase;
    double qa;          /* Q_i A_i (Gerstner only; 0 for sines) */
} ref_wave_comp;

typedef struct ref_noise_octave {
    double freq;        /* lattice cells per world unit */
    double amp;
    double drift[2];    /* world velocity of the pattern */
    double period;      /* lattice cells per tile */
    uint32_t seed;      /* hashed per octave */
} ref_noise_octave;

typedef struct ref_waves {
    ref_waves_desc desc;       /* with the defaults filled in */
    int nsine, ngerstner, noctaves;
    ref_wave_comp sine[REF_WAVES_MAX];
    ref_wave_comp gerstner[REF_WAVES_MAX];
    ref_noise_octave octave[REF_NOISE_OCTAVES_MAX];
    double q_sum;              /* sum Q_i k_i A_i over active Gerstner waves */
    double height_bound;       /* |y - level| <= height_bound everywhere */
    double slope_bound;        /* |grad h(u, v)| <= slope_bound (parameter domain) */
    double world_slope_bound;  /* |grad H(x, z)| bound in world space: slope_bound
                                  / (1 - q_sum); INFINITY when q_sum >= 1 */
    double min_wavelength;     /* smallest feature: min L, noise cell / 2^(octaves-1),
                                  the ocean's finest 2 texels */
    /* explosion rings with i0 != 0 and the Perlin set, resolved */
    int nexplosions;
    ref_explosion_desc explosion[REF_EXPLOSIONS_MAX];
    int has_perlin;
    ref_perlin_desc perlin;
    /* The spectrum ocean, OWNED by this struct (NULL when there is none):
     * ref_waves_release frees it. A struct copy of a ref_waves (or of a
     * ref_world holding one) shares the pointer: exactly one copy is
     * released, and no copy is used after that. */
    ref_ocean *ocean;
    ref_ocean_bounds ocean_any;  /* ref_ocean_bounds_any (zero without an ocean) */
    double fixed_height, fixed_slope;   /* the bounds' parts of every model but the ocean */
    double fold_bound;         /* q_sum + ocean_any.chop: the sideways map's
                                  derivative has operator norm <= this at any time */
} ref_waves;

/* A point of the surface with its frame. */
typedef struct ref_waves_point {
    double param[2];         /* (u, v): the undisplaced point */
    double pos[3];           /* P(u, v, t) */
    double dpdu[3];          /* B = dP/du (the chapter's binormal) */
    double dpdv[3];          /* T = dP/dv (the chapter's tangent) */
    double normal[3];        /* exact unit normal, y > 0: normalize(T x B) in
                                this y-up frame = the chapter's cross(B, T) in
                                its z-up one */
    double normal_approx[3]; /* the chapter's eq. 12 (drops the cross terms),
                                normalised */
    double jacobian;         /* det d(x, z)/d(u, v) of the horizontal map;
                                > 0 where the surface has no loops */
    double residual;         /* ref_waves_at: |(x, z) - P_xz(u, v)| reached */
    int iterations;          /* ref_waves_at: iterations used */
} ref_waves_point;

/* The lake's wave set (Gerstner waves at Q = 0.6, sines and noise). */
ref_waves_desc ref_waves_default(void);

/* Resolves a desc (NULL = all zero = flat water). Returns 0, or -1 with a
 * message in err (when err is not NULL) for bad input: counts out of range,
 * non-finite numbers, negative steepness, a bad ocean, ring or Perlin set.
 * It builds the ocean (heap memory): release w with ref_waves_release when
 * done. w is overwritten, not released, so release a used one first. On
 * error nothing is held (w->ocean is NULL). */
int ref_waves_init(ref_waves *w, const ref_waves_desc *desc, char *err, size_t errlen);

/* Frees what init allocated (the ocean); safe on a zeroed, failed or
 * already released wave set. The resolved parameters stay readable, but
 * queries must not be made after it when there was an ocean. */
void ref_waves_release(ref_waves *w);

/* Bounds for the frame at time t (tighter than the any-time fields when
 * there is an ocean: its exact per-frame bounds): |y - level| <= height,
 * |grad h(u, v)| <= slope, |grad H(x, z)| <= world_slope (INFINITY where
 * the sideways maps may fold). Any pointer may be NULL. */
void ref_waves_bounds_at(const ref_waves *w, double t, double *height, double *slope, double *world_slope);

/* A wave set at one time t, prepared for many queries: the ocean's frame
 * looked up once (a snapshot, ref_ocean.h: no lock a query after that) and
 * the frame's bounds worked out once. The plain queries below prepare one
 * per call; a ray march, a photon pass or a render prepares one and hands
 * it on (ref_trace's *_ctx functions). Read-only once begun, so any number
 * of threads may share one; the ctx queries give the plain ones' numbers
 * bit for bit. End it before releasing the wave set. */
typedef struct ref_waves_ctx {
    const ref_waves *w;
    double t;
    const ref_ocean_snapshot *ocean;     /* NULL without an ocean */
    double height, slope, world_slope;   /* ref_waves_bounds_at(w, t) */
    double fold;                         /* the sideways map's derivative has spectral
                                            norm <= fold (< 1: the map is one to one) */
    double disp_lo[2], disp_hi[2];       /* the sideways displacement (Gerstner's and
                                            the ocean's) lies in [lo, hi] per axis */
} ref_waves_ctx;

void ref_waves_ctx_begin(ref_waves_ctx *c, const ref_waves *w, double t);
void ref_waves_ctx_end(ref_waves_ctx *c);

/* A world-slope bound over a box of world points [x0, x1] x [z0, z1]:
 * |H(X) - H(X')| <= it * |X - X'| for X, X' in the box (INFINITY when the
 * sideways map may fold over the rest points that box can come from). At
 * most c->world_slope; with an ocean it takes the ocean's bounds of the
 * region the box's rest points lie in (ref_ocean_snapshot_box_bounds), so a
 * march's step can use the bound of where it goes rather than the worst of
 * the whole sea (proof in ref_waves.c). */
double ref_waves_ctx_world_slope_box(const ref_waves_ctx *c, double x0, double z0, double x1, double z1);

/* The same over the world points within distance reach of (x, z),
 * given its rest point uv (an inversion's, which converged): when
 * the frame's map is one to one (fold < 1) the rest points of those lie
 * within reach / (1 - C) of uv, C the map's bound there, so the region
 * is as small as the step (ref_waves_ctx_world_slope_box's is at least the
 * displacement's range); else the box around (x, z). */
double ref_waves_ctx_world_slope_near(const ref_waves_ctx *c, double x, double z, const double uv[2],
                                      double reach);

/* ref_waves_eval, ref_waves_at, ref_waves_rest_point, ref_waves_height at
 * the context's time. */
void ref_waves_ctx_eval(const ref_waves_ctx *c, double u, double v, ref_waves_point *out);
int ref_waves_ctx_at(const ref_waves_ctx *c, double x, double z, const double guess[2],
                     ref_waves_point *out);
int ref_waves_ctx_rest_point(const ref_waves_ctx *c, double x, double z, const double guess[2],
                             double uv[2], double *height);
double ref_waves_ctx_height(const ref_waves_ctx *c, double x, double z);

/* A march's memory between nearby queries (zero it before the first): the
 * last world point, its rest point and the sideways map's Jacobian there.
 * ref_waves_ctx_track is ref_waves_ctx_rest_point with the guess worked
 * out from it: one Newton step from the last rest point, which needs no
 * sample (the residual there is the world point's move), so a march step's
 * inversion starts nearer and samples the ocean less often. Its rest point
 * agrees with the plain query's to the inversion's tolerance. */
typedef struct ref_waves_track {
    int valid;
    double x, z;          /* the last world point */
    double uv[2];         /* its rest point */
    double jac[4];        /* d(x, z)/d(u, v) near it */
} ref_waves_track;

int ref_waves_ctx_track(const ref_waves_ctx *c, double x, double z, ref_waves_track *tr,
                        double uv[2], double *height);

/* Displaced position P(u, v, t). */
void ref_waves_displace(const ref_waves *w, double u, double v, double t, double pos[3]);

/* The full frame at parameter (u, v): position, B, T, both normals, Jacobian. */
void ref_waves_eval(const ref_waves *w, double u, double v, double t, ref_waves_point *out);

/* The noise component alone: height (relative, without level) and its
 * gradient in (u, v) (grad may be NULL). */
double ref_waves_noise(const ref_waves *w, double u, double v, double t, double grad[2]);

/* The surface over the world point (x, z): solves P_xz(u, v, t) = (x, z) for
 * the undisplaced point by damped Newton (backtracking on |residual|, at
 * most 50 iterations), falling back to the relaxed fixed point
 * (u, v) <- (x, z) - D(u, v) (a contraction with constant Q when Q < 1).
 * Converges to |residual| <= 1e-12 * max(1, |x|, |z|). guess (may be NULL)
 * is a starting (u, v), e.g. the previous sample of a march. Fills out (at
 * the best point reached) and returns 0, or -1 when it did not converge
 * (possible only when Q >= 1, where the surface folds and the height over
 * a point is not unique). */
int ref_waves_at(const ref_waves *w, double x, double z, double t,
                 const double guess[2], ref_waves_point *out);

/* The same inversion without the frame: the rest point uv under (x, z) and,
 * when height is not NULL, the surface height there (cheaper: no
 * derivatives). Returns 0, or -1 as ref_waves_at. */
int ref_waves_rest_point(const ref_waves *w, double x, double z, double t,
                         const double guess[2], double uv[2], double *height);

/* Height over the world point (x, z) (NaN if the inversion failed). */
double ref_waves_height(const ref_waves *w, double x, double z, double t);

/* The GLSL uniforms of packs/common/waves.glsl for a resolved wave set:
 * name, type and float values, in a fixed order: the waves as described
 * (uSineAngle, ...), then as resolved here (uWaveSine, ...: inactive
 * waves dropped, k D, omega, Q_i A_i D and the noise's octaves worked out
 * once, so no shader does it per vertex), then ref_wavefx_uniforms' (the
 * rings and the Perlin set), then the ocean's: uOceanN (int, cascades, 0 =
 * none), uOceanRes (int, N), uOceanTile (float[REF_OCEAN_CASCADES_MAX], L_c).
 * Returns how many were written
 * (at most max; REF_WAVES_UNIFORMS_MAX fits all). */
#define REF_WAVES_UNIFORMS_MAX (34 + REF_WAVEFX_UNIFORMS_MAX + 3)
int ref_waves_uniforms(const ref_waves *w, ref_waves_uniform *out, int max);

#endif
