/* test_glib: the .glib parser (viewer/scene/glib*.c, through glib.h).
 *
 * Each case writes its files under one mkdtemp directory (includes, shaders
 * and textures that must exist or must be missing), parses, and checks the
 * commands' kinds, numbers and lines and each diagnostic's exact file:line.
 */
#define _XOPEN_SOURCE 700       /* nftw(), to remove the temporary directory */
#include "check.h"
#include "glib.h"

#include <ftw.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char root[64];           /* the temporary directory of this run */

/* root/name in one of a few rotating buffers, so a check can use several. */
static const char *P(const char *name) {
    static char bufs[8][512];
    static int next;
    char *b = bufs[next++ % 8];
    snprintf(b, sizeof bufs[0], "%s/%s", root, name);
    return b;
}

/* Writes root/name (making its directories) with len bytes of text. */
static void put_bytes(const char *name, const char *text, size_t len) {
    char path[512];
    snprintf(path, sizeof path, "%s/%s", root, name);
    for (char *s = path + strlen(root) + 1; (s = strchr(s, '/')) != NULL; s++) {
        *s = '\0';
        mkdir(path, 0755);
        *s = '/';
    }
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "cannot write %s\n", path);
        exit(1);
    }
    fwrite(text, 1, len, f);
    fclose(f);
}

static void put(const char *name, const char *text) { put_bytes(name, text, strlen(text)); }

static glib_scene *load(const char *name, const char *text) {
    put(name, text);
    return glib_load(P(name));
}

static void dump(const glib_scene *s) {
    fprintf(stderr, "  diagnostics (%d):\n", s->ndiags);
    for (int i = 0; i < s->ndiags; i++)
        fprintf(stderr, "    %s:%d: %s: %s\n", s->diags[i].file, s->diags[i].line,
                s->diags[i].severity == DIAG_ERROR ? "error" : "warning", s->diags[i].text);
}

/* A diagnostic at exactly file:line with that severity whose message
 * contains msg; prints all of them when there is none. */
static bool has_diag(const glib_scene *s, const char *file, int line, diag_severity sev,
                     const char *msg) {
    for (int i = 0; i < s->ndiags; i++) {
        const diag *d = &s->diags[i];
        if (d->line == line && d->severity == sev && strcmp(d->file, file) == 0 &&
            strstr(d->text, msg))
            return true;
    }
    fprintf(stderr, "  wanted %s:%d: %s: ...%s...\n", file, line,
            sev == DIAG_ERROR ? "error" : "warning", msg);
    dump(s);
    return false;
}

static int count_sev(const glib_scene *s, diag_severity sev) {
    int n = 0;
    for (int i = 0; i < s->ndiags; i++)
        n += s->diags[i].severity == sev;
    return n;
}

static const unif_decl *find_uniform(const glib_cmd *c, const char *name) {
    for (int i = 0; i < c->nuniforms; i++)
        if (strcmp(c->uniforms[i].name, name) == 0)
            return &c->uniforms[i];
    return NULL;
}

#define CHECK_NO_DIAGS(s) do { CHECK_EQ((s)->ndiags, 0); if ((s)->ndiags) dump(s); } while (0)

/* ------------------------------------------------------------------ */

static void test_basic_scene(void) {
    glib_scene *s = load("basic.glib",
        "##OpenGL GLIB\n"
        "WindowSize 800 600\n"
        "Perspective 70\n"
        "LookAt 0 2 5  0 0 0  0 1 0\n"
        "Translate 1 2 3\n"
        "Rotate 90 0 1 0\n"
        "Scale 2\n"
        "Scale 1 2 3\n"
        "PushMatrix\n"
        "TransformBegin\n"
        "QuadXZ -0.5 10 64 32\n"
        "TransformEnd\n"
        "PopMatrix\n"
        "Timer 20\n"
        "GSTAP\n"
        "Clear\n");
    CHECK_NO_DIAGS(s);
    CHECK_EQ(s->ncmds, 15);
    CHECK(s->nfiles == 1 && strcmp(s->files[0], P("basic.glib")) == 0);
    static const glib_cmd_kind kinds[] = {
        GLIB_CMD_WINDOW_SIZE, GLIB_CMD_PERSPECTIVE, GLIB_CMD_LOOKAT, GLIB_CMD_TRANSLATE,
        GLIB_CMD_ROTATE, GLIB_CMD_SCALE, GLIB_CMD_SCALE, GLIB_CMD_PUSH_MATRIX,
        GLIB_CMD_PUSH_MATRIX, GLIB_CMD_QUAD_XZ, GLIB_CMD_POP_MATRIX, GLIB_CMD_POP_MATRIX,
        GLIB_CMD_TIMER, GLIB_CMD_GSTAP, GLIB_CMD_CLEAR };
    for (int i = 0; i < s->ncmds && i < 15; i++) {
        CHECK_MSG(s->cmds[i].kind == kinds[i], "cmd %d", i);
        CHECK_MSG(s->cmds[i].line == i + 2, "cmd %d line %d", i, s->cmds[i].line);
        CHECK_EQ(s->cmds[i].file, s->files[0]);
        CHECK(!s->cmds[i].wire);
    }
    if (s->ncmds == 15) {
        CHECK(s->cmds[0].nnum == 2 && s->cmds[0].num[0] == 800 && s->cmds[0].num[1] == 600);
        CHECK(s->cmds[1].nnum == 3 && s->cmds[1].num[0] == 70);
        CHECK(s->cmds[2].nnum == 9 && s->cmds[2].num[1] == 2 && s->cmds[2].num[7] == 1);
        CHECK_EQ(s->cmds[3].num[2], 3);
        CHECK(s->cmds[4].nnum == 4 && s->cmds[4].num[0] == 90 && s->cmds[4].num[2] == 1);
        CHECK(s->cmds[5].nnum == 1 && s->cmds[5].num[0] == 2);
        CHECK(s->cmds[6].nnum == 3 && s->cmds[6].num[2] == 3);
        CHECK(s->cmds[9].nnum == 4 && s->cmds[9].num[0] == -0.5 && s->cmds[9].num[1] == 10 &&
              s->cmds[9].num[2] == 64 && s->cmds[9].num[3] == 32);
        CHECK_EQ(s->cmds[12].num[0], 20);
    }
    glib_free(s);
}

static void test_header(void) {
    glib_scene *s = load("nohead.glib", "Sphere 1\n");
    CHECK(has_diag(s, P("nohead.glib"), 1, DIAG_WARNING, "first line is not '##OpenGL GLIB'"));
    CHECK(s->nerrors == 0 && s->ncmds == 1 && s->cmds[0].kind == GLIB_CMD_SPHERE);
    glib_free(s);

    /* odd case and spacing, a byte order mark, a comment after: still the header */
    s = load("head2.glib", "\xEF\xBB\xBF##opengl   glib   # mine\r\nSphere 1\r\n");
    CHECK_NO_DIAGS(s);
    CHECK(s->ncmds == 1 && s->cmds[0].line == 2);
    glib_free(s);
}

static void test_empty_file(void) {
    const char *texts[] = { "", "  \n\n \t\r\n" };
    for (int i = 0; i < 2; i++) {
        glib_scene *s = load("empty.glib", texts[i]);
        CHECK(s->ndiags == 1 && s->nerrors == 1 && s->ncmds == 0);
        CHECK(has_diag(s, P("empty.glib"), 1, DIAG_ERROR,
                       "empty file: expected '##OpenGL GLIB' and commands"));
        glib_free(s);
    }
    glib_scene *s = glib_parse(NULL, 0, NULL);
    CHECK(s && s->nerrors == 1 && s->nfiles == 1);
    CHECK(has_diag(s, "<memory>", 1, DIAG_ERROR, "empty file"));
    glib_free(s);

    /* header and comments only: valid, but worth a word */
    s = load("onlyhead.glib", "##OpenGL GLIB\n# nothing yet\n");
    CHECK(s->nerrors == 0 && s->ncmds == 0);
    CHECK(has_diag(s, P("onlyhead.glib"), 1, DIAG_WARNING, "no commands"));
    glib_free(s);
}

static void test_cannot_open(void) {
    glib_scene *s = glib_load(P("nope.glib"));
    CHECK(s && s->ncmds == 0 && s->nerrors == 1 && s->ndiags == 1);
    CHECK(has_diag(s, P("nope.glib"), 0, DIAG_ERROR, "No such file or directory"));
    CHECK(s->nfiles == 1 && strcmp(s->files[0], P("nope.glib")) == 0);
    glib_free(s);

    s = glib_load(root);        /* a directory */
    CHECK(has_diag(s, root, 0, DIAG_ERROR, "it is a directory"));
    glib_free(s);

    s = glib_load(NULL);
    CHECK(s && s->nerrors == 1);
    glib_free(s);
    glib_free(NULL);
}

static void test_comments(void) {
    put("c/sub/t.bmp", "x");
    put("c/a#b.bmp", "x");
    glib_scene *s = load("c/comments.glib",
        "##OpenGL GLIB\n"
        "# a whole line\n"
        "// another\n"
        "   # indented\n"
        "Sphere 1 # trailing\n"
        "Sphere 2 // trailing\n"
        "Sphere 3#not a comment\n"
        "Texture2D 1 sub//t.bmp\n"
        "Texture2D 2 a#b.bmp\n"
        "Program P uA {1 0 0}# after a bracket\n"
        "Sphere 4\t//\ttabs\n");
    CHECK_EQ(s->ncmds, 6);
    CHECK_EQ(s->nerrors, 1);
    CHECK(has_diag(s, P("c/comments.glib"), 7, DIAG_ERROR, "bad number '3#not' for r"));
    if (s->ncmds == 6) {
        CHECK(s->cmds[0].num[0] == 1 && s->cmds[0].line == 5);
        CHECK(s->cmds[1].num[0] == 2 && s->cmds[1].line == 6);
        CHECK_STR_EQ(s->cmds[2].path, P("c/sub//t.bmp"));
        CHECK_STR_EQ(s->cmds[3].path, P("c/a#b.bmp"));
        CHECK(s->cmds[4].nuniforms == 1 && s->cmds[4].uniforms[0].kind == UNIF_DECL_COLOR);
        CHECK(s->cmds[5].num[0] == 4 && s->cmds[5].line == 11);
    }
    glib_free(s);
}

static void test_case_insensitive(void) {
    put("ci/Foo.vert", "x");
    glib_scene *s = load("ci/case.glib",
        "##OpenGL GLIB\n"
        "sPhErE 1\n"
        "QUADxz 0 1\n"
        "transformbegin\n"
        "TRANSFORMEND\n"
        "wiresphere 2\n"
        "gstap\n"
        "VERTEX Foo.vert\n"
        "program MyProg uKaBig 1\n"
        "cull BACK\n");
    CHECK_NO_DIAGS(s);
    CHECK_EQ(s->ncmds, 9);
    if (s->ncmds == 9) {
        CHECK_EQ(s->cmds[0].kind, GLIB_CMD_SPHERE);
        CHECK_EQ(s->cmds[1].kind, GLIB_CMD_QUAD_XZ);
        CHECK_EQ(s->cmds[2].kind, GLIB_CMD_PUSH_MATRIX);
        CHECK_EQ(s->cmds[3].kind, GLIB_CMD_POP_MATRIX);
        CHECK(s->cmds[4].kind == GLIB_CMD_SPHERE && s->cmds[4].wire);
        CHECK_EQ(s->cmds[5].kind, GLIB_CMD_GSTAP);
        CHECK(s->cmds[6].kind == GLIB_CMD_VERTEX && strcmp(s->cmds[6].path, P("ci/Foo.vert")) == 0);
        CHECK(s->cmds[7].kind == GLIB_CMD_PROGRAM && strcmp(s->cmds[7].name, "MyProg") == 0);
        CHECK(s->cmds[7].nuniforms == 1 && strcmp(s->cmds[7].uniforms[0].name, "uKaBig") == 0);
        CHECK(s->cmds[8].kind == GLIB_CMD_CULL && strcmp(s->cmds[8].name, "back") == 0);
    }
    glib_free(s);

    /* file names ignore case as on Windows (issue 14; this was an error):
     * foo.vert is Foo.vert, with a warning naming the real file */
    s = load("ci/case2.glib", "##OpenGL GLIB\nVertex foo.vert\n");
    CHECK(has_diag(s, P("ci/case2.glib"), 2, DIAG_WARNING, "is '"));
    CHECK(s->nerrors == 0 && s->ncmds == 1 && strcmp(s->cmds[0].path, P("ci/Foo.vert")) == 0);
    glib_free(s);
}

static void test_continuation(void) {
    glib_scene *s = load("cont.glib",
        "##OpenGL GLIB\n"               /* 1 */
        "Program Water \\\n"            /* 2 */
        "    uA <0 \\\n"                /* 3 */
        "       0.5 1> \\   # why\n"    /* 4 */
        "    uB {1, 0.5, 0.25}\n"       /* 5 */
        "Sphere \\\n"                   /* 6 */
        "  1 \\\r\n"                    /* 7 */
        "  8 4\n"                       /* 8 */
        "Program P2 uA 1 \\\n"          /* 9 */
        "   uB 1.2.3\n"                 /* 10 */
        "Translate 1 2 \\");            /* 11: continued into the end of the file */
    /* glman's leniency (issue 14): 1.2.3 reads as 1.2, a missing z is 0 */
    CHECK_EQ(s->ncmds, 4);
    CHECK_EQ(s->nerrors, 0);
    if (s->ncmds == 4) {
        const glib_cmd *w = &s->cmds[0];
        CHECK(w->kind == GLIB_CMD_PROGRAM && w->line == 2 && w->nuniforms == 2);
        const unif_decl *a = find_uniform(w, "uA"), *b = find_uniform(w, "uB");
        CHECK(a && a->kind == UNIF_DECL_SLIDER && a->n == 3 && a->v[1] == 0.5 && a->line == 2);
        CHECK(b && b->kind == UNIF_DECL_COLOR && b->n == 3 && b->v[2] == 0.25);
        CHECK(s->cmds[1].kind == GLIB_CMD_SPHERE && s->cmds[1].line == 6);
        CHECK(s->cmds[1].num[0] == 1 && s->cmds[1].num[1] == 8 && s->cmds[1].num[2] == 4);
        CHECK(s->cmds[2].line == 9 && s->cmds[2].nuniforms == 2);
        CHECK(s->cmds[3].line == 11 && s->cmds[3].num[1] == 2 && s->cmds[3].num[2] == 0);
    }
    /* messages name the line the command starts on */
    CHECK(has_diag(s, P("cont.glib"), 9, DIAG_WARNING, "'1.2.3' read as 1.2"));
    glib_free(s);
}

