#include "render_prog.h"
#include "util.h"
#include "contract.h"
#include "gl_ctx.h"
#include "glsl_fix.h"
#include "glsl_hint.h"
#include "mem.h"
#include "program.h"
#include "strbuf.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const GLenum stage_gl[SHADER_STAGE_COUNT] = {
    GL_VERTEX_SHADER, GL_TESS_CONTROL_SHADER, GL_TESS_EVALUATION_SHADER,
    GL_GEOMETRY_SHADER, GL_FRAGMENT_SHADER };

static char *gl_info_log(GLuint obj, bool is_program) {
    GLint len = 0;
    if (is_program) glGetProgramiv(obj, GL_INFO_LOG_LENGTH, &len);
    else glGetShaderiv(obj, GL_INFO_LOG_LENGTH, &len);
    char *s = mem_zalloc((size_t)(len > 0 ? len : 1) + 1);
    if (len > 0) {
        if (is_program) glGetProgramInfoLog(obj, len, NULL, s);
        else glGetShaderInfoLog(obj, len, NULL, s);
    }
    return s;
}

/* The defines to compile with: TARN_CPU_RASTER on a CPU rasteriser
 * (packs/common/loops.glsl), the program's fixed ones, the current values
 * of the Define entries. */
static int collect_defines(const prog *p, shader_define *out, int max) {
    int n = 0;
    if (gl_ctx_cpu_rasteriser() && n < max) out[n++] = (shader_define){ .name = "TARN_CPU_RASTER", .value = "1" };
    for (int k = 0; k < PROG_FIXED_MAX; k++)
        if (p->fixed[k].name[0] && n < max) out[n++] = p->fixed[k];
    for (int i = 0; i < p->unifs->n && n < max; i++) {
        const unif_entry *e = &p->unifs->entries[i];
        if (!e->is_define) continue;
        if (e->widget == UNIF_WIDGET_CHECKBOX && e->value[0] == 0.0f) continue;
        memset(&out[n], 0, sizeof out[n]);
        snprintf(out[n].name, sizeof out[n].name, "%s", e->name);
        unif_define_value(e, out[n].value, (int)sizeof out[n].value);
        n++;
    }
    return n;
}

static void set_deps(prog *p, shader_src *src, int nsrc) {
    for (int i = 0; i < p->ndeps; i++) free(p->deps[i]);
    free(p->deps);
    p->deps = NULL;
    p->ndeps = 0;
    int total = 0;
    for (int s = 0; s < nsrc; s++) total += src[s].nfiles;
    if (total == 0) return;
    p->deps = mem_zalloc((size_t)total * sizeof *p->deps);
    for (int s = 0; s < nsrc; s++)
        for (int f = 0; f < src[s].nfiles; f++) p->deps[p->ndeps++] = mem_strdup(src[s].files[f]);
}

void prog_origins_free(prog_origins *o) {
    free(o->o);
    memset(o, 0, sizeof *o);
}

/* Adds what stage st of p reported to dl, and in from that they came
 * from it: render_messages.c merges a line that several programs report
 * into one naming them all. */
static void add_from_stage(diag_list *dl, const diag_list *msgs, shader_stage st, const prog *p, prog_origins *from) {
    for (int i = 0; i < msgs->n; i++) {
        if (from) {
            from->o = mem_grow(from->o, &from->cap, from->n + 1, sizeof *from->o);
            prog_origin *o = &from->o[from->n++];
            o->d = dl->n;
            o->stage = st;
            snprintf(o->prog, sizeof o->prog, "%s", p->name);
        }
        diag_push(dl, &msgs->d[i]);
    }
}

/* Compiles text as a stage; 0 on failure, with the driver's log in *raw. */
static GLuint try_compile(shader_stage st, const char *text, char **raw) {
    GLuint sh = glCreateShader(stage_gl[st]);
    glShaderSource(sh, 1, &text, NULL);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (ok) return sh;
    *raw = gl_info_log(sh, false);
    glDeleteShader(sh);
    return 0;
}

/* Compiles one stage as written; when the driver rejects it for a
 * construct NVIDIA accepted, compiles glsl_fix's rewrite of what the log
 * names instead (src->text becomes it) and adds a warning per rewrite.
 * On failure adds the mapped log of the text as written, with hints. */
