/* render_target: offscreen colour+depth framebuffers for headless
 * rendering, and the loaded scene's render targets as they are now
 * (render.h). */
#include "util.h"
#include "render_internal.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"

int render_targets(const render *r, render_target_info *out, int max) {
    const scene_state *s = &r->cur;
    int n = 0;
    for (int i = 0; s->glib && i < s->glib->ncmds; i++) {
        const glib_cmd *c = &s->glib->cmds[i];
        if (c->kind != GLIB_CMD_TEXTURE2D_EMPTY || s->cmd_res[i] < 0) continue;
        const gpu_tex *t = &s->texs[s->cmd_res[i]];
        if (!t->tex || !t->render_target) continue;
        if (n < max)
            out[n] = (render_target_info){ .unit = t->unit, .w = t->w, .h = t->h, .tex = t->tex,
                                           .is_float = t->format == GLIB_TARGET_RGBA16F || t->format == GLIB_TARGET_RGBA32F,
                                           .is_depth = t->format == GLIB_TARGET_DEPTH, .file = c->file, .line = c->line };
        n++;
    }
    return n;
}

/* One colour+depth framebuffer, its colour in `internal` (given as `type`). */
static bool target_create(render_target *t, int w, int h, unsigned internal, unsigned type) {
    glGenTextures(1, &t->color);
    glBindTexture(GL_TEXTURE_2D, t->color);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, w, h, 0, GL_RGBA, type, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    glGenRenderbuffers(1, &t->depth);
    glBindRenderbuffer(GL_RENDERBUFFER, t->depth);
    /* with stencil: the deferred water marks its pixels (water_deferred.h) */
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, w, h);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glGenFramebuffers(1, &t->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t->color, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, t->depth);
    bool ok = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (!ok) render_target_destroy(t);
    return ok;
}

bool render_target_create(render_target *t, int w, int h, bool is_float) {
    *t = (render_target){ .w = w, .h = h, .is_float = is_float };
    return target_create(t, w, h, is_float ? GL_RGBA32F : GL_RGBA8, is_float ? GL_FLOAT : GL_UNSIGNED_BYTE);
}

bool render_target_create_srgb(render_target *t, int w, int h) {
    *t = (render_target){ .w = w, .h = h, .is_srgb = true };
    return target_create(t, w, h, GL_SRGB8_ALPHA8, GL_UNSIGNED_BYTE);
}

void render_target_destroy(render_target *t) {
    if (t->fbo) glDeleteFramebuffers(1, &t->fbo);
    if (t->color) glDeleteTextures(1, &t->color);
    if (t->depth) glDeleteRenderbuffers(1, &t->depth);
    memset(t, 0, sizeof *t);
}

bool render_target_read(const render_target *t, float *rgba) {
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, t->w, t->h, GL_RGBA, GL_FLOAT, rgba);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    /* GL's row 0 is the bottom; files start at the top */
    size_t row = (size_t)t->w * 4;
    float *tmp = mem_alloc(row * sizeof(float));
    for (int y = 0; y < t->h / 2; y++) {
        float *a = rgba + (size_t)y * row, *b = rgba + (size_t)(t->h - 1 - y) * row;
        memcpy(tmp, a, row * sizeof(float));
        memcpy(a, b, row * sizeof(float));
        memcpy(b, tmp, row * sizeof(float));
    }
    free(tmp);
    return glGetError() == GL_NO_ERROR;
}
