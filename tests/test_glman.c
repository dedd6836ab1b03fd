/* test_glman: small glman-style projects (tests/data/glman/) open and look
 * as they did in glman (issue 14): its defaults, its built-in noise, its
 * raw noise cache, and a Texture2D rebinding a unit for the draws after it.
 * Rendered headless; the pictures are checked by pixels. */
#include <GL/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "support.h"
#include "gl_ctx.h"
#include "render.h"

#define W 64
#define H 64
#define TOL (1.5 / 255.0)   /* RGBA8 target: half a step of rounding, plus slack */
#define DATA TARN_SOURCE_DIR "/tests/data/glman/"

static gl_ctx *ctx;
static float px[W * H * 4];

/* Loads path into a fresh render and draws it into px (W x H). */
static bool draw_file(const char *path) {
    render *r = render_create(NULL);
    bool ok = render_load(r, path);
    CHECK_MSG(ok, "%s", render_messages(r));
    render_target tg;
    if (!render_target_create(&tg, W, H, false)) { fprintf(stderr, "no target\n"); exit(1); }
    render_frame(r, 0, tg.fbo, W, H, NULL);
    CHECK(render_target_read(&tg, px));
    render_target_destroy(&tg);
    render_destroy(r);
    return ok;
}

/* pixel (x, y), y = 0 the top row */
static const float *at(int x, int y) { return px + ((size_t)y * W + x) * 4; }

/* No WindowSize, no LookAt: the eye at the origin looking down -Z, so
 * `Translate 0 0 -4` and a bare Sphere (glman's 1 60 60) land in the middle. */
static void test_default_view_and_sphere(void) {
    if (!draw_file(DATA "defaults/defaults.glib")) return;
    const float *c = at(W / 2, H / 2);
    CHECK_NEAR(c[0], 1.0, TOL);
    CHECK_NEAR(c[1], 0.5, TOL);
    CHECK_NEAR(c[2], 0.0, TOL);
    const float *e = at(2, 2);   /* radius 1 at 4 under a 50 degree view: the corner is background */
    CHECK(e[0] < TOL && e[1] < TOL && e[2] < TOL);
}

/* A shader reading Noise2 and Noise3 with no Noise command and no Program
 * entry sees glman's noise: not black, about 0.5 and not constant. */
static void test_noise_always_present(void) {
    if (!draw_file(DATA "noise/noise.glib")) return;
    double lo = 1, hi = 0, sum = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const float *p = at(x, y);
            lo = p[0] < lo ? p[0] : lo;
            hi = p[0] > hi ? p[0] : hi;
            sum += p[0] + p[1];
        }
    const float *c = at(W / 2, H / 2);
    CHECK_MSG(!(c[0] == 0 && c[1] == 0 && c[2] == 0), "the centre is black: Noise2/Noise3 not bound");
    CHECK_MSG(fabs(sum / (2.0 * W * H) - 0.5) < 0.1, "mean %g", sum / (2.0 * W * H));
    CHECK_MSG(hi - lo > 0.05, "Noise2's red is flat: %g..%g", lo, hi);
}

/* glman's cached noise2d.064.tex in the project folder is read (raw
 * format: int32 s t, then s*t RGBA bytes): a constant file gives its value. */
static void test_noise_cache_file_is_read(void) {
    FILE *f = fopen(scratch_path("noise2d.064.tex"), "wb");
    if (!f) { CHECK(f != NULL); return; }
    unsigned char hdr[8] = { 64, 0, 0, 0, 64, 0, 0, 0 }, texel[4] = { 64, 128, 192, 255 };
    fwrite(hdr, 1, sizeof hdr, f);
    for (int i = 0; i < 64 * 64; i++) fwrite(texel, 1, sizeof texel, f);
    fclose(f);
    scratch_write("cache.glib",
                  "##OpenGL GLIB\nOrtho -1 1 -1 1\n"
                  "Vertex " DATA "noise/noise.vert\nFragment " DATA "noise/noise.frag\n"
                  "Program Noisy\nQuadXY 0 2\n");
    if (!draw_file(scratch_path("cache.glib"))) return;
    CHECK_NEAR(at(W / 2, H / 2)[0], 64 / 255.0, TOL);
    CHECK_NEAR(at(5, 50)[0], 64 / 255.0, TOL);
}

