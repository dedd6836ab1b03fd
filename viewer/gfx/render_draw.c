/* render_draw: the commands that draw: a mesh for the current program,
 * `WaterSurface points|mesh N`, and `World` through the static-world
 * cache and its layers. */
#include "util.h"
#include "strbuf.h"
#include "render_internal.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <string.h>

#include "geom.h"

/* `WaterSurface points N` / `mesh N`: N x N points, or the triangles
 * between them; uPointGrid (contract) tells the current program the N it
 * is drawn with. */
static void draw_points(render *r, const frame_state *f, const glib_cmd *c) {
    /* at the frame's detail, as a target sized by the same slider is: a
     * pass of one photon per texel and the splat of those photons agree */
    int n = c->arg[0] ? render_size_slider_count(&r->cur, c->arg, 4096) : (int)c->num[0];
    if (!f->in_once) n = render_size_detail_count(r, n);
    if (f->cur && f->cur->gl) {
        GLint loc = glGetUniformLocation(f->cur->gl, "uPointGrid");
        if (loc >= 0) glUniform1f(loc, (float)n);
    }
    world_draw_points(&r->world, n, strcmp(c->name, "mesh") == 0);
}

/* A mesh of command ci, drawn for the current program. */
void render_draw_mesh(render *r, const frame_state *f, int ci, const gpu_mesh *m) {
    const prog *p = f->cur && f->cur->gl ? f->cur : NULL;
    render_res_draw d = { .tangent_loc = p ? p->tangent_loc : -1, .face_index_loc = p ? p->face_index_loc : -1,
                   .face_index_int = p && p->face_index_int, .tess = p && p->tess,
                   .patch_vertices = f->patch_vertices };
    char why[MSG_MAX];
    if (m->prim == GEOM_PATCHES && m->patch_size > 0 && f->patch_cmd >= 0 && m->patch_size != f->patch_vertices)
        render_messages_draw_problem(r, ci, false, "ObjPatch draws patches of its faces' %d corners; "
                                     "NumPatchVertices %d (line %d) is for glBegin gl_patches and not used here",
                                     m->patch_size, f->patch_vertices, r->cur.glib->cmds[f->patch_cmd].line);
    bool drawn = render_res_mesh_draw_with(m, &d, why, sizeof why);
    if (why[0])
        render_messages_draw_problem(r, ci, !drawn, "%s %s%s", glib_cmd_name(r->cur.glib->cmds[ci].kind),
                                     drawn ? "" : "drew nothing: ", why);
    if (f->check_each) render_check_gl(r, f, ci, m, &d);
}

/* A World whose key has stayed while the time ran is drawn from its layers
 * (world_layers.h): built once, then composed: the first frame whole, each
 * later one the last whole frame copied and only the band where the
 * surface moves over the land composed over it (world_layer_band.h). */
static bool draw_world_layers(render *r, frame_state *f, int i, const world_cache_key *k, const char *which, float offset) {
    if (!world_can_composite(&r->world, k->samples)) return false;
    world_layers_use use = world_layers_check(&r->wlayers, i, k);
    if (use == WORLD_LAYERS_NO) return false;
    unsigned restore = f->cur ? f->cur->gl : 0;
    if (use == WORLD_LAYERS_BUILD) {
        if (!world_layers_begin_build(&r->wlayers, i, k)) return false;
        world_draw_layers(&r->world, which, offset, f->cam_eye, !f->in_rtt, restore);
        double lo, hi;
        world_wet_band(&r->world, &lo, &hi);
        const unsigned *ms = world_layers_begin_pick(&r->wlayers, i);
        if (ms) {   /* multisampled: a point a pixel picked to read back */
            world_layer_view id = { { 1, 1 }, { 0, 0 }, k->samples };
            world_pick_band_points(&r->world, ms, &id, lo, hi, restore);
        }
        world_layers_end_build(&r->wlayers, i, k, lo, hi);
    }
    world_layer_view lv;
    const unsigned *tex = world_layers_textures(&r->wlayers, i, k, &lv);
    if (!tex) return false;
    GLint vp[4];
    glGetIntegerv(GL_VIEWPORT, vp);
    world_layer_band band;
    if (world_layers_band_begin(&r->wlayers, i, k, &lv, &band)) {
        /* every pixel's depth is the copy's: the test would fail the band's */
        if (k->depth_test) glDisable(GL_DEPTH_TEST);
        world_composite_layers(&r->world, f->t, f->cam_eye, tex, &lv, vp[0], vp[1], restore, &band);
        if (k->depth_test) glEnable(GL_DEPTH_TEST);
    } else {
        /* multisampled: the depth copied, the colour composed over it */
        bool copied = k->depth_test && world_layers_copy_depth(&r->wlayers, i, k, vp[0], vp[1]);
        if (copied) glDisable(GL_DEPTH_TEST);
        world_composite_layers(&r->world, f->t, f->cam_eye, tex, &lv, vp[0], vp[1], restore, NULL);
        if (copied) glEnable(GL_DEPTH_TEST);
        world_layers_keep_whole(&r->wlayers, i, k);
    }
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
    render_check_gl(r, f, i, NULL, NULL);   /* the world's own errors, reported before the copy looks */
    world_cache_store(&r->wcache, i, &k);
}

