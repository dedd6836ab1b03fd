/* ref_ssim: the structural similarity index (Wang, Bovik, Sheikh,
 * Simoncelli, "Image Quality Assessment: From Error Visibility to
 * Structural Similarity", IEEE TIP 2004). Pure C, no I/O.
 *
 * Inputs are linear RGB, as everywhere in ref_metrics (an 8-bit file
 * decoded from sRGB, an EXR as stored). SSIM is computed on what a display
 * shows, by default on one grey plane: the luminance Y = 0.2126 R +
 * 0.7152 G + 0.0722 B of the linear values, clamped to [0, 1] and encoded
 * with the sRGB curve (a grey PNG's own values; an HDR value above 1 is
 * the display's white). With per_channel, SSIM is computed on each
 * sRGB-encoded channel R, G, B (clamped) and the three maps averaged.
 * A side with 1 or 2 channels is grey (channel 0).
 *
 * Per pixel (x, y), over the 11x11 Gaussian window (sd 1.5, weights
 * normalised to sum 1) centred on it:
 *
 *   SSIM = (2 mu_a mu_b + C1) (2 s_ab + C2) / ((mu_a^2 + mu_b^2 + C1) (s_a^2 + s_b^2 + C2))
 *
 * with the window's weighted means, variances and covariance, C1 =
 * (K1 L)^2, C2 = (K2 L)^2, K1 = 0.01, K2 = 0.03, L = 1 (the dynamic range
 * of the encoded values). As in the paper's code, only centres whose window
 * lies inside the image count (the map is NaN in a border of 5 pixels), and
 * there is no downsampling. The mean SSIM is over those centres inside the
 * mask (e.g. the reference's water). A window that touches a non-finite
 * value (taken as 0) leaves its centre out, counted in `invalid`.
 * SSIM is 1 for identical images and symmetric in A and B; it can be
 * negative (anti-correlated structure).
 */
#ifndef TARN_REF_SSIM_H
#define TARN_REF_SSIM_H

#include <stdbool.h>

#include "ref_metrics.h"    /* ref_fimage */

#define REF_SSIM_WINDOW 11
#define REF_SSIM_SIGMA 1.5
#define REF_SSIM_K1 0.01
#define REF_SSIM_K2 0.03

/* Zero means default in every field. */
typedef struct ref_ssim_desc {
    const unsigned char *mask;  /* w * h bytes, row 0 = top; nonzero =
                                   pooled; NULL = every centre */
    bool per_channel;           /* false: the luminance plane; true: R, G,
                                   B each, averaged */
} ref_ssim_desc;

typedef struct ref_ssim_result {
    double mean;        /* mean SSIM over the pooled centres; NaN if none */
    double min;         /* the lowest pooled value; NaN if none */
    long pooled;        /* centres in the mean (window inside, in the mask, finite) */
    long invalid;       /* in the mask and inside, left out: a non-finite value in the window */
    long border;        /* in the mask, left out: the window is not inside the image */
} ref_ssim_result;

/* Mean SSIM of a against b; map (w * h floats, may be NULL) gets the
 * per-pixel SSIM (NaN where the window is not inside or touches a
 * non-finite value). False, with why in err, when the sizes differ, an
 * image is empty or smaller than the window (11x11). */
bool ref_ssim(const ref_fimage *a, const ref_fimage *b, const ref_ssim_desc *d, float *map,
              ref_ssim_result *out, char *err, int errlen);

#endif
