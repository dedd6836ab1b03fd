/* fuzz_shader: libFuzzer target for shader assembly (shader_src_load:
 * #include resolution, #version / #define / GSTAP placement, #pragma once,
 * cycles, depth) and for mapping compiler logs back to files
 * (shader_src_map_log, shader_src_map_diags), then for the hints added to
 * such a log (glsl_hint_add, reading the assembled text for declarations). A
 * geometry stage also runs the GL_EXT_geometry_shader4 rewrite, with the
 * input primitive taken from the size.
 *
 * The input is a small file tree: its parts, split at NUL bytes, are
 *   0: the stage file main.frag
 *   1: a.glsl next to it             (#include "a.glsl")
 *   2: sub/b.glsl                    (#include "sub/b.glsl"; sub/ is an include dir too)
 *   3: a compiler info log to map    (else a log in every format is made up)
 * A part that is absent is a file that does not exist. Fixture files wait
 * in an include directory: common.glsl (#pragma once), waves.glsl (includes
 * common.glsl twice), self.glsl (includes itself), up.glsl (includes
 * ../main.frag: a cycle through the stage file).
 *
 * Invariants beyond "no crash, no report, no leak": a failure has a
 * `file:line: error:` message and no text; a success has text starting
 * with the #version directive (`#version` or `# version`), a hash of that text, and files[0] the stage file. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fuzz_util.h"
#include "glsl_hint.h"
#include "shader_src.h"

int LLVMFuzzerInitialize(int *argc, char ***argv) {
    (void)argc; (void)argv;
    fuzz_scratch("tarn-fuzz-shader");
    fuzz_mkdir("inc");
    fuzz_mkdir("sub");
    fuzz_write_text("inc/common.glsl", "#pragma once\nconst float PI = 3.14159265;\n"
                                       "float sq(float x) { return x * x; }\n");
    fuzz_write_text("inc/waves.glsl", "#version 330 compatibility\n#include \"common.glsl\"\n"
                                      "#include <common.glsl>\nfloat wave(float x) { return sin(PI * x); }\n");
    fuzz_write_text("inc/self.glsl", "// loops\n#include \"self.glsl\"\n");
    fuzz_write_text("inc/up.glsl", "#include \"../main.frag\"\n");
    return 0;
}

static void check(bool ok, const char *what) {
    if (!ok) { fprintf(stderr, "fuzz_shader: invariant broken: %s\n", what); abort(); }
}

/* Writes part k to name, or removes name when the input has no part k. */
static void put_part(const char *name, const uint8_t *parts[4], const size_t lens[4], int nparts, int k) {
    if (k < nparts) fuzz_write(name, parts[k], lens[k]);
    else unlink(fuzz_path(name));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (!fuzz_dir[0]) LLVMFuzzerInitialize(NULL, NULL);
    const uint8_t *parts[4];
    size_t lens[4];
    int nparts = 0;
    const uint8_t *p = data, *end = data + size;
    while (nparts < 4) {
        const uint8_t *z = nparts < 3 ? memchr(p, 0, (size_t)(end - p)) : NULL;
        parts[nparts] = p;
        lens[nparts] = z ? (size_t)(z - p) : (size_t)(end - p);
        nparts++;
        if (!z) break;
        p = z + 1;
    }
    put_part("main.frag", parts, lens, nparts, 0);
    put_part("a.glsl", parts, lens, nparts, 1);
    put_part("sub/b.glsl", parts, lens, nparts, 2);

    static const shader_define defines[] = { { "FOO", "1" }, { "BAR", "" }, { "LEVELS", "4" } };
    const char *dirs[] = { fuzz_path("inc"), "", fuzz_path("sub") };
    shader_src_desc d = {
        .path = fuzz_path("main.frag"),
        .stage = (shader_stage)(size % SHADER_STAGE_COUNT),
        .gstap = (size / SHADER_STAGE_COUNT) % 2 == 1,
        .defines = defines,
        .ndefines = (int)(size % 4),
        .include_dirs = dirs,
        .ninclude_dirs = 3,
        .gs_input = (shader_gs_input)((size / 10) % 5),
    };
    shader_src s;
    bool ok = shader_src_load(&d, &s);
    if (ok) {
        check(s.text != NULL, "text on success");
        /* "#version", or "# version" (a directive may have blanks after '#') */
        const char *v = s.text;
        check(*v == '#', "#version first");
        for (v++; *v == ' ' || *v == '\t'; v++) {}
        check(strncmp(v, "version", 7) == 0, "#version first");
        check(s.nfiles >= 1 && s.files[0] != NULL, "files[0] is the stage file");
        unsigned long long h = 14695981039346656037ull;
        for (const unsigned char *q = (const unsigned char *)s.text; *q; q++) h = (h ^ *q) * 1099511628211ull;
        check(h == s.hash, "hash of the text");
    } else {
        check(s.text == NULL, "no text on failure");
        check(s.error.severity == DIAG_ERROR && s.error.file[0] && s.error.text[0], "a file:line: error: message");
    }
    for (int i = 0; i < s.nfiles; i++) check(s.files[i] != NULL, "no NULL file");

    char *log;
    if (nparts == 4) {
        char *raw = malloc(lens[3] + 1);
        if (!raw) abort();
        memcpy(raw, parts[3], lens[3]);
        raw[lens[3]] = '\0';
        log = shader_src_map_log(&s, raw);
        free(raw);
    } else {
        log = shader_src_map_log(&s, "0:3(7): error: Mesa style\n1:100002(1): warning: in a.glsl\n"
                                     "0:200004: error: line base only\n0(5) : error C0000: NVIDIA style\n"
                                     "ERROR: 2:200001: 'x' : glslang style\nWARNING: 9:1: out of range\n"
                                     "ERROR: 0:99999999999999999999: overflow\nplain text\n");
    }
    check(log != NULL, "map_log returns text");
    diag_list l = { 0 };
    shader_src_map_diags(&s, log, DIAG_NOTE, &l);   /* mapping mapped lines leaves them */
    int n = l.n;
    glsl_hint_add(&l, 0, s.text);
    check(l.n >= n, "hints only add diags");
    diag_list_free(&l);
    free(log);
    (void)shader_stage_name(d.stage);
    (void)shader_stage_from_path(s.nfiles ? s.files[s.nfiles - 1] : "x.frag.glsl");
    shader_src_free(&s);
    return 0;
}
