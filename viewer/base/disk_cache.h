/* disk_cache: content tarn makes (a generated texture whose photon tracing
 * takes about a second) kept across runs in tarn's cache folder
 * (tarn_cache_dir: $XDG_CACHE_HOME/tarn/made/NAME, else ~/.cache/tarn/...),
 * so `tarn view`, `render` and compare-view do not make it again at every
 * start. Each file holds a key and its length beside the bytes: a read
 * answers only when both match what the caller asks for. The key must
 * change with everything the content depends on; disk_cache_build_key
 * changes whenever the tarn binary does (its code made the content).
 *
 * Nothing here is an error the user must act on: a folder that cannot be
 * made, a full disk or a damaged file only means the content is made
 * again (false). Writes go to a temporary file renamed into place, so two
 * processes writing at once or a reader meeting a half-written file see a
 * whole file or none. */
#ifndef TARN_DISK_CACHE_H
#define TARN_DISK_CACHE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Fills len bytes at out from the file NAME when it holds key and len;
 * false otherwise (out may then be partly written). NAME: letters, digits,
 * '-', '_' and '.' only (no folders). */
bool disk_cache_read(const char *name, uint64_t key, void *out, size_t len);

/* Keeps len bytes under NAME and key, replacing what was there. */
bool disk_cache_write(const char *name, uint64_t key, const void *data, size_t len);

/* A key that changes whenever the running binary changes (its size, time
 * and inode); 0 when it cannot be told (then nothing should be kept). */
uint64_t disk_cache_build_key(void);

#endif
