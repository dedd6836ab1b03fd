/* Tests of glsl_hint: the notes added after compiler messages for GLSL that
 * NVIDIA accepted and the spec forbids. The logs are Mesa 22.3's and
 * glslang's own lines (recorded from real compiles, already mapped to
 * file:line); test_glman checks the same against Mesa live. No GL. */
#include "check.h"
#include "glsl_fix.h"
#include "glsl_hint.h"

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

/* A test's log, a compiler's lines already mapped to file:line, as the
 * diags tarn reads it into (diag_add_log). */
static diag_list log_diags(const char *log) {
    diag_list l = { 0 };
    diag_add_log(&l, DIAG_NOTE, log);
    return l;
}

/* log with glsl_hint's notes (glsl_hint_add), formatted a line each. */
static char *annotate(const char *log, const char *source) {
    diag_list l = log_diags(log);
    glsl_hint_add(&l, 0, source);
    char *out = diag_list_format(&l, 0);
    diag_list_free(&l);
    return out;
}

static const char *src_frag =
    "#version 120\n"
    "flat varying vec3 vN;\n"
    "layout(location = 0) in vec2 vST;\n"
    "uniform float uK, uL;\n"
    "const float K = uK * 2.;\n"
    "float f(float x) { return 1; }\n"
    "void main() {\n"
    "  const float L = uK;\n"
    "  vN = vec3(1.);\n"
    "}\n";

/* The note after `after` (a line of the log) is exactly one line and holds want. */
static void check_note(const char *log, const char *source, const char *after, const char *want) {
    char *out = annotate(log, source);
    const char *a = strstr(out, after);
    const char *nl = a ? strchr(a, '\n') : NULL;
    const char *note = nl ? nl + 1 : NULL;
    const char *end = note ? strchr(note, '\n') : NULL;
    char line[1024] = "";
    if (note && end && (size_t)(end - note) < sizeof line) memcpy(line, note, (size_t)(end - note));
    bool ok = strncmp(line, "p.frag:", 7) == 0 && strstr(line, ": note: ") && strstr(line, want);
    CHECK_MSG(ok, "want a note with \"%s\" after \"%s\" in:\n%s", want, after, out);
    /* the compiler's own line stays first, as it was */
    CHECK_MSG(strncmp(out, log, strlen(log)) == 0, "%s", out);
    free(out);
}

static void test_mesa_messages(void) {
    check_note("p.frag:6: error: `return' with wrong type int, in function `f' returning float\n", src_frag,
               "returning float", "p.frag:6: note: 'f' is declared to return float but this line returns an int");
    check_note("p.frag:6: error: `return' with wrong type int, in function `f' returning float\n", src_frag,
               "returning float", "`return 1.0;`");
    check_note("p.frag:6: error: `return' with wrong type float, in function `g' returning int\n", NULL,
               "returning int", "`return int(...);`");
    /* an undeclared name's expression has Mesa's type "error": the line
     * before says what is wrong, no conversion to suggest */
    char *cascade = annotate("p.frag:6: error: `x' undeclared\n"
                             "p.frag:6: error: `return' with wrong type error, in function `f' returning float\n",
                             src_frag);
    CHECK_MSG(!strstr(cascade, "note:"), "%s", cascade);
    free(cascade);
    check_note("p.frag:5: error: initializer of const variable `K' must be a constant expression\n", src_frag,
               "expression", "p.frag:5: note: 'K' is declared const");
    /* K is global: its value moves into main(); L is local: dropping const is enough */
    check_note("p.frag:5: error: initializer of const variable `K' must be a constant expression\n", src_frag,
               "expression", "at the start of main()");
    char *out = annotate("p.frag:8: error: initializer of const variable `L' must be a constant "
                                   "expression\n", src_frag);
    CHECK(strstr(out, "Drop the word const") && !strstr(out, "start of main()"));
    free(out);
    check_note("p.frag:9: error: assignment to read-only variable 'vN'\n", src_frag, "'vN'",
               "'vN' is an input of this shader (declared flat varying)");
    check_note("p.frag:9: error: assignment to read-only variable 'vST'\n", src_frag, "'vST'",
               "`vec2 myvST = vST;`");
    check_note("p.frag:9: error: assignment to read-only variable 'uL'\n", src_frag, "'uL'",
               "'uL' is a uniform");
    check_note("p.frag:9: error: assignment to read-only variable 'q'\n", src_frag, "'q'",
               "GLSL forbids writing 'q'");
    check_note("p.frag:2: error: `gl_ModelViewMatrix' undeclared\n", "#version 330\ncompatibility = 1;\n",
               "undeclared", "Write `#version 330 compatibility`");
}

