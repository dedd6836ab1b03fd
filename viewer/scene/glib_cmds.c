/* glib_cmds.c: the handlers of glman's commands (glib_internal.h; the
 * rows of glib_table.c name them): numbers only (viewing, transforms,
 * geometry, colours), files, shaders, textures, passes, immediate mode
 * (glBegin ... glEnd), and the GL state keywords.
 */
#include "glib_internal.h"
#include "mem.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

/* ------------------------------------------------------------------ */
/* numbers only                                                       */

static bool same3(const double *a, const double *b) {
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

/* Arguments that are each fine but together make a singular matrix: these
 * would draw nothing (NaN) with no hint why. */
static bool check_degenerate(cmdctx *c, glib_cmd *cmd) {
    const double *n = cmd->num;
    switch (cmd->kind) {
    case GLIB_CMD_PERSPECTIVE:
        if (n[1] >= n[2]) {
            glib_cerr(c, "Perspective: near (%g) must be less than far (%g)", n[1], n[2]);
            return false;
        }
        return true;
    case GLIB_CMD_ORTHO:
        if (n[0] == n[1] || n[2] == n[3] || n[4] == n[5]) {
            glib_cerr(c, "Ortho: left/right, bottom/top and near/far must differ: %s", c->usage);
            return false;
        }
        return true;
    case GLIB_CMD_LOOKAT: {
        double d[3] = { n[3] - n[0], n[4] - n[1], n[5] - n[2] };
        double x[3] = { d[1] * n[8] - d[2] * n[7], d[2] * n[6] - d[0] * n[8],
                        d[0] * n[7] - d[1] * n[6] };
        if (same3(n, n + 3)) {
            glib_cerr(c, "LookAt: the eye and the point looked at are the same");
            return false;
        }
        if (x[0] == 0 && x[1] == 0 && x[2] == 0) {
            glib_cerr(c, "LookAt: the up vector is zero or along the line of sight; use e.g. 0 1 0");
            return false;
        }
        return true;
    }
    case GLIB_CMD_ROTATE:
        if (n[1] == 0 && n[2] == 0 && n[3] == 0) {
            glib_cerr(c, "Rotate: the axis is zero: Rotate deg ax ay az, e.g. Rotate 90 0 1 0");
            return false;
        }
        return true;
    default:
        return true;
    }
}

/* Scale and Box take one number for all three axes or all three. */
static bool one_or_three(cmdctx *c, glib_cmd *cmd, int given) {
    if (given == 2) {
        glib_cerr(c, "%s takes 1 number or 3, not 2: %s", c->spec->name, c->usage);
        return false;
    }
    if (given == 1)
        cmd->num[1] = cmd->num[2] = cmd->num[0];
    if (cmd->kind == GLIB_CMD_SCALE)
        cmd->nnum = given;      /* glib.h: nnum 1 or 3 */
    return true;
}

/* Commands whose arguments are numbers only. Optional ones get their
 * defaults, so nnum is always the full count (but Scale, see above). */
bool glib_h_nums(cmdctx *c, glib_cmd *cmd) {
    const cmd_spec *s = c->spec;
    if (c->nwords < s->nreq) {
        glib_missing_args(c, c->nwords);
        return false;
    }
    glib_warn_extra(c, s->nmax, "");
    int given = c->nwords < s->nmax ? c->nwords : s->nmax;
    for (int i = 0; i < given; i++)
        if (!glib_parse_arg(c, &s->args[i], c->words[i], &cmd->num[i]))
            return false;
    for (int i = given; i < s->nmax; i++)
        cmd->num[i] = s->args[i].def;
    cmd->nnum = s->nmax;
    if (cmd->kind == GLIB_CMD_SCALE || cmd->kind == GLIB_CMD_BOX)
        return one_or_three(c, cmd, given);
    if (cmd->kind == GLIB_CMD_TRANSLATE && given > 0 && given < 3)
        glib_cwarn(c, "Translate has %d number%s; glman fills the missing ones with 0 (Translate %g %g %g): write "
              "all three", given, given == 1 ? "" : "s", cmd->num[0], cmd->num[1], cmd->num[2]);
    return check_degenerate(c, cmd);
}

/* ------------------------------------------------------------------ */
/* files, shaders, textures, passes                                   */

static const arg_rule unit_rule = { "unit", "a texture unit", 'i', 0, LIM_UNIT, 0 };

bool glib_h_stage(cmdctx *c, glib_cmd *cmd) {
    glib_warn_extra(c, 1, path_hint);
    if (c->nwords == 0)
        return true;            /* no file: unset the stage */
    return glib_take_path(c, c->words[0], cmd->path);
}

bool glib_h_obj(cmdctx *c, glib_cmd *cmd) {
    if (c->nwords < 1) {
        glib_cerr(c, "%s needs a file: %s", c->spec->name, c->usage);
        return false;
    }
    glib_warn_extra(c, 1, path_hint);
    return glib_take_path(c, c->words[0], cmd->path);
}

static bool parse_format(cmdctx *c, const char *w, glib_target_format *f) {
    static const struct { const char *word; glib_target_format f; } formats[] = {
        { "float", GLIB_TARGET_RGBA32F }, { "float32", GLIB_TARGET_RGBA32F },
        { "float16", GLIB_TARGET_RGBA16F }, { "half", GLIB_TARGET_RGBA16F },
        { "depth", GLIB_TARGET_DEPTH }, { "rgba8", GLIB_TARGET_RGBA8 },
    };
    for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++)
        if (strcasecmp(w, formats[i].word) == 0)
            return *f = formats[i].f, true;
    glib_cerr(c, "Texture2D: unknown format '%.40s': write float, float16 or depth, or nothing for 8-bit RGBA",
         w);
    return false;
}

