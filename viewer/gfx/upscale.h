/* upscale: the windows' reduced frame brought up to the window's size.
 *
 * While time runs or the camera moves, the frame budget (ui/res_budget.h)
 * draws the scene at a fraction of the window's size; this module
 * enlarges that frame into a rectangle of the window. It replaces a
 * bilinear glBlitFramebuffer, which turns every reduced pixel into a soft
 * square.
 *
 * The filter (UPSCALE_CUBIC, the default) is separable, two fragment
 * passes (shaders/upscale.frag): the frame's rows to the destination's
 * width, then the columns to its height. Per output pixel and axis:
 *   - a cubic through the 4 nearest texels (Keys' family: Catmull-Rom with no
 *     sharpening, which interpolates and keeps an edge's slope
 *     where bilinear halves it; sharper as `sharpness` grows);
 *   - deringing: clamped to the range of the 2 nearest texels, so neither
 *     the negative lobes nor the sharpening overshoot what the reduced
 *     frame saw: the contrast the sharpening adds is bounded by the
 *     contrast that is there (no halos on the horizon or the shore).
 * Why not AMD FSR 1's EASU + RCAS, or a 2D edge-directed kernel: on the
 * CPU rasteriser the window runs on (llvmpipe) the cost is the texel
 * reads at the window's size; a 12-tap edge-directed pass measured 58 ms
 * at 960x540 (the blit ~10 ms, the whole budget 50 ms) and a 5-read 2D
 * Catmull-Rom 25-30 ms; the separable cubic reads 4 texels per output
 * pixel (+ 4 per pixel of the rect.w x src_h middle), about twice the
 * blit (docs/architecture.md has the figures).
 * UPSCALE_BILINEAR is today's glBlitFramebuffer(GL_LINEAR), kept for
 * comparison (viewer/tools/bench_upscale.c) and as the fallback when the
 * shader cannot be built.
 *
 * Colour: texels are fetched through the texture's format and written
 * through the framebuffer's, as a blit does. An sRGB texture is decoded to
 * linear on fetch (once per texel of the first pass, whose middle target
 * is 16-bit float linear) and, with GL_FRAMEBUFFER_SRGB enabled by the
 * caller, encoded on write: the filter works in linear light (the window's
 * world canvas), as the blit did. A plain RGBA8 texture (a glman scene,
 * drawn without sRGB) is filtered as the values it holds.
 *
 * 1:1 (source size = destination size) is a glBlitFramebuffer with
 * GL_NEAREST, whatever the filter: the full-resolution frame is copied bit
 * for bit, as before.
 *
 *     upscaler *u = upscale_create(NULL, &err);      (a current GL context)
 *     each frame: upscale_draw(u, canvas_tex, rw, rh, 0, (upscale_rect){ x, y, w, h });
 *     upscale_destroy(u);
 *
 * GL 3.3. Pixels outside the destination rectangle are not touched. */
#ifndef TARN_UPSCALE_H
#define TARN_UPSCALE_H

#include <stdbool.h>

typedef enum upscale_filter {
    UPSCALE_CUBIC = 0,     /* the separable sharpened cubic, deringed (default) */
    UPSCALE_BILINEAR,      /* glBlitFramebuffer(GL_LINEAR): the window before this module */
} upscale_filter;

/* Zero means default for every field. */
typedef struct upscale_desc {
    upscale_filter filter;
    /* The cubic's sharpening, 0..1: Keys' a = -0.5 - 0.5 sharpness
     * (-0.5 Catmull-Rom, -1 the sharpest); 0: UPSCALE_SHARPNESS_DEFAULT,
     * negative: none (Catmull-Rom). */
    float sharpness;
} upscale_desc;

/* Measured (viewer/tools/bench_upscale.c): a = -0.75, the cubic most
 * image libraries default to; at 0.19 of a side it lowers RMSE a little
 * more than Catmull-Rom, FLIP a little less; 1 lowers RMSE more and FLIP
 * less still. */
#define UPSCALE_SHARPNESS_DEFAULT 0.5f

typedef struct upscaler upscaler;

/* A destination rectangle in framebuffer pixels, origin bottom-left. */
typedef struct upscale_rect { int x, y, w, h; } upscale_rect;

/* Builds the pass in the current GL context. NULL desc: all defaults. When
 * the shader cannot be built (a GL without 3.3), the upscaler still works
 * as UPSCALE_BILINEAR and *err (if given) says why; it never returns NULL. */
upscaler *upscale_create(const upscale_desc *desc, const char **err);
void upscale_destroy(upscaler *u);

/* The filter in use: the desc's, or UPSCALE_BILINEAR after a failed build. */
upscale_filter upscale_filter_used(const upscaler *u);

/* Draws the bottom-left src_w x src_h texels of the 2D texture src_tex,
 * enlarged (or copied at 1:1) into rect of the framebuffer dst_fbo (0: the
 * window). The source's texels beyond src_w x src_h are never read, so a
 * canvas larger than the frame it holds is fine. Leaves dst_fbo bound
 * (GL_FRAMEBUFFER), the viewport and scissor as the caller had them, no
 * program and no vertex array bound, the active texture unit 0 with no
 * texture bound; GL_FRAMEBUFFER_SRGB is the caller's. */
void upscale_draw(upscaler *u, unsigned src_tex, int src_w, int src_h, unsigned dst_fbo, upscale_rect rect);

/* The sharp world: the reduced frame's water over a full-resolution world.
 * While the clock runs and the camera stands still, the static world (sky,
 * land and objects above the water) does not change, so the window keeps
 * it at full resolution (full_tex: rect.w x rect.h texels, drawn by
 * render_frame_world_at) and enlarges only what the scene drew over its
 * World in the reduced frame: a pixel of src_tex that differs from the
 * same pixel of world_tex (the frame's screen right after its World,
 * render_world_snapshot, the same size and format) is the water's. Two
 * passes: the water premultiplied by its share at the frame's size, then
 * each window pixel the bilinear water over the full world. Where the
 * frame is all world this is full_tex bit for bit; where it is all water,
 * the bilinear blit's picture. Same colour rules and GL state as
 * upscale_draw. false (nothing drawn): a texture missing or the programs
 * not built (the caller then calls upscale_draw). */
bool upscale_draw_over_world(upscaler *u, unsigned src_tex, unsigned world_tex, int src_w, int src_h,
                             unsigned full_tex, unsigned dst_fbo, upscale_rect rect);

#endif
