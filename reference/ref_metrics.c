/* ref_metrics: error metrics between float images and buffers, heat maps.
 * See ref_metrics.h and docs/metrics.md. */
#include "ref_metrics.h"
#include "mem.h"
#include "ref_render.h"
#include "strbuf.h"
#include "util.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Matplotlib's "inferno" (Nathaniel J. Smith and Stefan van der Walt, CC0):
 * 256 entries of 8-bit sRGB, 6 hex digits each. */
static const char inferno_hex[] =
    "00000401000501010601010802010a02020c02020e030210040312040314050417060419"
    "07051b08051d09061f0a07220b07240c08260d08290e092b10092d110a30120a32140b34"
    "150b37160b39180c3c190c3e1b0c411c0c431e0c451f0c48210c4a230c4c240c4f260c51"
    "280b53290b552b0b572d0b592f0a5b310a5c320a5e340a5f3609613809623909633b0964"
    "3d09653e0966400a67420a68440a68450a69470b6a490b6a4a0c6b4c0c6b4d0d6c4f0d6c"
    "510e6c520e6d540f6d550f6d57106e59106e5a116e5c126e5d126e5f136e61136e62146e"
    "64156e65156e67166e69166e6a176e6c186e6d186e6f196e71196e721a6e741a6e751b6e"
    "771c6d781c6d7a1d6d7c1d6d7d1e6d7f1e6c801f6c82206c84206b85216b87216b88226a"
    "8a226a8c23698d23698f24699025689225689326679526679727669827669a28659b2964"
    "9d29649f2a63a02a63a22b62a32c61a52c60a62d60a82e5fa92e5eab2f5ead305dae305c"
    "b0315bb1325ab3325ab43359b63458b73557b93556ba3655bc3754bd3853bf3952c03a51"
    "c13a50c33b4fc43c4ec63d4dc73e4cc83f4bca404acb4149cc4248ce4347cf4446d04545"
    "d24644d34743d44842d54a41d74b3fd84c3ed94d3dda4e3cdb503bdd513ade5238df5337"
    "e05536e15635e25734e35933e45a31e55c30e65d2fe75e2ee8602de9612bea632aeb6429"
    "eb6628ec6726ed6925ee6a24ef6c23ef6e21f06f20f1711ff1731df2741cf3761bf37819"
    "f47918f57b17f57d15f67e14f68013f78212f78410f8850ff8870ef8890cf98b0bf98c0a"
    "f98e09fa9008fa9207fa9407fb9606fb9706fb9906fb9b06fb9d07fc9f07fca108fca309"
    "fca50afca60cfca80dfcaa0ffcac11fcae12fcb014fcb216fcb418fbb61afbb81dfbba1f"
    "fbbc21fbbe23fac026fac228fac42afac62df9c72ff9c932f9cb35f8cd37f8cf3af7d13d"
    "f7d340f6d543f6d746f5d949f5db4cf4dd4ff4df53f4e156f3e35af3e55df2e661f2e865"
    "f2ea69f1ec6df1ed71f1ef75f1f179f2f27df2f482f3f586f3f68af4f88ef5f992f6fa96"
    "f8fb9af9fc9dfafda1fcffa4";

/* ---- colour map, sRGB ----------------------------------------------------- */

static int hexval(char c) {
    return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : 0;
}

static double inferno_entry(int i, int c) {
    const char *h = inferno_hex + 6 * i + 2 * c;
    return (hexval(h[0]) * 16 + hexval(h[1])) / 255.0;
}

void ref_colormap_inferno(double t, float rgb[3]) {
    if (!(t > 0)) t = 0;            /* NaN too */
    if (t > 1) t = 1;
    double x = t * 255.0;
    int i = (int)x;
    if (i > 254) i = 254;
    double f = x - i;
    for (int c = 0; c < 3; c++)
        rgb[c] = (float)((1 - f) * inferno_entry(i, c) + f * inferno_entry(i + 1, c));
}

