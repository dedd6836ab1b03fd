#include "water_deferred.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_program.h"

void water_deferred_init(water_deferred *d) { memset(d, 0, sizeof *d); }

static void free_textures(water_deferred *d) {
    if (d->ntex) glDeleteTextures(d->ntex, d->tex);
    memset(d->tex, 0, sizeof d->tex);
    d->ntex = d->tex_w = d->tex_h = 0;
}

void water_deferred_free(water_deferred *d) {
    free_textures(d);
    if (d->fbo) glDeleteFramebuffers(1, &d->fbo);
    if (d->vao) glDeleteVertexArrays(1, &d->vao);
    bool off = d->off;
    memset(d, 0, sizeof *d);
    d->off = off;
}

/* ---- the two programs ------------------------------------------------ */

/* p's split and its two programs, made once per build of p. */
static bool make_programs(prog *p) {
    prog_deferred *pd = &p->deferred;
    if (pd->tried) return pd->shade != 0;
    pd->tried = true;
    bool other_stages = p->stage_path[SHADER_TESS_CONTROL][0] || p->stage_path[SHADER_TESS_EVALUATION][0] ||
                        p->stage_path[SHADER_GEOMETRY][0];
    if (other_stages || !p->vertex_text || !p->fragment_text) {
        snprintf(pd->why, sizeof pd->why, "a program of more stages than a vertex and a fragment shader");
        return false;
    }
    glsl_deferred split;
    if (!glsl_deferred_split(p->fragment_text, &split)) {
        snprintf(pd->why, sizeof pd->why, "%s", split.why);
        return false;
    }
    char *vert = gl_program_fullscreen_vert(split.version);   /* a program's stages share a profile */
    pd->gbuffer = gl_program_link(p->vertex_text, split.gbuffer, "the G-buffer pass", pd->why, sizeof pd->why);
    pd->shade = pd->gbuffer ? gl_program_link(vert, split.shade, "the shade pass", pd->why, sizeof pd->why) : 0;
    free(vert);
    pd->ntex = split.ntex;
    pd->stamped = split.stamped;
    pd->gbuffer_tangent = pd->gbuffer ? glGetAttribLocation(pd->gbuffer, "Tangent") : -1;
    glsl_deferred_free(&split);
    if (!pd->shade && pd->gbuffer) {
        glDeleteProgram(pd->gbuffer);
        pd->gbuffer = 0;
    }
    return pd->shade != 0;
}

/* ---- the framebuffer ------------------------------------------------- */

/* The bound draw framebuffer's depth-stencil renderbuffer, when it is one
 * of ours, single-sample, with 8 stencil bits; else 0 and *why. */
static GLuint screen_depth_stencil(const char **why) {
    GLint fbo = 0, samples = 0, type = 0, name = 0, stencil = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    *why = "the window system's framebuffer";
    if (fbo == 0) return 0;
    glGetIntegerv(GL_SAMPLES, &samples);
    *why = "a multisampled frame (--msaa 1 draws it deferred)";
    if (samples > 1) return 0;
    *why = "a framebuffer without a stencil renderbuffer";
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT,
                                          GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    if (type != GL_RENDERBUFFER) return 0;
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_STENCIL_ATTACHMENT,
                                          GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    if (type != GL_RENDERBUFFER) return 0;
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_STENCIL_ATTACHMENT,
                                          GL_FRAMEBUFFER_ATTACHMENT_STENCIL_SIZE, &stencil);
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT,
                                          GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
    if (stencil < 8) return 0;
    *why = NULL;
    return (GLuint)name;
}

/* The G-buffer framebuffer: ntex RGBA32F textures of at least w x h and
 * the screen's depth-stencil; bound for drawing. */
static bool bind_gbuffer(water_deferred *d, int ntex, int w, int h, GLuint depth_rb) {
    bool remake = d->ntex != ntex || d->tex_w < w || d->tex_h < h;
    if (!d->fbo) glGenFramebuffers(1, &d->fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, d->fbo);
    if (remake) {
        GLint bound = 0;   /* the active unit's texture: the scene's, put back */
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
        free_textures(d);
        glGenTextures(ntex, d->tex);
        for (int k = 0; k < ntex; k++) {
            glBindTexture(GL_TEXTURE_2D, d->tex[k]);
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, NULL);
            static const GLfloat zero[4] = { 0, 0, 0, 0 };
            glClearTexImage(d->tex[k], 0, GL_RGBA, GL_FLOAT, zero);   /* no stamp matches a new texture */
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + (GLenum)k, GL_TEXTURE_2D, d->tex[k], 0);
        }
        for (int k = ntex; k < GLSL_DEFERRED_MAX_TEX; k++)
            glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + (GLenum)k, GL_TEXTURE_2D, 0, 0);
        d->ntex = ntex;
        d->tex_w = w;
        d->tex_h = h;
        GLenum bufs[GLSL_DEFERRED_MAX_TEX];
        for (int k = 0; k < ntex; k++) bufs[k] = GL_COLOR_ATTACHMENT0 + (GLenum)k;
        glDrawBuffers(ntex, bufs);
        glBindTexture(GL_TEXTURE_2D, (GLuint)bound);
    }
    if (remake || d->depth_rb != depth_rb) {
        glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth_rb);
        d->depth_rb = depth_rb;
    }
    return glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
}

