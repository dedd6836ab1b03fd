/* test_upscale: the window's upscaler (gfx/upscale.h). At 1:1 it copies
 * its input bit for bit (the full-resolution frame the window shows when
 * the picture is still); at 4x it is closer than the bilinear blit to the
 * truth on an image with a sharp edge and a smooth gradient; it makes no
 * NaN; it touches nothing outside its rectangle. The sharp world
 * (upscale_draw_over_world) shows the full-resolution world bit for bit
 * where the reduced frame kept its world, the bilinear blit where water
 * covers it, and halves the blit's error on a world with fine detail. */
#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "gl_ctx.h"
#include "gl_support.h"
#include "render.h"
#include "upscale.h"

#define W 256
#define H 144
#define F 4   /* the reduction */

/* A 2D texture of w x h RGBA floats (row 0 = bottom), nearest, as the
 * window's canvas is. */
static unsigned make_tex(GLenum internal, int w, int h, GLenum type, const void *px) {
    unsigned t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, w, h, 0, GL_RGBA, type, px);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    return t;
}

/* A w x h colour target of the given format, cleared to c. */
static void make_target(GLenum internal, int w, int h, unsigned *fbo, unsigned *tex, const float c[4]) {
    *tex = make_tex(internal, w, h, GL_FLOAT, NULL);
    glGenFramebuffers(1, fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, *fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, *tex, 0);
    CHECK_EQ(glCheckFramebufferStatus(GL_FRAMEBUFFER), GL_FRAMEBUFFER_COMPLETE);
    glClearColor(c[0], c[1], c[2], c[3]);
    glClear(GL_COLOR_BUFFER_BIT);
}

static void free_target(unsigned fbo, unsigned tex) {
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
}

/* 1:1 is a copy, byte for byte, for a plain and for an sRGB canvas drawn
 * into an sRGB target with sRGB writes on (the window's case). */
static void copy_case(GLenum internal, bool srgb_writes) {
    unsigned char *in = malloc(W * H * 4), *out = malloc(W * H * 4);
    unsigned seed = 12345;
    for (int i = 0; i < W * H * 4; i++) in[i] = (unsigned char)((seed = seed * 1103515245u + 12345u) >> 16);
    unsigned src = make_tex(internal, W, H, GL_UNSIGNED_BYTE, in), fbo, tex;
    make_target(internal, W, H, &fbo, &tex, (float[]){ 0, 0, 0, 0 });
    upscaler *u = upscale_create(NULL, NULL);
    if (srgb_writes) glEnable(GL_FRAMEBUFFER_SRGB);
    upscale_draw(u, src, W, H, fbo, (upscale_rect){ 0, 0, W, H });
    glDisable(GL_FRAMEBUFFER_SRGB);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, out);
    CHECK_MSG(memcmp(in, out, W * H * 4) == 0, "1:1 (format 0x%x) is not a copy", internal);
    CHECK_EQ(glGetError(), GL_NO_ERROR);
    upscale_destroy(u);
    free_target(fbo, tex);
    glDeleteTextures(1, &src);
    free(in);
    free(out);
}

static void test_one_to_one_exact(void) {
    copy_case(GL_RGBA8, false);
    copy_case(GL_SRGB8_ALPHA8, true);
}

/* The truth: a sharp slanted edge (0.1 to 0.8) over the left half, a
 * smooth wave of a gradient over the right; linear values. */
static void truth_at(double x, double y, float *rgba) {
    double v;
    if (x < W / 2) v = (x - 0.35 * y) > 40 ? 0.8 : 0.1;
    else v = 0.45 + 0.35 * sin(x * 0.09) * cos(y * 0.07);
    rgba[0] = (float)v;
    rgba[1] = (float)(0.5 * v + 0.2);
    rgba[2] = (float)(1.0 - v);
    rgba[3] = 1;
}

/* The scene sampled at each reduced pixel's centre, as the reduced frame
 * is drawn, enlarged by u into a float target; the RMSE against the truth
 * at each full pixel's centre over the edge's half (half 0) or the
 * gradient's (1), and whether every value is finite. */
