/* render_size: the sizes of the scene's render targets and point grids:
 * a number, a slider's value, the screen's (or a half or quarter of it),
 * each at the frame's detail where it is drawn every frame
 * (render_set_detail). */
#include "util.h"
#include "render_internal.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <string.h>

#include "strbuf.h"

/* The current value of the uniform `name` of the first Program that has
 * it (Texture2D sizes and point counts, which come before their Program). */
static bool program_value(const scene_state *s, const char *name, float *out) {
    for (int i = 0; i < s->nprogs; i++) {
        const unif_entry *e = unif_find(s->progs[i].unifs, name);
        if (e && !e->is_define) {
            *out = e->value[0];
            return true;
        }
    }
    return false;
}

#define NAMED_SIZE_FALLBACK 256
#define NAMED_SIZE_MAX 8192

/* A count a slider gives (a target's side, points per side): rounded and
 * kept in 1..max; a missing slider or a NaN gives NAMED_SIZE_FALLBACK. */
int render_size_slider_count(const scene_state *s, const char *name, int max) {
    float v;
    if (!program_value(s, name, &v) || !isfinite(v)) return NAMED_SIZE_FALLBACK;
    long n = lrintf(v);
    return n < 1 ? 1 : n > max ? max : (int)n;
}

/* A target side named `screen` is the frame's (a pass whose output is read
 * pixel for pixel by a screen pass needs no more and no less),
 * `screen_half` and `screen_quarter` a half and a quarter of it (rounded
 * up: a pass whose output is blurred or faint anyway); any other name is a
 * slider's (slider_count). */
static int screen_divisor(const char *name) {
    static const struct { const char *name; int div; } sides[] = {
        { "screen", 1 }, { "screen_half", 2 }, { "screen_quarter", 4 },
    };
    for (size_t i = 0; i < sizeof sides / sizeof sides[0]; i++)
        if (strcmp(name, sides[i].name) == 0) return sides[i].div;
    return 0;
}

/* A count the scene fixes (a target's side, points per side) at the
 * frame's detail: at least 16, so a pass still has something to draw. */
#define DETAIL_MIN_COUNT 16

int render_size_detail_count(const render *r, int n) { return world_detail_count(n, r->detail, DETAIL_MIN_COUNT); }

/* A target drawn every frame from the view's camera keeps this many times
 * the frame's detail a side (up to the scene's own size). Such a target
 * (natural's refraction and reflection) reaches the screen through
 * widened, wave-perturbed lookups, already coarser than the screen at full
 * size (512 a side behind 960x540); shrunk with the frame its texels
 * became most of a reduced frame's error. In the window on the lake
 * (scripts/live_error.sh, natural, 2026-12-06; docs/benchmark.md, "Targets
 * seen from the view") 2x cut the frame's RMSE by 8% at the same frame
 * rate, FLIP within the runs' spread (the budget draws a smaller frame to
 * pay for them); 4x cost more of the size than it gained; targets drawn
 * from the light (photons, caustics) doubled too made the frame smaller
 * for no gain. */
#define VIEW_TARGET_DETAIL 2.0

static int target_detail_count(const render *r, int n, bool from_view) {
    double d = from_view ? fmin(1.0, VIEW_TARGET_DETAIL * r->detail) : r->detail;
    return world_detail_count(n, d, DETAIL_MIN_COUNT);
}

/* Is command c a RenderToTexture (of every frame) into unit? */
static bool pass_draws_unit(const glib_cmd *c, int unit) {
    if (c->kind != GLIB_CMD_RENDER_TO_TEXTURE) return false;
    for (int k = 0; k < c->nnum; k++)
        if ((int)c->num[k] == unit) return true;
    return false;
}

/* Is texture unit drawn into by a RenderToTexture of every frame? Only
 * those cost every frame; one a RenderToTextureOnce fills (raymarch's
 * top-down views, a lookup table) is drawn once a load, and shrinking it
 * would draw it again at each change of detail, and worse. Asked once a
 * load (scene_state.per_frame). */
bool render_size_drawn_every_frame(const glib_scene *g, int unit) {
    for (int i = 0; i < g->ncmds; i++)
        if (pass_draws_unit(&g->cmds[i], unit)) return true;
    return false;
}

/* Is unit drawn every frame by a pass that sets the view's camera (`Camera
 * main`, `wide` or `mirror`: what it holds lies on the screen's own
 * pixels, more or less)? A pass from the light or the top, a full-screen
 * quad, or one that sets no camera (glman's files: tarn cannot tell what
 * they draw) is not. */