/* ---- the state a draw changes and puts back -------------------------- */

typedef struct saved_state {
    GLint fbo, program, vao, active, vp[4], scissor_box[4];
    GLboolean depth_test, cull, blend, stencil, scissor;
    GLint stencil_func, stencil_ref, stencil_mask, stencil_write, op[3];
    GLint units[GLSL_DEFERRED_MAX_TEX], bound[GLSL_DEFERRED_MAX_TEX];
    int nunits;
} saved_state;

static void save_state(saved_state *s) {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->fbo);
    glGetIntegerv(GL_CURRENT_PROGRAM, &s->program);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &s->vao);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &s->active);
    glGetIntegerv(GL_VIEWPORT, s->vp);
    glGetIntegerv(GL_SCISSOR_BOX, s->scissor_box);
    s->depth_test = glIsEnabled(GL_DEPTH_TEST);
    s->cull = glIsEnabled(GL_CULL_FACE);
    s->blend = glIsEnabled(GL_BLEND);
    s->stencil = glIsEnabled(GL_STENCIL_TEST);
    s->scissor = glIsEnabled(GL_SCISSOR_TEST);
    glGetIntegerv(GL_STENCIL_FUNC, &s->stencil_func);
    glGetIntegerv(GL_STENCIL_REF, &s->stencil_ref);
    glGetIntegerv(GL_STENCIL_VALUE_MASK, &s->stencil_mask);
    glGetIntegerv(GL_STENCIL_WRITEMASK, &s->stencil_write);
    glGetIntegerv(GL_STENCIL_FAIL, &s->op[0]);
    glGetIntegerv(GL_STENCIL_PASS_DEPTH_FAIL, &s->op[1]);
    glGetIntegerv(GL_STENCIL_PASS_DEPTH_PASS, &s->op[2]);
    s->nunits = 0;
}

static void enable(GLenum cap, GLboolean on) {
    if (on) glEnable(cap); else glDisable(cap);
}

static void restore_state(const saved_state *s) {
    for (int k = 0; k < s->nunits; k++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)s->units[k]);
        glBindTexture(GL_TEXTURE_2D, (GLuint)s->bound[k]);
    }
    glActiveTexture((GLenum)s->active);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)s->fbo);
    glUseProgram((GLuint)s->program);
    glBindVertexArray((GLuint)s->vao);
    glScissor(s->scissor_box[0], s->scissor_box[1], s->scissor_box[2], s->scissor_box[3]);
    enable(GL_DEPTH_TEST, s->depth_test);
    enable(GL_CULL_FACE, s->cull);
    enable(GL_BLEND, s->blend);
    enable(GL_STENCIL_TEST, s->stencil);
    enable(GL_SCISSOR_TEST, s->scissor);
    glStencilFunc((GLenum)s->stencil_func, s->stencil_ref, (GLuint)s->stencil_mask);
    glStencilMask((GLuint)s->stencil_write);
    glStencilOp((GLenum)s->op[0], (GLenum)s->op[1], (GLenum)s->op[2]);
}

/* ---- the units the G-buffer is read on ------------------------------- */

static bool is_sampler(GLenum t) {
    return (t >= GL_SAMPLER_1D && t <= GL_SAMPLER_2D_RECT_SHADOW) || (t >= GL_SAMPLER_1D_ARRAY && t <= GL_UNSIGNED_INT_SAMPLER_BUFFER) ||
           (t >= GL_SAMPLER_2D_MULTISAMPLE && t <= GL_UNSIGNED_INT_SAMPLER_2D_MULTISAMPLE_ARRAY) ||
           (t >= GL_SAMPLER_CUBE_MAP_ARRAY && t <= GL_UNSIGNED_INT_SAMPLER_CUBE_MAP_ARRAY);
}

/* n texture units no sampler of program prg reads (its values uploaded),
 * from the highest down; false when there are not that many. */
