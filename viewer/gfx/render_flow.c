/* render_flow: the flow map's backward advection (see render_flow.h).
 *
 * Why a map of displacements and not of the detail itself: advecting a
 * texture of ripples by repeated bilinear lookups blurs it a little every
 * frame (numerical diffusion: after a second at 60 frames the ripples
 * would be gone), while the displacement d = x - source is smooth (linear
 * in x for a current or inside a vortex's core), so bilinear lookups keep
 * it nearly exact, and the ripples are drawn sharp at x - d. Why RGBA32F:
 * d is summed over ~180 frames a period; half floats (11 bits) would round
 * off ~1 mm each step at 2-4 m. */
#include "render_flow.h"
#include "render_res.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image_io.h"
#include "strbuf.h"

void flow_desc_resolve(ref_flow_desc *d) {
    if (!(d->detail_amp > 0)) d->detail_amp = FLOW_DEFAULT_AMP;
    if (!(d->detail_cell > 0)) d->detail_cell = FLOW_DEFAULT_CELL;
    if (!(d->period > 0)) d->period = FLOW_DEFAULT_PERIOD;
    if (!(d->foam > 0)) d->foam = 0;
}

double flow_phase(int layer, double t, double period) {
    double q = t / period + (layer ? 0.5 : 0.0);
    return q - floor(q);
}

void flow_velocity(const ref_flow_desc *d, double x, double z, double v[2]) {
    v[0] = v[1] = 0;
    for (int i = 0; i < d->nterms && i < REF_FLOW_TERMS_MAX; i++) {
        const ref_flow_term *t = &d->term[i];
        if (t->kind == REF_FLOW_CURRENT) {
            v[0] += t->p[0];
            v[1] += t->p[1];
            continue;
        }
        double rx = x - t->p[0], rz = z - t->p[1], r = sqrt(rx * rx + rz * rz), R = t->p[3];
        if (!(r > 0)) continue;
        double speed = r < R ? t->p[2] * r / R : t->p[2] * R / r;
        v[0] += speed * -rz / r;
        v[1] += speed * rx / r;
    }
}

/* A 2D texture of one level, linear and clamped at its edges (the flow's
 * maps and its velocity map), from data (NULL: undefined). */
static unsigned linear_clamped(GLenum internal, int w, int h, GLenum format, const float *data) {
    unsigned t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, w, h, 0, format, GL_FLOAT, data);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    glBindTexture(GL_TEXTURE_2D, 0);
    return t;
}

static unsigned make_map(void) { return linear_clamped(GL_RGBA32F, FLOW_RES, FLOW_RES, GL_RGBA, NULL); }

/* A Flow texture's velocity map: R and G of the file (file order: its top
 * row at z = -half, GL's first row), linear, clamped at the edges. */
static bool load_velocity(gpu_flow *f, const prog_sources *src, diag_list *log) {
    img im = { 0 };
    char err[MSG_MAX];
    if (!render_res_read_image(src->files, f->d.texture, &im, err, sizeof err) || im.d != 1) {
        diag_add(log, DIAG_ERROR, NULL, 0, "Flow texture: %s", im.d > 1 ? "a volume is not a velocity map" : err);
        img_free(&im);
        return false;
    }
    float *rg = malloc((size_t)im.w * im.h * 2 * sizeof(float));
    if (!rg) { img_free(&im); return false; }
    for (size_t i = 0; i < (size_t)im.w * im.h; i++) {
        rg[2 * i] = im.px[i * im.channels];
        rg[2 * i + 1] = im.channels > 1 ? im.px[i * im.channels + 1] : 0.5f;   /* a grey map: no vz */
    }
    f->vel_tex = linear_clamped(GL_RG32F, im.w, im.h, GL_RG, rg);
    free(rg);
    img_free(&im);
    return true;
}

bool flow_build_program(gpu_flow *f, const prog_sources *src, diag_list *log, prog_origins *from) {
    if (!f->active) return true;
    bool ok = prog_build(&f->prog, src, log, from);
    prog_introspect(&f->prog, log);
    return ok;
}

