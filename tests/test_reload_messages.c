/* What a student reads after a save (issue #17): each error line once,
 * naming the program and the stage it broke; no uniform warnings about a
 * program whose sources failed (the warnings were about its last good
 * build, not the text on disk). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "support.h"
#include "gl_ctx.h"
#include "gl_support.h"
#include "render.h"

static const char *vert = "#version 330 compatibility\n"
                          "void main() { gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; }\n";

static const char *frag_using(const char *extra) {
    static char buf[1024];
    snprintf(buf, sizeof buf,
             "#version 330 compatibility\nuniform vec4 uColor;\n#include \"common.glsl\"\n"
             "out vec4 fragColor;\nvoid main() { fragColor = uColor * helper(1.0)%s; }\n", extra);
    return buf;
}

static void two_programs_scene(void) {
    scratch_write("a.vert", vert);
    scratch_write("water.frag", frag_using(""));
    scratch_write("sky.frag", frag_using(" + vec4(0.1)"));
    scratch_write("lake.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\n"
                               "Vertex a.vert\nFragment water.frag\nProgram Water uColor {0.2 0.4 0.6 1.}\n"
                               "QuadXY 0 1 1 1\n"
                               "Vertex a.vert\nFragment sky.frag\nProgram Sky uColor {0.2 0.4 0.6 1.}\n"
                               "QuadXY 0 1 1 1\n");
}

/* An error in a file both programs include: one line, naming both. */
static void test_shared_include_error_once_naming_programs(void) {
    two_programs_scene();
    scratch_write("common.glsl", "float helper(float x) { return x * 2.0 }\n");
    render *r = render_create(NULL);
    CHECK(!render_load(r, scratch_path("lake.glib")));
    const char *m = render_messages(r);
    fprintf(stderr, "%s", m);
    CHECK_MSG(count_of(m, "common.glsl:1:") == 1, "%s", m);
    CHECK_STR_CONTAINS(m, "(fragment shader of programs 'Water', 'Sky')");
    render_destroy(r);
}

/* An error in one program's own stage file names that program and stage. */
static void test_stage_error_names_program_and_stage(void) {
    two_programs_scene();
    scratch_write("common.glsl", "float helper(float x) { return x * 2.0; }\n");
    scratch_write("sky.frag", frag_using(" + undefined_thing"));
    render *r = render_create(NULL);
    CHECK(!render_load(r, scratch_path("lake.glib")));
    const char *m = render_messages(r);
    fprintf(stderr, "%s", m);
    CHECK_STR_CONTAINS(m, "sky.frag:5:");
    CHECK_STR_CONTAINS(m, "(fragment shader of program 'Sky')");
    CHECK(!strstr(m, "'Water'"));
    CHECK_MSG(count_of(m, "\n") == count_of(m, "(fragment shader of program 'Sky')"), "%s", m);
    render_destroy(r);
}

/* A save that both breaks the shader and adds a slider the last good build
 * lacks: the error, not "uniform 'uTypo' is not declared". */
static void test_no_uniform_warnings_for_a_failed_program(void) {
    two_programs_scene();
    scratch_write("common.glsl", "float helper(float x) { return x * 2.0; }\n");
    render *r = gl_test_load_scratch("lake.glib");
    scratch_write("water.frag", frag_using(" + oops("));
    scratch_write("lake.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\n"
                               "Vertex a.vert\nFragment water.frag\n"
                               "Program Water uColor {0.2 0.4 0.6 1.} uLevel <0. 1. 2.>\n"
                               "QuadXY 0 1 1 1\n"
                               "Vertex a.vert\nFragment sky.frag\nProgram Sky uColor {0.2 0.4 0.6 1.}\n"
                               "QuadXY 0 1 1 1\n");
    CHECK(!render_load(r, NULL));
    const char *m = render_messages(r);
    fprintf(stderr, "%s", m);
    CHECK_STR_CONTAINS(m, "water.frag:5:");
    CHECK_MSG(!strstr(m, "uLevel"), "%s", m);
    /* fixed: the new slider is the shader's, and still no warning */
    scratch_write("water.frag", "#version 330 compatibility\nuniform vec4 uColor;\nuniform float uLevel;\n"
                                "#include \"common.glsl\"\nout vec4 fragColor;\n"
                                "void main() { fragColor = uColor * helper(uLevel); }\n");
    CHECK_MSG(render_load(r, NULL), "%s", render_messages(r));
    CHECK_MSG(render_messages(r)[0] == '\0', "%s", render_messages(r));
    /* and a real typo in a program that builds is still reported */
    scratch_write("lake.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\n"
                               "Vertex a.vert\nFragment water.frag\n"
                               "Program Water uColor {0.2 0.4 0.6 1.} uLevel <0. 1. 2.> uLevle <0. 1. 2.>\n"
                               "QuadXY 0 1 1 1\n");
    render_load(r, NULL);
    CHECK_STR_CONTAINS(render_messages(r), "uniform 'uLevle' is not declared in program 'Water'");
    render_destroy(r);
}

