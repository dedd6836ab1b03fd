#include "glsl_deferred.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"
#include "shader_src.h"
#include "strbuf.h"

#define MAX_INPUTS 32
#define MAX_EDITS 256

typedef struct input {
    size_t a, b;        /* the declaration, from its first token to its ';' (inclusive) */
    int type;           /* index into types[] */
    char names[8][64];  /* its declarators */
    int arrays[8];      /* 0: not an array */
    int nnames;
} input;

typedef struct edit {
    size_t a, b;        /* the bytes replaced */
    char *with;         /* heap */
} edit;

typedef struct split {
    const char *s;
    size_t n;
    int version;
    size_t version_at, version_end;  /* the #version line (its newline excluded) */
    size_t first_stmt;   /* the first global statement (SIZE_MAX: none) */
    input in[MAX_INPUTS];
    int nin;
    int nmain;           /* main() definitions (every one renamed) */
    bool fragcoord, front;
    edit ed[MAX_EDITS];
    int ned;
    char *why;
} split;

static const struct { const char *name; int comp; char kind; } types[] = {
    { "float", 1, 'f' }, { "vec2", 2, 'f' }, { "vec3", 3, 'f' }, { "vec4", 4, 'f' },
    { "int", 1, 'i' },   { "ivec2", 2, 'i' }, { "ivec3", 3, 'i' }, { "ivec4", 4, 'i' },
    { "uint", 1, 'u' },  { "uvec2", 2, 'u' }, { "uvec3", 3, 'u' }, { "uvec4", 4, 'u' },
};

/* Built-ins a full-screen pass cannot give as the grid's draw did. */
static const char *const unsupported[] = {
    "gl_Color", "gl_SecondaryColor", "gl_TexCoord", "gl_FogFragCoord", "gl_FragDepth",
    "gl_PrimitiveID", "gl_SampleID", "gl_SamplePosition", "gl_SampleMaskIn", "gl_PointCoord",
    "gl_ClipDistance", "gl_CullDistance", "gl_Layer", "gl_ViewportIndex",
    "interpolateAtCentroid", "interpolateAtSample", "interpolateAtOffset",
};

static bool word_char(char c) { return isalnum((unsigned char)c) || c == '_'; }

static void fail(split *sp, char *why, const char *fmt, const char *arg) {
    if (!why[0]) snprintf(why, 160, fmt, arg);
    sp->why = why;
}

/* ---- tokens of one statement ---------------------------------------- */

typedef struct tok { size_t a, b; } tok;

static bool tok_is(const split *sp, const tok *t, const char *w) {
    size_t n = strlen(w);
    return t->b - t->a == n && memcmp(sp->s + t->a, w, n) == 0;
}

/* The end of the preprocessor line starting at i (its newline), joined
 * lines included. */
static size_t directive_end(const char *s, size_t n, size_t i) {
    while (i < n && s[i] != '\n') {
        if (s[i] == '\\' && i + 1 < n && s[i + 1] == '\n') i++;
        i++;
    }
    return i;
}

static int tokenize(const split *sp, size_t a, size_t b, tok *out, int max) {
    int nt = 0;
    for (size_t i = a; i < b && nt < max;) {
        char c = sp->s[i];
        if (isspace((unsigned char)c)) { i++; continue; }
        if (c == '#') { i = directive_end(sp->s, b, i); continue; }
        size_t e = i + 1;
        if (word_char(c)) while (e < b && word_char(sp->s[e])) e++;
        out[nt++] = (tok){ i, e };
        i = e;
    }
    return nt;
}

/* ---- one global statement ------------------------------------------- */

static bool is_qualifier(const split *sp, const tok *t) {
    static const char *const q[] = { "flat", "smooth", "noperspective", "centroid", "invariant", "precise",
                                     "highp", "mediump", "lowp" };
    for (size_t k = 0; k < sizeof q / sizeof q[0]; k++)
        if (tok_is(sp, t, q[k])) return true;
    return false;
}

