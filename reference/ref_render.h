/* ref_render: the CPU ground-truth renderer. One camera ray per pixel
 * centre (or N x N subsamples, or subsamples at given positions) through the world of ref_scene: the exact
 * displaced water surface, exact Fresnel both ways with total internal
 * reflection, exact Snell refraction, the refracted ray traced to the
 * terrain heightfield or an object, Beer-Lambert attenuation per channel,
 * reflection to objects, terrain and sky, and the floor under water lit by
 * caustics from photon tracing of the sun through the same surface.
 *
 * Besides the image it writes per-pixel buffers (refraction hit point,
 * reflection hit or direction, Fresnel factor, water path length, floor
 * irradiance, the surface point, what the primary ray met), so a pack's
 * error can be measured where it arises. Everything is double precision,
 * multi-threaded by rows and deterministic: the result is bitwise the same
 * for any thread count.
 *
 * Shading definitions (docs/reference.md, "The renderer"):
 *   dry terrain / objects (met by a ray in air):  ref_shade_lambert, no shadows
 *   terrain under water:   albedo (E_caustic(x, z) / pi + A_w(y))
 *   objects under water:   albedo (E_flat(p, n) / pi + A_w(y))
 *   A_w(y) = ambient (1 - R(0)) exp(-sigma max(0, level - y))
 *   water surface:         R L(reflected) + (1 - R) L(refracted)
 *   a path in water:       times exp(-sigma s) (no in-scattering: it fades to black)
 * Row 0 of every buffer is the TOP of the image (file order).
 */
#ifndef TARN_REF_RENDER_H
#define TARN_REF_RENDER_H

#include <stddef.h>
#include <stdint.h>

#include "ref_scene.h"
#include "ref_trace.h"

/* What the primary ray met first (the mask buffer). */
enum { REF_MASK_SKY = 0, REF_MASK_WATER = 1, REF_MASK_TERRAIN = 2, REF_MASK_OBJECT = 3 };

/* The flag channel of the reflection buffer. */
enum {
    REF_REFLECT_NONE = 0,       /* the primary ray met no water (xyz NaN) */
    REF_REFLECT_POINT = 1,      /* xyz: the terrain or object point the reflected ray met */
    REF_REFLECT_SKY = 2,        /* xyz: the unit direction of the reflected ray, which met
                                   nothing (the sky; or, from below, endless water) */
    REF_REFLECT_WATER = 3       /* xyz: the reflected ray met the water surface again there */
};

/* How the floor under water is lit by the sun. */
enum {
    REF_CAUSTICS_PHOTONS = 0,   /* photon tracing through the exact surface (default) */
    REF_CAUSTICS_FLAT = 1       /* the sun refracted by the flat mean plane (no photons) */
};

/* At most this many explicit subsample positions a pixel (GL's MSAA asks
 * for 16 at most; some GLs give 32). */
#define REF_MAX_SAMPLES 32

typedef struct ref_camera {
    double eye[3], center[3], up[3];   /* LookAt; up (0,0,0) = (0,1,0) */
    double fov_deg;                    /* vertical field of view (0 = 50) */
    int width, height;                 /* pixels (0 = 640 x 360) */
} ref_camera;

/* Fraction of the work done, 0..1; called from the thread that called
 * ref_render, about every 0.1 s and once with 1 at the end. */
typedef void (*ref_progress_fn)(void *user, double fraction);

/* Zero means default in every field (filled in by ref_render_resolve). */
typedef struct ref_render_desc {
    const ref_world *world;     /* required, ref_world_init'ed */
    ref_camera camera;
    double time;                /* simulated time of the waves */
    int threads;                /* 0 = every online core */
    int spp;                    /* N: N x N subsamples per pixel (0 = 1) */
    int nsamples;               /* > 0: this many subsamples per pixel at the positions
                                   below instead of the spp grid (0: the grid) */
    double samples[REF_MAX_SAMPLES][2];  /* their (x, y) in the pixel, each in [0, 1):
                                   x to the right, y DOWN (image rows; the caller turns
                                   GL's y-up sample position (x, y) into (x, 1 - y)).
                                   The reference knows no GL: MSAA's positions come
                                   from the caller (render_msaa.h) */
    int caustics;               /* REF_CAUSTICS_PHOTONS (0) or REF_CAUSTICS_FLAT */
    int caustic_res;            /* caustic grid cells along the longer side of
                                   the underwater floor (0 = 256); cells are square */
    int photons_per_cell;       /* k x k strata per cell area, k = round(sqrt(.)) (0 = 36) */
    uint64_t seed;              /* the photons' random numbers: 0 = the fixed default
                                   sequence (every cached reference so far); another
                                   value, another sampling of the same strata and count,
                                   so two seeds differ by photon noise alone */
    int max_depth;              /* water-surface interactions along a path (0 = 5);
                                   a path that would need more gets no more light */
    int radiance_n2;            /* 1: radiance crossing the surface is scaled by
                                   (n_t / n_i)^2 (physical radiance); 0 (default): by
                                   1 - R only, as the packs do */
    double t_tol;               /* root bracket of every ray cast (0 = 1e-9) */
    ref_progress_fn progress;   /* may be NULL */
    void *progress_user;
} ref_render_desc;

