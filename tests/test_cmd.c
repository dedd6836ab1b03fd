/* test_cmd: the command table as a user meets it: `tarn help` lists every
 * command, `tarn help X` and `tarn X --help` print X's usage (the same
 * text as the command file's cmd_X_usage), an unknown command exits 2, and
 * `tarn --version` says which tarn; and the option tables every command
 * parses with (cmd_opt_table.h), through a table of the test's own. No
 * OpenGL: help never makes a context. */
#include <ctype.h>
#include <math.h>
#include <stddef.h>
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

/* ---- the option table (cmd_opt_table.h), through a table of the test's own ---- */

typedef struct t_desc {
    const char *in, *out, *mode;
    int n, w, h, samples, nsets, custom;
    double x;
    bool flag;
    const char **sets;
} t_desc;

static bool t_set_custom(void *desc, const char *value, char *why, size_t whylen) {
    if (value && strcmp(value, "bad") == 0) { snprintf(why, whylen, "custom says no to '%s'", value); return false; }
    if (value && strcmp(value, "ok") != 0) return false;   /* why empty: "wants" says it */
    ((t_desc *)desc)->custom++;
    return true;
}

static const cmd_option t_options[] = {
    { "IN", .kind = CMD_ARG, .offset = offsetof(t_desc, in), .missing = "which input? give IN" },
    { "--out", "-o", "OUT", .kind = CMD_STRING, .offset = offsetof(t_desc, out), .help = "where it goes\n" },
    { "--count", .metavar = "N", .kind = CMD_INT, .offset = offsetof(t_desc, n), .lo = 1, .hi = 10,
      .help = "how many,\nfrom 1 to 10\n" },
    { "--x", .metavar = "X", .kind = CMD_DOUBLE, .offset = offsetof(t_desc, x), .lo = 0, .hi = 1, .wants = "0..1, e.g. 0.5",
      .help = "a share\n" },
    { "--size", .metavar = "WxH", .kind = CMD_SIZE, .offset = offsetof(t_desc, w), .offset2 = offsetof(t_desc, h),
      .lo = 8, .hi = 64, .help = "a size\n" },
    { "--flag", .kind = CMD_FLAG, .offset = offsetof(t_desc, flag), .help = "a flag\n" },
    { "--set", .metavar = "P.NAME=V", .kind = CMD_LIST, .offset = offsetof(t_desc, sets),
      .offset2 = offsetof(t_desc, nsets), .help = "repeatable\n" },
    { "--msaa", .metavar = "N", .kind = CMD_MSAA, .offset = offsetof(t_desc, samples), .help = "samples\n" },
    { "--custom", .metavar = "C", .kind = CMD_CUSTOM, .set = t_set_custom, .help = "ok or not\n" },
    { "--a-very-long-option", .metavar = "VALUE", .kind = CMD_STRING, .offset = offsetof(t_desc, mode),
      .help = "on a line of its own\n", .man = "the man page's own \\fBtext\\fR\n" },
    { 0 }
};

static const cmd_spec t_spec = {
    .name = "t",
    .synopsis = "IN [-o OUT] [--count N]\n[--flag]\n",
    .about = "About t.\n",
    .options = t_options,
    .notes = "exit codes: 0 ok\n",
    .extra = "one input at a time",
};

/* cmd_parse on a command line split at spaces; *err_text: what it said. */
static int t_parse(const char *line, t_desc *d, char *err_text, size_t errlen) {
    static char buf[1024];
    static const char *sets[64];
    char *argv[64];
    int argc = 0;
    snprintf(buf, sizeof buf, "%s", line);
    for (char *save = NULL, *a = strtok_r(buf, " ", &save); a && argc < 64; a = strtok_r(NULL, " ", &save))
        argv[argc++] = a;
    memset(d, 0, sizeof *d);
    d->sets = sets;
    char *text = NULL;
    size_t len = 0;
    FILE *err = open_memstream(&text, &len);
    int rc = cmd_parse(&t_spec, argc, argv, d, err);
    fclose(err);
    snprintf(err_text, errlen, "%s", text ? text : "");
    free(text);
    return rc;
}

