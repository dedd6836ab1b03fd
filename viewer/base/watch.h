/* watch: tells which watched files changed content, on Linux inotify.
 *
 * The viewer hands over every file a scene depends on (.glib files and their
 * includes, shaders, textures); watch_poll then says which of them a user
 * saved with new content, once per save, whatever the editor does to save:
 *
 *   - writes in place (pwrite into the file, then close);
 *   - truncates and writes, maybe in several write() calls with pauses;
 *   - writes a temp file and renames it over (vim backupcopy=no, VS Code);
 *   - renames the file to a backup (`file~`) and writes a new one (emacs,
 *     vim's default), creating vim's `4913` probe file on the way;
 *   - deletes the file and creates it again.
 *
 * How: the DIRECTORIES of the files are watched (a watch on the file itself
 * would follow the old inode away on a rename). An event for a watched name
 * marks that file dirty; once the file has been quiet for WATCH_QUIET_MS (or
 * at once when its last event was a writer's close and no writer holds it
 * open any more: the save is over, and every ms is the user's) it is hashed (FNV-1a 64 over its bytes) and reported only if the hash differs
 * from the one last recorded, so a save with the same content, or a `touch`,
 * reports nothing. A file still open for writing (modified, no close seen)
 * is given up to WATCH_WRITE_GRACE_MS; a file that disappeared is given up
 * to WATCH_MISSING_GRACE_MS to come back (delete-then-create). A file that
 * stays missing is reported once (its content is gone) and again when it
 * comes back. Files that change in one burst are reported by one poll.
 *
 * A watched directory that is deleted or moved away reports its files as
 * missing; watch_poll keeps trying to watch the path again (at least every
 * WATCH_RETRY_MS while it waits) and, once the directory is back, reports
 * the files whose content differs. A watched path that is a symlink to a
 * file is watched through the link and at its target (as resolved by
 * watch_set_files), so editing the target is seen too.
 *
 * Paths are kept in normalised absolute form: relative ones are resolved
 * against the current directory, then `//`, `.` and `..` are removed
 * lexically (as Go's filepath.Clean does). watch_changed returns that form.
 *
 * No globals: everything lives in one `watch`. Not thread-safe per object.
 */
#ifndef TARN_WATCH_H
#define TARN_WATCH_H

#include <stdbool.h>

#define WATCH_QUIET_MS         20  /* no events for this long: the save is over (its read then
                                      * waits for no writer to hold it, file.h; every ms is the user's) */
#define WATCH_WRITE_GRACE_MS   150 /* most to wait for the close of a file being written, when
                                      * whether a writer still holds it cannot be asked */
#define WATCH_WRITER_MAX_MS  10000 /* ...and while a writer provably still holds it open (a
                                      * stalled save): then the latest read is taken */
#define WATCH_WRITER_POLL_MS    50 /* how often to ask again */
#define WATCH_MISSING_GRACE_MS 200 /* most to wait for a deleted file to come back */
#define WATCH_BATCH_MS         100 /* most a settled file waits for others still busy */
#define WATCH_RETRY_MS         100 /* re-watch a deleted directory at least this often */

typedef struct watch watch;

/* Opens an inotify instance. NULL, with a message in err, on failure. */
watch *watch_create(char *err, int errlen);
void watch_destroy(watch *w); /* NULL is fine */

/* The bytes the watcher reads to hash a file go into c (file_cache.h),
 * where the scene's loads read them. And watch_set_files then takes as a
 * file's baseline what the loads last read of it: a file that changed
 * between a load's read and the watch_set_files after it (a save landing
 * while the scene loads) is reported by the next watch_poll, where without
 * a cache the change would be taken as the baseline and lost. c may be
 * NULL (the default). */
struct file_cache;
void watch_use_cache(watch *w, struct file_cache *c);

/* Replaces the set of watched files with paths[0..n-1] (duplicates are
 * merged). Watches their directories, and records each file's current
 * content hash (a missing file is recorded as missing; a directory or other
 * non-regular file counts as missing). Pending unreported changes are
 * dropped: the new baseline is the content now. Returns false, with a message
 * in err, when a path names no file (empty, ends in `/`, `.` or `..`) or its
 * directory cannot be watched (missing, not a directory, no permission, the
 * inotify watch limit); the previous set then stays in force, unchanged. */
bool watch_set_files(watch *w, const char *const *paths, int n, char *err, int errlen);

/* Waits up to timeout_ms (0: just look, never block; negative: no limit)
 * for watched files to change, and returns how many changed content since
 * they were last reported (or since watch_set_files), after debouncing; the
 * paths are watch_changed(w, 0..n-1). Returns 0 on timeout. A change that is
 * still settling when the time is up is kept for the next call, so polling
 * with 0 once a frame works. */
int watch_poll(watch *w, int timeout_ms);

/* The i-th changed path (normalised absolute) of the last watch_poll; valid
 * until the next watch_poll, watch_set_files or watch_destroy. NULL when i is
 * out of range. */
const char *watch_changed(const watch *w, int i);

/* The inotify fd, for a caller's own poll()/epoll: when it is readable, or
 * when watch_timeout_ms has passed, call watch_poll(w, 0). */
int watch_fd(const watch *w);

/* Milliseconds until a change that is settling is due to be decided: -1 when
 * nothing is pending (wait for the fd alone), 0 when it is due now. Use as
 * the timeout of a caller's own poll() on watch_fd. */
int watch_timeout_ms(const watch *w);

#endif