static double error_of(upscaler *u, const float *truth, int half, bool *finite) {
    static float small[(W / F) * (H / F) * 4], out[W * H * 4];
    for (int y = 0; y < H / F; y++)
        for (int x = 0; x < W / F; x++) truth_at((x + 0.5) * F, (y + 0.5) * F, small + (y * (W / F) + x) * 4);
    unsigned src = make_tex(GL_RGBA32F, W / F, H / F, GL_FLOAT, small);
    render_target t;
    CHECK(render_target_create(&t, W, H, true));
    upscale_draw(u, src, W / F, H / F, t.fbo, (upscale_rect){ 0, 0, W, H });
    CHECK(render_target_read(&t, out));   /* row 0 = top */
    double s = 0;
    for (int y = 0; y < H; y++)
        for (int x = half * W / 2; x < (half + 1) * W / 2; x++)
            for (int c = 0; c < 3; c++) {
                float o = out[((H - 1 - y) * W + x) * 4 + c], tr = truth[(y * W + x) * 4 + c];
                if (!isfinite(o)) *finite = false;
                s += (double)(o - tr) * (o - tr);
            }
    render_target_destroy(&t);
    glDeleteTextures(1, &src);
    return sqrt(s / (3.0 * W / 2 * H));
}

/* Measured on llvmpipe: on the gradient, bilinear 0.0129, the cubic
 * 0.0122 (5% closer: the clamp to the two nearest texels flattens the
 * wave's crests as bilinear does); on the edge (point samples of a step,
 * which no filter can place better than a texel: both draw a ramp) both
 * 0.0428. The cubic must be 3% closer on the gradient (far outside float
 * rounding, 1e-6; about half what it gains) and no worse than 1% on the
 * edge (its steeper ramp is clamped, so it cannot ring). */
static void test_better_than_bilinear(void) {
    static float truth[W * H * 4];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) truth_at(x + 0.5, y + 0.5, truth + (y * W + x) * 4);
    upscaler *bil = upscale_create(&(upscale_desc){ .filter = UPSCALE_BILINEAR }, NULL);
    const char *err = NULL;
    upscaler *cub = upscale_create(NULL, &err);
    CHECK_MSG(!err, "%s", err ? err : "");
    CHECK_EQ(upscale_filter_used(cub), UPSCALE_CUBIC);
    bool finite = true;
    double eb = error_of(bil, truth, 1, &finite), ec = error_of(cub, truth, 1, &finite);
    double edge_b = error_of(bil, truth, 0, &finite), edge_c = error_of(cub, truth, 0, &finite);
    printf("4x up, RMSE against the truth: gradient: bilinear %.4f, cubic %.4f; edge: bilinear %.4f, cubic %.4f\n",
           eb, ec, edge_b, edge_c);
    CHECK_MSG(ec < 0.97 * eb, "the cubic (%.4f) is not 3%% closer than bilinear (%.4f) on the gradient", ec, eb);
    CHECK_MSG(edge_c < 1.01 * edge_b, "the cubic (%.4f) is worse than bilinear (%.4f) on the edge", edge_c, edge_b);
    CHECK_MSG(finite, "a non-finite value in the output");
    upscale_destroy(bil);
    upscale_destroy(cub);
}

/* Extremes (0 beside 10^4, an HDR highlight in a float canvas) give no
 * NaN or negative value: the clamp keeps every output within its texels. */
static void test_no_nan(void) {
    static float small[8 * 8 * 4], out[37 * 29 * 4];
    for (int i = 0; i < 8 * 8; i++)
        for (int c = 0; c < 4; c++) small[i * 4 + c] = (i * 7 + c) % 3 == 0 ? 1e4f : 0.0f;
    unsigned src = make_tex(GL_RGBA32F, 8, 8, GL_FLOAT, small);
    render_target t;
    CHECK(render_target_create(&t, 37, 29, true));
    upscaler *u = upscale_create(NULL, NULL);
    upscale_draw(u, src, 8, 8, t.fbo, (upscale_rect){ 0, 0, 37, 29 });
    CHECK(render_target_read(&t, out));
    int bad = 0;
    for (int i = 0; i < 37 * 29; i++)
        for (int c = 0; c < 3; c++) bad += !isfinite(out[i * 4 + c]) || out[i * 4 + c] < 0 || out[i * 4 + c] > 1e4f;
    CHECK_MSG(bad == 0, "%d values not finite or outside [0, 1e4]", bad);
    upscale_destroy(u);
    render_target_destroy(&t);
    glDeleteTextures(1, &src);
}

