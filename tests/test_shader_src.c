/* Tests of shader_src: include resolution, #version/#define/GSTAP placement,
 * line mapping of compiler logs, errors with file:line, the hash.
 *
 * The line mapping is checked against a small model of a GLSL compiler's
 * line counting (`#line` semantics per version, and Mesa's habit of
 * reporting source string 0), writing logs in the Mesa, NVIDIA and glslang
 * formats; test_validate checks the same with glslang itself. */
#include "check.h"
#include "support.h"
#include "shader_src.h"

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>


/* s's assembly error as tarn prints it, `file:line: error: message`
 * (ERR: into a buffer that lives as long as the statement using it). */
static const char *error_line(const shader_src *s, char *buf, size_t n) {
    diag_format(&s->error, buf, n);
    return buf;
}
#define ERR_MAX (DIAG_FILE_MAX + DIAG_TEXT_MAX + 32)
#define ERR(s) error_line(&(s), (char[ERR_MAX]){ 0 }, ERR_MAX)

static bool mem_has(const char *p, size_t n, const char *needle) {
    size_t k = strlen(needle);
    for (size_t i = 0; i + k <= n; i++)
        if (memcmp(p + i, needle, k) == 0) return true;
    return false;
}

static bool load(shader_src *s, const char *name, shader_stage st, const shader_define *defs, int ndefs,
                 bool gstap) {
    const char *dirs[] = { shader_data("repo/packs/common") };
    shader_src_desc d = { .path = shader_data(name), .stage = st, .gstap = gstap, .defines = defs,
                          .ndefines = ndefs, .include_dirs = dirs, .ninclude_dirs = 1 };
    return shader_src_load(&d, s);
}

/* A model compiler: walks the text as a GLSL front end counts lines and
 * reports every line holding "undefined_" as an error, in `format`
 * ('m' Mesa, 'n' NVIDIA, 'g' glslang). mesa_drops_string reports source
 * string 0 whatever `#line` said, as Mesa 22 does for semantic errors. */
static char *fake_compile(const char *text, char format, bool mesa_drops_string) {
    int version = 0;
    bool es = false;
    sscanf(text, "#version %d", &version);
    if (strstr(text, "#version") == text) {
        const char *nl = strchr(text, '\n');
        es = nl && mem_has(text, (size_t)(nl - text), " es");
    }
    bool old_rule = !es && version < 330;
    char *log = calloc(1, 1);
    size_t loglen = 0;
    long line = 1, str = 0;
    const char *p = text;
    while (*p) {
        const char *e = strchr(p, '\n');
        size_t n = e ? (size_t)(e - p) : strlen(p);
        long nline, nstr;
        char tmp[256];
        if (n < sizeof tmp) { memcpy(tmp, p, n); tmp[n] = '\0'; } else tmp[0] = '\0';
        if (sscanf(tmp, "#line %ld %ld", &nline, &nstr) == 2) {
            line = old_rule ? nline + 1 : nline;
            str = nstr;
        } else {
            if (strstr(tmp, "undefined_")) {
                char msg[512];
                const char *id = strstr(tmp, "undefined_");
                char name[64];
                sscanf(id, "%63[A-Za-z0-9_]", name);
                if (format == 'm')
                    snprintf(msg, sizeof msg, "%ld:%ld(9): error: `%s' undeclared\n",
                             mesa_drops_string ? 0 : str, line, name);
                else if (format == 'n')
                    snprintf(msg, sizeof msg, "%ld(%ld) : error C1008: undefined variable \"%s\"\n",
                             str, line, name);
                else
                    snprintf(msg, sizeof msg, "ERROR: %ld:%ld: '%s' : undeclared identifier \n", str, line, name);
                size_t ml = strlen(msg);
                log = realloc(log, loglen + ml + 1);
                memcpy(log + loglen, msg, ml + 1);
                loglen += ml;
            }
            line++;
        }
        if (!e) break;
        p = e + 1;
    }
    return log;
}

/* The mapped log names `file_suffix:line: ` for identifier `name`. */
static bool mapped_has(const char *mapped, const char *file_suffix, int line, const char *name) {
    char want[256];
    snprintf(want, sizeof want, "%s:%d: ", file_suffix, line);
    for (const char *p = mapped; (p = strstr(p, want)) != NULL; p++) {
        const char *eol = strchr(p, '\n');
        const char *n = strstr(p, name);
        if (n && (!eol || n < eol)) return true;
    }
    return false;
}

