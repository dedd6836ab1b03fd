/* compare: `tarn compare A B`, the error of image A (under test) against
 * image B (the reference): a table, a heat map, JSON and CSV, and with
 * --buffers the reference's per-pixel buffers beside them. The metrics
 * themselves are reference/ref_metrics.h; this module reads the files
 * (image_io.h), decodes sRGB and writes the outputs. See docs/metrics.md. */
#ifndef TARN_COMPARE_H
#define TARN_COMPARE_H

#include <stdbool.h>
#include <stdio.h>

#include "image_io.h"

/* The command: argv holds the arguments after "compare" (argv[0] is A or
 * an option, not "compare"). Prints to stdout/stderr. Returns 0 when
 * compared, 1 when a file could not be read, compared or written, 2 on bad
 * usage (the usage text goes to stderr; --help prints it to stdout, 0). */
int cli_compare(int argc, char **argv);

/* The same with the streams given (tests): the table and "-" outputs go to
 * out, messages to err. */
int compare_run(int argc, char **argv, FILE *out, FILE *err);

/* The --help text. */
const char *compare_usage(void);

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
