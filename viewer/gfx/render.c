#include "util.h"
#include "render.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <cglm/cglm.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geom.h"
#include "glib.h"
#include "gpu_timer.h"
#include "mem.h"
#include "program.h"
#include "render_camera.h"
#include "render_msaa.h"
#include "render_prog.h"
#include "render_res.h"
#include "render_world.h"
#include "world_cache.h"
#include "world_layers.h"
#include "world_snapshot.h"
#include "scene.h"
#include "mem.h"
#include "strbuf.h"

#define MATRIX_STACK_MAX 30   /* GL guarantees 32 modelview entries */

/* What a glib says about viewing and time (the last command of each wins);
 * the viewing commands are read by the scene layer (scene_camera_from_glib),
 * the one reader the reference uses too. */
typedef struct scene_settings {
    scene_camera cam;
    double timer_s;
    float background[4];
    render_view view;        /* cam's LookAt, as the renderer takes it */
} scene_settings;

/* Everything built from one parse of the glib. */
typedef struct scene_state {
    glib_scene *glib;
    int *cmd_res;            /* per command: index into meshes/texs/progs, or -1 */
    gpu_mesh *meshes;
    int nmeshes;
    gpu_tex *texs;
    int ntexs;
    prog *progs;
    unif_set *unifs;         /* progs[i].unifs == &unifs[i] */
    bool *once_done;         /* per command: a RenderToTextureOnce block already drawn */
    uint64_t *once_sig;      /* per command: what a drawn block drew (once_signature) */
    bool *per_frame;         /* per Texture2D target: a RenderToTexture draws it every frame */
    bool *draw_warned;       /* per command: a problem drawing it was reported */
    bool flat_checked;       /* the first frame was looked at for a one-colour picture */
    bool samples_noise[2];   /* a program samples unit 2 / 3: glman's noise is built (note_noise_units) */
    int nprogs;
    scene_settings set;
} scene_state;

struct render {
    char root[GLIB_PATH_MAX];
    char packs_dir[GLIB_PATH_MAX + 16];
    char pack[GLIB_NAME_MAX];      /* --pack: replaces the scene's Pack */
    int water_mesh;                /* a setting's WaterMesh (0: the scene's own) */
    int water_mesh_loaded;         /* the one the world on screen was built with */
    gpu_world world;               /* kept across reloads while the world is unchanged */
    world_cache wcache;            /* World commands drawn after a Clear, kept while their key stays */
    world_layers wlayers;          /* ... and their layers, while only the time changes */
    world_snapshot snap;           /* the screen right before its water (render_set_world_snapshot) */
    bool world_only;               /* inside render_frame_world_at */
    char common_dir[GLIB_PATH_MAX + 16];
    const char *include_dirs[1];
    char path[GLIB_PATH_MAX];
    scene_state cur;
    char *messages;
    char *draw_messages;        /* problems met drawing (also in messages), since the load */
    diag_list diags;            /* the messages' diagnostics */
    bool errors;
    const char **deps;
    int ndeps;
    unsigned rtt_fbo, rtt_depth;
    int rtt_w, rtt_h;
    int samples;               /* MSAA requested (render_desc.samples) */
    /* Ask GL for errors after every command, to name the one at fault:
     * in the first frame after a load and after a frame that had an
     * error. Otherwise once a frame: glGetError can stall a GPU's
     * command stream, and the answer is almost always "none". */
    bool gl_check_each;
    bool draw_timing;          /* render_set_draw_timing: an interval per drawing command */
    render_msaa msaa;          /* the screen passes' multisampled target */
    int max_target;            /* the largest side a slider may give a target (0: not asked yet) */
    double detail;             /* render_set_detail: 1 (0 before the first call) everything as the scene says */
    /* The RenderToTextureOnce blocks the scene before a reload drew, by
     * their signature: the first frame after the reload skips a block whose
     * signature is here, its targets holding its pixels already. */
    uint64_t *kept_once;
    int nkept_once;
    long once_reused;          /* blocks so kept since render_create */
    gpu_timer timer;           /* per frame and per pass */
    gpu_tex noise[2];          /* glman's built-in Noise2 / Noise3, bound once a program samples them */
    char noise_dir[GLIB_PATH_MAX];  /* the project folder they were read for */
    bool verbose;              /* render_desc.verbose */
    bool no_spray;             /* render_desc.no_spray */
};

render *render_create(const render_desc *desc) {
    render *r = mem_zalloc(sizeof *r);
    snprintf(r->root, sizeof r->root, "%s", desc && desc->repo_root ? desc->repo_root : tarn_root());
    snprintf(r->common_dir, sizeof r->common_dir, "%s/packs/common", r->root);
    r->include_dirs[0] = r->common_dir;
    snprintf(r->packs_dir, sizeof r->packs_dir, "%s/packs", r->root);
    if (desc && desc->pack) snprintf(r->pack, sizeof r->pack, "%s", desc->pack);
    r->samples = desc ? desc->samples : 0;
    r->verbose = desc && desc->verbose;
    r->no_spray = desc && desc->no_spray;
    gpu_timer_init(&r->timer);
    world_cache_init(&r->wcache);
    world_layers_init(&r->wlayers);
    return r;
}

render_desc render_desc_of(const render *r) {
    return (render_desc){ .repo_root = r->root, .pack = r->pack[0] ? r->pack : NULL, .samples = r->samples,
                          .verbose = r->verbose, .no_spray = r->no_spray };
}

static void scene_free(scene_state *s) {
    for (int i = 0; i < s->nmeshes; i++) render_res_mesh_free(&s->meshes[i]);
    for (int i = 0; i < s->ntexs; i++) render_res_tex_free(&s->texs[i]);
    for (int i = 0; i < s->nprogs; i++) prog_free(&s->progs[i]);
    free(s->meshes);
    free(s->texs);
    free(s->progs);
    free(s->unifs);
    free(s->once_done);
    free(s->once_sig);
    free(s->per_frame);
    free(s->draw_warned);
    free(s->cmd_res);
    if (s->glib) glib_free(s->glib);
    memset(s, 0, sizeof *s);
}

static void free_deps(render *r) {
    for (int i = 0; i < r->ndeps; i++) free((char *)r->deps[i]);
    free(r->deps);
    r->deps = NULL;
    r->ndeps = 0;
}

void render_destroy(render *r) {
    if (!r) return;
    scene_free(&r->cur);
    world_free(&r->world);
    world_cache_free(&r->wcache);
    world_layers_free(&r->wlayers);
    world_snapshot_free(&r->snap);
    free_deps(r);
    free(r->messages);
    free(r->draw_messages);
    free(r->kept_once);
    diag_list_free(&r->diags);
    if (r->rtt_fbo) glDeleteFramebuffers(1, &r->rtt_fbo);
    if (r->rtt_depth) glDeleteRenderbuffers(1, &r->rtt_depth);
    render_msaa_free(&r->msaa);
    gpu_timer_free(&r->timer);
    render_res_tex_free(&r->noise[0]);
    render_res_tex_free(&r->noise[1]);
    free(r);
}

/* ---- settings ---- */

static render_view view_of(const scene_camera *cam) {
    render_view v;
    for (int k = 0; k < 3; k++) {
        v.eye[k] = (float)cam->eye[k];
        v.center[k] = (float)cam->center[k];
        v.up[k] = (float)cam->up[k];
    }
    return v;
}

static void settings_default(scene_settings *s) {
    memset(s, 0, sizeof *s);
    scene_camera_from_glib(NULL, &s->cam);
    s->timer_s = 10.0;
    s->background[3] = 1.0f;
    s->view = view_of(&s->cam);
}

static void settings_from_glib(scene_settings *s, const glib_scene *g) {
    settings_default(s);
    scene_camera_from_glib(g, &s->cam);
    s->view = view_of(&s->cam);
    bool have_background = false;
    for (int i = 0; i < g->ncmds; i++) {
        const glib_cmd *c = &g->cmds[i];
        switch (c->kind) {
        case GLIB_CMD_TIMER:
            if (c->nnum >= 1 && c->num[0] > 0) s->timer_s = c->num[0];
            break;
        case GLIB_CMD_BACKGROUND:   /* the first Background is the screen's clear colour */
            if (!have_background && c->nnum >= 3) {
                for (int k = 0; k < 4; k++) s->background[k] = k < c->nnum ? (float)c->num[k] : 1.0f;
                have_background = true;
            }
            break;
        default: break;
        }
    }
}

/* ---- loading ---- */

static void diags_to_log(const glib_scene *g, char **log) {
    for (int i = 0; i < g->ndiags; i++) {
        char line[DIAG_FILE_MAX + DIAG_TEXT_MAX + 32];
        diag_format(&g->diags[i], line, sizeof line);
        str_appendf(log, "%s\n", line);
    }
}

static int steal_mesh(scene_state *old, const char *key) {
    for (int i = 0; i < old->nmeshes; i++)
        if (old->meshes[i].vbo && strcmp(old->meshes[i].key, key) == 0) return i;
    return -1;
}

static void build_mesh(scene_state *s, scene_state *old, const glib_cmd *c, int ci, char **log) {
    gpu_mesh *m = &s->meshes[s->nmeshes];
    memset(m, 0, sizeof *m);
    render_res_key(c, m->key, sizeof m->key);
    int o = steal_mesh(old, m->key);
    if (o >= 0) {
        *m = old->meshes[o];
        memset(&old->meshes[o], 0, sizeof old->meshes[o]);
    } else if (!render_res_mesh_build(c, m, log) && c->path[0]) {
        /* a broken OBJ keeps the last good mesh of that file (as textures do) */
        for (int i = 0; i < old->nmeshes; i++) {
            const char *a = old->meshes[i].key, *at = strrchr(a, '@'), *bt = strrchr(m->key, '@');
            if (!old->meshes[i].vbo || !at || !bt || at - a != bt - m->key || memcmp(a, m->key, (size_t)(at - a)) != 0)
                continue;   /* the key without its file stamp: same command, same file */
            *m = old->meshes[i];   /* with its own key: the next reload retries the file */
            memset(&old->meshes[i], 0, sizeof old->meshes[i]);
            str_appendf(log, "%s:%d: note: keeping the last good mesh of '%s'\n", c->file, c->line, c->path);
            break;
        }
    }
    s->cmd_res[ci] = s->nmeshes++;
}

