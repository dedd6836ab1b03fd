/* ref_metrics: error metrics between two float images or per-pixel buffers
 * of equal size, and an error heat map. Pure C, no I/O: images are arrays
 * of floats the caller owns (row 0 = top, pixel (x, y) channel c at
 * px[(y * w + x) * channels + c], as image_io.h reads them).
 *
 * Three kinds of comparison, each with its own per-pixel error:
 *
 *   colour (ref_metrics_image)   linear RGB: the first 3 channels (a side
 *                                with 1 or 2 channels is grey: channel 0
 *                                stands for R, G and B; alpha is ignored).
 *                                Per-pixel error = max over the 3 channels
 *                                of |a - b| (L-infinity). RMSE, MAE and PSNR
 *                                are over all channel values.
 *   points (ref_metrics_points)  3-channel positions (hit points): per-pixel
 *                                error = Euclidean distance |a - b| in world
 *                                units, and in texels given a texel size.
 *   scalar (ref_metrics_scalar)  Fresnel factor, depth, irradiance: each
 *                                channel value is a sample; absolute and
 *                                relative error.
 *
 * A is the image under test, B the reference: only the relative error
 * (divided by |b|) and the sign of the bias (mean of a - b) depend on the
 * order.
 *
 * Pixels left out of every error statistic, and counted:
 *   - outside the mask (desc->mask[y * w + x] == 0): masked_out;
 *   - a compared channel is NaN in A (nan_a) or in B (nan_b), or else
 *     +-Inf (inf_a, inf_b). These four count over ALL pixels, inside the
 *     mask or not, so a NaN anywhere in a render is reported; `invalid`
 *     counts the pixels inside the mask left out because of them.
 * compared = pixels - masked_out - invalid. With compared == 0 every
 * statistic is NaN.
 *
 * Percentiles interpolate linearly between order statistics at rank
 * r = p/100 * (n - 1) over the sorted samples (numpy's default).
 *
 * Every function is pure and thread-safe. See docs/metrics.md.
 */
#ifndef TARN_REF_METRICS_H
#define TARN_REF_METRICS_H

#include <stdbool.h>

#define REF_METRICS_THRESHOLD 0.05   /* default over-threshold error (linear RGB) */
#define REF_METRICS_PEAK 1.0         /* PSNR peak: linear RGB white */
#define REF_METRICS_REL_FLOOR 1e-3   /* default floor of |b| in relative errors */

/* A float image the caller owns (not copied). */
typedef struct ref_fimage {
    const float *px;        /* w * h * channels floats, row 0 = top */
    int w, h, channels;
} ref_fimage;

/* Zero means default in every field. */
typedef struct ref_metrics_desc {
    double threshold;               /* colour: share of pixels whose error is
                                       > threshold (0 = 0.05); also used by
                                       points/scalar (0 there = none) */
    const unsigned char *mask;      /* w * h bytes, row 0 = top; nonzero =
                                       compare; NULL = every pixel */
    double peak;                    /* PSNR peak (0 = 1.0) */
    double texel_size;              /* points: world units per texel (0 = no
                                       texel statistics) */
    double rel_floor;               /* scalar: relative error divides by
                                       max(|b|, rel_floor) (0 = 1e-3) */
} ref_metrics_desc;

/* The pixels of one side of the reference's water mask: out[i] = 1 where
 * classes[i] (REF_MASK_* of ref_render.h, as floats: a mask.exr's values)
 * is water (water = true) or is not (false), and and_mask (may be NULL) is
 * nonzero. Error figures lead with the water side: it is what a water
 * technique gets right or wrong. */
void ref_mask_water(const float *classes, long n, int water, const unsigned char *and_mask, unsigned char *out);

/* How many pixels went where (see the header comment). */
typedef struct ref_pixel_counts {
    long pixels;            /* w * h */
    long compared;          /* in every statistic */
    long masked_out;        /* outside the mask */
    long invalid;           /* inside the mask, left out: non-finite in A or B */
    long nan_a, nan_b;      /* pixels with a NaN in a compared channel (all pixels) */
    long inf_a, inf_b;      /* pixels with +-Inf and no NaN there (all pixels) */
} ref_pixel_counts;

/* Statistics of a set of non-negative error samples. */
typedef struct ref_err_stats {
    long n;                 /* samples */
    double mean, rms, median, p95, p99, max;
    int max_x, max_y, max_c;    /* where the max is (first in scan order; the
                                   channel, or -1 for per-pixel samples);
                                   -1 when n == 0 */
} ref_err_stats;

