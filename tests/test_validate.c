/* Tests of validate: glslang checks of assembled stages (errors mapped to
 * file:line), and `tarn validate` over .glib files, directories and stage
 * files, with every combination of a Program's Define toggles. No GPU. */
#include "check.h"
#include "support.h"
#include "shader_src.h"
#include "validate.h"

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static char g_tmp[256];     /* scratch */

/* Assembles and compiles a fixture; returns whether it compiled, *log the messages. */
static bool check_stage(const char *name, shader_stage st, bool gstap, char **log) {
    const char *dirs[] = { shader_data("repo/packs/common") };
    shader_src_desc d = { .path = shader_data(name), .stage = st, .gstap = gstap, .include_dirs = dirs,
                          .ninclude_dirs = 1 };
    shader_src s;
    *log = NULL;
    if (!shader_src_load(&d, &s)) {
        fprintf(stderr, "  load %s: %s\n", name, s.error.text);
        shader_src_free(&s);
        return false;
    }
    diag_list l = { 0 };
    bool ok = validate_stage(&s, st, &l);
    *log = diag_list_format(&l, 0);
    diag_list_free(&l);
    shader_src_free(&s);
    return ok;
}

/* Runs validate over paths, returning what it printed (heap). */
static char *run_validate(const char *const *paths, int n, const char *root, int *rc, validate_result *res) {
    FILE *f = tmpfile();
    if (!f) return NULL;
    *rc = validate_run_ex(paths, n, root, f, res);
    long len = ftell(f);
    rewind(f);
    char *s = calloc(1, (size_t)(len > 0 ? len : 0) + 1);
    if (s && len > 0 && fread(s, 1, (size_t)len, f) != (size_t)len) s[0] = '\0';
    fclose(f);
    fprintf(stderr, "%s", s ? s : "");
    return s;
}

static int count_lines_with(const char *text, const char *needle) {
    int n = 0;
    for (const char *p = text; p && (p = strstr(p, needle)) != NULL; p += strlen(needle)) n++;
    return n;
}

static void test_good_compat_shader_validates(void) {
    char *log = NULL;
    CHECK_MSG(check_stage("good_compat.vert", SHADER_VERTEX, false, &log), "%s", log ? log : "");
    CHECK(log == NULL || log[0] == '\0');
    free(log);
    CHECK_MSG(check_stage("good_compat.frag", SHADER_FRAGMENT, false, &log), "%s", log ? log : "");
    CHECK(log == NULL || log[0] == '\0');
    free(log);
    /* a bare glman shader with no #version is compatibility 3.30 */
    CHECK(!check_stage("noversion.frag", SHADER_FRAGMENT, false, &log));
    CHECK_STR_CONTAINS(log, "noversion.frag:4: error: 'undefined_in_noversion'");
    CHECK_EQ(strstr(log, "gl_FragColor"), NULL);
    free(log);
}

static void test_error_in_included_file_reports_that_file_and_line(void) {
    char *log = NULL;
    CHECK(!check_stage("inc_error.frag", SHADER_FRAGMENT, false, &log));
    CHECK_STR_CONTAINS(log, "inc/bad_line4.glsl:4: error: ");
    CHECK_EQ(count_lines_with(log, "error:"), 1);
    free(log);

    /* two levels down, through inc/map_waves.glsl */
    CHECK(!check_stage("map_main.frag", SHADER_FRAGMENT, false, &log));
    CHECK_STR_CONTAINS(log, "inc/map_fresnel.glsl:4: error: 'undefined_in_fresnel' : undeclared identifier");
    CHECK_EQ(strstr(log, "compilation terminated"), NULL);     /* glslang's noise is dropped */
    CHECK_EQ(strstr(log, "No code generated"), NULL);
    free(log);
}

static void test_error_after_include_reports_main_file_line(void) {
    char *log = NULL;
    CHECK(!check_stage("after_inc_error.frag", SHADER_FRAGMENT, false, &log));
    CHECK_STR_CONTAINS(log, "after_inc_error.frag:6: error: 'no_such_variable'");
    free(log);
}

