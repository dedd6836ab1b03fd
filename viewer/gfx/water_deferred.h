/* water_deferred: the screen's water shaded once a pixel.
 *
 * A CPU rasteriser (llvmpipe) runs a fragment shader on blocks of pixels,
 * and every triangle that touches a block pays for all of it: the water
 * grid's far triangles cover a few pixels each, so the pack's heavy water
 * shader ran 1.3-1.5 times a water pixel (scene/glsl_deferred.h has the
 * figures). Deferred, the `WaterSurface` on the screen is two passes:
 *
 *  1. the grid, through the program's own vertex shader, into a G-buffer
 *     (the program's fragment inputs, RGBA32F) with the screen's own depth
 *     and stencil: the depth test as the glib set it, the depth written as
 *     before, stencil 1 where water was drawn;
 *  2. one full-screen triangle into the screen with the program's fragment
 *     shader reading its inputs back (glsl_deferred's "shade"), the
 *     stencil test passing only the water's pixels: llvmpipe skips a block
 *     the early stencil test empties, so no pixel but water's is shaded.
 *
 * Only where nothing changes but the cost: a single-sample framebuffer of
 * the renderer's own with a stencil buffer (not the window system's, not
 * MSAA, not a RenderToTexture pass), a program of a vertex and a fragment
 * stage that glsl_deferred can split, polygons filled, and a world without
 * the spectrum ocean (whose normals are filtered by each pixel's
 * footprint: beside a fold of its crests the shade pass's derivatives
 * difference two parts of the surface, +1.1% water error; the caller says
 * so, calls.keep_grid). Elsewhere, and where either pass's program does
 * not build, the caller draws the grid as before. The pixels are the grid's but at the water's edge (glsl_deferred.h:
 * derivatives), and where the glib blends the water (each pixel once here,
 * as often as triangles overlap there). Private to the renderer. */
#ifndef TARN_WATER_DEFERRED_H
#define TARN_WATER_DEFERRED_H

#include <stdbool.h>

#include "glsl_deferred.h"
#include "render_prog.h"

typedef struct water_deferred {
    bool off;                             /* render_set_deferred_water(false) */
    unsigned fbo, vao;
    unsigned tex[GLSL_DEFERRED_MAX_TEX];
    int tex_w, tex_h, ntex;               /* the G-buffer textures made */
    unsigned depth_rb;                    /* the screen depth-stencil attached to fbo */
    long draws;                           /* water drawn deferred */
    long stamp;                           /* this draw's (glsl_deferred.stamped), 1..2^24-1 */
    const char *skip_why;                 /* the last draw's reason to keep the grid (calls.keep_grid,
                                           * the framebuffer's, turned off), or NULL */
} water_deferred;

/* What the caller does for each pass's program: its uniforms (the
 * program's values, the world's, the cameras') and the grid. */
typedef struct water_deferred_calls {
    void (*upload)(unsigned program, void *user);
    void (*draw_grid)(int tangent_loc, void *user);
    void *user;
    const char *keep_grid;   /* the scene's reason to keep the grid (NULL: none) */
} water_deferred_calls;

void water_deferred_init(water_deferred *d);
void water_deferred_free(water_deferred *d);

/* Draws the water of p (the bound program) into the bound draw
 * framebuffer's viewport deferred, and returns true; false, having drawn
 * and changed nothing, where it cannot (above), p's split being made at
 * its first call for p's build. GL state is as it found it after. */
bool water_deferred_draw(water_deferred *d, prog *p, const water_deferred_calls *calls);

#endif