/* Mesa lists candidates under a call: the note comes after them, once. */
static void test_call_note_after_candidates(void) {
    const char *log =
        "p.frag:4: error: no matching function for call to `pow(vec2, float)'; candidates are:\n"
        "p.frag:4: error:    float pow(float, float)\n"
        "p.frag:4: error:    vec2 pow(vec2, vec2)\n"
        "p.frag:5: warning: `a' used uninitialized\n";
    char *out = annotate(log, NULL);
    const char *note = strstr(out, "p.frag:4: note: pow(vec2, float) mixes a vec2 with a scalar");
    CHECK_MSG(note && note > strstr(out, "vec2 pow(vec2, vec2)") && note < strstr(out, "p.frag:5: warning"),
              "%s", out);
    CHECK_STR_CONTAINS(out, "pow(a, vec2(b))");
    CHECK(note && strstr(note + 16, ": note: ") == NULL);    /* once */
    CHECK_GT(strlen(out), strlen(log));
    free(out);
    /* the last line of the log, without a newline */
    out = annotate("p.frag:3: error: no matching function for call to `atan(vec3, float)'; "
                             "candidates are:", NULL);
    CHECK_STR_CONTAINS(out, "candidates are:\np.frag:3: note: atan(vec3, float)");
    CHECK_STR_CONTAINS(out, "atan(a, vec3(b))");
    free(out);
    check_note("p.frag:3: error: no matching function for call to `dot(int, vec4)'\n", NULL, "dot(int",
               "dot(vec4(a), b)");
}

/* What is not NVIDIA's leniency gets no note; the log is unchanged. */
static void test_other_messages_unchanged(void) {
    static const char *const logs[] = {
        "p.frag:4: error: no matching function for call to `pow(vec2, vec3)'; candidates are:\n",
        "p.frag:4: error: no matching function for call to `myfn(float)'\n",
        "p.frag:4: error: `undefined_x' undeclared\n",
        "p.frag:4: error: `gl_ModelViewMatrix' undeclared\n",     /* compatibility #version below */
        "p.frag:4: warning: `a' used uninitialized\n",
        "some line the compiler wrote\n",
        "",
    };
    for (size_t i = 0; i < sizeof logs / sizeof logs[0]; i++) {
        char *out = annotate(logs[i], "#version 330 compatibility\n");
        CHECK_MSG(strcmp(out, logs[i]) == 0, "%zu: %s", i, out);
        free(out);
    }
    char *out = annotate(NULL, NULL);
    CHECK(out && out[0] == '\0');
    free(out);
}

/* glslang's wording (tarn validate) gets the same notes. */
static void test_glslang_messages(void) {
    check_note("p.frag:9: error: 'assign' :  l-value required \"vN\" (can't modify shader input)\n", src_frag,
               "shader input)", "'vN' is an input of this shader");
    check_note("p.frag:6: error: 'pow' : no matching overloaded function found\n", NULL, "found",
               "pow(v, vec3(s))");
    check_note("p.frag:5: error: '=' :  global const initializers must be constant ' const float'\n", NULL,
               "const float'", "Drop the word const");
    check_note("p.frag:8: error: 'non-constant initializer' : not supported for this version or the enabled "
               "extensions\n", NULL, "extensions", "Drop the word const");
    check_note("p.frag:2: error: 'gl_NormalMatrix' : undeclared identifier\n", "#version 400\n", "identifier",
               "Write `#version 400 compatibility`");
    char *out = annotate("p.frag:6: error: 'myfn' : no matching overloaded function found\n", NULL);
    CHECK(!strstr(out, "note"));
    free(out);
}

