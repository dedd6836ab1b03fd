#include "mem.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void *check(void *p, size_t n) {
    if (!p && n) {
        fprintf(stderr, "tarn: out of memory (%zu bytes)\n", n);
        abort();
    }
    return p;
}

void *mem_alloc(size_t n) { return check(malloc(n ? n : 1), n); }
void *mem_zalloc(size_t n) { return check(calloc(1, n ? n : 1), n); }
void *mem_realloc(void *p, size_t n) { return check(realloc(p, n ? n : 1), n); }

char *mem_strndup(const char *s, size_t n) {
    char *d = mem_alloc(n + 1);
    memcpy(d, s, n);
    d[n] = '\0';
    return d;
}

char *mem_strdup(const char *s) { return mem_strndup(s, strlen(s)); }

void *mem_grow(void *p, int *cap, int need, size_t elem) {
    if (need <= *cap) return p;
    int c = *cap > 0 ? *cap : 8;
    while (c < need) c *= 2;
    *cap = c;
    return mem_realloc(p, (size_t)c * elem);
}
