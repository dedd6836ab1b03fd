/* glib.c: the driver of the .glib parser (glib.h; the format is in
 * docs/glib.md): the parser's state and its diagnostics, the lines of a
 * text handed one at a time to the command table, and the public
 * functions (load, parse, free, what a parsed scene says).
 *
 * The text is read one logical line at a time (glib_lex.c: physical lines
 * joined at a trailing backslash, comments cut off); the first word picks a
 * row of the command table (glib_table.c) and that row's handler turns the
 * rest of the line into a glib_cmd. A bad line becomes a diagnostic and is
 * skipped, so one typo never hides the rest of the scene.
 *
 * Every limit (glib_internal.h) exists so that corrupt or hostile input (a
 * binary file, an include loop, a megabyte-long line) costs bounded memory
 * and time.
 */
#include "glib_internal.h"
#include "strbuf.h"
#include "mem.h"
#include "unif.h"

#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------ */
/* memory: bounded by the limits (mem.h: out of memory aborts)        */

/* ------------------------------------------------------------------ */
/* the parser's state and its diagnostics                             */

static void add_diag(parser *p, diag_severity sev, const char *file, int line,
                     const char *msg) {
    glib_scene *sc = p->sc;
    sc->diags = mem_grow(sc->diags, &p->diag_cap, sc->ndiags + 1, sizeof *sc->diags);
    diag *d = &sc->diags[sc->ndiags++];
    memset(d, 0, sizeof *d);
    d->severity = sev;
    snprintf(d->file, sizeof d->file, "%s", file ? file : "?");
    d->line = line;
    snprintf(d->text, sizeof d->text, "%s", msg);
    if (sev == DIAG_ERROR)
        sc->nerrors++;
}

__attribute__((format(printf, 5, 0)))
static void vdiag(parser *p, diag_severity sev, const char *file, int line,
                  const char *fmt, va_list ap) {
    if (p->sc->ndiags >= LIM_DIAGS - 1) {
        p->dropped++;
        p->dropped_errors += sev == DIAG_ERROR;
        return;
    }
    char msg[sizeof p->sc->diags[0].text];
    vsnprintf(msg, sizeof msg, fmt, ap);
    add_diag(p, sev, file, line, msg);
}

__attribute__((format(printf, 5, 6)))
void glib_report(parser *p, diag_severity sev, const char *file, int line,
            const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vdiag(p, sev, file, line, fmt, ap);
    va_end(ap);
}

/* Records a file name in scene->files (once) and returns the stored copy,
 * which commands and diagnostics point at. */
const char *glib_add_file(parser *p, const char *name) {
    glib_scene *sc = p->sc;
    for (int i = 0; i < sc->nfiles; i++)
        if (strcmp(sc->files[i], name) == 0)
            return sc->files[i];
    sc->files = mem_grow(sc->files, &p->file_cap, sc->nfiles + 1, sizeof *sc->files);
    sc->files[sc->nfiles] = mem_strdup(name);
    return sc->files[sc->nfiles++];
}

__attribute__((format(printf, 2, 3)))
void glib_cerr(cmdctx *c, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vdiag(c->p, DIAG_ERROR, c->file, c->line, fmt, ap);
    va_end(ap);
}

__attribute__((format(printf, 2, 3)))
void glib_cwarn(cmdctx *c, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vdiag(c->p, DIAG_WARNING, c->file, c->line, fmt, ap);
    va_end(ap);
}

/* ------------------------------------------------------------------ */
/* commands                                                           */

static void free_cmd_parts(glib_cmd *cmd) {
    free(cmd->cube_paths);
    free(cmd->uniforms);
    free(cmd->defines);
}

void glib_push_cmd(parser *p, glib_cmd *cmd) {
    glib_scene *sc = p->sc;
    if (sc->ncmds >= LIM_CMDS) {
        glib_report(p, DIAG_ERROR, cmd->file, cmd->line,
             "too many commands (more than %d); the rest of the scene is ignored", LIM_CMDS);
        free_cmd_parts(cmd);
        p->stop = true;
        return;
    }
    sc->cmds = mem_grow(sc->cmds, &p->cmd_cap, sc->ncmds + 1, sizeof *sc->cmds);
    sc->cmds[sc->ncmds++] = *cmd;
}

static void unknown_command(parser *p, const char *name, char *rest, const char *file, int line) {
    const char *near = glib_suggest(name);
    char hint[96] = "";
    if (near)
        snprintf(hint, sizeof hint, "; did you mean '%s'?", near);
    else if (glib_is_opener(*glib_skip_space(rest)))
        snprintf(hint, sizeof hint, "; a uniform on its own line? end the Program line above with '\\'");
    glib_report(p, DIAG_WARNING, file, line, "unknown command '%.60s' (skipped)%s", name, hint);
}

/* glman tolerated brackets around plain numbers and commas between them
 * (`Color [1 0 0]`, `Color 1, 0, 0`): on a command of numbers only they
 * are blanks. */
static void blank_brackets(char *s) {
    for (; *s; s++)
        if (*s == '[' || *s == ']' || *s == ',')
            *s = ' ';
}

