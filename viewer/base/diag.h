/* diag: tarn's one diagnostics type. Every layer that finds a problem in
 * the user's input (the parser, shader assembly and its line mapping, the
 * renderer, the validator) records a diag: severity, file, line, text. One
 * function prints them, as `file:line: warning|error: text`. */
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
} diag;

typedef struct diag_list {
    diag *d;
    int n, cap;
    int nerrors, nwarnings;
} diag_list;

void diag_add(diag_list *l, diag_severity sev, const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
/* Reads `file:line: error: text` lines (a compiler's log, a message
 * buffer) into l, one diag a line: `file: warning: text` has line 0,
 * `tarn: error: text` no file; lines of another shape become diags of
 * severity sev with no file. */
void diag_add_text(diag_list *l, diag_severity sev, const char *text);
void diag_list_free(diag_list *l);

/* `file:line: severity: text` (or `tarn: severity: text` with no file). */
void diag_format(const diag *d, char *out, size_t outlen);
/* Every diag of l, one a line, to f. */
void diag_print(const diag_list *l, FILE *f);
const char *diag_severity_name(diag_severity s);

#endif
