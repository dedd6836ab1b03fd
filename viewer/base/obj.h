/* obj: tarn's one Wavefront OBJ reader (issue #28), for the viewer's `Obj`
 * geometry (gfx/geom_obj.c) and the reference's world meshes
 * (reference/ref_mesh.c) alike, so that one file reads the same in both.
 *
 * Why here and not tinyobjloader: the reader must be usable from the
 * pure-C reference layer, which links nothing above base (and no C++), and
 * fuzzed in the C-only fuzz build (tests/fuzz/fuzz_obj.c); tinyobjloader
 * is a C++ header. Base is the one layer both users link.
 *
 * What it reads (text in memory: bytes and a length, and a name for the
 * messages):
 *  - `v x y z` with an optional w (dropped) or vertex colour r g b (kept:
 *    6 numbers); 5 or 7 numbers are checked, not kept;
 *  - `vt u [v [w]]` (u, v kept; a missing v is 0); `vn x y z`;
 *  - `f` (or `fo`) with 3 or more corners, each v, v/vt, v//vn or v/vt/vn;
 *    a negative index counts back from the last element defined so far;
 *    polygons are kept as polygons (obj_data.face_first);
 *  - `#` comments; a trailing backslash continues a line; a UTF-8 byte
 *    order mark; CRLF line ends; grouping, materials, free-form and the
 *    rest of OBJ's statements (o g s usemtl mtllib l p vp ...) are ignored.
 * Anything else is an error, "name:line: what is wrong" (or "name: ..."
 * for the whole text): unknown statements, bad numbers (non-finite
 * included), wrong counts, index 0 or out of range, a NUL byte (binary),
 * more than the limits below. Never a crash on any input (fuzzed). */
#ifndef TARN_OBJ_H
#define TARN_OBJ_H

#include <stdbool.h>
#include <stddef.h>

#define OBJ_MAX_BYTES (256L << 20)        /* an OBJ text: what a wrong path can cost */
#define OBJ_MAX_TRIANGLES (1 << 26)        /* the default of obj_opts.max_triangles */

/* One corner of a face: 0-based indices into v, vt, vn; -1 when absent. */
typedef struct obj_corner {
    int v, vt, vn;
} obj_corner;

typedef struct obj_data {
    double *v;              /* 3 a position */
    double *color;          /* NULL when no `v` has colours; else 3 a position, 1 1 1 where not given */
    int nv;
    double *vt;             /* 2 a texture coordinate */
    int nvt;
    double *vn;             /* 3 a normal, as written (not normalised) */
    int nvn;
    obj_corner *corner;     /* every face's corners, face after face, as written */
    int ncorner;
    int *face_first;        /* nface + 1 entries: face f is corner[face_first[f] .. face_first[f + 1]) */
    int nface;
    int ntri;               /* triangles the faces make fanned: the sum of (corners - 2) */
} obj_data;

/* Zero means the default. */
typedef struct obj_opts {
    int max_triangles;      /* more (fanned) is an error at the line that passes it; 0: OBJ_MAX_TRIANGLES */
    bool positions_only;    /* a reader of positions alone (the reference's meshes): a corner's vt
                             * and vn are not looked up (-1), so a file is not refused for texture
                             * coordinates or normals that would not be used */
    double max_abs;         /* a number's largest magnitude; 0: any finite one (the reference's
                             * doubles); the viewer's float meshes give FLT_MAX */
    struct file_cache *files;   /* obj_read reads through it (file_cache.h); NULL: the disk */
} obj_opts;

/* Parses len bytes of text (need not be NUL-terminated) into d. False,
 * with d empty and the message in err (err may be NULL), on the first
 * error. A text with no face is not an error (the callers say what it
 * lacks). o may be NULL. */
bool obj_parse(obj_data *d, const char *text, size_t len, const char *name, const obj_opts *o, char *err,
               size_t errlen);

/* Reads the file at path (at most OBJ_MAX_BYTES, as text: base/file.h)
 * and parses it, the messages naming path: "path: No such file or
 * directory", "path: it is a directory", "path:3: bad number 'x'". */
bool obj_read(obj_data *d, const char *path, const obj_opts *o, char *err, size_t errlen);

/* Frees the arrays and empties d; safe on an empty d. */
void obj_free(obj_data *d);

#endif
