/* render_msaa: anti-aliasing of the screen passes. render_frame.c draws a frame's
 * screen passes (those outside RenderToTexture) into a private
 * multisampled colour+depth target and resolves it into the caller's
 * framebuffer rectangle (glBlitFramebuffer); RenderToTexture passes stay
 * single-sample. The colour format follows the destination: 32-bit float
 * into a float target (EXR output keeps its precision), 16-bit float for a
 * world drawn to an 8-bit target (the window: linear radiance is resolved
 * linear and the window's sRGB encoding is applied by the resolve, as it
 * was by the draws), 8-bit otherwise. Private to the renderer (render*.c). */
#ifndef TARN_RENDER_MSAA_H
#define TARN_RENDER_MSAA_H

#include <stdbool.h>

typedef struct render_msaa {
    unsigned fbo, color, depth;
    int w, h, samples;
    unsigned format;          /* the colour's GL internal format */
    int max_samples;          /* GL_MAX_SAMPLES (0: not asked yet) */
    int default_samples;      /* what 0 asks for on this GL: RENDER_MSAA_DEFAULT, 1 on a CPU rasteriser */
} render_msaa;

/* The samples a request gives on this GL: 0 the default (RENDER_MSAA_DEFAULT
 * on a GPU, off on a CPU rasteriser such as llvmpipe, where it costs 3-4.5x
 * the frame), 1 off, else clamped to what the GL allows. */
int render_msaa_effective(render_msaa *m, int requested);

/* Binds the multisampled target for a w x h frame that will be resolved
 * into fbo (made or remade to fit), its viewport at the origin. False,
 * with nothing bound, when the frame is drawn single-sample: samples <= 1,
 * or the GL refuses the target. */
bool render_msaa_begin(render_msaa *m, int samples, unsigned fbo, int w, int h, bool linear);

/* Resolves the target into (x, y, w, h) of fbo and leaves fbo bound. */
void render_msaa_resolve(const render_msaa *m, unsigned fbo, int x, int y);

void render_msaa_free(render_msaa *m);

/* Where this GL samples with this many samples, as it reports them
 * (glGetMultisamplefv on a 1 x 1 multisampled target: x right, y UP in
 * the pixel), into pos[0..max); returns how many samples the GL gives (it
 * may give more than asked), 0 when it cannot say. Leaves the framebuffer
 * binding as it was. */
int render_msaa_positions(int samples, double (*pos)[2], int max);

/* The standard positions (Direct3D's, which GPUs and Mesa's llvmpipe use)
 * for 2, 4, 8 and 16 samples in the same y-up form; 0 for another count.
 * No GL needed. */
int render_msaa_standard_positions(int samples, double (*pos)[2], int max);

#endif
