/* Bad input through the renderer (render_load), one case each: the message
 * names the file and the line, nothing crashes, and what was on screen
 * stays there. The parsers' own tests (test_glib, test_shader_src,
 * test_unif, test_image, test_geom) check the many spellings of each
 * mistake; this file checks that each kind reaches the user through a
 * reload with the last good state kept.
 *
 * Every case starts from the same good scene (an OBJ covering the screen,
 * its left half the Program's uColor, its right half a texture), breaks
 * one thing, reloads, checks the message and the pixels, and puts the
 * thing back. */
#include <GL/gl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "support.h"
#include "gl_ctx.h"
#include "gl_support.h"
#include "render.h"
#include "unif.h"

#define W 32
#define H 32
#define TOL (1.5 / 255.0)

static float px[W * H * 4];
static render_target target;

static void write_bytes(const char *name, const void *data, size_t n) {
    FILE *f = fopen(scratch_path(name), "wb");
    if (!f) { perror(name); exit(1); }
    fwrite(data, 1, n, f);
    fclose(f);
}

static void remove_path(const char *name) {
    char cmd[700];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", scratch_path(name));
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", name);
}

static void le32(unsigned char *p, unsigned v) { p[0] = v & 255; p[1] = (v >> 8) & 255; p[2] = (v >> 16) & 255; p[3] = v >> 24; }
static void le16(unsigned char *p, unsigned v) { p[0] = v & 255; p[1] = (v >> 8) & 255; }

/* A 24-bit BMP header of w x h (as a file's first 54 bytes). */
static void bmp_header(unsigned char hdr[54], unsigned w, unsigned h, unsigned file_size) {
    memset(hdr, 0, 54);
    hdr[0] = 'B'; hdr[1] = 'M';
    le32(hdr + 2, file_size); le32(hdr + 10, 54); le32(hdr + 14, 40);
    le32(hdr + 18, w); le32(hdr + 22, h);
    le16(hdr + 26, 1); le16(hdr + 28, 24);
}

/* A 1x1 24-bit BMP of one colour. */
static void write_bmp(const char *name, int r, int g, int b) {
    unsigned char file[58];
    bmp_header(file, 1, 1, 58);
    file[54] = (unsigned char)b; file[55] = (unsigned char)g; file[56] = (unsigned char)r; file[57] = 0;
    write_bytes(name, file, sizeof file);
}

/* ---- the good scene ---- */

static const char *good_vert =
    "#version 330 compatibility\nout vec2 st;\n"
    "void main() { st = gl_MultiTexCoord0.st; gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; }\n";
static const char *good_frag =
    "#version 330 compatibility\n"
    "#include \"b_inc.glsl\"\n"
    "uniform sampler2D uTex;\n"
    "uniform vec4 uColor;\n"
    "in vec2 st;\n"
    "out vec4 c;\n"
    "void main() { c = st.x < 0.5 ? uColor * scale() : texture(uTex, vec2(0.5)); }\n";
static const char *good_inc = "float scale() { return 1.0; }\n";
/* two triangles over the whole screen, texture coordinates 0..1 */
static const char *good_obj =
    "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
#define PROGRAM_LINE 6
static const char *good_glib_fmt =
    "##OpenGL GLIB\n"
    "Ortho -1 1 -1 1\n"
    "Texture2D 5 b.bmp\n"
    "Vertex b.vert\n"
    "Fragment b.frag\n"
    "Program B uTex 5 uColor {0.25 0.5 0.75 1}%s\n"
    "Obj b.obj\n";

static void write_glib(const char *extra) {
    char text[1024];
    snprintf(text, sizeof text, good_glib_fmt, extra);
    scratch_write("b.glib", text);
}

static void write_good_scene(void) {
    scratch_write("b.vert", good_vert);
    scratch_write("b.frag", good_frag);
    scratch_write("b_inc.glsl", good_inc);
    scratch_write("b.obj", good_obj);
    write_bmp("b.bmp", 255, 128, 0);
    write_glib("");
}

static void draw(render *r) {
    render_frame(r, 0, target.fbo, W, H, NULL);
    render_target_read(&target, px);
}

static const float *at(int x, int y) { return px + ((size_t)y * W + x) * 4; }