/* ---- glsl_fix: the rewrites (the texts as shader_src assembles them) ---------- */

/* lines from the first #line on (an #extension may go before it) */
static int count_lines(const char *s) {
    int n = 0;
    const char *l = strstr(s, "\n#line ");
    if (l) s = l;
    for (; *s; s++) n += *s == '\n';
    return n;
}

/* Rewrites text (p.frag, numbered from line 2 after the #version) for log;
 * the result keeps every line, holds want and the notes hold note. */
static char *fix(const char *text, shader_stage st, const char *log, const char *want, const char *note) {
    char *files[1] = { "p.frag" };
    shader_src src = { .text = (char *)text, .files = files, .nfiles = 1 };
    diag_list l = log_diags(log), nl = { 0 };
    char *out = glsl_fix_rewrite(&src, st, text, &l, &nl);
    char *notes = nl.n ? diag_list_format(&nl, 0) : NULL;
    diag_list_free(&l);
    diag_list_free(&nl);
    CHECK_MSG(out != NULL, "no rewrite for %s", log);
    if (!out) { free(notes); return NULL; }
    CHECK_MSG(count_lines(out) == count_lines(text), "lines %d -> %d:\n%s", count_lines(text), count_lines(out), out);
    if (want) CHECK_MSG(strstr(out, want) != NULL, "want \"%s\" in:\n%s", want, out);
    if (note) CHECK_MSG(notes && strstr(notes, note), "want note \"%s\" in:\n%s", note, notes ? notes : "(none)");
    CHECK_MSG(notes && strstr(notes, "NVIDIA accepted this; the GLSL specification does not"), "%s", notes ? notes : "");
    free(notes);
    return out;
}

static void test_fix_return(void) {
    const char *t = "#version 330 compatibility\n#line 2 0\n"
                    "float f(float x) { if (x > 0.) return 1; return 0; }\n"
                    "vec3 g()\n{\n  return 2 ;\n}\nvoid main() { gl_FragColor = vec4(f(1.), g()); }\n";
    char *o = fix(t, SHADER_FRAGMENT, "p.frag:2: error: `return' with wrong type int, in function `f' returning float\n"
                  "p.frag:5: error: `return' with wrong type int, in function `g' returning vec3\n",
                  "return float(1); return float(0);", "p.frag:2: warning: rewrote `return 1;` as `return float(1);`");
    CHECK(o && strstr(o, "return vec3(2 );"));
    free(o);
    /* glslang's words (tarn validate) */
    o = fix(t, SHADER_FRAGMENT, "p.frag:5: error: 'return' : cannot convert return value to function return type\n",
            "return vec3(2 );", "p.frag:5: warning: ");
    CHECK(o && strstr(o, "return 1;"));   /* only the line named */
    free(o);
    diag_list w = log_diags("p.frag:2: warning: 'return' : type conversion on return values was not "
                            "explicitly allowed until version 420\n");
    CHECK(glsl_fix_wanted_by_warning(&w));
    diag_list_free(&w);
}

static void test_fix_const(void) {
    const char *t = "#version 330 compatibility\n#line 2 0\nuniform float uK;\nconst float G = uK * 2.;\n"
                    "void main() {\n  const float K = uK;\n  gl_FragColor = vec4(K, G, 0., 1.);\n}\n";
    char *o = fix(t, SHADER_FRAGMENT, "p.frag:3: error: initializer of const variable `G' must be a constant expression\n"
                  "p.frag:5: error: initializer of const variable `K' must be a constant expression\n",
                  "\nfloat G = uK * 2.;\n", "p.frag:5: warning: dropped `const` from 'K'");
    CHECK(o && strstr(o, "  float K = uK;"));
    free(o);
    o = fix(t, SHADER_FRAGMENT, "p.frag:3: error: '=' :  global const initializers must be constant ' const float'\n",
            "\nfloat G = uK * 2.;\n", "from 'G'");
    CHECK(o && strstr(o, "const float K"));
    free(o);
}