static void test_old_glsl_line_numbers(void) {
    /* GLSL 1.20: `#line N` numbers the next line N + 1 in glslang */
    char *log = NULL;
    CHECK(!check_stage("old120.vert", SHADER_VERTEX, false, &log));
    CHECK_STR_CONTAINS(log, "old120.vert:5: error: 'undefined_in_old'");
    free(log);
}

static void test_gstap_names_compile(void) {
    char *log = NULL;
    CHECK_MSG(check_stage("gstap.vert", SHADER_VERTEX, true, &log), "%s", log ? log : "");
    free(log);
    CHECK_MSG(check_stage("gstap.frag", SHADER_FRAGMENT, true, &log), "%s", log ? log : "");
    free(log);
    /* and without GSTAP they are unknown */
    CHECK(!check_stage("gstap.vert", SHADER_VERTEX, false, &log));
    CHECK_STR_CONTAINS(log, "gstap.vert:7: error: 'uNormalMatrix'");
    free(log);

    int rc = -1;
    validate_result res;
    const char *p1[] = { shader_data("gstap.glib") };
    char *out = run_validate(p1, 1, shader_data("repo"), &rc, &res);
    CHECK_EQ(rc, 0);
    CHECK(res.nerrors == 0 && res.nprograms == 1 && res.nstages == 2);
    free(out);
    const char *p2[] = { shader_data("nogstap.glib") };
    out = run_validate(p2, 1, shader_data("repo"), &rc, &res);
    CHECK_EQ(rc, 1);
    CHECK_STR_CONTAINS(out, "gstap.vert:7: error: ");
    free(out);
}

static void test_toggle_combination_that_breaks_is_found(void) {
    int rc = -1;
    validate_result res;
    const char *paths[] = { shader_data("toggle.glib") };
    char *out = run_validate(paths, 1, shader_data("repo"), &rc, &res);
    CHECK_EQ(rc, 1);
    CHECK_EQ(res.nprograms, 1);
    CHECK_EQ(res.ncombinations, 4);
    CHECK_EQ(res.nerrors, 1);
    CHECK_STR_CONTAINS(out, "toggle.frag:8: error: ");
    CHECK_STR_CONTAINS(out, "[with FOO=1 BAR=0] (2 of 4 combinations)\n");
    CHECK_EQ(strstr(out, "FOO=0"), NULL);
    CHECK_STR_CONTAINS(out, "validate: 1 programs, 2 stages, 4 combinations: 1 errors\n");
    free(out);
}

static void test_good_glib_passes(void) {
    int rc = -1;
    validate_result res;
    const char *paths[] = { shader_data("good.glib") };
    char *out = run_validate(paths, 1, shader_data("repo"), &rc, &res);
    CHECK_EQ(rc, 0);
    CHECK(res.nerrors == 0 && res.nwarnings == 0);
    CHECK_STR_CONTAINS(out, "validate: 1 programs, 2 stages, 1 combinations: 0 errors\n");
    free(out);
}

static void test_link_checks(void) {
    int rc = -1;
    validate_result res;
    const char *paths[] = { shader_data("link.glib") };
    char *out = run_validate(paths, 1, shader_data("repo"), &rc, &res);
    CHECK_EQ(rc, 1);
    CHECK_EQ(res.nprograms, 3);
    /* vec3 out, vec4 in: glslang's link finds it; it is placed at the Program line */
    CHECK_STR_CONTAINS(out, "link.glib:5: error: program Mismatch: ");
    CHECK_STR_CONTAINS(out, "vN");
    /* an input the vertex shader never writes (glslang's link does not look) */
    CHECK_STR_CONTAINS(out, "unwritten.frag:4: warning: fragment shader input 'vNormal' is not written by the vertex shader");
    CHECK_EQ(strstr(out, "vUnused"), NULL);             /* declared, never read: fine */
    /* gl_TexCoord/gl_Color between compatibility stages are not an error */
    CHECK_EQ(strstr(out, "TexCoord"), NULL);
    CHECK_EQ(strstr(out, "Anonymous"), NULL);
    CHECK_EQ(res.nerrors, 1);
    CHECK_EQ(res.nwarnings, 1);
    free(out);
}