static void test_uniform_kinds(void) {
    glib_scene *s = load("uni.glib",
        "##OpenGL GLIB\n"
        "Program Ocean uKa <0. 0.1 1.0> uColor {0.40, 1.0, 0.95, 1.} uLo < -2. 0.5 3.> "
        "uHi <-2. 0.5 3.> uShow <true > uHide < FALSE> uArr [1, 2, 3, 4] uTex 5 "
        "uRGB {1 0 0} uTight<0 1 2> uOne [7]\n");
    CHECK_NO_DIAGS(s);
    CHECK_EQ(s->ncmds, 1);
    const glib_cmd *c = &s->cmds[0];
    CHECK(strcmp(c->name, "Ocean") == 0 && c->nuniforms == 11);
    const unif_decl *u;
    CHECK((u = find_uniform(c, "uKa")) && u->kind == UNIF_DECL_SLIDER && u->n == 3 &&
          u->v[0] == 0 && u->v[1] == 0.1 && u->v[2] == 1);
    CHECK((u = find_uniform(c, "uColor")) && u->kind == UNIF_DECL_COLOR && u->n == 4 &&
          u->v[0] == 0.4 && u->v[3] == 1);
    CHECK((u = find_uniform(c, "uLo")) && u->kind == UNIF_DECL_SLIDER && u->v[0] == -2 &&
          u->v[1] == 0.5 && u->v[2] == 3);
    CHECK((u = find_uniform(c, "uHi")) && u->kind == UNIF_DECL_SLIDER && u->v[0] == -2);
    CHECK((u = find_uniform(c, "uShow")) && u->kind == UNIF_DECL_BOOL && u->n == 1 && u->v[0] == 1);
    CHECK((u = find_uniform(c, "uHide")) && u->kind == UNIF_DECL_BOOL && u->v[0] == 0);
    CHECK((u = find_uniform(c, "uArr")) && u->kind == UNIF_DECL_ARRAY && u->n == 4 && u->v[3] == 4);
    CHECK((u = find_uniform(c, "uTex")) && u->kind == UNIF_DECL_SCALAR && u->n == 1 && u->v[0] == 5);
    CHECK((u = find_uniform(c, "uRGB")) && u->kind == UNIF_DECL_COLOR && u->n == 3);
    CHECK((u = find_uniform(c, "uTight")) && u->kind == UNIF_DECL_SLIDER && u->v[2] == 2);
    CHECK((u = find_uniform(c, "uOne")) && u->kind == UNIF_DECL_ARRAY && u->n == 1 && u->v[0] == 7);
    CHECK(c->nuniforms > 0 && c->uniforms[0].file == s->files[0] && c->uniforms[0].line == 2);
    glib_free(s);
}

static void test_number_forms(void) {
    glib_scene *s = load("nums.glib",
        "##OpenGL GLIB\n"
        "Translate 1. .5 -2.\n"
        "Rotate 1e-3 +1 0 0\n"
        "Scale -.5e2\n"
        "Background 0 0 0 1E0\n"
        "Program P uA <-1e+1 0 .5>\n");
    CHECK_NO_DIAGS(s);
    CHECK_EQ(s->ncmds, 5);
    if (s->ncmds == 5) {
        CHECK(s->cmds[0].num[0] == 1 && s->cmds[0].num[1] == 0.5 && s->cmds[0].num[2] == -2);
        CHECK_NEAR(s->cmds[1].num[0], 1e-3, 1e-15);
        CHECK_EQ(s->cmds[1].num[1], 1);
        CHECK_EQ(s->cmds[2].num[0], -50);
        CHECK(s->cmds[3].nnum == 4 && s->cmds[3].num[3] == 1);
        CHECK_EQ(s->cmds[4].uniforms[0].v[0], -10);
    }
    glib_free(s);
}

static void test_bad_numbers(void) {
    glib_scene *s = load("badnum.glib",
        "##OpenGL GLIB\n"
        "Sphere 1.2.3\n"
        "Translate abc 0 0\n"
        "Scale nan\n"
        "Scale inf\n"
        "Scale 1e999\n"
        "Scale 0x10\n"
        "Scale 1e\n"
        "Program P uA <0 x 2> uB 1..2 uC {1 2 three} uD -\n");
    const char *f = P("badnum.glib");
    CHECK(has_diag(s, f, 2, DIAG_WARNING, "Sphere: '1.2.3' read as 1.2"));   /* atof, issue 14 */
    CHECK(has_diag(s, f, 3, DIAG_ERROR, "Translate: bad number 'abc' for x"));
    CHECK(has_diag(s, f, 4, DIAG_ERROR, "bad number 'nan'"));
    CHECK(has_diag(s, f, 5, DIAG_ERROR, "bad number 'inf'"));
    CHECK(has_diag(s, f, 6, DIAG_ERROR, "bad number '1e999'"));
    CHECK(has_diag(s, f, 7, DIAG_ERROR, "bad number '0x10'"));
    CHECK(has_diag(s, f, 8, DIAG_ERROR, "bad number '1e'"));
    CHECK(has_diag(s, f, 9, DIAG_ERROR, "uniform 'uA': bad number 'x'"));
    CHECK(has_diag(s, f, 9, DIAG_WARNING, "'1..2' read as 1"));
    CHECK(has_diag(s, f, 9, DIAG_ERROR, "uniform 'uC': bad number 'three'"));
    CHECK(has_diag(s, f, 9, DIAG_ERROR, "uniform 'uD': bad number '-'"));
    CHECK_EQ(s->nerrors, 9);
    /* the bad commands are skipped; the Program stays, without its bad uniforms */
    CHECK(s->ncmds == 2 && s->cmds[0].kind == GLIB_CMD_SPHERE && s->cmds[0].num[0] == 1.2);
    CHECK(s->cmds[1].kind == GLIB_CMD_PROGRAM && s->cmds[1].nuniforms == 1 &&
          s->cmds[1].uniforms[0].v[0] == 1);
    glib_free(s);
}

static void test_unclosed_brackets(void) {
    glib_scene *s = load("unclosed.glib",
        "##OpenGL GLIB\n"
        "Program A uA <0 1 2\n"
        "Program B uC {1 0 0\n"
        "Program C uD [1 2 3\n"
        "Program D uE <0 1 2} uF 1\n"
        "Program E uG <0 1 \\\n"
        "   2\n"
        "Program F uH 1 2>\n"
        "Program G uI <0 1 2 uJ <0 1 2>\n"
        "Sphere 1\n");
    const char *f = P("unclosed.glib");
    CHECK(has_diag(s, f, 2, DIAG_ERROR, "uniform 'uA': unclosed '<': add '>'"));
    CHECK(has_diag(s, f, 3, DIAG_ERROR, "uniform 'uC': unclosed '{': add '}'"));
    CHECK(has_diag(s, f, 4, DIAG_ERROR, "uniform 'uD': unclosed '[': add ']'"));
    CHECK(has_diag(s, f, 5, DIAG_ERROR, "uniform 'uE': '<' is not closed before '}'"));
    CHECK(has_diag(s, f, 6, DIAG_ERROR, "uniform 'uG': unclosed '<'"));
    CHECK(has_diag(s, f, 8, DIAG_ERROR, "'2>' is not a valid uniform name"));
    CHECK(has_diag(s, f, 9, DIAG_ERROR, "uniform 'uI': '<' is not closed before '<'"));
    CHECK_EQ(s->nerrors, 7);
    CHECK_EQ(s->ncmds, 8);
    if (s->ncmds == 8) {
        for (int i = 0; i < 5; i++)
            CHECK(s->cmds[i].kind == GLIB_CMD_PROGRAM && s->cmds[i].nuniforms == 0);
        CHECK_EQ(s->cmds[5].nuniforms, 1);       /* uH 1 is fine */
        CHECK(s->cmds[7].kind == GLIB_CMD_SPHERE && s->cmds[7].line == 10);
    }
    glib_free(s);
}

static void test_slider_checks(void) {
    glib_scene *s = load("slider.glib",
        "##OpenGL GLIB\n"
        "Program P uA <3 1 0> uB <0 5 1> uC <0 -1 1> uD <0 1> uE <maybe> uF <> uG {1 2} "
        "uH [1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17] uI <0 0 0>\n");
    const char *f = P("slider.glib");
    CHECK(has_diag(s, f, 2, DIAG_ERROR, "uniform 'uA': slider minimum 3 is greater than its maximum 0"));
    CHECK(has_diag(s, f, 2, DIAG_WARNING, "uniform 'uB': default 5 is outside <0 .. 1>; using 1"));
    CHECK(has_diag(s, f, 2, DIAG_WARNING, "uniform 'uC': default -1 is outside <0 .. 1>; using 0"));
    CHECK(has_diag(s, f, 2, DIAG_ERROR, "uniform 'uD': <> needs 3 numbers"));
    CHECK(has_diag(s, f, 2, DIAG_ERROR, "uniform 'uE': <> needs 3 numbers"));
    CHECK(has_diag(s, f, 2, DIAG_ERROR, "uniform 'uF': <> needs 3 numbers <min default max> or <true>/<false>, got 0"));
    CHECK(has_diag(s, f, 2, DIAG_ERROR, "uniform 'uG': {} needs 3 or 4 numbers"));
    CHECK(has_diag(s, f, 2, DIAG_ERROR, "uniform 'uH': [] needs 1 to 16 numbers [a b c], got 17"));
    CHECK_EQ(s->ncmds, 1);
    const unif_decl *u;
    CHECK((u = find_uniform(&s->cmds[0], "uB")) && u->v[1] == 1);
    CHECK((u = find_uniform(&s->cmds[0], "uC")) && u->v[1] == 0);
    CHECK((u = find_uniform(&s->cmds[0], "uI")) && u->kind == UNIF_DECL_SLIDER);
    CHECK_EQ(s->cmds[0].nuniforms, 3);
    glib_free(s);
}

static void test_duplicate_uniform(void) {
    glib_scene *s = load("dup.glib", "##OpenGL GLIB\nProgram P uA 1 uB 2 uA <0 3 5>\n");
    CHECK(has_diag(s, P("dup.glib"), 2, DIAG_WARNING, "Program P: uniform 'uA' is given twice; the later value wins"));
    CHECK(s->nerrors == 0 && s->ncmds == 1 && s->cmds[0].nuniforms == 2);
    const unif_decl *u = find_uniform(&s->cmds[0], "uA");
    CHECK(u && u->kind == UNIF_DECL_SLIDER && u->v[1] == 3);
    glib_free(s);
}

static void test_arg_counts(void) {
    glib_scene *s = load("args.glib",
        "##OpenGL GLIB\n"
        "Sphere\n"
        "LookAt 0 0 3\n"
        "Sphere 1 8 4 99 100\n"
        "Scale 1 2\n"
        "QuadXZ 0\n"
        "Clear now\n"
        "WindowSize 800\n"
        "Perspective\n"
        "Ortho -1 1 -1\n"
        "Color 1 0\n");
    const char *f = P("args.glib");
    CHECK(has_diag(s, f, 3, DIAG_ERROR,
                   "LookAt needs 9 numbers, got 3: LookAt ex ey ez cx cy cz ux uy uz"));
    CHECK(has_diag(s, f, 4, DIAG_WARNING,
                   "Sphere takes at most 3 arguments; ignoring '99' and what follows"));
    CHECK(has_diag(s, f, 5, DIAG_ERROR, "Scale takes 1 number or 3, not 2"));
    CHECK(has_diag(s, f, 7, DIAG_WARNING, "Clear takes no arguments; ignoring 'now'"));
    CHECK(has_diag(s, f, 8, DIAG_ERROR, "WindowSize needs a height"));
    CHECK(has_diag(s, f, 11, DIAG_ERROR, "Color needs a blue value"));
    CHECK(s->nerrors == 4 && count_sev(s, DIAG_WARNING) == 2);
    /* bare Sphere, QuadXZ 0, Perspective and a short Ortho take glman's
     * defaults (issue 14; they were errors) */
    CHECK_EQ(s->ncmds, 6);
    if (s->ncmds == 6) {
        CHECK(s->cmds[0].kind == GLIB_CMD_SPHERE && s->cmds[0].line == 2 && s->cmds[0].num[0] == 1);
        CHECK(s->cmds[1].kind == GLIB_CMD_SPHERE && s->cmds[1].line == 4 && s->cmds[1].nnum == 3);
        CHECK(s->cmds[1].num[1] == 8 && s->cmds[1].num[2] == 4);
        CHECK(s->cmds[2].kind == GLIB_CMD_QUAD_XZ && s->cmds[2].num[1] == 1);
        CHECK(s->cmds[3].kind == GLIB_CMD_CLEAR && s->cmds[3].nnum == 0);
        CHECK(s->cmds[4].kind == GLIB_CMD_PERSPECTIVE && s->cmds[4].num[0] == 50);
        CHECK(s->cmds[5].kind == GLIB_CMD_ORTHO && s->cmds[5].num[2] == -1 && s->cmds[5].num[3] == 3);
    }
    glib_free(s);
}

