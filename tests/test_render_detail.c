/* test_render_detail: render_set_detail, what the windows' frame budget
 * uses to make a reduced frame cheap. At detail d a target of a fixed or
 * slider-given size is d times as large a side (at least 16), one that
 * follows the frame is left alone (one drawn from the view's camera: twice
 * d), and detail 1 brings back the scene's
 * own sizes and meshes, pixel for pixel. A whole pack at a quarter detail
 * still draws the same picture in the large: natural's photons (one per
 * texel of a uPhotonGrid target, splatted as uPhotonGrid^2 points) must
 * shrink together, or the caustics' brightness would change by the ratio
 * of their counts. */
#include <GL/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "support.h"
#include "gl_ctx.h"
#include "gl_support.h"
#include "render.h"

#define W 160
#define H 90
#define LAKE TARN_SOURCE_DIR "/scenes/lake.glib"

static float px[W * H * 4];

static void draw(render *r) {
    render_target tg;
    if (!render_target_create(&tg, W, H, true)) { fprintf(stderr, "no target\n"); exit(1); }
    render_frame(r, 2.0, tg.fbo, W, H, NULL);
    CHECK(render_target_read(&tg, px));
    render_target_destroy(&tg);
    GLenum e = glGetError();
    CHECK_MSG(e == GL_NO_ERROR, "GL error 0x%x", e);
}

/* The sizes of the targets, as the screen pass sees them: the fixed
 * one's w x h, the slider's side, and the Once target's side + 1000 x the
 * screen-sized one's. */
static void sizes_at(render *r, double detail, const float want[4]) {
    render_set_detail(r, detail);
    draw(r);
    const float *c = px + ((H / 2) * W + W / 2) * 4;
    CHECK_MSG(c[0] == want[0] && c[1] == want[1] && c[2] == want[2] && c[3] == want[3],
              "detail %g: targets %gx%g, %g, %g; want %gx%g, %g, %g", detail, c[0], c[1], c[2], c[3], want[0],
              want[1], want[2], want[3]);
}

static void test_target_sizes(void) {
    scratch_write("sizes.vert", "#version 330 compatibility\n"
                                "void main() { gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; }\n");
    scratch_write("sizes.frag", "#version 330 compatibility\n"
                                "uniform sampler2D uFixed, uSlider, uScreen, uOnce;\n"
                                "out vec4 fragColor;\n"
                                "void main() {\n"
                                "    fragColor = vec4(vec2(textureSize(uFixed, 0)), float(textureSize(uSlider, 0).x),\n"
                                "                     float(textureSize(uOnce, 0).x + 1000 * textureSize(uScreen, 0).x));\n"
                                "}\n");
    scratch_write("sizes.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nBackground 0 0 0\n"
                                "Texture2D 3 256 128 float16\n"
                                "Texture2D 4 uSide uSide float16\n"
                                "Texture2D 5 screen screen float16\n"
                                "Texture2D 6 64 64 float16\n"
                                "RenderToTextureOnce 6\nClear\n"   /* drawn once a load: never shrunk */
                                "RenderToTexture 3\nClear\nRenderToTexture 4\nClear\nRenderToTexture 5\nClear\n"
                                "RenderToTexture\n"
                                "Vertex sizes.vert\nFragment sizes.frag\n"
                                "Program Sizes uSide <10 100 1000> uFixed 3 uSlider 4 uScreen 5 uOnce 6\n"
                                "QuadXY 0 1 1 1\n");
    render *r = gl_test_load_scratch("sizes.glib");
    float once = 64 + 1000 * W;
    sizes_at(r, 1.0, (float[]){ 256, 128, 100, once });
    /* a reduced side is a power of two when the scene's is, else none
     * (side_like_full: llvmpipe keys a shader's code on it) */
    sizes_at(r, 0.5, (float[]){ 128, 64, 50, once });
    sizes_at(r, 0.25, (float[]){ 64, 32, 25, once });
    sizes_at(r, 0.3, (float[]){ 64, 32, 30, once });    /* 77 x 38: the nearer powers of two, in ratio */
    sizes_at(r, 0.16, (float[]){ 32, 16, 17, once });   /* 16: not one, one texel more */
    sizes_at(r, 0.01, (float[]){ 16, 16, 17, once });   /* the floor: a pass still has something to draw */
    sizes_at(r, 1.0, (float[]){ 256, 128, 100, once });
    sizes_at(r, 0.0, (float[]){ 256, 128, 100, once });   /* out of range: the scene's own */
    render_destroy(r);
}

/* A target drawn every frame from the view's camera (natural's refraction
 * and reflection) keeps twice the frame's detail a side, up to its own
 * size; one drawn from the light, or by a pass that sets no camera, the
 * frame's detail. Red: the view target's side, green: the light's, blue:
 * the camera-less one's. */