static void test_missing_stage_file_is_reported_at_glib_line(void) {
    int rc = -1;
    validate_result res;
    const char *paths[] = { shader_data("missing_stage.glib") };
    char *out = run_validate(paths, 1, shader_data("repo"), &rc, &res);
    CHECK_EQ(rc, 1);
    CHECK_STR_CONTAINS(out, "missing_stage.glib:4: error: ");
    CHECK_EQ(count_lines_with(out, "missing_stage.glib:4: error: "), 1);    /* once */
    free(out);
}

static void test_no_paths_means_packs_and_scenes(void) {
    int rc = -1;
    validate_result res;
    char *out = run_validate(NULL, 0, shader_data("repo"), &rc, &res);
    /* packs/testpack/pack.glib (its shader includes packs/common) and
     * scenes/sub/scene.glib, whose GLSL 1.20 fragment shader reads a varying
     * the vertex shader does not write: an error before GLSL 1.30 */
    CHECK_EQ(res.nprograms, 2);
    CHECK_EQ(rc, 1);
    CHECK_EQ(res.nerrors, 1);
    CHECK_STR_CONTAINS(out, "scenes/sub/scene120.frag:3: error: fragment shader input 'vColour' is not written");
    CHECK_STR_CONTAINS(out, "validate: 2 programs, 4 stages, 2 combinations: 1 errors\n");
    free(out);
}

static void test_stage_files_and_directories(void) {
    int rc = -1;
    validate_result res;
    const char *paths[] = { shader_data("good_compat.vert"), shader_data("inc_error.frag"), shader_data("inc/map_waves.glsl"),
                            shader_data("no_such_file.frag"), shader_data("inc") };
    char *out = run_validate(paths, 5, shader_data("repo"), &rc, &res);
    CHECK_EQ(rc, 1);
    CHECK_EQ(res.nprograms, 0);
    CHECK_EQ(res.nstages, 2);
    CHECK_STR_CONTAINS(out, "inc/bad_line4.glsl:4: error: ");
    CHECK_STR_CONTAINS(out, "map_waves.glsl:0: warning: cannot tell the stage");   /* named: said */
    CHECK_STR_CONTAINS(out, "no_such_file.frag:0: error: No such file or directory");
    /* inc/ holds only includes (no main): nothing to check, nothing said of them */
    CHECK_EQ(strstr(out, "cycle_a.glsl"), NULL);
    CHECK_EQ(res.nerrors, 2);
    free(out);
}

/* A whole-number Define slider is validated at its other values too: every
 * value of a short range (MODE 0..3), the ends of a long one (STEPS 1..32),
 * each with the toggles at their defaults; an error only one value compiles
 * names that value. */
static void test_define_slider_values_are_validated(void) {
    char path[512], frag[512];
    snprintf(frag, sizeof frag, "%s/modes.frag", g_tmp);
    FILE *f = fopen(frag, "w");
    CHECK_NE(f, NULL);
    if (!f) return;
    fputs("#version 330 core\nout vec4 c;\nvoid main() {\n    c = vec4(0.0);\n"
          "    for (int i = 0; i < STEPS; i++) c += vec4(0.1);\n"
          "#if MODE == 2\n    c = 1;\n#endif\n}\n", f);
    fclose(f);
    snprintf(path, sizeof path, "%s/modes.glib", g_tmp);
    f = fopen(path, "w");
    CHECK_NE(f, NULL);
    if (!f) return;
    fputs("##OpenGL GLIB\nFragment modes.frag\nDefine MODE <0 0 3>\nDefine STEPS <1 8 32>\nDefine FLAG <true>\n"
          "Program Modes\n", f);
    fclose(f);
    int rc = -1;
    validate_result res;
    const char *paths[] = { path };
    char *out = run_validate(paths, 1, shader_data("repo"), &rc, &res);
    /* FLAG on and off, then MODE 1, 2, 3 and STEPS 1, 32 */
    CHECK_EQ(res.ncombinations, 2 + 3 + 2);
    CHECK(rc == 1 && res.nerrors == 1);
    CHECK_STR_CONTAINS(out, "modes.frag:7: error: ");
    CHECK_STR_CONTAINS(out, "[with MODE=2 FLAG=1]\n");
    free(out);
}

/* In a folder, a .glsl without a stage suffix is an include unless it has
 * a main() (however it is spaced); only that one gets the warning. */
