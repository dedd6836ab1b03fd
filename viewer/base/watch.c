/* watch: see watch.h. */
#include "watch.h"
#include "util.h"

#include "file_cache.h"
#include "mem.h"
#include "path.h"
#include "strbuf.h"

#include <assert.h>
#include <errno.h>
#include <limits.h>
#include <poll.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/inotify.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define MS    ((int64_t)1000000)
#define NEVER INT64_MAX

/* What a watched directory reports. IN_ONLYDIR makes a path that is not a
 * directory fail instead of watching a file. */
#define DIR_MASK                                                                                                       \
    (IN_CLOSE_WRITE | IN_MOVED_TO | IN_CREATE | IN_DELETE | IN_MODIFY | IN_MOVED_FROM | IN_ATTRIB | IN_DELETE_SELF |   \
     IN_MOVE_SELF | IN_ONLYDIR)

typedef struct watch_dir {
    char *path;
    int wd; /* -1: not watched now (deleted or moved away) */
} watch_dir;

typedef struct watch_key { /* where events for a file arrive */
    int dir;               /* index into dirs */
    char *base;            /* the name in that directory */
} watch_key;

typedef struct watch_file {
    char *path;       /* normalised absolute */
    watch_key key[2]; /* [0] the path itself; [1] a symlink's target */
    int nkeys;
    bool present;    /* recorded: the file existed */
    uint64_t hash;   /* recorded content hash, when present */
    bool dirty;      /* an event came since it was last decided */
    bool writing;    /* modified or created, no close seen yet */
    bool closed;     /* its last event was a writer's close (IN_CLOSE_WRITE) */
    int64_t last_ns; /* time of its last event */
} watch_file;

struct watch {
    int fd;
    file_cache *cache;   /* where what is read to hash it is kept (may be NULL) */
    watch_dir *dirs;
    int ndirs;
    watch_file *files;
    int nfiles;
    int *changed; /* indices into files, capacity nfiles */
    int nchanged;
    int64_t retry_ns; /* last re-watch attempt of a lost directory */
    int64_t next_ns;  /* when a pending file is next due (NEVER: none) */
    char *evbuf;      /* inotify read buffer */
};

enum { EVBUF_SIZE = 64 * 1024 };

static int64_t min64(int64_t a, int64_t b) { return a < b ? a : b; }

/* ---- paths -------------------------------------------------------------- */

/* The last component as written, before normalisation: a file path must end
 * in a name, not in "", "." or "..". */
static bool names_a_file(const char *path) {
    size_t len = strlen(path);
    if (len == 0 || path[len - 1] == '/') return false;
    const char *slash = strrchr(path, '/');
    const char *last = slash ? slash + 1 : path;
    return strcmp(last, ".") != 0 && strcmp(last, "..") != 0;
}

/* Splits a normalised absolute path into freshly allocated directory and
 * base name. */
static void split_path(const char *path, char **dir, char **base) {
    const char *slash = strrchr(path, '/');
    size_t dlen = (size_t)(slash - path);
    *dir = dlen ? mem_strndup(path, dlen) : mem_strdup("/");
    *base = mem_strdup(slash + 1);
}

/* ---- content ------------------------------------------------------------ */

