/* `tarn compare A B`: reads the images, runs ref_metrics, prints a table
 * and writes the heat map, JSON and CSV. See compare.h, docs/metrics.md. */
#include "compare.h"
#include "strbuf.h"
#include "datafmt.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "exit_code.h"
#include "file.h"
#include "mem.h"
#include "ref_buffers.h"
#include "ref_flip.h"
#include "ref_metrics.h"
#include "ref_render.h"
#include "ref_ssim.h"


/* ---- files -------------------------------------------------------------------- */

bool compare_is_srgb_path(const char *path) {
    static const char *exts[] = { "png", "jpg", "jpeg", "bmp", "gif", "tga", "webp", "ppm", "pgm", "pnm" };
    if (!path) return false;
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    if (!dot || (slash && dot < slash)) return false;
    char ext[8];
    size_t n = strlen(dot + 1);
    if (n == 0 || n >= sizeof ext) return false;
    for (size_t i = 0; i < n; i++) ext[i] = (char)tolower((unsigned char)dot[1 + i]);
    ext[n] = '\0';
    for (size_t i = 0; i < sizeof exts / sizeof exts[0]; i++)
        if (strcmp(ext, exts[i]) == 0) return true;
    return false;
}

bool compare_load(const char *path, bool decode_srgb, img *out, bool *decoded, char *err, int errlen) {
    if (decoded) *decoded = false;
    if (!img_read(path, out, err, errlen)) return false;
    if (out->d != 1) {
        snprintf(err, (size_t)errlen, "%s: a 3D image (depth %d); compare takes 2D images", path, out->d);
        img_free(out);
        return false;
    }
    if (decode_srgb && compare_is_srgb_path(path)) {
        int ch = out->channels, colour = ch >= 3 ? 3 : 1;
        long n = (long)out->w * out->h;
        for (long i = 0; i < n; i++)
            for (int c = 0; c < colour; c++) {
                float *v = &out->px[(size_t)i * (size_t)ch + (size_t)c];
                *v = (float)ref_srgb_to_linear(*v);
            }
        if (decoded) *decoded = true;
    }
    return true;
}

/* path with its extension (after the last '/') replaced by "." insert ext;
 * e.g. ("out/x.exr", "depth", ".exr") -> "out/x.depth.exr". */
static void sibling_path(char *dst, size_t len, const char *path, const char *insert, const char *ext) {
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    int stem = (dot && (!slash || dot > slash)) ? (int)(dot - path) : (int)strlen(path);
    snprintf(dst, len, "%.*s.%s%s", stem, path, insert, ext);
}

/* ---- results: an ordered list of named values --------------------------------- */

typedef enum { KV_NUM, KV_INT, KV_STR, KV_BOOL, KV_SHARE } kv_type;

typedef struct kv {
    const char *group;      /* NULL: top level; else a buffer's name */
    const char *key;
    const char *label;      /* for the table; NULL: JSON/CSV only */
    const char *unit;       /* table only, may be NULL */
    kv_type type;
    bool table_only;        /* a line of the table, not in JSON/CSV */
    double num;
    long inum;
    char *str;              /* KV_STR: owned */
} kv;

typedef struct kvlist {
    kv *v;
    int n, cap;
} kvlist;

static kv *kv_add(kvlist *l, const char *group, const char *key, const char *label, kv_type t) {
    l->v = mem_grow(l->v, &l->cap, l->n + 1, sizeof *l->v);
    kv *e = &l->v[l->n++];
    memset(e, 0, sizeof *e);
    e->group = group;
    e->key = key;
    e->label = label;
    e->type = t;
    return e;
}


static void kvlist_free(kvlist *l) {
    for (int i = 0; i < l->n; i++) free(l->v[i].str);
    free(l->v);
    memset(l, 0, sizeof *l);
}

static void add_num(kvlist *l, const char *g, const char *key, const char *label, double v, const char *unit) {
    kv *e = kv_add(l, g, key, label, KV_NUM);
    e->num = v;
    e->unit = unit;
}

/* A count, or null and no table line when it does not apply (v < 0). */
static void add_count_or_null(kvlist *l, const char *g, const char *key, const char *label, long v) {
    kv *e = kv_add(l, g, key, v >= 0 ? label : NULL, v >= 0 ? KV_INT : KV_NUM);
    e->inum = v;
    e->num = NAN;
}

static void add_share(kvlist *l, const char *g, const char *key, const char *label, double v) {
    kv_add(l, g, key, label, KV_SHARE)->num = v;
}

static void add_int(kvlist *l, const char *g, const char *key, const char *label, long v) {
    kv_add(l, g, key, label, KV_INT)->inum = v;
}

static void add_str(kvlist *l, const char *g, const char *key, const char *label, const char *s) {
    kv *e = kv_add(l, g, key, label, s ? KV_STR : KV_NUM);
    if (s) e->str = mem_strdup(s);
    else e->num = NAN;     /* null */
}

/* A line of the table only. */
static void add_note(kvlist *l, const char *g, const char *label, const char *s) {
    kv *e = kv_add(l, g, "", label, KV_STR);
    e->table_only = true;
    e->str = mem_strdup(s);
}

