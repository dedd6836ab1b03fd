/* tests/support.h: what several tests need (header-only, one include per
 * test program): a scratch directory under /tmp with the files a test
 * writes there; the shader fixtures of tests/data/shaders; running a
 * command line; counting a needle in a text.
 *
 *     if (!scratch_create("render")) return 1;   // /tmp/tarn-test-render-XXXXXX
 *     scratch_write("a.glib", "##OpenGL GLIB\n...");
 *     render_load(r, scratch_path("a.glib"));
 *     scratch_remove();
 */
#ifndef TARN_TEST_SUPPORT_H
#define TARN_TEST_SUPPORT_H

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static char scratch_dir[256];

static inline bool scratch_create(const char *name) {
    snprintf(scratch_dir, sizeof scratch_dir, "/tmp/tarn-test-%s-XXXXXX", name);
    if (mkdtemp(scratch_dir)) return true;
    perror(scratch_dir);
    return false;
}

/* The path of name in the scratch directory; a ring of 8 buffers, so a
 * call may take several paths at once. */
static inline const char *scratch_path(const char *name) {
    static char buf[8][512];
    static int i;
    i = (i + 1) % 8;
    snprintf(buf[i], sizeof buf[i], "%s/%s", scratch_dir, name);
    return buf[i];
}

/* Writes text to name; a test that cannot write its files cannot run. */
static inline void scratch_write(const char *name, const char *text) {
    FILE *f = fopen(scratch_path(name), "w");
    if (!f) { perror(name); exit(1); }
    fputs(text, f);
    fclose(f);
}

/* Dates name's modification back by age_s seconds: a file saved a while
 * ago, which a file cache may answer for from memory (file_cache.h). */
static inline bool scratch_age(const char *name, double age_s) {
    struct timespec now, t[2];
    clock_gettime(CLOCK_REALTIME, &now);
    long long ns = (long long)now.tv_sec * 1000000000LL + now.tv_nsec - (long long)(age_s * 1e9);
    t[0] = t[1] = (struct timespec){ .tv_sec = (time_t)(ns / 1000000000LL), .tv_nsec = (long)(ns % 1000000000LL) };
    return utimensat(AT_FDCWD, scratch_path(name), t, 0) == 0;
}

static inline void scratch_remove(void) {
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", scratch_dir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", scratch_dir);
}

/* How many times needle occurs in hay, not overlapping. */
static inline int count_of(const char *hay, const char *needle) {
    int n = 0;
    for (const char *p = hay; (p = strstr(p, needle)) != NULL; p += strlen(needle)) n++;
    return n;
}

/* tests/data/shaders/NAME, under $TARN_SOURCE_DIR (ctest sets it) or the
 * source tree the test was built from; a ring of 8 buffers. */
static inline const char *shader_data(const char *name) {
    static char buf[8][1200];
    static int i;
    const char *root = getenv("TARN_SOURCE_DIR");
    if (!root || !root[0]) root = TARN_SOURCE_DIR;
    i = (i + 1) % 8;
    snprintf(buf[i], sizeof buf[i], "%s/tests/data/shaders/%s", root, name);
    return buf[i];
}

/* Runs a shell command line; returns its exit status (-1 if it did not
 * exit), its output (cut to outlen - 1 bytes) in out. */
static inline int run_command(const char *cmdline, char *out, size_t outlen) {
    FILE *p = popen(cmdline, "r");
    if (!p) return -1;
    size_t n = fread(out, 1, outlen - 1, p);
    out[n] = '\0';
    int st = pclose(p);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

#endif
