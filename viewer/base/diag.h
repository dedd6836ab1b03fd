/* diag: tarn's one diagnostics type. Every layer that finds a problem in
 * the user's input (the parser, shader assembly and its line mapping, the
 * renderer, the validator) records a diag: severity, file, line, text, and
 * hands the list on; none of them writes a message as text for another to
 * read back. One function prints them, as `file:line: warning|error: text`.
 * The only text read into diags is a tool's log (the GL driver's,
 * glslang's): diag_add_log. */
#ifndef TARN_DIAG_H
#define TARN_DIAG_H

#include <stdbool.h>
#include <stdio.h>

typedef enum diag_severity { DIAG_NOTE = 0, DIAG_WARNING = 1, DIAG_ERROR = 2 } diag_severity;

#define DIAG_TEXT_MAX 512
#define DIAG_FILE_MAX 1024

typedef struct diag {
    diag_severity severity;
    char file[DIAG_FILE_MAX]; /* "" when no file is concerned */
    int line;                 /* 1-based; 0 when no line is concerned */
    char text[DIAG_TEXT_MAX];
    bool bare;                /* a line of a tool's log without that shape, or a
                               * plain sentence: printed as its text alone */
} diag;

typedef struct diag_list {
    diag *d;
    int n, cap;
    int nerrors, nwarnings;
} diag_list;

void diag_add(diag_list *l, diag_severity sev, const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
/* A plain sentence (no file, no severity word when printed): a bare diag. */
void diag_add_bare(diag_list *l, diag_severity sev, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* Reads a tool's log (a GL driver's or glslang's info log, already mapped
 * to the user's files by shader_src_map_diags) into l, one diag a line:
 * `file:line: error: text`, the shape compilers print; `file: warning:
 * text` has line 0, `tarn: error: text` no file; lines of another shape
 * become bare diags of severity sev, printed as the tool wrote them. Empty
 * lines are skipped. The one place tarn parses message text: tarn's own
 * messages are diags from the start (but the two of the header). */
void diag_add_log(diag_list *l, diag_severity sev, const char *log);
/* Appends a copy of d to l. */
void diag_push(diag_list *l, const diag *d);
void diag_list_free(diag_list *l);

/* `file:line: severity: text` (or `tarn: severity: text` with no file;
 * a bare diag's text alone). */
void diag_format(const diag *d, char *out, size_t outlen);
/* Every diag of l, one a line, to f. */
void diag_print(const diag_list *l, FILE *f);
/* Every diag of l from index from on, formatted, one a line: a heap string
 * ("" when none), for callers that hand messages on as text (a test, a
 * log shown to the user). */
char *diag_list_format(const diag_list *l, int from);
const char *diag_severity_name(diag_severity s);

#endif