static void test_includes_and_line_map(void) {
    shader_src s;
    bool ok = load(&s, "map_main.frag", SHADER_FRAGMENT, NULL, 0, false);
    CHECK_MSG(ok, "%s", ERR(s));
    if (!ok) { shader_src_free(&s); return; }
    CHECK_EQ(s.nfiles, 3);
    CHECK_STR_CONTAINS(s.files[0], "map_main.frag");
    CHECK_STR_CONTAINS(s.files[1], "inc/map_waves.glsl");
    CHECK_STR_CONTAINS(s.files[2], "inc/map_fresnel.glsl");
    CHECK_EQ(strncmp(s.text, "#version 330 compatibility\n", 27), 0);
    CHECK_EQ(strstr(s.text, "#include"), NULL);
    for (int drop = 0; drop <= 1; drop++) {
        const char formats[] = { 'm', 'n', 'g' };
        for (int f = 0; f < 3; f++) {
            if (drop && formats[f] != 'm') continue;
            char *log = fake_compile(s.text, formats[f], drop);
            char *mapped = shader_src_map_log(&s, log);
            CHECK_MSG(mapped_has(mapped, "map_main.frag", 7, "undefined_in_main"), "%c: %s", formats[f], mapped);
            CHECK_MSG(mapped_has(mapped, "inc/map_waves.glsl", 4, "undefined_in_waves"), "%c: %s", formats[f], mapped);
            CHECK_MSG(mapped_has(mapped, "inc/map_fresnel.glsl", 4, "undefined_in_fresnel"), "%c: %s", formats[f], mapped);
            if (formats[f] == 'g') CHECK_STR_CONTAINS(mapped, "map_main.frag:7: error: 'undefined_in_main' : undeclared identifier\n");
            if (formats[f] == 'm') CHECK_STR_CONTAINS(mapped, "map_main.frag:7: error: `undefined_in_main' undeclared\n");
            if (formats[f] == 'n') CHECK_STR_CONTAINS(mapped, "map_main.frag:7: error C1008: undefined variable");
            free(mapped);
            free(log);
        }
    }
    shader_src_free(&s);
}

static void test_old_version_line_rule(void) {
    shader_src s;
    bool ok = load(&s, "old120.vert", SHADER_VERTEX, NULL, 0, false);
    CHECK_MSG(ok, "%s", ERR(s));
    if (!ok) { shader_src_free(&s); return; }
    CHECK_EQ(strncmp(s.text, "#version 120\n", 13), 0);
    char *log = fake_compile(s.text, 'm', false);
    char *mapped = shader_src_map_log(&s, log);
    CHECK_MSG(mapped_has(mapped, "old120.vert", 5, "undefined_in_old"), "%s", mapped);
    free(mapped);
    free(log);
    shader_src_free(&s);
}

static void test_no_version_gets_glman_default(void) {
    shader_src s;
    bool ok = load(&s, "noversion.frag", SHADER_FRAGMENT, NULL, 0, false);
    CHECK_MSG(ok, "%s", ERR(s));
    if (!ok) { shader_src_free(&s); return; }
    CHECK_EQ(strncmp(s.text, "#version 330 compatibility", 26), 0);
    const char *nl = strchr(s.text, '\n');
    CHECK(nl && mem_has(s.text, (size_t)(nl - s.text), "//"));     /* says why, in a comment */
    CHECK_STR_CONTAINS(s.text, "#line 1 0\n");
    char *log = fake_compile(s.text, 'g', false);
    char *mapped = shader_src_map_log(&s, log);
    CHECK_MSG(mapped_has(mapped, "noversion.frag", 4, "undefined_in_noversion"), "%s", mapped);
    free(mapped);
    free(log);
    shader_src_free(&s);
}

static void test_defines_and_gstap_follow_version(void) {
    shader_define defs[2] = { { "FOO", "1" }, { "EMPTY", "" } };
    shader_src s;
    bool ok = load(&s, "gstap.vert", SHADER_VERTEX, defs, 2, true);
    CHECK_MSG(ok, "%s", ERR(s));
    if (!ok) { shader_src_free(&s); return; }
    CHECK_EQ(strncmp(s.text, "#version 330 compatibility\n", 27), 0);
    const char *foo = strstr(s.text, "#define FOO 1\n");
    const char *empty = strstr(s.text, "#define EMPTY\n");
    const char *avertex = strstr(s.text, "#define aVertex gl_Vertex\n");
    const char *line = strstr(s.text, "#line 2 0\n");
    CHECK(foo && empty && avertex && line);
    CHECK(foo < empty && empty < avertex && avertex < line);
    CHECK_STR_CONTAINS(s.text, "#define aTexCoord7 gl_MultiTexCoord7\n");
    CHECK_STR_CONTAINS(s.text, "#define aNormal gl_Normal\n");
    CHECK_STR_CONTAINS(s.text, "#define aColor gl_Color\n");
    CHECK_STR_CONTAINS(s.text, "#define uModelViewProjectionMatrix gl_ModelViewProjectionMatrix\n");
    CHECK_STR_CONTAINS(s.text, "#define uModelViewMatrixInverse gl_ModelViewMatrixInverse\n");
    /* no #version-breaking text before the prologue ends */
    CHECK_GT(strstr(s.text, "gstap.vert: glman's GSTAP"), line);
    shader_src_free(&s);

    /* fragment: matrices and aColor (gl_Color, the interpolated colour), no attributes */
    ok = load(&s, "gstap.frag", SHADER_FRAGMENT, NULL, 0, true);
    CHECK_MSG(ok, "%s", ERR(s));
    if (ok) {
        CHECK_STR_CONTAINS(s.text, "#define uNormalMatrix gl_NormalMatrix\n");
        CHECK_STR_CONTAINS(s.text, "#define aColor gl_Color\n");
        CHECK_EQ(strstr(s.text, "aVertex"), NULL);
        CHECK_EQ(strstr(s.text, "aTexCoord0"), NULL);
    }
    shader_src_free(&s);

    /* geometry: matrices only (its colours are gl_in[i].gl_FrontColor) */
    shader_src_desc gd = { .path = shader_data("gstap.frag"), .stage = SHADER_GEOMETRY, .gstap = true };
    ok = shader_src_load(&gd, &s);
    CHECK_MSG(ok, "%s", ERR(s));
    if (ok) {
        CHECK_STR_CONTAINS(s.text, "#define uNormalMatrix gl_NormalMatrix\n");
        CHECK_EQ(strstr(s.text, "aColor"), NULL);
    }
    shader_src_free(&s);

    /* without gstap: nothing */
    ok = load(&s, "gstap.vert", SHADER_VERTEX, NULL, 0, false);
    CHECK(ok);
    if (ok) CHECK_EQ(strstr(s.text, "#define"), NULL);
    shader_src_free(&s);
}

