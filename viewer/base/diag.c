#include "diag.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"
#include "strbuf.h"

const char *diag_severity_name(diag_severity s) {
    return s == DIAG_ERROR ? "error" : s == DIAG_WARNING ? "warning" : "note";
}

static diag *push(diag_list *l, diag_severity sev, const char *file, int line) {
    l->d = mem_grow(l->d, &l->cap, l->n + 1, sizeof *l->d);
    diag *d = &l->d[l->n++];
    memset(d, 0, sizeof *d);
    d->severity = sev;
    d->line = line;
    snprintf(d->file, sizeof d->file, "%s", file ? file : "");
    if (sev == DIAG_ERROR) l->nerrors++;
    if (sev == DIAG_WARNING) l->nwarnings++;
    return d;
}

void diag_add(diag_list *l, diag_severity sev, const char *file, int line, const char *fmt, ...) {
    diag *d = push(l, sev, file, line);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(d->text, sizeof d->text, fmt, ap);
    va_end(ap);
}

void diag_add_bare(diag_list *l, diag_severity sev, const char *fmt, ...) {
    diag *d = push(l, sev, NULL, 0);
    d->bare = true;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(d->text, sizeof d->text, fmt, ap);
    va_end(ap);
}

void diag_push(diag_list *l, const diag *d) {
    diag *x = push(l, d->severity, d->file, d->line);
    *x = *d;
}

/* Where the first ": note: ", ": warning: " or ": error: " of s (n bytes)
 * starts, and which; NULL when none: the text of a message may name
 * another severity after its own ("error: ... : warning: ..."). */
static const char *find_severity(const char *s, size_t n, int *k, size_t *patlen) {
    static const char *const pats[] = { ": note: ", ": warning: ", ": error: " };
    for (const char *p = s; p < s + n; p++)
        for (*k = 0; *k < 3; (*k)++) {
            *patlen = strlen(pats[*k]);
            if ((size_t)(s + n - p) >= *patlen && strncmp(p, pats[*k], *patlen) == 0) return p;
        }
    return NULL;
}

/* `file:line: severity: text`, the shape tarn and most compilers print. */
static bool parse_line(const char *s, size_t n, diag_severity *sev, char *file, size_t filelen, int *line,
                       const char **text) {
    int k;
    size_t patlen;
    const char *m = find_severity(s, n, &k, &patlen);
    if (m) {
        const char *colon = m - 1;
        while (colon > s && *colon >= '0' && *colon <= '9') colon--;
        if (colon > s && *colon == ':' && colon != m - 1) {
            snprintf(file, filelen, "%.*s", (int)(colon - s), s);
            *line = atoi(colon + 1);
        } else if (m - s == 4 && strncmp(s, "tarn", 4) == 0) {
            file[0] = '\0';            /* `tarn: error: text`: no file concerned */
            *line = 0;
        } else {
            snprintf(file, filelen, "%.*s", (int)(m - s), s);   /* `file: error: text` */
            *line = 0;
        }
        *sev = (diag_severity)k;
        *text = m + patlen;
        return true;
    }
    return false;
}

void diag_add_log(diag_list *l, diag_severity sev, const char *log) {
    for (const char *s = log; s && *s;) {
        const char *e = strchr(s, '\n');
        size_t n = e ? (size_t)(e - s) : strlen(s);
        if (n > 0) {
            char file[DIAG_FILE_MAX];
            int line = 0;
            diag_severity got;
            const char *t;
            if (parse_line(s, n, &got, file, sizeof file, &line, &t)) {
                diag *d = push(l, got, file, line);
                snprintf(d->text, sizeof d->text, "%.*s", (int)(s + n - t), t);
            } else {
                diag *d = push(l, sev, NULL, 0);
                d->bare = true;
                snprintf(d->text, sizeof d->text, "%.*s", (int)n, s);
            }
        }
        s = e ? e + 1 : s + n;
    }
}

void diag_list_free(diag_list *l) {
    free(l->d);
    memset(l, 0, sizeof *l);
}

void diag_format(const diag *d, char *out, size_t outlen) {
    if (d->bare)
        snprintf(out, outlen, "%s", d->text);
    else if (d->file[0])
        snprintf(out, outlen, "%s:%d: %s: %s", d->file, d->line, diag_severity_name(d->severity), d->text);
    else
        snprintf(out, outlen, "tarn: %s: %s", diag_severity_name(d->severity), d->text);
}

void diag_print(const diag_list *l, FILE *f) {
    char line[DIAG_FILE_MAX + DIAG_TEXT_MAX + 32];
    for (int i = 0; i < l->n; i++) {
        diag_format(&l->d[i], line, sizeof line);
        fprintf(f, "%s\n", line);
    }
}

char *diag_list_format(const diag_list *l, int from) {
    strbuf o = { 0 };
    strbuf_puts(&o, "");
    char line[DIAG_FILE_MAX + DIAG_TEXT_MAX + 32];
    for (int i = from < 0 ? 0 : from; i < l->n; i++) {
        diag_format(&l->d[i], line, sizeof line);
        strbuf_printf(&o, "%s\n", line);
    }
    return strbuf_take(&o);
}
