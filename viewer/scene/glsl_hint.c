/* glsl_hint: hints for GLSL that NVIDIA accepted and the spec forbids (glsl_hint.h). */
#include "glsl_hint.h"
#include "shader_src.h"

#include "mem.h"
#include "strbuf.h"

#include <ctype.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- how a name is declared in the source ------------------------------------ */

typedef struct decl_info {
    bool found;
    bool global;            /* outside every function */
    char quals[96];         /* its qualifier words ("uniform", "flat in", "const", ...) */
    char type[32];
} decl_info;

static bool is_ident_char(char ch) { return isalnum((unsigned char)ch) || ch == '_'; }

static bool is_qualifier(const char *w) {
    static const char *const q[] = { "const", "in", "out", "inout", "varying", "attribute", "uniform",
                                     "flat", "smooth", "noperspective", "centroid", "sample", "patch",
                                     "highp", "mediump", "lowp", "invariant", "precise" };
    for (size_t i = 0; i < sizeof q / sizeof q[0]; i++)
        if (strcmp(w, q[i]) == 0) return true;
    return false;
}

/* words after which a name is used, not declared */
static bool is_statement_word(const char *w) {
    static const char *const s[] = { "return", "else", "case", "if", "while", "for", "do", "switch" };
    for (size_t i = 0; i < sizeof s / sizeof s[0]; i++)
        if (strcmp(w, s[i]) == 0) return true;
    return false;
}


#define DECL_WORDS 12

/* The first declaration of name: a statement whose words before the name
 * end in a type (`flat in vec3 vN;`, `const float K = ...`). Preprocessor
 * lines are skipped. */
static decl_info find_decl(const char *source, const char *name) {
    decl_info d = {0};
    if (!source) return d;
    char *t = shader_src_blank_comments(source);
    char words[DECL_WORDS][32];
    int nw = 0, depth = 0;
    bool after_word = false;            /* the token before this one is a word (or a ',') */
    for (const char *p = t; *p && !d.found;) {
        if (*p == '#' ) {                /* a directive: to the end of its line */
            while (*p && *p != '\n') p++;
            continue;
        }
        if (!is_ident_char(*p)) {
            if (*p == '{') depth++;
            if (*p == '}' && depth > 0) depth--;
            if (strchr(";{}()", *p)) nw = 0;
            if (!isspace((unsigned char)*p)) after_word = *p == ',' && nw > 0;
            p++;
            continue;
        }
        const char *s = p;
        while (is_ident_char(*p)) p++;
        size_t n = (size_t)(p - s);
        if (isdigit((unsigned char)*s)) { after_word = false; continue; }
        if (n == strlen(name) && memcmp(s, name, n) == 0 && after_word && nw > 0 &&
            !is_statement_word(words[nw - 1]) && !is_qualifier(words[nw - 1])) {
            d.found = true;
            d.global = depth == 0;
            int type = nw - 1;
            while (type > 0 && !is_qualifier(words[type - 1])) type--;   /* `vec3 a, b`: the first word */
            memcpy(d.type, words[type], sizeof d.type);   /* both 32 bytes, NUL-terminated */
            size_t w = 0;
            for (int i = 0; i < nw; i++)
                if (is_qualifier(words[i]) && w < sizeof d.quals)
                    w += (size_t)snprintf(d.quals + w, sizeof d.quals - w, "%s%s", w ? " " : "", words[i]);
            break;
        }
        if (nw < DECL_WORDS && n < sizeof words[0]) {
            memcpy(words[nw], s, n);
            words[nw++][n] = '\0';
        }
        after_word = true;
    }
    free(t);
    return d;
}

static bool has_word(const char *list, const char *w) {
    size_t n = strlen(w);
    for (const char *p = list; (p = strstr(p, w)) != NULL; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == '\0' || p[n] == ' ')) return true;
    return false;
}

/* ---- the hints ------------------------------------------------------------------ */

/* Copies from up to the closing quote `'` into out; false when there is none. */
static bool quoted(const char *from, char *out, size_t outlen) {
    const char *e = strchr(from, '\'');
    if (!e || (size_t)(e - from) >= outlen) return false;
    memcpy(out, from, (size_t)(e - from));
    out[e - from] = '\0';
    return true;
}

static bool is_vector(const char *t) {
    size_t n = strlen(t);
    return n >= 4 && strncmp(t + n - 4, "vec", 3) == 0 && t[n - 1] >= '2' && t[n - 1] <= '4';
}

static bool is_scalar(const char *t) {
    return strcmp(t, "float") == 0 || strcmp(t, "int") == 0 || strcmp(t, "uint") == 0 ||
           strcmp(t, "double") == 0 || strcmp(t, "bool") == 0;
}