static void test_table_parses(void) {
    t_desc d;
    char err[8192];
    CHECK_EQ(t_parse("in.glib -o o.png --count 3 --x 0.25 --size 16x32 --flag --msaa 0 --set a=1 --set b=2", &d, err,
                     sizeof err), TARN_EXIT_OK);
    CHECK_STR_EQ(err, "");
    CHECK_STR_EQ(d.in, "in.glib");
    CHECK_STR_EQ(d.out, "o.png");
    CHECK_EQ(d.n, 3);
    CHECK_EQ(d.x, 0.25);
    CHECK(d.w == 16 && d.h == 32);
    CHECK(d.flag);
    CHECK_EQ(d.samples, 1);   /* 0: off, which render_desc.samples says as 1 */
    CHECK_EQ(d.nsets, 2);     /* a repeated option keeps every value, in order */
    if (d.nsets == 2) { CHECK_STR_EQ(d.sets[0], "a=1"); CHECK_STR_EQ(d.sets[1], "b=2"); }
    /* --name=value, the long and short spellings, the last of a repeated plain option, "-" a positional */
    CHECK_EQ(t_parse("--out=x.png --count=2 --count 4 - --custom ok --custom=ok", &d, err, sizeof err), TARN_EXIT_OK);
    CHECK_STR_EQ(d.out, "x.png");
    CHECK_EQ(d.n, 4);
    CHECK_STR_EQ(d.in, "-");
    CHECK_EQ(d.custom, 2);
    CHECK(!d.flag && d.nsets == 0);   /* what is not given stays zero: the default */
    CHECK_EQ(t_parse("in --x -0", &d, err, sizeof err), TARN_EXIT_OK);   /* a value may start with - */
    CHECK_EQ(t_parse("--flag -- --in", &d, err, sizeof err), TARN_EXIT_OK);   /* after --, a positional */
    CHECK_STR_EQ(d.in, "--in");
    CHECK(d.flag);
}