static int type_of(const split *sp, const tok *t) {
    for (int k = 0; k < (int)(sizeof types / sizeof types[0]); k++)
        if (tok_is(sp, t, types[k].name)) return k;
    return -1;
}

/* The declarators of an input: NAME [N], NAME ... up to the end. */
static bool read_names(split *sp, const tok *t, int k, int nt, input *in, char *why) {
    while (k < nt) {
        if (!word_char(sp->s[t[k].a]) || in->nnames == 8 || t[k].b - t[k].a >= 64) break;
        memcpy(in->names[in->nnames], sp->s + t[k].a, t[k].b - t[k].a);
        in->names[in->nnames][t[k].b - t[k].a] = 0;
        int arr = 0;
        k++;
        if (k < nt && tok_is(sp, &t[k], "[")) {
            if (k + 2 >= nt || !isdigit((unsigned char)sp->s[t[k + 1].a]) || !tok_is(sp, &t[k + 2], "]")) {
                fail(sp, why, "an input array '%s' whose size is not a number", in->names[in->nnames]);
                return false;
            }
            arr = atoi(sp->s + t[k + 1].a);
            k += 3;
        }
        in->arrays[in->nnames++] = arr;
        if (k == nt) return true;
        if (!tok_is(sp, &t[k], ",")) break;
        k++;
    }
    fail(sp, why, "an input declaration tarn does not read (%s)", "its declarators");
    return false;
}

/* The statement [a, end) ended by term (';' or '{') at global scope;
 * if_depth: how many #if blocks it is in. */
static void statement(split *sp, size_t a, size_t end, char term, int if_depth, char *why) {
    tok t[64];
    int nt = tokenize(sp, a, end, t, 64);
    if (nt == 0) return;
    if (sp->first_stmt == (size_t)-1) sp->first_stmt = a;
    bool is_in = false;
    int k = 0;
    for (; k < nt; k++) {
        if (tok_is(sp, &t[k], "layout")) {   /* layout( ... ) */
            int depth = 0;
            for (k++; k < nt; k++) {
                if (tok_is(sp, &t[k], "(")) depth++;
                else if (tok_is(sp, &t[k], ")") && --depth == 0) break;
            }
            continue;
        }
        if (tok_is(sp, &t[k], "in") || tok_is(sp, &t[k], "varying")) { is_in = true; continue; }
        if (tok_is(sp, &t[k], "sample") || tok_is(sp, &t[k], "patch")) {
            fail(sp, why, "a '%s' input (one value a sample or patch)", "sample");
            return;
        }
        if (!is_qualifier(sp, &t[k])) break;
    }
    if (!is_in) return;
    if (term == '{') { fail(sp, why, "an input block (%s { ... })", "in"); return; }
    if (if_depth > 0) { fail(sp, why, "an input declared inside %s", "#if"); return; }
    if (sp->nin == MAX_INPUTS) { fail(sp, why, "more than %s inputs", "32"); return; }
    input *in = &sp->in[sp->nin];
    memset(in, 0, sizeof *in);
    in->a = a;
    in->b = end + 1;
    in->type = k < nt ? type_of(sp, &t[k]) : -1;
    if (in->type < 0) {
        char ty[64] = "?";
        if (k < nt) snprintf(ty, sizeof ty, "%.*s", (int)(t[k].b - t[k].a), sp->s + t[k].a);
        fail(sp, why, "an input of type %s (float, int, uint and their vectors only)", ty);
        return;
    }
    if (read_names(sp, t, k + 1, nt, in, why)) sp->nin++;
}

/* ---- the walk over the text ----------------------------------------- */

static void directive(split *sp, size_t i, size_t e, int *if_depth) {
    size_t j = i + 1;
    while (j < e && (sp->s[j] == ' ' || sp->s[j] == '\t')) j++;
    size_t w = j;
    while (w < e && word_char(sp->s[w])) w++;
    size_t len = w - j;
    const char *d = sp->s + j;
    if ((len == 2 && !memcmp(d, "if", 2)) || (len == 5 && !memcmp(d, "ifdef", 5)) || (len == 6 && !memcmp(d, "ifndef", 6)))
        (*if_depth)++;
    else if (len == 5 && !memcmp(d, "endif", 5) && *if_depth > 0)
        (*if_depth)--;
    else if (len == 7 && !memcmp(d, "version", 7) && !sp->version) {
        sp->version = atoi(sp->s + w);
        sp->version_at = i;
        sp->version_end = e;
    }
}

