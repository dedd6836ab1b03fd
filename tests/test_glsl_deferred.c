/* glsl_deferred: a fragment shader split into a G-buffer writer and a
 * shade pass reading its inputs back (scene/glsl_deferred.h). Checked on
 * the texts themselves: what each declares and copies, the lines kept
 * (the #line mapping still names the user's lines), and what it refuses.
 * test_water_deferred compiles and draws both on llvmpipe. No GL. */
#include "check.h"
#include "glsl_deferred.h"
#include "shader_src.h"

#include <stdlib.h>
#include <string.h>

static int count_of(const char *hay, const char *needle) {
    int n = 0;
    for (const char *p = hay; (p = strstr(p, needle)) != NULL; p += strlen(needle)) n++;
    return n;
}

static int lines(const char *s, size_t n) {
    int k = 0;
    for (size_t i = 0; i < n && s[i]; i++) k += s[i] == '\n';
    return k;
}

static const char *frag =
    "#version 330 compatibility\n"
    "#define K 2\n"
    "// in vec4 vCommented;\n"
    "uniform float u;\n"
    "in vec2 vRest;\n"
    "flat in\n  ivec2 vI[2], vJ;\n"
    "layout(location = 0) out vec4 fragColor;\n"
    "float f(in float a) { return a * u; }\n"
    "void main() { if (gl_FragCoord.x < -1.0) discard; /* tarn: one llvmpipe function */\n"
    "    fragColor = vec4(vRest, gl_FragCoord.z, float(vI[1].y + vJ.x));\n"
    "}\n";

static void test_split_stores_every_component(void) {
    glsl_deferred d;
    CHECK_MSG(glsl_deferred_split(frag, &d), "%s", d.why);
    /* vRest 2 + vI 2 x 2 + vJ 2 + gl_FragCoord's z and w */
    CHECK_EQ(d.ncomp, 10);
    CHECK_EQ(d.ntex, 3);
    /* slot 11 spare: the draw's stamp, and a texel of another draw reads as 0 */
    CHECK(d.stamped);
    CHECK_STR_CONTAINS(d.gbuffer, "tarn_dfr_o2.w = tarn_dfr_stamp;");
    CHECK_STR_CONTAINS(d.shade, "if (tarn_dfr_v2.w != tarn_dfr_stamp) { tarn_dfr_v0 = vec4(0.0);");
    /* the G-buffer: the inputs as written, each component out by value or bits */
    CHECK_STR_CONTAINS(d.gbuffer, "#version 330 compatibility\n");
    CHECK_STR_CONTAINS(d.gbuffer, "flat in\n  ivec2 vI[2], vJ;");
    CHECK_STR_CONTAINS(d.gbuffer, "layout(location = 2) out vec4 tarn_dfr_o2;");
    CHECK_STR_CONTAINS(d.gbuffer, "tarn_dfr_o0.x = float(vRest.x);");
    CHECK_STR_CONTAINS(d.gbuffer, "tarn_dfr_o1.y = intBitsToFloat(vI[1].y);");
    CHECK_STR_CONTAINS(d.gbuffer, "tarn_dfr_o1.z = intBitsToFloat(vJ.x);");
    CHECK_STR_CONTAINS(d.gbuffer, "tarn_dfr_o2.x = gl_FragCoord.z;");
    CHECK(!strstr(d.gbuffer, "vCommented"));
    /* the shade: globals in the declarations' place, main renamed, the
     * inputs read back, gl_FragCoord the stored one */
    CHECK_STR_CONTAINS(d.shade, "ivec2 vI[2], vJ;\n");
    CHECK(!strstr(d.shade, "flat in"));
    CHECK_STR_CONTAINS(d.shade, "void tarn_dfr_main()");
    CHECK_STR_CONTAINS(d.shade, "vI[1].y = floatBitsToInt(tarn_dfr_v1.y);");
    CHECK_STR_CONTAINS(d.shade, "vec4(vRest, tarn_dfr_fragcoord.z,");
    CHECK_STR_CONTAINS(d.shade, "uniform sampler2D tarn_dfr_g2;");
    CHECK_STR_CONTAINS(d.shade, "tarn_dfr_fragcoord = vec4(gl_FragCoord.xy, tarn_dfr_v2.x, tarn_dfr_v2.y);");
    CHECK_STR_CONTAINS(d.shade, "float f(in float a)");   /* a parameter's `in` is no input */
    /* the never-taken kill is gone (it would test stencil late) */
    CHECK(!strstr(d.shade, "discard"));
    /* every line of the shader where it was: the body's lines up to main's
     * end are the original's */
    const char *end = strstr(d.shade, "\nuniform sampler2D tarn_dfr_g0");
    CHECK(end != NULL);
    if (end) CHECK_EQ(lines(d.shade, (size_t)(end - d.shade)), lines(frag, strlen(frag)));
    glsl_deferred_free(&d);
}

/* gl_FragCoord's x and y (the never-taken kill's) are the shade pass's
 * own: nothing stored, the text left as it is. */
static void test_fragcoord_xy_kept(void) {
    glsl_deferred d;
    CHECK_MSG(glsl_deferred_split("#version 330\nin vec2 v;\nout vec4 c;\n"
                                  "void main() {" SHADER_SRC_UNREACHED_KILL "\n"
                                  "  c = vec4(v, gl_FragCoord . xy); }\n", &d), "%s", d.why);
    CHECK(!strstr(d.shade, "discard"));   /* the kill blanked in this form too */
    CHECK_EQ(d.ncomp, 2);
    CHECK_EQ(d.ntex, 1);
    CHECK_STR_CONTAINS(d.shade, "vec4(v, gl_FragCoord . xy)");
    CHECK(!strstr(d.shade, "tarn_dfr_fragcoord"));
    glsl_deferred_free(&d);
    CHECK(glsl_deferred_split("#version 330\nin vec2 v;\nout vec4 c;\nvoid main() { c = gl_FragCoord; }\n", &d));
    CHECK_EQ(d.ncomp, 4);
    CHECK(!d.stamped);   /* no spare slot: the G-buffer is cleared instead */
    CHECK(!strstr(d.shade, "tarn_dfr_stamp"));
    glsl_deferred_free(&d);
}

