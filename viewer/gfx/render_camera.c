#include "render_camera.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <cglm/cglm.h>
#include <math.h>
#include <string.h>

static const char *const cam_names[RENDER_CAMERA_COUNT] = { "main", "wide", "mirror", "top", "light" };
static const char *const vp_uniforms[RENDER_CAMERA_COUNT] = { "uCamMainVP", "uCamWideVP", "uCamMirrorVP",
                                                              "uCamTopVP", "uCamLightVP" };
static const char *const inv_uniforms[RENDER_CAMERA_COUNT] = { "uCamMainInvVP", "uCamWideInvVP",
                                                               "uCamMirrorInvVP", "uCamTopInvVP", "uCamLightInvVP" };

int render_camera_kind_from_name(const char *name) {
    for (int k = 0; k < RENDER_CAMERA_COUNT; k++)
        if (strcmp(name, cam_names[k]) == 0) return k;
    return -1;
}

static void lookat(const render_view *v, mat4 out) {
    vec3 eye, center, up;
    memcpy(eye, v->eye, sizeof eye);
    memcpy(center, v->center, sizeof center);
    memcpy(up, v->up, sizeof up);
    glm_lookat(eye, center, up, out);
}

static void perspective(const render_camera_inputs *in, float scale, mat4 out) {
    if (in->ortho) {
        glm_ortho((float)in->ortho_lrbt[0], (float)in->ortho_lrbt[1], (float)in->ortho_lrbt[2],
                  (float)in->ortho_lrbt[3], -1000.0f, 1000.0f, out);
        return;
    }
    /* widen the field of view by scale, never to 180 degrees */
    double fov = in->fov_deg * (scale > 0 ? scale : 1.0f);
    if (fov > 170.0) fov = 170.0;
    glm_perspective(glm_rad((float)fov), in->aspect, (float)in->near_z, (float)in->far_z, out);
}

/* The reflection about the plane y = level: y -> 2 level - y. */
static void mirror_matrix(double level, mat4 out) {
    glm_mat4_identity(out);
    out[1][1] = -1.0f;
    out[3][1] = (float)(2.0 * level);
}

/* Straight down over the square |x|, |z| <= h: clip x = x / h, clip y = z / h,
 * depth from the top of the world (near) to below its floor (far). */
static void top_matrices(const render_camera_inputs *in, float h, mat4 view, mat4 proj) {
    double ymin = in->level - 2.0 * in->depth - 10.0, ymax = in->level + 50.0, range = ymax - ymin;
    glm_mat4_identity(view);
    glm_mat4_zero(proj);
    proj[0][0] = 1.0f / h;                       /* column-major: proj[col][row] */
    proj[2][1] = 1.0f / h;
    proj[1][2] = (float)(-2.0 / range);
    proj[3][2] = (float)(1.0 + 2.0 * ymin / range);
    proj[3][3] = 1.0f;
}

/* The sun's orthographic view of the world: a box of half size h around the
 * water's centre, the eye h out along the sun, depth over [0, 2h]. Every
 * length follows the world (h does): fixed metres here put a 2.4 km lake
 * outside the depth range and spent the depth buffer's precision on 400 m
 * of nothing over a 24 cm one. */
static void light_matrices(const render_camera_inputs *in, float h, mat4 view, mat4 proj) {
    const double *s = in->sun_dir;
    render_view v = { { 0, 0, 0 }, { 0, (float)in->level, 0 }, { 0, 1, 0 } };
    for (int k = 0; k < 3; k++) v.eye[k] = v.center[k] + (float)(s[k] * h);
    if (fabs(s[1]) > 0.99) { v.up[1] = 0; v.up[2] = 1; }   /* sun overhead: any horizontal up */
    lookat(&v, view);
    glm_ortho(-h, h, -h, h, 0.0f, 2.0f * h, proj);
}

