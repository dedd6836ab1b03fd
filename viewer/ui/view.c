/* `tarn view`: the interactive window, a client of app.h. Draws the scene,
 * the generated slider panel and any error overlay; the app watches every
 * file the scene reads and reloads within a frame or two of a save; orbit,
 * pan and zoom camera. */
#include <GL/gl.h>
#include <GLFW/glfw3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "strbuf.h"
#include "exit_code.h"
#include "glib.h"
#include "packset.h"
#include "panel.h"
#include "mem.h"
#include "render.h"
#include "render_setting.h"
#include "res_budget.h"
#include "upscale.h"
#include "util.h"
#include "view.h"

typedef struct viewer {
    app *app;
    render *r;
    panel_actions pending;       /* the panel's buttons of this frame, applied after it */
    packset_name packs[PACKSET_MAX];   /* what the panel's Pack combo offers */
    const char *pack_names[PACKSET_MAX];
    int npacks;
    /* the Setting combo: the settings of the pack drawing the scene */
    packset_bench bench;
    char bench_pack[PACKSET_NAME_MAX];   /* whose bench.txt that is ("" none read) */
    int *order;                          /* menu row -> bench.settings index, -1 the implicit default */
    const char **setting_names, **setting_tips;
    char (*tips)[PACKSET_COMMENT_MAX + 160];
    int nsettings;
    int setting;                         /* the menu row chosen last; -1 none since the pack was drawn */
    /* the scene's image, drawn at the budget's scale into its bottom-left
     * corner and upscaled into the window: sRGB for a world (the window's
     * encoding, so the picture is what drawing to the window gave) */
    render_target canvas;
    int drawn_w, drawn_h;        /* what the canvas holds (0: nothing yet) */
    upscaler *up;                /* the canvas into the window (made at the first frame) */
    /* the sharp world (gfx/upscale.h upscale_draw_over_world): the world
     * alone at the canvas's full size, kept while only the clock runs, under
     * the reduced frames' water */
    render_target world;
    uint64_t world_key;          /* the timeless picture key it was drawn for (0: none) */
    uint64_t last_timeless;      /* the timeless key of the last frame drawn (0: it drew no reduced world) */
    bool over_world;             /* the canvas's frame goes over it */
    bool world_off;              /* the script's `sharp-world 0`: enlarged whole, as before */
} viewer;

static void canvas_free(viewer *v) {
    render_target_destroy(&v->canvas);
    v->drawn_w = v->drawn_h = 0;
}

/* A w x h canvas of the format the scene needs; false (nothing drawn
 * this frame) when GL refuses it. */
static bool canvas_ensure(viewer *v, int w, int h, bool srgb) {
    render_target *c = &v->canvas;
    if (c->fbo && c->w == w && c->h == h && c->is_srgb == srgb) return true;
    canvas_free(v);
    if (srgb ? render_target_create_srgb(c, w, h) : render_target_create(c, w, h, false)) return true;
    fprintf(stderr, "tarn: cannot make a %dx%d scene canvas\n", w, h);
    return false;
}

/* Whether the full-resolution world holds this frame's world: drawn once
 * the picture's key without its time has held for two frames (the clock
 * running, nothing else changing), not while the camera or a slider moves
 * (a full-size world draw each frame would cost what the budget saves). */
static bool world_ready(viewer *v, app *a, int w, int h, const render_view *view, double t) {
    uint64_t k = app_picture_key_timeless(a, w, h);
    unsigned long long inputs = render_world_frame_inputs(v->r);   /* a save of the water's shader: none changed */
    k = hash_fnv1a(k, &inputs, sizeof inputs);
    bool held = k == v->last_timeless;
    v->last_timeless = k;
    if (k == v->world_key) return true;
    if (!held) return false;
    render_target *c = &v->world;
    if (!(c->fbo && c->w == w && c->h == h)) {
        render_target_destroy(c);
        if (!render_target_create_srgb(c, w, h)) return false;
    }
    render_frame_world_at(v->r, t, c->fbo, 0, 0, w, h, view);
    v->world_key = k;
    return true;
}

static void report_load(viewer *v) {
    const char *m = render_messages(v->r);
    if (m[0]) fputs(m, stderr);
    else fprintf(stderr, "tarn: loaded %s\n", render_scene_path(v->r));
}