static void test_unnamed_glsl_with_main_is_reported(void) {
    char dir[300], path[400];
    snprintf(dir, sizeof dir, "%s/glsl", g_tmp);
    CHECK_EQ(mkdir(dir, 0777), 0);
    const char *files[2][2] = { { "x.glsl", "vec3 f();\nvoid main\n ()\n{}\n" },
                                { "y.glsl", "float mainly() { return 1.0; }\nfloat domain(float x);\n" } };
    for (int i = 0; i < 2; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, files[i][0]);
        FILE *f = fopen(path, "w");
        CHECK_NE(f, NULL);
        if (!f) return;
        fputs(files[i][1], f);
        fclose(f);
    }
    int rc = -1;
    validate_result res;
    const char *paths[] = { dir };
    char *out = run_validate(paths, 1, shader_data("repo"), &rc, &res);
    CHECK(rc == 0 && res.nwarnings == 1);
    CHECK_STR_CONTAINS(out, "glsl/x.glsl:0: warning: cannot tell the stage");
    CHECK(out && strstr(out, "y.glsl") == NULL);
    free(out);
}

static void test_too_many_toggles_are_capped(void) {
    /* 12 toggles: 2^9 combinations, the last three at their defaults */
    char path[512], frag[512];
    snprintf(frag, sizeof frag, "%s/t12.frag", g_tmp);
    FILE *f = fopen(frag, "w");
    CHECK_NE(f, NULL);
    if (!f) return;
    fputs("#version 330 core\nout vec4 c;\nvoid main() {\n    c = vec4(0.0);\n"
          "#if defined(T10) && !defined(T11)\n    c = 1;\n#endif\n}\n", f);
    fclose(f);
    snprintf(path, sizeof path, "%s/t12.glib", g_tmp);
    f = fopen(path, "w");
    CHECK_NE(f, NULL);
    if (!f) return;
    fputs("##OpenGL GLIB\nFragment t12.frag\n", f);
    for (int i = 0; i < 12; i++) fprintf(f, "Define T%d <%s>\n", i, i == 10 ? "true" : "false");
    fputs("Program Many\n", f);
    fclose(f);
    int rc = -1;
    validate_result res;
    const char *paths[] = { path };
    char *out = run_validate(paths, 1, shader_data("repo"), &rc, &res);
    CHECK_EQ(res.ncombinations, 512);
    CHECK_EQ(res.nwarnings, 1);
    CHECK_STR_CONTAINS(out, "t12.glib:15: warning: Program Many has 12 Define toggles");
    /* T10 stays on, T11 off: the error shows in every combination */
    CHECK_EQ(rc, 1);
    CHECK_STR_CONTAINS(out, "t12.frag:6: error: ");
    CHECK_STR_CONTAINS(out, "T10=1 T11=0] (all 512 combinations)");
    free(out);
}

static void test_validate_stage_without_text(void) {
    shader_src s;
    shader_src_desc d = { .path = shader_data("missing_inc.frag"), .stage = SHADER_FRAGMENT };
    CHECK(!shader_src_load(&d, &s));
    diag_list l = { 0 };
    CHECK(!validate_stage(&s, SHADER_FRAGMENT, &l));
    char *log = diag_list_format(&l, 0);
    diag_list_free(&l);
    CHECK_STR_CONTAINS(log, "missing_inc.frag:3: error: ");
    free(log);
    shader_src_free(&s);
}

/* packs/common's world.glsl and waves.glsl both declare uWaterLevel: each
 * may be included first (world then waves once failed with a redefinition). */
static void test_world_and_waves_in_either_order(void) {
    const char *orders[2] = { "world_then_waves.frag", "waves_then_world.frag" };
    for (int i = 0; i < 2; i++) {
        const char *paths[] = { shader_data(orders[i]) };
        int rc = -1;
        validate_result res;
        char *out = run_validate(paths, 1, TARN_SOURCE_DIR, &rc, &res);
        CHECK_MSG(rc == 0 && res.nerrors == 0, "%s: %s", orders[i], out ? out : "");
        free(out);
    }
}

static void write_tmp(const char *name, const char *text) {
    char path[512];
    snprintf(path, sizeof path, "%s/%s", g_tmp, name);
    FILE *f = fopen(path, "w");
    CHECK_NE(f, NULL);
    if (!f) return;
    fputs(text, f);
    fclose(f);
}