static void add_bool(kvlist *l, const char *g, const char *key, const char *label, bool b) {
    kv_add(l, g, key, label, KV_BOOL)->inum = b;
}

static void add_counts(kvlist *l, const char *g, const ref_pixel_counts *c) {
    add_int(l, g, "pixels", NULL, c->pixels);
    add_int(l, g, "compared_pixels", "pixels compared", c->compared);
    add_int(l, g, "masked_pixels", c->masked_out ? "pixels outside the mask" : NULL, c->masked_out);
    add_int(l, g, "invalid_pixels", c->invalid ? "pixels left out (NaN/Inf)" : NULL, c->invalid);
    add_int(l, g, "nan_pixels_a", "NaN pixels in A", c->nan_a);
    add_int(l, g, "nan_pixels_b", "NaN pixels in B", c->nan_b);
    add_int(l, g, "inf_pixels_a", "Inf pixels in A", c->inf_a);
    add_int(l, g, "inf_pixels_b", "Inf pixels in B", c->inf_b);
}

/* ---- formatting ------------------------------------------------------------------ */

static void json_value(strbuf *o, const kv *e) {
    switch (e->type) {
    case KV_STR: json_put_str(o, e->str); break;
    case KV_INT: strbuf_printf(o, "%ld", e->inum); break;
    case KV_BOOL: strbuf_puts(o, e->inum ? "true" : "false"); break;
    default: json_put_num(o, e->num); break;
    }
}

static void write_json(FILE *f, const kvlist *l) {
    strbuf o = { 0 };
    strbuf_puts(&o, "{\n");
    bool first = true;
    for (int i = 0; i < l->n; i++) {
        if (l->v[i].group || l->v[i].table_only) continue;
        strbuf_printf(&o, "%s  \"%s\": ", first ? "" : ",\n", l->v[i].key);
        json_value(&o, &l->v[i]);
        first = false;
    }
    strbuf_printf(&o, "%s  \"buffers\": {", first ? "" : ",\n");
    const char *group = NULL;
    bool any = false;
    for (int i = 0; i < l->n; i++) {
        const kv *e = &l->v[i];
        if (!e->group || e->table_only) continue;
        if (!group || strcmp(group, e->group) != 0) {
            strbuf_printf(&o, "%s\n    \"%s\": {\n", group ? "\n    }," : "", e->group);
            group = e->group;
            first = true;
        }
        strbuf_printf(&o, "%s      \"%s\": ", first ? "" : ",\n", e->key);
        json_value(&o, e);
        first = false;
        any = true;
    }
    strbuf_puts(&o, any ? "\n    }\n  }\n}\n" : "}\n}\n");
    fputs(o.s, f);
    strbuf_free(&o);
}

static void write_csv(FILE *f, const kvlist *l) {
    strbuf o = { 0 };
    char name[600];
    bool first = true;
    for (int i = 0; i < l->n; i++) {
        const kv *e = &l->v[i];
        if (e->table_only) continue;
        if (e->group) snprintf(name, sizeof name, "%s.%s", e->group, e->key);
        else snprintf(name, sizeof name, "%s", e->key);
        if (!first) strbuf_puts(&o, ",");
        csv_put_str(&o, name, false);
        first = false;
    }
    strbuf_puts(&o, "\n");
    first = true;
    for (int i = 0; i < l->n; i++) {
        const kv *e = &l->v[i];
        if (e->table_only) continue;
        if (!first) strbuf_puts(&o, ",");
        first = false;
        switch (e->type) {
        case KV_STR: csv_put_str(&o, e->str, false); break;
        case KV_INT: strbuf_printf(&o, "%ld", e->inum); break;
        case KV_BOOL: strbuf_puts(&o, e->inum ? "true" : "false"); break;
        default: csv_put_num(&o, e->num); break;
        }
    }
    strbuf_puts(&o, "\n");
    fputs(o.s, f);
    strbuf_free(&o);
}

static void write_table(FILE *f, const kvlist *l) {
    const char *group = NULL;
    fprintf(f, "%-36s %s\n", "metric", "value");
    for (int i = 0; i < l->n; i++) {
        const kv *e = &l->v[i];
        if (!e->label) continue;
        if (e->group && (!group || strcmp(group, e->group) != 0)) {
            fprintf(f, "\nbuffer %s\n", e->group);
            group = e->group;
        }
        char val[128];
        if (e->type == KV_STR) {
            fprintf(f, "%s%-*s %s\n", e->group ? "  " : "", e->group ? 34 : 36, e->label, e->str);
            continue;
        }
        switch (e->type) {
        case KV_INT: snprintf(val, sizeof val, "%ld", e->inum); break;
        case KV_BOOL: snprintf(val, sizeof val, "%s", e->inum ? "yes" : "no"); break;
        case KV_SHARE:
            if (isnan(e->num)) snprintf(val, sizeof val, "n/a");
            else snprintf(val, sizeof val, "%.6g (%.3g%%)", e->num, 100.0 * e->num);
            break;
        default:
            if (isnan(e->num)) snprintf(val, sizeof val, "n/a");
            else if (isinf(e->num)) snprintf(val, sizeof val, "%s", e->num > 0 ? "inf" : "-inf");
            else snprintf(val, sizeof val, "%.6g%s%s", e->num, e->unit ? " " : "", e->unit ? e->unit : "");
            break;
        }
        fprintf(f, "%s%-*s %s\n", e->group ? "  " : "", e->group ? 34 : 36, e->label, val);
    }
}

