/* compare_view: `tarn compare-view`, packs side by side (see compare_view.h).
 * Each pack renders into its own float target the size of a cell (one
 * camera, one clock); the targets are blitted into the window's cells, or
 * halves of one view for the wipe. Heat maps: the CPU reference of the
 * frame at the cell size, each pack's error field against it coloured by
 * ref_heatmap into a texture blitted in place of the pack's image, and
 * recoloured every frame while the camera, time and size stay those of the
 * reference (so a slider's effect on the error shows live). The window,
 * its loop, hot reload and scripts are app.h's; this file is its hooks. */
#include "compare_view.h"

#include <GL/gl.h>
#include <GLFW/glfw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "exit_code.h"
#include "gl_ctx.h"
#include "panel.h"
#include "ref_metrics.h"
#include "refcache.h"
#include "render.h"
#include "strbuf.h"
#include "util.h"
#include "view_script.h"
#include "view_util.h"

_Static_assert(COMPARE_VIEW_MAX_PACKS <= PANEL_COMPARE_MAX_PACKS, "the panel has a row for every pack");

#define DIVIDER_GRAB 8    /* pixels either side of the wipe's divider that grab it */

typedef struct cv_pack {
    char name[64], label[80];
    render *r;
    render_target tg;            /* the pack's image, float, a cell's size */
    unsigned heat_tex, heat_fbo; /* its heat map, display values */
    int heat_w, heat_h;
    float *field;                /* its error field against the reference */
    bool have_heat;
    double gpu_ms, wall_ms;      /* smoothed */
    double rmse, psnr;          /* over the reference's water pixels: what ranks the packs */
    double frame_rmse;          /* the whole frame, second */
    char passes[512];            /* "RenderToTexture 6 7 (line 12)  1.20 ms", a pass a line */
} cv_pack;

typedef struct cview {
    app *app;
    app_state *s;                /* the app's camera, mouse and clock */
    GLFWwindow *win;             /* the app's */
    panel *panel;                /* the app's */
    const char *scene;
    cv_pack packs[COMPARE_VIEW_MAX_PACKS];
    render *scenes[COMPARE_VIEW_MAX_PACKS];   /* the packs' renderers, for the app */
    int n;
    int layout, wipe_a, wipe_b;
    float wipe;
    bool dragging_wipe;
    bool show_heat;
    float heat_max;
    double heat_scale;           /* the scale used last */
    refcache_image ref;
    bool have_ref, reported;
    double ref_t;
    orbit ref_cam;
    int ref_w, ref_h;
    refcache_opts ref_opts;
    char heat_status[256];
    panel_compare_actions pending;   /* the panel's buttons of this frame, applied after it */
    /* the scene area and the cells, framebuffer pixels (GL: y from the bottom) */
    int fb_w, fb_h, area_x, area_w, area_h, cell_w, cell_h;
} cview;

/* ---- layout ---- */

static void layout_cells(cview *v) {
    glfwGetFramebufferSize(v->win, &v->fb_w, &v->fb_h);
    v->area_x = app_scene_x(v->fb_w);
    v->area_w = v->fb_w - v->area_x;
    v->area_h = v->fb_h;
    if (v->layout == PANEL_LAYOUT_WIPE) {
        v->cell_w = v->area_w;
        v->cell_h = v->area_h;
    } else {
        int cols = 2, rows = v->n > 2 ? 2 : 1;
        v->cell_w = v->area_w / cols;
        v->cell_h = v->area_h / rows;
    }
    if (v->cell_w < 1) v->cell_w = 1;
    if (v->cell_h < 1) v->cell_h = 1;
}

/* Cell i's rectangle in framebuffer pixels (x, y from the bottom-left). */
static void cell_rect(const cview *v, int i, int *x, int *y) {
    int col = i % 2, row = i / 2;
    *x = v->area_x + col * v->cell_w;
    *y = v->area_h - (row + 1) * v->cell_h;
}

static bool pack_drawn(const cview *v, int i) {
    return v->layout != PANEL_LAYOUT_WIPE || i == v->wipe_a || i == v->wipe_b;
}

