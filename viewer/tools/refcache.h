/* refcache: reference images (reference/ref_render.h) of a scene's world
 * at a size, time and camera, cached on disk so reruns of `tarn bench` are
 * fast. The key is a hash of everything the image depends on: the world
 * (less the GL-only mesh resolutions), the camera, the size, the time and
 * the reference's quality settings (the subsample positions and a photon
 * seed other than 0 among them).
 * Files, in DIR:
 *
 *   STEM-WxH-tT-KEY.exr              linear RGB, 32-bit float
 *   STEM-WxH-tT-KEY.png              the same, sRGB 8-bit, to look at
 *   STEM-WxH-tT-KEY.NAME.exr         refract_hit (4), fresnel (1), depth (1),
 *                                    irradiance (3), mask (1)
 *
 * STEM is the scene's file name without .glib. */
#ifndef TARN_REFCACHE_H
#define TARN_REFCACHE_H

#include <stdbool.h>
#include <stdint.h>

#include "ref_render.h"

/* Zero means the reference's default in every field. */
typedef struct refcache_opts {
    int spp;                  /* N x N subsamples */
    int nsamples;             /* > 0: subsamples at these positions instead (MSAA's, from
                                 render_ref_positions; ref_render_desc.samples) */
    double samples[REF_MAX_SAMPLES][2];
    int caustic_res;
    int photons_per_cell;
    uint64_t seed;            /* the photons' seed (ref_render_desc.seed; 0: the default
                                 sequence, and the key of every cache file so far) */
    int threads;
    bool flat_caustics;
} refcache_opts;

typedef struct refcache_image {
    int w, h;
    float *color;             /* 3 channels, linear, row 0 at the top */
    float *refract_hit;       /* 4: xyz and what it met */
    float *fresnel;           /* 1 */
    float *depth;             /* 1 */
    float *irradiance;        /* 3 */
    float *mask;              /* 1: REF_MASK_* */
    bool from_cache;
    double seconds;           /* rendering time (0 when read from the cache) */
    char stem[1024];          /* DIR/STEM-WxH-tT-KEY ("" without a DIR) */
} refcache_image;

/* The key of a scene's reference (its Pack is not read: the world does not
 * depend on the pack). False with the parser's errors in err when it has
 * errors or no world. */
bool refcache_key(const char *scene, int w, int h, double t, const refcache_opts *o, uint64_t *key, char *err,
                  int errlen);

/* Reads the reference from dir when it is there, else renders it (calling
 * progress) and writes it there (dir NULL: render, write nothing).
 * name: the path whose file name makes STEM (NULL: scene; a wrapper scene
 * passes the scene it wraps, so settings that share a world share files).
 * view: a camera other than the scene's LookAt (NULL: the scene's). */
typedef struct refcache_view { double eye[3], center[3], up[3]; } refcache_view;
bool refcache_get(const char *dir, const char *scene, const char *name, int w, int h, double t,
                  const refcache_view *view, const refcache_opts *o, ref_progress_fn progress, void *user,
                  refcache_image *out, char *err, int errlen);

/* true when refcache_get would read it from dir without rendering. */
bool refcache_cached(const char *dir, const char *scene, const char *name, int w, int h, double t,
                     const refcache_opts *o);

void refcache_free(refcache_image *im);

/* Subsamples that match MSAA with this many samples (as render_samples
 * gives them; a GL context current): the positions this GL samples
 * (render_ref_positions), else the standard ones of 2, 4, 8, 16
 * (render_ref_standard_positions), else the nearest square grid
 * (render_ref_spp). Sets o->spp, o->nsamples and o->samples. */
void refcache_match_msaa(refcache_opts *o, int samples);

/* What o's subsamples are, for messages and reports: "2 x 2 subsamples
 * per pixel" or "4 subsamples per pixel at the GL's MSAA sample positions". */
void refcache_describe_samples(const refcache_opts *o, char *buf, int len);

#endif