/* The good scene's image: uColor on the left, the texel on the right. */
static bool shows_good(void) {
    const float *l = at(W / 4, H / 2), *r = at(3 * W / 4, H / 2);
    return fabs(l[0] - 0.25) <= TOL && fabs(l[1] - 0.5) <= TOL && fabs(l[2] - 0.75) <= TOL &&
           fabs(r[0] - 1.0) <= TOL && fabs(r[1] - 128 / 255.0) <= TOL && fabs(r[2] - 0.0) <= TOL;
}

static void print_pixels(void) {
    const float *l = at(W / 4, H / 2), *r = at(3 * W / 4, H / 2);
    fprintf(stderr, "  left %.3f %.3f %.3f, right %.3f %.3f %.3f\n", l[0], l[1], l[2], r[0], r[1], r[2]);
}

/* A renderer with the good scene loaded and on screen. */
static render *good_render(void) {
    write_good_scene();
    render *r = gl_test_load_scratch("b.glib");
    draw(r);
    CHECK_MSG(shows_good(), "the good scene is not on screen");
    return r;
}

/* "DIR/file:line:" (line < 0: "DIR/file" alone). */
static const char *where(const char *file, int line) {
    static char buf[4][700];
    static int i;
    i = (i + 1) % 4;
    if (line >= 0) snprintf(buf[i], sizeof buf[i], "%s:%d:", scratch_path(file), line);
    else snprintf(buf[i], sizeof buf[i], "%s", scratch_path(file));
    return buf[i];
}

/* Reloads after a mistake: an error, the messages hold every needle (NULL
 * ends them), the last good image stays. */
static void expect_kept(render *r, const char *what, ...) {
    bool ok = render_load(r, NULL);
    CHECK_MSG(!ok && render_has_errors(r), "%s: the reload reported no error", what);
    const char *msg = render_messages(r);
    va_list ap;
    va_start(ap, what);
    for (const char *needle; (needle = va_arg(ap, const char *)) != NULL;)
        CHECK_MSG(strstr(msg, needle) != NULL, "%s: expected \"%s\" in:\n%s", what, needle, msg);
    va_end(ap);
    draw(r);
    if (!shows_good()) print_pixels();
    CHECK_MSG(shows_good(), "%s: the last good image is gone", what);
    fprintf(stderr, "  %s:\n    %s", what, msg);
}

/* Puts the good scene back and checks it reloads cleanly. */
static void expect_recovers(render *r, const char *what) {
    write_good_scene();
    CHECK_MSG(render_load(r, NULL), "%s: the fixed scene does not load: %s", what, render_messages(r));
    draw(r);
    CHECK_MSG(shows_good(), "%s: the fixed scene is not on screen", what);
}

/* ---- shaders ---- */

static void test_missing_shader(void) {
    render *r = good_render();
    remove_path("b.frag");
    expect_kept(r, "missing shader", where("b.glib", 5), "b.frag", NULL);
    expect_recovers(r, "missing shader");
    render_destroy(r);
}

/* Unreadable: a directory where the file was (permissions do not stop
 * root, and tests may run as root), and, when not root, a file of mode 0. */
static void test_unreadable_shader(void) {
    render *r = good_render();
    remove_path("b.frag");
    mkdir(scratch_path("b.frag"), 0755);
    expect_kept(r, "shader is a directory", where("b.glib", 5), "b.frag", NULL);
    remove_path("b.frag");
    if (geteuid() != 0) {
        scratch_write("b.frag", good_frag);
        chmod(scratch_path("b.frag"), 0);
        expect_kept(r, "shader without read permission", where("b.glib", 5), "b.frag", NULL);
        chmod(scratch_path("b.frag"), 0644);
    }
    expect_recovers(r, "unreadable shader");
    render_destroy(r);
}

static void test_missing_include(void) {
    render *r = good_render();
    scratch_write("b_inc.glsl", "// helpers\n#include \"b_gone.glsl\"\nfloat scale() { return 1.0; }\n");
    expect_kept(r, "missing #include", where("b_inc.glsl", 2), "b_gone.glsl", NULL);
    remove_path("b_inc.glsl");
    expect_kept(r, "missing included file", where("b.frag", 2), "b_inc.glsl", NULL);
    remove_path("b_inc.glsl");
    mkdir(scratch_path("b_inc.glsl"), 0755);
    expect_kept(r, "#include of a directory", where("b.frag", 2), "b_inc.glsl", NULL);
    remove_path("b_inc.glsl");
    expect_recovers(r, "missing include");
    render_destroy(r);
}

