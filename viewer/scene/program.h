/* program: which shader stages a glib Program links. glman's stage
 * commands (Vertex, TessControl, TessEvaluation, Geometry, Fragment) and
 * GSTAP set state that each later Program takes; this is the one place that
 * follows that state, for the renderer (gfx/render_load.c) and validation
 * (check/validate.c) alike. No GL. */
#ifndef TARN_PROGRAM_H
#define TARN_PROGRAM_H

#include <stdbool.h>
#include "glib.h"
#include "shader_src.h"

/* The stage state at a point of the glib. */
typedef struct program_stages {
    const glib_cmd *stage[SHADER_STAGE_COUNT];  /* the command naming each stage; NULL: unused */
    bool gstap;                                 /* a GSTAP came before */
} program_stages;

void program_stages_init(program_stages *st);

/* The stage a command kind names; SHADER_STAGE_COUNT for other commands. */
shader_stage program_stage_of(glib_cmd_kind kind);

/* Takes command c into the state: a stage command with a file sets its
 * stage, one without unsets it; GSTAP turns gstap on (for good, as in
 * glman). Other commands leave the state as it is. */
void program_stages_step(program_stages *st, const glib_cmd *c);

/* The stages in use, in pipeline order, into out; returns how many. */
int program_stage_list(const program_stages *st, shader_stage out[SHADER_STAGE_COUNT]);

/* The file of stage s, "" when unused. */
const char *program_stage_path(const program_stages *st, shader_stage s);

/* How to assemble stage s: its file, GSTAP, the defines and include dirs
 * given (pointers kept, not copied). */
shader_src_desc program_stage_desc(const program_stages *st, shader_stage s, const shader_define *defines,
                                   int ndefines, const char *const *include_dirs, int ninclude_dirs);

/* The input primitive a geometry shader of `program` (a Program command of
 * g) must declare for the draw it is used with, when its file does not: the
 * first draw after the Program, before the next Program. ObjAdj gives
 * triangles_adjacency, LinesAdjacency lines_adjacency, PointCloud and
 * JitterCloud points, a Wire* draw lines; anything else, or no draw,
 * triangles (glman set the primitive per program too, so one program
 * serves one kind of draw). The draw commands are matched by name so that
 * new ones need only a row in glib's table. */
shader_gs_input program_gs_input(const glib_scene *g, const glib_cmd *program);

#endif