/* ---- the command ------------------------------------------------------------------ */

/* The buffers are reference/ref_buffers.h's. Point buffers may carry a flag
 * in channel 3 (what the ray met, ref_render.h); where it is the buffer's
 * direction_flag on either side, xyz is a direction, not a point, and the
 * pixel is left out. */
typedef ref_buffer_info buffer_kind;

/* Writes field's heat map to path; returns the scale (NaN on failure). */
static double write_heatmap(const char *path, const float *field, int w, int h, double scale, FILE *err) {
    img im;
    char msg[MSG_MAX];
    if (!img_alloc(&im, w, h, 3)) { fprintf(err, "tarn compare: %s: out of memory\n", path); return NAN; }
    double used = ref_heatmap(field, w, h, scale, im.px);
    bool ok = img_write(path, &im, msg, sizeof msg);
    img_free(&im);
    if (!ok) { fprintf(err, "tarn compare: cannot write the heat map: %s\n", msg); return NAN; }
    return used;
}

/* The reference's pixel classes (B.mask.exr beside B: REF_MASK_* per pixel),
 * or NULL when B has none (B is not a `tarn reference` output) or its size
 * differs. *why says which. */
static float *load_classes(const char *b, int w, int h, char *why, size_t whylen) {
    char path[4096], msg[512];
    sibling_path(path, sizeof path, b, "mask", ".exr");
    img m;
    if (!file_exists(path)) { msg_set(why, whylen, "no %s beside B", path); return NULL; }
    if (!img_read(path, &m, msg, sizeof msg)) { msg_set(why, whylen, "%s", msg); return NULL; }
    if (m.w != w || m.h != h || m.d != 1) {
        msg_set(why, whylen, "%s is %dx%d, the images %dx%d", path, m.w, m.h, w, h);
        img_free(&m);
        return NULL;
    }
    float *cls = mem_alloc((size_t)w * (size_t)h * sizeof *cls);
    for (long i = 0; i < (long)w * h; i++) cls[i] = m.px[(size_t)i * (size_t)m.channels];
    img_free(&m);
    return cls;
}

/* The perceptual figures of a comparison: the FLIP map of the whole frame
 * (pooled per region) and the images SSIM reads. */
typedef struct percept {
    const float *flip;      /* w * h, NULL when FLIP failed */
    const ref_fimage *a, *b;
} percept;

/* Mean SSIM over mask (NULL = all); NaN when it cannot be computed (an
 * image smaller than its window: the caller notes why). */
static double ssim_mean(const percept *pc, const unsigned char *mask, char *why, size_t whylen) {
    ref_ssim_desc d = { .mask = mask };
    ref_ssim_result r;
    char msg[MSG_MAX];
    if (!ref_ssim(pc->a, pc->b, &d, NULL, &r, msg, sizeof msg)) {
        if (why) msg_set(why, whylen, "%s", msg);
        return NAN;
    }
    return r.mean;
}

static double flip_mean_over(const percept *pc, const unsigned char *mask) {
    if (!pc->flip) return NAN;
    ref_flip_result r;
    ref_flip_pool(pc->flip, pc->a->w, pc->a->h, mask, &r);
    return r.mean;
}

/* RMSE, PSNR, MAE, FLIP, SSIM and the pixel count over the pixels on one
 * side of the reference's water mask (and inside --mask when given): the
 * error of the water technique, and of the world around it. */
static void add_region(kvlist *l, bool water, const ref_fimage *fa, const ref_fimage *fb, const float *cls,
                       const unsigned char *user_mask, double threshold, const percept *pc) {
    static const char *const keys[2][6] = {
        { "off_water_rmse", "off_water_psnr_db", "off_water_mae", "off_water_flip_mean", "off_water_ssim",
          "off_water_pixels" },
        { "water_rmse", "water_psnr_db", "water_mae", "water_flip_mean", "water_ssim", "water_pixels" },
    };
    static const char *const labels[2][6] = {
        { "off-water RMSE (sky, land, objects)", "off-water PSNR", "off-water mean abs. error",
          "off-water FLIP, mean", "off-water SSIM, mean", "off-water pixels" },
        { "water RMSE (reference's mask)", "water PSNR", "water mean abs. error",
          "water FLIP, mean", "water SSIM, mean", "water pixels" },
    };
    long n = (long)fa->w * fa->h;
    unsigned char *m = mem_alloc((size_t)n);
    ref_mask_water(cls, n, water, user_mask, m);
    ref_metrics_desc d = { .threshold = threshold, .mask = m };
    ref_image_metrics r;
    char msg[MSG_MAX];
    bool ok = ref_metrics_image(fa, fb, &d, &r, msg, sizeof msg);
    double flip = flip_mean_over(pc, m), ssim = ssim_mean(pc, m, NULL, 0);
    free(m);
    const char *const *k = keys[water], *const *lab = labels[water];
    add_num(l, NULL, k[0], lab[0], ok ? r.rmse : NAN, NULL);
    add_num(l, NULL, k[1], lab[1], ok ? r.psnr_db : NAN, "dB");
    add_num(l, NULL, k[2], lab[2], ok ? r.mae : NAN, NULL);
    add_num(l, NULL, k[3], lab[3], flip, NULL);
    add_num(l, NULL, k[4], lab[4], ssim, NULL);
    add_int(l, NULL, k[5], lab[5], ok ? r.count.compared : 0);
}