void render_camera_compute(const render_camera_inputs *in, render_camera_set *out) {
    mat4 view, proj, vp, m;
    /* main */
    lookat(&in->view, view);
    perspective(in, in->fov_scale[RENDER_CAMERA_MAIN], proj);
    memcpy(out->view[RENDER_CAMERA_MAIN], view, sizeof view);
    memcpy(out->proj[RENDER_CAMERA_MAIN], proj, sizeof proj);
    /* wide: the main view with its own (widened) field of view */
    memcpy(out->view[RENDER_CAMERA_WIDE], view, sizeof view);
    perspective(in, in->fov_scale[RENDER_CAMERA_WIDE], proj);
    memcpy(out->proj[RENDER_CAMERA_WIDE], proj, sizeof proj);
    /* mirror: the main view of the reflected world */
    mirror_matrix(in->level, m);
    glm_mat4_mul(view, m, vp);
    memcpy(out->view[RENDER_CAMERA_MIRROR], vp, sizeof vp);
    perspective(in, in->fov_scale[RENDER_CAMERA_MIRROR], proj);
    memcpy(out->proj[RENDER_CAMERA_MIRROR], proj, sizeof proj);
    /* top and light */
    out->top_half = (float)(in->half_size * 1.05);
    top_matrices(in, out->top_half, view, proj);
    memcpy(out->view[RENDER_CAMERA_TOP], view, sizeof view);
    memcpy(out->proj[RENDER_CAMERA_TOP], proj, sizeof proj);
    /* the square's corners (1.41 half sizes out), its depth, and what stands
     * on the shore (the lake's tallest object: 4.5 m of 12) */
    out->light_half = (float)(in->half_size * (1.5 + 2.0 / 12.0) + in->depth);
    light_matrices(in, out->light_half, view, proj);
    memcpy(out->view[RENDER_CAMERA_LIGHT], view, sizeof view);
    memcpy(out->proj[RENDER_CAMERA_LIGHT], proj, sizeof proj);
    for (int k = 0; k < RENDER_CAMERA_COUNT; k++) {
        mat4 a, b;
        memcpy(a, out->proj[k], sizeof a);
        memcpy(b, out->view[k], sizeof b);
        glm_mat4_mul(a, b, vp);
        memcpy(out->vp[k], vp, sizeof vp);
        glm_mat4_inv(vp, a);
        memcpy(out->inv_vp[k], a, sizeof a);
    }
}

void render_camera_eye(const render_camera_inputs *in, int kind, float eye[3]) {
    memcpy(eye, in->view.eye, 3 * sizeof(float));
    if (kind == RENDER_CAMERA_MIRROR) eye[1] = (float)(2.0 * in->level - in->view.eye[1]);
}

void render_camera_load(const render_camera_set *c, int kind) {
    glMatrixMode(GL_PROJECTION);
    glLoadMatrixf(c->proj[kind]);
    glMatrixMode(GL_MODELVIEW);
    glLoadMatrixf(c->view[kind]);
    glFrontFace(kind == RENDER_CAMERA_MIRROR ? GL_CW : GL_CCW);
}

void render_camera_upload(const render_camera_set *c, unsigned p) {
    for (int k = 0; k < RENDER_CAMERA_COUNT; k++) {
        GLint loc = glGetUniformLocation(p, vp_uniforms[k]);
        if (loc >= 0) glUniformMatrix4fv(loc, 1, GL_FALSE, c->vp[k]);
        loc = glGetUniformLocation(p, inv_uniforms[k]);
        if (loc >= 0) glUniformMatrix4fv(loc, 1, GL_FALSE, c->inv_vp[k]);
    }
    GLint loc = glGetUniformLocation(p, "uCamTopHalfSize");
    if (loc >= 0) glUniform1f(loc, c->top_half);
    loc = glGetUniformLocation(p, "uCamLightHalfSize");
    if (loc >= 0) glUniform1f(loc, c->light_half);
}
