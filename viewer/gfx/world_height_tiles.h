/* world_height_tiles: where the waves' height map is read. world.frag
 * asks the map (packs/common/world_wet.glsl, worldUnderWaterWithin) only for a
 * point of the land or of an object between the water's level less the
 * waves' bound and the level; elsewhere its texels are never read (the
 * spray aside, which reads it over all the water). On the lake that band
 * is a ring round the shore, yet the pass drew every texel: 14 ms of every
 * animated frame at full detail on llvmpipe, whatever the frame's size.
 * This module finds, on the CPU, the cells of the map such a point can
 * fall in, from the triangles the GPU draws (a triangle's points lie
 * between its corners' heights), so the pass draws only those cells and
 * the texels a bilinear lookup in them reads. Pure CPU: render_world.c
 * gives it the land's meshes and the objects' boxes, and draws the
 * rectangles. */
#ifndef TARN_WORLD_HEIGHT_TILES_H
#define TARN_WORLD_HEIGHT_TILES_H
#include <stdbool.h>

#define HEIGHT_TILES_CELLS 64   /* the mask's cells a side over the map */

typedef struct height_tiles {
    double map_half;       /* the map covers x, z in [-map_half, map_half] */
    double lo_y, hi_y;     /* the band of heights that reads the map */
    /* cell (i, j), i along x, j along z, from -map_half: may a point that
     * reads the map fall in it? */
    bool need[HEIGHT_TILES_CELLS * HEIGHT_TILES_CELLS];
} height_tiles;

/* No cell needed yet; the band [level - bound, level], widened for the
 * shader's float32 comparisons. */
void height_tiles_start(height_tiles *t, double map_half, double level, double bound);
/* Marks the cells under the triangles of an indexed triangle list (3
 * floats a vertex) whose heights reach the band. */
void height_tiles_add_triangles(height_tiles *t, const float *pos, const unsigned *idx, int nidx);
/* Marks the cells under an axis-aligned box (an object) that reaches the band. */
void height_tiles_add_box(height_tiles *t, const double lo[3], const double hi[3]);
int height_tiles_count(const height_tiles *t);

/* The rectangles to draw a map of res texels a side with: runs of cells
 * along x, a row each, every needed cell grown by the texels a bilinear
 * lookup inside it reads. Written as x0 z0 x1 z1 in [0, 1] map coordinates
 * (4 floats a rectangle) into out (room for max rectangles); returns their
 * count, or -1 when more than max (draw the whole map then). */
int height_tiles_rects(const height_tiles *t, int res, float *out, int max);

#endif
