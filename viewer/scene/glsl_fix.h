/* glsl_fix: run the GLSL that NVIDIA accepted and the spec (and Mesa)
 * rejects, by rewriting the construct the compiler named.
 *
 * glman course projects were written on NVIDIA machines. A stage is
 * always compiled as written first; only when the compiler rejects it
 * does the caller (render_prog.c's compile_stage, validate.c's compile)
 * hand glsl_fix_rewrite() the assembled text and the compiler's messages
 * as diags at the user's file:line (shader_src_map_diags). For each
 * message it knows it rewrites that construct, and only that one:
 *
 * - `return 0;` in a float (or vecN, intN) function: `return float(0);`
 *   (the returned expression wrapped in the function's return type);
 * - a `const` whose initialiser is not constant: the word const goes;
 * - a write to a shader input (`vST = ...`): a global copy `tarn_vST`,
 *   set from the input at the start of main(), stands for it everywhere;
 * - `pow(vec2, float)` and likewise atan, mod, min, max, step: the call
 *   becomes `tarn_pow(...)`, an overload set defined before the function
 *   that widens the scalar (the compiler picks the overload: no guessing
 *   of types);
 * - `flat varying` (any interpolation qualifier on `varying`): `flat in`
 *   in a fragment shader, `flat out` in a vertex shader;
 * - a fragment shader that writes gl_FragColor (or gl_FragData) and
 *   declares `out` variables: the outs become plain globals.
 *
 * Every rewrite stays on its line (nothing adds or removes a newline), so
 * the text's `#line` mapping still names the user's file:line. The caller
 * compiles the result again; a rewrite that does not help is not kept.
 *
 * glsl_fix_link_hint() explains, with both declarations' file:line, a link
 * that fails because a uniform has one type in one stage and another in
 * another (not rewritten: which type the shader means is not clear).
 * Pure C, no GL. */
#ifndef TARN_GLSL_FIX_H
#define TARN_GLSL_FIX_H

#include "shader_src.h"

/* text: the stage's assembled text (src->text or an earlier rewrite of
 * it); src gives the file names its #line directives number. log: the
 * failed compile's messages, mapped (its errors and warnings are read).
 * Returns the rewritten text (heap), or NULL when no message named a
 * construct it can rewrite or the rewrite changed nothing. Adds one
 * DIAG_WARNING per rewrite, at the rewritten line, to notes (NULL: none). */
char *glsl_fix_rewrite(const shader_src *src, shader_stage stage, const char *text, const diag_list *log,
                       diag_list *notes);

/* Does a message of log ask for a rewrite although the compiler accepted
 * the text? glslang only warns about `return 1;` in a float function,
 * which Mesa rejects. */
bool glsl_fix_wanted_by_warning(const diag_list *log);

/* log: a failed link's log, as the linker wrote it (Mesa's or glslang's:
 * it names no file:line to map); stage texts (NULL for stages a program
 * lacks) with their sources. Adds a DIAG_NOTE at the first declaration per
 * uniform declared with two types to notes; false when there is none. */
bool glsl_fix_link_hint(const char *log, const shader_src *const srcs[SHADER_STAGE_COUNT], diag_list *notes);

/* log: a failed link's log. When it says a fragment shader's input is
 * flat and the stage before writes it without `flat` (GLSL 4.30 and
 * NVIDIA: the fragment shader's qualifier decides), rewrites that output's
 * declaration as `flat out`: returns the stage rewritten, its new text in
 * *text (heap) and a DIAG_WARNING in notes (NULL: none); -1 when the log
 * asks for nothing. */
int glsl_fix_link_rewrite(const char *log, const shader_src *const srcs[SHADER_STAGE_COUNT], char **text,
                          diag_list *notes);

#endif
