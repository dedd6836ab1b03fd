/* ref_mesh: a triangle mesh from a Wavefront OBJ file, placed in the world,
 * and rays against it through a bounding-volume hierarchy (issue #25: a
 * world `Object mesh`, a boat, a rock, a pier).
 *
 * The triangles are kept in world coordinates (placed once at load), so a
 * hit needs no transform and the GL side uploads the very same triangles.
 * Each triangle's normal is its geometric one, (b - a) x (c - a) unit, by
 * the file's winding (counter-clockwise seen from outside, as OBJ has it):
 * the GL world draws flat faces with the same normals, so both renderers
 * shade a facet alike. Hits are Moller-Trumbore in double precision; the
 * hierarchy (median splits of the centroids along the longest axis, up to
 * REF_MESH_LEAF triangles a leaf) changes which triangles are tested, never
 * the t a triangle gives, and its boxes are tested with a margin wider than
 * a hit's rounding, so ref_mesh_hit and ref_mesh_hit_brute agree exactly
 * wherever the nearest hit is not a sliver, a grazing ray or a triangle
 * far larger than the hit's distance (its aspect over the ray's cosine,
 * times its corner's distance over the hit's, up to 1e5); beyond that the
 * hierarchy may skip a triangle whose rounded t lies before its box,
 * never returning a nearer hit. Pure after load: any number of threads
 * may trace one mesh. */
#ifndef TARN_REF_MESH_H
#define TARN_REF_MESH_H

#include <stdbool.h>
#include <stddef.h>

#include "obj.h"

#define REF_MESH_LEAF 4
#define REF_MESH_MAX_TRIANGLES (1 << 20)   /* what a wrong file can cost */

typedef struct ref_mesh ref_mesh;   /* opaque */

/* Where a mesh goes: turned rot_y_deg about +y (counter-clockwise seen from
 * above), scaled by scale (0: 1), then moved to pos. */
typedef struct ref_mesh_place {
    double pos[3];
    double rot_y_deg;
    double scale;
} ref_mesh_place;

/* Reads the OBJ file at path with tarn's one OBJ reader (base/obj.h:
 * v, vt, vn, f with v, v/vt, v//vn or v/vt/vn corners and negative
 * indices; grouping and materials skipped; positions only: a corner's vt
 * and vn are not looked up) and places its faces' triangles
 * (polygons fanned from their first corner). NULL, with "path:line: why"
 * in err, for a file that cannot be read or that obj_parse refuses (an
 * index that does not exist, an unknown statement, a bad number), no
 * triangle at all, or more than REF_MESH_MAX_TRIANGLES. */
ref_mesh *ref_mesh_load(const char *path, const ref_mesh_place *place, char *err, size_t errlen);

/* The same from len bytes of OBJ text already read (the scene's loader
 * reads a file once, for its content hash and its triangles); name for the
 * messages. */
ref_mesh *ref_mesh_parse(const char *text, size_t len, const char *name, const ref_mesh_place *place, char *err,
                         size_t errlen);

/* The same from an OBJ already parsed (obj_parse), name for the messages. */
ref_mesh *ref_mesh_from_obj(const obj_data *d, const char *name, const ref_mesh_place *place, char *err,
                            size_t errlen);

/* A mesh of ntri triangles given as 9 doubles each (a, b, c), as they are
 * (tests). NULL for ntri < 1. */
ref_mesh *ref_mesh_from_triangles(const double *tri, int ntri);

void ref_mesh_free(ref_mesh *m);

int ref_mesh_count(const ref_mesh *m);
/* Triangle i's corners, 9 doubles (a, b, c), and its unit normal. */
const double *ref_mesh_triangle(const ref_mesh *m, int i);
const double *ref_mesh_normal(const ref_mesh *m, int i);
/* The axis-aligned box around every triangle. */
void ref_mesh_bounds(const ref_mesh *m, double lo[3], double hi[3]);

/* The nearest triangle the ray o + t d meets with t in (tmin, tmax):
 * true with t and the triangle's normal (not turned towards the ray). */
bool ref_mesh_hit(const ref_mesh *m, const double o[3], const double d[3], double tmin, double tmax,
                  double *t, double n[3]);

/* The same by testing every triangle (the hierarchy's check). */
bool ref_mesh_hit_brute(const ref_mesh *m, const double o[3], const double d[3], double tmin,
                        double tmax, double *t, double n[3]);

#endif