static void test_view_target_sizes(void) {
    scratch_write("view.frag", "#version 330 compatibility\n"
                               "uniform sampler2D uView, uLight, uNone;\n"
                               "out vec4 fragColor;\n"
                               "void main() {\n"
                               "    fragColor = vec4(float(textureSize(uView, 0).x), float(textureSize(uLight, 0).x),\n"
                               "                     float(textureSize(uNone, 0).x), 0.0);\n"
                               "}\n");
    scratch_write("view.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\nBackground 0 0 0\n"
                               "Texture2D 3 512 512 float16\n"
                               "Texture2D 4 512 512 float16\n"
                               "Texture2D 5 512 512 float16\n"
                               "RenderToTexture 3\nCamera mirror\nClear\n"
                               "RenderToTexture 4\nCamera light\nClear\n"
                               "RenderToTexture 5\nClear\n"
                               "RenderToTexture\nCamera main\n"   /* the screen's camera: not unit 5's */
                               "Vertex sizes.vert\nFragment view.frag\n"
                               "Program View uView 3 uLight 4 uNone 5\n"
                               "QuadXY 0 1 1 1\n");
    render *r = gl_test_load_scratch("view.glib");
    const struct { double detail; float view, light, none; } want[] = {
        { 1.0, 512, 512, 512 },
        { 0.5, 512, 256, 256 },    /* twice a half: the whole */
        { 0.28, 256, 128, 128 },   /* 287 and 143: the nearer powers of two */
        { 0.125, 128, 64, 64 },
        { 0.01, 16, 16, 16 },      /* the floor */
    };
    for (size_t k = 0; k < sizeof want / sizeof want[0]; k++) {
        render_set_detail(r, want[k].detail);
        draw(r);
        const float *c = px + ((H / 2) * W + W / 2) * 4;
        CHECK_MSG(c[0] == want[k].view && c[1] == want[k].light && c[2] == want[k].none,
                  "detail %g: view, light, no camera %g, %g, %g; want %g, %g, %g", want[k].detail, c[0], c[1], c[2],
                  want[k].view, want[k].light, want[k].none);
    }
    render_destroy(r);
}

static double mean_rgb(const float *p) {
    double s = 0;
    for (int i = 0; i < W * H; i++) s += (p[4 * i] + p[4 * i + 1] + p[4 * i + 2]) / 3.0;
    return s / (W * H);
}

static double rmse(const float *a, const float *b) {
    double s = 0;
    for (int i = 0; i < W * H; i++)
        for (int k = 0; k < 3; k++) s += (double)(a[4 * i + k] - b[4 * i + k]) * (a[4 * i + k] - b[4 * i + k]);
    return sqrt(s / (3.0 * W * H));
}

/* A pack on the lake: the quarter-detail frame is the full one, coarser;
 * detail 1 again is exactly the full one. */
static void check_pack(const char *pack, double max_mean_rel, double max_rmse) {
    render *r = render_create(&(render_desc){ .pack = pack });
    CHECK_MSG(render_load(r, LAKE), "%s", render_messages(r));
    render_set_world_cache(r, false);   /* every frame drawn: what is compared is the drawing */
    draw(r);
    float *full = malloc(sizeof px);
    memcpy(full, px, sizeof px);
    render_set_detail(r, 0.25);
    draw(r);
    double m0 = mean_rgb(full), m1 = mean_rgb(px), e = rmse(full, px);
    printf("%s: mean %.4f at detail 1, %.4f at 1/4 (%+.2f%%); RMSE between them %.4f\n", pack, m0, m1,
           100 * (m1 / m0 - 1), e);
    CHECK_MSG(fabs(m1 / m0 - 1) <= max_mean_rel, "%s: a quarter detail changed the mean by %.2f%%", pack,
              100 * (m1 / m0 - 1));
    CHECK_MSG(e <= max_rmse, "%s: a quarter detail is %.4f RMSE from the full one", pack, e);
    CHECK_MSG(e > 0, "%s: a quarter detail drew the same pixels: nothing shrank", pack);
    render_set_detail(r, 1.0);
    draw(r);
    CHECK_MSG(memcmp(full, px, sizeof px) == 0, "%s: detail 1 after 1/4 is not the full frame", pack);
    free(full);
    render_destroy(r);
}

/* Tolerances: the whole-image mean moves by under 3% (a mismatch of the
 * photon grid and its splat would scale natural's caustics 16 times, the
 * pool floor's brightness by far more than that), and the pixels by
 * under 0.05 RMSE in linear radiance (coarser refraction targets, caustic
 * map and meshes at a side 1/4 of the full one; measured 0.01-0.03). */
static void test_packs(void) {
    check_pack("natural", 0.03, 0.05);
    check_pack("caustic_tex", 0.03, 0.05);
    check_pack("raymarch", 0.03, 0.05);
}

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    if (!scratch_create("detail")) return 1;
    RUN(test_target_sizes);
    RUN(test_view_target_sizes);
    RUN(test_packs);
    gl_ctx_destroy(ctx);
    scratch_remove();
    return check_summary();
}