static void test_include_cycle(void) {
    render *r = good_render();
    scratch_write("b_inc.glsl", "#include \"b_inc2.glsl\"\nfloat scale() { return 1.0; }\n");
    scratch_write("b_inc2.glsl", "// back again\n#include \"b_inc.glsl\"\n");
    expect_kept(r, "#include cycle", where("b_inc2.glsl", 2), "include cycle", NULL);
    scratch_write("b_inc.glsl", "#include \"b.frag\"\n");
    expect_kept(r, "#include of the stage file", where("b_inc.glsl", 1), "include cycle", NULL);
    expect_recovers(r, "include cycle");
    render_destroy(r);
}

static void test_compile_error(void) {
    render *r = good_render();
    scratch_write("b_inc.glsl", "float scale() {\n    return 1.0 +;\n}\n");
    expect_kept(r, "syntax error in an include", where("b_inc.glsl", 2), NULL);
    expect_recovers(r, "compile error");
    render_destroy(r);
}

/* A program with no stage at all, and one whose stages do not link. */
static void test_program_links_on_no_stage(void) {
    render *r = good_render();
    scratch_write("b.glib",
               "##OpenGL GLIB\nOrtho -1 1 -1 1\nTexture2D 5 b.bmp\n"
               "Vertex\nFragment\n"
               "Program B uTex 5 uColor {0.25 0.5 0.75 1}\nObj b.obj\n");
    bool ok = render_load(r, NULL);
    CHECK(!ok);
    CHECK_STR_CONTAINS(render_messages(r), "no shader stage");
    fprintf(stderr, "  no stage:\n    %s", render_messages(r));
    /* a Program line with no stage keeps that Program's last good build */
    draw(r);
    CHECK_MSG(shows_good(), "a program with no stage lost the last good program");
    expect_recovers(r, "no stage");

    /* each stage compiles, but the program does not link: a function
     * declared and called, defined in no stage */
    scratch_write("b.frag", "#version 330 compatibility\nfloat defined_nowhere(float x);\nout vec4 c;\n"
                         "void main() { c = vec4(defined_nowhere(1.)); }\n");
    expect_kept(r, "link error", where("b.glib", PROGRAM_LINE), "link", NULL);
    expect_recovers(r, "link error");
    render_destroy(r);
}

/* ---- textures ---- */

static void test_missing_texture(void) {
    render *r = good_render();
    remove_path("b.bmp");
    expect_kept(r, "missing texture", where("b.glib", 3), "b.bmp", NULL);
    mkdir(scratch_path("b.bmp"), 0755);
    expect_kept(r, "texture is a directory", where("b.glib", 3), "b.bmp", NULL);
    remove_path("b.bmp");
    expect_recovers(r, "missing texture");
    render_destroy(r);
}

static void test_texture_unsupported_format(void) {
    render *r = good_render();
    scratch_write("b.bmp", "this is not a bitmap\n");
    expect_kept(r, "text under an image name", where("b.glib", 3), "b.bmp", NULL);
    /* an extension no image library knows */
    scratch_write("b.qqq", "P?\n");
    write_glib("");
    char text[1024];
    snprintf(text, sizeof text, good_glib_fmt, "");
    char *bmp = strstr(text, "b.bmp");
    if (bmp) memcpy(bmp, "b.qqq", 5);
    scratch_write("b.glib", text);
    expect_kept(r, "unknown image format", where("b.glib", 3), "b.qqq", NULL);
    expect_recovers(r, "unsupported format");
    render_destroy(r);
}

static void test_texture_absurd_size(void) {
    render *r = good_render();
    unsigned char hdr[54];
    bmp_header(hdr, 100000, 100000, 54);
    write_bytes("b.bmp", hdr, sizeof hdr);
    expect_kept(r, "texture of 100000 x 100000", where("b.glib", 3), "b.bmp", "size", NULL);
    bmp_header(hdr, 20000, 1, 54 + 60000);
    write_bytes("b.bmp", hdr, sizeof hdr);
    expect_kept(r, "texture wider than any GL allows", where("b.glib", 3), "b.bmp", NULL);
    bmp_header(hdr, 16384, 16384, 54);   /* within the limits, but no pixels behind the header */
    write_bytes("b.bmp", hdr, sizeof hdr);
    expect_kept(r, "a 16384 x 16384 header with no pixels", where("b.glib", 3), "b.bmp", NULL);
    expect_recovers(r, "absurd size");
    render_destroy(r);
}

