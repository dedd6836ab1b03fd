#include "world_cache.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <string.h>

void world_cache_init(world_cache *c) {
    memset(c, 0, sizeof *c);
    for (int i = 0; i < WORLD_CACHE_SLOTS; i++) c->slot[i].cmd = -1;
}

static void slot_free(world_cache_slot *s) {
    if (s->fbo) glDeleteFramebuffers(1, &s->fbo);
    if (s->color_rb) glDeleteRenderbuffers(1, &s->color_rb);
    if (s->depth_rb) glDeleteRenderbuffers(1, &s->depth_rb);
    memset(s, 0, sizeof *s);
    s->cmd = -1;
}

void world_cache_free(world_cache *c) {
    for (int i = 0; i < WORLD_CACHE_SLOTS; i++) slot_free(&c->slot[i]);
}

void world_cache_key_init(world_cache_key *k) { memset(k, 0, sizeof *k); }

/* The internal format of a colour attachment of the bound draw framebuffer,
 * from its sizes and type (the window's own buffers have no name to ask):
 * the cache keeps the same format, so the copies are exact. 0: unknown. */
static unsigned color_format(GLenum att) {
    GLint type = GL_NONE, r = 0, g = 0, b = 0, a = 0, comp = 0;
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    if (type == GL_NONE) return 0;
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_RED_SIZE, &r);
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_GREEN_SIZE, &g);
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_BLUE_SIZE, &b);
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_ALPHA_SIZE, &a);
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &comp);
    if (comp == GL_FLOAT && r == 32 && g == 32 && b == 32) return a == 32 ? GL_RGBA32F : a == 0 ? GL_RGB32F : 0;
    if (comp == GL_FLOAT && r == 16 && g == 16 && b == 16) return a == 16 ? GL_RGBA16F : a == 0 ? GL_RGB16F : 0;
    if (comp == GL_UNSIGNED_NORMALIZED && r == 8 && g == 8 && b == 8) return a == 8 ? GL_RGBA8 : a == 0 ? GL_RGB8 : 0;
    if (comp == GL_UNSIGNED_NORMALIZED && r == 16 && g == 16 && b == 16 && a == 16) return GL_RGBA16;
    if (comp == GL_UNSIGNED_NORMALIZED && r == 10 && g == 10 && b == 10 && a == 2) return GL_RGB10_A2;
    return 0;
}

static unsigned depth_format(GLenum att) {
    GLint type = GL_NONE, d = 0, s = 0, comp = 0;
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    if (type == GL_NONE) return 0;
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &d);
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_STENCIL_SIZE, &s);
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &comp);
    if (d == 0) return 0;
    if (comp == GL_FLOAT) return d == 32 ? (s == 8 ? GL_DEPTH32F_STENCIL8 : s == 0 ? GL_DEPTH_COMPONENT32F : 0) : 0;
    if (d == 24) return s == 8 ? GL_DEPTH24_STENCIL8 : s == 0 ? GL_DEPTH_COMPONENT24 : 0;
    if (s != 0) return 0;
    return d == 16 ? GL_DEPTH_COMPONENT16 : d == 32 ? GL_DEPTH_COMPONENT32 : 0;
}

static void key_state(world_cache_key *k) {
    glGetFloatv(GL_MODELVIEW_MATRIX, k->modelview);
    glGetFloatv(GL_PROJECTION_MATRIX, k->projection);
    GLint vp[4];
    glGetIntegerv(GL_VIEWPORT, vp);
    k->vp_w = vp[2];
    k->vp_h = vp[3];
    /* a function counts only while enabled: a frame's first World must not
     * miss because the last frame left another blend function behind */
    k->cull = glIsEnabled(GL_CULL_FACE);
    if (k->cull) {
        glGetIntegerv(GL_CULL_FACE_MODE, &k->cull_mode);
        glGetIntegerv(GL_FRONT_FACE, &k->front_face);
    }
    k->depth_test = glIsEnabled(GL_DEPTH_TEST);
    if (k->depth_test) glGetIntegerv(GL_DEPTH_FUNC, &k->depth_func);
    k->blend = glIsEnabled(GL_BLEND);
    if (k->blend) {
        glGetIntegerv(GL_BLEND_SRC_RGB, &k->blend_func[0]);
        glGetIntegerv(GL_BLEND_DST_RGB, &k->blend_func[1]);
        glGetIntegerv(GL_BLEND_SRC_ALPHA, &k->blend_func[2]);
        glGetIntegerv(GL_BLEND_DST_ALPHA, &k->blend_func[3]);
        glGetIntegerv(GL_BLEND_EQUATION_RGB, &k->blend_eq[0]);
        glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &k->blend_eq[1]);
    }
    glGetIntegerv(GL_POLYGON_MODE, k->polygon_mode);
}

