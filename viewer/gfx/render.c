/* render: the render's lifetime, its settings and what it tells of the
 * scene; the parts of its work are in the files render_internal.h lists. */
#include "util.h"
#include "render_internal.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"

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
    r->shared_files = desc && desc->files;
    r->files = r->shared_files ? desc->files : file_cache_create();
    r->sources = (prog_sources){ .include_dirs = r->include_dirs, .ninclude_dirs = 1, .common_dir = r->common_dir,
                                 .files = r->files };
    gpu_timer_init(&r->timer);
    world_cache_init(&r->wcache);
    world_layers_init(&r->wlayers);
    water_deferred_init(&r->deferred);
    return r;
}

render_desc render_desc_of(const render *r) {
    return (render_desc){ .repo_root = r->root, .pack = r->pack[0] ? r->pack : NULL, .samples = r->samples,
                          .verbose = r->verbose, .no_spray = r->no_spray,
                          .files = r->shared_files ? r->files : NULL };
}

void render_destroy(render *r) {
    if (!r) return;
    render_load_scene_free(&r->cur);
    world_free(&r->world);
    world_cache_free(&r->wcache);
    world_layers_free(&r->wlayers);
    world_snapshot_free(&r->snap);
    water_deferred_free(&r->deferred);
    render_load_free_deps(r);
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
    if (!r->shared_files) file_cache_destroy(r->files);
    free(r);
}

bool render_has_scene(const render *r) { return r->cur.glib != NULL; }
bool render_has_world(const render *r) { return r->world.active; }

unsigned long long render_world_programs_hash(const render *r) {
    if (!r->world.active) return 0;
    const gpu_world *w = &r->world;
    unsigned long long h = HASH_FNV1A_BASIS;
    for (int m = 0; m < WORLD_MODES; m++) h = hash_fnv1a(h, &w->progs[m].hash, sizeof w->progs[m].hash);
    h = hash_fnv1a(h, &w->height_prog.hash, sizeof w->height_prog.hash);
    for (int ms = 0; ms < 2; ms++) h = hash_fnv1a(h, &w->layers_prog[ms].hash, sizeof w->layers_prog[ms].hash);
    /* the ocean's and the flow's passes move the surface the shore is wet under */
    for (int k = 0; k < OCEAN_PROGS; k++) h = hash_fnv1a(h, &w->ocean.progs[k].hash, sizeof w->ocean.progs[k].hash);
    return hash_fnv1a(h, &w->flow.prog.hash, sizeof w->flow.prog.hash);
}
bool render_reads_clock(const render *r) { return r->reads_clock; }

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
    render_load_settings_default(&s);
    return s.view;
}

void render_set_world_cache(render *r, bool on) {
    r->wcache.off = !on;
    r->wlayers.off = !on;
    if (!on) world_cache_free(&r->wcache);
    if (!on) world_layers_free(&r->wlayers);
}

long render_world_cache_hits(const render *r) { return r->wcache.hits; }

void render_set_deferred_water(render *r, bool on) {
    r->deferred.off = !on;
    if (!on) water_deferred_free(&r->deferred);
}

long render_deferred_water_draws(const render *r) { return r->deferred.draws; }

const char *render_deferred_water_why(const render *r) {
    if (r->deferred.skip_why) return r->deferred.skip_why;
    for (int i = 0; i < r->cur.nprogs; i++) {
        const prog_deferred *pd = &r->cur.progs[i].deferred;
        if (pd->tried && !pd->shade) return pd->why;
    }
    return NULL;
}

void render_keep_world_layers(render *r, bool keep) { r->wlayers.keep_larger = keep; }

bool render_set_world_height_map(render *r, bool on) {
    diag_list log = { 0 };
    bool ok = world_set_height_map(&r->world, on, &r->sources, &log, NULL);
    diag_list_free(&log);
    world_cache_free(&r->wcache);   /* the world may draw differently now */
    return ok;
}

void render_set_world_height_cells(render *r, bool on) {
    world_set_height_cells(&r->world, on);
    world_cache_free(&r->wcache);   /* drawn again, not copied: the test compares drawings */
    world_layers_free(&r->wlayers);
}

long render_world_layer_frames(const render *r) { return r->wlayers.composites; }
long render_world_band_frames(const render *r) { return r->wlayers.band_composites; }

void render_set_detail(render *r, double detail) {
    r->detail = detail > 0 && detail < 1 ? detail : 1;
}

void render_set_samples(render *r, int samples) { r->samples = samples; }
int render_samples(render *r) { return render_msaa_effective(&r->msaa, r->samples); }

int render_samples_on_this_gl(int requested) {
    render_msaa m = { 0 };
    return render_msaa_effective(&m, requested);
}

void render_set_world_snapshot(render *r, bool on) { r->snap.on = on; }   /* the texture stays for the next */

unsigned render_world_snapshot(const render *r, int *w, int *h) {
    if (w) *w = r->snap.valid ? r->snap.w : 0;
    if (h) *h = r->snap.valid ? r->snap.h : 0;
    return r->snap.valid ? r->snap.tg.color : 0;
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