/* ---- meshes ---- */

static void test_missing_obj(void) {
    render *r = good_render();
    remove_path("b.obj");
    expect_kept(r, "missing OBJ", where("b.glib", 7), "b.obj", NULL);
    mkdir(scratch_path("b.obj"), 0755);
    expect_kept(r, "OBJ is a directory", where("b.glib", 7), "b.obj", NULL);
    remove_path("b.obj");
    expect_recovers(r, "missing OBJ");
    render_destroy(r);
}

static void test_obj_bad_indices(void) {
    render *r = good_render();
    scratch_write("b.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nf 1 2 3\nf 1 3 9\n");
    expect_kept(r, "OBJ index out of range", where("b.glib", 7), where("b.obj", 5), NULL);
    scratch_write("b.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nf 0 1 2\n");
    expect_kept(r, "OBJ index 0", where("b.glib", 7), where("b.obj", 4), NULL);
    scratch_write("b.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nvt 0 0\nf 1/1 2/7 3/1\n");
    expect_kept(r, "OBJ texture index out of range", where("b.glib", 7), where("b.obj", 5), NULL);
    expect_recovers(r, "OBJ bad indices");
    render_destroy(r);
}

/* ---- glib ---- */

static void test_glib_include_missing_and_cycle(void) {
    render *r = good_render();
    write_glib("\nInclude b_more.glib");
    expect_kept(r, "missing glib Include", where("b.glib", 7), "b_more.glib", NULL);
    scratch_write("b_more.glib", "Include b.glib\n");
    expect_kept(r, "glib Include cycle", where("b_more.glib", 1), NULL);
    remove_path("b_more.glib");
    expect_recovers(r, "glib include");
    render_destroy(r);
}

/* ---- uniforms ---- */

/* A uniform the shader does not have (or optimises out) is a warning: the
 * rest of the edit applies, and the message names the glib line. */
static void test_uniform_absent_or_optimised_out(void) {
    render *r = good_render();
    write_glib(" uGhost 0.5");
    CHECK_MSG(render_load(r, NULL), "%s", render_messages(r));
    CHECK_STR_CONTAINS(render_messages(r), where("b.glib", PROGRAM_LINE));
    CHECK_STR_CONTAINS(render_messages(r), "uGhost");
    fprintf(stderr, "  absent uniform:\n    %s", render_messages(r));
    draw(r);
    CHECK(shows_good());
    /* declared but unused: the linker drops it */
    scratch_write("b.frag", "#version 330 compatibility\n#include \"b_inc.glsl\"\nuniform sampler2D uTex;\n"
                         "uniform vec4 uColor;\nuniform float uUnused;\nin vec2 st;\nout vec4 c;\n"
                         "void main() { c = st.x < 0.5 ? uColor * scale() : texture(uTex, vec2(0.5)); }\n");
    write_glib(" uUnused <0. 0.5 1.>");
    CHECK_MSG(render_load(r, NULL), "%s", render_messages(r));
    CHECK_STR_CONTAINS(render_messages(r), where("b.glib", PROGRAM_LINE));
    CHECK_STR_CONTAINS(render_messages(r), "uUnused");
    draw(r);
    CHECK(shows_good());
    expect_recovers(r, "absent uniform");
    render_destroy(r);
}

/* A uniform of another type than the shader declares: a warning naming the
 * glib line and both types; that uniform is not uploaded (uColor keeps GL's
 * default, 0, so the left half goes black: the one visible change). */
static void test_uniform_of_another_type(void) {
    render *r = good_render();
    write_glib(" uExtra 1");
    scratch_write("b.frag", "#version 330 compatibility\n#include \"b_inc.glsl\"\nuniform sampler2D uTex;\n"
                         "uniform vec4 uColor;\nuniform vec3 uExtra;\nin vec2 st;\nout vec4 c;\n"
                         "void main() { c = st.x < 0.5 ? uColor * scale() + vec4(uExtra, 0.) * 0. : texture(uTex, vec2(0.5)); }\n");
    char text[1024];
    snprintf(text, sizeof text, good_glib_fmt, "");
    char *col = strstr(text, "uColor {0.25 0.5 0.75 1}");
    if (col) memcpy(col, "uColor <0. 0.25 1.>     ", 24);   /* a slider for a vec4 */
    scratch_write("b.glib", text);
    bool ok = render_load(r, NULL);
    const char *msg = render_messages(r);
    fprintf(stderr, "  uniform of another type:\n    %s", msg);
    CHECK_MSG(ok, "%s", msg);
    CHECK_STR_CONTAINS(msg, where("b.glib", PROGRAM_LINE));
    CHECK_STR_CONTAINS(msg, "uColor");
    CHECK_STR_CONTAINS(msg, "vec4");
    draw(r);
    CHECK(!isnan(at(0, 0)[0]));
    expect_recovers(r, "uniform of another type");
    render_destroy(r);
}