bool flow_create(gpu_flow *f, const ref_flow_desc *desc, double half_size, const prog_sources *src,
                  diag_list *log, prog_origins *from) {
    flow_free(f);
    f->d = *desc;
    flow_desc_resolve(&f->d);
    f->half = (float)(FLOW_MARGIN * half_size);
    bool ok = true;
    for (int i = 0; i < 2; i++) {
        f->tex[i] = make_map();
        glGenFramebuffers(1, &f->fbo[i]);
        glBindFramebuffer(GL_FRAMEBUFFER, f->fbo[i]);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, f->tex[i], 0);
        glDrawBuffer(GL_COLOR_ATTACHMENT0);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) ok = false;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (!ok) diag_add(log, DIAG_ERROR, NULL, 0, "the flow map's RGBA32F target is not complete on this GL");
    if (f->d.texture[0] && !load_velocity(f, src, log)) ok = false;
    prog *p = &f->prog;
    memset(p, 0, sizeof *p);
    memset(&f->unifs, 0, sizeof f->unifs);
    p->unifs = &f->unifs;
    p->world_uniforms = true;   /* tarn's uniforms, not sliders */
    snprintf(p->name, sizeof p->name, "FlowAdvect");
    snprintf(p->stage_path[SHADER_VERTEX], GLIB_PATH_MAX, "%s/world_height.vert", src->common_dir);
    snprintf(p->stage_path[SHADER_FRAGMENT], GLIB_PATH_MAX, "%s/flow_advect.frag", src->common_dir);
    f->active = true;
    return flow_build_program(f, src, log, from) && ok;
}

void flow_free(gpu_flow *f) {
    if (f->active) {
        prog_free(&f->prog);
        glDeleteFramebuffers(2, f->fbo);
        glDeleteTextures(2, f->tex);
        if (f->vel_tex) glDeleteTextures(1, &f->vel_tex);
    }
    memset(f, 0, sizeof *f);
}

void flow_bind(const gpu_flow *f) {
    if (!f->active) return;
    glActiveTexture(GL_TEXTURE0 + FLOW_UNIT);
    glBindTexture(GL_TEXTURE_2D, f->tex[f->cur]);
    glActiveTexture(GL_TEXTURE0);
}

/* The terms and the map's frame: every program that includes flow.glsl. */
static void upload_field(const gpu_flow *f, unsigned p) {
    GLint loc = glGetUniformLocation(p, "uFlowN");
    if (loc >= 0) glUniform1i(loc, f->d.nterms);
    int kind[REF_FLOW_TERMS_MAX] = { 0 };
    float term[REF_FLOW_TERMS_MAX][4] = { { 0 } };
    for (int i = 0; i < f->d.nterms; i++) {
        kind[i] = (int)f->d.term[i].kind;
        for (int k = 0; k < 4; k++) term[i][k] = (float)f->d.term[i].p[k];
    }
    loc = glGetUniformLocation(p, "uFlowKind");
    if (loc >= 0) glUniform1iv(loc, REF_FLOW_TERMS_MAX, kind);
    loc = glGetUniformLocation(p, "uFlowTerm");
    if (loc >= 0) glUniform4fv(loc, REF_FLOW_TERMS_MAX, &term[0][0]);
    loc = glGetUniformLocation(p, "uFlowRect");
    if (loc >= 0) glUniform2f(loc, f->half, 1.0f / (2.0f * f->half));
}

void flow_upload(const gpu_flow *f, unsigned p) {
    if (!f->active || !p) return;
    upload_field(f, p);
    GLint loc = glGetUniformLocation(p, "uFlowMap");
    if (loc >= 0) glUniform1i(loc, FLOW_UNIT);
    loc = glGetUniformLocation(p, "uFlowDetail");
    if (loc >= 0)
        glUniform4f(loc, (float)f->d.detail_amp, (float)(1.0 / f->d.detail_cell), (float)f->d.foam, 0.0f);
    double wa = 1.0 - fabs(2.0 * flow_phase(0, f->t, f->d.period) - 1.0);
    loc = glGetUniformLocation(p, "uFlowWeight");
    if (loc >= 0) glUniform2f(loc, (float)wa, (float)(1.0 - wa));
}