static void key_textures(world_cache_key *k, int albedo_unit, int sky_unit) {
    GLint active;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    glActiveTexture(GL_TEXTURE0 + (GLenum)albedo_unit);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &k->tex_units[0]);
    glActiveTexture(GL_TEXTURE0 + (GLenum)sky_unit);
    glGetIntegerv(GL_TEXTURE_BINDING_CUBE_MAP, &k->tex_units[1]);
    glActiveTexture((GLenum)active);
}

bool world_cache_key_gl(world_cache_key *k, int albedo_unit, int sky_unit) {
    GLint fbo = 0, db0 = GL_NONE, db1 = GL_NONE;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    glGetIntegerv(GL_DRAW_BUFFER0, &db0);
    glGetIntegerv(GL_DRAW_BUFFER1, &db1);
    if (db1 != GL_NONE) return false;   /* the world writes one colour: the others would be undefined */
    GLenum catt = (GLenum)db0;
    if (fbo == 0) catt = db0 == GL_BACK ? GL_BACK_LEFT : db0 == GL_FRONT ? GL_FRONT_LEFT : (GLenum)db0;
    k->color_fmt = db0 == GL_NONE ? 0 : color_format(catt);
    k->depth_fmt = depth_format(fbo == 0 ? GL_DEPTH : GL_DEPTH_ATTACHMENT);
    if (db0 != GL_NONE && !k->color_fmt) return false;
    if (!k->color_fmt && !k->depth_fmt) return false;
    glGetIntegerv(GL_SAMPLES, &k->samples);
    key_state(k);
    key_textures(k, albedo_unit, sky_unit);
    return k->vp_w > 0 && k->vp_h > 0;
}

static bool has_stencil(const world_cache_key *k) {
    return k->depth_fmt == GL_DEPTH24_STENCIL8 || k->depth_fmt == GL_DEPTH32F_STENCIL8;
}

unsigned world_cache_depth_attachment(const world_cache_key *k) {
    return has_stencil(k) ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT;
}

unsigned world_cache_copy_mask(const world_cache_key *k) {
    return (k->color_fmt ? GL_COLOR_BUFFER_BIT : 0) | (k->depth_fmt ? GL_DEPTH_BUFFER_BIT : 0) |
           (has_stencil(k) ? GL_STENCIL_BUFFER_BIT : 0);
}

static world_cache_slot *find(world_cache *c, int cmd) {
    for (int i = 0; i < WORLD_CACHE_SLOTS; i++)
        if (c->slot[i].cmd == cmd) return &c->slot[i];
    return NULL;
}

/* The framebuffer bindings, scissor and sRGB writes a copy changes, put back after. */
typedef struct saved_gl {
    GLint draw_fbo, read_fbo, rb;
    GLboolean scissor, srgb;
} saved_gl;

static void save_gl(saved_gl *s) {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->draw_fbo);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s->read_fbo);
    glGetIntegerv(GL_RENDERBUFFER_BINDING, &s->rb);
    s->scissor = glIsEnabled(GL_SCISSOR_TEST);
    glDisable(GL_SCISSOR_TEST);   /* a blit obeys the scissor */
    /* and, into an sRGB target with this on, decodes and encodes again:
     * llvmpipe's round trip moved pixels by one level (a window's sRGB
     * canvas); off, the cache's copies are the bytes, as its key promises */
    s->srgb = glIsEnabled(GL_FRAMEBUFFER_SRGB);
    glDisable(GL_FRAMEBUFFER_SRGB);
}

static void restore_gl(const saved_gl *s) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)s->read_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)s->draw_fbo);
    glBindRenderbuffer(GL_RENDERBUFFER, (GLuint)s->rb);
    if (s->scissor) glEnable(GL_SCISSOR_TEST);
    if (s->srgb) glEnable(GL_FRAMEBUFFER_SRGB);
}