static void process_line(parser *p, char *s, const char *file, int line) {
    s = glib_skip_space(s);
    if (!*s)
        return;
    char *name = s;
    while (*s && !glib_is_space((unsigned char)*s))
        s++;
    if (*s)
        *s++ = '\0';
    const cmd_spec *spec = glib_find_spec(name);
    if (!spec) {
        unknown_command(p, name, s, file, line);
        return;
    }
    cmdctx c = { .p = p, .file = file, .line = line, .spec = spec, .rest = s };
    glib_build_usage(spec, c.usage, sizeof c.usage);
    if (spec->fn == glib_h_nums || spec->fn == glib_h_world_nums || spec->fn == glib_h_vertex)
        blank_brackets(s);
    if (!spec->raw && (c.nwords = glib_split_words(s, c.words, LIM_WORDS)) < 0) {
        glib_cerr(&c, "%s: unclosed '\"': add the closing quote", spec->name);
        return;
    }
    glib_cmd cmd;
    memset(&cmd, 0, sizeof cmd);
    cmd.kind = spec->kind;
    cmd.file = file;
    cmd.line = line;
    cmd.wire = spec->wire;
    if (spec->fn(&c, &cmd))
        glib_push_cmd(p, &cmd);
    else
        free_cmd_parts(&cmd);
}

/* ------------------------------------------------------------------ */
/* the top file and its lines                                         */

/* glman demands the header; we only remind (a header with a trailing
 * comment or odd spacing still counts). */
static bool is_header(const char *b, size_t n) {
    static const char want[] = "##openglglib";
    size_t k = 0;
    for (size_t i = 0; i < n && want[k]; i++) {
        if (glib_is_space((unsigned char)b[i]))
            continue;
        if (tolower((unsigned char)b[i]) != want[k++])
            return false;
    }
    return want[k] == '\0';
}

static bool all_space(const char *s, size_t n) {
    for (size_t i = 0; i < n; i++)
        if (!glib_is_space((unsigned char)s[i]) && s[i] != '\n')
            return false;
    return true;
}

/* The top file must say what it is; an included file need not. */
static bool check_top(parser *p, const reader *r, const char *file) {
    if (all_space(r->text + r->pos, r->len - r->pos)) {
        glib_report(p, DIAG_ERROR, file, 1, "empty file: expected '##OpenGL GLIB' and commands");
        return false;
    }
    reader first = *r;
    const char *b = "";
    size_t n = 0;
    glib_next_phys(&first, &b, &n);
    if (is_header(b, n))
        return true;
    /* glman opened files whose header follows blank or comment lines
     * (projects that ran in glman do this): the header anywhere before
     * the first command is fine; only a file without it is worth a word */
    for (int line = 1;; line++) {
        size_t k = 0;
        while (k < n && glib_is_space((unsigned char)b[k]))
            k++;
        bool blank = k == n || b[k] == '\n' || b[k] == '\r';
        bool comment = !blank && (b[k] == '#' || (b[k] == '/' && k + 1 < n && b[k + 1] == '/'));
        if (is_header(b, n)) {
            glib_report(p, DIAG_NOTE, file, line, "the '##OpenGL GLIB' header is on line %d, after blank or comment "
                   "lines; glman read it there too", line);
            return true;
        }
        if (!blank && !comment)
            break;
        if (first.pos >= first.len)
            break;
        glib_next_phys(&first, &b, &n);
    }
    glib_report(p, DIAG_WARNING, file, 1,
           "first line is not '##OpenGL GLIB': glman will not open this file; add that line");
    return true;
}

void glib_parse_text(parser *p, const char *text, size_t len, const char *file, bool top) {
    reader r = { text ? text : "", text ? len : 0, 0, 0 };
    if (r.len >= 3 && memcmp(r.text, "\xEF\xBB\xBF", 3) == 0)
        r.pos = 3;              /* a UTF-8 byte order mark from a Windows editor */
    if (top && !check_top(p, &r, file))
        return;
    logical lg = { .buf = mem_alloc(LIM_LINE_CHARS + 1) };
    int binary = 0;
    while (!p->stop && glib_next_logical(&r, &lg)) {
        if (lg.too_long) {
            glib_report(p, DIAG_ERROR, file, lg.first_line,
                 "line too long (over %d characters); command skipped", LIM_LINE_CHARS);
        } else if (lg.bad_byte >= 0) {
            glib_report(p, DIAG_ERROR, file, lg.first_line,
                 lg.bad_byte >= 0x80 ? "byte 0x%02X at column %d is not UTF-8 text; line skipped (save the file as UTF-8)"
                                     : "binary data (byte 0x%02X at column %d) in a text file; line skipped",
                 lg.bad_byte, lg.bad_col);
            if (++binary >= LIM_BINARY_LINES) {
                glib_report(p, DIAG_ERROR, file, lg.first_line,
                     "this does not look like a .glib text file; stopped reading it");
                break;
            }
        } else {
            process_line(p, lg.buf, file, lg.first_line);
        }
    }
    free(lg.buf);
    if (top && p->pack_override && !p->pack_seen && !p->stop)
        glib_override_pack_at_end(p, file);
}