static GLuint compile_stage(const prog *p, shader_src *src, shader_stage st, diag_list *dl, prog_origins *from) {
    char *raw = NULL;
    GLuint sh = try_compile(st, src->text, &raw);
    if (sh) return sh;
    diag_list mapped = { 0 }, retry = { 0 }, notes = { 0 };
    shader_src_map_diags(src, raw, DIAG_NOTE, &mapped);
    const diag_list *cur = &mapped;   /* the log of the text last compiled */
    char *text = NULL;
    for (int tries = 0; tries < 4 && !sh; tries++) {
        char *fixed = glsl_fix_rewrite(src, st, text ? text : src->text, cur, &notes);
        if (!fixed) break;
        free(text);
        text = fixed;
        char *raw2 = NULL;
        sh = try_compile(st, text, &raw2);
        diag_list_free(&retry);
        shader_src_map_diags(src, raw2, DIAG_NOTE, &retry);
        cur = &retry;
        free(raw2);
    }
    diag_list_free(&retry);
    if (sh) {
        free(src->text);
        src->text = text;
        add_from_stage(dl, &notes, st, p, from);
    } else {
        free(text);
        /* what NVIDIA let through and Mesa does not, in plain words */
        glsl_hint_add(&mapped, 0, src->text);
        if (!mapped.n) diag_add(&mapped, DIAG_ERROR, src->nfiles ? src->files[0] : "?", 0, "compile failed");
        add_from_stage(dl, &mapped, st, p, from);
    }
    diag_list_free(&notes);
    diag_list_free(&mapped);
    free(raw);
    return sh;
}

/* Links the stages; on failure adds the error and the linker's log to dl
 * and keeps the log, as the driver wrote it, in *raw_out (NULL: not). */
static GLuint link_program(const prog *p, const GLuint *shaders, const shader_src *src, diag_list *dl,
                           char **raw_out) {
    GLuint prg = glCreateProgram();
    for (int s = 0; s < SHADER_STAGE_COUNT; s++)
        if (shaders[s]) glAttachShader(prg, shaders[s]);
    /* glman's Tangent attribute gets a fixed slot, away from gl_Vertex's 0. */
    glBindAttribLocation(prg, 6, "Tangent");
    glLinkProgram(prg);
    GLint ok = 0;
    glGetProgramiv(prg, GL_LINK_STATUS, &ok);
    if (!ok) {
        char *raw = gl_info_log(prg, true);
        int first = (int)strcspn(raw, "\n");
        diag_add(dl, DIAG_ERROR, p->cmd ? p->cmd->file : "?", p->cmd ? p->cmd->line : 0,
                 "program '%s' failed to link: %.*s", p->name, first, raw);
        if (raw[first]) diag_add_log(dl, DIAG_NOTE, raw + first + 1);   /* the linker's other lines */
        /* a uniform with one type in one stage and another in another: say which */
        const shader_src *srcs[SHADER_STAGE_COUNT];
        for (int s = 0; s < SHADER_STAGE_COUNT; s++) srcs[s] = shaders[s] ? &src[s] : NULL;
        glsl_fix_link_hint(raw, srcs, dl);
        if (raw_out) *raw_out = raw;
        else free(raw);
        glDeleteProgram(prg);
        return 0;
    }
    return prg;
}

static void keep_source(prog *p, const shader_src *src) {
    free(p->source);
    p->source = NULL;
    for (int s = 0; s < SHADER_STAGE_COUNT; s++)
        if (src[s].text) str_appendf(&p->source, "%s\n", src[s].text);
    free(p->vertex_text);
    free(p->fragment_text);
    p->vertex_text = src[SHADER_VERTEX].text ? mem_strdup(src[SHADER_VERTEX].text) : NULL;
    p->fragment_text = src[SHADER_FRAGMENT].text ? mem_strdup(src[SHADER_FRAGMENT].text) : NULL;
}

void prog_deferred_free(prog *p) {
    if (p->deferred.gbuffer) glDeleteProgram(p->deferred.gbuffer);
    if (p->deferred.shade) glDeleteProgram(p->deferred.shade);
    memset(&p->deferred, 0, sizeof p->deferred);
}

/* Is name a whole word of the program's source (declared, maybe compiled
 * out by a Define or unused)? */
