/* render_ocean: the spectrum ocean's passes (see render_ocean.h).
 *
 * Per frame whose time changed, per cascade layer c:
 *   1. packs/common/ocean_spectrum.frag: h~(k, t) from h0 and w, the four
 *      complex spectra into pair 0 (two MRT targets, A and B);
 *   2. packs/common/ocean_fft.frag: log2 N horizontal, then log2 N vertical
 *      radix-2 Stockham passes, pair 0 -> 1 -> 0 ..., an even count, so the
 *      frame lands in pair 0 in the reference's A/B layout.
 * Each pass is one fullscreen triangle (packs/common/world_height.vert,
 * made from gl_VertexID) into an N x N layer; one draw per layer per pass,
 * cascades * (1 + 2 log2 N) draws a frame (3 cascades of 256^2: 51).
 *   3. packs/common/ocean_foam.frag: the folding foam from the frame's
 *      Jacobian and the foam before (render_ocean.h, OCEAN_FOAM_*), one
 *      draw a cascade, foam ping-pong.
 *
 * Why fragment passes and not compute shaders. (1) The rest of tarn's GPU
 * work is fragment passes into FBOs, timed and state-managed one way
 * (world_update_height); a compute dispatch would need its own barriers
 * (glMemoryBarrier before every read) and GL 4.3, while packs are #version
 * 330 and the program must run where only 3.3 is offered. (2) On Mesa
 * llvmpipe (the CPU machine) a compute shader brings no shared-memory win:
 * its workgroups run as threads of the same CPU cores, with a barrier per
 * butterfly stage, while a fragment pass is the path llvmpipe tiles and
 * threads best (16 x 16 tiles over all cores, SIMD over 8 pixels); a
 * Stockham pass is a gather of two texels per output, exactly what a
 * fragment shader does well, so a shared-memory FFT would save only the
 * texture traffic between stages, which is small at these sizes (a 256^2
 * RGBA32F pair is 2 MiB, cache-resident). (3) On a discrete GPU the
 * fragment version costs 2 log2 N full-screen passes of N^2 texels; at
 * 256^2 that is 16 passes of 65k texels, a few tens of microseconds. The
 * measured costs per size are in tests/test_ocean_gl.c's output and the
 * issue's report. */
#include "render_ocean.h"
#include "render_res.h"
#include "util.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"
#include "strbuf.h"

static unsigned make_array(GLenum internal, GLenum format, int n, int layers, const float *data) {
    unsigned t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D_ARRAY, t);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, (GLint)internal, n, n, layers, 0, format, GL_FLOAT, data);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, 0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    return t;
}

static void init_prog(gpu_ocean *o, int which, const prog_sources *src) {
    static const char *const names[OCEAN_PROGS] = { "OceanSpectrum", "OceanFFTx", "OceanFFTz", "OceanFoam" };
    static const char *const frags[OCEAN_PROGS] = { "ocean_spectrum.frag", "ocean_fft.frag", "ocean_fft.frag",
                                                    "ocean_foam.frag" };
    prog *p = &o->progs[which];
    memset(p, 0, sizeof *p);
    memset(&o->prog_unifs[which], 0, sizeof o->prog_unifs[which]);
    p->unifs = &o->prog_unifs[which];
    p->world_uniforms = true;   /* its uniforms are tarn's, not sliders */
    snprintf(p->name, sizeof p->name, "%s", names[which]);
    snprintf(p->stage_path[SHADER_VERTEX], GLIB_PATH_MAX, "%s/world_height.vert", src->common_dir);
    snprintf(p->stage_path[SHADER_FRAGMENT], GLIB_PATH_MAX, "%s/%s", src->common_dir, frags[which]);
    if (which == OCEAN_PROG_FFT_V) {
        snprintf(p->fixed[0].name, sizeof p->fixed[0].name, "OCEAN_FFT_VERTICAL");
        snprintf(p->fixed[0].value, sizeof p->fixed[0].value, "1");
    }
}

bool ocean_build_programs(gpu_ocean *o, const prog_sources *src, diag_list *log, prog_origins *from) {
    if (!o->active) return true;
    bool ok = true;
    for (int i = 0; i < OCEAN_PROGS; i++) {
        if (!prog_build(&o->progs[i], src, log, from)) ok = false;
        prog_introspect(&o->progs[i], log);
    }
    return ok;
}

