/* compare_view: `tarn compare-view`, packs side by side (see compare_view.h).
 * Each pack renders into its own float target the size of a cell (one
 * camera, one clock); the targets are blitted into the window's cells, or
 * halves of one view for the wipe. Heat maps: the CPU reference of the
 * frame at the cell size, each pack's error field against it coloured by
 * ref_heatmap into a texture blitted in place of the pack's image, and
 * recoloured again and again while the camera, time and size stay those of
 * the reference (so a slider's effect on the error shows live). Both run on
 * heat_job's worker thread, the window polls it each frame (progress in the
 * panel); GL stays here: the packs' pixels are read back and the maps
 * uploaded on this thread. A scripted run waits for each job, so what a
 * script checks or shoots is the frame's own. The window, its loop, hot
 * reload and scripts are app.h's; this file is its hooks. */
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
#include "heat_job.h"
#include "mem.h"
#include "panel.h"
#include "mem.h"
#include "ref_flip.h"
#include "ref_metrics.h"
#include "refcache.h"
#include "render.h"
#include "res_budget.h"
#include "strbuf.h"
#include "util.h"
#include "view_script.h"
#include "view_util.h"

_Static_assert(COMPARE_VIEW_MAX_PACKS <= PANEL_COMPARE_MAX_PACKS, "the panel has a row for every pack");

#define DIVIDER_GRAB 8    /* pixels either side of the wipe's divider that grab it */
#define LEGEND_STEPS 32   /* colours of the heat maps' legend (the panel interpolates between them) */

_Static_assert(COMPARE_VIEW_MAX_PACKS <= HEAT_JOB_MAX_PACKS, "the worker takes every pack");

typedef struct cv_pack {
    char name[64], title[72], label[80];   /* "basic", "basic #2", "2 basic #2" (over its view) */
    render *r;
    render_target tg;            /* the pack's image, float, a cell's size */
    unsigned heat_tex, heat_fbo; /* its heat map, display values */
    int heat_w, heat_h;
    float *pixels;               /* its image read back for the worker (RGBA, row 0 at the top) */
    bool have_heat;
    double gpu_ms, wall_ms;      /* smoothed */
    double rmse, psnr;          /* over the reference's water pixels: what ranks the packs */
    double frame_rmse;          /* the whole frame, second */
    double flip;                /* HDR-FLIP over the water, when the maps show FLIP (else NaN) */
    char passes[512];            /* "RenderToTexture 6 7 (line 12)  1.20 ms", a pass a line */
    bool loaded;                 /* the scene is loaded (the first pack before the window's
                                    first frame, the others after it: load_next_pack) */
    bool drawn;                  /* its target holds a frame of drawn_w x drawn_h */
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
    bool load_failed;            /* a pack's scene had errors (a script's run then fails) */
    int layout, wipe_a, wipe_b;
    float wipe;
    bool dragging_wipe;
    bool show_heat;
    float heat_max;
    double heat_scale;           /* the scale used last */
    int metric;                  /* heat_metric the panel asks for */
    int shown_metric;            /* heat_metric of the maps on screen */
    refcache_image ref;
    bool have_ref, reported;
    double ref_t;
    orbit ref_cam;
    int ref_w, ref_h;
    refcache_opts ref_opts;
    heat_job *job;               /* the reference and the maps, off this thread */
    bool scripted;               /* wait for each job: a script checks the frame's own */
    double pend_t;               /* what the running reference is of */
    orbit pend_cam;
    int pend_w, pend_h;
    double pend_started;
    float legend_rgb[LEGEND_STEPS * 3];   /* the maps' ramp, no error to the scale, display values */
    bool passes_over_views;      /* each pass's time over its pack's view (else in the panel only) */
    char heat_status[256];
    panel_compare_actions pending;   /* the panel's buttons of this frame, applied after it */
    /* the scene area and the cells, framebuffer pixels (GL: y from the bottom) */
    int fb_w, fb_h, area_x, area_w, area_h, cell_w, cell_h;
    int drawn_w, drawn_h;        /* the packs' images: this corner of their targets (the frame budget) */
    double drawn_scale;          /* ... at this scale of the cells */
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
    return v->packs[i].loaded && (v->layout != PANEL_LAYOUT_WIPE || i == v->wipe_a || i == v->wipe_b);
}