static void test_missing_include_is_file_line_error(void) {
    shader_src s;
    CHECK(!load(&s, "missing_inc.frag", SHADER_FRAGMENT, NULL, 0, false));
    CHECK_STR_CONTAINS(ERR(s), "missing_inc.frag:3: error: ");
    CHECK_STR_CONTAINS(ERR(s), "no_such_file.glsl");
    CHECK_EQ(s.text, NULL);
    CHECK_GE(s.nfiles, 1);          /* the watcher still watches the stage file */
    shader_src_free(&s);
}

static void test_include_cycle_is_file_line_error(void) {
    shader_src s;
    CHECK(!load(&s, "cycle_main.frag", SHADER_FRAGMENT, NULL, 0, false));
    CHECK_STR_CONTAINS(ERR(s), "inc/cycle_b.glsl:3: error: include cycle");
    CHECK_STR_CONTAINS(ERR(s), "cycle_a.glsl -> ");
    CHECK_EQ(s.nfiles, 3);
    shader_src_free(&s);
}

static void test_missing_stage_file(void) {
    shader_src s;
    CHECK(!load(&s, "no_such_stage.frag", SHADER_FRAGMENT, NULL, 0, false));
    CHECK_STR_CONTAINS(ERR(s), "no_such_stage.frag:0: error: cannot read shader");
    shader_src_free(&s);
    /* a directory is unreadable too */
    CHECK(!load(&s, "inc", SHADER_FRAGMENT, NULL, 0, false));
    CHECK_STR_CONTAINS(ERR(s), ":0: error: cannot read shader");
    shader_src_free(&s);
}

static void test_bad_define_name(void) {
    shader_define defs[1] = { { "2BAD", "1" } };
    shader_src s;
    CHECK(!load(&s, "good_compat.frag", SHADER_FRAGMENT, defs, 1, false));
    CHECK_STR_CONTAINS(ERR(s), "2BAD");
    shader_src_free(&s);
    shader_define gl[1] = { { "GL_MINE", "1" } };
    CHECK(!load(&s, "good_compat.frag", SHADER_FRAGMENT, gl, 1, false));
    CHECK_STR_CONTAINS(ERR(s), "GL_MINE");
    shader_src_free(&s);
}

/* A scratch directory, for files the test writes. */
static char g_tmp[256];

static void write_file(const char *name, const char *text) {
    char path[512];
    snprintf(path, sizeof path, "%s/%s", g_tmp, name);
    FILE *f = fopen(path, "wb");
    if (!f) { perror(path); return; }
    fputs(text, f);
    fclose(f);
}

static const char *tmp(const char *name) {
    static char buf[4][512];
    static int i;
    i = (i + 1) % 4;
    snprintf(buf[i], sizeof buf[i], "%s/%s", g_tmp, name);
    return buf[i];
}

static void test_include_depth_limit(void) {
    /* d0 includes d1 ... includes d40: 40 levels */
    for (int i = 0; i <= 40; i++) {
        char name[32], text[128];
        snprintf(name, sizeof name, "d%d.glsl", i);
        if (i < 40) snprintf(text, sizeof text, "// level %d\n#include \"d%d.glsl\"\n", i, i + 1);
        else snprintf(text, sizeof text, "float deepest() { return 1.0; }\n");
        write_file(name, text);
    }
    write_file("deep.frag", "#version 330 compatibility\n#include \"d0.glsl\"\nvoid main() {}\n");
    shader_src s;
    shader_src_desc d = { .path = tmp("deep.frag"), .stage = SHADER_FRAGMENT };
    CHECK(!shader_src_load(&d, &s));
    CHECK_STR_CONTAINS(ERR(s), "d31.glsl:2: error: #include nested too deeply");
    shader_src_free(&s);

    /* 32 levels are fine */
    write_file("d32.glsl", "float deepest() { return 1.0; }\n");
    write_file("deep32.frag", "#version 330 compatibility\n#include \"d1.glsl\"\nvoid main() {}\n");
    d.path = tmp("deep32.frag");
    bool ok = shader_src_load(&d, &s);
    CHECK_MSG(ok, "%s", ERR(s));
    CHECK_EQ(s.nfiles, 33);
    shader_src_free(&s);
}