static void ensure_targets(cview *v) {
    for (int i = 0; i < v->n; i++) {
        cv_pack *p = &v->packs[i];
        if (p->tg.fbo && p->tg.w == v->cell_w && p->tg.h == v->cell_h) continue;
        render_target_destroy(&p->tg);
        if (!render_target_create(&p->tg, v->cell_w, v->cell_h, true))
            fprintf(stderr, "tarn compare-view: cannot create a %dx%d target\n", v->cell_w, v->cell_h);
    }
}

/* ---- heat maps ---- */

static bool ref_valid(const cview *v) {
    return v->have_ref && v->s->t == v->ref_t && orbit_equal(&v->s->cam, &v->ref_cam) && v->ref_w == v->cell_w &&
           v->ref_h == v->cell_h;
}

static void on_ref_progress(void *user, double f) {
    cview *v = user;
    char title[160];
    snprintf(title, sizeof title, "tarn compare-view: computing the reference, %.0f%%", 100 * f);
    glfwSetWindowTitle(v->win, title);
}

/* The CPU reference of this frame at the cell size; time pauses. */
static bool compute_reference(cview *v) {
    layout_cells(v);
    v->s->paused = true;
    render_view rv = orbit_view(&v->s->cam);
    refcache_view view;
    for (int k = 0; k < 3; k++) {
        view.eye[k] = rv.eye[k];
        view.center[k] = rv.center[k];
        view.up[k] = rv.up[k];
    }
    refcache_free(&v->ref);
    v->have_ref = false;
    char err[4096] = "";
    double t0 = clock_now_s();
    fprintf(stderr, "tarn compare-view: computing the reference at %dx%d, t = %.3f s ...\n", v->cell_w, v->cell_h,
            v->s->t);
    bool ok = refcache_get(NULL, v->scene, NULL, v->cell_w, v->cell_h, v->s->t, &view, &v->ref_opts,
                           on_ref_progress, v, &v->ref, err, sizeof err);
    char title[1200];
    snprintf(title, sizeof title, "tarn compare-view — %s", v->scene);
    glfwSetWindowTitle(v->win, title);
    if (!ok) {
        snprintf(v->heat_status, sizeof v->heat_status, "no reference: %.200s", err);
        fprintf(stderr, "tarn compare-view: %s\n", err);
        return false;
    }
    v->have_ref = true;
    v->ref_t = v->s->t;
    v->ref_cam = v->s->cam;
    v->ref_w = v->cell_w;
    v->ref_h = v->cell_h;
    v->show_heat = true;
    v->reported = false;
    snprintf(v->heat_status, sizeof v->heat_status, "reference %dx%d at t = %.3f s, computed in %.1f s",
             v->cell_w, v->cell_h, v->s->t, clock_now_s() - t0);
    fprintf(stderr, "tarn compare-view: %s\n", v->heat_status);
    return true;
}

static void upload_heat(cv_pack *p, const float *rgb, int w, int h) {
    if (!p->heat_tex || p->heat_w != w || p->heat_h != h) {
        if (!p->heat_tex) glGenTextures(1, &p->heat_tex);
        if (!p->heat_fbo) glGenFramebuffers(1, &p->heat_fbo);
        glBindTexture(GL_TEXTURE_2D, p->heat_tex);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, w, h, 0, GL_RGB, GL_FLOAT, NULL);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glBindFramebuffer(GL_FRAMEBUFFER, p->heat_fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, p->heat_tex, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        p->heat_w = w;
        p->heat_h = h;
    }
    glBindTexture(GL_TEXTURE_2D, p->heat_tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int y = 0; y < h; y++)   /* ref_heatmap's row 0 is the top; GL's the bottom */
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, h - 1 - y, w, 1, GL_RGB, GL_FLOAT, rgb + (size_t)y * w * 3);
    glBindTexture(GL_TEXTURE_2D, 0);
}

