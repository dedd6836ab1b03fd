/* `tarn view`: the interactive window. Draws the scene, the generated slider
 * panel and any error overlay; watches every file the scene reads and
 * reloads within a frame or two of a save; orbit/pan/zoom camera. */
#include <GL/gl.h>
#include <GLFW/glfw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "exit_code.h"
#include "view.h"
#include "gl_ctx.h"
#include "image_io.h"
#include "panel.h"
#include "render.h"
#include "view_script.h"
#include "view_util.h"
#include "watch.h"

#define PANEL_WIDTH 440   /* the slider panel's column, left of the scene */

typedef struct viewer {
    gl_ctx *ctx;
    GLFWwindow *win;
    render *r;
    panel *panel;
    watch *watch;
    orbit cam, cam_home;
    double t, last_wall;
    bool paused;
    view_mouse mouse;
    int shots;
    double fps;
} viewer;

/* ---- actions ---- */

static void report_load(viewer *v) {
    const char *m = render_messages(v->r);
    if (m[0]) fputs(m, stderr);
    else fprintf(stderr, "tarn: loaded %s\n", render_scene_path(v->r));
}

/* A dependency in a directory that does not exist (a typo in the glib)
 * cannot be watched; watch the rest rather than nothing. */
static bool dir_exists(const char *path) {
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", path);
    char *slash = strrchr(dir, '/');
    if (!slash) return true;
    *slash = '\0';
    struct stat st;
    return stat(dir[0] ? dir : "/", &st) == 0 && S_ISDIR(st.st_mode);
}

static void rewatch(viewer *v) {
    if (!v->watch) return;
    const char *const *paths;
    int n = render_deps(v->r, &paths);
    char err[512];
    if (watch_set_files(v->watch, paths, n, err, sizeof err)) return;
    const char **ok = calloc((size_t)n + 1, sizeof *ok);
    int nok = 0;
    for (int i = 0; ok && i < n; i++)
        if (dir_exists(paths[i])) ok[nok++] = paths[i];
    if (!ok || !watch_set_files(v->watch, ok, nok, err, sizeof err))
        fprintf(stderr, "tarn: watching files: %s\n", err);
    free(ok);
}

static void reload(viewer *v) {
    render_load(v->r, NULL);
    report_load(v);
    rewatch(v);
}

static bool screenshot(viewer *v, const char *path) { return view_screenshot(v->win, path); }

static void preset(viewer *v, bool save) {
    char path[1100], err[512] = "";
    unif_preset_path(render_scene_path(v->r), path, (int)sizeof path);
    int n;
    unif_set *sets = render_uniforms(v->r, &n);
    bool ok = save ? unif_preset_save(sets, n, path, err, sizeof err)
                   : unif_preset_load(sets, n, path, err, sizeof err);
    if (ok && !save) render_rebuild_programs(v->r);   /* defines may have changed */
    fprintf(stderr, "tarn: %s preset %s%s%s\n", save ? "save" : "load", path, ok ? "" : ": ", ok ? "" : err);
}

static void apply_actions(viewer *v, const panel_actions *a) {
    int n;
    unif_set *sets = render_uniforms(v->r, &n);
    if (a->reset_all)
        for (int i = 0; i < n; i++) unif_reset_all(&sets[i]);
    if (a->recompile || a->reset_all) {
        render_rebuild_programs(v->r);
        report_load(v);
        rewatch(v);
    }
    if (a->save_preset) preset(v, true);
    if (a->load_preset) preset(v, false);
    if (a->reload) reload(v);
    if (a->toggle_pause) v->paused = !v->paused;
    if (a->screenshot) {
        char path[128];
        view_shot_path(v->shots++, path, sizeof path);
        screenshot(v, path);
    }
}

/* ---- input ---- */

static void on_scroll(GLFWwindow *w, double dx, double dy) {
    viewer *v = glfwGetWindowUserPointer(w);
    if (!v->panel || !panel_wants_mouse(v->panel)) v->mouse.scroll += dy;
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods) {
    viewer *v = glfwGetWindowUserPointer(w);
    if (action != GLFW_PRESS || !v->panel || panel_wants_keyboard(v->panel)) return;
    panel_actions a;
    memset(&a, 0, sizeof a);
    switch (key) {
    case GLFW_KEY_ESCAPE: case GLFW_KEY_Q: glfwSetWindowShouldClose(w, 1); break;
    case GLFW_KEY_R: a.reload = true; break;
    case GLFW_KEY_SPACE: a.toggle_pause = true; break;
    case GLFW_KEY_P: case GLFW_KEY_F12: a.screenshot = true; break;
    case GLFW_KEY_HOME: case GLFW_KEY_F: v->cam = v->cam_home; break;
    default: break;
    }
    apply_actions(v, &a);
}

static void handle_mouse(viewer *v) {
    view_mouse_update(&v->mouse, v->win, panel_wants_mouse(v->panel), &v->cam);
}

/* ---- the loop ---- */