static void walk(split *sp, char *why) {
    const char *s = sp->s;
    size_t n = sp->n, start = (size_t)-1;
    int depth = 0, if_depth = 0, start_if = 0;
    bool line_start = true;
    for (size_t i = 0; i < n && !sp->why;) {
        char c = s[i];
        if (c == '\n') { line_start = true; i++; continue; }
        if (c == ' ' || c == '\t' || c == '\r') { i++; continue; }
        if (c == '#' && line_start) {
            size_t e = directive_end(s, n, i);
            directive(sp, i, e, &if_depth);
            i = e;
            continue;
        }
        line_start = false;
        if (depth == 0 && start == (size_t)-1 && c != ';' && c != '}') { start = i; start_if = if_depth; }
        if (c == '{') {
            if (depth == 0 && start != (size_t)-1) { statement(sp, start, i, '{', start_if, why); start = (size_t)-1; }
            depth++;
        } else if (c == '}') {
            if (depth > 0) depth--;
        } else if (c == ';' && depth == 0) {
            if (start != (size_t)-1) statement(sp, start, i, ';', start_if, why);
            start = (size_t)-1;
        }
        i++;
    }
}

/* Every identifier named w (in #define bodies too; the text's comments are
 * blanks): their positions in at (up to max). Returns how many. */
static int each_word(const split *sp, const char *w, size_t *at, int max) {
    size_t len = strlen(w);
    int count = 0;
    for (size_t i = 0; i < sp->n;) {
        if (!word_char(sp->s[i])) { i++; continue; }
        size_t e = i;
        while (e < sp->n && word_char(sp->s[e])) e++;
        if (e - i == len && memcmp(sp->s + i, w, len) == 0) {
            if (at && count < max) at[count] = i;
            count++;
        }
        i = e;
    }
    return count;
}

/* Does the text read gl_FragCoord's z or w (the whole vector, or a
 * swizzle with z or w)? Its x and y are the full-screen pass's own. */
static bool fragcoord_depth_read(const split *sp) {
    size_t at[512];
    int n = each_word(sp, "gl_FragCoord", at, 512);
    if (n > 512) return true;
    for (int i = 0; i < n; i++) {
        size_t j = at[i] + 12;
        while (j < sp->n && isspace((unsigned char)sp->s[j])) j++;
        if (j >= sp->n || sp->s[j] != '.') return true;
        j++;
        while (j < sp->n && isspace((unsigned char)sp->s[j])) j++;
        size_t k = j;
        while (k < sp->n && word_char(sp->s[k])) k++;
        if (k == j) return true;
        for (size_t c = j; c < k; c++)
            if (!strchr("xyrgst", sp->s[c])) return true;
    }
    return false;
}

/* ---- the two texts -------------------------------------------------- */

static void add_edit(split *sp, size_t a, size_t b, char *with) {
    if (sp->ned == MAX_EDITS) { free(with); sp->why = "too many edits"; return; }
    sp->ed[sp->ned++] = (edit){ a, b, with };
}

static int cmp_edit(const void *x, const void *y) {
    const edit *a = x, *b = y;
    if (a->a != b->a) return a->a < b->a ? -1 : 1;
    return a->b < b->b ? -1 : a->b > b->b;   /* an insertion before a replacement at the same place */
}

/* The component of slot c: "tarn_dfr_v<c/4>.<xyzw>" (or _o for outputs). */
static void slot_name(char *out, size_t n, const char *pre, int c) {
    snprintf(out, n, "tarn_dfr_%s%d.%c", pre, c / 4, "xyzw"[c % 4]);
}