static void test_hash_changes_iff_text_changes(void) {
    write_file("h.frag", "#version 330 compatibility\nvoid main() { gl_FragColor = vec4(1.0); }\n");
    shader_src_desc d = { .path = tmp("h.frag"), .stage = SHADER_FRAGMENT };
    shader_src a, b;
    CHECK(shader_src_load(&d, &a));
    CHECK(shader_src_load(&d, &b));
    CHECK(a.hash == b.hash && strcmp(a.text, b.text) == 0);
    shader_src_free(&b);

    shader_define on[1] = { { "FOO", "1" } };
    d.defines = on;
    d.ndefines = 1;
    CHECK(shader_src_load(&d, &b));
    CHECK(a.hash != b.hash && strcmp(a.text, b.text) != 0);
    shader_src_free(&b);
    d.defines = NULL;
    d.ndefines = 0;

    write_file("h.frag", "#version 330 compatibility\nvoid main() { gl_FragColor = vec4(0.5); }\n");
    CHECK(shader_src_load(&d, &b));
    CHECK_NE(a.hash, b.hash);
    shader_src_free(&b);

    /* the same text again: the same hash (CRLF is read as LF) */
    write_file("h.frag", "#version 330 compatibility\r\nvoid main() { gl_FragColor = vec4(1.0); }\r\n");
    CHECK(shader_src_load(&d, &b));
    CHECK_EQ(a.hash, b.hash);
    shader_src_free(&b);

    /* an included file's change shows too */
    write_file("hi.glsl", "float k() { return 1.0; }\n");
    write_file("h2.frag", "#version 330 compatibility\n#include \"hi.glsl\"\nvoid main() {}\n");
    d.path = tmp("h2.frag");
    shader_src c1, c2;
    CHECK(shader_src_load(&d, &c1));
    write_file("hi.glsl", "float k() { return 2.0; }\n");
    CHECK(shader_src_load(&d, &c2));
    CHECK_NE(c1.hash, c2.hash);
    shader_src_free(&c1);
    shader_src_free(&c2);
    shader_src_free(&a);
}

static void test_include_search_order_and_once(void) {
    /* next to the includer first, then the include dirs; <> alike */
    char sub[300];
    snprintf(sub, sizeof sub, "%s/sub", g_tmp);
    mkdir(sub, 0755);
    write_file("sub/common.glsl", "float from_dir() { return 1.0; }\n");
    write_file("local.glsl", "#pragma once\nfloat from_local() { return 1.0; }\n");
    write_file("o.frag", "#version 330 compatibility\n#include \"local.glsl\"\n#include <common.glsl>\n"
                         "#include \"local.glsl\"\nvoid main() {}\n");
    const char *dirs[] = { sub };
    shader_src_desc d = { .path = tmp("o.frag"), .stage = SHADER_FRAGMENT, .include_dirs = dirs,
                          .ninclude_dirs = 1 };
    shader_src s;
    bool ok = shader_src_load(&d, &s);
    CHECK_MSG(ok, "%s", ERR(s));
    if (ok) {
        CHECK_EQ(s.nfiles, 3);
        CHECK_STR_CONTAINS(s.files[2], "sub/common.glsl");
        const char *first = strstr(s.text, "from_local");
        CHECK(first && strstr(first + 1, "from_local") == NULL);   /* #pragma once */
        CHECK_EQ(strstr(s.text, "#pragma once"), NULL);
        /* numbering survives the skipped include: main() is line 5 */
        char *log = NULL;
        const char *m = strstr(s.text, "void main");
        /* count the line the model compiler gives main() */
        size_t off = (size_t)(m - s.text);
        char *cut = strndup(s.text, off);
        char *full = malloc(off + 64);
        snprintf(full, off + 64, "%sundefined_main_here\n", cut);
        log = fake_compile(full, 'g', false);
        char *mapped = shader_src_map_log(&s, log);
        CHECK_MSG(mapped_has(mapped, "o.frag", 5, "undefined_main_here"), "%s", mapped);
        free(mapped);
        free(log);
        free(full);
        free(cut);
    }
    shader_src_free(&s);
}

static void test_version_line_with_comment_tail(void) {
    /* a block comment opened on the #version line, code after it */
    write_file("t.frag", "// header comment\n#version 330 core /* a comment\n  that goes on */\n"
                         "out vec4 c;\nvoid main() { c = undefined_tail; }\n");
    shader_src_desc d = { .path = tmp("t.frag"), .stage = SHADER_FRAGMENT };
    shader_define defs[1] = { { "X", "2" } };
    d.defines = defs;
    d.ndefines = 1;
    shader_src s;
    bool ok = shader_src_load(&d, &s);
    CHECK_MSG(ok, "%s", ERR(s));
    if (ok) {
        CHECK_EQ(strncmp(s.text, "#version 330 core\n#define X 2\n", 30), 0);
        char *log = fake_compile(s.text, 'g', false);
        char *mapped = shader_src_map_log(&s, log);
        CHECK_MSG(mapped_has(mapped, "t.frag", 5, "undefined_tail"), "%s\n---\n%s", mapped, s.text);
        free(mapped);
        free(log);
    }
    shader_src_free(&s);
}

/* The text between the first occurrence of a and of b comes in that order. */
static bool before(const char *text, const char *a, const char *b) {
    const char *pa = strstr(text, a), *pb = strstr(text, b);
    return pa && pb && pa < pb;
}

/* A geometry shader written for GL_EXT_geometry_shader4 (glman's): GLSL
 * 1.50's names, its #extension line gone, #version 150 compatibility, the
 * layouts it lacks after the file's own #extension lines, and messages
 * still on the user's lines. */
