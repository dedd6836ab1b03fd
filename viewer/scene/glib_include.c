/* glib_include.c: files read in place of a line (Include, and a Pack's
 * pack.glib): the include stack, its cycles and its bounds
 * (glib_internal.h).
 */
#ifndef _DEFAULT_SOURCE
#define _DEFAULT_SOURCE         /* realpath(), which is XSI, not plain POSIX */
#endif
#include "glib_internal.h"
#include "strbuf.h"
#include "file_cache.h"
#include "mem.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Reads a whole regular file of at most LIM_FILE_BYTES into *out (NUL
 * terminated, freed by the caller); on failure *why says why. Its lines, a
 * byte order mark and binary bytes are glib_parse_text's: glib_parse reads text
 * from memory too. */
bool glib_read_file(parser *p, const char *path, char **out, size_t *len, char *why, size_t whylen) {
    /* settled: a reload during a save reads the saved text, not a torn or empty one */
    file_text_opts o = { .max_bytes = LIM_FILE_BYTES, .settle = true };
    *out = file_cache_read(p->files, path, &o, len, NULL, why, whylen);
    return *out != NULL;
}

/* Reads text as the file `name` with the include stack pushed; takes canon. */
void glib_parse_nested(parser *p, const char *text, size_t len, const char *name,
                  char *canon, bool top) {
    p->stack_name[p->depth] = name;
    p->stack_canon[p->depth] = canon;
    p->depth++;
    glib_parse_text(p, text, len, name, top);
    p->depth--;
    free(canon);
}

/* A path that names the same file however it is spelled, for cycles. */
char *glib_canonical(const char *path) {
    char *real = realpath(path, NULL);
    return real ? real : mem_strdup(path);
}

/* Appends s to buf (size bytes, *n used), cutting what does not fit. */
void glib_append_cut(char *buf, size_t size, size_t *n, const char *s) {
    size_t l = strlen(s);
    if (*n + l >= size)
        l = size - 1 - *n;
    memcpy(buf + *n, s, l);
    *n += l;
    buf[*n] = '\0';
}

static void report_cycle(cmdctx *c, int at, const char *path) {
    char chain[256] = "";
    size_t n = 0;
    for (int i = at; i < c->p->depth; i++) {
        glib_append_cut(chain, sizeof chain, &n, c->p->stack_name[i]);
        glib_append_cut(chain, sizeof chain, &n, " -> ");
    }
    glib_append_cut(chain, sizeof chain, &n, path);
    glib_cerr(c, "%s cycle: %s; remove one of these Includes", c->spec->name, chain);
}

/* Reads the file at path in place of the current line (Include, Pack). */
void glib_include_file(cmdctx *c, const char *path) {
    parser *p = c->p;
    char why[MSG_MAX], *buf;
    size_t len;
    if (p->nreads >= LIM_INCLUDE_READS) {
        glib_cerr(c, "more than %d Includes in one scene; '%s' skipped", LIM_INCLUDE_READS, path);
        return;
    }
    char real[GLIB_PATH_MAX];
    snprintf(real, sizeof real, "%s", path);
    if (access(real, R_OK) != 0) {
        glib_check_readable(c, real);            /* says why, or finds the name in another case */
        if (access(real, R_OK) != 0)
            return;
    }
    path = real;
    if (!glib_read_file(p, path, &buf, &len, why, sizeof why)) {   /* a directory or huge */
        glib_cerr(c, "cannot open '%s' (from command %s): %s", path, c->spec->name, why);
        return;
    }
    p->nreads++;
    char *canon = glib_canonical(path);
    for (int i = 0; i < p->depth; i++)
        if (strcmp(p->stack_canon[i], canon) == 0) {
            report_cycle(c, i, path);
            free(canon);
            free(buf);
            return;
        }
    if (p->depth > LIM_INCLUDE_DEPTH) {
        glib_cerr(c, "%s '%s' is nested more than %d files deep; is there a loop?", c->spec->name,
             path, LIM_INCLUDE_DEPTH);
        free(canon);
        free(buf);
        return;
    }
    glib_parse_nested(p, buf, len, glib_add_file(p, path), canon, false);
    free(buf);
}

/* Include file: its commands are read in place of this line. */
bool glib_h_include(cmdctx *c, glib_cmd *cmd) {
    char path[GLIB_PATH_MAX];
    if (c->nwords < 1) {
        glib_cerr(c, "Include needs a file: %s", c->usage);
        return false;
    }
    glib_warn_extra(c, 1, path_hint);
    if (glib_resolve_path(c, c->words[0], path))
        glib_include_file(c, path);
    return false;               /* no command of its own: its lines are inlined */
}