/* Builds the mask: nonzero where M's first channel is > 0.5. */
static unsigned char *load_mask(const char *path, int w, int h, FILE *err) {
    img m;
    char msg[MSG_MAX];
    if (!img_read(path, &m, msg, sizeof msg)) { fprintf(err, "tarn compare: cannot read the mask: %s\n", msg); return NULL; }
    unsigned char *mask = NULL;
    if (m.w != w || m.h != h || m.d != 1)
        fprintf(err, "tarn compare: the mask %s is %dx%d, the images are %dx%d\n", path, m.w, m.h, w, h);
    else {
        mask = mem_alloc((size_t)w * (size_t)h);
        for (long i = 0; i < (long)w * h; i++) mask[i] = m.px[(size_t)i * (size_t)m.channels] > 0.5f;
    }
    img_free(&m);
    return mask;
}

/* Compares one buffer pair into l (group = its name). False on failure. */
static bool compare_buffer(const buffer_kind *bk, const char *pa, const char *pb, const compare_desc *o,
                           const unsigned char *mask, int mw, int mh, kvlist *l, FILE *err) {
    img a = {0}, b = {0};
    char msg[MSG_MAX];
    bool ok = false;
    float *field = NULL;
    unsigned char *own_mask = NULL;
    if (!compare_load(pa, !o->linear, &a, NULL, msg, sizeof msg) ||
        !compare_load(pb, !o->linear, &b, NULL, msg, sizeof msg)) {
        fprintf(err, "tarn compare: buffer %s: cannot read %s\n", bk->name, msg);
        goto done;
    }
    if (a.w != b.w || a.h != b.h) {
        fprintf(err, "tarn compare: buffer %s: sizes differ: A (%s) is %dx%d, B (%s) is %dx%d\n",
                bk->name, pa, a.w, a.h, pb, b.w, b.h);
        goto done;
    }
    ref_fimage fa = { a.px, a.w, a.h, a.channels }, fb = { b.px, b.w, b.h, b.channels };
    ref_metrics_desc d = { .texel_size = o->texel };
    if (mask && a.w == mw && a.h == mh) d.mask = mask;
    else if (mask) fprintf(err, "tarn compare: buffer %s is %dx%d, not the mask's %dx%d: compared unmasked\n",
                           bk->name, a.w, a.h, mw, mh);
    ref_err_kind kind = bk->err;
    if (kind == REF_ERR_POINT && (a.channels < 3 || b.channels < 3)) kind = REF_ERR_SCALAR;
    const char *g = bk->name;
    /* The flag channel: pixels whose flags differ; directions left out. */
    long flag_mismatch = -1, directions = -1;
    if (kind == REF_ERR_POINT && a.channels >= 4 && b.channels >= 4) {
        long n = (long)a.w * a.h;
        flag_mismatch = 0;
        if (bk->direction_flag) {
            directions = 0;
            own_mask = mem_alloc((size_t)n);
        }
        for (long i = 0; i < n; i++) {
            bool in = !d.mask || d.mask[i];
            float ka = a.px[(size_t)i * (size_t)a.channels + 3], kb = b.px[(size_t)i * (size_t)b.channels + 3];
            if (in && ka != kb && !isnan(ka) && !isnan(kb)) flag_mismatch++;
            if (own_mask) {
                bool dir = ka == (float)bk->direction_flag || kb == (float)bk->direction_flag;
                own_mask[i] = in && !dir;
                if (in && dir) directions++;
            }
        }
        if (own_mask) d.mask = own_mask;
    }
    if (kind == REF_ERR_POINT) {
        ref_point_metrics m;
        if (!ref_metrics_points(&fa, &fb, &d, &m, msg, sizeof msg)) {
            fprintf(err, "tarn compare: buffer %s: %s\n", g, msg);
            goto done;
        }
        add_str(l, g, "kind", NULL, "point");
        add_str(l, g, "a", NULL, pa);
        add_str(l, g, "b", NULL, pb);
        add_int(l, g, "width", NULL, m.width);
        add_int(l, g, "height", NULL, m.height);
        add_counts(l, g, &m.count);
        add_count_or_null(l, g, "flag_mismatch_pixels", "pixels whose flags differ", flag_mismatch);
        add_count_or_null(l, g, "direction_pixels", "pixels left out: a direction", directions);
        add_num(l, g, "dist_mean", "hit point error, mean", m.world.mean, "world units");
        add_num(l, g, "dist_rms", NULL, m.world.rms, NULL);
        add_num(l, g, "dist_median", "hit point error, median", m.world.median, "world units");
        add_num(l, g, "dist_p95", "hit point error, 95th percentile", m.world.p95, "world units");
        add_num(l, g, "dist_p99", NULL, m.world.p99, NULL);
        add_num(l, g, "dist_max", "hit point error, max", m.world.max, "world units");
        add_int(l, g, "dist_max_at_x", NULL, m.world.max_x);
        add_int(l, g, "dist_max_at_y", NULL, m.world.max_y);
        bool tx = m.texel_size > 0;
        add_num(l, g, "texel_size", tx ? "texel size" : NULL, tx ? m.texel_size : NAN, "world units");
        add_num(l, g, "texel_mean", tx ? "hit point error, mean" : NULL, m.texels.mean, "texels");
        add_num(l, g, "texel_median", tx ? "hit point error, median" : NULL, m.texels.median, "texels");
        add_num(l, g, "texel_p95", tx ? "hit point error, 95th percentile" : NULL, m.texels.p95, "texels");
        add_num(l, g, "texel_max", tx ? "hit point error, max" : NULL, m.texels.max, "texels");
    } else {
        ref_scalar_metrics m;
        if (!ref_metrics_scalar(&fa, &fb, &d, &m, msg, sizeof msg)) {
            fprintf(err, "tarn compare: buffer %s: %s\n", g, msg);
            goto done;
        }
        add_str(l, g, "kind", NULL, "scalar");
        add_str(l, g, "a", NULL, pa);
        add_str(l, g, "b", NULL, pb);
        add_int(l, g, "width", NULL, m.width);
        add_int(l, g, "height", NULL, m.height);
        add_int(l, g, "channels", NULL, m.channels);
        add_counts(l, g, &m.count);
        add_num(l, g, "rmse", "RMSE", m.abs.rms, NULL);
        add_num(l, g, "abs_mean", "absolute error, mean", m.abs.mean, NULL);
        add_num(l, g, "abs_median", "absolute error, median", m.abs.median, NULL);
        add_num(l, g, "abs_p95", "absolute error, 95th percentile", m.abs.p95, NULL);
        add_num(l, g, "abs_p99", NULL, m.abs.p99, NULL);
        add_num(l, g, "abs_max", "absolute error, max", m.abs.max, NULL);
        add_int(l, g, "abs_max_at_x", NULL, m.abs.max_x);
        add_int(l, g, "abs_max_at_y", NULL, m.abs.max_y);
        add_int(l, g, "abs_max_at_channel", NULL, m.abs.max_c);
        add_num(l, g, "bias", "bias, mean of A - B", m.bias, NULL);
        add_num(l, g, "rel_floor", NULL, m.rel_floor, NULL);
        add_num(l, g, "rel_mean", "relative error, mean", m.rel.mean, NULL);
        add_num(l, g, "rel_median", "relative error, median", m.rel.median, NULL);
        add_num(l, g, "rel_p95", "relative error, 95th percentile", m.rel.p95, NULL);
        add_num(l, g, "rel_max", "relative error, max", m.rel.max, NULL);
    }
    if (o->out) {
        char hp[4096];
        const char *dot = strrchr(o->out, '.'), *slash = strrchr(o->out, '/');
        sibling_path(hp, sizeof hp, o->out, g, dot && (!slash || dot > slash) ? dot : ".png");
        field = mem_alloc((size_t)a.w * (size_t)a.h * sizeof *field);
        if (!ref_metrics_error_field(&fa, &fb, kind, &d, field, msg, sizeof msg)) {
            fprintf(err, "tarn compare: buffer %s: heat map: %s\n", g, msg);
            goto done;
        }
        double s = write_heatmap(hp, field, a.w, a.h, 0, err);
        if (isnan(s)) goto done;
        add_str(l, g, "heatmap", "heat map", hp);
        add_num(l, g, "heatmap_scale", "heat map scale (pale yellow)", s, NULL);
    }
    ok = true;
done:
    free(field);
    free(own_mask);
    img_free(&a);
    img_free(&b);
    return ok;
}

