/* disk_cache: content kept across runs (see disk_cache.h). */
#include "disk_cache.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "file.h"
#include "util.h"

#define MAGIC "tarnmade"   /* 8 bytes: a file of this module */

typedef struct header {
    char magic[8];
    uint64_t key, len;
} header;

static bool name_ok(const char *name) {
    if (!name || !name[0] || name[0] == '.') return false;
    for (const char *s = name; *s; s++)
        if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || (*s >= '0' && *s <= '9') || *s == '-' ||
              *s == '_' || *s == '.'))
            return false;
    return true;
}

/* dir/made, and the file's path in it */
static bool paths(const char *name, char *dir, size_t dlen, char *path, size_t plen) {
    char cache[2048];
    if (!name_ok(name) || !tarn_cache_dir(cache, sizeof cache)) return false;
    int n = snprintf(dir, dlen, "%s/made", cache);
    int m = snprintf(path, plen, "%s/made/%s", cache, name);
    return n > 0 && (size_t)n < dlen && m > 0 && (size_t)m < plen;
}

bool disk_cache_read(const char *name, uint64_t key, void *out, size_t len) {
    char dir[4096], path[4096];
    if (key == 0 || !paths(name, dir, sizeof dir, path, sizeof path)) return false;
    FILE *f = fopen(path, "rb");
    if (!f) return false;
    header h;
    bool ok = fread(&h, sizeof h, 1, f) == 1 && memcmp(h.magic, MAGIC, 8) == 0 && h.key == key && h.len == len &&
              fread(out, 1, len, f) == len && fgetc(f) == EOF;   /* nothing more: not another file's tail */
    fclose(f);
    return ok;
}

bool disk_cache_write(const char *name, uint64_t key, const void *data, size_t len) {
    char dir[4096], path[4096], tmp[4200], err[256];
    if (key == 0 || !paths(name, dir, sizeof dir, path, sizeof path)) return false;
    if (!file_mkdir_p(dir, err, sizeof err)) return false;
    snprintf(tmp, sizeof tmp, "%s.%ld.tmp", path, (long)getpid());
    FILE *f = fopen(tmp, "wb");
    if (!f) return false;
    header h = { .key = key, .len = len };
    memcpy(h.magic, MAGIC, 8);
    bool ok = fwrite(&h, sizeof h, 1, f) == 1 && fwrite(data, 1, len, f) == len;
    ok = fclose(f) == 0 && ok;
    if (ok) ok = rename(tmp, path) == 0;
    if (!ok) remove(tmp);
    return ok;
}

uint64_t disk_cache_build_key(void) {
    struct stat st;
    if (stat("/proc/self/exe", &st) != 0) return 0;
    uint64_t parts[5] = { (uint64_t)st.st_size, (uint64_t)st.st_mtim.tv_sec, (uint64_t)st.st_mtim.tv_nsec,
                          (uint64_t)st.st_ino, (uint64_t)st.st_dev };
    uint64_t k = hash_fnv1a(HASH_FNV1A_BASIS, parts, sizeof parts);
    return k ? k : 1;
}