bool ocean_create(gpu_ocean *o, int cascades, int res, const float *tile, float lambda, const float *h0,
                  const float *omega, const prog_sources *src,  diag_list *log,
                  prog_origins *from) {
    ocean_free(o);
    if (cascades < 1 || cascades > REF_OCEAN_CASCADES_MAX || res < 2 || (res & (res - 1)) != 0) {
        diag_add(log, DIAG_ERROR, NULL, 0, "the ocean's %d cascades of %d^2 are not what the GPU passes take",
                 cascades, res);
        return false;
    }
    o->cascades = cascades;
    o->res = res;
    while ((1 << o->log2res) < res) o->log2res++;
    for (int c = 0; c < cascades; c++) o->tile[c] = tile[c];
    o->lambda = lambda;
    o->h0_tex = make_array(GL_RGBA32F, GL_RGBA, res, cascades, h0);
    o->omega_tex = make_array(GL_R32F, GL_RED, res, cascades, omega);
    for (int p = 0; p < 2; p++)
        for (int s = 0; s < 2; s++) o->tex[p][s] = make_array(GL_RGBA32F, GL_RGBA, res, cascades, NULL);
    bool ok = true;
    for (int p = 0; p < 2; p++) {
        glGenFramebuffers(cascades, o->fbo[p]);
        for (int c = 0; c < cascades; c++) {
            glBindFramebuffer(GL_FRAMEBUFFER, o->fbo[p][c]);
            glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, o->tex[p][0], 0, c);
            glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, o->tex[p][1], 0, c);
            static const GLenum bufs[2] = { GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1 };
            glDrawBuffers(2, bufs);
            if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) ok = false;
        }
    }
    /* the foam, zero at first (the first update restarts it anyway) */
    float *zero = mem_zalloc((size_t)res * res * cascades * 2 * sizeof(float));
    for (int p = 0; p < 2; p++) {
        o->foam_tex[p] = make_array(GL_RG32F, GL_RG, res, cascades, zero);
        glGenFramebuffers(cascades, o->foam_fbo[p]);
        for (int c = 0; c < cascades; c++) {
            glBindFramebuffer(GL_FRAMEBUFFER, o->foam_fbo[p][c]);
            glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, o->foam_tex[p], 0, c);
            glDrawBuffer(GL_COLOR_ATTACHMENT0);
            if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) ok = false;
        }
    }
    free(zero);
    /* each cascade's slope variance, the mean of hx^2 + hz^2 over its tile
     * in time: sum over k of |k|^2 (|h0(k)|^2 + |h0(-k)|^2) (the transform
     * is unnormalised, as ref_ocean_variance's sum of h; k = 0 and the
     * Nyquist row and column are not drawn, ocean_spectrum.frag) */
    for (int c = 0; c < cascades; c++) {
        double v = 0;
        for (int j = 0; j < res; j++)
            for (int i = 0; i < res; i++) {
                if (i == res / 2 || j == res / 2) continue;
                double kx = 2 * 3.14159265358979323846 * (i < res / 2 ? i : i - res) / tile[c];
                double kz = 2 * 3.14159265358979323846 * (j < res / 2 ? j : j - res) / tile[c];
                const float *t = h0 + (((size_t)c * res + j) * res + i) * 4;
                v += (kx * kx + kz * kz) * ((double)t[0] * t[0] + (double)t[1] * t[1] + (double)t[2] * t[2] +
                                            (double)t[3] * t[3]);
            }
        o->slope_var[c] = (float)v;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (!ok) diag_add(log, DIAG_ERROR, NULL, 0, "the ocean's RGBA32F targets are not complete on this GL");
    for (int i = 0; i < OCEAN_PROGS; i++) init_prog(o, i, src);
    o->active = true;
    return ocean_build_programs(o, src, log, from) && ok;
}

