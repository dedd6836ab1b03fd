/* A burst of saves while the renderer reloads (issue #17): a writer
 * saves whole, valid versions of a shader the way `cat > file` does
 * (truncate, then write; here in two write() calls with a pause between,
 * as a larger file or a slow editor writes), over and over, while the
 * reader assembles or reloads it. Every version written is valid, so no
 * read may see a text that no version had, and no reload may report an
 * error (before the reads settled, 6 of 12 bursts of 10 saves showed
 * `water.frag:0: error: syntax error, unexpected end of file`). */
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "check.h"
#include "support.h"
#include "file.h"
#include "gl_ctx.h"
#include "gl_support.h"
#include "render.h"
#include "shader_src.h"

#define BURST_S 1.2          /* how long the writer saves */
#define SAVE_GAP_US 45000    /* between two saves: 20 a second, a burst faster than a hand's */
#define HALF_GAP_US 4000     /* between the two halves of one save */

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void sleep_us(long us) {
    struct timespec ts = { us / 1000000, (us % 1000000) * 1000 };
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR) {}
}

/* Version v of a valid fragment shader, a few KB long (so that a save in
 * two halves leaves a half that does not compile), ending in a marker. */
static void version_text(int v, char *out, size_t n) {
    int k = snprintf(out, n, "#version 330 compatibility\nuniform vec4 uColor;\nout vec4 fragColor;\n");
    for (int i = 0; i < 60; i++)
        k += snprintf(out + k, n - (size_t)k, "float f%d(float x) { return x * %d.0 + %d.0; }\n", i, i + v, v);
    snprintf(out + k, n - (size_t)k, "void main() { fragColor = uColor + vec4(f%d(0.0) * 0.0); }\n// end of version %d\n",
             v % 60, v);
}

/* The writer: a child that saves versions 0, 1, 2, ... until killed. */
static pid_t start_writer(const char *path) {
    pid_t pid = fork();
    if (pid != 0) return pid;
    static char text[8192];
    for (int v = 0;; v = (v + 1) % 7) {
        version_text(v, text, sizeof text);
        size_t n = strlen(text), half = n / 2;
        int fd = open(path, O_WRONLY | O_TRUNC | O_CREAT, 0644);
        if (fd < 0) _exit(1);
        if (write(fd, text, half) != (ssize_t)half) _exit(1);
        sleep_us(HALF_GAP_US);
        if (write(fd, text + half, n - half) != (ssize_t)(n - half)) _exit(1);
        close(fd);
        sleep_us(SAVE_GAP_US);
    }
}

static void stop_writer(pid_t pid) {
    kill(pid, SIGKILL);
    waitpid(pid, NULL, 0);
}

/* Is text one of the versions, whole? */
static bool is_a_version(const char *text) {
    static char want[8192];
    for (int v = 0; v < 7; v++) {
        version_text(v, want, sizeof want);
        if (text && strcmp(text, want) == 0) return true;
    }
    return false;
}

static void test_file_reads_are_whole_saves(void) {
    char first[8192];
    version_text(0, first, sizeof first);
    scratch_write("raw.frag", first);
    pid_t w = start_writer(scratch_path("raw.frag"));
    int reads = 0, torn = 0;
    for (double end = now_s() + BURST_S; now_s() < end; reads++) {
        char err[256];
        file_text_opts o = { .max_bytes = 1 << 20, .settle = true };
        char *text = file_read_text(scratch_path("raw.frag"), &o, NULL, err, sizeof err);
        if (!is_a_version(text)) {
            if (torn++ == 0) fprintf(stderr, "  torn read: %zu bytes\n", text ? strlen(text) : 0);
        }
        free(text);
        sleep_us(700);
    }
    stop_writer(w);
    fprintf(stderr, "  %d reads, %d torn (the writer's close %s)\n", reads, torn,
            file_writer_holds(scratch_path("raw.frag")) >= 0 ? "asked by a lease" : "unknown here: the age rule");
    CHECK_GE(reads, 20);
    CHECK_MSG(torn == 0, "%d of %d reads saw a text no save had", torn, reads);
}