static bool is_regular(const char *path) {
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* ---- tables ------------------------------------------------------------- */

static void free_tables(watch_dir *dirs, int ndirs, watch_file *files, int nfiles) {
    for (int i = 0; i < ndirs; i++) free(dirs[i].path);
    for (int i = 0; i < nfiles; i++) {
        free(files[i].path);
        for (int k = 0; k < files[i].nkeys; k++) free(files[i].key[k].base);
    }
    free(dirs);
    free(files);
}

static bool dirs_have_wd(const watch_dir *dirs, int ndirs, int wd) {
    for (int i = 0; i < ndirs; i++)
        if (dirs[i].wd == wd) return true;
    return false;
}

/* Watches `path` (a directory) for the new table *dirs and returns its
 * index, reusing an entry with the same path or the same watch (the same
 * directory reached by another path). -1 with errno set when inotify refuses
 * it. */
static int add_dir(watch *w, watch_dir **dirs, int *ndirs, int *cap, const char *path) {
    for (int i = 0; i < *ndirs; i++)
        if (strcmp((*dirs)[i].path, path) == 0) return i;
    int wd = inotify_add_watch(w->fd, path, DIR_MASK);
    if (wd < 0) return -1;
    for (int i = 0; i < *ndirs; i++)
        if ((*dirs)[i].wd == wd) return i;
    *dirs = mem_grow(*dirs, cap, *ndirs + 1, sizeof **dirs);
    (*dirs)[*ndirs] = (watch_dir){ .path = mem_strdup(path), .wd = wd };
    return (*ndirs)++;
}

/* ---- events ------------------------------------------------------------- */

static void mark_dirty(watch_file *f, int64_t t) {
    f->dirty = true;
    f->last_ns = t;
}

static void mark_dir_dirty(watch *w, int dir, int64_t t) {
    for (int i = 0; i < w->nfiles; i++)
        for (int k = 0; k < w->files[i].nkeys; k++)
            if (w->files[i].key[k].dir == dir) {
                mark_dirty(&w->files[i], t);
                w->files[i].writing = w->files[i].closed = false;
            }
}

static void handle_event(watch *w, const struct inotify_event *ev, int64_t t) {
    if (ev->mask & IN_Q_OVERFLOW) { /* events were lost: look at everything */
        for (int i = 0; i < w->nfiles; i++) {
            mark_dirty(&w->files[i], t);
            w->files[i].writing = w->files[i].closed = false;
        }
        return;
    }
    for (int d = 0; d < w->ndirs; d++) {
        watch_dir *dir = &w->dirs[d];
        if (dir->wd != ev->wd) continue;
        if (ev->mask & (IN_IGNORED | IN_DELETE_SELF | IN_MOVE_SELF | IN_UNMOUNT)) {
            /* The directory is gone from its path; what was watched is not
             * there. A moved directory keeps its watch: drop it (its
             * IN_IGNORED will arrive for a wd we no longer hold). */
            if (ev->mask & IN_MOVE_SELF) inotify_rm_watch(w->fd, dir->wd);
            if (ev->mask & (IN_IGNORED | IN_MOVE_SELF)) dir->wd = -1;
            mark_dir_dirty(w, d, t);
            continue;
        }
        if (ev->len == 0) continue;
        for (int i = 0; i < w->nfiles; i++) {
            watch_file *f = &w->files[i];
            for (int k = 0; k < f->nkeys; k++) {
                if (f->key[k].dir != d || strcmp(f->key[k].base, ev->name) != 0) continue;
                mark_dirty(f, t);
                f->closed = (ev->mask & IN_CLOSE_WRITE) != 0;
                if (ev->mask & (IN_CLOSE_WRITE | IN_MOVED_TO | IN_DELETE | IN_MOVED_FROM))
                    f->writing = false;
                else if ((ev->mask & IN_MODIFY) || ((ev->mask & IN_CREATE) && !(ev->mask & IN_ISDIR)))
                    f->writing = true;
            }
        }
    }
}

/* Reads and handles every queued event, without blocking. */
static void drain(watch *w) {
    for (;;) {
        ssize_t got = read(w->fd, w->evbuf, EVBUF_SIZE);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) return; /* EAGAIN: empty */
        int64_t t = clock_now_ns();
        for (char *p = w->evbuf; p < w->evbuf + got;) {
            const struct inotify_event *ev = (const struct inotify_event *)(void *)p;
            handle_event(w, ev, t);
            p += sizeof *ev + ev->len;
        }
    }
}

static bool any_lost_dir(const watch *w) {
    for (int d = 0; d < w->ndirs; d++)
        if (w->dirs[d].wd < 0) return true;
    return false;
}

