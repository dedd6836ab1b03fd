/* glib_path.c: the files a .glib names (glib_internal.h): resolved
 * relative to the file that names them, with glman's Windows habits
 * (backslashes, names that differ in case) forgiven, and checked readable.
 */
#include "glib_internal.h"
#include "strbuf.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

const char path_hint[] = " (quote a path that has spaces: \"my file.png\")";

/* Paths are relative to the file that names them, so a scene and its
 * shaders move together. Backslashes become slashes: glman ran on Windows
 * and student files say textures\water.bmp. */
bool glib_resolve_path(cmdctx *c, const char *word, char out[GLIB_PATH_MAX]) {
    size_t dirlen = 0;
    if (word[0] != '/' && word[0] != '\\') {
        const char *slash = strrchr(c->file, '/');
        dirlen = slash ? (size_t)(slash - c->file) + 1 : 0;
    }
    size_t wl = strlen(word);
    if (dirlen + wl >= GLIB_PATH_MAX) {
        glib_cerr(c, "%s: path too long (%zu characters, at most %d): '%.40s...'",
             c->spec->name, dirlen + wl, GLIB_PATH_MAX - 1, word);
        return false;
    }
    memcpy(out, c->file, dirlen);
    memcpy(out + dirlen, word, wl + 1);
    for (char *q = out + dirlen; *q; q++)
        if (*q == '\\')
            *q = '/';
    return true;
}

/* In directory dir (a prefix of a path, "" for the current one) finds the
 * entry named like name but for case; into out (of size size). */
static bool case_entry(const char *dir, const char *name, size_t len, char *out, size_t size) {
    DIR *d = opendir(dir[0] ? dir : ".");
    if (!d)
        return false;
    bool found = false;
    struct dirent *e;
    while (!found && (e = readdir(d)) != NULL)
        found = strlen(e->d_name) == len && strncasecmp(e->d_name, name, len) == 0 &&
                strlen(e->d_name) < size;
    if (found)
        memcpy(out, e->d_name, len + 1);
    closedir(d);
    return found;
}

/* glman ran on Windows, where file names ignore case: a project says
 * TEXTURES/Water.BMP for textures/water.bmp. Finds the real name, one
 * path component at a time (a component that exists as written is kept). */
static bool case_match(const char *path, char alt[GLIB_PATH_MAX]) {
    size_t n = 0, i = 0;
    if (path[0] == '/')
        alt[n++] = path[i++];
    alt[n] = '\0';
    while (path[i]) {
        size_t len = strcspn(path + i, "/");
        if (n + len + 1 >= GLIB_PATH_MAX)
            return false;
        memcpy(alt + n, path + i, len);
        alt[n + len] = '\0';
        struct stat st;
        if (stat(alt, &st) != 0) {
            char dir[GLIB_PATH_MAX];
            memcpy(dir, alt, n);
            dir[n] = '\0';
            if (!case_entry(dir, path + i, len, alt + n, GLIB_PATH_MAX - n))
                return false;
        }
        n += len;
        i += len;
        if (path[i] == '/')
            alt[n++] = path[i++];
        alt[n] = '\0';
    }
    return strcmp(alt, path) != 0;
}

/* The renderer reports a missing file too, but only when it gets there;
 * saying it here puts the message next to the line that named it. A name
 * that differs from the file on disk only in case is that file (glman's
 * Windows habit), with a warning naming the real file. */
void glib_check_readable(cmdctx *c, char path[GLIB_PATH_MAX]) {
    char why[MSG_MAX];
    struct stat st;
    if (access(path, R_OK) != 0)
        snprintf(why, sizeof why, "%s", strerror(errno));
    else if (stat(path, &st) == 0 && S_ISDIR(st.st_mode))
        snprintf(why, sizeof why, "it is a directory");
    else
        return;
    char alt[GLIB_PATH_MAX];
    if (case_match(path, alt) && access(alt, R_OK) == 0 && stat(alt, &st) == 0 &&
        !S_ISDIR(st.st_mode)) {
        glib_cwarn(c, "%s: '%s' is '%s' on disk; using it (file names are case-sensitive here, "
                 "not on Windows where glman ran)", c->spec->name, path, alt);
        memcpy(path, alt, strlen(alt) + 1);
        return;
    }
    glib_cerr(c, "cannot open '%s' (from command %s): %s", path, c->spec->name, why);
}

/* Resolves and checks a path; false only when it cannot be stored. A file
 * that is missing now keeps its command: it may appear before the render. */
bool glib_take_path(cmdctx *c, const char *word, char out[GLIB_PATH_MAX]) {
    if (!glib_resolve_path(c, word, out))
        return false;
    glib_check_readable(c, out);
    return true;
}