bool ocean_create_from(gpu_ocean *o, const ref_ocean *ref, const prog_sources *src,
                        diag_list *log, prog_origins *from) {
    const ref_ocean_desc *d = ref_ocean_get_desc(ref);
    int n = d->res, nc = d->cascades;
    size_t texels = (size_t)n * n;
    float *h0 = mem_alloc(texels * nc * 4 * sizeof(float));
    float *omega = mem_alloc(texels * nc * sizeof(float));
    float tile[REF_OCEAN_CASCADES_MAX];
    for (int c = 0; c < nc; c++) {
        ref_ocean_gpu_spectrum(ref, c, h0 + texels * 4 * c, omega + texels * c);
        tile[c] = (float)d->tile[c];
    }
    bool ok = ocean_create(o, nc, n, tile, (float)d->choppiness, h0, omega, src, log, from);
    free(h0);
    free(omega);
    return ok;
}

void ocean_free(gpu_ocean *o) {
    if (!o->active) {
        memset(o, 0, sizeof *o);
        return;
    }
    for (int i = 0; i < OCEAN_PROGS; i++) prog_free(&o->progs[i]);
    for (int p = 0; p < 2; p++) {
        glDeleteFramebuffers(o->cascades, o->fbo[p]);
        glDeleteTextures(2, o->tex[p]);
    }
    for (int p = 0; p < 2; p++) glDeleteFramebuffers(o->cascades, o->foam_fbo[p]);
    glDeleteTextures(2, o->foam_tex);
    glDeleteTextures(1, &o->h0_tex);
    glDeleteTextures(1, &o->omega_tex);
    memset(o, 0, sizeof *o);
}

static void bind_array(int unit, unsigned tex) {
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_2D_ARRAY, tex);
}

void ocean_bind(const gpu_ocean *o) {
    if (!o->active) return;
    bind_array(OCEAN_UNIT_A, o->tex[0][0]);
    bind_array(OCEAN_UNIT_B, o->tex[0][1]);
    bind_array(OCEAN_UNIT_FOAM, o->foam_tex[o->foam_cur]);
    glActiveTexture(GL_TEXTURE0);
}

static void seti(unsigned p, const char *name, int v) {
    GLint loc = glGetUniformLocation(p, name);
    if (loc >= 0) glUniform1i(loc, v);
}

void ocean_upload(unsigned p) {
    seti(p, "uOceanA", OCEAN_UNIT_A);
    seti(p, "uOceanB", OCEAN_UNIT_B);
    seti(p, "uOceanFoam", OCEAN_UNIT_FOAM);
}

static unsigned long long progs_hash(const gpu_ocean *o) {
    unsigned long long h = HASH_FNV1A_BASIS;
    for (int i = 0; i < OCEAN_PROGS; i++) h = hash_fnv1a(h, &o->progs[i].hash, sizeof o->progs[i].hash);
    return h;
}