/* ---- the Setting combo ---- */

static void settings_free(viewer *v) {
    packset_bench_free(&v->bench);
    free(v->order);
    free(v->setting_names);
    free(v->setting_tips);
    free(v->tips);
    v->order = NULL;
    v->setting_names = v->setting_tips = NULL;
    v->tips = NULL;
    v->nsettings = 0;
    v->bench_pack[0] = '\0';
}

/* The menu of the pack drawing the scene, read when that pack changed
 * (default first, then paper, then bench.txt's order; packset_menu). */
static void settings_sync(viewer *v) {
    const char *pack = render_has_world(v->r) ? render_pack(v->r) : "";
    if (strcmp(pack, v->bench_pack) == 0) return;
    settings_free(v);
    v->setting = -1;
    snprintf(v->bench_pack, sizeof v->bench_pack, "%s", pack);
    if (!pack[0]) return;
    char err[MSG_MAX] = "";
    if (!packset_bench_load(tarn_root(), pack, &v->bench, err, sizeof err)) fputs(err, stderr);
    int cap = v->bench.n + 1;
    v->order = mem_alloc((size_t)cap * sizeof *v->order);
    v->setting_names = mem_alloc((size_t)cap * sizeof *v->setting_names);
    v->setting_tips = mem_alloc((size_t)cap * sizeof *v->setting_tips);
    v->tips = mem_alloc((size_t)cap * sizeof *v->tips);
    v->nsettings = packset_menu(&v->bench, v->order);
    for (int i = 0; i < v->nsettings; i++) {
        const packset_setting *st = v->order[i] < 0 ? NULL : &v->bench.settings[v->order[i]];
        char na[PACKSET_COMMENT_MAX] = "";
        bool applies = render_setting_applicable(st, na, sizeof na);
        snprintf(v->tips[i], sizeof v->tips[i], "%s%s%s%s", st ? st->comment : "the pack's defaults",
                 applies ? "" : " [not applicable here: ", applies ? "" : na, applies ? "" : "]");
        v->setting_names[i] = st ? st->name : "default";
        v->setting_tips[i] = v->tips[i];
    }
}

/* What picking row i of the Setting combo does: the pack's defaults, then
 * the setting (render_setting_apply), said on screen and recorded. */
static bool choose_setting(viewer *v, app *a, int i) {
    settings_sync(v);
    if (i < 0 || i >= v->nsettings) return false;
    const packset_setting *st = v->order[i] < 0 ? NULL : &v->bench.settings[v->order[i]];
    const char *name = v->setting_names[i];
    char msg[MSG_MAX] = "";
    bool ok = render_setting_apply(v->r, st, msg, sizeof msg);
    v->setting = i;
    if (msg[0]) fputs(msg, stderr);
    fprintf(stderr, "tarn: setting %s of the %s pack%s\n", name, v->bench_pack, ok ? "" : " (in part: see above)");
    app_rewatch(a);   /* a scene.WaterMesh reloads the scene */
    app_picture_changed(a);
    app_record_setting(a, name);
    if (ok) app_toast(a, "setting %s of the %s pack", name, v->bench_pack);
    else app_toast(a, "setting %s applied in part: see the messages", name);
    return ok;
}

static int setting_row(viewer *v, const char *name) {
    settings_sync(v);
    for (int i = 0; i < v->nsettings; i++)
        if (strcmp(v->setting_names[i], name) == 0) return i;
    return -1;
}

/* ---- hooks ---- */

/* "tarn: reloaded scenes/lake.glib (water.frag changed)", then what the load said. */
static void on_reload(void *user, app *a) {
    viewer *v = user;
    render_load(v->r, NULL);
    char line[2048];
    view_reload_line("tarn", render_scene_path(v->r), app_reload_cause(a), app_reload_compiled_s(a), line, sizeof line);
    fprintf(stderr, "%s\n", line);
    fputs(render_messages(v->r), stderr);
}

