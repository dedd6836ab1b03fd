#include "file.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "mem.h"
#include "strbuf.h"

/* One read of the whole file, with its stat before (*before) and after
 * (*after). NULL with err and errno set on failure. */
static char *read_once(const char *path, size_t max_bytes, size_t *len, struct stat *before,
                       struct stat *after, char *err, size_t errlen) {
    *len = 0;
    if (stat(path, before) != 0) {
        int e = errno;
        msg_set(err, errlen, "cannot open '%s': %s", path, strerror(e));
        errno = e;
        return NULL;
    }
    if (!S_ISREG(before->st_mode)) {
        msg_set(err, errlen, "'%s' is not a regular file", path);
        errno = S_ISDIR(before->st_mode) ? EISDIR : EINVAL;
        return NULL;
    }
    FILE *f = fopen(path, "rb");
    if (!f) {
        int e = errno;
        msg_set(err, errlen, "cannot open '%s': %s", path, strerror(e));
        errno = e;
        return NULL;
    }
    strbuf b = { 0 };
    char chunk[65536];
    size_t n;
    while ((n = fread(chunk, 1, sizeof chunk, f)) > 0) {
        if (max_bytes && b.len + n > max_bytes) {
            fclose(f);
            strbuf_free(&b);
            msg_set(err, errlen, "'%s' is larger than %zu bytes", path, max_bytes);
            errno = EFBIG;
            return NULL;
        }
        strbuf_put(&b, chunk, n);
    }
    int bad = ferror(f) ? (errno ? errno : EIO) : 0;
    if (!bad && fstat(fileno(f), after) != 0) bad = errno;
    fclose(f);
    if (bad) {
        strbuf_free(&b);
        msg_set(err, errlen, "cannot read '%s'", path);
        errno = bad;
        return NULL;
    }
    *len = b.len;
    if (!b.s) return mem_strdup("");
    return strbuf_take(&b);
}

char *file_read(const char *path, size_t max_bytes, size_t *len, char *err, size_t errlen) {
    struct stat before, after;
    size_t n = 0;
    char *s = read_once(path, max_bytes, &n, &before, &after, err, errlen);
    if (len) *len = n;
    return s;
}

static double now_ms(clockid_t clock) {
    struct timespec ts;
    clock_gettime(clock, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static void sleep_ms(double ms) {
    struct timespec ts = { (time_t)(ms / 1e3), (long)(fmod(ms, 1e3) * 1e6) };
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR) {}
}

static bool same_stat(const struct stat *a, const struct stat *b) {
    return a->st_ino == b->st_ino && a->st_dev == b->st_dev && a->st_size == b->st_size &&
           a->st_mtim.tv_sec == b->st_mtim.tv_sec && a->st_mtim.tv_nsec == b->st_mtim.tv_nsec;
}

/* How long ago the file was modified, in ms (the file's clock is the wall
 * clock); a time in the future (another machine's clock) counts as long ago. */
static double age_ms(const struct stat *st) {
    double m = (double)st->st_mtim.tv_sec * 1e3 + (double)st->st_mtim.tv_nsec * 1e-6;
    double age = now_ms(CLOCK_REALTIME) - m;
    return age < 0 ? 1e9 : age;
}

char *file_read_settled(const char *path, size_t max_bytes, size_t *len, char *err, size_t errlen) {
    double start = now_ms(CLOCK_MONOTONIC);
    for (;;) {
        struct stat before, after;
        size_t n = 0;
        char *s = read_once(path, max_bytes, &n, &before, &after, err, errlen);
        double waited = now_ms(CLOCK_MONOTONIC) - start;
        if (!s || waited >= FILE_SETTLE_MAX_MS) {   /* a failure is not waited out */
            if (len) *len = n;
            return s;
        }
        /* (/proc and the like say size 0 whatever they hold) */
        bool torn = !same_stat(&before, &after) || ((off_t)n != after.st_size && after.st_size != 0);
        /* an empty file just truncated (`cat >`) is given longer to fill */
        double age = age_ms(&after), settle = n == 0 ? FILE_EMPTY_WAIT_MS : FILE_SETTLE_MS;
        bool young = age < settle;
        if (!torn && !young) {
            if (len) *len = n;
            return s;
        }
        free(s);
        sleep_ms(young && n > 0 ? settle - age + 1 : 5);
    }
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

void file_dirname(const char *path, char *out, size_t outlen) {
    const char *slash = strrchr(path, '/');
    if (!slash)
        snprintf(out, outlen, ".");
    else if (slash == path)
        snprintf(out, outlen, "/");
    else
        snprintf(out, outlen, "%.*s", (int)(slash - path), path);
}

bool file_exists(const char *path) {
    struct stat st;
    return path && stat(path, &st) == 0;
}

bool file_is_dir(const char *path) {
    struct stat st;
    return path && stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}
