#define _GNU_SOURCE   /* F_SETLEASE, F_SETSIG (fcntl.h) */
#include "file.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "mem.h"
#include "strbuf.h"
#include "util.h"

/* "8 MiB" for a whole number of MiB, else "N bytes". */
static void size_text(size_t n, char *out, size_t outlen) {
    if (n % ((size_t)1 << 20) == 0)
        msg_set(out, outlen, "%zu MiB", n >> 20);
    else
        msg_set(out, outlen, "%zu bytes", n);
}

/* path opened read-only without blocking (a FIFO put where the file was is
 * refused, not waited on), an interrupted open tried again; -1 with errno
 * set when it cannot be. */
static int open_for_reading(const char *path) {
    int fd;
    do fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    while (fd < 0 && errno == EINTR);
    return fd;
}

/* Appends the regular file at path to b, at most max_bytes of it (0: no
 * limit: a "regular" file such as /proc/self/pagemap would otherwise be
 * read for ever); false with the reason in why. *before and *after: the
 * file's stat before the read and of the open file after it. */
static bool read_all(const char *path, size_t max_bytes, strbuf *b, struct stat *before, struct stat *after,
                     char *why, size_t whylen) {
    /* opened before it is looked at (open_for_reading) */
    int fd = open_for_reading(path);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0) {
        msg_set(why, whylen, "%s", strerror(errno));
        if (fd >= 0) close(fd);
        return false;
    }
    *before = *after = st;
    if (!S_ISREG(st.st_mode)) {
        msg_set(why, whylen, S_ISDIR(st.st_mode) ? "it is a directory" : "it is not a regular file");
        close(fd);
        return false;
    }
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        msg_set(why, whylen, "%s", strerror(errno));
        close(fd);
        return false;
    }
    char chunk[65536];
    size_t n;
    bool big = false;
    while (!big && (n = fread(chunk, 1, sizeof chunk, f)) > 0) {
        big = max_bytes && b->len + n > max_bytes;
        if (!big) strbuf_put(b, chunk, n);
    }
    int bad = ferror(f) ? (errno ? errno : EIO) : 0;
    if (!bad && fstat(fileno(f), after) != 0) bad = errno;
    fclose(f);
    if (big) {
        char lim[32];
        size_text(max_bytes, lim, sizeof lim);
        msg_set(why, whylen, "it is larger than %s", lim);
    } else if (bad) {
        msg_set(why, whylen, "%s", strerror(bad));
    }
    return !big && !bad;
}

/* The line (from 1) of the first NUL byte in s, 0 when there is none. */
static int nul_line(const char *s, size_t n) {
    const char *z = memchr(s, '\0', n);
    int line = 1;
    for (const char *p = s; z && p < z; p++) line += *p == '\n';
    return z ? line : 0;
}

/* Drops the \r of every \r\n in b (NUL-terminated). */
static void crlf_to_lf(strbuf *b) {
    size_t w = 0;
    for (size_t r = 0; r < b->len; r++)
        if (b->s[r] != '\r' || r + 1 == b->len || b->s[r + 1] != '\n') b->s[w++] = b->s[r];
    b->len = w;
    b->s[w] = '\0';
}

/* The wall clock, in ms: the clock files are stamped with. */
static double wall_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static void stamp_of(const struct stat *st, file_stamp *out) {
    out->dev = (unsigned long long)st->st_dev;
    out->ino = (unsigned long long)st->st_ino;
    out->size = (long long)st->st_size;
    out->mtime_ns = (long long)st->st_mtim.tv_sec * 1000000000LL + st->st_mtim.tv_nsec;
    out->ctime_ns = (long long)st->st_ctim.tv_sec * 1000000000LL + st->st_ctim.tv_nsec;
}

static bool same_stat(const struct stat *a, const struct stat *b) {
    return a->st_ino == b->st_ino && a->st_dev == b->st_dev && a->st_size == b->st_size &&
           a->st_mtim.tv_sec == b->st_mtim.tv_sec && a->st_mtim.tv_nsec == b->st_mtim.tv_nsec;
}

/* How long before at_ms (the wall clock, the files' clock) a file was
 * modified; a time in the future (another machine's clock) counts as long ago. */
static double age_at(long long mtime_ns, double at_ms) {
    double age = at_ms - (double)mtime_ns * 1e-6;
    return age < 0 ? 1e9 : age;
}

int file_writer_holds(const char *path) {
    int fd = open_for_reading(path);
    if (fd < 0) return -1;
    /* a lease broken while held signals its holder: SIGIO by default,
     * whose default action ends the process; SIGURG's is to ignore it */
    fcntl(fd, F_SETSIG, SIGURG);
    int r = fcntl(fd, F_SETLEASE, F_RDLCK);
    int err = errno;
    if (r == 0) fcntl(fd, F_SETLEASE, F_UNLCK);
    close(fd);
    return r == 0 ? 0 : err == EAGAIN ? 1 : -1;
}

/* Is a read that was not torn a whole save (file.h)? false: not yet
 * (*wait_ms: how long to wait before reading again). */
static bool read_is_whole(const char *path, const strbuf *b, const file_stamp *stamp, double *wait_ms) {
    int writer = file_writer_holds(path);
    *wait_ms = 5;
    if (writer == 0 && b->len > 0) return true;
    if (writer == 1) return false;
    /* cannot ask: a file quiet for a while is taken; an empty file just
     * truncated is given longer to fill, closed or not (a writer may
     * truncate by path, then open it to write) */
    double age = age_at(stamp->mtime_ns, wall_ms()), settle = b->len == 0 ? FILE_EMPTY_WAIT_MS : FILE_SETTLE_MS;
    if (age >= settle) return true;
    if (b->len > 0) *wait_ms = settle - age + 1;
    return false;
}