static void frame(viewer *v, view_script *script) {
    double now = glfwGetTime();
    double dt = now - v->last_wall;
    v->last_wall = now;
    if (dt > 0) v->fps = v->fps * 0.9 + 0.1 / dt;
    if (!v->paused && !script) v->t += dt;
    if (v->watch && watch_poll(v->watch, 0) > 0) reload(v);
    handle_mouse(v);
    int w, h;
    glfwGetFramebufferSize(v->win, &w, &h);
    render_view view = orbit_view(&v->cam);
    /* the scene sits right of the panel when the window has room for both */
    int x0 = w > PANEL_WIDTH + 160 ? PANEL_WIDTH : 0;
    glClearColor(0.12f, 0.12f, 0.13f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    /* a world is lit in linear radiance: the window encodes sRGB, as the
     * reference's PNG does; glman scenes are shown as drawn */
    if (render_has_world(v->r)) glEnable(GL_FRAMEBUFFER_SRGB);
    render_frame_at(v->r, v->t, 0, x0, 0, w - x0, h, &view);
    glDisable(GL_FRAMEBUFFER_SRGB);
    int n;
    unif_set *sets = render_uniforms(v->r, &n);
    char passes[1024];
    render_pass_summary(v->r, passes, sizeof passes);
    panel_info info = { .scene_path = render_scene_path(v->r), .gpu_ms = render_gpu_ms(v->r, false),
                        .fps = v->fps, .paused = v->paused, .time_s = v->t,
                        .error_text = render_has_errors(v->r) ? render_messages(v->r) : NULL, .passes = passes };
    panel_actions a;
    memset(&a, 0, sizeof a);
    panel_begin_frame(v->panel);
    panel_draw(v->panel, sets, n, &info, &a);
    panel_render(v->panel);
    apply_actions(v, &a);
}

static int run(viewer *v, const view_desc *d) {
    view_script *script = NULL;
    if (d->script) {
        char err[512];
        script = view_script_load(d->script, err, sizeof err);
        if (!script) { fprintf(stderr, "tarn: %s\n", err); return TARN_EXIT_USAGE; }
    }
    int rc = TARN_EXIT_OK;
    while (!glfwWindowShouldClose(v->win)) {
        glfwPollEvents();
        frame(v, script);
        char lost[1024];
        if (gl_ctx_lost(v->ctx, lost, sizeof lost)) { fprintf(stderr, "tarn: %s\n", lost); rc = TARN_EXIT_NO_GL; break; }
        if (script) {
            view_script_ctx sc = { .r = v->r, .time_s = &v->t };
            int st = view_script_step(script, &sc);
            if (st == VIEW_SCRIPT_SCREENSHOT) screenshot(v, view_script_arg(script));
            if (st == VIEW_SCRIPT_RELOAD) reload(v);
            if (st == VIEW_SCRIPT_REBUILD) render_rebuild_programs(v->r);
            if (st == VIEW_SCRIPT_FAILED) rc = TARN_EXIT_INPUT;
            if (st == VIEW_SCRIPT_DONE || st == VIEW_SCRIPT_FAILED) glfwSetWindowShouldClose(v->win, 1);
        }
        glfwSwapBuffers(v->win);
    }
    view_script_free(script);
    return rc;
}

int view_run(const view_desc *d) {
    viewer v;
    memset(&v, 0, sizeof v);
    char err[1024];
    /* GL objects need the context first, so the glib's WindowSize is
     * applied by resizing once the scene is loaded */
    v.ctx = gl_ctx_create_window(d->width > 0 ? d->width : 1000, d->height > 0 ? d->height : 700,
                                 "tarn", err, sizeof err);
    if (!v.ctx) { fprintf(stderr, "tarn: %s\n", err); return TARN_EXIT_NO_GL; }
    v.win = gl_ctx_window(v.ctx);
    glfwSetWindowUserPointer(v.win, &v);
    render_desc rd = { .pack = d->pack };
    v.r = render_create(&rd);
    bool ok = render_load(v.r, d->glib);
    report_load(&v);
    if (d->width <= 0 || d->height <= 0) {
        int w, h;
        render_window_size(v.r, &w, &h);
        glfwSetWindowSize(v.win, w + PANEL_WIDTH, h);   /* room for the panel beside the scene */
    }
    char title[1200];
    snprintf(title, sizeof title, "tarn — %s", d->glib);
    glfwSetWindowTitle(v.win, title);
    /* ours first: the ImGui backend chains to callbacks installed before it */
    glfwSetScrollCallback(v.win, on_scroll);
    glfwSetKeyCallback(v.win, on_key);
    v.panel = panel_create(v.win, "#version 130");
    v.watch = watch_create(err, sizeof err);
    if (!v.watch) fprintf(stderr, "tarn: hot reload is off: %s\n", err);
    rewatch(&v);
    v.cam = v.cam_home = orbit_from_view(render_default_view(v.r));
    v.t = d->time_s;
    v.last_wall = glfwGetTime();
    int rc = run(&v, d);
    if (rc == TARN_EXIT_OK && !ok && d->script) rc = TARN_EXIT_INPUT;
    watch_destroy(v.watch);
    panel_destroy(v.panel);
    render_destroy(v.r);
    gl_ctx_destroy(v.ctx);
    return rc;
}
