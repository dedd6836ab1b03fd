/* ref_ssim: SSIM (Wang et al. 2004), see ref_ssim.h. */
#include "ref_ssim.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"
#include "strbuf.h"

#define R (REF_SSIM_WINDOW / 2)

/* Display value of a linear value: clamped, sRGB-encoded. */
static double display(double v) {
    if (!(v > 0)) return 0;
    return v >= 1 ? 1 : ref_linear_to_srgb(v);
}

/* The grey plane (chan < 0: luminance; else channel chan) of im, display
 * encoded; bad[i] |= 1 where a used value is non-finite (then 0). */
static void plane(const ref_fimage *im, int chan, double *out, unsigned char *bad) {
    size_t n = (size_t)im->w * (size_t)im->h, ch = (size_t)im->channels;
    for (size_t i = 0; i < n; i++) {
        const float *p = im->px + i * ch;
        double rgb[3];
        for (int c = 0; c < 3; c++) rgb[c] = p[ch >= 3 ? (size_t)c : 0];
        double v = chan < 0 ? 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2] : rgb[chan];
        if (!isfinite(v)) { v = 0; bad[i] = 1; }
        out[i] = display(v);
    }
}

/* Gaussian-weighted window sums of the 5 planes (a, b, a^2, b^2, ab) and
 * of bad, at the centres whose window lies inside; then SSIM there. */
static void ssim_plane(const double *a, const double *b, const unsigned char *bad, int w, int h,
                       const double *g, double *acc) {
    int vw = w - 2 * R;
    size_t n = (size_t)w * (size_t)h;
    double *hs = mem_alloc(n * 6 * sizeof *hs);     /* horizontal sums, columns R..w-R-1 */
    for (int y = 0; y < h; y++)
        for (int x = R; x < w - R; x++) {
            double s[6] = {0};
            for (int k = -R; k <= R; k++) {
                size_t i = (size_t)y * (size_t)w + (size_t)(x + k);
                double wk = g[k + R];
                s[0] += wk * a[i];
                s[1] += wk * b[i];
                s[2] += wk * a[i] * a[i];
                s[3] += wk * b[i] * b[i];
                s[4] += wk * a[i] * b[i];
                s[5] += wk * bad[i];
            }
            memcpy(hs + ((size_t)y * (size_t)vw + (size_t)(x - R)) * 6, s, sizeof s);
        }
    const double c1 = (REF_SSIM_K1 * 1.0) * (REF_SSIM_K1 * 1.0), c2 = (REF_SSIM_K2 * 1.0) * (REF_SSIM_K2 * 1.0);
    for (int y = R; y < h - R; y++)
        for (int x = R; x < w - R; x++) {
            double s[6] = {0};
            for (int k = -R; k <= R; k++) {
                const double *p = hs + ((size_t)(y + k) * (size_t)vw + (size_t)(x - R)) * 6;
                for (int j = 0; j < 6; j++) s[j] += g[k + R] * p[j];
            }
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            if (s[5] > 0) { acc[i] = NAN; continue; }
            double ma = s[0], mb = s[1];
            double va = s[2] - ma * ma, vb = s[3] - mb * mb, cab = s[4] - ma * mb;
            acc[i] += (2 * ma * mb + c1) * (2 * cab + c2) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
        }
    free(hs);
}

bool ref_ssim(const ref_fimage *a, const ref_fimage *b, const ref_ssim_desc *dd, float *map,
              ref_ssim_result *out, char *err, int errlen) {
    ref_ssim_desc d = dd ? *dd : (ref_ssim_desc){0};
    const ref_fimage *ims[2] = { a, b };
    for (int k = 0; k < 2; k++)
        if (!ims[k] || !ims[k]->px || ims[k]->w <= 0 || ims[k]->h <= 0 || ims[k]->channels <= 0) {
            msg_set(err, (size_t)errlen, "%s is empty", k == 0 ? "A" : "B");
            return false;
        }
    if (a->w != b->w || a->h != b->h) {
        msg_set(err, (size_t)errlen, "sizes differ: A is %dx%d, B is %dx%d", a->w, a->h, b->w, b->h);
        return false;
    }
    int w = a->w, h = a->h;
    if (w < REF_SSIM_WINDOW || h < REF_SSIM_WINDOW) {
        msg_set(err, (size_t)errlen, "SSIM needs images of at least %dx%d (its window): these are %dx%d",
                REF_SSIM_WINDOW, REF_SSIM_WINDOW, w, h);
        return false;
    }
    double g[REF_SSIM_WINDOW], gs = 0;
    for (int k = -R; k <= R; k++) gs += g[k + R] = exp(-(double)(k * k) / (2 * REF_SSIM_SIGMA * REF_SSIM_SIGMA));
    for (int k = 0; k < REF_SSIM_WINDOW; k++) g[k] /= gs;

    size_t n = (size_t)w * (size_t)h;
    double *pa = mem_alloc(n * sizeof *pa), *pb = mem_alloc(n * sizeof *pb), *acc = mem_zalloc(n * sizeof *acc);
    unsigned char *bad = mem_zalloc(n);
    int planes = d.per_channel ? 3 : 1;
    for (int c = 0; c < planes; c++) {
        plane(a, d.per_channel ? c : -1, pa, bad);
        plane(b, d.per_channel ? c : -1, pb, bad);
    }
    for (int c = 0; c < planes; c++) {
        if (planes > 1) {
            plane(a, c, pa, bad);
            plane(b, c, pb, bad);
        }
        ssim_plane(pa, pb, bad, w, h, g, acc);
    }
    ref_ssim_result r = { .mean = NAN, .min = NAN };
    double sum = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            bool inside = x >= R && x < w - R && y >= R && y < h - R;
            double v = inside ? acc[i] / planes : NAN;
            if (map) map[i] = (float)v;
            if (d.mask && !d.mask[i]) continue;
            if (!inside) { r.border++; continue; }
            if (isnan(v)) { r.invalid++; continue; }
            sum += v;
            if (r.pooled == 0 || v < r.min) r.min = v;
            r.pooled++;
        }
    if (r.pooled) r.mean = sum / (double)r.pooled;
    if (out) *out = r;
    free(pa);
    free(pb);
    free(acc);
    free(bad);
    return true;
}
