/* render_spray: the spray's passes (see render_spray.h). */
#include "render_spray.h"
#include "render_res.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mem.h"
#include "strbuf.h"

void spray_desc_resolve(ref_spray_desc *d) {
    if (!(d->life > 0)) d->life = SPRAY_DEFAULT_LIFE;
    if (!(d->size > 0)) d->size = SPRAY_DEFAULT_SIZE;
    if (d->count <= 0) d->count = SPRAY_DEFAULT_COUNT;
    if (d->count > SPRAY_COUNT_MAX) d->count = SPRAY_COUNT_MAX;
    if (!(d->rate >= 0)) d->rate = 0;
}

static unsigned make_state(int res) {
    unsigned t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, res, res, 0, GL_RGBA, GL_FLOAT, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    glBindTexture(GL_TEXTURE_2D, 0);
    return t;
}

void spray_clear(gpu_spray *s) {
    if (!s->active) return;
    static const float zero[4] = { 0, 0, 0, 0 };
    for (int i = 0; i < 2; i++) {
        glBindFramebuffer(GL_FRAMEBUFFER, s->fbo[i]);
        glClearBufferfv(GL_COLOR, 0, zero);
        glClearBufferfv(GL_COLOR, 1, zero);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    s->valid = false;
}

bool spray_build_programs(gpu_spray *s, const prog_sources *src, diag_list *log, prog_origins *from) {
    if (!s->active) return true;
    bool ok = true;
    for (int i = 0; i < SPRAY_PROGS; i++) {
        if (!prog_build(&s->progs[i], src, log, from)) ok = false;
        prog_introspect(&s->progs[i], log);
    }
    return ok;
}

static void init_prog(gpu_spray *s, int which, const prog_sources *src) {
    static const char *const names[SPRAY_PROGS] = { "SprayUpdate", "SprayDraw" };
    static const char *const verts[SPRAY_PROGS] = { "world_height.vert", "spray_draw.vert" };
    static const char *const frags[SPRAY_PROGS] = { "spray_update.frag", "spray_draw.frag" };
    prog *p = &s->progs[which];
    p->unifs = &s->unifs[which];
    p->world_uniforms = true;   /* tarn's uniforms, not sliders */
    snprintf(p->name, sizeof p->name, "%s", names[which]);
    snprintf(p->stage_path[SHADER_VERTEX], GLIB_PATH_MAX, "%s/%s", src->common_dir, verts[which]);
    snprintf(p->stage_path[SHADER_FRAGMENT], GLIB_PATH_MAX, "%s/%s", src->common_dir, frags[which]);
}

bool spray_create(gpu_spray *s, const ref_spray_desc *desc, double half_size, const prog_sources *src,
                  void (*set_defines)(const void *ctx, prog *p), const void *ctx,
                  diag_list *log, prog_origins *from) {
    spray_free(s);
    s->d = *desc;
    spray_desc_resolve(&s->d);
    s->half = (float)half_size;
    s->res = (int)ceil(sqrt((double)s->d.count));
    bool ok = true;
    for (int i = 0; i < 2; i++) {
        s->pos_tex[i] = make_state(s->res);
        s->vel_tex[i] = make_state(s->res);
        glGenFramebuffers(1, &s->fbo[i]);
        glBindFramebuffer(GL_FRAMEBUFFER, s->fbo[i]);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, s->pos_tex[i], 0);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, s->vel_tex[i], 0);
        static const GLenum bufs[2] = { GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1 };
        glDrawBuffers(2, bufs);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) ok = false;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (!ok) diag_add(log, DIAG_ERROR, NULL, 0, "the spray's RGBA32F state targets are not complete on this GL");
    memset(s->progs, 0, sizeof s->progs);
    memset(s->unifs, 0, sizeof s->unifs);
    for (int i = 0; i < SPRAY_PROGS; i++) {
        init_prog(s, i, src);
        if (set_defines) set_defines(ctx, &s->progs[i]);
    }
    s->active = true;
    spray_clear(s);
    return spray_build_programs(s, src, log, from) && ok;
}

void spray_free(gpu_spray *s) {
    if (s->active) {
        for (int i = 0; i < SPRAY_PROGS; i++) prog_free(&s->progs[i]);
        glDeleteFramebuffers(2, s->fbo);
        glDeleteTextures(2, s->pos_tex);
        glDeleteTextures(2, s->vel_tex);
    }
    memset(s, 0, sizeof *s);
}

static void seti(unsigned p, const char *name, int v) {
    GLint loc = glGetUniformLocation(p, name);
    if (loc >= 0) glUniform1i(loc, v);
}

static void bind_state(const gpu_spray *s, int which) {
    glActiveTexture(GL_TEXTURE0 + SPRAY_UNIT_POS);
    glBindTexture(GL_TEXTURE_2D, s->pos_tex[which]);
    glActiveTexture(GL_TEXTURE0 + SPRAY_UNIT_VEL);
    glBindTexture(GL_TEXTURE_2D, s->vel_tex[which]);
    glActiveTexture(GL_TEXTURE0);
}