/* Opens FILE or "-" (out) for writing. */
static FILE *open_out(const char *path, FILE *out, FILE *err) {
    if (strcmp(path, "-") == 0) return out;
    FILE *f = fopen(path, "w");
    if (!f) fprintf(err, "tarn compare: cannot write %s: %s\n", path, strerror(errno));
    return f;
}

static bool close_out(FILE *f, const char *path, FILE *out, FILE *err) {
    bool ok = !ferror(f);
    if (f != out) ok = (fclose(f) == 0) && ok;
    else fflush(f);
    if (!ok) fprintf(err, "tarn compare: error writing %s\n", path);
    return ok;
}

/* One comparison's state, shared by the report's steps below. */
typedef struct run_ctx {
    const compare_desc *o;
    FILE *out, *err;
    img ia, ib;
    bool dec_a, dec_b;
    ref_fimage fa, fb;
    unsigned char *mask;   /* --mask, or NULL */
    float *flip;           /* the whole frame's FLIP map */
    bool flip_hdr;
    ref_flip_result fr;
    kvlist l;
} run_ctx;

/* The inputs: names, decoding, size, channels. */
static void add_inputs(run_ctx *c, const ref_image_metrics *m) {
    const compare_desc *o = c->o;
    kvlist *l = &c->l;
    char size[64], desc[4200];
    snprintf(size, sizeof size, "%dx%d", m->width, m->height);
    snprintf(desc, sizeof desc, "%s (%s, %d channels)", o->a, c->dec_a ? "sRGB, decoded to linear" : "linear",
             c->ia.channels);
    add_note(l, NULL, "A (under test)", desc);
    snprintf(desc, sizeof desc, "%s (%s, %d channels)", o->b, c->dec_b ? "sRGB, decoded to linear" : "linear",
             c->ib.channels);
    add_note(l, NULL, "B (reference)", desc);
    add_str(l, NULL, "a", NULL, o->a);
    add_str(l, NULL, "b", NULL, o->b);
    add_bool(l, NULL, "a_srgb_decoded", NULL, c->dec_a);
    add_bool(l, NULL, "b_srgb_decoded", NULL, c->dec_b);
    add_int(l, NULL, "width", NULL, m->width);
    add_int(l, NULL, "height", NULL, m->height);
    add_note(l, NULL, "size", size);
    add_int(l, NULL, "channels_a", NULL, c->ia.channels);
    add_int(l, NULL, "channels_b", NULL, c->ib.channels);
}