/* The call's vector and scalar arguments and a portable rewrite. */
static void call_text(const char *fn, char args[][32], int na, const char *vec, strbuf *o) {
    strbuf_printf(o, "%s(", fn);
    for (int i = 0; i < na; i++) strbuf_printf(o, "%s%s", i ? ", " : "", args[i]);
    strbuf_printf(o, ") mixes a %s with a scalar; GLSL's %s takes arguments of one type (NVIDIA widens "
                  "the scalar, the spec and Mesa do not). Widen it yourself: %s(", vec, fn, fn);
    for (int i = 0; i < na; i++) {
        char letter = (char)('a' + i);
        if (is_scalar(args[i])) strbuf_printf(o, "%s%s(%c)", i ? ", " : "", vec, letter);
        else strbuf_printf(o, "%s%c", i ? ", " : "", letter);
    }
    strbuf_puts(o, ")");
}

/* Mesa: "no matching function for call to `pow(vec2, float)'; candidates are:" */
static bool hint_call(const char *msg, const char *source, strbuf *o) {
    (void)source;
    char call[160];
    const char *q = strchr(msg, '`');
    if (!q || !quoted(q + 1, call, sizeof call)) return false;
    char *open = strchr(call, '('), *close = strrchr(call, ')');
    if (!open || !close || close < open) return false;
    *open = *close = '\0';
    char args[6][32];
    int na = 0;
    const char *vec = NULL;
    bool scalar = false;
    for (char *save = NULL, *a = strtok_r(open + 1, ", ", &save); a && na < 6; a = strtok_r(NULL, ", ", &save)) {
        snprintf(args[na], sizeof args[na], "%s", a);
        if (is_vector(args[na])) {
            if (vec && strcmp(vec, args[na]) != 0) return false;   /* vec2 with vec3: another mistake */
            vec = args[na];
        } else if (is_scalar(args[na])) {
            scalar = true;
        } else {
            return false;
        }
        na++;
    }
    if (!vec || !scalar) return false;
    call_text(call, args, na, vec, o);
    return true;
}

/* glslang names the function but not the types: "'pow' : no matching
 * overloaded function found". Only built-ins that have no (genType, float)
 * form, where NVIDIA's widening is the likely cause. */
static bool hint_call_glslang(const char *msg, const char *source, strbuf *o) {
    (void)source;
    static const char *const fns[] = { "pow", "atan", "dot", "distance", "reflect", "cross", "faceforward" };
    char fn[32];
    if (sscanf(msg, "'%31[^']'", fn) != 1) return false;
    for (size_t i = 0; i < sizeof fns / sizeof fns[0]; i++) {
        if (strcmp(fn, fns[i]) != 0) continue;
        strbuf_printf(o, "if a scalar stands where %s wants a vector: GLSL's %s takes arguments of one type "
                      "(NVIDIA widens the scalar, the spec does not). Widen it yourself: %s(v, vec3(s)), "
                      "not %s(v, s)", fn, fn, fn, fn);
        return true;
    }
    return false;
}

/* Mesa: "`return' with wrong type int, in function `f' returning float" */
static bool hint_return(const char *msg, const char *source, strbuf *o) {
    (void)source;
    char got[32], fn[96], want[32];
    if (sscanf(msg, "`return' with wrong type %31[^,], in function `%95[^']' returning %31s", got, fn, want) != 3)
        return false;
    /* Mesa's type of an expression it could not type (an undeclared name,
     * a bad call): the error before this one is the mistake, not a type */
    if (strcmp(got, "error") == 0) return false;
    strbuf_printf(o, "'%s' is declared to return %s but this line returns a%s %s; GLSL does not convert a "
                  "returned value (NVIDIA does). ", fn, want, strchr("aeiou", got[0]) ? "n" : "", got);
    if (strcmp(want, "float") == 0 && strcmp(got, "int") == 0)
        strbuf_puts(o, "Return a float: `return 1.0;` rather than `return 1;`, or `return float(i);`");
    else
        strbuf_printf(o, "Convert it: `return %s(...);`", want);
    return true;
}

static void const_text(const char *name, const char *source, strbuf *o) {
    decl_info d = name ? find_decl(source, name) : (decl_info){0};
    if (name) strbuf_printf(o, "'%s' is declared const but its", name);
    else strbuf_puts(o, "this const's");
    strbuf_puts(o, " value is only known when the shader runs (it reads a uniform, an input, a texture or a "
                "variable); GLSL wants a const fixed when compiling (NVIDIA relaxes this). Drop the word const");
    if (d.found && d.global)
        strbuf_printf(o, " and give '%s' its value at the start of main() (a global's initialiser must be "
                      "constant too)", name);
}

/* Mesa: "initializer of const variable `K' must be a constant expression" */
static bool hint_const(const char *msg, const char *source, strbuf *o) {
    char name[64];
    if (sscanf(msg, "initializer of const variable `%63[^']'", name) != 1) return false;
    const_text(name, source, o);
    return true;
}

/* glslang: "'=' : global const initializers must be constant ..." and
 * "'non-constant initializer' : not supported for this version ..." (no name) */
static bool hint_const_glslang(const char *msg, const char *source, strbuf *o) {
    (void)msg;
    const_text(NULL, source, o);
    return true;
}

