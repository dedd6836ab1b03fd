/* validate: `tarn validate`, shader checking with glslang, no GPU needed.
 *
 * Every Program of a .glib is compiled for every combination of its boolean
 * `Define` toggles (2^n, at most 2^9), each stage assembled by shader_src
 * exactly as the renderer assembles it, then linked, so an error that shows
 * only with FOO=1 is found before anyone ticks the box.
 *
 * glslang runs through its C interface with client and target NONE: it then
 * checks desktop GLSL as a driver does (with an OpenGL client it would apply
 * SPIR-V rules and demand layout(location) on every uniform). The profile
 * and version come from each shader's #version (glman's `#version 330
 * compatibility` when it has none), so compatibility shaders may use
 * gl_Vertex, gl_ModelViewMatrix and the rest.
 *
 * On top of glslang's link this checks what glslang's linker does not: a
 * later stage's input that the stage before does not write (a warning, as
 * in Mesa; an error for GLSL before 1.30, as in Mesa). It drops glslang's
 * spurious "Anonymous member name used for global variable" link error for
 * the compatibility built-ins (gl_TexCoord, gl_Color, ...) that glslang 12
 * reports whenever a 3.30 compatibility fragment shader reads them. A
 * compatibility geometry shader before 4.00 that writes gl_FrontColor,
 * gl_TexCoord and the like is checked as 4.00 compatibility, where glslang
 * first declares those outputs (GLSL 1.50 compatibility and Mesa have
 * them), its lines kept. Errors of GLSL that NVIDIA let through carry
 * glsl_hint's note, as in the renderer.
 */
#ifndef TARN_VALIDATE_H
#define TARN_VALIDATE_H

#include <stdbool.h>
#include <stdio.h>

#include "shader_src.h"

typedef struct validate_result {
    int nerrors;            /* distinct error messages printed */
    int nwarnings;
    int nstages;            /* stages per Program (not times combinations) plus loose stage files */
    int ncombinations;      /* Define combinations compiled, over all Programs */
    int nprograms;
} validate_result;

/* Compiles one assembled stage with glslang. Adds its messages, mapped to
 * the user's file:line, to out (NULL: not wanted). Returns true if it
 * compiles. */
bool validate_stage(const shader_src *src, shader_stage stage, diag_list *out);

/* `tarn validate [PATH...]`. Each PATH is a .glib, a pack directory (every
 * *.glib inside, recursively), a shader stage file (the stage from its
 * extension: .vert .vs .tesc .tese .geom .gs .frag .fs, or a .glsl with a
 * stage suffix such as water.frag.glsl; others are skipped with a warning)
 * or a directory of stage files. With no PATH: every .glib of every
 * <repo_root>/packs/NAME directory and of <repo_root>/scenes (recursively).
 * `#include` searches the including file's directory, then
 * <repo_root>/packs/common.
 *
 * Combinations: every combination of a Program's `Define NAME <true>`
 * toggles (the first 9; the rest at their defaults), then each
 * whole-number Define slider (`Define MODE <0 0 6>`) at its other values
 * with the toggles at their defaults: every value of a range of at most 8,
 * else its two ends (code under `#if MODE == 5` is compiled too).
 *
 * Prints each problem once as `file:line: error: message`, with
 * ` [with FOO=1 BAR=0]` (the first failing combination, a slider's value
 * first) when it has toggles and `(k of N combinations)` when it fails in
 * several, then the summary line
 * `validate: N programs, M stages, K combinations: E errors`.
 * Returns 0 if there were no errors, 1 otherwise. */
int validate_run(const char *const *paths, int npaths, const char *repo_root, FILE *out);

/* validate_run that also hands back the counts (res may be NULL). */
int validate_run_ex(const char *const *paths, int npaths, const char *repo_root, FILE *out,
                    validate_result *res);

#endif