static bool parse_sizes(cmdctx *c, glib_cmd *cmd, int count, double max) {
    static const char *const syms[] = { "w", "h", "d" };
    for (int i = 0; i < count; i++) {
        arg_rule r = { syms[i], NULL, 'i', 1, max, 0 };
        if (!glib_parse_arg(c, &r, c->words[1 + i], &cmd->num[1 + i]))
            return false;
    }
    cmd->nnum = 1 + count;
    return true;
}

/* The w and h of an empty Texture2D: each a number, or the name of a
 * slider of a Program of this glib (kept in cmd->name and cmd->arg; the
 * renderer sizes the target from the slider's value, num 0 until then). */
static bool parse_target_size(cmdctx *c, glib_cmd *cmd) {
    static const char *const syms[] = { "w", "h" };
    char *names[] = { cmd->name, cmd->arg };
    for (int i = 0; i < 2; i++) {
        const char *w = c->words[1 + i];
        if (glib_is_ident(w)) {
            if (!glib_take_uniform_name(c, "Texture2D", w, names[i], GLIB_NAME_MAX))
                return false;
            cmd->num[1 + i] = 0;
            continue;
        }
        arg_rule r = { syms[i], NULL, 'i', 1, 16384, 0 };
        if (!glib_parse_arg(c, &r, w, &cmd->num[1 + i]))
            return false;
    }
    cmd->nnum = 3;
    return true;
}

/* Texture2D unit file | Texture2D unit w h [format]: a size after the
 * unit means an empty render target. */
bool h_tex2d(cmdctx *c, glib_cmd *cmd) {
    if (c->nwords < 2) {
        glib_cerr(c, "Texture2D needs a unit and a file, or a unit and a size: %s", c->usage);
        return false;
    }
    if (!glib_parse_arg(c, &unit_rule, c->words[0], &cmd->num[0]))
        return false;
    cmd->nnum = 1;
    if (c->words[1][0] == '@') {       /* a texture tarn generates: not a file */
        glib_warn_extra(c, 2, "");
        static const char *const known[] = { "@caustics", "@foam", "@water_normal", "@terrain_normal" };
        for (size_t i = 0; i < sizeof known / sizeof known[0]; i++)
            if (strcmp(c->words[1], known[i]) == 0) {
                snprintf(cmd->path, sizeof cmd->path, "%s", known[i]);
                return true;
            }
        glib_cerr(c, "Texture2D: unknown generated texture '%.40s': write @caustics, @foam, "
                "@water_normal or @terrain_normal", c->words[1]);
        return false;
    }
    /* a size is a number or the name of a slider (`Texture2D 4 uRes uRes`);
     * a single word that is no number is a file */
    bool sized = glib_is_decimal(c->words[1]) ||
                 (c->nwords >= 3 && glib_is_ident(c->words[1]) && (glib_is_ident(c->words[2]) || glib_is_decimal(c->words[2])));
    if (!sized) {
        glib_warn_extra(c, 2, path_hint);
        return glib_take_path(c, c->words[1], cmd->path);
    }
    if (c->nwords < 3) {
        glib_cerr(c, "Texture2D: an empty texture needs a width and a height: %s", c->usage);
        return false;
    }
    cmd->kind = GLIB_CMD_TEXTURE2D_EMPTY;
    glib_warn_extra(c, 4, "");
    if (!parse_target_size(c, cmd))
        return false;
    return c->nwords < 4 || parse_format(c, c->words[3], &cmd->format);
}