/* Water first: the error of the technique, where the reference sees
 * water; the world around it second (the whole frame follows). */
static void add_regions(run_ctx *c, const percept *pc) {
    char why[MSG_MAX] = "";
    float *cls = load_classes(c->o->b, c->ia.w, c->ia.h, why, sizeof why);
    if (cls) {
        add_region(&c->l, true, &c->fa, &c->fb, cls, c->mask, c->o->threshold, pc);
        add_region(&c->l, false, &c->fa, &c->fb, cls, c->mask, c->o->threshold, pc);
        free(cls);
    } else {
        add_note(&c->l, NULL, "water-only error", why);
        add_num(&c->l, NULL, "water_rmse", NULL, NAN, NULL);
        add_num(&c->l, NULL, "water_flip_mean", NULL, NAN, NULL);
        add_num(&c->l, NULL, "water_ssim", NULL, NAN, NULL);
    }
}

/* The whole frame's pixel metrics. */
static void add_frame(kvlist *l, const ref_image_metrics *m) {
    add_counts(l, NULL, &m->count);
    add_num(l, NULL, "rmse", "RMSE, whole frame (linear RGB)", m->rmse, NULL);
    add_num(l, NULL, "rmse_r", NULL, m->rmse_c[0], NULL);
    add_num(l, NULL, "rmse_g", NULL, m->rmse_c[1], NULL);
    add_num(l, NULL, "rmse_b", NULL, m->rmse_c[2], NULL);
    add_num(l, NULL, "psnr_db", "PSNR (peak 1.0)", m->psnr_db, "dB");
    add_num(l, NULL, "psnr_peak", NULL, m->peak, NULL);
    add_num(l, NULL, "mae", "mean absolute error", m->mae, NULL);
    add_num(l, NULL, "max_abs", "max absolute error", m->max_abs, NULL);
    add_int(l, NULL, "max_at_x", NULL, m->max_x);
    add_int(l, NULL, "max_at_y", NULL, m->max_y);
    add_int(l, NULL, "max_at_channel", NULL, m->max_c);
    if (m->max_x >= 0) {
        static const char *names[3] = { "red", "green", "blue" };
        char at[96];
        snprintf(at, sizeof at, "(%d, %d), %s", m->max_x, m->max_y, names[m->max_c]);
        add_note(l, NULL, "  at pixel (x, y from top-left)", at);
    }
    add_num(l, NULL, "threshold", "threshold", m->threshold, NULL);
    add_int(l, NULL, "over_threshold_pixels", "pixels over the threshold", m->over_threshold);
    add_share(l, NULL, "over_threshold_share", "share over the threshold", m->over_threshold_share);
    add_int(l, NULL, "differing_pixels", "pixels that differ at all", m->differing);
    add_num(l, NULL, "bias_r", NULL, m->bias[0], NULL);
    add_num(l, NULL, "bias_g", NULL, m->bias[1], NULL);
    add_num(l, NULL, "bias_b", NULL, m->bias[2], NULL);
    add_num(l, NULL, "error_median", "pixel error, median", m->pixel_err.median, NULL);
    add_num(l, NULL, "error_p95", "pixel error, 95th percentile", m->pixel_err.p95, NULL);
    add_num(l, NULL, "error_p99", "pixel error, 99th percentile", m->pixel_err.p99, NULL);
}

