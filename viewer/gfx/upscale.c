/* upscale: the reduced frame into the window (see upscale.h). */
#include "upscale.h"
#include "strbuf.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <stdio.h>
#include <stdlib.h>

#include "gl_program.h"
#include "mem.h"
#include "upscale_frag.h"   /* upscale_frag_src: shaders/upscale.frag, built in by embed.cmake */

/* A linear 16-bit float target of its own, grown, never shrunk. */
typedef struct float_target {
    unsigned tex, fbo;
    int w, h;
} float_target;

struct upscaler {
    upscale_filter filter;
    float sharpness;
    unsigned prog, vao;
    unsigned read_fbo;          /* the source texture attached, for the blits */
    /* the first pass's output: the frame's rows at the destination's width,
     * linear 16-bit float (an sRGB canvas decoded once) */
    float_target mid;
    int u_src, u_axis, u_scale, u_origin, u_last, u_a;
    /* upscale_draw_over_world: its two programs (built at its first use),
     * and the frame's water premultiplied by its share, at the frame's
     * size, filtered linearly */
    unsigned mask_prog, over_prog;
    float_target water;
    bool over_tried;
    int u_over_scale, u_over_origin, u_over_size, u_over_last;
    char err[MSG_MAX];
};

/* Which of the reduced frame's pixels its water changed: the texel
 * differs from the snapshot taken right before the water (both
 * decoded the same way, so an untouched texel is equal to the bit). Out:
 * the frame's colour premultiplied by that share (1 or 0) and the share. */
static const char mask_frag[] =
    "#version 330 core\n"
    "uniform sampler2D uFrame, uWorld;\n"
    "out vec4 fragColor;\n"
    "void main() {\n"
    "    ivec2 p = ivec2(gl_FragCoord.xy);\n"
    "    vec3 f = texelFetch(uFrame, p, 0).rgb;\n"
    "    float water = any(notEqual(f, texelFetch(uWorld, p, 0).rgb)) ? 1.0 : 0.0;\n"
    "    fragColor = vec4(f * water, water);\n"
    "}\n";

/* Each window pixel: the water's share, enlarged bilinearly with the
 * water's colour (premultiplied, so no world texel of the reduced frame
 * bleeds in), over the full-resolution world. */
static const char over_frag[] =
    "#version 330 core\n"
    "uniform sampler2D uWater, uFull;\n"
    "uniform vec2 uScale, uOrigin, uSize, uLast;\n"
    "out vec4 fragColor;\n"
    "void main() {\n"
    "    vec2 d = gl_FragCoord.xy - uOrigin;\n"
    "    vec2 s = clamp(d * uScale, vec2(0.5), uLast + 0.5);\n"
    "    vec4 w = texture(uWater, s / uSize);\n"
    "    vec3 world = texelFetch(uFull, ivec2(d), 0).rgb;\n"
    "    fragColor = vec4(w.rgb + (1.0 - w.a) * world, 1.0);\n"
    "}\n";

/* A program of the full-screen triangle and frag_src, or 0 with err said. */
static unsigned link_program(const char *frag_src, char *err, size_t errlen) {
    char *vert = gl_program_fullscreen_vert("#version 330 core");
    char why[400] = "";
    unsigned prog = gl_program_link(vert, frag_src, "the upscale shader", why, sizeof why);
    free(vert);
    if (!prog) snprintf(err, errlen, "tarn: %s (bilinear instead)", why);
    return prog;
}

/* The cubic's program, or false with u->err said (the upscaler then blits). */
static bool build(upscaler *u) {
    u->prog = link_program(upscale_frag_src, u->err, sizeof u->err);
    if (!u->prog) return false;
    u->u_src = glGetUniformLocation(u->prog, "uSrc");
    u->u_axis = glGetUniformLocation(u->prog, "uAxis");
    u->u_scale = glGetUniformLocation(u->prog, "uScale");
    u->u_origin = glGetUniformLocation(u->prog, "uOrigin");
    u->u_last = glGetUniformLocation(u->prog, "uLast");
    u->u_a = glGetUniformLocation(u->prog, "uA");
    return true;
}

/* t, at least w x h, sampled with filter (GL_NEAREST or GL_LINEAR). */
static bool float_target_ensure(float_target *t, int w, int h, GLint filter) {
    if (t->tex && t->w >= w && t->h >= h) return true;
    w = w > t->w ? w : t->w;
    h = h > t->h ? h : t->h;
    if (t->tex) glDeleteTextures(1, &t->tex);
    if (!t->fbo) glGenFramebuffers(1, &t->fbo);
    glGenTextures(1, &t->tex);
    glBindTexture(GL_TEXTURE_2D, t->tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, w, h, 0, GL_RGBA, GL_HALF_FLOAT, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t->tex, 0);
    bool ok = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    t->w = ok ? w : 0;
    t->h = ok ? h : 0;
    return ok;
}

static void float_target_free(float_target *t) {
    if (t->fbo) glDeleteFramebuffers(1, &t->fbo);
    if (t->tex) glDeleteTextures(1, &t->tex);
}

