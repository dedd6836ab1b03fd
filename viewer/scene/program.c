/* program.c: the stage state a glib Program links (program.h). */
#include "program.h"

#include <string.h>

void program_stages_init(program_stages *st) {
    memset(st, 0, sizeof *st);
}

shader_stage program_stage_of(glib_cmd_kind kind) {
    switch (kind) {
    case GLIB_CMD_VERTEX: return SHADER_VERTEX;
    case GLIB_CMD_TESS_CONTROL: return SHADER_TESS_CONTROL;
    case GLIB_CMD_TESS_EVALUATION: return SHADER_TESS_EVALUATION;
    case GLIB_CMD_GEOMETRY: return SHADER_GEOMETRY;
    case GLIB_CMD_FRAGMENT: return SHADER_FRAGMENT;
    default: return SHADER_STAGE_COUNT;
    }
}

void program_stages_step(program_stages *st, const glib_cmd *c) {
    if (c->kind == GLIB_CMD_GSTAP) {
        st->gstap = true;
        return;
    }
    shader_stage s = program_stage_of(c->kind);
    if (s != SHADER_STAGE_COUNT)
        st->stage[s] = c->path[0] ? c : NULL;   /* `Vertex` alone unsets the stage */
}

int program_stage_list(const program_stages *st, shader_stage out[SHADER_STAGE_COUNT]) {
    int n = 0;
    for (int s = 0; s < SHADER_STAGE_COUNT; s++)
        if (st->stage[s])
            out[n++] = (shader_stage)s;
    return n;
}

const char *program_stage_path(const program_stages *st, shader_stage s) {
    return (unsigned)s < SHADER_STAGE_COUNT && st->stage[s] ? st->stage[s]->path : "";
}

shader_src_desc program_stage_desc(const program_stages *st, shader_stage s, const shader_define *defines,
                                   int ndefines, const char *const *include_dirs, int ninclude_dirs) {
    shader_src_desc d = { .path = program_stage_path(st, s), .stage = s, .gstap = st->gstap,
                          .defines = defines, .ndefines = ndefines, .include_dirs = include_dirs,
                          .ninclude_dirs = ninclude_dirs };
    return d;
}