/* An input component as an lvalue or value: name, name[i], with .x... */
static void comp_name(char *out, size_t n, const input *in, int k, int i, int c) {
    int comp = types[in->type].comp;
    char idx[16] = "";
    if (in->arrays[k]) snprintf(idx, sizeof idx, "[%d]", i);
    if (comp == 1) snprintf(out, n, "%s%s", in->names[k], idx);
    else snprintf(out, n, "%s%s.%c", in->names[k], idx, "xyzw"[c]);
}

/* One stored component: input in, its declarator k, element e, component c. */
typedef struct component { const input *in; int k, e, c; } component;

/* The inputs' components in slot order; how many (at most max). */
static int components(const split *sp, component *out, int max) {
    int n = 0;
    for (int i = 0; i < sp->nin; i++) {
        const input *in = &sp->in[i];
        for (int k = 0; k < in->nnames; k++) {
            int elems = in->arrays[k] ? in->arrays[k] : 1;
            for (int e = 0; e < elems; e++)
                for (int c = 0; c < types[in->type].comp; c++, n++)
                    if (n < max) out[n] = (component){ in, k, e, c };
        }
    }
    return n;
}

static int count_components(const split *sp) {
    return components(sp, NULL, 0) + (sp->fragcoord ? 2 : 0) + (sp->front ? 1 : 0);
}

/* The stored components' copies, "dst = conv(src);" a line each: into the
 * outputs (to_gbuffer) or from the read texels. Returns the next slot. */
static int copy_lines(const split *sp, char **t, bool to_gbuffer) {
    component cs[GLSL_DEFERRED_MAX_COMPONENTS];
    int n = components(sp, cs, GLSL_DEFERRED_MAX_COMPONENTS);
    for (int i = 0; i < n; i++) {
        char slot[48], var[160];
        slot_name(slot, sizeof slot, to_gbuffer ? "o" : "v", i);
        comp_name(var, sizeof var, cs[i].in, cs[i].k, cs[i].e, cs[i].c);
        char kind = types[cs[i].in->type].kind;
        const char *conv = to_gbuffer ? (kind == 'i' ? "intBitsToFloat" : kind == 'u' ? "uintBitsToFloat" : "float")
                                       : (kind == 'i' ? "floatBitsToInt" : kind == 'u' ? "floatBitsToUint" : "float");
        str_appendf(t, "    %s = %s(%s);\n", to_gbuffer ? slot : var, conv, to_gbuffer ? var : slot);
    }
    return n;
}

static char *gbuffer_text(const split *sp, int ntex, bool stamped) {
    char *t = NULL;
    str_appendf(&t, "%.*s\n", (int)(sp->version_end - sp->version_at), sp->s + sp->version_at);
    for (int i = 0; i < sp->nin; i++)
        str_appendf(&t, "%.*s\n", (int)(sp->in[i].b - sp->in[i].a), sp->s + sp->in[i].a);
    for (int k = 0; k < ntex; k++) str_appendf(&t, "layout(location = %d) out vec4 tarn_dfr_o%d;\n", k, k);
    if (stamped) str_appendf(&t, "uniform float tarn_dfr_stamp;\n");
    str_appendf(&t, "void main() {\n");
    for (int k = 0; k < ntex; k++) str_appendf(&t, "    tarn_dfr_o%d = vec4(0.0);\n", k);
    if (stamped) str_appendf(&t, "    tarn_dfr_o%d.w = tarn_dfr_stamp;\n", ntex - 1);
    int last = copy_lines(sp, &t, true);
    char dst[48];
    if (sp->fragcoord) {
        slot_name(dst, sizeof dst, "o", last++);
        str_appendf(&t, "    %s = gl_FragCoord.z;\n", dst);
        slot_name(dst, sizeof dst, "o", last++);
        str_appendf(&t, "    %s = gl_FragCoord.w;\n", dst);
    }
    if (sp->front) {
        slot_name(dst, sizeof dst, "o", last++);
        str_appendf(&t, "    %s = gl_FrontFacing ? 1.0 : 0.0;\n", dst);
    }
    str_appendf(&t, "}\n");
    return t;
}

