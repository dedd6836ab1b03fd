/* render_once: RenderToTextureOnce blocks across a reload. A block is
 * drawn on the first frame after a load (glman's rule), except when the
 * reload changed nothing it draws from (its signature): its targets still
 * hold its pixels (render.h, render_once_reused). */
#include "util.h"
#include "render_internal.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <string.h>

#include "mem.h"

/* The RenderToTextureOnce blocks that draw into unit (a target that lost
 * its pixels) draw again, and those after them; the others keep theirs
 * (a per-frame target resized with the frame's detail must not redraw a
 * light's depth). */
void render_once_redraw_unit(scene_state *s, int unit) {
    bool after = false;   /* a block after one that draws again may read what it draws */
    for (int i = 0; i < s->glib->ncmds; i++) {
        const glib_cmd *c = &s->glib->cmds[i];
        if (c->kind != GLIB_CMD_RENDER_TO_TEXTURE_ONCE) continue;
        for (int k = 0; k < c->nnum; k++) after = after || (int)c->num[k] == unit;
        if (after) s->once_done[i] = false;
    }
}

/* The signatures of the RenderToTextureOnce blocks the scene drew, for
 * the first frame of the next one (render_once_kept). */
void render_once_keep(render *r, const scene_state *s) {
    r->nkept_once = 0;
    if (!s->glib) return;
    r->kept_once = mem_realloc(r->kept_once, (size_t)(s->glib->ncmds > 0 ? s->glib->ncmds : 1) * sizeof *r->kept_once);
    for (int i = 0; i < s->glib->ncmds; i++)
        if (s->once_done[i] && s->once_sig[i]) r->kept_once[r->nkept_once++] = s->once_sig[i];
}

static uint64_t sig_str(uint64_t h, const char *str) { return hash_fnv1a(h, str, strlen(str) + 1); }

/* A program's source and slider values; and the time, when it reads the
 * clock (glman's Timer, or uTime): such a block shows the time of the
 * load, so a reload draws it again. */
static uint64_t sig_prog(uint64_t h, const prog *p, double t) {
    if (!p) return hash_fnv1a(h, "-", 1);
    h = hash_fnv1a(h, &p->hash, sizeof p->hash);
    if (p->gl && (glGetUniformLocation(p->gl, "Timer") >= 0 || glGetUniformLocation(p->gl, "uTime") >= 0))
        h = hash_fnv1a(h, &t, sizeof t);
    for (int k = 0; p->unifs && k < p->unifs->n; k++) {
        const unif_entry *e = &p->unifs->entries[k];
        h = sig_str(h, e->name);
        h = hash_fnv1a(h, e->value, sizeof e->value);
    }
    return h;
}

/* Everything a RenderToTextureOnce block at command i draws from: its
 * commands and the programs they use (their source and slider values),
 * the program it starts with, every texture of the scene (object and
 * size: a target resized, or an image reloaded, is another object or
 * size), the world (its description and programs; a block draws it at
 * full detail) and the cameras it draws with (the one the frame had
 * loaded, unless the block names its own first). The time only where a
 * program of the block reads it: the world's own shading near the
 * waterline moves with the waves, and a kept block keeps it as the load
 * that drew it saw it. */
uint64_t render_once_signature(const render *r, const frame_state *f, int i) {
    const scene_state *s = &r->cur;
    uint64_t h = HASH_FNV1A_BASIS;
    bool own_camera = false;
    for (int k = i; k < s->glib->ncmds; k++) {
        const glib_cmd *c = &s->glib->cmds[k];
        if (k > i && (c->kind == GLIB_CMD_RENDER_TO_TEXTURE || c->kind == GLIB_CMD_RENDER_TO_TEXTURE_ONCE)) break;
        h = hash_fnv1a(h, &c->kind, sizeof c->kind);
        h = hash_fnv1a(h, c->num, (size_t)c->nnum * sizeof c->num[0]);
        h = sig_str(sig_str(sig_str(h, c->name), c->arg), c->path);
        if (c->kind == GLIB_CMD_PROGRAM && s->cmd_res[k] >= 0) h = sig_prog(h, &s->progs[s->cmd_res[k]], f->t);
        if (c->kind == GLIB_CMD_CAMERA) {
            int kind = render_camera_kind_from_name(c->name);
            own_camera = own_camera || k == i + 1;
            if (kind >= 0) {
                h = hash_fnv1a(h, f->cams.view[kind], sizeof f->cams.view[kind]);
                h = hash_fnv1a(h, f->cams.proj[kind], sizeof f->cams.proj[kind]);
            }
        }
    }
    if (!own_camera) {   /* the camera the frame had loaded */
        h = hash_fnv1a(h, f->cams.view[f->cam_kind], sizeof f->cams.view[f->cam_kind]);
        h = hash_fnv1a(h, f->cams.proj[f->cam_kind], sizeof f->cams.proj[f->cam_kind]);
    }
    h = hash_fnv1a(h, &f->depth, sizeof f->depth);   /* inside a PushMatrix: conservatively, another block */
    h = sig_prog(h, f->cur, f->t);
    for (int k = 0; k < s->ntexs; k++) {
        const gpu_tex *t = &s->texs[k];
        int v[4] = { (int)t->tex, t->unit, t->w, t->h };
        h = hash_fnv1a(h, v, sizeof v);
    }
    if (r->world.active) {
        h = hash_fnv1a(h, &r->world.desc, sizeof r->world.desc);
        for (int m = 0; m < WORLD_MODES; m++) h = hash_fnv1a(h, &r->world.progs[m].hash, sizeof r->world.progs[m].hash);
    }
    return h ? h : 1;
}

/* A block the scene before the reload drew with this signature: its
 * targets hold its pixels. Only while no block has been drawn this frame
 * (a later block may read what an earlier one drew). */
bool render_once_kept(render *r, const frame_state *f, uint64_t sig) {
    if (f->once_drawn) return false;
    for (int k = 0; k < r->nkept_once; k++)
        if (r->kept_once[k] == sig) {
            r->once_reused++;
            return true;
        }
    return false;
}

long render_once_reused(const render *r) { return r->once_reused; }
