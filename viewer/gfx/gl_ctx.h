/* gl_ctx: OpenGL contexts. Headless through EGL (no X server: the Mesa
 * surfaceless platform, or the EGL device platform on a GPU), or a GLFW
 * window. Both are OpenGL 4.5 compatibility contexts so glman shaders that
 * read gl_Vertex and gl_ModelViewMatrix work. */
#ifndef TARN_GL_CTX_H
#define TARN_GL_CTX_H

#include <stdbool.h>

typedef struct gl_ctx gl_ctx;

/* Creates a headless context and makes it current. NULL with a message that
 * says what is missing (no EGL vendor library, no driver, no OpenGL 4.5
 * compatibility context) and how to install it. */
gl_ctx *gl_ctx_create_headless(char *err, int errlen);

/* Creates a window of w x h and makes its context current. */
gl_ctx *gl_ctx_create_window(int w, int h, const char *title, char *err, int errlen);

void gl_ctx_destroy(gl_ctx *c);

/* The GLFWwindow* of a window context, NULL when headless. */
void *gl_ctx_window(gl_ctx *c);

/* true when the context is lost (a GPU reset, the driver restarted:
 * glGetGraphicsResetStatus; contexts are made with reset notification where
 * the driver offers it), with a message saying what happened and what to
 * do. Nothing can be drawn in a lost context: end with exit code 3. Call
 * it once a frame. TARN_SIMULATE_CONTEXT_LOSS=N in the environment makes
 * the check after the first N report a loss (tests). */
bool gl_ctx_lost(gl_ctx *c, char *err, int errlen);

/* "4.5 (Compatibility Profile) Mesa ... | llvmpipe ..." */
const char *gl_ctx_describe(gl_ctx *c);

/* true when the current context's GL_RENDERER is a rasteriser on the CPU
 * (llvmpipe, softpipe, SwiftShader, lavapipe): anti-aliasing costs 3-4.5x a
 * frame there (render_msaa.c) and shaders are built with TARN_CPU_RASTER
 * (packs/common/loops.glsl: loops kept rolled, compiles about twice as fast). */
bool gl_ctx_cpu_rasteriser(void);

/* true when a display can be opened (DISPLAY or WAYLAND_DISPLAY set). */
bool gl_ctx_have_display(void);

/* Can the current context draw a w x h frame of bytes_per_pixel (all its
 * targets together: colour, depth, samples)? No when a side is beyond the
 * GL's maximum (viewport, renderbuffer, texture) or the frame would take
 * more than a quarter of the machine's memory (issue #30: WindowSize 16000 16000
 * asked for 4.4 GB and 10.7 s a frame). False with the reason in why. */
bool gl_ctx_frame_fits(int w, int h, double bytes_per_pixel, char *why, int whylen);

#endif