bool h_tex3d(cmdctx *c, glib_cmd *cmd) {
    if (c->nwords < 2) {
        glib_cerr(c, "Texture3D needs a unit and a file, or a unit and a size: %s", c->usage);
        return false;
    }
    if (!glib_parse_arg(c, &unit_rule, c->words[0], &cmd->num[0]))
        return false;
    cmd->nnum = 1;
    if (!glib_is_decimal(c->words[1])) {
        glib_warn_extra(c, 2, path_hint);
        return glib_take_path(c, c->words[1], cmd->path);
    }
    if (c->nwords < 4) {
        glib_cerr(c, "Texture3D: an empty texture needs a width, a height and a depth: %s", c->usage);
        return false;
    }
    glib_warn_extra(c, 4, "");
    return parse_sizes(c, cmd, 3, 2048);
}

bool glib_h_cube(cmdctx *c, glib_cmd *cmd) {
    if (c->nwords < 7) {
        glib_cerr(c, "CubeMap needs a unit and 6 files, got %d file%s: %s",
             c->nwords ? c->nwords - 1 : 0, c->nwords == 2 ? "" : "s", c->usage);
        return false;
    }
    glib_warn_extra(c, 7, path_hint);
    if (!glib_parse_arg(c, &unit_rule, c->words[0], &cmd->num[0]))
        return false;
    cmd->nnum = 1;
    cmd->cube_paths = mem_alloc(6 * sizeof *cmd->cube_paths);
    for (int i = 0; i < 6; i++)
        if (!glib_take_path(c, c->words[1 + i], cmd->cube_paths[i]))
            return false;
    return true;
}

bool glib_h_rtt(cmdctx *c, glib_cmd *cmd) {
    glib_warn_extra(c, GLIB_MAX_UNITS, "");
    int n = c->nwords < GLIB_MAX_UNITS ? c->nwords : GLIB_MAX_UNITS;
    for (int i = 0; i < n; i++) {
        if (!glib_parse_arg(c, &unit_rule, c->words[i], &cmd->num[i]))
            return false;
        for (int j = 0; j < i; j++)
            if (cmd->num[j] == cmd->num[i])
                glib_cwarn(c, "RenderToTexture: unit %g is listed twice", cmd->num[i]);
    }
    cmd->nnum = n;
    return true;
}

/* Clamp: real files write it (with or without words after it) before a
 * draw; glman took it as a texture wrap state. It is kept as a command
 * that changes nothing, never an error. */
bool glib_h_clamp(cmdctx *c, glib_cmd *cmd) {
    (void)c;
    (void)cmd;
    return true;
}

static void vdiag_note(cmdctx *c, const char *text) {
    glib_report(c->p, DIAG_NOTE, c->file, c->line, "MessageBox: %.400s", text);
}

/* MessageBox text: glman pops the text up; tarn prints it as a note. */
bool glib_h_message(cmdctx *c, glib_cmd *cmd) {
    (void)cmd;
    char *s = glib_skip_space(c->rest);
    size_t n = strlen(s);
    if (n >= 2 && s[0] == '"' && s[n - 1] == '"') {
        s[n - 1] = '\0';
        s++;
    }
    vdiag_note(c, s);
    return false;               /* nothing to run */
}

/* ------------------------------------------------------------------ */
/* immediate mode: glBegin mode, glVertex x y z [w] ..., glEnd        */

