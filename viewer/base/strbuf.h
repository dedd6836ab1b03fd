/* strbuf: a growing string (the one string builder), and msg_*: messages
 * into a caller's fixed buffer (the `char *err, int errlen` convention of
 * functions that can fail). */
#ifndef TARN_STRBUF_H
#define TARN_STRBUF_H

#include <stdarg.h>
#include <stddef.h>

typedef struct strbuf {
    char *s; /* NUL-terminated; NULL until the first append */
    size_t len, cap;
} strbuf;

void strbuf_put(strbuf *b, const char *s, size_t n);
void strbuf_puts(strbuf *b, const char *s);
void strbuf_printf(strbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void strbuf_vprintf(strbuf *b, const char *fmt, va_list ap);
/* The string ("" when empty), owned by the caller; b is empty again. */
char *strbuf_take(strbuf *b);
void strbuf_free(strbuf *b);

/* Appends to a heap string (*s may be NULL): the renderer's logs. */
void str_appendf(char **s, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* The one size of a message buffer of that convention (`char err[MSG_MAX]`,
 * `char why[MSG_MAX]`): a path of up to 1024 bytes and a few sentences, or
 * a few such lines. One size, so a message handed on from one buffer to
 * another is never cut on the way. */
#define MSG_MAX 4096

/* err (may be NULL or errlen 0) := the message / += one more line (a
 * newline first when err is not empty) / := "". Truncated to fit, never
 * overrun. */
void msg_set(char *err, size_t errlen, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
void msg_add(char *err, size_t errlen, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
void msg_clear(char *err, size_t errlen);

#endif
