/* ref_flip: LDR-FLIP and HDR-FLIP (see ref_flip.h), written from the
 * papers: Andersson et al., HPG 2020 (FLIP) and Eurographics 2021 short
 * papers (HDR-FLIP). */
#include "ref_flip.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"
#include "strbuf.h"
#include "util.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* The paper's constants. */
#define FLIP_QC 0.7         /* colour difference exponent */
#define FLIP_PC 0.4         /* remap knee: share of cmax ... */
#define FLIP_PT 0.95        /* ... mapped to this */
#define FLIP_W 0.082        /* feature width, degrees */
#define FLIP_QF 0.5         /* feature difference exponent */
#define FLIP_TM_TARGET 0.85 /* HDR: the tone-mapped value that sets x* */

/* The contrast sensitivity functions, per YyCxCz channel: a sum of two
 * Gaussians a sqrt(pi / b) exp(-pi^2 d^2 / b), d in degrees (Table 1 of
 * the paper; the second Gaussian is used by Cz only). */
static const double csf_a1[3] = { 1.0, 1.0, 34.1 }, csf_b1[3] = { 0.0047, 0.0053, 0.04 };
static const double csf_a2[3] = { 0.0, 0.0, 13.5 }, csf_b2[3] = { 1e-5, 1e-5, 0.025 };

/* ACES filmic, Narkowicz's fit x (2.51 x + 0.03) / (x (2.43 x + 0.59) +
 * 0.14), applied to 0.6 x (the fit's pre-exposure undone). */
static double aces(double x) {
    double s = 0.6 * x;
    return s * (2.51 * s + 0.03) / (s * (2.43 * s + 0.59) + 0.14);
}

void ref_flip_defaults(ref_flip_desc *d) {
    if (!(d->ppd > 0)) d->ppd = REF_FLIP_PPD;
}

/* ---- colour ------------------------------------------------------------------- */

/* Linear sRGB <-> XYZ, derived from the sRGB primaries and D65
 * (IEC 61966-2-1: R 0.64 0.33, G 0.30 0.60, B 0.15 0.06, W 0.3127 0.3290),
 * and the white's XYZ (the reference white of L*a*b* and YyCxCz). */
typedef struct space {
    double m[3][3], inv[3][3], white[3];
} space;

static void inv3(const double a[3][3], double o[3][3]) {
    double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
               - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
               + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
            o[r][c] = (a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1]) / det;
        }
}

static void space_init(space *s) {
    static const double xy[4][2] = { { 0.64, 0.33 }, { 0.30, 0.60 }, { 0.15, 0.06 }, { 0.3127, 0.3290 } };
    double p[3][3], pi[3][3], w[3], k[3];
    for (int c = 0; c < 3; c++) {
        p[0][c] = xy[c][0] / xy[c][1];
        p[1][c] = 1.0;
        p[2][c] = (1.0 - xy[c][0] - xy[c][1]) / xy[c][1];
    }
    w[0] = xy[3][0] / xy[3][1];
    w[1] = 1.0;
    w[2] = (1.0 - xy[3][0] - xy[3][1]) / xy[3][1];
    inv3(p, pi);
    for (int r = 0; r < 3; r++) k[r] = pi[r][0] * w[0] + pi[r][1] * w[1] + pi[r][2] * w[2];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) s->m[r][c] = p[r][c] * k[c];
    inv3(s->m, s->inv);
    for (int r = 0; r < 3; r++) s->white[r] = s->m[r][0] + s->m[r][1] + s->m[r][2];
}

static void mul3(const double m[3][3], const double v[3], double o[3]) {
    for (int r = 0; r < 3; r++) o[r] = m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2];
}

