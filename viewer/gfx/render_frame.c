/* render_frame: a frame: the water's state advanced to its time, GL's
 * state as glman starts one, the cameras, the scene's commands
 * (render_exec.c), the spray over it and the multisample resolve. */
#include "util.h"
#include "render_internal.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <string.h>

static float camera_scale(const scene_state *s, int ci) {
    float v = render_exec_cmd_number(s, ci, 1.0f);
    return v > 0 ? v : 1.0f;
}

static void camera_inputs(const render *r, const render_view *v, int w, int h, render_camera_inputs *out) {
    const scene_state *s = &r->cur;
    const scene_settings *set = &s->set;
    const scene_camera *sc = &set->cam;
    render_camera_inputs in = { .view = *v, .fov_deg = sc->fov_deg, .near_z = sc->near_z, .far_z = sc->far_z,
                                .ortho = sc->ortho, .aspect = h > 0 ? (float)w / (float)h : 1.0f,
                                .level = 0, .half_size = 12, .depth = 3, .sun_dir = { 0, 1, 0 } };
    memcpy(in.ortho_lrbt, sc->ortho_lrbt, sizeof in.ortho_lrbt);
    for (int k = 0; k < RENDER_CAMERA_COUNT; k++) in.fov_scale[k] = 1.0f;
    if (r->world.active) {
        const ref_world_desc *d = &r->world.w.d;
        in.level = d->water_level;
        in.half_size = d->half_size;
        in.depth = d->depth;
        memcpy(in.sun_dir, d->sun_dir, sizeof in.sun_dir);
        /* the land reaches REF_WORLD_HORIZON, as in the reference (a glib's
         * far plane of 200 m cut off land it draws); the skirt's corners lie
         * up to sqrt 2 times that away, so 4 times clears them. Depth
         * precision hardly changes: it is set by the near plane. */
        if (in.far_z < 4.0 * REF_WORLD_HORIZON) in.far_z = 4.0 * REF_WORLD_HORIZON;
    }
    for (int i = 0; i < s->glib->ncmds; i++) {
        const glib_cmd *c = &s->glib->cmds[i];
        int k = c->kind == GLIB_CMD_CAMERA ? render_camera_kind_from_name(c->name) : -1;
        if (k >= 0) in.fov_scale[k] = camera_scale(s, i);
    }
    *out = in;
}

/* The water's state at time t, before the frame binds its target: the
 * ocean's passes, then the height map, which reads them; each leaves the
 * frame's own passes "screen" again. A world-only frame keeps the last
 * frame's: the water's state is not its to advance. */
static void update_water(render *r, double t) {
    if (!r->cur.glib || r->world_only) return;
    if (world_update_ocean(&r->world, t, &r->timer)) gpu_timer_mark(&r->timer, "screen");
    if (world_update_flow(&r->world, t, &r->timer)) gpu_timer_mark(&r->timer, "screen");
    if (r->draw_timing) render_timing_mark_now(r, "world height");
    world_update_height(&r->world, t, r->detail);
    /* the spray after the height map: an ocean's upward speed is read from it */
    if (world_update_spray(&r->world, t, &r->timer)) gpu_timer_mark(&r->timer, "screen");
}

/* The rectangle cleared to the scene's Background, GL in glman's state:
 * Flat, LineWidth, PointSize and PointSizeMode of the last frame do not
 * leak into the first draws. */
static void start_gl_state(unsigned fbo, int x, int y, int w, int h, const float *bg) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(x, y, w, h);
    glScissor(x, y, w, h);   /* the clear stays inside the scene's rectangle */
    glEnable(GL_SCISSOR_TEST);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glColor4f(1, 1, 1, 1);
    glShadeModel(GL_SMOOTH);
    glLineWidth(1);
    glPointSize(1);
    glDisable(GL_PROGRAM_POINT_SIZE);
    glClearColor(bg[0], bg[1], bg[2], bg[3]);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
}

/* Every camera of the frame from view v, the main one loaded. */
static void start_cameras(const render *r, frame_state *f, const render_view *v) {
    memcpy(f->eye, v->eye, sizeof f->eye);
    camera_inputs(r, v, f->w, f->h, &f->cam_in);
    render_camera_compute(&f->cam_in, &f->cams);
    render_camera_load(&f->cams, RENDER_CAMERA_MAIN);
    f->cam_kind = RENDER_CAMERA_MAIN;
    memcpy(f->cam_eye, v->eye, sizeof f->cam_eye);
}