/* The primitives glBegin takes, as glman passed them to OpenGL. */
static const char *const begin_modes[] = {
    "gl_points", "gl_lines", "gl_line_strip", "gl_line_loop", "gl_triangles",
    "gl_triangle_strip", "gl_triangle_fan", "gl_quads", "gl_lines_adjacency",
    "gl_triangles_adjacency", "gl_patches",
};

bool glib_h_begin(cmdctx *c, glib_cmd *cmd) {
    parser *p = c->p;
    if (p->begin_file) {
        glib_cerr(c, "glBegin inside the glBegin of %s:%d: end that one with glEnd first", p->begin_file,
             p->begin_line);
        return false;
    }
    if (c->nwords < 1) {
        glib_cerr(c, "glBegin needs a primitive, e.g. glBegin gl_patches: %s", c->usage);
        return false;
    }
    glib_warn_extra(c, 1, "");
    for (size_t i = 0; i < sizeof begin_modes / sizeof begin_modes[0]; i++)
        if (strcasecmp(c->words[0], begin_modes[i]) == 0) {
            snprintf(cmd->name, sizeof cmd->name, "%s", begin_modes[i]);
            p->begin_file = c->file;
            p->begin_line = c->line;
            p->begin_nverts = 0;
            return true;
        }
    glib_cerr(c, "glBegin: unknown primitive '%.40s': write gl_patches, gl_triangles, gl_lines, gl_points, "
            "gl_lines_adjacency, gl_triangles_adjacency, gl_line_strip, gl_triangle_strip, ...", c->words[0]);
    return false;
}

bool glib_h_vertex(cmdctx *c, glib_cmd *cmd) {
    if (!c->p->begin_file) {
        glib_cwarn(c, "glVertex outside glBegin ... glEnd draws nothing (skipped): put it after a glBegin line");
        return false;
    }
    if (!glib_h_nums(c, cmd))
        return false;
    if (cmd->num[3] != 1)
        glib_cwarn(c, "glVertex: w = %g is not passed on; tarn draws the point x y z with w = 1", cmd->num[3]);
    c->p->begin_nverts++;
    return true;
}

bool glib_h_end(cmdctx *c, glib_cmd *cmd) {
    (void)cmd;
    parser *p = c->p;
    glib_warn_extra(c, 0, "");
    if (!p->begin_file) {
        glib_cwarn(c, "glEnd without a glBegin (skipped)");
        return false;
    }
    if (p->begin_nverts == 0)
        glib_cwarn(c, "glBegin (line %d) ... glEnd has no glVertex: it draws nothing", p->begin_line);
    p->begin_file = NULL;
    return true;
}

/* ------------------------------------------------------------------ */
/* keyword commands (our extensions)                                  */

bool glib_h_cull(cmdctx *c, glib_cmd *cmd) {
    static const keyword k[] = {
        { "back", "back", 0 }, { "front", "front", 0 }, { "none", "none", 0 }, { "off", "none", 0 },
    };
    const keyword *m = glib_find_keyword(c, k, sizeof k / sizeof k[0], "back, front or none");
    if (m)
        snprintf(cmd->name, sizeof cmd->name, "%s", m->canon);
    return m != NULL;
}

bool glib_h_blend(cmdctx *c, glib_cmd *cmd) {
    static const keyword k[] = {
        { "off", "off", 0 }, { "none", "off", 0 }, { "alpha", "alpha", 0 }, { "add", "add", 0 },
        { "premultiplied", "premultiplied", 0 },
    };
    const keyword *m = glib_find_keyword(c, k, sizeof k / sizeof k[0], "off, alpha, premultiplied or add");
    if (m)
        snprintf(cmd->name, sizeof cmd->name, "%s", m->canon);
    return m != NULL;
}

bool glib_h_depth(cmdctx *c, glib_cmd *cmd) {
    static const keyword k[] = {
        { "on", "on", 1 }, { "off", "off", 0 }, { "1", "on", 1 }, { "0", "off", 0 },
        { "true", "on", 1 }, { "false", "off", 0 },
    };
    const keyword *m = glib_find_keyword(c, k, sizeof k / sizeof k[0], "on or off");
    if (!m)
        return false;
    cmd->num[0] = m->value;
    cmd->nnum = 1;
    snprintf(cmd->name, sizeof cmd->name, "%s", m->canon);
    return true;
}
