/* shader_src: assembles a shader stage's source text (see shader_src.h). */
#include "shader_src.h"
#include "util.h"

#include "file_cache.h"
#include "mem.h"
#include "path.h"
#include "strbuf.h"

#include <assert.h>
#include <ctype.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

/* ---- paths and files ------------------------------------------------------ */

static bool is_regular_file(const char *path) {
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* A stage file or include as text (a BOM dropped, CRLF as LF), or NULL
 * with the reason in why: binary (a NUL byte), a directory, or larger than
 * SHADER_SRC_MAX_FILE_BYTES. */
static char *read_text(file_cache *files, const char *path, char *why, size_t whylen) {
    file_text_opts o = { .max_bytes = SHADER_SRC_MAX_FILE_BYTES, .strip_bom = true, .crlf_to_lf = true,
                         .reject_nul = true, .settle = true };  /* a reload during a save reads the saved text */
    return file_cache_read(files, path, &o, NULL, NULL, why, whylen);
}

/* ---- scanning GLSL lines -------------------------------------------------- */

typedef struct line_view {
    const char *p;      /* start */
    size_t n;           /* length, without the '\n' */
} line_view;

/* Updates *in_comment across one line (block comments only; `//` ends it). */
static void scan_comments(line_view l, bool *in_comment) {
    for (size_t i = 0; i < l.n; i++) {
        if (*in_comment) {
            if (l.p[i] == '*' && i + 1 < l.n && l.p[i + 1] == '/') { *in_comment = false; i++; }
        } else if (l.p[i] == '/' && i + 1 < l.n && l.p[i + 1] == '/') {
            return;
        } else if (l.p[i] == '/' && i + 1 < l.n && l.p[i + 1] == '*') {
            *in_comment = true;
            i++;
        }
    }
}

/* True when the line has something but whitespace and comments; updates
 * *in_comment. */
static bool line_has_code(line_view l, bool *in_comment) {
    bool code = false;
    for (size_t i = 0; i < l.n; i++) {
        if (*in_comment) {
            if (l.p[i] == '*' && i + 1 < l.n && l.p[i + 1] == '/') { *in_comment = false; i++; }
        } else if (l.p[i] == '/' && i + 1 < l.n && l.p[i + 1] == '/') {
            break;
        } else if (l.p[i] == '/' && i + 1 < l.n && l.p[i + 1] == '*') {
            *in_comment = true;
            i++;
        } else if (!isspace((unsigned char)l.p[i])) {
            code = true;
        }
    }
    return code;
}

/* If the line (not starting inside a comment) is a preprocessor directive,
 * returns a pointer just past its name and sets *name and *name_len. */
static const char *directive(line_view l, const char **name, size_t *name_len) {
    size_t i = 0;
    while (i < l.n && (l.p[i] == ' ' || l.p[i] == '\t')) i++;
    if (i >= l.n || l.p[i] != '#') return NULL;
    i++;
    while (i < l.n && (l.p[i] == ' ' || l.p[i] == '\t')) i++;
    size_t s = i;
    while (i < l.n && (isalnum((unsigned char)l.p[i]) || l.p[i] == '_')) i++;
    *name = l.p + s;
    *name_len = i - s;
    return l.p + i;
}

static bool word_is(const char *w, size_t n, const char *lit) {
    return n == strlen(lit) && memcmp(w, lit, n) == 0;
}

/* ---- assembly -------------------------------------------------------------- */

typedef struct src_file {
    char *path;         /* as shown (lexically normalised) */
    char *id;           /* realpath, for identity */
    bool once;          /* has #pragma once */
    int times;          /* times included so far */
} src_file;

typedef struct asm_ctx {
    const shader_src_desc *desc;
    shader_src *out;
    strbuf text;
    src_file *files;
    int nfiles, capfiles;
    int stack[SHADER_SRC_MAX_INCLUDE_DEPTH + 2];
    int depth;
    bool old_line_rule; /* desktop GLSL < 3.30: `#line N` numbers the next line N + 1 */
    /* a geometry shader's first line of code, where the layouts it lacks go */
    bool gs_marked;
    size_t gs_mark;             /* offset in text */
    int gs_mark_file, gs_mark_line;
    bool failed;
} asm_ctx;

static void fail(asm_ctx *c, const char *file, int line, const char *fmt, ...) {
    if (c->failed) return;
    c->failed = true;
    diag *d = &c->out->error;
    d->severity = DIAG_ERROR;
    snprintf(d->file, sizeof d->file, "%s", file);
    d->line = line;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(d->text, sizeof d->text, fmt, ap);
    va_end(ap);
}

/* Index of the file with this identity, adding it when new. */
static int file_index(asm_ctx *c, const char *path) {
    char *id = realpath(path, NULL);
    if (!id) id = path_clean(path);
    for (int i = 0; i < c->nfiles; i++)
        if (strcmp(c->files[i].id, id) == 0) { free(id); return i; }
    c->files = mem_grow(c->files, &c->capfiles, c->nfiles + 1, sizeof *c->files);
    src_file *f = &c->files[c->nfiles];
    memset(f, 0, sizeof *f);
    f->path = path_clean(path);
    f->id = id;
    return c->nfiles++;
}

static void line_directive(strbuf *b, bool old_line_rule, int fidx, int line) {
    long v = (long)fidx * SHADER_SRC_LINE_BASE + line - (old_line_rule ? 1 : 0);
    strbuf_printf(b, "#line %ld %d\n", v, fidx);
}

static void emit_line_directive(asm_ctx *c, int fidx, int line) {
    line_directive(&c->text, c->old_line_rule, fidx, line);
}

static bool line_is_pragma_once(line_view l) {
    const char *name;
    size_t nn;
    const char *rest = directive(l, &name, &nn);
    if (!rest || !word_is(name, nn, "pragma")) return false;
    const char *end = l.p + l.n;
    while (rest < end && (*rest == ' ' || *rest == '\t')) rest++;
    return (size_t)(end - rest) >= 4 && memcmp(rest, "once", 4) == 0 &&
           (end - rest == 4 || !(isalnum((unsigned char)rest[4]) || rest[4] == '_'));
}

static bool has_pragma_once(const char *text) {
    bool in_comment = false;
    const char *p = text;
    while (*p) {
        const char *e = strchr(p, '\n');
        line_view l = { p, e ? (size_t)(e - p) : strlen(p) };
        if (!in_comment && line_is_pragma_once(l)) return true;
        scan_comments(l, &in_comment);
        if (!e) break;
        p = e + 1;
    }
    return false;
}

static bool emit_file(asm_ctx *c, int fidx, const char *text, int first_line, bool in_comment);

/* ---- glman-era GLSL ------------------------------------------------------------ */

static bool is_ident_char(char ch) { return isalnum((unsigned char)ch) || ch == '_'; }

/* GL_EXT_geometry_shader4's per-vertex input arrays -> GLSL 1.50's gl_in member */
static const char *const gs_ext_inputs[][2] = {
    { "gl_PositionIn", "gl_Position" }, { "gl_PointSizeIn", "gl_PointSize" },
    { "gl_ClipVertexIn", "gl_ClipVertex" }, { "gl_FrontColorIn", "gl_FrontColor" },
    { "gl_BackColorIn", "gl_BackColor" }, { "gl_FrontSecondaryColorIn", "gl_FrontSecondaryColor" },
    { "gl_BackSecondaryColorIn", "gl_BackSecondaryColor" }, { "gl_TexCoordIn", "gl_TexCoord" },
    { "gl_FogFragCoordIn", "gl_FogFragCoord" },
};

static const char *gs_ext_member(const char *w, size_t n) {
    for (size_t i = 0; i < sizeof gs_ext_inputs / sizeof gs_ext_inputs[0]; i++)
        if (word_is(w, n, gs_ext_inputs[i][0])) return gs_ext_inputs[i][1];
    return NULL;
}

/* Index just past the ']' matching the '[' at l.p[open]; 0 when the line
 * does not close it. */
static size_t bracket_end(line_view l, size_t open) {
    int depth = 0;
    for (size_t i = open; i < l.n; i++) {
        if (l.p[i] == '[') depth++;
        else if (l.p[i] == ']' && --depth == 0) return i + 1;
    }
    return 0;
}

/* Emits one line of a geometry shader with GL_EXT_geometry_shader4's names
 * in GLSL 1.50's: gl_PositionIn[i] -> gl_in[i].gl_Position,
 * gl_VerticesIn -> gl_in.length(), `varying in` -> `in`, `varying out` ->
 * `out`, and a plain `varying` (EXT_geometry_shader4's `varying out`;
 * Mesa agrees, glslang would read an input) -> `out`. */
static void emit_gs_line(strbuf *o, line_view l) {
    size_t i = 0;
    while (i < l.n) {
        if (!is_ident_char(l.p[i])) { strbuf_put(o, l.p + i++, 1); continue; }
        size_t s = i;
        while (i < l.n && is_ident_char(l.p[i])) i++;
        const char *w = l.p + s;
        size_t n = i - s;
        if (word_is(w, n, "gl_VerticesIn")) { strbuf_puts(o, "gl_in.length()"); continue; }
        size_t j = i;
        while (j < l.n && (l.p[j] == ' ' || l.p[j] == '\t')) j++;
        if (word_is(w, n, "varying")) {
            size_t k = j;
            while (k < l.n && is_ident_char(l.p[k])) k++;
            bool io = j > i && (word_is(l.p + j, k - j, "in") || word_is(l.p + j, k - j, "out"));
            strbuf_put(o, io ? l.p + j : "out", io ? k - j : 3);
            if (io) i = k;
            continue;
        }
        const char *member = gs_ext_member(w, n);
        size_t close = member && j < l.n && l.p[j] == '[' ? bracket_end(l, j) : 0;
        if (close) {
            strbuf_puts(o, "gl_in");
            strbuf_put(o, l.p + j, close - j);
            strbuf_printf(o, ".%s", member);
            i = close;
            continue;
        }
        strbuf_put(o, w, n);
    }
    strbuf_puts(o, "\n");
}

static bool is_gs4_extension(line_view l) {
    const char *name;
    size_t nn;
    const char *rest = directive(l, &name, &nn);
    if (!rest || !word_is(name, nn, "extension")) return false;
    const char *end = l.p + l.n;
    for (const char *q = rest; q < end; q++) {
        if (!is_ident_char(*q) || (q > rest && is_ident_char(q[-1]))) continue;
        const char *e = q;
        while (e < end && is_ident_char(*e)) e++;
        if (word_is(q, (size_t)(e - q), "GL_EXT_geometry_shader4")) return true;
    }
    return false;
}

static const char *const gs_input_names[] = {
    [SHADER_GS_IN_TRIANGLES] = "triangles", [SHADER_GS_IN_TRIANGLES_ADJACENCY] = "triangles_adjacency",
    [SHADER_GS_IN_LINES] = "lines", [SHADER_GS_IN_LINES_ADJACENCY] = "lines_adjacency",
    [SHADER_GS_IN_POINTS] = "points",
};

/* What a text's layout qualifiers say (comments blanked first). */
typedef struct layout_scan {
    bool in, out;       /* `layout(...) in;` / `layout(...) out;`: a primitive declaration */
    bool binding;       /* some layout(...) holds `binding` */
    bool uniform_location;  /* `layout(... location ...) uniform` */
} layout_scan;

char *shader_src_blank_comments(const char *text) {
    char *t = mem_strdup(text);
    bool block = false, line = false;
    for (char *p = t; *p; p++) {
        if (block) {
            if (p[0] == '*' && p[1] == '/') { p[0] = p[1] = ' '; p++; block = false; }
            else if (*p != '\n') *p = ' ';
        } else if (line) {
            if (*p == '\n') line = false;
            else *p = ' ';
        } else if (p[0] == '/' && (p[1] == '/' || p[1] == '*')) {
            block = p[1] == '*';
            line = !block;
            p[0] = p[1] = ' ';
            p++;
        }
    }
    return t;
}

static const char *skip_space(const char *p) {
    while (isspace((unsigned char)*p)) p++;
    return p;
}

static layout_scan scan_layouts(const char *text) {
    layout_scan r = {0};
    char *t = shader_src_blank_comments(text);
    for (const char *p = t; (p = strstr(p, "layout")) != NULL; p += 6) {
        if ((p > t && is_ident_char(p[-1])) || is_ident_char(p[6])) continue;
        const char *q = skip_space(p + 6);
        if (*q != '(') continue;
        const char *close = strchr(q, ')');
        if (!close) break;
        bool location = false;
        for (const char *b = q; (b = strstr(b, "binding")) != NULL && b < close; b += 7)
            if (!is_ident_char(b[-1]) && !is_ident_char(b[7])) r.binding = true;
        for (const char *b = q; (b = strstr(b, "location")) != NULL && b < close; b += 8)
            if (!is_ident_char(b[-1]) && !is_ident_char(b[8])) location = true;
        q = skip_space(close + 1);
        size_t n = 0;
        while (is_ident_char(q[n])) n++;
        if (location && word_is(q, n, "uniform")) r.uniform_location = true;
        bool in = word_is(q, n, "in"), out = word_is(q, n, "out");
        if ((in || out) && *skip_space(q + n) == ';') {
            r.in |= in;
            r.out |= out;
        }
    }
    free(t);
    return r;
}

/* Handles `#include` on line `line` of file fidx; `rest` points past "include". */
static bool do_include(asm_ctx *c, int fidx, int line, const char *rest, const char *end) {
    const char *from = c->files[fidx].path;
    while (rest < end && (*rest == ' ' || *rest == '\t')) rest++;
    char close = rest < end && *rest == '"' ? '"' : rest < end && *rest == '<' ? '>' : 0;
    const char *q = close ? memchr(rest + 1, close, (size_t)(end - rest - 1)) : NULL;
    if (!q || q == rest + 1) {
        fail(c, from, line, "malformed #include: expected \"file\" or <file>");
        return false;
    }
    size_t nlen = (size_t)(q - rest - 1);
    char name[1024];
    if (nlen >= sizeof name) { fail(c, from, line, "#include name too long"); return false; }
    memcpy(name, rest + 1, nlen);
    name[nlen] = '\0';
    for (const char *t = q + 1; t < end; t++) {
        if (*t == ' ' || *t == '\t') continue;
        if (*t == '/' && t + 1 < end && (t[1] == '/' || t[1] == '*')) break;
        fail(c, from, line, "unexpected text after #include \"%s\"", name);
        return false;
    }

    /* where: next to the including file, then the include dirs */
    char *found = NULL;
    if (name[0] == '/') {
        if (is_regular_file(name)) found = path_clean(name);
    } else {
        char *dir = path_dir(from);
        char *cand = path_join(dir, name);
        free(dir);
        if (is_regular_file(cand)) found = cand;
        else free(cand);
        for (int i = 0; !found && i < c->desc->ninclude_dirs; i++) {
            const char *idir = c->desc->include_dirs[i];
            if (!idir || !idir[0]) continue;
            cand = path_join(idir, name);
            if (is_regular_file(cand)) found = cand;
            else free(cand);
        }
    }
    if (!found) {
        char where[400] = "";
        size_t w = 0;
        char *dir = path_dir(from);
        w += (size_t)snprintf(where, sizeof where, "%s", dir);
        free(dir);
        for (int i = 0; i < c->desc->ninclude_dirs && w < sizeof where; i++)
            if (c->desc->include_dirs[i] && c->desc->include_dirs[i][0])
                w += (size_t)snprintf(where + w, sizeof where - w, ", %s", c->desc->include_dirs[i]);
        fail(c, from, line, "cannot find include \"%s\" (looked in %s)", name, where);
        return false;
    }

    int k = file_index(c, found);
    /* a cycle: k is already being read */
    for (int d = 0; d <= c->depth; d++) {
        if (c->stack[d] != k) continue;
        char chain[400] = "";
        size_t w = 0;
        for (int e = d; e <= c->depth && w < sizeof chain; e++)
            w += (size_t)snprintf(chain + w, sizeof chain - w, "%s -> ", c->files[c->stack[e]].path);
        if (w < sizeof chain) snprintf(chain + w, sizeof chain - w, "%s", c->files[k].path);
        free(found);
        fail(c, from, line, "include cycle: %s", chain);
        return false;
    }
    if (c->depth + 1 > SHADER_SRC_MAX_INCLUDE_DEPTH) {
        free(found);
        fail(c, from, line, "#include nested too deeply (more than %d levels) at \"%s\"",
             SHADER_SRC_MAX_INCLUDE_DEPTH, name);
        return false;
    }
    char why[MSG_MAX];
    char *text = read_text(c->desc->files, found, why, sizeof why);
    if (!text) {
        fail(c, from, line, "cannot read include \"%s\": %s", found, why);
        free(found);
        return false;
    }
    free(found);
    if (c->files[k].times == 0) c->files[k].once = has_pragma_once(text);
    if (c->files[k].once && c->files[k].times > 0) {
        free(text);
        strbuf_puts(&c->text, "\n");            /* keeps the including file's numbering */
        return true;
    }
    c->files[k].times++;
    c->stack[++c->depth] = k;
    emit_line_directive(c, k, 1);
    bool ok = emit_file(c, k, text, 1, false);
    c->depth--;
    free(text);
    if (ok) emit_line_directive(c, fidx, line + 1);
    return ok;
}

/* Emits lines first_line.. of text (file fidx), resolving includes. */
static bool emit_file(asm_ctx *c, int fidx, const char *text, int first_line, bool in_comment) {
    const char *p = text;
    int line = 1;
    bool seen_code = fidx == 0;     /* an included file's leading #version is dropped */
    while (*p) {
        const char *e = strchr(p, '\n');
        line_view l = { p, e ? (size_t)(e - p) : strlen(p) };
        if (line >= SHADER_SRC_LINE_BASE) {
            fail(c, c->files[fidx].path, line, "file too long (more than %d lines)",
                 SHADER_SRC_LINE_BASE - 1);
            return false;
        }
        if (line >= first_line) {
            bool handled = false;
            if (!in_comment) {
                const char *name;
                size_t nn;
                const char *rest = directive(l, &name, &nn);
                if (rest && word_is(name, nn, "include")) {
                    if (!do_include(c, fidx, line, rest, l.p + l.n)) return false;
                    handled = true;
                } else if (line_is_pragma_once(l)) {
                    strbuf_puts(&c->text, "\n");
                    handled = true;
                } else if (rest && word_is(name, nn, "version") && !seen_code) {
                    strbuf_puts(&c->text, "\n");
                    handled = true;
                } else if (c->desc->stage == SHADER_GEOMETRY && is_gs4_extension(l)) {
                    strbuf_puts(&c->text, "// tarn: GL_EXT_geometry_shader4 dropped; its names become GLSL 1.50's\n");
                    handled = true;
                } else if (!rest && c->desc->stage == SHADER_GEOMETRY && !c->gs_marked) {
                    bool ic = false;
                    if (line_has_code(l, &ic)) {
                        c->gs_marked = true;
                        c->gs_mark = c->text.len;
                        c->gs_mark_file = fidx;
                        c->gs_mark_line = line;
                    }
                }
            }
            if (!handled && c->desc->stage == SHADER_GEOMETRY) {
                emit_gs_line(&c->text, l);
            } else if (!handled) {
                strbuf_put(&c->text, l.p, l.n);
                strbuf_puts(&c->text, "\n");
            }
            bool ic = in_comment;
            if (line_has_code(l, &ic)) seen_code = true;
        }
        scan_comments(l, &in_comment);
        if (!e) break;
        p = e + 1;
        line++;
    }
    return true;
}

static bool valid_identifier(const char *s) {
    if (!(isalpha((unsigned char)s[0]) || s[0] == '_')) return false;
    for (const char *p = s; *p; p++)
        if (!(isalnum((unsigned char)*p) || *p == '_')) return false;
    return true;
}

static const char *const gstap_matrices[][2] = {
    { "uModelViewMatrix", "gl_ModelViewMatrix" },
    { "uProjectionMatrix", "gl_ProjectionMatrix" },
    { "uModelViewProjectionMatrix", "gl_ModelViewProjectionMatrix" },
    { "uNormalMatrix", "gl_NormalMatrix" },
    { "uModelViewMatrixInverse", "gl_ModelViewMatrixInverse" },
};

static void emit_prologue(asm_ctx *c) {
    const shader_src_desc *d = c->desc;
    for (int i = 0; i < d->ndefines; i++) {
        if (d->defines[i].value[0]) strbuf_printf(&c->text, "#define %s %s\n", d->defines[i].name, d->defines[i].value);
        else strbuf_printf(&c->text, "#define %s\n", d->defines[i].name);
    }
    if (d->gstap) {
        strbuf_puts(&c->text, "// GSTAP: glman's generic names for the compatibility built-ins\n");
        if (d->stage == SHADER_VERTEX) {
            strbuf_puts(&c->text, "#define aVertex gl_Vertex\n#define aNormal gl_Normal\n"
                              "#define aColor gl_Color\n");
            for (int i = 0; i < 8; i++) strbuf_printf(&c->text, "#define aTexCoord%d gl_MultiTexCoord%d\n", i, i);
        }
        /* a compatibility fragment shader reads the interpolated colour as
         * gl_Color; the vertex attributes (aVertex, aNormal, aTexCoordN)
         * have no fragment built-in, nor has any stage in between */
        if (d->stage == SHADER_FRAGMENT) strbuf_puts(&c->text, "#define aColor gl_Color\n");
        for (size_t i = 0; i < sizeof gstap_matrices / sizeof gstap_matrices[0]; i++)
            strbuf_printf(&c->text, "#define %s %s\n", gstap_matrices[i][0], gstap_matrices[i][1]);
    }
}

/* Finds the stage file's #version: its 1-based line (0 if none comes first),
 * and the directive's extent in that line. A #version after code is left to
 * the compiler to report. */
typedef struct version_info {
    int line;
    size_t start, len;      /* the directive text within the line */
    int number;
    bool es;
} version_info;

static version_info find_version(const char *text) {
    version_info v = {0};
    bool in_comment = false;
    const char *p = text;
    int line = 1;
    while (*p) {
        const char *e = strchr(p, '\n');
        line_view l = { p, e ? (size_t)(e - p) : strlen(p) };
        const char *name;
        size_t nn;
        const char *rest = in_comment ? NULL : directive(l, &name, &nn);
        if (rest && word_is(name, nn, "version")) {
            v.line = line;
            size_t s = 0;
            while (s < l.n && (l.p[s] == ' ' || l.p[s] == '\t')) s++;
            const char *end = l.p + l.n, *q = rest;
            while (q < end && !(q[0] == '/' && q + 1 < end && (q[1] == '/' || q[1] == '*'))) q++;
            while (q > rest && (q[-1] == ' ' || q[-1] == '\t')) q--;
            v.start = s;
            v.len = (size_t)(q - (l.p + s));
            char num[32] = "";
            const char *r = rest;
            while (r < q && (*r == ' ' || *r == '\t')) r++;
            size_t k = 0;
            while (r < q && isdigit((unsigned char)*r) && k + 1 < sizeof num) num[k++] = *r++;
            num[k] = '\0';
            v.number = atoi(num);
            while (r < q && (*r == ' ' || *r == '\t')) r++;
            v.es = (q - r >= 2 && r[0] == 'e' && r[1] == 's') || v.number == 100;
            return v;
        }
        bool ic = in_comment;
        if (line_has_code(l, &ic)) return v;    /* code first: no #version in place */
        in_comment = ic;
        if (!e) break;
        p = e + 1;
        line++;
    }
    return v;
}

/* The layouts a glman-era geometry shader lacks (in the whole text, its
 * includes too), spliced in before its first line of code, then `#line`
 * so that line keeps its number. After the file's #extension lines, which
 * must come before any code; before any use of gl_in.length(), which
 * needs the input layout. */
static void add_gs_layouts(asm_ctx *c) {
    layout_scan ls = scan_layouts(c->text.s ? c->text.s : "");
    if (ls.in && ls.out) return;
    strbuf b = {0};
    strbuf_put(&b, c->text.s, c->gs_mark);
    unsigned in = (unsigned)c->desc->gs_input;
    if (!ls.in)
        strbuf_printf(&b, "layout(%s) in;  // tarn: the input primitive of the draw\n",
                      gs_input_names[in < sizeof gs_input_names / sizeof gs_input_names[0] ? in : 0]);
    if (!ls.out)
        strbuf_printf(&b, "layout(triangle_strip, max_vertices = %d) out;  // tarn: glman's output\n",
                      SHADER_SRC_GS_MAX_VERTICES);
    line_directive(&b, c->old_line_rule, c->gs_mark_file, c->gs_mark_line);
    strbuf_puts(&b, c->text.s + c->gs_mark);
    strbuf_free(&c->text);
    c->text = b;
}

/* Inserts `#extension NAME : enable` right after the #version line (the
 * prologue is all directives, so it is still before any code), unless the
 * text names the extension itself. */
static void enable_extension(char **text, const char *name, const char *why) {
    if (strstr(*text, name)) return;
    char *nl = strchr(*text, '\n');
    if (!nl) return;
    strbuf b = {0};
    strbuf_put(&b, *text, (size_t)(nl + 1 - *text));
    strbuf_printf(&b, "#extension %s : enable  // tarn: %s\n", name, why);
    strbuf_puts(&b, nl + 1);
    free(*text);
    *text = strbuf_take(&b);
}

/* NVIDIA allowed layout(binding = N) from GLSL 3.30 on (glman's manual says
 * so), and layout(location = N) on a uniform; Mesa wants
 * GL_ARB_shading_language_420pack before 4.20 and
 * GL_ARB_explicit_uniform_location before 4.30. */
static void enable_layout_extensions(char **text, int version) {
    layout_scan ls = scan_layouts(*text);
    if (ls.binding && version < 420)
        enable_extension(text, "GL_ARB_shading_language_420pack", "for layout(binding) before GLSL 4.20");
    if (ls.uniform_location && version < 430)
        enable_extension(text, "GL_ARB_explicit_uniform_location", "for a uniform's layout(location) before GLSL 4.30");
}

const char *shader_src_next_main_body(const char *t, const char **from) {
    for (const char *p = *from; (p = strstr(p, "main")) != NULL; p += 4) {
        *from = p + 4;
        if ((p > t && is_ident_char(p[-1])) || is_ident_char(p[4])) continue;
        const char *q = skip_space(p + 4);
        if (*q != '(') continue;
        q = skip_space(q + 1);
        if (strncmp(q, "void", 4) == 0 && !is_ident_char(q[4])) q = skip_space(q + 4);
        if (*q != ')') continue;
        q = skip_space(q + 1);
        if (*q == '{') return q + 1;
    }
    return NULL;
}

/* SHADER_SRC_UNREACHED_KILL after the brace of every main() definition
 * (one in each branch of an #if that holds several). */
static void add_unreached_kill(char **text) {
    char *t = shader_src_blank_comments(*text);
    strbuf b = {0};
    size_t copied = 0;
    for (const char *from = t, *body; (body = shader_src_next_main_body(t, &from)) != NULL;) {
        size_t at = (size_t)(body - t);
        strbuf_put(&b, *text + copied, at - copied);
        strbuf_puts(&b, SHADER_SRC_UNREACHED_KILL);
        copied = at;
    }
    free(t);
    if (!copied) { free(b.s); return; }
    strbuf_puts(&b, *text + copied);
    free(*text);
    *text = strbuf_take(&b);
}

/* The description's stage and defines; false (failed at the file) where
 * one is bad. */
static bool check_desc(asm_ctx *c, const shader_src_desc *desc, const char *path) {
    if (!path[0]) { fail(c, "(none)", 0, "no shader file named"); return false; }
    if ((unsigned)desc->stage >= SHADER_STAGE_COUNT) {
        fail(c, path, 0, "bad shader stage %d", (int)desc->stage);
        return false;
    }
    for (int i = 0; i < desc->ndefines; i++) {
        const shader_define *d = &desc->defines[i];
        if (!valid_identifier(d->name)) {
            fail(c, path, 0, "bad #define name \"%s\"", d->name);
            return false;
        }
        if (strncmp(d->name, "GL_", 3) == 0) {
            fail(c, path, 0, "#define %s: names starting with GL_ are reserved in GLSL", d->name);
            return false;
        }
        if (strpbrk(d->value, "\r\n")) {
            fail(c, path, 0, "#define %s: a value may not hold a line break", d->name);
            return false;
        }
    }
    return true;
}

/* A stage file with a #version on line v->line: that line first (1.50
 * for a geometry shader glman wrote at 1.20), then tarn's prologue, then
 * the rest of the file from there on. */
static bool emit_versioned(asm_ctx *c, const char *main_text, const version_info *v, bool gs_bump, int version) {
    const char *lp = main_text;
    for (int i = 1; i < v->line; i++) lp = strchr(lp, '\n') + 1;
    const char *le = strchr(lp, '\n');
    size_t ln = le ? (size_t)(le - lp) : strlen(lp);
    if (gs_bump) {
        strbuf_printf(&c->text, "#version 150 compatibility  // tarn: was '%.*s'; geometry shaders need 1.50\n",
                      (int)v->len, lp + v->start);
    } else {
        strbuf_put(&c->text, lp + v->start, v->len);
        strbuf_puts(&c->text, "\n");
    }
    c->old_line_rule = !v->es && version < 330;
    emit_prologue(c);
    /* what followed the directive on its line (a comment, maybe opening a block) */
    line_view tail = { lp + v->start + v->len, ln - v->start - v->len };
    bool in_comment = false;
    bool tail_has_text = false;
    for (size_t i = 0; i < tail.n; i++)
        if (!isspace((unsigned char)tail.p[i])) tail_has_text = true;
    scan_comments(tail, &in_comment);
    if (tail_has_text) {
        emit_line_directive(c, 0, v->line);
        strbuf_put(&c->text, tail.p, tail.n);
        strbuf_puts(&c->text, "\n");
    } else {
        emit_line_directive(c, 0, v->line + 1);
    }
    return emit_file(c, 0, main_text, v->line + 1, in_comment);
}

/* A stage file without #version: glman's default, 3.30 compatibility. */
static bool emit_unversioned(asm_ctx *c, const char *main_text) {
    strbuf_puts(&c->text, "#version 330 compatibility  "
                          "// tarn: the file has no #version; glman's default assumed\n");
    c->old_line_rule = false;
    emit_prologue(c);
    emit_line_directive(c, 0, 1);
    return emit_file(c, 0, main_text, 1, false);
}

/* Hands the files found so far to out (even on failure: the caller
 * watches them) and frees the context's own. */
static void hand_over_files(asm_ctx *c, shader_src *out) {
    if (c->nfiles > 0) {
        out->files = mem_zalloc((size_t)c->nfiles * sizeof *out->files);
        for (int i = 0; i < c->nfiles; i++) { out->files[i] = c->files[i].path; c->files[i].path = NULL; }
        out->nfiles = c->nfiles;
    }
    for (int i = 0; i < c->nfiles; i++) { free(c->files[i].path); free(c->files[i].id); }
    free(c->files);
}

bool shader_src_load(const shader_src_desc *desc, shader_src *out) {
    assert(desc && out);
    memset(out, 0, sizeof *out);
    asm_ctx c = { .desc = desc, .out = out };
    const char *path = desc->path ? desc->path : "";
    char *main_text = NULL;
    bool ok = false;
    version_info v = {0};
    int version = 330;          /* the one the compiler sees */
    if (check_desc(&c, desc, path)) {
        file_index(&c, path);   /* the stage file: file 0 */
        c.stack[0] = 0;
        c.files[0].times = 1;
        char why[MSG_MAX];
        main_text = read_text(desc->files, path, why, sizeof why);
        if (!main_text) {
            fail(&c, path, 0, "cannot read shader: %s", why);
        } else {
            v = find_version(main_text);
            /* geometry shaders came with GLSL 1.50; glman's were 1.20 + GL_EXT_geometry_shader4 */
            bool gs_bump = desc->stage == SHADER_GEOMETRY && v.line && !v.es && v.number > 0 && v.number < 150;
            version = gs_bump ? 150 : v.line ? v.number : 330;
            ok = v.line ? emit_versioned(&c, main_text, &v, gs_bump, version) : emit_unversioned(&c, main_text);
        }
    }
    free(main_text);
    hand_over_files(&c, out);
    if (!ok) {
        free(c.text.s);
        out->text = NULL;
        if (!out->error.text[0]) {
            out->error.severity = DIAG_ERROR;
            snprintf(out->error.file, sizeof out->error.file, "%s", path);
            snprintf(out->error.text, sizeof out->error.text, "cannot assemble shader");
        }
        return false;
    }
    if (c.gs_marked) add_gs_layouts(&c);
    out->text = c.text.s ? c.text.s : mem_strdup("");
    if (!v.es) enable_layout_extensions(&out->text, version);
    if (desc->cpu_raster && desc->stage == SHADER_FRAGMENT) add_unreached_kill(&out->text);
    out->hash = hash_fnv1a(HASH_FNV1A_BASIS, out->text, strlen(out->text));
    return true;
}

void shader_src_free(shader_src *s) {
    if (!s) return;
    free(s->text);
    for (int i = 0; i < s->nfiles; i++) free(s->files[i]);
    free(s->files);
    s->text = NULL;
    s->files = NULL;
    s->nfiles = 0;
}

/* ---- info logs ---------------------------------------------------------------- */

/* Parses a non-negative decimal; advances *p. */
static bool parse_uint(const char **p, const char *end, long *v) {
    const char *q = *p;
    long x = 0;
    if (q >= end || !isdigit((unsigned char)*q)) return false;
    while (q < end && isdigit((unsigned char)*q)) {
        if (x > (LONG_MAX - 9) / 10) return false;
        x = x * 10 + (*q++ - '0');
    }
    *p = q;
    *v = x;
    return true;
}

/* (reported index, reported line) -> (file index, real line) */
static bool decode_loc(const shader_src *s, long idx, long line, int *file, long *real) {
    if (line >= SHADER_SRC_LINE_BASE) {
        long k = line / SHADER_SRC_LINE_BASE;
        if (k >= s->nfiles) return false;
        *file = (int)k;
        *real = line % SHADER_SRC_LINE_BASE;
        return true;
    }
    if (idx < 0 || idx >= s->nfiles) return false;
    *file = (int)idx;
    *real = line;
    return true;
}

/* A driver's or glslang's log line, placed: the file (an index of
 * s->files) and line it means, its severity when the format says it
 * before the place (glslang), and the message after the place. */
typedef struct log_line {
    int file;
    long line;
    const char *sev;        /* "error", "warning", "note", "error: unimplemented"; NULL: in text */
    const char *text;
    size_t n;
} log_line;

static bool place_line(const shader_src *s, line_view l, log_line *out) {
    const char *p = l.p, *end = l.p + l.n;
    while (p < end && (*p == ' ' || *p == '\t')) p++;
    static const char *const sev[][2] = {
        { "ERROR: ", "error" }, { "WARNING: ", "warning" }, { "NOTE: ", "note" },
        { "UNIMPLEMENTED: ", "error: unimplemented" },
    };
    long idx, line;
    /* glslang, AMD, Apple: "ERROR: 0:12: message" */
    for (size_t i = 0; i < sizeof sev / sizeof sev[0]; i++) {
        size_t n = strlen(sev[i][0]);
        if ((size_t)(end - p) < n || memcmp(p, sev[i][0], n) != 0) continue;
        const char *q = p + n;
        if (!parse_uint(&q, end, &idx) || q >= end || *q != ':') return false;
        q++;
        if (!parse_uint(&q, end, &line) || q >= end || *q != ':') return false;
        q++;
        while (q < end && *q == ' ') q++;
        if (!decode_loc(s, idx, line, &out->file, &out->line)) return false;
        const char *e = end;
        while (e > q && (e[-1] == ' ' || e[-1] == '\t')) e--;
        *out = (log_line){ out->file, out->line, sev[i][1], q, (size_t)(e - q) };
        return true;
    }
    const char *q = p;
    if (!parse_uint(&q, end, &idx)) return false;
    if (q < end && *q == ':') {
        /* Mesa: "0:12(5): error: message" */
        q++;
        if (!parse_uint(&q, end, &line)) return false;
        if (q < end && *q == '(') {
            long col;
            q++;
            if (!parse_uint(&q, end, &col) || q >= end || *q != ')') return false;
            q++;
        }
        if (q >= end || *q != ':') return false;
        q++;
    } else if (q < end && *q == '(') {
        /* NVIDIA: "0(12) : error C0000: message" */
        q++;
        if (!parse_uint(&q, end, &line) || q >= end || *q != ')') return false;
        q++;
        while (q < end && *q == ' ') q++;
        if (q >= end || *q != ':') return false;
        q++;
    } else {
        return false;
    }
    while (q < end && *q == ' ') q++;
    if (!decode_loc(s, idx, line, &out->file, &out->line)) return false;
    *out = (log_line){ out->file, out->line, NULL, q, (size_t)(end - q) };
    return true;
}

/* The log's lines one at a time (a last line without '\n' too). */
static bool next_log_line(const char **p, line_view *l) {
    if (!*p || !**p) return false;
    const char *e = strchr(*p, '\n');
    *l = (line_view){ *p, e ? (size_t)(e - *p) : strlen(*p) };
    *p = e ? e + 1 : *p + l->n;
    return true;
}

/* The mapped form of one placed line: `file:line: [severity: ]message`. */
static void put_placed(const shader_src *s, const log_line *m, strbuf *o) {
    strbuf_printf(o, "%s:%ld: ", s->files[m->file], m->line);
    if (m->sev) strbuf_printf(o, "%s: ", m->sev);
    strbuf_put(o, m->text, m->n);
}

char *shader_src_map_log(const shader_src *s, const char *log) {
    strbuf o = {0};
    strbuf_puts(&o, "");
    if (!log) return o.s;
    const char *p = log;
    while (*p) {
        const char *e = strchr(p, '\n');
        line_view l = { p, e ? (size_t)(e - p) : strlen(p) };
        log_line m;
        if (s && place_line(s, l, &m)) put_placed(s, &m, &o);
        else strbuf_put(&o, l.p, l.n);
        if (!e) break;
        strbuf_puts(&o, "\n");
        p = e + 1;
    }
    return o.s;
}

/* The severity a message names first ("error: ..." -> DIAG_ERROR, with
 * *text past it); false when it names none. */
static bool leading_severity(const char **text, size_t *n, diag_severity *sev) {
    static const struct { const char *word; diag_severity sev; } words[] = {
        { "error: ", DIAG_ERROR }, { "warning: ", DIAG_WARNING }, { "note: ", DIAG_NOTE },
    };
    for (size_t i = 0; i < sizeof words / sizeof words[0]; i++) {
        size_t k = strlen(words[i].word);
        if (*n >= k && memcmp(*text, words[i].word, k) == 0) {
            *text += k;
            *n -= k;
            *sev = words[i].sev;
            return true;
        }
    }
    return false;
}

void shader_src_map_diags(const shader_src *s, const char *log, diag_severity sev, diag_list *out) {
    line_view l;
    for (const char *p = log; next_log_line(&p, &l);) {
        if (l.n == 0) continue;
        log_line m;
        if (!s || !place_line(s, l, &m)) {   /* no place of the stage's: the tool's own words */
            char *line = mem_strndup(l.p, l.n);
            diag_add_log(out, sev, line);
            free(line);
            continue;
        }
        const char *file = s->files[m.file], *text = m.text;
        size_t n = m.n;
        diag_severity got;
        if (m.sev) {   /* glslang's word before the place: "error", "error: unimplemented", ... */
            got = m.sev[0] == 'w' ? DIAG_WARNING : m.sev[0] == 'n' ? DIAG_NOTE : DIAG_ERROR;
            const char *more = strchr(m.sev, ' ');   /* "unimplemented" */
            diag_add(out, got, file, (int)m.line, "%s%s%.*s", more ? more + 1 : "", more ? ": " : "", (int)n, text);
        } else if (leading_severity(&text, &n, &got)) {   /* Mesa's "error: ..." after the place */
            diag_add(out, got, file, (int)m.line, "%.*s", (int)n, text);
        } else {   /* NVIDIA's "error C0000: ...": as written, placed */
            diag_add_bare(out, sev, "%s:%ld: %.*s", file, m.line, (int)n, text);
        }
    }
}

const char *shader_stage_name(shader_stage st) {
    switch (st) {
    case SHADER_VERTEX: return "vertex";
    case SHADER_TESS_CONTROL: return "tess control";
    case SHADER_TESS_EVALUATION: return "tess evaluation";
    case SHADER_GEOMETRY: return "geometry";
    case SHADER_FRAGMENT: return "fragment";
    default: return "unknown";
    }
}

static shader_stage stage_from_word(const char *w, size_t n) {
    static const struct { const char *w; shader_stage st; } words[] = {
        { "vert", SHADER_VERTEX }, { "vs", SHADER_VERTEX }, { "vertex", SHADER_VERTEX },
        { "tesc", SHADER_TESS_CONTROL }, { "tcs", SHADER_TESS_CONTROL },
        { "tese", SHADER_TESS_EVALUATION }, { "tes", SHADER_TESS_EVALUATION },
        { "geom", SHADER_GEOMETRY }, { "gs", SHADER_GEOMETRY }, { "geometry", SHADER_GEOMETRY },
        { "frag", SHADER_FRAGMENT }, { "fs", SHADER_FRAGMENT }, { "fragment", SHADER_FRAGMENT },
    };
    for (size_t i = 0; i < sizeof words / sizeof words[0]; i++)
        if (n == strlen(words[i].w) && strncasecmp(w, words[i].w, n) == 0) return words[i].st;
    return SHADER_STAGE_COUNT;
}

shader_stage shader_stage_from_path(const char *path) {
    if (!path) return SHADER_STAGE_COUNT;
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    const char *dot = strrchr(base, '.');
    if (!dot || dot == base) return SHADER_STAGE_COUNT;
    const char *ext = dot + 1;
    if (strcasecmp(ext, "glsl") != 0) {
        /* only the short extensions; "vertex"/"fragment" as an extension is unusual */
        if (strcasecmp(ext, "vertex") == 0 || strcasecmp(ext, "fragment") == 0 ||
            strcasecmp(ext, "geometry") == 0)
            return SHADER_STAGE_COUNT;
        return stage_from_word(ext, strlen(ext));
    }
    /* name.SUFFIX.glsl, name_SUFFIX.glsl, name-SUFFIX.glsl */
    const char *e = dot, *s = dot;
    while (s > base && s[-1] != '.' && s[-1] != '_' && s[-1] != '-') s--;
    if (s == base) return SHADER_STAGE_COUNT;
    return stage_from_word(s, (size_t)(e - s));
}
