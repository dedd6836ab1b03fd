/* obj.c: the Wavefront OBJ reader (obj.h). */
#include "obj.h"
#include "strbuf.h"
#include "file_cache.h"
#include "mem.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define OBJ_MAX_RECORDS (INT_MAX / 4)     /* of each kind, and corners */
#define OBJ_TOKENS_PREALLOC 64

typedef struct parser {
    obj_data *d;
    const char *name;
    char *err;
    size_t errlen;
    int line;                   /* the logical line's first physical line; 0: the whole text */
    bool failed;
    int max_tri;
    bool positions_only;
    double max_abs;
    int capv, capc, capvt, capvn, capcorner, capface;
} parser;

static bool fail(parser *p, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static bool fail(parser *p, const char *fmt, ...) {
    if (p->failed) return false;
    p->failed = true;
    if (p->err && p->errlen > 0) {
        char msg[MSG_MAX];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg, sizeof msg, fmt, ap);
        va_end(ap);
        if (p->line > 0) snprintf(p->err, p->errlen, "%s:%d: %s", p->name, p->line, msg);
        else snprintf(p->err, p->errlen, "%s: %s", p->name, msg);
    }
    return false;
}

/* A token shown in a message: printable, short. */
static void show_token(char *dst, size_t n, const char *tok) {
    size_t k = 0;
    for (; tok[k] && k + 4 < n && k < 24; k++) {
        unsigned char c = (unsigned char)tok[k];
        dst[k] = (c >= 32 && c < 127) ? (char)c : '?';
    }
    if (tok[k]) { dst[k++] = '.'; dst[k++] = '.'; dst[k++] = '.'; }
    dst[k] = 0;
}

static bool parse_double(parser *p, const char *tok, double *out) {
    char *end;
    errno = 0;
    double d = strtod(tok, &end);
    if (end == tok || *end || !isfinite(d) || (errno == ERANGE && fabs(d) > 1.0)) {
        char shown[32];
        show_token(shown, sizeof shown, tok);
        return fail(p, "bad number '%s'", shown);
    }
    if (fabs(d) > p->max_abs) {
        char shown[32];
        show_token(shown, sizeof shown, tok);
        return fail(p, "number '%s' too large here (at most %g)", shown, p->max_abs);
    }
    *out = d;
    return true;
}

/* Room for element `count` of an array of elem-byte elements. */
static bool room(parser *p, void **arr, int count, int *cap, size_t elem, const char *what) {
    if (count >= OBJ_MAX_RECORDS) return fail(p, "too many '%s' records (at most %d)", what, OBJ_MAX_RECORDS);
    if (count >= *cap) *arr = mem_grow(*arr, cap, count + 1, elem);
    return true;
}

/* v, vt or vn: ntok numbers, need_min..need_max of them; the first `width` kept. */
static bool record(parser *p, double **arr, int *count, int *cap, int width, char **tok, int ntok,
                   int need_min, int need_max, const char *what, double extra[4]) {
    if (ntok < need_min || ntok > need_max) {
        if (need_min == need_max) return fail(p, "'%s' needs %d numbers, got %d", what, need_min, ntok);
        return fail(p, "'%s' needs %d to %d numbers, got %d", what, need_min, need_max, ntok);
    }
    if (!room(p, (void **)arr, *count, cap, (size_t)width * sizeof(double), what)) return false;
    double *r = *arr + (size_t)*count * width;
    for (int c = 0; c < width; c++) r[c] = 0;
    for (int c = 0; c < ntok && c < width; c++)
        if (!parse_double(p, tok[c], &r[c])) return false;
    for (int c = width; c < ntok; c++) {   /* w, or vertex colours */
        double x = 0;
        if (!parse_double(p, tok[c], &x)) return false;
        if (extra && c - width < 4) extra[c - width] = x;
    }
    (*count)++;
    return true;
}

static bool vertex(parser *p, char **tok, int ntok) {
    obj_data *d = p->d;
    double extra[4] = { 0, 0, 0, 0 };
    int k = d->nv;
    if (!record(p, &d->v, &d->nv, &p->capv, 3, tok, ntok, 3, 7, "v", extra)) return false;
    if (ntok == 6 && !d->color) {   /* the first colour: the vertices before it are white */
        p->capc = p->capv;
        d->color = mem_alloc((size_t)p->capc * 3 * sizeof *d->color);
        for (long i = 0; i < 3L * k; i++) d->color[i] = 1;
    }
    if (d->color) {
        if (p->capc < p->capv) {
            p->capc = p->capv;
            d->color = mem_realloc(d->color, (size_t)p->capc * 3 * sizeof *d->color);
        }
        for (int c = 0; c < 3; c++) d->color[3 * (size_t)k + c] = ntok == 6 ? extra[c] : 1;
    }
    return true;
}