static void test_defaults(void) {
    glib_scene *s = load("defaults.glib",
        "##OpenGL GLIB\n"
        "Sphere 1\n"
        "Box 2\n"
        "Box 1 2 3\n"
        "Scale 2\n"
        "Color 1 0 0\n"
        "QuadXY 0 1\n"
        "Torus 1 0.25\n"
        "Cylinder 1 2\n"
        "Teapot\n"
        "Noise2D\n"
        "Noise3D 32\n"
        "Perspective 60\n"
        "Ortho -1 1 -1 1\n");
    CHECK_NO_DIAGS(s);
    CHECK_EQ(s->ncmds, 13);
    if (s->ncmds == 13) {
        const glib_cmd *c = s->cmds;
        CHECK(c[0].nnum == 3 && c[0].num[1] == 60 && c[0].num[2] == 60);   /* glman's */
        CHECK(c[1].nnum == 3 && c[1].num[0] == 2 && c[1].num[1] == 2 && c[1].num[2] == 2);
        CHECK(c[2].nnum == 3 && c[2].num[1] == 2 && c[2].num[2] == 3);
        CHECK(c[3].nnum == 1 && c[3].num[0] == 2);
        CHECK(c[4].nnum == 4 && c[4].num[3] == 1);
        CHECK(c[5].nnum == 4 && c[5].num[2] == 1 && c[5].num[3] == 1);
        CHECK(c[6].nnum == 4 && c[6].num[2] == 20 && c[6].num[3] == 40);
        CHECK(c[7].nnum == 4 && c[7].num[2] == 32 && c[7].num[3] == 8);
        CHECK(c[8].kind == GLIB_CMD_TEAPOT && c[8].nnum == 1 && c[8].num[0] == 1);
        CHECK(c[9].kind == GLIB_CMD_NOISE2D && c[9].nnum == 1 && c[9].num[0] == 64);
        CHECK(c[10].kind == GLIB_CMD_NOISE3D && c[10].num[0] == 32);
        CHECK(c[11].nnum == 3 && c[11].num[1] == 0.1 && c[11].num[2] == 1000);
        CHECK(c[12].nnum == 6 && c[12].num[3] == 1 && c[12].num[5] == 1000);
    }
    glib_free(s);
}

static void test_range_checks(void) {
    glib_scene *s = load("range.glib",
        "##OpenGL GLIB\n"
        "Sphere 0\n"
        "Sphere 1 2\n"
        "QuadXZ 0 1 2.5\n"
        "Perspective 180\n"
        "LookAt 1 1 1  1 1 1  0 1 0\n"
        "LookAt 0 5 0  0 0 0  0 1 0\n"
        "Rotate 30 0 0 0\n"
        "Perspective 60 10 1\n"
        "Texture2D 40 x.bmp\n"
        "WindowSize 0 600\n"
        "Ortho 1 1 -1 1\n");
    const char *f = P("range.glib");
    CHECK(has_diag(s, f, 2, DIAG_ERROR, "Sphere: r must be greater than 0, not '0'"));
    CHECK(has_diag(s, f, 3, DIAG_ERROR, "Sphere: slices must be a whole number from 3 to 1024, not '2'"));
    CHECK(has_diag(s, f, 4, DIAG_ERROR, "QuadXZ: nx must be a whole number from 1 to 4096, not '2.5'"));
    CHECK(has_diag(s, f, 5, DIAG_ERROR, "Perspective: fov must be an angle between 0 and 180"));
    CHECK(has_diag(s, f, 6, DIAG_ERROR, "LookAt: the eye and the point looked at are the same"));
    CHECK(has_diag(s, f, 7, DIAG_ERROR, "LookAt: the up vector is zero or along the line of sight"));
    CHECK(has_diag(s, f, 8, DIAG_ERROR, "Rotate: the axis is zero"));
    CHECK(has_diag(s, f, 9, DIAG_ERROR, "Perspective: near (10) must be less than far (1)"));
    CHECK(has_diag(s, f, 10, DIAG_ERROR, "Texture2D: unit must be a whole number from 0 to 31, not '40'"));
    CHECK(has_diag(s, f, 11, DIAG_ERROR, "WindowSize: w must be a whole number from 1 to 16384"));
    CHECK(has_diag(s, f, 12, DIAG_ERROR, "Ortho: left/right, bottom/top and near/far must differ"));
    CHECK(s->ncmds == 0 && s->nerrors == 11);
    glib_free(s);
}

static void test_paths_relative(void) {
    put("rel/sub/water.vert", "x");
    put("rel/tex/w.bmp", "x");
    put("rel/sub/tex/w2.bmp", "x");
    put("rel/abs.frag", "x");
    char text[1024];
    snprintf(text, sizeof text,
             "##OpenGL GLIB\n"
             "Vertex water.vert\n"
             "Texture2D 5 ../tex/w.bmp\n"
             "Fragment %s\n"
             "Texture2D 6 tex\\w2.bmp\n"
             "Vertex\n", P("rel/abs.frag"));
    glib_scene *s = load("rel/sub/scene.glib", text);
    CHECK_NO_DIAGS(s);
    CHECK_EQ(s->ncmds, 5);
    if (s->ncmds == 5) {
        CHECK_STR_EQ(s->cmds[0].path, P("rel/sub/water.vert"));
        CHECK_STR_EQ(s->cmds[1].path, P("rel/sub/../tex/w.bmp"));
        CHECK_STR_EQ(s->cmds[2].path, P("rel/abs.frag"));
        CHECK_STR_EQ(s->cmds[3].path, P("rel/sub/tex/w2.bmp"));
        CHECK(s->cmds[4].kind == GLIB_CMD_VERTEX && s->cmds[4].path[0] == '\0');
    }
    glib_free(s);

    /* a file with no directory part: paths stay relative to the cwd */
    const char *t = "##OpenGL GLIB\nVertex some/x.vert\n";
    s = glib_parse(t, strlen(t), "scene.glib");
    CHECK(s->ncmds == 1 && strcmp(s->cmds[0].path, "some/x.vert") == 0);
    CHECK(has_diag(s, "scene.glib", 2, DIAG_ERROR, "cannot open 'some/x.vert' (from command Vertex)"));
    glib_free(s);
}

static void test_missing_files(void) {
    put("miss/have.bmp", "x");
    glib_scene *s = load("miss/m.glib",
        "##OpenGL GLIB\n"
        "Vertex gone.vert\n"
        "Fragment gone.frag\n"
        "TessControl gone.tcs\n"
        "TessEvaluation gone.tes\n"
        "Geometry gone.geom\n"
        "Texture2D 5 gone.bmp\n"
        "Texture3D 6 gone3.tif\n"
        "Obj gone.obj\n"
        "CubeMap 7 have.bmp have.bmp gone_py.bmp have.bmp have.bmp have.bmp\n"
        "Texture2D 4 .\n");
    char f[512];
    snprintf(f, sizeof f, "%s", P("miss/m.glib"));
    char want[600];
    static const char *const lines[][2] = {
        { "gone.vert", "Vertex" }, { "gone.frag", "Fragment" }, { "gone.tcs", "TessControl" },
        { "gone.tes", "TessEvaluation" }, { "gone.geom", "Geometry" }, { "gone.bmp", "Texture2D" },
        { "gone3.tif", "Texture3D" }, { "gone.obj", "Obj" }, { "gone_py.bmp", "CubeMap" },
    };
    for (int i = 0; i < 9; i++) {
        char rel[64];
        snprintf(rel, sizeof rel, "miss/%s", lines[i][0]);
        snprintf(want, sizeof want, "cannot open '%s' (from command %s): No such file or directory",
                 P(rel), lines[i][1]);
        CHECK_MSG(has_diag(s, f, 2 + i, DIAG_ERROR, want), "%s", want);
    }
    CHECK(has_diag(s, f, 11, DIAG_ERROR, "it is a directory"));
    CHECK_EQ(s->nerrors, 10);
    /* the commands stay: the files may appear before the renderer needs them */
    CHECK_EQ(s->ncmds, 10);
    if (s->ncmds == 10) {
        const glib_cmd *cube = &s->cmds[8];
        CHECK(cube->kind == GLIB_CMD_CUBEMAP && cube->cube_paths && cube->num[0] == 7);
        CHECK(cube->cube_paths && strcmp(cube->cube_paths[2], P("miss/gone_py.bmp")) == 0);
        CHECK(cube->cube_paths && strcmp(cube->cube_paths[5], P("miss/have.bmp")) == 0);
    }
    glib_free(s);
}

static void test_case_hint(void) {
    put("hint/Water.BMP", "x");
    glib_scene *s = load("hint/h.glib", "##OpenGL GLIB\nTexture2D 5 water.bmp\n");
    char want[600];
    /* issue 14: glman ran on Windows, so the name in another case is that
     * file (it was an error with a hint) */
    snprintf(want, sizeof want, "is '%s' on disk; using it", P("hint/Water.BMP"));
    CHECK(has_diag(s, P("hint/h.glib"), 2, DIAG_WARNING, want));
    CHECK(s->nerrors == 0 && s->ncmds == 1 && strcmp(s->cmds[0].path, P("hint/Water.BMP")) == 0);
    glib_free(s);

    /* every component, backslashes as separators, and an Include too */
    put("hint/Tex/Sky24.bmp", "x");
    put("hint/Parts/Inc.glib", "Sphere 3\n");
    s = load("hint/h2.glib", "##OpenGL GLIB\nTexture2D 6 TEX\\SKY24.BMP\nInclude parts/inc.GLIB\n");
    CHECK(s->nerrors == 0 && count_sev(s, DIAG_WARNING) == 2);
    CHECK(s->ncmds == 2 && strcmp(s->cmds[0].path, P("hint/Tex/Sky24.bmp")) == 0);
    CHECK(s->ncmds == 2 && s->cmds[1].kind == GLIB_CMD_SPHERE && s->cmds[1].num[0] == 3);
    snprintf(want, sizeof want, "is '%s' on disk", P("hint/Tex/Sky24.bmp"));
    CHECK(has_diag(s, P("hint/h2.glib"), 2, DIAG_WARNING, want));
    glib_free(s);
}

static void test_include(void) {
    put("inc/parts/w.vert", "x");
    put("inc/parts/part.glib", "# no header needed here\nSphere 2\nVertex w.vert\n");
    glib_scene *s = load("inc/main.glib",
        "##OpenGL GLIB\n"
        "Sphere 1\n"
        "Include parts/part.glib\n"
        "Sphere 3\n"
        "include \"parts/part.glib\"\n");
    CHECK_NO_DIAGS(s);
    CHECK_EQ(s->nfiles, 2);
    CHECK_EQ(s->ncmds, 6);
    if (s->nfiles == 2 && s->ncmds == 6) {
        CHECK_STR_EQ(s->files[1], P("inc/parts/part.glib"));
        CHECK(s->cmds[0].num[0] == 1 && s->cmds[0].file == s->files[0] && s->cmds[0].line == 2);
        CHECK(s->cmds[1].num[0] == 2 && s->cmds[1].file == s->files[1] && s->cmds[1].line == 2);
        CHECK(s->cmds[2].kind == GLIB_CMD_VERTEX && s->cmds[2].file == s->files[1] &&
              s->cmds[2].line == 3 && strcmp(s->cmds[2].path, P("inc/parts/w.vert")) == 0);
        CHECK(s->cmds[3].num[0] == 3 && s->cmds[3].line == 4);
        CHECK(s->cmds[4].file == s->files[1] && s->cmds[5].kind == GLIB_CMD_VERTEX);
    }
    glib_free(s);

    /* an error inside an included file names that file */
    put("inc/bad.glib", "\n\nSphere -1\n");
    s = load("inc/main2.glib", "##OpenGL GLIB\nInclude bad.glib\n");
    CHECK(has_diag(s, P("inc/bad.glib"), 3, DIAG_ERROR, "Sphere: r must be greater than 0"));
    glib_free(s);
}

static void test_include_missing(void) {
    glib_scene *s = load("incm/main.glib",
        "##OpenGL GLIB\n\nInclude nope.glib\nInclude\nSphere 1\n");
    char want[600];
    snprintf(want, sizeof want, "cannot open '%s' (from command Include): No such file or directory",
             P("incm/nope.glib"));
    CHECK(has_diag(s, P("incm/main.glib"), 3, DIAG_ERROR, want));
    CHECK(has_diag(s, P("incm/main.glib"), 4, DIAG_ERROR, "Include needs a file: Include file.glib"));
    CHECK(s->nerrors == 2 && s->ncmds == 1 && s->cmds[0].line == 5 && s->nfiles == 1);
    glib_free(s);

    s = load("incm/dir.glib", "##OpenGL GLIB\nInclude .\n");
    CHECK(has_diag(s, P("incm/dir.glib"), 2, DIAG_ERROR, "(from command Include): it is a directory"));
    CHECK_EQ(s->nerrors, 1);
    glib_free(s);
}

static void test_include_cycle(void) {
    put("cyc/b.glib", "Sphere 2\nInclude a.glib\nSphere 3\n");
    glib_scene *s = load("cyc/a.glib", "##OpenGL GLIB\nSphere 1\nInclude b.glib\nSphere 4\n");
    char want[600];
    snprintf(want, sizeof want, "Include cycle: %s -> %s -> %s", P("cyc/a.glib"),
             P("cyc/b.glib"), P("cyc/a.glib"));
    CHECK(has_diag(s, P("cyc/b.glib"), 2, DIAG_ERROR, want));
    CHECK(s->nerrors == 1 && s->ncmds == 4);
    for (int i = 0; i < s->ncmds; i++)
        CHECK_EQ(s->cmds[i].num[0], i + 1);
    glib_free(s);

    /* itself, spelled differently */
    s = load("cyc/self.glib", "##OpenGL GLIB\nInclude ./self.glib\nSphere 1\n");
    CHECK(has_diag(s, P("cyc/self.glib"), 2, DIAG_ERROR, "Include cycle"));
    CHECK_EQ(s->ncmds, 1);
    glib_free(s);
}

static void test_include_depth(void) {
    char name[64], text[128];
    for (int i = 0; i < 40; i++) {
        snprintf(name, sizeof name, "deep/d%d.glib", i);
        snprintf(text, sizeof text, "%sInclude d%d.glib\nSphere 1\n", i ? "" : "##OpenGL GLIB\n",
                 i + 1);
        put(name, text);
    }
    glib_scene *s = glib_load(P("deep/d0.glib"));
    CHECK(has_diag(s, P("deep/d32.glib"), 1, DIAG_ERROR, "is nested more than 32 files deep"));
    CHECK_EQ(s->nerrors, 1);
    CHECK_EQ(s->ncmds, 33);      /* d0 .. d32 */
    CHECK_EQ(s->nfiles, 33);
    glib_free(s);
}

