/* render_load: a scene built from a glib (its settings, meshes, textures,
 * programs and world, and the files it depends on), and built again on a
 * reload, keeping per part what worked (render.h). */
#include "util.h"
#include "render_internal.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geom.h"
#include "mem.h"
#include "program.h"
#include "strbuf.h"

void render_load_scene_free(scene_state *s) {
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
    free(s->from_view);
    free(s->draw_warned);
    free(s->cmd_res);
    if (s->glib) glib_free(s->glib);
    memset(s, 0, sizeof *s);
}

void render_load_free_deps(render *r) {
    for (int i = 0; i < r->ndeps; i++) free((char *)r->deps[i]);
    free(r->deps);
    r->deps = NULL;
    r->ndeps = 0;
}

static render_view view_of(const scene_camera *cam) {
    render_view v;
    for (int k = 0; k < 3; k++) {
        v.eye[k] = (float)cam->eye[k];
        v.center[k] = (float)cam->center[k];
        v.up[k] = (float)cam->up[k];
    }
    return v;
}

void render_load_settings_default(scene_settings *s) {
    memset(s, 0, sizeof *s);
    scene_camera_from_glib(NULL, &s->cam);
    s->timer_s = 10.0;
    s->background[3] = 1.0f;
    s->view = view_of(&s->cam);
}

