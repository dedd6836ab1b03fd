/* glib_world.c: the handlers of the commands that describe the world
 * and draw it (our extensions; docs/glib.md): Sun, Sky, Water, Terrain,
 * the waves, Object, Flow, and the pack's World, Camera, If, WaterSurface
 * (glib_internal.h; the rows of glib_table.c name them).
 *
 * These commands keep nnum = the numbers written: what is left out takes
 * the world model's default (ref_world_init), which lives in one place.
 * Here only the form is checked (numbers, whole numbers, counts); ranges
 * are repaired by scene_from_glib, with a message, so a slider-happy user
 * never loses the scene to one absurd value.
 */
#include "glib_internal.h"

#include <ctype.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

/* Sun, Sky, Water, WaterMesh, Wave*: numbers only, nnum as written. */
bool glib_h_world_nums(cmdctx *c, glib_cmd *cmd) {
    const cmd_spec *s = c->spec;
    if (!glib_nums_from(c, cmd, 0, s->args, s->nreq, s->nmax, s->name))
        return false;
    const double *n = cmd->num;
    int given = cmd->nnum;
    if (cmd->kind == GLIB_CMD_SUN && given != 3 && given != 6) {
        glib_cerr(c, "Sun: the irradiance needs 3 numbers (r g b), got %d: %s", given - 3, c->usage);
        return false;
    }
    if (cmd->kind == GLIB_CMD_SUN && n[0] == 0 && n[1] == 0 && n[2] == 0) {
        glib_cerr(c, "Sun: the direction is zero; write the direction towards the sun, e.g. Sun 0.4 0.8 -0.45");
        return false;
    }
    if (cmd->kind == GLIB_CMD_WATER && given > 2 && given != 5) {
        glib_cerr(c, "Water: the absorption needs 3 numbers (ar ag ab), got %d: %s", given - 2, c->usage);
        return false;
    }
    return true;
}

#define RES_RULE(s) { s, NULL, 'i', 0, 65536, 0 }

bool glib_h_terrain(cmdctx *c, glib_cmd *cmd) {
    static const keyword k[] = { { "flat", "flat", 0 }, { "lake", "lake", 1 }, { "slope", "slope", 2 },
                                 { "pool", "pool", 3 } };
    static const arg_rule rules[] = {
        { "half_size", NULL, 'r', 0, 0, 0 }, { "depth", NULL, 'r', 0, 0, 0 },
        { "shore_height_or_slope", NULL, 'r', 0, 0, 0 }, SEED_RULE("seed"), RES_RULE("res"),
    };
    const keyword *m = glib_mode_word(c, k, sizeof k / sizeof k[0], "flat, lake, slope or pool");
    if (!m)
        return false;
    snprintf(cmd->name, sizeof cmd->name, "%s", m->canon);
    return glib_nums_from(c, cmd, 1, rules, 0, 5, "Terrain");
}

bool glib_h_wave_ocean(cmdctx *c, glib_cmd *cmd) {
    static const keyword k[] = { { "phillips", "phillips", 1 }, { "jonswap", "jonswap", 2 },
                                 { "tma", "tma", 3 } };
    static const arg_rule rules[] = {
        { "wind_speed", "a wind speed in m/s", 'r', 0, 0, 0 }, { "wind_angle_deg", NULL, 'r', 0, 0, 0 },
        { "choppiness", NULL, 'r', 0, 0, 0 }, { "res", NULL, 'i', 0, 65536, 0 }, SEED_RULE("seed"),
        { "fetch", NULL, 'r', 0, 0, 0 }, { "depth", NULL, 'r', 0, 0, 0 },
        { "spreading", NULL, 'r', 0, 0, 0 }, { "amplitude", NULL, 'r', 0, 0, 0 },
    };
    const keyword *m = glib_mode_word(c, k, sizeof k / sizeof k[0], "phillips, jonswap or tma");
    if (!m)
        return false;
    snprintf(cmd->name, sizeof cmd->name, "%s", m->canon);
    return glib_nums_from(c, cmd, 1, rules, 1, 9, "WaveOcean");
}

/* Object mesh FILE x y z [rot_y_deg [scale [R G B]]] (issue #25): the
 * file resolved like Obj's, the numbers as written (nnum 3 to 8). */
