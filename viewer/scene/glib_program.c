/* glib_program.c: the Program command (a name, then uniform/value
 * pairs: glib_values.c) and the Define toggles it takes with it
 * (glib_internal.h).
 */
#include "glib_internal.h"
#include "mem.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void add_uniform(cmdctx *c, glib_cmd *cmd, const unif_decl *u, int *cap) {
    for (int i = 0; i < cmd->nuniforms; i++)
        if (strcmp(cmd->uniforms[i].name, u->name) == 0) {
            glib_cwarn(c, "Program %s: uniform '%s' is given twice; the later value wins",
                  cmd->name, u->name);
            cmd->uniforms[i] = *u;
            return;
        }
    if (cmd->nuniforms >= LIM_PROGRAM_UNIFORMS || c->p->scene_uniforms >= LIM_SCENE_UNIFORMS) {
        glib_cerr(c, "Program %s: too many uniforms (at most %d on one Program); '%s' ignored",
             cmd->name, LIM_PROGRAM_UNIFORMS, u->name);
        return;
    }
    cmd->uniforms = mem_grow(cmd->uniforms, cap, cmd->nuniforms + 1, sizeof *cmd->uniforms);
    cmd->uniforms[cmd->nuniforms++] = *u;
    c->p->scene_uniforms++;
}

static void take_pending_defines(parser *p, glib_cmd *cmd) {
    cmd->defines = p->pending;
    cmd->ndefines = p->npending;
    p->pending = NULL;
    p->npending = p->pending_cap = 0;
}

/* Reads one `name value` pair of a Program line into u; false when the
 * rest of the line cannot be read. *ok says whether u is usable. */
static bool program_uniform(cmdctx *c, glib_cmd *cmd, char **sp, unif_decl *u, bool *ok) {
    char *s = *sp;
    bool named = !glib_is_opener(*s);
    if (!named)
        glib_cerr(c, "Program %s: a value '%c...' has no uniform name before it", cmd->name, *s);
    else
        named = glib_take_name(c, &s, u->name, "uniform");
    s = glib_skip_space(s);
    *sp = s;
    *ok = false;
    if (!*s) {
        if (named)
            glib_cerr(c, "Program %s: uniform '%s' has no value: write %s 5, <min default max>, <true>, [a b c] or {r g b}",
                 cmd->name, u->name, u->name);
        return false;
    }
    char owner[GLIB_NAME_MAX * 2 + 32];
    snprintf(owner, sizeof owner, "Program %s: uniform '%s'", cmd->name, u->name);
    val_result r = glib_read_value(c, sp, u, owner);
    *ok = r == VAL_OK && named;
    return r != VAL_STOP;
}

bool glib_h_program(cmdctx *c, glib_cmd *cmd) {
    char *s = glib_skip_space(c->rest), *e = s;
    while (*e && !glib_is_space((unsigned char)*e) && !glib_is_opener(*e))
        e++;
    if (e == s) {
        glib_cerr(c, "Program needs a name: %s", c->usage);
        return false;
    }
    if (e - s >= GLIB_NAME_MAX) {
        glib_cerr(c, "Program name '%.40s...' is too long (at most %d characters)", s, GLIB_NAME_MAX - 1);
        return false;
    }
    memcpy(cmd->name, s, (size_t)(e - s));
    /* `Program Cold Giraffe uA <0 1 2>`: glman's name is one word, the
     * rest name/value pairs. A bare word followed by another word that is
     * no value (or by nothing) cannot be a pair: it is more of the name
     * the student wrote. tarn keeps glman's one-word name and skips the
     * rest of it, so the pairs after it line up as they did in glman. */
    for (s = glib_skip_space(e);;) {
        char *we = s;
        while (*we && !glib_is_space((unsigned char)*we) && !glib_is_opener(*we))
            we++;
        if (we == s || glib_is_opener(*we) || !isalpha((unsigned char)*s))
            break;
        char *next = glib_skip_space(we);
        char *ne = next;
        while (*ne && !glib_is_space((unsigned char)*ne) && !glib_is_opener(*ne))
            ne++;
        char *num_end = next;
        if (*next && ne > next)
            (void)strtod(next, &num_end);
        double bv;
        char saved = *ne;
        *ne = '\0';
        bool boolword = *next && glib_is_bool_word(next, &bv);
        *ne = saved;
        bool value_next = glib_is_opener(*next) || (*next && num_end > next) || *next == '.' || *next == '-' || boolword;
        /* a last bare word: a name's word when capitalised (Giraffe), else a
         * uniform without its value (uA), which is an error below */
        if (value_next || (!*next && !isupper((unsigned char)*s)))
            break;
        glib_cwarn(c, "Program %s: '%.*s' read as part of the program's name (glman's name is one word; the "
              "words after it are uniform/value pairs): write the name as one word, e.g. %s_%.*s",
              cmd->name, (int)(we - s), s, cmd->name, (int)(we - s), s);
        s = glib_skip_space(we);
    }
    e = s;
    int cap = 0;
    for (s = glib_skip_space(e); *s; s = glib_skip_space(s)) {
        unif_decl u = { .file = c->file, .line = c->line };
        bool ok;
        bool go_on = program_uniform(c, cmd, &s, &u, &ok);
        if (ok)
            add_uniform(c, cmd, &u, &cap);
        if (!go_on)
            break;
    }
    take_pending_defines(c->p, cmd);
    return true;
}

static void add_pending(cmdctx *c, const unif_decl *u) {
    parser *p = c->p;
    for (int i = 0; i < p->npending; i++)
        if (strcmp(p->pending[i].name, u->name) == 0) {
            glib_cwarn(c, "Define %s is given twice before the next Program; the later one wins", u->name);
            p->pending[i] = *u;
            return;
        }
    p->pending = mem_grow(p->pending, &p->pending_cap, p->npending + 1, sizeof *p->pending);
    p->pending[p->npending++] = *u;
}

/* Define NAME [<true>|<false>|value|<min default max>]: a #define the
 * shaders of the next Program are compiled with (a bare name is <true>). */
bool glib_h_define(cmdctx *c, glib_cmd *cmd) {
    unif_decl u = { .file = c->file, .line = c->line, .kind = UNIF_DECL_BOOL,
                       .v = { 1 }, .n = 1 };
    char *s = glib_skip_space(c->rest);
    if (!*s) {
        glib_cerr(c, "Define needs a name: %s", c->usage);
        return false;
    }
    if (!glib_take_name(c, &s, u.name, "Define"))
        return false;
    s = glib_skip_space(s);
    if (*s) {
        char owner[GLIB_NAME_MAX + 16];
        snprintf(owner, sizeof owner, "Define %s", u.name);
        if (glib_read_value(c, &s, &u, owner) != VAL_OK)
            return false;
        if (u.kind == UNIF_DECL_ARRAY || u.kind == UNIF_DECL_COLOR) {
            glib_cerr(c, "Define %s takes <true>, <false>, a number or <min default max>, not a list",
                 u.name);
            return false;
        }
        s = glib_skip_space(s);
        if (*s)
            glib_cwarn(c, "Define %s: ignoring '%.40s' after the value", u.name, s);
    }
    memcpy(cmd->name, u.name, sizeof cmd->name);
    cmd->uniforms = mem_alloc(sizeof u);
    cmd->uniforms[0] = u;
    cmd->nuniforms = 1;
    add_pending(c, &u);
    return true;
}