/* FLIP and SSIM of the whole frame (inside --mask). */
static void add_flip_ssim(run_ctx *c, const percept *pc) {
    kvlist *l = &c->l;
    ref_flip_result *fr = &c->fr;
    bool hdr = c->flip_hdr;
    ref_flip_pool(c->flip, c->ia.w, c->ia.h, c->mask, fr);
    char fl[96];
    snprintf(fl, sizeof fl, "%s-FLIP at %.0f pixels per degree", hdr ? "HDR" : "LDR", fr->ppd);
    add_note(l, NULL, "FLIP", fl);
    add_str(l, NULL, "flip_kind", NULL, hdr ? "HDR" : "LDR");
    add_num(l, NULL, "flip_ppd", NULL, fr->ppd, NULL);
    add_num(l, NULL, "flip_mean", "FLIP, whole frame, mean", fr->mean, NULL);
    add_num(l, NULL, "flip_weighted_median", "FLIP, weighted median", fr->weighted_median, NULL);
    add_num(l, NULL, "flip_q1", "FLIP, 1st weighted quartile", fr->q1, NULL);
    add_num(l, NULL, "flip_q3", "FLIP, 3rd weighted quartile", fr->q3, NULL);
    add_num(l, NULL, "flip_min", "FLIP, min", fr->min, NULL);
    add_num(l, NULL, "flip_max", "FLIP, max", fr->max, NULL);
    add_num(l, NULL, "flip_start_exposure", hdr ? "FLIP, start exposure" : NULL, fr->start_exposure, NULL);
    add_num(l, NULL, "flip_stop_exposure", hdr ? "FLIP, stop exposure" : NULL, fr->stop_exposure, NULL);
    add_count_or_null(l, NULL, "flip_exposures", "FLIP, exposures", hdr ? fr->num_exposures : -1);
    char swhy[256] = "";
    double ssim = ssim_mean(pc, c->mask, swhy, sizeof swhy);
    add_num(l, NULL, "ssim", "SSIM, whole frame, mean (luminance)", ssim, NULL);
    if (isnan(ssim) && swhy[0]) add_note(l, NULL, "  SSIM n/a", swhy);
}

/* --flip-map: the FLIP map in magma. False where it could not be written. */
static bool write_flip_map(run_ctx *c) {
    const char *path = c->o->flip_map;
    if (!path) {
        add_str(&c->l, NULL, "flip_map", NULL, NULL);
        return true;
    }
    img fm;
    char fmsg[1024];
    bool ok = img_alloc(&fm, c->ia.w, c->ia.h, 3);
    if (ok) {
        ref_flip_colorize(c->flip, c->ia.w, c->ia.h, c->mask, fm.px);
        ok = img_write(path, &fm, fmsg, sizeof fmsg);
        img_free(&fm);
        if (!ok) fprintf(c->err, "tarn compare: cannot write the FLIP map: %s\n", fmsg);
    } else fprintf(c->err, "tarn compare: %s: out of memory\n", path);
    add_str(&c->l, NULL, "flip_map", "FLIP map (magma)", ok ? path : NULL);
    return ok;
}

/* --out: the colour error's heat map. *all_ok false where it could not be
 * written; false (an error already said) where the field was not made. */
static bool write_heat(run_ctx *c, const ref_metrics_desc *d, bool *all_ok) {
    if (!c->o->out) {
        add_str(&c->l, NULL, "heatmap", NULL, NULL);
        add_num(&c->l, NULL, "heatmap_scale", NULL, NAN, NULL);
        return true;
    }
    char msg[MSG_MAX];
    float *field = mem_alloc((size_t)c->ia.w * (size_t)c->ia.h * sizeof *field);
    if (!ref_metrics_error_field(&c->fa, &c->fb, REF_ERR_COLOR, d, field, msg, sizeof msg)) {
        fprintf(c->err, "tarn compare: heat map: %s\n", msg);
        free(field);
        return false;
    }
    double s = write_heatmap(c->o->out, field, c->ia.w, c->ia.h, c->o->max_err, c->err);
    free(field);
    if (isnan(s)) *all_ok = false;
    add_str(&c->l, NULL, "heatmap", "heat map", isnan(s) ? NULL : c->o->out);
    add_num(&c->l, NULL, "heatmap_scale", "heat map scale (pale yellow)", s, NULL);
    return true;
}

/* --buffers: each buffer found beside both A and B. False where one of
 * them could not be compared. */
static bool compare_buffers(run_ctx *c) {
    const compare_desc *o = c->o;
    bool ok = true;
    int found = 0;
    for (int k = 0; k < REF_BUF_COUNT; k++) {
        if (!ref_buffers[k].measured) continue;
        char pa[4096], pb[4096];
        sibling_path(pa, sizeof pa, o->a, ref_buffers[k].name, ".exr");
        sibling_path(pb, sizeof pb, o->b, ref_buffers[k].name, ".exr");
        bool ea = file_exists(pa), eb = file_exists(pb);
        if (!ea && !eb) continue;
        found++;
        if (ea != eb) {
            fprintf(c->err, "tarn compare: buffer %s: only %s exists (no %s): not compared\n",
                    ref_buffers[k].name, ea ? pa : pb, ea ? pb : pa);
            continue;
        }
        if (!compare_buffer(&ref_buffers[k], pa, pb, o, c->mask, c->ia.w, c->ia.h, &c->l, c->err)) ok = false;
    }
    if (!found) {
        char pa[4096];
        sibling_path(pa, sizeof pa, o->a, "NAME", ".exr");
        fprintf(c->err, "tarn compare: --buffers: no buffers beside A or B (looked for %s, NAME = "
                "refract_hit, reflect, fresnel, depth, irradiance)\n", pa);
    }
    return ok;
}

