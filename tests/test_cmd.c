/* test_cmd: the command table as a user meets it: `tarn help` lists every
 * command, `tarn help X` and `tarn X --help` print X's usage (the same
 * text as the command file's cmd_X_usage), an unknown command exits 2, and
 * `tarn --version` says which tarn. No OpenGL: help never makes a context. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "cmd.h"
#include "image_io.h"
#include "support.h"

static const char *bin;

/* Every command there is, with the text its file holds (NULL: help, whose
 * text lives beside the table). */
static const struct { const char *name; const char *(*usage)(void); } expected[] = {
    { "view", cmd_view_usage },           { "render", cmd_render_usage },
    { "validate", cmd_validate_usage },   { "reference", cmd_reference_usage },
    { "compare", cmd_compare_usage },     { "compare-view", cmd_compare_view_usage },
    { "bench", cmd_bench_usage },         { "assets", cmd_assets_usage },
    { "record", cmd_record_usage },       { "sheet", cmd_sheet_usage },
    { "help", NULL },
};
enum { NEXPECTED = sizeof expected / sizeof expected[0] };

static int tarn(const char *args, char *out, size_t outlen) {
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "%s %s 2>&1", bin, args);
    return run_command(cmd, out, outlen);
}

/* The names in the "commands:" block of `tarn help` (first word of each
 * line up to the blank line). */
static int listed_names(const char *out, char names[][32], int max) {
    const char *p = strstr(out, "commands:\n");
    int n = 0;
    if (!p) return 0;
    for (p = strchr(p, '\n') + 1; *p == ' ' && n < max; p = strchr(p, '\n') + 1) {
        while (*p == ' ') p++;
        int len = 0;
        while (p[len] && !isspace((unsigned char)p[len]) && len < 31) len++;
        memcpy(names[n], p, (size_t)len);
        names[n++][len] = '\0';
        if (!strchr(p, '\n')) break;
    }
    return n;
}

static void test_help_lists_every_command(void) {
    char out[8192], names[32][32];
    CHECK_EQ(tarn("help", out, sizeof out), 0);
    int n = listed_names(out, names, 32);
    CHECK_MSG(n == NEXPECTED, "%d commands listed:\n%s", n, out);
    for (int i = 0; i < NEXPECTED; i++) {
        bool found = false;
        for (int k = 0; k < n; k++) found = found || strcmp(names[k], expected[i].name) == 0;
        CHECK_MSG(found, "'%s' not in `tarn help`", expected[i].name);
    }
    char again[8192];
    CHECK_EQ(tarn("--help", again, sizeof again), 0);
    CHECK_MSG(strcmp(again, out) == 0, "`tarn --help` differs from `tarn help`:\n%s", again);
}

static void test_help_command_prints_its_usage(void) {
    for (int i = 0; i < NEXPECTED; i++) {
        char args[128], via_help[16384], via_flag[16384], want[64];
        snprintf(args, sizeof args, "help %s", expected[i].name);
        CHECK_MSG(tarn(args, via_help, sizeof via_help) == 0, "%s", args);
        snprintf(want, sizeof want, "usage: tarn %s", expected[i].name);
        CHECK_MSG(strncmp(via_help, want, strlen(want)) == 0, "`tarn %s` begins:\n%.200s", args, via_help);
        if (expected[i].usage)
            CHECK_MSG(strcmp(via_help, expected[i].usage()) == 0, "`tarn %s` is not cmd_%s_usage()", args,
                      expected[i].name);
        snprintf(args, sizeof args, "%s --help", expected[i].name);
        CHECK_MSG(tarn(args, via_flag, sizeof via_flag) == 0, "%s", args);
        CHECK_MSG(strcmp(via_flag, via_help) == 0, "`tarn %s` differs from `tarn help %s`", args, expected[i].name);
    }
}

static void test_unknown_command_exits_2(void) {
    char out[8192];
    CHECK_EQ(tarn("frobnicate", out, sizeof out), TARN_EXIT_USAGE);
    CHECK_STR_CONTAINS(out, "unknown command 'frobnicate'");
    CHECK_STR_CONTAINS(out, "compare-view");   /* the list, from the table */
    CHECK_EQ(tarn("help frobnicate", out, sizeof out), TARN_EXIT_USAGE);
    CHECK_STR_CONTAINS(out, "unknown command 'frobnicate'");
}

/* A pack that does not exist is a usage error naming the packs, before
 * any window opens or scene loads (issue #30: it was an error at the
 * scene's Pack line, and the window opened anyway). */
static void test_unknown_pack_is_a_usage_error(void) {
    char out[8192];
    const char *cases[] = { "view scenes/lake.glib --pack nope", "render scenes/lake.glib --pack nope -o x.png",
                            "compare-view scenes/lake.glib --packs natural,nope" };
    for (int i = 0; i < 3; i++) {
        CHECK_MSG(tarn(cases[i], out, sizeof out) == TARN_EXIT_USAGE, "tarn %s: %s", cases[i], out);
        CHECK_STR_CONTAINS(out, "no pack 'nope' in ");
        CHECK_STR_CONTAINS(out, "/packs: the packs are ");
        CHECK_STR_CONTAINS(out, "natural");
        CHECK_STR_CONTAINS(out, "raymarch");
    }
}

static void test_version(void) {
    char out[256];
    CHECK_EQ(tarn("--version", out, sizeof out), 0);
    int major = -1, minor = -1, patch = -1;
    CHECK_MSG(sscanf(out, "tarn %d.%d.%d", &major, &minor, &patch) == 3, "%s", out);
    CHECK(major >= 0 && minor >= 0 && patch >= 0);
}

