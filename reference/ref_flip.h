/* ref_flip: the FLIP image difference evaluator (Andersson, Nilsson,
 * Akenine-Moller, Oskarsson, Astrom, Fairchild, "FLIP: A Difference
 * Evaluator for Alternating Images", HPG 2020) and its HDR extension
 * (Andersson, Nilsson, Shirley, Akenine-Moller, "Visualizing Errors in
 * Rendered High Dynamic Range Images", Eurographics 2021 short papers).
 * Pure C, no I/O; written from the papers, checked against the values of
 * the authors' tool (../shared/flip-oracle, tests/test_flip.c).
 *
 * LDR-FLIP, per pixel, on two linear RGB images in [0, 1] (an 8-bit sRGB
 * file decoded to linear, as `tarn compare` reads it):
 *   1. linear RGB -> XYZ (sRGB primaries, D65) -> YyCxCz (the linearised
 *      L*a*b*: 116 Y/Yn - 16, 500 (X/Xn - Y/Yn), 200 (Y/Yn - Z/Zn));
 *   2. each channel filtered by the paper's contrast sensitivity
 *      functions in the spatial domain (sums of Gaussians
 *      a sqrt(pi/b) exp(-pi^2 r^2 / b), r in degrees, normalised to unit
 *      sum on the pixel grid, radius 3 sd of the widest, borders clamped);
 *   3. back to linear RGB, clamped to [0, 1], -> CIELAB, Hunt-adjusted
 *      (a, b scaled by 0.01 L), HyAB distance |dL| + |d(a, b)|, raised to
 *      q_c = 0.7 and remapped to [0, 1]: [0, p_c cmax] -> [0, p_t] and
 *      [p_c cmax, cmax] -> [p_t, 1] (p_c 0.4, p_t 0.95, cmax the distance
 *      of green to blue);
 *   4. edges and points: the luminance Y convolved with the first and
 *      second derivatives of a Gaussian (sd 0.5 w ppd, w = 0.082 degrees;
 *      positive and negative weights each normalised to +-1); the feature
 *      difference is (max(|d edge|, |d point|) / sqrt 2)^q_f, q_f = 0.5;
 *   5. FLIP = colour^(1 - feature), in [0, 1].
 *
 * HDR-FLIP on two linear images (any range): each is scaled by 2^e and
 * tone mapped by ACES (Narkowicz's fit, with its 0.6 pre-exposure) for
 * exposures e from start to stop in num equal steps, clamped to [0, 1],
 * compared by LDR-FLIP; the error is the per-pixel max over exposures.
 * Automatic exposures, from the reference only: with x* the input that the
 * tone mapper maps to 0.85, start = log2(x* / Ymax), stop = log2(x* /
 * Ymedian) (Y the Rec. 709 luminance 0.2126 R + 0.7152 G + 0.0722 B;
 * median the (n/2)-th smallest, 0-based), num = max(2, ceil(stop - start)).
 *
 * Viewing: pixels per degree, default 67.02 (0.7 m from a 0.7 m wide,
 * 3840-pixel display: 0.7 * 3840 / 0.7 * pi / 180).
 *
 * Pooled values, as the authors' tool prints them, over the pixels in a
 * mask (e.g. the reference's water) or all: mean, min, max, and the
 * weighted median and quartiles: with the pooled values sorted ascending
 * and S their sum, the p-quantile is the first value at which the running
 * sum exceeds p S (each pixel weighted by its own error, so the median is
 * the error that half of the total error lies below).
 *
 * Inputs: the first 3 channels are R, G, B; a 1- or 2-channel image is
 * grey (channel 0 for all three). A non-finite channel value is taken as 0
 * in the filters, and its pixel is left out of the pooled values
 * (counted). Every function is pure and thread-safe. See docs/metrics.md.
 */
#ifndef TARN_REF_FLIP_H
#define TARN_REF_FLIP_H

#include <stdbool.h>

