/* replay_main: runs a fuzz target (LLVMFuzzerTestOneInput) over files, the
 * way libFuzzer replays a corpus, in a normal (gcc, or sanitizer) build:
 *
 *     fuzz_replay_glib DIR_OR_FILE...
 *
 * Directories are read in name order. Every crash the fuzzer found is kept
 * as a file under tests/fuzz/regress_*; ctest replays those and the seed
 * corpus here, so a crash that comes back fails an ordinary test. A
 * directory that is missing or empty is an error (a typo must not pass). */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int replay_file(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) { perror(path); return 0; }
    size_t cap = 4096, n = 0, got;
    uint8_t *buf = malloc(cap);
    while (buf && (got = fread(buf + n, 1, cap - n, f)) > 0) {
        n += got;
        if (n == cap) {
            uint8_t *b = realloc(buf, cap *= 2);
            if (!b) { free(buf); buf = NULL; }
            buf = b;
        }
    }
    fclose(f);
    if (!buf) { fprintf(stderr, "%s: out of memory\n", path); return 0; }
    /* an exact-size copy, so reading past the input is caught as libFuzzer would */
    uint8_t *exact = malloc(n ? n : 1);
    if (!exact) { free(buf); return 0; }
    memcpy(exact, buf, n);
    free(buf);
    LLVMFuzzerTestOneInput(exact, n);
    free(exact);
    return 1;
}

static int cmp_names(const void *a, const void *b) {
    return strcmp(*(char *const *)a, *(char *const *)b);
}

int main(int argc, char **argv) {
    LLVMFuzzerInitialize(&argc, &argv);
    int total = 0, bad = 0;
    for (int i = 1; i < argc; i++) {
        struct stat st;
        if (stat(argv[i], &st) != 0) { perror(argv[i]); bad++; continue; }
        if (!S_ISDIR(st.st_mode)) { total += replay_file(argv[i]); continue; }
        DIR *d = opendir(argv[i]);
        if (!d) { perror(argv[i]); bad++; continue; }
        char **names = NULL;
        int n = 0;
        struct dirent *e;
        while ((e = readdir(d)) != NULL) {
            if (e->d_name[0] == '.') continue;
            char **nn = realloc(names, (size_t)(n + 1) * sizeof *names);
            if (!nn) break;
            names = nn;
            names[n++] = strdup(e->d_name);
        }
        closedir(d);
        qsort(names, (size_t)n, sizeof *names, cmp_names);
        int here = 0;
        for (int k = 0; k < n; k++) {
            char path[4096];
            snprintf(path, sizeof path, "%s/%s", argv[i], names[k]);
            if (stat(path, &st) == 0 && S_ISREG(st.st_mode)) here += replay_file(path);
            free(names[k]);
        }
        free(names);
        if (here == 0) { fprintf(stderr, "%s: no inputs\n", argv[i]); bad++; }
        total += here;
    }
    fprintf(stderr, "replayed %d input(s)%s\n", total, bad ? ", with errors" : "");
    return bad ? 1 : 0;
}
