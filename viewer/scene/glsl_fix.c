/* glsl_fix: rewrites for GLSL that NVIDIA accepted and the spec rejects (glsl_fix.h). */
#include "glsl_fix.h"

#include "mem.h"
#include "strbuf.h"

#include <ctype.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define WHY "NVIDIA accepted this; the GLSL specification does not"

/* ---- the text: lines, #line numbers, depths ------------------------------------ */

typedef struct line_info {
    size_t start, end;      /* [start, end): the line without its '\n' */
    int file;
    long line;
    bool directive;
} line_info;

typedef struct edit {
    size_t at, del;
    char *ins;
    int prio;               /* at one position: the lower, the further left */
} edit;

typedef struct fixer {
    const shader_src *src;
    shader_stage stage;
    const char *text;
    char *b;                /* text with comments blanked (same offsets) */
    size_t n;
    int *depth;             /* brace depth before each char */
    line_info *ln;
    int nln;
    edit *ed;
    int ned, cap;
    diag_list notes;        /* a warning a rewrite */
    char done[64][64];      /* what was rewritten already (a name, a kind and line) */
    int ndone;
    size_t fn_defs_at;      /* where overloads go; (size_t)-1 none yet */
    char fn_defs[8][16];
    int nfn_defs;
    int version;            /* the text's #version (0: none) */
    bool es;
} fixer;

static bool is_ident_char(char ch) { return isalnum((unsigned char)ch) || ch == '_'; }

static void build_lines(fixer *f) {
    int version = 0;
    char profile[32] = "";
    bool old_rule = false;
    if (sscanf(f->text, " #version %d %31s", &version, profile) >= 1)
        old_rule = version < 330 && version != 100 && version != 300 && strcmp(profile, "es") != 0;
    f->version = version;
    f->es = strcmp(profile, "es") == 0 || version == 100 || version == 300;
    int cap = 0, file = 0;
    long line = 1;
    for (size_t p = 0; p <= f->n;) {
        const char *e = memchr(f->text + p, '\n', f->n - p);
        size_t end = e ? (size_t)(e - f->text) : f->n;
        const char *q = f->text + p;
        while (q < f->text + end && (*q == ' ' || *q == '\t')) q++;
        bool dir = q < f->text + end && *q == '#';
        f->ln = mem_grow(f->ln, &cap, f->nln + 1, sizeof *f->ln);
        f->ln[f->nln++] = (line_info){ p, end, file, line, dir };
        long a, k;
        int got = dir ? sscanf(q, "# line %ld %ld", &a, &k) : 0;
        if (got >= 1) {
            long next = old_rule ? a + 1 : a;
            if (next >= SHADER_SRC_LINE_BASE) {
                file = (int)(next / SHADER_SRC_LINE_BASE);
                line = next % SHADER_SRC_LINE_BASE;
            } else {
                file = got == 2 ? (int)k : file;
                line = next;
            }
        } else {
            line++;
        }
        if (!e) break;
        p = end + 1;
    }
}

static int line_of(const fixer *f, size_t pos) {
    int lo = 0, hi = f->nln - 1;
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (f->ln[mid].start <= pos) lo = mid;
        else hi = mid - 1;
    }
    return lo;
}

static bool in_directive(const fixer *f, size_t pos) { return f->ln[line_of(f, pos)].directive; }

static void build_depths(fixer *f) {
    f->depth = mem_zalloc((f->n + 1) * sizeof *f->depth);
    int d = 0;
    for (int i = 0; i < f->nln; i++) {
        const line_info *l = &f->ln[i];
        for (size_t p = l->start; p < l->end; p++) {
            f->depth[p] = d;
            if (l->directive) continue;
            if (f->b[p] == '{') d++;
            else if (f->b[p] == '}' && d > 0) d--;
        }
        if (l->end <= f->n) f->depth[l->end] = d;
    }
}

/* the physical line that holds (file, line) of the user's text; -1 none */
static int find_line(const fixer *f, const char *file, long line) {
    int k = -1;
    for (int i = 0; i < f->src->nfiles; i++)
        if (strcmp(f->src->files[i], file) == 0) { k = i; break; }
    if (k < 0) return -1;
    for (int i = 0; i < f->nln; i++)
        if (!f->ln[i].directive && f->ln[i].file == k && f->ln[i].line == line) return i;
    return -1;
}