static void ensure_targets(cview *v) {
    for (int i = 0; i < v->n; i++) {
        cv_pack *p = &v->packs[i];
        if (p->tg.fbo && p->tg.w == v->cell_w && p->tg.h == v->cell_h) continue;
        render_target_destroy(&p->tg);
        p->drawn = false;
        if (!render_target_create(&p->tg, v->cell_w, v->cell_h, true))
            fprintf(stderr, "tarn compare-view: cannot create a %dx%d target\n", v->cell_w, v->cell_h);
    }
}

/* ---- heat maps ---- */

static bool ref_valid(const cview *v) {
    return v->have_ref && v->s->t == v->ref_t && orbit_equal(&v->s->cam, &v->ref_cam) && v->ref_w == v->cell_w &&
           v->ref_h == v->cell_h;
}

/* Starts the CPU reference of this frame at the cell size on the worker;
 * time pauses (the reference is of this moment). */
static void start_reference(cview *v) {
    layout_cells(v);
    if (heat_job_running(v->job) == HEAT_JOB_REFERENCE) return;
    heat_job_wait(v->job);   /* maps of the old reference: no longer wanted */
    v->s->paused = true;
    render_view rv = orbit_view(&v->s->cam);
    refcache_view view;
    for (int k = 0; k < 3; k++) {
        view.eye[k] = rv.eye[k];
        view.center[k] = rv.center[k];
        view.up[k] = rv.up[k];
    }
    v->pend_t = v->s->t;
    v->pend_cam = v->s->cam;
    v->pend_w = v->cell_w;
    v->pend_h = v->cell_h;
    v->pend_started = clock_now_s();
    char subs[96];
    refcache_describe_samples(&v->ref_opts, subs, (int)sizeof subs);
    fprintf(stderr, "tarn compare-view: computing the reference at %dx%d (%s), t = %.3f s ...\n", v->cell_w,
            v->cell_h, subs, v->s->t);
    heat_job_start_reference(v->job, v->scene, v->cell_w, v->cell_h, v->s->t, &view, &v->ref_opts);
    snprintf(v->heat_status, sizeof v->heat_status, "computing the reference %dx%d: 0%%", v->pend_w, v->pend_h);
}

/* The finished reference replaces the last one. */
static bool finish_reference(cview *v) {
    char err[MSG_MAX] = "";
    refcache_image im;
    if (!heat_job_take_reference(v->job, &im, err, sizeof err)) {
        snprintf(v->heat_status, sizeof v->heat_status, "no reference: %.200s", err);
        fprintf(stderr, "tarn compare-view: %s\n", err);
        return false;
    }
    refcache_free(&v->ref);
    v->ref = im;
    v->have_ref = true;
    v->ref_t = v->pend_t;
    v->ref_cam = v->pend_cam;
    v->ref_w = v->pend_w;
    v->ref_h = v->pend_h;
    v->show_heat = true;
    v->reported = false;
    for (int i = 0; i < v->n; i++) v->packs[i].have_heat = false;
    char subs[96];
    refcache_describe_samples(&v->ref_opts, subs, (int)sizeof subs);
    snprintf(v->heat_status, sizeof v->heat_status, "reference %dx%d at t = %.3f s (%s, as the packs' MSAA), computed in %.1f s",
             v->ref_w, v->ref_h, v->ref_t, subs, clock_now_s() - v->pend_started);
    fprintf(stderr, "tarn compare-view: %s\n", v->heat_status);
    return true;
}

/* The script's `heat`: the reference now, before the next step. */
static bool compute_reference_now(cview *v) {
    start_reference(v);
    return heat_job_wait(v->job) == HEAT_JOB_REFERENCE && finish_reference(v);
}