/* Only the rectangle is drawn: the rest keeps its clear colour exactly,
 * and the caller's viewport and scissor come back. */
static void test_rect_only(void) {
    static float small[20 * 10 * 4], out[W * H * 4];
    for (int i = 0; i < 20 * 10 * 4; i++) small[i] = (float)(i % 17) / 16.0f;
    unsigned src = make_tex(GL_RGBA32F, 20, 10, GL_FLOAT, small), fbo, tex;
    const float clear[4] = { 0.25f, 0.5f, 0.75f, 1.0f };
    make_target(GL_RGBA32F, W, H, &fbo, &tex, clear);
    upscale_rect r = { 30, 20, 150, 90 };
    glViewport(1, 2, 3, 4);
    glScissor(5, 6, 7, 8);
    upscaler *u = upscale_create(NULL, NULL);
    upscale_draw(u, src, 20, 10, fbo, r);
    GLint vp[4], sc[4];
    glGetIntegerv(GL_VIEWPORT, vp);
    glGetIntegerv(GL_SCISSOR_BOX, sc);
    CHECK(vp[0] == 1 && vp[1] == 2 && vp[2] == 3 && vp[3] == 4);
    CHECK(sc[0] == 5 && sc[1] == 6 && sc[2] == 7 && sc[3] == 8);
    CHECK(!glIsEnabled(GL_SCISSOR_TEST));
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_FLOAT, out);   /* row 0 = bottom, as the rect */
    int outside_changed = 0, inside_kept = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const float *p = out + (y * W + x) * 4;
            bool in = x >= r.x && x < r.x + r.w && y >= r.y && y < r.y + r.h;
            bool kept = p[0] == clear[0] && p[1] == clear[1] && p[2] == clear[2] && p[3] == clear[3];
            if (!in && !kept) outside_changed++;
            if (in && kept) inside_kept++;
        }
    CHECK_MSG(outside_changed == 0, "%d pixels outside the rectangle changed", outside_changed);
    CHECK_MSG(inside_kept < r.w * r.h / 100, "%d pixels inside the rectangle were not drawn", inside_kept);
    CHECK_EQ(glGetError(), GL_NO_ERROR);
    upscale_destroy(u);
    free_target(fbo, tex);
    glDeleteTextures(1, &src);
}

/* ---- the sharp world ---- */

/* The world: fine stripes (detail a 4x reduction cannot hold); the water:
 * a disc of a smooth gradient over it. */
static void world_at(double x, double y, unsigned char *rgba) {
    int stripe = ((int)(x / 3) + (int)(y / 5)) % 2;
    rgba[0] = (unsigned char)(stripe ? 200 : 40);
    rgba[1] = (unsigned char)(90 + (int)x % 64);
    rgba[2] = (unsigned char)(stripe ? 30 : 160);
    rgba[3] = 255;
}

static bool in_water(double x, double y) { return (x - 150) * (x - 150) + (y - 70) * (y - 70) < 50.0 * 50.0; }

static void scene_at(double x, double y, unsigned char *rgba) {
    if (!in_water(x, y)) { world_at(x, y, rgba); return; }
    rgba[0] = 20;
    rgba[1] = (unsigned char)(60 + x * 0.5);
    rgba[2] = (unsigned char)(120 + y * 0.6);
    rgba[3] = 255;
}

