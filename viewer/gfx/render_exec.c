/* render_exec: one command of the glib run in a frame, as glman runs the
 * file: state and transforms, If blocks, cameras, programs, passes into
 * targets (RenderToTexture, RenderToTextureOnce), and the draws
 * (render_draw.c). */
#include "util.h"
#include "render_internal.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* glman's Noise2 and Noise3 are there for every shader without any
 * command: built once per project folder (whose cached .tex files win),
 * bound to units 2 and 3 before the scene's own textures, so a Noise2D or
 * a Texture2D on those units still takes over. Each is built at the first
 * frame after a load that has a program sampling its unit
 * (render_load.c's note_noise_units). */
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
        if (!r->noise[k].tex && s->samples_noise[k]) render_res_noise_builtin(r->files, dir, k == 1, &r->noise[k]);
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

/* What the frame's draws may sample, bound at its start. */
void render_exec_bind_textures(render *r) {
    bind_builtin_noise(r, &r->cur);
    bind_textures(&r->cur);
    world_bind_textures(&r->world);
}

/* The number a `Camera` (fov scale) or `World` (clip offset) command asks
 * for: the one written, else the current value of the named float uniform
 * of the Program before it, else def. */
float render_exec_cmd_number(const scene_state *s, int ci, float def) {
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

void render_exec_end_pass(frame_state *f) {
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
 * does not (World: render_draw_world, which looks first); other commands leave it. */
static void track_clean(frame_state *f, const glib_cmd *c) {
    if (c->kind == GLIB_CMD_CLEAR) {
        f->clean = true;
        glGetFloatv(GL_COLOR_CLEAR_VALUE, f->clean_rgba);
    } else if (render_res_is_geometry(c->kind) || c->kind == GLIB_CMD_GL_BEGIN || c->kind == GLIB_CMD_WATER_SURFACE ||
               c->kind == GLIB_CMD_SPLAT) {
        f->clean = false;
    }
}


/* render_set_draw_timing: an interval of its own for each drawing command */
static void mark_draw(render *r, const glib_cmd *c) {
    if (!render_res_writes_pixels(c->kind) || c->kind == GLIB_CMD_CLEAR) return;
    char name[GPU_TIMER_NAME];
    snprintf(name, sizeof name, "%s:%d", glib_cmd_name(c->kind), c->line);
    render_timing_mark_now(r, name);
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

/* Which passes a world-only frame draws: those into screen-sized targets
 * (caustic_tex draws its World into one and copies it to the screen);
 * not a RenderToTextureOnce block (kept for the real frames), nor a pass
 * of the water's own (a light's view, a mirror, photons). */
static bool world_only_pass(const scene_state *s, const glib_cmd *c) {
    if (c->kind != GLIB_CMD_RENDER_TO_TEXTURE || c->nnum == 0) return false;
    for (int k = 0; k < c->nnum; k++)
        if (!render_size_screen_unit(s, (int)c->num[k])) return false;
    return true;
}

/* One command's own words into h: kind, numbers, names (its file and
 * line aside: a comment added above it changes no picture). */
static uint64_t hash_cmd(uint64_t h, const glib_cmd *c) {
    h = hash_fnv1a(h, &c->kind, sizeof c->kind);
    h = hash_fnv1a(h, &c->wire, sizeof c->wire);
    h = hash_fnv1a(h, &c->nnum, sizeof c->nnum);
    h = hash_fnv1a(h, c->num, sizeof c->num[0] * (size_t)c->nnum);
    h = hash_fnv1a(h, c->name, strlen(c->name) + 1);
    h = hash_fnv1a(h, c->path, strlen(c->path) + 1);
    h = hash_fnv1a(h, c->arg, strlen(c->arg) + 1);
    return hash_fnv1a(h, &c->format, sizeof c->format);
}

/* What command i adds through its resource: a texture's or mesh's key
 * (its files' stamps), the bound program's texts for a draw that is not
 * the world's (the World is drawn with the world's own programs). */
static uint64_t hash_cmd_inputs(const scene_state *s, int i, int bound, uint64_t h) {
    const glib_cmd *c = &s->glib->cmds[i];
    int res = s->cmd_res[i];
    if (res >= 0 && render_res_is_texture(c->kind)) h = hash_fnv1a(h, s->texs[res].key, strlen(s->texs[res].key));
    else if (res >= 0 && render_res_is_geometry(c->kind))
        h = hash_fnv1a(h, s->meshes[res].key, strlen(s->meshes[res].key));
    bool own_program = c->kind != GLIB_CMD_WORLD && c->kind != GLIB_CMD_CLEAR;
    if (own_program && bound >= 0 && render_res_writes_pixels(c->kind))
        h = hash_fnv1a(h, &s->progs[bound].hash, sizeof s->progs[bound].hash);
    return h;
}

unsigned long long render_world_frame_inputs(const render *r) {
    const scene_state *s = &r->cur;
    if (!s->glib) return 0;
    uint64_t h = HASH_FNV1A_BASIS;
    h = hash_fnv1a(h, &r->world.builds, sizeof r->world.builds);
    unsigned long long progs = render_world_programs_hash(r);
    h = hash_fnv1a(h, &progs, sizeof progs);
    h = hash_fnv1a(h, &r->samples, sizeof r->samples);
    /* the commands render_frame_world_at runs (runs() below, If blocks
     * aside: a false one's words count too), up to the screen's water */
    bool in_rtt = false, skipping = false;
    int bound = -1;
    for (int i = 0; i < s->glib->ncmds; i++) {
        const glib_cmd *c = &s->glib->cmds[i];
        bool pass_cmd = c->kind == GLIB_CMD_RENDER_TO_TEXTURE || c->kind == GLIB_CMD_RENDER_TO_TEXTURE_ONCE;
        if (pass_cmd) {
            in_rtt = c->nnum > 0;
            skipping = in_rtt && !world_only_pass(s, c);
        }
        if (skipping) continue;
        if (c->kind == GLIB_CMD_WATER_SURFACE && !in_rtt) break;
        if (c->kind == GLIB_CMD_PROGRAM) bound = s->cmd_res[i];
        h = hash_cmd_inputs(s, i, bound, hash_cmd(h, c));
    }
    return h;
}

/* The screen as the scene left it before its water (the sharp world's
 * snapshot), and what a world-only frame stops at. */
static bool water_on_screen(const frame_state *f, const glib_cmd *c) {
    return c->kind == GLIB_CMD_WATER_SURFACE && !f->in_rtt;
}

/* Whether command c runs: not after a world-only frame's water, nor in a
 * false If, a block skipped or one a reload kept (whose commands run, but
 * none that writes pixels). The first WaterSurface on the screen takes
 * the world's snapshot on the way. */
static bool runs(render *r, frame_state *f, const glib_cmd *c) {
    if (r->world_only && f->water_reached) return false;
    if (skipped_by_if(r, f, c)) return false;
    bool pass_cmd = c->kind == GLIB_CMD_RENDER_TO_TEXTURE || c->kind == GLIB_CMD_RENDER_TO_TEXTURE_ONCE;
    if (f->skipping && !pass_cmd) return false;
    f->skipping = false;
    if (r->world_only && pass_cmd && c->nnum > 0 && !world_only_pass(&r->cur, c)) {
        f->skipping = true;   /* the block's pixels are not the screen's world */
        return false;
    }
    if (water_on_screen(f, c) && !f->water_reached) {
        f->water_reached = true;
        if (r->world_only) return false;
        world_snapshot_take(&r->snap, f->screen_fbo, f->x, f->y, f->w, f->h);
    }
    if (r->world_only && c->kind == GLIB_CMD_SPLAT) return false;
    if (pass_cmd) f->replaying = false;
    /* a kept block leaves the state (camera, program, transforms) a drawn one does */
    return !(f->replaying && render_res_writes_pixels(c->kind));
}

/* `RenderToTextureOnce` at command i: drawn at full detail on the first
 * frame after a load, skipped after; replayed without its pixels when a
 * reload changed nothing it draws from (render_once.c). */
static void begin_once(render *r, frame_state *f, int i) {
    scene_state *s = &r->cur;
    const glib_cmd *c = &s->glib->cmds[i];
    if (s->once_done[i] || c->nnum == 0) { f->skipping = true; return; }
    s->once_done[i] = true;
    s->once_sig[i] = render_once_signature(r, f, i);
    f->replaying = render_once_kept(r, f, s->once_sig[i]);   /* a reload that changed none of it */
    f->once_drawn = f->once_drawn || !f->replaying;
    f->in_once = true;
    world_set_detail(&r->world, 1.0);
    render_timing_mark_pass(r, c);
    leave_target(f);
    begin_rtt(r, c);
    f->in_rtt = true;
    upload_target_size(f);
}

/* `RenderToTexture u1 u2 ...` begins a pass; with no unit, back to the
 * screen. Either ends a RenderToTextureOnce block. */
static void begin_pass(render *r, frame_state *f, const glib_cmd *c) {
    if (f->in_once) world_set_detail(&r->world, r->detail);
    f->in_once = false;
    render_timing_mark_pass(r, c);
    if (c->nnum > 0) { leave_target(f); begin_rtt(r, c); f->in_rtt = true; }
    else render_exec_end_pass(f);
    upload_target_size(f);
}

/* `Camera NAME`: its matrices loaded, its eye the sky box's centre. */
static void use_camera(frame_state *f, const glib_cmd *c) {
    int k = render_camera_kind_from_name(c->name);
    if (k < 0) return;
    render_camera_load(&f->cams, k);
    f->cam_kind = k;
    render_camera_eye(&f->cam_in, k, f->cam_eye);
}

/* `Program NAME`: bound, with its uniforms, the world's and the cameras'. */
static void use_program(render *r, frame_state *f, int res) {
    const scene_state *s = &r->cur;
    f->cur = res >= 0 ? &s->progs[res] : NULL;
    glUseProgram(f->cur ? f->cur->gl : 0);
    if (!f->cur || !f->cur->gl) return;
    prog_upload(f->cur, f->t, s->set.timer_s);
    world_upload(&r->world, f->cur->gl, f->t, f->eye);
    render_camera_upload(&f->cams, f->cur->gl);
    upload_target_size(f);
}

static void exec_cmd(render *r, frame_state *f, int i) {
    scene_state *s = &r->cur;
    const glib_cmd *c = &s->glib->cmds[i];
    int res = s->cmd_res[i];
    if (!runs(r, f, c)) return;
    track_clean(f, c);
    if (c->kind == GLIB_CMD_RENDER_TO_TEXTURE_ONCE) begin_once(r, f, i);
    else if (c->kind == GLIB_CMD_CAMERA) use_camera(f, c);
    else if (c->kind == GLIB_CMD_SPLAT) render_splat(r, (int)c->num[0], (int)c->num[1]);
    else if (render_res_is_geometry(c->kind) || c->kind == GLIB_CMD_GL_BEGIN) {
        if (res >= 0) render_draw_mesh(r, f, i, &s->meshes[res]);
    } else if (c->kind == GLIB_CMD_NUM_PATCH_VERTICES) {
        f->patch_vertices = (int)c->num[0];
        f->patch_cmd = i;
    } else if (c->kind == GLIB_CMD_PROGRAM) use_program(r, f, res);
    else if (c->kind == GLIB_CMD_WORLD) render_draw_world(r, f, i);
    else if (c->kind == GLIB_CMD_WATER_SURFACE) render_draw_water(r, f, c);
    else if (c->kind == GLIB_CMD_RENDER_TO_TEXTURE) begin_pass(r, f, c);
    else if (render_res_is_texture(c->kind)) {
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

/* Every command of the scene, each checked for GL errors where the frame
 * looks after each. */
void render_exec_commands(render *r, frame_state *f) {
    const glib_scene *g = r->cur.glib;
    for (int i = 0; i < g->ncmds; i++) {
        if (r->draw_timing) mark_draw(r, &g->cmds[i]);
        exec_cmd(r, f, i);
        if (f->check_each) render_check_gl(r, f, i, NULL, NULL);   /* after a draw, render_draw_mesh has checked */
    }
    if (r->draw_timing) render_timing_mark_now(r, "screen");   /* the last draw's pixels in its own interval */
}