/* Each drawn pack's error field against the reference, one scale for all. */
static void update_heat(cview *v) {
    int w = v->cell_w, h = v->cell_h;
    size_t n = (size_t)w * h;
    float *rgba = malloc(n * 4 * sizeof *rgba), *rgb = malloc(n * 3 * sizeof *rgb);
    double scale = 0;
    for (int i = 0; rgba && rgb && i < v->n; i++) {
        cv_pack *p = &v->packs[i];
        p->have_heat = false;
        if (!pack_drawn(v, i) || !p->tg.fbo) continue;
        free(p->field);
        p->field = malloc(n * sizeof *p->field);
        if (!p->field || !render_target_read(&p->tg, rgba)) continue;
        ref_fimage A = { rgba, w, h, 4 }, B = { v->ref.color, w, h, 3 };
        ref_image_metrics m;
        char err[256];
        if (!ref_metrics_error_field(&A, &B, REF_ERR_COLOR, NULL, p->field, err, sizeof err) ||
            !ref_metrics_image(&A, &B, NULL, &m, err, sizeof err))
            continue;
        p->frame_rmse = m.rmse;
        /* water first: the error of the water technique, where the
         * reference sees water (the rest of the frame is one world) */
        unsigned char *water = malloc(n);
        ref_image_metrics wm;
        if (water) ref_mask_water(v->ref.mask, (long)n, 1, NULL, water);
        ref_metrics_desc wd = { .mask = water };
        bool have_water = water && ref_metrics_image(&A, &B, &wd, &wm, err, sizeof err) && wm.count.compared > 0;
        free(water);
        p->rmse = have_water ? wm.rmse : m.rmse;
        p->psnr = have_water ? wm.psnr_db : m.psnr_db;
        p->have_heat = true;
        double s = ref_heatmap_auto_scale(p->field, (long)n);
        if (s > scale) scale = s;
    }
    if (v->heat_max > 0) scale = v->heat_max;
    v->heat_scale = scale;
    for (int i = 0; rgb && i < v->n; i++) {
        cv_pack *p = &v->packs[i];
        if (!p->have_heat) continue;
        ref_heatmap(p->field, w, h, scale, rgb);
        upload_heat(p, rgb, w, h);
    }
    if (!v->reported) {
        for (int i = 0; i < v->n; i++)
            if (v->packs[i].have_heat)
                fprintf(stderr, "tarn compare-view: heat map %s: water RMSE %.4f, PSNR %.2f dB; whole frame %.4f "
                        "(scale %.4f)\n",
                        v->packs[i].label, v->packs[i].rmse, v->packs[i].psnr, v->packs[i].frame_rmse, v->heat_scale);
        v->reported = true;
    }
    free(rgba);
    free(rgb);
}

/* ---- drawing ---- */

static void draw_packs(cview *v, const render_view *view) {
    for (int i = 0; i < v->n; i++) {
        cv_pack *p = &v->packs[i];
        if (!pack_drawn(v, i) || !p->tg.fbo) continue;
        double t0 = clock_now_s();
        render_frame(p->r, v->s->t, p->tg.fbo, p->tg.w, p->tg.h, view);
        glFinish();   /* one pack at a time, so each has its own wall time */
        double wall = (clock_now_s() - t0) * 1e3, gpu = render_gpu_ms(p->r, false);
        p->wall_ms = p->wall_ms > 0 ? 0.9 * p->wall_ms + 0.1 * wall : wall;
        if (gpu >= 0) p->gpu_ms = p->gpu_ms > 0 ? 0.9 * p->gpu_ms + 0.1 * gpu : gpu;
        view_pass_summary(p->r, p->passes, sizeof p->passes);
    }
}