static void test_slider_range_bad(void) {
    render *r = good_render();
    write_glib(" uS <1. 0.5 0.>");
    expect_kept(r, "slider min > max", where("b.glib", PROGRAM_LINE), "uS", NULL);
    write_glib(" uS <0. nan 1.>");
    expect_kept(r, "slider default NaN", where("b.glib", PROGRAM_LINE), "uS", NULL);
    write_glib(" uS <0. 0.5 1e999>");
    expect_kept(r, "slider max overflows", where("b.glib", PROGRAM_LINE), "uS", NULL);
    expect_recovers(r, "slider range");
    render_destroy(r);
}

/* ---- presets ---- */

static void test_preset_corrupt_or_old(void) {
    render *r = good_render();
    int n = 0;
    unif_set *sets = render_uniforms(r, &n);
    char err[2048];
    CHECK(unif_preset_save(sets, n, scratch_path("b.preset"), err, sizeof err));

    scratch_write("b.preset", "tarn-preset 1\nB uColor 4 0.1 0.2\n");
    sets = render_uniforms(r, &n);
    CHECK(!unif_preset_load(sets, n, scratch_path("b.preset"), err, sizeof err));
    CHECK_STR_CONTAINS(err, where("b.preset", 2));
    fprintf(stderr, "  corrupt preset: %s\n", err);
    draw(r);
    CHECK_MSG(shows_good(), "a corrupt preset changed the image");

    scratch_write("b.preset", "tarn-preset 0\nB uColor 4 0.1 0.2 0.3 1\n");
    CHECK(!unif_preset_load(sets, n, scratch_path("b.preset"), err, sizeof err));
    CHECK_STR_CONTAINS(err, where("b.preset", 1));
    CHECK_STR_CONTAINS(err, "version");
    fprintf(stderr, "  old preset: %s\n", err);
    draw(r);
    CHECK_MSG(shows_good(), "an old preset changed the image");

    write_bytes("b.preset", "\x7f" "ELF\x02\x01\x01\0\0\0", 10);
    CHECK(!unif_preset_load(sets, n, scratch_path("b.preset"), err, sizeof err));
    CHECK_STR_CONTAINS(err, "b.preset");
    draw(r);
    CHECK_MSG(shows_good(), "a binary preset changed the image");

    remove_path("b.preset");
    CHECK(!unif_preset_load(sets, n, scratch_path("b.preset"), err, sizeof err));
    CHECK_STR_CONTAINS(err, "b.preset");
    draw(r);
    CHECK(shows_good());
    render_destroy(r);
}

/* Nothing above left GL in an error state. */
static void test_no_gl_errors_after_all_that(void) {
    GLenum e = glGetError();
    CHECK_MSG(e == GL_NO_ERROR, "GL error 0x%x", e);
}

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    fprintf(stderr, "context: %s\n", gl_ctx_describe(ctx));
    if (!scratch_create("bad")) return 1;
    if (!render_target_create(&target, W, H, false)) { fprintf(stderr, "no target\n"); return 1; }
    RUN(test_missing_shader);
    RUN(test_unreadable_shader);
    RUN(test_missing_include);
    RUN(test_include_cycle);
    RUN(test_compile_error);
    RUN(test_program_links_on_no_stage);
    RUN(test_missing_texture);
    RUN(test_texture_unsupported_format);
    RUN(test_texture_absurd_size);
    RUN(test_missing_obj);
    RUN(test_obj_bad_indices);
    RUN(test_glib_include_missing_and_cycle);
    RUN(test_uniform_absent_or_optimised_out);
    RUN(test_uniform_of_another_type);
    RUN(test_slider_range_bad);
    RUN(test_preset_corrupt_or_old);
    RUN(test_no_gl_errors_after_all_that);
    render_target_destroy(&target);
    gl_ctx_destroy(ctx);
    scratch_remove();
    return check_summary();
}
