/* file: reading and writing whole files, and making folders. */
#ifndef TARN_FILE_H
#define TARN_FILE_H

#include <stdbool.h>
#include <stddef.h>

/* The whole file, NUL-terminated (len, may be NULL, excludes the NUL), or
 * NULL with the reason in err when it cannot be opened, is not a regular
 * file, or is larger than max_bytes (0: no limit). */
char *file_read(const char *path, size_t max_bytes, size_t *len, char *err, size_t errlen);

/* file_read for a file a user may be saving right now (the viewer's
 * reload): a read is taken only when the file did not change while it was
 * read (the same size, modification time and inode before and after, and
 * the size read) and was last modified at least FILE_SETTLE_MS ago
 * (FILE_EMPTY_WAIT_MS for an empty file: `cat > f` truncates first, and
 * a file just emptied is "still being written"), else it is read again. A
 * file that has been quiet that long is read once, without waiting. After
 * FILE_SETTLE_MAX_MS the latest read is taken as it is.
 * On failure errno says why as well as err: EISDIR (a folder), EINVAL
 * (another non-regular file), EFBIG (over max_bytes), or open's. */
#define FILE_SETTLE_MS 30
#define FILE_EMPTY_WAIT_MS 100
#define FILE_SETTLE_MAX_MS 250
char *file_read_settled(const char *path, size_t max_bytes, size_t *len, char *err, size_t errlen);

/* Writes n bytes to path (replacing it). False with the reason in err. */
bool file_write(const char *path, const void *data, size_t n, char *err, size_t errlen);

/* mkdir -p: every missing folder of path. False with the reason in err. */
bool file_mkdir_p(const char *path, char *err, size_t errlen);

/* The folder part of path ("a/b.glib" -> "a", "b.glib" -> ".") in out. */
void file_dirname(const char *path, char *out, size_t outlen);

bool file_exists(const char *path);
bool file_is_dir(const char *path);

#endif