/* The droplets over the finished frame (render_spray.h), the main camera's. */
static void draw_spray(render *r, const frame_state *f) {
    if (!r->world.spray.active || f->in_rtt || r->world_only) return;
    gpu_timer_mark(&r->timer, "spray draw");
    glBindFramebuffer(GL_FRAMEBUFFER, f->screen_fbo);
    glViewport(f->x, f->y, f->w, f->h);
    world_draw_spray(&r->world, f->cams.vp[RENDER_CAMERA_MAIN], f->eye, f->w, f->h);
}

/* What the commands left is undone for the caller and the next frame. */
static void end_commands(render *r, frame_state *f) {
    for (; f->depth > 0; f->depth--)   /* unbalanced PushMatrix in the glib */
        if (f->depth <= MATRIX_STACK_MAX) glPopMatrix();
    glPopMatrix();
    if (f->in_rtt) render_exec_end_pass(f);
    if (f->in_once) world_set_detail(&r->world, r->detail);
    glUseProgram(0);
    glFrontFace(GL_CCW);
    if (!r->world_only) r->nkept_once = 0;   /* the first frame after a load has decided every block */
}

/* The scene's commands into fbo's rectangle (cleared already) at time t. */
static void run_scene(render *r, double t, unsigned fbo, int x, int y, int w, int h, const render_view *view) {
    const scene_state *s = &r->cur;
    render_view v = view ? *view : s->set.view;
    render_size_targets(r, w, h);
    world_set_detail(&r->world, r->detail);
    world_follow_waves(&r->world, t);
    render_exec_bind_textures(r);
    frame_state f = { .screen_fbo = fbo, .x = x, .y = y, .w = w, .h = h, .t = t, .clean = true };
    memcpy(f.clean_rgba, s->set.background, sizeof f.clean_rgba);   /* cleared to it (start_gl_state) */
    start_cameras(r, &f, &v);
    glPushMatrix();
    f.patch_vertices = 3;   /* GL's default patch size */
    f.patch_cmd = -1;
    for (int k = 0; k < 16 && glGetError() != GL_NO_ERROR; k++) {}   /* not ours: the caller's */
    f.check_each = r->gl_check_each;
    render_exec_commands(r, &f);
    draw_spray(r, &f);
    render_check_frame_errors(r, &f);
    end_commands(r, &f);
}

void render_frame(render *r, double t, unsigned fbo, int w, int h, const render_view *view) {
    render_frame_at(r, t, fbo, 0, 0, w, h, view);
}

void render_frame_at(render *r, double t, unsigned fbo, int x, int y, int w, int h, const render_view *view) {
    gpu_timer_begin_frame(&r->timer);
    const scene_state *s = &r->cur;
    /* the screen passes go to the multisampled target, resolved at the end */
    unsigned dest = fbo;
    int dest_x = x, dest_y = y;
    world_snapshot_frame(&r->snap);
    update_water(r, t);
    bool ms = s->glib && render_msaa_begin(&r->msaa, render_samples(r), fbo, w, h, r->world.active);
    if (ms) { fbo = r->msaa.fbo; x = 0; y = 0; }
    start_gl_state(fbo, x, y, w, h, s->set.background);
    if (s->glib) run_scene(r, t, fbo, x, y, w, h, view);
    if (ms) render_msaa_resolve(&r->msaa, dest, dest_x, dest_y);
    if (s->glib && !s->flat_checked && !r->world_only) render_check_flat_picture(r, dest, dest_x, dest_y, w, h);
    gpu_timer_end_frame(&r->timer);
}

void render_frame_world_at(render *r, double t, unsigned fbo, int x, int y, int w, int h, const render_view *view) {
    double detail = r->detail;
    r->detail = 1.0;
    r->world_only = true;
    render_frame_at(r, t, fbo, x, y, w, h, view);
    r->world_only = false;
    r->detail = detail;
    world_set_detail(&r->world, detail);
}