static void test_table_errors(void) {
    static const struct { const char *line, *says; } cases[] = {
        { "in --frob", "tarn t: unknown option '--frob'\n\nusage: tarn t IN" },
        { "in -x", "unknown option '-x'" },
        { "in --count", "tarn t: --count wants 1..10\n" },          /* missing value */
        { "in --count 11", "tarn t: --count wants 1..10\n" },       /* out of range */
        { "in --count 2.5", "--count wants 1..10" },                /* not whole */
        { "in --x 2", "--x wants 0..1, e.g. 0.5" },                 /* a range of its own words */
        { "in --x nan", "--x wants 0..1, e.g. 0.5" },
        { "in --size 4x4", "--size wants WxH" },                    /* the size's own bounds */
        { "in --size 16by16", "--size wants WxH" },
        { "in --msaa 17", "--msaa wants 0..16 samples" },
        { "in --flag=1", "--flag takes no value" },
        { "in --custom bad", "tarn t: custom says no to 'bad'\n" }, /* a setter's own reason */
        { "in --custom what", "--custom wants C" },                 /* ...or the metavar */
        { "in -o", "-o wants OUT" },                                /* as the user spelled it */
        { "--flag", "tarn t: which input? give IN\n" },             /* a required one */
        { "in more", "tarn t: one input at a time (got another: 'more')" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        t_desc d;
        char err[8192];
        CHECK_MSG(t_parse(cases[i].line, &d, err, sizeof err) == TARN_EXIT_USAGE, "'%s' is not a usage error", cases[i].line);
        CHECK_MSG(strstr(err, cases[i].says) != NULL, "'%s' says:\n%s\nnot: %s", cases[i].line, err, cases[i].says);
        CHECK_MSG(strstr(err, "\n\nusage: tarn t IN [-o OUT]") != NULL, "'%s': no usage after the message", cases[i].line);
    }
}

static void test_table_usage_and_roff(void) {
    char text[CMD_USAGE_MAX];
    cmd_usage(&t_spec, text, sizeof text);
    CHECK_STR_EQ(text, "usage: tarn t IN [-o OUT] [--count N]\n"
                       "              [--flag]\n"
                       "\n"
                       "About t.\n"
                       "\n"
                       "  -o, --out OUT    where it goes\n"
                       "  --count N        how many,\n"
                       "                   from 1 to 10\n"
                       "  --x X            a share\n"
                       "  --size WxH       a size\n"
                       "  --flag           a flag\n"
                       "  --set P.NAME=V   repeatable\n"
                       "  --msaa N         samples\n"
                       "  --custom C       ok or not\n"
                       "  --a-very-long-option VALUE\n"
                       "                   on a line of its own\n"
                       "\n"
                       "exit codes: 0 ok\n");
    strbuf b = {0};
    cmd_roff_options(&t_spec, &b);
    CHECK_STR_CONTAINS(b.s, ".TP\n.BR \\-o \", \" \\-\\-out \" \\fIOUT\\fR\"\nwhere it goes\n");
    CHECK_STR_CONTAINS(b.s, ".TP\n.BI \\-\\-count \" N\"\nhow many,\nfrom 1 to 10\n");   /* unindented */
    CHECK_STR_CONTAINS(b.s, ".TP\n.B \\-\\-flag\na flag\n");
    CHECK_STR_CONTAINS(b.s, ".TP\n.BI \\-\\-a\\-very\\-long\\-option \" VALUE\"\nthe man page's own \\fBtext\\fR\n");
    CHECK(strstr(b.s, "IN") == NULL);   /* a positional with no help is the synopsis's alone */
    strbuf_free(&b);
}

/* Each command's table, as `tarn` runs it: the messages the scripts and
 * tests read, and exit 2. */
static void test_commands_parse_by_their_tables(void) {
    static const struct { const char *args, *says; } cases[] = {
        { "render x.glib -o x.png --frames 0", "tarn render: --frames wants 1..100000" },
        { "render x.glib -o x.png --bogus", "tarn render: unknown option '--bogus'" },
        { "render x.glib", "where to? give -o OUT.png" },
        { "view", "tarn view: which scene? give FILE.glib" },
        { "view a.glib b.glib", "one scene at a time" },
        { "reference s.glib -o x.exr --spp 0", "--spp wants 1..16 (N x N subsamples)" },
        { "reference s.glib -o x.exr --spp 2 --msaa 4", "--spp and --msaa: give one" },
        { "compare a b --threshold 0", "--threshold wants a number > 0" },
        { "compare a b --json - --csv -", "cannot both go to stdout" },
        { "compare-view s.glib --packs natural", "which packs? give --packs a,b (2 to 4)" },
        { "bench --time-axis sideways", "--time-axis wants auto, gpu, wall or cpu" },
        { "bench --times 1,x", "--times wants up to" },
        { "record s.session -o x/ --fps 0", "--fps wants a whole number 1..240" },
        { "sheet s.glib", "what to vary? give --vary PROGRAM.NAME=A:B:N" },
        { "sheet s.glib --vary a=1:2:3 --vary b=1:2:3 --vary c=1:2:3", "at most two --vary" },
        { "assets --size 2", "tarn assets: --size wants 4..1024" },
        { "help --frob", "tarn help: unknown option '--frob'" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char out[16384];
        CHECK_MSG(tarn(cases[i].args, out, sizeof out) == TARN_EXIT_USAGE, "tarn %s: %s", cases[i].args, out);
        CHECK_MSG(strstr(out, cases[i].says) != NULL, "tarn %s says:\n%.300s\nnot: %s", cases[i].args, out, cases[i].says);
    }
}

int main(void) {
    bin = getenv("TARN_BIN");
    if (!bin) { fprintf(stderr, "run through ctest (TARN_BIN)\n"); return 1; }
    RUN(test_help_lists_every_command);
    RUN(test_help_command_prints_its_usage);
    RUN(test_unknown_command_exits_2);
    RUN(test_unknown_pack_is_a_usage_error);
    RUN(test_version);
    RUN(test_table_parses);
    RUN(test_table_errors);
    RUN(test_table_usage_and_roff);
    RUN(test_commands_parse_by_their_tables);
    RUN(test_sheet);
    return check_summary();
}
