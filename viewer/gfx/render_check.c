/* render_check: what a frame's drawing did wrong, said with the glib line
 * at fault: a GL error after a command (render.gl_check_each says when to
 * look), and a first picture of one colour while uniforms are unset. */
#include "util.h"
#include "render_internal.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"

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
void render_check_gl(render *r, const frame_state *f, int ci, const gpu_mesh *m, const render_res_draw *d) {
    GLenum e = glGetError();
    if (e == GL_NO_ERROR) return;
    for (int k = 0; k < 16 && glGetError() != GL_NO_ERROR; k++) {}
    const glib_cmd *c = &r->cur.glib->cmds[ci];
    const char *name = glib_cmd_name(c->kind);
    if (!m) {
        render_messages_draw_problem(r, ci, true, "%s: OpenGL failed here (%s); the rest of the scene is drawn", name,
                                     gl_error_name(e));
        return;
    }
    const char *prim = render_res_mesh_prim_name(m, d), *with = "";
    const prog *p = f->cur;
    if (p && p->gl && p->gs_input && !p->tess) {
        const char *want = gs_input_word(p->gs_input, &with);
        render_messages_draw_problem(r, ci, true, "%s drew nothing (%s): it draws %s but program '%s' has a geometry "
                                     "shader that takes %s (layout(%s) in); draw %s with it, or change the shader's "
                                     "layout; the rest of the scene is drawn",
                                     name, gl_error_name(e), prim, p->name, want, want, with);
        return;
    }
    render_messages_draw_problem(r, ci, true, "%s drew nothing (%s) as %s with program '%s': check that the program's "
                                 "stages fit what is drawn (a geometry shader's layout, tessellation stages); the rest "
                                 "of the scene is drawn", name, gl_error_name(e), prim, p ? p->name : "(none)");
}

/* After a frame checked once at its end: an error sends the next frame
 * through the checks after each command, which name the command (the
 * draw drew nothing either way; the rest of the frame is drawn). */
void render_check_frame_errors(render *r, const frame_state *f) {
    if (f->check_each) {
        r->gl_check_each = false;
        return;
    }
    if (glGetError() == GL_NO_ERROR) return;
    for (int k = 0; k < 16 && glGetError() != GL_NO_ERROR; k++) {}
    r->gl_check_each = true;
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
void render_check_flat_picture(render *r, unsigned fbo, int x, int y, int w, int h) {
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
    render_messages_draw_problem(r, ci, false, "the picture is one flat colour, and program '%s' uses %d uniform%s that "
                                 "the glib gives no value, so %s 0: %s; give %s a value in the Program line (e.g. %s "
                                 "<0. 1. 2.>)", p->name, most, most == 1 ? "" : "s",
                                 most == 1 ? "it stays" : "they stay", best, most == 1 ? "it" : "each", first);
}
