/* file: reading and writing whole files, and making folders. */
#ifndef TARN_FILE_H
#define TARN_FILE_H

#include <stdbool.h>
#include <stddef.h>

/* The whole file, NUL-terminated (len, may be NULL, excludes the NUL), or
 * NULL with the reason in err when it cannot be opened, is not a regular
 * file, or is larger than max_bytes (0: no limit). */
char *file_read(const char *path, size_t max_bytes, size_t *len, char *err, size_t errlen);

/* Writes n bytes to path (replacing it). False with the reason in err. */
bool file_write(const char *path, const void *data, size_t n, char *err, size_t errlen);

/* mkdir -p: every missing folder of path. False with the reason in err. */
bool file_mkdir_p(const char *path, char *err, size_t errlen);

/* The folder part of path ("a/b.glib" -> "a", "b.glib" -> ".") in out. */
void file_dirname(const char *path, char *out, size_t outlen);

bool file_exists(const char *path);
bool file_is_dir(const char *path);

#endif
