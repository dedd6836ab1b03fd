/* `tarn view`: the interactive window, a client of app.h. Draws the scene,
 * the generated slider panel and any error overlay; the app watches every
 * file the scene reads and reloads within a frame or two of a save; orbit,
 * pan and zoom camera. */
#include <GL/gl.h>
#include <GLFW/glfw3.h>
#include <stdio.h>
#include <string.h>

#include "app.h"
#include "exit_code.h"
#include "packset.h"
#include "panel.h"
#include "render.h"
#include "util.h"
#include "view.h"

typedef struct viewer {
    app *app;
    render *r;
    panel_actions pending;       /* the panel's buttons of this frame, applied after it */
    packset_name packs[PACKSET_MAX];   /* what the panel's Pack combo offers */
    const char *pack_names[PACKSET_MAX];
    int npacks;
} viewer;

static void report_load(viewer *v) {
    const char *m = render_messages(v->r);
    if (m[0]) fputs(m, stderr);
    else fprintf(stderr, "tarn: loaded %s\n", render_scene_path(v->r));
}

/* ---- hooks ---- */

/* "tarn: reloaded scenes/lake.glib (water.frag changed)", then what the load said. */
static void on_reload(void *user, app *a) {
    viewer *v = user;
    render_load(v->r, NULL);
    const char *cause = app_reload_cause(a);
    fprintf(stderr, "tarn: reloaded %s%s%s%s\n", render_scene_path(v->r), cause[0] ? " (" : "", cause,
            cause[0] ? ")" : "");
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
    bool ok = render_load(v->r, NULL);
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

/* The window's own script action: `pack NAME` does what picking NAME in
 * the panel's Pack combo does (tests drive the switch this way). */
static view_script_status script_action(void *user, const char *cmd, char *rest, const char *file, int line) {
    viewer *v = user;
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
    if (p->recompile || p->reset_all) {
        render_rebuild_programs(v->r);
        report_load(v);
        app_rewatch(a);
    }
    if (p->save_preset) preset(v, true);
    if (p->load_preset) preset(v, false);
    if (p->switch_pack) switch_pack(v, a, p->pack);
}

static void on_draw(void *user, app *a) {
    viewer *v = user;
    app_state *s = app_get_state(a);
    int w, h;
    glfwGetFramebufferSize(app_window(a), &w, &h);
    render_view view = orbit_view(&s->cam);
    int x0 = app_scene_x(w);
    glClearColor(0.12f, 0.12f, 0.13f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    /* a world is lit in linear radiance: the window encodes sRGB, as the
     * reference's PNG does; glman scenes are shown as drawn */
    if (render_has_world(v->r)) glEnable(GL_FRAMEBUFFER_SRGB);
    render_frame_at(v->r, s->t, 0, x0, 0, w - x0, h, &view);
    glDisable(GL_FRAMEBUFFER_SRGB);
}

static void on_panel(void *user, app *a, panel_actions *common) {
    viewer *v = user;
    app_state *s = app_get_state(a);
    int n;
    unif_set *sets = render_uniforms(v->r, &n);
    char passes[1024];
    view_pass_summary(v->r, passes, sizeof passes);
    panel_info info = { .scene_path = render_scene_path(v->r), .gpu_ms = render_gpu_ms(v->r, false),
                        .cpu_raster = s->cpu_raster, .frame_ms = s->frame_ms, .fps = s->fps,
                        .paused = s->paused, .time_s = s->t,
                        .error_text = render_has_errors(v->r) ? render_messages(v->r) : NULL,
                        .scene_x = app_scene_x_window(a), .passes = passes,
                        /* a pack draws a world's water; a glman scene has none to switch */
                        .packs = v->pack_names, .npacks = render_has_world(v->r) ? v->npacks : 0,
                        .pack = current_pack(v) };
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
                    .recordable = true, .record = d->record, .pack = d->pack,
                    .draw = on_draw, .panel = on_panel, .apply = on_apply, .reload = on_reload,
                    .script_action = script_action };
    v.app = app_create(&ad);
    if (!v.app) return TARN_EXIT_NO_GL;
    render_desc rd = { .pack = d->pack, .samples = d->samples };
    v.r = render_create(&rd);
    v.npacks = packset_list(tarn_root(), v.packs, PACKSET_MAX);
    for (int i = 0; i < v.npacks; i++) v.pack_names[i] = v.packs[i];
    bool ok = render_load(v.r, d->glib);
    report_load(&v);
    if (d->width <= 0 || d->height <= 0) {
        int w, h;
        render_window_size(v.r, &w, &h);
        app_fit_window(v.app, w, h);   /* room for the panel beside the scene */
    }
    app_home(v.app, render_default_view(v.r));
    int rc = app_run(v.app, &v.r, 1);
    if (rc == TARN_EXIT_OK && !ok && d->script) rc = TARN_EXIT_INPUT;
    render_destroy(v.r);
    app_destroy(v.app);
    return rc;
}