static void test_ext_geometry_shader_rewritten(void) {
    write_file("ext.geom", "#version 120\n"
               "#extension GL_EXT_geometry_shader4 : enable\n"
               "#extension GL_ARB_gpu_shader5 : enable\n"
               "\n"
               "varying in vec3 vN[gl_VerticesIn];\n"                       /* 5 */
               "varying out vec3 gN;\n"
               "varying  float gF;  // gl_PositionIn in a comment\n"
               "void main() {\n"
               "  for (int i = 0; i < gl_VerticesIn; i++) {\n"
               "    gl_FrontColor = gl_FrontColorIn[i]; gl_TexCoord[0] = gl_TexCoordIn[ i ][0];\n"   /* 10 */
               "    gl_Position = gl_PositionIn [idx[i]] + undefined_gs;\n"
               "    EmitVertex();\n"
               "  }\n"
               "}\n");
    shader_src_desc d = { .path = tmp("ext.geom"), .stage = SHADER_GEOMETRY };
    shader_src s;
    bool ok = shader_src_load(&d, &s);
    CHECK_MSG(ok, "%s", ERR(s));
    if (ok) {
        CHECK_EQ(strncmp(s.text, "#version 150 compatibility", 26), 0);
        CHECK_STR_CONTAINS(s.text, "in vec3 vN[gl_in.length()];\n");
        CHECK_STR_CONTAINS(s.text, "\nout vec3 gN;\n");
        CHECK_STR_CONTAINS(s.text, "\nout  float gF;");   /* the blanks after `varying` stay */
        CHECK_STR_CONTAINS(s.text, "i < gl_in.length();");
        CHECK_STR_CONTAINS(s.text, "gl_FrontColor = gl_in[i].gl_FrontColor;");
        CHECK_STR_CONTAINS(s.text, "gl_TexCoord[0] = gl_in[ i ].gl_TexCoord[0];");
        CHECK_STR_CONTAINS(s.text, "gl_Position = gl_in[idx[i]].gl_Position + undefined_gs;");
        CHECK_EQ(strstr(s.text, "varying"), NULL);
        CHECK_EQ(strstr(s.text, "#extension GL_EXT_geometry_shader4"), NULL);
        CHECK(before(s.text, "#extension GL_ARB_gpu_shader5", "layout(triangles) in;"));
        CHECK(before(s.text, "layout(triangles) in;", "layout(triangle_strip, max_vertices = 64) out;"));
        CHECK(before(s.text, "max_vertices = 64) out;", "in vec3 vN["));
        char *log = fake_compile(s.text, 'm', false);
        char *mapped = shader_src_map_log(&s, log);
        CHECK_MSG(mapped_has(mapped, "ext.geom", 11, "undefined_gs"), "%s\n---\n%s", mapped, s.text);
        free(mapped);
        free(log);
    }
    shader_src_free(&s);

    /* the draw decides the input primitive */
    d.gs_input = SHADER_GS_IN_TRIANGLES_ADJACENCY;
    ok = shader_src_load(&d, &s);
    CHECK(ok && strstr(s.text, "layout(triangles_adjacency) in;"));
    shader_src_free(&s);
    d.gs_input = SHADER_GS_IN_LINES_ADJACENCY;
    ok = shader_src_load(&d, &s);
    CHECK(ok && strstr(s.text, "layout(lines_adjacency) in;"));
    shader_src_free(&s);

    /* a file's own layouts stay alone; only the missing one is added; no
     * #version: glman's 330 compatibility already has geometry shaders */
    write_file("own.geom", "layout( points )  in ;\n"
               "void main() { gl_Position = gl_in[0].gl_Position + undefined_own; EmitVertex(); }\n");
    shader_src_desc d2 = { .path = tmp("own.geom"), .stage = SHADER_GEOMETRY };
    ok = shader_src_load(&d2, &s);
    CHECK_MSG(ok, "%s", ERR(s));
    if (ok) {
        CHECK_EQ(strncmp(s.text, "#version 330 compatibility", 26), 0);
        CHECK_EQ(strstr(s.text, "layout(triangles)"), NULL);
        CHECK(before(s.text, "layout(triangle_strip, max_vertices = 64) out;", "layout( points )"));
        char *log = fake_compile(s.text, 'g', false);
        char *mapped = shader_src_map_log(&s, log);
        CHECK_MSG(mapped_has(mapped, "own.geom", 2, "undefined_own"), "%s\n---\n%s", mapped, s.text);
        free(mapped);
        free(log);
    }
    shader_src_free(&s);
    write_file("both.geom", "#version 400\nlayout(triangles) in;\n/* layout(x) out; */\n"
               "layout(line_strip, max_vertices = 2) out;\nvoid main() { }\n");
    shader_src_desc d3 = { .path = tmp("both.geom"), .stage = SHADER_GEOMETRY };
    ok = shader_src_load(&d3, &s);
    CHECK(ok && strncmp(s.text, "#version 400\n", 13) == 0 && !strstr(s.text, "tarn: glman's output"));
    shader_src_free(&s);

    /* layouts from an include count too */
    write_file("lay.glsl", "layout(triangles) in;\nlayout(triangle_strip, max_vertices = 3) out;\n");
    write_file("inc.geom", "#include \"lay.glsl\"\nvoid main() { gl_Position = gl_in[0].gl_Position; }\n");
    shader_src_desc d5 = { .path = tmp("inc.geom"), .stage = SHADER_GEOMETRY };
    ok = shader_src_load(&d5, &s);
    CHECK_MSG(ok && !strstr(s.text, "tarn: the input primitive") && !strstr(s.text, "tarn: glman's output"),
              "%s", ok ? s.text : ERR(s));
    shader_src_free(&s);

    /* only geometry shaders are rewritten */
    write_file("v.vert", "#version 120\nvarying vec3 gl_PositionInX;\nvoid main() { }\n");
    shader_src_desc d4 = { .path = tmp("v.vert"), .stage = SHADER_VERTEX };
    ok = shader_src_load(&d4, &s);
    CHECK(ok && strstr(s.text, "varying vec3 gl_PositionInX;") && !strstr(s.text, "layout"));
    shader_src_free(&s);
}

