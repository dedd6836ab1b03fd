#include "util.h"

#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "file.h"

#ifndef TARN_SOURCE_DIR
#define TARN_SOURCE_DIR "."
#endif
#ifndef TARN_DATA_DIR
#define TARN_DATA_DIR ""
#endif
#ifndef TARN_DATA_REL
#define TARN_DATA_REL ""   /* the data folder relative to the executable's folder */
#endif

int64_t clock_now_ns(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (int64_t)t.tv_sec * 1000000000 + t.tv_nsec;
}

double clock_now_s(void) { return (double)clock_now_ns() * 1e-9; }

uint64_t hash_fnv1a(uint64_t h, const void *data, size_t n) {
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

void clock_sleep_s(double s) {
    if (!(s > 0)) return;
    struct timespec ts = { (time_t)s, (long)((s - (double)(time_t)s) * 1e9) };
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR) {}
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

static bool has_packs(const char *dir) {
    char probe[PATH_MAX + 128];
    snprintf(probe, sizeof probe, "%s/packs", dir);
    return file_is_dir(probe);
}

/* The data folder beside the running executable (e.g. PREFIX/bin/tarn ->
 * PREFIX/share/tarn): the install's own, wherever its prefix is. */
static bool exe_data_dir(char *out) {
    char exe[PATH_MAX], dir[PATH_MAX + 64];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0 || !TARN_DATA_REL[0]) return false;
    exe[n] = '\0';
    char *slash = strrchr(exe, '/');
    if (!slash) return false;
    *slash = '\0';
    snprintf(dir, sizeof dir, "%s/%s", exe, TARN_DATA_REL);
    return has_packs(dir) && realpath(dir, out) != NULL;
}

/* The one answer, found once: tarn_root is called from any thread, and
 * readlink/realpath are not worth repeating for every scene load. The one
 * file-scope state of this module. */
static struct {
    pthread_once_t once;
    char dir[PATH_MAX];
} root_ctx = { PTHREAD_ONCE_INIT, "" };

static void root_find(void) {
    if (exe_data_dir(root_ctx.dir)) return;
    /* a build-tree tarn: the configured install when it is there, else the sources */
    const char *dir = TARN_DATA_DIR[0] && has_packs(TARN_DATA_DIR) ? TARN_DATA_DIR : TARN_SOURCE_DIR;
    snprintf(root_ctx.dir, sizeof root_ctx.dir, "%s", dir);
}

const char *tarn_root(void) {
    const char *env = getenv("TARN_ROOT");
    if (env && env[0]) return env;
    pthread_once(&root_ctx.once, root_find);
    return root_ctx.dir;
}

bool tarn_cache_dir(char *out, size_t len) {
    const char *xdg = getenv("XDG_CACHE_HOME");
    const char *home = getenv("HOME");
    int n;
    if (xdg && xdg[0] == '/') n = snprintf(out, len, "%s/tarn", xdg);   /* the spec: a relative one is ignored */
    else if (home && home[0]) n = snprintf(out, len, "%s/.cache/tarn", home);
    else return false;
    return n > 0 && (size_t)n < len;
}

int side_off_pow2(int k, int full) {
    bool pow2 = k >= 4 && (k & (k - 1)) == 0;
    return pow2 && k + 1 < full ? k + 1 : k;
}

int side_like_full(int k, int full, int min) {
    if (k < min) k = min;
    if (!(full >= 4 && (full & (full - 1)) == 0)) return side_off_pow2(k, full);
    int p = 1;
    while (p < k && p < full) p <<= 1;               /* the power of two at or above k */
    if (p > 1 && (double)k * k < (double)p * p / 2) p >>= 1;   /* nearer below, in ratio */
    while (p < min && p < full) p <<= 1;
    return p;
}