static void test_unknown_command(void) {
    glib_scene *s = load("unk.glib",
        "##OpenGL GLIB\n"
        "Foo 1 2\n"
        "Sphear 1\n"
        "Program P uA 1\n"
        "   uB <0 1 2>\n"
        "Tessellation x\n"
        "Sphere 1\n");
    const char *f = P("unk.glib");
    CHECK(has_diag(s, f, 2, DIAG_WARNING, "unknown command 'Foo' (skipped)"));
    CHECK(has_diag(s, f, 3, DIAG_WARNING, "unknown command 'Sphear' (skipped); did you mean 'Sphere'?"));
    CHECK(has_diag(s, f, 5, DIAG_WARNING, "unknown command 'uB' (skipped); a uniform on its own line?"));
    CHECK(has_diag(s, f, 6, DIAG_WARNING, "unknown command 'Tessellation' (skipped)"));
    CHECK(s->nerrors == 0 && s->ndiags == 4 && s->ncmds == 2);
    glib_free(s);
}

static void test_binary_junk(void) {
    static const char t1[] = "##OpenGL GLIB\nSph\0ere 1\nSphere 2\n# caf\xe9 latin-1 comment is fine\n"
                             "Sphere \xff\nSphere 3 # \x01\n";
    put_bytes("bin/nul.glib", t1, sizeof t1 - 1);
    glib_scene *s = glib_load(P("bin/nul.glib"));
    const char *f = P("bin/nul.glib");
    CHECK(has_diag(s, f, 2, DIAG_ERROR, "binary data (byte 0x00 at column 4)"));
    CHECK(has_diag(s, f, 5, DIAG_ERROR, "byte 0xFF at column 8 is not UTF-8"));
    CHECK(s->nerrors == 2 && s->ncmds == 2);
    if (s->ncmds == 2)
        CHECK(s->cmds[0].line == 3 && s->cmds[1].line == 6 && s->cmds[1].num[0] == 3);
    glib_free(s);

    /* valid UTF-8 in a path is fine */
    put("bin/eau\xc3\xa9.bmp", "x");
    s = load("bin/utf8.glib", "##OpenGL GLIB\nTexture2D 5 eau\xc3\xa9.bmp\n");
    CHECK_NO_DIAGS(s);
    glib_free(s);

    /* a whole binary file: a few errors, then it stops reading */
    size_t n = 256 * 1024;
    char *junk = malloc(n);
    uint32_t x = 12345;
    for (size_t i = 0; i < n; i++) {
        x = x * 1664525u + 1013904223u;
        junk[i] = (char)(x >> 24);
    }
    put_bytes("bin/junk.glib", junk, n);
    s = glib_load(P("bin/junk.glib"));
    CHECK(s->nerrors >= 1 && s->ndiags <= 8);
    CHECK(has_diag(s, P("bin/junk.glib"), 1, DIAG_WARNING, "first line is not"));
    bool stopped = false;
    for (int i = 0; i < s->ndiags; i++)
        stopped |= strstr(s->diags[i].text, "stopped reading it") != NULL;
    CHECK(stopped);
    glib_free(s);
    /* the same bytes from memory */
    s = glib_parse(junk, n, "junk");
    CHECK(s->nerrors >= 1 && s->ndiags <= 8);
    glib_free(s);
    free(junk);
}

/* Random text built from the pieces the grammar uses, plus random bytes:
 * whatever comes in, no crash (ASan watches), bounded diagnostics. */
static void test_fuzz(void) {
    static const char *const pieces[] = {
        "Sphere", "Program", "Define", "Include", "Texture2D", "CubeMap", "LookAt", "QuadXZ",
        "RenderToTexture", "Scale", "Box", "Cull", "Blend", "DepthTest", "Vertex", "Obj",
        " ", " ", "  ", "\t", "\n", "\n", "\r\n", "\\\n", "\\", "#", "//", "\"", "<", ">", "{", "}",
        "[", "]", ",", "1", "-2.", ".5", "1e3", "1e999", "true", "false", "uA", "x.bmp",
        "/tmp", "..", "\xc3", "\xa9", "\xff", "on", "float", "7", "0",
    };
    uint32_t x = 99;
    char text[2048];
    for (int iter = 0; iter < 3000; iter++) {
        size_t n = 0;
        if (iter % 2)
            n = (size_t)snprintf(text, sizeof text, "##OpenGL GLIB\n");
        while (n < sizeof text - 32) {
            x = x * 1664525u + 1013904223u;
            if ((x >> 28) == 0) {
                text[n++] = (char)(x >> 8);
                continue;
            }
            const char *p = pieces[(x >> 8) % (sizeof pieces / sizeof pieces[0])];
            size_t l = strlen(p);
            memcpy(text + n, p, l);
            n += l;
            if ((x & 0xff) < 4)
                break;
        }
        char virt[600];
        snprintf(virt, sizeof virt, "%s/fuzz.glib", root);
        glib_scene *s = glib_parse(text, n, virt);
        CHECK(s && s->ndiags <= 200);
        for (int i = 0; s && i < s->ncmds; i++) {
            CHECK(s->cmds[i].kind > GLIB_CMD_NONE && s->cmds[i].kind < GLIB_CMD_KIND_COUNT);
            CHECK(s->cmds[i].nnum >= 0 && s->cmds[i].nnum <= GLIB_MAX_NUMS);
            CHECK_GE(s->cmds[i].line, 1);
        }
        glib_free(s);
    }
}

static void test_long_inputs(void) {
    size_t big = 20000;
    char *t = malloc(big + 256);
    /* a path longer than GLIB_PATH_MAX */
    int n = snprintf(t, 256, "##OpenGL GLIB\nTexture2D 5 ");
    memset(t + n, 'p', 2000);
    strcpy(t + n + 2000, ".bmp\nSphere 1\n");
    glib_scene *s = glib_parse(t, strlen(t), P("long.glib"));
    CHECK(has_diag(s, P("long.glib"), 2, DIAG_ERROR, "Texture2D: path too long"));
    CHECK(s->ncmds == 1 && s->cmds[0].line == 3);
    glib_free(s);

    /* names longer than GLIB_NAME_MAX */
    n = snprintf(t, 256, "##OpenGL GLIB\nProgram P u");
    memset(t + n, 'a', 100);
    strcpy(t + n + 100, " 1 uB 2\nDefine ");
    n = (int)strlen(t);
    memset(t + n, 'D', 80);
    strcpy(t + n + 80, "\nProgram ");
    n = (int)strlen(t);
    memset(t + n, 'Q', 80);
    strcpy(t + n + 80, "\n");
    s = glib_parse(t, strlen(t), P("long.glib"));
    CHECK(has_diag(s, P("long.glib"), 2, DIAG_ERROR, "uniform name 'uaaaa"));
    CHECK(has_diag(s, P("long.glib"), 2, DIAG_ERROR, "is too long (at most 63 characters)"));
    CHECK(has_diag(s, P("long.glib"), 3, DIAG_ERROR, "Define name 'DDDD"));
    CHECK(has_diag(s, P("long.glib"), 4, DIAG_ERROR, "Program name 'QQQ"));
    CHECK(s->ncmds == 1 && s->cmds[0].nuniforms == 1 && strcmp(s->cmds[0].uniforms[0].name, "uB") == 0);
    glib_free(s);

    /* a line past the line limit, with and without a newline after it */
    n = snprintf(t, 256, "##OpenGL GLIB\nSphere 1 ");
    memset(t + n, 'x', big);
    strcpy(t + n + big, "\nSphere 2\n");
    s = glib_parse(t, strlen(t), P("long.glib"));
    CHECK(has_diag(s, P("long.glib"), 2, DIAG_ERROR, "line too long (over 16384 characters)"));
    CHECK(s->ncmds == 1 && s->cmds[0].num[0] == 2);
    glib_free(s);
    memset(t + 14, 'a', big);
    s = glib_parse(t, 14 + big, P("long.glib"));
    CHECK(has_diag(s, P("long.glib"), 2, DIAG_ERROR, "line too long"));
    glib_free(s);
    free(t);
}

static void test_diag_cap(void) {
    size_t n = 0, cap = 16 + 500 * 8;
    char *t = malloc(cap);
    n += (size_t)snprintf(t, cap, "##OpenGL GLIB\nClear\n");
    for (int i = 0; i < 500; i++)
        n += (size_t)snprintf(t + n, cap - n, "Foo\n");
    glib_scene *s = glib_parse(t, n, "cap.glib");
    CHECK_EQ(s->ndiags, 200);
    CHECK(has_diag(s, "cap.glib", 0, DIAG_WARNING, "too many errors: 301 more diagnostics not shown (0 errors)"));
    CHECK_EQ(s->nerrors, 0);
    glib_free(s);

    n = (size_t)snprintf(t, cap, "##OpenGL GLIB\n");
    for (int i = 0; i < 300; i++)
        n += (size_t)snprintf(t + n, cap - n, "Sphere 0\n");
    s = glib_parse(t, n, "cap.glib");
    CHECK(s->ndiags == 200 && s->nerrors == 200);
    CHECK(has_diag(s, "cap.glib", 0, DIAG_ERROR, "101 more diagnostics not shown (101 errors)"));
    glib_free(s);
    free(t);
}

static void test_command_cap(void) {
    size_t cap = 20 + 17000 * 6, n = 0;
    char *t = malloc(cap);
    n += (size_t)snprintf(t, cap, "##OpenGL GLIB\n");
    for (int i = 0; i < 17000; i++)
        n += (size_t)snprintf(t + n, cap - n, "Clear\n");
    glib_scene *s = glib_parse(t, n, "many.glib");
    CHECK(s->ncmds == 16384 && s->nerrors == 1);
    CHECK(has_diag(s, "many.glib", 16384 + 2, DIAG_ERROR, "too many commands (more than 16384)"));
    glib_free(s);
    free(t);
}

/* Sizes and point counts a slider gives: `Texture2D 4 uRes uRes` names the
 * uniforms (kept in name and arg, num 0), a file stays a file, and
 * glib_uniform_consumed finds every uniform a command reads. */
static void test_sizes_from_sliders(void) {
    glib_scene *s = load("named/n.glib",
        "##OpenGL GLIB\n"
        "Texture2D 4 uRes uRes float16\n"               /* 2 */
        "Texture2D 5 512 uH depth\n"                    /* 3 */
        "Texture2D 6 uW 8\n"                            /* 4 */
        "WaterSurface points uN\n"                      /* 5 */
        "Camera wide uFov\n"                            /* 6 */
        "Texture2D 7 uRes 9x\n"                         /* 7 */
        "Texture2D 8 uRes\n");                          /* 8 */
    const char *f = P("named/n.glib");
    CHECK(has_diag(s, f, 7, DIAG_WARNING, "ignoring '9x'"));   /* a file 'uRes' with an extra word */
    CHECK(has_diag(s, f, 7, DIAG_ERROR, "cannot open"));
    CHECK(has_diag(s, f, 8, DIAG_ERROR, "cannot open"));
    CHECK_EQ(s->ncmds, 7);
    if (s->ncmds == 7) {
        const glib_cmd *c = s->cmds;
        CHECK(c[0].kind == GLIB_CMD_TEXTURE2D_EMPTY && c[0].nnum == 3 && strcmp(c[0].name, "uRes") == 0 &&
              strcmp(c[0].arg, "uRes") == 0 && c[0].num[1] == 0 && c[0].format == GLIB_TARGET_RGBA16F);
        CHECK(c[1].kind == GLIB_CMD_TEXTURE2D_EMPTY && c[1].name[0] == '\0' && c[1].num[1] == 512 &&
              strcmp(c[1].arg, "uH") == 0 && c[1].format == GLIB_TARGET_DEPTH);
        CHECK(strcmp(c[2].name, "uW") == 0 && c[2].arg[0] == '\0' && c[2].num[2] == 8);
        CHECK(c[3].kind == GLIB_CMD_WATER_SURFACE && strcmp(c[3].name, "points") == 0 &&
              strcmp(c[3].arg, "uN") == 0 && c[3].nnum == 0);
        CHECK(c[5].kind == GLIB_CMD_TEXTURE2D_FILE && strcmp(c[5].path, P("named/uRes")) == 0);
    }
    bool count = false;
    CHECK(glib_uniform_consumed(s, "uRes", &count) && count);
    CHECK(glib_uniform_consumed(s, "uH", &count) && count);
    CHECK(glib_uniform_consumed(s, "uN", &count) && count);
    CHECK(glib_uniform_consumed(s, "uFov", &count) && !count);
    CHECK(!glib_uniform_consumed(s, "uOther", NULL));
    glib_free(s);
}