/* A uniform the shader declares but does not use (here compiled out by a
 * Define) is never called undeclared: not at start-up, not on a reload
 * that keeps the build (issue #30: R printed "not declared" for each), and
 * the inactive ones are one summary line a load, the same each time. */
static void test_inactive_uniforms_one_line_same_on_reload(void) {
    scratch_write("a.vert", vert);
    scratch_write("water.frag", "#version 330 compatibility\nuniform vec4 uColor;\nuniform float uLevel;\n"
                                "uniform float uGlint;\nout vec4 fragColor;\n"
                                "void main() {\n#ifdef USE_LEVEL\n fragColor = uColor * uLevel * uGlint;\n"
                                "#else\n fragColor = uColor;\n#endif\n}\n");
    scratch_write("lake.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\n"
                               "Vertex a.vert\nFragment water.frag\n"
                               "Program Water uColor {0.2 0.4 0.6 1.} uLevel <0. 1. 2.> uGlint <0. 1. 2.>\n"
                               "QuadXY 0 1 1 1\n");
    render *r = gl_test_load_scratch("lake.glib");
    char first[2048];
    snprintf(first, sizeof first, "%s", render_messages(r));
    fprintf(stderr, "start-up: %s", first);
    CHECK_STR_CONTAINS(first, "lake.glib:5: note: 2 uniforms of the glib are declared but inactive as built");
    CHECK_STR_CONTAINS(first, "uLevel (Water), uGlint (Water)");
    CHECK_MSG(count_of(first, "\n") == 1, "one line, not one a uniform: %s", first);
    CHECK_MSG(!strstr(first, "not declared"), "%s", first);
    render_load(r, NULL);   /* R: the same text, the build kept */
    fprintf(stderr, "reload: %s", render_messages(r));
    CHECK_MSG(strcmp(render_messages(r), first) == 0, "start-up said:\n%sreload said:\n%s", first,
              render_messages(r));
    render_destroy(r);
    /* --verbose (render_desc.verbose): the summary, then each at its glib line */
    r = render_create(&(render_desc){ .verbose = true });
    CHECK_MSG(render_load(r, scratch_path("lake.glib")), "%s", render_messages(r));
    const char *v = render_messages(r);
    fprintf(stderr, "verbose: %s", v);
    CHECK_STR_CONTAINS(v, "lake.glib:5: note: 2 uniforms of the glib are declared but inactive as built");
    CHECK_STR_CONTAINS(v, "lake.glib:5: note: uniform 'uLevel' is declared in program 'Water' but inactive as built");
    CHECK_STR_CONTAINS(v, "lake.glib:5: note: uniform 'uGlint' is declared in program 'Water' but inactive as built");
    CHECK_MSG(count_of(v, "\n") == 3, "the summary and a line each: %s", v);
    CHECK_MSG(!strstr(v, "uColor"), "uColor is active: %s", v);
    render_destroy(r);
}

/* A glib and shaders that no longer belong together (issue #27: the
 * shader declares none of the glib's uniforms, the picture is black): one
 * line naming the program, its glib line and its shader files, not a
 * warning a uniform; one typo among declared uniforms is still its own. */
static void test_glib_and_shaders_apart_one_line(void) {
    scratch_write("a.vert", vert);
    scratch_write("other.frag", "#version 330 compatibility\nuniform float uSomethingElse;\nout vec4 fragColor;\n"
                                "void main() { fragColor = vec4(uSomethingElse); }\n");
    scratch_write("apart.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\n"
                                "Vertex a.vert\nFragment other.frag\n"
                                "Program Stripes uA <0. 1. 2.> uB <0. 1. 2.> uColor {1. 0. 0. 1.}\n"
                                "QuadXY 0 1 1 1\n");
    render *r = render_create(NULL);
    render_load(r, scratch_path("apart.glib"));
    const char *m = render_messages(r);
    fprintf(stderr, "%s", m);
    CHECK_STR_CONTAINS(m, "apart.glib:5: warning: none of the 3 uniforms the glib gives Program 'Stripes' "
                          "(uA, uB, uColor) is declared in its shaders (a.vert, other.frag): "
                          "do the glib and the shaders belong together?");
    CHECK_MSG(!strstr(m, "is not declared"), "one line, not one a uniform: %s", m);
    render_destroy(r);
    /* one of the two declared: the other is a typo, said as before */
    scratch_write("other.frag", "#version 330 compatibility\nuniform float uA;\nout vec4 fragColor;\n"
                                "void main() { fragColor = vec4(uA); }\n");
    scratch_write("apart.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\n"
                                "Vertex a.vert\nFragment other.frag\n"
                                "Program Stripes uA <0. 1. 2.> uB <0. 1. 2.>\n"
                                "QuadXY 0 1 1 1\n");
    r = render_create(NULL);
    render_load(r, scratch_path("apart.glib"));
    m = render_messages(r);
    CHECK_STR_CONTAINS(m, "uniform 'uB' is not declared in program 'Stripes'");
    CHECK_MSG(!strstr(m, "belong together"), "%s", m);
    render_destroy(r);
    /* a single glib uniform undeclared: its own warning (one name is a typo more likely) */
    scratch_write("apart.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\n"
                                "Vertex a.vert\nFragment other.frag\nProgram Stripes uB <0. 1. 2.>\n"
                                "QuadXY 0 1 1 1\n");
    r = render_create(NULL);
    render_load(r, scratch_path("apart.glib"));
    m = render_messages(r);
    CHECK_STR_CONTAINS(m, "uniform 'uB' is not declared in program 'Stripes'");
    CHECK_MSG(!strstr(m, "belong together"), "%s", m);
    render_destroy(r);
}