double ref_srgb_to_linear(double c) {
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

double ref_linear_to_srgb(double c) {
    return c <= 0.0031308 ? c * 12.92 : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

/* ---- percentiles ----------------------------------------------------------- */

double ref_percentile_sorted(const double *sorted, long n, double p) {
    if (n <= 0 || !sorted) return NAN;
    if (!(p > 0)) p = 0;
    if (p > 100) p = 100;
    double r = p / 100.0 * (double)(n - 1);
    long i = (long)floor(r);
    if (i >= n - 1) return sorted[n - 1];
    double f = r - (double)i;
    return sorted[i] + f * (sorted[i + 1] - sorted[i]);
}

double ref_percentile(double *v, long n, double p) {
    if (n <= 0 || !v) return NAN;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return ref_percentile_sorted(v, n, p);
}

/* ---- statistics of error samples ------------------------------------------ */

/* Samples go in one at a time; finish sorts them for the percentiles. */
typedef struct sampler {
    double *v;
    long n;
    double sum, sumsq, max;
    long max_i;
    int max_c;
} sampler;

static void sampler_init(sampler *s, long capacity) {
    memset(s, 0, sizeof *s);
    s->max_i = -1;
    s->max_c = -1;
    s->v = mem_alloc((size_t)(capacity > 0 ? capacity : 1) * sizeof *s->v);
}

static void sampler_add(sampler *s, double e, long pixel, int channel) {
    s->v[s->n++] = e;
    s->sum += e;
    s->sumsq += e * e;
    if (s->max_i < 0 || e > s->max) { s->max = e; s->max_i = pixel; s->max_c = channel; }
}

static void stats_nan(ref_err_stats *st) {
    st->n = 0;
    st->mean = st->rms = st->median = st->p95 = st->p99 = st->max = NAN;
    st->max_x = st->max_y = st->max_c = -1;
}

/* Fills st from the samples and frees them. */
static void sampler_finish(sampler *s, int w, ref_err_stats *st) {
    stats_nan(st);
    if (s->n > 0) {
        qsort(s->v, (size_t)s->n, sizeof *s->v, cmp_double);
        st->n = s->n;
        st->mean = s->sum / (double)s->n;
        st->rms = sqrt(s->sumsq / (double)s->n);
        st->median = ref_percentile_sorted(s->v, s->n, 50);
        st->p95 = ref_percentile_sorted(s->v, s->n, 95);
        st->p99 = ref_percentile_sorted(s->v, s->n, 99);
        st->max = s->max;
        st->max_x = (int)(s->max_i % w);
        st->max_y = (int)(s->max_i / w);
        st->max_c = s->max_c;
    }
    free(s->v);
    s->v = NULL;
}

/* ---- pairs of images -------------------------------------------------------- */

/* Which channels of A and B a comparison reads. */
typedef struct pair {
    const ref_fimage *a, *b;
    const unsigned char *mask;
    int w, h;
    int nc;             /* compared channels */
    int ia[4], ib[4];   /* channel of A / B for each compared channel */
} pair;

static bool image_ok(const ref_fimage *im) {
    return im && im->px && im->w > 0 && im->h > 0 && im->channels > 0;
}

static bool pair_init(pair *p, const ref_fimage *a, const ref_fimage *b, ref_err_kind kind,
                      const ref_metrics_desc *d, char *err, int errlen) {
    memset(p, 0, sizeof *p);
    if (!image_ok(a) || !image_ok(b)) {
        msg_set(err, (size_t)errlen, "%s is empty", !image_ok(a) ? "A" : "B");
        return false;
    }
    if (a->w != b->w || a->h != b->h) {
        msg_set(err, (size_t)errlen, "sizes differ: A is %dx%d, B is %dx%d", a->w, a->h, b->w, b->h);
        return false;
    }
    p->a = a;
    p->b = b;
    p->mask = d ? d->mask : NULL;
    p->w = a->w;
    p->h = a->h;
    int ca = a->channels, cb = b->channels;
    switch (kind) {
    case REF_ERR_COLOR:
        /* Fewer than 3 channels: grey, channel 0 stands for R, G and B. */
        p->nc = 3;
        for (int c = 0; c < 3; c++) {
            p->ia[c] = ca >= 3 ? c : 0;
            p->ib[c] = cb >= 3 ? c : 0;
        }
        break;
    case REF_ERR_POINT:
        if (ca < 3 || cb < 3) {
            msg_set(err, (size_t)errlen, "hit points need 3 channels (x, y, z): A has %d, B has %d", ca, cb);
            return false;
        }
        p->nc = 3;
        for (int c = 0; c < 3; c++) p->ia[c] = p->ib[c] = c;
        break;
    case REF_ERR_SCALAR:
        if (ca == 1 || cb == 1) p->nc = ca > cb ? ca : cb;
        else p->nc = ca < cb ? ca : cb;
        if (p->nc > 4) p->nc = 4;
        for (int c = 0; c < p->nc; c++) {
            p->ia[c] = ca == 1 ? 0 : c;
            p->ib[c] = cb == 1 ? 0 : c;
        }
        break;
    default:
        msg_set(err, (size_t)errlen, "unknown error kind %d", (int)kind);
        return false;
    }
    return true;
}

/* 0 finite, 1 a NaN, 2 an Inf (and no NaN) in the compared channels. */
static int nonfinite(const float *px, const int *idx, int nc) {
    int inf = 0;
    for (int c = 0; c < nc; c++) {
        float v = px[idx[c]];
        if (isnan(v)) return 1;
        if (isinf(v)) inf = 2;
    }
    return inf;
}

/* Classifies pixel i and counts it: true when it is compared. */
static bool pair_pixel(const pair *p, long i, ref_pixel_counts *n, const float **pa, const float **pb) {
    const float *a = p->a->px + (size_t)i * (size_t)p->a->channels;
    const float *b = p->b->px + (size_t)i * (size_t)p->b->channels;
    int fa = nonfinite(a, p->ia, p->nc), fb = nonfinite(b, p->ib, p->nc);
    if (fa == 1) n->nan_a++;
    if (fa == 2) n->inf_a++;
    if (fb == 1) n->nan_b++;
    if (fb == 2) n->inf_b++;
    if (p->mask && !p->mask[i]) { n->masked_out++; return false; }
    if (fa || fb) { n->invalid++; return false; }
    n->compared++;
    *pa = a;
    *pb = b;
    return true;
}

/* The per-pixel error of a compared pixel. */
static double pixel_error(const pair *p, ref_err_kind kind, const float *a, const float *b) {
    double e = 0;
    if (kind == REF_ERR_POINT) {
        for (int c = 0; c < 3; c++) {
            double t = (double)a[c] - (double)b[c];
            e += t * t;
        }
        return sqrt(e);
    }
    for (int c = 0; c < p->nc; c++) {
        double t = fabs((double)a[p->ia[c]] - (double)b[p->ib[c]]);
        if (t > e) e = t;
    }
    return e;
}

static double share(long k, long n) { return n > 0 ? (double)k / (double)n : NAN; }

/* ---- colour -------------------------------------------------------------------- */

bool ref_metrics_image(const ref_fimage *a, const ref_fimage *b, const ref_metrics_desc *d,
                       ref_image_metrics *out, char *err, int errlen) {
    memset(out, 0, sizeof *out);
    pair p;
    if (!pair_init(&p, a, b, REF_ERR_COLOR, d, err, errlen)) return false;
    long npx = (long)p.w * p.h;
    sampler s;
    sampler_init(&s, npx);
    out->width = p.w;
    out->height = p.h;
    out->channels = p.nc;
    out->count.pixels = npx;
    out->peak = d && d->peak > 0 ? d->peak : REF_METRICS_PEAK;
    out->threshold = d && d->threshold > 0 ? d->threshold : REF_METRICS_THRESHOLD;
    out->max_x = out->max_y = out->max_c = -1;
    double sumsq[3] = {0}, sum[3] = {0}, sumabs = 0, maxabs = -1;
    for (long i = 0; i < npx; i++) {
        const float *pa, *pb;
        if (!pair_pixel(&p, i, &out->count, &pa, &pb)) continue;
        double e = 0;
        for (int c = 0; c < p.nc; c++) {
            double t = (double)pa[p.ia[c]] - (double)pb[p.ib[c]], at = fabs(t);
            sum[c] += t;
            sumsq[c] += t * t;
            sumabs += at;
            if (at > e) e = at;
            if (at > maxabs) {
                maxabs = at;
                out->max_x = (int)(i % p.w);
                out->max_y = (int)(i / p.w);
                out->max_c = c;
            }
        }
        if (e > out->threshold) out->over_threshold++;
        if (e > 0) out->differing++;
        sampler_add(&s, e, i, -1);
    }
    sampler_finish(&s, p.w, &out->pixel_err);
    long n = out->count.compared;
    for (int c = 0; c < 3; c++) { out->rmse_c[c] = NAN; out->bias[c] = NAN; }
    if (n > 0) {
        double total = 0;
        for (int c = 0; c < 3; c++) {
            total += sumsq[c];
            out->rmse_c[c] = sqrt(sumsq[c] / (double)n);
            out->bias[c] = sum[c] / (double)n;
        }
        out->rmse = sqrt(total / ((double)n * p.nc));
        out->mae = sumabs / ((double)n * p.nc);
        out->max_abs = maxabs;
        out->psnr_db = out->rmse > 0 ? 20.0 * log10(out->peak / out->rmse) : INFINITY;
    } else {
        out->rmse = out->mae = out->max_abs = out->psnr_db = NAN;
    }
    out->over_threshold_share = share(out->over_threshold, n);
    return true;
}

/* ---- hit points ------------------------------------------------------------------- */

bool ref_metrics_points(const ref_fimage *a, const ref_fimage *b, const ref_metrics_desc *d,
                        ref_point_metrics *out, char *err, int errlen) {
    memset(out, 0, sizeof *out);
    pair p;
    if (!pair_init(&p, a, b, REF_ERR_POINT, d, err, errlen)) return false;
    long npx = (long)p.w * p.h;
    out->texel_size = d && d->texel_size > 0 ? d->texel_size : 0;
    out->threshold = d && d->threshold > 0 ? d->threshold : 0;
    sampler sw, st;
    bool texels = out->texel_size > 0;
    sampler_init(&sw, npx);
    sampler_init(&st, texels ? npx : 1);
    out->width = p.w;
    out->height = p.h;
    out->count.pixels = npx;
    for (long i = 0; i < npx; i++) {
        const float *pa, *pb;
        if (!pair_pixel(&p, i, &out->count, &pa, &pb)) continue;
        double e = pixel_error(&p, REF_ERR_POINT, pa, pb);
        sampler_add(&sw, e, i, -1);
        if (texels) sampler_add(&st, e / out->texel_size, i, -1);
        if (out->threshold > 0 && e > out->threshold) out->over_threshold++;
    }
    sampler_finish(&sw, p.w, &out->world);
    sampler_finish(&st, p.w, &out->texels);
    out->over_threshold_share = out->threshold > 0 ? share(out->over_threshold, out->count.compared) : NAN;
    return true;
}

/* ---- scalar buffers ----------------------------------------------------------------- */

bool ref_metrics_scalar(const ref_fimage *a, const ref_fimage *b, const ref_metrics_desc *d,
                        ref_scalar_metrics *out, char *err, int errlen) {
    memset(out, 0, sizeof *out);
    pair p;
    if (!pair_init(&p, a, b, REF_ERR_SCALAR, d, err, errlen)) return false;
    long npx = (long)p.w * p.h;
    out->rel_floor = d && d->rel_floor > 0 ? d->rel_floor : REF_METRICS_REL_FLOOR;
    out->threshold = d && d->threshold > 0 ? d->threshold : 0;
    sampler sa, sr;
    sampler_init(&sa, npx * p.nc);
    sampler_init(&sr, npx * p.nc);
    out->width = p.w;
    out->height = p.h;
    out->channels = p.nc;
    out->count.pixels = npx;
    double bias = 0;
    for (long i = 0; i < npx; i++) {
        const float *pa, *pb;
        if (!pair_pixel(&p, i, &out->count, &pa, &pb)) continue;
        double e = 0;
        for (int c = 0; c < p.nc; c++) {
            double va = pa[p.ia[c]], vb = pb[p.ib[c]], t = va - vb, at = fabs(t);
            double den = fabs(vb) > out->rel_floor ? fabs(vb) : out->rel_floor;
            bias += t;
            sampler_add(&sa, at, i, c);
            sampler_add(&sr, at / den, i, c);
            if (at > e) e = at;
        }
        if (out->threshold > 0 && e > out->threshold) out->over_threshold++;
    }
    long n = sa.n;
    sampler_finish(&sa, p.w, &out->abs);
    sampler_finish(&sr, p.w, &out->rel);
    out->bias = n > 0 ? bias / (double)n : NAN;
    out->over_threshold_share = out->threshold > 0 ? share(out->over_threshold, out->count.compared) : NAN;
    return true;
}

/* ---- error fields and heat maps --------------------------------------------------- */

bool ref_metrics_error_field(const ref_fimage *a, const ref_fimage *b, ref_err_kind kind,
                             const ref_metrics_desc *d, float *field, char *err, int errlen) {
    pair p;
    if (!pair_init(&p, a, b, kind, d, err, errlen)) return false;
    if (!field) { msg_set(err, (size_t)errlen, "no field to write"); return false; }
    long npx = (long)p.w * p.h;
    ref_pixel_counts n = {0};
    for (long i = 0; i < npx; i++) {
        const float *pa, *pb;
        long invalid = n.invalid;
        if (pair_pixel(&p, i, &n, &pa, &pb)) field[i] = (float)pixel_error(&p, kind, pa, pb);
        else field[i] = n.invalid > invalid ? NAN : -1.0f;
    }
    return true;
}

double ref_heatmap_auto_scale(const float *field, long n) {
    double *v = mem_alloc((size_t)(n > 0 ? n : 1) * sizeof *v);
    long k = 0;
    double scale = 1;
    for (long i = 0; i < n; i++)
        if (field[i] >= 0) v[k++] = field[i];   /* not NaN, not masked out */
    if (k > 0) {
        double p99 = ref_percentile(v, k, 99), mx = v[k - 1];
        if (p99 > 0 && isfinite(p99)) scale = p99;
        else if (mx > 0 && isfinite(mx)) scale = mx;
    }
    free(v);
    return scale;
}

double ref_heatmap(const float *field, int w, int h, double scale, float *rgb) {
    long n = (long)w * h;
    if (!(scale > 0) || !isfinite(scale)) scale = ref_heatmap_auto_scale(field, n);
    for (long i = 0; i < n; i++) {
        float *o = rgb + 3 * i;
        float e = field[i];
        if (isnan(e)) { o[0] = 0; o[1] = 1; o[2] = 1; }
        else if (e < 0) { o[0] = o[1] = o[2] = 0.5f; }
        else ref_colormap_inferno(e / scale, o);
    }
    return scale;
}

void ref_mask_water(const float *classes, long n, int water, const unsigned char *and_mask, unsigned char *out) {
    const float w = (float)REF_MASK_WATER;
    for (long i = 0; i < n; i++) out[i] = ((classes[i] == w) == (water != 0)) && (!and_mask || and_mask[i]);
}