static void blit(unsigned fbo, int sx0, int sx1, int sh, int dx, int dy) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBlitFramebuffer(sx0, 0, sx1, sh, dx + sx0, dy, dx + sx1, dy + sh, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

/* Blits pack i's image (or heat map) columns [x0, x1) of its cell to (dx, dy). */
static void show(cview *v, int i, int x0, int x1, int dx, int dy, bool heat) {
    cv_pack *p = &v->packs[i];
    if (heat && p->have_heat) {
        glDisable(GL_FRAMEBUFFER_SRGB);   /* heat maps are display values already */
        blit(p->heat_fbo, x0, x1, p->heat_h, dx, dy);
    } else if (p->tg.fbo) {
        /* a world is lit in linear radiance: the window encodes sRGB, as `tarn view` does */
        if (render_has_world(p->r)) glEnable(GL_FRAMEBUFFER_SRGB);
        blit(p->tg.fbo, x0, x1, p->tg.h, dx, dy);
        glDisable(GL_FRAMEBUFFER_SRGB);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

static void fill(int x, int y, int w, int h, float r, float g, float b) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(x, y, w, h);
    glClearColor(r, g, b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
}

static int wipe_px(const cview *v) {
    int x = (int)lroundf(v->wipe * (float)v->cell_w);
    return x < 0 ? 0 : x > v->cell_w ? v->cell_w : x;
}

/* Window coordinates (ImGui's, top-left origin) of framebuffer pixel (x, y). */
static void to_window(const cview *v, int x, int y, float *wx, float *wy) {
    int ww, wh;
    glfwGetWindowSize(v->win, &ww, &wh);
    float sx = v->fb_w > 0 ? (float)ww / (float)v->fb_w : 1.0f, sy = v->fb_h > 0 ? (float)wh / (float)v->fb_h : 1.0f;
    *wx = (float)x * sx;
    *wy = (float)(v->fb_h - y) * sy;
}

static void label_pack(cview *v, int i, int x, int ytop, bool heat, bool right) {
    cv_pack *p = &v->packs[i];
    strbuf text = { 0 };
    strbuf_printf(&text, "%s\n%.2f ms GPU  %.1f ms wall", p->label, p->gpu_ms, p->wall_ms);
    if (heat && p->have_heat)
        strbuf_printf(&text, "\nwater RMSE %.4f  PSNR %.1f dB\nframe RMSE %.4f", p->rmse, p->psnr, p->frame_rmse);
    if (p->passes[0]) strbuf_printf(&text, "\n%s", p->passes);
    float wx, wy;
    to_window(v, x, ytop, &wx, &wy);
    panel_label(v->panel, right ? wx - 6 : wx + 6, wy + 6, text.s, right);
    strbuf_free(&text);
}

static void compose(cview *v, bool heat) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, v->fb_w, v->fb_h);
    glClearColor(0.12f, 0.12f, 0.13f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    if (v->layout == PANEL_LAYOUT_WIPE) {
        int split = wipe_px(v), dx = v->area_x, dy = 0;
        show(v, v->wipe_a, 0, split, dx, dy, heat);
        show(v, v->wipe_b, split, v->cell_w, dx, dy, heat);
        fill(dx + split - 1, dy, 2, v->cell_h, 1, 1, 1);
    } else {
        for (int i = 0; i < v->n; i++) {
            int x, y;
            cell_rect(v, i, &x, &y);
            show(v, i, 0, v->cell_w, x, y, heat);
        }
        for (int i = 1; i < 2; i++) fill(v->area_x + i * v->cell_w - 1, 0, 2, v->area_h, 0.12f, 0.12f, 0.13f);
        if (v->n > 2) fill(v->area_x, v->area_h - v->cell_h - 1, v->area_w, 2, 0.12f, 0.12f, 0.13f);
    }
}

static void labels(cview *v, bool heat) {
    if (v->layout == PANEL_LAYOUT_WIPE) {
        label_pack(v, v->wipe_a, v->area_x, v->cell_h, heat, false);
        label_pack(v, v->wipe_b, v->area_x + v->cell_w, v->cell_h, heat, true);
        return;
    }
    for (int i = 0; i < v->n; i++) {
        int x, y;
        cell_rect(v, i, &x, &y);
        label_pack(v, i, x, y + v->cell_h, heat, false);
    }
}

/* ---- loading, reloading ---- */

static void report(cv_pack *p) {
    const char *m = render_messages(p->r);
    if (m[0]) fprintf(stderr, "%s: %s", p->label, m);
}

static void on_reload(void *user, app *a) {
    cview *v = user;
    const char *cause = app_reload_cause(a);
    fprintf(stderr, "tarn compare-view: reloaded %s%s%s%s\n", v->scene, cause[0] ? " (" : "", cause, cause[0] ? ")" : "");
    for (int i = 0; i < v->n; i++) {
        render_load(v->packs[i].r, NULL);
        report(&v->packs[i]);
    }
}

/* ---- input ---- */

static void on_key(void *user, app *a, int key) {
    cview *v = user;
    switch (key) {
    case GLFW_KEY_H:
        if (ref_valid(v)) v->show_heat = !v->show_heat;
        else compute_reference(v);
        break;
    case GLFW_KEY_G: v->layout = PANEL_LAYOUT_GRID; break;
    case GLFW_KEY_W: v->layout = PANEL_LAYOUT_WIPE; break;
    case GLFW_KEY_TAB:
        v->wipe_b = (v->wipe_b + 1) % v->n;
        if (v->wipe_b == v->wipe_a) v->wipe_b = (v->wipe_b + 1) % v->n;
        break;
    default: break;
    }
}

/* The cells for this frame's size, then the mouse: a left press within
 * DIVIDER_GRAB pixels of the wipe's divider drags it, other drags move
 * the camera. */
static void on_mouse(void *user, app *a) {
    cview *v = user;
    layout_cells(v);
    double mx, my;
    glfwGetCursorPos(v->win, &mx, &my);
    int ww, wh;
    glfwGetWindowSize(v->win, &ww, &wh);
    double fx = ww > 0 ? mx * v->fb_w / ww : mx;
    bool left = glfwGetMouseButton(v->win, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    bool ui = panel_wants_mouse(v->panel);
    if (v->layout == PANEL_LAYOUT_WIPE && left && !ui && !v->s->mouse.dragging_orbit && !v->dragging_wipe) {
        double divider = v->area_x + wipe_px(v);
        if (fabs(fx - divider) <= DIVIDER_GRAB) v->dragging_wipe = true;
    }
    if (!left) v->dragging_wipe = false;
    if (v->dragging_wipe) {
        v->wipe = (float)((fx - v->area_x) / (v->cell_w > 0 ? v->cell_w : 1));
        v->wipe = fmaxf(0.0f, fminf(1.0f, v->wipe));
        v->s->mouse.last_x = mx;
        v->s->mouse.last_y = my;
        return;
    }
    view_mouse_update(&v->s->mouse, v->win, ui, &v->s->cam);
}

/* What the panel asked for besides reload, pause and screenshot (the app's). */
static void on_apply(void *user, app *a) {
    cview *v = user;
    const panel_compare_actions *p = &v->pending;
    for (int i = 0; i < v->n; i++)
        if (p->recompile[i]) {
            render_rebuild_programs(v->packs[i].r);
            report(&v->packs[i]);
        }
    if (p->reset_camera) v->s->cam = v->s->cam_home;
    if (p->compute_heat) compute_reference(v);
}

/* ---- the frame ---- */

static bool heat_shown(const cview *v) { return v->show_heat && ref_valid(v); }

static void on_draw(void *user, app *a) {
    cview *v = user;
    if (v->wipe_a == v->wipe_b) v->wipe_b = (v->wipe_a + 1) % v->n;
    ensure_targets(v);
    render_view view = orbit_view(&v->s->cam);
    draw_packs(v, &view);
    bool heat = heat_shown(v);
    if (heat) update_heat(v);
    if (v->have_ref && !ref_valid(v))
        snprintf(v->heat_status, sizeof v->heat_status,
                 "heat maps are stale: the camera, time or size changed since the reference (H recomputes)");
    compose(v, heat);
}

static void on_panel(void *user, app *a, panel_actions *common) {
    cview *v = user;
    bool heat = heat_shown(v);
    panel_compare_pack pp[COMPARE_VIEW_MAX_PACKS];
    for (int i = 0; i < v->n; i++) {
        cv_pack *p = &v->packs[i];
        pp[i] = (panel_compare_pack){ .name = p->label, .gpu_ms = pack_drawn(v, i) ? p->gpu_ms : -1,
                                      .wall_ms = pack_drawn(v, i) ? p->wall_ms : -1,
                                      .rmse = heat && p->have_heat ? p->rmse : NAN,
                                      .psnr_db = heat && p->have_heat ? p->psnr : NAN,
                                      .error_text = render_has_errors(p->r) ? render_messages(p->r) : NULL };
        pp[i].sets = render_uniforms(p->r, &pp[i].nsets);
    }
    const char *status = v->heat_status[0] ? v->heat_status : "no heat maps yet: H computes them";
    bool cpu_raster = v->s->cpu_raster;
    panel_compare pc = { .scene_path = v->scene, .frame_ms = v->s->frame_ms, .fps = v->s->fps, .time_s = v->s->t, .paused = v->s->paused,
                         .packs = pp, .npacks = v->n, .layout = &v->layout, .wipe_a = &v->wipe_a,
                         .wipe_b = &v->wipe_b, .wipe = &v->wipe, .show_heat = &v->show_heat,
                         .heat_max = &v->heat_max, .heat_status = status,
                         .note = cpu_raster ? "llvmpipe: GPU timestamps do not time the rasterisation; "
                                              "wall time (after glFinish) does"
                                            : "per pass GPU times in each pack's corner" };
    panel_draw_compare(v->panel, &pc, &v->pending);
    labels(v, heat);
    *common = v->pending.common;
}

/* ---- script actions of our own ---- */

static view_script_status script_action(void *user, const char *cmd, char *rest, const char *file, int line) {
    cview *v = user;
    char a[64] = "", b[64] = "";
    int na = sscanf(rest, "%63s %63s", a, b);
    if (strcmp(cmd, "pack") == 0) {
        int k = atoi(a);
        if (k < 1 || k > v->n) {
            fprintf(stderr, "%s:%d: pack wants 1..%d\n", file, line, v->n);
            return VIEW_SCRIPT_FAILED;
        }
        app_script_use(v->app, k - 1);
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "layout") == 0) {
        if (strcmp(a, "grid") == 0) v->layout = PANEL_LAYOUT_GRID;
        else if (strcmp(a, "wipe") == 0) v->layout = PANEL_LAYOUT_WIPE;
        else { fprintf(stderr, "%s:%d: layout wants grid or wipe\n", file, line); return VIEW_SCRIPT_FAILED; }
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "wipe") == 0) {
        int x = atoi(a), y = atoi(b);
        if (na < 2 || x < 1 || y < 1 || x > v->n || y > v->n || x == y) {
            fprintf(stderr, "%s:%d: wipe wants two different packs, 1..%d\n", file, line, v->n);
            return VIEW_SCRIPT_FAILED;
        }
        v->layout = PANEL_LAYOUT_WIPE;
        v->wipe_a = x - 1;
        v->wipe_b = y - 1;
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "divider") == 0) {
        v->wipe = fmaxf(0.0f, fminf(1.0f, (float)atof(a)));
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "heat") == 0) return compute_reference(v) ? VIEW_SCRIPT_CONTINUE : VIEW_SCRIPT_FAILED;
    if (strcmp(cmd, "heat-show") == 0) {
        v->show_heat = strcmp(a, "on") == 0;
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "heat-max") == 0) {
        v->heat_max = (float)atof(a);
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "orbit") == 0) {
        orbit_rotate(&v->s->cam, (float)atof(a), (float)atof(b));
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "timings") == 0) {
        for (int i = 0; i < v->n; i++)
            fprintf(stderr, "tarn compare-view: %s: %.3f ms GPU, %.3f ms wall%s\n", v->packs[i].label,
                    v->packs[i].gpu_ms, v->packs[i].wall_ms, pack_drawn(v, i) ? "" : " (not drawn)");
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "expect-heat") == 0) {
        bool ok = ref_valid(v);
        for (int i = 0; i < v->n; i++)
            if (pack_drawn(v, i) && (!v->packs[i].have_heat || !isfinite(v->packs[i].rmse))) ok = false;
        if (!ok) {
            fprintf(stderr, "%s:%d: expect-heat: %s\n", file, line,
                    ref_valid(v) ? "a pack has no heat map" : "no valid reference for this frame");
            return VIEW_SCRIPT_FAILED;
        }
        fprintf(stderr, "tarn compare-view: script: every pack has a heat map\n");
        return VIEW_SCRIPT_CONTINUE;
    }
    fprintf(stderr, "%s:%d: unknown script action '%s'\n", file, line, cmd);
    return VIEW_SCRIPT_FAILED;
}

