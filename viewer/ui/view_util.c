/* view_util: the orbit camera, the mouse and screenshots (see view_util.h). */
#include "view_util.h"
#include "strbuf.h"

#include <GL/gl.h>
#include <GLFW/glfw3.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "glib.h"
#include "image_io.h"
#include "util.h"

orbit orbit_from_view(render_view v) {
    orbit o;
    memcpy(o.center, v.center, sizeof o.center);
    memcpy(o.up, v.up, sizeof o.up);
    float d[3] = { v.eye[0] - v.center[0], v.eye[1] - v.center[1], v.eye[2] - v.center[2] };
    o.distance = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (o.distance < 1e-6f) o.distance = 1.0f;
    o.yaw = atan2f(d[0], d[2]);
    o.pitch = asinf(fmaxf(-1.0f, fminf(1.0f, d[1] / o.distance)));
    return o;
}

render_view orbit_view(const orbit *o) {
    render_view v;
    memcpy(v.center, o->center, sizeof v.center);
    memcpy(v.up, o->up, sizeof v.up);
    v.eye[0] = o->center[0] + o->distance * cosf(o->pitch) * sinf(o->yaw);
    v.eye[1] = o->center[1] + o->distance * sinf(o->pitch);
    v.eye[2] = o->center[2] + o->distance * cosf(o->pitch) * cosf(o->yaw);
    return v;
}

void orbit_pan(orbit *o, float dx, float dy) {
    /* camera right = normalize(cross(forward, up)), camera up = cross(right, forward) */
    render_view v = orbit_view(o);
    float f[3] = { v.center[0] - v.eye[0], v.center[1] - v.eye[1], v.center[2] - v.eye[2] };
    float fl = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int i = 0; i < 3; i++) f[i] /= fl;
    float rgt[3] = { f[1] * o->up[2] - f[2] * o->up[1], f[2] * o->up[0] - f[0] * o->up[2],
                     f[0] * o->up[1] - f[1] * o->up[0] };
    float rl = sqrtf(rgt[0] * rgt[0] + rgt[1] * rgt[1] + rgt[2] * rgt[2]);
    if (rl < 1e-6f) return;
    for (int i = 0; i < 3; i++) rgt[i] /= rl;
    float u[3] = { rgt[1] * f[2] - rgt[2] * f[1], rgt[2] * f[0] - rgt[0] * f[2], rgt[0] * f[1] - rgt[1] * f[0] };
    float k = o->distance * 0.0015f;
    for (int i = 0; i < 3; i++) o->center[i] += (-dx * rgt[i] + dy * u[i]) * k;
}

void orbit_rotate(orbit *o, float dx, float dy) {
    o->yaw -= dx * 0.01f;
    o->pitch = fmaxf(-1.55f, fminf(1.55f, o->pitch + dy * 0.01f));
}

void orbit_zoom(orbit *o, double clicks) {
    o->distance *= powf(0.9f, (float)clicks);
    o->distance = fmaxf(1e-3f, o->distance);
}

bool orbit_equal(const orbit *a, const orbit *b) {
    return memcmp(a->center, b->center, sizeof a->center) == 0 && memcmp(a->up, b->up, sizeof a->up) == 0 &&
           a->distance == b->distance && a->yaw == b->yaw && a->pitch == b->pitch;
}

void view_mouse_press(view_mouse *m, int button, double x, double y) {
    if (!m->pressed) {
        m->press_x = x;
        m->press_y = y;
    }
    m->pressed |= button;
}

