/* program.c: the stage state a glib Program links (program.h). */
#include "program.h"

#include <string.h>
#include <strings.h>

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

shader_gs_input program_gs_input(const glib_scene *g, const glib_cmd *program) {
    /* glman's draws and what they hand a geometry shader (a Wire variant:
     * lines); by name, so draws added to glib's table later need a row here
     * only when they are not triangles */
    static const struct { const char *name; shader_gs_input in; } draws[] = {
        { "ObjAdj", SHADER_GS_IN_TRIANGLES_ADJACENCY }, { "LinesAdjacency", SHADER_GS_IN_LINES_ADJACENCY },
        { "PointCloud", SHADER_GS_IN_POINTS }, { "JitterCloud", SHADER_GS_IN_POINTS },
        { "QuadXY", SHADER_GS_IN_TRIANGLES }, { "QuadXZ", SHADER_GS_IN_TRIANGLES },
        { "QuadYZ", SHADER_GS_IN_TRIANGLES }, { "Sphere", SHADER_GS_IN_TRIANGLES },
        { "Torus", SHADER_GS_IN_TRIANGLES }, { "Box", SHADER_GS_IN_TRIANGLES },
        { "Cylinder", SHADER_GS_IN_TRIANGLES }, { "Cone", SHADER_GS_IN_TRIANGLES },
        { "Teapot", SHADER_GS_IN_TRIANGLES }, { "Obj", SHADER_GS_IN_TRIANGLES },
        { "Triangles", SHADER_GS_IN_TRIANGLES }, { "DiskXY", SHADER_GS_IN_TRIANGLES },
        { "QuadBox", SHADER_GS_IN_TRIANGLES }, { "Soccerball", SHADER_GS_IN_TRIANGLES },
        { "WaterSurface", SHADER_GS_IN_TRIANGLES },
        { "Shp", SHADER_GS_IN_LINES },   /* shapefile polylines and polygon rings: line strips */
    };
    if (!g || !program || program < g->cmds || program >= g->cmds + g->ncmds) return SHADER_GS_IN_TRIANGLES;
    for (const glib_cmd *c = program + 1; c < g->cmds + g->ncmds && c->kind != GLIB_CMD_PROGRAM; c++) {
        const char *name = glib_cmd_name(c->kind);
        for (size_t i = 0; i < sizeof draws / sizeof draws[0]; i++) {
            if (strcasecmp(name, draws[i].name) != 0) continue;
            if (c->kind == GLIB_CMD_WATER_SURFACE && strcmp(c->name, "points") == 0) return SHADER_GS_IN_POINTS;
            return c->wire && draws[i].in == SHADER_GS_IN_TRIANGLES ? SHADER_GS_IN_LINES : draws[i].in;
        }
    }
    return SHADER_GS_IN_TRIANGLES;
}
