#include "world_layers.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"
#include "world_layer_band.h"

void world_layers_init(world_layers *l) {
    memset(l, 0, sizeof *l);
    for (int i = 0; i < WORLD_CACHE_SLOTS; i++) l->slot[i].cmd = -1;
    world_cache_init(&l->whole);
}

static void slot_free(world_layers_slot *s) {
    if (s->fbo) glDeleteFramebuffers(1, &s->fbo);
    glDeleteTextures(4, s->tex);
    if (s->depth_rb) glDeleteRenderbuffers(1, &s->depth_rb);
    if (s->pick_fbo) glDeleteFramebuffers(1, &s->pick_fbo);
    if (s->pick_tex) glDeleteTextures(1, &s->pick_tex);
    if (s->band_vbo) glDeleteBuffers(1, &s->band_vbo);
    long gen = s->gen;   /* a whole frame kept of a build before is never taken for a later one */
    memset(s, 0, sizeof *s);
    s->cmd = -1;
    s->gen = gen;
}

void world_layers_free(world_layers *l) {
    for (int i = 0; i < WORLD_CACHE_SLOTS; i++) slot_free(&l->slot[i]);
    world_cache_free(&l->whole);
}

static world_layers_slot *find(world_layers *l, int cmd) {
    for (int i = 0; i < WORLD_CACHE_SLOTS; i++)
        if (l->slot[i].cmd == cmd) return &l->slot[i];
    return NULL;
}

/* k without its time: what the layers depend on */
static world_cache_key timeless(const world_cache_key *k) {
    world_cache_key u = *k;
    u.t = 0;
    return u;
}

/* k without its time and its size: what says the camera stood still
 * between two frames while the clock ran, even where the window's frame
 * budget drew them at two sizes (the size is in the projection's aspect,
 * the viewport and the meshes' level of detail) */
static world_cache_key timeless_sizeless(const world_cache_key *k) {
    world_cache_key u = timeless(k);
    memset(u.projection, 0, sizeof u.projection);
    u.vp_w = u.vp_h = 0;
    u.lod = 0;
    return u;
}

static bool same_but_time_and_size(const world_cache_key *a, const world_cache_key *b) {
    world_cache_key x = timeless_sizeless(a), y = timeless_sizeless(b);
    return memcmp(&x, &y, sizeof x) == 0;
}

/* The most two projections' horizontal focal lengths (the aspect) may
 * differ by for one's layers to serve the other: a reduced frame's sides
 * are rounded apart (0.1-1.2%, more at the smallest sizes) */
#define ASPECT_SLACK 0.05f

/* Is the projection the same but for its aspect (projection[0], the
 * focal length over the aspect), within ASPECT_SLACK? A point's
 * normalised device coordinates then differ only in x, by their ratio
 * (world_layers_textures' world_layer_view corrects for it). */
static bool same_but_aspect(const world_cache_key *a, const world_cache_key *b) {
    for (int i = 1; i < 16; i++)
        if (a->projection[i] != b->projection[i]) return false;
    return fabsf(a->projection[0] - b->projection[0]) <= ASPECT_SLACK * fabsf(a->projection[0]);
}

/* Do layers that hold have (its time zeroed) serve a frame of want (the
 * same)? Those of its own size do; while keep_larger is set, so do larger
 * ones of the same world and camera (the window draws smaller while a
 * save's job takes a core): the composite picks the texel that sees what
 * each pixel sees, and shrinking, then growing back, builds nothing. */
static bool layers_serve(const world_layers *l, const world_cache_key *have, const world_cache_key *want) {
    if (memcmp(have, want, sizeof *want) == 0) return true;
    /* multisampled layers serve their own size (world_layers_copy_depth) */
    if (!l->keep_larger || have->samples > 1 || have->vp_w < want->vp_w || have->vp_h < want->vp_h) return false;
    return same_but_time_and_size(have, want) && same_but_aspect(have, want);
}

world_layers_use world_layers_check(world_layers *l, int cmd, const world_cache_key *k) {
    /* no blending: the pass writes each pixel (each sample) once */
    if (l->off || k->blend || !k->color_fmt || !k->depth_fmt) return WORLD_LAYERS_NO;
    world_layers_slot *s = find(l, cmd);
    if (!s) s = find(l, -1);
    if (!s || s->broken) return WORLD_LAYERS_NO;
    s->cmd = cmd;
    world_cache_key u = timeless(k);
    if (s->valid && layers_serve(l, &s->key, &u)) {
        s->last = *k;
        return WORLD_LAYERS_READY;
    }
    /* the clock runs: the layers pay from this frame on, at this size (a
     * budget's new size builds them at once, not one plain draw later) */
    bool running = s->seen && same_but_time_and_size(&s->last, k) && s->last.t != k->t;
    s->seen = true;
    s->last = *k;
    return running ? WORLD_LAYERS_BUILD : WORLD_LAYERS_NO;
}

