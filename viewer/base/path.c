#include "path.h"

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mem.h"

char *path_clean(const char *path) {
    size_t len = strlen(path);
    char *out = mem_alloc(len + 2);
    bool abs = path[0] == '/';
    /* where each component kept starts in out, to pop it on ".." */
    size_t *starts = mem_alloc((len / 2 + 2) * sizeof *starts);
    int ncomp = 0, nup = 0;   /* nup: leading ".." kept in a relative path */
    size_t o = 0;
    if (abs) out[o++] = '/';
    for (const char *p = path; *p;) {
        while (*p == '/') p++;
        if (!*p) break;
        const char *e = strchr(p, '/');
        size_t n = e ? (size_t)(e - p) : strlen(p);
        if (n == 2 && p[0] == '.' && p[1] == '.') {
            if (ncomp > nup) {   /* drop the last name and the '/' before it */
                o = starts[--ncomp];
                if (o > (abs ? 1u : 0u)) o--;
            } else if (!abs) {   /* above a relative start: kept */
                if (o > 0) out[o++] = '/';
                starts[ncomp++] = o;
                nup++;
                out[o++] = '.';
                out[o++] = '.';
            }                    /* ("/.." is "/") */
        } else if (!(n == 1 && p[0] == '.')) {
            if (o > 0 && out[o - 1] != '/') out[o++] = '/';
            starts[ncomp++] = o;
            memcpy(out + o, p, n);
            o += n;
        }
        p += n;
    }
    if (o == 0) out[o++] = '.';
    out[o] = '\0';
    free(starts);
    return out;
}

/* The current directory, heap; NULL (errno set) when it is gone. */
static char *current_dir(void) {
    for (size_t cap = 256;; cap *= 2) {
        char *buf = mem_alloc(cap);
        if (getcwd(buf, cap)) return buf;
        free(buf);
        if (errno != ERANGE) return NULL;
    }
}

char *path_absolute(const char *path) {
    if (path[0] == '/') return path_clean(path);
    char *cwd = current_dir();
    if (!cwd) return NULL;
    char *r = path_join(cwd, path);
    free(cwd);
    return r;
}

char *path_dir(const char *path) {
    const char *slash = strrchr(path, '/');
    if (!slash) return mem_strdup(".");
    if (slash == path) return mem_strdup("/");
    return mem_strndup(path, (size_t)(slash - path));
}

char *path_join(const char *dir, const char *name) {
    if (name[0] == '/' || !dir || !dir[0] || strcmp(dir, ".") == 0) return path_clean(name);
    size_t n = strlen(dir) + strlen(name) + 2;
    char *j = mem_alloc(n);
    snprintf(j, n, "%s/%s", dir, name);
    char *r = path_clean(j);
    free(j);
    return r;
}
