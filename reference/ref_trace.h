/* ref_trace: rays against the exact water surface and a terrain heightfield,
 * Beer-Lambert attenuation, and photon tracing of the sun for caustics.
 *
 * Rays are o + t d with d a unit vector (t is then a distance). Every
 * function is pure: it reads its inputs, writes its outputs, keeps no state,
 * so any number of threads may call them at once. The photon tracer is
 * split into a plan and row ranges so that a renderer can hand rows to
 * threads; its random numbers are a function of the seed and the stratum
 * alone, so the result does not depend on how the rows are split.
 *
 * See docs/reference.md for the method and the tolerances.
 */
#ifndef TARN_REF_TRACE_H
#define TARN_REF_TRACE_H

#include <stddef.h>
#include <stdint.h>

#include "ref_optics.h"
#include "ref_waves.h"

/* Where the sea folds (no Lipschitz bound of the height holds), the water
 * march steps as if the sideways map's smallest singular value were this:
 * a fold narrower than the height change of such a step may be missed. */
#define REF_TRACE_FOLD_FLOOR 0.1

/* Zero means default in every field. */
typedef struct ref_trace_opts {
    double t_min;       /* start of the ray segment (0) */
    double t_max;       /* end of the ray segment (0 = 1e4) */
    double t_tol;       /* refine the crossing to a bracket this wide (0 = 1e-9) */
    double min_step;    /* water march: smallest step (0 = min_wavelength / 128) */
    int max_steps;      /* march steps before giving up (0 = 1000000) */
} ref_trace_opts;

/* ---- ray vs the displaced water surface --------------------------------- */

typedef struct ref_water_hit {
    int hit;                /* 1 when the ray meets the surface in [t_min, t_max] */
    int from_below;         /* the ray was under water before the hit */
    double t;
    ref_waves_point surf;   /* position, (u, v), exact normal (y > 0), ... */
    int evals;              /* surface evaluations used (march + refinement) */
} ref_water_hit;

/* First crossing of the ray with y = H(x, z, time). The ray is clipped to
 * the slab |y - level| <= the frame's height bound, then marched with steps
 * max(|f| / L, min_step), f(t) = y(t) - H(x(t), z(t)) and L = |d.y| +
 * (world slope bound) |d.xz| a Lipschitz bound of f: the frame's, or with
 * an ocean the bound of the region the step reaches, whichever is larger a
 * step (so no crossing is skipped unless it is thinner than min_step).
 * Where the sideways map may fold no bound holds and the step is that of a
 * map whose least singular value were REF_TRACE_FOLD_FLOOR. Then refined
 * by Brent's method to t_tol. Returns hit->hit. */
int ref_trace_water(const ref_waves *w, double time, const double o[3], const double d[3],
                    const ref_trace_opts *opts, ref_water_hit *hit);

/* The same on a prepared wave set (ref_waves.h: the frame looked up and its
 * bounds worked out once, by the caller, for any number of rays; each
 * march step of ref_trace_water would otherwise look the frame up again).
 * The same numbers as ref_trace_water at wc's time. */
int ref_trace_water_ctx(const ref_waves_ctx *wc, const double o[3], const double d[3],
                        const ref_trace_opts *opts, ref_water_hit *hit);

/* ---- ray vs a terrain heightfield ---------------------------------------- */

typedef double (*ref_height_fn)(const void *user, double x, double z);
typedef void (*ref_gradient_fn)(const void *user, double x, double z, double grad[2]);

typedef struct ref_terrain {
    ref_height_fn height;       /* required: y of the terrain over (x, z) */
    const void *user;           /* passed to height and gradient */
    ref_gradient_fn gradient;   /* NULL: central differences, step
                                   6e-6 * cbrt(max(1, |x|, |z|)) */
    double lipschitz;           /* a bound on |grad h|; 0 = unknown: fixed steps */
    double step;                /* the fixed step without a bound (0 = 0.01) */
    double min_step;            /* smallest step with a bound (0 = 1e-5) */
    int bounded;                /* ymin <= h <= ymax holds: rays are clipped to it */
    double ymin, ymax;
} ref_terrain;

typedef struct ref_terrain_hit {
    int hit;
    int inside;                 /* the ray started under the terrain (hit at t_min) */
    double t;
    double pos[3];
    double normal[3];           /* unit, y > 0 */
    int evals;
} ref_terrain_hit;

/* First crossing of the ray with y = h(x, z): marched with Lipschitz steps
 * max(g / (|d.y| + lipschitz |d.xz|), min_step) when a bound is given (no
 * crossing thicker than min_step is skipped), else fixed steps, then refined
 * by Brent's method to t_tol. Returns hit->hit. */
int ref_trace_terrain(const ref_terrain *ter, const double o[3], const double d[3],
                      const ref_trace_opts *opts, ref_terrain_hit *hit);

/* Unit normal of the terrain at (x, z). */
void ref_terrain_normal(const ref_terrain *ter, double x, double z, double n[3]);