static void test_stage_assembly_reads_whole_saves(void) {
    char first[8192];
    version_text(0, first, sizeof first);
    scratch_write("stage.frag", first);
    pid_t w = start_writer(scratch_path("stage.frag"));
    int loads = 0, bad = 0;
    for (double end = now_s() + BURST_S; now_s() < end; loads++) {
        shader_src s;
        shader_src_desc d = { .path = scratch_path("stage.frag"), .stage = SHADER_FRAGMENT };
        bool ok = shader_src_load(&d, &s);
        /* the assembled text ends with the file's own last line */
        if (!ok || !s.text || !strstr(s.text, "// end of version")) bad++;
        shader_src_free(&s);
        sleep_us(700);
    }
    stop_writer(w);
    fprintf(stderr, "  %d loads, %d incomplete\n", loads, bad);
    CHECK_GE(loads, 20);
    CHECK_MSG(bad == 0, "%d of %d stage loads were not a whole save", bad, loads);
}

/* A writer child tells the reader when its first step is on disk
 * (a byte down a pipe), so the reader's timing does not rest on how soon
 * a loaded machine runs the child. */
static bool step_done(int fd) {
    return write(fd, "s", 1) == 1;
}

static bool wait_step(int fd) {
    char c;
    return read(fd, &c, 1) == 1;
}

/* The writer's close is asked of the file itself: held open for writing
 * (by another process, as an editor would) it is "held", once closed not,
 * and a reader's own open is no writer. */
static void test_writer_holds_while_open(void) {
    scratch_write("held.frag", "void main() {}\n");
    const char *path = scratch_path("held.frag");
    if (file_writer_holds(path) < 0) {
        SKIP("this filesystem or user cannot take a read lease: the age rule alone applies\n");
        return;
    }
    int reader = open(path, O_RDONLY);
    CHECK_EQ(file_writer_holds(path), 0);
    int opened[2], go[2];   /* one pipe each way: a child reading its own byte would hang the test */
    CHECK_EQ(pipe(opened), 0);
    CHECK_EQ(pipe(go), 0);
    pid_t pid = fork();
    if (pid == 0) {   /* holds the file open for writing until told */
        int fd = open(path, O_WRONLY | O_APPEND);
        if (fd < 0) _exit(1);
        if (!step_done(opened[1])) _exit(1);
        if (!wait_step(go[0])) _exit(1);
        close(fd);
        _exit(0);
    }
    CHECK(wait_step(opened[0]));   /* the writer has it open */
    CHECK_EQ(file_writer_holds(path), 1);
    CHECK(step_done(go[1]));
    waitpid(pid, NULL, 0);
    CHECK_EQ(file_writer_holds(path), 0);
    close(reader);
    for (int i = 0; i < 2; i++) {
        close(opened[i]);
        close(go[i]);
    }
}

/* A settled read of path, begun now, gives the whole text the writer
 * child pid saves, and the child wrote it all; the child's step pipe is
 * closed after. */
static void read_is_the_save(const char *path, const char *text, pid_t pid, int step[2]) {
    char why[256];
    file_text_opts o = { .max_bytes = 1 << 20, .settle = true };
    char *got = file_read_text(path, &o, NULL, why, sizeof why);
    int status = 0;
    waitpid(pid, &status, 0);
    CHECK_EQ(WEXITSTATUS(status), 0);
    CHECK_MSG(got && strcmp(got, text) == 0, "read %zu bytes of a %zu-byte save", got ? strlen(got) : 0,
              strlen(text));
    free(got);
    close(step[0]);
    close(step[1]);
}

/* A save stalled mid-write (half written, a pause longer than any fixed
 * settle time, then the rest): a read begun during the pause, when the
 * half is FILE_SETTLE_MS and more old, waits for the writer's close and
 * gets the whole save, not the half. */
