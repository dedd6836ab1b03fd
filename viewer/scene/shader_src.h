/* shader_src: assembles the source text of one shader stage.
 *
 * It reads the stage file, resolves `#include "file"` and `#include <file>`
 * (relative to the including file first, then each include dir), inserts the
 * `Define` toggles and, for glman's GSTAP, the GSTAP names, and keeps
 * `#version` the first directive. Every original line keeps its number:
 * the text carries `#line LINE FILEINDEX` directives, and
 * shader_src_map_log() turns a compiler's info log back into
 * `file:line: message` lines.
 *
 * The assembled text, for a stage file with `#version` on line 1:
 *
 *     #version 330 compatibility            <- the file's own line
 *     #define FOO 1                         <- desc->defines, in order
 *     #define uModelViewMatrix gl_ModelViewMatrix   <- GSTAP (desc->gstap)
 *     ...
 *     #line 2 0                             <- the file's line 2 follows
 *     ...
 *     #line 100001 1                        <- an included file (index 1)
 *     ...
 *     #line 7 0                             <- back in the stage file
 *
 * Line numbers: lines of files[0] carry their real number. Lines of an
 * included file k >= 1 carry k * SHADER_SRC_LINE_BASE + line, as well as
 * the index k. The offset is there because Mesa (22.3, llvmpipe) reports
 * most semantic errors with source-string number 0 whatever `#line` said, so
 * the line number alone must tell the file; glslang and syntax errors on
 * Mesa do carry k. shader_src_map_log() undoes both.
 * `#line N` sets the number of the next line to N (GLSL >= 3.30 and ES) or
 * N + 1 (desktop GLSL before 3.30, which glslang and Mesa both follow); the
 * directives are written for the file's own #version.
 *
 * A file with no #version gets glman's default, `#version 330
 * compatibility`, with a comment saying so.
 *
 * glman-era GLSL that NVIDIA took and Mesa does not is rewritten, line for
 * line (messages keep the user's line numbers):
 * - a geometry shader written for GL_EXT_geometry_shader4: its `#extension`
 *   line goes; `gl_PositionIn[i]` becomes `gl_in[i].gl_Position` (and
 *   gl_TexCoordIn, gl_FrontColorIn, ... likewise), `gl_VerticesIn`
 *   `gl_in.length()`, `varying in` / `varying out` / `varying` `in` / `out` /
 *   `out`; a
 *   #version before 1.50 becomes `#version 150 compatibility`; without
 *   `layout(...) in;` / `layout(...) out;` the input primitive is
 *   desc->gs_input and the output a triangle_strip of
 *   SHADER_SRC_GS_MAX_VERTICES, inserted before the first line of code
 *   (after the file's #extension lines), then `#line` to renumber;
 * - `layout(binding = N)` before GLSL 4.20 enables
 *   GL_ARB_shading_language_420pack (NVIDIA allowed it from 3.30), and
 *   `layout(location = N) uniform` before 4.30
 *   GL_ARB_explicit_uniform_location;
 * - GSTAP's aColor exists in the fragment stage too (gl_Color).
 */
#ifndef TARN_SHADER_SRC_H
#define TARN_SHADER_SRC_H

#include <stdbool.h>
#include "diag.h"

typedef enum shader_stage {
    SHADER_VERTEX,
    SHADER_TESS_CONTROL,
    SHADER_TESS_EVALUATION,
    SHADER_GEOMETRY,
    SHADER_FRAGMENT,
    SHADER_STAGE_COUNT
} shader_stage;

/* The input primitive of a geometry shader, for one that does not say
 * (glman-era files set it from the program, not with `layout(...) in;`):
 * the draw the Program is used with decides it (program_gs_input). */
typedef enum shader_gs_input {
    SHADER_GS_IN_TRIANGLES = 0,         /* the default: glman's solids */
    SHADER_GS_IN_TRIANGLES_ADJACENCY,   /* ObjAdj */
    SHADER_GS_IN_LINES,                 /* the Wire variants */
    SHADER_GS_IN_LINES_ADJACENCY,       /* LinesAdjacency */
    SHADER_GS_IN_POINTS                 /* PointCloud, JitterCloud */
} shader_gs_input;

/* The output a geometry shader without `layout(...) out;` gets: glman set
 * it with glProgramParameteri, which GLSL 1.50 replaced by the layout.
 * 64 vertices: a vertex of gl_Position and three vec4 outputs (16
 * components) times 64 is 1024, GL's guaranteed minimum of
 * GL_MAX_GEOMETRY_TOTAL_OUTPUT_COMPONENTS, so the program links on every
 * driver; course shaders emit 3 to a few dozen vertices per primitive. */
#define SHADER_SRC_GS_MAX_VERTICES 64

/* One `#define NAME VALUE` line. value "" gives `#define NAME`; a true bool
 * toggle is best passed as "1" (so both `#ifdef FOO` and `#if FOO` work);
 * a false bool toggle is simply not passed. */