static void test_textures(void) {
    put("tex/w.bmp", "x");
    put("tex/vol.tif", "x");
    put("tex/my water.png", "x");
    for (int i = 0; i < 6; i++) {
        char nm[32];
        snprintf(nm, sizeof nm, "tex/sky%d.png", i);
        put(nm, "x");
    }
    glib_scene *s = load("tex/t.glib",
        "##OpenGL GLIB\n"
        "Texture2D 5 w.bmp\n"                           /* 2 */
        "Texture2D 6 512 256\n"                         /* 3 */
        "Texture2D 7 512 256 float\n"                   /* 4 */
        "Texture2D 8 64 64 FLOAT16\n"                   /* 5 */
        "Texture2D 9 1024 1024 depth\n"                 /* 6 */
        "Texture2D 10 8 8 bogus\n"                      /* 7 */
        "Texture2D 11 512\n"                            /* 8 */
        "Texture3D 3 vol.tif\n"                         /* 9 */
        "Texture3D 4 64 32 16\n"                        /* 10 */
        "CubeMap 1 sky0.png sky1.png sky2.png sky3.png sky4.png sky5.png\n" /* 11 */
        "RenderToTexture 6 7\n"                         /* 12 */
        "RenderToTexture\n"                             /* 13 */
        "RenderToTexture 6 6\n"                         /* 14 */
        "Texture2D 12 \"my water.png\"\n"               /* 15 */
        "Texture2D 13 \"my water.png\n"                 /* 16 */
        "CubeMap 1 sky0.png\n"                          /* 17 */
        "Texture2D 5 my water.png\n"                    /* 18 */
        "Texture3D 4 64 32\n");                         /* 19 */
    const char *f = P("tex/t.glib");
    CHECK(has_diag(s, f, 7, DIAG_ERROR, "Texture2D: unknown format 'bogus'"));
    CHECK(has_diag(s, f, 8, DIAG_ERROR, "Texture2D: an empty texture needs a width and a height"));
    CHECK(has_diag(s, f, 14, DIAG_WARNING, "RenderToTexture: unit 6 is listed twice"));
    CHECK(has_diag(s, f, 16, DIAG_ERROR, "Texture2D: unclosed '\"'"));
    CHECK(has_diag(s, f, 17, DIAG_ERROR, "CubeMap needs a unit and 6 files, got 1 file"));
    CHECK(has_diag(s, f, 18, DIAG_WARNING, "ignoring 'water.png' (quote a path that has spaces"));
    CHECK(has_diag(s, f, 18, DIAG_ERROR, "cannot open"));
    CHECK(has_diag(s, f, 19, DIAG_ERROR, "Texture3D: an empty texture needs a width, a height and a depth"));
    CHECK(s->nerrors == 6 && count_sev(s, DIAG_WARNING) == 2);
    CHECK_EQ(s->ncmds, 13);
    if (s->ncmds == 13) {
        const glib_cmd *c = s->cmds;
        CHECK(c[0].kind == GLIB_CMD_TEXTURE2D_FILE && c[0].nnum == 1 && c[0].num[0] == 5 &&
              strcmp(c[0].path, P("tex/w.bmp")) == 0);
        CHECK(c[1].kind == GLIB_CMD_TEXTURE2D_EMPTY && c[1].nnum == 3 && c[1].num[1] == 512 &&
              c[1].num[2] == 256 && c[1].format == GLIB_TARGET_RGBA8 && c[1].path[0] == '\0');
        CHECK_EQ(c[2].format, GLIB_TARGET_RGBA32F);
        CHECK_EQ(c[3].format, GLIB_TARGET_RGBA16F);
        CHECK_EQ(c[4].format, GLIB_TARGET_DEPTH);
        CHECK(c[5].kind == GLIB_CMD_TEXTURE3D && c[5].nnum == 1 && strcmp(c[5].path, P("tex/vol.tif")) == 0);
        CHECK(c[6].kind == GLIB_CMD_TEXTURE3D && c[6].nnum == 4 && c[6].num[3] == 16 && c[6].path[0] == '\0');
        CHECK(c[7].kind == GLIB_CMD_CUBEMAP && c[7].cube_paths &&
              strcmp(c[7].cube_paths[0], P("tex/sky0.png")) == 0 &&
              strcmp(c[7].cube_paths[5], P("tex/sky5.png")) == 0);
        CHECK(c[8].kind == GLIB_CMD_RENDER_TO_TEXTURE && c[8].nnum == 2 && c[8].num[1] == 7);
        CHECK(c[9].kind == GLIB_CMD_RENDER_TO_TEXTURE && c[9].nnum == 0);
        CHECK_EQ(c[10].nnum, 2);
        CHECK(strcmp(c[11].path, P("tex/my water.png")) == 0 && c[11].line == 15);
        CHECK(strcmp(c[12].path, P("tex/my")) == 0 && c[12].line == 18);
    }
    glib_free(s);
}

static void test_define(void) {
    glib_scene *s = load("def.glib",
        "##OpenGL GLIB\n"
        "Define WAVES <true>\n"         /* 2 */
        "Define FOAM <False>\n"         /* 3 */
        "Define OCTAVES 4\n"            /* 4 */
        "Define STEPS <8 32 64>\n"      /* 5 */
        "Define BARE\n"                 /* 6 */
        "Program P1 uA 1\n"             /* 7 */
        "Define LATE 1\n"               /* 8 */
        "Define LATE 2\n"               /* 9 */
        "Program P2\n"                  /* 10 */
        "Define 1X\n"                   /* 11 */
        "Define C {1 0 0}\n"            /* 12 */
        "Define D <1 2>\n"              /* 13 */
        "Define E 1 junk\n"             /* 14 */
        "Define\n"                      /* 15 */
        "Define ORPHAN\n");             /* 16 */
    const char *f = P("def.glib");
    CHECK(has_diag(s, f, 9, DIAG_WARNING, "Define LATE is given twice before the next Program; the later one wins"));
    CHECK(has_diag(s, f, 11, DIAG_ERROR, "'1X' is not a valid Define name"));
    CHECK(has_diag(s, f, 12, DIAG_ERROR, "Define C takes <true>, <false>, a number or <min default max>, not a list"));
    CHECK(has_diag(s, f, 13, DIAG_ERROR, "Define D: <> needs 3 numbers"));
    CHECK(has_diag(s, f, 14, DIAG_WARNING, "Define E: ignoring 'junk' after the value"));
    CHECK(has_diag(s, f, 15, DIAG_ERROR, "Define needs a name"));
    CHECK(has_diag(s, f, 16, DIAG_WARNING, "Define ORPHAN comes after the last Program"));
    CHECK(has_diag(s, f, 14, DIAG_WARNING, "Define E comes after the last Program"));
    CHECK_EQ(s->nerrors, 4);
    /* DEFINE x5, P1, DEFINE x2, P2, DEFINE E, DEFINE ORPHAN */
    CHECK_EQ(s->ncmds, 11);
    if (s->ncmds == 11) {
        const glib_cmd *c = s->cmds;
        CHECK(c[0].kind == GLIB_CMD_DEFINE && strcmp(c[0].name, "WAVES") == 0 && c[0].nuniforms == 1 &&
              c[0].uniforms[0].kind == UNIF_DECL_BOOL && c[0].uniforms[0].v[0] == 1);
        CHECK(c[1].uniforms[0].kind == UNIF_DECL_BOOL && c[1].uniforms[0].v[0] == 0);
        CHECK(c[2].uniforms[0].kind == UNIF_DECL_SCALAR && c[2].uniforms[0].v[0] == 4);
        CHECK(c[3].uniforms[0].kind == UNIF_DECL_SLIDER && c[3].uniforms[0].v[1] == 32);
        CHECK(c[4].uniforms[0].kind == UNIF_DECL_BOOL && c[4].uniforms[0].v[0] == 1 &&
              strcmp(c[4].uniforms[0].name, "BARE") == 0);
        const glib_cmd *p1 = &c[5], *p2 = &c[8];
        CHECK(p1->kind == GLIB_CMD_PROGRAM && p1->ndefines == 5 && p1->nuniforms == 1);
        if (p1->ndefines == 5) {
            CHECK(strcmp(p1->defines[0].name, "WAVES") == 0 && p1->defines[0].line == 2);
            CHECK(strcmp(p1->defines[3].name, "STEPS") == 0 && p1->defines[3].v[2] == 64);
            CHECK_EQ(p1->defines[4].file, s->files[0]);
        }
        CHECK(p2->kind == GLIB_CMD_PROGRAM && p2->ndefines == 1 && p2->nuniforms == 0);
        if (p2->ndefines == 1)
            CHECK(strcmp(p2->defines[0].name, "LATE") == 0 && p2->defines[0].v[0] == 2 &&
                  p2->defines[0].line == 9);
        CHECK(c[9].kind == GLIB_CMD_DEFINE && strcmp(c[9].name, "E") == 0);
    }
    glib_free(s);
}

static void test_extensions(void) {
    glib_scene *s = load("ext.glib",
        "##OpenGL GLIB\n"
        "Cull back\n" "Cull FRONT\n" "Cull none\n" "Cull off\n" "Cull sideways\n" "Cull\n"
        "DepthTest on\n" "DepthTest OFF\n" "DepthTest 1\n" "DepthTest 0\n" "DepthTest maybe\n"
        "Blend alpha\n" "Blend add\n" "Blend off\n" "Blend none\n" "Blend screen\n");
    const char *f = P("ext.glib");
    CHECK(has_diag(s, f, 6, DIAG_ERROR, "Cull: unknown mode 'sideways': write back, front or none"));
    CHECK(has_diag(s, f, 7, DIAG_ERROR, "Cull needs one of back, front or none"));
    CHECK(has_diag(s, f, 12, DIAG_ERROR, "DepthTest: unknown mode 'maybe': write on or off"));
    CHECK(has_diag(s, f, 17, DIAG_ERROR, "Blend: unknown mode 'screen'"));
    CHECK(s->nerrors == 4 && s->ncmds == 12);
    if (s->ncmds == 12) {
        const glib_cmd *c = s->cmds;
        CHECK(c[0].kind == GLIB_CMD_CULL && strcmp(c[0].name, "back") == 0);
        CHECK(strcmp(c[1].name, "front") == 0 && strcmp(c[2].name, "none") == 0 &&
              strcmp(c[3].name, "none") == 0);
        CHECK(c[4].kind == GLIB_CMD_DEPTH_TEST && c[4].nnum == 1 && c[4].num[0] == 1);
        CHECK(c[5].num[0] == 0 && c[6].num[0] == 1 && c[7].num[0] == 0);
        CHECK(c[8].kind == GLIB_CMD_BLEND && strcmp(c[8].name, "alpha") == 0);
        CHECK(strcmp(c[9].name, "add") == 0 && strcmp(c[10].name, "off") == 0 &&
              strcmp(c[11].name, "off") == 0);
    }
    glib_free(s);
}

static void test_program_errors(void) {
    glib_scene *s = load("prog.glib",
        "##OpenGL GLIB\n"
        "Program\n"                     /* 2 */
        "Program P uA\n"                /* 3 */
        "Program P uA true\n"           /* 4 */
        "Program P 2x 1 uB 2\n"         /* 5 */
        "Program P <0 1 2> uC 3\n"      /* 6 */
        "Program P uA 1 }\n");          /* 7 */
    const char *f = P("prog.glib");
    CHECK(has_diag(s, f, 2, DIAG_ERROR, "Program needs a name: Program Name [uniform value ...]"));
    CHECK(has_diag(s, f, 3, DIAG_ERROR, "Program P: uniform 'uA' has no value: write uA 5"));
    CHECK(has_diag(s, f, 4, DIAG_ERROR, "uniform 'uA': write <true> (with the angle brackets) for a checkbox"));
    CHECK(has_diag(s, f, 5, DIAG_ERROR, "'2x' is not a valid uniform name"));
    CHECK(has_diag(s, f, 6, DIAG_ERROR, "Program P: a value '<...' has no uniform name before it"));
    CHECK(has_diag(s, f, 7, DIAG_ERROR, "'}' is not a valid uniform name"));
    CHECK(s->nerrors == 6 && s->ncmds == 5);
    if (s->ncmds == 5) {
        CHECK(s->cmds[2].nuniforms == 1 && strcmp(s->cmds[2].uniforms[0].name, "uB") == 0);
        CHECK(s->cmds[3].nuniforms == 1 && strcmp(s->cmds[3].uniforms[0].name, "uC") == 0);
    }
    glib_free(s);
}

/* ------------------------------------------------------------------ */
/* describing the world                                                */

static void test_world_commands(void) {
    glib_scene *s = load("world.glib",
        "##OpenGL GLIB\n"
        "Sun 0.4 0.8 -0.45\n"                                   /* 2 */
        "sun 1 2 3  3 2.85 2.6\n"                               /* 3 */
        "Sky 0.25 0.45 0.85  0.7 0.8 0.92\n"                    /* 4 */
        "Water 0.1\n"                                           /* 5 */
        "Water -0.5 1.34\n"                                     /* 6 */
        "Water 0 1.333 0.45 0.09 0.06\n"                        /* 7 */
        "WaterMesh 128\n"                                       /* 8 */
        "Terrain LAKE\n"                                        /* 9 */
        "Terrain slope 10 2 0.3 7 64\n"                         /* 10 */
        "WaveSine 160 2.3 0.012\n"                              /* 11 */
        "WaveGerstner 20 9 0.1 1.5 2\n"                         /* 12 */
        "WaveSteepness 0.6\n"                                   /* 13 */
        "WaveNoise 0.01 2 3 0 30 1 32 0.5\n"                    /* 14 */
        "Object sphere 1 2 3 0.5 0.1 0.2 0.3\n"                 /* 15 */
        "Object Box 1 2 3 0.4 0.5 0.6 0.7 0.8 0.9\n"            /* 16 */
        "Object cylinder -7.5 0.3 6.5 0.25 2.2 0.35 0.25 0.15\n" /* 17 */
        "Pack basic\n"                                          /* 18 */
        "World\n"                                               /* 19 */
        "World below\n"                                         /* 20 */
        "WaterSurface\n");                                      /* 21 */
    CHECK_NO_DIAGS(s);
    CHECK_EQ(s->ncmds, 20);
    static const glib_cmd_kind kinds[] = {
        GLIB_CMD_SUN, GLIB_CMD_SUN, GLIB_CMD_SKY, GLIB_CMD_WATER, GLIB_CMD_WATER, GLIB_CMD_WATER,
        GLIB_CMD_WATER_MESH, GLIB_CMD_TERRAIN, GLIB_CMD_TERRAIN, GLIB_CMD_WAVE_SINE,
        GLIB_CMD_WAVE_GERSTNER, GLIB_CMD_WAVE_STEEPNESS, GLIB_CMD_WAVE_NOISE, GLIB_CMD_OBJECT,
        GLIB_CMD_OBJECT, GLIB_CMD_OBJECT, GLIB_CMD_PACK, GLIB_CMD_WORLD, GLIB_CMD_WORLD,
        GLIB_CMD_WATER_SURFACE };
    for (int i = 0; i < s->ncmds && i < 20; i++) {
        CHECK_MSG(s->cmds[i].kind == kinds[i], "cmd %d", i);
        CHECK_MSG(s->cmds[i].line == i + 2, "cmd %d line %d", i, s->cmds[i].line);
    }
    if (s->ncmds == 20) {
        const glib_cmd *c = s->cmds;
        /* nnum counts the numbers written: the rest are the world's defaults */
        CHECK(c[0].nnum == 3 && c[0].num[0] == 0.4 && c[0].num[2] == -0.45 && c[0].num[3] == 0);
        CHECK(c[1].nnum == 6 && c[1].num[3] == 3 && c[1].num[5] == 2.6);
        CHECK(c[2].nnum == 6 && c[2].num[0] == 0.25 && c[2].num[5] == 0.92);
        CHECK(c[3].nnum == 1 && c[3].num[0] == 0.1);
        CHECK(c[4].nnum == 2 && c[4].num[0] == -0.5 && c[4].num[1] == 1.34);
        CHECK(c[5].nnum == 5 && c[5].num[2] == 0.45 && c[5].num[4] == 0.06);
        CHECK(c[6].nnum == 1 && c[6].num[0] == 128);
        CHECK(strcmp(c[7].name, "lake") == 0 && c[7].nnum == 0);
        CHECK(strcmp(c[8].name, "slope") == 0 && c[8].nnum == 5 && c[8].num[0] == 10 &&
              c[8].num[1] == 2 && c[8].num[2] == 0.3 && c[8].num[3] == 7 && c[8].num[4] == 64);
        CHECK(c[9].nnum == 3 && c[9].num[0] == 160 && c[9].num[1] == 2.3 && c[9].num[2] == 0.012);
        CHECK(c[10].nnum == 5 && c[10].num[3] == 1.5 && c[10].num[4] == 2);
        CHECK(c[11].nnum == 1 && c[11].num[0] == 0.6);
        CHECK(c[12].nnum == 8 && c[12].num[0] == 0.01 && c[12].num[2] == 3 && c[12].num[4] == 30 &&
              c[12].num[6] == 32 && c[12].num[7] == 0.5);
        CHECK(strcmp(c[13].name, "sphere") == 0 && c[13].nnum == 7 && c[13].num[3] == 0.5 &&
              c[13].num[6] == 0.3);
        CHECK(strcmp(c[14].name, "box") == 0 && c[14].nnum == 9 && c[14].num[8] == 0.9);
        CHECK(strcmp(c[15].name, "cylinder") == 0 && c[15].nnum == 8 && c[15].num[1] == 0.3 &&
              c[15].num[4] == 2.2);
        CHECK_STR_EQ(c[16].name, "basic");
        CHECK(strcmp(c[17].name, "all") == 0 && strcmp(c[18].name, "below") == 0);
        CHECK_EQ(c[19].nnum, 0);
    }
    glib_free(s);
}