/* A w x h 24-bit BMP of one colour (bottom-up rows padded to 4 bytes). */
static void write_solid_bmp(const char *name, unsigned char r, unsigned char g, unsigned char b) {
    enum { S = 4, ROW = S * 3, SIZE = 54 + ROW * S };
    unsigned char h[54] = { 'B', 'M', SIZE, 0, 0, 0, 0, 0, 0, 0, 54, 0, 0, 0, 40, 0, 0, 0,
                            S, 0, 0, 0, S, 0, 0, 0, 1, 0, 24, 0 };
    FILE *f = fopen(scratch_path(name), "wb");
    if (!f) { CHECK(f != NULL); return; }
    fwrite(h, 1, sizeof h, f);
    for (int i = 0; i < S * S; i++) {
        unsigned char bgr[3] = { b, g, r };
        fwrite(bgr, 1, 3, f);
    }
    fclose(f);
}

/* glman runs the file in order: `Texture2D 6 a.bmp`, a quad, `Texture2D 6
 * b.bmp`, a quad: each quad shows its own image (the course's sky box loads
 * one image per wall on one unit; binding all at the frame's start showed
 * the last image on every wall). */
static void test_texture_rebinds_in_order(void) {
    write_solid_bmp("a.bmp", 255, 0, 0);
    write_solid_bmp("b.bmp", 0, 0, 255);
    scratch_write("tex.vert", "#version 120\nvarying vec2 vST;\n"
                  "void main() { vST = gl_MultiTexCoord0.st; gl_Position = ftransform(); }\n");
    scratch_write("tex.frag", "#version 120\nuniform sampler2D uTex;\nvarying vec2 vST;\n"
                  "void main() { gl_FragColor = texture2D(uTex, vST); }\n");
    scratch_write("sky.glib",
                  "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex tex.vert\nFragment tex.frag\n"
                  "Program Wall uTex 6\n"
                  "Texture2D 6 a.bmp\nPushMatrix\nTranslate -0.5 0 0\nQuadXY 0 0.5\nPopMatrix\n"
                  "Texture2D 6 b.bmp\nPushMatrix\nTranslate 0.5 0 0\nQuadXY 0 0.5\nPopMatrix\n");
    if (!draw_file(scratch_path("sky.glib"))) return;
    const float *l = at(W / 4, H / 2), *r = at(3 * W / 4, H / 2);
    CHECK_MSG(l[0] > 1 - TOL && l[2] < TOL, "left quad %g %g %g, want a.bmp's red", l[0], l[1], l[2]);
    CHECK_MSG(r[2] > 1 - TOL && r[0] < TOL, "right quad %g %g %g, want b.bmp's blue", r[0], r[1], r[2]);
}

/* Flat / Smooth: a vertex colour that grows with x over a quad is one colour
 * per triangle under Flat (the provoking vertex's) and a ramp under Smooth. */
static void test_flat_and_smooth(void) {
    scratch_write("ramp.vert", "#version 120\n"
                  "void main() { gl_FrontColor = vec4(gl_Vertex.x * 0.5 + 0.5, 0., 0., 1.);\n"
                  "              gl_Position = ftransform(); }\n");
    scratch_write("ramp.frag", "#version 120\nvoid main() { gl_FragColor = gl_Color; }\n");
    const char *modes[2] = { "Flat", "Smooth" };
    float a[2], b[2];
    for (int m = 0; m < 2; m++) {
        char text[512];
        snprintf(text, sizeof text, "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex ramp.vert\n"
                 "Fragment ramp.frag\nProgram Ramp\n%s\nQuadXY 0 1\n", modes[m]);
        scratch_write("ramp.glib", text);
        if (!draw_file(scratch_path("ramp.glib"))) return;
        /* two pixels on one row near the bottom: one triangle of the quad */
        a[m] = at(W / 4, H - 4)[0];
        b[m] = at(3 * W / 4, H - 4)[0];
    }
    CHECK_MSG(fabsf(a[0] - b[0]) < TOL, "Flat: %g vs %g, want one colour", a[0], b[0]);
    CHECK_MSG(b[1] - a[1] > 0.3, "Smooth: %g vs %g, want a ramp", a[1], b[1]);
}

int main(void) {
    char err[512];
    ctx = gl_ctx_create_headless(err, sizeof err);
    if (!ctx) {
        fprintf(stderr, "skip: %s\n", err);
        return 77;
    }
    if (!scratch_create("glman")) return 1;
    RUN(test_default_view_and_sphere);
    RUN(test_noise_always_present);
    RUN(test_noise_cache_file_is_read);
    RUN(test_texture_rebinds_in_order);
    RUN(test_flat_and_smooth);
    gl_ctx_destroy(ctx);
    scratch_remove();
    return check_summary();
}