typedef struct shader_define {
    char name[64];
    char value[64];
} shader_define;

typedef struct shader_src_desc {
    const char *path;                   /* the stage file */
    shader_stage stage;
    bool gstap;                         /* insert the GSTAP names */
    const shader_define *defines;
    int ndefines;
    const char *const *include_dirs;    /* searched after the including file's dir */
    int ninclude_dirs;
    shader_gs_input gs_input;           /* SHADER_GEOMETRY only: when the file has no input layout */
    struct file_cache *files;           /* where the stage file and includes are read (file_cache.h);
                                         * NULL: from disk */
    bool cpu_raster;                    /* for llvmpipe: a fragment stage's main() starts with a
                                         * kill never taken (SHADER_SRC_UNREACHED_KILL, below) */
} shader_src_desc;

typedef struct shader_src {
    char *text;                 /* the assembled source (heap); NULL after a failure */
    char **files;               /* files[0] = the stage file, then includes in the
                                 * order first met; what the watcher should watch.
                                 * Also filled (with what was found) on failure. */
    int nfiles;
    unsigned long long hash;    /* FNV-1a 64 of text */
    diag error;                 /* on failure: the error, at the file:line it concerns */
} shader_src;

/* What desc->cpu_raster writes right after the `{` of a fragment stage's
 * main() (on that line: every line keeps its number). llvmpipe (Mesa 22.3)
 * compiles an opaque fragment shader's variant twice, a function for the
 * blocks on a primitive's edge and one for whole blocks; opaque is no
 * blending, no depth or stencil test, a full colour mask, one sample and no
 * kill in the shader: the full-screen passes (height maps, photons, FFTs,
 * copies). A kill the shader may do leaves one function, about half the
 * LLVM time of such a pass (the lake's world height map 200 -> 120 ms,
 * natural's photons 380 -> 125 ms cold; docs/benchmark.md, "One function a
 * shader"), frames as fast. gl_FragCoord.x is at least 0 (a pixel's
 * centre, or its corner with pixel_center_integer), so it is never taken;
 * a pass with a depth test still tests early (the kill only moves the
 * depth write after the shader). On a GPU a kill can cost early-Z: never
 * there. */
#define SHADER_SRC_UNREACHED_KILL " if (gl_FragCoord.x < -1.0) discard; /* tarn: one llvmpipe function */"

/* Lines of files[k], k >= 1, are numbered k * SHADER_SRC_LINE_BASE + line. */
#define SHADER_SRC_LINE_BASE 100000
#define SHADER_SRC_MAX_INCLUDE_DEPTH 32
#define SHADER_SRC_MAX_FILE_BYTES (8L << 20)   /* one stage file or include */

/* Assembles desc->path into *out (which it zeroes first). Returns false and
 * sets out->error (a DIAG_ERROR) on a missing or unreadable file (or one over 8 MiB), a
 * missing include, an include cycle, includes nested deeper than 32, a
 * `#version` after other code, or a define name that is not an identifier. Always call
 * shader_src_free() afterwards, whether it succeeded or not. */
bool shader_src_load(const shader_src_desc *desc, shader_src *out);
void shader_src_free(shader_src *s);

/* Rewrites a compiler's info log so that every message reads
 * `file:line: message`. Understands Mesa (`0:12(5): error: ...`), NVIDIA
 * (`0(12) : error C0000: ...`) and glslang/AMD (`ERROR: 0:12: ...`,
 * `WARNING: ...`, which become `file:12: error: ...` / `warning:`). Lines it
 * does not recognise, or whose file index is out of range, pass through
 * unchanged. Returns a heap string (never NULL unless out of memory). */
char *shader_src_map_log(const shader_src *s, const char *log);
/* The same mapping, into diags (diag_add_log reads each mapped line):
 * how tarn takes in a compiler's log. Lines of no shape it knows become
 * bare diags of severity sev, kept as the compiler wrote them. */
void shader_src_map_diags(const shader_src *s, const char *log, diag_severity sev, diag_list *out);

/* "vertex", "tess control", "tess evaluation", "geometry", "fragment". */
const char *shader_stage_name(shader_stage st);

/* The stage a file name implies: .vert .vs .tesc .tese .geom .gs .frag .fs,
 * or for .glsl a stage suffix before it (water.frag.glsl, water_vert.glsl,
 * water-fs.glsl). SHADER_STAGE_COUNT when it implies none. */
shader_stage shader_stage_from_path(const char *path);

/* text with its comments turned to blanks (newlines kept, so lines and
 * columns stay), for scanning GLSL without matching inside a comment. Heap. */
char *shader_src_blank_comments(const char *text);

/* Where the body of a `main ( [void] ) {` definition begins (just past its
 * brace) in t, text with its comments blanked: the next one from *from
 * (start with *from = t; it is moved past), or NULL when there is none. */
const char *shader_src_next_main_body(const char *t, const char **from);

#endif
