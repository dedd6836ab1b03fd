/* The sharp world's two renderer parts (render.h): the snapshot of the
 * screen right before its water, and render_frame_world_at.
 *   - The world-only frame is the frame's screen as it was before the
 *     water, bit for bit (the same size and time), for every pack
 *     (caustic_tex's world reaches the screen by a copy of a pass): what
 *     the window shows from it where the reduced frame kept its world is
 *     what a full frame shows there.
 *   - The snapshot is that too, at the frame's size; and a frame differs
 *     from it where the water drew, so both kinds of pixel exist.
 *   - A world-only frame between two frames changes nothing the next frame
 *     draws (passes drawn once, the world's layers, the water's state).
 *   - A scene without a WaterSurface has no snapshot (the window then
 *     enlarges the whole frame). */
#include <GL/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "gl_ctx.h"
#include "gl_support.h"
#include "render.h"

#define W 192
#define H 108
#define LAKE TARN_SOURCE_DIR "/scenes/lake.glib"

/* The w x h bottom-left texels of colour texture tex (any format), as floats. */
static float *read_tex(unsigned tex, int w, int h) {
    unsigned fbo;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    float *px = malloc((size_t)w * h * 4 * sizeof(float));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, px);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    return px;
}

static render_target target(bool srgb, int w, int h) {
    render_target t;
    CHECK(srgb ? render_target_create_srgb(&t, w, h) : render_target_create(&t, w, h, true));
    return t;
}

/* Pixels whose colour differs between a and b. */
static int differing(const float *a, const float *b, int n) {
    int d = 0;
    for (int i = 0; i < n; i++) d += memcmp(a + i * 4, b + i * 4, 3 * sizeof(float)) != 0;
    return d;
}

static void check_world_alone(const char *pack, bool srgb) {
    render *r = render_create(&(render_desc){ .pack = pack });
    CHECK_MSG(render_load(r, LAKE), "%s", render_messages(r));
    render_set_world_snapshot(r, true);
    render_target f = target(srgb, W, H), wo = target(srgb, W, H);
    if (srgb) glEnable(GL_FRAMEBUFFER_SRGB);
    render_frame(r, 2.0, f.fbo, W, H, NULL);
    int sw = 0, sh = 0;
    unsigned snap = render_world_snapshot(r, &sw, &sh);
    CHECK_MSG(snap != 0, "%s: no snapshot after a frame of the lake", pack);
    CHECK_EQ(sw, W);
    CHECK_EQ(sh, H);
    float *frame_px = read_tex(f.color, W, H), *snap_px = snap ? read_tex(snap, W, H) : NULL;
    render_frame_world_at(r, 2.0, wo.fbo, 0, 0, W, H, NULL);
    glDisable(GL_FRAMEBUFFER_SRGB);
    float *world_px = read_tex(wo.color, W, H);
    CHECK_EQ(glGetError(), GL_NO_ERROR);
    if (snap_px) {
        int water = differing(frame_px, snap_px, W * H), off = differing(world_px, snap_px, W * H);
        printf("%s (%s): %d of %d pixels drawn over the World; the world-only frame differs from the snapshot at %d\n",
               pack, srgb ? "sRGB" : "float", water, W * H, off);
        CHECK_EQ(off, 0);
        CHECK_GT(water, W * H / 10);        /* the lake's water */
        CHECK_LT(water, W * H * 9 / 10);    /* its sky and shore */
    }
    free(frame_px);
    free(snap_px);
    free(world_px);
    render_target_destroy(&f);
    render_target_destroy(&wo);
    render_destroy(r);
}

static void test_world_alone(void) {
    check_world_alone("basic", true);
    check_world_alone("natural", true);
    check_world_alone("raymarch", false);
    check_world_alone("caustic_tex", true);   /* its World reaches the screen by a copy pass */
}

/* Two renderers draw the same frames; one draws a world-only frame of
 * another size and time between them: the next frame is the same, bit for
 * bit, and the world's layers took the same frames. raymarch: its top-down
 * views are drawn once and kept. */
static void test_world_only_leaves_the_frames(void) {
    render *a = render_create(&(render_desc){ .pack = "raymarch" }), *b = render_create(&(render_desc){ .pack = "raymarch" });
    CHECK_MSG(render_load(a, LAKE) && render_load(b, LAKE), "%s", render_messages(a));
    render_set_world_snapshot(b, true);
    render_target fa = target(true, W, H), fb = target(true, W, H), big = target(true, 2 * W, 2 * H);
    glEnable(GL_FRAMEBUFFER_SRGB);
    render_frame(a, 1.0, fa.fbo, W, H, NULL);
    render_frame(b, 1.0, fb.fbo, W, H, NULL);
    render_frame_world_at(b, 1.5, big.fbo, 0, 0, 2 * W, 2 * H, NULL);
    for (double t = 2.0; t <= 3.0; t += 0.5) {
        render_frame(a, t, fa.fbo, W, H, NULL);
        render_frame(b, t, fb.fbo, W, H, NULL);
    }
    glDisable(GL_FRAMEBUFFER_SRGB);
    float *pa = read_tex(fa.color, W, H), *pb = read_tex(fb.color, W, H);
    int off = differing(pa, pb, W * H);
    printf("raymarch: after a world-only frame, %d pixels differ; layer frames %ld and %ld\n", off,
           render_world_layer_frames(a), render_world_layer_frames(b));
    CHECK_EQ(off, 0);
    CHECK_EQ(render_world_layer_frames(b), render_world_layer_frames(a));
    CHECK_GT(render_world_layer_frames(a), 0);
    free(pa);
    free(pb);
    render_target_destroy(&fa);
    render_target_destroy(&fb);
    render_target_destroy(&big);
    render_destroy(a);
    render_destroy(b);
}

static void test_no_world_no_snapshot(void) {
    render *r = render_create(NULL);
    CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/tests/data/glman/noise/noise.glib"), "%s", render_messages(r));
    render_set_world_snapshot(r, true);
    render_target f = target(false, W, H);
    render_frame(r, 0.5, f.fbo, W, H, NULL);
    int sw = -1, sh = -1;
    CHECK_EQ(render_world_snapshot(r, &sw, &sh), 0u);
    CHECK_EQ(sw, 0);
    render_target_destroy(&f);
    render_destroy(r);
}

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    RUN(test_world_alone);
    RUN(test_world_only_leaves_the_frames);
    RUN(test_no_world_no_snapshot);
    gl_ctx_destroy(ctx);
    return check_summary();
}
