/* fuzz_util.h: what the fuzz targets share (a scratch directory of fixture
 * files that the fuzzed text may name). Header-only: each target is one
 * translation unit, built either with libFuzzer (TARN_FUZZ) or with
 * replay_main.c, which replays corpus files in a normal ctest test. */
#ifndef TARN_FUZZ_UTIL_H
#define TARN_FUZZ_UTIL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* A per-process scratch directory, removed at exit. */
static char fuzz_dir[256];

static inline void fuzz_rm_dir(void) {
    if (!fuzz_dir[0]) return;
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", fuzz_dir);
    if (system(cmd) != 0) fprintf(stderr, "fuzz: could not remove %s\n", fuzz_dir);
}

static inline const char *fuzz_scratch(const char *prefix) {
    if (fuzz_dir[0]) return fuzz_dir;
    const char *tmp = getenv("TMPDIR");
    snprintf(fuzz_dir, sizeof fuzz_dir, "%s/%s-XXXXXX", tmp && tmp[0] ? tmp : "/tmp", prefix);
    if (!mkdtemp(fuzz_dir)) { perror(fuzz_dir); abort(); }
    atexit(fuzz_rm_dir);
    return fuzz_dir;
}

/* dir/name, in one of a few rotating static buffers. */
static inline const char *fuzz_path(const char *name) {
    static char buf[8][512];
    static int i;
    i = (i + 1) % 8;
    snprintf(buf[i], sizeof buf[i], "%s/%s", fuzz_dir, name);
    return buf[i];
}

static inline void fuzz_write(const char *name, const void *data, size_t n) {
    const char *path = fuzz_path(name);
    FILE *f = fopen(path, "wb");
    if (!f) { perror(path); abort(); }
    if (n && fwrite(data, 1, n, f) != n) { perror(path); abort(); }
    fclose(f);
    /* a second old: a file modified under FILE_SETTLE_MS ago may be a save
     * still going on, and the readers wait that out (each run would) */
    struct timespec now, ts[2];
    clock_gettime(CLOCK_REALTIME, &now);
    ts[0] = ts[1] = (struct timespec){ now.tv_sec - 1, now.tv_nsec };
    if (utimensat(AT_FDCWD, path, ts, 0) != 0) { perror(path); abort(); }
}

static inline void fuzz_write_text(const char *name, const char *text) { fuzz_write(name, text, strlen(text)); }

static inline void fuzz_mkdir(const char *name) {
    const char *path = fuzz_path(name);
    if (mkdir(path, 0755) != 0) { perror(path); abort(); }
}

#endif
