/* render_messages: the latest load's messages, each line once, with their
 * diagnostics, and the problems met drawing since (render.h). */
#include "util.h"
#include "render_internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"
#include "strbuf.h"

/* One message line (a diag, formatted) and the programs whose build
 * reported it. */
typedef struct msg_line {
    diag d;
    char *text;              /* d formatted */
    shader_stage stage;
    strbuf progs;            /* "'Water', 'Sky'" */
    int nprogs;
    bool mixed_stages;
} msg_line;

static void msg_line_add_prog(msg_line *m, const prog_origin *o) {
    char quoted[GLIB_NAME_MAX + 4];
    snprintf(quoted, sizeof quoted, "'%s'", o->prog);
    if (m->nprogs == 0) m->stage = o->stage;
    else if (m->stage != o->stage) m->mixed_stages = true;
    if (m->progs.s && strstr(m->progs.s, quoted)) return;
    if (m->nprogs++ > 0) strbuf_puts(&m->progs, ", ");
    strbuf_puts(&m->progs, quoted);
}

/* " (fragment shader of programs 'Water', 'Sky')", or "" for a line no
 * program's build reported. */
static void msg_line_suffix(strbuf *out, const msg_line *m) {
    strbuf_puts(out, "");
    if (m->nprogs > 0 && m->mixed_stages) strbuf_printf(out, " (programs %s)", m->progs.s);
    else if (m->nprogs > 0)
        strbuf_printf(out, " (%s shader of program%s %s)", shader_stage_name(m->stage), m->nprogs > 1 ? "s" : "",
                      m->progs.s);
}

/* The load's diags, each line once: a line that several programs report
 * (an error in a file they all include) names them all, with its stage. */
static msg_line *merge_lines(const diag_list *dl, const prog_origins *from, int *nout) {
    msg_line *lines = NULL;
    int n = 0, k = 0;
    char text[DIAG_FILE_MAX + DIAG_TEXT_MAX + 32];
    for (int d = 0; d < dl->n; d++) {
        diag_format(&dl->d[d], text, sizeof text);
        int i = 0;
        while (i < n && strcmp(lines[i].text, text) != 0) i++;
        if (i == n) {
            lines = mem_realloc(lines, (size_t)(n + 1) * sizeof *lines);
            memset(&lines[n], 0, sizeof lines[n]);
            lines[n].d = dl->d[d];
            lines[n++].text = mem_strdup(text);
        }
        while (from && k < from->n && from->o[k].d < d) k++;
        for (; from && k < from->n && from->o[k].d == d; k++) msg_line_add_prog(&lines[i], &from->o[k]);
    }
    *nout = n;
    return lines;
}

/* The latest load's messages: each line once (an error in a file that
 * several programs include is reported by each) with the programs that
 * reported it, as diags (from which errors are told apart from warnings)
 * and as text formatted from them. */
void render_messages_set(render *r, diag_list *dl, prog_origins *from) {
    int n = 0;
    msg_line *lines = merge_lines(dl, from, &n);
    diag_list_free(dl);
    if (from) prog_origins_free(from);
    free(r->messages);
    r->messages = NULL;
    diag_list_free(&r->diags);
    strbuf out = { 0 }, suffix = { 0 };
    strbuf_puts(&out, "");
    for (int i = 0; i < n; i++) {
        suffix.len = 0;
        msg_line_suffix(&suffix, &lines[i]);
        diag d = lines[i].d;   /* the suffix is part of the line's text */
        snprintf(d.text, sizeof d.text, "%s%s", lines[i].d.text, suffix.s);
        diag_push(&r->diags, &d);
        strbuf_printf(&out, "%s%s\n", lines[i].text, suffix.s);
        free(lines[i].text);
        strbuf_free(&lines[i].progs);
    }
    strbuf_free(&suffix);
    free(lines);
    r->messages = strbuf_take(&out);
    free(r->draw_messages);   /* problems drawing are found afresh */
    r->draw_messages = NULL;
    if (r->cur.draw_warned && r->cur.glib)
        memset(r->cur.draw_warned, 0, (size_t)r->cur.glib->ncmds * sizeof *r->cur.draw_warned);
}

const char *render_messages(const render *r) { return r->messages ? r->messages : ""; }
const char *render_draw_messages(const render *r) { return r->draw_messages ? r->draw_messages : ""; }
const diag_list *render_diags(const render *r) { return &r->diags; }
bool render_has_errors(const render *r) { return r->errors; }

void render_messages_draw_problem(render *r, int ci, bool error, const char *fmt, ...) {
    scene_state *s = &r->cur;
    if (s->draw_warned[ci]) return;
    s->draw_warned[ci] = true;
    const glib_cmd *c = &s->glib->cmds[ci];
    char msg[MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    diag_add(&r->diags, error ? DIAG_ERROR : DIAG_WARNING, c->file, c->line, "%s", msg);
    char line[DIAG_FILE_MAX + DIAG_TEXT_MAX + 32];
    diag_format(&r->diags.d[r->diags.n - 1], line, sizeof line);
    str_appendf(&r->draw_messages, "%s\n", line);
    str_appendf(&r->messages, "%s\n", line);
    if (error) r->errors = true;
}
