/* mem: tarn's one out-of-memory policy. Inputs are bounded where they are
 * read (the parser's limits, image and target sizes clamped), so running
 * out of memory is not bad input but a machine that cannot go on: these
 * wrappers print "tarn: out of memory (N bytes)" and abort, and no caller
 * checks for NULL. Code that asks for a size a user chose (a render target,
 * an image) checks that size against its limit first. */
#ifndef TARN_MEM_H
#define TARN_MEM_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

void *mem_alloc(size_t n);  /* malloc */
void *mem_zalloc(size_t n); /* calloc(1, n) */
void *mem_realloc(void *p, size_t n);
char *mem_strdup(const char *s);
char *mem_strndup(const char *s, size_t n);
/* Room for need elements of elem bytes in p, whose capacity *cap grows by
 * doubling (from 8): the one growing array. Returns p, moved perhaps. */
void *mem_grow(void *p, int *cap, int need, size_t elem);

#ifdef __cplusplus
}
#endif

#endif
