/* GL tests on the headless context (Mesa llvmpipe through EGL): small
 * scenes whose pixel values follow from the scene itself (a uniform colour,
 * a transform, a texture, Timer), and the reload rules: a shader error keeps
 * the previous image, a fixed shader applies, slider values survive. */
#include <GL/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "file_cache.h"
#include "support.h"
#include "gl_ctx.h"
#include "gl_support.h"
#include "render.h"
#include "scene.h"
#include "watch.h"
#include <time.h>

#define W 64
#define H 64
#define TOL (1.5 / 255.0)   /* RGBA8 target: half a step of rounding, plus slack */

static gl_ctx *ctx;
static float px[W * H * 4];

/* Renders r at time t into a fresh W x H target and reads it back. */
static void draw(render *r, double t) {
    render_target tg;
    if (!render_target_create(&tg, W, H, false)) { fprintf(stderr, "no target\n"); exit(1); }
    render_frame(r, t, tg.fbo, W, H, NULL);
    render_target_read(&tg, px);
    render_target_destroy(&tg);
}

/* pixel (x, y), y = 0 the top row */
static const float *at(int x, int y) { return px + ((size_t)y * W + x) * 4; }

#define CHECK_RGB(p, r_, g_, b_) do { const float *q_ = (p); \
    CHECK_NEAR(q_[0], r_, TOL); CHECK_NEAR(q_[1], g_, TOL); CHECK_NEAR(q_[2], b_, TOL); } while (0)

static void test_uniform_colour_fills_the_screen(void) {
    scratch_write("flat.vert", flat_vert);
    scratch_write("flat.frag", flat_frag);
    scratch_write("flat.glib",
               "##OpenGL GLIB\nOrtho -1 1 -1 1\nBackground 0 0 0\n"
               "Vertex flat.vert\nFragment flat.frag\n"
               "Program Flat uColor {0.2 0.4 0.6 1.}\nQuadXY 0 1 1 1\n");
    render *r = gl_test_load_scratch("flat.glib");
    draw(r, 0);
    CHECK_RGB(at(0, 0), 0.2, 0.4, 0.6);
    CHECK_RGB(at(W / 2, H / 2), 0.2, 0.4, 0.6);
    CHECK_RGB(at(W - 1, H - 1), 0.2, 0.4, 0.6);
    render_destroy(r);
}

/* Translate 0.5 0 0, Scale 0.25: the quad covers x in [0.25, 0.75] of NDC,
 * i.e. pixels 40..55 of 64, and y in [-0.25, 0.25], rows 24..39. */
static void test_transforms_place_geometry(void) {
    scratch_write("xf.glib",
               "##OpenGL GLIB\nOrtho -1 1 -1 1\nBackground 0 0 1\n"
               "Vertex flat.vert\nFragment flat.frag\n"
               "Program Flat uColor {1 0 0 1}\n"
               "PushMatrix\nTranslate 0.5 0 0\nScale 0.25\nQuadXY 0 1 1 1\nPopMatrix\n");
    render *r = gl_test_load_scratch("xf.glib");
    draw(r, 0);
    CHECK_RGB(at(48, 32), 1, 0, 0);        /* inside */
    CHECK_RGB(at(41, 25), 1, 0, 0);
    CHECK_RGB(at(54, 38), 1, 0, 0);
    CHECK_RGB(at(38, 32), 0, 0, 1);        /* left of it: background */
    CHECK_RGB(at(57, 32), 0, 0, 1);        /* right of it */
    CHECK_RGB(at(48, 21), 0, 0, 1);        /* above it */
    CHECK_RGB(at(16, 32), 0, 0, 1);
    render_destroy(r);
}

/* Timer: a 0..1 sawtooth of period `Timer secs`: at t = 12.5 with a 10 s
 * period it is 0.25. */
