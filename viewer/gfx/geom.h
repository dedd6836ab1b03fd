/* geom: meshes for glman's geometry commands (QuadXY/XZ/YZ, Sphere, Torus,
 * Box, Cylinder, Cone, Teapot, Obj and their Wire* variants; ObjAdj,
 * ObjPatch, DiskXY, QuadBox, PointCloud, JitterCloud, Soccerball, Xarrow,
 * Triangles, LinesAdjacency and glBegin's vertices).
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
 *  - Sphere: centred; as the course's sphere code (OsuSphere): s = (lng +
 *    pi) / 2pi, t = (lat + pi/2) / pi, the point (cos lat cos lng, sin lat,
 *    -cos lat sin lng): the seam (s = 0/1) at -x, s = 0.25 at +z (facing
 *    glman's default camera), s = 0.5 at +x, s increasing eastwards seen from
 *    outside; Tangent = d/d(latitude), towards the north pole (+y), as
 *    glman's (the one mesh whose tangent is +v).
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

#include "obj.h"

#define GEOM_MAX_DIV 2048       /* most segments on one side of a grid */
#define GEOM_MAX_TEAPOT_GRID 128
#define GEOM_MAX_FILE_BYTES OBJ_MAX_BYTES   /* an OBJ or shapefile: what a wrong path can cost */

/* How the indices are read: as GL's primitive of the same name. */
typedef enum geom_prim {
    GEOM_TRIANGLES = 0,
    GEOM_LINES,                 /* wire variants: index pairs */
    GEOM_POINTS,
    GEOM_LINES_ADJACENCY,       /* 4 indices a primitive */
    GEOM_TRIANGLES_ADJACENCY,   /* 6: v0 a01 v1 a12 v2 a20 */
    GEOM_PATCHES,               /* patch_size indices a patch (tessellation) */
    /* what glBegin may also draw */
    GEOM_LINE_STRIP, GEOM_LINE_LOOP, GEOM_TRIANGLE_STRIP, GEOM_TRIANGLE_FAN, GEOM_QUADS
} geom_prim;

typedef struct geom_mesh {
    float *pos;                 /* 3 floats a vertex */
    float *nrm;                 /* 3, unit */
    float *tc;                  /* 2 */
    float *tan;                 /* 3, unit, perpendicular to nrm */
    float *tcp;                 /* NULL, or 1 a vertex: the third texture
                                 * coordinate p (QuadBox, PointCloud, Soccerball) */
    int nvert;
    unsigned *idx;              /* read as prim says */
    int nidx;
    geom_prim prim;
    int patch_size;             /* GEOM_PATCHES: indices a patch; 0: the scene's
                                 * NumPatchVertices decides */
    /* Parts drawn one at a time with a uniform telling which (Soccerball's
     * FaceIndex): part k is idx[part_first[k] .. part_first[k + 1]); NULL
     * and 0 when the mesh is one draw. part_first has nparts + 1 entries. */
    int *part_first;
    int nparts;
} geom_mesh;

/* axis 0: QuadYZ (x = offset), 1: QuadXZ (y = offset), 2: QuadXY (z = offset).
 * n1, n2 are the glib's two counts in its order (QuadXY z size nx ny, QuadXZ
 * y size nx nz, QuadYZ x size ny nz); default 1. */
bool geom_quad(geom_mesh *m, int axis, float offset, float size, int n1, int n2, bool wire);

/* Reorders the triangles of an nu x nv cell grid made by geom_quad (cells
 * row by row along u) into bands `band` cells wide, each band swept row by
 * row, and renumbers the vertices by first use. The same triangles with the
 * same winding; a vertex is reused while it is still in a small vertex
 * cache (llvmpipe shades each vertex of a row-ordered 256-cell grid about
 * 3.6 times). False, and m unchanged, when m is not such a grid. */
bool geom_grid_bands(geom_mesh *m, int nu, int nv, int band);

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

/* Reads a Wavefront OBJ file with tarn's one OBJ reader (base/obj.h, which
 * the reference's world meshes use too): v (x y z [w] or x y z r g b), vt,
 * vn and f with corners v, v/vt, v//vn or v/vt/vn (negative indices count
 * back from the last element defined); polygons are fan-triangulated.
 * Corners without vn get area-weighted smooth normals of the faces sharing
 * the position; without vt, tc is (0, 0). Grouping, material and other OBJ
 * statements are ignored. Errors (false, mesh empty) are "path:line:
 * message" for bad indices (0, out of range), bad numbers, malformed or
 * unknown statements, and "path: reason" for a missing/unreadable file, a
 * binary one (a NUL byte), one over OBJ_MAX_BYTES or one with no faces. A
 * UTF-8 byte order mark and CRLF line ends are read as text.
 * (geom_obj.c; the other shapes: geom_shapes.c, geom_teapot.c,
 * geom_soccerball.c, geom_shp.c, on geom_build.c's mesh builder.) */
bool geom_obj_load(geom_mesh *m, const char *path, char *err, int errlen);

/* Wire variant of an OBJ (WireObj): the same vertices, GL_LINES over each
 * edge of its triangles once. */
bool geom_obj_load_wire(geom_mesh *m, const char *path, char *err, int errlen);

