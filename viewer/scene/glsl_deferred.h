/* glsl_deferred: a water fragment shader split for deferred shading.
 *
 * On a CPU rasteriser (Mesa's llvmpipe) a fragment shader runs on blocks
 * of pixels, and a triangle that covers a few pixels of a block pays for
 * the whole block: the water grid's far triangles, a few pixels each,
 * shaded the lake's water 1.3-1.5 times over (its water pass 98 ms at 128
 * cells a side, 64 ms at 32, of which the vertices ~10 and ~4). So the
 * screen's water is drawn in two passes (gfx/water_deferred.h): the grid
 * with a fragment shader that only stores its inputs (the G-buffer), then
 * one full-screen triangle that runs the pack's shader once a pixel where
 * the grid was drawn.
 *
 * glsl_deferred_split makes both fragment shaders from the pack's
 * assembled fragment text:
 *   gbuffer  the #version line, the shader's input declarations as
 *            written, and a main() that packs every input component (a
 *            float as it is, an int or uint by its bits) into RGBA32F
 *            outputs 0..ntex-1;
 *   shade    the shader as written (its comments blank) with each input
 *            declaration turned into a global of its type (on its line:
 *            the #line mapping still names the user's file:line), every
 *            main() renamed, and a main() that reads the globals back from
 *            samplers tarn_dfr_g0..g(ntex-1) at gl_FragCoord and calls it.
 * gl_FragCoord (its z and w) and gl_FrontFacing, which differ in a
 * full-screen pass, are stored too and read back in their place.
 *
 * What it cannot split (the reason in why): GLSL before 330, an input
 * block, an input inside #if (which inputs the stage has is the
 * preprocessor's), a type other than float, int, uint and their vectors,
 * more than GLSL_DEFERRED_MAX_COMPONENTS components, the compatibility
 * profile's built-in inputs (gl_Color, gl_TexCoord...), gl_FragDepth,
 * per-sample or per-primitive inputs and interpolateAt*. The caller then
 * draws the water as before.
 *
 * Derivatives (dFdx, fwidth, a texture()'s implicit level) in the shade
 * pass difference neighbouring pixels' stored inputs: the same as the
 * grid's inside a triangle, the surface's own across triangles, and
 * against a cleared texel (0) at the water's edge, where a pixel beside
 * the shore or an object takes a wider footprint.
 * Pure C, no GL. */
#ifndef TARN_GLSL_DEFERRED_H
#define TARN_GLSL_DEFERRED_H

#include <stdbool.h>

#define GLSL_DEFERRED_MAX_TEX 7
#define GLSL_DEFERRED_MAX_COMPONENTS (4 * GLSL_DEFERRED_MAX_TEX)

typedef struct glsl_deferred {
    char *gbuffer;   /* heap; NULL when not split */
    char *shade;     /* heap; NULL when not split */
    int ntex;        /* RGBA32F targets the G-buffer writes (1..GLSL_DEFERRED_MAX_TEX) */
    int ncomp;       /* components stored */
    bool stamped;    /* a spare slot (the last texture's w) holds uniform tarn_dfr_stamp: the shade
                      * pass reads a texel whose stamp is not its own as a cleared one (0), so the
                      * G-buffer needs no clear a draw (the stencil's still) */
    char version[96];  /* the #version line (the full-screen triangle's vertex shader takes it) */
    char why[160];   /* why it was not split */
} glsl_deferred;

/* Splits frag (a fragment stage's assembled text). false: out->why says
 * why, and nothing is allocated. */
bool glsl_deferred_split(const char *frag, glsl_deferred *out);
void glsl_deferred_free(glsl_deferred *d);

#endif