/* Equal key: reuse. A texture that fails keeps the last good one of that file. */
static void build_tex(scene_state *s, scene_state *old, const glib_cmd *c, int ci, char **log) {
    gpu_tex *t = &s->texs[s->ntexs];
    memset(t, 0, sizeof *t);
    render_res_key(c, t->key, sizeof t->key);
    for (int i = 0; i < old->ntexs; i++) {
        if (old->texs[i].tex && strcmp(old->texs[i].key, t->key) == 0) {
            *t = old->texs[i];
            memset(&old->texs[i], 0, sizeof old->texs[i]);
            s->cmd_res[ci] = s->ntexs++;
            return;
        }
    }
    char key[RES_KEY_MAX];
    memcpy(key, t->key, sizeof key);
    if (!render_res_tex_build(c, t, log)) {
        const char *want = c->kind == GLIB_CMD_CUBEMAP && c->cube_paths ? c->cube_paths[0] : c->path;
        for (int i = 0; i < old->ntexs; i++) {
            if (old->texs[i].tex && want[0] && strcmp(old->texs[i].path, want) == 0) {
                *t = old->texs[i];
                memset(&old->texs[i], 0, sizeof old->texs[i]);
                str_appendf(log, "%s:%d: note: keeping the last good image of '%s'\n", c->file, c->line, want);
                break;
            }
        }
        /* a glib edit that names another file, which fails: keep what that unit showed */
        int unit = t->unit;
        unsigned target = t->target;
        for (int i = 0; !t->tex && i < old->ntexs; i++) {
            const gpu_tex *o = &old->texs[i];
            if (!o->tex || o->render_target || o->unit != unit || o->target != target) continue;
            str_appendf(log, "%s:%d: note: keeping the last good image of unit %d ('%s')\n", c->file, c->line,
                        unit, o->path);
            *t = old->texs[i];
            memset(&old->texs[i], 0, sizeof old->texs[i]);
        }
        if (!t->tex) return;
        /* the kept image keeps its own key: the next reload tries the broken
         * file again and reports it until it is fixed */
        s->cmd_res[ci] = s->ntexs++;
        return;
    }
    memcpy(t->key, key, sizeof key);
    s->cmd_res[ci] = s->ntexs++;
}

static prog *find_old_prog(scene_state *old, const char *name) {
    for (int i = 0; i < old->nprogs; i++)
        if (!old->progs[i].cmd && strcmp(old->progs[i].name, name) == 0) return &old->progs[i];
    return NULL;
}

static void build_prog(render *r, scene_state *s, scene_state *old, const glib_cmd *c,
                       const program_stages *st, int ci, char **log) {
    prog *p = &s->progs[s->nprogs];
    memset(p, 0, sizeof *p);
    p->unifs = &s->unifs[s->nprogs];
    snprintf(p->name, sizeof p->name, "%s", c->name);
    p->cmd = c;
    p->gstap = st->gstap;
    p->world_uniforms = r->world.active;
    world_set_wave_defines(&r->world, p);   /* only the wave models the world has */
    if (r->world.active && r->world.has_above_water) {   /* `If above_water` as a define: a pack
                                                           * compiles out what only it needs */
        shader_define *d = &p->fixed[PROG_FIXED_MAX - 1];   /* the wave defines use at most 7 */
        snprintf(d->name, sizeof d->name, "WORLD_ABOVE_WATER");
        snprintf(d->value, sizeof d->value, "1");
    }
    p->scene = s->glib;
    for (int k = 0; k < SHADER_STAGE_COUNT; k++)
        snprintf(p->stage_path[k], sizeof p->stage_path[k], "%s", program_stage_path(st, (shader_stage)k));
    char err[512] = "";
    if (!glib_unif_set(p->unifs, c, err, sizeof err)) str_appendf(log, "%s\n", err);
    snprintf(p->unifs->program, sizeof p->unifs->program, "%s", c->name);
    prog *o = find_old_prog(old, p->name);
    if (o) {   /* the last good build and the user's values (defines first) */
        p->gl = o->gl;
        p->hash = o->hash;
        p->good = o->good;
        p->source = o->source;   /* the kept build's text: says declared-but-inactive from undeclared */
        o->source = NULL;
        o->gl = 0;
        o->cmd = c;   /* marks it taken */
        unif_merge(p->unifs, o->unifs);
    }
    prog_build(p, (const char *const *)r->include_dirs, 1, log);
    prog_introspect(p, log);
    if (o) unif_merge(p->unifs, o->unifs);   /* now both carry shader types */
    s->cmd_res[ci] = s->nprogs++;
}

/* If/EndIf must pair up; an unmatched one is reported and the renderer
 * treats a missing EndIf as the end of the scene. */
static void check_if_nesting(const glib_scene *g, char **log) {
    int depth = 0;
    const glib_cmd *open_if = NULL;
    for (int i = 0; i < g->ncmds; i++) {
        const glib_cmd *c = &g->cmds[i];
        if (c->kind == GLIB_CMD_IF) { if (depth++ == 0) open_if = c; }
        else if (c->kind == GLIB_CMD_END_IF && --depth < 0) {
            str_appendf(log, "%s:%d: error: EndIf without an If\n", c->file, c->line);
            depth = 0;
        }
    }
    if (depth > 0 && open_if)
        str_appendf(log, "%s:%d: error: If without an EndIf (the block runs to the end)\n", open_if->file, open_if->line);
}

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
static int slider_count(const scene_state *s, const char *name, int max) {
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

static int detail_count(const render *r, int n) { return world_detail_count(n, r->detail, DETAIL_MIN_COUNT); }

/* Is texture unit drawn into by a RenderToTexture of every frame? Only
 * those cost every frame; one a RenderToTextureOnce fills (raymarch's
 * top-down views, a lookup table) is drawn once a load, and shrinking it
 * would draw it again at each change of detail, and worse. Asked once a
 * load (scene_state.per_frame). */
static bool drawn_every_frame(const glib_scene *g, int unit) {
    for (int i = 0; i < g->ncmds; i++) {
        const glib_cmd *c = &g->cmds[i];
        if (c->kind != GLIB_CMD_RENDER_TO_TEXTURE) continue;
        for (int k = 0; k < c->nnum; k++)
            if ((int)c->num[k] == unit) return true;
    }
    return false;
}

static int target_side(const render *r, const char *name, int screen, int max, bool per_frame) {
    int div = screen_divisor(name);
    if (!div) {
        int n = slider_count(&r->cur, name, max);
        return per_frame ? detail_count(r, n) : n;
    }
    int n = (screen + div - 1) / div;   /* the frame's size is already the reduced one */
    return n < 1 ? 1 : n > max ? max : n;
}

/* The RenderToTextureOnce blocks that draw into unit (a target that lost
 * its pixels) draw again, and those after them; the others keep theirs
 * (a per-frame target resized with the frame's detail must not redraw a
 * light's depth). */
static void once_redraw_unit(scene_state *s, int unit) {
    bool after = false;   /* a block after one that draws again may read what it draws */
    for (int i = 0; i < s->glib->ncmds; i++) {
        const glib_cmd *c = &s->glib->cmds[i];
        if (c->kind != GLIB_CMD_RENDER_TO_TEXTURE_ONCE) continue;
        for (int k = 0; k < c->nnum; k++) after = after || (int)c->num[k] == unit;
        if (after) s->once_done[i] = false;
    }
}

/* Render targets whose size a slider (or the frame) gives follow it, and
 * those drawn every frame the frame's detail; a resized target loses its
 * contents, so the RenderToTextureOnce blocks that fill it draw again. */
static void size_targets(render *r, int screen_w, int screen_h) {
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
        bool per_frame = s->per_frame[i];
        int w = c->name[0] ? target_side(r, c->name, screen_w, max, per_frame) : (int)c->num[1];
        int h = c->arg[0] ? target_side(r, c->arg, screen_h, max, per_frame) : (int)c->num[2];
        if (per_frame && !c->name[0]) w = detail_count(r, w);
        if (per_frame && !c->arg[0]) h = detail_count(r, h);
        if (w == t->w && h == t->h) continue;
        render_res_target_resize(t, w, h);
        once_redraw_unit(s, (int)c->num[0]);
        r->nkept_once = 0;   /* its pixels are gone */
    }
}

/* Names in sizes and point counts that no Program has: said once a load. */
static void check_named_counts(const scene_state *s, char **log) {
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
                str_appendf(log, "%s:%d: warning: %s: no Program of this glib has a uniform '%s' to give "
                            "the size; using %d (add it as a slider, e.g. %s <64 512 2048>)\n",
                            c->file, c->line, glib_cmd_name(c->kind), names[k], NAMED_SIZE_FALLBACK, names[k]);
        }
    }
}

static geom_prim begin_prim(const char *mode) {
    static const struct { const char *name; geom_prim prim; } modes[] = {
        { "gl_points", GEOM_POINTS }, { "gl_lines", GEOM_LINES }, { "gl_line_strip", GEOM_LINE_STRIP },
        { "gl_line_loop", GEOM_LINE_LOOP }, { "gl_triangles", GEOM_TRIANGLES },
        { "gl_triangle_strip", GEOM_TRIANGLE_STRIP }, { "gl_triangle_fan", GEOM_TRIANGLE_FAN },
        { "gl_quads", GEOM_QUADS }, { "gl_lines_adjacency", GEOM_LINES_ADJACENCY },
        { "gl_triangles_adjacency", GEOM_TRIANGLES_ADJACENCY }, { "gl_patches", GEOM_PATCHES },
    };
    for (size_t i = 0; i < sizeof modes / sizeof modes[0]; i++)
        if (strcmp(mode, modes[i].name) == 0) return modes[i].prim;
    return GEOM_POINTS;
}

/* glBegin MODE, glVertex ..., glEnd: one mesh of the vertices up to the
 * glEnd (the parser pairs them), drawn where the glBegin stands. Built on
 * every load: a handful of vertices. */
static void build_begin(scene_state *s, int ci, char **log) {
    const glib_scene *g = s->glib;
    int n = 0;
    for (int k = ci + 1; k < g->ncmds && g->cmds[k].kind != GLIB_CMD_GL_END; k++) n += g->cmds[k].kind == GLIB_CMD_GL_VERTEX;
    if (n == 0) return;
    float *xyz = mem_alloc(sizeof *xyz * 3 * (size_t)n);
    n = 0;
    for (int k = ci + 1; k < g->ncmds && g->cmds[k].kind != GLIB_CMD_GL_END; k++) {
        if (g->cmds[k].kind != GLIB_CMD_GL_VERTEX) continue;
        for (int c = 0; c < 3; c++) xyz[3 * n + c] = (float)g->cmds[k].num[c];
        n++;
    }
    gpu_mesh *m = &s->meshes[s->nmeshes];
    memset(m, 0, sizeof *m);
    geom_mesh gm;
    if (geom_points(&gm, xyz, n, begin_prim(g->cmds[ci].name)) && render_res_mesh_upload(&gm, m))
        s->cmd_res[ci] = s->nmeshes++;
    else
        str_appendf(log, "%s:%d: error: glBegin: cannot build its %d vertices\n", g->cmds[ci].file, g->cmds[ci].line, n);
    geom_free(&gm);
    free(xyz);
}