static void readonly_text(const char *name, const char *source, strbuf *o) {
    decl_info d = find_decl(source, name);
    const char *type = d.found ? d.type : "vec3";
    if (d.found && (has_word(d.quals, "in") || has_word(d.quals, "varying") || has_word(d.quals, "attribute")))
        strbuf_printf(o, "'%s' is an input of this shader (declared %s); GLSL makes inputs read-only "
                      "(NVIDIA lets a shader write them). Copy it and change the copy: `%s my%s = %s;` at "
                      "the start of main(), then use my%s", name, d.quals, type, name, name, name);
    else if (d.found && has_word(d.quals, "uniform"))
        strbuf_printf(o, "'%s' is a uniform, which a shader may only read. Copy it and change the copy: "
                      "`%s my%s = %s;`", name, type, name, name);
    else if (d.found && has_word(d.quals, "const"))
        strbuf_printf(o, "'%s' is declared const; drop the word const to change it", name);
    else
        strbuf_printf(o, "GLSL forbids writing '%s' here; copy it into a local variable and change that", name);
}

/* Mesa: "assignment to read-only variable 'vN'" */
static bool hint_readonly(const char *msg, const char *source, strbuf *o) {
    char name[64];
    if (sscanf(msg, "assignment to read-only variable '%63[^']'", name) != 1) return false;
    readonly_text(name, source, o);
    return true;
}

/* glslang: "'assign' :  l-value required "vN" (can't modify shader input)" */
static bool hint_readonly_glslang(const char *msg, const char *source, strbuf *o) {
    char name[64];
    const char *q = strstr(msg, "l-value required \"");
    if (!q || sscanf(q, "l-value required \"%63[^\"]\"", name) != 1) return false;
    readonly_text(name, source, o);
    return true;
}

/* "`gl_ModelViewMatrix' undeclared" (Mesa), "'gl_ModelViewMatrix' :
 * undeclared identifier" (glslang), under a core #version */
static bool hint_core_builtin(const char *msg, const char *source, strbuf *o) {
    char name[64];
    if (!source || sscanf(msg + 1, "%63[A-Za-z0-9_]", name) != 1 || strncmp(name, "gl_", 3) != 0) return false;
    int version = 0;
    char first[128] = "", profile[32] = "";
    snprintf(first, sizeof first, "%.*s", (int)strcspn(source, "\n"), source);   /* the #version line */
    if (sscanf(first, "#version %d %31s", &version, profile) < 1 || version < 140) return false;
    if (strcmp(profile, "compatibility") == 0 || strcmp(profile, "es") == 0) return false;
    strbuf_printf(o, "'%s' is a compatibility-profile built-in, and `#version %d` without a profile means the "
                  "core profile, which lacks it (NVIDIA lets it through). Write `#version %d compatibility`",
                  name, version, version);
    return true;
}

typedef bool (*hint_fn)(const char *msg, const char *source, strbuf *o);

/* A message (after "error: ") that starts with `start` and holds `has`
 * (NULL: anything) -> its hint. Mesa's wording first, then glslang's (for
 * `tarn validate`). */
static const struct { const char *start, *has; hint_fn fn; } hints[] = {
    { "no matching function for call to `", NULL, hint_call },
    { "`return' with wrong type ", NULL, hint_return },
    { "initializer of const variable `", NULL, hint_const },
    { "assignment to read-only variable '", NULL, hint_readonly },
    { "`gl_", "' undeclared", hint_core_builtin },
    { "'", "no matching overloaded function found", hint_call_glslang },
    { "'=' : ", "global const initializers must be constant", hint_const_glslang },
    { "'non-constant initializer' : ", NULL, hint_const_glslang },
    { "'", "l-value required \"", hint_readonly_glslang },
    { "'gl_", "undeclared identifier", hint_core_builtin },
};

/* ---- the messages -------------------------------------------------------------- */

/* The hint for an error's text, into o; false when it names nothing NVIDIA let through. */
static bool hint_for(const char *msg, const char *source, strbuf *o) {
    for (size_t i = 0; i < sizeof hints / sizeof hints[0]; i++) {
        if (strncmp(msg, hints[i].start, strlen(hints[i].start)) != 0) continue;
        if (hints[i].has && !strstr(msg, hints[i].has)) continue;
        o->len = 0;
        if (o->s) o->s[0] = '\0';
        if (hints[i].fn(msg, source, o) && o->len > 0) return true;
    }
    return false;
}

void glsl_hint_add(diag_list *l, int from, const char *source) {
    diag_list out = { 0 };
    diag note = { .severity = DIAG_NOTE };
    bool pending = false;
    strbuf h = { 0 };
    for (int i = 0; i < l->n; i++) {
        const diag *d = &l->d[i];
        bool error = i >= from && d->severity == DIAG_ERROR && !d->bare;
        /* Mesa lists candidates under a call as more errors, indented */
        if (pending && !(error && d->text[0] == ' ')) {
            diag_push(&out, &note);
            pending = false;
        }
        diag_push(&out, d);
        if (!error || d->text[0] == ' ' || !hint_for(d->text, source, &h)) continue;
        snprintf(note.file, sizeof note.file, "%s", d->file);
        note.line = d->line;
        snprintf(note.text, sizeof note.text, "%s", h.s);
        pending = true;
    }
    if (pending) diag_push(&out, &note);
    strbuf_free(&h);
    diag_list_free(l);
    *l = out;
}