/* The globals the inputs become, on the declaration's own lines. */
static char *global_decl(const split *sp, const input *in) {
    char *t = NULL;
    str_appendf(&t, "%s ", types[in->type].name);
    for (int k = 0; k < in->nnames; k++) {
        str_appendf(&t, "%s%s", k ? ", " : "", in->names[k]);
        if (in->arrays[k]) str_appendf(&t, "[%d]", in->arrays[k]);
    }
    str_appendf(&t, ";");
    for (size_t i = in->a; i < in->b; i++)
        if (sp->s[i] == '\n') str_appendf(&t, "\n");
    return t;
}

static char *shade_epilogue(const split *sp, int ntex, bool stamped) {
    char *t = NULL;
    str_appendf(&t, "\n");
    for (int k = 0; k < ntex; k++) str_appendf(&t, "uniform sampler2D tarn_dfr_g%d;\n", k);
    if (stamped) str_appendf(&t, "uniform float tarn_dfr_stamp;\n");
    str_appendf(&t, "void main() {\n    ivec2 tarn_dfr_p = ivec2(gl_FragCoord.xy);\n");
    for (int k = 0; k < ntex; k++)
        str_appendf(&t, "    vec4 tarn_dfr_v%d = texelFetch(tarn_dfr_g%d, tarn_dfr_p, 0);\n", k, k);
    if (stamped) {   /* a texel of an earlier draw reads as a cleared one */
        str_appendf(&t, "    if (tarn_dfr_v%d.w != tarn_dfr_stamp) {", ntex - 1);
        for (int k = 0; k < ntex; k++) str_appendf(&t, " tarn_dfr_v%d = vec4(0.0);", k);
        str_appendf(&t, " }\n");
    }
    int last = copy_lines(sp, &t, false);
    char z[48], w[48], f[48];
    if (sp->fragcoord) {
        slot_name(z, sizeof z, "v", last++);
        slot_name(w, sizeof w, "v", last++);
        str_appendf(&t, "    tarn_dfr_fragcoord = vec4(gl_FragCoord.xy, %s, %s);\n", z, w);
    }
    if (sp->front) {
        slot_name(f, sizeof f, "v", last++);
        str_appendf(&t, "    tarn_dfr_front = %s != 0.0;\n", f);
    }
    str_appendf(&t, "    tarn_dfr_main();\n}\n");
    return t;
}

static char *apply_edits(split *sp) {
    qsort(sp->ed, (size_t)sp->ned, sizeof sp->ed[0], cmp_edit);
    strbuf b = { 0 };
    size_t at = 0;
    for (int i = 0; i < sp->ned; i++) {
        if (sp->ed[i].a < at) continue;   /* inside an edit already made (cannot happen: disjoint) */
        strbuf_put(&b, sp->s + at, sp->ed[i].a - at);
        strbuf_puts(&b, sp->ed[i].with);
        at = sp->ed[i].b;
    }
    strbuf_puts(&b, sp->s + at);
    return strbuf_take(&b);
}

static void free_edits(split *sp) {
    for (int i = 0; i < sp->ned; i++) free(sp->ed[i].with);
    sp->ned = 0;
}

/* Every main() definition (one in each branch of an #if that holds
 * several, as shader_src's kill finds them): renamed tarn_dfr_main. */
static void rename_mains(split *sp) {
    for (const char *from = sp->s; shader_src_next_main_body(sp->s, &from) != NULL; sp->nmain++) {
        size_t at = (size_t)(from - sp->s) - 4;   /* from: just past the word main */
        add_edit(sp, at, at + 4, mem_strdup("tarn_dfr_main"));
    }
}

/* The shade text's edits: declarations, the two built-ins (main's names:
 * rename_mains). */