/* ---- the command ---- */

static void load_packs(cview *v, const cli_compare_view_desc *d, bool *ok) {
    for (int i = 0; i < v->n; i++) {
        cv_pack *p = &v->packs[i];
        snprintf(p->name, sizeof p->name, "%s", d->packs[i]);
        int copy = 1;
        for (int j = 0; j < i; j++) copy += strcmp(d->packs[j], d->packs[i]) == 0;
        if (copy > 1) snprintf(p->label, sizeof p->label, "%d %s #%d", i + 1, p->name, copy);
        else snprintf(p->label, sizeof p->label, "%d %s", i + 1, p->name);
        render_desc rd = { .pack = p->name };
        p->r = v->scenes[i] = render_create(&rd);
        if (!render_load(p->r, d->glib)) *ok = false;
        report(p);
        p->rmse = p->psnr = p->frame_rmse = NAN;
    }
}

static void free_packs(cview *v) {
    for (int i = 0; i < v->n; i++) {
        cv_pack *p = &v->packs[i];
        render_target_destroy(&p->tg);
        if (p->heat_fbo) glDeleteFramebuffers(1, &p->heat_fbo);
        if (p->heat_tex) glDeleteTextures(1, &p->heat_tex);
        free(p->field);
        render_destroy(p->r);
    }
    refcache_free(&v->ref);
}