/* One index of a corner (len bytes at s): 1-based, negative from the end. */
static bool parse_index(parser *p, const char *s, size_t len, int count, const char *what, int *out) {
    char buf[32];
    if (len == 0 || len >= sizeof buf) {
        if (len == 0) return fail(p, "empty %s index", what);
        return fail(p, "bad %s index", what);
    }
    memcpy(buf, s, len);
    buf[len] = 0;
    char *end;
    errno = 0;
    long k = strtol(buf, &end, 10);
    if (end == buf || *end || errno == ERANGE) {
        char shown[32];
        show_token(shown, sizeof shown, buf);
        return fail(p, "bad %s index '%s'", what, shown);
    }
    if (k == 0) return fail(p, "%s index 0 (OBJ indices start at 1)", what);
    long r = k > 0 ? k - 1 : (long)count + k;
    if (r < 0 || r >= count)
        return fail(p, "%s index %ld out of range: that %s does not exist (%d defined so far; "
                       "negative indices count back from the last)", what, k, what, count);
    *out = (int)r;
    return true;
}

static bool face(parser *p, char **tok, int ntok) {
    obj_data *d = p->d;
    if (ntok < 3) return fail(p, "a face needs at least 3 vertices, got %d", ntok);
    if (d->ntri > p->max_tri - (ntok - 2))
        return fail(p, "more than %d triangles (faces fanned): too large a model for this use", p->max_tri);
    if (d->ncorner > OBJ_MAX_RECORDS - ntok) return fail(p, "too many face corners (at most %d)", OBJ_MAX_RECORDS);
    if (!room(p, (void **)&d->face_first, d->nface + 1, &p->capface, sizeof *d->face_first, "f")) return false;
    if (d->ncorner + ntok > p->capcorner)
        d->corner = mem_grow(d->corner, &p->capcorner, d->ncorner + ntok, sizeof *d->corner);
    for (int c = 0; c < ntok; c++) {
        const char *s = tok[c];
        const char *s1 = strchr(s, '/');
        const char *s2 = s1 ? strchr(s1 + 1, '/') : NULL;
        if (s2 && strchr(s2 + 1, '/')) {
            char shown[32];
            show_token(shown, sizeof shown, s);
            return fail(p, "bad face vertex '%s' (v, v/vt, v//vn or v/vt/vn)", shown);
        }
        obj_corner *k = &d->corner[d->ncorner + c];
        k->vt = k->vn = -1;
        size_t lv = s1 ? (size_t)(s1 - s) : strlen(s);
        if (!parse_index(p, s, lv, d->nv, "vertex", &k->v)) return false;
        if (p->positions_only) continue;
        if (s1) {
            size_t lt = s2 ? (size_t)(s2 - s1 - 1) : strlen(s1 + 1);
            if (lt > 0 && !parse_index(p, s1 + 1, lt, d->nvt, "texture coordinate", &k->vt)) return false;
        }
        if (s2 && s2[1] && !parse_index(p, s2 + 1, strlen(s2 + 1), d->nvn, "normal", &k->vn)) return false;
    }
    d->face_first[d->nface] = d->ncorner;
    d->ncorner += ntok;
    d->nface++;
    d->face_first[d->nface] = d->ncorner;
    d->ntri += ntok - 2;
    return true;
}

static bool is_ignored_statement(const char *kw) {
    static const char *const ignored[] = {
        "o", "g", "s", "mg", "usemtl", "mtllib", "l", "p", "vp", "cstype", "deg", "bmat",
        "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv", "sp", "end", "con",
        "lod", "bevel", "c_interp", "d_interp", "usemap", "maplib", "shadow_obj",
        "trace_obj", "ctech", "stech", "call", "csh"};
    for (size_t k = 0; k < sizeof ignored / sizeof ignored[0]; k++)
        if (!strcmp(kw, ignored[k])) return true;
    return false;
}