bool render_size_drawn_from_view(const glib_scene *g, int unit) {
    for (int i = 0; i < g->ncmds; i++) {
        if (!pass_draws_unit(&g->cmds[i], unit)) continue;
        for (int j = i + 1; j < g->ncmds; j++) {
            const glib_cmd *c = &g->cmds[j];
            if (c->kind == GLIB_CMD_RENDER_TO_TEXTURE || c->kind == GLIB_CMD_RENDER_TO_TEXTURE_ONCE) break;
            if (c->kind == GLIB_CMD_CAMERA &&
                (!strcmp(c->name, "main") || !strcmp(c->name, "wide") || !strcmp(c->name, "mirror")))
                return true;
        }
    }
    return false;
}

static int target_side(const render *r, const char *name, int screen, int max, bool per_frame, bool from_view) {
    int div = screen_divisor(name);
    if (!div) {
        int n = render_size_slider_count(&r->cur, name, max);
        return per_frame ? target_detail_count(r, n, from_view) : n;
    }
    int n = (screen + div - 1) / div;   /* the frame's size is already the reduced one */
    return n < 1 ? 1 : n > max ? max : n;
}

/* Render targets whose size a slider (or the frame) gives follow it, and
 * those drawn every frame the frame's detail; a resized target loses its
 * contents, so the RenderToTextureOnce blocks that fill it draw again. */
void render_size_targets(render *r, int screen_w, int screen_h) {
    scene_state *s = &r->cur;
    if (!r->max_target) {   /* asked once: the context's limit does not change */
        GLint max = 0;
        glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max);
        /* a slider dragged to an absurd end must not ask for gigabytes: 8192
         * a side is 1 GiB in RGBA32F, the most a target may take this way */
        r->max_target = max < 1 || max > NAMED_SIZE_MAX ? NAMED_SIZE_MAX : max;
    }
    int max = r->max_target;
    for (int i = 0; i < s->glib->ncmds; i++) {
        const glib_cmd *c = &s->glib->cmds[i];
        if (c->kind != GLIB_CMD_TEXTURE2D_EMPTY || s->cmd_res[i] < 0) continue;
        /* a world-only frame draws only the screen-sized passes: the others keep their size */
        if (r->world_only && !(screen_divisor(c->name) && screen_divisor(c->arg))) continue;
        gpu_tex *t = &s->texs[s->cmd_res[i]];
        bool per_frame = s->per_frame[i], from_view = s->from_view[i];
        int w = c->name[0] ? target_side(r, c->name, screen_w, max, per_frame, from_view) : (int)c->num[1];
        int h = c->arg[0] ? target_side(r, c->arg, screen_h, max, per_frame, from_view) : (int)c->num[2];
        if (per_frame && !c->name[0]) w = target_detail_count(r, w, from_view);
        if (per_frame && !c->arg[0]) h = target_detail_count(r, h, from_view);
        if (w == t->w && h == t->h) continue;
        render_res_target_resize(t, w, h);
        render_once_redraw_unit(s, (int)c->num[0]);
        r->nkept_once = 0;   /* its pixels are gone */
    }
}

/* Names in sizes and point counts that no Program has: said once a load. */
void render_size_check_names(const scene_state *s, diag_list *log) {
    for (int i = 0; i < s->glib->ncmds; i++) {
        const glib_cmd *c = &s->glib->cmds[i];
        const char *names[2] = { NULL, NULL };
        if (c->kind == GLIB_CMD_TEXTURE2D_EMPTY) { names[0] = c->name; names[1] = c->arg; }
        if (c->kind == GLIB_CMD_WATER_SURFACE) names[0] = c->arg;
        for (int k = 0; k < 2; k++) {
            float v;
            if (!names[k] || !names[k][0] || (k == 1 && strcmp(names[1], names[0]) == 0)) continue;
            if (c->kind == GLIB_CMD_TEXTURE2D_EMPTY && screen_divisor(names[k])) continue;
            if (!program_value(s, names[k], &v))
                diag_add(log, DIAG_WARNING, c->file, c->line, "%s: no Program of this glib has a uniform '%s' to give "
                         "the size; using %d (add it as a slider, e.g. %s <64 512 2048>)",
                         glib_cmd_name(c->kind), names[k], NAMED_SIZE_FALLBACK, names[k]);
        }
    }
}

/* Whether texture unit is a render target the size of the screen (or a
 * half or quarter of it): a pass into it draws the frame's own view. */
bool render_size_screen_unit(const scene_state *s, int unit) {
    for (int i = 0; i < s->glib->ncmds; i++) {
        const glib_cmd *c = &s->glib->cmds[i];
        if (c->kind == GLIB_CMD_TEXTURE2D_EMPTY && (int)c->num[0] == unit)
            return screen_divisor(c->name) && screen_divisor(c->arg);
    }
    return false;
}