/* sRGB bytes to linear, for the error */
static double lin(unsigned char b) {
    double c = b / 255.0;
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

/* The window's case: sRGB canvas, snapshot and world, drawn into an sRGB
 * target with sRGB writes on. The reduced frame and its snapshot are point
 * samples at the reduced pixels' centres, as a renderer draws them. */
static void test_over_world(void) {
    enum { RW = W / F, RH = H / F };
    static unsigned char world[W * H * 4], truth[W * H * 4], small[RW * RH * 4], snap[RW * RH * 4];
    static unsigned char over[W * H * 4], blit_px[W * H * 4];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            world_at(x + 0.5, y + 0.5, world + (y * W + x) * 4);
            scene_at(x + 0.5, y + 0.5, truth + (y * W + x) * 4);
        }
    for (int y = 0; y < RH; y++)
        for (int x = 0; x < RW; x++) {
            scene_at((x + 0.5) * F, (y + 0.5) * F, small + (y * RW + x) * 4);
            world_at((x + 0.5) * F, (y + 0.5) * F, snap + (y * RW + x) * 4);
        }
    unsigned frame_tex = make_tex(GL_SRGB8_ALPHA8, RW, RH, GL_UNSIGNED_BYTE, small);
    unsigned snap_tex = make_tex(GL_SRGB8_ALPHA8, RW, RH, GL_UNSIGNED_BYTE, snap);
    unsigned world_tex = make_tex(GL_SRGB8_ALPHA8, W, H, GL_UNSIGNED_BYTE, world);
    unsigned fbo, tex;
    make_target(GL_SRGB8_ALPHA8, W, H, &fbo, &tex, (float[]){ 0, 0, 0, 1 });
    upscaler *u = upscale_create(&(upscale_desc){ .filter = UPSCALE_BILINEAR }, NULL);
    glEnable(GL_FRAMEBUFFER_SRGB);
    upscale_rect rect = { 0, 0, W, H };
    CHECK(upscale_draw_over_world(u, frame_tex, snap_tex, RW, RH, world_tex, fbo, rect));
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, over);
    upscale_draw(u, frame_tex, RW, RH, fbo, rect);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, blit_px);
    glDisable(GL_FRAMEBUFFER_SRGB);
    CHECK_EQ(glGetError(), GL_NO_ERROR);
    /* a pixel whose four nearest reduced texels are all world (or all
     * water): far enough from the disc's edge that no bilinear tap
     * crosses it, with a texel's margin for where the point samples fall */
    int world_px = 0, world_off = 0, water_px = 0, water_off = 0;
    double e_over = 0, e_blit = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double d = sqrt((x + 0.5 - 150) * (x + 0.5 - 150) + (y + 0.5 - 70) * (y + 0.5 - 70));
            const unsigned char *o = over + (y * W + x) * 4, *b = blit_px + (y * W + x) * 4;
            const unsigned char *wd = world + (y * W + x) * 4, *tr = truth + (y * W + x) * 4;
            bool inner = x >= F && x < W - F && y >= F && y < H - F;
            if (d > 50 + 2.5 * F && inner) {
                world_px++;
                world_off += memcmp(o, wd, 3) != 0;
            } else if (d < 50 - 2.5 * F) {
                water_px++;
                for (int c = 0; c < 3; c++) water_off += abs(o[c] - b[c]) > 1;   /* the blit's, to 8-bit rounding */
            }
            for (int c = 0; c < 3; c++) {
                e_over += (lin(o[c]) - lin(tr[c])) * (lin(o[c]) - lin(tr[c]));
                e_blit += (lin(b[c]) - lin(tr[c])) * (lin(b[c]) - lin(tr[c]));
            }
        }
    e_over = sqrt(e_over / (3.0 * W * H));
    e_blit = sqrt(e_blit / (3.0 * W * H));
    printf("sharp world, 4x: RMSE %.4f against the blit's %.4f; %d world pixels, %d off; %d water pixels, %d values off\n",
           e_over, e_blit, world_px, world_off, water_px, water_off);
    CHECK_GT(world_px, W * H / 2);
    CHECK_GT(water_px, 1000);
    CHECK_EQ(world_off, 0);
    CHECK_EQ(water_off, 0);
    /* the stripes are most of the blit's error, and the world's pixels
     * carry none: well under half (the disc's edge, a texel wide, remains) */
    CHECK_LT(e_over, 0.5 * e_blit);
    /* no snapshot: nothing drawn, the caller blits */
    CHECK(!upscale_draw_over_world(u, frame_tex, 0, RW, RH, world_tex, fbo, rect));
    upscale_destroy(u);
    free_target(fbo, tex);
    glDeleteTextures(1, &frame_tex);
    glDeleteTextures(1, &snap_tex);
    glDeleteTextures(1, &world_tex);
}

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    RUN(test_one_to_one_exact);
    RUN(test_better_than_bilinear);
    RUN(test_no_nan);
    RUN(test_rect_only);
    RUN(test_over_world);
    gl_ctx_destroy(ctx);
    return check_summary();
}
