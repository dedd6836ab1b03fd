#include "world_layer_band.h"

#include <math.h>
#include <stdbool.h>

#define T LAYER_BAND_TILE

void layer_band_heights(double level, double bound, double *lo, double *hi) {
    double eps = 1e-4 * (fabs(level) + fabs(bound) + 1.0);
    *lo = level - fabs(bound) - eps;
    *hi = level + eps;
}

/* Does tile (i, j) hold a point in [lo, hi]? */
static bool tile_in_band(const float *pos, int w, int h, int i, int j, double lo, double hi) {
    int x1 = (i + 1) * T < w ? (i + 1) * T : w, y1 = (j + 1) * T < h ? (j + 1) * T : h;
    for (int y = j * T; y < y1; y++)
        for (int x = i * T; x < x1; x++) {
            const float *p = pos + 4 * ((long)y * w + x);
            if (p[3] > 0.5f && !(p[1] < lo || p[1] > hi)) return true;
        }
    return false;
}

int layer_band_rects(const float *pos, int w, int h, double lo, double hi, int *out, int max) {
    int tw = (w + T - 1) / T, th = (h + T - 1) / T, n = 0;
    for (int j = 0; j < th; j++) {
        for (int i = 0; i < tw;) {
            if (!tile_in_band(pos, w, h, i, j, lo, hi)) {
                i++;
                continue;
            }
            int i0 = i;
            while (i < tw && tile_in_band(pos, w, h, i, j, lo, hi)) i++;
            if (n >= max) return -1;
            int *r = out + 4 * n++;
            r[0] = i0 * T;
            r[1] = j * T;
            r[2] = i * T < w ? i * T : w;
            r[3] = (j + 1) * T < h ? (j + 1) * T : h;
        }
    }
    return n;
}
