#include "util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "file.h"

#ifndef TARN_SOURCE_DIR
#define TARN_SOURCE_DIR "."
#endif
#ifndef TARN_DATA_DIR
#define TARN_DATA_DIR ""
#endif

double clock_now_s(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int cmp_str_ptr(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

double median_double(double *v, size_t n) {
    if (n == 0) return 0;
    qsort(v, n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

bool opt_size(const char *s, int *w, int *h) {
    char x, extra; /* extra: "640x360junk" is not a size */
    return s && sscanf(s, "%d%c%d%c", w, &x, h, &extra) == 3 && (x == 'x' || x == 'X') && *w > 0 && *h > 0 &&
           *w <= 16384 && *h <= 16384;
}

bool opt_double(const char *s, double *out) {
    char *end;
    if (!s) return false;
    *out = strtod(s, &end);
    return end != s && *end == '\0';
}

bool opt_is_help(const char *a) { return a && (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0); }

const char *tarn_root(void) {
    const char *env = getenv("TARN_ROOT");
    if (env && env[0]) return env;
    /* an installed tarn: TARN_DATA_DIR holds packs/ (the source tree may be gone) */
    static const char data[] = TARN_DATA_DIR;
    char probe[4096];
    if (data[0]) {
        snprintf(probe, sizeof probe, "%s/packs", data);
        if (file_is_dir(probe)) return data;
    }
    return TARN_SOURCE_DIR;
}