static void test_world_errors(void) {
    glib_scene *s = load("world_bad.glib",
        "##OpenGL GLIB\n"
        "Sun 1 2\n"                             /* 2 */
        "Sun 0 0 0\n"                           /* 3 */
        "Sun 0 1 0 1\n"                         /* 4 */
        "Water 0 1.3 0.1\n"                     /* 5 */
        "Water\n"                               /* 6 */
        "WaterMesh 1.5\n"                       /* 7 */
        "Terrain\n"                             /* 8 */
        "Terrain pond\n"                        /* 9 */
        "Terrain lake 12 x\n"                   /* 10 */
        "Terrain lake 12 3 0.6 -1\n"            /* 11 */
        "WaveSine 10 2\n"                       /* 12 */
        "WaveGerstner 10\n"                     /* 13 */
        "WaveNoise 0.1 2 3.5\n"                 /* 14 */
        "Object sphere 1 2 3\n"                 /* 15 */
        "Object cone 1 2 3 4 5 6 7\n"           /* 16 */
        "Object\n"                              /* 17 */
        "World sideways\n"                      /* 18 */
        "WaterSurface now\n"                    /* 19 */
        "Sky 1 1 1 1 1 1 1\n"                   /* 20 */
        "Pack\n"                                /* 21 */
        "Pack ../evil\n"                        /* 22 */
        "Sky 1 1 1\n");                         /* 23 */
    const char *f = P("world_bad.glib");
    CHECK(has_diag(s, f, 2, DIAG_ERROR, "Sun needs a direction z: Sun dx dy dz [r g b]"));
    CHECK(has_diag(s, f, 3, DIAG_ERROR, "Sun: the direction is zero"));
    CHECK(has_diag(s, f, 4, DIAG_ERROR, "Sun: the irradiance needs 3 numbers (r g b), got 1"));
    CHECK(has_diag(s, f, 5, DIAG_ERROR, "Water: the absorption needs 3 numbers (ar ag ab), got 1: Water level [ior [ar ag ab]]"));
    CHECK(has_diag(s, f, 6, DIAG_ERROR, "Water needs a water level"));
    CHECK(has_diag(s, f, 7, DIAG_ERROR, "WaterMesh: res must be a whole number from 0 to 65536, not '1.5'"));
    CHECK(has_diag(s, f, 8, DIAG_ERROR, "Terrain needs one of flat, lake, slope or pool"));
    CHECK(has_diag(s, f, 9, DIAG_ERROR, "Terrain: unknown kind 'pond': write flat, lake, slope or pool"));
    CHECK(has_diag(s, f, 10, DIAG_ERROR, "Terrain: bad number 'x' for depth"));
    CHECK(has_diag(s, f, 11, DIAG_ERROR, "Terrain: seed must be a whole number from 0 to 4294967295, not '-1'"));
    CHECK(has_diag(s, f, 12, DIAG_ERROR, "WaveSine needs an amplitude: WaveSine angle_deg wavelength amplitude [speed [phase]]"));
    CHECK(has_diag(s, f, 13, DIAG_ERROR, "WaveGerstner needs at least 3 numbers, got 1"));
    CHECK(has_diag(s, f, 14, DIAG_ERROR, "WaveNoise: octaves must be a whole number"));
    CHECK(has_diag(s, f, 15, DIAG_ERROR, "Object sphere needs 7 numbers, got 3: Object sphere x y z r R G B"));
    CHECK(has_diag(s, f, 16, DIAG_ERROR, "Object: unknown kind 'cone': write sphere, box, cylinder or mesh"));
    CHECK(has_diag(s, f, 17, DIAG_ERROR, "Object needs one of sphere, box, cylinder or mesh"));
    CHECK(has_diag(s, f, 18, DIAG_ERROR, "World: unknown mode 'sideways': write World all|above|below [offset]"));
    CHECK(has_diag(s, f, 19, DIAG_ERROR, "WaterSurface: write WaterSurface, WaterSurface points N or WaterSurface mesh N"));
    CHECK(has_diag(s, f, 20, DIAG_WARNING, "Sky takes at most 6 arguments; ignoring '1'"));
    CHECK(has_diag(s, f, 21, DIAG_ERROR, "Pack needs a name: Pack name"));
    CHECK(has_diag(s, f, 22, DIAG_ERROR, "Pack: '../evil' is not a pack name"));
    CHECK(has_diag(s, f, 23, DIAG_ERROR, "Sky needs 6 numbers, got 3"));
    CHECK(s->nerrors == 21 && count_sev(s, DIAG_WARNING) == 1);
    CHECK_EQ(s->ncmds, 1);       /* Sky 1 1 1 1 1 1 (1) */
    glib_free(s);
}

/* Issue #25's world commands: the look (SkySun, Clouds, Haze,
 * GroundDetail) keep the numbers written; Object mesh resolves its file
 * beside the scene and takes 3 to 8 numbers, a colour whole or not at all. */
static void test_look_commands(void) {
    put("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    glib_scene *s = load("look.glib",
        "##OpenGL GLIB\n"
        "SkySun 0.27\n"                          /* 2 */
        "Clouds 0.5 900 1500\n"                  /* 3 */
        "Haze 300\n"                             /* 4 */
        "GroundDetail 1\n"                       /* 5 */
        "Object mesh m.obj 1 2 3 45 2 0.5 0.4 0.3\n" /* 6 */
        "Object mesh m.obj 1 2 3\n"              /* 7 */
        "SkySun\n"                               /* 8 */
        "Clouds x\n"                             /* 9 */
        "Object mesh\n"                          /* 10 */
        "Object mesh m.obj 1 2\n"                /* 11 */
        "Object mesh m.obj 1 2 3 0 1 0.5\n"      /* 12 */
        "Object mesh nothere.obj 1 2 3\n");      /* 13 */
    const char *f = P("look.glib");
    CHECK(has_diag(s, f, 8, DIAG_ERROR, "SkySun needs an angular radius in degrees"));
    CHECK(has_diag(s, f, 9, DIAG_ERROR, "Clouds: bad number 'x'"));
    CHECK(has_diag(s, f, 10, DIAG_ERROR, "Object mesh needs a file"));
    CHECK(has_diag(s, f, 11, DIAG_ERROR, "Object mesh needs at least 3 numbers, got 2"));
    CHECK(has_diag(s, f, 12, DIAG_ERROR, "Object mesh: the colour needs 3 numbers (R G B), got 1"));
    CHECK(has_diag(s, f, 13, DIAG_ERROR, "cannot open"));
    CHECK_GE(s->ncmds, 6);
    if (s->ncmds >= 6) {
        const glib_cmd *c = s->cmds;
        CHECK(c[0].kind == GLIB_CMD_SKY_SUN && c[0].nnum == 1 && c[0].num[0] == 0.27);
        CHECK(c[1].kind == GLIB_CMD_CLOUDS && c[1].nnum == 3 && c[1].num[2] == 1500);
        CHECK(c[2].kind == GLIB_CMD_HAZE && c[2].num[0] == 300);
        CHECK(c[3].kind == GLIB_CMD_GROUND_DETAIL && c[3].num[0] == 1);
        CHECK(c[4].kind == GLIB_CMD_OBJECT && strcmp(c[4].name, "mesh") == 0 && c[4].nnum == 8 &&
              c[4].num[3] == 45 && c[4].num[7] == 0.3 && strstr(c[4].path, "m.obj") != NULL);
        CHECK(c[5].kind == GLIB_CMD_OBJECT && c[5].nnum == 3);
    }
    glib_free(s);
}

/* The pack contract's drawing commands (docs/packs/contract.md). */
static void test_pack_contract_commands(void) {
    glib_scene *s = load("contract.glib",
        "##OpenGL GLIB\n"
        "Camera mirror 1.5\n"                  /* 2 */
        "Camera main uFovScale\n"              /* 3 */
        "Camera top\n"                         /* 4 */
        "World above -0.02\n"                  /* 5 */
        "WaterSurface points 64\n"             /* 6 */
        "RenderToTextureOnce 6 7\n"            /* 7 */
        "Splat 8 9\n"                          /* 8 */
        "Texture2D 10 @caustics\n"             /* 9 */
        "Camera sideways\n"                    /* 10 */
        "Camera main 0\n"                      /* 11 */
        "Texture2D 11 @nothing\n"              /* 12 */
        "WaterSurface points\n"                /* 13 */
        "Splat 1\n"                           /* 14 */
        "WaterSurface mesh uPhotonGrid\n");    /* 15 */
    const char *f = P("contract.glib");
    CHECK_EQ(s->ncmds, 9);
    if (s->ncmds == 9) {
        CHECK(s->cmds[0].kind == GLIB_CMD_CAMERA && !strcmp(s->cmds[0].name, "mirror") && s->cmds[0].nnum == 1 &&
              s->cmds[0].num[0] == 1.5 && s->cmds[0].arg[0] == '\0');
        CHECK(s->cmds[1].kind == GLIB_CMD_CAMERA && !strcmp(s->cmds[1].name, "main") && s->cmds[1].nnum == 0 &&
              !strcmp(s->cmds[1].arg, "uFovScale"));
        CHECK(s->cmds[2].kind == GLIB_CMD_CAMERA && !strcmp(s->cmds[2].name, "top"));
        CHECK(s->cmds[3].kind == GLIB_CMD_WORLD && !strcmp(s->cmds[3].name, "above") && s->cmds[3].nnum == 1 &&
              s->cmds[3].num[0] == -0.02);
        CHECK(s->cmds[4].kind == GLIB_CMD_WATER_SURFACE && !strcmp(s->cmds[4].name, "points") &&
              s->cmds[4].num[0] == 64);
        CHECK(s->cmds[5].kind == GLIB_CMD_RENDER_TO_TEXTURE_ONCE && s->cmds[5].nnum == 2 && s->cmds[5].num[1] == 7);
        CHECK(s->cmds[6].kind == GLIB_CMD_SPLAT && s->cmds[6].num[0] == 8 && s->cmds[6].num[1] == 9);
        CHECK(s->cmds[7].kind == GLIB_CMD_TEXTURE2D_FILE && !strcmp(s->cmds[7].path, "@caustics"));
        CHECK(s->cmds[8].kind == GLIB_CMD_WATER_SURFACE && !strcmp(s->cmds[8].name, "mesh") &&
              !strcmp(s->cmds[8].arg, "uPhotonGrid") && s->cmds[8].nnum == 0);
    }
    CHECK(has_diag(s, f, 10, DIAG_ERROR, "Camera: unknown camera 'sideways'"));
    CHECK(has_diag(s, f, 11, DIAG_ERROR, "Camera: fov_scale must be greater than 0"));
    CHECK(has_diag(s, f, 12, DIAG_ERROR, "unknown generated texture '@nothing'"));
    CHECK(has_diag(s, f, 13, DIAG_ERROR, "WaterSurface: write WaterSurface, WaterSurface points N or WaterSurface mesh N"));
    CHECK(has_diag(s, f, 14, DIAG_ERROR, "Splat needs"));
    glib_free(s);
}

static glib_scene *load_opts(const char *name, const char *text, const char *packs,
                             const char *override) {
    put(name, text);
    glib_options o = { .packs_dir = packs, .pack_override = override };
    return glib_load_opts(P(name), &o);
}

