#include "file_cache.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"
#include "path.h"
#include "strbuf.h"
#include "util.h"

/* One file as last read. */
typedef struct held_file {
    char *key;              /* path_absolute */
    char *bytes;            /* as on disk, NUL-terminated */
    size_t len;
    uint64_t hash;
    file_stamp stamp;       /* when read */
    bool trusted;           /* it was FILE_CACHE_TRUST_MS old when read */
    bool made;              /* file_cache_made's: key is a name, no stamp */
    bool missing;           /* a reader was last told the file does not exist (no bytes) */
} held_file;

struct file_cache {
    pthread_mutex_t lock;
    held_file *files;
    int n, cap;
    file_cache_counts counts;
};

file_cache *file_cache_create(void) {
    file_cache *c = mem_zalloc(sizeof *c);
    pthread_mutex_init(&c->lock, NULL);
    return c;
}

void file_cache_destroy(file_cache *c) {
    if (!c) return;
    for (int i = 0; i < c->n; i++) {
        free(c->files[i].key);
        free(c->files[i].bytes);
    }
    free(c->files);
    pthread_mutex_destroy(&c->lock);
    free(c);
}

/* The file held under key, or NULL. Under the lock. */
static held_file *find(file_cache *c, const char *key) {
    for (int i = 0; i < c->n; i++)
        if (strcmp(c->files[i].key, key) == 0) return &c->files[i];
    return NULL;
}

/* The entry of key, added empty when there is none. Under the lock. */
static held_file *find_or_add(file_cache *c, const char *key) {
    held_file *f = find(c, key);
    if (f) return f;
    c->files = mem_grow(c->files, &c->cap, c->n + 1, sizeof *c->files);
    f = &c->files[c->n++];
    *f = (held_file){ .key = mem_strdup(key) };
    return f;
}

/* A copy of the held bytes of key when they may stand for the file now
 * (file_cache.h), else NULL. */
static char *held_copy(file_cache *c, const char *key, size_t max_bytes, size_t *len, uint64_t *hash) {
    file_stamp now;
    if (!file_stamp_now(key, &now)) return NULL;
    char *copy = NULL;
    pthread_mutex_lock(&c->lock);
    held_file *f = find(c, key);
    if (f && !f->made && f->trusted && file_stamp_same(&f->stamp, &now) && !(max_bytes && f->len > max_bytes)) {
        copy = mem_alloc(f->len + 1);
        memcpy(copy, f->bytes, f->len + 1);
        *len = f->len;
        *hash = f->hash;
        c->counts.hits++;
    }
    pthread_mutex_unlock(&c->lock);
    return copy;
}

/* Keeps a copy of bytes as key's content: trusted when the file was
 * FILE_CACHE_TRUST_MS old as the read began. */
static void hold(file_cache *c, const char *key, const char *bytes, size_t len, uint64_t hash,
                 const file_stamp *stamp) {
    char *copy = mem_alloc(len + 1);
    memcpy(copy, bytes, len + 1);
    pthread_mutex_lock(&c->lock);
    held_file *f = find_or_add(c, key);
    free(f->bytes);
    f->bytes = copy;
    f->missing = false;
    f->len = len;
    f->hash = hash;
    f->stamp = *stamp;
    f->trusted = file_stamp_age_ms(stamp) >= FILE_CACHE_TRUST_MS;
    c->counts.reads++;
    pthread_mutex_unlock(&c->lock);
}

/* A reader found no file at key: kept as such (file_cache_held_missing),
 * over what was held of it before. */
static void hold_missing(file_cache *c, const char *key) {
    pthread_mutex_lock(&c->lock);
    held_file *f = find_or_add(c, key);
    if (!f->made) {
        free(f->bytes);
        f->bytes = NULL;
        f->len = 0;
        f->missing = true;
        f->trusted = false;   /* no bytes to answer a read with */
    }
    pthread_mutex_unlock(&c->lock);
}

/* The file's bytes from memory or disk (kept), or NULL with why. */
static char *bytes_of(file_cache *c, const char *key, const file_text_opts *o, size_t *len, uint64_t *hash,
                      char *why, size_t whylen) {
    char *b = held_copy(c, key, o->max_bytes, len, hash);
    if (b) return b;
    file_stamp stamp;
    b = file_read_stamped(key, o, len, &stamp, why, whylen);
    if (!b) {
        if (!file_exists(key)) hold_missing(c, key);
        return NULL;
    }
    *hash = hash_fnv1a(HASH_FNV1A_BASIS, b, *len);
    hold(c, key, b, *len, *hash, &stamp);
    return b;
}