static bool free_units(GLuint prg, int n, GLint *units) {
    GLint max_frag = 0, max_all = 0, count = 0;
    glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &max_frag);
    glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &max_all);
    int max = max_frag < max_all ? max_frag : max_all;
    if (max > 64) max = 64;
    bool used[64] = { false };
    glGetProgramiv(prg, GL_ACTIVE_UNIFORMS, &count);
    for (GLint i = 0; i < count; i++) {
        char name[128];
        GLint size = 0;
        GLenum type = 0;
        glGetActiveUniform(prg, (GLuint)i, sizeof name, NULL, &size, &type, name);
        if (!is_sampler(type) || strncmp(name, "tarn_dfr_", 9) == 0) continue;
        GLint loc = glGetUniformLocation(prg, name);
        for (GLint e = 0; loc >= 0 && e < size; e++) {
            GLint unit = -1;
            glGetUniformiv(prg, loc + e, &unit);
            if (unit >= 0 && unit < 64) used[unit] = true;
        }
    }
    int got = 0;
    for (int u = max - 1; u >= 0 && got < n; u--)
        if (!used[u]) units[got++] = u;
    return got == n;
}

/* ---- the draw -------------------------------------------------------- */

/* The stencil, and the G-buffer unless stamped (a draw's texels tell
 * themselves from older ones: glsl_deferred.stamped). */
static void clear_gbuffer(const water_deferred *d, const GLint vp[4], bool stamped) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(vp[0], vp[1], vp[2], vp[3]);
    static const GLfloat zero[4] = { 0, 0, 0, 0 };
    for (int k = 0; !stamped && k < d->ntex; k++) glClearBufferfv(GL_COLOR, k, zero);
    GLint s0 = 0;
    glStencilMask(0xFF);
    glClearBufferiv(GL_STENCIL, 0, &s0);
    glDisable(GL_SCISSOR_TEST);
}

static void set_stamp(GLuint prg, long stamp) {
    GLint loc = glGetUniformLocation(prg, "tarn_dfr_stamp");
    if (loc >= 0) glUniform1f(loc, (float)stamp);
}

bool water_deferred_draw(water_deferred *d, prog *p, const water_deferred_calls *calls) {
    d->skip_why = d->off ? "turned off (render_set_deferred_water, tarn render --grid-water)" : calls->keep_grid;
    if (d->skip_why || !p || !p->gl) return false;
    GLint poly[2] = { GL_FILL, GL_FILL };
    glGetIntegerv(GL_POLYGON_MODE, poly);
    if (poly[0] != GL_FILL) {
        d->skip_why = "polygons drawn as lines or points (PolygonMode)";
        return false;
    }
    GLuint depth_rb = screen_depth_stencil(&d->skip_why);
    if (!depth_rb || !make_programs(p)) return false;
    const prog_deferred *pd = &p->deferred;
    saved_state st;
    save_state(&st);
    GLint vp[4];
    memcpy(vp, st.vp, sizeof vp);
    if (!bind_gbuffer(d, pd->ntex, vp[0] + vp[2], vp[1] + vp[3], depth_rb)) {
        restore_state(&st);
        return false;
    }
    /* the units the G-buffer is read on: those the shade program's own
     * samplers (its values uploaded) leave free */
    glUseProgram(pd->shade);
    calls->upload(pd->shade, calls->user);
    GLint units[GLSL_DEFERRED_MAX_TEX];
    if (!free_units(pd->shade, pd->ntex, units)) {
        restore_state(&st);
        return false;
    }
    /* 1. the grid into the G-buffer, stencil 1 where it is drawn */
    clear_gbuffer(d, vp, pd->stamped);
    d->stamp = d->stamp % 16777215 + 1;   /* exact in a float; never the cleared 0 */
    glDisable(GL_BLEND);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 1, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glUseProgram(pd->gbuffer);
    calls->upload(pd->gbuffer, calls->user);
    set_stamp(pd->gbuffer, d->stamp);
    calls->draw_grid(pd->gbuffer_tangent, calls->user);
    /* 2. the pack's shader once a water pixel */
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)st.fbo);
    enable(GL_BLEND, st.blend);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glStencilFunc(GL_EQUAL, 1, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glUseProgram(pd->shade);
    set_stamp(pd->shade, d->stamp);
    for (int k = 0; k < pd->ntex; k++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)units[k]);
        st.units[st.nunits] = units[k];
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &st.bound[st.nunits++]);
        glBindTexture(GL_TEXTURE_2D, d->tex[k]);
        char name[32];
        snprintf(name, sizeof name, "tarn_dfr_g%d", k);
        glUniform1i(glGetUniformLocation(pd->shade, name), units[k]);
    }
    if (!d->vao) glGenVertexArrays(1, &d->vao);
    glBindVertexArray(d->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    d->draws++;
    restore_state(&st);
    return true;
}