typedef struct ref_image_metrics {
    int width, height;
    int channels;               /* compared: always 3 (R, G, B; grey broadcast) */
    ref_pixel_counts count;
    double rmse;                /* sqrt(mean over compared pixels and channels of (a-b)^2) */
    double rmse_c[3];           /* per channel: R, G, B */
    double psnr_db;             /* 20 log10(peak / rmse); +INFINITY when rmse == 0 */
    double peak;
    double mae;                 /* mean over compared pixels and channels of |a-b| */
    double max_abs;             /* largest |a-b| of any compared channel value */
    int max_x, max_y, max_c;    /* where it is (first in scan order), -1 if none */
    double threshold;
    long over_threshold;        /* pixels whose error (max over channels) > threshold */
    double over_threshold_share;/* over_threshold / compared */
    long differing;             /* pixels whose error is > 0 */
    double bias[3];             /* mean of a - b per channel */
    ref_err_stats pixel_err;    /* per-pixel error (max over channels) */
} ref_image_metrics;

typedef struct ref_point_metrics {
    int width, height;
    ref_pixel_counts count;
    ref_err_stats world;        /* Euclidean distance, world units */
    double texel_size;          /* world units per texel; 0 = none */
    ref_err_stats texels;       /* world / texel_size (all NaN, n = 0 without one) */
    double threshold;           /* world units; 0 = none */
    long over_threshold;        /* pixels with distance > threshold */
    double over_threshold_share;
} ref_point_metrics;

typedef struct ref_scalar_metrics {
    int width, height;
    int channels;               /* compared per pixel */
    ref_pixel_counts count;     /* pixels */
    ref_err_stats abs;          /* |a - b| over every compared channel value */
    ref_err_stats rel;          /* |a - b| / max(|b|, rel_floor) */
    double rel_floor;
    double bias;                /* mean of a - b over channel values */
    double threshold;           /* 0 = none */
    long over_threshold;        /* pixels with max over channels |a-b| > threshold */
    double over_threshold_share;
} ref_scalar_metrics;

/* Per-pixel error kinds (ref_metrics_error_field). */
typedef enum ref_err_kind {
    REF_ERR_COLOR = 0,          /* max over the RGB channels of |a - b| */
    REF_ERR_POINT,              /* Euclidean distance of the first 3 channels */
    REF_ERR_SCALAR              /* max over the compared channels of |a - b| */
} ref_err_kind;

/* Colour metrics (see above). False, with "why" in err, when the sizes
 * differ ("A is 64x32, B is 32x32"), an image is empty, or memory runs out. */
bool ref_metrics_image(const ref_fimage *a, const ref_fimage *b, const ref_metrics_desc *d,
                       ref_image_metrics *out, char *err, int errlen);

/* Hit-point metrics: both images need at least 3 channels (x, y, z). */
bool ref_metrics_points(const ref_fimage *a, const ref_fimage *b, const ref_metrics_desc *d,
                        ref_point_metrics *out, char *err, int errlen);

/* Scalar-buffer metrics: a 1-channel side is broadcast against the other;
 * otherwise the first min(channels) channels, at most 4, are compared. */
bool ref_metrics_scalar(const ref_fimage *a, const ref_fimage *b, const ref_metrics_desc *d,
                        ref_scalar_metrics *out, char *err, int errlen);

/* The per-pixel error of a kind into field (w * h floats): >= 0 for a
 * compared pixel, NaN where A or B is non-finite (inside the mask), -1
 * outside the mask. Same errors as above. */
bool ref_metrics_error_field(const ref_fimage *a, const ref_fimage *b, ref_err_kind kind,
                             const ref_metrics_desc *d, float *field, char *err, int errlen);

/* The heat map's automatic scale for a field: the 99th percentile of its
 * compared values; if that is 0, their max; if that is 0 too (or nothing
 * was compared), 1. */
double ref_heatmap_auto_scale(const float *field, long n);

/* Colours a field into rgb (w * h * 3 floats, display-ready sRGB values in
 * 0..1, write them as they are): a compared value e maps through the
 * inferno ramp at t = clamp(e / scale, 0, 1) (black = no error, pale yellow
 * = scale or more); NaN (non-finite in A or B) is cyan (0, 1, 1), masked-out
 * pixels grey (0.5). scale <= 0 or non-finite means automatic. Returns the
 * scale used. */
double ref_heatmap(const float *field, int w, int h, double scale, float *rgb);

/* Matplotlib's inferno colour map (Smith and van der Walt, CC0), 256 8-bit
 * sRGB entries interpolated linearly; t is clamped to [0, 1]. inferno(0) =
 * (0, 0, 4)/255, inferno(1) = (252, 255, 164)/255. */
void ref_colormap_inferno(double t, float rgb[3]);

/* p-th percentile (0..100) of n sorted ascending values (see above); NaN
 * when n == 0. */
double ref_percentile_sorted(const double *sorted, long n, double p);

/* The same for unsorted values: sorts v in place first. */
double ref_percentile(double *v, long n, double p);

/* sRGB decoding (IEC 61966-2-1): c <= 0.04045 ? c / 12.92 :
 * ((c + 0.055) / 1.055)^2.4; and its inverse. */
double ref_srgb_to_linear(double c);
double ref_linear_to_srgb(double c);

#endif