char *file_cache_read(file_cache *c, const char *path, const file_text_opts *o, size_t *len, uint64_t *hash,
                      char *why, size_t whylen) {
    static const file_text_opts none = { 0 };
    if (!o) o = &none;
    size_t n = 0;
    uint64_t h = 0;
    char *key = c ? path_absolute(path) : NULL;
    char *b;
    if (key) {
        b = bytes_of(c, key, o, &n, &h, why, whylen);
    } else {   /* no cache, or no current directory to make the path absolute */
        file_stamp stamp;
        b = file_read_stamped(path, o, &n, &stamp, why, whylen);
        if (b) h = hash_fnv1a(HASH_FNV1A_BASIS, b, n);
    }
    free(key);
    if (b) b = file_text_finish(b, &n, o, why, whylen);
    if (len) *len = b ? n : 0;
    if (hash) *hash = h;
    return b;
}

char *file_cache_bytes(file_cache *c, const char *path, size_t max_bytes, size_t *len, char *err, size_t errlen) {
    char why[MSG_MAX];
    file_text_opts o = { .max_bytes = max_bytes };
    char *s = file_cache_read(c, path, &o, len, NULL, why, sizeof why);
    if (!s) msg_set(err, errlen, "cannot open '%s': %s", path, why);
    return s;
}

bool file_cache_refresh(file_cache *c, const char *path, uint64_t *hash) {
    char why[MSG_MAX];
    size_t n = 0;
    file_stamp stamp;
    file_text_opts o = { 0 };
    char *b = file_read_stamped(path, &o, &n, &stamp, why, sizeof why);
    if (!b) return false;
    *hash = hash_fnv1a(HASH_FNV1A_BASIS, b, n);
    char *key = c ? path_absolute(path) : NULL;
    if (key) hold(c, key, b, n, *hash, &stamp);
    free(key);
    free(b);
    return true;
}

/* What is held for path: its bytes (*hash), a reader's finding it
 * missing (*missing), or nothing (false). */
static bool held_entry(file_cache *c, const char *path, uint64_t *hash, bool *missing) {
    char *key = c ? path_absolute(path) : NULL;
    if (!key) return false;
    pthread_mutex_lock(&c->lock);
    held_file *f = find(c, key);
    if (f) {
        *hash = f->hash;
        *missing = f->missing;
    }
    pthread_mutex_unlock(&c->lock);
    free(key);
    return f != NULL;
}

bool file_cache_held(file_cache *c, const char *path, uint64_t *hash) {
    bool missing = false;
    return held_entry(c, path, hash, &missing) && !missing;
}

bool file_cache_held_missing(file_cache *c, const char *path) {
    uint64_t hash;
    bool missing = false;
    return held_entry(c, path, &hash, &missing) && missing;
}

bool file_cache_made(file_cache *c, const char *name, void *out, size_t len, file_cache_make_fn make, void *user,
                     char *err, size_t errlen) {
    if (!c) return make(user, out, len, err, errlen);
    bool have = false;
    size_t held_len = 0;
    pthread_mutex_lock(&c->lock);
    held_file *f = find(c, name);
    if (f && f->made) {
        have = true;
        held_len = f->len;
        if (held_len == len) {
            memcpy(out, f->bytes, len);
            c->counts.hits++;
        }
    }
    pthread_mutex_unlock(&c->lock);
    if (have) {
        if (held_len != len) msg_set(err, errlen, "'%s' is held at %zu bytes, asked for %zu", name, held_len, len);
        return held_len == len;
    }
    if (!make(user, out, len, err, errlen)) return false;
    char *copy = mem_alloc(len);
    memcpy(copy, out, len);
    pthread_mutex_lock(&c->lock);
    c->counts.made++;
    f = find(c, name);
    if (f) {
        free(copy);   /* another thread made it meanwhile: the same bytes */
    } else {
        c->files = mem_grow(c->files, &c->cap, c->n + 1, sizeof *c->files);
        c->files[c->n++] = (held_file){ .key = mem_strdup(name), .bytes = copy, .len = len, .made = true };
    }
    pthread_mutex_unlock(&c->lock);
    return true;
}

file_cache_counts file_cache_counts_of(file_cache *c) {
    file_cache_counts k = { 0 };
    if (!c) return k;
    pthread_mutex_lock(&c->lock);
    k = c->counts;
    pthread_mutex_unlock(&c->lock);
    return k;
}