/* glman-era GLSL under glslang as under Mesa: an EXT_geometry_shader4
 * geometry shader (rewritten by shader_src) that passes gl_FrontColor on
 * validates clean, an error in one is on its line; writing a
 * fragment shader's input is glslang's error on its line, with tarn's note
 * after it, counted once. */
static void test_glman_era_glsl(void) {
    write_tmp("ext.vert", "#version 120\nvoid main() { gl_Position = gl_ModelViewMatrix * gl_Vertex; }\n");
    write_tmp("ext.geom", "#version 120\n#extension GL_EXT_geometry_shader4 : enable\nvarying out float gK;\n"
              "void main() {\n  for (int i = 0; i < gl_VerticesIn; i++) {\n    gK = 1.;\n"
              "    gl_FrontColor = gl_FrontColorIn[i];\n"
              "    gl_Position = gl_ProjectionMatrix * gl_PositionIn[i];\n    EmitVertex();\n  }\n}\n");
    /* the same with no #version (glman's 330 compatibility) and an error on line 6 */
    write_tmp("bad.geom", "#extension GL_EXT_geometry_shader4 : enable\nvarying out float gK;\n"
              "void main() {\n  for (int i = 0; i < gl_VerticesIn; i++) {\n    gl_FrontColor = gl_FrontColorIn[i];\n"
              "    gK = undefined_gk;\n    gl_Position = gl_PositionIn[i];\n    EmitVertex();\n  }\n}\n");
    write_tmp("ext.frag", "#version 120\nvarying float gK;\nvoid main() { gl_FragColor = vec4(gK); }\n");
    write_tmp("in.frag", "#version 120\nvarying float gK;\nvoid main() {\n  gK = 2.;\n  gl_FragColor = vec4(gK);\n}\n");
    write_tmp("ext.glib", "##OpenGL GLIB\nVertex ext.vert\nGeometry ext.geom\nFragment ext.frag\nProgram Ext\n"
              "QuadXY 0 1\nFragment in.frag\nProgram In\nQuadXY 0 1\n"
              "Geometry bad.geom\nFragment ext.frag\nProgram Bad\nQuadXY 0 1\n");
    char path[512];
    snprintf(path, sizeof path, "%s/ext.glib", g_tmp);
    const char *paths[] = { path };
    int rc = -1;
    validate_result res;
    char *out = run_validate(paths, 1, shader_data("repo"), &rc, &res);
    /* the write to an input is NVIDIA's leniency: rewritten (a local copy)
     * and validated with a warning that says so (issue #27) */
    CHECK_MSG(rc == 1 && res.nerrors == 1, "%s", out ? out : "");
    CHECK(out && !strstr(out, "ext.geom"));     /* gl_FrontColor written: glslang checks it as 4.00 */
    CHECK_STR_CONTAINS(out, "bad.geom:6: error: 'undefined_gk'");
    CHECK_STR_CONTAINS(out, "in.frag:4: warning: 'gK' is an input and the shader writes it");
    CHECK(out && !strstr(out, "in.frag:4: error"));
    free(out);
}

int main(void) {
    snprintf(g_tmp, sizeof g_tmp, "/tmp/tarn_test_validate_XXXXXX");
    if (!mkdtemp(g_tmp)) { perror("mkdtemp"); return 1; }
    RUN(test_good_compat_shader_validates);
    RUN(test_error_in_included_file_reports_that_file_and_line);
    RUN(test_error_after_include_reports_main_file_line);
    RUN(test_old_glsl_line_numbers);
    RUN(test_gstap_names_compile);
    RUN(test_toggle_combination_that_breaks_is_found);
    RUN(test_good_glib_passes);
    RUN(test_link_checks);
    RUN(test_missing_stage_file_is_reported_at_glib_line);
    RUN(test_no_paths_means_packs_and_scenes);
    RUN(test_stage_files_and_directories);
    RUN(test_too_many_toggles_are_capped);
    RUN(test_unnamed_glsl_with_main_is_reported);
    RUN(test_define_slider_values_are_validated);
    RUN(test_validate_stage_without_text);
    RUN(test_world_and_waves_in_either_order);
    RUN(test_glman_era_glsl);
    char cmd[320];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", g_tmp);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", g_tmp);
    return check_summary();
}