/* Tries to watch again the directories that were deleted or moved away; one
 * that is back makes its files dirty (they are compared by content). */
static void retry_lost_dirs(watch *w, int64_t t) {
    if (!any_lost_dir(w)) return;
    w->retry_ns = t;
    for (int d = 0; d < w->ndirs; d++) {
        if (w->dirs[d].wd >= 0) continue;
        int wd = inotify_add_watch(w->fd, w->dirs[d].path, DIR_MASK);
        if (wd < 0) continue;
        w->dirs[d].wd = wd;
        mark_dir_dirty(w, d, t);
    }
}

/* ---- deciding ----------------------------------------------------------- */

/* Is f still being written: its close not seen, and either within the
 * grace or a writer provably holding it (up to WATCH_WRITER_MAX_MS)?
 * *until gets when to look again. */
static bool still_writing(const watch_file *f, int64_t t, int64_t *until) {
    if (!f->writing) return false;
    *until = f->last_ns + WATCH_WRITE_GRACE_MS * MS;
    if (t < *until) return true;
    if (t < f->last_ns + WATCH_WRITER_MAX_MS * MS && file_writer_holds(f->path) == 1) {
        *until = t + WATCH_WRITER_POLL_MS * MS;
        return true;
    }
    return false;
}

/* When f's burst of events is over: WATCH_QUIET_MS after its last event,
 * or at that event when it was the writer's close and no other writer
 * holds the file open (the save is over: an editor's write-and-close is
 * taken at once, not a fixed time later). */
static int64_t quiet_at(const watch_file *f) {
    if (f->closed && file_writer_holds(f->path) != 1) return f->last_ns;
    return f->last_ns + WATCH_QUIET_MS * MS;
}

/* Decides the dirty files that have settled, appending the changed ones to
 * w->changed. Returns when the next undecided file is due (NEVER if none). */
static int64_t decide(watch *w, int64_t t) {
    int64_t next = NEVER, earliest_ready = NEVER;
    bool busy = false;
    int nready = 0;
    for (int i = 0; i < w->nfiles; i++) {
        watch_file *f = &w->files[i];
        if (!f->dirty) continue;
        int64_t quiet = quiet_at(f);
        int64_t ready_at = quiet;
        if (t < quiet) { /* still in a burst */
            busy = true;
            if (quiet < next) next = quiet;
            continue;
        }
        int64_t until;
        if (still_writing(f, t, &until)) { /* wait for the close */
            if (until < next) next = until;
            continue;
        }
        if (f->writing) {
            ready_at = t;
        } else if (f->present && !is_regular(f->path)) { /* wait for it to come back */
            int64_t back = f->last_ns + WATCH_MISSING_GRACE_MS * MS;
            if (t < back) {
                if (back < next) next = back;
                continue;
            }
            ready_at = back;
        }
        nready++;
        if (ready_at < earliest_ready) earliest_ready = ready_at;
    }
    if (nready == 0) return next;
    /* Let files of the same burst that are still busy join, for a while. */
    if (busy && t < earliest_ready + WATCH_BATCH_MS * MS) {
        int64_t batch_at = earliest_ready + WATCH_BATCH_MS * MS;
        return batch_at < next ? batch_at : next;
    }
    for (int i = 0; i < w->nfiles; i++) {
        watch_file *f = &w->files[i];
        if (!f->dirty || t < quiet_at(f)) continue;
        int64_t again;
        if (still_writing(f, t, &again)) continue;
        uint64_t h = 0;
        bool present = file_cache_refresh(w->cache, f->path, &h);
        if (!present && f->present && !f->writing && t < f->last_ns + WATCH_MISSING_GRACE_MS * MS) {
            next = min64(next, f->last_ns + WATCH_MISSING_GRACE_MS * MS);
            continue; /* gone just now: wait for it */
        }
        f->dirty = false;
        f->writing = false;
        if (present == f->present && (!present || h == f->hash)) continue;
        f->present = present;
        f->hash = h;
        w->changed[w->nchanged++] = i;
    }
    return next;
}