static void test_pack_include(void) {
    put("pk/packs/calm/water.vert", "x");
    put("pk/packs/calm/pack.glib", "##OpenGL GLIB\n# the calm pack\nWorld\nVertex water.vert\nSphere -1\nWaterSurface\n");
    put("pk/packs/rough/pack.glib", "World above\n");
    put("pk/packs/notapack/readme.txt", "x");
    const char *text = "##OpenGL GLIB\nSun 0 1 0\nPack calm\nSphere 2\n";
    glib_scene *s = load_opts("pk/lake.glib", text, P("pk/packs"), NULL);
    /* the pack's lines come in place of the Pack line, and its messages
     * name its own file and lines */
    CHECK(has_diag(s, P("pk/packs/calm/pack.glib"), 5, DIAG_ERROR, "Sphere: r must be greater than 0"));
    CHECK(s->nerrors == 1 && s->ndiags == 1);
    CHECK(s->nfiles == 2 && strcmp(s->files[1], P("pk/packs/calm/pack.glib")) == 0);
    CHECK_EQ(s->ncmds, 6);
    if (s->ncmds == 6) {
        const glib_cmd *c = s->cmds;
        CHECK_EQ(c[0].kind, GLIB_CMD_SUN);
        CHECK(c[1].kind == GLIB_CMD_PACK && strcmp(c[1].name, "calm") == 0 && c[1].line == 3 &&
              c[1].file == s->files[0]);
        CHECK(c[2].kind == GLIB_CMD_WORLD && c[2].file == s->files[1] && c[2].line == 3);
        CHECK(c[3].kind == GLIB_CMD_VERTEX && strcmp(c[3].path, P("pk/packs/calm/water.vert")) == 0);
        CHECK(c[4].kind == GLIB_CMD_WATER_SURFACE && c[4].line == 6);
        CHECK(c[5].kind == GLIB_CMD_SPHERE && c[5].file == s->files[0] && c[5].line == 4);
    }
    glib_free(s);

    /* without a packs directory, Pack is only recorded */
    s = load_opts("pk/lake.glib", text, NULL, NULL);
    CHECK_NO_DIAGS(s);
    CHECK(s->ncmds == 3 && s->cmds[1].kind == GLIB_CMD_PACK && strcmp(s->cmds[1].name, "calm") == 0);
    glib_free(s);
    s = glib_load(P("pk/lake.glib"));           /* glib_load is glib_load_opts(path, NULL) */
    CHECK(s->ncmds == 3 && s->ndiags == 0);
    glib_free(s);

    /* a second Pack is a warning, and only the first pack is read */
    s = load_opts("pk/two.glib", "##OpenGL GLIB\nPack rough\nPack calm\n", P("pk/packs"), NULL);
    CHECK(has_diag(s, P("pk/two.glib"), 3, DIAG_WARNING,
                   "Pack calm ignored: this scene's pack is already 'rough'"));
    CHECK(s->ncmds == 2 && s->cmds[0].kind == GLIB_CMD_PACK && s->cmds[1].kind == GLIB_CMD_WORLD &&
          strcmp(s->cmds[1].name, "above") == 0);
    glib_free(s);

    /* a pack that includes the scene that names it is a cycle */
    put("pk/packs/loop/pack.glib", "Include ../../cyc.glib\n");
    s = load_opts("pk/cyc.glib", "##OpenGL GLIB\nPack loop\n", P("pk/packs"), NULL);
    CHECK(has_diag(s, P("pk/packs/loop/pack.glib"), 1, DIAG_ERROR, "Include cycle:"));
    glib_free(s);
}

static void test_pack_missing(void) {
    put("pm/packs/basic/pack.glib", "World\n");
    put("pm/packs/natural/pack.glib", "World\n");
    put("pm/packs/common/waves.glsl", "x");
    glib_scene *s = load_opts("pm/a.glib", "##OpenGL GLIB\n\nPack basik\nSphere 1\n", P("pm/packs"), NULL);
    char want[600];
    snprintf(want, sizeof want,
             "Pack: no pack 'basik' in %s (no basik/pack.glib); the packs are: basic, natural; did you mean 'basic'?",
             P("pm/packs"));
    CHECK(has_diag(s, P("pm/a.glib"), 3, DIAG_ERROR, want));
    /* the command stays, so tools see which pack was asked for */
    CHECK(s->nerrors == 1 && s->ncmds == 2 && s->cmds[0].kind == GLIB_CMD_PACK &&
          strcmp(s->cmds[0].name, "basik") == 0);
    glib_free(s);

    s = load_opts("pm/b.glib", "##OpenGL GLIB\nPack x\n", P("pm/nowhere"), NULL);
    CHECK(has_diag(s, P("pm/b.glib"), 2, DIAG_ERROR, "the packs are: (none)"));
    glib_free(s);
}

static void test_pack_override(void) {
    put("po/packs/basic/pack.glib", "World\n");
    put("po/packs/natural/pack.glib", "World above\nWorld below\n");
    /* the override replaces the scene's pack */
    glib_scene *s = load_opts("po/a.glib", "##OpenGL GLIB\nPack basic\nSphere 1\n", P("po/packs"), "natural");
    CHECK_NO_DIAGS(s);
    CHECK_EQ(s->ncmds, 4);
    if (s->ncmds == 4) {
        CHECK(s->cmds[0].kind == GLIB_CMD_PACK && strcmp(s->cmds[0].name, "natural") == 0 &&
              s->cmds[0].line == 2);
        CHECK(strcmp(s->cmds[1].name, "above") == 0 && strcmp(s->cmds[2].name, "below") == 0);
        CHECK_EQ(s->cmds[3].kind, GLIB_CMD_SPHERE);
    }
    glib_free(s);

    /* a world scene with no Pack gets the override's at the end of the top file */
    put("po/inc.glib", "Sphere 2\n");
    s = load_opts("po/b.glib", "##OpenGL GLIB\nInclude inc.glib\nSphere 1\nSun 0 1 0\n", P("po/packs"), "basic");
    CHECK_NO_DIAGS(s);
    CHECK_EQ(s->ncmds, 5);
    if (s->ncmds == 5) {
        CHECK(s->cmds[0].num[0] == 2 && s->cmds[1].num[0] == 1);
        CHECK(s->cmds[3].kind == GLIB_CMD_PACK && strcmp(s->cmds[3].name, "basic") == 0 &&
              s->cmds[3].file == s->files[0] && s->cmds[3].line == 0);
        CHECK(s->cmds[4].kind == GLIB_CMD_WORLD && strcmp(s->cmds[4].file, P("po/packs/basic/pack.glib")) == 0);
    }
    glib_free(s);

    /* a plain glman scene (no world command) given a pack is refused: the
     * pack would draw its world and water over the scene's own */
    s = load_opts("po/glman.glib", "##OpenGL GLIB\nInclude inc.glib\nSphere 1\n", P("po/packs"), "basic");
    CHECK(has_diag(s, P("po/glman.glib"), 0, DIAG_ERROR, "--pack basic: this scene describes no world"));
    CHECK(has_diag(s, P("po/glman.glib"), 0, DIAG_ERROR, "Give --pack a world scene (scenes/lake.glib"));
    CHECK_EQ(s->nerrors, 1);
    for (int i = 0; i < s->ncmds; i++) CHECK(s->cmds[i].kind != GLIB_CMD_PACK && s->cmds[i].kind != GLIB_CMD_WORLD);
    glib_free(s);

    /* a missing override pack is an error at line 0 of the top file */
    s = load_opts("po/c.glib", "##OpenGL GLIB\nSun 0 1 0\nSphere 1\n", P("po/packs"), "nope");
    CHECK(has_diag(s, P("po/c.glib"), 0, DIAG_ERROR, "no pack 'nope'"));
    CHECK(has_diag(s, P("po/c.glib"), 0, DIAG_ERROR, "the packs are: basic, natural"));
    glib_free(s);
    s = load_opts("po/d.glib", "##OpenGL GLIB\nPack basic\n", P("po/packs"), "a/b");
    CHECK(has_diag(s, P("po/d.glib"), 2, DIAG_ERROR, "'a/b' (the pack chosen instead of the scene's) is not a pack name"));
    glib_free(s);

    /* no packs directory: the name is replaced or added, nothing is read */
    s = load_opts("po/e.glib", "##OpenGL GLIB\nSphere 1\nSky 0.2 0.4 0.8 0.7 0.8 0.9\n", NULL, "natural");
    CHECK_NO_DIAGS(s);
    CHECK(s->ncmds == 3 && s->cmds[2].kind == GLIB_CMD_PACK && strcmp(s->cmds[2].name, "natural") == 0);
    glib_free(s);
}

static void test_print_diags(void) {
    glib_scene *s = load("print.glib", "##OpenGL GLIB\n\nFoo\nSphere 0\n");
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    glib_print_diags(s, f);
    fclose(f);
    char want[1200];
    snprintf(want, sizeof want,
             "%s:3: warning: unknown command 'Foo' (skipped)\n"
             "%s:4: error: Sphere: r must be greater than 0, not '0'\n",
             P("print.glib"), P("print.glib"));
    CHECK_MSG(buf && strcmp(buf, want) == 0, "got:\n%s", buf ? buf : "(null)");
    free(buf);
    glib_free(s);
}

static void test_cmd_name(void) {
    CHECK_STR_EQ(glib_cmd_name(GLIB_CMD_QUAD_XZ), "QuadXZ");
    CHECK_STR_EQ(glib_cmd_name(GLIB_CMD_TEXTURE2D_EMPTY), "Texture2D");
    CHECK_STR_EQ(glib_cmd_name(GLIB_CMD_DEPTH_TEST), "DepthTest");
    CHECK_STR_EQ(glib_cmd_name(GLIB_CMD_KIND_COUNT), "?");
    CHECK_STR_EQ(glib_cmd_name((glib_cmd_kind)-1), "?");
    CHECK_STR_EQ(glib_cmd_name(GLIB_CMD_WAVE_GERSTNER), "WaveGerstner");
    CHECK_STR_EQ(glib_cmd_name(GLIB_CMD_WATER_SURFACE), "WaterSurface");
    for (int k = 1; k < GLIB_CMD_KIND_COUNT; k++)
        CHECK_MSG(strcmp(glib_cmd_name((glib_cmd_kind)k), "?") != 0, "kind %d", k);
}

/* The way glman projects are written: CRLF, tabs, Windows paths, padded
 * brackets, wire shapes, comments everywhere. */
static void test_glman_real_file(void) {
    put("proj/ocean.vert", "x");
    put("proj/ocean.frag", "x");
    put("proj/textures/sky.bmp", "x");
    glib_scene *s = load("proj/ocean.glib",
        "##OpenGL GLIB\r\n"
        "// Project 5 -- ocean\r\n"
        "\r\n"
        "Perspective 70\r\n"
        "LookAt 0 0 3  0 0 0  0 1 0\r\n"
        "\r\n"
        "Texture2D  5  textures\\sky.bmp\r\n"
        "Vertex   ocean.vert\r\n"
        "Fragment ocean.frag\r\n"
        "Program  Ocean\t\t\t\t\\\r\n"
        "\tuAmp   <0. 0.1 0.5>\t\t\\\r\n"
        "\tuColor {0.40, 1.0, 0.95, 1.}\t\\\r\n"
        "\tuSky   5\t\t\t\\\r\n"
        "\tuUseFoam <true>\r\n"
        "\r\n"
        "TransformBegin\r\n"
        "\tTranslate 0. -0.2 0.\r\n"
        "\tQuadXZ -0.2 2. 200 200\r\n"
        "TransformEnd\r\n"
        "WireSphere 0.25 30 30  # the buoy\r\n"
        "Noise3D 128\r");
    CHECK_NO_DIAGS(s);
    CHECK_EQ(s->ncmds, 12);
    if (s->ncmds == 12) {
        const glib_cmd *c = s->cmds;
        CHECK(c[2].kind == GLIB_CMD_TEXTURE2D_FILE && strcmp(c[2].path, P("proj/textures/sky.bmp")) == 0);
        CHECK(c[5].kind == GLIB_CMD_PROGRAM && c[5].line == 10 && c[5].nuniforms == 4);
        const unif_decl *u = find_uniform(&c[5], "uColor");
        CHECK(u && u->n == 4 && u->v[2] == 0.95);
        CHECK((u = find_uniform(&c[5], "uUseFoam")) && u->kind == UNIF_DECL_BOOL);
        CHECK(c[6].kind == GLIB_CMD_PUSH_MATRIX && c[6].line == 16);
        CHECK(c[8].kind == GLIB_CMD_QUAD_XZ && c[8].num[2] == 200);
        CHECK(c[10].kind == GLIB_CMD_SPHERE && c[10].wire && c[10].line == 20);
        CHECK(c[11].kind == GLIB_CMD_NOISE3D && c[11].line == 21);
    }
    glib_free(s);

    /* old Mac line ends (a lone CR) count lines too */
    s = load("proj/cr.glib", "##OpenGL GLIB\rSphere 1\r\rSphere 0\r");
    CHECK(s->ncmds == 1 && s->cmds[0].line == 2);
    CHECK(has_diag(s, P("proj/cr.glib"), 4, DIAG_ERROR, "Sphere: r must be greater than 0"));
    glib_free(s);
}

/* Issue 14: numbers as glman's atof read them, brackets and commas around
 * plain numbers, a header with a version after it, <0>/<1> checkboxes. */
static void test_glman_numbers(void) {
    glib_scene *s = load("gl14/num.glib",
        "##OpenGL GLIB 8\n"                    /* 1 */
        "Translate 0.1. -0.1. 1..\n"           /* 2 */
        "Color [1 0 0]\n"                      /* 3 */
        "Background [0 0.5 0]\n"               /* 4 */
        "Color 1, 0.5, 0\n"                    /* 5 */
        "Program P uOn <1> uOff <0> uTwo <2> uT <true>\n"); /* 6 */
    const char *f = P("gl14/num.glib");
    CHECK(has_diag(s, f, 2, DIAG_WARNING, "Translate: '0.1.' read as 0.1"));
    CHECK(has_diag(s, f, 2, DIAG_WARNING, "'-0.1.' read as -0.1"));
    CHECK(has_diag(s, f, 2, DIAG_WARNING, "'1..' read as 1"));
    CHECK(s->nerrors == 0 && s->ndiags == 3);
    CHECK_EQ(s->ncmds, 5);
    if (s->ncmds == 5) {
        const glib_cmd *c = s->cmds;
        CHECK(c[0].num[0] == 0.1 && c[0].num[1] == -0.1 && c[0].num[2] == 1);
        CHECK(c[1].kind == GLIB_CMD_COLOR && c[1].num[0] == 1 && c[1].num[1] == 0 && c[1].num[3] == 1);
        CHECK(c[2].kind == GLIB_CMD_BACKGROUND && c[2].num[1] == 0.5);
        CHECK(c[3].num[0] == 1 && c[3].num[1] == 0.5 && c[3].num[2] == 0);
        const unif_decl *u;
        CHECK((u = find_uniform(&c[4], "uOn")) && u->kind == UNIF_DECL_BOOL && u->v[0] == 1);
        CHECK((u = find_uniform(&c[4], "uOff")) && u->kind == UNIF_DECL_BOOL && u->v[0] == 0);
        CHECK((u = find_uniform(&c[4], "uTwo")) && u->kind == UNIF_DECL_BOOL && u->v[0] == 1);
        CHECK((u = find_uniform(&c[4], "uT")) && u->kind == UNIF_DECL_BOOL && u->v[0] == 1);
    }
    glib_free(s);
}