/* --verbose: each inactive uniform a note at its own glib line. */
static void note_each_inactive(const scene_state *s, char **log) {
    for (int i = 0; i < s->nprogs; i++) {
        int n = prog_inactive_uniforms(&s->progs[i], NULL, 0);
        if (n <= 0) continue;
        const unif_entry **found = mem_alloc((size_t)n * sizeof *found);
        n = prog_inactive_uniforms(&s->progs[i], found, n);
        for (int k = 0; k < n; k++)
            str_appendf(log, "%s:%d: note: uniform '%s' is declared in program '%s' but inactive as built\n",
                        found[k]->glib_file ? found[k]->glib_file : "?", found[k]->glib_line, found[k]->name,
                        s->progs[i].name);
        free(found);
    }
}

/* The glib's uniforms that shaders declare but do not use, in one line a
 * load (issue #30: a line each buried the real messages): the same words
 * at start-up and on every reload. */
#define INACTIVE_NAMED 8
static void note_inactive_uniforms(const scene_state *s, bool verbose, char **log) {
    int total = 0, shown = 0;
    char *list = NULL;
    const unif_entry *first = NULL;
    for (int i = 0; i < s->nprogs; i++) {
        const unif_entry *found[INACTIVE_NAMED];
        int n = prog_inactive_uniforms(&s->progs[i], found, INACTIVE_NAMED);
        for (int k = 0; k < n && k < INACTIVE_NAMED && shown < INACTIVE_NAMED; k++, shown++) {
            str_appendf(&list, "%s%s (%s)", shown ? ", " : "", found[k]->name, s->progs[i].name);
            if (!first) first = found[k];
        }
        total += n;
    }
    if (total > 0)   /* at the first one's glib line: an editor jumps there */
        str_appendf(log, "%s:%d: note: %d uniform%s of the glib %s declared but inactive as built "
                    "(compiled out by a Define, or unused): %s%s\n",
                    first && first->glib_file ? first->glib_file : "?", first ? first->glib_line : 0, total,
                    total == 1 ? "" : "s", total == 1 ? "is" : "are", list,
                    total > shown ? verbose ? ", ... (each below)" : ", ... (--verbose lists each)" : "");
    free(list);
    if (verbose) note_each_inactive(s, log);
}

/* Which of glman's noise units the programs sample (a sampler in the
 * shader set to 2 or 3, Noise2 and Noise3 by name), known once the
 * programs are introspected: the 64^3 texture costs ~250 ms of CPU a
 * load, which a scene that never reads it (every pack's) need not pay. */
static void note_noise_units(scene_state *s) {
    s->samples_noise[0] = s->samples_noise[1] = false;
    for (int i = 0; i < s->nprogs; i++) {
        const unif_set *u = s->progs[i].unifs;
        for (int k = 0; u && k < u->n; k++) {
            const unif_entry *e = &u->entries[k];
            int unit = (int)e->value[0];
            if (e->type == UNIF_SAMPLER && e->in_shader && (unit == 2 || unit == 3)) s->samples_noise[unit - 2] = true;
        }
    }
}

static bool build_scene(render *r, scene_state *s, scene_state *old, char **log) {
    int n = s->glib->ncmds;
    s->cmd_res = mem_alloc((size_t)(n > 0 ? n : 1) * sizeof *s->cmd_res);
    s->meshes = mem_zalloc((size_t)(n > 0 ? n : 1) * sizeof *s->meshes);
    s->texs = mem_zalloc((size_t)(n > 0 ? n : 1) * sizeof *s->texs);
    s->progs = mem_zalloc((size_t)(n > 0 ? n : 1) * sizeof *s->progs);
    s->unifs = mem_zalloc((size_t)(n > 0 ? n : 1) * sizeof *s->unifs);
    s->once_done = mem_zalloc((size_t)(n > 0 ? n : 1) * sizeof *s->once_done);
    s->once_sig = mem_zalloc((size_t)(n > 0 ? n : 1) * sizeof *s->once_sig);
    s->per_frame = mem_zalloc((size_t)(n > 0 ? n : 1) * sizeof *s->per_frame);
    s->draw_warned = mem_zalloc((size_t)(n > 0 ? n : 1) * sizeof *s->draw_warned);
    /* old programs are matched by name; clear the "taken" marks */
    for (int i = 0; i < old->nprogs; i++) old->progs[i].cmd = NULL;
    program_stages st;
    program_stages_init(&st);
    for (int i = 0; i < n; i++) {
        const glib_cmd *c = &s->glib->cmds[i];
        s->cmd_res[i] = -1;
        if (render_res_is_geometry(c->kind)) build_mesh(s, old, c, i, log);
        else if (c->kind == GLIB_CMD_GL_BEGIN) build_begin(s, i, log);
        else if (render_res_is_texture(c->kind)) build_tex(s, old, c, i, log);
        if (c->kind == GLIB_CMD_TEXTURE2D_EMPTY) s->per_frame[i] = drawn_every_frame(s->glib, (int)c->num[0]);
        else if (c->kind == GLIB_CMD_PROGRAM) build_prog(r, s, old, c, &st, i, log);
        else program_stages_step(&st, c);
    }
    settings_from_glib(&s->set, s->glib);
    note_noise_units(s);
    note_inactive_uniforms(s, r->verbose, log);
    check_if_nesting(s->glib, log);
    check_named_counts(s, log);
    return true;
}

static void add_dep(render *r, const char *path) {
    if (!path || !path[0]) return;
    for (int i = 0; i < r->ndeps; i++)
        if (strcmp(r->deps[i], path) == 0) return;
    r->deps = mem_realloc(r->deps, (size_t)(r->ndeps + 1) * sizeof *r->deps);
    r->deps[r->ndeps++] = mem_strdup(path);
}

static void collect_deps(render *r, const glib_scene *g, const scene_state *s) {
    free_deps(r);
    add_dep(r, r->path);
    if (g)
        for (int i = 0; i < g->nfiles; i++) add_dep(r, g->files[i]);
    if (g)
        for (int i = 0; i < g->ncmds; i++) {
            const glib_cmd *c = &g->cmds[i];
            if (c->kind == GLIB_CMD_CUBEMAP && c->cube_paths)
                for (int f = 0; f < 6; f++) add_dep(r, c->cube_paths[f]);
            else if (render_res_is_geometry(c->kind) || render_res_is_texture(c->kind))
                add_dep(r, c->path);
        }
    for (int i = 0; i < s->nprogs; i++)
        for (int k = 0; k < s->progs[i].ndeps; k++) add_dep(r, s->progs[i].deps[k]);
    if (r->world.active) {
        for (int k = 0; k < r->world.progs[0].ndeps; k++) add_dep(r, r->world.progs[0].deps[k]);
        for (int i = 0; i < OCEAN_PROGS; i++)   /* the ocean's passes (none without an ocean) */
            for (int k = 0; k < r->world.ocean.progs[i].ndeps; k++) add_dep(r, r->world.ocean.progs[i].deps[k]);
        for (int k = 0; k < r->world.flow.prog.ndeps; k++) add_dep(r, r->world.flow.prog.deps[k]);   /* none without a Flow */
        for (int i = 0; i < SPRAY_PROGS; i++)   /* the spray's (none without a Spray) */
            for (int k = 0; k < r->world.spray.progs[i].ndeps; k++) add_dep(r, r->world.spray.progs[i].deps[k]);
    }
}

/* The signatures of the RenderToTextureOnce blocks the scene drew, for
 * the first frame of the next one (exec_once). */
static void keep_once_blocks(render *r, const scene_state *s) {
    r->nkept_once = 0;
    if (!s->glib) return;
    r->kept_once = mem_realloc(r->kept_once, (size_t)(s->glib->ncmds > 0 ? s->glib->ncmds : 1) * sizeof *r->kept_once);
    for (int i = 0; i < s->glib->ncmds; i++)
        if (s->once_done[i] && s->once_sig[i]) r->kept_once[r->nkept_once++] = s->once_sig[i];
}

/* The world the scene describes (if any), rebuilt only when it changed. */
static void build_world(render *r, const glib_scene *g, char **log) {
    ref_world_desc desc;
    scene_camera cam;
    bool has_world = false;
    char err[1024] = "";
    if (!scene_from_glib(g, &desc, &cam, &has_world, err, sizeof err)) str_appendf(log, "%s\n", err);
    if (has_world && r->water_mesh > 0) desc.water_mesh_res = r->water_mesh;
    r->water_mesh_loaded = r->water_mesh;
    if (r->no_spray) desc.spray.on = false;   /* no state, no pass: as a scene without Spray */
    if (has_world) world_build(&r->world, &desc, (const char *const *)r->include_dirs, r->common_dir, log);
    else world_free(&r->world);
}

/* One message line and the programs whose build reported it. */
typedef struct msg_line {
    char *text;
    char stage[32];
    strbuf progs;            /* "'Water', 'Sky'" */
    int nprogs;
    bool mixed_stages;
} msg_line;

static void msg_line_add_prog(msg_line *m, const char *stage, const char *pname) {
    char quoted[GLIB_NAME_MAX + 4];
    snprintf(quoted, sizeof quoted, "'%s'", pname);
    if (m->nprogs == 0) snprintf(m->stage, sizeof m->stage, "%s", stage);
    else if (strcmp(m->stage, stage) != 0) m->mixed_stages = true;
    if (m->progs.s && strstr(m->progs.s, quoted)) return;
    if (m->nprogs++ > 0) strbuf_puts(&m->progs, ", ");
    strbuf_puts(&m->progs, quoted);
}

static void msg_line_print(strbuf *out, const msg_line *m) {
    strbuf_puts(out, m->text);
    if (m->nprogs > 0 && m->mixed_stages) strbuf_printf(out, " (programs %s)", m->progs.s);
    else if (m->nprogs > 0)
        strbuf_printf(out, " (%s shader of program%s %s)", m->stage, m->nprogs > 1 ? "s" : "", m->progs.s);
    strbuf_puts(out, "\n");
}

/* The log's lines, each once: a line that several programs report (an
 * error in a file they all include) names them all; a tagged line
 * (RENDER_PROG_TAG) names its stage and program. */
static char *merge_lines(const char *log) {
    msg_line *lines = NULL;
    int n = 0;
    for (const char *s = log; s && *s;) {
        const char *e = strchr(s, '\n');
        size_t len = e ? (size_t)(e - s) : strlen(s);
        char *line = mem_strndup(s, len);
        s += len + (e ? 1 : 0);
        char *stage = strchr(line, RENDER_PROG_TAG), *pname = stage ? strchr(stage + 1, RENDER_PROG_TAG) : NULL;
        if (stage) *stage++ = '\0';
        if (pname) *pname++ = '\0';
        int i = 0;
        while (i < n && strcmp(lines[i].text, line) != 0) i++;
        if (i == n) {
            lines = mem_realloc(lines, (size_t)(n + 1) * sizeof *lines);
            memset(&lines[n], 0, sizeof lines[n]);
            lines[n++].text = line;
        }
        if (stage && pname) msg_line_add_prog(&lines[i], stage, pname);   /* (they point into line) */
        if (lines[i].text != line) free(line);
    }
    strbuf out = { 0 };
    for (int i = 0; i < n; i++) {
        msg_line_print(&out, &lines[i]);
        free(lines[i].text);
        strbuf_free(&lines[i].progs);
    }
    free(lines);
    return out.s;
}

