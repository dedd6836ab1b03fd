/* file_cache: the one place tarn reads and hashes the files a scene is made
 * of (.glib files and their includes, shaders and their #includes, OBJ
 * models, textures), for every layer. A reader asks it for a file's bytes
 * by path; it reads the disk only when it holds nothing for the file or the
 * file changed since, else it answers from memory. So a `Define` toggle, a
 * pack switch or the window's compile job rebuilds from the bytes in
 * memory, and a save is read once.
 *
 * When a held copy is trusted: the file's stamp (file.h: device, inode,
 * size, modification and change times) is the one it had when read, it was
 * read with no tighter max_bytes than asked now, and it was already
 * FILE_CACHE_TRUST_MS old when read. The last rule is because the kernel
 * stamps files from a coarse clock: a file written twice within a few ms
 * may keep one stamp, so bytes read that soon after a write are used once
 * and read again next time. The viewer's watcher feeds the cache too
 * (file_cache_refresh): each save it sees is read once, hashed, and kept
 * for the reload that follows.
 *
 * Keys are paths made absolute and cleaned (path.h): "a/../b.frag" and
 * "$PWD/b.frag" are one file. Symlinks are not followed for the key (the
 * stamp is the target's, so an edited target is read again).
 *
 * Thread-safe: the window's compile job reads through the same cache from
 * its thread. Every function takes a NULL cache and then reads the disk,
 * as if nothing were held. */
#ifndef TARN_FILE_CACHE_H
#define TARN_FILE_CACHE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "file.h"

#define FILE_CACHE_TRUST_MS 30

typedef struct file_cache file_cache;

file_cache *file_cache_create(void);
void file_cache_destroy(file_cache *c);   /* NULL is fine */

/* file_read_text, from memory when the held copy is trusted (above): a
 * heap copy the caller frees, with o's text options applied (o may be
 * NULL); NULL with the reason alone in why. *hash (may be NULL): FNV-1a 64
 * (util.h) of the file's bytes as on disk. */
char *file_cache_read(file_cache *c, const char *path, const file_text_opts *o, size_t *len, uint64_t *hash,
                      char *why, size_t whylen);

/* file_read's contract through the cache: the bytes (at most max_bytes, 0
 * no limit), or NULL with "cannot open 'PATH': why" in err. */
char *file_cache_bytes(file_cache *c, const char *path, size_t max_bytes, size_t *len, char *err, size_t errlen);

/* Reads path from disk whatever is held (a watcher saw it change), keeps
 * the bytes and returns their hash in *hash; false (and nothing held) when
 * it is not a regular file that can be read. */
bool file_cache_refresh(file_cache *c, const char *path, uint64_t *hash);

/* The hash of the bytes last read of path (what its readers were last
 * given), without reading: false when nothing is held for it. The watcher
 * compares it with the file now, so a change between a scene's read and
 * the watch that follows is not lost. */
bool file_cache_held(file_cache *c, const char *path, uint64_t *hash);
/* Were path's readers last told it does not exist (a read through the
 * cache found no file there, and none was read since)? The watcher takes
 * a file that exists by the time it is watched as changed: a scene that
 * failed on a missing file is loaded again when the file appears, even
 * when it appeared between the load and the watch (window_app_xvfb's
 * folder made and then filled, under ASAN, 2026-12-07). */
bool file_cache_held_missing(file_cache *c, const char *path);

/* Content tarn makes rather than reads (a generated texture: the caustic
 * tile's photon tracing takes about a second), held under a name that is
 * no path ("@caustics/128"), so a reload, the window's compile job and
 * compare-view's other packs make it once. The first call runs make(user,
 * out, len, err, errlen) to fill len bytes at out and keeps them; later
 * calls with the name copy them to out (len must be the same). The content
 * must depend on the name alone (put every input into it). make runs
 * outside the lock: two threads asking at once may both make it (the same
 * bytes; one is kept). False: make failed (err says why; nothing kept) or
 * len differs from what is held. A NULL cache makes it every time. */
typedef bool (*file_cache_make_fn)(void *user, void *out, size_t len, char *err, size_t errlen);
bool file_cache_made(file_cache *c, const char *name, void *out, size_t len, file_cache_make_fn make, void *user,
                     char *err, size_t errlen);

/* Reads from disk and answers from memory since the cache was made (for
 * tests and benchmarks: a Define toggle must read nothing), and the times
 * file_cache_made's maker ran and succeeded. */
typedef struct file_cache_counts {
    long reads, hits, made;
} file_cache_counts;
file_cache_counts file_cache_counts_of(file_cache *c);

#endif
