/* test_height_tiles: the cells of the waves' height map that a test of wet
 * land reads (viewer/gfx/world_height_tiles.h), on hand-made triangles and
 * boxes whose cells are known, and the rectangles that draw them: every
 * texel a bilinear lookup in a needed cell reads lies in a rectangle, and
 * nothing far from one does. */
#include <stdlib.h>

#include "check.h"
#include "world_height_tiles.h"

#define N HEIGHT_TILES_CELLS

/* map half 32: a cell is 1 m, cell i covers x in [-32 + i, -31 + i] */
static void start(height_tiles *t) { height_tiles_start(t, 32.0, 0.0, 0.5); }

static void test_triangles_in_the_band_only(void) {
    height_tiles t;
    start(&t);
    /* x, z in cells 32..33 and 40: one triangle at the level, one far above, one far below */
    const float pos[] = { 0.5f, 0.0f, 0.5f, 1.5f, -0.1f, 0.5f, 0.5f, 0.2f, 1.5f,
                          8.5f, 5.0f, 8.5f, 9.5f, 5.0f, 8.5f, 8.5f, 5.0f, 9.5f,
                          8.5f, -5.0f, 0.5f, 9.5f, -5.0f, 0.5f, 8.5f, -5.0f, 1.5f };
    const unsigned idx[] = { 0, 1, 2, 3, 4, 5, 6, 7, 8 };
    height_tiles_add_triangles(&t, pos, idx, 9);
    CHECK_EQ(height_tiles_count(&t), 4);   /* the first's box: cells 32..33 in x and z */
    CHECK(t.need[32 * N + 32] && t.need[33 * N + 33] && t.need[32 * N + 33] && t.need[33 * N + 32]);
    /* a triangle from below the band to above it crosses it */
    const float tall[] = { -20.5f, -3.0f, -20.5f, -20.2f, 3.0f, -20.5f, -20.5f, 0.0f, -20.2f };
    height_tiles_add_triangles(&t, tall, idx, 3);
    CHECK_EQ(height_tiles_count(&t), 5);
    CHECK(t.need[11 * N + 11]);
}

static void test_boxes_and_the_map_edge(void) {
    height_tiles t;
    start(&t);
    const double lo[3] = { 30.5, -1.0, -40.0 }, hi[3] = { 40.0, 1.0, -31.5 };   /* past two edges */
    height_tiles_add_box(&t, lo, hi);
    CHECK_EQ(height_tiles_count(&t), 2 * 1);   /* x cells 62, 63; z cell 0 */
    CHECK(t.need[0 * N + 62] && t.need[0 * N + 63]);
    const double alo[3] = { 0, 0.6, 0 }, ahi[3] = { 1, 2, 1 };   /* above the level: never wet */
    height_tiles_add_box(&t, alo, ahi);
    const double out_lo[3] = { 100, -1, 100 }, out_hi[3] = { 101, 1, 101 };   /* beyond the map */
    height_tiles_add_box(&t, out_lo, out_hi);
    CHECK_EQ(height_tiles_count(&t), 2);
}

/* Is texel (u, v) of a res-texel map inside one of the n rectangles? */
static bool drawn(const float *rects, int n, int res, int u, int v) {
    double x = (u + 0.5) / res, z = (v + 0.5) / res;
    for (int k = 0; k < n; k++) {
        const float *r = rects + 4 * k;
        if (x >= r[0] && x < r[2] && z >= r[1] && z < r[3]) return true;
    }
    return false;
}

/* Every texel whose centre is within a texel of a point of a needed cell
 * (the four a bilinear lookup there reads) is drawn; a texel four cells
 * and two texels away is not. */
static void check_rects(const height_tiles *t, int res) {
    float *rects = malloc(sizeof(float) * 4 * N * N);
    int n = height_tiles_rects(t, res, rects, N * N);
    CHECK(n > 0);
    double texel = 64.0 / res;   /* in metres, with cells of 1 m */
    int missing = 0, extra = 0;
    for (int v = 0; v < res; v++)
        for (int u = 0; u < res; u++) {
            double x = (u + 0.5) * texel, z = (v + 0.5) * texel;   /* from the map's corner */
            double nearest = INFINITY;
            for (int k = 0; k < N * N; k++) {
                if (!t->need[k]) continue;
                double ci = k % N, cj = k / N;   /* the cell [ci, ci + 1] x [cj, cj + 1] */
                double dx = fmax(0, fmax(ci - x, x - ci - 1)), dz = fmax(0, fmax(cj - z, z - cj - 1));
                nearest = fmin(nearest, fmax(dx, dz));
            }
            bool on = drawn(rects, n, res, u, v);
            if (nearest < texel && !on) missing++;
            if (nearest > 4 + 2 * texel && on) extra++;
        }
    CHECK_MSG(missing == 0, "res %d: %d texels a lookup reads are not drawn", res, missing);
    CHECK_MSG(extra == 0, "res %d: %d texels far from every needed cell are drawn", res, extra);
    CHECK_EQ(height_tiles_rects(t, res, rects, 1), -1);   /* no room: the whole map */
    free(rects);
}

static void test_rects_cover_the_lookups(void) {
    height_tiles t;
    start(&t);
    const double lo[3] = { -10.2, -0.1, 3.3 }, hi[3] = { -7.9, 0.1, 3.4 };
    height_tiles_add_box(&t, lo, hi);
    const double lo2[3] = { 20, -0.1, -30 }, hi2[3] = { 20.5, 0.1, 10 };
    height_tiles_add_box(&t, lo2, hi2);
    const int res[] = { 256, 100, 64, 37, 32 };
    for (int k = 0; k < 5; k++) check_rects(&t, res[k]);
}

int main(void) {
    RUN(test_triangles_in_the_band_only);
    RUN(test_boxes_and_the_map_edge);
    RUN(test_rects_cover_the_lookups);
    return check_summary();
}