/* One pass: the state at t - dt moves to t (emission at t). */
static void step(gpu_spray *s, double t, double dt, void (*upload)(const void *, unsigned, double), const void *ctx) {
    unsigned p = s->progs[SPRAY_PROG_UPDATE].gl;
    if (upload) upload(ctx, p, t);
    seti(p, "uSprayPos", SPRAY_UNIT_POS);
    seti(p, "uSprayVel", SPRAY_UNIT_VEL);
    seti(p, "uSprayRes", s->res);
    seti(p, "uSprayCount", s->d.count);
    GLint loc = glGetUniformLocation(p, "uSpraySeed");
    if (loc >= 0) glUniform1ui(loc, s->d.seed);
    loc = glGetUniformLocation(p, "uSprayStep");   /* the step's numbers: of its time, to the millisecond */
    if (loc >= 0) glUniform1ui(loc, (unsigned)(long long)llround(t * 1000.0));
    loc = glGetUniformLocation(p, "uSprayDt");
    if (loc >= 0) glUniform1f(loc, (float)dt);
    double q = s->d.rate * dt / s->d.count;
    loc = glGetUniformLocation(p, "uSprayEmit");
    if (loc >= 0) glUniform4f(loc, (float)s->d.threshold, (float)(q < 1 ? q : 1), (float)s->d.life, s->half);
    loc = glGetUniformLocation(p, "uSprayFd");
    if (loc >= 0) glUniform1f(loc, (float)SPRAY_DT_FD);
    bind_state(s, s->cur);
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo[1 - s->cur]);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    s->cur = 1 - s->cur;
    s->steps++;
}

bool spray_update(gpu_spray *s, double t, gpu_timer *timer, void (*upload)(const void *ctx, unsigned p, double t),
                  const void *ctx) {
    if (!s->active) return false;
    for (int i = 0; i < SPRAY_PROGS; i++)
        if (!s->progs[i].gl) return false;
    if (s->valid && t == s->t) return false;   /* a still frame, or a second view */
    double dt = t - s->t, from = s->t;
    if (!s->valid || dt < 0 || dt > SPRAY_JUMP_DT) {
        spray_clear(s);   /* from empty, a life before t */
        from = t - s->d.life;
    }
    int n = (int)ceil((t - from) / SPRAY_STEP_MAX - 1e-9);
    if (n < 1) n = 1;
    if (timer) gpu_timer_mark(timer, "spray update");
    render_res_pass_state(s->res, s->res);
    render_res_vertexid_begin();   /* the vertices come from gl_VertexID */
    glUseProgram(s->progs[SPRAY_PROG_UPDATE].gl);
    for (int k = 1; k <= n; k++) {
        /* equal steps, the last landing on t exactly */
        double tk = k == n ? t : from + (t - from) * k / n, tprev = k == 1 ? from : from + (t - from) * (k - 1) / n;
        step(s, tk, tk - tprev, upload, ctx);
    }
    render_res_vertexid_end();
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    s->t = t;
    s->valid = true;
    return true;
}

void spray_draw(const gpu_spray *s, const float vp[16], const float eye[3], int w, int h,
                void (*upload)(const void *ctx, unsigned p, double t), const void *ctx) {
    if (!s->active || !s->valid || !s->progs[SPRAY_PROG_DRAW].gl) return;
    unsigned p = s->progs[SPRAY_PROG_DRAW].gl;
    glUseProgram(p);
    if (upload) upload(ctx, p, s->t);
    seti(p, "uSprayPos", SPRAY_UNIT_POS);
    seti(p, "uSprayRes", s->res);
    GLint loc = glGetUniformLocation(p, "uSprayVP");
    if (loc >= 0) glUniformMatrix4fv(loc, 1, GL_FALSE, vp);
    loc = glGetUniformLocation(p, "uSprayEye");
    if (loc >= 0) glUniform3fv(loc, 1, eye);
    loc = glGetUniformLocation(p, "uSpraySize");
    if (loc >= 0) glUniform1f(loc, (float)s->d.size);
    loc = glGetUniformLocation(p, "uSprayViewport");
    if (loc >= 0) glUniform2f(loc, (float)w, (float)h);
    bind_state(s, s->cur);
    GLboolean depth_mask;
    glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);   /* premultiplied */
    glEnable(GL_PROGRAM_POINT_SIZE);
    render_res_vertexid_begin();   /* the vertices come from gl_VertexID */
    glDrawArrays(GL_POINTS, 0, s->d.count);
    render_res_vertexid_end();
    glDisable(GL_PROGRAM_POINT_SIZE);
    glDisable(GL_BLEND);
    glDepthMask(depth_mask);
    glUseProgram(0);
}

void spray_read(const gpu_spray *s, float *pos, float *vel) {
    if (!s->active) return;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, s->fbo[s->cur]);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, s->res, s->res, GL_RGBA, GL_FLOAT, pos);
    glReadBuffer(GL_COLOR_ATTACHMENT1);
    glReadPixels(0, 0, s->res, s->res, GL_RGBA, GL_FLOAT, vel);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}