/* `World`: drawn, or, right after a Clear, copied from the static-world
 * cache when nothing it depends on has changed (world_cache.h). */
void render_draw_world(render *r, frame_state *f, int i) {
    const scene_state *s = &r->cur;
    const glib_cmd *c = &s->glib->cmds[i];
    const char *which = c->name[0] ? c->name : "all";
    float offset = render_exec_cmd_number(s, i, 0.0f);
    if (r->world_only) {
        /* a frame of its own size and time: the caches keep the window's frames' */
        f->clean = false;
        world_draw(&r->world, which, offset, f->t, f->cam_eye, !f->in_rtt, f->cur ? f->cur->gl : 0);
        return;
    }
    draw_world_cached(r, f, i, which, offset);
}

/* What water_deferred asks of the renderer for each of its programs: the
 * uniforms use_program (render_exec.c) gives the glib's program, and the
 * grid. */
typedef struct deferred_call {
    render *r;
    const frame_state *f;
    const prog *p;
} deferred_call;

static void deferred_upload(unsigned gl, void *user) {
    const deferred_call *c = user;
    prog_upload_to(c->p, gl, c->f->t, c->r->cur.set.timer_s);
    world_upload(&c->r->world, gl, c->f->t, c->f->eye);
    render_camera_upload(&c->f->cams, gl);
    GLint loc = glGetUniformLocation(gl, "uTargetSize");
    if (loc >= 0) {
        GLint vp[4];
        glGetIntegerv(GL_VIEWPORT, vp);
        glUniform2f(loc, (float)vp[2], (float)vp[3]);
    }
}

static void deferred_grid(int tangent_loc, void *user) {
    const deferred_call *c = user;
    world_draw_water(&c->r->world, tangent_loc);
}

/* The screen's water through water_deferred; false: draw it as before. */
static bool draw_water_deferred(render *r, const frame_state *f) {
    scene_state *s = &r->cur;
    if (f->in_rtt || !f->cur || f->cur < s->progs || f->cur >= s->progs + s->nprogs) return false;
    deferred_call c = { r, f, f->cur };
    water_deferred_calls calls = { deferred_upload, deferred_grid, &c, NULL };
    /* The spectrum ocean's normals are filtered by each pixel's footprint,
     * the derivatives of its rest point; deferred, a pixel beside a fold of
     * the choppy crests differences two parts of the surface: the ocean's
     * water error rose 1.1% (every pack; other wave sets within 0.05%) */
    if (r->world.active && r->world.w.waves.ocean)
        calls.keep_grid = "the spectrum ocean's filtered normals need the grid's own derivatives";
    return water_deferred_draw(&r->deferred, &s->progs[f->cur - s->progs], &calls);
}

/* `WaterSurface`: the world's water, or `points|mesh N` of it. */
void render_draw_water(render *r, const frame_state *f, const glib_cmd *c) {
    if (c->name[0]) {   /* "points" or "mesh" */
        draw_points(r, f, c);
        return;
    }
    /* the surface nearer than the near plane is still water: an eye a
     * few centimetres above it (scenes/hard/at_level.glib) saw the
     * bottom third of the frame through a hole the near plane cut;
     * depth clamping keeps it (what is behind the eye is still
     * clipped by the x and y planes) */
    glEnable(GL_DEPTH_CLAMP);
    if (!draw_water_deferred(r, f)) world_draw_water(&r->world, f->cur ? f->cur->tangent_loc : -1);
    glDisable(GL_DEPTH_CLAMP);
}
