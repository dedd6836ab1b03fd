/* world_layer_band: where a World's layers can change with the time. A
 * pixel composed from the layers (world_layers.frag) changes only where
 * its point lies in the band of heights a wet test reads the moving
 * surface for, [level - the waves' bound, level) (world_wet.glsl): a point
 * above the level is always dry, one below the band always wet, the sky
 * never wet. On the lake that band is the ring round the shore; the rest
 * of a composed frame is the same at every time, so after the first the
 * renderer copies the rest and composes only the tiles this module finds.
 * Pure CPU: world_layers.c gives it the point layer read back once per
 * build. */
#ifndef TARN_WORLD_LAYER_BAND_H
#define TARN_WORLD_LAYER_BAND_H

#define LAYER_BAND_TILE 16   /* a tile's pixels a side: llvmpipe shades blocks of 16 x 16 and 4 x 4 */

/* The band [lo, hi] of heights to compose for a water level and the
 * waves' bound (any bound not less than the shader's), widened for the
 * shader's float32 comparisons. */
void layer_band_heights(double level, double bound, double *lo, double *hi);

/* The tiles of a w x h layer whose points (pos: RGBA floats a pixel, row
 * by row from the bottom: xyz the point, w > 0.5 a point, else the sky or
 * nothing) reach the band [lo, hi], as pixel rectangles x0 y0 x1 y1 (runs
 * of tiles along x merged, a row of tiles each) in out (room for max).
 * Returns their count, or -1 when more than max. A point whose height is
 * not a number counts as in the band. */
int layer_band_rects(const float *pos, int w, int h, double lo, double hi, int *out, int max);
#endif