static void test_timer_is_a_sawtooth(void) {
    scratch_write("timer.frag",
               "#version 330 compatibility\nuniform float Timer;\nout vec4 c;\n"
               "void main() { c = vec4(Timer, 0., 0., 1.); }\n");
    scratch_write("timer.glib",
               "##OpenGL GLIB\nOrtho -1 1 -1 1\nTimer 10\nVertex flat.vert\nFragment timer.frag\n"
               "Program T\nQuadXY 0 1 1 1\n");
    render *r = gl_test_load_scratch("timer.glib");
    draw(r, 12.5);
    CHECK_NEAR(at(10, 10)[0], 0.25, TOL);
    draw(r, 7.0);
    CHECK_NEAR(at(10, 10)[0], 0.70, TOL);
    render_destroy(r);
}

/* render_reads_clock: a glman scene reads the clock when a program uses
 * Timer (declared but unused is not read: the picture does not move) in a
 * draw of every frame (not only in a RenderToTextureOnce block), a world
 * scene always (its water moves); a rebuild decides again. Each
 * answer is checked against the pixels: two times give two pictures
 * exactly when the clock is read. */
static bool pictures_differ(render *r, double t0, double t1) {
    draw(r, t0);
    float a = at(10, 10)[0];
    draw(r, t1);
    return fabsf(a - at(10, 10)[0]) > TOL;
}

static void test_reads_clock(void) {
    scratch_write("still.frag", "#version 330 compatibility\nuniform float Timer;\nout vec4 c;\n"
                                "void main() { c = vec4(0.5, 0., 0., 1.); }\n");
    scratch_write("clock.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex flat.vert\nFragment still.frag\n"
                                "Program T\nQuadXY 0 1 1 1\n");
    render *r = gl_test_load_scratch("clock.glib");
    CHECK_MSG(!render_reads_clock(r), "Timer declared, never used: the picture is still");
    CHECK(!pictures_differ(r, 1.0, 3.0));
    scratch_write("still.frag", "#version 330 compatibility\nuniform float Timer;\nout vec4 c;\n"
                                "void main() { c = vec4(Timer, 0., 0., 1.); }\n");
    CHECK_MSG(render_rebuild_programs(r), "%s", render_messages(r));
    CHECK_MSG(render_reads_clock(r), "Timer used after a rebuild: the picture moves");
    CHECK(pictures_differ(r, 1.0, 3.0));
    render_destroy(r);

    /* Timer read only in a RenderToTextureOnce block: fixed in its target
     * at the load's first frame; the frames after draw without it */
    scratch_write("show.frag", "#version 330 compatibility\nuniform sampler2D uT;\nout vec4 c;\n"
                               "void main() { c = texture(uT, vec2(0.5)); }\n");   /* the target's middle, which the quad covers */
    scratch_write("once.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nTimer 10\nTexture2D 6 4 4 float\n"
                               "RenderToTextureOnce 6\nClear\nVertex flat.vert\nFragment still.frag\nProgram T\n"
                               "QuadXY 0 1 1 1\nRenderToTexture\nFragment show.frag\nProgram S uT 6\n"
                               "QuadXY 0 1 1 1\n");
    r = gl_test_load_scratch("once.glib");
    CHECK_MSG(!render_reads_clock(r), "Timer read in a RenderToTextureOnce block alone: the frames after are still");
    CHECK(!pictures_differ(r, 1.0, 3.0));
    CHECK_NEAR(at(10, 10)[0], 0.1, TOL);   /* the block ran, at the first frame's time (Timer 10: t / 10) */
    render_destroy(r);
    /* the same block's program bound again after it, for a frame's draw: read */
    scratch_write("again.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nTimer 10\nTexture2D 6 4 4 float\n"
                                "RenderToTextureOnce 6\nClear\nVertex flat.vert\nFragment still.frag\nProgram T\n"
                                "QuadXY 0 1 1 1\nRenderToTexture\nProgram T\nQuadXY 0 1 1 1\n");
    r = gl_test_load_scratch("again.glib");
    CHECK_MSG(render_reads_clock(r), "the Timer program draws every frame too");
    CHECK(pictures_differ(r, 1.0, 3.0));
    render_destroy(r);

    render *lake = render_create(&(render_desc){ .pack = "basic" });
    CHECK_MSG(render_load(lake, TARN_SOURCE_DIR "/scenes/lake.glib"), "%s", render_messages(lake));
    CHECK_MSG(render_reads_clock(lake), "the lake's water moves");
    render_destroy(lake);
}