/* One pass: layer L moves by dt[L], restarting first when reset[L]. */
static void step(gpu_flow *f, const float dt[2], const float reset[2]) {
    unsigned p = f->prog.gl;
    glBindFramebuffer(GL_FRAMEBUFFER, f->fbo[1 - f->cur]);
    glActiveTexture(GL_TEXTURE0 + FLOW_UNIT);
    glBindTexture(GL_TEXTURE_2D, f->tex[f->cur]);
    glActiveTexture(GL_TEXTURE0);
    GLint loc = glGetUniformLocation(p, "uFlowStepDt");
    if (loc >= 0) glUniform2f(loc, dt[0], dt[1]);
    loc = glGetUniformLocation(p, "uFlowStepReset");
    if (loc >= 0) glUniform2f(loc, reset[0], reset[1]);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    f->cur = 1 - f->cur;
    f->steps++;
}

bool flow_update(gpu_flow *f, double t, gpu_timer *timer) {
    if (!f->active || !f->prog.gl) return false;
    if (f->valid && t == f->t) {
        flow_bind(f);
        return false;   /* a still frame, or a second view */
    }
    double T = f->d.period, dt = t - f->t;
    bool jump = !f->valid || dt < 0 || dt > FLOW_JUMP_DT || dt > 0.5 * T;
    if (timer) gpu_timer_mark(timer, "flow advect");
    render_res_pass_state(FLOW_RES, FLOW_RES);
    render_res_vertexid_begin();   /* the vertices come from gl_VertexID */
    unsigned p = f->prog.gl;
    glUseProgram(p);
    upload_field(f, p);
    GLint loc = glGetUniformLocation(p, "uFlowPrev");
    if (loc >= 0) glUniform1i(loc, FLOW_UNIT);
    loc = glGetUniformLocation(p, "uFlowPassRes");
    if (loc >= 0) glUniform1f(loc, (float)FLOW_RES);
    loc = glGetUniformLocation(p, "uFlowVel");   /* set, with or without a map: a sampler left on unit 0 */
    if (loc >= 0) glUniform1i(loc, FLOW_UNIT_VEL);
    loc = glGetUniformLocation(p, "uFlowVelHalf");
    if (loc >= 0) glUniform1f(loc, (float)(f->half / FLOW_MARGIN));
    glActiveTexture(GL_TEXTURE0 + FLOW_UNIT_VEL);
    glBindTexture(GL_TEXTURE_2D, f->vel_tex);
    glActiveTexture(GL_TEXTURE0);
    float age[2] = { (float)(flow_phase(0, t, T) * T), (float)(flow_phase(1, t, T) * T) };
    if (jump) {
        /* from both layers' restarts to t in equal steps of each one's age */
        float sdt[2] = { age[0] / FLOW_CATCHUP_STEPS, age[1] / FLOW_CATCHUP_STEPS };
        float on[2] = { 1, 1 }, off[2] = { 0, 0 };
        for (int s = 0; s < FLOW_CATCHUP_STEPS; s++) step(f, sdt, s == 0 ? on : off);
        f->catchups++;
    } else {
        /* a layer whose phase wrapped since f->t restarted at t - age */
        float sdt[2], reset[2];
        for (int l = 0; l < 2; l++) {
            double o = l ? 0.5 : 0.0;
            bool wrapped = floor(t / T + o) != floor(f->t / T + o);
            reset[l] = wrapped ? 1.0f : 0.0f;
            sdt[l] = wrapped ? age[l] : (float)dt;
        }
        step(f, sdt, reset);
    }
    render_res_vertexid_end();
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    flow_bind(f);
    f->t = t;
    f->valid = true;
    return true;
}

void flow_read(const gpu_flow *f, float *rgba) {
    if (!f->active) return;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, f->fbo[f->cur]);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, FLOW_RES, FLOW_RES, GL_RGBA, GL_FLOAT, rgba);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}
