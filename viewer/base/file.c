#include "file.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "mem.h"
#include "strbuf.h"

char *file_read(const char *path, size_t max_bytes, size_t *len, char *err, size_t errlen) {
    if (len) *len = 0;
    struct stat st;
    if (stat(path, &st) != 0) {
        msg_set(err, errlen, "cannot open '%s': %s", path, strerror(errno));
        return NULL;
    }
    if (!S_ISREG(st.st_mode)) {
        msg_set(err, errlen, "'%s' is not a regular file", path);
        return NULL;
    }
    FILE *f = fopen(path, "rb");
    if (!f) {
        msg_set(err, errlen, "cannot open '%s': %s", path, strerror(errno));
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
            return NULL;
        }
        strbuf_put(&b, chunk, n);
    }
    bool bad = ferror(f);
    fclose(f);
    if (bad) {
        strbuf_free(&b);
        msg_set(err, errlen, "cannot read '%s'", path);
        return NULL;
    }
    if (len) *len = b.len;
    return strbuf_take(&b);
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