static void test_fix_input(void) {
    const char *t = "#version 120\n#line 1 0\nvarying vec2 vST;\nfloat h() { return vST.x; }\n"
                    "void main()\n{\n  vST = vST * 0.5; vST.s += 0.;\n  gl_FragColor = vec4(vST, h(), 1.);\n}\n";
    char *o = fix(t, SHADER_FRAGMENT, "p.frag:6: error: assignment to read-only variable 'vST'\n",
                  "varying vec2 vST; vec2 tarn_vST;\n", "p.frag:6: warning: 'vST' is an input");
    CHECK(o && strstr(o, "return tarn_vST.x;") && strstr(o, "{ tarn_vST = vST;\n") &&
          strstr(o, "tarn_vST = tarn_vST * 0.5; tarn_vST.s") && strstr(o, "vec4(tarn_vST, h()"));
    free(o);
    o = fix(t, SHADER_FRAGMENT, "p.frag:6: error: 'assign' :  l-value required \"vST\" (can't modify shader input)\n",
            "{ tarn_vST = vST;", NULL);
    free(o);
}

static void test_fix_widen(void) {
    const char *t = "#version 120\n#line 1 0\nvarying vec2 vST;\nvec2 f(vec2 a)\n{\n  return pow(a, 2.) + pow(1., 2.);\n}\n"
                    "void main() { gl_FragColor = vec4(f(vST), pow(2., 3.), 1.); }\n";
    char *o = fix(t, SHADER_FRAGMENT, "p.frag:5: error: no matching function for call to `pow(vec2, float)'; candidates are:\n"
                  "p.frag:5: error:    float pow(float, float)\n",
                  "return tarn_pow(a, 2.) + tarn_pow(1., 2.);", "p.frag:5: warning: rewrote pow(...) as tarn_pow(...)");
    /* the overloads go before the function, on its line; main's own pow stays */
    CHECK(o && strstr(o, "vec2 tarn_pow(vec2 a, float b) { return pow(a, vec2(b)); }") &&
          strstr(o, "} vec2 f(vec2 a)\n") && strstr(o, "pow(2., 3.), 1.)") && !strstr(o, "tarn_pow(2., 3.)"));
    free(o);
    /* glslang names the function only */
    o = fix(t, SHADER_FRAGMENT, "p.frag:5: error: 'pow' : no matching overloaded function found\n", "tarn_pow(a, 2.)", NULL);
    free(o);
}

static void test_fix_varying_and_outs(void) {
    const char *t = "#version 330 compatibility\n#line 2 0\nflat varying vec3 vN;\n"
                    "layout(location = 0) out vec4 fColor;\nvoid f(out float x) { x = 1.; }\n"
                    "void main() { fColor = vec4(vN, 1.); gl_FragColor = fColor; }\n";
    char *o = fix(t, SHADER_FRAGMENT, "p.frag:2: error: qualifier 'flat' cannot be applied to the deprecated storage "
                  "qualifier 'varying'\n", "\nflat in vec3 vN;\n", "p.frag:2: warning: rewrote `varying`");
    free(o);
    o = fix(t, SHADER_FRAGMENT, "p.frag:0: error: fragment shader writes to both `gl_FragColor' and `fColor'\n",
            "\nvec4 fColor;\n", "p.frag:3: warning: the shader writes gl_FragColor");
    CHECK(o && strstr(o, "void f(out float x)"));   /* a parameter's out stays */
    free(o);
    /* before GLSL 1.30 `flat` is GL_EXT_gpu_shader4's (and `#line 1` numbers the next line 2) */
    const char *old = "#version 120\n#line 1 0\nflat varying vec3 vN;\nvoid main() { gl_FragColor = vec4(vN, 1.); }\n";
    o = fix(old, SHADER_FRAGMENT, "p.frag:2: error: syntax error, unexpected NEW_IDENTIFIER\n",
            "#version 120\n#extension GL_EXT_gpu_shader4 : enable", "p.frag:2: warning: `flat` before GLSL 1.30");
    free(o);
}

