/* What the GL tests share: the headless context they run in (or the skip
 * when the machine has none), and the flat-colour program they draw with.
 * Header-only, like support.h; include it after gl_ctx.h. */
#ifndef TARN_TEST_GL_SUPPORT_H
#define TARN_TEST_GL_SUPPORT_H

#include <stdio.h>
#include <string.h>
#include "gl_ctx.h"
#include "render.h"
#include "unif.h"

/* The test's exit code when it cannot run: ctest's SKIP_RETURN_CODE. */
#define GL_TEST_SKIP 77

/* A headless OpenGL context, or NULL after printing "skip: why" (the test
 * then returns GL_TEST_SKIP). */
static inline gl_ctx *gl_test_context(void) {
    char err[512];
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    if (!ctx) fprintf(stderr, "skip: %s\n", err);
    return ctx;
}

/* A program that draws the geometry in uniform vec4 uColor. */
static const char *const flat_vert =
    "#version 330 compatibility\n"
    "void main() { gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; }\n";

static const char *const flat_frag =
    "#version 330 compatibility\n"
    "uniform vec4 uColor;\n"
    "out vec4 fragColor;\n"
    "void main() { fragColor = uColor; }\n";

/* The entry `name` (a slider, colour, checkbox or Define) of Program
 * `program` of r's scene (NULL: of the first Program that has it), or NULL. */
static inline unif_entry *gl_test_uniform(render *r, const char *program, const char *name) {
    int n;
    unif_set *sets = render_uniforms(r, &n);
    for (int i = 0; i < n; i++) {
        if (program && strcmp(sets[i].program, program) != 0) continue;
        unif_entry *e = unif_find(&sets[i], name);
        if (e) return e;
    }
    return NULL;
}

#endif