static bool in_source(const prog *p, const char *name) {
    size_t n = strlen(name);
    for (const char *s = p->source; s && (s = strstr(s, name)) != NULL; s += n) {
        bool start = s == p->source || !(isalnum((unsigned char)s[-1]) || s[-1] == '_');
        bool end = !(isalnum((unsigned char)s[n]) || s[n] == '_');
        if (start && end) return true;
    }
    return false;
}

bool prog_build(prog *p, const prog_sources *sources, diag_list *dl, prog_origins *from) {
    shader_define defines[64];
    int ndefines = collect_defines(p, defines, 64);
    shader_src src[SHADER_STAGE_COUNT];
    memset(src, 0, sizeof src);
    bool ok = true, any = false;
    unsigned long long hash = HASH_FNV1A_BASIS;
    for (int s = 0; s < SHADER_STAGE_COUNT; s++) {
        if (!p->stage_path[s][0]) continue;
        any = true;
        shader_src_desc d = { .path = p->stage_path[s], .stage = (shader_stage)s,
            .gstap = p->gstap, .defines = defines, .ndefines = ndefines,
            .include_dirs = sources->include_dirs, .ninclude_dirs = sources->ninclude_dirs,
            .files = sources->files,
            .gs_input = program_gs_input(p->scene, p->cmd),
            .cpu_raster = gl_ctx_cpu_rasteriser() };
        if (!shader_src_load(&d, &src[s])) {
            diag_list e = { 0 };
            diag_push(&e, &src[s].error);
            add_from_stage(dl, &e, (shader_stage)s, p, from);
            diag_list_free(&e);
            ok = false;
            /* still watch the stage file so fixing it triggers a reload */
            if (!src[s].nfiles) {
                src[s].files = mem_alloc(sizeof *src[s].files);
                src[s].files[0] = mem_strdup(p->stage_path[s]);
                src[s].nfiles = 1;
            }
            continue;
        }
        hash = hash_fnv1a(hash, &src[s].hash, sizeof src[s].hash);
    }
    set_deps(p, src, SHADER_STAGE_COUNT);
    if (!any) {
        diag_add(dl, DIAG_ERROR, p->cmd ? p->cmd->file : "?", p->cmd ? p->cmd->line : 0,
                 "Program '%s' has no shader stage: name files with Vertex and Fragment before the Program line",
                 p->name);
        ok = false;
    }
    if (ok && p->good && p->gl && hash == p->hash) {   /* same text: keep the build */
        for (int s = 0; s < SHADER_STAGE_COUNT; s++) shader_src_free(&src[s]);
        return true;
    }
    GLuint shaders[SHADER_STAGE_COUNT] = {0};
    for (int s = 0; ok && s < SHADER_STAGE_COUNT; s++) {
        if (!p->stage_path[s][0]) continue;
        shaders[s] = compile_stage(p, &src[s], (shader_stage)s, dl, from);
        if (!shaders[s]) ok = false;
    }
    GLuint prg = 0;
    if (ok) {
        /* a flat fragment input over an output without flat (NVIDIA linked it): link the rewrite */
        char *link_raw = NULL;
        diag_list link_log = { 0 }, notes = { 0 };
        prg = link_program(p, shaders, src, &link_log, &link_raw);
        const shader_src *srcs[SHADER_STAGE_COUNT];
        for (int s = 0; s < SHADER_STAGE_COUNT; s++) srcs[s] = shaders[s] ? &src[s] : NULL;
        char *text = NULL;
        int st = prg ? -1 : glsl_fix_link_rewrite(link_raw, srcs, &text, &notes);
        free(link_raw);
        char *raw = NULL;
        GLuint sh = st >= 0 ? try_compile((shader_stage)st, text, &raw) : 0;
        free(raw);
        if (sh) {
            GLuint old = shaders[st];
            shaders[st] = sh;
            diag_list log2 = { 0 };
            prg = link_program(p, shaders, src, &log2, NULL);
            if (prg) {
                glDeleteShader(old);
                free(src[st].text);
                src[st].text = text;
                text = NULL;
                diag_list_free(&link_log);
                add_from_stage(dl, &notes, (shader_stage)st, p, from);
            } else {
                glDeleteShader(sh);
                shaders[st] = old;
            }
            diag_list_free(&log2);
        }
        for (int i = 0; i < link_log.n; i++) diag_push(dl, &link_log.d[i]);
        diag_list_free(&link_log);
        free(text);
        diag_list_free(&notes);
    }
    if (prg) keep_source(p, src);
    for (int s = 0; s < SHADER_STAGE_COUNT; s++) {
        if (shaders[s]) glDeleteShader(shaders[s]);
        shader_src_free(&src[s]);
    }
    if (!prg) { p->good = false; return false; }
    prog_deferred_free(p);   /* made from the build it replaces */
    if (p->gl) glDeleteProgram(p->gl);
    p->gl = prg;
    p->hash = hash;
    p->good = true;
    return true;
}

