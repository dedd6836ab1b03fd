#include "strbuf.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"

static void reserve(strbuf *b, size_t extra) {
    if (b->s && b->len + extra + 1 <= b->cap) return;
    size_t cap = b->cap ? b->cap : 64;
    while (cap < b->len + extra + 1) cap *= 2;
    b->s = mem_realloc(b->s, cap);
    b->cap = cap;
}

void strbuf_put(strbuf *b, const char *s, size_t n) {
    reserve(b, n);
    memcpy(b->s + b->len, s, n);
    b->len += n;
    b->s[b->len] = '\0';
}

void strbuf_puts(strbuf *b, const char *s) { strbuf_put(b, s, strlen(s)); }

void strbuf_vprintf(strbuf *b, const char *fmt, va_list ap) {
    va_list ap2;
    va_copy(ap2, ap);
    int n = vsnprintf(NULL, 0, fmt, ap2);
    va_end(ap2);
    if (n <= 0) {
        reserve(b, 0);
        b->s[b->len] = '\0';   /* an empty append still leaves a string (was unterminated) */
        return;
    }
    reserve(b, (size_t)n);
    vsnprintf(b->s + b->len, (size_t)n + 1, fmt, ap);
    b->len += (size_t)n;
}

void strbuf_printf(strbuf *b, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    strbuf_vprintf(b, fmt, ap);
    va_end(ap);
}

char *strbuf_take(strbuf *b) {
    char *s = b->s ? b->s : mem_strdup("");
    b->s = NULL;
    b->len = b->cap = 0;
    return s;
}

void strbuf_free(strbuf *b) {
    free(b->s);
    b->s = NULL;
    b->len = b->cap = 0;
}

void str_appendf(char **s, const char *fmt, ...) {
    strbuf b = { .s = *s, .len = *s ? strlen(*s) : 0 };
    b.cap = *s ? b.len + 1 : 0;
    va_list ap;
    va_start(ap, fmt);
    strbuf_vprintf(&b, fmt, ap);
    va_end(ap);
    *s = b.s;
}

static void vmsg_at(char *err, size_t errlen, size_t at, const char *fmt, va_list ap) {
    if (!err || errlen == 0 || at >= errlen) return;
    vsnprintf(err + at, errlen - at, fmt, ap);
}

void msg_set(char *err, size_t errlen, const char *fmt, ...) {
    if (!err || errlen == 0) return;
    err[0] = '\0';
    va_list ap;
    va_start(ap, fmt);
    vmsg_at(err, errlen, 0, fmt, ap);
    va_end(ap);
}

void msg_clear(char *err, size_t errlen) {
    if (err && errlen > 0) err[0] = '\0';
}

void msg_add(char *err, size_t errlen, const char *fmt, ...) {
    if (!err || errlen == 0) return;
    size_t len = strnlen(err, errlen - 1);
    err[len] = '\0';
    if (len > 0 && len + 1 < errlen) {
        err[len++] = '\n';
        err[len] = '\0';
    }
    if (len + 1 >= errlen) return;
    va_list ap;
    va_start(ap, fmt);
    vmsg_at(err, errlen, len, fmt, ap);
    va_end(ap);
}