/* layout(binding = N) before GLSL 4.20 enables GL_ARB_shading_language_420pack
 * (before any code, the lines still the user's); not from 4.20 on, not for
 * a binding in a comment, not twice. Likewise a uniform's layout(location). */
static void test_binding_enables_420pack(void) {
    static const struct { const char *text; bool want; } cases[] = {
        { "#version 330 compatibility\nlayout(binding = 3) uniform sampler2D t;\n"
          "void main() { gl_FragColor = undefined_b; }\n", true },
        { "layout(location = 0, binding=3) uniform sampler2D t;\nvoid main() { }\n", true },
        { "#version 420\nlayout(binding = 3) uniform sampler2D t;\nvoid main() { }\n", false },
        { "#version 330\n// layout(binding = 3)\nuniform sampler2D t;\nvoid main() { }\n", false },
        { "#version 330\n#extension GL_ARB_shading_language_420pack : require\n"
          "layout(binding = 3) uniform sampler2D t;\nvoid main() { }\n", false },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        write_file("b.frag", cases[i].text);
        shader_src_desc d = { .path = tmp("b.frag"), .stage = SHADER_FRAGMENT, .gstap = true };
        shader_src s;
        bool ok = shader_src_load(&d, &s);
        CHECK_MSG(ok, "%s", ERR(s));
        if (!ok) { shader_src_free(&s); continue; }
        const char *ext = strstr(s.text, "#extension GL_ARB_shading_language_420pack : enable");
        CHECK_MSG((ext != NULL) == cases[i].want, "case %zu:\n%s", i, s.text);
        if (ext) CHECK(before(s.text, "#version", "#extension") && before(s.text, "#extension", "#line"));
        if (i == 0) {
            char *log = fake_compile(s.text, 'm', false);
            char *mapped = shader_src_map_log(&s, log);
            CHECK_MSG(mapped_has(mapped, "b.frag", 3, "undefined_b"), "%s", mapped);
            free(mapped);
            free(log);
        }
        shader_src_free(&s);
    }
    /* a uniform's layout(location) before 4.30: GL_ARB_explicit_uniform_location;
     * an input's needs nothing */
    static const struct { const char *text; bool want; } loc[] = {
        { "#version 330 compatibility\nlayout(location = 3) uniform float uK;\nvoid main() { }\n", true },
        { "#version 330\nlayout(location = 0) in vec3 p;\nlayout(location=0) out vec4 c;\nvoid main() { }\n",
          false },
        { "#version 430\nlayout(location = 3) uniform float uK;\nvoid main() { }\n", false },
    };
    for (size_t i = 0; i < sizeof loc / sizeof loc[0]; i++) {
        write_file("l.frag", loc[i].text);
        shader_src_desc d = { .path = tmp("l.frag"), .stage = SHADER_FRAGMENT };
        shader_src s;
        bool ok = shader_src_load(&d, &s);
        CHECK(ok);
        if (ok) {
            const char *ext = strstr(s.text, "#extension GL_ARB_explicit_uniform_location : enable");
            CHECK_MSG((ext != NULL) == loc[i].want, "case %zu:\n%s", i, s.text);
            CHECK(!strstr(s.text, "420pack"));
        }
        shader_src_free(&s);
    }
}

static void test_include_quirks(void) {
    /* an include's own #version is dropped; an #include in a comment is not one */
    write_file("inc_v.glsl", "#version 330 compatibility\nfloat a() { return 1.0; }\n");
    write_file("q.frag", "#version 330 compatibility\n/*\n#include \"nope.glsl\"\n*/\n"
                         "#include \"inc_v.glsl\" // the real one\nvoid main() { float x = undefined_q; }\n");
    shader_src_desc d = { .path = tmp("q.frag"), .stage = SHADER_FRAGMENT };
    shader_src s;
    bool ok = shader_src_load(&d, &s);
    CHECK_MSG(ok, "%s", ERR(s));
    if (ok) {
        const char *v = strstr(s.text, "#version");
        CHECK(v == s.text && strstr(v + 1, "#version") == NULL);
        CHECK_EQ(s.nfiles, 2);
        char *log = fake_compile(s.text, 'm', true);
        char *mapped = shader_src_map_log(&s, log);
        CHECK_MSG(mapped_has(mapped, "q.frag", 6, "undefined_q"), "%s", mapped);
        free(mapped);
        free(log);
    }
    shader_src_free(&s);

    /* a UTF-8 byte order mark before #version */
    write_file("bom.frag", "\xEF\xBB\xBF#version 120\nvoid main() {}\n");
    d.path = tmp("bom.frag");
    ok = shader_src_load(&d, &s);
    CHECK_MSG(ok, "%s", ERR(s));
    if (ok) CHECK_EQ(strncmp(s.text, "#version 120\n", 13), 0);
    shader_src_free(&s);

    write_file("bad.frag", "#version 330 compatibility\n#include waves.glsl\nvoid main() {}\n");
    d.path = tmp("bad.frag");
    CHECK(!shader_src_load(&d, &s));
    CHECK_STR_CONTAINS(ERR(s), "bad.frag:2: error: malformed #include");
    shader_src_free(&s);
}

