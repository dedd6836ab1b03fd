/* What the GL tests share: the headless context they run in (or the skip
 * when the machine has none), and the flat-colour program they draw with.
 * Header-only, like support.h; include it after gl_ctx.h. */
#ifndef TARN_TEST_GL_SUPPORT_H
#define TARN_TEST_GL_SUPPORT_H

#include <GL/gl.h>
#include <GL/glext.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "check.h"
#include "gl_ctx.h"
#include "ref_waves.h"
#include "render.h"
#include "render_world.h"
#include "shader_src.h"
#include "support.h"
#include "unif.h"

/* The test's exit code when it cannot run: ctest's SKIP_RETURN_CODE. */
#define GL_TEST_SKIP 77

/* A headless OpenGL context, or NULL after printing "skip: why" (the test
 * then returns GL_TEST_SKIP). */
static inline gl_ctx *gl_test_context(void) {
    char err[512];
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    if (!ctx) fprintf(stderr, "skip: %s\n", err);
    return ctx;
}

/* packs/common, tarn's shared GLSL (TARN_SOURCE_DIR from the environment
 * first: an installed copy's tests). */
static inline const char *gl_test_common_dir(void) {
    static char dir[1024];
    snprintf(dir, sizeof dir, "%s/packs/common", getenv("TARN_SOURCE_DIR") ? getenv("TARN_SOURCE_DIR") : TARN_SOURCE_DIR);
    return dir;
}

/* packs/common as the include dir and the world programs' dir, read from
 * disk: where a test's world, ocean, flow and spray programs come from. */
static inline const prog_sources *gl_test_sources(void) {
    static const char *inc[1];
    static prog_sources src;
    inc[0] = gl_test_common_dir();
    src = (prog_sources){ .include_dirs = inc, .ninclude_dirs = 1, .common_dir = inc[0] };
    return &src;
}

/* Whether the last frame ran a pass whose timer name holds `what` (the
 * passes a feature adds: "ocean", "flow advect", "spray draw"). */
static inline bool gl_test_has_pass(render *r, const char *what) {
    const char (*names)[GPU_TIMER_NAME];
    const double *ms;
    int n = render_pass_times(r, true, &names, &ms);
    for (int i = 0; i < n; i++)
        if (strstr(names[i], what)) return true;
    return false;
}

/* Builds gw (zeroed first) from desc with packs/common's shaders: what a
 * test of a world feature builds to look at the GL side alone. The build
 * log is printed (empty for a clean build); true when the world built. */
static inline bool gl_test_world_build(gpu_world *gw, const ref_world_desc *desc) {
    memset(gw, 0, sizeof *gw);
    diag_list log = { 0 };
    bool ok = world_build(gw, desc, gl_test_sources(), &log, NULL);
    diag_print(&log, stderr);
    diag_list_free(&log);
    return ok;
}

/* Compiles the shader file at path as a stage of type, its #include lines
 * resolved from packs/common (tarn's shared GLSL) and with the defines
 * given: what the wave tests compile waves.glsl with. 0 when it does not
 * compile, the log (mapped through #include to the files' lines) on
 * stderr. */
static inline GLuint gl_test_compile(GLenum type, const char *path, const shader_define *defs, int ndefs) {
    const char *inc[1] = { gl_test_common_dir() };
    shader_src src;
    shader_src_desc d = { .path = path, .stage = type == GL_VERTEX_SHADER ? SHADER_VERTEX : SHADER_FRAGMENT,
                          .defines = defs, .ndefines = ndefs, .include_dirs = inc, .ninclude_dirs = 1 };
    if (!shader_src_load(&d, &src)) {
        char line[DIAG_FILE_MAX + DIAG_TEXT_MAX + 32];
        diag_format(&src.error, line, sizeof line);
        fprintf(stderr, "%s\n", line);
        return 0;
    }
    GLuint sh = glCreateShader(type);
    const char *text = src.text;
    glShaderSource(sh, 1, &text, NULL);
    glCompileShader(sh);
    GLint ok;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096];
        glGetShaderInfoLog(sh, sizeof log, NULL, log);
        char *mapped = shader_src_map_log(&src, log);
        fprintf(stderr, "%s\n", mapped ? mapped : log);
        free(mapped);
        glDeleteShader(sh);
        sh = 0;
    }
    shader_src_free(&src);
    return sh;
}

/* Links a vertex and a fragment shader (and deletes them); 0 when either
 * is 0 or the link fails. */
static inline GLuint gl_test_link(GLuint vs, GLuint fs) {
    if (!vs || !fs) {
        if (vs) glDeleteShader(vs);
        if (fs) glDeleteShader(fs);
        return 0;
    }
    GLuint p = glCreateProgram();
    glAttachShader(p, vs);
    glAttachShader(p, fs);
    glLinkProgram(p);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) { glDeleteProgram(p); return 0; }
    return p;
}

/* Sets the wave set's uniforms (ref_waves_uniforms) in program p, as
 * render_world's world_upload does: what a test shader including
 * waves.glsl reads. */
static inline void gl_test_upload_waves(GLuint p, const ref_waves *w) {
    ref_waves_uniform u[REF_WAVES_UNIFORMS_MAX];
    int n = ref_waves_uniforms(w, u, REF_WAVES_UNIFORMS_MAX);
    for (int i = 0; i < n; i++) {
        GLint loc = glGetUniformLocation(p, u[i].name);
        if (loc < 0) continue;
        if (u[i].is_int) glUniform1i(loc, u[i].i);
        else if (u[i].is_uint) glUniform1uiv(loc, u[i].count, u[i].u);
        else if (u[i].comps == 4) glUniform4fv(loc, u[i].count, u[i].v);
        else if (u[i].comps == 3) glUniform3fv(loc, u[i].count, u[i].v);
        else glUniform1fv(loc, u[i].count, u[i].v);
    }
}

/* A program that draws the geometry in uniform vec4 uColor. */
static const char *const flat_vert =
    "#version 330 compatibility\n"
    "void main() { gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; }\n";

static const char *const flat_frag =
    "#version 330 compatibility\n"
    "uniform vec4 uColor;\n"
    "out vec4 fragColor;\n"
    "void main() { fragColor = uColor; }\n";

/* The entry `name` (a slider, colour, checkbox or Define) of Program
 * `program` of r's scene (NULL: of the first Program that has it), or NULL. */
static inline unif_entry *gl_test_uniform(render *r, const char *program, const char *name) {
    int n;
    unif_set *sets = render_uniforms(r, &n);
    for (int i = 0; i < n; i++) {
        if (program && strcmp(sets[i].program, program) != 0) continue;
        unif_entry *e = unif_find(&sets[i], name);
        if (e) return e;
    }
    return NULL;
}

/* A new renderer with the scratch folder's scene `glib` loaded; a failed
 * load is a failed check that prints the load's messages. */
static inline render *gl_test_load_scratch(const char *glib) {
    render *r = render_create(NULL);
    CHECK_MSG(render_load(r, scratch_path(glib)), "%s", render_messages(r));
    return r;
}

#endif