static bool object_mesh(cmdctx *c, glib_cmd *cmd) {
    static const arg_rule rules[8] = {
        { "x", NULL, 'r', 0, 0, 0 }, { "y", NULL, 'r', 0, 0, 0 }, { "z", NULL, 'r', 0, 0, 0 },
        { "rot_y_deg", NULL, 'r', 0, 0, 0 }, { "scale", NULL, 'r', 0, 0, 0 },
        { "R", NULL, 'r', 0, 0, 0 }, { "G", NULL, 'r', 0, 0, 0 }, { "B", NULL, 'r', 0, 0, 0 },
    };
    snprintf(c->usage, sizeof c->usage, "Object mesh file.obj x y z [rot_y_deg [scale [R G B]]]");
    snprintf(cmd->name, sizeof cmd->name, "mesh");
    if (c->nwords < 2) {
        glib_cerr(c, "Object mesh needs a file: %s", c->usage);
        return false;
    }
    if (!glib_take_path(c, c->words[1], cmd->path))
        return false;
    if (!glib_nums_from(c, cmd, 2, rules, 3, 8, "Object mesh"))
        return false;
    if (cmd->nnum > 5 && cmd->nnum < 8) {
        glib_cerr(c, "Object mesh: the colour needs 3 numbers (R G B), got %d: %s", cmd->nnum - 5, c->usage);
        return false;
    }
    return true;
}

bool glib_h_object(cmdctx *c, glib_cmd *cmd) {
    static const keyword k[] = { { "sphere", "sphere", 7 }, { "box", "box", 9 },
                                 { "cylinder", "cylinder", 8 } };
    static const char *const syms[3][9] = {
        { "x", "y", "z", "r", "R", "G", "B" },
        { "x", "y", "z", "hx", "hy", "hz", "R", "G", "B" },
        { "x", "y", "z", "r", "h", "R", "G", "B" },
    };
    if (c->nwords >= 1 && strcasecmp(c->words[0], "mesh") == 0)
        return object_mesh(c, cmd);
    const keyword *m = glib_mode_word(c, k, sizeof k / sizeof k[0], "sphere, box, cylinder or mesh");
    if (!m)
        return false;
    int which = (int)(m - k), n = (int)m->value;
    arg_rule rules[9];
    char what[64], usage[96];
    size_t u = (size_t)snprintf(usage, sizeof usage, "Object %s", m->canon);
    for (int i = 0; i < n; i++) {
        rules[i] = (arg_rule){ syms[which][i], NULL, 'r', 0, 0, 0 };
        u += (size_t)snprintf(usage + u, sizeof usage - u, " %s", syms[which][i]);
    }
    snprintf(what, sizeof what, "Object %s", m->canon);
    snprintf(cmd->name, sizeof cmd->name, "%s", m->canon);
    snprintf(c->usage, sizeof c->usage, "%s", usage);   /* the usage of this kind */
    return glib_nums_from(c, cmd, 1, rules, n, n, what);
}

/* Flow: one term of the flow field (its velocities add), or the look of
 * the detail it carries; the numbers each kind takes, as Object's. */
bool glib_h_flow(cmdctx *c, glib_cmd *cmd) {
    static const keyword k[] = { { "current", "current", 2 }, { "vortex", "vortex", 4 },
                                 { "detail", "detail", 4 } };
    static const arg_rule rules[3][4] = {
        { { "vx", "a speed vx (m/s)", 'r', 0, 0, 0 }, { "vz", "a speed vz (m/s)", 'r', 0, 0, 0 } },
        { { "x", NULL, 'r', 0, 0, 0 }, { "z", NULL, 'r', 0, 0, 0 }, { "strength", "a speed (m/s)", 'r', 0, 0, 0 },
          { "radius", "a radius (m)", 'r', 0, 0, 0 } },
        { { "amplitude", "an amplitude (m)", 'r', 0, 0, 0 }, { "cell", NULL, 'r', 0, 0, 0 },
          { "period", NULL, 'r', 0, 0, 0 }, { "foam", NULL, 'r', 0, 0, 0 } },
    };
    static const char *const usages[3] = { "Flow current vx vz", "Flow vortex x z strength radius",
                                           "Flow detail amplitude [cell [period [foam]]]" };
    static const arg_rule scale_rule = { "scale", "a speed scale (m/s)", 'r', 0, 0, 0 };
    if (c->nwords >= 1 && strcasecmp(c->words[0], "texture") == 0) {   /* Flow texture file scale */
        snprintf(cmd->name, sizeof cmd->name, "texture");
        snprintf(c->usage, sizeof c->usage, "Flow texture file scale");
        if (c->nwords < 3) {
            glib_cerr(c, "Flow texture needs a file and a scale: %s", c->usage);
            return false;
        }
        return glib_take_path(c, c->words[1], cmd->path) && glib_nums_from(c, cmd, 2, &scale_rule, 1, 1, "Flow texture");
    }
    const keyword *m = glib_mode_word(c, k, sizeof k / sizeof k[0], "current, vortex, texture or detail");
    if (!m)
        return false;
    int which = (int)(m - k), n = (int)m->value;
    char what[32];
    snprintf(what, sizeof what, "Flow %s", m->canon);
    snprintf(cmd->name, sizeof cmd->name, "%s", m->canon);
    snprintf(c->usage, sizeof c->usage, "%s", usages[which]);
    return glib_nums_from(c, cmd, 1, rules[which], which == 2 ? 1 : n, n, what);
}