static unif_type map_gl_type(GLenum t) {
    switch (t) {
    case GL_FLOAT: return UNIF_FLOAT;
    case GL_FLOAT_VEC2: return UNIF_VEC2;
    case GL_FLOAT_VEC3: return UNIF_VEC3;
    case GL_FLOAT_VEC4: return UNIF_VEC4;
    case GL_INT: case GL_UNSIGNED_INT: return UNIF_INT;
    case GL_BOOL: return UNIF_BOOL;
    case GL_FLOAT_MAT3: return UNIF_MAT3;
    case GL_FLOAT_MAT4: return UNIF_MAT4;
    case GL_SAMPLER_1D: case GL_SAMPLER_2D: case GL_SAMPLER_3D: case GL_SAMPLER_CUBE:
    case GL_SAMPLER_2D_SHADOW: case GL_SAMPLER_2D_ARRAY: case GL_INT_SAMPLER_2D:
    case GL_UNSIGNED_INT_SAMPLER_2D: case GL_SAMPLER_2D_RECT: case GL_SAMPLER_CUBE_SHADOW:
        return UNIF_SAMPLER;
    default: return UNIF_TYPE_UNKNOWN;
    }
}

/* Which stages the linked build has (shaders stay attached after their
 * deletion), for the draws: tessellation takes patches, a geometry
 * shader its declared input. */
static void stages_of(prog *p) {
    GLuint sh[SHADER_STAGE_COUNT];
    GLsizei n = 0;
    glGetAttachedShaders(p->gl, SHADER_STAGE_COUNT, &n, sh);
    bool geom = false;
    for (GLsizei i = 0; i < n; i++) {
        GLint type = 0;
        glGetShaderiv(sh[i], GL_SHADER_TYPE, &type);
        p->tess = p->tess || type == GL_TESS_EVALUATION_SHADER;
        geom = geom || type == GL_GEOMETRY_SHADER;
    }
    GLint in = 0;
    if (geom) glGetProgramiv(p->gl, GL_GEOMETRY_INPUT_TYPE, &in);
    p->gs_input = (unsigned)in;
}

/* One active uniform of the program: tarn's own (Timer, FaceIndex, the
 * contract's), or a slider's shader type and location. */
static void introspect_uniform(prog *p, GLuint index) {
    char name[UNIF_NAME_MAX];
    GLint size = 0;
    GLenum type = 0;
    glGetActiveUniform(p->gl, index, sizeof name, NULL, &size, &type, name);
    if (strncmp(name, "gl_", 3) == 0) return;
    char *bracket = strstr(name, "[0]");
    if (bracket) *bracket = '\0';
    if (strchr(name, '.') || strchr(name, '[')) return;  /* struct members: not ours */
    GLint loc = glGetUniformLocation(p->gl, name);
    if (strcmp(name, "Timer") == 0) { p->timer_loc = loc; return; }
    if (strcmp(name, "FaceIndex") == 0) {   /* set by the Soccerball, face by face */
        p->face_index_loc = loc;
        p->face_index_int = type == GL_INT;
        return;
    }
    /* set by tarn (the pack contract's table): no slider */
    if (contract_is_camera_uniform(name) || (p->world_uniforms && contract_is_world_uniform(name))) return;
    unif_entry *e = unif_set_shader_type(p->unifs, name, map_gl_type(type), size, loc);
    if (!e || e->from_glib) return;
    /* glman's noise samplers live at fixed units */
    int unit = strcmp(name, "Noise2") == 0 ? 2 : strcmp(name, "Noise3") == 0 ? 3 : -1;
    if (e->type == UNIF_SAMPLER && unit >= 0) {
        e->value[0] = e->def[0] = (float)unit;
        /* an introspected sampler is not uploaded per frame (unif_uploadable):
         * set it in the program once, so a shader that declares Noise2 or
         * Noise3 reads glman's built-in noise without naming it anywhere */
        glProgramUniform1i(p->gl, loc, unit);
    }
}