static void add_edit(fixer *f, size_t at, size_t del, const char *ins, int prio) {
    for (int i = 0; i < f->ned; i++)   /* the same edit twice (two messages, one place) */
        if (f->ed[i].at == at && f->ed[i].del == del && strcmp(f->ed[i].ins, ins) == 0) return;
    f->ed = mem_grow(f->ed, &f->cap, f->ned + 1, sizeof *f->ed);
    f->ed[f->ned++] = (edit){ at, del, mem_strdup(ins), prio };
}

static void note(fixer *f, size_t pos, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void note(fixer *f, size_t pos, const char *fmt, ...) {
    const line_info *l = &f->ln[line_of(f, pos)];
    const char *file = l->file >= 0 && l->file < f->src->nfiles ? f->src->files[l->file] : "?";
    char text[DIAG_TEXT_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    diag_add(&f->notes, DIAG_WARNING, file, (int)l->line, "%s", text);
}

static void fixer_free(fixer *f) {
    for (int i = 0; i < f->ned; i++) free(f->ed[i].ins);
    free(f->ed);
    free(f->ln);
    free(f->depth);
    free(f->b);
    diag_list_free(&f->notes);
}

/* Appends the fixer's notes to *notes (NULL: dropped). */
static void hand_notes(const fixer *f, diag_list *notes) {
    for (int i = 0; notes && i < f->notes.n; i++) diag_push(notes, &f->notes.d[i]);
}

static bool done(fixer *f, const char *name) {
    for (int i = 0; i < f->ndone; i++)
        if (strcmp(f->done[i], name) == 0) return true;
    if (f->ndone < 64) snprintf(f->done[f->ndone++], sizeof f->done[0], "%s", name);
    return false;
}

/* ---- scanning ------------------------------------------------------------------ */

static size_t skip_ws(const fixer *f, size_t p) {
    while (p < f->n && isspace((unsigned char)f->b[p])) p++;
    return p;
}

static size_t skip_ws_back(const fixer *f, size_t p) {   /* p: one past; returns one past the last non-space */
    while (p > 0 && isspace((unsigned char)f->b[p - 1])) p--;
    return p;
}

/* Is the identifier at p exactly word (whole token)? */
static bool word_at(const fixer *f, size_t p, const char *word) {
    size_t n = strlen(word);
    return p + n <= f->n && memcmp(f->b + p, word, n) == 0 && (p == 0 || !is_ident_char(f->b[p - 1])) &&
           !is_ident_char(f->b[p + n]);
}

/* The next whole-word occurrence of word in [from, to), outside directives; to on none. */
static size_t find_word(const fixer *f, size_t from, size_t to, const char *word) {
    size_t n = strlen(word);
    for (size_t p = from; p + n <= to; p++) {
        if (f->b[p] != word[0] || !word_at(f, p, word)) continue;
        if (in_directive(f, p)) continue;
        return p;
    }
    return to;
}

/* Copies the identifier at p into out; its length (0: none). */
static size_t ident_at(const fixer *f, size_t p, char *out, size_t outlen) {
    size_t e = p;
    while (e < f->n && is_ident_char(f->b[e])) e++;
    if (e == p || e - p >= outlen || isdigit((unsigned char)f->b[p])) { if (outlen) out[0] = '\0'; return 0; }
    memcpy(out, f->b + p, e - p);
    out[e - p] = '\0';
    return e - p;
}

/* The start of the statement holding pos: after the last ';', '{' or '}'
 * (outside directives), then past blanks and directive lines. */
static size_t stmt_start(const fixer *f, size_t pos) {
    size_t p = pos;
    while (p > 0) {
        char c = f->b[p - 1];
        if ((c == ';' || c == '{' || c == '}') && !in_directive(f, p - 1)) break;
        p--;
    }
    for (;;) {
        p = skip_ws(f, p);
        if (p < f->n && in_directive(f, p)) { p = f->ln[line_of(f, p)].end; continue; }
        return p;
    }
}

/* The '{' of the function whose body holds pos; (size_t)-1 at global scope. */
static size_t function_brace(const fixer *f, size_t pos) {
    if (pos > f->n || f->depth[pos] == 0) return (size_t)-1;
    for (size_t p = pos; p-- > 0;)
        if (f->b[p] == '{' && f->depth[p] == 0 && !in_directive(f, p)) return p;
    return (size_t)-1;
}

/* The return type and name of the function whose '{' is at brace. */
static bool function_header(const fixer *f, size_t brace, char *type, size_t tlen, char *name, size_t nlen) {
    size_t p = skip_ws_back(f, brace);
    if (p == 0 || f->b[p - 1] != ')') return false;
    int d = 0;
    for (p = p - 1;; p--) {
        if (f->b[p] == ')') d++;
        else if (f->b[p] == '(' && --d == 0) break;
        if (p == 0) return false;
    }
    size_t e = skip_ws_back(f, p), s = e;
    while (s > 0 && is_ident_char(f->b[s - 1])) s--;
    if (s == e || e - s >= nlen) return false;
    memcpy(name, f->b + s, e - s);
    name[e - s] = '\0';
    e = skip_ws_back(f, s);
    s = e;
    while (s > 0 && is_ident_char(f->b[s - 1])) s--;
    if (s == e || e - s >= tlen) return false;
    memcpy(type, f->b + s, e - s);
    type[e - s] = '\0';
    return true;
}

/* Where definitions for code at pos can go: the start of the global
 * declaration or function that holds it (active code: the compiler saw it). */
static size_t global_start(const fixer *f, size_t pos) {
    size_t brace = function_brace(f, pos);
    return stmt_start(f, brace != (size_t)-1 ? brace : pos);
}

/* The ';' that ends the expression starting at p (brackets balanced); n on none. */
static size_t expr_end(const fixer *f, size_t p) {
    int d = 0;
    for (; p < f->n; p++) {
        char c = f->b[p];
        if (c == '(' || c == '[') d++;
        else if ((c == ')' || c == ']') && d > 0) d--;
        else if ((c == ';' || c == '{' || c == '}') && d == 0) return c == ';' ? p : f->n;
    }
    return f->n;
}

static bool is_value_type(const char *t) {
    static const char *const v[] = { "float", "int", "uint", "double", "bool" };
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
        if (strcmp(t, v[i]) == 0) return true;
    size_t n = strlen(t);
    if (n < 4 || t[n - 1] < '2' || t[n - 1] > '4' || strncmp(t + n - 4, "vec", 3) != 0) return false;
    return n == 4 || (n == 5 && strchr("iubd", t[0]));
}

/* ---- the rewrites ---------------------------------------------------------------- */

/* `return 1;` in a float function -> `return float(1);` (each return on the line). */
static void fix_return(fixer *f, int li) {
    const line_info *l = &f->ln[li];
    char key[32];
    snprintf(key, sizeof key, "ret:%d", li);
    if (done(f, key)) return;
    for (size_t p = find_word(f, l->start, l->end, "return"); p < l->end;
         p = find_word(f, p + 6, l->end, "return")) {
        size_t brace = function_brace(f, p);
        char type[32], name[64];
        if (brace == (size_t)-1 || !function_header(f, brace, type, sizeof type, name, sizeof name) ||
            !is_value_type(type))
            continue;
        size_t s = skip_ws(f, p + 6), e = expr_end(f, s);
        if (e >= f->n || s >= e) continue;
        char tpre[40];
        snprintf(tpre, sizeof tpre, "%s(", type);
        add_edit(f, s, 0, tpre, 1);
        add_edit(f, e, 0, ")", 3);
        size_t ee = skip_ws_back(f, e);
        note(f, p, "rewrote `return %.*s;` as `return %s(%.*s);`: %s() returns %s, and this returned another "
             "type (%s: write the value as a %s)", (int)(ee - s), f->text + s, type, (int)(ee - s), f->text + s,
             name, type, WHY, type);
    }
}

/* A const whose initialiser is not constant: drop `const` from the statement on the line. */
static void fix_const(fixer *f, int li, const char *name) {
    const line_info *l = &f->ln[li];
    char key[32];
    snprintf(key, sizeof key, "const:%d", li);
    if (done(f, key)) return;
    size_t first = skip_ws(f, l->start);
    if (first >= l->end) return;
    size_t s = stmt_start(f, first), e = expr_end(f, s);
    if (e > f->n) e = f->n;
    for (size_t p = find_word(f, s, e, "const"); p < e; p = find_word(f, p + 5, e, "const")) {
        int paren = 0;   /* a function parameter's const is not it */
        for (size_t q = s; q < p; q++) paren += f->b[q] == '(' ? 1 : f->b[q] == ')' ? -1 : 0;
        if (paren != 0) continue;
        size_t del = 5;
        while (p + del < e && (f->b[p + del] == ' ' || f->b[p + del] == '\t')) del++;
        add_edit(f, p, del, "", 3);
        char nm[64] = "";
        if (!name || !name[0]) {   /* the declared name: the word before '=' */
            size_t eq = p;
            while (eq < e && f->b[eq] != '=') eq++;
            size_t ne = skip_ws_back(f, eq), ns = ne;
            while (ns > p && is_ident_char(f->b[ns - 1])) ns--;
            if (ne > ns && ne - ns < sizeof nm) { memcpy(nm, f->b + ns, ne - ns); nm[ne - ns] = '\0'; }
        }
        const char *n = name && name[0] ? name : nm;
        note(f, p, "dropped `const` from %s%s%s: its initialiser is only known when the shader runs (%s: a "
             "const must be a constant expression)", n[0] ? "'" : "", n[0] ? n : "the declaration",
             n[0] ? "'" : "", WHY);
    }
}

static bool is_qual_word(const char *w) {
    static const char *const q[] = { "in", "varying", "attribute", "flat", "smooth", "noperspective", "centroid",
                                     "sample", "highp", "mediump", "lowp", "invariant", "patch", "precise" };
    for (size_t i = 0; i < sizeof q / sizeof q[0]; i++)
        if (strcmp(w, q[i]) == 0) return true;
    return false;
}

/* A write to an input `X`: a global `TYPE tarn_X;` after its declaration,
 * `tarn_X = X;` first thing in main(), every later use renamed. */
static void fix_input(fixer *f, const char *name, int li) {
    char key[64];
    snprintf(key, sizeof key, "in:%s", name);
    if (done(f, key)) return;
    size_t decl_end = f->n, name_at = f->n;
    char type[32] = "";
    for (size_t p = find_word(f, 0, f->n, name); p < f->n; p = find_word(f, p + 1, f->n, name)) {
        if (f->depth[p] != 0) continue;
        size_t s = stmt_start(f, p);
        bool input = false;
        char w[32];
        type[0] = '\0';
        for (size_t q = s; q < p;) {
            size_t len = ident_at(f, q, w, sizeof w);
            if (!len) {
                if (f->b[q] == '(') {   /* layout(...) */
                    int d = 0;
                    for (; q < p; q++) { d += f->b[q] == '(' ? 1 : f->b[q] == ')' ? -1 : 0; if (!d) break; }
                }
                q++;
                continue;
            }
            if (strcmp(w, "in") == 0 || strcmp(w, "varying") == 0 || strcmp(w, "attribute") == 0) input = true;
            else if (strcmp(w, "uniform") == 0 || strcmp(w, "out") == 0 || strcmp(w, "const") == 0) { input = false; break; }
            else if (!type[0] && !is_qual_word(w) && strcmp(w, "layout") != 0) snprintf(type, sizeof type, "%s", w);
            q += len;
        }
        if (!input || !type[0] || (!is_value_type(type) && strncmp(type, "mat", 3) != 0)) continue;
        decl_end = expr_end(f, p);
        name_at = p;
        break;
    }
    if (decl_end >= f->n) return;
    /* main's body */
    const char *from = f->b, *main_body = shader_src_next_main_body(f->b, &from);
    size_t body = main_body ? (size_t)(main_body - f->b) : f->n;
    if (body >= f->n || body < decl_end) return;
    /* an array input keeps its size */
    size_t after = skip_ws(f, name_at + strlen(name));
    char suffix[64] = "";
    if (after < f->n && f->b[after] == '[') {
        size_t e = after;
        while (e < f->n && f->b[e] != ']') e++;
        if (e < f->n && e - after + 1 < sizeof suffix) memcpy(suffix, f->b + after, e - after + 1);
    }
    char ins[192];
    snprintf(ins, sizeof ins, " %s tarn_%s%s;", type, name, suffix);
    add_edit(f, decl_end + 1, 0, ins, 3);
    snprintf(ins, sizeof ins, " tarn_%s = %s;", name, name);
    add_edit(f, body, 0, ins, 3);
    for (size_t p = find_word(f, decl_end, f->n, name); p < f->n; p = find_word(f, p + 1, f->n, name)) {
        size_t b = skip_ws_back(f, p);
        if (b > 0 && f->b[b - 1] == '.') continue;   /* a member of that name */
        add_edit(f, p, 0, "tarn_", 2);
    }
    note(f, li >= 0 ? f->ln[li].start : name_at, "'%s' is an input and the shader writes it: it now reads a copy, tarn_%s (a global set "
         "from %s at the start of main()) (%s: inputs are read-only; declare a local copy and change that)",
         name, name, name, WHY);
}

/* pow(vec2, float) and friends: the call becomes tarn_pow(...), overloads that widen the scalar. */
static const char *const widen_fns[] = { "pow", "atan", "mod", "min", "max", "step" };

static bool widen_fn(const char *fn) {
    for (size_t i = 0; i < sizeof widen_fns / sizeof widen_fns[0]; i++)
        if (strcmp(fn, widen_fns[i]) == 0) return true;
    return false;
}

static void fix_widen(fixer *f, int li, const char *fn) {
    const line_info *l = &f->ln[li];
    char key[48];
    snprintf(key, sizeof key, "%s:%d", fn, li);
    if (done(f, key)) return;
    bool any = false;
    for (size_t p = find_word(f, l->start, l->end, fn); p < l->end; p = find_word(f, p + 1, l->end, fn)) {
        size_t q = skip_ws(f, p + strlen(fn));
        size_t b = skip_ws_back(f, p);
        if (q >= f->n || f->b[q] != '(' || (b > 0 && f->b[b - 1] == '.')) continue;
        add_edit(f, p, 0, "tarn_", 2);
        size_t g = global_start(f, p);
        if (f->fn_defs_at == (size_t)-1 || g < f->fn_defs_at) f->fn_defs_at = g;
        any = true;
    }
    if (!any) return;
    bool have = false;
    for (int i = 0; i < f->nfn_defs; i++) have |= strcmp(f->fn_defs[i], fn) == 0;
    if (!have && f->nfn_defs < 8) snprintf(f->fn_defs[f->nfn_defs++], sizeof f->fn_defs[0], "%s", fn);
    note(f, l->start, "rewrote %s(...) as tarn_%s(...), which widens a scalar argument to the vector's size "
         "(%s: %s takes arguments of one type; write %s(v, vec3(s)))", fn, fn, WHY, fn, fn);
}

static void fn_defs_text(const fixer *f, strbuf *o) {
    static const char *const t[] = { "float", "vec2", "vec3", "vec4" };
    for (int k = 0; k < f->nfn_defs; k++) {
        const char *fn = f->fn_defs[k];
        for (int i = 0; i < 4; i++)
            strbuf_printf(o, "%s tarn_%s(%s a, %s b) { return %s(a, b); } ", t[i], fn, t[i], t[i], fn);
        for (int i = 1; i < 4; i++) {
            strbuf_printf(o, "%s tarn_%s(%s a, float b) { return %s(a, %s(b)); } ", t[i], fn, t[i], fn, t[i]);
            strbuf_printf(o, "%s tarn_%s(float a, %s b) { return %s(%s(a), b); } ", t[i], fn, t[i], fn, t[i]);
        }
        if (strcmp(fn, "atan") == 0)
            for (int i = 0; i < 4; i++) strbuf_printf(o, "%s tarn_atan(%s a) { return atan(a); } ", t[i], t[i]);
    }
}

/* `#extension NAME : enable` after the #version line (a `#line` follows it
 * in every assembled text, so the user's lines keep their numbers). */
static void enable_extension(fixer *f, const char *name) {
    if (strstr(f->text, name) || f->nln < 2 || !f->ln[0].directive) return;
    char ins[128];
    snprintf(ins, sizeof ins, "\n#extension %s : enable  // tarn: NVIDIA enabled it unasked", name);
    add_edit(f, f->ln[0].end, 0, ins, 3);
}

/* `flat` under GLSL before 1.30 (a syntax error there): NVIDIA read it as
 * GL_EXT_gpu_shader4's, which tarn enables. */
static void fix_flat_syntax(fixer *f, int li) {
    if (f->version >= 130 || f->es || done(f, "gpu_shader4")) return;
    const line_info *l = &f->ln[li];
    size_t p = find_word(f, l->start, l->end, "flat");
    if (p >= l->end) p = find_word(f, l->start, l->end, "noperspective");
    if (p >= l->end || f->depth[p] != 0) return;
    enable_extension(f, "GL_EXT_gpu_shader4");
    note(f, p, "`flat` before GLSL 1.30 needs GL_EXT_gpu_shader4, which tarn enabled (%s: write #version 130 or "
         "later, or enable the extension)", WHY);
}

/* `flat varying` -> `flat in` (fragment) / `flat out` (vertex). */
static void fix_varying(fixer *f, int li) {
    const char *to = f->stage == SHADER_FRAGMENT ? "in" : f->stage == SHADER_VERTEX ? "out" : NULL;
    char key[32];
    snprintf(key, sizeof key, "varying:%d", li);
    if (!to || done(f, key)) return;
    const line_info *l = &f->ln[li];
    for (size_t p = find_word(f, l->start, l->end, "varying"); p < l->end; p = find_word(f, p + 7, l->end, "varying")) {
        add_edit(f, p, 7, to, 3);
        note(f, p, "rewrote `varying` after an interpolation qualifier as `%s` (%s: `varying` takes no "
             "flat/smooth/noperspective; write `flat %s`)", to, WHY, to);
    }
}

/* A fragment shader writing gl_FragColor with `out` variables declared: the outs become globals. */
static void fix_outs(fixer *f) {
    if (f->stage != SHADER_FRAGMENT || done(f, "outs")) return;
    for (size_t p = find_word(f, 0, f->n, "out"); p < f->n; p = find_word(f, p + 3, f->n, "out")) {
        if (f->depth[p] != 0) continue;
        size_t s = stmt_start(f, p);
        int paren = 0;
        for (size_t q = s; q < p; q++) paren += f->b[q] == '(' ? 1 : f->b[q] == ')' ? -1 : 0;
        if (paren != 0) continue;
        size_t del = 3;
        while (p + del < f->n && (f->b[p + del] == ' ' || f->b[p + del] == '\t')) del++;
        add_edit(f, p, del, "", 3);
        size_t lay = find_word(f, s, p, "layout");   /* layout(location = 0): outputs only */
        if (lay < p) {
            size_t q = skip_ws(f, lay + 6);
            int d = 0;
            for (; q < p; q++) { d += f->b[q] == '(' ? 1 : f->b[q] == ')' ? -1 : 0; if (f->b[q] == ')' && !d) break; }
            if (q < p) {
                q++;
                while (q < p && (f->b[q] == ' ' || f->b[q] == '\t')) q++;
                add_edit(f, lay, q - lay, "", 3);
            }
        }
        size_t e = expr_end(f, p);
        size_t ne = skip_ws_back(f, e < f->n ? e : p);
        note(f, p, "the shader writes gl_FragColor, so `%.*s` is no output: it is now a plain global (%s: a "
             "fragment shader writes gl_FragColor or its own outputs, not both)",
             (int)(ne > s ? ne - s : 0), f->text + s, WHY);
    }
}

/* ---- the log --------------------------------------------------------------------- */

/* "file:line: error: msg" -> its parts (file and line into the buffers). */
bool glsl_fix_wanted_by_warning(const diag_list *log) {
    for (int i = 0; log && i < log->n; i++)
        if (strstr(log->d[i].text, "'return' : type conversion on return values was not explicitly allowed"))
            return true;
    return false;
}

static void fix_message(fixer *f, const char *file, long lno, const char *msg) {
    int li = find_line(f, file, lno);
    char a[64] = "";
    if (strstr(msg, "writes to both `gl_Frag") ||
        strstr(msg, "Cannot use gl_FragColor or gl_FragData when using user-defined outputs")) {
        fix_outs(f);
        return;
    }
    if (li < 0) return;
    if ((strncmp(msg, "`return' with wrong type ", 25) == 0 && strncmp(msg + 25, "error,", 6) != 0) ||
        strncmp(msg, "'return' : cannot convert return value", 38) == 0 ||
        strncmp(msg, "'return' : type conversion on return values", 43) == 0) {
        fix_return(f, li);
    } else if (sscanf(msg, "initializer of const variable `%63[^']'", a) == 1 ||
               strstr(msg, "global const initializers must be constant") ||
               strncmp(msg, "'non-constant initializer'", 26) == 0) {
        fix_const(f, li, a);
    } else if (sscanf(msg, "assignment to read-only variable '%63[^']'", a) == 1 ||
               (strstr(msg, "(can't modify shader input)") && strstr(msg, "l-value required \"") &&
                sscanf(strstr(msg, "l-value required \""), "l-value required \"%63[^\"]\"", a) == 1)) {
        if (strncmp(a, "gl_", 3) != 0) fix_input(f, a, li);
    } else if (sscanf(msg, "no matching function for call to `%63[^(]", a) == 1) {
        /* only a vector mixed with a scalar: what NVIDIA widened */
        const char *args = strchr(msg, '(');
        bool vec = args && strstr(args, "vec"), scalar = args && (strstr(args, "float") || strstr(args, "int"));
        if (widen_fn(a) && vec && scalar) fix_widen(f, li, a);
    } else if (sscanf(msg, "'%63[^']' : no matching overloaded function found", a) == 1) {
        if (widen_fn(a)) fix_widen(f, li, a);
    } else if (strstr(msg, "cannot be applied to the deprecated storage qualifier 'varying'")) {
        fix_varying(f, li);
    } else if (strstr(msg, "syntax error")) {
        fix_flat_syntax(f, li);
    }
}

static int edit_cmp(const void *a, const void *b) {
    const edit *x = a, *y = b;
    if (x->at != y->at) return x->at < y->at ? 1 : -1;   /* from the end */
    return y->prio - x->prio;                           /* higher priority first: ends up right */
}

char *glsl_fix_rewrite(const shader_src *src, shader_stage stage, const char *text, const diag_list *log,
                       diag_list *notes) {
    if (!src || !text || !log) return NULL;
    fixer f = { .src = src, .stage = stage, .text = text, .n = strlen(text), .fn_defs_at = (size_t)-1 };
    f.b = shader_src_blank_comments(text);
    build_lines(&f);
    build_depths(&f);
    for (int i = 0; i < log->n; i++) {   /* its errors and warnings; not Mesa's indented candidates */
        const diag *d = &log->d[i];
        if (d->severity >= DIAG_WARNING && !d->bare && d->file[0] && d->text[0] != ' ')
            fix_message(&f, d->file, d->line, d->text);
    }
    if (f.nfn_defs) {
        strbuf d = {0};
        fn_defs_text(&f, &d);
        add_edit(&f, f.fn_defs_at, 0, d.s, 0);
        strbuf_free(&d);
    }
    char *out = NULL;
    if (f.ned) {
        qsort(f.ed, (size_t)f.ned, sizeof *f.ed, edit_cmp);
        /* build forwards from the sorted-backwards list */
        strbuf o = {0};
        size_t pos = 0;
        for (int i = f.ned - 1; i >= 0; i--) {
            const edit *x = &f.ed[i];
            if (x->at < pos) continue;   /* overlaps an earlier deletion */
            strbuf_put(&o, text + pos, x->at - pos);
            strbuf_puts(&o, x->ins);
            pos = x->at + x->del;
        }
        strbuf_puts(&o, text + pos);
        out = strbuf_take(&o);
        if (strcmp(out, text) == 0) { free(out); out = NULL; }
    }
    if (out) hand_notes(&f, notes);
    fixer_free(&f);
    return out;
}

/* ---- a uniform with two types ---------------------------------------------------- */

/* Where a declaration is, in the user's files. */
typedef struct decl_at {
    const char *file;
    int line;
} decl_at;

/* The declaration of uniform name in src's text: its type and file:line. */
static bool find_uniform(const shader_src *src, const char *name, char *type, size_t tlen, decl_at *where) {
    fixer f = { .src = src, .text = src->text, .n = strlen(src->text) };
    f.b = shader_src_blank_comments(src->text);
    build_lines(&f);
    build_depths(&f);
    bool found = false;
    for (size_t p = find_word(&f, 0, f.n, name); p < f.n && !found; p = find_word(&f, p + 1, f.n, name)) {
        if (f.depth[p] != 0) continue;
        size_t s = stmt_start(&f, p);
        if (find_word(&f, s, p, "uniform") >= p) continue;
        char w[32], last[32] = "";
        for (size_t q = s; q < p;) {
            size_t len = ident_at(&f, q, w, sizeof w);
            if (!len) { q++; continue; }
            if (strcmp(w, "uniform") != 0 && !is_qual_word(w) && strcmp(w, "layout") != 0 && !last[0])
                snprintf(last, sizeof last, "%s", w);
            q += len;
        }
        if (!last[0]) continue;
        snprintf(type, tlen, "%s", last);
        const line_info *l = &f.ln[line_of(&f, p)];
        where->file = l->file >= 0 && l->file < src->nfiles ? src->files[l->file] : "?";
        where->line = (int)l->line;
        found = true;
    }
    free(f.ln);
    free(f.depth);
    free(f.b);
    return found;
}

bool glsl_fix_link_hint(const char *log, const shader_src *const srcs[SHADER_STAGE_COUNT], diag_list *notes) {
    if (!log) return false;
    bool any = false;
    strbuf o = {0};
    char seen[8][64];
    int nseen = 0;
    for (const char *p = log; p && *p; p = strchr(p, '\n') ? strchr(p, '\n') + 1 : NULL) {
        char name[64];
        const char *m;
        if ((m = strstr(p, "uniform `")) && sscanf(m, "uniform `%63[^']' declared as type", name) == 1) {
        } else if ((m = strstr(p, "Types must match:")) && (m = strchr(m, '"'))) {
            /* glslang: ... " vec3 uC" ... : the last word in the quotes */
            const char *q = strchr(m + 1, '"');
            if (!q) continue;
            const char *s = q;
            while (s > m + 1 && (isalnum((unsigned char)s[-1]) || s[-1] == '_')) s--;
            if ((size_t)(q - s) >= sizeof name || q == s) continue;
            memcpy(name, s, (size_t)(q - s));
            name[q - s] = '\0';
        } else {
            continue;
        }
        bool dup = false;
        for (int i = 0; i < nseen; i++) dup |= strcmp(seen[i], name) == 0;
        if (dup || nseen >= 8) continue;
        snprintf(seen[nseen++], sizeof seen[0], "%s", name);
        char types[SHADER_STAGE_COUNT][32];
        decl_at where[SHADER_STAGE_COUNT];
        int st[SHADER_STAGE_COUNT], n = 0;
        for (int s = 0; s < SHADER_STAGE_COUNT; s++)
            if (srcs[s] && srcs[s]->text &&
                find_uniform(srcs[s], name, types[n], sizeof types[n], &where[n]))
                st[n++] = s;
        bool differ = false;
        for (int i = 1; i < n; i++) differ |= strcmp(types[i], types[0]) != 0;
        if (!differ) continue;
        o.len = 0;
        strbuf_printf(&o, "uniform '%s' is declared", name);
        for (int i = 0; i < n; i++)
            strbuf_printf(&o, "%s %s in the %s shader (%s:%d)", i == 0 ? "" : i == n - 1 ? " and" : ",", types[i],
                          shader_stage_name((shader_stage)st[i]), where[i].file, where[i].line);
        strbuf_printf(&o, "; NVIDIA linked this, the GLSL specification does not: one uniform has one type in "
                      "every stage. Declare it the same in both (the type the glib's value has)");
        diag_add(notes, DIAG_NOTE, where[0].file, where[0].line, "%s", o.s);
        any = true;
    }
    strbuf_free(&o);
    return any;
}

int glsl_fix_link_rewrite(const char *log, const shader_src *const srcs[SHADER_STAGE_COUNT], char **text,
                          diag_list *notes) {
    *text = NULL;
    const char *m = log ? strstr(log, " shader output `") : NULL;
    char name[64];
    if (!m || !strstr(m, "but fragment shader input specifies flat") ||
        sscanf(m, " shader output `%63[^']'", name) != 1)
        return -1;
    /* the stage that writes it: the last before the fragment shader */
    int st = -1;
    for (int s = SHADER_FRAGMENT - 1; s >= 0 && st < 0; s--)
        if (srcs[s] && srcs[s]->text) st = s;
    if (st < 0) return -1;
    const shader_src *src = srcs[st];
    fixer f = { .src = src, .stage = (shader_stage)st, .text = src->text, .n = strlen(src->text) };
    f.b = shader_src_blank_comments(src->text);
    build_lines(&f);
    build_depths(&f);
    for (size_t p = find_word(&f, 0, f.n, name); p < f.n && !f.ned; p = find_word(&f, p + 1, f.n, name)) {
        if (f.depth[p] != 0) continue;
        size_t s = stmt_start(&f, p);
        size_t q = find_word(&f, s, p, "out");
        size_t len = 3;
        if (q >= p) { q = find_word(&f, s, p, "varying"); len = 7; }
        if (q >= p) continue;
        size_t sm = find_word(&f, s, p, "smooth");
        if (sm < p) add_edit(&f, sm, 6, "", 3);
        bool old = f.version < 130 && !f.es;   /* no `out` there: GL_EXT_gpu_shader4's flat varying */
        add_edit(&f, q, len, old ? "flat varying" : "flat out", 3);
        if (old) enable_extension(&f, "GL_EXT_gpu_shader4");
        note(&f, p, "'%s' is flat in the fragment shader: its output here is now flat too (%s, before GLSL "
             "4.30: write the same interpolation qualifier in both stages)", name, WHY);
    }
    int ret = -1;
    if (f.ned) {
        qsort(f.ed, (size_t)f.ned, sizeof *f.ed, edit_cmp);
        strbuf o = {0};
        size_t pos = 0;
        for (int i = f.ned - 1; i >= 0; i--) {
            strbuf_put(&o, src->text + pos, f.ed[i].at - pos);
            strbuf_puts(&o, f.ed[i].ins);
            pos = f.ed[i].at + f.ed[i].del;
        }
        strbuf_puts(&o, src->text + pos);
        *text = strbuf_take(&o);
        hand_notes(&f, notes);
        ret = st;
    }
    fixer_free(&f);
    return ret;
}