/* Issue 14: missing arguments take glman's defaults (docs/glib.md). */
static void test_glman_defaults(void) {
    glib_scene *s = load("gl14/def.glib",
        "##OpenGL GLIB\n"
        "Sphere\nSphere 2\nTorus\nQuadXY\nBox\nCone\nCylinder\nPerspective\nOrtho\n"
        "Translate 1 2\nNoise2D\nNoise3D 300\nWireSphere\n");
    /* issue 27: a 2-number Translate is glman's (0 for z), with a warning */
    CHECK(s->ndiags == 1 && has_diag(s, P("gl14/def.glib"), 11, DIAG_WARNING,
                                     "Translate has 2 numbers; glman fills the missing ones with 0 (Translate 1 2 0)"));
    CHECK_EQ(s->ncmds, 13);
    if (s->ncmds == 13) {
        const glib_cmd *c = s->cmds;
        CHECK(c[0].num[0] == 1 && c[0].num[1] == 60 && c[0].num[2] == 60);
        CHECK(c[1].num[0] == 2 && c[1].num[1] == 60 && c[1].num[2] == 60);
        CHECK(c[2].num[0] == 1 && c[2].num[1] == 0.5 && c[2].num[2] == 20 && c[2].num[3] == 40);
        CHECK(c[3].num[0] == 0 && c[3].num[1] == 1 && c[3].num[2] == 1 && c[3].num[3] == 1);
        CHECK(c[4].num[0] == 2 && c[4].num[1] == 2 && c[4].num[2] == 2);
        CHECK(c[5].num[0] == 1 && c[5].num[1] == 1);
        CHECK(c[6].num[0] == 1 && c[6].num[1] == 1);
        CHECK_EQ(c[7].num[0], 50);
        CHECK(c[8].num[0] == -3 && c[8].num[1] == 3 && c[8].num[2] == -3 && c[8].num[3] == 3);
        CHECK(c[9].num[0] == 1 && c[9].num[1] == 2 && c[9].num[2] == 0);
        CHECK_EQ(c[10].num[0], 64);
        CHECK_EQ(c[11].num[0], 300);
        CHECK(c[12].wire && c[12].num[0] == 1 && c[12].num[1] == 60);
    }
    glib_free(s);
}

/* Issue 14: the state commands of real glman files are commands, never
 * "unknown" (and Flat gets no "did you mean 'Splat'?"); MessageBox prints. */
static void test_glman_state(void) {
    glib_scene *s = load("gl14/state.glib",
        "##OpenGL GLIB\n"
        "Flat\nSmooth\nLineWidth 3\nPointSize 4.5\nPointSizeMode 1\nClamp\n"
        "MessageBox \"Press the T key\"\nLineWidth\n");
    const char *f = P("gl14/state.glib");
    CHECK(s->nerrors == 0 && count_sev(s, DIAG_WARNING) == 0);
    CHECK(has_diag(s, f, 8, DIAG_NOTE, "MessageBox: Press the T key"));
    static const glib_cmd_kind kinds[] = {
        GLIB_CMD_FLAT, GLIB_CMD_SMOOTH, GLIB_CMD_LINE_WIDTH, GLIB_CMD_POINT_SIZE,
        GLIB_CMD_POINT_SIZE_MODE, GLIB_CMD_CLAMP, GLIB_CMD_LINE_WIDTH };
    CHECK_EQ(s->ncmds, 7);
    for (int i = 0; i < s->ncmds && i < 7; i++)
        CHECK_MSG(s->cmds[i].kind == kinds[i], "cmd %d", i);
    if (s->ncmds == 7) {
        CHECK(s->cmds[2].num[0] == 3 && s->cmds[3].num[0] == 4.5 && s->cmds[4].num[0] == 1);
        CHECK_EQ(s->cmds[6].num[0], 1);
    }
    glib_free(s);
}

/* Issue 14: glman's other geometry and its immediate-mode patches parse,
 * with glman's defaults; glBegin/glVertex/glEnd pair up or say why not. */
static void test_glman_geometry(void) {
    put("gl14/m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    glib_scene *s = load("gl14/geom.glib",
        "##OpenGL GLIB\n"
        "DiskXY\nQuadBox\nPointCloud\nJitterCloud 2 3 4\nSoccerball\nXarrow\n"
        "LinesAdjacency [0 0 0] [1 0 0] [2 0 0] [3 0 0]\nTriangles 0 0 0, 1 0 0, 0 1 0\n"
        "WireObj m.obj\nObjAdj m.obj\nObjPatch m.obj\nNumPatchVertices 4\n"
        "GLBEGIN GL_PATCHES\nglVertex 0 0 0\nglvertex [1 0 0]\nglVertex 1 1 0 1\nglVertex 0 1 0\nglend\n");
    CHECK_NO_DIAGS(s);
    static const glib_cmd_kind kinds[] = {
        GLIB_CMD_DISK_XY, GLIB_CMD_QUAD_BOX, GLIB_CMD_POINT_CLOUD, GLIB_CMD_JITTER_CLOUD,
        GLIB_CMD_SOCCERBALL, GLIB_CMD_XARROW, GLIB_CMD_LINES_ADJACENCY, GLIB_CMD_TRIANGLES,
        GLIB_CMD_OBJ, GLIB_CMD_OBJ_ADJ, GLIB_CMD_OBJ_PATCH, GLIB_CMD_NUM_PATCH_VERTICES,
        GLIB_CMD_GL_BEGIN, GLIB_CMD_GL_VERTEX, GLIB_CMD_GL_VERTEX, GLIB_CMD_GL_VERTEX,
        GLIB_CMD_GL_VERTEX, GLIB_CMD_GL_END };
    int n = (int)(sizeof kinds / sizeof kinds[0]);
    CHECK_EQ(s->ncmds, n);
    for (int i = 0; i < s->ncmds && i < n; i++)
        CHECK_MSG(s->cmds[i].kind == kinds[i], "cmd %d is %s", i, glib_cmd_name(s->cmds[i].kind));
    if (s->ncmds == n) {
        const glib_cmd *c = s->cmds;
        CHECK_EQ(c[1].num[0], 10);                                   /* QuadBox [10] */
        CHECK(c[2].num[0] == 10 && c[2].num[1] == 10 && c[2].num[2] == 10);
        CHECK(c[3].num[0] == 2 && c[3].num[1] == 3 && c[3].num[2] == 4);
        CHECK(c[4].num[0] == 1 && c[5].num[0] == 100);              /* Soccerball [1], Xarrow [100] */
        CHECK(c[6].nnum == 12 && c[6].num[9] == 3 && c[7].nnum == 9 && c[7].num[7] == 1);
        CHECK(c[8].wire && !c[9].wire && c[9].path[0] && c[10].path[0]);
        CHECK_EQ(c[11].num[0], 4);
        CHECK_STR_EQ(c[12].name, "gl_patches");
        CHECK(c[14].num[0] == 1 && c[14].num[3] == 1 && c[15].num[3] == 1);   /* w defaults to 1 */
        CHECK_STR_EQ(glib_cmd_name(c[12].kind), "glBegin");
    }
    glib_free(s);

    s = load("gl14/begin_bad.glib",
        "##OpenGL GLIB\n"
        "glVertex 0 0 0\nglEnd\nglBegin gl_polygon_x\nglBegin gl_lines\nglBegin gl_points\n"
        "glVertex 1 2\nglVertex 1 2 3 2\nNumPatchVertices 0\nNumPatchVertices 33\n");
    const char *f = P("gl14/begin_bad.glib");
    CHECK(has_diag(s, f, 2, DIAG_WARNING, "glVertex outside glBegin"));
    CHECK(has_diag(s, f, 3, DIAG_WARNING, "glEnd without a glBegin"));
    CHECK(has_diag(s, f, 4, DIAG_ERROR, "unknown primitive 'gl_polygon_x'"));
    CHECK(has_diag(s, f, 6, DIAG_ERROR, "glBegin inside the glBegin of"));
    CHECK(has_diag(s, f, 7, DIAG_ERROR, "glVertex needs"));
    CHECK(has_diag(s, f, 8, DIAG_WARNING, "w = 2 is not passed on"));
    CHECK(has_diag(s, f, 9, DIAG_ERROR, "n must be a whole number from 1 to 32"));
    CHECK(has_diag(s, f, 10, DIAG_ERROR, "n must be a whole number from 1 to 32"));
    CHECK(has_diag(s, f, 5, DIAG_ERROR, "glBegin without a glEnd"));
    glib_free(s);

    s = load("gl14/tri_bad.glib", "##OpenGL GLIB\nTriangles 0 0 0 1 0 0\nLinesAdjacency\nObjAdj\n");
    f = P("gl14/tri_bad.glib");
    CHECK(has_diag(s, f, 2, DIAG_ERROR, "Triangles needs 9 numbers, got 6"));
    CHECK(has_diag(s, f, 3, DIAG_ERROR, "LinesAdjacency needs 12 numbers, got 0"));
    CHECK(has_diag(s, f, 4, DIAG_ERROR, "ObjAdj needs a file"));
    CHECK_EQ(s->ncmds, 0);
    glib_free(s);
}

static int rm_entry(const char *path, const struct stat *sb, int flag, struct FTW *ftw) {
    return remove(path);
}

/* Issue 27: glman's leniency. A slider with four numbers (a comma for a
 * decimal point) is read as glman's atof read its blank-separated words;
 * a two-word Program name keeps the uniform pairs after it in line; the
 * header may follow blank and comment lines. */
static void test_glman_leniency_27(void) {
    glib_scene *s = load("gl27/l.glib",
        "\n# a project header comment\n##OpenGL GLIB\n"
        "Program P uA < 0,01 0.1 1.0 > uB <0 0.5 0.75 1>\n"     /* 4 */
        "Program Cold Giraffe uK <0 1 2> uC {1, 0, 0}\n"         /* 5 */
        "Program Warm Giraffe\n");                             /* 6 */
    const char *f = P("gl27/l.glib");
    CHECK_MSG(s->nerrors == 0 && s->ncmds == 3, "%d errors", s->nerrors);
    CHECK(!has_diag(s, f, 1, DIAG_WARNING, "first line is not"));
    CHECK(has_diag(s, f, 4, DIAG_WARNING, "uniform 'uA': a slider has more than 3 numbers (0,01 0.1 1.0)"));
    CHECK(has_diag(s, f, 4, DIAG_WARNING, "used <0 0.1 1>"));
    CHECK(has_diag(s, f, 5, DIAG_WARNING, "Program Cold: 'Giraffe' read as part of the program's name"));
    CHECK(has_diag(s, f, 6, DIAG_WARNING, "Program Warm: 'Giraffe' read as part of the program's name"));
    if (s->ncmds == 3) {
        const unif_decl *u;
        CHECK((u = find_uniform(&s->cmds[0], "uA")) && u->kind == UNIF_DECL_SLIDER && u->n == 3 &&
              u->v[0] == 0 && u->v[1] == 0.1 && u->v[2] == 1.0);
        CHECK((u = find_uniform(&s->cmds[0], "uB")) && u->kind == UNIF_DECL_SLIDER && u->v[0] == 0 &&
              u->v[1] == 0.5 && u->v[2] == 0.75);
        CHECK(strcmp(s->cmds[1].name, "Cold") == 0 && s->cmds[1].nuniforms == 2);
        CHECK((u = find_uniform(&s->cmds[1], "uK")) && u->kind == UNIF_DECL_SLIDER && u->v[1] == 1);
        CHECK((u = find_uniform(&s->cmds[1], "uC")) && u->kind == UNIF_DECL_COLOR);
        CHECK_EQ(s->cmds[2].nuniforms, 0);
    }
    glib_free(s);
    /* a file that never says it: still the warning */
    s = load("gl27/n.glib", "# comment\nSphere\n##OpenGL GLIB\n");
    CHECK(has_diag(s, P("gl27/n.glib"), 1, DIAG_WARNING, "first line is not '##OpenGL GLIB'"));
    glib_free(s);
}

int main(void) {
    snprintf(root, sizeof root, "/tmp/test_glib_XXXXXX");
    if (!mkdtemp(root)) {
        perror("mkdtemp");
        return 1;
    }
    RUN(test_basic_scene);
    RUN(test_header);
    RUN(test_empty_file);
    RUN(test_cannot_open);
    RUN(test_comments);
    RUN(test_case_insensitive);
    RUN(test_continuation);
    RUN(test_uniform_kinds);
    RUN(test_number_forms);
    RUN(test_bad_numbers);
    RUN(test_unclosed_brackets);
    RUN(test_slider_checks);
    RUN(test_duplicate_uniform);
    RUN(test_arg_counts);
    RUN(test_defaults);
    RUN(test_range_checks);
    RUN(test_paths_relative);
    RUN(test_missing_files);
    RUN(test_case_hint);
    RUN(test_include);
    RUN(test_include_missing);
    RUN(test_include_cycle);
    RUN(test_include_depth);
    RUN(test_unknown_command);
    RUN(test_binary_junk);
    RUN(test_fuzz);
    RUN(test_long_inputs);
    RUN(test_diag_cap);
    RUN(test_command_cap);
    RUN(test_textures);
    RUN(test_sizes_from_sliders);
    RUN(test_define);
    RUN(test_extensions);
    RUN(test_program_errors);
    RUN(test_world_commands);
    RUN(test_world_errors);
    RUN(test_look_commands);
    RUN(test_pack_contract_commands);
    RUN(test_pack_include);
    RUN(test_pack_missing);
    RUN(test_pack_override);
    RUN(test_print_diags);
    RUN(test_cmd_name);
    RUN(test_glman_real_file);
    RUN(test_glman_numbers);
    RUN(test_glman_defaults);
    RUN(test_glman_leniency_27);
    RUN(test_glman_state);
    RUN(test_glman_geometry);
    nftw(root, rm_entry, 16, FTW_DEPTH | FTW_PHYS);
    return check_summary();
}