int cli_compare_view(const cli_compare_view_desc *d) {
    if (d->npacks < 2 || d->npacks > COMPARE_VIEW_MAX_PACKS) {
        fprintf(stderr, "tarn compare-view: give 2 to 4 packs (--packs a,b)\n");
        return TARN_EXIT_USAGE;
    }
    cview *v = calloc(1, sizeof *v);
    if (!v) return TARN_EXIT_INPUT;
    v->scene = d->glib;
    v->n = d->npacks;
    v->wipe = 0.5f;
    v->wipe_b = 1;
    v->ref_opts.caustic_res = d->ref_caustic_res > 0 ? d->ref_caustic_res : 128;
    v->ref_opts.photons_per_cell = d->ref_photons > 0 ? d->ref_photons : 16;
    app_desc ad = { .name = "tarn compare-view", .scene_path = d->glib,
                    .width = d->width > 0 ? d->width + APP_PANEL_WIDTH : 1400,
                    .height = d->height > 0 ? d->height : 800, .time_s = d->time_s, .script = d->script,
                    .user = v, .draw = on_draw, .panel = on_panel, .apply = on_apply, .reload = on_reload,
                    .mouse = on_mouse, .key = on_key, .script_action = script_action };
    v->app = app_create(&ad);
    if (!v->app) {
        free(v);
        return TARN_EXIT_NO_GL;
    }
    v->s = app_get_state(v->app);
    v->win = app_window(v->app);
    v->panel = app_panel(v->app);
    bool ok = true;
    load_packs(v, d, &ok);
    fprintf(stderr, "tarn compare-view: loaded %s\n", d->glib);
    if (d->width <= 0 || d->height <= 0) {
        int w, h;
        render_window_size(v->packs[0].r, &w, &h);
        app_fit_window(v->app, w, h);
    }
    app_home(v->app, render_default_view(v->packs[0].r));
    int rc = app_run(v->app, v->scenes, v->n);
    if (rc == TARN_EXIT_OK && !ok && d->script) rc = TARN_EXIT_INPUT;
    free_packs(v);
    app_destroy(v->app);
    free(v);
    return rc;
}
