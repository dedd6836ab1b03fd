/* When OpenGL cannot start, or its context is lost, tarn ends with exit
 * code 3 and a message that says what is missing and how to install it.
 *
 * The failed starts are made real with the environment variables that
 * libglvnd and Mesa read: __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent (no
 * EGL vendor library: as if libegl-mesa0 were not installed),
 * LIBGL_DRIVERS_PATH=/nonexistent (EGL loads, the driver does not: as if
 * libgl1-mesa-dri were missing) and MESA_GL_VERSION_OVERRIDE=3.3COMPAT (a
 * driver too old for OpenGL 4.5). A lost context cannot be caused on
 * purpose, so TARN_SIMULATE_CONTEXT_LOSS=N makes gl_ctx_lost() report one
 * after N frames (gl_ctx.h); the real check, glGetGraphicsResetStatus on a
 * context made with reset notification, is asked in-process too. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "check.h"
#include "gl_ctx.h"

static const char *bin, *src;
static char dir[256];
static char out[16384];

/* Runs `env ENV tarn ARGS` with stderr and stdout in out; the exit code. */
static int run_tarn(const char *env, const char *args) {
    char log[512], cmd[4096];
    snprintf(log, sizeof log, "%s/out.txt", dir);
    snprintf(cmd, sizeof cmd, "env %s '%s' %s > '%s' 2>&1", env, bin, args, log);
    int st = system(cmd);
    out[0] = '\0';
    FILE *f = fopen(log, "r");
    if (f) {
        size_t n = fread(out, 1, sizeof out - 1, f);
        out[n] = '\0';
        fclose(f);
    }
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static bool exists(const char *path) {
    struct stat st;
    return stat(path, &st) == 0;
}

static char scene[1024];

static void render_args(char *args, size_t len, const char *png, const char *more) {
    snprintf(args, len, "render '%s' -o '%s/%s' --size 64x48 %s", scene, dir, png, more);
}

static void test_no_egl_vendor(void) {
    char args[2048];
    render_args(args, sizeof args, "a.png", "");
    int rc = run_tarn("__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent", args);
    fprintf(stderr, "  exit %d: %s", rc, out);
    CHECK_EQ(rc, 3);
    CHECK_STR_CONTAINS(out, "no EGL driver was found");
    CHECK_STR_CONTAINS(out, "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent");   /* the likely culprit, named */
    CHECK_STR_CONTAINS(out, "apt-get install");
    CHECK_STR_CONTAINS(out, "libegl-mesa0");
    CHECK(!exists("a.png"));
}

static void test_no_driver(void) {
    char args[2048];
    render_args(args, sizeof args, "b.png", "");
    int rc = run_tarn("LIBGL_DRIVERS_PATH=/nonexistent", args);
    if (rc == 0) SKIP("the EGL driver here is not Mesa's (LIBGL_DRIVERS_PATH changes nothing)");
    fprintf(stderr, "  exit %d: %s", rc, out);
    CHECK_EQ(rc, 3);
    CHECK_STR_CONTAINS(out, "could not load an OpenGL driver");
    CHECK_STR_CONTAINS(out, "libgl1-mesa-dri");
    CHECK_STR_CONTAINS(out, "apt-get install");
}

static void test_driver_too_old(void) {
    char args[2048];
    render_args(args, sizeof args, "c.png", "");
    int rc = run_tarn("MESA_GL_VERSION_OVERRIDE=3.3COMPAT", args);
    if (rc == 0) SKIP("the driver here is not Mesa's (MESA_GL_VERSION_OVERRIDE changes nothing)");
    fprintf(stderr, "  exit %d: %s", rc, out);
    CHECK_EQ(rc, 3);
    CHECK_STR_CONTAINS(out, "no OpenGL 4.5 compatibility-profile context");
    CHECK_STR_CONTAINS(out, "apt-get install");
}

/* Lost before the first frame is written: exit 3, no file. Lost at the
 * third of five frames: the two finished frames are written, then exit 3. */
static void test_context_lost(void) {
    char args[2048];
    render_args(args, sizeof args, "lost.png", "");
    int rc = run_tarn("TARN_SIMULATE_CONTEXT_LOSS=0", args);
    fprintf(stderr, "  exit %d: %s", rc, out);
    if (rc == 3 && strstr(out, "cannot start OpenGL")) SKIP("no OpenGL here at all");
    CHECK_EQ(rc, 3);
    CHECK_STR_CONTAINS(out, "the OpenGL context was lost");
    CHECK_STR_CONTAINS(out, "start tarn again");
    CHECK_STR_CONTAINS(out, "apt-get install --reinstall");
    char path[600];
    snprintf(path, sizeof path, "%s/lost.png", dir);
    CHECK(!exists(path));

    render_args(args, sizeof args, "f%d.png", "--frames 5");
    rc = run_tarn("TARN_SIMULATE_CONTEXT_LOSS=2", args);
    CHECK_EQ(rc, 3);
    CHECK_STR_CONTAINS(out, "the OpenGL context was lost");
    for (int f = 0; f < 5; f++) {
        snprintf(path, sizeof path, "%s/f%04d.png", dir, f);
        CHECK_MSG(exists(path) == (f < 2), "frame %d %s", f, f < 2 ? "is missing" : "was written after the loss");
    }
}

/* A healthy context reports no loss, frame after frame. */
static void test_healthy_context_is_not_lost(void) {
    char err[1024];
    gl_ctx *c = gl_ctx_create_headless(err, sizeof err);
    if (!c) SKIP("%s", err);
    for (int i = 0; i < 3; i++) CHECK_MSG(!gl_ctx_lost(c, err, sizeof err), "%s", err);
    gl_ctx_destroy(c);
}

int main(void) {
    bin = getenv("TARN_BIN");
    src = getenv("TARN_SOURCE_DIR");
    if (!bin || !bin[0] || !src || !src[0]) {
        fprintf(stderr, "skip: TARN_BIN and TARN_SOURCE_DIR are not set (run through ctest)\n");
        return 77;
    }
    if (getenv("TARN_SIMULATE_CONTEXT_LOSS")) unsetenv("TARN_SIMULATE_CONTEXT_LOSS");
    snprintf(scene, sizeof scene, "%s/tests/data/window/scene.glib", src);
    snprintf(dir, sizeof dir, "/tmp/tarn-test-glctx-XXXXXX");
    if (!mkdtemp(dir)) return 1;
    if (chdir(dir) != 0) return 1;
    RUN(test_no_egl_vendor);
    RUN(test_no_driver);
    RUN(test_driver_too_old);
    RUN(test_context_lost);
    RUN(test_healthy_context_is_not_lost);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
    return check_summary();
}
