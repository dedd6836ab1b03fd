/* render_msaa: the multisampled target of the screen passes (see
 * render_msaa.h). */
#include "render_msaa.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <string.h>

#include "gl_ctx.h"
#include "render.h"

int render_msaa_effective(render_msaa *m, int requested) {
    if (!m->max_samples) {
        GLint v = 0;
        glGetIntegerv(GL_MAX_SAMPLES, &v);
        m->max_samples = v > 1 ? v : 1;
        m->default_samples = gl_ctx_cpu_rasteriser() ? 1 : RENDER_MSAA_DEFAULT;
    }
    int n = requested > 0 ? requested : m->default_samples;
    if (n <= 1) return 1;
    return n < m->max_samples ? n : m->max_samples;
}

/* The colour format that keeps what the destination keeps (see the header). */
static GLenum format_for(unsigned fbo, bool linear) {
    GLint type = GL_NONE, bits = 8;
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    GLenum att = fbo ? GL_COLOR_ATTACHMENT0 : GL_BACK_LEFT;
    glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &type);
    glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_RED_SIZE, &bits);
    while (glGetError() != GL_NO_ERROR) {}   /* a surfaceless default framebuffer has no colour to ask about */
    if (type == GL_FLOAT) return bits > 16 ? GL_RGBA32F : GL_RGBA16F;
    return linear ? GL_RGBA16F : GL_RGBA8;
}

static bool make(render_msaa *m, int samples, int w, int h, GLenum format) {
    render_msaa_free(m);
    glGenRenderbuffers(1, &m->color);
    glBindRenderbuffer(GL_RENDERBUFFER, m->color);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, w, h);
    glGenRenderbuffers(1, &m->depth);
    glBindRenderbuffer(GL_RENDERBUFFER, m->depth);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, w, h);
    glGenFramebuffers(1, &m->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, m->fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, m->color);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, m->depth);
    bool ok = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE && glGetError() == GL_NO_ERROR;
    if (!ok) { render_msaa_free(m); return false; }
    m->w = w;
    m->h = h;
    m->samples = samples;
    m->format = format;
    return true;
}

bool render_msaa_begin(render_msaa *m, int samples, unsigned fbo, int w, int h, bool linear) {
    if (samples <= 1 || w <= 0 || h <= 0) return false;
    GLenum format = format_for(fbo, linear);
    bool fits = m->fbo && m->w == w && m->h == h && m->samples == samples && m->format == format;
    if (!fits && !make(m, samples, w, h, format)) {
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        return false;   /* drawn without: a GL that cannot is no reason to draw nothing */
    }
    glBindFramebuffer(GL_FRAMEBUFFER, m->fbo);
    glViewport(0, 0, w, h);
    return true;
}

void render_msaa_resolve(const render_msaa *m, unsigned fbo, int x, int y) {
    glDisable(GL_SCISSOR_TEST);   /* a blit is scissored */
    glBindFramebuffer(GL_READ_FRAMEBUFFER, m->fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glBlitFramebuffer(0, 0, m->w, m->h, x, y, x + m->w, y + m->h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
}

void render_msaa_free(render_msaa *m) {
    if (m->fbo) glDeleteFramebuffers(1, &m->fbo);
    if (m->color) glDeleteRenderbuffers(1, &m->color);
    if (m->depth) glDeleteRenderbuffers(1, &m->depth);
    int max = m->max_samples, def = m->default_samples;
    memset(m, 0, sizeof *m);
    m->max_samples = max;
    m->default_samples = def;
}

int render_msaa_positions(int samples, double (*pos)[2], int max) {
    if (samples <= 1) return 0;
    while (glGetError() != GL_NO_ERROR) {}
    GLint prev = 0;
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &prev);
    GLuint rb = 0, fbo = 0;
    glGenRenderbuffers(1, &rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, 1, 1);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    GLint n = 0;
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE) glGetIntegerv(GL_SAMPLES, &n);
    for (int i = 0; i < n && i < max; i++) {
        GLfloat v[2] = { 0.5f, 0.5f };
        glGetMultisamplefv(GL_SAMPLE_POSITION, (GLuint)i, v);
        pos[i][0] = v[0];
        pos[i][1] = v[1];
    }
    if (glGetError() != GL_NO_ERROR) n = 0;
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)prev);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &rb);
    return n > 1 ? n : 0;
}

/* Direct3D's standard sample patterns in 1/16 pixel from the centre; GL
 * implementations report them as (0.5 + x / 16, 0.5 + y / 16). */
static const signed char STD2[2][2] = { { 4, 4 }, { -4, -4 } };
static const signed char STD4[4][2] = { { -2, -6 }, { 6, -2 }, { -6, 2 }, { 2, 6 } };
static const signed char STD8[8][2] = { { 1, -3 }, { -1, 3 }, { 5, 1 }, { -3, -5 },
                                        { -5, 5 }, { -7, -1 }, { 3, 7 }, { 7, -7 } };
static const signed char STD16[16][2] = { { 1, 1 }, { -1, -3 }, { -3, 2 }, { 4, -1 }, { -5, -2 }, { 2, 5 },
                                          { 5, 3 }, { 3, -5 }, { -2, 6 }, { 0, -7 }, { -4, -6 }, { -6, 4 },
                                          { -8, 0 }, { 7, -4 }, { 6, 7 }, { -7, -8 } };

int render_msaa_standard_positions(int samples, double (*pos)[2], int max) {
    const signed char(*t)[2] = samples == 2 ? STD2 : samples == 4 ? STD4 : samples == 8 ? STD8
                                : samples == 16 ? STD16 : NULL;
    if (!t) return 0;
    for (int i = 0; i < samples && i < max; i++) {
        pos[i][0] = 0.5 + t[i][0] / 16.0;
        pos[i][1] = 0.5 + t[i][1] / 16.0;
    }
    return samples;
}