/* GSTAP maps aVertex and uModelViewProjectionMatrix to the built-ins. */
static void test_gstap_names_work(void) {
    scratch_write("gstap.vert",
               "#version 330 compatibility\n"
               "void main() { gl_Position = uModelViewProjectionMatrix * aVertex; }\n");
    scratch_write("gstap.glib",
               "##OpenGL GLIB\nGSTAP\nOrtho -1 1 -1 1\nVertex gstap.vert\nFragment flat.frag\n"
               "Program G uColor {0 1 0 1}\nQuadXY 0 1 1 1\n");
    render *r = gl_test_load_scratch("gstap.glib");
    draw(r, 0);
    CHECK_RGB(at(32, 32), 0, 1, 0);
    render_destroy(r);
}

/* A 2x2 BMP (24-bit, bottom-up rows as BMP stores them) mapped on the
 * screen: the image's top-left texel shows at the screen's top left. */
static void write_bmp_2x2(const char *name) {
    /* top row: red, green; bottom row: blue, white (as the image is seen) */
    unsigned char file[70] = { 'B', 'M', 70, 0, 0, 0, 0, 0, 0, 0, 54, 0, 0, 0,
        40, 0, 0, 0, 2, 0, 0, 0, 2, 0, 0, 0, 1, 0, 24, 0, 0, 0, 0, 0, 16, 0, 0, 0,
        0x13, 0x0b, 0, 0, 0x13, 0x0b, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
    const unsigned char rows[16] = {
        255, 0, 0, 255, 255, 255, 0, 0,      /* bottom row (BGR): blue, white, pad */
        0, 0, 255, 0, 255, 0, 0, 0 };        /* top row: red, green, pad */
    memcpy(file + 54, rows, 16);
    FILE *f = fopen(scratch_path(name), "wb");
    if (!f) exit(1);
    fwrite(file, 1, sizeof file, f);
    fclose(f);
}

static void test_texture_from_bmp(void) {
    write_bmp_2x2("quad.bmp");
    scratch_write("tex.vert",
               "#version 330 compatibility\nout vec2 st;\n"
               "void main() { st = gl_MultiTexCoord0.st; gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; }\n");
    scratch_write("tex.frag",
               "#version 330 compatibility\nuniform sampler2D uTex;\nin vec2 st;\nout vec4 c;\n"
               "void main() { c = texelFetch(uTex, ivec2(st * 2.0), 0); }\n");
    scratch_write("tex.glib",
               "##OpenGL GLIB\nOrtho -1 1 -1 1\nTexture2D 5 quad.bmp\nVertex tex.vert\nFragment tex.frag\n"
               "Program Tex uTex 5\nQuadXY 0 1 1 1\n");
    render *r = gl_test_load_scratch("tex.glib");
    draw(r, 0);
    CHECK_RGB(at(8, 8), 1, 0, 0);            /* top left: red */
    CHECK_RGB(at(56, 8), 0, 1, 0);           /* top right: green */
    CHECK_RGB(at(8, 56), 0, 0, 1);           /* bottom left: blue */
    CHECK_RGB(at(56, 56), 1, 1, 1);          /* bottom right: white */
    render_destroy(r);
}

/* Pass 1 draws a colour into texture unit 6; pass 2 shows that texture. */
static void test_render_to_texture(void) {
    scratch_write("show.frag",
               "#version 330 compatibility\nuniform sampler2D uTarget;\nin vec2 st;\nout vec4 c;\n"
               "void main() { c = texture(uTarget, st) * vec4(0.5, 0.5, 0.5, 1.); }\n");
    scratch_write("rtt.glib",
               "##OpenGL GLIB\nOrtho -1 1 -1 1\nTexture2D 6 32 32\n"
               "RenderToTexture 6\nBackground 0 0 0\nClear\n"
               "Vertex flat.vert\nFragment flat.frag\nProgram Fill uColor {0.8 0.6 0.4 1}\nQuadXY 0 1 1 1\n"
               "RenderToTexture\n"
               "Vertex tex.vert\nFragment show.frag\nProgram Show uTarget 6\nQuadXY 0 1 1 1\n");
    render *r = gl_test_load_scratch("rtt.glib");
    draw(r, 0);
    CHECK_RGB(at(32, 32), 0.4, 0.3, 0.2);
    /* the panel's per-pass times name the pass by its glib line and units */
    char passes[512];
    render_gpu_ms(r, true);   /* wait for the frame's timer queries */
    render_pass_summary(r, passes, sizeof passes);
    CHECK_STR_CONTAINS(passes, "pass:4 6 ");
    CHECK_STR_CONTAINS(passes, "screen:11 ");   /* the RenderToTexture that ends it */
    CHECK_STR_CONTAINS(passes, " ms");
    render_destroy(r);
}

/* A shader error keeps the last good program (and so the image) and names
 * the file and line; fixing it applies the change. */
static void test_shader_error_keeps_last_good_then_fix_applies(void) {
    scratch_write("edit.frag", "#version 330 compatibility\nout vec4 c;\nvoid main() { c = vec4(0., 1., 0., 1.); }\n");
    scratch_write("edit.glib",
               "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex flat.vert\nFragment edit.frag\nProgram E\nQuadXY 0 1 1 1\n");
    render *r = gl_test_load_scratch("edit.glib");
    draw(r, 0);
    CHECK_RGB(at(32, 32), 0, 1, 0);

    scratch_write("edit.frag", "#version 330 compatibility\nout vec4 c;\n\nvoid main() { c = vec4(1., 0., 0., 1.) + nope; }\n");
    CHECK(!render_load(r, NULL));
    CHECK(render_has_errors(r));
    char want[600];
    snprintf(want, sizeof want, "%s:4:", scratch_path("edit.frag"));
    CHECK_STR_CONTAINS(render_messages(r), want);
    draw(r, 0);
    CHECK_RGB(at(32, 32), 0, 1, 0);           /* still the last good green */

    scratch_write("edit.frag", "#version 330 compatibility\nout vec4 c;\nvoid main() { c = vec4(0., 0., 1., 1.); }\n");
    CHECK_MSG(render_load(r, NULL), "%s", render_messages(r));
    CHECK(!render_has_errors(r));
    draw(r, 0);
    CHECK_RGB(at(32, 32), 0, 0, 1);           /* the fix applied */
    render_destroy(r);
}

/* An error in a file two programs include is one message, not one per
 * program, and it is an error diagnostic with its file and line. */
static void test_included_error_reported_once(void) {
    scratch_write("inc_bad.glsl", "vec4 shade() { return vec4(1.0) + nope; }\n");
    scratch_write("inc.frag", "#version 330 compatibility\n#include \"inc_bad.glsl\"\nout vec4 c;\n"
                              "void main() { c = shade(); }\n");
    scratch_write("inc.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex flat.vert\nFragment inc.frag\n"
                              "Program A\nQuadXY 0 1 1 1\nProgram B\nQuadXY 0 0.5 1 1\n");
    render *r = render_create(NULL);
    CHECK(!render_load(r, scratch_path("inc.glib")));
    /* the compiler's first message for the line, as both programs got it */
    char want[600];
    snprintf(want, sizeof want, "%s:1: error:", scratch_path("inc_bad.glsl"));
    const char *m = render_messages(r), *first = strstr(m, want);
    CHECK_MSG(first, "%s", m);
    if (first) {
        char line[800];
        snprintf(line, sizeof line, "%.*s", (int)strcspn(first, "\n"), first);
        const char *again = strstr(first + strlen(line), line);
        CHECK_MSG(!again, "printed twice: %s", line);
    }
    const diag_list *dl = render_diags(r);
    bool found = false;
    for (int i = 0; i < dl->n; i++)
        found |= dl->d[i].severity == DIAG_ERROR && dl->d[i].line == 1 &&
                 strcmp(dl->d[i].file, scratch_path("inc_bad.glsl")) == 0;
    CHECK_MSG(found, "%s", m);
    render_destroy(r);
}

/* A glib with an error keeps the whole last good scene. */
static void test_glib_error_keeps_last_good_scene(void) {
    scratch_write("g.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex flat.vert\nFragment flat.frag\n"
                         "Program F uColor {1 1 0 1}\nQuadXY 0 1 1 1\n");
    render *r = gl_test_load_scratch("g.glib");
    scratch_write("g.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex flat.vert\nFragment flat.frag\n"
                         "Program F uColor {1 1 0 1\nQuadXY 0 1 1 1\n");
    CHECK(!render_load(r, NULL));
    CHECK_STR_CONTAINS(render_messages(r), "g.glib:5:");
    draw(r, 0);
    CHECK_RGB(at(32, 32), 1, 1, 0);
    render_destroy(r);
}

/* Slider values survive a reload; a changed default resets that uniform. */
static void test_slider_values_survive_reload(void) {
    scratch_write("s.frag", "#version 330 compatibility\nuniform float uGrey;\nuniform float uBlue;\nout vec4 c;\n"
                         "void main() { c = vec4(uGrey, uGrey, uBlue, 1.); }\n");
    scratch_write("s.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex flat.vert\nFragment s.frag\n"
                         "Program S uGrey <0. 0.2 1.> uBlue <0. 0.1 1.>\nQuadXY 0 1 1 1\n");
    render *r = gl_test_load_scratch("s.glib");
    unif_entry *grey = gl_test_uniform(r, "S", "uGrey"), *blue = gl_test_uniform(r, "S", "uBlue");
    CHECK(grey && blue);
    if (!grey || !blue) { render_destroy(r); return; }
    grey->value[0] = 0.6f;     /* what dragging the slider does */
    blue->value[0] = 0.8f;
    draw(r, 0);
    CHECK_RGB(at(32, 32), 0.6, 0.6, 0.8);
    /* the glib changes uBlue's default only */
    scratch_write("s.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex flat.vert\nFragment s.frag\n"
                         "Program S uGrey <0. 0.2 1.> uBlue <0. 0.3 1.>\nQuadXY 0 1 1 1\n");
    CHECK_MSG(render_load(r, NULL), "%s", render_messages(r));
    grey = gl_test_uniform(r, "S", "uGrey");
    blue = gl_test_uniform(r, "S", "uBlue");
    CHECK(grey && fabsf(grey->value[0] - 0.6f) < 1e-6f);
    CHECK(blue && fabsf(blue->value[0] - 0.3f) < 1e-6f);
    draw(r, 0);
    CHECK_RGB(at(32, 32), 0.6, 0.6, 0.3);
    float got[1];
    CHECK(render_read_uniform(r, "S", "uGrey", got, 1) && fabsf(got[0] - 0.6f) < 1e-6f);
    render_destroy(r);
}

/* A Define toggle compiles the shader with or without the #define, from
 * the sources in memory: it reads no file (issue #28). */
static void test_define_toggle_recompiles(void) {
    scratch_write("d.frag", "#version 330 compatibility\nout vec4 c;\nvoid main() {\n#ifdef RED\n"
                         "c = vec4(1., 0., 0., 1.);\n#else\nc = vec4(0., 0., 1., 1.);\n#endif\n}\n");
    scratch_write("d.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex flat.vert\nFragment d.frag\n"
                         "Define RED <true>\nProgram D\nQuadXY 0 1 1 1\n");
    /* saved a while ago: the cache may answer for them (file_cache.h) */
    CHECK(scratch_age("d.frag", 5) && scratch_age("d.glib", 5) && scratch_age("flat.vert", 5));
    file_cache *files = file_cache_create();
    render *r = render_create(&(render_desc){ .files = files });
    CHECK_MSG(render_load(r, scratch_path("d.glib")), "%s", render_messages(r));
    file_cache_counts loaded = file_cache_counts_of(files);
    CHECK_EQ(loaded.reads, 3);   /* the glib and two stages, each once */
    draw(r, 0);
    CHECK_RGB(at(32, 32), 1, 0, 0);
    unif_entry *red = gl_test_uniform(r, "D", "RED");
    CHECK(red && red->is_define);
    if (red) {
        red->value[0] = 0;    /* unticking the checkbox */
        CHECK(render_rebuild_programs(r));
        draw(r, 0);
        CHECK_RGB(at(32, 32), 0, 0, 1);
    }
    file_cache_counts rebuilt = file_cache_counts_of(files);
    CHECK_EQ(rebuilt.reads, loaded.reads);
    CHECK_EQ(rebuilt.hits, loaded.hits + 2);   /* both stages from memory */
    render_destroy(r);
    file_cache_destroy(files);
}

/* The built-in noise: each channel an octave centred on 0.5. */
static void test_noise_texture_is_centred(void) {
    scratch_write("n.frag", "#version 330 compatibility\nuniform sampler2D Noise2;\nin vec2 st;\nout vec4 c;\n"
                         "void main() { c = texture(Noise2, st); }\n");
    scratch_write("n.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nNoise2D 64\nVertex tex.vert\nFragment n.frag\n"
                         "Program N Noise2 2\nQuadXY 0 1 1 1\n");
    render *r = gl_test_load_scratch("n.glib");
    draw(r, 0);
    double mean[4] = {0};
    for (int i = 0; i < W * H; i++)
        for (int k = 0; k < 4; k++) mean[k] += px[i * 4 + k] / (W * H);
    for (int k = 0; k < 4; k++) CHECK_NEAR(mean[k], 0.5, 0.05);
    render_destroy(r);
}

/* Every file the scene reads is a dependency the watcher must watch. */
static void test_deps_list_every_file(void) {
    scratch_write("inc.glsl", "vec4 tint() { return vec4(0.5); }\n");
    scratch_write("inc.frag", "#version 330 compatibility\n#include \"inc.glsl\"\nout vec4 c;\nvoid main() { c = tint(); }\n");
    scratch_write("sub.glib", "Vertex flat.vert\nFragment inc.frag\n");
    scratch_write("deps.glib", "##OpenGL GLIB\nInclude sub.glib\nTexture2D 5 quad.bmp\nProgram I\nQuadXY 0 1 1 1\n");
    render *r = gl_test_load_scratch("deps.glib");
    const char *const *deps;
    int n = render_deps(r, &deps);
    const char *want[] = { "deps.glib", "sub.glib", "flat.vert", "inc.frag", "inc.glsl", "quad.bmp" };
    for (size_t w = 0; w < sizeof want / sizeof *want; w++) {
        bool found = false;
        for (int i = 0; i < n; i++)
            if (strstr(deps[i], want[w]) && strcmp(deps[i] + strlen(deps[i]) - strlen(want[w]), want[w]) == 0) found = true;
        CHECK_MSG(found, "%s is not among the %d dependencies", want[w], n);
    }
    render_destroy(r);
}

/* A 1x1 24-bit BMP of one colour. */
static void write_bmp_1x1(const char *name, unsigned char r_, unsigned char g_, unsigned char b_) {
    unsigned char file[58] = { 'B', 'M', 58, 0, 0, 0, 0, 0, 0, 0, 54, 0, 0, 0,
        40, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 24, 0, 0, 0, 0, 0, 4, 0, 0, 0,
        0x13, 0x0b, 0, 0, 0x13, 0x0b, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
    file[54] = b_; file[55] = g_; file[56] = r_;
    FILE *f = fopen(scratch_path(name), "wb");
    if (!f) exit(1);
    fwrite(file, 1, sizeof file, f);
    fclose(f);
}

/* CubeMap: the face a direction looks at is the file given for it. */
static void test_cube_map_faces(void) {
    const char *faces[6] = { "px.bmp", "nx.bmp", "py.bmp", "ny.bmp", "pz.bmp", "nz.bmp" };
    const unsigned char col[6][3] = { {255,0,0}, {0,255,0}, {0,0,255}, {255,255,0}, {0,255,255}, {255,0,255} };
    for (int i = 0; i < 6; i++) write_bmp_1x1(faces[i], col[i][0], col[i][1], col[i][2]);
    scratch_write("cube.frag", "#version 330 compatibility\nuniform samplerCube uSky;\nuniform vec3 uDir;\nout vec4 c;\n"
                            "void main() { c = texture(uSky, uDir); }\n");
    scratch_write("cube.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nCubeMap 7 px.bmp nx.bmp py.bmp ny.bmp pz.bmp nz.bmp\n"
                            "Vertex flat.vert\nFragment cube.frag\nProgram C uSky 7 uDir [0 0 1]\nQuadXY 0 1 1 1\n");
    render *r = gl_test_load_scratch("cube.glib");
    int n;
    unif_set *sets = render_uniforms(r, &n);
    unif_entry *dir_e = n ? unif_find(&sets[0], "uDir") : NULL;
    CHECK_NE(dir_e, NULL);
    for (int f = 0; dir_e && f < 6; f++) {
        float d[3] = {0, 0, 0};
        d[f / 2] = (f % 2) ? -1.0f : 1.0f;
        memcpy(dir_e->value, d, sizeof d);
        draw(r, 0);
        CHECK_MSG(fabsf(at(32, 32)[0] - col[f][0] / 255.0f) < TOL && fabsf(at(32, 32)[1] - col[f][1] / 255.0f) < TOL &&
                  fabsf(at(32, 32)[2] - col[f][2] / 255.0f) < TOL, "face %d shows %g %g %g", f,
                  at(32, 32)[0], at(32, 32)[1], at(32, 32)[2]);
    }
    render_destroy(r);
}

/* An OBJ triangle with its corners at NDC (-1,-1), (1,-1), (-1,1) fills
 * the lower-left half of the screen. */
static void test_obj_geometry(void) {
    scratch_write("tri.obj", "# one triangle\nv -1 -1 0\nv 1 -1 0\nv -1 1 0\nf 1 2 3\n");
    scratch_write("obj.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nBackground 0 0 0\nVertex flat.vert\nFragment flat.frag\n"
                           "Program O uColor {1 1 1 1}\nObj tri.obj\n");
    render *r = gl_test_load_scratch("obj.glib");
    draw(r, 0);
    CHECK_RGB(at(8, 56), 1, 1, 1);     /* bottom left: inside */
    CHECK_RGB(at(56, 8), 0, 0, 0);     /* top right: outside */
    CHECK_RGB(at(20, 40), 1, 1, 1);    /* below the diagonal */
    CHECK_RGB(at(40, 20), 0, 0, 0);    /* above it */
    render_destroy(r);
}

static double now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* The viewer's loop in small: a save (editor-style rename over the file)
 * is seen by the watcher on the scene's dependencies, and the reload shows
 * the new colour. The latency is printed (timing is not asserted here). */
static void test_save_is_seen_and_reloaded(void) {
    scratch_write("live.frag", "#version 330 compatibility\nout vec4 c;\nvoid main() { c = vec4(1., 0., 1., 1.); }\n");
    scratch_write("live.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex flat.vert\nFragment live.frag\nProgram L\nQuadXY 0 1 1 1\n");
    render *r = gl_test_load_scratch("live.glib");
    char err[256];
    watch *w = watch_create(err, sizeof err);
    CHECK_MSG(w != NULL, "%s", err);
    if (!w) { render_destroy(r); return; }
    const char *const *deps;
    int n = render_deps(r, &deps);
    CHECK(watch_set_files(w, deps, n, err, sizeof err));
    draw(r, 0);
    CHECK_RGB(at(32, 32), 1, 0, 1);
    scratch_write("live.frag.tmp", "#version 330 compatibility\nout vec4 c;\nvoid main() { c = vec4(0., 1., 1., 1.); }\n");
    char tmp[512];
    snprintf(tmp, sizeof tmp, "%s", scratch_path("live.frag.tmp"));
    double t0 = now_ms();
    CHECK_EQ(rename(tmp, scratch_path("live.frag")), 0);
    int changed = watch_poll(w, 2000);
    CHECK_EQ(changed, 1);
    CHECK(render_load(r, NULL));
    draw(r, 0);
    fprintf(stderr, "  save to new image: %.1f ms\n", now_ms() - t0);
    CHECK_RGB(at(32, 32), 0, 1, 1);
    CHECK_EQ(watch_poll(w, 300), 0);   /* one save, one reload */
    watch_destroy(w);
    render_destroy(r);
}

static void test_no_gl_errors(void) {
    render *r = render_create(NULL);
    CHECK(render_load(r, scratch_path("rtt.glib")));
    draw(r, 0);
    /* rtt.glib: the screen, then a pass into unit 6 (line 4), then the screen again (line 11) */
    const char (*names)[GPU_TIMER_NAME];
    const double *ms;
    int n = render_pass_times(r, true, &names, &ms);
    CHECK_EQ(n, 3);
    if (n == 3) {
        CHECK_STR_EQ(names[0], "screen");
        CHECK_MSG(strcmp(names[1], "pass:4 6") == 0, "%s", names[1]);
        CHECK_MSG(strcmp(names[2], "screen:11") == 0, "%s", names[2]);
        for (int i = 0; i < n; i++) CHECK_GE(ms[i], 0);
    }
    GLenum e = glGetError();
    CHECK_MSG(e == GL_NO_ERROR, "GL error 0x%x", e);
    render_destroy(r);
}

/* A plain glman scene: an If block does not make it a world (no terrain,
 * no sky, no sRGB output), and its WindowSize is what `render` writes by
 * default and what `reference` reads (one reader, scene_camera_from_glib;
 * render.c once refused sizes under 16 and drew 800x600). */
static void test_plain_scene_viewing_and_no_world(void) {
    scratch_write("plain.glib", "##OpenGL GLIB\nWindowSize 12 10\nOrtho -1 1 -1 1\n"
                  "Define FOO <false>\nVertex flat.vert\nFragment flat.frag\n"
                  "Program F uColor {0 1 0 1}\nIf FOO\nQuadXY 0 1\nEndIf\nQuadXY 0 1\n");
    render *r = gl_test_load_scratch("plain.glib");
    int w = 0, h = 0;
    render_window_size(r, &w, &h);
    CHECK_MSG(w == 12 && h == 10, "render's size %dx%d", w, h);
    CHECK(!render_has_world(r));
    render_destroy(r);
    ref_world_desc d;
    scene_camera cam;
    bool has = true;
    char err[512];
    CHECK_MSG(scene_load(scratch_path("plain.glib"), NULL, &d, &cam, &has, err, sizeof err), "%s", err);
    CHECK_MSG(cam.width == 12 && cam.height == 10, "the reference's size %dx%d", cam.width, cam.height);
    CHECK(!has);
}

int main(void) {
    ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    fprintf(stderr, "context: %s\n", gl_ctx_describe(ctx));
    if (!scratch_create("render")) return 1;
    RUN(test_uniform_colour_fills_the_screen);
    RUN(test_transforms_place_geometry);
    RUN(test_timer_is_a_sawtooth);
    RUN(test_reads_clock);
    RUN(test_gstap_names_work);
    RUN(test_texture_from_bmp);
    RUN(test_render_to_texture);
    RUN(test_shader_error_keeps_last_good_then_fix_applies);
    RUN(test_included_error_reported_once);
    RUN(test_glib_error_keeps_last_good_scene);
    RUN(test_slider_values_survive_reload);
    RUN(test_define_toggle_recompiles);
    RUN(test_noise_texture_is_centred);
    RUN(test_deps_list_every_file);
    RUN(test_cube_map_faces);
    RUN(test_obj_geometry);
    RUN(test_save_is_seen_and_reloaded);
    RUN(test_no_gl_errors);
    RUN(test_plain_scene_viewing_and_no_world);
    gl_ctx_destroy(ctx);
    scratch_remove();
    return check_summary();
}