/* A layer texture: one sample, or samples with the standard (fixed)
 * locations the frame's renderbuffers have. */
static unsigned make_tex(int w, int h, int samples, GLenum fmt) {
    unsigned t;
    glGenTextures(1, &t);
    if (samples > 1) {
        glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, t);
        glTexImage2DMultisample(GL_TEXTURE_2D_MULTISAMPLE, samples, fmt, w, h, GL_TRUE);
        return t;
    }
    glBindTexture(GL_TEXTURE_2D, t);
    glTexImage2D(GL_TEXTURE_2D, 0, fmt, w, h, 0, GL_RGBA, GL_FLOAT, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

/* The wet and dry layers' format. One sample: RGBA32F, the wet layer's
 * alpha holds the depth. Several: the frame's own where it is one of the
 * renderer's multisampled targets' (render_msaa.h: 16-bit float for a
 * world drawn to an 8-bit target), so a sample composed from the layers
 * is the one drawn, and a 1920x1080 frame's layers take 265 MB, not 400. */
static GLenum shading_format(const world_cache_key *k) {
    bool own = k->color_fmt == GL_RGBA16F || k->color_fmt == GL_RGBA8;
    return k->samples > 1 && own ? k->color_fmt : GL_RGBA32F;
}

/* The depth: a renderbuffer for one sample (the wet layer's alpha holds
 * it), a texture the composite reads for several (a sample's own depth,
 * not its pixel centre's). */
static void attach_depth(world_layers_slot *s, const world_cache_key *k) {
    GLenum att = world_cache_depth_attachment(k);
    if (k->samples > 1) {
        s->tex[3] = make_tex(k->vp_w, k->vp_h, k->samples, k->depth_fmt);
        glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, att, GL_TEXTURE_2D_MULTISAMPLE, s->tex[3], 0);
        return;
    }
    glGenRenderbuffers(1, &s->depth_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, s->depth_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, k->depth_fmt, k->vp_w, k->vp_h);
    glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, att, GL_RENDERBUFFER, s->depth_rb);
}

/* The target, kept while the size, the samples and the formats stay. */
static bool slot_alloc(world_layers_slot *s, const world_cache_key *k) {
    if (s->fbo && s->key.vp_w == k->vp_w && s->key.vp_h == k->vp_h && s->key.depth_fmt == k->depth_fmt &&
        s->samples == k->samples && s->key.color_fmt == k->color_fmt)
        return true;
    /* a new size: new textures, the command's last key kept (the clock
     * still runs) */
    int cmd = s->cmd;
    bool seen = s->seen;
    world_cache_key last = s->last;
    slot_free(s);
    s->cmd = cmd;
    s->seen = seen;
    s->last = last;
    GLint tex2d = 0, tex_ms = 0;
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &tex2d);
    glGetIntegerv(GL_TEXTURE_BINDING_2D_MULTISAMPLE, &tex_ms);
    GLenum target = k->samples > 1 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
    glGenFramebuffers(1, &s->fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, s->fbo);
    for (int i = 0; i < 3; i++) {
        s->tex[i] = make_tex(k->vp_w, k->vp_h, k->samples, i < 2 ? shading_format(k) : GL_RGBA32F);
        glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, target, s->tex[i], 0);
    }
    attach_depth(s, k);
    glBindTexture(GL_TEXTURE_2D, (GLuint)tex2d);
    glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, (GLuint)tex_ms);
    s->samples = k->samples;
    s->key.vp_w = k->vp_w;
    s->key.vp_h = k->vp_h;
    s->key.depth_fmt = k->depth_fmt;
    s->key.color_fmt = k->color_fmt;
    return glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
}

bool world_layers_begin_build(world_layers *l, int cmd, const world_cache_key *k) {
    world_layers_slot *s = find(l, cmd);
    if (!s) return false;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &l->saved.draw_fbo);
    glGetIntegerv(GL_RENDERBUFFER_BINDING, &l->saved.rb);
    glGetIntegerv(GL_VIEWPORT, l->saved.vp);
    glGetFloatv(GL_COLOR_CLEAR_VALUE, l->saved.clear);
    l->saved.scissor = glIsEnabled(GL_SCISSOR_TEST) == GL_TRUE;
    s->valid = false;
    if (!slot_alloc(s, k)) {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)l->saved.draw_fbo);
        glBindRenderbuffer(GL_RENDERBUFFER, (GLuint)l->saved.rb);
        while (glGetError() != GL_NO_ERROR) {}
        slot_free(s);
        s->cmd = cmd;
        s->broken = true;
        return false;
    }
    static const GLenum bufs[3] = { GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2 };
    glDrawBuffers(3, bufs);
    glViewport(0, 0, k->vp_w, k->vp_h);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(0, 0, 0, 1);   /* the wet layer's alpha is the depth: 1, nothing drawn */
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    static const float no_point[4] = { 0, 0, 0, 0 };   /* the point layer's w: 0, no point */
    glClearBufferfv(GL_COLOR, 2, no_point);
    glClearColor(l->saved.clear[0], l->saved.clear[1], l->saved.clear[2], l->saved.clear[3]);
    return true;
}