static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/* One logical line, NUL-terminated and writable. */
static bool statement(parser *p, char *text) {
    char *hash = strchr(text, '#');
    if (hash) *hash = 0;
    int ntok = 0, cap = OBJ_TOKENS_PREALLOC;
    char *stack_tok[OBJ_TOKENS_PREALLOC];
    char **tok = stack_tok;
    for (char *s = text;;) {
        while (is_space(*s)) s++;
        if (!*s) break;
        if (ntok == cap) {   /* a face may have many corners */
            char **bigger = mem_alloc(sizeof *bigger * (size_t)cap * 2);
            memcpy(bigger, tok, sizeof *tok * (size_t)ntok);
            if (tok != stack_tok) free(tok);
            tok = bigger;
            cap *= 2;
        }
        tok[ntok++] = s;
        while (*s && !is_space(*s)) s++;
        if (*s) *s++ = 0;
    }
    bool ok = true;
    if (ntok > 0) {
        obj_data *d = p->d;
        const char *kw = tok[0];
        char **args = tok + 1;
        int nargs = ntok - 1;
        if (!strcmp(kw, "v")) ok = vertex(p, args, nargs);
        else if (!strcmp(kw, "vt")) ok = record(p, &d->vt, &d->nvt, &p->capvt, 2, args, nargs, 1, 3, "vt", NULL);
        else if (!strcmp(kw, "vn")) ok = record(p, &d->vn, &d->nvn, &p->capvn, 3, args, nargs, 3, 3, "vn", NULL);
        else if (!strcmp(kw, "f") || !strcmp(kw, "fo")) ok = face(p, args, nargs);
        else if (!is_ignored_statement(kw)) {
            char shown[32];
            show_token(shown, sizeof shown, kw);
            ok = fail(p, "unknown statement '%s' (v, vt, vn and f are read; o, g, s, usemtl and the "
                         "like are skipped)", shown);
        }
    }
    if (tok != stack_tok) free(tok);
    return ok;
}

bool obj_parse(obj_data *d, const char *text, size_t len, const char *name, const obj_opts *o, char *err,
               size_t errlen) {
    if (!d) return false;
    memset(d, 0, sizeof *d);
    if (err && errlen > 0) err[0] = 0;
    parser p = { .d = d, .name = name ? name : "(null)", .err = err, .errlen = errlen };
    p.max_tri = o && o->max_triangles > 0 ? o->max_triangles : OBJ_MAX_TRIANGLES;
    p.positions_only = o && o->positions_only;
    p.max_abs = o && o->max_abs > 0 ? o->max_abs : INFINITY;
    if (!text) len = 0;
    if (len > (size_t)OBJ_MAX_BYTES) {
        fail(&p, "it is larger than %ld MiB", OBJ_MAX_BYTES >> 20);
        return false;
    }
    const char *s = text, *end = text + len;
    if (len >= 3 && !memcmp(s, "\xEF\xBB\xBF", 3)) s += 3;   /* a UTF-8 byte order mark */

    /* logical lines: a trailing backslash continues the line; "\r\n" is a line end */
    char *buf = NULL;
    int cap = 0, lineno = 1;
    while (s < end && !p.failed) {
        p.line = lineno;
        int n = 0;
        for (;;) {
            const char *nl = memchr(s, '\n', (size_t)(end - s));
            const char *stop = nl ? nl : end;
            size_t k = (size_t)(stop - s);
            if (memchr(s, 0, k)) {
                p.line = lineno;
                fail(&p, "binary data (a NUL byte), not text");
                break;
            }
            if (nl && k > 0 && s[k - 1] == '\r') k--;
            bool cont = k > 0 && s[k - 1] == '\\';
            if (cont) k--;
            buf = mem_grow(buf, &cap, n + (int)k + 2, 1);   /* k < OBJ_MAX_BYTES: no overflow */
            memcpy(buf + n, s, k);
            n += (int)k;
            lineno++;
            s = nl ? nl + 1 : end;
            if (cont && nl) { buf[n++] = ' '; continue; }
            break;
        }
        if (p.failed) break;
        buf[n] = 0;
        statement(&p, buf);
    }
    free(buf);
    if (p.failed) {
        obj_free(d);
        return false;
    }
    return true;
}

bool obj_read(obj_data *d, const char *path, const obj_opts *o, char *err, size_t errlen) {
    if (!d) return false;
    memset(d, 0, sizeof *d);
    if (!path || !*path) {
        if (err && errlen > 0) snprintf(err, errlen, "%s: no file name", path ? path : "(null)");
        return false;
    }
    file_text_opts opts = { .max_bytes = (size_t)OBJ_MAX_BYTES, .strip_bom = true, .crlf_to_lf = true,
                            .reject_nul = true };
    char why[MSG_MAX];
    size_t len = 0;
    char *text = file_cache_read(o ? o->files : NULL, path, &opts, &len, NULL, why, sizeof why);
    if (!text) {
        if (err && errlen > 0) snprintf(err, errlen, "%s: %s", path, why);
        return false;
    }
    bool ok = obj_parse(d, text, len, path, o, err, errlen);
    free(text);
    return ok;
}

void obj_free(obj_data *d) {
    if (!d) return;
    free(d->v); free(d->color); free(d->vt); free(d->vn); free(d->corner); free(d->face_first);
    memset(d, 0, sizeof *d);
}