/* rgb (w x h, row 0 at the top) into a texture with a framebuffer to blit
 * from, made or resized as needed. */
static void upload_rgb(unsigned *tex, unsigned *fbo, const float *rgb, int w, int h, bool resize) {
    if (!*tex || resize) {
        if (!*tex) glGenTextures(1, tex);
        if (!*fbo) glGenFramebuffers(1, fbo);
        glBindTexture(GL_TEXTURE_2D, *tex);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, w, h, 0, GL_RGB, GL_FLOAT, NULL);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glBindFramebuffer(GL_FRAMEBUFFER, *fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, *tex, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    glBindTexture(GL_TEXTURE_2D, *tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int y = 0; y < h; y++)   /* ref_heatmap's row 0 is the top; GL's the bottom */
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, h - 1 - y, w, 1, GL_RGB, GL_FLOAT, rgb + (size_t)y * w * 3);
    glBindTexture(GL_TEXTURE_2D, 0);
}

static void upload_heat(cv_pack *p, const float *rgb, int w, int h) {
    upload_rgb(&p->heat_tex, &p->heat_fbo, rgb, w, h, p->heat_w != w || p->heat_h != h);
    p->heat_w = w;
    p->heat_h = h;
}

/* The legend's ramp, for the panel: the maps' colours from no error to
 * the scale (the maps' own function, so the two cannot disagree). */
static void make_legend(cview *v) {
    if (v->shown_metric == HEAT_METRIC_FLIP) {   /* FLIP's own ramp, 0 to 1 */
        for (int i = 0; i < LEGEND_STEPS; i++) ref_flip_magma((double)i / (LEGEND_STEPS - 1), &v->legend_rgb[3 * i]);
        return;
    }
    float field[LEGEND_STEPS];
    for (int i = 0; i < LEGEND_STEPS; i++) field[i] = (float)(v->heat_scale * i / (LEGEND_STEPS - 1));
    ref_heatmap(field, LEGEND_STEPS, 1, v->heat_scale, v->legend_rgb);
}

/* The worker's maps (of the frame that was read back) into the packs'
 * textures and figures. */
static void take_maps(cview *v) {
    const heat_maps *m = heat_job_maps(v->job);
    if (m->w != v->ref_w || m->h != v->ref_h) return;   /* of a reference since replaced */
    for (int i = 0; i < v->n && i < m->n; i++) {
        cv_pack *p = &v->packs[i];
        p->have_heat = m->map[i].ok;
        if (!p->have_heat) continue;
        p->rmse = m->map[i].rmse;
        p->psnr = m->map[i].psnr;
        p->frame_rmse = m->map[i].frame_rmse;
        p->flip = m->map[i].flip;
        upload_heat(p, m->map[i].rgb, m->w, m->h);
    }
    v->heat_scale = m->scale;
    v->shown_metric = m->metric;
    if (!v->reported) {
        for (int i = 0; i < v->n; i++)
            if (v->packs[i].have_heat)
                fprintf(stderr, "tarn compare-view: heat map %s: water RMSE %.4f, PSNR %.2f dB; whole frame %.4f "
                        "(scale %.4f)%s\n",
                        v->packs[i].label, v->packs[i].rmse, v->packs[i].psnr, v->packs[i].frame_rmse, v->heat_scale,
                        m->metric == HEAT_METRIC_FLIP ? "; HDR-FLIP map" : "");
        v->reported = true;
    }
}

/* What the worker finished since the last frame; the reference's progress. */
static void poll_heat(cview *v) {
    heat_job_kind done = heat_job_poll(v->job);
    if (done == HEAT_JOB_REFERENCE) finish_reference(v);
    else if (done == HEAT_JOB_MAPS) take_maps(v);
    if (heat_job_running(v->job) == HEAT_JOB_REFERENCE)
        snprintf(v->heat_status, sizeof v->heat_status, "computing the reference %dx%d: %.0f%%", v->pend_w,
                 v->pend_h, 100 * heat_job_progress(v->job));
}