/* A copy went wrong (a format the blit refused): draw this command from now on. */
static void give_up(world_cache_slot *s, int cmd) {
    while (glGetError() != GL_NO_ERROR) {}
    slot_free(s);
    s->cmd = cmd;
    s->broken = true;
}

bool world_cache_restore(world_cache *c, int cmd, const world_cache_key *k) {
    world_cache_slot *s = find(c, cmd);
    if (c->off || !s || !s->valid || s->broken || memcmp(&s->key, k, sizeof *k) != 0) return false;
    GLint vp[4];
    glGetIntegerv(GL_VIEWPORT, vp);
    saved_gl g;
    save_gl(&g);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, s->fbo);
    glBlitFramebuffer(0, 0, k->vp_w, k->vp_h, vp[0], vp[1], vp[0] + k->vp_w, vp[1] + k->vp_h, world_cache_copy_mask(k), GL_NEAREST);
    restore_gl(&g);
    if (glGetError() != GL_NO_ERROR) { give_up(s, cmd); return false; }
    c->hits++;
    return true;
}

static void alloc_rb(unsigned *rb, int samples, unsigned fmt, int w, int h) {
    glGenRenderbuffers(1, rb);
    glBindRenderbuffer(GL_RENDERBUFFER, *rb);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, fmt, w, h);
}

/* Storage for k's pixels, kept while the size, formats and samples stay. */
static bool slot_alloc(world_cache_slot *s, const world_cache_key *k) {
    if (s->fbo && s->key.vp_w == k->vp_w && s->key.vp_h == k->vp_h && s->key.color_fmt == k->color_fmt &&
        s->key.depth_fmt == k->depth_fmt && s->key.samples == k->samples)
        return true;
    int cmd = s->cmd;
    slot_free(s);
    s->cmd = cmd;
    glGenFramebuffers(1, &s->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo);   /* both: glReadBuffer below is the read binding's */
    if (k->color_fmt) {
        alloc_rb(&s->color_rb, k->samples, k->color_fmt, k->vp_w, k->vp_h);
        glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, s->color_rb);
    } else {
        glDrawBuffer(GL_NONE);
        glReadBuffer(GL_NONE);
    }
    if (k->depth_fmt) {
        alloc_rb(&s->depth_rb, k->samples, k->depth_fmt, k->vp_w, k->vp_h);
        glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, world_cache_depth_attachment(k), GL_RENDERBUFFER, s->depth_rb);
    }
    return glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
}

/* Command cmd's slot, or a free one taken for it; NULL: none left (more
 * World commands than slots: the rest are drawn), or it gave up */
static world_cache_slot *slot_for(world_cache *c, int cmd) {
    if (c->off) return NULL;
    world_cache_slot *s = find(c, cmd);
    if (!s) s = find(c, -1);
    if (!s || s->broken) return NULL;
    s->cmd = cmd;
    return s;
}

void world_cache_store(world_cache *c, int cmd, const world_cache_key *k) {
    world_cache_slot *s = slot_for(c, cmd);
    if (!s) return;
    bool same_time = s->seen && s->seen_t == k->t;
    s->seen = true;
    s->seen_t = k->t;
    if (same_time) world_cache_store_now(c, cmd, k);
}

void world_cache_store_now(world_cache *c, int cmd, const world_cache_key *k) {
    world_cache_slot *s = slot_for(c, cmd);
    if (!s) return;
    s->valid = false;
    GLint vp[4], db0 = GL_NONE, read_buf = GL_NONE;
    glGetIntegerv(GL_VIEWPORT, vp);
    glGetIntegerv(GL_DRAW_BUFFER0, &db0);
    saved_gl g;
    save_gl(&g);
    if (!slot_alloc(s, k)) { restore_gl(&g); give_up(s, cmd); return; }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)g.draw_fbo);
    glGetIntegerv(GL_READ_BUFFER, &read_buf);
    if (k->color_fmt) glReadBuffer((GLenum)db0);   /* read what the world was drawn into */
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, s->fbo);
    glBlitFramebuffer(vp[0], vp[1], vp[0] + k->vp_w, vp[1] + k->vp_h, 0, 0, k->vp_w, k->vp_h, world_cache_copy_mask(k), GL_NEAREST);
    if (k->color_fmt) glReadBuffer((GLenum)read_buf);
    restore_gl(&g);
    if (glGetError() != GL_NO_ERROR) { give_up(s, cmd); return; }
    s->key = *k;
    s->valid = true;
    c->stores++;
}