static void test_map_log_passthrough(void) {
    shader_src s;
    bool ok = load(&s, "map_main.frag", SHADER_FRAGMENT, NULL, 0, false);
    CHECK(ok);
    if (!ok) { shader_src_free(&s); return; }
    const char *log = "ERROR: 1 compilation errors.  No code generated.\n"
                      "error: linking failed\n"
                      "7:3(1): error: bad index\n"
                      "WARNING: 0:2: 'x' : something \n"
                      "0(4) : warning C7050: \"c\" might be used before being initialized\n"
                      "ERROR: 0:200001: 'y' : in an include";
    char *m = shader_src_map_log(&s, log);
    CHECK_STR_CONTAINS(m, "ERROR: 1 compilation errors.  No code generated.\n");
    CHECK_STR_CONTAINS(m, "error: linking failed\n");
    CHECK_STR_CONTAINS(m, "7:3(1): error: bad index\n");          /* file 7 does not exist */
    CHECK_STR_CONTAINS(m, "map_main.frag:2: warning: 'x' : something\n");
    CHECK_STR_CONTAINS(m, "map_main.frag:4: warning C7050:");
    CHECK_STR_CONTAINS(m, "inc/map_fresnel.glsl:1: error: 'y' : in an include");
    CHECK_NE(m[strlen(m) - 1], '\n');
    free(m);
    m = shader_src_map_log(&s, "");
    CHECK(m && m[0] == '\0');
    free(m);
    shader_src_free(&s);
}

/* A driver's log as diags: mapped lines are file:line diags of their
 * severity; a line of no known shape is kept, bare, as the driver wrote it. */
static void test_map_diags(void) {
    shader_src s;
    bool ok = load(&s, "map_main.frag", SHADER_FRAGMENT, NULL, 0, false);
    CHECK(ok);
    if (!ok) { shader_src_free(&s); return; }
    diag_list l = { 0 };
    shader_src_map_diags(&s, "0:200001(5): error: 'y' undeclared\nerror: linking failed\n\n"
                             "WARNING: 0:2: 'x' : something \n", DIAG_NOTE, &l);
    CHECK_EQ(l.n, 3);
    if (l.n == 3) {
        CHECK(l.d[0].severity == DIAG_ERROR && l.d[0].line == 1 && !l.d[0].bare);
        CHECK_STR_CONTAINS(l.d[0].file, "inc/map_fresnel.glsl");
        CHECK_STR_EQ(l.d[0].text, "'y' undeclared");
        CHECK(l.d[1].bare && l.d[1].severity == DIAG_NOTE && l.d[1].file[0] == '\0');
        CHECK_STR_EQ(l.d[1].text, "error: linking failed");
        CHECK(l.d[2].severity == DIAG_WARNING && l.d[2].line == 2);
        CHECK_STR_EQ(l.d[2].text, "'x' : something");
    }
    CHECK(l.nerrors == 1 && l.nwarnings == 1);
    diag_list_free(&l);
    shader_src_map_diags(&s, NULL, DIAG_NOTE, &l);
    CHECK_EQ(l.n, 0);
    shader_src_free(&s);
}

static void test_stage_names_and_paths(void) {
    CHECK_STR_EQ(shader_stage_name(SHADER_VERTEX), "vertex");
    CHECK_STR_EQ(shader_stage_name(SHADER_FRAGMENT), "fragment");
    CHECK_STR_EQ(shader_stage_name(SHADER_TESS_CONTROL), "tess control");
    CHECK_EQ(shader_stage_from_path("a/b/water.vert"), SHADER_VERTEX);
    CHECK_EQ(shader_stage_from_path("water.vs"), SHADER_VERTEX);
    CHECK_EQ(shader_stage_from_path("water.tesc"), SHADER_TESS_CONTROL);
    CHECK_EQ(shader_stage_from_path("water.tese"), SHADER_TESS_EVALUATION);
    CHECK_EQ(shader_stage_from_path("water.geom"), SHADER_GEOMETRY);
    CHECK_EQ(shader_stage_from_path("water.gs"), SHADER_GEOMETRY);
    CHECK_EQ(shader_stage_from_path("water.FRAG"), SHADER_FRAGMENT);
    CHECK_EQ(shader_stage_from_path("water.fs"), SHADER_FRAGMENT);
    CHECK_EQ(shader_stage_from_path("water.frag.glsl"), SHADER_FRAGMENT);
    CHECK_EQ(shader_stage_from_path("water_vert.glsl"), SHADER_VERTEX);
    CHECK_EQ(shader_stage_from_path("water-gs.glsl"), SHADER_GEOMETRY);
    CHECK_EQ(shader_stage_from_path("waves.glsl"), SHADER_STAGE_COUNT);
    CHECK_EQ(shader_stage_from_path("scene.glib"), SHADER_STAGE_COUNT);
    CHECK_EQ(shader_stage_from_path("Makefile"), SHADER_STAGE_COUNT);
}