static void settings_from_glib(scene_settings *s, const glib_scene *g) {
   render_load_settings_default(s);
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

static void diags_to_log(const glib_scene *g, diag_list *log) {
    for (int i = 0; i < g->ndiags; i++) diag_push(log, &g->diags[i]);
}

static int steal_mesh(scene_state *old, const char *key) {
    for (int i = 0; i < old->nmeshes; i++)
        if (old->meshes[i].vbo && strcmp(old->meshes[i].key, key) == 0) return i;
    return -1;
}

static void build_mesh(scene_state *s, scene_state *old, const glib_cmd *c, int ci, diag_list *log) {
    gpu_mesh *m = &s->meshes[s->nmeshes];
    memset(m, 0, sizeof *m);
    render_res_key(c, m->key, sizeof m->key);
    int o = steal_mesh(old, m->key);
    if (o >= 0) {
        *m = old->meshes[o];
        memset(&old->meshes[o], 0, sizeof old->meshes[o]);
    } else if (!render_res_mesh_build(c, s->glib->read_through, m, log) && c->path[0]) {
        /* a broken OBJ keeps the last good mesh of that file (as textures do) */
        for (int i = 0; i < old->nmeshes; i++) {
            const char *a = old->meshes[i].key, *at = strrchr(a, '@'), *bt = strrchr(m->key, '@');
            if (!old->meshes[i].vbo || !at || !bt || at - a != bt - m->key || memcmp(a, m->key, (size_t)(at - a)) != 0)
                continue;   /* the key without its file stamp: same command, same file */
            *m = old->meshes[i];   /* with its own key: the next reload retries the file */
            memset(&old->meshes[i], 0, sizeof old->meshes[i]);
            diag_add(log, DIAG_NOTE, c->file, c->line, "keeping the last good mesh of '%s'", c->path);
            break;
        }
    }
    s->cmd_res[ci] = s->nmeshes++;
}

/* Equal key: reuse. A texture that fails keeps the last good one of that file. */
static void build_tex(scene_state *s, scene_state *old, const glib_cmd *c, int ci, diag_list *log) {
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
    if (!render_res_tex_build(c, s->glib->read_through, t, log)) {
        const char *want = c->kind == GLIB_CMD_CUBEMAP && c->cube_paths ? c->cube_paths[0] : c->path;
        for (int i = 0; i < old->ntexs; i++) {
            if (old->texs[i].tex && want[0] && strcmp(old->texs[i].path, want) == 0) {
                *t = old->texs[i];
                memset(&old->texs[i], 0, sizeof old->texs[i]);
                diag_add(log, DIAG_NOTE, c->file, c->line, "keeping the last good image of '%s'", want);
                break;
            }
        }
        /* a glib edit that names another file, which fails: keep what that unit showed */
        int unit = t->unit;
        unsigned target = t->target;
        for (int i = 0; !t->tex && i < old->ntexs; i++) {
            const gpu_tex *o = &old->texs[i];
            if (!o->tex || o->render_target || o->unit != unit || o->target != target) continue;
            diag_add(log, DIAG_NOTE, c->file, c->line, "keeping the last good image of unit %d ('%s')",
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
                       const program_stages *st, int ci, diag_list *log, prog_origins *from) {
    prog *p = &s->progs[s->nprogs];
    memset(p, 0, sizeof *p);
    p->unifs = &s->unifs[s->nprogs];
    snprintf(p->name, sizeof p->name, "%s", c->name);
    p->cmd = c;
    p->gstap = st->gstap;
    p->world_uniforms = r->world.active;
    world_set_defines(&r->world, p);   /* only the wave models the world has */
    if (r->world.active && r->world.has_above_water) {   /* `If above_water` as a define: a pack
                                                           * compiles out what only it needs */
        shader_define *d = &p->fixed[PROG_FIXED_MAX - 1];   /* world_set_defines leaves it */
        snprintf(d->name, sizeof d->name, "WORLD_ABOVE_WATER");
        snprintf(d->value, sizeof d->value, "1");
    }
    p->scene = s->glib;
    for (int k = 0; k < SHADER_STAGE_COUNT; k++)
        snprintf(p->stage_path[k], sizeof p->stage_path[k], "%s", program_stage_path(st, (shader_stage)k));
    glib_unif_set(p->unifs, c, log);
    snprintf(p->unifs->program, sizeof p->unifs->program, "%s", c->name);
    prog *o = find_old_prog(old, p->name);
    if (o) {   /* the last good build and the user's values (defines first) */
        p->gl = o->gl;
        p->hash = o->hash;
        p->good = o->good;
        p->source = o->source;   /* the kept build's text: says declared-but-inactive from undeclared */
        o->source = NULL;
        p->vertex_text = o->vertex_text;   /* ... and its stages and deferred water (water_deferred.h) */
        p->fragment_text = o->fragment_text;
        p->deferred = o->deferred;
        o->vertex_text = o->fragment_text = NULL;
        memset(&o->deferred, 0, sizeof o->deferred);
        o->gl = 0;
        o->cmd = c;   /* marks it taken */
        unif_merge(p->unifs, o->unifs);
    }
    prog_build(p, &r->sources, log, from);
    prog_introspect(p, log);
    if (o) unif_merge(p->unifs, o->unifs);   /* now both carry shader types */
    s->cmd_res[ci] = s->nprogs++;
}

/* If/EndIf must pair up; an unmatched one is reported and the renderer
 * treats a missing EndIf as the end of the scene. */
static void check_if_nesting(const glib_scene *g, diag_list *log) {
    int depth = 0;
    const glib_cmd *open_if = NULL;
    for (int i = 0; i < g->ncmds; i++) {
        const glib_cmd *c = &g->cmds[i];
        if (c->kind == GLIB_CMD_IF) { if (depth++ == 0) open_if = c; }
        else if (c->kind == GLIB_CMD_END_IF && --depth < 0) {
            diag_add(log, DIAG_ERROR, c->file, c->line, "EndIf without an If");
            depth = 0;
        }
    }
    if (depth > 0 && open_if)
        diag_add(log, DIAG_ERROR, open_if->file, open_if->line, "If without an EndIf (the block runs to the end)");
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
static void build_begin(scene_state *s, int ci, diag_list *log) {
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
        diag_add(log, DIAG_ERROR, g->cmds[ci].file, g->cmds[ci].line, "glBegin: cannot build its %d vertices", n);
    geom_free(&gm);
    free(xyz);
}

/* --verbose: each inactive uniform a note at its own glib line. */
static void note_each_inactive(const scene_state *s, diag_list *log) {
    for (int i = 0; i < s->nprogs; i++) {
        int n = prog_inactive_uniforms(&s->progs[i], NULL, 0);
        if (n <= 0) continue;
        const unif_entry **found = mem_alloc((size_t)n * sizeof *found);
        n = prog_inactive_uniforms(&s->progs[i], found, n);
        for (int k = 0; k < n; k++)
            diag_add(log, DIAG_NOTE, found[k]->glib_file ? found[k]->glib_file : "?", found[k]->glib_line,
                     "uniform '%s' is declared in program '%s' but inactive as built", found[k]->name,
                        s->progs[i].name);
        free(found);
    }
}

/* The glib's uniforms that shaders declare but do not use, in one line a
 * load (issue #30: a line each buried the real messages): the same words
 * at start-up and on every reload. */
#define INACTIVE_NAMED 8
static void note_inactive_uniforms(const scene_state *s, bool verbose, diag_list *log) {
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
        diag_add(log, DIAG_NOTE, first && first->glib_file ? first->glib_file : "?", first ? first->glib_line : 0,
                 "%d uniform%s of the glib %s declared but inactive as built "
                 "(compiled out by a Define, or unused): %s%s",
                 total,
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

/* The terrain's height map is baked the first time a program of the scene
 * reads it (caustic_tex's march): a scene whose programs do not pays
 * nothing for it. */
static void want_terrain_map(render *r, const scene_state *s) {
    if (!r->world.active) return;
    for (int i = 0; i < s->nprogs; i++)
        if (s->progs[i].gl && glGetUniformLocation(s->progs[i].gl, "uTerrainHeightMap") >= 0) {
            world_bake_terrain_map(&r->world);
            return;
        }
}

static bool build_scene(render *r, scene_state *s, scene_state *old, diag_list *log, prog_origins *from) {
    int n = s->glib->ncmds;
    s->cmd_res = mem_alloc((size_t)(n > 0 ? n : 1) * sizeof *s->cmd_res);
    s->meshes = mem_zalloc((size_t)(n > 0 ? n : 1) * sizeof *s->meshes);
    s->texs = mem_zalloc((size_t)(n > 0 ? n : 1) * sizeof *s->texs);
    s->progs = mem_zalloc((size_t)(n > 0 ? n : 1) * sizeof *s->progs);
    s->unifs = mem_zalloc((size_t)(n > 0 ? n : 1) * sizeof *s->unifs);
    s->once_done = mem_zalloc((size_t)(n > 0 ? n : 1) * sizeof *s->once_done);
    s->once_sig = mem_zalloc((size_t)(n > 0 ? n : 1) * sizeof *s->once_sig);
    s->per_frame = mem_zalloc((size_t)(n > 0 ? n : 1) * sizeof *s->per_frame);
    s->from_view = mem_zalloc((size_t)(n > 0 ? n : 1) * sizeof *s->from_view);
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
        if (c->kind == GLIB_CMD_TEXTURE2D_EMPTY) {
            s->per_frame[i] = render_size_drawn_every_frame(s->glib, (int)c->num[0]);
            s->from_view[i] = s->per_frame[i] && render_size_drawn_from_view(s->glib, (int)c->num[0]);
        } else if (c->kind == GLIB_CMD_PROGRAM) build_prog(r, s, old, c, &st, i, log, from);
        else program_stages_step(&st, c);
    }
    settings_from_glib(&s->set, s->glib);
    note_noise_units(s);
    note_inactive_uniforms(s, r->verbose, log);
    check_if_nesting(s->glib, log);
    render_size_check_names(s, log);
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
   render_load_free_deps(r);
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

/* Does a program read the clock: glman's Timer or tarn's uTime, active in
 * its build? */
static bool prog_reads_clock(const prog *p) {
    return p->gl && (p->timer_loc >= 0 || glGetUniformLocation(p->gl, "uTime") >= 0);
}

/* Do the frames after the first draw with a program that reads the clock?
 * The program each drawing command uses is the one the last `Program`
 * before it bound, outside `RenderToTextureOnce` blocks: a block runs on a
 * load's first frame only (render_exec.c skips it after, its `Program`
 * with it), so a Timer read there is fixed in its target. */
static bool frames_read_clock(const scene_state *s) {
    int bound = -1;
    bool in_once = false;
    for (int i = 0; s->glib && i < s->glib->ncmds; i++) {
        glib_cmd_kind k = s->glib->cmds[i].kind;
        if (k == GLIB_CMD_RENDER_TO_TEXTURE_ONCE || k == GLIB_CMD_RENDER_TO_TEXTURE)
            in_once = k == GLIB_CMD_RENDER_TO_TEXTURE_ONCE;
        else if (in_once) continue;
        else if (k == GLIB_CMD_PROGRAM) bound = s->cmd_res[i];
        else if (bound >= 0 && render_res_writes_pixels(k) && prog_reads_clock(&s->progs[bound])) return true;
    }
    return false;
}

static bool scene_reads_clock(const render *r) {
    if (frames_read_clock(&r->cur)) return true;
    const gpu_world *w = &r->world;
    if (!w->active) return false;
    if (w->ocean.active || w->flow.active || w->spray.active) return true;   /* stepped in time on their own */
    for (int i = 0; i < WORLD_MODES; i++)
        if (prog_reads_clock(&w->progs[i])) return true;
    return prog_reads_clock(&w->height_prog) || prog_reads_clock(&w->layers_prog[0]) ||
           prog_reads_clock(&w->layers_prog[1]);
}

/* The world the scene describes (if any), rebuilt only when it changed. */
static void build_world(render *r, const glib_scene *g, diag_list *log, prog_origins *from) {
    ref_world_desc desc;
    scene_camera cam;
    bool has_world = false;
    scene_from_glib(g, &desc, &cam, &has_world, log);
    if (has_world && r->water_mesh > 0) desc.water_mesh_res = r->water_mesh;
    r->water_mesh_loaded = r->water_mesh;
    if (r->no_spray) desc.spray.on = false;   /* no state, no pass: as a scene without Spray */
    if (has_world) world_build(&r->world, &desc, &r->sources, log, from);
    else world_free(&r->world);
}

/* The world's caches (the static world's pixels, its layers) hold the
 * world as it was drawn; their keys hold everything else it depends on
 * (camera, time, GL state, targets). So a load or rebuild keeps them where
 * the world's description and its programs' texts are the same, and
 * forgets them where either changed (a GL name reused by the new world's
 * textures must not match an old key). A save of a pack's shader then
 * redraws no world: with the clock running, the frame after it had built
 * the world's layers again, 100-120 ms of raymarch's on the lake. */
typedef struct world_was {
    bool active;
    unsigned builds;              /* world_build's count: a new description builds anew */
    unsigned long long programs;
} world_was;

static void world_remember(const render *r, world_was *w) {
    w->active = r->world.active;
    w->builds = r->world.builds;
    w->programs = render_world_programs_hash(r);
}

static void world_caches_update(render *r, const world_was *w) {
    bool same = w->active && r->world.active && r->world.builds == w->builds &&
                render_world_programs_hash(r) == w->programs;
    if (same) return;
    world_cache_free(&r->wcache);
    world_layers_free(&r->wlayers);
}

bool render_load(render *r, const char *glib_path) {
    if (glib_path && glib_path != r->path) snprintf(r->path, sizeof r->path, "%s", glib_path);
    diag_list log = { 0 };
    prog_origins from = { 0 };
    glib_options opts = { .packs_dir = r->packs_dir, .pack_override = r->pack[0] ? r->pack : NULL,
                          .files = r->files };
    glib_scene *g = glib_load_opts(r->path, &opts);
    diags_to_log(g, &log);
    if (g->nerrors > 0 && r->cur.glib) {
        /* a half-written glib: keep everything that is on screen */
        diag_add_bare(&log, DIAG_NOTE, "%s: the scene has errors; keeping the last good scene", r->path);
        collect_deps(r, g, &r->cur);
        glib_free(g);
        render_messages_set(r, &log, &from);
        r->errors = true;
        return false;
    }
    world_was was;
    world_remember(r, &was);
    build_world(r, g, &log, &from);
    world_caches_update(r, &was);
    scene_state fresh;
    memset(&fresh, 0, sizeof fresh);
    fresh.glib = g;
    build_scene(r, &fresh, &r->cur, &log, &from);
    want_terrain_map(r, &fresh);
    render_once_keep(r, &r->cur);
    render_load_scene_free(&r->cur);
    r->cur = fresh;
    collect_deps(r, g, &r->cur);
    render_messages_set(r, &log, &from);
    r->errors = g->nerrors > 0 || r->diags.nerrors > 0;
    r->reads_clock = scene_reads_clock(r);
    r->gl_check_each = true;
    return !r->errors;
}

bool render_rebuild_programs(render *r) {
    diag_list log = { 0 };
    prog_origins from = { 0 };
    bool ok = true;
    for (int i = 0; i < r->cur.nprogs; i++) {
        prog *p = &r->cur.progs[i];
        if (!prog_build(p, &r->sources, &log, &from)) ok = false;
        prog_introspect(p, &log);
    }
    note_noise_units(&r->cur);
    want_terrain_map(r, &r->cur);
    world_was was;
    world_remember(r, &was);
    if (r->world.active) {
        if (!world_build_programs(&r->world, &r->sources, &log, &from)) ok = false;
    }
    world_caches_update(r, &was);
    collect_deps(r, r->cur.glib, &r->cur);
    render_messages_set(r, &log, &from);
    r->errors = !ok;
    r->reads_clock = scene_reads_clock(r);
    r->gl_check_each = true;
    return ok;
}