upscaler *upscale_create(const upscale_desc *desc, const char **err) {
    upscale_desc d = desc ? *desc : (upscale_desc){ 0 };
    upscaler *u = mem_zalloc(sizeof *u);
    u->filter = d.filter;
    glGenVertexArrays(1, &u->vao);
    u->sharpness = d.sharpness == 0 ? UPSCALE_SHARPNESS_DEFAULT : d.sharpness < 0 ? 0 : d.sharpness;
    glGenFramebuffers(1, &u->read_fbo);
    while (glGetError() != GL_NO_ERROR) {}
    if (u->filter == UPSCALE_CUBIC && !build(u)) u->filter = UPSCALE_BILINEAR;
    while (glGetError() != GL_NO_ERROR) {}   /* a failed build leaves nothing for the caller's checks */
    if (err) *err = u->err[0] ? u->err : NULL;
    return u;
}

void upscale_destroy(upscaler *u) {
    if (!u) return;
    if (u->prog) glDeleteProgram(u->prog);
    if (u->vao) glDeleteVertexArrays(1, &u->vao);
    float_target_free(&u->mid);
    if (u->read_fbo) glDeleteFramebuffers(1, &u->read_fbo);
    if (u->mask_prog) glDeleteProgram(u->mask_prog);
    if (u->over_prog) glDeleteProgram(u->over_prog);
    float_target_free(&u->water);
    free(u);
}

upscale_filter upscale_filter_used(const upscaler *u) { return u->filter; }

/* A blit of the source into rect: GL_NEAREST at 1:1 (a copy), GL_LINEAR
 * otherwise (the window before this module). Blits are scissored. */
static void blit(upscaler *u, unsigned src_tex, int src_w, int src_h, unsigned dst_fbo, upscale_rect r) {
    GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST);
    glDisable(GL_SCISSOR_TEST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, u->read_fbo);
    glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, src_tex, 0);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, dst_fbo);
    bool copy = src_w == r.w && src_h == r.h;
    glBlitFramebuffer(0, 0, src_w, src_h, r.x, r.y, r.x + r.w, r.y + r.h, GL_COLOR_BUFFER_BIT,
                      copy ? GL_NEAREST : GL_LINEAR);
    glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, dst_fbo);
    if (scissor) glEnable(GL_SCISSOR_TEST);
}

/* The GL state the pass changes, to give back as the caller had it. */
typedef struct saved_state {
    GLint viewport[4], scissor[4];
    GLboolean scissor_on, depth_on, blend_on, cull_on, stencil_on;
} saved_state;

static saved_state save_state(void) {
    saved_state s;
    glGetIntegerv(GL_VIEWPORT, s.viewport);
    glGetIntegerv(GL_SCISSOR_BOX, s.scissor);
    s.scissor_on = glIsEnabled(GL_SCISSOR_TEST);
    s.depth_on = glIsEnabled(GL_DEPTH_TEST);
    s.blend_on = glIsEnabled(GL_BLEND);
    s.cull_on = glIsEnabled(GL_CULL_FACE);
    s.stencil_on = glIsEnabled(GL_STENCIL_TEST);
    return s;
}

static void set_enabled(GLenum cap, GLboolean on) {
    if (on) glEnable(cap);
    else glDisable(cap);
}

/* The caller's state saved, and the passes' set: scissored to each pass's
 * rectangle, no depth test, blending, culling or stencil. */
static saved_state begin_passes(void) {
    saved_state s = save_state();
    glEnable(GL_SCISSOR_TEST);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_STENCIL_TEST);
    return s;
}

static void restore_state(const saved_state *s) {
    glViewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
    glScissor(s->scissor[0], s->scissor[1], s->scissor[2], s->scissor[3]);
    set_enabled(GL_SCISSOR_TEST, s->scissor_on);
    set_enabled(GL_DEPTH_TEST, s->depth_on);
    set_enabled(GL_BLEND, s->blend_on);
    set_enabled(GL_CULL_FACE, s->cull_on);
    set_enabled(GL_STENCIL_TEST, s->stencil_on);
}

/* One axis: tex (its texels 0..last along the axis) into the w x h
 * rectangle at (x, y) of the bound framebuffer. */
