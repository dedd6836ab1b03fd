/* render_setting: a pack's named setting applied to a running scene (render_setting.h). */
#include "render_setting.h"
#include "strbuf.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"
#include "util.h"

static void append(char *msg, int msglen, const char *fmt, ...) {
    if (!msg || msglen <= 0) return;
    size_t used = strlen(msg);
    if (used + 1 >= (size_t)msglen) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg + used, (size_t)msglen - used, fmt, ap);
    va_end(ap);
}

static bool is_scene(const packset_assign *a) { return strcmp(a->program, "scene") == 0; }

bool render_setting_applicable(const packset_setting *s, char *why, int whylen) {
    if (why && whylen > 0) why[0] = '\0';
    for (int k = 0; s && k < s->nassign; k++) {
        const packset_assign *a = &s->assign[k];
        if (is_scene(a) && strcmp(a->name, "WaterMesh") != 0) {
            append(why, whylen, "scene.%s does not apply to a running scene (only scene.WaterMesh does)", a->name);
            return false;
        }
    }
    return true;
}

/* The setting's scene assignments as world overrides; a reload when the
 * world on screen was built without them. */
static bool set_world(render *r, const packset_setting *s, char *msg, int msglen) {
    bool ok = true;
    for (int k = 0; s && k < s->nassign; k++) {
        const packset_assign *a = &s->assign[k];
        if (!is_scene(a) || render_set_world_override(r, a->name, a->value, a->nvalue)) continue;
        append(msg, msglen, "setting '%s': scene.%s does not apply to a running scene (only scene.WaterMesh=N "
                            "does); `tarn bench` applies it through a scene that adds the line\n", s->name, a->name);
        ok = false;
    }
    if (!render_world_overrides_pending(r)) return ok;
    if (!render_load(r, NULL)) {
        append(msg, msglen, "%s", render_messages(r));
        ok = false;
    }
    return ok;
}

/* Back to the defaults (reset), then s's uniform and Define assignments;
 * the programs rebuilt when a Define changed. */
static bool assign_uniforms(render *r, const packset_setting *s, bool reset, char *msg, int msglen) {
    int n;
    unif_set *sets = render_uniforms(r, &n);
    bool rebuild = false, ok = true;
    for (int i = 0; reset && i < n; i++) rebuild = unif_reset_all_ex(&sets[i]) || rebuild;
    if (s) {
        bool changed = false;
        size_t used = msg && msglen > 0 ? strlen(msg) : 0;
        ok = packset_apply(sets, n, s, &changed, msg ? msg + used : NULL, msg ? msglen - (int)used : 0);
        rebuild = rebuild || changed;
    }
    if (rebuild && !render_rebuild_programs(r)) {
        append(msg, msglen, "%s", render_messages(r));
        ok = false;
    }
    return ok;
}

bool render_setting_assign(render *r, const packset_setting *s, char *msg, int msglen) {
    bool ok = set_world(r, s, msg, msglen);
    return assign_uniforms(r, s, false, msg, msglen) && ok;
}

bool render_setting_apply(render *r, const packset_setting *s, char *msg, int msglen) {
    render_clear_world_overrides(r);
    bool ok = set_world(r, s, msg, msglen);
    return assign_uniforms(r, s, true, msg, msglen) && ok;
}

bool render_setting_apply_named(render *r, const char *root, const char *name, char *msg, int msglen) {
    const char *pack = render_pack(r);
    if (!pack[0]) {
        append(msg, msglen, "setting %s: the scene is drawn by no pack (a setting belongs to a pack's bench.txt)\n",
               name);
        return false;
    }
    packset_bench b;
    char err[MSG_MAX] = "";
    packset_bench_load(root ? root : tarn_root(), pack, &b, err, sizeof err);   /* bad lines: the good ones stay */
    const packset_setting *s = packset_setting_named(&b, name);
    bool ok = s || strcmp(name, "default") == 0;
    if (ok) ok = render_setting_apply(r, s, msg, msglen);
    else {
        append(msg, msglen, "setting %s: the %s pack has no such setting; it has", name, pack);
        int *order = mem_alloc((size_t)(b.n + 1) * sizeof *order);
        int n = packset_menu(&b, order);
        for (int i = 0; i < n; i++) append(msg, msglen, " %s", order[i] < 0 ? "default" : b.settings[order[i]].name);
        free(order);
        append(msg, msglen, " (%s)\n", b.path[0] ? b.path : "no bench.txt");
    }
    packset_bench_free(&b);
    return ok;
}