/* A slider that glib commands read (a target's size, a field-of-view
 * scale) is in use though no shader declares it: an int or a float with
 * no location, so it has its widget and nothing is uploaded. */
static void keep_consumed_sliders(prog *p) {
    for (int i = 0; i < p->unifs->n; i++) {
        const unif_entry *e = &p->unifs->entries[i];
        bool is_count = false;
        if (e->is_define || !e->from_glib || e->in_shader || !glib_uniform_consumed(p->scene, e->name, &is_count))
            continue;
        char name[UNIF_NAME_MAX];
        snprintf(name, sizeof name, "%s", e->name);
        unif_set_shader_type(p->unifs, name, is_count ? UNIF_INT : UNIF_FLOAT, 1, -1);
    }
}

/* A glib uniform a Program's shaders should read: not a Define, not one
 * that glib commands consume. */
static bool glib_shader_uniform(const prog *p, const unif_entry *e) {
    return !e->is_define && e->from_glib && !glib_uniform_consumed(p->scene, e->name, NULL);
}

/* None of the glib's uniforms (two or more) declared at all: the glib and
 * the shaders no longer belong together (a black picture, in glman too):
 * one line that says so, not one warning a uniform. True where said. */
static bool warn_none_declared(const prog *p, diag_list *dl) {
    int nglib = 0, ndeclared = 0;
    for (int i = 0; i < p->unifs->n; i++) {
        const unif_entry *e = &p->unifs->entries[i];
        if (!glib_shader_uniform(p, e)) continue;
        nglib++;
        ndeclared += e->in_shader || in_source(p, e->name);
    }
    if (nglib < 2 || ndeclared > 0) return false;
    char names[256] = "", files[512] = "";
    int shown = 0;
    for (int i = 0; i < p->unifs->n; i++) {
        const unif_entry *e = &p->unifs->entries[i];
        if (!glib_shader_uniform(p, e)) continue;
        size_t l = strlen(names);
        if (shown == 6) { snprintf(names + l, sizeof names - l, ", ..."); break; }
        snprintf(names + l, sizeof names - l, "%s%s", shown ? ", " : "", e->name);
        shown++;
    }
    for (int st = 0; st < SHADER_STAGE_COUNT; st++) {
        if (!p->stage_path[st][0]) continue;
        const char *base = strrchr(p->stage_path[st], '/');
        size_t l = strlen(files);
        snprintf(files + l, sizeof files - l, "%s%s", l ? ", " : "", base ? base + 1 : p->stage_path[st]);
    }
    diag_add(dl, DIAG_WARNING, p->cmd && p->cmd->file ? p->cmd->file : "?", p->cmd ? p->cmd->line : 0,
             "none of the %d uniforms the glib gives Program '%s' (%s) is declared in its shaders (%s): "
             "do the glib and the shaders belong together?", nglib, p->name, names, files[0] ? files : "none");
    return true;
}

/* Each glib uniform the shaders do not declare (an inactive one, which
 * they do, has its summary line: prog_inactive_uniforms), and each written
 * as another type than declared (not uploaded). */
static void warn_unmatched(const prog *p, diag_list *dl, bool none_declared) {
    for (int i = 0; i < p->unifs->n && !none_declared; i++) {
        const unif_entry *e = &p->unifs->entries[i];
        if (e->is_define || !e->from_glib || e->in_shader || in_source(p, e->name)) continue;
        diag_add(dl, DIAG_WARNING, e->glib_file ? e->glib_file : "?", e->glib_line,
                 "uniform '%s' is not declared in program '%s' (a typo in the glib or the shader?)", e->name, p->name);
    }
    for (int i = 0; i < p->unifs->n; i++) {
        const unif_entry *e = &p->unifs->entries[i];
        const char *why = unif_type_mismatch(e);
        if (e->is_define || !e->from_glib || !e->in_shader || !why) continue;
        diag_add(dl, DIAG_WARNING, e->glib_file ? e->glib_file : "(glib)", e->glib_line,
                 "uniform '%s': %s, but the shader declares %s; it is not set", e->name, why, unif_type_name(e->type));
    }
}

