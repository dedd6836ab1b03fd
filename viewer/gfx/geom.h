/* geom: meshes for glman's geometry commands (QuadXY/XZ/YZ, Sphere, Torus,
 * Box, Cylinder, Cone, Teapot, Obj and their Wire* variants).
 *
 * Every mesh carries per vertex a position, a unit normal, a texture
 * coordinate and a unit tangent perpendicular to the normal pointing along
 * +u of the texture coordinate (glman's `Tangent` attribute); the bitangent
 * is cross(normal, tangent), along +v. Triangles wind counter-clockwise seen
 * from outside (from the +normal side). Wire variants keep the same vertices
 * and give GL_LINES index pairs along the parameter lines instead.
 *
 * No NaN ever: zero sizes give degenerate but finite meshes with valid
 * normals; negative sizes act as their absolute value; subdivisions <= 0
 * take the default and are clamped to [minimum, GEOM_MAX_DIV]. Non-finite
 * arguments (NaN, inf) are refused (false). On false the mesh is empty.
 *
 * Conventions (y up, as glman and GLUT):
 *  - Quad: spans -size..+size on its two axes at `offset` on the third; the
 *    normal is +axis; tc 0..1 with (tangent, bitangent) = QuadXY (+x, +y),
 *    QuadXZ (+x, -z: upright seen from above), QuadYZ (-z, +y: upright seen
 *    from +x).
 *  - Sphere: centred; longitude around +y, 0 at +z, increasing towards +x;
 *    tc = (lon / 2pi, (lat + pi/2) / pi); Tangent = d/d(longitude).
 *  - Torus: as GLUT's, in the xy plane around the z axis; r_major is the
 *    distance from the centre to the tube's centre, r_minor the tube radius;
 *    `rings` segments around z, `sides` around the tube; tc = (ring angle /
 *    2pi, tube angle / 2pi).
 *  - Box: centred, full edge lengths, 24 vertices with flat normals, tc 0..1
 *    on each face.
 *  - Cylinder: centred on the origin along y (y from -h/2 to h/2), both caps;
 *    side tc = (angle / 2pi, (y + h/2) / h), caps mapped from above (top)
 *    and below (bottom).
 *  - Cone: base of radius r at y = -h/2 (capped), apex at y = +h/2.
 *  - Teapot: the Newell teapot (its 32 bicubic Bezier patches) placed as
 *    GLUT's glutSolidTeapot(size): spout along +x, lid up +y, spanning
 *    x -1.5..1.72, y -0.75..0.825, z -1..1 times size; `grid` segments per
 *    patch side; tc 0..1 on each patch.
 */
#ifndef TARN_GEOM_H
#define TARN_GEOM_H

#include <stdbool.h>

#define GEOM_MAX_DIV 2048       /* most segments on one side of a grid */
#define GEOM_MAX_TEAPOT_GRID 128
#define GEOM_OBJ_MAX_FILE_BYTES (256L << 20)   /* an OBJ file: what a wrong path can cost */

typedef struct geom_mesh {
    float *pos;                 /* 3 floats a vertex */
    float *nrm;                 /* 3, unit */
    float *tc;                  /* 2 */
    float *tan;                 /* 3, unit, perpendicular to nrm */
    int nvert;
    unsigned *idx;              /* triangles, or index pairs when lines */
    int nidx;
    bool lines;                 /* GL_LINES (wire variants) instead of GL_TRIANGLES */
} geom_mesh;

/* axis 0: QuadYZ (x = offset), 1: QuadXZ (y = offset), 2: QuadXY (z = offset).
 * n1, n2 are the glib's two counts in its order (QuadXY z size nx ny, QuadXZ
 * y size nx nz, QuadYZ x size ny nz); default 1. */
bool geom_quad(geom_mesh *m, int axis, float offset, float size, int n1, int n2, bool wire);

/* Defaults: 32 slices, 16 stacks; at least 3 and 2. */
bool geom_sphere(geom_mesh *m, float r, int slices, int stacks, bool wire);

/* Defaults: 16 sides, 32 rings; at least 3 each. */
bool geom_torus(geom_mesh *m, float r_major, float r_minor, int sides, int rings, bool wire);

bool geom_box(geom_mesh *m, float dx, float dy, float dz, bool wire);

/* Defaults: 32 slices (at least 3), 1 stack. */
bool geom_cylinder(geom_mesh *m, float r, float h, int slices, int stacks, bool wire);
bool geom_cone(geom_mesh *m, float r, float h, int slices, int stacks, bool wire);

/* Default grid 10 (segments per patch side), at most GEOM_MAX_TEAPOT_GRID. */
bool geom_teapot(geom_mesh *m, float size, int grid, bool wire);

/* Reads a Wavefront OBJ file: v (x y z [w] or x y z r g b), vt, vn and f
 * with corners v, v/vt, v//vn or v/vt/vn (negative indices count back from
 * the last element defined); polygons are fan-triangulated. Corners without
 * vn get area-weighted smooth normals of the faces sharing the position;
 * without vt, tc is (0, 0). Grouping, material and other OBJ statements are
 * ignored. Errors (false, mesh empty) are "path:line: message" for bad
 * indices (0, out of range), bad numbers, malformed or unknown statements,
 * and "path: reason" for a missing/unreadable file, a binary one (a NUL
 * byte), one over GEOM_OBJ_MAX_FILE_BYTES or one with no faces. A UTF-8
 * byte order mark and CRLF line ends are read as text. */
bool geom_obj_load(geom_mesh *m, const char *path, char *err, int errlen);

/* Frees the arrays and empties the mesh; safe on an empty mesh. */
void geom_free(geom_mesh *m);

#endif