/* Reads the drawn packs back and hands them to the worker, when it is free. */
static void request_maps(cview *v) {
    if (heat_job_busy(v->job)) return;
    const float *rgba[COMPARE_VIEW_MAX_PACKS] = { 0 };
    size_t n = (size_t)v->cell_w * v->cell_h;
    for (int i = 0; i < v->n; i++) {
        cv_pack *p = &v->packs[i];
        if (!pack_drawn(v, i) || !p->tg.fbo) continue;
        p->pixels = mem_realloc(p->pixels, n * 4 * sizeof *p->pixels);
        if (render_target_read(&p->tg, p->pixels)) rgba[i] = p->pixels;
    }
    heat_job_set_metric(v->job, (heat_metric)v->metric);
    heat_job_start_maps(v->job, rgba, v->n, v->cell_w, v->cell_h, &v->ref, v->heat_max);
    if (v->scripted && heat_job_wait(v->job) == HEAT_JOB_MAPS) take_maps(v);
}

/* ---- drawing ---- */

/* The packs shown into their targets at scale; only_new: those that
 * have nothing drawn there yet (a pack just loaded, the others' frames
 * still the picture). */
static void draw_packs(cview *v, const render_view *view, double scale, bool only_new) {
    for (int i = 0; i < v->n; i++) {
        cv_pack *p = &v->packs[i];
        if (!pack_drawn(v, i) || !p->tg.fbo || (only_new && p->drawn)) continue;
        p->drawn = true;
        double t0 = clock_now_s();
        render_set_detail(p->r, scale);   /* the passes and meshes shrink with the frame */
        render_frame(p->r, v->s->t, p->tg.fbo, v->drawn_w, v->drawn_h, view);
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

/* A pack's image, drawn at drawn_w x drawn_h, upscaled into columns
 * [x0, x1) of a cell at (dx, dy). */
static void blit_image(const cview *v, unsigned fbo, int x0, int x1, int dx, int dy) {
    if (v->drawn_w == v->cell_w && v->drawn_h == v->cell_h) {
        blit(fbo, x0, x1, v->cell_h, dx, dy);
        return;
    }
    double sx = (double)v->drawn_w / v->cell_w;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBlitFramebuffer((int)lround(x0 * sx), 0, (int)lround(x1 * sx), v->drawn_h, dx + x0, dy, dx + x1, dy + v->cell_h,
                      GL_COLOR_BUFFER_BIT, GL_LINEAR);
}

/* Blits pack i's image (or heat map) columns [x0, x1) of its cell to (dx, dy). */
static void show(cview *v, int i, int x0, int x1, int dx, int dy, bool heat) {
    cv_pack *p = &v->packs[i];
    if (!p->loaded) return;   /* its label says it is loading */
    if (heat && p->have_heat) {
        glDisable(GL_FRAMEBUFFER_SRGB);   /* heat maps are display values already */
        blit(p->heat_fbo, x0, x1, p->heat_h, dx, dy);
    } else if (p->tg.fbo) {
        /* a world is lit in linear radiance: the window encodes sRGB, as `tarn view` does */
        if (render_has_world(p->r)) glEnable(GL_FRAMEBUFFER_SRGB);
        blit_image(v, p->tg.fbo, x0, x1, dx, dy);
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

/* Pack i's name, times and error over the part of the scene it has
 * (framebuffer columns x0..x1, top row ytop): centred at the top, clear of
 * the corners, where what a view shows at its edges is. */
static void label_pack(cview *v, int i, int x0, int x1, int ytop, bool heat) {
    cv_pack *p = &v->packs[i];
    strbuf text = { 0 };
    /* two lines at most, so the view stays visible; the GPU time, the
     * frame's error and each pass's time are in the panel */
    if (!p->loaded) strbuf_printf(&text, "%s\nloading... (compiling its shaders)", p->label);
    else strbuf_printf(&text, "%s  %.1f ms", p->label, p->wall_ms);
    if (heat && p->have_heat && v->shown_metric == HEAT_METRIC_FLIP)
        strbuf_printf(&text, "\nwater FLIP %.3f  RMSE %.4f", p->flip, p->rmse);
    else if (heat && p->have_heat) strbuf_printf(&text, "\nwater RMSE %.4f  PSNR %.1f dB", p->rmse, p->psnr);
    if (p->passes[0] && v->passes_over_views) strbuf_printf(&text, "\n%s", p->passes);
    float wx0, wx1, wy;
    to_window(v, x0, ytop, &wx0, &wy);
    to_window(v, x1, ytop, &wx1, &wy);
    panel_label_between(v->panel, wx0 + 2, wx1 - 2, wy + 6, text.s);
    strbuf_free(&text);
}

/* ---- the heat maps' legend: in the panel, outside the views (issue #30) ---- */

static bool legend_shown(const cview *v, bool heat) {
    if (!heat || !(v->heat_scale > 0)) return false;
    for (int i = 0; i < v->n; i++)
        if (v->packs[i].have_heat) return true;
    return false;
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
        int split = v->area_x + wipe_px(v);
        label_pack(v, v->wipe_a, v->area_x, split, v->cell_h, heat);
        label_pack(v, v->wipe_b, split, v->area_x + v->cell_w, v->cell_h, heat);
        return;
    }
    for (int i = 0; i < v->n; i++) {
        int x, y;
        cell_rect(v, i, &x, &y);
        label_pack(v, i, x, x + v->cell_w, y + v->cell_h, heat);
    }
}

/* ---- loading, reloading ---- */

static void report(cv_pack *p) {
    const char *m = render_messages(p->r);
    if (m[0]) fprintf(stderr, "%s: %s", p->label, m);
}

static void on_reload(void *user, app *a) {
    cview *v = user;
    char line[2048];
    view_reload_line("tarn compare-view", v->scene, app_reload_cause(a), app_reload_compiled_s(a), line, sizeof line);
    fprintf(stderr, "%s\n", line);
    for (int i = 0; i < v->n; i++) {
        if (!v->packs[i].loaded) continue;   /* load_next_pack reads the files as they are then */
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
        else start_reference(v);
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
 * the camera. The press is judged where it happened (the button callback's
 * position), not where the cursor is a slow frame later. */
static void cv_mouse(cview *v, const view_mouse_input *in) {
    layout_cells(v);
    int ww, wh;
    glfwGetWindowSize(v->win, &ww, &wh);
    double sx = ww > 0 ? (double)v->fb_w / ww : 1.0;
    bool ui = panel_wants_mouse(v->panel) || (in->pressed && panel_contains(v->panel, in->press_x, in->press_y));
    if (v->layout == PANEL_LAYOUT_WIPE && (in->pressed & VIEW_MOUSE_LEFT) && !ui && !v->s->mouse.dragging_orbit &&
        !v->dragging_wipe) {
        double divider = v->area_x + wipe_px(v);
        if (fabs(in->press_x * sx - divider) <= DIVIDER_GRAB) v->dragging_wipe = true;
    }
    if (v->dragging_wipe) {
        v->wipe = (float)((in->x * sx - v->area_x) / (v->cell_w > 0 ? v->cell_w : 1));
        v->wipe = fmaxf(0.0f, fminf(1.0f, v->wipe));
        v->s->mouse.last_x = in->x;
        v->s->mouse.last_y = in->y;
        if (!in->left) v->dragging_wipe = false;   /* released: this frame's position was the last */
        return;
    }
    view_mouse_step(&v->s->mouse, in, ui, &v->s->cam);
}

static void on_mouse(void *user, app *a) {
    cview *v = user;
    view_mouse_input in;
    view_mouse_read(&v->s->mouse, v->win, &in);
    cv_mouse(v, &in);
}

/* What the panel asked for besides reload, pause and screenshot (the app's). */
static void on_apply(void *user, app *a) {
    cview *v = user;
    const panel_compare_actions *p = &v->pending;
    for (int i = 0; i < v->n; i++)
        if (p->recompile[i]) {
            app_picture_changed(a);
            render_rebuild_programs(v->packs[i].r);
            report(&v->packs[i]);
        }
    if (p->reset_camera) v->s->cam = v->s->cam_home;
    if (p->compute_heat) start_reference(v);
}

/* ---- the frame ---- */

static bool heat_shown(const cview *v) { return v->show_heat && ref_valid(v); }

static void on_draw(void *user, app *a) {
    cview *v = user;
    if (v->wipe_a == v->wipe_b) v->wipe_b = (v->wipe_a + 1) % v->n;
    ensure_targets(v);
    poll_heat(v);
    bool heat = heat_shown(v);
    /* heat maps read the packs' images back: those are full size */
    double scale;
    int what[4] = { v->layout, v->wipe_a, v->wipe_b, v->layout == PANEL_LAYOUT_WIPE };
    uint64_t key = hash_fnv1a(app_picture_key(a, v->cell_w, v->cell_h), what, sizeof what);
    bool draw = app_budget_plan(a, key, heat, &scale);
    render_view view = orbit_view(&v->s->cam);
    if (draw || v->drawn_w == 0 || v->drawn_w > v->cell_w || v->drawn_h > v->cell_h) {
        if (!draw) scale = 1.0;
        res_budget_size(scale, v->cell_w, v->cell_h, &v->drawn_w, &v->drawn_h);
        v->drawn_scale = scale;
        draw_packs(v, &view, scale, false);
    } else {
        draw_packs(v, &view, v->drawn_scale, true);   /* a pack loaded since: the same picture, its part */
    }
    app_budget_drawn(a, v->drawn_w, v->drawn_h, v->cell_w, v->cell_h);
    if (heat) request_maps(v);
    if (heat_job_busy(v->job)) app_keep_awake(a);   /* its result (the maps just asked for too) arrives between frames */
    if (v->have_ref && !ref_valid(v) && heat_job_running(v->job) != HEAT_JOB_REFERENCE)
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
        pp[i] = (panel_compare_pack){ .name = p->title, .passes = p->passes, .gpu_ms = pack_drawn(v, i) ? p->gpu_ms : -1,
                                      .wall_ms = pack_drawn(v, i) ? p->wall_ms : -1,
                                      .rmse = heat && p->have_heat ? p->rmse : NAN,
                                      .psnr_db = heat && p->have_heat ? p->psnr : NAN,
                                      .flip = heat && p->have_heat ? p->flip : NAN,
                                      .error_text = render_has_errors(p->r) ? render_messages(p->r) : NULL };
        pp[i].sets = render_uniforms(p->r, &pp[i].nsets);
    }
    const char *status = v->heat_status[0] ? v->heat_status : "no heat maps yet: H computes them";
    bool legend = legend_shown(v, heat);
    if (legend) make_legend(v);
    bool cpu_raster = v->s->cpu_raster;
    char res[160];
    app_budget_text(a, res, sizeof res);
    panel_compare pc = { .budget_ms = app_budget_ms(a), .resolution = res, .scene_path = v->scene, .frame_ms = v->s->frame_ms, .fps = v->s->fps, .time_s = v->s->t, .paused = v->s->paused,
                         .packs = pp, .npacks = v->n, .layout = &v->layout, .wipe_a = &v->wipe_a,
                         .wipe_b = &v->wipe_b, .wipe = &v->wipe, .show_heat = &v->show_heat,
                         .heat_max = &v->heat_max, .heat_status = status,
                         .legend_rgb = legend ? v->legend_rgb : NULL, .legend_n = LEGEND_STEPS,
                         .legend_scale = v->heat_scale, .passes_over_views = &v->passes_over_views,
                         .metric = &v->metric, .legend_flip = v->shown_metric == HEAT_METRIC_FLIP,
                         .note = cpu_raster ? "llvmpipe: GPU timestamps do not time the rasterisation; "
                                              "wall time (after glFinish) does"
                                            : NULL };
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
    if (strcmp(cmd, "drag") == 0) {   /* a press, a move and a release, all between two frames */
        double x0, y0, x1, y1;
        if (sscanf(rest, "%lf %lf %lf %lf", &x0, &y0, &x1, &y1) != 4) {
            fprintf(stderr, "%s:%d: drag wants X0 Y0 X1 Y1 (window pixels)\n", file, line);
            return VIEW_SCRIPT_FAILED;
        }
        view_mouse_input in = { .x = x1, .y = y1, .left = true, .pressed = VIEW_MOUSE_LEFT, .press_x = x0, .press_y = y0 };
        cv_mouse(v, &in);
        in = (view_mouse_input){ .x = x1, .y = y1 };
        cv_mouse(v, &in);
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "expect-divider") == 0) {
        double want = atof(a);
        bool ok = fabs(v->wipe - want) <= 0.01;
        fprintf(stderr, "%s:%d: expect-divider %.3f: the divider is at %.3f%s\n", file, line, want, v->wipe,
                ok ? "" : " (FAILED)");
        return ok ? VIEW_SCRIPT_CONTINUE : VIEW_SCRIPT_FAILED;
    }
    if (strcmp(cmd, "expect-camera") == 0) {   /* home: where F puts it; moved: elsewhere */
        bool home = orbit_equal(&v->s->cam, &v->s->cam_home);
        bool ok = strcmp(a, "home") == 0 ? home : strcmp(a, "moved") == 0 ? !home : false;
        fprintf(stderr, "%s:%d: expect-camera %s: the camera is %s%s\n", file, line, a, home ? "home" : "moved",
                ok ? "" : " (FAILED)");
        return ok ? VIEW_SCRIPT_CONTINUE : VIEW_SCRIPT_FAILED;
    }
    if (strcmp(cmd, "metric") == 0) {   /* color | flip: what the heat maps show */
        char word[16] = "";
        sscanf(rest, "%15s", word);
        if (strcmp(word, "color") != 0 && strcmp(word, "flip") != 0) {
            fprintf(stderr, "%s:%d: metric wants color or flip\n", file, line);
            return VIEW_SCRIPT_FAILED;
        }
        v->metric = word[0] == 'f' ? HEAT_METRIC_FLIP : HEAT_METRIC_COLOR;
        v->reported = false;   /* the next maps' figures are said again */
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "heat") == 0) return compute_reference_now(v) ? VIEW_SCRIPT_CONTINUE : VIEW_SCRIPT_FAILED;
    if (strcmp(cmd, "heat-show") == 0) {
        v->show_heat = strcmp(a, "on") == 0;
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "heat-max") == 0) {
        v->heat_max = (float)atof(a);
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

/* The packs' renderers, and the first pack's scene, loaded before the
 * window's first frame (the others load after it, load_next_pack). */
static void load_packs(cview *v, const compare_view_desc *d) {
    for (int i = 0; i < v->n; i++) {
        cv_pack *p = &v->packs[i];
        snprintf(p->name, sizeof p->name, "%s", d->packs[i]);
        int copy = 1;
        for (int j = 0; j < i; j++) copy += strcmp(d->packs[j], d->packs[i]) == 0;
        if (copy > 1) snprintf(p->title, sizeof p->title, "%s #%d", p->name, copy);
        else snprintf(p->title, sizeof p->title, "%s", p->name);
        snprintf(p->label, sizeof p->label, "%d %s", i + 1, p->title);
        render_desc rd = { .pack = p->name, .samples = d->samples, .files = app_files(v->app) };
        p->r = v->scenes[i] = render_create(&rd);
        p->rmse = p->psnr = p->frame_rmse = NAN;
    }
    char loading[1024], which[128];
    snprintf(which, sizeof which, " (pack 1 of %d: %s)", v->n, v->packs[0].title);
    view_loading_text(d->glib, v->packs[0].name, which, loading, sizeof loading);
    app_splash(v->app, loading);
    v->load_failed = !render_load(v->packs[0].r, d->glib);
    v->packs[0].loaded = true;
    report(&v->packs[0]);
}

/* After a frame is on screen: the next pack's scene (its tile said
 * "loading..." until now); false once every pack is loaded. */
static bool load_next_pack(void *user, app *a) {
    cview *v = user;
    int i = 0;
    while (i < v->n && v->packs[i].loaded) i++;
    if (i == 1)   /* the GLFW clock, as the script's `clock` (scripts/first_frame_bench.sh) */
        fprintf(stderr, "tarn compare-view: first picture at %.3f ms, %s drawn; loading the others\n",
                glfwGetTime() * 1e3, v->packs[0].title);
    if (i < v->n) {
        cv_pack *p = &v->packs[i];
        if (!render_load(p->r, v->scene)) v->load_failed = true;
        p->loaded = true;
        report(p);
        app_rewatch(a);            /* its shaders are watched too; on_draw draws it (drawn is false) */
        i++;
    }
    if (i < v->n) return true;
    fprintf(stderr, "tarn compare-view: loaded %s (%d packs)\n", v->scene, v->n);
    return false;
}

static void free_packs(cview *v) {
    for (int i = 0; i < v->n; i++) {
        cv_pack *p = &v->packs[i];
        render_target_destroy(&p->tg);
        if (p->heat_fbo) glDeleteFramebuffers(1, &p->heat_fbo);
        if (p->heat_tex) glDeleteTextures(1, &p->heat_tex);
        free(p->pixels);
        render_destroy(p->r);
    }
    heat_job_destroy(v->job);   /* first: its maps borrow the reference */
    refcache_free(&v->ref);
}

int compare_view_run(const compare_view_desc *d) {
    if (d->npacks < 2 || d->npacks > COMPARE_VIEW_MAX_PACKS) {
        fprintf(stderr, "tarn compare-view: give 2 to 4 packs (--packs a,b)\n");
        return TARN_EXIT_USAGE;
    }
    cview *v = mem_zalloc(sizeof *v);
    v->scene = d->glib;
    v->n = d->npacks;
    v->wipe = 0.5f;
    v->wipe_b = 1;
    v->ref_opts.caustic_res = d->ref_caustic_res > 0 ? d->ref_caustic_res : 128;
    v->ref_opts.photons_per_cell = d->ref_photons > 0 ? d->ref_photons : 16;
    v->job = heat_job_create();
    v->scripted = d->script != NULL;
    app_desc ad = { .name = "tarn compare-view", .scene_path = d->glib,
                    .width = d->width > 0 ? d->width + APP_PANEL_WIDTH : 1400,
                    .height = d->height > 0 ? d->height : 800, .time_s = d->time_s, .script = d->script,
                    .user = v, .draw = on_draw, .panel = on_panel, .apply = on_apply, .reload = on_reload,
                    .mouse = on_mouse, .key = on_key, .script_action = script_action,
                    .between_frames = load_next_pack };
    v->app = app_create(&ad);
    if (!v->app) {
        heat_job_destroy(v->job);
        free(v);
        return TARN_EXIT_NO_GL;
    }
    v->s = app_get_state(v->app);
    v->win = app_window(v->app);
    v->panel = app_panel(v->app);
    load_packs(v, d);
    /* the reference is subsampled where the packs' MSAA samples, so an
     * anti-aliased edge is compared with an edge anti-aliased alike */
    refcache_match_msaa(&v->ref_opts, render_samples(v->packs[0].r));
    if (d->width <= 0 || d->height <= 0) {
        int w, h;
        render_window_size(v->packs[0].r, &w, &h);
        app_fit_window(v->app, w, h);
    }
    app_home(v->app, render_default_view(v->packs[0].r));
    int rc = app_run(v->app, v->scenes, v->n);
    if (rc == TARN_EXIT_OK && v->load_failed && d->script) rc = TARN_EXIT_INPUT;
    free_packs(v);
    app_destroy(v->app);
    free(v);
    return rc;
}