static void test_front_facing_and_uint(void) {
    glsl_deferred d;
    CHECK_MSG(glsl_deferred_split("#version 450\nflat in uint vU;\nsmooth in float vS;\nout vec4 c;\n"
                                  "void main() { c = vec4(float(vU) + vS, gl_FrontFacing ? 1.0 : 0.0, 0.0, 1.0); }\n",
                                  &d), "%s", d.why);
    CHECK_EQ(d.ncomp, 3);
    CHECK_STR_CONTAINS(d.gbuffer, "#version 450\n");
    CHECK_STR_CONTAINS(d.gbuffer, "tarn_dfr_o0.x = uintBitsToFloat(vU);");
    CHECK(!strstr(d.gbuffer, "gl_FragCoord"));   /* not read: nothing stored */
    CHECK_STR_CONTAINS(d.gbuffer, "gl_FrontFacing ? 1.0 : 0.0;");
    CHECK_STR_CONTAINS(d.shade, "vU = floatBitsToUint(tarn_dfr_v0.x);");
    CHECK_STR_CONTAINS(d.shade, "tarn_dfr_front ? 1.0");
    CHECK_STR_CONTAINS(d.shade, "bool tarn_dfr_front; uint vU;\n");   /* declared before any use */
    glsl_deferred_free(&d);
}

/* A main() in each branch of an #if: both renamed (the shade's own main
 * is the only one whichever branch is compiled); a "main" in a comment or
 * another word is left. */
static void test_every_main_renamed(void) {
    glsl_deferred d;
    CHECK_MSG(glsl_deferred_split("#version 330\nin vec2 v;\nout vec4 c;\n// void main() { }\n"
                                  "float mainly(float x) { return x; }\n"
                                  "#ifdef X\nvoid main() { c = vec4(v, 0, 1); }\n#else\n"
                                  "void main(void)\n{ c = vec4(v, 1, 1); }\n#endif\n", &d), "%s", d.why);
    CHECK_EQ(count_of(d.shade, "void tarn_dfr_main()"), 1);
    CHECK_EQ(count_of(d.shade, "void tarn_dfr_main(void)"), 1);
    CHECK_EQ(count_of(d.shade, "void main()"), 1);   /* the shade's own */
    CHECK_STR_CONTAINS(d.shade, "float mainly(");
    glsl_deferred_free(&d);
}

/* What it cannot split, each with its reason. */
static void test_refusals(void) {
    static const struct { const char *text, *why; } cases[] = {
        { "#version 120\nvarying vec2 v;\nvoid main() { gl_FragColor = vec4(v, 0, 1); }\n", "330" },
        { "in vec2 v;\nvoid main() { }\n", "without #version" },
        { "#version 330\nin Block { vec2 v; } b;\nout vec4 c;\nvoid main() { c = vec4(b.v, 0, 1); }\n", "input block" },
        { "#version 330\n#ifdef X\nin vec2 v;\n#endif\nout vec4 c;\nvoid main() { c = vec4(0); }\n", "#if" },
        { "#version 330\nin mat3 m;\nout vec4 c;\nvoid main() { c = vec4(m[0], 1); }\n", "type mat3" },
        { "#version 330 compatibility\nin vec2 v;\nvoid main() { gl_FragColor = gl_Color; }\n", "gl_Color" },
        { "#version 330\nin vec2 v;\nout vec4 c;\nvoid main() { c = vec4(v, 0, 1); gl_FragDepth = 0.5; }\n",
          "gl_FragDepth" },
        { "#version 400\nsample in vec2 v;\nout vec4 c;\nvoid main() { c = vec4(v, 0, 1); }\n", "sample" },
        { "#version 330\nout vec4 c;\nvoid main() { c = vec4(1); }\n", "no input" },
        { "#version 330\nin vec4 a, b, c, d, e, f, g, h;\nout vec4 o;\nvoid main() { o = a; }\n", "more input" },
        { "#version 330\nin vec2 v;\nout vec4 c;\nvoid f() { c = vec4(v, 0, 1); }\n", "main" },
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        glsl_deferred d;
        bool ok = glsl_deferred_split(cases[k].text, &d);
        CHECK_MSG(!ok, "case %zu split", k);
        CHECK_MSG(strstr(d.why, cases[k].why) != NULL, "case %zu: '%s' lacks '%s'", k, d.why, cases[k].why);
        CHECK(d.shade == NULL && d.gbuffer == NULL);
        glsl_deferred_free(&d);
    }
}

/* Nothing in it reads past a text cut anywhere (an unterminated comment,
 * declaration or block). */
static void test_cut_texts(void) {
    size_t n = strlen(frag);
    char *t = malloc(n + 1);
    for (size_t k = 0; k <= n; k++) {
        memcpy(t, frag, k);
        t[k] = 0;
        glsl_deferred d;
        glsl_deferred_split(t, &d);
        glsl_deferred_free(&d);
    }
    free(t);
    glsl_deferred d;
    CHECK(!glsl_deferred_split(NULL, &d));
}

int main(void) {
    RUN(test_split_stores_every_component);
    RUN(test_fragcoord_xy_kept);
    RUN(test_front_facing_and_uint);
    RUN(test_every_main_renamed);
    RUN(test_refusals);
    RUN(test_cut_texts);
    return check_summary();
}
