#include "world_snapshot.h"

#include <GL/gl.h>
#include <GL/glext.h>

void world_snapshot_frame(world_snapshot *s) { s->valid = false; }

void world_snapshot_free(world_snapshot *s) { render_target_destroy(&s->tg); }

/* The kind of target a raw copy of fbo's colour needs: 8-bit sRGB, float
 * (a 16-bit screen widens exactly), or 8-bit linear. */
typedef enum { KIND_PLAIN, KIND_SRGB, KIND_FLOAT } kind;

static kind screen_kind(unsigned fbo) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    GLint enc = GL_LINEAR, type = GL_UNSIGNED_NORMALIZED;
    glGetFramebufferAttachmentParameteriv(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                          GL_FRAMEBUFFER_ATTACHMENT_COLOR_ENCODING, &enc);
    glGetFramebufferAttachmentParameteriv(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                          GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &type);
    return type == GL_FLOAT ? KIND_FLOAT : enc == GL_SRGB ? KIND_SRGB : KIND_PLAIN;
}

/* The target, of kind k and at least w x h (grown, never shrunk, so the
 * budget's sizes do not make a new one each). */
static bool ensure(world_snapshot *s, kind k, int w, int h) {
    render_target *t = &s->tg;
    kind have = t->is_float ? KIND_FLOAT : t->is_srgb ? KIND_SRGB : KIND_PLAIN;
    if (t->fbo && have == k && t->w >= w && t->h >= h) return true;
    if (t->fbo && have == k) {
        w = t->w > w ? t->w : w;
        h = t->h > h ? t->h : h;
    }
    render_target_destroy(t);
    return k == KIND_SRGB ? render_target_create_srgb(t, w, h) : render_target_create(t, w, h, k == KIND_FLOAT);
}

void world_snapshot_take(world_snapshot *s, unsigned fbo, int x, int y, int w, int h) {
    if (!s->on || fbo == 0 || w <= 0 || h <= 0) return;
    GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST), srgb = glIsEnabled(GL_FRAMEBUFFER_SRGB);
    if (ensure(s, screen_kind(fbo), w, h)) {
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_FRAMEBUFFER_SRGB);   /* the values as stored: no decode, no encode */
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, s->tg.fbo);
        glBlitFramebuffer(x, y, x + w, y + h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        s->w = w;
        s->h = h;
        s->valid = true;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    if (scissor) glEnable(GL_SCISSOR_TEST);
    if (srgb) glEnable(GL_FRAMEBUFFER_SRGB);
}
