/* geom_shp.c: ESRI shapefiles' lines (Shp; geom.h). */
#include "geom_build.h"
#include "strbuf.h"
#include "file_cache.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- Shp: ESRI shapefiles (the .shp main file) ---- */

static uint32_t shp_be32(const unsigned char *p) {
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}
static uint32_t shp_le32(const unsigned char *p) {
    return (uint32_t)p[3] << 24 | (uint32_t)p[2] << 16 | (uint32_t)p[1] << 8 | p[0];
}
static double shp_le64f(const unsigned char *p) {
    uint64_t u = 0;
    for (int k = 7; k >= 0; k--) u = u << 8 | p[k];
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

static bool shp_fail(char *err, int errlen, const char *path, const char *fmt, ...) {
    if (err && errlen > 0) {
        char msg[MSG_MAX];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg, sizeof msg, fmt, ap);
        va_end(ap);
        snprintf(err, (size_t)errlen, "%s: %s", path, msg);
    }
    return false;
}

static const char *shp_type_name(int t) {
    switch (t) {
    case 0: return "Null"; case 1: return "Point"; case 3: return "PolyLine"; case 5: return "Polygon";
    case 8: return "MultiPoint"; case 11: return "PointZ"; case 13: return "PolyLineZ";
    case 15: return "PolygonZ"; case 18: return "MultiPointZ"; case 21: return "PointM";
    case 23: return "PolyLineM"; case 25: return "PolygonM"; case 28: return "MultiPointM";
    case 31: return "MultiPatch"; default: return "unknown";
    }
}

static bool shp_lines(int t) { return t == 3 || t == 5 || t == 13 || t == 15 || t == 23 || t == 25; }

bool geom_shp_load(geom_mesh *m, const char *path, char *err, int errlen) {
    return geom_shp_read(m, NULL, path, err, errlen);
}

/* One read: the file's bytes, what its header declared, the mesh so far. */
typedef struct shp_read {
    const unsigned char *f;
    size_t len, declared;       /* the file's bytes; the header's length (bytes) */
    double box[4], w, h;        /* the bounding box (x0, y0, x1, y1), its size (1 where empty) */
    const char *path;
    char *err;
    int errlen;
    mb b;
} shp_read;

/* The 100-byte header: file code, version, length, type, box. */
static bool shp_header(shp_read *r) {
    const unsigned char *f = r->f;
    if (r->len < 100)
        return shp_fail(r->err, r->errlen, r->path, "not a shapefile: %zu bytes, shorter than the 100-byte header",
                        r->len);
    if (shp_be32(f) != 9994)
        return shp_fail(r->err, r->errlen, r->path, "not a shapefile (.shp): its file code is %u, not 9994",
                        shp_be32(f));
    if (shp_le32(f + 28) != 1000)
        return shp_fail(r->err, r->errlen, r->path, "not a shapefile: version %u, not 1000", shp_le32(f + 28));
    r->declared = (size_t)shp_be32(f + 24) * 2;
    if (r->declared > r->len)
        return shp_fail(r->err, r->errlen, r->path, "truncated: the header says %zu bytes, the file has %zu",
                        r->declared, r->len);
    if (r->declared < 100) r->declared = r->len;   /* a writer that left the length 0: read what is there */
    int type = (int)shp_le32(f + 32);
    if (type != 0 && !shp_lines(type))
        return shp_fail(r->err, r->errlen, r->path, "shape type %d (%s): tarn draws PolyLine and Polygon shapefiles "
                        "(3, 5 and their Z/M variants)", type, shp_type_name(type));
    for (int k = 0; k < 4; k++) r->box[k] = shp_le64f(f + 36 + 8 * k);
    r->w = r->box[2] - r->box[0];
    r->h = r->box[3] - r->box[1];
    if (!isfinite(r->w) || !(r->w > 0)) r->w = 1;
    if (!isfinite(r->h) || !(r->h > 0)) r->h = 1;
    return true;
}

/* Part p of record rec (its points parts[p] up to the next part's first):
 * a line strip, closed for a polygon where its ends differ. */