void prog_introspect(prog *p, diag_list *dl) {
    for (int i = 0; i < p->unifs->n; i++) {
        p->unifs->entries[i].in_shader = false;
        p->unifs->entries[i].location = -1;
    }
    p->timer_loc = -1;
    p->tangent_loc = -1;
    p->face_index_loc = -1;
    p->tess = false;
    p->gs_input = 0;
    if (!p->gl) return;
    stages_of(p);
    GLint count = 0;
    glGetProgramiv(p->gl, GL_ACTIVE_UNIFORMS, &count);
    for (GLint i = 0; i < count; i++) introspect_uniform(p, (GLuint)i);
    keep_consumed_sliders(p);
    /* a program that failed to build runs its last good build: what that
     * lacks says nothing about the sources on disk, whose errors are the news */
    if (p->good) warn_unmatched(p, dl, warn_none_declared(p, dl));
    p->tangent_loc = glGetAttribLocation(p->gl, "Tangent");
}

int prog_inactive_uniforms(const prog *p, const unif_entry **found, int max) {
    int n = 0;
    if (!p->good || !p->unifs) return 0;   /* a failed build's slots say nothing of its sources */
    for (int i = 0; i < p->unifs->n; i++) {
        const unif_entry *e = &p->unifs->entries[i];
        if (e->is_define || !e->from_glib || e->in_shader || !in_source(p, e->name)) continue;
        if (found && n < max) found[n] = e;
        n++;
    }
    return n;
}

static void upload_entry(const unif_entry *e) {
    int n = e->array_len > 1 ? e->array_len : 1;
    int comp = unif_type_components(e->type);
    if (comp > 0 && n * comp > UNIF_MAX_COMPONENTS) n = UNIF_MAX_COMPONENTS / comp;  /* values hold 16 */
    int loc = e->location;
    switch (e->type) {
    case UNIF_FLOAT: glUniform1fv(loc, n, e->value); break;
    case UNIF_VEC2: glUniform2fv(loc, n, e->value); break;
    case UNIF_VEC3: glUniform3fv(loc, n, e->value); break;
    case UNIF_VEC4: glUniform4fv(loc, n, e->value); break;
    case UNIF_MAT3: glUniformMatrix3fv(loc, 1, GL_FALSE, e->value); break;
    case UNIF_MAT4: glUniformMatrix4fv(loc, 1, GL_FALSE, e->value); break;
    case UNIF_INT: case UNIF_BOOL: case UNIF_SAMPLER: {
        GLint iv[UNIF_MAX_COMPONENTS];
        if (n > UNIF_MAX_COMPONENTS) n = UNIF_MAX_COMPONENTS;
        for (int i = 0; i < n; i++) iv[i] = (GLint)lrintf(e->value[i]);
        glUniform1iv(loc, n, iv);
        break;
    }
    default: break;
    }
}

void prog_upload(const prog *p, double t, double timer_s) {
    for (int i = 0; i < p->unifs->n; i++) {
        const unif_entry *e = &p->unifs->entries[i];
        if (e->location < 0 || !unif_uploadable(e)) continue;
        upload_entry(e);
    }
    if (p->timer_loc >= 0) {
        double period = timer_s > 0 ? timer_s : 10.0;
        glUniform1f(p->timer_loc, (float)(fmod(t, period) / period));
    }
}

void prog_upload_to(const prog *p, unsigned gl, double t, double timer_s) {
    for (int i = 0; i < p->unifs->n; i++) {
        unif_entry e = p->unifs->entries[i];
        if (e.location < 0 || !unif_uploadable(&e)) continue;
        e.location = glGetUniformLocation(gl, e.name);
        if (e.location >= 0) upload_entry(&e);
    }
    GLint timer = glGetUniformLocation(gl, "Timer");
    if (p->timer_loc >= 0 && timer >= 0) {
        double period = timer_s > 0 ? timer_s : 10.0;
        glUniform1f(timer, (float)(fmod(t, period) / period));
    }
}

void prog_free(prog *p) {
    free(p->source);
    p->source = NULL;
    free(p->vertex_text);
    free(p->fragment_text);
    p->vertex_text = p->fragment_text = NULL;
    prog_deferred_free(p);
    if (p->gl) glDeleteProgram(p->gl);
    p->gl = 0;
    if (p->unifs) unif_set_free(p->unifs);
    for (int i = 0; i < p->ndeps; i++) free(p->deps[i]);
    free(p->deps);
    p->deps = NULL;
    p->ndeps = 0;
}
