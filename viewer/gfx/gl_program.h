/* gl_program: a GL program linked from a vertex and a fragment text, for
 * tarn's own passes (the upscaler, the deferred water); a glib's `Program`
 * is render_prog.h's, with its messages mapped to the user's files. */
#ifndef TARN_GL_PROGRAM_H
#define TARN_GL_PROGRAM_H

#include <stddef.h>

/* The linked program, or 0 with why (up to whylen) saying which stage
 * failed and the driver's first words; what names the program in it.
 * glman's Tangent attribute is bound to 6, as render_prog.c binds it. */
unsigned gl_program_link(const char *vert, const char *frag, const char *what, char *why, size_t whylen);

/* A vertex shader (heap) of one triangle covering the viewport, drawn with
 * glDrawArrays(GL_TRIANGLES, 0, 3) and no vertex buffer, in version (a
 * `#version ...` line, without its newline). */
char *gl_program_fullscreen_vert(const char *version);

#endif