static double lab_f(double t) {
    const double d = 6.0 / 29.0;
    return t > d * d * d ? cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

/* Linear RGB -> CIELAB with the Hunt adjustment (a, b scaled by 0.01 L). */
static void rgb_to_lab_hunt(const space *s, const double rgb[3], double lab[3]) {
    double xyz[3];
    mul3(s->m, rgb, xyz);
    double fx = lab_f(xyz[0] / s->white[0]), fy = lab_f(xyz[1] / s->white[1]), fz = lab_f(xyz[2] / s->white[2]);
    double L = 116.0 * fy - 16.0;
    lab[0] = L;
    lab[1] = 0.01 * L * 500.0 * (fx - fy);
    lab[2] = 0.01 * L * 200.0 * (fy - fz);
}

static double hyab(const double a[3], const double b[3]) {
    return fabs(a[0] - b[0]) + hypot(a[1] - b[1], a[2] - b[2]);
}

/* ---- filters ------------------------------------------------------------------- */

/* One separable pass along x (dir 0) or y (dir 1) of a planar image: out
 * = sum over k of wt[k] * in[clamped position + k - r]. */
static void pass(const float *in, float *out, int w, int h, const double *wt, int r, int dir) {
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double acc = 0;
            for (int k = -r; k <= r; k++) {
                int xx = x, yy = y;
                if (dir == 0) { xx = x + k; xx = xx < 0 ? 0 : xx >= w ? w - 1 : xx; }
                else { yy = y + k; yy = yy < 0 ? 0 : yy >= h ? h - 1 : yy; }
                acc += wt[k + r] * in[(size_t)yy * (size_t)w + (size_t)xx];
            }
            out[(size_t)y * (size_t)w + (size_t)x] = (float)acc;
        }
}

/* 1D weights of the CSFs: ycx[0..n) for Yy, ycx[n..2n) for Cx (each sums to
 * 1), cz1/cz2 the two Gaussians of Cz split so that the 2D kernel
 * cz1(x) cz1(y) + cz2(x) cz2(y) is the paper's sum of Gaussians with unit
 * total. The radius covers 3 sd of the widest Gaussian. */
static int csf_radius(double ppd) {
    double bmax = 0;
    for (int c = 0; c < 3; c++) {
        if (csf_b1[c] > bmax) bmax = csf_b1[c];
        if (csf_b2[c] > bmax) bmax = csf_b2[c];
    }
    return (int)ceil(3.0 * sqrt(bmax / (2.0 * M_PI * M_PI)) * ppd);
}

static void csf_weights(double ppd, int r, double *wy, double *wcx, double *cz1, double *cz2) {
    int n = 2 * r + 1;
    double sy = 0, scx = 0, s1 = 0, s2 = 0;
    for (int i = 0; i < n; i++) {
        double d = (i - r) / ppd, d2 = d * d;
        wy[i] = exp(-M_PI * M_PI * d2 / csf_b1[0]);
        wcx[i] = exp(-M_PI * M_PI * d2 / csf_b1[1]);
        /* each factor carries the square root of its amplitude */
        cz1[i] = sqrt(csf_a1[2] * sqrt(M_PI / csf_b1[2])) * exp(-M_PI * M_PI * d2 / csf_b1[2]);
        cz2[i] = sqrt(csf_a2[2] * sqrt(M_PI / csf_b2[2])) * exp(-M_PI * M_PI * d2 / csf_b2[2]);
        sy += wy[i];
        scx += wcx[i];
        s1 += cz1[i];
        s2 += cz2[i];
    }
    double sz = sqrt(s1 * s1 + s2 * s2);
    for (int i = 0; i < n; i++) {
        wy[i] /= sy;
        wcx[i] /= scx;
        cz1[i] /= sz;
        cz2[i] /= sz;
    }
}

/* Feature filters: a Gaussian (sum 1) and its first and second derivatives
 * (positive weights sum to 1, negative to -1). */
static int feature_radius(double ppd) { return (int)ceil(3.0 * 0.5 * FLIP_W * ppd); }