/* tarn sheet: a 3 x 2 sheet of a uniform pair is 6 tiles, found in the
 * image as the non-paper rectangles of the tile size, each different from
 * the others as the values differ; a uniform the scene lacks stops it with
 * the name (exit 2). The one test here that draws: skipped without GL. */
static void test_sheet(void) {
    if (!scratch_create("sheet")) return;
    scratch_write("s.vert", "#version 120\nvarying vec2 vST;\n"
                            "void main() { vST = gl_MultiTexCoord0.st; gl_Position = ftransform(); }\n");
    scratch_write("s.frag", "#version 120\nuniform float uFreq;\nuniform float uShift;\nvarying vec2 vST;\n"
                            "void main() { float s = step(0.5, fract(vST.s * uFreq));\n"
                            "  gl_FragColor = vec4(s, uShift, 1. - s, 1.); }\n");
    scratch_write("s.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex s.vert\nFragment s.frag\n"
                            "Program Stripes uFreq <1. 2. 10.> uShift <0. 0. 1.>\nQuadXY 0 1 1 1\n");
    char args[2048], out[8192];
    snprintf(args, sizeof args, "sheet %s --vary Stripes.uFreq=1:9:3 --vary uShift=0:1:2 --size 48x32 -o %s",
             scratch_path("s.glib"), scratch_path("sheet.png"));
    int rc = tarn(args, out, sizeof out);
    if (rc == TARN_EXIT_NO_GL) { fprintf(stderr, "skip: no OpenGL: %s", out); scratch_remove(); return; }
    CHECK_MSG(rc == 0, "tarn %s: %s", args, out);
    img im;
    char err[512];
    CHECK_MSG(img_read(scratch_path("sheet.png"), &im, err, sizeof err), "%s", err);
    enum { TW = 48, TH = 32 };
    int ch = im.channels, tx[8], ty[8], n = 0;
    #define PX(x, y) (im.px + ((size_t)(y) * im.w + (x)) * ch)
    #define PAPER(x, y) ((x) < 0 || (y) < 0 || (PX(x, y)[0] > 0.99f && PX(x, y)[1] > 0.99f && PX(x, y)[2] > 0.99f))
    for (int y = 0; y + TH <= im.h && n < 8; y++)
        for (int x = 0; x + TW <= im.w && n < 8; x++) {
            if (PAPER(x, y) || !PAPER(x - 1, y) || !PAPER(x, y - 1)) continue;
            bool full = PAPER(x + TW, y) && PAPER(x, y + TH);
            for (int k = 0; k < TW && full; k++) full = !PAPER(x + k, y) && !PAPER(x + k, y + TH - 1);
            for (int k = 0; k < TH && full; k++) full = !PAPER(x, y + k) && !PAPER(x + TW - 1, y + k);
            if (full) { tx[n] = x; ty[n] = y; n++; }
        }
    CHECK_MSG(n == 6, "%d tiles of 48x32 in the %dx%d sheet", n, im.w, im.h);
    int same = 0;
    for (int a = 0; a < n; a++)
        for (int b = a + 1; b < n; b++) {
            double diff = 0;
            for (int y = 0; y < TH; y++)
                for (int x = 0; x < TW; x++)
                    for (int c = 0; c < 3; c++) diff += fabs(PX(tx[a] + x, ty[a] + y)[c] - PX(tx[b] + x, ty[b] + y)[c]);
            same += diff / (TW * TH) < 0.05;
        }
    CHECK_MSG(same == 0, "%d pairs of tiles alike", same);
    /* the labels: ink below each tile */
    int labelled = 0;
    for (int t = 0; t < n; t++) {
        int ink = 0;
        for (int y = ty[t] + TH; y < ty[t] + TH + 24 && y < im.h; y++)
            for (int x = tx[t]; x < tx[t] + TW; x++) ink += PX(x, y)[0] < 0.2f && PX(x, y)[1] < 0.2f && PX(x, y)[2] < 0.2f;
        labelled += ink > 20;
    }
    CHECK_MSG(labelled == n, "%d of %d tiles labelled", labelled, n);
    #undef PAPER
    #undef PX
    img_free(&im);
    snprintf(args, sizeof args, "sheet %s --vary Stripes.uNope=1:9:3 -o %s", scratch_path("s.glib"),
             scratch_path("x.png"));
    CHECK_EQ(tarn(args, out, sizeof out), TARN_EXIT_USAGE);
    CHECK_STR_CONTAINS(out, "uNope");
    snprintf(args, sizeof args, "sheet %s --vary Stripes.uFreq=1:9 -o %s", scratch_path("s.glib"),
             scratch_path("x.png"));
    CHECK_EQ(tarn(args, out, sizeof out), TARN_EXIT_USAGE);
    CHECK_STR_CONTAINS(out, "--vary wants PROGRAM.NAME=A:B:N");
    scratch_remove();
}

int main(void) {
    bin = getenv("TARN_BIN");
    if (!bin) { fprintf(stderr, "run through ctest (TARN_BIN)\n"); return 1; }
    RUN(test_help_lists_every_command);
    RUN(test_help_command_prints_its_usage);
    RUN(test_unknown_command_exits_2);
    RUN(test_unknown_pack_is_a_usage_error);
    RUN(test_version);
    RUN(test_sheet);
    return check_summary();
}