static bool shp_part(shp_read *r, int rec, const unsigned char *parts, const unsigned char *pts,
                     const unsigned char *zs, uint32_t p, uint32_t np, uint32_t npt, bool z, bool closed) {
    static const double nz[3] = {0, 0, 1}, tx[3] = {1, 0, 0};
    mb *b = &r->b;
    uint32_t first = shp_le32(parts + 4 * p), end = p + 1 < np ? shp_le32(parts + 4 * (p + 1)) : npt;
    if (first > end || end > npt)
        return shp_fail(r->err, r->errlen, r->path, "record %d: part %u runs from point %u to %u of %u", rec, p,
                        first, end, npt);
    if (!mb_reserve(b, (long)(end - first), 2L * (end - first + 1))) return false;
    int v0 = b->m.nvert;
    for (uint32_t i = first; i < end; i++) {
        double x = shp_le64f(pts + 16 * i), y = shp_le64f(pts + 16 * i + 8);
        double pz = z ? shp_le64f(zs + 8 * i) : 0;
        if (!isfinite(x) || !isfinite(y) || !isfinite(pz))
            return shp_fail(r->err, r->errlen, r->path, "record %d: point %u is not a finite number", rec, i);
        double pos[3] = {x, y, pz};
        mb_vert(b, pos, nz, (x - r->box[0]) / r->w, (y - r->box[1]) / r->h, tx);
        if (i > first) mb_line(b, b->m.nvert - 2, b->m.nvert - 1);
    }
    int n = b->m.nvert - v0;
    if (closed && n > 2) {
        const float *a = b->m.pos + 3 * v0, *e = b->m.pos + 3 * (b->m.nvert - 1);
        if (a[0] != e[0] || a[1] != e[1] || a[2] != e[2]) mb_line(b, b->m.nvert - 1, v0);
    }
    return true;
}

/* Record rec, whose header is at *at; *at moves past it. */
static bool shp_record(shp_read *r, int rec, size_t *at) {
    const unsigned char *f = r->f;
    size_t declared = r->declared;
    if (declared - *at < 8)
        return shp_fail(r->err, r->errlen, r->path, "truncated: record %d's header at byte %zu is cut off", rec, *at);
    size_t clen = (size_t)shp_be32(f + *at + 4) * 2;
    size_t c = *at + 8;
    if (clen > declared - c)
        return shp_fail(r->err, r->errlen, r->path,
                        "truncated: record %d (at byte %zu) needs %zu bytes, the file ends %zu bytes on", rec, *at,
                        clen, declared - c);
    *at = c + clen;
    if (clen < 4)
        return shp_fail(r->err, r->errlen, r->path, "record %d (at byte %zu) has no shape type", rec, c - 8);
    int rt = (int)shp_le32(f + c);
    if (rt == 0) return true;                          /* a null shape: nothing to draw */
    if (!shp_lines(rt))
        return shp_fail(r->err, r->errlen, r->path,
                        "record %d is shape type %d (%s): tarn draws PolyLine and Polygon shapes", rec, rt,
                        shp_type_name(rt));
    if (clen < 44)
        return shp_fail(r->err, r->errlen, r->path, "record %d (at byte %zu): %zu bytes, too short for a %s", rec,
                        c - 8, clen, shp_type_name(rt));
    uint32_t np = shp_le32(f + c + 36), npt = shp_le32(f + c + 40);
    size_t need = 44 + (size_t)np * 4 + (size_t)npt * 16;
    bool z = rt == 13 || rt == 15;
    if (z) need += 16 + (size_t)npt * 8;
    if (np > clen || npt > clen || need > clen)
        return shp_fail(r->err, r->errlen, r->path,
                        "record %d (at byte %zu): %u parts and %u points need %zu bytes, it has %zu", rec, c - 8, np,
                        npt, need, clen);
    const unsigned char *parts = f + c + 44, *pts = parts + (size_t)np * 4;
    const unsigned char *zs = pts + (size_t)npt * 16 + 16;
    bool closed = rt == 5 || rt == 15 || rt == 25;
    for (uint32_t p = 0; p < np; p++)
        if (!shp_part(r, rec, parts, pts, zs, p, np, npt, z, closed)) return false;
    return true;
}

/* The header, then every record, then at least one line. */
static bool shp_parse(shp_read *r) {
    if (!shp_header(r)) return false;
    size_t at = 100;
    int rec = 0;
    while (at < r->declared)
        if (!shp_record(r, ++rec, &at)) return false;
    if (r->b.m.nidx == 0)
        return shp_fail(r->err, r->errlen, r->path, "no line to draw: %d record%s, none with two points", rec,
                        rec == 1 ? "" : "s");
    return true;
}

bool geom_shp_read(geom_mesh *m, struct file_cache *files, const char *path, char *err, int errlen) {
    if (!m) return false;
    memset(m, 0, sizeof *m);
    if (err && errlen > 0) err[0] = '\0';
    char why[MSG_MAX];
    size_t len = 0;
    unsigned char *f = (unsigned char *)file_cache_bytes(files, path, (size_t)GEOM_MAX_FILE_BYTES, &len, why,
                                                         sizeof why);
    if (!f) return shp_fail(err, errlen, path, "%s", why);
    shp_read r = { .f = f, .len = len, .path = path, .err = err, .errlen = errlen };
    mb_init(&r.b, true);
    bool ok = shp_parse(&r);
    free(f);
    if (!ok) {
        r.b.ok = false;
        if (err && errlen > 0 && !err[0]) shp_fail(err, errlen, path, "too large");
    }
    return mb_finish(&r.b, m) && ok;
}