static void feature_weights(double ppd, int r, double *g, double *dg, double *ddg) {
    double sd = 0.5 * FLIP_W * ppd, sg = 0, dpos = 0, dneg = 0, ddpos = 0, ddneg = 0;
    int n = 2 * r + 1;
    for (int i = 0; i < n; i++) {
        double x = i - r;
        g[i] = exp(-x * x / (2.0 * sd * sd));
        dg[i] = -x * g[i];
        ddg[i] = (x * x / (sd * sd) - 1.0) * g[i];
        sg += g[i];
        if (dg[i] > 0) dpos += dg[i]; else dneg -= dg[i];
        if (ddg[i] > 0) ddpos += ddg[i]; else ddneg -= ddg[i];
    }
    for (int i = 0; i < n; i++) {
        g[i] /= sg;
        dg[i] /= dg[i] > 0 ? dpos : dneg;
        ddg[i] /= ddg[i] > 0 ? ddpos : ddneg;
    }
}

/* ---- LDR-FLIP ------------------------------------------------------------------ */

/* Linear RGB in [0, 1], 3 floats a pixel (already clamped). */
typedef struct ldr_pair {
    const float *ref, *test;
    int w, h;
} ldr_pair;

/* LDR-FLIP of a pair of clamped linear RGB images into map. */
static void ldr_flip(const space *s, const ldr_pair *p, double ppd, float *map) {
    int w = p->w, h = p->h;
    size_t n = (size_t)w * (size_t)h;
    /* planes per image: 0 Yy, 1 Cx, 2 Cz (first Gaussian), 3 Cz (second),
     * 4 luminance Y for the features */
    float *pl[2][5], *tmp = mem_alloc(n * sizeof *tmp);
    for (int im = 0; im < 2; im++)
        for (int c = 0; c < 5; c++) pl[im][c] = mem_alloc(n * sizeof(float));
    for (int im = 0; im < 2; im++) {
        const float *src = im ? p->test : p->ref;
        for (size_t i = 0; i < n; i++) {
            double rgb[3] = { src[3 * i], src[3 * i + 1], src[3 * i + 2] }, xyz[3];
            mul3(s->m, rgb, xyz);
            double xr = xyz[0] / s->white[0], yr = xyz[1] / s->white[1], zr = xyz[2] / s->white[2];
            pl[im][0][i] = (float)(116.0 * yr - 16.0);
            pl[im][1][i] = (float)(500.0 * (xr - yr));
            pl[im][2][i] = pl[im][3][i] = (float)(200.0 * (yr - zr));
            pl[im][4][i] = (float)yr;
        }
    }

    /* colour: CSF filtering, then the Hunt-adjusted HyAB distance */
    int r = csf_radius(ppd), nw = 2 * r + 1;
    double *wy = mem_alloc((size_t)nw * 4 * sizeof(double)), *wcx = wy + nw, *c1 = wcx + nw, *c2 = c1 + nw;
    csf_weights(ppd, r, wy, wcx, c1, c2);
    const double *wts[4] = { wy, wcx, c1, c2 };
    for (int im = 0; im < 2; im++)
        for (int c = 0; c < 4; c++) {
            pass(pl[im][c], tmp, w, h, wts[c], r, 0);
            pass(tmp, pl[im][c], w, h, wts[c], r, 1);
        }
    free(wy);

    double lg[3], lb[3];
    rgb_to_lab_hunt(s, (const double[3]){ 0, 1, 0 }, lg);
    rgb_to_lab_hunt(s, (const double[3]){ 0, 0, 1 }, lb);
    double cmax = pow(hyab(lg, lb), FLIP_QC), pccmax = FLIP_PC * cmax;
    for (size_t i = 0; i < n; i++) {
        double lab[2][3];
        for (int im = 0; im < 2; im++) {
            double yr = (pl[im][0][i] + 16.0) / 116.0;
            double xyz[3] = { s->white[0] * (yr + pl[im][1][i] / 500.0), s->white[1] * yr,
                              s->white[2] * (yr - (pl[im][2][i] + pl[im][3][i]) / 200.0) }, rgb[3];
            mul3(s->inv, xyz, rgb);
            for (int c = 0; c < 3; c++) rgb[c] = rgb[c] < 0 ? 0 : rgb[c] > 1 ? 1 : rgb[c];
            rgb_to_lab_hunt(s, rgb, lab[im]);
        }
        double e = pow(hyab(lab[0], lab[1]), FLIP_QC);
        e = e < pccmax ? e * FLIP_PT / pccmax : FLIP_PT + (e - pccmax) / (cmax - pccmax) * (1.0 - FLIP_PT);
        map[i] = (float)e;
    }

    /* features: edges (first derivative) and points (second) of Y */
    int fr = feature_radius(ppd), fw = 2 * fr + 1;
    double *g = mem_alloc((size_t)fw * 3 * sizeof(double)), *dg = g + fw, *ddg = dg + fw;
    feature_weights(ppd, fr, g, dg, ddg);
    float *f[2][4];     /* per image: edge x, edge y, point x, point y */
    for (int im = 0; im < 2; im++) {
        for (int k = 0; k < 4; k++) f[im][k] = mem_alloc(n * sizeof(float));
        pass(pl[im][4], tmp, w, h, dg, fr, 0);
        pass(tmp, f[im][0], w, h, g, fr, 1);
        pass(pl[im][4], tmp, w, h, g, fr, 0);
        pass(tmp, f[im][1], w, h, dg, fr, 1);
        pass(pl[im][4], tmp, w, h, ddg, fr, 0);
        pass(tmp, f[im][2], w, h, g, fr, 1);
        pass(pl[im][4], tmp, w, h, g, fr, 0);
        pass(tmp, f[im][3], w, h, ddg, fr, 1);
    }
    free(g);
    for (size_t i = 0; i < n; i++) {
        double edge[2], point[2];
        for (int im = 0; im < 2; im++) {
            edge[im] = hypot(f[im][0][i], f[im][1][i]);
            point[im] = hypot(f[im][2][i], f[im][3][i]);
        }
        double de = fabs(edge[0] - edge[1]), dp = fabs(point[0] - point[1]);
        double feat = pow((de > dp ? de : dp) / sqrt(2.0), FLIP_QF);
        map[i] = (float)pow(map[i], 1.0 - feat);
    }
    for (int im = 0; im < 2; im++) {
        for (int k = 0; k < 4; k++) free(f[im][k]);
        for (int c = 0; c < 5; c++) free(pl[im][c]);
    }
    free(tmp);
}