/* The latest load's messages: each line once (an error in a file that
 * several programs include is reported by each), and their diagnostics,
 * from which errors are told apart from warnings. */
static void set_messages(render *r, char *log) {
    char *merged = merge_lines(log);
    free(log);
    free(r->messages);
    r->messages = merged;
    free(r->draw_messages);   /* problems drawing are found afresh */
    r->draw_messages = NULL;
    if (r->cur.draw_warned && r->cur.glib)
        memset(r->cur.draw_warned, 0, (size_t)r->cur.glib->ncmds * sizeof *r->cur.draw_warned);
    diag_list_free(&r->diags);
    diag_add_text(&r->diags, DIAG_NOTE, r->messages);
}

bool render_load(render *r, const char *glib_path) {
    if (glib_path && glib_path != r->path) snprintf(r->path, sizeof r->path, "%s", glib_path);
    char *log = NULL;
    glib_options opts = { .packs_dir = r->packs_dir, .pack_override = r->pack[0] ? r->pack : NULL };
    glib_scene *g = glib_load_opts(r->path, &opts);
    diags_to_log(g, &log);
    if (g->nerrors > 0 && r->cur.glib) {
        /* a half-written glib: keep everything that is on screen */
        str_appendf(&log, "%s: the scene has errors; keeping the last good scene\n", r->path);
        collect_deps(r, g, &r->cur);
        glib_free(g);
        set_messages(r, log);
        r->errors = true;
        return false;
    }
    build_world(r, g, &log);
    world_cache_free(&r->wcache);   /* the world, its program or the commands may differ */
    world_layers_free(&r->wlayers);
    scene_state fresh;
    memset(&fresh, 0, sizeof fresh);
    fresh.glib = g;
    build_scene(r, &fresh, &r->cur, &log);
    keep_once_blocks(r, &r->cur);
    scene_free(&r->cur);
    r->cur = fresh;
    collect_deps(r, g, &r->cur);
    set_messages(r, log);
    r->errors = g->nerrors > 0 || r->diags.nerrors > 0;
    r->gl_check_each = true;
    return !r->errors;
}

bool render_rebuild_programs(render *r) {
    char *log = NULL;
    bool ok = true;
    for (int i = 0; i < r->cur.nprogs; i++) {
        prog *p = &r->cur.progs[i];
        if (!prog_build(p, (const char *const *)r->include_dirs, 1, &log)) ok = false;
        prog_introspect(p, &log);
    }
    note_noise_units(&r->cur);
    world_cache_free(&r->wcache);   /* the world's program may draw differently now */
    world_layers_free(&r->wlayers);
    if (r->world.active) {
        if (!world_build_programs(&r->world, (const char *const *)r->include_dirs, &log)) ok = false;
    }
    collect_deps(r, r->cur.glib, &r->cur);
    set_messages(r, log);
    r->errors = !ok;
    r->gl_check_each = true;
    return ok;
}

const char *render_messages(const render *r) { return r->messages ? r->messages : ""; }
const char *render_draw_messages(const render *r) { return r->draw_messages ? r->draw_messages : ""; }
const diag_list *render_diags(const render *r) { return &r->diags; }
bool render_has_errors(const render *r) { return r->errors; }
bool render_has_scene(const render *r) { return r->cur.glib != NULL; }
bool render_has_world(const render *r) { return r->world.active; }

bool render_set_world_override(render *r, const char *command, const float *v, int n) {
    if (strcmp(command, "WaterMesh") != 0 || n != 1 || !isfinite(v[0])) return false;
    double m = v[0] < 8 ? 8 : v[0] > 2048 ? 2048 : v[0];   /* scene.c's MESH_RES_MIN..MAX */
    r->water_mesh = (int)m;
    return true;
}

void render_clear_world_overrides(render *r) { r->water_mesh = 0; }

bool render_world_overrides_pending(const render *r) { return r->water_mesh != r->water_mesh_loaded; }

void render_set_pack(render *r, const char *pack) {
    snprintf(r->pack, sizeof r->pack, "%s", pack ? pack : "");
}

const char *render_pack(const render *r) {
    const glib_scene *g = r->cur.glib;
    for (int i = g ? g->ncmds - 1 : -1; i >= 0; i--)
        if (g->cmds[i].kind == GLIB_CMD_PACK) return g->cmds[i].name;
    return "";
}
const char *render_scene_path(const render *r) { return r->path; }


int render_deps(const render *r, const char *const **paths) {
    *paths = (const char *const *)r->deps;
    return r->ndeps;
}

unif_set *render_uniforms(render *r, int *nsets) {
    *nsets = r->cur.nprogs;
    return r->cur.unifs;
}

void render_window_size(const render *r, int *w, int *h) {
    const scene_settings *s = &r->cur.set;
    scene_camera def;
    scene_camera_from_glib(NULL, &def);
    *w = r->cur.glib ? s->cam.width : def.width;
    *h = r->cur.glib ? s->cam.height : def.height;
}

render_view render_default_view(const render *r) {
    if (r->cur.glib) return r->cur.set.view;
    scene_settings s;
    settings_default(&s);
    return s.view;
}

/* ---- drawing ---- */

/* glman's Noise2 and Noise3 are there for every shader without any
 * command: built once per project folder (whose cached .tex files win),
 * bound to units 2 and 3 before the scene's own textures, so a Noise2D or
 * a Texture2D on those units still takes over. Each is built at the first
 * frame after a load that has a program sampling its unit
 * (note_noise_units). */
static void bind_builtin_noise(render *r, const scene_state *s) {
    char dir[GLIB_PATH_MAX];
    const char *top = s->glib && s->glib->nfiles ? s->glib->files[0] : "";
    const char *slash = strrchr(top, '/');
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - top) : 0, top);
    if (strcmp(dir, r->noise_dir) != 0) {   /* another project: its own .tex files */
        render_res_tex_free(&r->noise[0]);
        render_res_tex_free(&r->noise[1]);
        snprintf(r->noise_dir, sizeof r->noise_dir, "%s", dir);
    }
    for (int k = 0; k < 2; k++) {
        if (!r->noise[k].tex && s->samples_noise[k]) render_res_noise_builtin(dir, k == 1, &r->noise[k]);
        if (!r->noise[k].tex) continue;
        glActiveTexture(GL_TEXTURE0 + (GLenum)r->noise[k].unit);
        glBindTexture(r->noise[k].target, r->noise[k].tex);
    }
    glActiveTexture(GL_TEXTURE0);
}

static void bind_tex(const gpu_tex *t) {
    if (!t->tex) return;
    glActiveTexture(GL_TEXTURE0 + (GLenum)t->unit);
    glBindTexture(t->target, t->tex);
    glActiveTexture(GL_TEXTURE0);
}

/* Every texture at the frame's start (the last at a unit wins), so a draw
 * before the texture's command sees what glman's previous frame left. */
static void bind_textures(const scene_state *s) {
    for (int i = 0; i < s->ntexs; i++) bind_tex(&s->texs[i]);
}

/* The number a `Camera` (fov scale) or `World` (clip offset) command asks
 * for: the one written, else the current value of the named float uniform
 * of the Program before it, else def. */
static float cmd_number(const scene_state *s, int ci, float def) {
    const glib_cmd *c = &s->glib->cmds[ci];
    if (c->nnum > 0) return (float)c->num[0];
    if (!c->arg[0]) return def;
    for (int i = ci - 1; i >= 0; i--) {
        if (s->glib->cmds[i].kind != GLIB_CMD_PROGRAM || s->cmd_res[i] < 0) continue;
        unif_entry *e = unif_find(s->progs[s->cmd_res[i]].unifs, c->arg);
        return e && isfinite(e->value[0]) ? e->value[0] : def;
    }
    return def;
}

static float camera_scale(const scene_state *s, int ci) {
    float v = cmd_number(s, ci, 1.0f);
    return v > 0 ? v : 1.0f;
}

static void camera_inputs(const render *r, const render_view *v, int w, int h, cam_inputs *out) {
    const scene_state *s = &r->cur;
    const scene_settings *set = &s->set;
    const scene_camera *sc = &set->cam;
    cam_inputs in = { .view = *v, .fov_deg = sc->fov_deg, .near_z = sc->near_z, .far_z = sc->far_z,
                      .ortho = sc->ortho, .aspect = h > 0 ? (float)w / (float)h : 1.0f,
                      .level = 0, .half_size = 12, .depth = 3, .sun_dir = { 0, 1, 0 } };
    memcpy(in.ortho_lrbt, sc->ortho_lrbt, sizeof in.ortho_lrbt);
    for (int k = 0; k < CAM_COUNT; k++) in.fov_scale[k] = 1.0f;
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
        int k = c->kind == GLIB_CMD_CAMERA ? cam_kind_from_name(c->name) : -1;
        if (k >= 0) in.fov_scale[k] = camera_scale(s, i);
    }
    *out = in;
}

/* RenderToTexture u1 u2 ...: colour units become attachments 0..n-1, a
 * depth-format unit the depth attachment (else a private depth buffer). */
static void begin_rtt(render *r, const glib_cmd *c) {
    const scene_state *s = &r->cur;
    if (!r->rtt_fbo) glGenFramebuffers(1, &r->rtt_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, r->rtt_fbo);
    GLenum bufs[GLIB_MAX_UNITS];
    int nbufs = 0, w = 0, h = 0;
    bool have_depth = false;
    for (int a = 0; a < 8; a++)
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + (GLenum)a, GL_TEXTURE_2D, 0, 0);
    for (int k = 0; k < c->nnum && k < GLIB_MAX_UNITS; k++) {
        int unit = (int)c->num[k];
        const gpu_tex *t = NULL;
        for (int i = 0; i < s->ntexs; i++)
            if (s->texs[i].tex && s->texs[i].render_target && s->texs[i].unit == unit) t = &s->texs[i];
        if (!t) continue;
        w = t->w;
        h = t->h;
        if (t->format == GLIB_TARGET_DEPTH) {
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, t->tex, 0);
            have_depth = true;
        } else {
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + (GLenum)nbufs, GL_TEXTURE_2D, t->tex, 0);
            bufs[nbufs] = GL_COLOR_ATTACHMENT0 + (GLenum)nbufs;
            nbufs++;
        }
    }
    if (!have_depth && w > 0) {
        if (!r->rtt_depth) glGenRenderbuffers(1, &r->rtt_depth);
        if (r->rtt_w != w || r->rtt_h != h) {
            glBindRenderbuffer(GL_RENDERBUFFER, r->rtt_depth);
            glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
            r->rtt_w = w;
            r->rtt_h = h;
        }
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, r->rtt_depth);
    }
    if (nbufs) glDrawBuffers(nbufs, bufs);
    else glDrawBuffer(GL_NONE);
    if (w > 0) glViewport(0, 0, w, h);
}

