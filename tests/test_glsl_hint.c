/* Tests of glsl_hint: the notes added after compiler messages for GLSL that
 * NVIDIA accepted and the spec forbids. The logs are Mesa 22.3's and
 * glslang's own lines (recorded from real compiles, already mapped to
 * file:line); test_glman checks the same against Mesa live. No GL. */
#include "check.h"
#include "glsl_hint.h"

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

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
    char *out = glsl_hint_annotate(log, source);
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
    check_note("p.frag:5: error: initializer of const variable `K' must be a constant expression\n", src_frag,
               "expression", "p.frag:5: note: 'K' is declared const");
    /* K is global: its value moves into main(); L is local: dropping const is enough */
    check_note("p.frag:5: error: initializer of const variable `K' must be a constant expression\n", src_frag,
               "expression", "at the start of main()");
    char *out = glsl_hint_annotate("p.frag:8: error: initializer of const variable `L' must be a constant "
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
    char *out = glsl_hint_annotate(log, NULL);
    const char *note = strstr(out, "p.frag:4: note: pow(vec2, float) mixes a vec2 with a scalar");
    CHECK_MSG(note && note > strstr(out, "vec2 pow(vec2, vec2)") && note < strstr(out, "p.frag:5: warning"),
              "%s", out);
    CHECK_STR_CONTAINS(out, "pow(a, vec2(b))");
    CHECK(note && strstr(note + 16, ": note: ") == NULL);    /* once */
    CHECK(strlen(out) > strlen(log));
    free(out);
    /* the last line of the log, without a newline */
    out = glsl_hint_annotate("p.frag:3: error: no matching function for call to `atan(vec3, float)'; "
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
        char *out = glsl_hint_annotate(logs[i], "#version 330 compatibility\n");
        CHECK_MSG(strcmp(out, logs[i]) == 0, "%zu: %s", i, out);
        free(out);
    }
    char *out = glsl_hint_annotate(NULL, NULL);
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
    char *out = glsl_hint_annotate("p.frag:6: error: 'myfn' : no matching overloaded function found\n", NULL);
    CHECK(!strstr(out, "note"));
    free(out);
}

int main(void) {
    RUN(test_mesa_messages);
    RUN(test_call_note_after_candidates);
    RUN(test_other_messages_unchanged);
    RUN(test_glslang_messages);
    return check_summary();
}