bool glib_h_world(cmdctx *c, glib_cmd *cmd) {
    static const arg_rule offset_rule = { "offset", "a clip offset", 'r', 0, 0, 0 };
    static const char *const modes[] = { "all", "above", "below" };
    snprintf(cmd->name, sizeof cmd->name, "all");
    if (c->nwords == 0)
        return true;
    size_t m = 0;
    while (m < 3 && strcasecmp(c->words[0], modes[m]) != 0)
        m++;
    if (m == 3) {
        glib_cerr(c, "World: unknown mode '%.40s': write World all|above|below [offset]", c->words[0]);
        return false;
    }
    snprintf(cmd->name, sizeof cmd->name, "%s", modes[m]);
    glib_warn_extra(c, 2, "");
    if (c->nwords < 2)
        return true;
    const char *w = c->words[1];
    if (isalpha((unsigned char)w[0]) || w[0] == '_') {   /* a float slider of the last Program */
        return glib_take_uniform_name(c, "World", w, cmd->arg, sizeof cmd->arg);
    }
    if (!glib_parse_arg(c, &offset_rule, w, &cmd->num[0]))
        return false;
    cmd->nnum = 1;
    return true;
}

/* Camera main|mirror|top|light [fov_scale | uniform] */
bool glib_h_camera(cmdctx *c, glib_cmd *cmd) {
    static const arg_rule scale_rule = { "fov_scale", "a field-of-view scale", 'p', 0, 0, 0 };
    static const char *const kinds[] = { "main", "wide", "mirror", "top", "light" };
    if (c->nwords < 1) {
        glib_cerr(c, "Camera needs main, wide, mirror, top or light: %s", c->usage);
        return false;
    }
    size_t k = 0;
    while (k < 5 && strcasecmp(c->words[0], kinds[k]) != 0)
        k++;
    if (k == 5) {
        glib_cerr(c, "Camera: unknown camera '%.40s': write main, wide, mirror, top or light", c->words[0]);
        return false;
    }
    snprintf(cmd->name, sizeof cmd->name, "%s", kinds[k]);
    glib_warn_extra(c, 2, "");
    if (c->nwords < 2)
        return true;
    const char *w = c->words[1];
    if (isalpha((unsigned char)w[0]) || w[0] == '_') {
        return glib_take_uniform_name(c, "Camera", w, cmd->arg, sizeof cmd->arg);
    }
    if (!glib_parse_arg(c, &scale_rule, w, &cmd->num[0]))
        return false;
    cmd->nnum = 1;
    return true;
}

/* If [not] NAME: a block the renderer skips while NAME is false */
bool glib_h_if(cmdctx *c, glib_cmd *cmd) {
    int w = 0;
    if (c->nwords >= 1 && strcasecmp(c->words[0], "not") == 0) {
        cmd->num[0] = 1;
        cmd->nnum = 1;
        w = 1;
    }
    if (c->nwords <= w) {
        glib_cerr(c, "If needs a condition: %s", c->usage);
        return false;
    }
    glib_warn_extra(c, w + 1, "");
    const char *name = c->words[w];
    if (!(isalpha((unsigned char)name[0]) || name[0] == '_') || strlen(name) >= sizeof cmd->name) {
        glib_cerr(c, "If: '%.40s' is not a condition: write a Define name, above_water, under_water or waves", name);
        return false;
    }
    snprintf(cmd->name, sizeof cmd->name, "%s", name);
    return true;
}

/* WaterSurface [points|mesh N|uniform] */
bool glib_h_water_surface(cmdctx *c, glib_cmd *cmd) {
    static const arg_rule n_rule = { "N", "a point count per side", 'i', 1, 4096, 0 };
    if (c->nwords == 0)
        return true;
    bool points = strcasecmp(c->words[0], "points") == 0, mesh = strcasecmp(c->words[0], "mesh") == 0;
    if (!(points || mesh) || c->nwords < 2) {
        glib_cerr(c, "WaterSurface: write WaterSurface, WaterSurface points N or WaterSurface mesh N");
        return false;
    }
    glib_warn_extra(c, 2, "");
    snprintf(cmd->name, sizeof cmd->name, "%s", points ? "points" : "mesh");
    if (glib_is_ident(c->words[1]))   /* N from a slider: `WaterSurface points uPhotonGrid` */
        return glib_take_uniform_name(c, "WaterSurface", c->words[1], cmd->arg, sizeof cmd->arg);
    if (!glib_parse_arg(c, &n_rule, c->words[1], &cmd->num[0]))
        return false;
    cmd->nnum = 1;
    return true;
}