typedef struct frame_state {
    unsigned screen_fbo;
    int x, y, w, h;
    bool in_rtt;
    bool skipping;           /* inside a RenderToTextureOnce block already drawn */
    cam_inputs cam_in;
    float cam_eye[3];        /* the current camera's eye (the mirror's is reflected): the sky box's centre */
    int if_depth, if_false;  /* If blocks: nesting, and how deep the first false one is (0: none) */
    cam_set cams;
    int depth;
    const prog *cur;
    double t;
    float eye[3];
    int patch_vertices;      /* NumPatchVertices: the size of the patches drawn next */
    int patch_cmd;           /* the NumPatchVertices command that set it, or -1 */
    int cam_kind;            /* the camera loaded last (cam_kind) */
    /* The static-world cache: the current target holds only what a Clear
     * to clean_rgba left (nothing drawn since); the screen's own state
     * while a pass draws into a texture. */
    bool clean, screen_clean;
    float clean_rgba[4], screen_rgba[4];
    bool check_each;         /* render.gl_check_each for this frame */
    bool once_drawn;         /* a RenderToTextureOnce block was drawn this frame */
    bool in_once;            /* drawing one: at full detail, whatever the frame's (it is kept) */
    bool replaying;          /* in one a reload kept: its commands run, but none that writes pixels */
    bool water_reached;      /* the first WaterSurface on the screen has come (water_on_screen) */
} frame_state;

static void mark_pass(render *r, const glib_cmd *c) {
    char name[GPU_TIMER_NAME];
    int n = snprintf(name, sizeof name, "%s:%d", c->nnum ? "pass" : "screen", c->line);
    for (int k = 0; k < c->nnum && n < (int)sizeof name - 4; k++) n += snprintf(name + n, sizeof name - (size_t)n, " %d", (int)c->num[k]);
    gpu_timer_mark(&r->timer, name);
}

static bool writes_pixels(glib_cmd_kind k);
static void mark_now(render *r, const char *name);

/* render_set_draw_timing: an interval of its own for each drawing command */
static void mark_draw(render *r, const glib_cmd *c) {
    if (!writes_pixels(c->kind) || c->kind == GLIB_CMD_CLEAR) return;
    char name[GPU_TIMER_NAME];
    snprintf(name, sizeof name, "%s:%d", glib_cmd_name(c->kind), c->line);
    mark_now(r, name);
}

/* A mark that times what was drawn before it: a CPU rasteriser (llvmpipe)
 * bins draws and rasterises them at a later flush, and resolves a
 * timestamp query there too, so without the finishes a draw's pixels fell
 * in a later draw's interval (the water's under the World before it). */
static void mark_now(render *r, const char *name) {
    glFinish();
    gpu_timer_mark(&r->timer, name);
    glFinish();
}

void render_set_draw_timing(render *r, bool on) { r->draw_timing = on; }

static void end_rtt(frame_state *f) {
    glBindFramebuffer(GL_FRAMEBUFFER, f->screen_fbo);
    glViewport(f->x, f->y, f->w, f->h);
    if (f->in_rtt) {   /* back from a pass: the screen as the pass found it */
        f->clean = f->screen_clean;
        memcpy(f->clean_rgba, f->screen_rgba, sizeof f->clean_rgba);
    }
    f->in_rtt = false;
}

/* A pass begins: the screen's state is kept; the texture holds whatever
 * it held until a Clear. */
static void leave_target(frame_state *f) {
    if (!f->in_rtt) {
        f->screen_clean = f->clean;
        memcpy(f->screen_rgba, f->clean_rgba, sizeof f->screen_rgba);
    }
    f->clean = false;
}

/* Command c, about to run: a Clear leaves the current target clean, a draw
 * does not (World: draw_world, which looks first); other commands leave it. */
static void track_clean(frame_state *f, const glib_cmd *c) {
    if (c->kind == GLIB_CMD_CLEAR) {
        f->clean = true;
        glGetFloatv(GL_COLOR_CLEAR_VALUE, f->clean_rgba);
    } else if (render_res_is_geometry(c->kind) || c->kind == GLIB_CMD_GL_BEGIN || c->kind == GLIB_CMD_WATER_SURFACE ||
               c->kind == GLIB_CMD_SPLAT) {
        f->clean = false;
    }
}

static bool writes_pixels(glib_cmd_kind k) {
    return k == GLIB_CMD_CLEAR || render_res_is_geometry(k) || k == GLIB_CMD_GL_BEGIN || k == GLIB_CMD_WATER_SURFACE ||
           k == GLIB_CMD_SPLAT || k == GLIB_CMD_WORLD;
}

static const gpu_tex *tex_at_unit(const scene_state *s, int unit) {
    const gpu_tex *t = NULL;
    for (int i = 0; i < s->ntexs; i++)   /* the last one declared at a unit wins, as bound */
        if (s->texs[i].tex && s->texs[i].unit == unit) t = &s->texs[i];
    return t;
}

/* Adds every photon's energy bilinearly into the w x h grid over the world
 * square |x|, |z| <= hs (texel (i, j) centred at x = -hs + (i + 0.5) 2hs / w,
 * row j likewise in z), as irradiance: energy over the texel's area. */
static void splat_photons(const float *photons, long n, float *grid, int w, int h, double hs) {
    double cw = 2 * hs / w, ch = 2 * hs / h, inv_area = 1.0 / (cw * ch);
    for (long p = 0; p < n; p++) {
        const float *ph = photons + p * 4;
        if (!(ph[3] > 0) || !isfinite(ph[0]) || !isfinite(ph[1]) || !isfinite(ph[2])) continue;
        double gx = (ph[0] + hs) / cw - 0.5, gy = (ph[1] + hs) / ch - 0.5;
        int i0 = (int)floor(gx), j0 = (int)floor(gy);
        double fx = gx - i0, fy = gy - j0;
        for (int dj = 0; dj < 2; dj++)
            for (int di = 0; di < 2; di++) {
                int i = i0 + di, j = j0 + dj;
                if (i < 0 || j < 0 || i >= w || j >= h) continue;
                double wgt = (di ? fx : 1 - fx) * (dj ? fy : 1 - fy);
                float *g = grid + ((size_t)j * w + i) * 4;
                float e = (float)(ph[2] * wgt * inv_area);
                g[0] += e;
                g[1] += e;
                g[2] += e;
                g[3] = 1.0f;
            }
    }
}

/* `Splat SRC DST`: the paper's CPU caustics. Each texel of SRC is a photon
 * (R, G: world x, z of its floor hit; B: energy; A > 0: valid); DST gets the
 * irradiance they make over the world square and is uploaded. */
static void splat(const render *r, int src_unit, int dst_unit) {
    const scene_state *s = &r->cur;
    const gpu_tex *src = tex_at_unit(s, src_unit), *dst = tex_at_unit(s, dst_unit);
    if (!src || !dst || src->target != GL_TEXTURE_2D || dst->target != GL_TEXTURE_2D) return;
    float *in = mem_alloc((size_t)src->w * src->h * 4 * sizeof(float));
    float *out = mem_zalloc((size_t)dst->w * dst->h * 4 * sizeof(float));
    glBindTexture(GL_TEXTURE_2D, src->tex);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, in);
    double hs = r->world.active ? r->world.w.d.half_size : 12.0;
    splat_photons(in, (long)src->w * src->h, out, dst->w, dst->h, hs);
    glBindTexture(GL_TEXTURE_2D, dst->tex);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, dst->w, dst->h, GL_RGBA, GL_FLOAT, out);
    glBindTexture(GL_TEXTURE_2D, 0);
    free(in);
    free(out);
}

static void exec_state_cmd(const glib_cmd *c) {
    switch (c->kind) {
    case GLIB_CMD_COLOR:
        glColor4f((float)c->num[0], (float)c->num[1], (float)c->num[2], c->nnum > 3 ? (float)c->num[3] : 1.0f);
        break;
    case GLIB_CMD_CLEAR: glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT); break;
    case GLIB_CMD_BACKGROUND:
        glClearColor((float)c->num[0], (float)c->num[1], (float)c->num[2], c->nnum > 3 ? (float)c->num[3] : 1.0f);
        break;
    case GLIB_CMD_CULL:
        if (strcmp(c->name, "none") == 0) glDisable(GL_CULL_FACE);
        else { glEnable(GL_CULL_FACE); glCullFace(strcmp(c->name, "front") == 0 ? GL_FRONT : GL_BACK); }
        break;
    case GLIB_CMD_DEPTH_TEST:
        if (c->nnum > 0 && c->num[0] == 0) glDisable(GL_DEPTH_TEST); else glEnable(GL_DEPTH_TEST);
        break;
    /* glman's state commands apply to the draws that follow */
    case GLIB_CMD_FLAT: glShadeModel(GL_FLAT); break;
    case GLIB_CMD_SMOOTH: glShadeModel(GL_SMOOTH); break;
    case GLIB_CMD_LINE_WIDTH: glLineWidth((float)c->num[0]); break;
    case GLIB_CMD_POINT_SIZE: glPointSize((float)c->num[0]); break;
    case GLIB_CMD_POINT_SIZE_MODE:
        if (c->num[0] != 0) glEnable(GL_PROGRAM_POINT_SIZE); else glDisable(GL_PROGRAM_POINT_SIZE);
        break;
    case GLIB_CMD_BLEND:
        if (strcmp(c->name, "off") == 0) { glDisable(GL_BLEND); break; }
        glEnable(GL_BLEND);
        if (strcmp(c->name, "add") == 0) glBlendFunc(GL_ONE, GL_ONE);
        else if (strcmp(c->name, "premultiplied") == 0) glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        else glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        break;
    default: break;
    }
}

static void exec_transform(frame_state *f, const glib_cmd *c) {
    switch (c->kind) {
    case GLIB_CMD_TRANSLATE: glTranslatef((float)c->num[0], (float)c->num[1], (float)c->num[2]); break;
    case GLIB_CMD_ROTATE: glRotatef((float)c->num[0], (float)c->num[1], (float)c->num[2], (float)c->num[3]); break;
    case GLIB_CMD_SCALE:
        if (c->nnum >= 3) glScalef((float)c->num[0], (float)c->num[1], (float)c->num[2]);
        else glScalef((float)c->num[0], (float)c->num[0], (float)c->num[0]);
        break;
    case GLIB_CMD_PUSH_MATRIX:   /* deeper pushes are ignored rather than overflowing GL's stack */
        if (f->depth < MATRIX_STACK_MAX) glPushMatrix();
        f->depth++;
        break;
    case GLIB_CMD_POP_MATRIX:
        if (f->depth > 0 && f->depth <= MATRIX_STACK_MAX) glPopMatrix();
        if (f->depth > 0) f->depth--;
        break;
    default: break;
    }
}