/* More of a frame than this in the band: composing it alone saves too
 * little to pay for the copy of the rest */
#define BAND_MOST 0.6

/* The band's triangles in viewport coordinates, from rectangles of
 * pixels, each corner with its outward direction. */
static void band_upload(world_layers_slot *s, const int *rects, int n, int w, int h) {
    float *v = mem_alloc((size_t)(n > 0 ? n : 1) * 24 * sizeof *v);
    for (int i = 0; i < n; i++) {
        const int *r = rects + 4 * i;
        float x0 = 2.0f * r[0] / w - 1, y0 = 2.0f * r[1] / h - 1, x1 = 2.0f * r[2] / w - 1, y1 = 2.0f * r[3] / h - 1;
        const float tri[24] = { x0, y0, -1, -1, x1, y0, 1, -1, x1, y1, 1, 1,
                                x0, y0, -1, -1, x1, y1, 1, 1,  x0, y1, -1, 1 };
        memcpy(v + 24 * i, tri, sizeof tri);
    }
    if (!s->band_vbo) glGenBuffers(1, &s->band_vbo);
    GLint before = 0;
    glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &before);
    glBindBuffer(GL_ARRAY_BUFFER, s->band_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)((size_t)n * 24 * sizeof *v), v, GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, (GLuint)before);
    free(v);
    s->band_verts = 6 * n;
}

const unsigned *world_layers_begin_pick(world_layers *l, int cmd) {
    world_layers_slot *s = find(l, cmd);
    if (!s || s->samples <= 1) return NULL;
    int w = s->key.vp_w, h = s->key.vp_h;
    if (!s->pick_fbo) {
        GLint tex2d = 0;
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &tex2d);
        s->pick_tex = make_tex(w, h, 1, GL_RGBA32F);
        glBindTexture(GL_TEXTURE_2D, (GLuint)tex2d);
        glGenFramebuffers(1, &s->pick_fbo);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, s->pick_fbo);
        glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, s->pick_tex, 0);
    }
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, s->pick_fbo);
    glDrawBuffer(GL_COLOR_ATTACHMENT0);
    if (glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, s->fbo);
        return NULL;
    }
    static const float no_point[4] = { 0, 0, 0, 0 };
    glClearBufferfv(GL_COLOR, 0, no_point);
    s->picked = true;
    return s->tex;
}

/* The tiles whose points reach [lo, hi], from the point layer read back
 * (multisampled: the points world_layers_begin_pick's pass picked; none
 * picked, no band). */
static void find_band(world_layers_slot *s, double lo, double hi, bool picked) {
    int w = s->key.vp_w, h = s->key.vp_h, tiles = ((w + LAYER_BAND_TILE - 1) / LAYER_BAND_TILE) *
                                                  ((h + LAYER_BAND_TILE - 1) / LAYER_BAND_TILE);
    s->band_verts = -1;
    if (s->samples > 1 && !picked) return;
    float *pos = mem_alloc((size_t)w * h * 4 * sizeof *pos);
    int *rects = mem_alloc((size_t)tiles * 4 * sizeof *rects);
    GLint tex2d = 0, align = 4;
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &tex2d);
    glGetIntegerv(GL_PACK_ALIGNMENT, &align);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glBindTexture(GL_TEXTURE_2D, s->samples > 1 ? s->pick_tex : s->tex[2]);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, pos);
    glBindTexture(GL_TEXTURE_2D, (GLuint)tex2d);
    glPixelStorei(GL_PACK_ALIGNMENT, align);
    int n = layer_band_rects(pos, w, h, lo, hi, rects, tiles);
    long area = 0;
    for (int i = 0; i < n; i++) area += (long)(rects[4 * i + 2] - rects[4 * i]) * (rects[4 * i + 3] - rects[4 * i + 1]);
    if (n >= 0 && area <= BAND_MOST * w * h) band_upload(s, rects, n, w, h);
    free(rects);
    free(pos);
}

