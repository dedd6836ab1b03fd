/* compare: `tarn compare A B`, the error of image A (under test) against
 * image B (the reference): RMSE, FLIP (ref_flip.h) and SSIM (ref_ssim.h),
 * water first; a table, a heat map, a FLIP map, JSON and CSV, and with
 * --buffers the reference's per-pixel buffers beside them. The metrics
 * themselves are reference/ref_metrics.h; this module reads the files
 * (image_io.h), decodes sRGB and writes the outputs. See docs/metrics.md. */
#ifndef TARN_COMPARE_H
#define TARN_COMPARE_H

#include <stdbool.h>
#include <stdio.h>

#include "image_io.h"

/* What to compare and what to write (zero means default: no heat map, no
 * JSON/CSV/mask, automatic --max). Paths "-" for json or csv mean `out`;
 * not both (the caller checks). */
typedef struct compare_desc {
    const char *a, *b;                 /* A under test, B the reference */
    const char *out, *json, *csv, *mask;
    const char *flip_map;              /* the FLIP error map, magma (NULL: none) */
    double threshold, max_err, texel;  /* 0: defaults (docs/metrics.md) */
    bool buffers, linear;
} compare_desc;

/* Compares: the table and "-" outputs go to out, messages to err. Returns
 * 0 when compared, 1 when a file could not be read, compared or written. */
int compare_run(const compare_desc *d, FILE *out, FILE *err);

/* True when the file's extension is one of the 8-bit display formats that
 * store sRGB-encoded values (png, jpg, jpeg, bmp, gif, tga, webp, ppm, pgm,
 * pnm); EXR, HDR, TIFF and the rest are taken as linear. */
bool compare_is_srgb_path(const char *path);

/* Reads an image for comparison: img_read, then, when decode_srgb is set
 * and compare_is_srgb_path(path), the colour channels (the first 3, or
 * channel 0 of a 1- or 2-channel image; never alpha) are decoded from sRGB
 * to linear. *decoded (may be NULL) tells whether it was. 2D only. False
 * with "path: reason" in err. */
bool compare_load(const char *path, bool decode_srgb, img *out, bool *decoded, char *err, int errlen);

#endif
