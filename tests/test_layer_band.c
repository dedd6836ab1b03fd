/* test_layer_band: the tiles of a composed World that can change with the
 * time (viewer/gfx/world_layer_band.h), on hand-made point layers whose
 * tiles are known: a point in the band marks its tile, points above the
 * level, below the band, the sky and nothing do not, runs of tiles along
 * a row merge, the frame's edge clips the last tiles, and a layer with
 * more runs than room is refused. */
#include <math.h>
#include <stdlib.h>

#include "check.h"
#include "world_layer_band.h"

#define T LAYER_BAND_TILE

/* a w x h point layer, every pixel a point at height y */
static float *layer(int w, int h, float y) {
    float *p = calloc((size_t)w * h * 4, sizeof *p);
    for (int i = 0; i < w * h; i++) {
        p[4 * i + 1] = y;
        p[4 * i + 3] = 1.0f;
    }
    return p;
}

static void put(float *p, int w, int x, int y, float height, float is_point) {
    p[4 * (y * w + x) + 1] = height;
    p[4 * (y * w + x) + 3] = is_point;
}

static void test_heights(void) {
    double lo, hi;
    layer_band_heights(2.0, -0.5, &lo, &hi);   /* the bound's sign does not matter */
    CHECK(lo < 1.5 && lo > 1.499);
    CHECK(hi > 2.0 && hi < 2.001);
}

static void test_one_tile_each_kind(void) {
    int w = 4 * T, h = 2 * T, r[4 * 8];
    float *p = layer(w, h, 5.0f);   /* everything above the band */
    CHECK_EQ(layer_band_rects(p, w, h, -0.5, 0.0, r, 8), 0);
    put(p, w, T + 3, 2, -0.2f, 1.0f);            /* in the band: tile (1, 0) */
    put(p, w, 3 * T, T + 1, -0.3f, 0.0f);        /* in the band but the sky: nothing */
    put(p, w, 2 * T + 5, T + 5, -0.6f, 1.0f);    /* below the band: wet at every time */
    put(p, w, 0, T, NAN, 1.0f);                  /* not a number: composed, to be safe */
    CHECK_EQ(layer_band_rects(p, w, h, -0.5, 0.0, r, 8), 2);
    CHECK(r[0] == T && r[1] == 0 && r[2] == 2 * T && r[3] == T);
    CHECK(r[4] == 0 && r[5] == T && r[6] == T && r[7] == 2 * T);
    free(p);
}

static void test_runs_merge_and_the_edge_clips(void) {
    int w = 3 * T + 5, h = T + 7, r[4 * 8];   /* the last column and row of tiles are partial */
    float *p = layer(w, h, 5.0f);
    for (int x = T; x < w; x++) put(p, w, x, h - 1, 0.0f, 1.0f);   /* the top row, from tile 1 to the edge */
    CHECK_EQ(layer_band_rects(p, w, h, -0.5, 0.0, r, 8), 1);
    CHECK(r[0] == T && r[1] == T && r[2] == w && r[3] == h);
    put(p, w, 0, 0, -0.1f, 1.0f);
    put(p, w, 2 * T, 0, -0.1f, 1.0f);   /* two tiles of the bottom row with a gap: two runs */
    CHECK_EQ(layer_band_rects(p, w, h, -0.5, 0.0, r, 8), 3);
    CHECK_EQ(layer_band_rects(p, w, h, -0.5, 0.0, r, 2), -1);   /* no room */
    free(p);
}

int main(void) {
    RUN(test_heights);
    RUN(test_one_tile_each_kind);
    RUN(test_runs_merge_and_the_edge_clips);
    return check_summary();
}