/* ObjAdj: the OBJ's triangles as GL_TRIANGLES_ADJACENCY (v0 a01 v1 a12 v2
 * a20), a_ij the far corner of the triangle across edge ij (edges matched by
 * position); an edge with no other triangle (a boundary, or one shared by
 * more than two) takes the triangle's own third corner, so a geometry
 * shader sees a folded, not a missing, neighbour. */
bool geom_obj_load_adjacency(geom_mesh *m, const char *path, char *err, int errlen);

/* ObjPatch: the OBJ's faces as GL_PATCHES. When every face has the same
 * number n of corners (3 to 32) each face is one patch of n vertices in
 * the file's order (patch_size n); otherwise faces are fanned into
 * triangles, patches of 3. */
bool geom_obj_load_patches(geom_mesh *m, const char *path, char *err, int errlen);

/* The four above, read through files (file_cache.h; NULL: the disk) as
 * prim: GEOM_TRIANGLES (Obj), GEOM_LINES (WireObj),
 * GEOM_TRIANGLES_ADJACENCY (ObjAdj), GEOM_PATCHES (ObjPatch). */
struct file_cache;
bool geom_obj_read(geom_mesh *m, struct file_cache *files, const char *path, geom_prim prim, char *err,
                   int errlen);

/* The mesh of an OBJ already parsed (obj_parse), drawn as prim:
 * GEOM_TRIANGLES (Obj), GEOM_LINES (WireObj), GEOM_TRIANGLES_ADJACENCY
 * (ObjAdj) or GEOM_PATCHES (ObjPatch); name for the messages ("name: no
 * faces"). The loaders above are obj_read and this. */
bool geom_obj_mesh(geom_mesh *m, const obj_data *d, geom_prim prim, const char *name, char *err, int errlen);

/* Shp: an ESRI shapefile's main file (.shp): PolyLine (3) and Polygon (5)
 * records, and their Z (13, 15) and M (23, 25) variants; null shapes are
 * skipped. Each part is drawn as a line strip (GEOM_LINES pairs), a
 * polygon's ring closed when its last point is not its first. Positions
 * are the file's x, y (its own units: degrees for a world map) on the XY
 * plane, z = 0 (the Z variants: the file's z); normal +z, Tangent +x; tc is
 * x, y over the file's bounding box (0..1); one draw. False, with
 * "path: why" in err, for a file that cannot be read, is not a shapefile
 * (file code 9994, version 1000), holds other shapes (Point, MultiPoint,
 * MultiPatch: named), is truncated or inconsistent (the record named), or
 * has no line in it. Bounded: GEOM_MAX_FILE_BYTES. */
bool geom_shp_load(geom_mesh *m, const char *path, char *err, int errlen);
/* geom_shp_load read through files (file_cache.h; NULL: the disk). */
bool geom_shp_read(geom_mesh *m, struct file_cache *files, const char *path, char *err, int errlen);

/* n points given (3 floats each) as one primitive: Triangles (3 points,
 * GEOM_TRIANGLES, normal from the winding), LinesAdjacency (4 points,
 * GEOM_LINES_ADJACENCY), glBegin..glEnd (any count and prim). tc is (x, y)
 * of each point; tangent any perpendicular. */
bool geom_points(geom_mesh *m, const float *xyz, int n, geom_prim prim);

/* DiskXY: the unit disk in z = 0 facing +z, `slices` sectors (default 64,
 * at least 3); tc = (x + 1, y + 1) / 2, tangent +x. */
bool geom_disk_xy(geom_mesh *m, int slices);

/* QuadBox n: n quads parallel to XY spanning the cube [-1, 1]^3, evenly
 * from z = -1 to z = 1 (one at z = 0 when n is 1), drawn back to front
 * seen from +z; 3D texture coordinates (tc, tcp) = (x + 1, y + 1, z + 1) / 2. */
bool geom_quad_box(geom_mesh *m, int n);

/* PointCloud / JitterCloud nx ny nz: nx*ny*nz points over the cube
 * [-1, 1]^3, at cell centres, or (jitter) at a random place in each cell
 * (a fixed seed: the same cloud every time); (tc, tcp) = the point mapped
 * to 0..1, normal the unit vector from the centre (+z at the centre). */
bool geom_point_cloud(geom_mesh *m, int nx, int ny, int nz, bool jitter);

/* Xarrow: an arrow along +x from 0 to 1 (a shaft of radius 0.02 to x =
 * 0.8, a head of radius 0.06), `slices` around (default 100, at least 3). */
bool geom_xarrow(geom_mesh *m, int slices);

/* Soccerball r: a truncated icosahedron's 12 pentagons and 20 hexagons on
 * the sphere of radius r (each face a fan from its centre, subdivided and
 * pushed out to the sphere; normals radial). Part k is face k: 0-11 the
 * pentagons, 12-31 the hexagons (glman's FaceIndex). Per face, (s, t) maps
 * the face's circumscribed square to 0..1 (t up, towards +y), tcp the
 * distance from the face centre over the face's radius (0 centre, 1
 * corners); Tangent as the sphere's (towards the north pole). */
bool geom_soccerball(geom_mesh *m, float r);

/* Frees the arrays and empties the mesh; safe on an empty mesh. */
void geom_free(geom_mesh *m);

#endif