static void test_stalled_save_is_read_whole(void) {
    char text[8192];
    version_text(3, text, sizeof text);
    scratch_write("stall.frag", "");
    const char *path = scratch_path("stall.frag");
    if (file_writer_holds(path) < 0) {
        SKIP("this filesystem or user cannot take a read lease: a stall past FILE_SETTLE_MS reads the half\n");
        return;
    }
    int step[2];
    CHECK_EQ(pipe(step), 0);
    pid_t pid = fork();
    if (pid == 0) {
        size_t n = strlen(text), half = n / 2;
        int fd = open(path, O_WRONLY | O_TRUNC);
        if (fd < 0 || write(fd, text, half) != (ssize_t)half) _exit(1);
        if (!step_done(step[1])) _exit(1);
        sleep_us(100000);   /* over three times FILE_SETTLE_MS; well within FILE_SETTLE_MAX_MS */
        if (write(fd, text + half, n - half) != (ssize_t)(n - half)) _exit(1);
        close(fd);
        _exit(0);
    }
    CHECK(wait_step(step[0]));
    sleep_us(40000);        /* the half is on disk, 40 ms old: the age rule alone would take it */
    read_is_the_save(path, text, pid, step);
}

/* A writer that empties the file by its path, then opens it to write the
 * new text (no writer holds it in between): a read begun while it is
 * empty waits for the text, not takes the empty file. */
static void test_emptied_then_written_is_read_whole(void) {
    char text[8192];
    version_text(5, text, sizeof text);
    scratch_write("trunc.frag", "// an older version\n");
    const char *path = scratch_path("trunc.frag");
    int step[2];
    CHECK_EQ(pipe(step), 0);
    pid_t pid = fork();
    if (pid == 0) {
        if (truncate(path, 0) != 0) _exit(1);
        if (!step_done(step[1])) _exit(1);
        sleep_us(20000);    /* well within FILE_EMPTY_WAIT_MS */
        int fd = open(path, O_WRONLY);
        size_t n = strlen(text);
        if (fd < 0 || write(fd, text, n) != (ssize_t)n) _exit(1);
        close(fd);
        _exit(0);
    }
    CHECK(wait_step(step[0]));   /* emptied, no writer holding it */
    read_is_the_save(path, text, pid, step);
}

/* The viewer's reload in a burst: no reload reports an error. */
static void test_reloads_in_a_burst_report_no_error(void) {
    char first[8192];
    version_text(0, first, sizeof first);
    scratch_write("water.frag", first);
    scratch_write("flat.vert", "#version 330 compatibility\n"
                               "void main() { gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; }\n");
    scratch_write("lake.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex flat.vert\nFragment water.frag\n"
                               "Program Water uColor {0.2 0.4 0.6 1.}\nQuadXY 0 1 1 1\n");
    render *r = gl_test_load_scratch("lake.glib");
    pid_t w = start_writer(scratch_path("water.frag"));
    int loads = 0, failed = 0;
    for (double end = now_s() + BURST_S; now_s() < end; loads++) {
        if (!render_load(r, NULL) || render_messages(r)[0]) {
            if (failed++ == 0) fprintf(stderr, "  first failed reload:\n%s", render_messages(r));
        }
        sleep_us(700);
    }
    stop_writer(w);
    fprintf(stderr, "  %d reloads, %d reported something\n", loads, failed);
    CHECK_GE(loads, 10);
    CHECK_MSG(failed == 0, "%d of %d reloads reported an error no save had", failed, loads);
    render_destroy(r);
}

int main(void) {
    if (!scratch_create("reload-race")) return 1;
    RUN(test_file_reads_are_whole_saves);
    RUN(test_stage_assembly_reads_whole_saves);
    RUN(test_writer_holds_while_open);
    RUN(test_stalled_save_is_read_whole);
    RUN(test_emptied_then_written_is_read_whole);
    char err[512];
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    if (ctx) {
        RUN(test_reloads_in_a_burst_report_no_error);
        gl_ctx_destroy(ctx);
    } else {
        fprintf(stderr, "skip the GL case: %s\n", err);
    }
    scratch_remove();
    return check_summary();
}
