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
    /* MSAA off: these check shader outputs pixel for pixel (an ID, a
     * vertex count), which a resolve blends at edges; test_msaa checks MSAA */
    render *r = render_create(&(render_desc){ .samples = 1 });
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

/* A sampler of another name set to unit 3 on the Program line reads the
 * built-in Noise3 too (it is built when a program samples its unit). */
static void test_noise_at_its_unit_by_any_name(void) {
    if (!draw_file(DATA "noise/named.glib")) return;
    double lo = 1, hi = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            lo = at(x, y)[0] < lo ? at(x, y)[0] : lo;
            hi = at(x, y)[0] > hi ? at(x, y)[0] : hi;
        }
    CHECK_MSG(lo > 0.1 && hi < 0.9 && hi - lo > 0.05, "Noise3 at unit 3 read as %g..%g", lo, hi);
}

/* glman's cached noise2d.064.tex in the project folder is read (raw
 * format: int32 s t, then s*t RGBA bytes): a constant file gives its value. */
static void test_noise_cache_file_is_read(void) {
    FILE *f = fopen(scratch_path("noise2d.064.tex"), "wb");
    if (!f) { CHECK_NE(f, NULL); return; }
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
    if (!f) { CHECK_NE(f, NULL); return; }
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

/* Loads path; its messages (the compiler's, mapped, with tarn's notes)
 * into msgs. Returns whether it loaded cleanly. */
static bool load_messages(const char *path, char *msgs, size_t len) {
    render *r = render_create(NULL);
    bool ok = render_load(r, path);
    snprintf(msgs, len, "%s", render_messages(r));
    render_destroy(r);
    return ok;
}

/* The fraction of pixels that are not the black background. */
static double coverage(void) {
    int n = 0;
    for (int i = 0; i < W * H; i++)
        if (px[i * 4] > TOL || px[i * 4 + 1] > TOL || px[i * 4 + 2] > TOL) n++;
    return (double)n / (W * H);
}

/* A geometry shader written for GL_EXT_geometry_shader4, as glman's course
 * ones are (#version 120, gl_PositionIn, gl_VerticesIn, gl_FrontColorIn,
 * `varying out`, no layouts): it shrinks each triangle to half its size
 * about its centroid, so the full-screen quad covers a quarter of the
 * picture, and its colour says gl_VerticesIn was 3 and gl_FrontColorIn
 * carried Color's green. */
static void test_ext_geometry_shader(void) {
    scratch_write("pass.vert", "#version 120\n"
                  "void main() { gl_FrontColor = gl_Color; gl_Position = gl_ModelViewMatrix * gl_Vertex; }\n");
    scratch_write("shrink.geom", "#version 120\n#extension GL_EXT_geometry_shader4 : enable\n"
                  "varying out float gK;\n"
                  "void main() {\n"
                  "  vec4 c = (gl_PositionIn[0] + gl_PositionIn[1] + gl_PositionIn[2]) / 3.;\n"
                  "  for (int i = 0; i < gl_VerticesIn; i++) {\n"
                  "    gl_FrontColor = gl_FrontColorIn[i];\n"
                  "    gK = float(gl_VerticesIn) / 3.;\n"
                  "    gl_Position = gl_ProjectionMatrix * mix(c, gl_PositionIn[i], 0.5);\n"
                  "    EmitVertex();\n"
                  "  }\n"
                  "  EndPrimitive();\n"
                  "}\n");
    scratch_write("shrink.frag", "#version 120\nvarying float gK;\n"
                  "void main() { gl_FragColor = vec4(gK, gl_Color.g, 0., 1.); }\n");
    scratch_write("shrink.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex pass.vert\nGeometry shrink.geom\n"
                  "Fragment shrink.frag\nProgram Shrink\nColor 0 1 0\nQuadXY 0 1\n");
    if (!draw_file(scratch_path("shrink.glib"))) return;
    double cov = coverage();
    CHECK_MSG(fabs(cov - 0.25) < 0.03, "coverage %g, want a quarter (each triangle at half size)", cov);
    const float *corner = at(1, 1);
    CHECK(corner[0] < TOL && corner[1] < TOL);
    int lit = 0;
    for (int i = 0; i < W * H; i++) {
        if (px[i * 4] <= TOL && px[i * 4 + 1] <= TOL) continue;
        lit++;
        if (px[i * 4] < 1 - TOL || px[i * 4 + 1] < 1 - TOL) {
            CHECK_MSG(false, "pixel %d: %g %g, want 1 1 (gl_VerticesIn 3, Color's green)", i, px[i * 4],
                      px[i * 4 + 1]);
            break;
        }
    }
    CHECK_GT(lit, 0);

    /* an error in it is still on the user's line */
    scratch_write("shrink_bad.geom", "#version 120\n#extension GL_EXT_geometry_shader4 : enable\n"
                  "void main() {\n  gl_Position = gl_PositionIn[0] * undefined_here;\n  EmitVertex();\n}\n");
    scratch_write("shrink_bad.glib", "##OpenGL GLIB\nVertex pass.vert\nGeometry shrink_bad.geom\n"
                  "Fragment shrink.frag\nProgram Bad\nQuadXY 0 1\n");
    char msgs[4096];
    CHECK(!load_messages(scratch_path("shrink_bad.glib"), msgs, sizeof msgs));
    CHECK_MSG(strstr(msgs, "shrink_bad.geom:4: error:") && strstr(msgs, "undefined_here"), "%s", msgs);
}

/* A layout-less geometry shader used with a Wire draw gets `lines` in (a
 * triangles one would fail at every draw, GL_INVALID_OPERATION): it turns
 * each edge of the square into a band 0.2 wide, so the edges are lit and
 * the middle is not. */
static void test_geometry_input_follows_draw(void) {
    scratch_write("band.geom", "#version 120\n#extension GL_EXT_geometry_shader4 : enable\n"
                  "void main() {\n"
                  "  vec4 p0 = gl_ProjectionMatrix * gl_PositionIn[0], p1 = gl_ProjectionMatrix * gl_PositionIn[1];\n"
                  "  vec2 t = normalize(p1.xy - p0.xy), n = vec2(-t.y, t.x) * 0.1;\n"
                  "  gl_FrontColor = vec4(float(gl_VerticesIn) / 2., 0., 0., 1.);\n"
                  "  gl_Position = p0 - vec4(n, 0., 0.); EmitVertex();\n"
                  "  gl_Position = p0 + vec4(n, 0., 0.); EmitVertex();\n"
                  "  gl_Position = p1 - vec4(n, 0., 0.); EmitVertex();\n"
                  "  gl_Position = p1 + vec4(n, 0., 0.); EmitVertex();\n"
                  "  EndPrimitive();\n"
                  "}\n");
    scratch_write("band.frag", "#version 120\nvoid main() { gl_FragColor = gl_Color; }\n");
    scratch_write("band.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex pass.vert\nGeometry band.geom\n"
                  "Fragment band.frag\nProgram Band\nWireQuadXY 0 0.5\n");
    if (!draw_file(scratch_path("band.glib"))) return;
    const float *top = at(W / 2, H / 4), *left = at(W / 4, H / 2), *mid = at(W / 2, H / 2);
    CHECK_MSG(top[0] > 1 - TOL && left[0] > 1 - TOL, "edges %g %g, want 1 (gl_VerticesIn 2)", top[0], left[0]);
    CHECK_MSG(mid[0] < TOL, "middle %g, want background", mid[0]);
}

/* `layout(binding = 6)` on a sampler under #version 330, no unit on the
 * Program line: the sampler reads unit 6 (NVIDIA took this; Mesa needs
 * GL_ARB_shading_language_420pack, which tarn enables). A uniform with
 * `layout(location = 3)` likewise (GL_ARB_explicit_uniform_location), set
 * from the Program line. */
static void test_layout_binding_under_330(void) {
    write_solid_bmp("bind.bmp", 255, 0, 0);
    scratch_write("bind.vert", "#version 120\nvoid main() { gl_TexCoord[0] = gl_MultiTexCoord0; "
                  "gl_Position = ftransform(); }\n");
    scratch_write("bind.frag", "#version 330 compatibility\nlayout(binding = 6) uniform sampler2D uTex;\n"
                  "layout(location = 3) uniform float uG;\n"
                  "void main() { gl_FragColor = texture(uTex, gl_TexCoord[0].st) + vec4(0., uG, 0., 0.); }\n");
    scratch_write("bind.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex bind.vert\nFragment bind.frag\n"
                  "Program Bind uG 0.5\nTexture2D 6 bind.bmp\nQuadXY 0 1\n");
    if (!draw_file(scratch_path("bind.glib"))) return;
    const float *c = at(W / 2, H / 2);
    CHECK_MSG(c[0] > 1 - TOL && fabsf(c[1] - 0.5f) < TOL && c[2] < TOL,
              "centre %g %g %g, want bind.bmp's red and uG's 0.5 green", c[0], c[1], c[2]);
}

/* GSTAP's aColor in a fragment shader is gl_Color, the interpolated colour
 * (the project failed to compile there). */
static void test_gstap_color_in_fragment(void) {
    scratch_write("gs.vert", "#version 330 compatibility\nout vec4 vColor;\n"
                  "void main() { gl_FrontColor = aColor; gl_Position = uModelViewProjectionMatrix * aVertex; }\n");
    scratch_write("gs.frag", "#version 330 compatibility\nvoid main() { gl_FragColor = aColor; }\n");
    scratch_write("gs.glib", "##OpenGL GLIB\nGSTAP\nOrtho -1 1 -1 1\nVertex gs.vert\nFragment gs.frag\n"
                  "Program Gs\nColor 0 0 1\nQuadXY 0 1\n");
    if (!draw_file(scratch_path("gs.glib"))) return;
    const float *c = at(W / 2, H / 2);
    CHECK_MSG(c[2] > 1 - TOL && c[0] < TOL && c[1] < TOL, "centre %g %g %g, want Color's blue", c[0], c[1], c[2]);
}

/* What NVIDIA accepted and Mesa rejects now runs (glsl_fix): each shader
 * below fails to compile as written; tarn rewrites what the compiler named,
 * warns at the user's file:line that it did and why, and the picture is
 * what the shader means (the quad fills the frame; at its centre vST is
 * 0.5, 0.5). A valid shader is compiled as written: no warning. */
static void test_nvidia_glsl_runs(void) {
    static const struct { const char *frag; const char *warn; float r, g, b; } cases[] = {
        { "#version 120\nvarying vec2 vST;\nfloat f(float x) { if (x > 2.) return 1; return 0; }\n"
          "vec3 g() { return 1; }\nvoid main() { gl_FragColor = vec4(f(vST.x), g().x * 0.5, 0., 1.); }\n",
          "n.frag:3: warning: rewrote `return 1;` as `return float(1);`", 0, 0.5f, 0 },
        { "#version 120\nvarying vec2 vST;\nuniform float uK;\n\nvoid main() {\n  const float K = uK * 2.;\n"
          "  gl_FragColor = vec4(K, 0., 0., 1.);\n}\n",
          "n.frag:6: warning: dropped `const` from 'K'", 0.5f, 0, 0 },
        { "#version 120\nvarying vec2 vST;\nfloat h() { return vST.x; }\n"
          "void main() {\n  vST = vST * 0.5;\n  gl_FragColor = vec4(vST, h(), 1.);\n}\n",
          "n.frag:5: warning: 'vST' is an input and the shader writes it", 0.25f, 0.25f, 0.25f },
        { "#version 330 compatibility\nin vec2 vST;\nvoid main() {\n  vec2 a = pow(vST, 2.);\n"
          "  gl_FragColor = vec4(a, pow(0.5, 1.), 1.);\n}\n",
          "n.frag:4: warning: rewrote pow(...) as tarn_pow(...)", 0.25f, 0.25f, 0.5f },
        { "#version 330 compatibility\nflat varying vec2 vST;\nvoid main() { gl_FragColor = vec4(0., 1., 0., 1.); }\n",
          "n.frag:2: warning: rewrote `varying` after an interpolation qualifier as `in`", 0, 1, 0 },
        { "#version 330 compatibility\nin vec2 vST;\nout vec4 fColor;\n"
          "void main() { fColor = vec4(0., 0., vST.x, 1.); gl_FragColor = fColor; }\n",
          "n.frag:3: warning: the shader writes gl_FragColor, so `out vec4 fColor` is no output", 0, 0, 0.5f },
        { "#version 120\nflat varying vec2 vST;\nvoid main() { gl_FragColor = vec4(1., 0., 1., 1.); }\n",
          "n.frag:2: warning: `flat` before GLSL 1.30 needs GL_EXT_gpu_shader4", 1, 0, 1 },
        { "#version 120\nvarying vec2 vST;\nvoid main() { gl_FragColor = vec4(vST, 0., 1.); }\n", NULL, 0.5f, 0.5f, 0 },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        bool flat = strstr(cases[i].frag, "flat") != NULL;
        /* a flat input's vertex shader: the same version, without flat (the link fix adds it) */
        scratch_write("n.vert", strstr(cases[i].frag, "330") ?
                      "#version 330 compatibility\nout vec2 vST;\n"
                      "void main() { vST = gl_MultiTexCoord0.st; gl_Position = ftransform(); }\n" :
                      flat ? "#version 120\nflat varying vec2 vST;\n"
                             "void main() { vST = gl_MultiTexCoord0.st; gl_Position = ftransform(); }\n"
                           : "#version 120\nvarying vec2 vST;\n"
                             "void main() { vST = gl_MultiTexCoord0.st; gl_Position = ftransform(); }\n");
        scratch_write("n.frag", cases[i].frag);
        scratch_write("n.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex n.vert\nFragment n.frag\n"
                      "Program N uK <0. 0.25 1.>\nQuadXY 0 1\n");
        char msgs[8192];
        bool ok = load_messages(scratch_path("n.glib"), msgs, sizeof msgs);
        CHECK_MSG(ok, "case %zu:\n%s", i, msgs);
        if (cases[i].warn)
            CHECK_MSG(strstr(msgs, cases[i].warn) && strstr(msgs, "NVIDIA accepted this; the GLSL specification does not"),
                      "case %zu: want \"%s\" in:\n%s", i, cases[i].warn, msgs);
        else
            CHECK_MSG(!strstr(msgs, "NVIDIA accepted"), "case %zu: a valid shader was rewritten:\n%s", i, msgs);
        if (!ok || !draw_file(scratch_path("n.glib"))) continue;
        const float *c = at(W / 2, H / 2);
        CHECK_MSG(fabsf(c[0] - cases[i].r) < 0.03f && fabsf(c[1] - cases[i].g) < 0.03f && fabsf(c[2] - cases[i].b) < 0.03f,
                  "case %zu: centre %g %g %g, want %g %g %g", i, c[0], c[1], c[2], cases[i].r, cases[i].g, cases[i].b);
    }
}

/* A flat fragment input over a vertex output without flat: the output is
 * rewritten flat (GLSL 4.30 and NVIDIA let the fragment's qualifier
 * decide), and a uniform with two types says which stage declares which. */
static void test_nvidia_link_leniency(void) {
    scratch_write("l.vert", "#version 330 compatibility\nout vec2 vST;\n"
                  "void main() { vST = gl_MultiTexCoord0.st; gl_Position = ftransform(); }\n");
    scratch_write("l.frag", "#version 330 compatibility\nflat in vec2 vST;\nvoid main() { gl_FragColor = vec4(1.); }\n");
    scratch_write("l.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex l.vert\nFragment l.frag\nProgram L\nQuadXY 0 1\n");
    char msgs[8192];
    CHECK_MSG(load_messages(scratch_path("l.glib"), msgs, sizeof msgs) &&
              strstr(msgs, "l.vert:2: warning: 'vST' is flat in the fragment shader"), "%s", msgs);
    scratch_write("u.vert", "#version 120\nuniform vec3 uC;\nvoid main() { gl_Position = ftransform() + vec4(uC, 0.); }\n");
    scratch_write("u.frag", "#version 120\n\nuniform vec4 uC;\nvoid main() { gl_FragColor = uC; }\n");
    scratch_write("u.glib", "##OpenGL GLIB\nVertex u.vert\nFragment u.frag\nProgram U uC {1 0 0}\nQuadXY 0 1\n");
    CHECK(!load_messages(scratch_path("u.glib"), msgs, sizeof msgs));
    CHECK_MSG(strstr(msgs, "uniform 'uC' is declared vec3 in the vertex shader (") &&
              strstr(msgs, "u.vert:2) and vec4 in the fragment shader (") && strstr(msgs, "u.frag:3)"), "%s", msgs);
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
    RUN(test_noise_at_its_unit_by_any_name);
    RUN(test_noise_cache_file_is_read);
    RUN(test_texture_rebinds_in_order);
    RUN(test_flat_and_smooth);
    RUN(test_ext_geometry_shader);
    RUN(test_geometry_input_follows_draw);
    RUN(test_layout_binding_under_330);
    RUN(test_gstap_color_in_fragment);
    RUN(test_nvidia_glsl_runs);
    RUN(test_nvidia_link_leniency);
    gl_ctx_destroy(ctx);
    scratch_remove();
    return check_summary();
}