/* ---- API ---------------------------------------------------------------- */

watch *watch_create(char *err, int errlen) {
    watch *w = mem_zalloc(sizeof *w);
    w->evbuf = mem_alloc(EVBUF_SIZE);
    w->next_ns = NEVER;
    w->fd = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    if (w->fd < 0) {
        msg_set(err, (size_t)errlen, "watch: cannot start inotify: %s%s", strerror(errno),
                errno == EMFILE ? " (raise fs.inotify.max_user_instances)" : "");
        free(w->evbuf);
        free(w);
        return NULL;
    }
    return w;
}

void watch_use_cache(watch *w, file_cache *c) { w->cache = c; }

void watch_destroy(watch *w) {
    if (!w) return;
    close(w->fd);
    free_tables(w->dirs, w->ndirs, w->files, w->nfiles);
    free(w->changed);
    free(w->evbuf);
    free(w);
}

/* Records f's content now as its baseline. With a cache, a file whose
 * content differs from what its readers were last given (changed between
 * the scene's read and this watch, which no event of the new set can tell)
 * keeps what they read as its baseline and is due at once: the next poll
 * reports it; so does one they found missing that exists now. */
static void record_baseline(watch *w, watch_file *f) {
    uint64_t read_hash = 0;
    bool was_read = file_cache_held(w->cache, f->path, &read_hash);
    if (file_cache_held_missing(w->cache, f->path)) {   /* its readers found none: one now is a change */
        f->present = false;
        f->hash = 0;
        f->dirty = is_regular(f->path);
        f->last_ns = clock_now_ns() - WATCH_QUIET_MS * MS;
        return;
    }
    f->present = file_cache_refresh(w->cache, f->path, &f->hash);
    if (!was_read || (f->present && f->hash == read_hash)) return;
    f->present = true;
    f->hash = read_hash;
    f->dirty = true;
    f->last_ns = clock_now_ns() - WATCH_QUIET_MS * MS;
}