/* read_all, and with `settle` again until the file holds still (file.h);
 * *stamp: the file as it was read. */
static bool read_settled(const char *path, const file_text_opts *o, strbuf *b, file_stamp *stamp, char *why,
                         size_t whylen) {
    double start = clock_now_s() * 1e3;
    for (;;) {
        struct stat before, after;
        b->len = 0;
        if (b->s) b->s[0] = '\0';
        double began = wall_ms();
        if (!read_all(path, o->max_bytes, b, &before, &after, why, whylen)) return false;
        stamp_of(&after, stamp);
        stamp->read_ms = began;
        if (!o->settle || clock_now_s() * 1e3 - start >= FILE_SETTLE_MAX_MS) return true;
        /* (/proc and the like say size 0 whatever they hold) */
        bool torn = !same_stat(&before, &after) || ((off_t)b->len != after.st_size && after.st_size != 0);
        double wait_ms = 5;
        if (!torn && read_is_whole(path, b, stamp, &wait_ms)) return true;
        clock_sleep_s(wait_ms / 1e3);
    }
}

char *file_text_finish(char *bytes, size_t *len, const file_text_opts *o, char *why, size_t whylen) {
    static const file_text_opts none = { 0 };
    if (!o) o = &none;
    strbuf b = { .s = bytes, .len = *len, .cap = *len + 1 };
    int nul = o->reject_nul && b.s ? nul_line(b.s, b.len) : 0;
    if (nul) {
        strbuf_free(&b);
        *len = 0;
        msg_set(why, whylen, "binary data (a NUL byte at line %d), not text", nul);
        return NULL;
    }
    if (o->strip_bom && b.len >= 3 && memcmp(b.s, "\xEF\xBB\xBF", 3) == 0) {
        memmove(b.s, b.s + 3, b.len - 2);   /* the NUL too */
        b.len -= 3;
    }
    if (o->crlf_to_lf && b.s) crlf_to_lf(&b);
    *len = b.len;
    return b.s;
}

char *file_read_stamped(const char *path, const file_text_opts *o, size_t *len, file_stamp *stamp, char *why,
                        size_t whylen) {
    static const file_text_opts none = { 0 };
    strbuf b = { 0 };
    *len = 0;
    memset(stamp, 0, sizeof *stamp);
    if (!read_settled(path, o ? o : &none, &b, stamp, why, whylen)) {
        strbuf_free(&b);
        return NULL;
    }
    *len = b.len;
    return strbuf_take(&b);
}

char *file_read_text(const char *path, const file_text_opts *o, size_t *len, char *why, size_t whylen) {
    size_t n = 0;
    file_stamp st;
    char *bytes = file_read_stamped(path, o, &n, &st, why, whylen);
    char *text = bytes ? file_text_finish(bytes, &n, o, why, whylen) : NULL;
    if (len) *len = text ? n : 0;
    return text;
}

bool file_stamp_now(const char *path, file_stamp *out) {
    struct stat st;
    memset(out, 0, sizeof *out);
    if (stat(path, &st) != 0 || !S_ISREG(st.st_mode)) return false;
    stamp_of(&st, out);
    out->read_ms = wall_ms();
    return true;
}

bool file_stamp_same(const file_stamp *a, const file_stamp *b) {
    return a->dev == b->dev && a->ino == b->ino && a->size == b->size && a->mtime_ns == b->mtime_ns &&
           a->ctime_ns == b->ctime_ns;
}

double file_stamp_age_ms(const file_stamp *st) { return age_at(st->mtime_ns, st->read_ms); }

char *file_read(const char *path, size_t max_bytes, size_t *len, char *err, size_t errlen) {
    char why[MSG_MAX];
    file_text_opts o = { .max_bytes = max_bytes };
    char *s = file_read_text(path, &o, len, why, sizeof why);
    if (!s) msg_set(err, errlen, "cannot open '%s': %s", path, why);
    return s;
}

bool file_write(const char *path, const void *data, size_t n, char *err, size_t errlen) {
    FILE *f = fopen(path, "wb");
    if (!f) {
        msg_set(err, errlen, "cannot write '%s': %s", path, strerror(errno));
        return false;
    }
    bool ok = fwrite(data, 1, n, f) == n;
    ok = fclose(f) == 0 && ok;
    if (!ok) msg_set(err, errlen, "cannot write '%s' (disk full?)", path);
    return ok;
}

bool file_mkdir_p(const char *path, char *err, size_t errlen) {
    char p[4096];
    if (!path || !path[0] || strlen(path) >= sizeof p) {
        msg_set(err, errlen, "bad folder name");
        return false;
    }
    snprintf(p, sizeof p, "%s", path);
    for (char *s = p + 1;; s++) {
        bool end = *s == '\0';
        if (*s == '/' || end) {
            *s = '\0';
            if (mkdir(p, 0777) != 0 && errno != EEXIST) {
                msg_set(err, errlen, "cannot make folder '%s': %s", p, strerror(errno));
                return false;
            }
            if (!file_is_dir(p)) {
                msg_set(err, errlen, "'%s' exists and is not a folder", p);
                return false;
            }
            if (end) break;
            *s = '/';
        }
    }
    return true;
}

bool file_exists(const char *path) {
    struct stat st;
    return path && stat(path, &st) == 0;
}

bool file_is_dir(const char *path) {
    struct stat st;
    return path && stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}