void view_mouse_read(view_mouse *m, void *glfw_window, view_mouse_input *in) {
    GLFWwindow *win = glfw_window;
    memset(in, 0, sizeof *in);
    glfwGetCursorPos(win, &in->x, &in->y);
    in->left = glfwGetMouseButton(win, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    in->pan = glfwGetMouseButton(win, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
              glfwGetMouseButton(win, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    in->pressed = m->pressed;
    in->press_x = m->press_x;
    in->press_y = m->press_y;
    m->pressed = 0;
}

void view_mouse_step(view_mouse *m, const view_mouse_input *in, bool ui_wants, orbit *cam) {
    /* a press since the last frame counts as held this frame (a click
     * between two frames), and its drag starts where it was */
    bool left = in->left || (in->pressed & VIEW_MOUSE_LEFT);
    bool pan = in->pan || (in->pressed & VIEW_MOUSE_PAN);
    if (in->pressed && in->press_x < m->ui_right) ui_wants = true;   /* pressed on the panel: its press */   /* pressed on the panel: its press */
    bool new_orbit = left && !m->dragging_orbit && !ui_wants;
    bool new_pan = pan && !m->dragging_pan && !ui_wants;
    if (in->pressed && (new_orbit || new_pan)) {
        m->last_x = in->press_x;
        m->last_y = in->press_y;
    }
    float dx = (float)(in->x - m->last_x), dy = (float)(in->y - m->last_y);
    m->dragging_orbit = left && (m->dragging_orbit || !ui_wants);
    m->dragging_pan = pan && (m->dragging_pan || !ui_wants);
    bool from_press = in->pressed != 0;   /* a drag begun by a press we saw applies at once */
    if (m->dragging_orbit && (!new_orbit || from_press)) orbit_rotate(cam, dx, dy);
    if (m->dragging_pan && (!new_pan || from_press)) orbit_pan(cam, dx, dy);
    if (m->scroll != 0) {
        orbit_zoom(cam, m->scroll);
        m->scroll = 0;
    }
    m->last_x = in->x;
    m->last_y = in->y;
}

void view_mouse_update(view_mouse *m, void *glfw_window, bool ui_wants, orbit *cam) {
    view_mouse_input in;
    view_mouse_read(m, glfw_window, &in);
    view_mouse_step(m, &in, ui_wants, cam);
}

static void make_opaque(img *im) {
    size_t n = (size_t)im->w * (size_t)im->h;
    for (size_t i = 0; i < n; i++) im->px[i * 4 + 3] = 1.0f;
}

bool view_screenshot(void *glfw_window, const char *path, char *said, size_t len) {
    int w, h;
    glfwGetFramebufferSize(glfw_window, &w, &h);
    return view_screenshot_area(0, 0, w, h, path, said, len);
}

bool view_screenshot_area(int x, int y, int w, int h, const char *path, char *said, size_t len) {
    img im;
    memset(&im, 0, sizeof im);
    if (w <= 0 || h <= 0 || !img_alloc(&im, w, h, 4)) {
        snprintf(said, len, "screenshot failed: no memory for %d x %d", w, h);
        return false;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(x, y, w, h, GL_RGBA, GL_FLOAT, im.px);
    img_flip_rows(&im);
    make_opaque(&im);
    char err[MSG_MAX], abs[PATH_MAX];
    bool ok = img_write(path, &im, err, sizeof err);
    if (ok) snprintf(said, len, "screenshot %s", realpath(path, abs) ? abs : path);
    else snprintf(said, len, "screenshot failed: %s", err);
    img_free(&im);
    return ok;
}

void view_pass_name(const char *timer_name, char *out, size_t len) {
    int line = 0, used = 0;
    if (sscanf(timer_name, "pass:%d%n", &line, &used) == 1)
        snprintf(out, len, "RenderToTexture%s (line %d)", timer_name + used, line);
    else if (sscanf(timer_name, "screen:%d", &line) == 1)
        snprintf(out, len, "to the screen (line %d)", line);
    else
        snprintf(out, len, "%s", timer_name);
}

void view_pass_summary(render *r, char *out, size_t len) {
    const char (*names)[GPU_TIMER_NAME];
    const double *ms;
    int n = render_pass_times(r, false, &names, &ms);
    size_t used = 0;
    if (len > 0) out[0] = '\0';
    for (int i = 0; i < n && used + 80 < len; i++) {
        char name[GPU_TIMER_NAME + 32];
        view_pass_name(names[i], name, sizeof name);
        int k = snprintf(out + used, len - used, "%s%s  %.2f ms", i ? "\n" : "", name, ms[i]);
        if (k < 0) break;
        used += (size_t)k;
    }
}

void view_shot_path(int n, char *out, size_t len) {
    time_t now = time(NULL);
    struct tm tmv;
    localtime_r(&now, &tmv);
    char stamp[32];
    strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &tmv);
    snprintf(out, len, "tarn-%s-%d.png", stamp, n);
}

void view_reload_cause(const char *const *paths, int n, char *out, size_t len) {
    if (len == 0) return;
    out[0] = '\0';
    int shown = n > 3 ? 2 : n;   /* four and more: two names and a count */
    size_t used = 0;
    for (int i = 0; i < shown && used < len; i++) {
        const char *slash = strrchr(paths[i], '/');
        const char *sep = i == 0 ? "" : i == shown - 1 && shown == n ? " and " : ", ";
        used += (size_t)snprintf(out + used, len - used, "%s%s", sep, slash ? slash + 1 : paths[i]);
    }
    if (n > shown && used < len) used += (size_t)snprintf(out + used, len - used, " and %d more", n - shown);
    if (n > 0 && used < len) snprintf(out + used, len - used, " changed");
}

void view_reload_line(const char *who, const char *scene, const char *cause, double compiled_s, char *out,
                      size_t len) {
    int n = snprintf(out, len, "%s: reloaded %s%s%s%s", who, scene, cause[0] ? " (" : "", cause, cause[0] ? ")" : "");
    if (compiled_s >= 0 && n >= 0 && (size_t)n < len)
        snprintf(out + n, len - (size_t)n, ", compiled off the frame in %.2f s", compiled_s);
}

void view_compiling_text(const char *cause, char *out, size_t len) {
    static const char suffix[] = " changed";
    size_t n = strlen(cause), k = strlen(suffix);
    if (n >= k && strcmp(cause + n - k, suffix) == 0) n -= k;
    snprintf(out, len, "compiling %.*s%s... (the last good build draws meanwhile)", (int)n, cause, n ? " " : "");
}

void view_loading_text(const char *glib, const char *pack, const char *extra, char *out, size_t n) {
    char packs[4096];
    snprintf(packs, sizeof packs, "%s/packs", tarn_root());
    glib_options opt = { .packs_dir = packs, .pack_override = pack };
    glib_scene *g = glib_load_opts(glib, &opt);
    int programs = 0;
    bool world = false;
    for (int i = 0; i < g->ncmds; i++) {
        programs += g->cmds[i].kind == GLIB_CMD_PROGRAM;
        world |= glib_cmd_describes_world(g->cmds[i].kind);
    }
    glib_free(g);
    const char *base = strrchr(glib, '/');
    int k = programs + (world ? 4 : 0);   /* the world's own: its three parts and the height map */
    snprintf(out, n, "loading %s: compiling %d program%s ...%s", base ? base + 1 : glib, k, k == 1 ? "" : "s",
             extra ? extra : "");
}