typedef struct ref_render_result {
    int width, height, spp;
    int nsamples;         /* the desc's explicit positions (0: the spp grid) */
    /* per pixel, row-major, row 0 at the top; NaN marks "undefined here" */
    double *color;        /* 3: linear RGB radiance (mean of the subsamples) */
    unsigned char *mask;  /* 1: REF_MASK_* of the pixel-centre ray */
    double *surface;      /* 3: where the primary ray meets the water surface */
    double *refract_hit;  /* 4: xyz, the first point the refracted ray meets, and
                             what it is (REF_MASK_TERRAIN, _OBJECT, _WATER: the
                             surface again; REF_MASK_SKY (0): nothing, xyz NaN) */
    double *reflect;      /* 4: xyz + flag (REF_REFLECT_*) */
    double *fresnel;      /* 1: exact R at the primary water hit (1 on TIR) */
    double *depth;        /* 1: path length in water (see docs/reference.md) */
    double *irradiance;   /* 3: the sun's irradiance at refract_hit as its shading uses it */
    /* the caustic grid used (REF_CAUSTICS_PHOTONS): irradiance per unit floor
       area for a sun of irradiance 1 (times sun_irradiance[c] per channel),
       the photon stats and the plan (its d.floor is cleared: the terrain was
       the world's, through this render's context) */
    ref_caustics caustics;
    int have_caustics;
    double seconds_photons, seconds_pixels;   /* wall time of the two phases */
    int threads;                              /* threads used */
} ref_render_result;

/* The desc with every default filled in (world copied as a pointer). */
ref_render_desc ref_render_resolve(const ref_render_desc *d);

/* The camera ray through image point (px, py) in pixels, (0, 0) the top-left
 * corner of the image, (w, h) the bottom-right (a pixel centre is (i + 0.5,
 * j + 0.5)): o = eye, d = normalize(f + sx r + sy u) with f the view
 * direction, r = normalize(f x up), u = r x f, sy = (1 - 2 py / h) tan(fov/2),
 * sx = (2 px / w - 1) tan(fov/2) w / h (OpenGL's LookAt and Perspective).
 * cam must be resolved (width, height, fov set). */
void ref_camera_ray(const ref_camera *cam, double px, double py, double o[3], double d[3]);

/* Renders. Returns 0 and fills out (ref_render_free it), or -1 with a
 * message in err (no world, bad sizes, out of memory, photon plan errors);
 * out is then empty. */
int ref_render(const ref_render_desc *d, ref_render_result *out, char *err, size_t errlen);

void ref_render_free(ref_render_result *r);

/* Sun irradiance under flat water at point p with unit normal n (per
 * channel): E_sun (1 - R(cos_s)) cos_s / cos_t max(0, -n . t_s)
 * exp(-sigma max(0, level - p.y) / cos_t), with t_s the sun refracted by
 * the plane y = level, cos_s = sun.y, cos_t = -t_s.y. What lights objects
 * under water, and the terrain with REF_CAUSTICS_FLAT or off the grid. */
void ref_render_flat_sun(const ref_world *w, const double p[3], const double n[3], double e[3]);

/* The caustic irradiance at floor point (x, z) from a result's grid, per
 * channel (bilinear between cell centres, clamped at the grid's edge; the
 * flat formula outside it). */
void ref_render_caustic_at(const ref_render_result *r, const ref_world *w, double x, double z,
                           double e[3]);

#endif