/* The table (stdout, or stderr when JSON or CSV takes stdout), --json and
 * --csv. False where a file could not be written. */
static bool write_outputs(run_ctx *c) {
    const compare_desc *o = c->o;
    FILE *table = (o->json && strcmp(o->json, "-") == 0) || (o->csv && strcmp(o->csv, "-") == 0) ? c->err : c->out;
    bool ok = true;
    write_table(table, &c->l);
    if (o->json) {
        FILE *f = open_out(o->json, c->out, c->err);
        if (!f) ok = false;
        else { write_json(f, &c->l); if (!close_out(f, o->json, c->out, c->err)) ok = false; }
    }
    if (o->csv) {
        FILE *f = open_out(o->csv, c->out, c->err);
        if (!f) ok = false;
        else { write_csv(f, &c->l); if (!close_out(f, o->csv, c->out, c->err)) ok = false; }
    }
    return ok;
}

/* Reads A and B; false (having said why) where either cannot be read or
 * their sizes differ, or --mask cannot be read. */
static bool load_inputs(run_ctx *c) {
    const compare_desc *o = c->o;
    char msg[MSG_MAX];
    bool ok_a, ok_b;
    if (!(ok_a = compare_load(o->a, !o->linear, &c->ia, &c->dec_a, msg, sizeof msg)))
        fprintf(c->err, "tarn compare: cannot read A: %s\n", msg);
    if (!(ok_b = compare_load(o->b, !o->linear, &c->ib, &c->dec_b, msg, sizeof msg)))
        fprintf(c->err, "tarn compare: cannot read B: %s\n", msg);
    if (!ok_a || !ok_b) return false;
    if (c->ia.w != c->ib.w || c->ia.h != c->ib.h) {
        fprintf(c->err, "tarn compare: sizes differ: A (%s) is %dx%d, B (%s) is %dx%d\n",
                o->a, c->ia.w, c->ia.h, o->b, c->ib.w, c->ib.h);
        return false;
    }
    if (o->mask && !(c->mask = load_mask(o->mask, c->ia.w, c->ia.h, c->err))) return false;
    c->fa = (ref_fimage){ c->ia.px, c->ia.w, c->ia.h, c->ia.channels };
    c->fb = (ref_fimage){ c->ib.px, c->ib.w, c->ib.h, c->ib.channels };
    return true;
}

/* Everything measured, in the report's order; TARN_EXIT_INPUT where a
 * metric could not be had or an output not written. */
static int measure(run_ctx *c) {
    const compare_desc *o = c->o;
    char msg[MSG_MAX];
    ref_metrics_desc d = { .threshold = o->threshold, .mask = c->mask };
    ref_image_metrics m;
    if (!ref_metrics_image(&c->fa, &c->fb, &d, &m, msg, sizeof msg)) {
        fprintf(c->err, "tarn compare: %s vs %s: %s\n", o->a, o->b, msg);
        return TARN_EXIT_INPUT;
    }
    add_inputs(c, &m);
    /* FLIP over the whole frame (its filters see every pixel), pooled per
     * region below: LDR-FLIP when both files are 8-bit display images (the
     * authors' tool reads them so), HDR-FLIP when either is linear */
    c->flip_hdr = !(compare_is_srgb_path(o->a) && compare_is_srgb_path(o->b));
    ref_flip_desc fd = { .hdr = c->flip_hdr };
    c->flip = mem_alloc((size_t)c->ia.w * (size_t)c->ia.h * sizeof *c->flip);
    if (!ref_flip_map(&c->fa, &c->fb, &fd, c->flip, NULL, &c->fr, msg, sizeof msg)) {
        fprintf(c->err, "tarn compare: FLIP: %s\n", msg);
        return TARN_EXIT_INPUT;
    }
    percept pc = { c->flip, &c->fa, &c->fb };
    add_regions(c, &pc);
    add_frame(&c->l, &m);
    add_flip_ssim(c, &pc);
    bool all_ok = write_flip_map(c);
    if (!write_heat(c, &d, &all_ok)) return TARN_EXIT_INPUT;
    if (o->buffers && !compare_buffers(c)) all_ok = false;
    if (!write_outputs(c)) all_ok = false;
    return all_ok ? TARN_EXIT_OK : TARN_EXIT_INPUT;
}

int compare_run(const compare_desc *cd, FILE *out, FILE *err) {
    run_ctx c = { .o = cd, .out = out, .err = err };
    int rc = load_inputs(&c) ? measure(&c) : TARN_EXIT_INPUT;
    kvlist_free(&c.l);
    free(c.flip);
    free(c.mask);
    img_free(&c.ia);
    img_free(&c.ib);
    return rc;
}
