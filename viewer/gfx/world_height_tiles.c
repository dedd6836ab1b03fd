#include "world_height_tiles.h"
#include "world_layer_band.h"

#include <math.h>
#include <string.h>

#define N HEIGHT_TILES_CELLS

void height_tiles_start(height_tiles *t, double map_half, double level, double bound) {
    memset(t, 0, sizeof *t);
    t->map_half = map_half;
    layer_band_heights(level, bound, &t->lo_y, &t->hi_y);   /* the band a wet test reads the map in */
}

/* The cells [x0, x1] x [z0, z1] meets (clamped to the map), marked. */
static void mark(height_tiles *t, double x0, double z0, double x1, double z1) {
    double cell = 2 * t->map_half / N;
    double fi0 = floor((x0 + t->map_half) / cell), fi1 = floor((x1 + t->map_half) / cell);
    double fj0 = floor((z0 + t->map_half) / cell), fj1 = floor((z1 + t->map_half) / cell);
    if (!(fi1 >= 0 && fj1 >= 0 && fi0 < N && fj0 < N)) return;   /* outside the map (or NaN) */
    int i0 = fi0 < 0 ? 0 : (int)fi0, i1 = fi1 >= N ? N - 1 : (int)fi1;
    int j0 = fj0 < 0 ? 0 : (int)fj0, j1 = fj1 >= N ? N - 1 : (int)fj1;
    for (int j = j0; j <= j1; j++)
        for (int i = i0; i <= i1; i++) t->need[j * N + i] = true;
}

void height_tiles_add_triangles(height_tiles *t, const float *pos, const unsigned *idx, int nidx) {
    for (int k = 0; k + 2 < nidx; k += 3) {
        const float *a = pos + 3 * idx[k], *b = pos + 3 * idx[k + 1], *c = pos + 3 * idx[k + 2];
        double lo = fmin(a[1], fmin(b[1], c[1])), hi = fmax(a[1], fmax(b[1], c[1]));
        if (hi < t->lo_y || lo > t->hi_y) continue;
        mark(t, fmin(a[0], fmin(b[0], c[0])), fmin(a[2], fmin(b[2], c[2])), fmax(a[0], fmax(b[0], c[0])),
             fmax(a[2], fmax(b[2], c[2])));
    }
}

void height_tiles_add_box(height_tiles *t, const double lo[3], const double hi[3]) {
    if (hi[1] < t->lo_y || lo[1] > t->hi_y) return;
    mark(t, lo[0], lo[2], hi[0], hi[2]);
}

int height_tiles_count(const height_tiles *t) {
    int n = 0;
    for (int k = 0; k < N * N; k++) n += t->need[k];
    return n;
}

/* Is cell (i, j) within grow cells of a needed one? */
static bool grown(const height_tiles *t, int i, int j, int grow) {
    for (int b = j - grow; b <= j + grow; b++)
        for (int a = i - grow; a <= i + grow; a++)
            if (a >= 0 && b >= 0 && a < N && b < N && t->need[b * N + a]) return true;
    return false;
}

int height_tiles_rects(const height_tiles *t, int res, float *out, int max) {
    /* a lookup at a point reads the texels whose centres are within a texel
     * of it, a texel being N / res cells: grow by that, rounded up */
    int grow = res > 0 ? (N + res - 1) / res : N;
    int n = 0;
    for (int j = 0; j < N; j++) {
        for (int i = 0; i < N;) {
            if (!grown(t, i, j, grow)) {
                i++;
                continue;
            }
            int i0 = i;
            while (i < N && grown(t, i, j, grow)) i++;
            if (n >= max) return -1;
            float *r = out + 4 * n++;
            r[0] = (float)i0 / N;
            r[1] = (float)j / N;
            r[2] = (float)i / N;
            r[3] = (float)(j + 1) / N;
        }
    }
    return n;
}