#include "ref_metrics.h"    /* ref_fimage */

#define REF_FLIP_PPD 67.0206432731       /* 0.7 m, 0.7 m wide, 3840 px */

/* Zero means default in every field. */
typedef struct ref_flip_desc {
    double ppd;             /* pixels per degree (0 = REF_FLIP_PPD) */
    bool hdr;               /* false: LDR-FLIP (inputs clamped to [0, 1]);
                               true: HDR-FLIP (exposures below) */
    bool srgb;              /* LDR: the inputs hold sRGB-encoded values (a
                               PNG as stored): decoded to linear first */
    bool fixed_exposures;   /* HDR: use start/stop_exposure as given; false:
                               choose them from the reference */
    double start_exposure, stop_exposure;   /* HDR, with fixed_exposures */
    int num_exposures;      /* HDR: 0 = max(2, ceil(stop - start)) */
} ref_flip_desc;

/* Fills the zero fields of d with their defaults (ppd). The exposures
 * depend on the reference: ref_flip_exposures. */
void ref_flip_defaults(ref_flip_desc *d);

/* What a run used, and its pooled values. */
typedef struct ref_flip_result {
    bool hdr;
    double ppd;
    double start_exposure, stop_exposure;   /* HDR; NaN for LDR */
    int num_exposures;                      /* HDR; 0 for LDR */
    long pixels;            /* w * h */
    long pooled;            /* in the pooled values (inside the mask, finite) */
    long invalid;           /* inside the mask, left out: non-finite in A or B */
    double mean, weighted_median, q1, q3, min, max;  /* NaN when pooled == 0 */
} ref_flip_result;

/* The automatic HDR exposures of a reference image (see above). A black
 * reference gives 0 and 0; a median of 0 uses the smallest nonzero
 * luminance instead. */
void ref_flip_exposures(const ref_fimage *ref, double *start, double *stop);

/* The per-pixel FLIP error of test against ref into map (w * h floats, row
 * 0 = top, each in [0, 1]); exposure_map (may be NULL) gets, for HDR, the
 * index of the exposure that gave each pixel's max over num - 1 (0 = start,
 * 1 = stop), 0 for LDR. info (may be NULL) gets what was used, with every
 * pooled value over all pixels. False, with why in err, when the sizes
 * differ, an image is empty, or the exposures are bad (start > stop). */
bool ref_flip_map(const ref_fimage *test, const ref_fimage *ref, const ref_flip_desc *d,
                  float *map, float *exposure_map, ref_flip_result *info, char *err, int errlen);

/* Pools a map over the pixels where mask (w * h bytes, may be NULL) is
 * nonzero and the map is finite: fills out's pooled fields (pixels,
 * pooled, invalid, mean ... max); leaves the others. */
void ref_flip_pool(const float *map, int w, int h, const unsigned char *mask, ref_flip_result *out);

/* The one call for a figure: the map, pooled over mask (NULL = every
 * pixel). d may be NULL (LDR, defaults). */
bool ref_flip_mean(const ref_fimage *test, const ref_fimage *ref, const unsigned char *mask,
                   const ref_flip_desc *d, ref_flip_result *out, char *err, int errlen);

/* Matplotlib's "magma" (Smith and van der Walt, CC0), the authors' error
 * map colours: entry round(255 t) of 256 8-bit sRGB entries (t clamped to
 * [0, 1], NaN as 0). magma(0) = (0, 0, 4)/255, magma(1) = (252, 253,
 * 191)/255. */
void ref_flip_magma(double t, float rgb[3]);

/* Colours a map into rgb (w * h * 3 floats, display-ready sRGB in [0, 1]):
 * magma, as the authors' tool writes its error maps. Pixels outside mask
 * (may be NULL) are grey (0.5), NaN (non-finite in A or B) cyan (0, 1, 1),
 * as in ref_heatmap. */
void ref_flip_colorize(const float *map, int w, int h, const unsigned char *mask, float *rgb);

#endif