void world_layers_end_build(world_layers *l, int cmd, const world_cache_key *k, double band_lo, double band_hi) {
    world_layers_slot *s = find(l, cmd);
    bool picked = s && s->picked;
    if (s) s->picked = false;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)l->saved.draw_fbo);
    glBindRenderbuffer(GL_RENDERBUFFER, (GLuint)l->saved.rb);
    glViewport(l->saved.vp[0], l->saved.vp[1], l->saved.vp[2], l->saved.vp[3]);
    if (l->saved.scissor) glEnable(GL_SCISSOR_TEST);
    if (!s) return;
    s->key = timeless(k);
    s->valid = true;
    s->gen++;
    find_band(s, band_lo, band_hi, picked);
    l->builds++;
}

const unsigned *world_layers_textures(world_layers *l, int cmd, const world_cache_key *k, world_layer_view *v) {
    world_layers_slot *s = find(l, cmd);
    if (!s || !s->valid) return NULL;
    /* a pixel's normalised x is the layer's over r (the focal lengths'
     * ratio): texel = ((2 (px + 0.5) / w - 1) r + 1) lw / 2 */
    double r = k->projection[0] != 0 ? s->key.projection[0] / (double)k->projection[0] : 1.0;
    v->scale[0] = (float)(r * s->key.vp_w / k->vp_w);
    v->scale[1] = (float)((double)s->key.vp_h / k->vp_h);
    v->offset[0] = (float)((1.0 - r) * s->key.vp_w / 2.0);
    v->offset[1] = 0.0f;
    v->samples = s->samples;
    return s->tex;
}

bool world_layers_copy_depth(world_layers *l, int cmd, const world_cache_key *k, int x, int y) {
    world_layers_slot *s = find(l, cmd);
    if (!s || !s->valid || s->samples <= 1 || s->key.vp_w != k->vp_w || s->key.vp_h != k->vp_h) return false;
    GLint read = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, s->fbo);
    glBlitFramebuffer(0, 0, k->vp_w, k->vp_h, x, y, x + k->vp_w, y + k->vp_h,
                      world_cache_copy_mask(k) & ~(unsigned)GL_COLOR_BUFFER_BIT, GL_NEAREST);   /* with the stencil */
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)read);
    return true;
}

/* The key a whole composed frame of slot s at k is kept under: k without
 * its time, and the build it was composed from in the time's place */
static world_cache_key whole_key(const world_layers_slot *s, const world_cache_key *k) {
    world_cache_key u = timeless(k);
    u.t = (double)s->gen;
    return u;
}

/* Can a frame at k compose slot s's band alone? (world_layers_band_begin) */
static bool band_fits(const world_layers *l, const world_layers_slot *s, const world_cache_key *k) {
    bool passes = !k->depth_test || k->depth_func == GL_LESS || k->depth_func == GL_LEQUAL ||
                  k->depth_func == GL_ALWAYS;
    world_cache_key u = timeless(k);
    return s && s->valid && s->band_verts >= 0 && passes && layers_serve(l, &s->key, &u);
}

/* Where the frame's pixels fall in the layers' viewport: a pixel's centre
 * c reads texel c scale + offset, so the layers' x (2 texel / lw - 1) is
 * the frame's (2 c / fw - 1) times lw / (fw scale), moved; and where the
 * frame resamples, its tiles' edges fall between pixel centres, so a
 * pixel of margin keeps a centre on an edge inside the band. */
static void band_map(const world_layers_slot *s, const world_cache_key *k, const world_layer_view *v,
                     world_layer_band *b) {
    const int lsize[2] = { s->key.vp_w, s->key.vp_h }, fsize[2] = { k->vp_w, k->vp_h };
    bool identity = true;
    for (int i = 0; i < 2; i++) {
        double a = lsize[i] / (fsize[i] * (double)v->scale[i]);
        b->map[i] = (float)a;
        b->map[2 + i] = (float)((1.0 - 2.0 * v->offset[i] / lsize[i]) * a - 1.0);
        identity = identity && v->scale[i] == 1.0f && v->offset[i] == 0.0f && lsize[i] == fsize[i];
    }
    for (int i = 0; i < 2; i++) b->pad[i] = identity ? 0.0f : 2.0f / (float)fsize[i];
}

bool world_layers_band_begin(world_layers *l, int cmd, const world_cache_key *k, const world_layer_view *v,
                             world_layer_band *band) {
    world_layers_slot *s = find(l, cmd);
    if (!band_fits(l, s, k)) return false;
    world_cache_key u = whole_key(s, k);
    if (!world_cache_restore(&l->whole, cmd, &u)) return false;
    band->vbo = s->band_vbo;
    band->verts = s->band_verts;
    band_map(s, k, v, band);
    l->band_composites++;
    return true;
}

void world_layers_keep_whole(world_layers *l, int cmd, const world_cache_key *k) {
    world_layers_slot *s = find(l, cmd);
    if (!band_fits(l, s, k)) return;
    world_cache_key u = whole_key(s, k);
    world_cache_store_now(&l->whole, cmd, &u);
}
