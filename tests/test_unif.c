/* test_unif: the uniform model (uniforms/unif.c) without OpenGL or the
 * parser: glib Program commands are built by hand here. */
#include "check.h"
#include "strbuf.h"
#include "glib.h"
#include "unif.h"

#include <float.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define FILE_NAME "scene.glib"


/* glib_unif_set, its diags formatted into err one a line ("" when none). */
static bool unif_set_said(unif_set *set, const glib_cmd *cmd, char *err, size_t errlen) {
    diag_list dl = { 0 };
    bool ok = glib_unif_set(set, cmd, &dl);
    char *said = diag_list_format(&dl, 0);
    msg_set(err, errlen, "%s", said);
    free(said);
    diag_list_free(&dl);
    return ok;
}

static unif_decl mk(const char *name, unif_decl_kind kind, int line, int n, const double *v) {
    unif_decl u;
    memset(&u, 0, sizeof u);
    snprintf(u.name, sizeof u.name, "%s", name);
    u.kind = kind;
    u.line = line;
    u.file = FILE_NAME;
    u.n = n;
    for (int i = 0; i < n && i < GLIB_MAX_NUMS; i++) u.v[i] = v[i];
    return u;
}
#define SLIDER(name, line, a, b, c) mk(name, UNIF_DECL_SLIDER, line, 3, (const double[]){a, b, c})
#define BOOLU(name, line, b) mk(name, UNIF_DECL_BOOL, line, 1, (const double[]){b})
#define COLOR3(name, line, r, g, b) mk(name, UNIF_DECL_COLOR, line, 3, (const double[]){r, g, b})
#define COLOR4(name, line, r, g, b, a) mk(name, UNIF_DECL_COLOR, line, 4, (const double[]){r, g, b, a})
#define SCALAR(name, line, x) mk(name, UNIF_DECL_SCALAR, line, 1, (const double[]){x})
#define ARRAY(name, line, n, ...) mk(name, UNIF_DECL_ARRAY, line, n, (const double[]){__VA_ARGS__})

static glib_cmd program(const char *name, unif_decl *u, int nu, unif_decl *d, int nd) {
    glib_cmd c;
    memset(&c, 0, sizeof c);
    c.kind = GLIB_CMD_PROGRAM;
    c.file = FILE_NAME;
    c.line = 10;
    snprintf(c.name, sizeof c.name, "%s", name);
    c.uniforms = u;
    c.nuniforms = nu;
    c.defines = d;
    c.ndefines = nd;
    return c;
}

static char tmpdir[256];

static void make_tmpdir(void) {
    if (tmpdir[0]) return;
    snprintf(tmpdir, sizeof tmpdir, "/tmp/test_unif.XXXXXX");
    if (!mkdtemp(tmpdir)) { perror("mkdtemp"); exit(2); }
}

static void tmp_path(char *out, size_t outlen, const char *name) {
    make_tmpdir();
    snprintf(out, outlen, "%s/%s", tmpdir, name);
}

static void write_text(const char *path, const char *text) {
    FILE *f = fopen(path, "w");
    if (!f) { perror(path); exit(2); }
    fputs(text, f);
    fclose(f);
}