/* ---- inputs -------------------------------------------------------------------- */

/* Channel c of pixel i: a side with fewer than 3 channels is grey. */
static double chan(const ref_fimage *im, size_t i, int c) {
    return im->px[i * (size_t)im->channels + (size_t)(im->channels >= 3 ? c : 0)];
}

/* RGB copy of im with non-finite values 0; bad[i] set where one was. */
static float *rgb_copy(const ref_fimage *im, unsigned char *bad) {
    size_t n = (size_t)im->w * (size_t)im->h;
    float *o = mem_alloc(n * 3 * sizeof *o);
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            double v = chan(im, i, c);
            if (!isfinite(v)) { v = 0; bad[i] = 1; }
            o[3 * i + (size_t)c] = (float)v;
        }
    return o;
}

static double luminance(const float *rgb) {
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

static int cmp_float(const void *a, const void *b) {
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* x* with aces(x*) = 0.85: the larger root of a quadratic. */
static double aces_inverse(double t) {
    /* aces(x) = (A x^2 + B x) / (C x^2 + D x + E) */
    double A = 0.36 * 2.51, B = 0.6 * 0.03, C = 0.36 * 2.43, D = 0.6 * 0.59, E = 0.14;
    double qa = A - t * C, qb = B - t * D, qc = -t * E;
    double h = -0.5 * qb / qa;
    return h + sqrt(h * h - qc / qa);
}

static void exposures_of(const float *rgb, size_t n, double *start, double *stop) {
    float *y = mem_alloc(n * sizeof *y);
    double ymax = 0, ymin_nz = INFINITY;
    for (size_t i = 0; i < n; i++) {
        double v = luminance(rgb + 3 * i);
        y[i] = (float)v;
        if (v > ymax) ymax = v;
        if (v > 0 && v < ymin_nz) ymin_nz = v;
    }
    qsort(y, n, sizeof *y, cmp_float);
    double ymed = y[n / 2];
    free(y);
    if (!(ymax > 0)) { *start = *stop = 0; return; }
    if (!(ymed > 0)) ymed = ymin_nz;
    double xs = aces_inverse(FLIP_TM_TARGET);
    *start = log2(xs / ymax);
    *stop = log2(xs / ymed);
}

void ref_flip_exposures(const ref_fimage *ref, double *start, double *stop) {
    *start = *stop = 0;
    if (!ref || !ref->px || ref->w <= 0 || ref->h <= 0 || ref->channels <= 0) return;
    size_t n = (size_t)ref->w * (size_t)ref->h;
    unsigned char *bad = mem_zalloc(n);
    float *rgb = rgb_copy(ref, bad);
    exposures_of(rgb, n, start, stop);
    free(rgb);
    free(bad);
}

/* ---- pooling ------------------------------------------------------------------- */

/* The first sorted value at which the running sum exceeds p * sum. */
static double weighted_quantile(const double *v, long n, double sum, double p) {
    double run = 0;
    for (long i = 0; i < n; i++) {
        run += v[i];
        if (run > p * sum) return v[i];
    }
    return 0;
}

void ref_flip_pool(const float *map, int w, int h, const unsigned char *mask, ref_flip_result *out) {
    long n = (long)w * h, k = 0, invalid = 0;
    double *v = mem_alloc((size_t)(n > 0 ? n : 1) * sizeof *v), sum = 0;
    for (long i = 0; i < n; i++) {
        if (mask && !mask[i]) continue;
        if (!isfinite(map[i])) { invalid++; continue; }
        v[k++] = map[i];
        sum += map[i];
    }
    out->pixels = n;
    out->pooled = k;
    out->invalid = invalid;
    if (k == 0) {
        out->mean = out->weighted_median = out->q1 = out->q3 = out->min = out->max = NAN;
    } else {
        qsort(v, (size_t)k, sizeof *v, cmp_double);
        out->mean = sum / (double)k;
        out->min = v[0];
        out->max = v[k - 1];
        out->weighted_median = weighted_quantile(v, k, sum, 0.5);
        out->q1 = weighted_quantile(v, k, sum, 0.25);
        out->q3 = weighted_quantile(v, k, sum, 0.75);
    }
    free(v);
}

/* ---- the map ------------------------------------------------------------------- */

bool ref_flip_map(const ref_fimage *test, const ref_fimage *ref, const ref_flip_desc *dd,
                  float *map, float *exposure_map, ref_flip_result *info, char *err, int errlen) {
    ref_flip_desc d = dd ? *dd : (ref_flip_desc){0};
    ref_flip_defaults(&d);
    const ref_fimage *ims[2] = { test, ref };
    for (int k = 0; k < 2; k++)
        if (!ims[k] || !ims[k]->px || ims[k]->w <= 0 || ims[k]->h <= 0 || ims[k]->channels <= 0) {
            msg_set(err, (size_t)errlen, "%s is empty", k == 0 ? "A" : "B");
            return false;
        }
    if (test->w != ref->w || test->h != ref->h) {
        msg_set(err, (size_t)errlen, "sizes differ: A is %dx%d, B is %dx%d", test->w, test->h, ref->w, ref->h);
        return false;
    }
    if (!isfinite(d.ppd)) { msg_set(err, (size_t)errlen, "pixels per degree must be finite"); return false; }
    int w = ref->w, h = ref->h;
    size_t n = (size_t)w * (size_t)h;
    unsigned char *bad = mem_zalloc(n);
    float *rt = rgb_copy(test, bad), *rr = rgb_copy(ref, bad);
    double start = NAN, stop = NAN;
    int num = 0;
    bool ok = true;
    space s;
    space_init(&s);

    if (!d.hdr) {
        for (size_t i = 0; i < 3 * n; i++) {
            if (d.srgb) {
                rt[i] = (float)ref_srgb_to_linear(rt[i]);
                rr[i] = (float)ref_srgb_to_linear(rr[i]);
            }
            rt[i] = rt[i] < 0 ? 0 : rt[i] > 1 ? 1 : rt[i];
            rr[i] = rr[i] < 0 ? 0 : rr[i] > 1 ? 1 : rr[i];
        }
        ldr_pair p = { rr, rt, w, h };
        ldr_flip(&s, &p, d.ppd, map);
        if (exposure_map) memset(exposure_map, 0, n * sizeof *exposure_map);
    } else {
        if (d.fixed_exposures) { start = d.start_exposure; stop = d.stop_exposure; }
        else exposures_of(rr, n, &start, &stop);
        if (!isfinite(start) || !isfinite(stop) || start > stop) {
            msg_set(err, (size_t)errlen, "bad exposures: start %g, stop %g (start <= stop, both finite)", start, stop);
            ok = false;
            goto done;
        }
        num = d.num_exposures > 0 ? d.num_exposures : (int)fmax(2.0, ceil(stop - start));
        if (num < 2) num = 2;
        float *lt = mem_alloc(3 * n * sizeof *lt), *lr = mem_alloc(3 * n * sizeof *lr);
        float *tmap = mem_alloc(n * sizeof *tmap);
        for (size_t i = 0; i < n; i++) {
            map[i] = 0;
            if (exposure_map) exposure_map[i] = 0;
        }
        double step = (stop - start) / (num - 1);
        for (int e = 0; e < num; e++) {
            double m = pow(2.0, start + e * step);
            for (size_t i = 0; i < 3 * n; i++) {
                double a = aces(m * rt[i]), b = aces(m * rr[i]);
                lt[i] = (float)(a < 0 ? 0 : a > 1 ? 1 : a);
                lr[i] = (float)(b < 0 ? 0 : b > 1 ? 1 : b);
            }
            ldr_pair p = { lr, lt, w, h };
            ldr_flip(&s, &p, d.ppd, tmap);
            for (size_t i = 0; i < n; i++)
                if (tmap[i] > map[i]) {
                    map[i] = tmap[i];
                    if (exposure_map) exposure_map[i] = (float)e / (float)(num - 1);
                }
        }
        free(lt);
        free(lr);
        free(tmap);
    }
    for (size_t i = 0; i < n; i++)
        if (bad[i]) map[i] = NAN;
    if (info) {
        memset(info, 0, sizeof *info);
        info->hdr = d.hdr;
        info->ppd = d.ppd;
        info->start_exposure = start;
        info->stop_exposure = stop;
        info->num_exposures = num;
        ref_flip_pool(map, w, h, NULL, info);
    }
done:
    free(bad);
    free(rt);
    free(rr);
    return ok;
}

bool ref_flip_mean(const ref_fimage *test, const ref_fimage *ref, const unsigned char *mask,
                   const ref_flip_desc *d, ref_flip_result *out, char *err, int errlen) {
    if (!test || !ref || test->w <= 0 || test->h <= 0) {
        msg_set(err, (size_t)errlen, "%s is empty", !test || test->w <= 0 || test->h <= 0 ? "A" : "B");
        return false;
    }
    float *map = mem_alloc((size_t)test->w * (size_t)test->h * sizeof *map);
    bool ok = ref_flip_map(test, ref, d, map, NULL, out, err, errlen);
    if (ok) ref_flip_pool(map, test->w, test->h, mask, out);
    free(map);
    return ok;
}

/* ---- colours ------------------------------------------------------------------- */

/* Matplotlib's "magma" (Nathaniel J. Smith and Stefan van der Walt, CC0):
 * 256 entries of 8-bit sRGB, 6 hex digits each. */
static const char magma_hex[] =
    "00000401000501010601010802010902020b02020d03030f030312040414050416060518"
    "06051a07061c08071e0907200a08220b09240c09260d0a290e0b2b100b2d110c2f120d31"
    "130d34140e36150e38160f3b180f3d19103f1a10421c10441d11471e114920114b21114e"
    "22115024125325125527125829115a2a115c2c115f2d11612f1163311165331067341069"
    "36106b38106c390f6e3b0f703d0f713f0f72400f74420f75440f76451077471078491078"
    "4a10794c117a4e117b4f127b51127c52137c54137d56147d57157e59157e5a167e5c167f"
    "5d177f5f187f601880621980641a80651a80671b80681c816a1c816b1d816d1d816e1e81"
    "701f81721f817320817521817621817822817922827b23827c23827e2482802582812581"
    "8326818426818627818827818928818b29818c29818e2a81902a81912b81932b80942c80"
    "962c80982d80992d809b2e7f9c2e7f9e2f7fa02f7fa1307ea3307ea5317ea6317da8327d"
    "aa337dab337cad347cae347bb0357bb2357bb3367ab5367ab73779b83779ba3878bc3978"
    "bd3977bf3a77c03a76c23b75c43c75c53c74c73d73c83e73ca3e72cc3f71cd4071cf4070"
    "d0416fd2426fd3436ed5446dd6456cd8456cd9466bdb476adc4869de4968df4a68e04c67"
    "e24d66e34e65e44f64e55064e75263e85362e95462ea5661eb5760ec5860ed5a5fee5b5e"
    "ef5d5ef05f5ef1605df2625df2645cf3655cf4675cf4695cf56b5cf66c5cf66e5cf7705c"
    "f7725cf8745cf8765cf9785df9795df97b5dfa7d5efa7f5efa815ffb835ffb8560fb8761"
    "fc8961fc8a62fc8c63fc8e64fc9065fd9266fd9467fd9668fd9869fd9a6afd9b6bfe9d6c"
    "fe9f6dfea16efea36ffea571fea772fea973feaa74feac76feae77feb078feb27afeb47b"
    "feb67cfeb77efeb97ffebb81febd82febf84fec185fec287fec488fec68afec88cfeca8d"
    "fecc8ffecd90fecf92fed194fed395fed597fed799fed89afdda9cfddc9efddea0fde0a1"
    "fde2a3fde3a5fde5a7fde7a9fde9aafdebacfcecaefceeb0fcf0b2fcf2b4fcf4b6fcf6b8"
    "fcf7b9fcf9bbfcfbbdfcfdbf";

static int hexval(char c) {
    return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : 0;
}

void ref_flip_magma(double t, float rgb[3]) {
    if (!(t > 0)) t = 0;
    if (t > 1) t = 1;
    int i = (int)(t * 255.0 + 0.5);
    const char *e = magma_hex + 6 * i;
    for (int c = 0; c < 3; c++) rgb[c] = (float)((hexval(e[2 * c]) * 16 + hexval(e[2 * c + 1])) / 255.0);
}

void ref_flip_colorize(const float *map, int w, int h, const unsigned char *mask, float *rgb) {
    for (long i = 0; i < (long)w * h; i++) {
        float *o = rgb + 3 * i;
        if (mask && !mask[i]) o[0] = o[1] = o[2] = 0.5f;
        else if (!isfinite(map[i])) { o[0] = 0; o[1] = o[2] = 1; }
        else ref_flip_magma(map[i], o);
    }
}