/* ------------------------------------------------------------------ */
/* the public functions                                               */

static void finish(parser *p) {
    glib_scene *sc = p->sc;
    if (p->begin_file)
        glib_report(p, DIAG_ERROR, p->begin_file, p->begin_line,
               "glBegin without a glEnd: its vertices draw nothing; add glEnd after the last glVertex");
    for (int i = 0; i < p->npending; i++)
        glib_report(p, DIAG_WARNING, p->pending[i].file, p->pending[i].line,
             "Define %s comes after the last Program, so no shader sees it; move it above a Program",
             p->pending[i].name);
    free(p->pending);
    p->pending = NULL;
    if (sc->ncmds == 0 && sc->nerrors == 0 && sc->nfiles > 0)
        glib_report(p, DIAG_WARNING, sc->files[0], 1, "no commands: the scene draws nothing");
    if (p->dropped) {
        char msg[MSG_MAX];
        snprintf(msg, sizeof msg, "too many errors: %d more diagnostics not shown (%d errors); fix the ones above first",
                 p->dropped, p->dropped_errors);
        add_diag(p, p->dropped_errors ? DIAG_ERROR : DIAG_WARNING,
                 sc->files[0], 0, msg);
    }
}

static glib_scene *new_scene(parser *p) {
    memset(p, 0, sizeof *p);
    p->sc = mem_alloc(sizeof *p->sc);
    memset(p->sc, 0, sizeof *p->sc);
    return p->sc;
}

glib_scene *glib_parse(const char *text, size_t len, const char *virtual_path) {
    parser p;
    glib_scene *sc = new_scene(&p);
    const char *name = glib_add_file(&p, virtual_path ? virtual_path : "<memory>");
    glib_parse_nested(&p, text, len, name, glib_canonical(name), true);
    finish(&p);
    return sc;
}

glib_scene *glib_load(const char *path) {
    return glib_load_opts(path, NULL);
}

glib_scene *glib_load_opts(const char *path, const glib_options *opt) {
    parser p;
    glib_scene *sc = new_scene(&p);
    if (opt) {
        p.packs_dir = opt->packs_dir && opt->packs_dir[0] ? opt->packs_dir : NULL;
        p.pack_override = opt->pack_override && opt->pack_override[0] ? opt->pack_override : NULL;
        p.files = sc->read_through = opt->files;
    }
    const char *name = glib_add_file(&p, path ? path : "<null>");
    char *buf, why[128];
    size_t len;
    if (!path || !glib_read_file(&p, path, &buf, &len, why, sizeof why)) {
        glib_report(&p, DIAG_ERROR, name, 0, "cannot open '%s': %s", name, path ? why : "no path given");
    } else {
        glib_parse_nested(&p, buf, len, name, glib_canonical(path), true);
        free(buf);
    }
    finish(&p);
    return sc;
}

void glib_free(glib_scene *scene) {
    if (!scene)
        return;
    for (int i = 0; i < scene->ncmds; i++)
        free_cmd_parts(&scene->cmds[i]);
    for (int i = 0; i < scene->nfiles; i++)
        free(scene->files[i]);
    free(scene->cmds);
    free(scene->diags);
    free(scene->files);
    free(scene);
}

void glib_print_diags(const glib_scene *scene, void *stream) {
    diag_list l = { .d = scene ? scene->diags : NULL, .n = scene ? scene->ndiags : 0 };
    diag_print(&l, stream);
}

bool glib_uniform_consumed(const glib_scene *scene, const char *name, bool *is_count) {
    for (int i = 0; scene && i < scene->ncmds; i++) {
        const glib_cmd *c = &scene->cmds[i];
        bool count = c->kind == GLIB_CMD_WATER_SURFACE || c->kind == GLIB_CMD_TEXTURE2D_EMPTY;
        if (!count && c->kind != GLIB_CMD_CAMERA && c->kind != GLIB_CMD_WORLD)
            continue;
        if (strcmp(c->arg, name) == 0 || (c->kind == GLIB_CMD_TEXTURE2D_EMPTY && strcmp(c->name, name) == 0)) {
            if (is_count)
                *is_count = count;
            return true;
        }
    }
    return false;
}

unif_program_decl glib_program_decl(const glib_cmd *c) {
    unif_program_decl d = {
        .name = c->name, .file = c->file, .line = c->line,
        .defines = c->defines, .ndefines = c->ndefines,
        .uniforms = c->uniforms, .nuniforms = c->nuniforms,
    };
    return d;
}

bool glib_unif_set(unif_set *set, const glib_cmd *program, diag_list *dl) {
    if (!set || !program) return false;
    if (program->kind != GLIB_CMD_PROGRAM) {
        if (dl) diag_add(dl, DIAG_ERROR, program->file ? program->file : "(glib)", program->line, "not a Program command");
        return false;
    }
    unif_program_decl d = glib_program_decl(program);
    return unif_set_from_decls(set, &d, dl);
}