/* Valid text, or a message that is no NVIDIA leniency: no rewrite at all. */
static void test_fix_leaves_others(void) {
    const char *t = "#version 330 compatibility\n#line 2 0\nuniform float uK;\nvoid main() { gl_FragColor = vec4(uK); }\n";
    char *files[1] = { "p.frag" };
    shader_src src = { .text = (char *)t, .files = files, .nfiles = 1 };
    static const char *const logs[] = {
        "", "p.frag:3: error: `undefined_x' undeclared\n",
        "p.frag:3: error: no matching function for call to `pow(vec2, vec3)'; candidates are:\n",
        "p.frag:3: error: no matching function for call to `myfn(vec2, float)'\n",
        "p.frag:3: error: assignment to read-only variable 'uK'\n",   /* a uniform: no input to copy */
        "q.frag:3: error: `return' with wrong type int, in function `f' returning float\n",
    };
    for (size_t i = 0; i < sizeof logs / sizeof logs[0]; i++) {
        diag_list l = log_diags(logs[i]), notes = { 0 };
        char *o = glsl_fix_rewrite(&src, SHADER_FRAGMENT, t, &l, &notes);
        CHECK_MSG(o == NULL && notes.n == 0, "%zu: %s", i, o ? o : "");
        free(o);
        diag_list_free(&l);
        diag_list_free(&notes);
    }
}

/* A uniform declared vec3 in one stage and vec4 in another: say which, where. */
static void test_link_hint(void) {
    char *fv[1] = { "v.vert" }, *ff[1] = { "f.frag" };
    shader_src v = { .text = "#version 120\n#line 1 0\nuniform vec3 uC;\nvoid main() { gl_Position = vec4(uC, 1.); }\n",
                     .files = fv, .nfiles = 1 };
    shader_src f = { .text = "#version 120\n#line 1 0\n\nuniform vec4 uC;\nvoid main() { gl_FragColor = uC; }\n",
                     .files = ff, .nfiles = 1 };
    const shader_src *srcs[SHADER_STAGE_COUNT] = { [SHADER_VERTEX] = &v, [SHADER_FRAGMENT] = &f };
    diag_list l = { 0 };
    CHECK(glsl_fix_link_hint("error: uniform `uC' declared as type `vec4' and type `vec3'\n", srcs, &l));
    char *h = diag_list_format(&l, 0);
    CHECK_MSG(strstr(h, "uniform 'uC' is declared vec3 in the vertex shader (v.vert:2) and vec4 in the "
                        "fragment shader (f.frag:3)"), "%s", h);
    free(h);
    diag_list_free(&l);
    CHECK(glsl_fix_link_hint("ERROR: Linking fragment stages: Types must match: an earlier stage: \" vec3 uC\"", srcs,
                             &l));
    h = diag_list_format(&l, 0);
    CHECK(strstr(h, "'uC'"));
    free(h);
    diag_list_free(&l);
    CHECK(!glsl_fix_link_hint("error: something else\n", srcs, &l) && l.n == 0);
}

int main(void) {
    RUN(test_mesa_messages);
    RUN(test_call_note_after_candidates);
    RUN(test_other_messages_unchanged);
    RUN(test_glslang_messages);
    RUN(test_fix_return);
    RUN(test_fix_const);
    RUN(test_fix_input);
    RUN(test_fix_widen);
    RUN(test_fix_varying_and_outs);
    RUN(test_fix_leaves_others);
    RUN(test_link_hint);
    return check_summary();
}
