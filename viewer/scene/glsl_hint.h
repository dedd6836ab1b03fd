/* glsl_hint: plain words for GLSL that NVIDIA accepted and the GLSL spec
 * (and so Mesa) forbids.
 *
 * glman course projects were written on NVIDIA machines, whose compiler
 * lets through code the spec rejects: `pow(vec2, float)`, writing to a
 * fragment shader's `in` variable, `return 1;` in a float function, a
 * `const` set from a uniform. Mesa's messages for these are correct but
 * terse. glsl_hint_annotate() reads a compiler log already mapped to
 * `file:line: error: message` (shader_src_map_log) and, after each message
 * it knows (and after the candidate lines Mesa lists under it), adds
 * `file:line: note: ...` saying what the line does that GLSL forbids and
 * how to write it portably. The compiler's own lines stay as they were.
 *
 * The patterns are Mesa's messages (checked against Mesa 22.3, llvmpipe);
 * the table of patterns and hints is in glsl_hint.c. No GL. */
#ifndef TARN_GLSL_HINT_H
#define TARN_GLSL_HINT_H

/* log: a mapped compiler log; source: the stage's text as compiled (to
 * see how a variable named in a message is declared, and the #version), or
 * NULL. Returns a heap string: log with the notes added. */
char *glsl_hint_annotate(const char *log, const char *source);

#endif