/* On screen as well as on stderr: the student sees where it went. */
static void preset(viewer *v, bool save) {
    char path[1100], err[512] = "";
    unif_preset_path(render_scene_path(v->r), path, (int)sizeof path);
    int n;
    unif_set *sets = render_uniforms(v->r, &n);
    bool ok = save ? unif_preset_save(sets, n, path, err, sizeof err)
                   : unif_preset_load(sets, n, path, err, sizeof err);
    if (ok && !save) render_rebuild_programs(v->r);   /* defines may have changed */
    fprintf(stderr, "tarn: %s preset %s%s%s\n", save ? "save" : "load", path, ok ? "" : ": ", ok ? "" : err);
    if (ok) app_toast(v->app, "preset %s %s", save ? "saved to" : "loaded from", path);
    else app_toast(v->app, "preset not %s: %s", save ? "saved" : "loaded", err);
}

/* The same world drawn by another pack, live: a reload with the pack
 * overridden (the sliders of programs it shares with the last keep their
 * values, as on any reload). A failed load keeps the picture and says why. */
static void switch_pack(viewer *v, app *a, int i) {
    if (i < 0 || i >= v->npacks) return;
    char before[PACKSET_NAME_MAX];
    snprintf(before, sizeof before, "%s", render_pack(v->r));
    render_set_pack(v->r, v->packs[i]);
    render_clear_world_overrides(v->r);   /* a setting's WaterMesh belonged to the last pack */
    bool ok = render_load(v->r, NULL);
    app_picture_changed(a);
    /* refused (the scene kept its last good state, a glman scene has no
     * world for a pack): the scene on screen keeps its pack, so that the
     * next save reloads it and not the refusal */
    if (strcmp(render_pack(v->r), v->packs[i]) != 0) render_set_pack(v->r, before[0] ? before : NULL);
    report_load(v);
    app_rewatch(a);
    if (ok) {
        app_record_pack(a, v->packs[i]);
        app_toast(a, "drawn by the %s pack", v->packs[i]);
    }
    else app_toast(a, "the %s pack failed to load: see the messages", v->packs[i]);
}

static int current_pack(const viewer *v) {
    const char *now = render_pack(v->r);
    for (int i = 0; i < v->npacks; i++)
        if (strcmp(v->packs[i], now) == 0) return i;
    return -1;
}

/* `setting NAME`: what picking NAME in the Setting combo does. */
static view_script_status setting_action(viewer *v, char *rest, const char *file, int line) {
    char name[PACKSET_NAME_MAX] = "";
    sscanf(rest, "%63s", name);
    int i = setting_row(v, name);
    if (i < 0) {
        fprintf(stderr, "%s:%d: setting: %s has no setting '%s'; it has", file, line,
                v->bench_pack[0] ? v->bench_pack : "the scene (no pack)", name);
        for (int k = 0; k < v->nsettings; k++) fprintf(stderr, " %s", v->setting_names[k]);
        fputc('\n', stderr);
        return VIEW_SCRIPT_FAILED;
    }
    return choose_setting(v, v->app, i) ? VIEW_SCRIPT_CONTINUE : VIEW_SCRIPT_FAILED;
}

/* The window's own script actions: `pack NAME` and `setting NAME` do what
 * picking NAME in the panel's Pack or Setting combo does (tests drive the
 * switches this way); `world-cache 0|1` turns the world's caches off and
 * on (scripts/window_bench.sh's A/B); `sharp-world 0|1` the full-resolution
 * world under a reduced frame's water (scripts/live_error.sh's A/B). */
static view_script_status script_action(void *user, const char *cmd, char *rest, const char *file, int line) {
    viewer *v = user;
    if (strcmp(cmd, "setting") == 0) return setting_action(v, rest, file, line);
    if (strcmp(cmd, "world-cache") == 0) {   /* the static-world cache and the layers, for A/B runs */
        render_set_world_cache(v->r, atoi(rest) != 0);
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "sharp-world") == 0) {   /* the full-resolution world under the water, for A/B runs */
        v->world_off = atoi(rest) == 0;
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "pack") != 0) {
        fprintf(stderr, "%s:%d: unknown script action '%s'\n", file, line, cmd);
        return VIEW_SCRIPT_FAILED;
    }
    char name[PACKSET_NAME_MAX] = "";
    sscanf(rest, "%63s", name);
    for (int i = 0; i < v->npacks; i++)
        if (strcmp(v->packs[i], name) == 0) {
            switch_pack(v, v->app, i);
            return VIEW_SCRIPT_CONTINUE;
        }
    fprintf(stderr, "%s:%d: pack: no pack '%s' under %s/packs\n", file, line, name, tarn_root());
    return VIEW_SCRIPT_FAILED;
}