bool ocean_update(gpu_ocean *o, double t, gpu_timer *timer) {
    if (!o->active) return false;
    for (int i = 0; i < OCEAN_PROGS; i++)
        if (!o->progs[i].gl) return false;
    unsigned long long hash = progs_hash(o);
    if (o->valid && t == o->t && hash == o->hash) {
        ocean_bind(o);
        return false;   /* a still frame, or a second view */
    }
    int n = o->res;
    render_res_pass_state(n, n);
    render_res_vertexid_begin();   /* the vertices come from gl_VertexID */

    /* the spectrum, into pair 0 */
    if (timer) gpu_timer_mark(timer, "ocean spectrum");
    unsigned p = o->progs[OCEAN_PROG_SPECTRUM].gl;
    glUseProgram(p);
    bind_array(OCEAN_UNIT_A, o->h0_tex);
    bind_array(OCEAN_UNIT_B, o->omega_tex);
    seti(p, "uOceanH0", OCEAN_UNIT_A);
    seti(p, "uOceanOmega", OCEAN_UNIT_B);
    seti(p, "uOceanPassRes", n);
    GLint loc = glGetUniformLocation(p, "uOceanLambda");
    if (loc >= 0) glUniform1f(loc, o->lambda);
    loc = glGetUniformLocation(p, "uTime");
    if (loc >= 0) glUniform1f(loc, (float)t);
    GLint layer = glGetUniformLocation(p, "uOceanLayer"), tile = glGetUniformLocation(p, "uOceanPassTile");
    for (int c = 0; c < o->cascades; c++) {
        glBindFramebuffer(GL_FRAMEBUFFER, o->fbo[0][c]);
        glUniform1i(layer, c);
        glUniform1f(tile, o->tile[c]);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }

    /* log2 N passes along x, then along z */
    if (timer) gpu_timer_mark(timer, "ocean fft");
    int src = 0;
    for (int dir = 0; dir < 2; dir++) {
        p = o->progs[dir == 0 ? OCEAN_PROG_FFT_H : OCEAN_PROG_FFT_V].gl;
        glUseProgram(p);
        seti(p, "uOceanSrcA", OCEAN_UNIT_A);
        seti(p, "uOceanSrcB", OCEAN_UNIT_B);
        seti(p, "uOceanPassRes", n);
        layer = glGetUniformLocation(p, "uOceanLayer");
        GLint size = glGetUniformLocation(p, "uOceanSize");
        for (int s = 2; s <= n; s <<= 1) {
            bind_array(OCEAN_UNIT_A, o->tex[src][0]);
            bind_array(OCEAN_UNIT_B, o->tex[src][1]);
            glUniform1i(size, s);
            for (int c = 0; c < o->cascades; c++) {
                glBindFramebuffer(GL_FRAMEBUFFER, o->fbo[1 - src][c]);
                glUniform1i(layer, c);
                glDrawArrays(GL_TRIANGLES, 0, 3);
            }
            src = 1 - src;
        }
    }

    /* the foam: decayed by the time step since the foam's time, topped up
     * with this frame's coverage; restarted from the coverage after a jump
     * (backwards, or over OCEAN_FOAM_RESET_DT); a step of 0 (the programs
     * rebuilt, same time) decays nothing */
    if (timer) gpu_timer_mark(timer, "ocean foam");
    double dt = t - o->foam_t;
    bool reset = !o->foam_valid || dt < 0 || dt > OCEAN_FOAM_RESET_DT;
    float keep = reset ? 0.0f : (float)exp(-dt / OCEAN_FOAM_DECAY);
    if (reset) o->foam_resets++;
    p = o->progs[OCEAN_PROG_FOAM].gl;
    glUseProgram(p);
    bind_array(OCEAN_UNIT_A, o->tex[0][0]);
    bind_array(OCEAN_UNIT_B, o->tex[0][1]);
    bind_array(OCEAN_UNIT_FOAM, o->foam_tex[o->foam_cur]);
    seti(p, "uOceanSrcA", OCEAN_UNIT_A);
    seti(p, "uOceanSrcB", OCEAN_UNIT_B);
    seti(p, "uOceanFoamPrev", OCEAN_UNIT_FOAM);
    loc = glGetUniformLocation(p, "uOceanFoamKeep");
    if (loc >= 0) glUniform1f(loc, keep);
    loc = glGetUniformLocation(p, "uOceanFoamJ");
    if (loc >= 0) glUniform1f(loc, (float)OCEAN_FOAM_J);
    loc = glGetUniformLocation(p, "uOceanFoamSoft");
    if (loc >= 0) glUniform1f(loc, (float)OCEAN_FOAM_SOFT);
    layer = glGetUniformLocation(p, "uOceanLayer");
    GLint var = glGetUniformLocation(p, "uOceanSlopeVar");
    for (int c = 0; c < o->cascades; c++) {
        glBindFramebuffer(GL_FRAMEBUFFER, o->foam_fbo[1 - o->foam_cur][c]);
        glUniform1i(layer, c);
        glUniform1f(var, o->slope_var[c]);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    o->foam_cur = 1 - o->foam_cur;
    o->foam_t = t;
    o->foam_valid = true;

    render_res_vertexid_end();
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    ocean_bind(o);   /* src is 0 again: the frame */
    o->t = t;
    o->hash = hash;
    o->valid = true;
    o->frames++;
    return true;
}

void ocean_read_foam(const gpu_ocean *o, int c, float *foam) {
    if (!o->active) return;
    GLuint fbo;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glFramebufferTextureLayer(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, o->foam_tex[o->foam_cur], 0, c);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, o->res, o->res, GL_RG, GL_FLOAT, foam);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
}

void ocean_read(const gpu_ocean *o, int c, float *a, float *b) {
    if (!o->active) return;
    GLuint fbo;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    for (int s = 0; s < 2; s++) {
        glFramebufferTextureLayer(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, o->tex[0][s], 0, c);
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glReadPixels(0, 0, o->res, o->res, GL_RGBA, GL_FLOAT, s == 0 ? a : b);
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
}
