/* glsl_hint: plain words for GLSL that NVIDIA accepted and the GLSL spec
 * (and so Mesa) forbids.
 *
 * glman course projects were written on NVIDIA machines, whose compiler
 * lets through code the spec rejects: `pow(vec2, float)`, writing to a
 * fragment shader's `in` variable, `return 1;` in a float function, a
 * `const` set from a uniform. Mesa's messages for these are correct but
 * terse. glsl_hint_add() reads a compiler's messages as diags (mapped to
 * the user's files: shader_src_map_diags) and, after each error it knows
 * (and after the candidate lines Mesa lists under it), adds a note at the
 * same file:line saying what the line does that GLSL forbids and how to
 * write it portably. The compiler's own messages stay as they were.
 *
 * The patterns are Mesa's messages (checked against Mesa 22.3, llvmpipe);
 * the table of patterns and hints is in glsl_hint.c. No GL. */
#ifndef TARN_GLSL_HINT_H
#define TARN_GLSL_HINT_H

#include "diag.h"

/* l: diags whose entries from index from on are a compiler's messages;
 * source: the stage's text as compiled (to see how a variable named in a
 * message is declared, and the #version), or NULL. Inserts a DIAG_NOTE
 * after each error it has a hint for (after the indented candidate errors
 * that follow it). */
void glsl_hint_add(diag_list *l, int from, const char *source);

#endif