bool watch_set_files(watch *w, const char *const *paths, int n, char *err, int errlen) {
    watch_dir *dirs = NULL;
    watch_file *files = NULL;
    int ndirs = 0, dcap = 0, nfiles = 0;
    int *changed = NULL;
    char *norm = NULL, *dpath = NULL, *base = NULL;
    char *real = NULL, *rdir = NULL, *rbase = NULL;
    bool any_since_read = false;

    assert(w && (paths || n <= 0));
    if (n < 0) n = 0;
    drain(w); /* keep the old set's directory states current */
    if (n > 0) {
        files = mem_zalloc((size_t)n * sizeof *files);
        changed = mem_zalloc((size_t)n * sizeof *changed);
    }
    for (int i = 0; i < n; i++) {
        const char *p = paths[i];
        if (!p || !names_a_file(p)) {
            msg_set(err, (size_t)errlen, "watch: '%s' does not name a file", p ? p : "(null)");
            goto fail;
        }
        norm = path_absolute(p);
        if (!norm) {
            msg_set(err, (size_t)errlen, "watch: cannot resolve '%s': %s", p, strerror(errno));
            goto fail;
        }
        bool dup = false;
        for (int j = 0; j < nfiles && !dup; j++) dup = strcmp(files[j].path, norm) == 0;
        if (dup) {
            free(norm);
            norm = NULL;
            continue;
        }
        split_path(norm, &dpath, &base);
        int d = add_dir(w, &dirs, &ndirs, &dcap, dpath);
        if (d < 0) {
            int e = errno;
            msg_set(err, (size_t)errlen, "watch: cannot watch directory '%s' of '%s': %s%s", dpath, p, strerror(e),
                    e == ENOSPC ? " (raise fs.inotify.max_user_watches)" : "");
            goto fail;
        }
        watch_file *f = &files[nfiles++];
        f->path = norm;
        f->key[0] = (watch_key){ .dir = d, .base = base };
        f->nkeys = 1;
        norm = base = NULL;
        free(dpath);
        dpath = NULL;

        /* A symlink: watch its target's directory too (best effort). */
        struct stat st;
        if (lstat(f->path, &st) == 0 && S_ISLNK(st.st_mode) && (real = realpath(f->path, NULL))) {
            split_path(real, &rdir, &rbase);
            int d2 = add_dir(w, &dirs, &ndirs, &dcap, rdir);
            if (d2 >= 0 && !(dirs[d2].wd == dirs[d].wd && strcmp(rbase, f->key[0].base) == 0)) {
                f->key[1] = (watch_key){ .dir = d2, .base = rbase };
                f->nkeys = 2;
                rbase = NULL;
            }
        }
        free(real);
        free(rdir);
        free(rbase);
        real = rdir = rbase = NULL;

        record_baseline(w, f);
        any_since_read |= f->dirty;
    }

    /* Success: drop the watches the new set no longer needs. */
    for (int d = 0; d < w->ndirs; d++)
        if (w->dirs[d].wd >= 0 && !dirs_have_wd(dirs, ndirs, w->dirs[d].wd)) inotify_rm_watch(w->fd, w->dirs[d].wd);
    free_tables(w->dirs, w->ndirs, w->files, w->nfiles);
    free(w->changed);
    w->dirs = dirs;
    w->ndirs = ndirs;
    w->files = files;
    w->nfiles = nfiles;
    w->changed = changed;
    w->nchanged = 0;
    w->next_ns = any_since_read ? clock_now_ns() : NEVER;
    return true;

fail:
    /* Roll back: remove the watches that only the new set had added. */
    for (int d = 0; d < ndirs; d++)
        if (!dirs_have_wd(w->dirs, w->ndirs, dirs[d].wd)) inotify_rm_watch(w->fd, dirs[d].wd);
    free_tables(dirs, ndirs, files, nfiles);
    free(changed);
    free(norm);
    free(dpath);
    free(base);
    free(real);
    free(rdir);
    free(rbase);
    return false;
}

int watch_poll(watch *w, int timeout_ms) {
    assert(w);
    w->nchanged = 0;
    int64_t deadline = timeout_ms < 0 ? NEVER : clock_now_ns() + (int64_t)timeout_ms * MS;
    for (;;) {
        drain(w);
        int64_t t = clock_now_ns();
        if (any_lost_dir(w) && t - w->retry_ns >= WATCH_RETRY_MS * MS) retry_lost_dirs(w, t);
        int64_t next = decide(w, t);
        w->next_ns = next;
        if (w->nchanged > 0) return w->nchanged;
        if (t >= deadline) return 0;
        int64_t wake = min64(deadline, next);
        if (any_lost_dir(w)) wake = min64(wake, t + WATCH_RETRY_MS * MS);
        int wait_ms = -1;
        if (wake != NEVER) {
            int64_t ms = (wake - t + MS - 1) / MS;
            wait_ms = ms > INT_MAX ? INT_MAX : (int)ms;
        }
        struct pollfd pfd = { .fd = w->fd, .events = POLLIN };
        if (poll(&pfd, 1, wait_ms) < 0 && errno != EINTR) return 0;
    }
}

const char *watch_changed(const watch *w, int i) {
    if (!w || i < 0 || i >= w->nchanged) return NULL;
    return w->files[w->changed[i]].path;
}

int watch_fd(const watch *w) {
    assert(w);
    return w->fd;
}

int watch_timeout_ms(const watch *w) {
    assert(w);
    int64_t t = clock_now_ns(), next = w->next_ns;
    if (any_lost_dir(w)) next = min64(next, w->retry_ns + WATCH_RETRY_MS * MS);
    if (next == NEVER) return -1;
    if (next <= t) return 0;
    int64_t ms = (next - t + MS - 1) / MS;
    return ms > INT_MAX ? INT_MAX : (int)ms;
}