/* What the panel asked for besides reload, pause and screenshot (the app's). */
static void on_apply(void *user, app *a) {
    viewer *v = user;
    const panel_actions *p = &v->pending;
    int n;
    unif_set *sets = render_uniforms(v->r, &n);
    if (p->reset_all)
        for (int i = 0; i < n; i++) unif_reset_all(&sets[i]);
    if (p->recompile || p->reset_all || p->load_preset) app_picture_changed(a);
    if (p->recompile || p->reset_all) {
        render_rebuild_programs(v->r);
        report_load(v);
        app_rewatch(a);
    }
    if (p->save_preset) preset(v, true);
    if (p->load_preset) preset(v, false);
    if (p->switch_pack) switch_pack(v, a, p->pack);
    if (p->switch_setting) choose_setting(v, a, p->setting);
}

/* The scene at the budget's scale into the canvas (when the picture
 * changed, or to bring it to full resolution), then the canvas into the
 * scene area: copied at full resolution; while only the clock runs, its
 * water over the world kept at full resolution (world_ready); else
 * enlarged by the sharpened, deringed cubic (gfx/upscale.h) on a GPU, the
 * linear blit on a CPU rasteriser (below). */
static void on_draw(void *user, app *a) {
    viewer *v = user;
    app_state *s = app_get_state(a);
    int w, h;
    glfwGetFramebufferSize(app_window(a), &w, &h);
    int x0 = app_scene_x(w), aw = w - x0 > 0 ? w - x0 : 1, ah = h > 0 ? h : 1;
    /* a world is lit in linear radiance: the window encodes sRGB, as the
     * reference's PNG does; glman scenes are shown as drawn */
    bool world = render_has_world(v->r);
    double scale;
    bool draw = app_budget_plan(a, app_picture_key(a, aw, ah), false, &scale);
    if (!canvas_ensure(v, aw, ah, world)) return;
    if (draw || v->drawn_w == 0) {
        if (!draw) scale = 1.0;   /* a new canvas holds nothing yet */
        res_budget_size(scale, aw, ah, &v->drawn_w, &v->drawn_h);
        render_view view = orbit_view(&s->cam);
        if (world) glEnable(GL_FRAMEBUFFER_SRGB);
        /* before the frame: the world-only frame starts a snapshot of its own */
        bool reduced_world = world && !v->world_off && v->drawn_w < aw;
        app_sharp_world(a, world && !v->world_off);
        v->over_world = reduced_world && world_ready(v, a, aw, ah, &view, s->t);
        /* a full frame breaks the hold: a paused picture's first reduced
         * frame after a save must not draw the world (its key held since
         * the clock stopped, while the job compiles the still frame) */
        if (!reduced_world) v->last_timeless = 0;
        render_set_world_snapshot(v->r, v->over_world);   /* only a frame that goes over it pays the copy */
        render_set_detail(v->r, scale);   /* the passes and meshes shrink with the frame */
        render_frame_at(v->r, s->t, v->canvas.fbo, 0, 0, v->drawn_w, v->drawn_h, &view);
    }
    app_budget_drawn(a, v->drawn_w, v->drawn_h, aw, ah);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glViewport(0, 0, w, h);
    glClearColor(0.12f, 0.12f, 0.13f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    /* sRGB to sRGB: decoded, filtered in linear, encoded again (1:1 a copy) */
    if (world) glEnable(GL_FRAMEBUFFER_SRGB);
    if (!v->up) {
        /* On a CPU rasteriser the cubic costs about 10 ms a frame more than
         * the linear blit (bench_upscale, 960x540: 17 against 7 ms), which
         * the 50 ms budget pays in pixels, for 0-6% less error: there the
         * blit; on a GPU both cost nothing and the cubic is the closer. */
        const char *err = NULL;
        upscale_desc ud = { .filter = s->cpu_raster ? UPSCALE_BILINEAR : UPSCALE_CUBIC };
        v->up = upscale_create(&ud, &err);
        if (err) fprintf(stderr, "%s\n", err);
    }
    upscale_rect rect = { x0, 0, aw, ah };
    int sw = 0, sh = 0;
    unsigned snap = v->over_world ? render_world_snapshot(v->r, &sw, &sh) : 0;
    bool over = snap && sw == v->drawn_w && sh == v->drawn_h &&
                upscale_draw_over_world(v->up, v->canvas.color, snap, v->drawn_w, v->drawn_h, v->world.color, 0, rect);
    if (!over) upscale_draw(v->up, v->canvas.color, v->drawn_w, v->drawn_h, 0, rect);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDisable(GL_FRAMEBUFFER_SRGB);
}

static void on_panel(void *user, app *a, panel_actions *common) {
    viewer *v = user;
    app_state *s = app_get_state(a);
    int n;
    unif_set *sets = render_uniforms(v->r, &n);
    settings_sync(v);
    char passes[1024];
    view_pass_summary(v->r, passes, sizeof passes);
    char res[160];
    app_budget_text(a, res, sizeof res);
    panel_info info = { .budget_ms = app_budget_ms(a), .resolution = res, .scene_path = render_scene_path(v->r), .gpu_ms = render_gpu_ms(v->r, false),
                        .cpu_raster = s->cpu_raster, .frame_ms = s->frame_ms, .fps = s->fps,
                        .paused = s->paused, .time_s = s->t,
                        .error_text = render_has_errors(v->r) ? render_messages(v->r) : NULL,
                        .scene_x = app_scene_x_window(a), .passes = passes,
                        /* a pack draws a world's water; a glman scene has none to switch */
                        .packs = v->pack_names, .npacks = render_has_world(v->r) ? v->npacks : 0,
                        .pack = current_pack(v), .settings = v->setting_names,
                        .setting_tips = v->setting_tips, .nsettings = v->nsettings, .setting = v->setting };
    panel_draw(app_panel(a), sets, n, &info, &v->pending);
    *common = v->pending;
}

/* ---- the command ---- */

int view_run(const view_desc *d) {
    viewer v;
    memset(&v, 0, sizeof v);
    /* GL objects need the context first, so the glib's WindowSize is
     * applied by resizing once the scene is loaded */
    app_desc ad = { .name = "tarn", .scene_path = d->glib, .width = d->width, .height = d->height,
                    .time_s = d->time_s, .script = d->script, .user = &v,
                    .recordable = true, .record = d->record, .pack = d->pack, .verbose = d->verbose,
                    .draw = on_draw, .panel = on_panel, .apply = on_apply, .reload = on_reload,
                    .script_action = script_action };
    v.app = app_create(&ad);
    if (!v.app) return TARN_EXIT_NO_GL;
    render_desc rd = { .pack = d->pack, .samples = d->samples, .verbose = d->verbose, .files = app_files(v.app) };
    v.r = render_create(&rd);
    v.npacks = packset_list(tarn_root(), v.packs, PACKSET_MAX);
    for (int i = 0; i < v.npacks; i++) v.pack_names[i] = v.packs[i];
    char loading[1024];
    view_loading_text(d->glib, d->pack, "", loading, sizeof loading);
    app_splash(v.app, loading);
    bool ok = render_load(v.r, d->glib);
    report_load(&v);
    app_toast(v.app, "F1 or ? shows the keys and the mouse");
    if (d->width <= 0 || d->height <= 0) {
        int w, h;
        render_window_size(v.r, &w, &h);
        app_fit_window(v.app, w, h);   /* room for the panel beside the scene */
    }
    if (ok && d->setting) {
        int i = setting_row(&v, d->setting);
        if (i >= 0) ok = choose_setting(&v, v.app, i);
        else {
            char msg[MSG_MAX] = "";
            ok = render_setting_apply_named(v.r, NULL, d->setting, msg, sizeof msg);   /* says which exist */
            fputs(msg, stderr);
        }
    }
    app_home(v.app, render_default_view(v.r));
    int rc = app_run(v.app, &v.r, 1);
    if (rc == TARN_EXIT_OK && !ok && d->script) rc = TARN_EXIT_INPUT;
    settings_free(&v);
    canvas_free(&v);
    render_target_destroy(&v.world);
    upscale_destroy(v.up);
    render_destroy(v.r);
    app_destroy(v.app);
    return rc;
}