static char *read_text(const char *path) {
    static char buf[8192];
    FILE *f = fopen(path, "r");
    if (!f) return NULL;
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

/* ---- building from the glib ---- */

static void test_from_glib_kinds(void) {
    unif_decl u[] = {
        SLIDER("uK", 11, 0, 0.5, 2),
        BOOLU("uFoam", 11, 1),
        COLOR3("uWater", 12, 0.1, 0.4, 0.9),
        COLOR4("uSky", 12, 1, 0.9, 0.8, 0.5),
        SCALAR("uTex", 13, 5),
        ARRAY("uW", 13, 3, 1, 2, 3),
    };
    unif_decl d[] = {
        BOOLU("FOAM", 8, 0),
        SLIDER("STEPS", 9, 1, 4, 8),
        SCALAR("SCALE", 9, 2.5),
        SCALAR("COUNT", 9, 3),
        SLIDER("BIAS", 9, 0.5, 1, 2),
    };
    glib_cmd cmd = program("Water", u, 6, d, 5);
    unif_set set = {0};
    char err[512] = "junk";
    CHECK(unif_set_said(&set, &cmd, err, sizeof err));
    CHECK_EQ(err[0], '\0');
    CHECK_STR_EQ(set.program, "Water");
    CHECK_EQ(set.n, 11);

    /* defines first, in file order */
    unif_entry *e = &set.entries[0];
    CHECK(strcmp(e->name, "FOAM") == 0 && e->is_define && e->widget == UNIF_WIDGET_CHECKBOX);
    CHECK(e->type == UNIF_BOOL && e->value[0] == 0.0f);
    e = &set.entries[1];
    CHECK(strcmp(e->name, "STEPS") == 0 && e->is_define && e->widget == UNIF_WIDGET_SLIDER);
    CHECK(e->type == UNIF_INT && e->min == 1.0f && e->max == 8.0f && e->def[0] == 4.0f);
    e = &set.entries[2];
    CHECK(strcmp(e->name, "SCALE") == 0 && e->widget == UNIF_WIDGET_NONE && e->type == UNIF_FLOAT);
    CHECK_EQ(set.entries[3].type, UNIF_INT);
    CHECK_EQ(set.entries[4].type, UNIF_FLOAT);   /* <0.5 1 2> is not all whole */

    char text[64];
    unif_define_value(&set.entries[0], text, sizeof text);
    CHECK_STR_EQ(text, "0");
    unif_define_value(&set.entries[1], text, sizeof text);
    CHECK_STR_EQ(text, "4");
    unif_define_value(&set.entries[2], text, sizeof text);
    CHECK_STR_EQ(text, "2.5");
    unif_define_value(&set.entries[4], text, sizeof text);
    CHECK_MSG(strcmp(text, "1.0") == 0, "got %s", text);   /* a float define stays a float in GLSL */

    e = unif_find(&set, "uK");
    CHECK(e && !e->is_define && e->widget == UNIF_WIDGET_SLIDER && e->type == UNIF_FLOAT);
    CHECK(e && e->min == 0.0f && e->max == 2.0f && e->def[0] == 0.5f && e->value[0] == 0.5f);
    CHECK(e && e->from_glib && !e->in_shader && e->location == -1 && e->ncomp == 1);
    CHECK(e && e->glib_line == 11 && e->glib_file && strcmp(e->glib_file, FILE_NAME) == 0);
    CHECK(e && e->glib_kind == UNIF_DECL_SLIDER);

    e = unif_find(&set, "uFoam");
    CHECK(e && e->widget == UNIF_WIDGET_CHECKBOX && e->type == UNIF_BOOL && e->value[0] == 1.0f);
    e = unif_find(&set, "uWater");
    CHECK(e && e->widget == UNIF_WIDGET_COLOR && e->type == UNIF_VEC3 && e->ncomp == 3);
    CHECK(e && e->value[0] == 0.1f && e->value[1] == 0.4f && e->value[2] == 0.9f);
    e = unif_find(&set, "uSky");
    CHECK(e && e->widget == UNIF_WIDGET_COLOR && e->type == UNIF_VEC4 && e->ncomp == 4 && e->value[3] == 0.5f);
    e = unif_find(&set, "uTex");
    CHECK(e && e->widget == UNIF_WIDGET_NONE && e->ncomp == 1 && e->value[0] == 5.0f);
    e = unif_find(&set, "uW");
    CHECK(e && e->widget == UNIF_WIDGET_NONE && e->ncomp == 3 && e->array_len == 3);
    CHECK(e && e->value[0] == 1.0f && e->value[2] == 3.0f);
    CHECK_EQ(unif_find(&set, "nope"), NULL);

    unif_set_free(&set);
    CHECK(set.n == 0 && set.entries == NULL);
}

static void test_not_a_program(void) {
    glib_cmd cmd;
    memset(&cmd, 0, sizeof cmd);
    cmd.kind = GLIB_CMD_SPHERE;
    cmd.file = FILE_NAME;
    cmd.line = 4;
    unif_set set = {0};
    char err[256];
    CHECK(!unif_set_said(&set, &cmd, err, sizeof err));
    CHECK_STR_CONTAINS(err, "scene.glib:4:");
    CHECK_EQ(set.n, 0);
    CHECK(!glib_unif_set(&set, NULL, NULL));
}

/* ---- shader types ---- */

static void test_int_vs_float_slider(void) {
    unif_decl u[] = {
        SLIDER("uSteps", 11, 0.4, 2.6, 9.7),
        SLIDER("uK", 11, 0.4, 2.6, 9.7),
        SCALAR("uTex", 12, 5),
        SCALAR("uFlag", 12, 2),
    };
    glib_cmd cmd = program("P", u, 4, NULL, 0);
    unif_set set = {0};
    CHECK(glib_unif_set(&set, &cmd, NULL));
    unif_entry *e = unif_set_shader_type(&set, "uSteps", UNIF_INT, 1, 7);
    CHECK_EQ(e, unif_find(&set, "uSteps"));
    CHECK(e && e->type == UNIF_INT && e->in_shader && e->location == 7 && unif_is_int(e));
    CHECK(e && e->widget == UNIF_WIDGET_SLIDER);
    CHECK(e && e->min == 0.0f && e->max == 10.0f && e->def[0] == 3.0f && e->value[0] == 3.0f);
    CHECK(e && !unif_type_mismatch(e) && unif_uploadable(e));
    CHECK(e && unif_set_component(e, 0, 2.4) && e->value[0] == 2.0f);
    CHECK(e && unif_set_component(e, 0, 50.0) && e->value[0] == 10.0f);
    CHECK(e && !unif_set_component(e, 0, 10.2));       /* rounds to the same */
    CHECK(e && !unif_is_default(e));
    unif_reset(e);
    CHECK(e && e->value[0] == 3.0f && unif_is_default(e));

    e = unif_set_shader_type(&set, "uK", UNIF_FLOAT, 1, 8);
    CHECK(e && e->type == UNIF_FLOAT && !unif_is_int(e));
    CHECK(e && e->min == 0.4f && e->max == 9.7f && e->def[0] == 2.6f);
    CHECK(e && unif_set_component(e, 0, 2.45) && e->value[0] == 2.45f);
    CHECK(e && unif_set_component(e, 0, -3.0) && e->value[0] == 0.4f);
    CHECK(e && !unif_set_component(e, 0, NAN) && e->value[0] == 0.4f);
    CHECK(e && !unif_set_component(e, 99, 1.0));

    e = unif_set_shader_type(&set, "uTex", UNIF_SAMPLER, 1, 2);
    CHECK(e && e->type == UNIF_SAMPLER && e->value[0] == 5.0f && !unif_type_mismatch(e));
    CHECK(e && unif_uploadable(e));             /* glib-written unit: ours to set */
    e = unif_set_shader_type(&set, "uFlag", UNIF_BOOL, 1, 3);
    CHECK(e && e->value[0] == 1.0f && !unif_type_mismatch(e));

    /* built-ins are not entries */
    CHECK_EQ(unif_set_shader_type(&set, "gl_ModelViewMatrix", UNIF_MAT4, 1, -1), NULL);
    CHECK_EQ(set.n, 4);
    unif_set_free(&set);
}

static void test_fit_arrays_and_colours(void) {
    unif_decl u[] = {
        ARRAY("uDir", 11, 3, 0.0, 1.0, 0.0),
        ARRAY("uLights", 11, 6, 1, 2, 3, 4, 5, 6),
        ARRAY("uW", 12, 3, 1.0, 2.0, 3.0),
        ARRAY("uI", 12, 2, 1.4, 2.6),
        COLOR3("uC4", 13, 0.5, 0.5, 0.5),
        COLOR4("uC3", 13, 0.1, 0.2, 0.3, 0.4),
        ARRAY("uBad", 14, 4, 1, 2, 3, 4),
        ARRAY("uLong", 14, 6, 1, 2, 3, 4, 5, 6),
    };
    glib_cmd cmd = program("P", u, 8, NULL, 0);
    unif_set set = {0};
    CHECK(glib_unif_set(&set, &cmd, NULL));

    unif_entry *e = unif_set_shader_type(&set, "uDir", UNIF_VEC3, 1, 1);
    CHECK(e && e->array_len == 1 && e->ncomp == 3 && !unif_type_mismatch(e) && unif_uploadable(e));
    e = unif_set_shader_type(&set, "uLights[0]", UNIF_VEC3, 2, 2);   /* GL's array spelling */
    CHECK(e && strcmp(e->name, "uLights") == 0 && e->array_len == 2 && e->ncomp == 6);
    CHECK(e && !unif_type_mismatch(e));
    e = unif_set_shader_type(&set, "uW[0]", UNIF_FLOAT, 8, 3);     /* fills a prefix */
    CHECK(e && e->array_len == 3 && !unif_type_mismatch(e));
    e = unif_set_shader_type(&set, "uI[0]", UNIF_INT, 2, 4);
    CHECK(e && e->value[0] == 1.0f && e->value[1] == 3.0f && !unif_type_mismatch(e));
    e = unif_set_shader_type(&set, "uC4", UNIF_VEC4, 1, 5);
    CHECK(e && e->ncomp == 3 && e->value[3] == 1.0f && e->def[3] == 1.0f && !unif_type_mismatch(e));
    e = unif_set_shader_type(&set, "uC3", UNIF_VEC3, 1, 6);
    CHECK(e && e->ncomp == 3 && !unif_type_mismatch(e));
    e = unif_set_shader_type(&set, "uBad", UNIF_VEC3, 1, 7);
    CHECK(e && unif_type_mismatch(e) && !unif_uploadable(e));
    e = unif_set_shader_type(&set, "uLong[0]", UNIF_FLOAT, 4, 8);
    CHECK(e && unif_type_mismatch(e) && !unif_uploadable(e));
    CHECK_EQ(set.n, 8);
    unif_set_free(&set);
}

static void test_type_mismatch(void) {
    unif_decl u[] = {
        COLOR3("uCol", 12, 1, 0, 0),
        SLIDER("uVec", 13, 0, 1, 2),
        BOOLU("uV2", 14, 1),
        SCALAR("uV3", 15, 2),
        SLIDER("uOk", 16, 0, 1, 2),
    };
    glib_cmd cmd = program("P", u, 5, NULL, 0);
    unif_set set = {0};
    CHECK(glib_unif_set(&set, &cmd, NULL));
    CHECK_EQ(unif_type_mismatch(unif_find(&set, "uCol")), NULL);   /* nothing known yet */

    unif_entry *e = unif_set_shader_type(&set, "uCol", UNIF_FLOAT, 1, 1);
    CHECK(e && unif_type_mismatch(e) != NULL && !unif_uploadable(e));
    CHECK(e && e->widget == UNIF_WIDGET_COLOR && e->value[0] == 1.0f);  /* left as written */
    char msg[256];
    CHECK_GT(unif_describe_mismatch(e, msg, sizeof msg), 0);
    CHECK_STR_CONTAINS(msg, "scene.glib:12: uniform 'uCol'");
    CHECK_STR_CONTAINS(msg, "colour");
    CHECK_STR_CONTAINS(msg, "declares float");

    CHECK_NE(unif_type_mismatch(unif_set_shader_type(&set, "uVec", UNIF_VEC3, 1, 2)), NULL);
    CHECK_NE(unif_type_mismatch(unif_set_shader_type(&set, "uV2", UNIF_VEC2, 1, 3)), NULL);
    CHECK_NE(unif_type_mismatch(unif_set_shader_type(&set, "uV3", UNIF_VEC3, 1, 4)), NULL);
    e = unif_set_shader_type(&set, "uOk", UNIF_FLOAT, 1, 5);
    CHECK(e && unif_type_mismatch(e) == NULL);
    CHECK(unif_describe_mismatch(e, msg, sizeof msg) == 0 && msg[0] == '\0');

    /* fixed again when the shader changes its declaration */
    e = unif_set_shader_type(&set, "uCol", UNIF_VEC3, 1, 1);
    CHECK(e && unif_type_mismatch(e) == NULL && unif_uploadable(e));
    unif_set_free(&set);
}

static void test_introspected_defaults(void) {
    unif_set set = {0};
    snprintf(set.program, sizeof set.program, "P");
    unif_entry *e = unif_set_shader_type(&set, "uAmp", UNIF_FLOAT, 1, 0);
    CHECK(e && !e->from_glib && e->in_shader && e->widget == UNIF_WIDGET_SLIDER);
    CHECK(e && e->min == 0.0f && e->max == 1.0f && e->def[0] == 0.0f && e->ncomp == 1);
    CHECK(e && unif_uploadable(e));
    e = unif_set_shader_type(&set, "uOctaves", UNIF_INT, 1, 1);
    CHECK(e && e->widget == UNIF_WIDGET_SLIDER && e->min == 0.0f && e->max == 10.0f && unif_is_int(e));
    e = unif_set_shader_type(&set, "uShow", UNIF_BOOL, 1, 2);
    CHECK(e && e->widget == UNIF_WIDGET_CHECKBOX && e->value[0] == 0.0f);
    e = unif_set_shader_type(&set, "uWind", UNIF_VEC2, 1, 3);
    CHECK(e && e->widget == UNIF_WIDGET_DRAG && e->ncomp == 2 && e->min == e->max);
    e = unif_set_shader_type(&set, "uSunDir", UNIF_VEC3, 1, 4);
    CHECK(e && e->widget == UNIF_WIDGET_DRAG && e->ncomp == 3);
    e = unif_set_shader_type(&set, "uDeepColor", UNIF_VEC3, 1, 5);
    CHECK(e && e->widget == UNIF_WIDGET_COLOR && e->ncomp == 3 && e->value[0] == 1.0f);
    e = unif_set_shader_type(&set, "fogColour", UNIF_VEC4, 1, 6);
    CHECK(e && e->widget == UNIF_WIDGET_COLOR && e->ncomp == 4);
    e = unif_set_shader_type(&set, "uPlane", UNIF_VEC4, 1, 7);
    CHECK(e && e->widget == UNIF_WIDGET_DRAG && e->ncomp == 4);
    e = unif_set_shader_type(&set, "uMirror", UNIF_MAT4, 1, 8);
    CHECK(e && e->widget == UNIF_WIDGET_NONE && e->ncomp == 16 && e->value[0] == 1.0f && e->value[5] == 1.0f);
    CHECK(e && !unif_uploadable(e));          /* the renderer's own */
    e = unif_set_shader_type(&set, "uReflection", UNIF_SAMPLER, 1, 9);
    CHECK(e && e->widget == UNIF_WIDGET_NONE && !unif_uploadable(e));
    e = unif_set_shader_type(&set, "Noise3", UNIF_SAMPLER, 1, 10);
    CHECK(e && e->value[0] == 3.0f);
    e = unif_set_shader_type(&set, "Timer", UNIF_FLOAT, 1, 11);
    CHECK(e && e->widget == UNIF_WIDGET_NONE && !unif_uploadable(e));
    e = unif_set_shader_type(&set, "uWeights[0]", UNIF_FLOAT, 40, 12);
    CHECK(e && strcmp(e->name, "uWeights") == 0 && e->widget == UNIF_WIDGET_NONE);
    CHECK(e && e->ncomp <= UNIF_MAX_COMPONENTS && e->array_len == e->ncomp);
    CHECK_EQ(set.n, 13);
    /* seen again: same entry, no duplicate */
    CHECK_EQ(unif_set_shader_type(&set, "uAmp", UNIF_FLOAT, 1, 0), unif_find(&set, "uAmp"));
    CHECK_EQ(set.n, 13);
    /* the shader changed the declaration: rebuilt for the new type */
    e = unif_set_shader_type(&set, "uAmp", UNIF_INT, 1, 0);
    CHECK(e && e->type == UNIF_INT && e->max == 10.0f);
    CHECK_EQ(set.n, 13);
    unif_set_free(&set);
}

/* ---- malformed input ---- */

static void test_malformed_ranges_repaired(void) {
    unif_decl u[] = {
        SLIDER("uSwap", 20, 5, 1, 0),
        SLIDER("uNan", 21, 0, NAN, 1),
        SLIDER("uOut", 22, 0, 7, 5),
        SLIDER("uInf", 23, 0, 0.5, INFINITY),
        SLIDER("uHuge", 24, -1e300, 0, 1),
        mk("uTwo", UNIF_DECL_SLIDER, 25, 2, (const double[]){2, 4}),
        mk("uNone", UNIF_DECL_SLIDER, 26, 0, NULL),
        COLOR3("uCol", 27, 1, NAN, 0),
        mk("uCol2", UNIF_DECL_COLOR, 28, 2, (const double[]){1, 1}),
        BOOLU("uB", 29, NAN),
        mk("", UNIF_DECL_SCALAR, 30, 1, (const double[]){1}),
        SLIDER("uGood", 31, 0, 0.25, 1),
        SLIDER("uSwap", 32, 5, 1, 0),
    };
    glib_cmd cmd = program("P", u, 13, NULL, 0);
    unif_set set = {0};
    char err[4096];
    CHECK(!unif_set_said(&set, &cmd, err, sizeof err));
    CHECK_STR_CONTAINS(err, "scene.glib:20: warning: uniform 'uSwap': min 5 is greater than max 0; swapped");
    CHECK_STR_CONTAINS(err, "scene.glib:21: warning: uniform 'uNan': default is not a finite number");
    CHECK_STR_CONTAINS(err, "scene.glib:22: warning: uniform 'uOut': default 7 is outside");
    CHECK_STR_CONTAINS(err, "scene.glib:23: warning: uniform 'uInf': max is not a finite number");
    CHECK_STR_CONTAINS(err, "scene.glib:24: warning: uniform 'uHuge': min is not a finite number");
    CHECK_STR_CONTAINS(err, "scene.glib:25: warning: uniform 'uTwo'");
    CHECK_STR_CONTAINS(err, "scene.glib:27: warning: uniform 'uCol'");
    CHECK_STR_CONTAINS(err, "scene.glib:28: warning: uniform 'uCol2'");
    CHECK_STR_CONTAINS(err, "scene.glib:29: warning: uniform 'uB'");
    CHECK_STR_CONTAINS(err, "scene.glib:30:");
    CHECK_STR_CONTAINS(err, "scene.glib:32: warning: uniform 'uSwap': written twice (first at line 20)");

    unif_entry *e = unif_find(&set, "uSwap");
    CHECK(e && e->min == 0.0f && e->max == 5.0f && e->def[0] == 1.0f && e->glib_line == 32);
    e = unif_find(&set, "uNan");
    CHECK(e && e->min == 0.0f && e->max == 1.0f && e->def[0] == 0.0f && e->value[0] == 0.0f);
    e = unif_find(&set, "uOut");
    CHECK(e && e->def[0] == 5.0f && e->value[0] == 5.0f);
    e = unif_find(&set, "uInf");
    CHECK(e && isfinite(e->max) && e->max >= 1.0f && e->def[0] == 0.5f);
    e = unif_find(&set, "uHuge");
    CHECK(e && isfinite(e->min) && e->min <= 0.0f && e->max == 1.0f);
    e = unif_find(&set, "uTwo");
    CHECK(e && e->min == 2.0f && e->max == 4.0f && e->def[0] == 2.0f);
    e = unif_find(&set, "uNone");
    CHECK(e && e->min == 0.0f && e->max == 1.0f && e->widget == UNIF_WIDGET_SLIDER);
    e = unif_find(&set, "uCol");
    CHECK(e && e->value[0] == 1.0f && e->value[1] == 0.0f && e->ncomp == 3);
    e = unif_find(&set, "uCol2");
    CHECK(e && e->ncomp == 3 && e->value[2] == 0.0f);
    e = unif_find(&set, "uB");
    CHECK(e && e->widget == UNIF_WIDGET_CHECKBOX && e->value[0] == 0.0f);
    e = unif_find(&set, "uGood");
    CHECK(e && e->def[0] == 0.25f);
    for (int i = 0; i < set.n; i++) {
        const unif_entry *x = &set.entries[i];
        CHECK_NE(x->name[0], '\0');
        CHECK_LE(x->min, x->max);
        for (int k = 0; k < UNIF_MAX_COMPONENTS; k++) CHECK(isfinite(x->value[k]) && isfinite(x->def[k]));
        if (x->widget == UNIF_WIDGET_SLIDER) CHECK(x->def[0] >= x->min && x->def[0] <= x->max);
    }
    CHECK_EQ(set.n, 11);
    unif_set_free(&set);

    /* each repair a warning at its line; no list at all is fine */
    diag_list dl = { 0 };
    CHECK(!glib_unif_set(&set, &cmd, &dl));
    CHECK_EQ(dl.nwarnings, dl.n);
    CHECK_EQ(dl.nerrors, 0);
    CHECK_GE(dl.n, 11);
    if (dl.n > 0) {
        CHECK_STR_EQ(dl.d[0].file, "scene.glib");
        CHECK_EQ(dl.d[0].line, 20);
    }
    diag_list_free(&dl);
    unif_set_free(&set);
    CHECK(!glib_unif_set(&set, &cmd, NULL));
    unif_set_free(&set);

    /* glib kinds a define cannot take, and counts beyond the arrays */
    unif_decl d[] = { COLOR3("TINT", 5, 1, 1, 1), SLIDER("OK", 6, 1, 2, 3) };
    unif_decl big = mk("uBig", UNIF_DECL_ARRAY, 7, 3, (const double[]){1, 2, 3});
    big.n = 1000;
    glib_cmd cmd2 = program("P", &big, 1, d, 2);
    CHECK(!unif_set_said(&set, &cmd2, err, sizeof err));
    CHECK_STR_CONTAINS(err, "scene.glib:5: warning: define 'TINT'");
    CHECK(unif_find(&set, "TINT") == NULL && unif_find(&set, "OK") != NULL);
    e = unif_find(&set, "uBig");
    CHECK(e && e->ncomp == UNIF_MAX_COMPONENTS);
    unif_set_free(&set);
}

/* ---- merge ---- */

/* Builds a set like the renderer does: glib, then the shader's declarations. */
static void build(unif_set *set, unif_decl *u, int nu, unif_decl *d, int nd,
                  const char *const *names, const unif_type *types, int ntypes) {
    glib_cmd cmd = program("Water", u, nu, d, nd);
    memset(set, 0, sizeof *set);
    glib_unif_set(set, &cmd, NULL);
    for (int i = 0; i < ntypes; i++) unif_set_shader_type(set, names[i], types[i], 1, i);
}

static void test_merge(void) {
    unif_decl u_old[] = {
        SLIDER("uK", 11, 0, 0.5, 2),
        SLIDER("uN", 11, 0, 3, 10),
        COLOR3("uCol", 12, 1, 0, 0),
        SLIDER("uGone", 12, 0, 1, 2),
        SLIDER("uRange", 13, 0, 1, 2),
        SLIDER("uType", 13, 0, 1, 2),
        COLOR3("uAlpha", 14, 1, 1, 1),
    };
    unif_decl d_old[] = { BOOLU("FOAM", 8, 0), SLIDER("STEPS", 9, 1, 4, 8) };
    const char *const names_old[] = { "uK", "uN", "uCol", "uGone", "uRange", "uType", "uAlpha", "uAmp" };
    const unif_type types_old[] = { UNIF_FLOAT, UNIF_INT, UNIF_VEC3, UNIF_FLOAT, UNIF_FLOAT, UNIF_FLOAT,
                                    UNIF_VEC4, UNIF_FLOAT };
    unif_set old;
    build(&old, u_old, 7, d_old, 2, names_old, types_old, 8);
    CHECK_EQ(old.n, 10);
    /* the user moves everything */
    for (int i = 0; i < old.n; i++) {
        unif_entry *e = &old.entries[i];
        for (int k = 0; k < e->ncomp; k++) unif_set_component(e, k, e->min + 0.75 * (e->max - e->min));
        if (e->widget == UNIF_WIDGET_COLOR) for (int k = 0; k < e->ncomp; k++) e->value[k] = 0.25f;
        if (e->widget == UNIF_WIDGET_CHECKBOX) e->value[0] = 1.0f;
    }
    CHECK_EQ(unif_find(&old, "uK")->value[0], 1.5f);
    CHECK_EQ(unif_find(&old, "uN")->value[0], 8.0f);   /* 7.5 rounded */
    CHECK_EQ(unif_find(&old, "STEPS")->value[0], 6.0f);

    unif_decl u_new[] = {
        SLIDER("uNew", 10, 0, 0.1, 1),
        COLOR3("uCol", 12, 1, 0, 0),
        SLIDER("uN", 11, 0, 4, 10),            /* default changed */
        SLIDER("uK", 11, 0, 0.5, 2),           /* unchanged, moved to another place */
        SLIDER("uRange", 13, 0, 1, 3),         /* max changed */
        SLIDER("uType", 13, 0, 1, 2),          /* the shader now says int */
        COLOR4("uAlpha", 14, 1, 1, 1, 1),      /* ncomp changed */
    };
    unif_decl d_new[] = { BOOLU("FOAM", 8, 0), SLIDER("STEPS", 9, 1, 4, 8) };
    const char *const names_new[] = { "uNew", "uCol", "uN", "uK", "uRange", "uType", "uAlpha", "uAmp" };
    const unif_type types_new[] = { UNIF_FLOAT, UNIF_VEC3, UNIF_INT, UNIF_FLOAT, UNIF_FLOAT, UNIF_INT,
                                    UNIF_VEC4, UNIF_FLOAT };
    unif_set fresh;
    build(&fresh, u_new, 7, d_new, 2, names_new, types_new, 8);
    unif_merge(&fresh, &old);

    CHECK_EQ(unif_find(&fresh, "uK")->value[0], 1.5f);          /* kept */
    CHECK_EQ(unif_find(&fresh, "uN")->value[0], 4.0f);          /* new default */
    const unif_entry *c = unif_find(&fresh, "uCol");
    CHECK(c->value[0] == 0.25f && c->value[1] == 0.25f && c->value[2] == 0.25f);
    CHECK_EQ(unif_find(&fresh, "uGone"), NULL);                  /* dropped */
    CHECK_EQ(unif_find(&fresh, "uRange")->value[0], 1.0f);      /* range changed: reset */
    CHECK_EQ(unif_find(&fresh, "uType")->value[0], 1.0f);       /* type changed: reset */
    CHECK_EQ(unif_find(&fresh, "uAlpha")->value[0], 1.0f);      /* ncomp changed: reset */
    CHECK_EQ(unif_find(&fresh, "uNew")->value[0], 0.1f);
    CHECK_EQ(unif_find(&fresh, "uAmp")->value[0], 0.75f);       /* introspected: kept */
    CHECK_EQ(unif_find(&fresh, "FOAM")->value[0], 1.0f);        /* define kept */
    CHECK_EQ(unif_find(&fresh, "STEPS")->value[0], 6.0f);
    CHECK(unif_find(&fresh, "uK")->in_shader && unif_find(&fresh, "uK")->location == 3);

    /* the introspected uniform now written in the glib: the glib's default wins */
    unif_decl u3[] = { SLIDER("uAmp", 15, 0, 0.3, 1) };
    const char *const names3[] = { "uAmp" };
    const unif_type types3[] = { UNIF_FLOAT };
    unif_set third;
    build(&third, u3, 1, NULL, 0, names3, types3, 1);
    unif_merge(&third, &fresh);
    CHECK_EQ(unif_find(&third, "uAmp")->value[0], 0.3f);
    unif_set_free(&third);

    /* merge before the shader's types are known still carries values */
    unif_decl u4[] = { SLIDER("uK", 11, 0, 0.5, 2) };
    build(&third, u4, 1, NULL, 0, NULL, NULL, 0);
    unif_merge(&third, &fresh);
    CHECK_EQ(unif_find(&third, "uK")->value[0], 1.5f);
    unif_set_free(&third);

    unif_merge(&fresh, NULL);
    unif_merge(NULL, &old);
    unif_set_free(&old);
    unif_set_free(&fresh);
}

/* The renderer's order: merge (so defines compile with the user's values),
 * introspect, merge again once both sides carry shader types. Introspecting
 * the same set again (a define recompile) keeps the values. */
static void test_merge_twice_like_the_renderer(void) {
    unif_decl u[] = { SLIDER("uN", 11, 0.5, 3, 10), SLIDER("uF", 11, 0, 3, 10) };
    const char *const names[] = { "uN", "uF" };
    const unif_type t_old[] = { UNIF_FLOAT, UNIF_INT };
    const unif_type t_new[] = { UNIF_INT, UNIF_INT };
    unif_set old;
    build(&old, u, 2, NULL, 0, names, t_old, 2);
    unif_set_component(unif_find(&old, "uN"), 0, 7.4);   /* float slider */
    unif_set_component(unif_find(&old, "uF"), 0, 8.0);   /* int slider */

    glib_cmd cmd = program("Water", u, 2, NULL, 0);
    unif_set fresh = {0};
    glib_unif_set(&fresh, &cmd, NULL);
    unif_merge(&fresh, &old);
    for (int i = 0; i < 2; i++) unif_set_shader_type(&fresh, names[i], t_new[i], 1, i);
    unif_merge(&fresh, &old);
    CHECK_EQ(unif_find(&fresh, "uN")->value[0], 3.0f);    /* float -> int: reset */
    CHECK_EQ(unif_find(&fresh, "uF")->value[0], 8.0f);    /* int -> int: kept */

    unif_set_component(unif_find(&fresh, "uN"), 0, 6);
    for (int i = 0; i < 2; i++) unif_set_shader_type(&fresh, names[i], t_new[i], 1, i);
    CHECK_EQ(unif_find(&fresh, "uN")->value[0], 6.0f);
    CHECK_EQ(unif_find(&fresh, "uF")->value[0], 8.0f);
    unif_set_free(&old);
    unif_set_free(&fresh);
}

static void test_reset_all(void) {
    unif_decl u[] = { SLIDER("uK", 11, 0, 0.5, 2) };
    unif_decl d[] = { BOOLU("FOAM", 8, 0) };
    glib_cmd cmd = program("P", u, 1, d, 1);
    unif_set set = {0};
    CHECK(glib_unif_set(&set, &cmd, NULL));
    unif_set_component(unif_find(&set, "uK"), 0, 1.0);
    CHECK(!unif_reset_all_ex(&set));                 /* no define moved */
    CHECK_EQ(unif_find(&set, "uK")->value[0], 0.5f);
    unif_set_component(unif_find(&set, "FOAM"), 0, 1.0);
    CHECK_EQ(unif_find(&set, "FOAM")->value[0], 1.0f);
    CHECK(unif_reset_all_ex(&set));                  /* recompile */
    CHECK_EQ(unif_find(&set, "FOAM")->value[0], 0.0f);
    unif_set_component(unif_find(&set, "uK"), 0, 2.0);
    unif_reset_all(&set);
    CHECK_EQ(unif_find(&set, "uK")->value[0], 0.5f);
    unif_set_free(&set);
}

/* ---- presets ---- */

typedef struct two_sets { unif_set s[2]; } two_sets;

static void build_presets(two_sets *t) {
    unif_decl u1[] = {
        SLIDER("uK", 11, -1000, 0, 1000),
        SLIDER("uN", 11, 0, 3, 10),
        COLOR4("uCol", 12, 1, 0, 0, 1),
        BOOLU("uFoam", 12, 0),
        SCALAR("uTex", 13, 4),
    };
    unif_decl d1[] = { SLIDER("STEPS", 9, 1, 4, 8) };
    const char *const n1[] = { "uK", "uN", "uCol", "uFoam", "uTex", "uWind" };
    const unif_type t1[] = { UNIF_FLOAT, UNIF_INT, UNIF_VEC4, UNIF_BOOL, UNIF_SAMPLER, UNIF_VEC3 };
    glib_cmd cmd = program("Water", u1, 5, d1, 1);
    memset(t, 0, sizeof *t);
    glib_unif_set(&t->s[0], &cmd, NULL);
    for (int i = 0; i < 6; i++) unif_set_shader_type(&t->s[0], n1[i], t1[i], 1, i);

    unif_decl u2[] = { SLIDER("uK", 20, 0, 0.5, 1) };
    glib_cmd cmd2 = program("Sky", u2, 1, NULL, 0);
    glib_unif_set(&t->s[1], &cmd2, NULL);
}

static void free_presets(two_sets *t) {
    unif_set_free(&t->s[0]);
    unif_set_free(&t->s[1]);
}

static void move_values(two_sets *t) {
    unif_set *w = &t->s[0];
    unif_find(w, "uK")->value[0] = 0.1f;            /* not exact in decimal */
    CHECK(unif_set_component(unif_find(w, "uN"), 0, 7));
    unif_entry *c = unif_find(w, "uCol");
    c->value[0] = 1.0f / 3.0f; c->value[1] = 1e-7f; c->value[2] = 0.123456789f; c->value[3] = 0.5f;
    unif_find(w, "uFoam")->value[0] = 1.0f;
    unif_entry *wind = unif_find(w, "uWind");
    wind->value[0] = FLT_MAX; wind->value[1] = -FLT_MIN; wind->value[2] = 1e-40f;   /* denormal */
    unif_find(w, "STEPS")->value[0] = 7.0f;
    unif_find(&t->s[1], "uK")->value[0] = 0.987654321f;
}

static bool values_equal(const two_sets *a, const two_sets *b) {
    for (int s = 0; s < 2; s++) {
        if (a->s[s].n != b->s[s].n) return false;
        for (int i = 0; i < a->s[s].n; i++)
            if (memcmp(a->s[s].entries[i].value, b->s[s].entries[i].value,
                       sizeof a->s[s].entries[i].value) != 0) return false;
    }
    return true;
}

static void test_preset_round_trip(void) {
    two_sets a, b;
    build_presets(&a);
    build_presets(&b);
    move_values(&a);
    CHECK(!values_equal(&a, &b));

    char path[512], err[1024];
    tmp_path(path, sizeof path, "round.preset");
    CHECK_MSG(unif_preset_save(a.s, 2, path, err, sizeof err), "%s", err);
    CHECK_EQ(err[0], '\0');
    char tmp[600];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    CHECK_NE(access(tmp, F_OK), 0);                  /* the temp file was renamed */
    char *text = read_text(path);
    CHECK(text && strncmp(text, "tarn-preset 1\n", 14) == 0);
    CHECK(text && strstr(text, "Water uK 1 ") && strstr(text, "Sky uK 1 "));
    CHECK(text && strstr(text, "Water uCol 4 "));
    CHECK(text && !strstr(text, "uTex"));            /* fixed values are not presets */

    bool defines_changed = false;
    CHECK_MSG(unif_preset_load_ex(b.s, 2, path, err, sizeof err, &defines_changed), "%s", err);
    CHECK_MSG(err[0] == '\0', "%s", err);
    CHECK(defines_changed);
    CHECK(values_equal(&a, &b));                     /* bit-exact */
    CHECK_EQ(unif_find(&b.s[0], "uK")->value[0], 0.1f);
    CHECK_EQ(unif_find(&b.s[0], "uWind")->value[0], FLT_MAX);
    CHECK_EQ(unif_find(&b.s[0], "uWind")->value[2], 1e-40f);

    /* loading the same again changes no define */
    CHECK(unif_preset_load_ex(b.s, 2, path, err, sizeof err, &defines_changed));
    CHECK(!defines_changed);

    /* saving over an existing preset replaces it */
    unif_reset_all(&a.s[0]);
    CHECK(unif_preset_save(a.s, 2, path, err, sizeof err));
    CHECK(unif_preset_load(b.s, 2, path, err, sizeof err));
    CHECK(values_equal(&a, &b));

    /* cannot write: a message, the old file kept */
    char bad[600];
    snprintf(bad, sizeof bad, "%s/no/such/dir/x.preset", tmpdir);
    CHECK(!unif_preset_save(a.s, 2, bad, err, sizeof err));
    CHECK_STR_CONTAINS(err, "no/such/dir");
    free_presets(&a);
    free_presets(&b);
}

/* Each corrupt preset is refused and leaves every value as it was. */
static void test_preset_corrupt_changes_nothing(void) {
    two_sets a, before;
    build_presets(&a);
    build_presets(&before);
    char path[512], err[1024];
    tmp_path(path, sizeof path, "corrupt.preset");
    static const struct { const char *text, *expect; } cases[] = {
        { "tarn-preset 1\nWater uK 1 5\nWater uN 1 0.5x\n", ":3: '0.5x' is not a number" },
        { "tarn-preset 1\nWater uK 1 5\nSky uK 1 nan\n", ":3: 'nan' is not a number" },
        { "tarn-preset 1\nWater uK 1 1e999\n", "not a number" },
        { "tarn-preset 1\nWater uK 1 5\nWater uCol 4 1 2 3\n", ":3: count 4 but 3 values" },
        { "tarn-preset 1\nWater uK 2 5\nWater uK\n", "corrupt" },
        { "tarn-preset 1\nWater uK x 5\n", "corrupt" },
        { "tarn-preset 1\nWater uK 99 5\n", "corrupt" },
        { "tarn-preset 1\nWater uK 1 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17\n", "corrupt" },
        { "tarn-preset 2\nWater uK 1 5\n", ":1: preset version 2 is not supported" },
        { "tarn-preset 0\nWater uK 1 5\n", "version 0 is not supported" },
        { "tarn-preset one\nWater uK 1 5\n", "bad preset header" },
        { "Water uK 1 5\n", ":1: not a tarn preset" },
        { "# only a comment\n\n", "empty, not a tarn preset" },
        { "", "empty, not a tarn preset" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        write_text(path, cases[i].text);
        bool dc = true;
        CHECK_MSG(!unif_preset_load_ex(a.s, 2, path, err, sizeof err, &dc), "case %zu", i);
        CHECK_MSG(!dc, "case %zu", i);
        CHECK_MSG(values_equal(&a, &before), "case %zu changed values", i);
        CHECK_STR_CONTAINS(err, cases[i].expect);
    }
    /* binary junk */
    FILE *f = fopen(path, "wb");
    fwrite("tarn-preset 1\n\0\1\2", 1, 17, f);
    fclose(f);
    CHECK(!unif_preset_load(a.s, 2, path, err, sizeof err));
    CHECK(values_equal(&a, &before));
    /* missing file */
    char missing[600];
    snprintf(missing, sizeof missing, "%s/missing.preset", tmpdir);
    CHECK(!unif_preset_load(a.s, 2, missing, err, sizeof err));
    CHECK_STR_CONTAINS(err, "missing.preset");
    CHECK(values_equal(&a, &before));
    CHECK(!unif_preset_load(a.s, 2, NULL, NULL, 0));
    free_presets(&a);
    free_presets(&before);
}

static void test_preset_unknown_skipped(void) {
    two_sets a;
    build_presets(&a);
    char path[512], err[2048];
    tmp_path(path, sizeof path, "skip.preset");
    write_text(path,
               "tarn-preset 1\n"
               "# a comment\n"
               "Water uK 1 12.5\n"
               "Ghost uK 1 3\n"
               "Water uNope 1 3\n"
               "Water uCol 3 0.1 0.2 0.3\n"
               "Water uTex 1 7\n"
               "\r\n"
               "Water uN 1 99\n"
               "Sky uK 1 0.25\r\n"
               "Water uFoam 1 1\n");
    CHECK_MSG(unif_preset_load(a.s, 2, path, err, sizeof err), "%s", err);
    CHECK_STR_CONTAINS(err, ":4: no program 'Ghost'");
    CHECK_STR_CONTAINS(err, ":5: program 'Water' has no uniform 'uNope'");
    CHECK_STR_CONTAINS(err, ":6: 'uCol' in program 'Water' has 4 values, the preset 3; skipped");
    CHECK_STR_CONTAINS(err, ":7: program 'Water' has no uniform 'uTex'");   /* fixed: not a preset value */
    CHECK_STR_CONTAINS(err, ":9: 'uN' in program 'Water': a value outside its range was clamped");
    CHECK_EQ(unif_find(&a.s[0], "uK")->value[0], 12.5f);
    CHECK_EQ(unif_find(&a.s[0], "uN")->value[0], 10.0f);
    CHECK_EQ(unif_find(&a.s[0], "uCol")->value[0], 1.0f);      /* skipped: unchanged */
    CHECK_EQ(unif_find(&a.s[0], "uTex")->value[0], 4.0f);
    CHECK_EQ(unif_find(&a.s[1], "uK")->value[0], 0.25f);
    CHECK_EQ(unif_find(&a.s[0], "uFoam")->value[0], 1.0f);
    free_presets(&a);
}

static void test_preset_path(void) {
    char out[256];
    unif_preset_path("dir/scene.glib", out, sizeof out);
    CHECK_STR_EQ(out, "dir/scene.preset");
    unif_preset_path("/abs/lake.glib", out, sizeof out);
    CHECK_STR_EQ(out, "/abs/lake.preset");
    unif_preset_path("scene.glib", out, sizeof out);
    CHECK_STR_EQ(out, "scene.preset");
    unif_preset_path("dir.v2/scene", out, sizeof out);
    CHECK_STR_EQ(out, "dir.v2/scene.preset");
    unif_preset_path("dir/.hidden", out, sizeof out);
    CHECK_STR_EQ(out, "dir/.hidden.preset");
    unif_preset_path("dir/a.b.glib", out, sizeof out);
    CHECK_STR_EQ(out, "dir/a.b.preset");
    char small[10];
    unif_preset_path("dir/scene.glib", small, sizeof small);
    CHECK_EQ(small[0], '\0');
    unif_preset_path("", out, sizeof out);
    CHECK_EQ(out[0], '\0');
    unif_preset_path(NULL, out, sizeof out);
    CHECK_EQ(out[0], '\0');
}

static void cleanup(void) {
    if (!tmpdir[0]) return;
    const char *names[] = { "round.preset", "corrupt.preset", "skip.preset" };
    char p[600];
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        snprintf(p, sizeof p, "%s/%s", tmpdir, names[i]);
        remove(p);
    }
    rmdir(tmpdir);
}

int main(void) {
    RUN(test_from_glib_kinds);
    RUN(test_not_a_program);
    RUN(test_int_vs_float_slider);
    RUN(test_fit_arrays_and_colours);
    RUN(test_type_mismatch);
    RUN(test_introspected_defaults);
    RUN(test_malformed_ranges_repaired);
    RUN(test_merge);
    RUN(test_merge_twice_like_the_renderer);
    RUN(test_reset_all);
    RUN(test_preset_round_trip);
    RUN(test_preset_corrupt_changes_nothing);
    RUN(test_preset_unknown_skipped);
    RUN(test_preset_path);
    cleanup();
    return check_summary();
}