/* `If NAME`: a Define toggle of any Program that is on, or a scene fact. */
static bool condition(const render *r, const frame_state *f, const char *name) {
    if (strcmp(name, "above_water") == 0) return r->world.active && r->world.has_above_water;
    if (strcmp(name, "waves") == 0) {   /* any wave model with an active wave: the WAVES_HAS_* set */
        const ref_waves *w = &r->world.w.waves;
        return r->world.active &&
               (w->nsine || w->ngerstner || w->noctaves || w->ocean || w->nexplosions || w->has_perlin);
    }
    if (strcmp(name, "under_water") == 0)
        return r->world.active && f->eye[1] < r->world.w.d.water_level;
    for (int p = 0; p < r->cur.nprogs; p++) {
        const unif_entry *e = unif_find(r->cur.progs[p].unifs, name);
        if (e && e->is_define) return e->value[0] != 0;
    }
    return false;
}

/* Handles If/EndIf; true when command c is inside a false block. */
static bool skipped_by_if(const render *r, frame_state *f, const glib_cmd *c) {
    if (c->kind == GLIB_CMD_IF) {
        f->if_depth++;
        if (!f->if_false && condition(r, f, c->name) == (c->nnum > 0 && c->num[0] == 1)) f->if_false = f->if_depth;
        return true;
    }
    if (c->kind == GLIB_CMD_END_IF) {
        if (f->if_depth > 0 && f->if_false == f->if_depth) f->if_false = 0;
        if (f->if_depth > 0) f->if_depth--;
        return true;
    }
    return f->if_false != 0;
}

/* uTargetSize (contract): the size in texels of what the current program
 * draws into, the viewport's; set when a program is bound and when a pass
 * begins or ends. */
static void upload_target_size(const frame_state *f) {
    if (!f->cur || !f->cur->gl) return;
    GLint loc = glGetUniformLocation(f->cur->gl, "uTargetSize");
    if (loc < 0) return;
    GLint vp[4];
    glGetIntegerv(GL_VIEWPORT, vp);
    glUniform2f(loc, (float)vp[2], (float)vp[3]);
}

/* `WaterSurface points N` / `mesh N`: N x N points, or the triangles
 * between them; uPointGrid (contract) tells the current program the N it
 * is drawn with. */
static void draw_points(render *r, const frame_state *f, const glib_cmd *c) {
    /* at the frame's detail, as a target sized by the same slider is: a
     * pass of one photon per texel and the splat of those photons agree */
    int n = c->arg[0] ? slider_count(&r->cur, c->arg, 4096) : (int)c->num[0];
    if (!f->in_once) n = detail_count(r, n);
    if (f->cur && f->cur->gl) {
        GLint loc = glGetUniformLocation(f->cur->gl, "uPointGrid");
        if (loc >= 0) glUniform1f(loc, (float)n);
    }
    world_draw_points(&r->world, n, strcmp(c->name, "mesh") == 0);
}

/* A problem met drawing command ci: said once a load, with its glib line,
 * in the messages (and the draw messages, for `tarn render`). */
__attribute__((format(printf, 4, 5)))
static void draw_problem(render *r, int ci, bool error, const char *fmt, ...) {
    scene_state *s = &r->cur;
    if (s->draw_warned[ci]) return;
    s->draw_warned[ci] = true;
    const glib_cmd *c = &s->glib->cmds[ci];
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    char *line = NULL;
    str_appendf(&line, "%s:%d: %s: %s\n", c->file, c->line, error ? "error" : "warning", msg);
    str_appendf(&r->draw_messages, "%s", line);
    str_appendf(&r->messages, "%s", line);
    diag_add_text(&r->diags, DIAG_NOTE, line);
    free(line);
    if (error) r->errors = true;
}

static const char *gl_error_name(GLenum e) {
    switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    default: return "an unknown GL error";
    }
}

/* What a geometry shader's input layout is called, and a command drawing it. */
static const char *gs_input_word(unsigned in, const char **draw_with) {
    switch (in) {
    case GL_POINTS: *draw_with = "PointCloud or glBegin gl_points"; return "points";
    case GL_LINES: *draw_with = "a Wire command (WireSphere, WireObj, ...)"; return "lines";
    case GL_LINES_ADJACENCY: *draw_with = "LinesAdjacency"; return "lines_adjacency";
    case GL_TRIANGLES_ADJACENCY: *draw_with = "ObjAdj"; return "triangles_adjacency";
    default: *draw_with = "a solid (Sphere, Obj, QuadXY, ...)"; return "triangles";
    }
}

/* After command ci: a GL error it caused is reported (once) with its line
 * and what to do, and cleared, so the rest of the frame draws and the
 * picture can be read back. m, d: the mesh it drew, or NULL. */
static void check_gl(render *r, const frame_state *f, int ci, const gpu_mesh *m, const render_res_draw *d) {
    GLenum e = glGetError();
    if (e == GL_NO_ERROR) return;
    for (int k = 0; k < 16 && glGetError() != GL_NO_ERROR; k++) {}
    const glib_cmd *c = &r->cur.glib->cmds[ci];
    const char *name = glib_cmd_name(c->kind);
    if (!m) {
        draw_problem(r, ci, true, "%s: OpenGL failed here (%s); the rest of the scene is drawn", name, gl_error_name(e));
        return;
    }
    const char *prim = render_res_mesh_prim_name(m, d), *with = "";
    const prog *p = f->cur;
    if (p && p->gl && p->gs_input && !p->tess) {
        const char *want = gs_input_word(p->gs_input, &with);
        draw_problem(r, ci, true, "%s drew nothing (%s): it draws %s but program '%s' has a geometry shader "
                     "that takes %s (layout(%s) in); draw %s with it, or change the shader's layout; the rest "
                     "of the scene is drawn", name, gl_error_name(e), prim, p->name, want, want, with);
        return;
    }
    draw_problem(r, ci, true, "%s drew nothing (%s) as %s with program '%s': check that the program's stages "
                 "fit what is drawn (a geometry shader's layout, tessellation stages); the rest of the scene is drawn",
                 name, gl_error_name(e), prim, p ? p->name : "(none)");
}

/* A mesh of command ci, drawn for the current program. */
static void draw_mesh(render *r, const frame_state *f, int ci, const gpu_mesh *m) {
    const prog *p = f->cur && f->cur->gl ? f->cur : NULL;
    render_res_draw d = { .tangent_loc = p ? p->tangent_loc : -1, .face_index_loc = p ? p->face_index_loc : -1,
                   .face_index_int = p && p->face_index_int, .tess = p && p->tess,
                   .patch_vertices = f->patch_vertices };
    char why[512];
    if (m->prim == GEOM_PATCHES && m->patch_size > 0 && f->patch_cmd >= 0 && m->patch_size != f->patch_vertices)
        draw_problem(r, ci, false, "ObjPatch draws patches of its faces' %d corners; NumPatchVertices %d "
                     "(line %d) is for glBegin gl_patches and not used here", m->patch_size,
                     f->patch_vertices, r->cur.glib->cmds[f->patch_cmd].line);
    bool drawn = render_res_mesh_draw_with(m, &d, why, sizeof why);
    if (why[0])
        draw_problem(r, ci, !drawn, "%s %s%s", glib_cmd_name(r->cur.glib->cmds[ci].kind),
                     drawn ? "" : "drew nothing: ", why);
    if (f->check_each) check_gl(r, f, ci, m, &d);
}

/* `World`: drawn, or, right after a Clear, copied from the static-world
 * cache when nothing it depends on has changed (world_cache.h). */
/* A World whose key has stayed while the time ran is drawn from its layers
 * (world_layers.h): built once, then one full-screen pass a frame. */
static bool draw_world_layers(render *r, frame_state *f, int i, const world_cache_key *k, const char *which, float offset) {
    world_layers_use use = world_layers_check(&r->wlayers, i, k);
    if (use == WORLD_LAYERS_NO) return false;
    unsigned restore = f->cur ? f->cur->gl : 0;
    if (use == WORLD_LAYERS_BUILD) {
        if (!world_layers_begin_build(&r->wlayers, i, k)) return false;
        world_draw_layers(&r->world, which, offset, f->cam_eye, !f->in_rtt, restore);
        world_layers_end_build(&r->wlayers, i, k);
    }
    const unsigned *tex = world_layers_textures(&r->wlayers, i);
    if (!tex) return false;
    GLint vp[4];
    glGetIntegerv(GL_VIEWPORT, vp);
    world_composite_layers(&r->world, f->t, f->cam_eye, tex, vp[0], vp[1], restore);
    r->wlayers.composites++;
    return true;
}

/* The World command i through the caches: copied from the last frame, or
 * composed from its layers, or drawn (and kept for the next frame). */
static void draw_world_cached(render *r, frame_state *f, int i, const char *which, float offset) {
    world_cache_key k;
    world_cache_key_init(&k);
    k.t = f->t;
    memcpy(k.eye, f->cam_eye, sizeof k.eye);
    k.offset = offset;
    k.which = strcmp(which, "above") == 0 ? 1 : strcmp(which, "below") == 0 ? 2 : 0;
    k.to_screen = !f->in_rtt;
    k.lod = r->world.lod;
    memcpy(k.clear_rgba, f->clean_rgba, sizeof k.clear_rgba);
    bool cacheable = f->clean && r->world.active && !r->wcache.off &&
                     world_cache_key_gl(&k, WORLD_UNIT_ALBEDO, WORLD_UNIT_SKY);
    f->clean = false;
    if (cacheable && world_cache_restore(&r->wcache, i, &k)) return;
    if (cacheable && draw_world_layers(r, f, i, &k, which, offset)) {
        world_cache_store(&r->wcache, i, &k);   /* a still frame after it copies, as after a draw */
        return;
    }
    world_draw(&r->world, which, offset, f->t, f->cam_eye, !f->in_rtt, f->cur ? f->cur->gl : 0);
    if (!cacheable) return;
    check_gl(r, f, i, NULL, NULL);   /* the world's own errors, reported before the copy looks */
    world_cache_store(&r->wcache, i, &k);
}

static void draw_world(render *r, frame_state *f, int i) {
    const scene_state *s = &r->cur;
    const glib_cmd *c = &s->glib->cmds[i];
    const char *which = c->name[0] ? c->name : "all";
    float offset = cmd_number(s, i, 0.0f);
    if (r->world_only) {
        /* a frame of its own size and time: the caches keep the window's frames' */
        f->clean = false;
        world_draw(&r->world, which, offset, f->t, f->cam_eye, !f->in_rtt, f->cur ? f->cur->gl : 0);
        return;
    }
    draw_world_cached(r, f, i, which, offset);
}