static void shade_edits(split *sp) {
    for (int i = 0; i < sp->nin; i++) add_edit(sp, sp->in[i].a, sp->in[i].b, global_decl(sp, &sp->in[i]));
    size_t at[512];
    int n = each_word(sp, "gl_FragCoord", at, 512);
    for (int i = 0; sp->fragcoord && i < n && i < 512; i++)
        add_edit(sp, at[i], at[i] + 12, mem_strdup("tarn_dfr_fragcoord"));
    n = each_word(sp, "gl_FrontFacing", at, 512);
    for (int i = 0; i < n && i < 512; i++) add_edit(sp, at[i], at[i] + 14, mem_strdup("tarn_dfr_front"));
    /* their globals, before the first statement (on its line) */
    char *g = NULL;
    str_appendf(&g, "%s%s", sp->fragcoord ? "vec4 tarn_dfr_fragcoord; " : "", sp->front ? "bool tarn_dfr_front; " : "");
    if (g && g[0]) add_edit(sp, sp->first_stmt, sp->first_stmt, g);
    else free(g);
}

/* The text the split reads and the shade pass is made of: frag with its
 * comments blank (shader_src_blank_comments: lines and columns kept) and
 * shader_src's never-taken kill blank too: it gives llvmpipe's opaque
 * passes one function, but in the shade pass (not opaque: it tests
 * stencil) it would move the stencil test after the shader, and every
 * pixel of the screen was shaded. Heap. */
static char *split_text(const char *frag) {
    char *t = mem_strdup(frag ? frag : "");
    for (char *at = t; (at = strstr(at, SHADER_SRC_UNREACHED_KILL)) != NULL;)
        memset(at, ' ', strlen(SHADER_SRC_UNREACHED_KILL));
    char *blank = shader_src_blank_comments(t);
    free(t);
    return blank;
}

bool glsl_deferred_split(const char *frag, glsl_deferred *out) {
    memset(out, 0, sizeof *out);
    split *sp = calloc(1, sizeof *sp);
    if (!sp) { snprintf(out->why, sizeof out->why, "out of memory"); return false; }
    char *text = split_text(frag);
    sp->s = text;
    sp->n = strlen(sp->s);
    sp->first_stmt = (size_t)-1;
    walk(sp, out->why);
    rename_mains(sp);
    if (!sp->why && sp->version < 330) fail(sp, out->why, "GLSL %s (330 or later is needed)", sp->version ? "before 330" : "without #version");
    if (!sp->why && sp->nmain == 0) fail(sp, out->why, "no %s", "void main()");
    for (size_t k = 0; !sp->why && k < sizeof unsupported / sizeof unsupported[0]; k++)
        if (each_word(sp, unsupported[k], NULL, 0)) fail(sp, out->why, "the built-in %s", unsupported[k]);
    sp->fragcoord = fragcoord_depth_read(sp);
    sp->front = each_word(sp, "gl_FrontFacing", NULL, 0) > 0;
    int ncomp = sp->why ? 0 : count_components(sp);
    if (!sp->why && ncomp == 0) fail(sp, out->why, "no %s to store", "input");
    if (!sp->why && ncomp > GLSL_DEFERRED_MAX_COMPONENTS)
        fail(sp, out->why, "more input components than the G-buffer holds (%s)", "28");
    if (!sp->why) {
        int ntex = (ncomp + 3) / 4;
        bool stamped = ncomp % 4 != 0;   /* a spare slot: the draw's stamp instead of a clear */
        shade_edits(sp);
        if (!sp->why) {
            char *body = apply_edits(sp);
            char *epi = shade_epilogue(sp, ntex, stamped);
            str_appendf(&body, "%s", epi);
            free(epi);
            out->shade = body;
            out->gbuffer = gbuffer_text(sp, ntex, stamped);
            out->stamped = stamped;
            out->ntex = ntex;
            out->ncomp = ncomp;
            snprintf(out->version, sizeof out->version, "%.*s", (int)(sp->version_end - sp->version_at),
                     sp->s + sp->version_at);
        } else {
            snprintf(out->why, sizeof out->why, "%s", sp->why);
        }
    }
    free_edits(sp);
    bool ok = out->shade != NULL;
    free(sp);
    free(text);
    return ok;
}

void glsl_deferred_free(glsl_deferred *d) {
    free(d->gbuffer);
    free(d->shade);
    d->gbuffer = d->shade = NULL;
}
