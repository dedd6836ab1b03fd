#include "world_snapshot.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <string.h>

void world_snapshot_frame(world_snapshot *s) { s->valid = false; }

void world_snapshot_free(world_snapshot *s) {
    if (s->fbo) glDeleteFramebuffers(1, &s->fbo);
    if (s->tex) glDeleteTextures(1, &s->tex);
    bool on = s->on;
    memset(s, 0, sizeof *s);
    s->on = on;
}

/* The internal format of fbo's first colour attachment, as far as a raw
 * copy needs it: 8-bit sRGB, 8-bit linear, or 16/32-bit float. */
static unsigned screen_format(unsigned fbo) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    GLint enc = GL_LINEAR, type = GL_UNSIGNED_NORMALIZED, bits = 8;
    GLenum a = fbo ? GL_COLOR_ATTACHMENT0 : GL_BACK_LEFT;
    glGetFramebufferAttachmentParameteriv(GL_READ_FRAMEBUFFER, a, GL_FRAMEBUFFER_ATTACHMENT_COLOR_ENCODING, &enc);
    glGetFramebufferAttachmentParameteriv(GL_READ_FRAMEBUFFER, a, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &type);
    glGetFramebufferAttachmentParameteriv(GL_READ_FRAMEBUFFER, a, GL_FRAMEBUFFER_ATTACHMENT_RED_SIZE, &bits);
    if (type == GL_FLOAT) return bits > 16 ? GL_RGBA32F : GL_RGBA16F;
    return enc == GL_SRGB ? GL_SRGB8_ALPHA8 : GL_RGBA8;
}

/* A texture of the format, at least w x h (grown, never shrunk). */
static bool ensure(world_snapshot *s, unsigned format, int w, int h) {
    if (s->tex && s->format == format && s->tex_w >= w && s->tex_h >= h) return true;
    if (s->tex) glDeleteTextures(1, &s->tex);
    if (!s->fbo) glGenFramebuffers(1, &s->fbo);
    w = s->format == format && s->tex_w > w ? s->tex_w : w;
    h = s->format == format && s->tex_h > h ? s->tex_h : h;
    glGenTextures(1, &s->tex);
    glBindTexture(GL_TEXTURE_2D, s->tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, format, w, h);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, s->fbo);
    glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, s->tex, 0);
    bool ok = glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    s->format = format;
    s->tex_w = ok ? w : 0;
    s->tex_h = ok ? h : 0;
    return ok;
}

void world_snapshot_take(world_snapshot *s, unsigned fbo, int x, int y, int w, int h) {
    if (!s->on || fbo == 0 || w <= 0 || h <= 0) return;
    GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST), srgb = glIsEnabled(GL_FRAMEBUFFER_SRGB);
    if (ensure(s, screen_format(fbo), w, h)) {
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_FRAMEBUFFER_SRGB);   /* the values as stored: no decode, no encode */
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, s->fbo);
        glBlitFramebuffer(x, y, x + w, y + h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        s->w = w;
        s->h = h;
        s->valid = true;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    if (scissor) glEnable(GL_SCISSOR_TEST);
    if (srgb) glEnable(GL_FRAMEBUFFER_SRGB);
}