/* A file beyond SHADER_SRC_MAX_FILE_BYTES is refused, and so is a "regular"
 * file that never ends (/proc/self/pagemap reads on for terabytes). */
static void test_file_size_limit(void) {
    char path[600];
    snprintf(path, sizeof path, "%s/huge.glsl", g_tmp);
    FILE *f = fopen(path, "wb");
    CHECK_NE(f, NULL);
    if (!f) return;
    static char line[1024];
    memset(line, ' ', sizeof line - 1);
    line[sizeof line - 2] = '\n';
    for (long n = 0; n <= SHADER_SRC_MAX_FILE_BYTES; n += (long)sizeof line - 1) fputs(line, f);
    fclose(f);
    write_file("big.frag", "#version 330 compatibility\n#include \"huge.glsl\"\nvoid main() {}\n");
    shader_src s;
    shader_src_desc d = { .path = tmp("big.frag"), .stage = SHADER_FRAGMENT };
    CHECK(!shader_src_load(&d, &s));
    CHECK_STR_CONTAINS(ERR(s), "big.frag:2: error: cannot read include");
    CHECK_STR_CONTAINS(ERR(s), "larger than 8 MiB");
    shader_src_free(&s);
    struct stat st;
    if (stat("/proc/self/pagemap", &st) == 0 && S_ISREG(st.st_mode)) {
        write_file("proc.frag", "#version 330 compatibility\n#include \"/proc/self/pagemap\"\nvoid main() {}\n");
        d.path = tmp("proc.frag");
        CHECK(!shader_src_load(&d, &s));
        CHECK_STR_CONTAINS(ERR(s), "proc.frag:2: error: cannot read include");
        shader_src_free(&s);
    }
}

/* For llvmpipe a fragment stage's main() starts with a kill never taken
 * (one compiled function instead of two): after the brace of each main()
 * definition, on its line; not in a comment, not in mainly(), not in a
 * prototype, not in another stage, not without desc.cpu_raster. */
static void test_cpu_raster_kill(void) {
    write_file("k.frag", "#version 330 compatibility\n"
                         "// void main() { in a comment\n"
                         "float mainly() { return 1.0; }\n"
                         "void main(void);\n"
                         "#ifdef TWO\n"
                         "void main ( )\n{ gl_FragColor = vec4(1.0); }\n"
                         "#else\n"
                         "void main() {\n    gl_FragColor = vec4(mainly());\n}\n"
                         "#endif\n");
    shader_src plain = {0}, kill = {0}, vert = {0};
    shader_src_desc d = { .path = tmp("k.frag"), .stage = SHADER_FRAGMENT };
    bool ok = shader_src_load(&d, &plain);
    CHECK_MSG(ok, "%s", ERR(plain));
    d.cpu_raster = true;
    ok = ok && shader_src_load(&d, &kill);
    CHECK_MSG(ok, "%s", ERR(kill));
    d.stage = SHADER_VERTEX;
    ok = ok && shader_src_load(&d, &vert);
    CHECK(ok);
    if (ok) {
        CHECK_EQ(count_of(plain.text, SHADER_SRC_UNREACHED_KILL), 0);
        CHECK_EQ(count_of(vert.text, SHADER_SRC_UNREACHED_KILL), 0);
        CHECK_EQ(count_of(kill.text, SHADER_SRC_UNREACHED_KILL), 2);
        CHECK_EQ(count_of(kill.text, "\n"), count_of(plain.text, "\n"));   /* every line keeps its number */
        CHECK_STR_CONTAINS(kill.text, "\n{" SHADER_SRC_UNREACHED_KILL " gl_FragColor = vec4(1.0); }\n");
        CHECK_STR_CONTAINS(kill.text, "void main() {" SHADER_SRC_UNREACHED_KILL "\n");
        CHECK_STR_CONTAINS(kill.text, "// void main() { in a comment\n");
        CHECK_STR_CONTAINS(kill.text, "float mainly() { return 1.0; }\n");
        CHECK_STR_CONTAINS(kill.text, "void main(void);\n");
        CHECK_NE(kill.hash, plain.hash);
    }
    shader_src_free(&plain);
    shader_src_free(&kill);
    shader_src_free(&vert);
}

int main(void) {
    snprintf(g_tmp, sizeof g_tmp, "/tmp/tarn_test_shader_src_XXXXXX");
    if (!mkdtemp(g_tmp)) { perror("mkdtemp"); return 1; }
    RUN(test_includes_and_line_map);
    RUN(test_old_version_line_rule);
    RUN(test_no_version_gets_glman_default);
    RUN(test_defines_and_gstap_follow_version);
    RUN(test_missing_include_is_file_line_error);
    RUN(test_include_cycle_is_file_line_error);
    RUN(test_missing_stage_file);
    RUN(test_bad_define_name);
    RUN(test_include_depth_limit);
    RUN(test_hash_changes_iff_text_changes);
    RUN(test_include_search_order_and_once);
    RUN(test_version_line_with_comment_tail);
    RUN(test_include_quirks);
    RUN(test_ext_geometry_shader_rewritten);
    RUN(test_binding_enables_420pack);
    RUN(test_map_log_passthrough);
    RUN(test_map_diags);
    RUN(test_stage_names_and_paths);
    RUN(test_file_size_limit);
    RUN(test_cpu_raster_kill);
    char cmd[320];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", g_tmp);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", g_tmp);
    return check_summary();
}