static void pass(const upscaler *u, unsigned tex, int axis, int last, double scale, int x, int y, int w, int h) {
    glViewport(x, y, w, h);
    glScissor(x, y, w, h);
    glBindTexture(GL_TEXTURE_2D, tex);
    glUniform1i(u->u_axis, axis);
    glUniform1f(u->u_scale, (float)scale);
    glUniform2f(u->u_origin, (float)x, (float)y);
    glUniform1i(u->u_last, last);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

/* The separable cubic: the frame's rows to the destination's width into
 * the linear middle target, then its columns to the destination's height.
 * Separable because on a CPU rasteriser the cost is the taps at the
 * destination's size: 4 there (plus 4 at rect.w x src_h) against 16. */
static void draw_cubic(upscaler *u, unsigned src_tex, int src_w, int src_h, unsigned dst_fbo, upscale_rect r) {
    if (!float_target_ensure(&u->mid, r.w, src_h, GL_NEAREST)) {
        blit(u, src_tex, src_w, src_h, dst_fbo, r);
        return;
    }
    saved_state s = begin_passes();
    GLboolean srgb = glIsEnabled(GL_FRAMEBUFFER_SRGB);
    glUseProgram(u->prog);
    glActiveTexture(GL_TEXTURE0);
    glUniform1i(u->u_src, 0);
    glUniform1f(u->u_a, -0.5f - 0.5f * u->sharpness);
    glBindVertexArray(u->vao);
    glBindFramebuffer(GL_FRAMEBUFFER, u->mid.fbo);
    glDisable(GL_FRAMEBUFFER_SRGB);   /* the middle target holds linear values as they are */
    pass(u, src_tex, 0, src_w - 1, (double)src_w / r.w, 0, 0, r.w, src_h);
    glBindFramebuffer(GL_FRAMEBUFFER, dst_fbo);
    if (srgb) glEnable(GL_FRAMEBUFFER_SRGB);   /* the caller's encoding, as a blit's */
    pass(u, u->mid.tex, 1, src_h - 1, (double)src_h / r.h, r.x, r.y, r.w, r.h);
    glBindVertexArray(0);
    glBindTexture(GL_TEXTURE_2D, 0);
    glUseProgram(0);
    restore_state(&s);
}

void upscale_draw(upscaler *u, unsigned src_tex, int src_w, int src_h, unsigned dst_fbo, upscale_rect rect) {
    if (src_w <= 0 || src_h <= 0 || rect.w <= 0 || rect.h <= 0) return;
    bool copy = src_w == rect.w && src_h == rect.h;
    if (copy || u->filter == UPSCALE_BILINEAR || !u->prog) blit(u, src_tex, src_w, src_h, dst_fbo, rect);
    else draw_cubic(u, src_tex, src_w, src_h, dst_fbo, rect);
}

/* ---- the reduced frame's water over the full-resolution world ---- */

static bool build_over(upscaler *u) {
    if (u->over_tried) return u->over_prog != 0;
    u->over_tried = true;
    char err[MSG_MAX];
    u->mask_prog = link_program(mask_frag, err, sizeof err);
    u->over_prog = u->mask_prog ? link_program(over_frag, err, sizeof err) : 0;
    if (!u->over_prog) {
        fprintf(stderr, "%s\n", err);
        return false;
    }
    glUseProgram(u->mask_prog);
    glUniform1i(glGetUniformLocation(u->mask_prog, "uFrame"), 0);
    glUniform1i(glGetUniformLocation(u->mask_prog, "uWorld"), 1);
    glUseProgram(u->over_prog);
    glUniform1i(glGetUniformLocation(u->over_prog, "uWater"), 0);
    glUniform1i(glGetUniformLocation(u->over_prog, "uFull"), 1);
    u->u_over_scale = glGetUniformLocation(u->over_prog, "uScale");
    u->u_over_origin = glGetUniformLocation(u->over_prog, "uOrigin");
    u->u_over_size = glGetUniformLocation(u->over_prog, "uSize");
    u->u_over_last = glGetUniformLocation(u->over_prog, "uLast");
    glUseProgram(0);
    return true;
}

static void bind_unit(int unit, unsigned tex) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, tex);
}

bool upscale_draw_over_world(upscaler *u, unsigned src_tex, unsigned world_tex, int src_w, int src_h,
                             unsigned full_tex, unsigned dst_fbo, upscale_rect r) {
    if (src_w <= 0 || src_h <= 0 || r.w <= 0 || r.h <= 0 || !world_tex || !full_tex) return false;
    if (!build_over(u) || !float_target_ensure(&u->water, src_w, src_h, GL_LINEAR)) return false;
    saved_state st = begin_passes();
    GLboolean srgb = glIsEnabled(GL_FRAMEBUFFER_SRGB);
    glBindVertexArray(u->vao);
    /* the water and its share, at the frame's size, in linear values */
    glBindFramebuffer(GL_FRAMEBUFFER, u->water.fbo);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glViewport(0, 0, src_w, src_h);
    glScissor(0, 0, src_w, src_h);
    glUseProgram(u->mask_prog);
    bind_unit(1, world_tex);
    bind_unit(0, src_tex);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    /* over the world, at the window's size, encoded as the caller asks */
    glBindFramebuffer(GL_FRAMEBUFFER, dst_fbo);
    if (srgb) glEnable(GL_FRAMEBUFFER_SRGB);
    glViewport(r.x, r.y, r.w, r.h);
    glScissor(r.x, r.y, r.w, r.h);
    glUseProgram(u->over_prog);
    glUniform2f(u->u_over_scale, (float)src_w / r.w, (float)src_h / r.h);
    glUniform2f(u->u_over_origin, (float)r.x, (float)r.y);
    glUniform2f(u->u_over_size, (float)u->water.w, (float)u->water.h);
    glUniform2f(u->u_over_last, (float)(src_w - 1), (float)(src_h - 1));
    bind_unit(1, full_tex);
    bind_unit(0, u->water.tex);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    bind_unit(1, 0);
    bind_unit(0, 0);
    glBindVertexArray(0);
    glUseProgram(0);
    restore_state(&st);
    return true;
}
