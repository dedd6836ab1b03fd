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

/* One message line and the programs whose build reported it. */
typedef struct msg_line {
    char *text;
    char stage[32];
    strbuf progs;            /* "'Water', 'Sky'" */
    int nprogs;
    bool mixed_stages;
} msg_line;

static void msg_line_add_prog(msg_line *m, const char *stage, const char *pname) {
    char quoted[GLIB_NAME_MAX + 4];
    snprintf(quoted, sizeof quoted, "'%s'", pname);
    if (m->nprogs == 0) snprintf(m->stage, sizeof m->stage, "%s", stage);
    else if (strcmp(m->stage, stage) != 0) m->mixed_stages = true;
    if (m->progs.s && strstr(m->progs.s, quoted)) return;
    if (m->nprogs++ > 0) strbuf_puts(&m->progs, ", ");
    strbuf_puts(&m->progs, quoted);
}

static void msg_line_print(strbuf *out, const msg_line *m) {
    strbuf_puts(out, m->text);
    if (m->nprogs > 0 && m->mixed_stages) strbuf_printf(out, " (programs %s)", m->progs.s);
    else if (m->nprogs > 0)
        strbuf_printf(out, " (%s shader of program%s %s)", m->stage, m->nprogs > 1 ? "s" : "", m->progs.s);
    strbuf_puts(out, "\n");
}

/* The log's lines, each once: a line that several programs report (an
 * error in a file they all include) names them all; a tagged line
 * (RENDER_PROG_TAG) names its stage and program. */
static char *merge_lines(const char *log) {
    msg_line *lines = NULL;
    int n = 0;
    for (const char *s = log; s && *s;) {
        const char *e = strchr(s, '\n');
        size_t len = e ? (size_t)(e - s) : strlen(s);
        char *line = mem_strndup(s, len);
        s += len + (e ? 1 : 0);
        char *stage = strchr(line, RENDER_PROG_TAG), *pname = stage ? strchr(stage + 1, RENDER_PROG_TAG) : NULL;
        if (stage) *stage++ = '\0';
        if (pname) *pname++ = '\0';
        int i = 0;
        while (i < n && strcmp(lines[i].text, line) != 0) i++;
        if (i == n) {
            lines = mem_realloc(lines, (size_t)(n + 1) * sizeof *lines);
            memset(&lines[n], 0, sizeof lines[n]);
            lines[n++].text = line;
        }
        if (stage && pname) msg_line_add_prog(&lines[i], stage, pname);   /* (they point into line) */
        if (lines[i].text != line) free(line);
    }
    strbuf out = { 0 };
    for (int i = 0; i < n; i++) {
        msg_line_print(&out, &lines[i]);
        free(lines[i].text);
        strbuf_free(&lines[i].progs);
    }
    free(lines);
    return out.s;
}

/* The latest load's messages: each line once (an error in a file that
 * several programs include is reported by each), and their diagnostics,
 * from which errors are told apart from warnings. */
void render_messages_set(render *r, char *log) {
    char *merged = merge_lines(log);
    free(log);
    free(r->messages);
    r->messages = merged;
    free(r->draw_messages);   /* problems drawing are found afresh */
    r->draw_messages = NULL;
    if (r->cur.draw_warned && r->cur.glib)
        memset(r->cur.draw_warned, 0, (size_t)r->cur.glib->ncmds * sizeof *r->cur.draw_warned);
    diag_list_free(&r->diags);
    diag_add_text(&r->diags, DIAG_NOTE, r->messages);
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
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    char *line = NULL;
    str_appendf(&line, "%s:%d: %s: %s\n", c->file, c->line, error ? "error" : "warning", msg);
    str_appendf(&r->draw_messages, "%s", line);
    str_appendf(&r->messages, "%s", line);
    diag_add_text(&r->diags, DIAG_NOTE, line);
    free(line);
    if (error) r->errors = true;
}