/* Draws one frame of the loaded scene into a small target; returns the
 * draw messages (issue #27: "say why a picture is black"). */
static const char *draw_once(render *r) {
    render_target tg;
    CHECK(render_target_create(&tg, 32, 32, false));
    render_frame_at(r, 0.0, tg.fbo, 0, 0, 32, 32, NULL);
    render_target_destroy(&tg);
    return render_draw_messages(r);
}

/* A one-colour picture while the program uses uniforms the glib never
 * gives (0, in tarn as in glman): said once, naming them and what to do;
 * not when each is given, nor when the picture is not flat. */
static void test_flat_picture_names_unset_uniforms(void) {
    scratch_write("a.vert", vert);
    scratch_write("glow.frag", "#version 330 compatibility\nuniform float uBright;\nuniform vec3 uTint;\n"
                               "uniform float uGiven;\nout vec4 fragColor;\n"
                               "void main() { fragColor = vec4(uTint * uBright * uGiven + GRADIENT, 1.); }\n");
    const char *glib = "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex a.vert\nFragment glow.frag\n%s\n"
                       "Program Glow uGiven <0. 1. 2.>%s\nQuadXY 0 1 1 1\n";
    char text[512];
    snprintf(text, sizeof text, glib, "Define GRADIENT 0.0", "");
    scratch_write("flat.glib", text);
    render *r = render_create(NULL);
    render_load(r, scratch_path("flat.glib"));
    const char *m = draw_once(r);
    fprintf(stderr, "%s", m);
    CHECK_STR_CONTAINS(m, "flat.glib:6: warning: the picture is one flat colour, and program 'Glow' uses 2 uniforms "
                          "that the glib gives no value, so they stay 0: uBright, uTint; give each a value");
    CHECK_EQ(count_of(draw_once(r), "flat colour"), 1);   /* once a load */
    /* each given: no word */
    snprintf(text, sizeof text, glib, "Define GRADIENT 0.0", " uBright <0. 1. 2.> uTint {1. 1. 1.}");
    scratch_write("flat.glib", text);
    render_load(r, NULL);
    m = draw_once(r);
    CHECK_MSG(!strstr(m, "flat colour"), "%s", m);
    /* unset but the picture varies: no word either */
    snprintf(text, sizeof text, glib, "Define GRADIENT gl_FragCoord.x / 32.", "");
    scratch_write("flat.glib", text);
    render_load(r, NULL);
    m = draw_once(r);
    CHECK_MSG(!strstr(m, "flat colour"), "%s", m);
    render_destroy(r);
}

/* A shapefile (or OBJ) that is not there: one line at its glib line naming
 * it, not a second "cannot build" after the parser's (issue #27). */
static void test_missing_file_said_once(void) {
    scratch_write("a.vert", vert);
    scratch_write("water.frag", frag_using(""));
    scratch_write("common.glsl", "float helper(float x) { return x; }\n");
    scratch_write("map.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex a.vert\nFragment water.frag\n"
                              "Program Map uColor {1. 1. 1. 1.}\nShp coast.shp\nObj boat.obj\n");
    render *r = render_create(NULL);
    render_load(r, scratch_path("map.glib"));
    const char *m = render_messages(r);
    fprintf(stderr, "%s", m);
    CHECK_STR_CONTAINS(m, "map.glib:6: error: cannot open '");
    CHECK_STR_CONTAINS(m, "coast.shp' (from command Shp)");
    CHECK_STR_CONTAINS(m, "map.glib:7: error: cannot open '");
    CHECK_STR_CONTAINS(m, "boat.obj' (from command Obj)");
    CHECK_MSG(count_of(m, "coast.shp") == 1 && count_of(m, "boat.obj") == 1, "once each: %s", m);
    render_destroy(r);
}

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    if (!scratch_create("reload-messages")) return 1;
    RUN(test_shared_include_error_once_naming_programs);
    RUN(test_stage_error_names_program_and_stage);
    RUN(test_no_uniform_warnings_for_a_failed_program);
    RUN(test_inactive_uniforms_one_line_same_on_reload);
    RUN(test_glib_and_shaders_apart_one_line);
    RUN(test_flat_picture_names_unset_uniforms);
    RUN(test_missing_file_said_once);
    gl_ctx_destroy(ctx);
    scratch_remove();
    return check_summary();
}
