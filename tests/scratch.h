/* tests/scratch.h: a test's scratch directory under /tmp, the files it
 * writes there, and its removal (header-only, one per test program).
 *
 *     if (!scratch_create("render")) return 1;   // /tmp/tarn-test-render-XXXXXX
 *     scratch_write("a.glib", "##OpenGL GLIB\n...");
 *     render_load(r, scratch_path("a.glib"));
 *     scratch_remove();
 */
#ifndef TARN_TEST_SCRATCH_H
#define TARN_TEST_SCRATCH_H

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

static char scratch_dir[256];

static bool scratch_create(const char *name) {
    snprintf(scratch_dir, sizeof scratch_dir, "/tmp/tarn-test-%s-XXXXXX", name);
    if (mkdtemp(scratch_dir)) return true;
    perror(scratch_dir);
    return false;
}

/* The path of name in the scratch directory; a ring of 8 buffers, so a
 * call may take several paths at once. */
static const char *scratch_path(const char *name) {
    static char buf[8][512];
    static int i;
    i = (i + 1) % 8;
    snprintf(buf[i], sizeof buf[i], "%s/%s", scratch_dir, name);
    return buf[i];
}

/* Writes text to name; a test that cannot write its files cannot run. */
static void scratch_write(const char *name, const char *text) {
    FILE *f = fopen(scratch_path(name), "w");
    if (!f) { perror(name); exit(1); }
    fputs(text, f);
    fclose(f);
}

static void scratch_remove(void) {
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", scratch_dir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", scratch_dir);
}

#endif
