/* test_cmd: the command table as a user meets it: `tarn help` lists every
 * command, `tarn help X` and `tarn X --help` print X's usage (the same
 * text as the command file's cmd_X_usage), an unknown command exits 2, and
 * `tarn --version` says which tarn. No OpenGL: help never makes a context. */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "cmd.h"
#include "support.h"

static const char *bin;

/* Every command there is, with the text its file holds (NULL: help, whose
 * text lives beside the table). */
static const struct { const char *name; const char *(*usage)(void); } expected[] = {
    { "view", cmd_view_usage },           { "render", cmd_render_usage },
    { "validate", cmd_validate_usage },   { "reference", cmd_reference_usage },
    { "compare", cmd_compare_usage },     { "compare-view", cmd_compare_view_usage },
    { "bench", cmd_bench_usage },         { "assets", cmd_assets_usage },
    { "record", cmd_record_usage },       { "help", NULL },
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
    CHECK(tarn("help", out, sizeof out) == 0);
    int n = listed_names(out, names, 32);
    CHECK_MSG(n == NEXPECTED, "%d commands listed:\n%s", n, out);
    for (int i = 0; i < NEXPECTED; i++) {
        bool found = false;
        for (int k = 0; k < n; k++) found = found || strcmp(names[k], expected[i].name) == 0;
        CHECK_MSG(found, "'%s' not in `tarn help`", expected[i].name);
    }
    char again[8192];
    CHECK(tarn("--help", again, sizeof again) == 0);
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
    CHECK(tarn("frobnicate", out, sizeof out) == TARN_EXIT_USAGE);
    CHECK_STR_CONTAINS(out, "unknown command 'frobnicate'");
    CHECK_STR_CONTAINS(out, "compare-view");   /* the list, from the table */
    CHECK(tarn("help frobnicate", out, sizeof out) == TARN_EXIT_USAGE);
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
        CHECK_STR_CONTAINS(out, "no pack 'nope': the packs are ");
        CHECK_STR_CONTAINS(out, "natural");
        CHECK_STR_CONTAINS(out, "raymarch");
    }
}

static void test_version(void) {
    char out[256];
    CHECK(tarn("--version", out, sizeof out) == 0);
    int major = -1, minor = -1, patch = -1;
    CHECK_MSG(sscanf(out, "tarn %d.%d.%d", &major, &minor, &patch) == 3, "%s", out);
    CHECK(major >= 0 && minor >= 0 && patch >= 0);
}

int main(void) {
    bin = getenv("TARN_BIN");
    if (!bin) { fprintf(stderr, "run through ctest (TARN_BIN)\n"); return 1; }
    RUN(test_help_lists_every_command);
    RUN(test_help_command_prints_its_usage);
    RUN(test_unknown_command_exits_2);
    RUN(test_unknown_pack_is_a_usage_error);
    RUN(test_version);
    return check_summary();
}
