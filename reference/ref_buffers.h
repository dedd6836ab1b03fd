/* ref_buffers: the one list of per-pixel buffers. The reference writes
 * them (ref_render_result), `tarn reference` saves them as OUT.NAME.exr,
 * the cache keeps them, `tarn compare --buffers` and `tarn bench` measure a
 * pack's against them, and a pack's bench.txt names them on `buffer` lines.
 * Everything that lists buffers iterates this table, in this order. */
#ifndef TARN_REF_BUFFERS_H
#define TARN_REF_BUFFERS_H

#include "ref_metrics.h"
#include "ref_render.h"

typedef enum ref_buffer_id {
    REF_BUF_COLOR = 0, /* linear RGB: the image itself */
    REF_BUF_REFRACT_HIT,
    REF_BUF_REFLECT,
    REF_BUF_FRESNEL,
    REF_BUF_DEPTH,
    REF_BUF_IRRADIANCE,
    REF_BUF_SURFACE,
    REF_BUF_MASK,
    REF_BUF_COUNT
} ref_buffer_id;

/* What a pack's colour output holds for each value of its `Define
 * TARN_OUTPUT` (docs/packs/contract.md): the buffers a pack can show. */
typedef enum ref_output {
    REF_OUTPUT_COLOR = 0,       /* the normal image */
    REF_OUTPUT_REFRACT_HIT = 1, /* world xyz the refracted ray meets */
    REF_OUTPUT_FRESNEL = 2,     /* the Fresnel reflectance, in R */
    REF_OUTPUT_IRRADIANCE = 3,  /* sun irradiance at the refraction hit, RGB */
    REF_OUTPUT_DEPTH = 4,       /* the path length in water, in R */
    REF_OUTPUT_COUNT
} ref_output;

typedef struct ref_buffer_info {
    ref_buffer_id id;
    const char *name;       /* "refract_hit" (bench.txt, compare's output, JSON keys) */
    const char *suffix;     /* file name after the stem: ".refract_hit.exr" (".exr": the image) */
    int channels;           /* in the reference's result and its file */
    ref_err_kind err;       /* how an error against it is measured */
    bool measured;          /* compare --buffers measures it (not the image or the mask) */
    int direction_flag;     /* channel 3 value meaning "xyz is a direction": left out (0: none) */
    ref_output tarn_output; /* the TARN_OUTPUT value a pack writes it with (0: a pack cannot) */
    const char *meaning;
} ref_buffer_info;

extern const ref_buffer_info ref_buffers[REF_BUF_COUNT];

/* The buffer called name, or NULL. */
const ref_buffer_info *ref_buffer_named(const char *name);
/* The buffer a pack writes with TARN_OUTPUT = value, or NULL. */
const ref_buffer_info *ref_buffer_for_output(int value);
/* The result's data for a buffer (NULL for the mask, which is bytes). */
const double *ref_buffer_data(const ref_render_result *r, ref_buffer_id id);

#endif
