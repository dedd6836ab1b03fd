#include "costmodel.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

double cost_model_grid_kvertices(int n) { return (double)(n + 1) * (double)(n + 1) / 1e3; }

double cost_model_predict(const cost_model *m, double mpixels, double kvertices) {
    return m->a + m->b * mpixels + m->c * kvertices;
}

/* Solves the 3x3 system A x = y by Gaussian elimination with partial
 * pivoting; false when it is singular (relative to its own scale). */
static bool solve3(double A[3][3], double y[3], double x[3]) {
    double scale = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) scale = fmax(scale, fabs(A[i][j]));
    if (!(scale > 0)) return false;
    for (int col = 0; col < 3; col++) {
        int piv = col;
        for (int r = col + 1; r < 3; r++)
            if (fabs(A[r][col]) > fabs(A[piv][col])) piv = r;
        if (fabs(A[piv][col]) < 1e-12 * scale) return false;
        if (piv != col) {
            for (int j = 0; j < 3; j++) {
                double t = A[col][j]; A[col][j] = A[piv][j]; A[piv][j] = t;
            }
            double t = y[col]; y[col] = y[piv]; y[piv] = t;
        }
        for (int r = col + 1; r < 3; r++) {
            double f = A[r][col] / A[col][col];
            for (int j = col; j < 3; j++) A[r][j] -= f * A[col][j];
            y[r] -= f * y[col];
        }
    }
    for (int r = 2; r >= 0; r--) {
        double s = y[r];
        for (int j = r + 1; j < 3; j++) s -= A[r][j] * x[j];
        x[r] = s / A[r][r];
    }
    return true;
}

static int distinct(const cost_sample *s, int n, bool pixels) {
    int count = 0;
    for (int i = 0; i < n; i++) {
        double v = pixels ? s[i].mpixels : s[i].kvertices;
        bool seen = false;
        for (int j = 0; j < i && !seen; j++) seen = fabs((pixels ? s[j].mpixels : s[j].kvertices) - v) <= 1e-9 * fabs(v);
        count += !seen;
    }
    return count;
}

bool cost_model_fit(const cost_sample *s, int n, cost_model *out, char *err, size_t errlen) {
    memset(out, 0, sizeof *out);
    if (n < 4) {
        snprintf(err, errlen, "%d timed frames; the fit needs at least 4", n);
        return false;
    }
    for (int i = 0; i < n; i++)
        if (!(isfinite(s[i].ms) && s[i].ms > 0 && isfinite(s[i].mpixels) && isfinite(s[i].kvertices))) {
            snprintf(err, errlen, "sample %d is not a finite positive time", i + 1);
            return false;
        }
    if (distinct(s, n, true) < 2 || distinct(s, n, false) < 2) {
        snprintf(err, errlen, "the samples need at least two image sizes and two meshes");
        return false;
    }
    /* normal equations of [1 p v] x = ms */
    double A[3][3] = { { 0 } }, y[3] = { 0 }, x[3];
    for (int i = 0; i < n; i++) {
        double f[3] = { 1.0, s[i].mpixels, s[i].kvertices };
        for (int r = 0; r < 3; r++) {
            y[r] += f[r] * s[i].ms;
            for (int c = 0; c < 3; c++) A[r][c] += f[r] * f[c];
        }
    }
    if (!solve3(A, y, x)) {
        snprintf(err, errlen, "the samples do not separate pixels from vertices");
        return false;
    }
    out->a = x[0];
    out->b = x[1];
    out->c = x[2];
    out->n = n;
    double mean = 0, ss_tot = 0, ss_res = 0;
    for (int i = 0; i < n; i++) mean += s[i].ms / n;
    for (int i = 0; i < n; i++) {
        double r = s[i].ms - cost_model_predict(out, s[i].mpixels, s[i].kvertices);
        ss_res += r * r;
        ss_tot += (s[i].ms - mean) * (s[i].ms - mean);
    }
    out->r2 = ss_tot > 0 ? 1.0 - ss_res / ss_tot : 1.0;
    out->rms_residual = sqrt(ss_res / n);
    return true;
}