/* ---- attenuation ----------------------------------------------------------- */

/* Beer-Lambert transmittance exp(-sigma_c * distance) per channel. */
void ref_beer_lambert(const double sigma[3], double distance, double trans[3]);

/* ---- a camera ray through the surface -------------------------------------- */

typedef struct ref_refraction {
    ref_water_hit water;        /* water.hit == 0: the ray misses the surface */
    double n1, n2;              /* index before and after the surface */
    double cos_i;
    double fresnel;             /* exact R, 1 on total internal reflection */
    int tir;
    double reflect_dir[3];
    double refract_dir[3];      /* valid when !tir */
    ref_terrain_hit floor;      /* the refracted ray against the terrain */
    double water_path;          /* distance travelled in water: from above, the
                                   refracted segment to the floor (INFINITY if
                                   none); from below, origin to the surface */
} ref_refraction;

/* The ray meets the water, splits by exact Fresnel/Snell (from above or
 * below), and the refracted ray is traced to the terrain (ter may be NULL).
 * The terrain is not tested before the water: a renderer traces the camera
 * ray to the terrain itself first. Returns out->water.hit. */
int ref_trace_refraction(const ref_waves *w, double time, double n_air, double n_water,
                         const ref_terrain *ter, const double o[3], const double d[3],
                         const ref_trace_opts *opts, ref_refraction *out);

/* ---- photon tracing for caustics ------------------------------------------- */

typedef struct ref_caustics_desc {
    const ref_waves *waves;     /* required */
    double time;
    double sun_dir[3];          /* towards the sun, y > 0 (0,0,0 = straight up); normalised */
    double sun_irradiance;      /* E_sun on a plane facing the sun (0 = 1) */
    double n_air, n_water;      /* 0 = REF_N_AIR, REF_N_WATER */
    const ref_terrain *floor;   /* NULL: the flat floor y = floor_y */
    double floor_y;
    double sigma[3];            /* extinction in water per channel, 1/world unit */
    double x0, z0, x1, z1;      /* the floor region of the grid (required) */
    int nx, nz;                 /* grid cells (0 = 64 each) */
    int photons_per_cell;       /* about this many per cell: k x k strata per
                                   cell-sized area, k = round(sqrt(.)) (0 = 256) */
    double margin;              /* emission margin around the flat-water preimage of
                                   the region, world units (0 = auto) */
    uint64_t seed;              /* 0 = a fixed default */
    ref_trace_opts opts;        /* for the water and floor traces */
} ref_caustics_desc;

typedef struct ref_caustics_plan {
    ref_caustics_desc d;        /* resolved */
    double sun[3];              /* unit, towards the sun */
    double emit_y;              /* the horizontal emission plane above the waves */
    double ex0, ez0;            /* emission region corner */
    double sx, sz;              /* stratum size */
    int mx, mz;                 /* strata per row, rows */
    double photon_flux;         /* E_sun cos(theta_sun) sx sz, per photon */
    double cell_dx, cell_dz;
} ref_caustics_plan;

typedef struct ref_caustics_stats {
    long photons, hit_water, hit_dry, hit_floor, in_grid;
    double flux_emitted;        /* sum of photon flux */
    double flux_reflected;      /* sum flux R at the water */
    double flux_transmitted;    /* sum flux (1 - R) */
    double flux_in_grid[3];     /* deposited in the grid, after attenuation */
} ref_caustics_stats;

typedef struct ref_caustics {
    int nx, nz;
    double x0, z0, x1, z1;
    double *irradiance;         /* nx*nz*3, row-major (z rows of x cells), per
                                   unit floor surface area */
    double *area;               /* nx*nz floor surface area of each cell */
    ref_caustics_stats stats;
    ref_caustics_plan plan;
} ref_caustics;

/* Resolves the desc and lays out the emission strata. 0, or -1 and err. */
int ref_caustics_plan_init(const ref_caustics_desc *d, ref_caustics_plan *p, char *err, size_t errlen);

/* Traces strata rows [row0, row1) of the plan, adding flux (not yet divided
 * by area) into flux[nx*nz*3] and counts into *st (both accumulate; st may
 * be NULL). */
void ref_caustics_trace_rows(const ref_caustics_plan *p, int row0, int row1,
                             double *flux, ref_caustics_stats *st);

/* Floor surface area of each grid cell (flat: dx dz; heightfield: the
 * integral of sqrt(1 + |grad h|^2) by 4x4 midpoints). */
void ref_caustics_cell_areas(const ref_caustics_plan *p, double *area);

/* All of it on one thread: plan, every row, flux / area. 0, or -1 and err. */
int ref_caustics_trace(const ref_caustics_desc *d, ref_caustics *out, char *err, size_t errlen);
void ref_caustics_free(ref_caustics *c);

/* splitmix64, the generator the photon tracer uses (exposed for tests). */
uint64_t ref_splitmix64(uint64_t *state);

#endif