/* ---- RenderToTextureOnce across a reload ---- */


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
static uint64_t once_signature(const render *r, const frame_state *f, int i) {
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
            int kind = cam_kind_from_name(c->name);
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
static bool once_kept(render *r, const frame_state *f, uint64_t sig) {
    if (f->once_drawn) return false;
    for (int k = 0; k < r->nkept_once; k++)
        if (r->kept_once[k] == sig) {
            r->once_reused++;
            return true;
        }
    return false;
}

/* Whether texture unit is a render target the size of the screen (or a
 * half or quarter of it): a pass into it draws the frame's own view. */
static bool screen_sized_unit(const scene_state *s, int unit) {
    for (int i = 0; i < s->glib->ncmds; i++) {
        const glib_cmd *c = &s->glib->cmds[i];
        if (c->kind == GLIB_CMD_TEXTURE2D_EMPTY && (int)c->num[0] == unit)
            return screen_divisor(c->name) && screen_divisor(c->arg);
    }
    return false;
}

/* Which passes a world-only frame draws: those into screen-sized targets
 * (caustic_tex draws its World into one and copies it to the screen);
 * not a RenderToTextureOnce block (kept for the real frames), nor a pass
 * of the water's own (a light's view, a mirror, photons). */
static bool world_only_pass(const scene_state *s, const glib_cmd *c) {
    if (c->kind != GLIB_CMD_RENDER_TO_TEXTURE || c->nnum == 0) return false;
    for (int k = 0; k < c->nnum; k++)
        if (!screen_sized_unit(s, (int)c->num[k])) return false;
    return true;
}

/* The screen as the scene left it before its water (the sharp world's
 * snapshot), and what a world-only frame stops at. */
static bool water_on_screen(const frame_state *f, const glib_cmd *c) {
    return c->kind == GLIB_CMD_WATER_SURFACE && !f->in_rtt;
}

static void exec_cmd(render *r, frame_state *f, int i) {
    scene_state *s = &r->cur;
    const glib_cmd *c = &s->glib->cmds[i];
    int res = s->cmd_res[i];
    if (r->world_only && f->water_reached) return;
    if (skipped_by_if(r, f, c)) return;
    bool pass_cmd = c->kind == GLIB_CMD_RENDER_TO_TEXTURE || c->kind == GLIB_CMD_RENDER_TO_TEXTURE_ONCE;
    if (f->skipping && !pass_cmd) return;
    f->skipping = false;
    if (r->world_only && pass_cmd && c->nnum > 0 && !world_only_pass(s, c)) {
        f->skipping = true;   /* the block's pixels are not the screen's world */
        return;
    }
    if (water_on_screen(f, c) && !f->water_reached) {
        f->water_reached = true;
        if (r->world_only) return;
        world_snapshot_take(&r->snap, f->screen_fbo, f->x, f->y, f->w, f->h);
    }
    if (r->world_only && c->kind == GLIB_CMD_SPLAT) return;
    if (pass_cmd) f->replaying = false;
    /* a kept block leaves the state (camera, program, transforms) a drawn one does */
    if (f->replaying && writes_pixels(c->kind)) return;
    track_clean(f, c);
    if (c->kind == GLIB_CMD_RENDER_TO_TEXTURE_ONCE) {
        if (s->once_done[i] || c->nnum == 0) { f->skipping = true; return; }
        s->once_done[i] = true;
        s->once_sig[i] = once_signature(r, f, i);
        f->replaying = once_kept(r, f, s->once_sig[i]);   /* a reload that changed none of it */
        f->once_drawn = f->once_drawn || !f->replaying;
        f->in_once = true;
        world_set_detail(&r->world, 1.0);
        mark_pass(r, c);
        leave_target(f);
        begin_rtt(r, c);
        f->in_rtt = true;
        upload_target_size(f);
    } else if (c->kind == GLIB_CMD_CAMERA) {
        int k = cam_kind_from_name(c->name);
        if (k >= 0) {
            cam_load(&f->cams, k);
            f->cam_kind = k;
            cam_eye(&f->cam_in, k, f->cam_eye);
        }
    } else if (c->kind == GLIB_CMD_SPLAT) {
        splat(r, (int)c->num[0], (int)c->num[1]);
    } else if (render_res_is_geometry(c->kind) || c->kind == GLIB_CMD_GL_BEGIN) {
        if (res >= 0) draw_mesh(r, f, i, &s->meshes[res]);
    } else if (c->kind == GLIB_CMD_NUM_PATCH_VERTICES) {
        f->patch_vertices = (int)c->num[0];
        f->patch_cmd = i;
    } else if (c->kind == GLIB_CMD_PROGRAM) {
        f->cur = res >= 0 ? &s->progs[res] : NULL;
        glUseProgram(f->cur ? f->cur->gl : 0);
        if (f->cur && f->cur->gl) {
            prog_upload(f->cur, f->t, s->set.timer_s);
            world_upload(&r->world, f->cur->gl, f->t, f->eye);
            cam_upload(&f->cams, f->cur->gl);
            upload_target_size(f);
        }
    } else if (c->kind == GLIB_CMD_WORLD) {
        draw_world(r, f, i);
    } else if (c->kind == GLIB_CMD_WATER_SURFACE) {
        if (c->name[0]) draw_points(r, f, c);   /* "points" or "mesh" */
        else {
            /* the surface nearer than the near plane is still water: an eye a
             * few centimetres above it (scenes/hard/at_level.glib) saw the
             * bottom third of the frame through a hole the near plane cut;
             * depth clamping keeps it (what is behind the eye is still
             * clipped by the x and y planes) */
            glEnable(GL_DEPTH_CLAMP);
            world_draw_water(&r->world, f->cur ? f->cur->tangent_loc : -1);
            glDisable(GL_DEPTH_CLAMP);
        }
    } else if (c->kind == GLIB_CMD_RENDER_TO_TEXTURE) {
        if (f->in_once) world_set_detail(&r->world, r->detail);
        f->in_once = false;
        mark_pass(r, c);
        if (c->nnum > 0) { leave_target(f); begin_rtt(r, c); f->in_rtt = true; }
        else end_rtt(f);
        upload_target_size(f);
    } else if (render_res_is_texture(c->kind)) {
        /* glman runs the file in order: a Texture2D after a draw rebinds its
         * unit for the draws after it (the course's sky box: one image per
         * wall on one unit) */
        if (res >= 0) bind_tex(&s->texs[res]);
    } else if (c->kind >= GLIB_CMD_TRANSLATE && c->kind <= GLIB_CMD_POP_MATRIX) {
        exec_transform(f, c);
    } else {
        exec_state_cmd(c);
    }
}

void render_set_world_cache(render *r, bool on) {
    r->wcache.off = !on;
    r->wlayers.off = !on;
    if (!on) world_cache_free(&r->wcache);
    if (!on) world_layers_free(&r->wlayers);
}

long render_world_cache_hits(const render *r) { return r->wcache.hits; }

long render_once_reused(const render *r) { return r->once_reused; }

bool render_set_world_height_map(render *r, bool on) {
    char *log = NULL;
    bool ok = world_set_height_map(&r->world, on, (const char *const *)r->include_dirs, &log);
    free(log);
    world_cache_free(&r->wcache);   /* the world may draw differently now */
    return ok;
}

long render_world_layer_frames(const render *r) { return r->wlayers.composites; }

void render_set_detail(render *r, double detail) {
    r->detail = detail > 0 && detail < 1 ? detail : 1;
}

/* After a frame checked once at its end: an error sends the next frame
 * through the checks after each command, which name the command (the
 * draw drew nothing either way; the rest of the frame is drawn). */
static void frame_gl_errors(render *r, const frame_state *f) {
    if (f->check_each) {
        r->gl_check_each = false;
        return;
    }
    if (glGetError() == GL_NO_ERROR) return;
    for (int k = 0; k < 16 && glGetError() != GL_NO_ERROR; k++) {}
    r->gl_check_each = true;
}

void render_frame(render *r, double t, unsigned fbo, int w, int h, const render_view *view) {
    render_frame_at(r, t, fbo, 0, 0, w, h, view);
}

void render_set_samples(render *r, int samples) { r->samples = samples; }
int render_samples(render *r) { return render_msaa_effective(&r->msaa, r->samples); }

int render_samples_on_this_gl(int requested) {
    render_msaa m = { 0 };
    return render_msaa_effective(&m, requested);
}

int render_ref_spp(int samples) {
    int n = 1;
    while ((n + 1) * (n + 1) <= samples || (n + 1) * (n + 1) - samples < samples - n * n) n++;
    return n;
}

/* GL's y up in the pixel as the image's y down, kept inside [0, 1). */
static int to_image_positions(int n, double (*pos)[2], int max) {
    for (int i = 0; i < n && i < max; i++) {
        pos[i][1] = 1.0 - pos[i][1];
        for (int k = 0; k < 2; k++) {
            if (pos[i][k] >= 1.0) pos[i][k] = nextafter(1.0, 0.0);
            if (!(pos[i][k] >= 0.0)) pos[i][k] = 0.0;
        }
    }
    return n < max ? n : max;
}

int render_ref_positions(int samples, double (*pos)[2], int max) {
    return to_image_positions(render_msaa_positions(samples, pos, max), pos, max);
}

int render_ref_standard_positions(int samples, double (*pos)[2], int max) {
    return to_image_positions(render_msaa_standard_positions(samples, pos, max), pos, max);
}

/* Names program p's uniforms that the shader uses but the glib gives no
 * value (so they stay 0, as in glman) into list; returns how many. */
static int unset_uniforms(const prog *p, char *list, size_t n) {
    int count = 0;
    list[0] = '\0';
    for (int i = 0; p->unifs && i < p->unifs->n; i++) {
        const unif_entry *e = &p->unifs->entries[i];
        if (e->is_define || e->from_glib || !e->in_shader || e->location < 0 || e->type == UNIF_SAMPLER) continue;
        bool zero = true;
        for (int k = 0; k < e->ncomp; k++) zero = zero && e->value[k] == 0.0f;
        if (!zero) continue;
        size_t l = strlen(list);
        if (count < 6) snprintf(list + l, n - l, "%s%s", count ? ", " : "", e->name);
        else if (count == 6) snprintf(list + l, n - l, ", ...");
        count++;
    }
    return count;
}

/* Issue #27: "say why a picture is black". After a load's first frame, a
 * picture of one colour while a program uses uniforms the glib never sets
 * (0 in tarn as in glman) is said once, with what to give; a flat picture
 * with every input set is the scene's own business and is not. */
static void check_flat_picture(render *r, unsigned fbo, int x, int y, int w, int h) {
    scene_state *s = &r->cur;
    s->flat_checked = true;
    if (r->world.active || w <= 0 || h <= 0) return;
    int worst = -1, most = 0;
    char names[256], best[256] = "";
    for (int i = 0; i < s->nprogs; i++) {
        int k = unset_uniforms(&s->progs[i], names, sizeof names);
        if (k > most) { most = k; worst = i; snprintf(best, sizeof best, "%s", names); }
    }
    if (worst < 0) return;
    unsigned char *px = mem_alloc((size_t)w * (size_t)h * 4);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(x, y, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px);
    bool flat = true;
    for (size_t i = 4; flat && i < (size_t)w * (size_t)h * 4; i += 4) flat = memcmp(px + i, px, 3) == 0;
    free(px);
    if (!flat) return;
    const prog *p = &s->progs[worst];
    int ci = (int)(p->cmd - s->glib->cmds);
    if (ci < 0 || ci >= s->glib->ncmds) return;
    char first[64];
    snprintf(first, sizeof first, "%.*s", (int)strcspn(best, ","), best);
    draw_problem(r, ci, false, "the picture is one flat colour, and program '%s' uses %d uniform%s that the glib "
                 "gives no value, so %s 0: %s; give %s a value in the Program line (e.g. %s <0. 1. 2.>)",
                 p->name, most, most == 1 ? "" : "s", most == 1 ? "it stays" : "they stay", best,
                 most == 1 ? "it" : "each", first);
}

void render_frame_at(render *r, double t, unsigned fbo, int x, int y, int w, int h, const render_view *view) {
    gpu_timer_begin_frame(&r->timer);
    const scene_state *s = &r->cur;
    /* the screen passes go to the multisampled target, resolved at the end */
    unsigned dest = fbo;
    int dest_x = x, dest_y = y;
    /* the ocean's passes, then the height map, which reads them: before the
     * frame binds its target; the frame's own passes are "screen" again */
    world_snapshot_frame(&r->snap);
    /* a world-only frame keeps the last frame's: the water's state is not its to advance */
    bool update = s->glib && !r->world_only;
    if (update && world_update_ocean(&r->world, t, &r->timer)) gpu_timer_mark(&r->timer, "screen");
    if (update && world_update_flow(&r->world, t, &r->timer)) gpu_timer_mark(&r->timer, "screen");
    if (update && r->draw_timing) mark_now(r, "world height");
    if (update) world_update_height(&r->world, t, r->detail);
    /* the spray after the height map: an ocean's upward speed is read from it */
    if (update && world_update_spray(&r->world, t, &r->timer)) gpu_timer_mark(&r->timer, "screen");
    bool ms = s->glib && render_msaa_begin(&r->msaa, render_samples(r), fbo, w, h, r->world.active);
    if (ms) { fbo = r->msaa.fbo; x = 0; y = 0; }
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(x, y, w, h);
    glScissor(x, y, w, h);   /* the clear stays inside the scene's rectangle */
    glEnable(GL_SCISSOR_TEST);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glColor4f(1, 1, 1, 1);
    /* each frame starts from glman's state: Flat, LineWidth, PointSize and
     * PointSizeMode of the last frame do not leak into the first draws */
    glShadeModel(GL_SMOOTH);
    glLineWidth(1);
    glPointSize(1);
    glDisable(GL_PROGRAM_POINT_SIZE);
    const float *bg = s->set.background;
    glClearColor(bg[0], bg[1], bg[2], bg[3]);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    if (s->glib) {
        render_view v = view ? *view : s->set.view;
        size_targets(r, w, h);
        world_set_detail(&r->world, r->detail);
        world_follow_waves(&r->world, t);
        bind_builtin_noise(r, s);
        bind_textures(s);
        world_bind_textures(&r->world);
        frame_state f = { .screen_fbo = fbo, .x = x, .y = y, .w = w, .h = h, .t = t, .clean = true };
        memcpy(f.clean_rgba, bg, sizeof f.clean_rgba);   /* cleared to it above */
        memcpy(f.eye, v.eye, sizeof f.eye);
        camera_inputs(r, &v, w, h, &f.cam_in);
        cam_compute(&f.cam_in, &f.cams);
        cam_load(&f.cams, CAM_MAIN);
        f.cam_kind = CAM_MAIN;
        memcpy(f.cam_eye, v.eye, sizeof f.cam_eye);
        glPushMatrix();
        f.patch_vertices = 3;   /* GL's default patch size */
        f.patch_cmd = -1;
        for (int k = 0; k < 16 && glGetError() != GL_NO_ERROR; k++) {}   /* not ours: the caller's */
        f.check_each = r->gl_check_each;
        for (int i = 0; i < s->glib->ncmds; i++) {
            if (r->draw_timing) mark_draw(r, &s->glib->cmds[i]);
            exec_cmd(r, &f, i);
            if (f.check_each) check_gl(r, &f, i, NULL, NULL);   /* after a draw, draw_mesh has checked already */
        }
        if (r->draw_timing) mark_now(r, "screen");   /* the last draw's pixels in its own interval */
        if (r->world.spray.active && !f.in_rtt && !r->world_only) {
            /* the droplets over the finished frame (render_spray.h), the main camera's */
            gpu_timer_mark(&r->timer, "spray draw");
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            glViewport(x, y, w, h);
            world_draw_spray(&r->world, f.cams.vp[CAM_MAIN], f.eye, w, h);
        }
        frame_gl_errors(r, &f);
        for (; f.depth > 0; f.depth--)   /* unbalanced PushMatrix in the glib */
            if (f.depth <= MATRIX_STACK_MAX) glPopMatrix();
        glPopMatrix();
        if (f.in_rtt) end_rtt(&f);
        if (f.in_once) world_set_detail(&r->world, r->detail);
        glUseProgram(0);
        glFrontFace(GL_CCW);
        if (!r->world_only) r->nkept_once = 0;   /* the first frame after a load has decided every block */
    }
    if (ms) render_msaa_resolve(&r->msaa, dest, dest_x, dest_y);
    if (s->glib && !s->flat_checked && !r->world_only) check_flat_picture(r, dest, dest_x, dest_y, w, h);
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

void render_set_world_snapshot(render *r, bool on) { r->snap.on = on; }   /* the texture stays for the next */

unsigned render_world_snapshot(const render *r, int *w, int *h) {
    if (w) *w = r->snap.valid ? r->snap.w : 0;
    if (h) *h = r->snap.valid ? r->snap.h : 0;
    return r->snap.valid ? r->snap.tg.color : 0;
}

double render_gpu_ms(render *r, bool wait) {
    gpu_timer_collect(&r->timer, wait);
    return r->timer.frame_ms;
}

int render_pass_times(render *r, bool wait, const char (**names)[GPU_TIMER_NAME], const double **ms) {
    gpu_timer_collect(&r->timer, wait);
    *names = (const char (*)[GPU_TIMER_NAME])r->timer.pass_names;
    *ms = r->timer.pass_ms;
    return r->timer.npasses;
}

int render_targets(const render *r, render_target_info *out, int max) {
    const scene_state *s = &r->cur;
    int n = 0;
    for (int i = 0; s->glib && i < s->glib->ncmds; i++) {
        const glib_cmd *c = &s->glib->cmds[i];
        if (c->kind != GLIB_CMD_TEXTURE2D_EMPTY || s->cmd_res[i] < 0) continue;
        const gpu_tex *t = &s->texs[s->cmd_res[i]];
        if (!t->tex || !t->render_target) continue;
        if (n < max)
            out[n] = (render_target_info){ .unit = t->unit, .w = t->w, .h = t->h, .tex = t->tex,
                                           .is_float = t->format == GLIB_TARGET_RGBA16F || t->format == GLIB_TARGET_RGBA32F,
                                           .is_depth = t->format == GLIB_TARGET_DEPTH, .file = c->file, .line = c->line };
        n++;
    }
    return n;
}

void render_pass_summary(render *r, char *out, int len) {
    const char (*names)[GPU_TIMER_NAME];
    const double *ms;
    int n = render_pass_times(r, false, &names, &ms), used = 0;
    if (len > 0) out[0] = '\0';
    for (int i = 0; i < n && used < len - 40; i++)
        used += snprintf(out + used, (size_t)(len - used), "%s%s %.2f ms", i ? "\n" : "", names[i], ms[i]);
}

bool render_read_uniform(render *r, const char *program, const char *name, float *out, int n) {
    for (int i = 0; i < r->cur.nprogs; i++) {
        prog *p = &r->cur.progs[i];
        if (strcmp(p->name, program) != 0 || !p->gl) continue;
        GLint loc = glGetUniformLocation(p->gl, name);
        if (loc < 0) return false;
        float buf[16];
        glGetUniformfv(p->gl, loc, buf);
        memcpy(out, buf, (size_t)(n < 16 ? n : 16) * sizeof(float));
        return true;
    }
    return false;
}

/* ---- offscreen targets ---- */

/* One colour+depth framebuffer, its colour in `internal` (given as `type`). */
static bool target_create(render_target *t, int w, int h, unsigned internal, unsigned type) {
    glGenTextures(1, &t->color);
    glBindTexture(GL_TEXTURE_2D, t->color);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, w, h, 0, GL_RGBA, type, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    glGenRenderbuffers(1, &t->depth);
    glBindRenderbuffer(GL_RENDERBUFFER, t->depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glGenFramebuffers(1, &t->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t->color, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t->depth);
    bool ok = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (!ok) render_target_destroy(t);
    return ok;
}

bool render_target_create(render_target *t, int w, int h, bool is_float) {
    *t = (render_target){ .w = w, .h = h, .is_float = is_float };
    return target_create(t, w, h, is_float ? GL_RGBA32F : GL_RGBA8, is_float ? GL_FLOAT : GL_UNSIGNED_BYTE);
}

bool render_target_create_srgb(render_target *t, int w, int h) {
    *t = (render_target){ .w = w, .h = h, .is_srgb = true };
    return target_create(t, w, h, GL_SRGB8_ALPHA8, GL_UNSIGNED_BYTE);
}

void render_target_destroy(render_target *t) {
    if (t->fbo) glDeleteFramebuffers(1, &t->fbo);
    if (t->color) glDeleteTextures(1, &t->color);
    if (t->depth) glDeleteRenderbuffers(1, &t->depth);
    memset(t, 0, sizeof *t);
}

bool render_target_read(const render_target *t, float *rgba) {
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, t->w, t->h, GL_RGBA, GL_FLOAT, rgba);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    /* GL's row 0 is the bottom; files start at the top */
    size_t row = (size_t)t->w * 4;
    float *tmp = mem_alloc(row * sizeof(float));
    for (int y = 0; y < t->h / 2; y++) {
        float *a = rgba + (size_t)y * row, *b = rgba + (size_t)(t->h - 1 - y) * row;
        memcpy(tmp, a, row * sizeof(float));
        memcpy(a, b, row * sizeof(float));
        memcpy(b, tmp, row * sizeof(float));
    }
    free(tmp);
    return glGetError() == GL_NO_ERROR;
}
