/* validate: glslang validation of shader stages and .glib Programs (see validate.h). */
#include "validate.h"

#include "diag.h"
#include "file.h"
#include "glib.h"
#include "glsl_fix.h"
#include "glsl_hint.h"
#include "mem.h"
#include "program.h"
#include "strbuf.h"

#include <glslang/Include/glslang_c_interface.h>
#include <glslang/Public/resource_limits_c.h>

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#define MAX_TOGGLES_VARIED 9        /* 2^9 combinations at most: caustic_tex's 11 toggles at 2^10 took tarn validate past 45 s */
#define MAX_DEFINES 64

/* The module's one context: glslang's process state. */
typedef struct validate_ctx {
    bool glslang_ready;
} validate_ctx;

static validate_ctx g_validate;

static void ensure_glslang(void) {
    if (!g_validate.glslang_ready) {
        glslang_initialize_process();
        g_validate.glslang_ready = true;
    }
}

/* ---- small helpers ---------------------------------------------------------- */

static char *xprintf(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static char *xprintf(const char *fmt, ...) {
    strbuf b = { 0 };
    va_list ap;
    va_start(ap, fmt);
    strbuf_vprintf(&b, fmt, ap);
    va_end(ap);
    return strbuf_take(&b);
}

static bool is_regular_file(const char *path) {
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

static bool is_dir(const char *path) {
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

static const char *path_ext(const char *path) {
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    const char *dot = strrchr(base, '.');
    return dot && dot != base ? dot + 1 : "";
}

typedef struct strlist {
    char **v;
    int n, cap;
} strlist;

static void strlist_add(strlist *l, char *owned) {
    l->v = mem_grow(l->v, &l->cap, l->n + 1, sizeof *l->v);
    l->v[l->n++] = owned;
}

static void strlist_free(strlist *l) {
    for (int i = 0; i < l->n; i++) free(l->v[i]);
    free(l->v);
    memset(l, 0, sizeof *l);
}

static int cmp_str(const void *a, const void *b) {
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* ---- messages ---------------------------------------------------------------- */

/* A diagnostic, and the combinations of a Program it appeared in. */
typedef struct vmsg {
    diag d;
    int count;              /* combinations it appeared in */
    int first_combo;
} vmsg;

typedef struct vmsgs {
    vmsg *v;
    int n, cap;
} vmsgs;

static bool same_diag(const diag *a, const diag *b) {
    return a->severity == b->severity && a->line == b->line && strcmp(a->file, b->file) == 0 &&
           strcmp(a->text, b->text) == 0;
}

/* Adds d unless it is there (a message can come twice from one compile);
 * returns its index. */
static int msgs_add(vmsgs *m, const diag *d) {
    diag x = *d;
    /* glslang likes double spaces ("'=' :  cannot convert") */
    size_t w = 0;
    for (const char *p = d->text; *p; p++)
        if (!(*p == ' ' && w > 0 && x.text[w - 1] == ' ')) x.text[w++] = *p;
    x.text[w] = '\0';
    for (int i = 0; i < m->n; i++)
        if (same_diag(&m->v[i].d, &x)) return i;
    m->v = mem_grow(m->v, &m->cap, m->n + 1, sizeof *m->v);
    m->v[m->n] = (vmsg){ x, 0, 0 };
    return m->n++;
}

static void msgs_addf(vmsgs *m, diag_severity s, const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
static void msgs_addf(vmsgs *m, diag_severity s, const char *file, int line, const char *fmt, ...) {
    diag d = { .severity = s, .line = line };
    snprintf(d.file, sizeof d.file, "%s", file ? file : "");
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(d.text, sizeof d.text, fmt, ap);
    va_end(ap);
    msgs_add(m, &d);
}

static void msgs_add_list(vmsgs *m, const diag_list *l) {
    for (int i = 0; i < l->n; i++) msgs_add(m, &l->d[i]);
}

static void msgs_free(vmsgs *m) {
    free(m->v);
    memset(m, 0, sizeof *m);
}

/* Adds one combination's messages to a Program's table. */
static void msgs_merge(vmsgs *table, const vmsgs *m, int combo) {
    for (int i = 0; i < m->n; i++) {
        int n = table->n, j = msgs_add(table, &m->v[i].d);
        if (j == n) table->v[j].first_combo = combo;
        table->v[j].count++;
    }
}

static bool starts_with(const char *s, const char *prefix) {
    return strncmp(s, prefix, strlen(prefix)) == 0;
}

/* glslang's lines that say nothing of their own. */
static bool is_noise(const char *line) {
    return strstr(line, "No code generated") || strstr(line, "' : compilation terminated") ||
           (starts_with(line, "ERROR: ") && isdigit((unsigned char)line[7]) &&
            strstr(line, " compilation errors"));
}

/* A line of a compiler's log that no place of the stage's was found in
 * (the tool's own words) and that starts a message, as a diag (pending);
 * false for a continuation line. */
static bool message_start(const shader_src *src, const char *p, diag *pending) {
    diag_list l = { 0 };
    if (starts_with(p, "ERROR: ")) {   /* no location: the stage file's */
        diag_add(&l, DIAG_ERROR, src->files[0], 0, "%s", p + 7);
    } else if (starts_with(p, "WARNING: ")) {
        diag_add(&l, DIAG_WARNING, src->files[0], 0, "%s", p + 9);
    } else if (strstr(p, ": error") || strstr(p, ": warning")) {
        const char *er = strstr(p, ": error"), *wa = strstr(p, ": warning");
        diag_add_log(&l, er && (!wa || er < wa) ? DIAG_ERROR : DIAG_WARNING, p);
    }
    bool start = l.n > 0;
    if (start) *pending = l.d[0];
    diag_list_free(&l);
    return start;
}

/* Splits a compiler log into messages, mapped to the user's files
 * (shader_src_map_diags: a diag a line). An error or warning at a place
 * starts a message; lines of the tool's own (a note, a candidate list)
 * continue the message before them unless they start one themselves.
 * tarn's notes on what NVIDIA let through (glsl_hint) follow their error.
 * *mapped_out (if wanted) gets the log's lines as diags, for glsl_fix. */
static void add_compile_log(const shader_src *src, const char *log, bool compiled, vmsgs *m, diag_list *mapped_out) {
    if (!log || !log[0]) return;
    diag_list lines = { 0 }, found = { 0 };
    shader_src_map_diags(src, log, DIAG_NOTE, &lines);
    for (int i = 0; mapped_out && i < lines.n; i++) diag_push(mapped_out, &lines.d[i]);
    diag pending;
    bool has_pending = false;
    for (int i = 0; i < lines.n; i++) {
        diag *d = &lines.d[i];
        size_t n = strlen(d->text);
        while (n > 0 && isspace((unsigned char)d->text[n - 1])) d->text[--n] = '\0';
        if (n == 0 || is_noise(d->text)) continue;
        diag next;
        bool starts = !d->bare && d->severity != DIAG_NOTE ? (next = *d, true)
                    : d->bare && message_start(src, d->text, &next);
        if (starts) {
            if (has_pending) diag_push(&found, &pending);
            pending = next;
            has_pending = true;
            continue;
        }
        char t[DIAG_FILE_MAX + DIAG_TEXT_MAX + 32];
        if (d->bare) snprintf(t, sizeof t, "%s", d->text);
        else diag_format(d, t, sizeof t);   /* a note at a place, as the log said it */
        const char *c = t;
        while (isspace((unsigned char)*c)) c++;
        if (!has_pending) {
            memset(&pending, 0, sizeof pending);
            pending.severity = compiled ? DIAG_WARNING : DIAG_ERROR;
            snprintf(pending.file, sizeof pending.file, "%s", src->files[0]);
            has_pending = true;
            msg_set(pending.text, sizeof pending.text, "%s", c);
        } else {
            size_t len = strlen(pending.text);
            snprintf(pending.text + len, sizeof pending.text - len, " %s", c);
        }
    }
    if (has_pending) diag_push(&found, &pending);
    diag_list_free(&lines);
    glsl_hint_add(&found, 0, src->text);
    msgs_add_list(m, &found);
    diag_list_free(&found);
}

/* ---- glslang -------------------------------------------------------------------- */

static const glslang_stage_t glslang_stages[SHADER_STAGE_COUNT] = {
    GLSLANG_STAGE_VERTEX, GLSLANG_STAGE_TESSCONTROL, GLSLANG_STAGE_TESSEVALUATION,
    GLSLANG_STAGE_GEOMETRY, GLSLANG_STAGE_FRAGMENT,
};

static glslang_input_t make_input(const char *code, shader_stage st) {
    glslang_input_t in;
    memset(&in, 0, sizeof in);
    in.language = GLSLANG_SOURCE_GLSL;
    in.stage = glslang_stages[st];
    /* NONE: desktop GLSL as a driver sees it (no SPIR-V rules) */
    in.client = GLSLANG_CLIENT_NONE;
    in.target_language = GLSLANG_TARGET_NONE;
    in.code = code;
    /* every assembled text starts with a #version; these only apply without one */
    in.default_version = 110;
    in.default_profile = GLSLANG_NO_PROFILE;
    in.force_default_version_and_profile = 0;
    in.forward_compatible = 0;
    in.messages = GLSLANG_MSG_DEFAULT_BIT;
    in.resource = glslang_default_resource();
    return in;
}

/* glslang (12) gives a compatibility geometry shader its colour and
 * texture-coordinate outputs (gl_FrontColor, gl_TexCoord, ...) only from
 * GLSL 4.00 on, where GLSL 1.50 compatibility has them and Mesa agrees; a
 * glman geometry shader (#version 150 compatibility after shader_src's
 * rewrite, or glman's 330 default) that writes them would fail here and
 * work in the renderer. Such a text is checked as 4.00 compatibility: a
 * heap copy with the #version line replaced and, when the text counted
 * lines by the pre-3.30 `#line` rule, each `#line N` raised by one so
 * messages keep their lines. NULL when the text needs none of this. */
static char *gs_compat_text(const char *text) {
    static const char *const outs[] = { "gl_FrontColor", "gl_BackColor", "gl_FrontSecondaryColor",
                                        "gl_BackSecondaryColor", "gl_TexCoord", "gl_FogFragCoord" };
    int version = 0;
    char profile[32] = "";
    const char *nl = strchr(text, '\n');
    if (!nl || sscanf(text, "#version %d %31s", &version, profile) != 2 || version >= 400 ||
        strcmp(profile, "compatibility") != 0)
        return NULL;
    bool writes = false;
    for (size_t i = 0; i < sizeof outs / sizeof outs[0] && !writes; i++) {
        size_t n = strlen(outs[i]);
        for (const char *p = text; (p = strstr(p, outs[i])) != NULL && !writes; p += n)
            writes = p[-1] != '.' && !isalnum((unsigned char)p[n]) && p[n] != '_';   /* gl_in[i].gl_X is an input */
    }
    if (!writes) return NULL;
    bool old_rule = version < 330;
    strbuf out = {0};
    strbuf_puts(&out, "#version 400 compatibility\n");
    for (const char *p = nl + 1; *p;) {
        const char *e = strchr(p, '\n');
        size_t n = e ? (size_t)(e - p) + 1 : strlen(p);
        long line, file;
        if (old_rule && sscanf(p, "#line %ld %ld", &line, &file) == 2)
            strbuf_printf(&out, "#line %ld %ld\n", line + 1, file);
        else
            strbuf_put(&out, p, n);
        p += n;
    }
    return strbuf_take(&out);
}

/* Compiles src; its messages go to m. Returns the shader (the caller
 * deletes it) and sets *ok; *preprocessed (if wanted) gets a heap copy of
 * the preprocessed text.
 *
 * glslang's C interface parses the text glslang_shader_preprocess() left
 * behind, not input->code: without preprocessing first it parses an empty
 * string and says yes to anything. The info log collects both steps, so a
 * message can come twice (msgs_add keeps one). */
static glslang_shader_t *compile_text(const shader_src *src, const char *text, shader_stage st, vmsgs *m,
                                      bool *ok, char **preprocessed, diag_list *mapped) {
    ensure_glslang();
    if (preprocessed) *preprocessed = NULL;
    char *gs_text = st == SHADER_GEOMETRY ? gs_compat_text(text) : NULL;
    glslang_input_t in = make_input(gs_text ? gs_text : text, st);
    glslang_shader_t *sh = glslang_shader_create(&in);
    if (!sh) {
        free(gs_text);
        msgs_addf(m, DIAG_ERROR, src->files[0], 0, "glslang could not create a %s shader", shader_stage_name(st));
        *ok = false;
        return NULL;
    }
    int before = m->n;
    *ok = glslang_shader_preprocess(sh, &in) != 0;
    if (*ok) {
        const char *code = glslang_shader_get_preprocessed_code(sh);
        if (preprocessed && code) *preprocessed = mem_strdup(code);
        *ok = glslang_shader_parse(sh, &in) != 0;
    }
    add_compile_log(src, glslang_shader_get_info_log(sh), *ok, m, mapped);
    free(gs_text);
    if (!*ok) {
        /* a failure glslang explained nowhere still counts */
        bool any = false;
        for (int i = before; i < m->n; i++) any |= m->v[i].d.severity == DIAG_ERROR;
        if (!any) msgs_addf(m, DIAG_ERROR, src->files[0], 0, "the %s shader does not compile", shader_stage_name(st));
    }
    return sh;
}

/* As the renderer does (render_prog.c): the text as written first; when
 * glslang rejects it (or warns of a returned int Mesa rejects) for a
 * construct NVIDIA accepted, glsl_fix's rewrite, which becomes src->text
 * when it compiles, its warnings in m. */
static glslang_shader_t *compile(shader_src *src, shader_stage st, vmsgs *m, bool *ok, char **preprocessed) {
    vmsgs first = {0};
    diag_list cur = { 0 }, notes = { 0 };
    glslang_shader_t *sh = compile_text(src, src->text, st, &first, ok, preprocessed, &cur);
    if (sh && (!*ok || glsl_fix_wanted_by_warning(&cur))) {
        char *text = NULL;
        for (int tries = 0; tries < 4; tries++) {
            char *fixed = glsl_fix_rewrite(src, st, text ? text : src->text, &cur, &notes);
            diag_list_free(&cur);
            if (!fixed) break;
            free(text);
            text = fixed;
            vmsgs again = {0};
            bool ok2 = false;
            char *pp2 = NULL;
            glslang_shader_t *sh2 = compile_text(src, text, st, &again, &ok2, preprocessed ? &pp2 : NULL, &cur);
            if (sh2 && ok2 && !glsl_fix_wanted_by_warning(&cur)) {
                glslang_shader_delete(sh);
                sh = sh2;
                *ok = true;
                if (preprocessed) { free(*preprocessed); *preprocessed = pp2; }
                free(src->text);
                src->text = text;
                text = NULL;
                msgs_free(&first);
                msgs_add_list(&first, &notes);   /* glsl_fix's warnings */
                for (int i = 0; i < again.n; i++) msgs_add(&first, &again.v[i].d);
                msgs_free(&again);
                break;
            }
            free(pp2);
            if (sh2) glslang_shader_delete(sh2);
            msgs_free(&again);
        }
        free(text);
    }
    diag_list_free(&cur);
    diag_list_free(&notes);
    for (int i = 0; i < first.n; i++) msgs_add(m, &first.v[i].d);
    msgs_free(&first);
    return sh;
}

bool validate_stage(const shader_src *src, shader_stage stage, diag_list *out) {
    if (!src || !src->text || (unsigned)stage >= SHADER_STAGE_COUNT) {
        if (out && src && src->error.text[0]) diag_push(out, &src->error);
        else if (out) diag_add_bare(out, DIAG_ERROR, "error: no shader text");
        return false;
    }
    vmsgs m = {0};
    bool ok = false;
    shader_src copy = *src;   /* compile() may put glsl_fix's rewrite in its text */
    copy.text = mem_strdup(src->text);
    glslang_shader_t *sh = compile(&copy, stage, &m, &ok, NULL);
    free(copy.text);
    if (sh) glslang_shader_delete(sh);
    for (int i = 0; out && i < m.n; i++) diag_push(out, &m.v[i].d);
    msgs_free(&m);
    return ok;
}

/* glslang 12 reports "Anonymous member name used for global variable or
 * other anonymous member" when a 3.30 compatibility fragment shader reads
 * the gl_PerFragment built-ins (gl_TexCoord, gl_Color, ...): not an error. */
static bool is_spurious_link_error(const char *msg) {
    if (!strstr(msg, "Anonymous member name used for global variable")) return false;
    static const char *const builtins[] = {
        "TexCoord", "FogFragCoord", "Color", "SecondaryColor", "FrontColor", "BackColor",
        "FrontSecondaryColor", "BackSecondaryColor", "ClipVertex", "PointSize", "Position",
        "ClipDistance", "CullDistance",
    };
    const char *last = strrchr(msg, ' ');
    last = last ? last + 1 : msg;
    if (starts_with(last, "gl_")) return true;
    for (size_t i = 0; i < sizeof builtins / sizeof builtins[0]; i++)
        if (strcmp(last, builtins[i]) == 0) return true;
    return false;
}

/* Replaces every `from` in *s by `to` (which is not longer). */
static void replace_all(char *s, const char *from, const char *to) {
    size_t nf = strlen(from), nt = strlen(to);
    for (char *p = s; (p = strstr(p, from)) != NULL; p += nt) {
        memmove(p + nt, p + nf, strlen(p + nf) + 1);
        memcpy(p, to, nt);
    }
}

typedef struct link_log {
    const glib_cmd *prog;
    vmsgs *m;
    int reported, spurious;
} link_log;

static void link_message(link_log *l, diag_severity s, const char *text) {
    if (is_spurious_link_error(text)) { l->spurious++; return; }
    msgs_addf(l->m, s, l->prog->file, l->prog->line, "program %s: %s", l->prog->name, text);
    l->reported += s == DIAG_ERROR;
}

/* Links the compiled stages; messages are placed at the Program's line. */
static void link_stages(glslang_shader_t *const *sh, int n, const glib_cmd *prog, vmsgs *m, char **log_out) {
    if (log_out) *log_out = NULL;
    glslang_program_t *p = glslang_program_create();
    if (!p) return;
    for (int i = 0; i < n; i++) glslang_program_add_shader(p, sh[i]);
    int ok = glslang_program_link(p, GLSLANG_MSG_DEFAULT_BIT);
    const char *log = glslang_program_get_info_log(p);
    if (log_out && log) *log_out = mem_strdup(log);
    /* messages start with ERROR: or WARNING:, continuation lines are indented */
    char *copy = mem_strdup(log);
    char *pending = NULL;
    diag_severity pending_sev = DIAG_ERROR;
    link_log l = { prog, m, 0, 0 };
    for (char *q = copy; q && *q;) {
        char *e = strchr(q, '\n');
        if (e) *e = '\0';
        size_t len = strlen(q);
        while (len > 0 && isspace((unsigned char)q[len - 1])) q[--len] = '\0';
        /* glslang names the other side of a uniform mismatch "unknown stage" */
        replace_all(q, "Linking unknown stage and ", "Linking ");
        replace_all(q, "unknown stage stage:", "an earlier stage:");
        const char *t = q;
        while (isspace((unsigned char)*t)) t++;
        bool head = starts_with(q, "ERROR: ") || starts_with(q, "WARNING: ");
        if (head || !pending) {
            if (pending) link_message(&l, pending_sev, pending);
            free(pending);
            pending = NULL;
            if (*t) {
                pending_sev = starts_with(q, "WARNING: ") ? DIAG_WARNING : DIAG_ERROR;
                pending = mem_strdup(head ? q + (pending_sev == DIAG_WARNING ? 9 : 7) : t);
            }
        } else if (*t) {
            char *joined = xprintf("%s %s", pending, t);
            free(pending);
            pending = joined;
        }
        q = e ? e + 1 : NULL;
    }
    if (pending) link_message(&l, pending_sev, pending);
    free(pending);
    free(copy);
    /* a failed link whose only errors were spurious passes */
    if (!ok && l.reported == 0 && l.spurious == 0)
        msgs_addf(m, DIAG_ERROR, prog->file, prog->line, "program %s: glslang could not link it", prog->name);
    glslang_program_delete(p);
}

/* ---- stage interfaces (what glslang's linker leaves out) --------------------- */

typedef struct tok {
    const char *p;
    int n;
    long str, line;
} tok;

typedef struct toks {
    tok *v;
    int n, cap;
    int version;
    bool es;
} toks;

static void toks_add(toks *t, tok k) {
    t->v = mem_grow(t->v, &t->cap, t->n + 1, sizeof *t->v);
    t->v[t->n++] = k;
}

static bool is_ident_start(char c) { return isalpha((unsigned char)c) || c == '_'; }
static bool is_ident_char(char c) { return isalnum((unsigned char)c) || c == '_'; }

/* Tokenises preprocessed GLSL, following #line to know where each token was. */
static void tokenize(const char *code, toks *t) {
    long line = 1, str = 0;
    bool line_start = true;
    bool old_rule = false;
    const char *p = code;
    while (*p) {
        if (*p == '\n') { line++; line_start = true; p++; continue; }
        if (isspace((unsigned char)*p)) { p++; continue; }
        if (line_start && *p == '#') {
            const char *e = strchr(p, '\n');
            size_t n = e ? (size_t)(e - p) : strlen(p);
            char buf[128];
            if (n < sizeof buf) {
                memcpy(buf, p, n);
                buf[n] = '\0';
                long a, b;
                int v;
                char prof[16] = "";
                int got = sscanf(buf, "# line %ld %ld", &a, &b);
                if (got >= 1) {
                    line = (old_rule ? a + 1 : a) - 1;   /* the '\n' below adds one */
                    if (got == 2) str = b;
                } else if (sscanf(buf, "# version %d %15s", &v, prof) >= 1) {
                    t->version = v;
                    t->es = strcmp(prof, "es") == 0 || v == 100;
                    old_rule = !t->es && v < 330;
                }
            }
            p += n;
            continue;
        }
        line_start = false;
        if (p[0] == '/' && p[1] == '/') { while (*p && *p != '\n') p++; continue; }
        if (p[0] == '/' && p[1] == '*') {
            p += 2;
            while (*p && !(p[0] == '*' && p[1] == '/')) { if (*p == '\n') line++; p++; }
            if (*p) p += 2;
            continue;
        }
        tok k = { p, 1, str, line };
        if (is_ident_start(*p)) {
            while (is_ident_char(p[k.n])) k.n++;
        } else if (isdigit((unsigned char)*p) || (*p == '.' && isdigit((unsigned char)p[1]))) {
            while (is_ident_char(p[k.n]) || p[k.n] == '.') k.n++;
        }
        toks_add(t, k);
        p += k.n;
    }
}

static bool tok_is(const tok *k, const char *s) {
    return (size_t)k->n == strlen(s) && memcmp(k->p, s, (size_t)k->n) == 0;
}

typedef struct ivar {
    char name[64];
    bool block;
    bool in;                    /* input (else output) */
    long str, line;
    bool used;
} ivar;

typedef struct iface {
    ivar *v;
    int n, cap;
    int version;
    bool es;
} iface;

static void iface_add(iface *f, const tok *name, bool block, bool in) {
    if (name->n >= 64 || (name->n >= 3 && memcmp(name->p, "gl_", 3) == 0)) return;
    f->v = mem_grow(f->v, &f->cap, f->n + 1, sizeof *f->v);
    ivar *x = &f->v[f->n++];
    memset(x, 0, sizeof *x);
    memcpy(x->name, name->p, (size_t)name->n);
    x->block = block;
    x->in = in;
    x->str = name->str;
    x->line = name->line;
}

static int skip_group(const toks *t, int i, char open, char close) {
    int depth = 0;
    for (; i < t->n; i++) {
        if (t->v[i].n == 1 && t->v[i].p[0] == open) depth++;
        else if (t->v[i].n == 1 && t->v[i].p[0] == close && --depth == 0) return i;
    }
    return t->n - 1;
}

static bool is_qualifier(const tok *k) {
    static const char *const q[] = {
        "in", "out", "varying", "attribute", "uniform", "buffer", "shared", "const", "flat",
        "smooth", "noperspective", "centroid", "sample", "patch", "invariant", "precise",
        "highp", "mediump", "lowp", "coherent", "volatile", "restrict", "readonly", "writeonly",
        "inout",
    };
    for (size_t i = 0; i < sizeof q / sizeof q[0]; i++)
        if (tok_is(k, q[i])) return true;
    return false;
}

/* The qualifiers of a declaration from tokens [s, e): direction of in/out
 * (0 none, 1 in, 2 out) and whether it has layout(location). Returns the
 * index after the qualifiers. */
static int read_qualifiers(const toks *t, int s, int e, shader_stage st, int *dir, bool *location) {
    *dir = 0;
    *location = false;
    int i = s;
    while (i < e) {
        const tok *k = &t->v[i];
        if (tok_is(k, "layout") && i + 1 < e && tok_is(&t->v[i + 1], "(")) {
            int close = skip_group(t, i + 1, '(', ')');
            for (int j = i + 1; j < close; j++)
                if (tok_is(&t->v[j], "location")) *location = true;
            i = close + 1;
            continue;
        }
        if (!is_qualifier(k)) break;
        if (tok_is(k, "in")) *dir = 1;
        else if (tok_is(k, "out")) *dir = 2;
        else if (tok_is(k, "varying")) *dir = st == SHADER_FRAGMENT ? 1 : 2;
        else if (tok_is(k, "attribute") || tok_is(k, "uniform") || tok_is(k, "buffer") ||
                 tok_is(k, "inout")) { *dir = 0; return e; }
        i++;
    }
    return i;
}

/* A global declaration [s, e) (no braces): records its in/out names. */
static void read_declaration(const toks *t, int s, int e, shader_stage st, iface *f) {
    for (int i = s; i < e; i++)
        if (tok_is(&t->v[i], "struct") || tok_is(&t->v[i], "(") ) {
            /* a function prototype, or `layout(...)` handled below */
            if (tok_is(&t->v[i], "(") && i > s && tok_is(&t->v[i - 1], "layout")) continue;
            return;
        }
    int dir;
    bool location;
    int i = read_qualifiers(t, s, e, st, &dir, &location);
    if (!dir || location || i >= e) return;
    i++;                                            /* the type */
    if (i < e && tok_is(&t->v[i], "[")) i = skip_group(t, i, '[', ']') + 1;
    while (i < e) {
        if (!is_ident_start(t->v[i].p[0])) return;
        iface_add(f, &t->v[i], false, dir == 1);
        i++;
        if (i < e && tok_is(&t->v[i], "[")) i = skip_group(t, i, '[', ']') + 1;
        while (i < e && !tok_is(&t->v[i], ",")) i++;   /* an initializer */
        i++;
    }
}

static void read_interface(const char *code, shader_stage st, iface *f) {
    toks t = {0};
    tokenize(code, &t);
    f->version = t.version;
    f->es = t.es;
    int s = 0;
    for (int i = 0; i < t.n; i++) {
        if (tok_is(&t.v[i], ";")) {
            read_declaration(&t, s, i, st, f);
            s = i + 1;
        } else if (tok_is(&t.v[i], "{")) {
            int close = skip_group(&t, i, '{', '}');
            int dir;
            bool location;
            read_qualifiers(&t, s, i, st, &dir, &location);
            bool is_struct = false;
            for (int j = s; j < i; j++) is_struct |= tok_is(&t.v[j], "struct");
            if (dir && !location && i > s) {
                /* an interface block: matched by its block name */
                iface_add(f, &t.v[i - 1], true, dir == 1);
            }
            if (dir || is_struct) {
                /* `} instance;` or `} var;` follows */
                i = close;
                while (i + 1 < t.n && !tok_is(&t.v[i + 1], ";")) i++;
                i++;
                s = i + 1;
            } else {
                i = close;      /* a function body */
                s = i + 1;
            }
        }
    }
    /* an input counts only when the stage reads it */
    for (int k = 0; k < f->n; k++) {
        if (!f->v[k].in) continue;
        int uses = 0;
        size_t n = strlen(f->v[k].name);
        for (int i = 0; i < t.n; i++)
            if ((size_t)t.v[i].n == n && memcmp(t.v[i].p, f->v[k].name, n) == 0) uses++;
        f->v[k].used = f->v[k].block || uses > 1;
    }
    free(t.v);
}

/* Inputs of each stage that the stage before it does not write. */
static void check_interfaces(const shader_src *src, char *const *pp, const shader_stage *stages, int n,
                             vmsgs *m) {
    iface f[SHADER_STAGE_COUNT];
    memset(f, 0, sizeof f);
    bool have[SHADER_STAGE_COUNT] = { false };
    for (int i = 0; i < n; i++) {
        if (!pp[i]) continue;
        read_interface(pp[i], stages[i], &f[i]);
        have[i] = true;
    }
    for (int i = 1; i < n; i++) {
        if (!have[i] || !have[i - 1]) continue;
        const iface *cur = &f[i], *prev = &f[i - 1];
        for (int k = 0; k < cur->n; k++) {
            const ivar *v = &cur->v[k];
            if (!v->in || !v->used) continue;
            bool found = false;
            for (int j = 0; j < prev->n && !found; j++)
                found = !prev->v[j].in && prev->v[j].block == v->block &&
                        strcmp(prev->v[j].name, v->name) == 0;
            if (found) continue;
            /* Mesa: an error before GLSL 1.30, a warning after */
            bool error = !cur->es && cur->version < 130;
            char *raw = xprintf("%s: %ld:%ld: %s shader input %s'%s' is not written by the %s shader\n",
                                error ? "ERROR" : "WARNING", v->str, v->line,
                                shader_stage_name(stages[i]), v->block ? "block " : "", v->name,
                                shader_stage_name(stages[i - 1]));
            add_compile_log(&src[stages[i]], raw, true, m, NULL);
            free(raw);
        }
    }
    for (int i = 0; i < n; i++) free(f[i].v);
}

/* ---- a run ------------------------------------------------------------------------- */

typedef struct run {
    FILE *out;
    const char *include_dirs[1];
    char common_dir[4096];
    diag_list diags;        /* what the current file showed; flush() prints them */
    validate_result res;
} run;

/* Prints the diagnostics so far (diag_print, as every command does) and
 * counts them: each file's as soon as it is done. */
static void flush(run *r) {
    diag_print(&r->diags, r->out);
    r->res.nerrors += r->diags.nerrors;
    r->res.nwarnings += r->diags.nwarnings;
    diag_list_free(&r->diags);
}

static void add_msg(run *r, const vmsg *v, const char *suffix) {
    diag_add(&r->diags, v->d.severity, v->d.file, v->d.line, "%s%s", v->d.text, suffix ? suffix : "");
}

typedef struct toggle {
    const char *name;
    bool deflt;
} toggle;

/* A whole-number Define slider at one more value (`#if DEBUG_PASS == 5`
 * compiles code the default leaves out): validated with the toggles at
 * their defaults. */
typedef struct slider_value {
    int define;             /* index into the fixed Defines */
    long long value;
} slider_value;

#define SLIDER_ALL_VALUES 8         /* a range this short: every value; longer: min and max */
#define MAX_SLIDER_VALUES 128

/* The values of the program's whole-number Define sliders to validate
 * beside their defaults. */
static int slider_values(const glib_cmd *cmd, const shader_define *fixed, int nfixed, slider_value *out) {
    int n = 0;
    for (int i = 0, f = 0; i < cmd->ndefines && f < nfixed; i++) {
        const unif_decl *u = &cmd->defines[i];
        if (u->kind == UNIF_DECL_BOOL) continue;
        int fi = f++;   /* fixed[] holds the non-toggles in this order */
        if (u->kind != UNIF_DECL_SLIDER || u->n < 3) continue;
        double lo = u->v[0], def = u->v[1], hi = u->v[2];
        if (lo != floor(lo) || hi != floor(hi) || !(lo <= hi) || hi - lo > 1e6) continue;
        long long span = (long long)(hi - lo);
        for (long long k = 0; k <= span && n < MAX_SLIDER_VALUES; k++) {
            long long v = (long long)lo + k;
            bool end = k == 0 || k == span;
            if ((double)v == def || (span >= SLIDER_ALL_VALUES && !end)) continue;
            out[n++] = (slider_value){ fi, v };
        }
    }
    return n;
}

static void format_number(double v, char *buf, size_t n) {
    if (v == (double)(long long)v && v > -1e9 && v < 1e9) snprintf(buf, n, "%lld", (long long)v);
    else snprintf(buf, n, "%.9g", v);
}

/* Did the glib parser already report an error on this command's line? */
static bool glib_reported(const glib_scene *sc, const glib_cmd *c) {
    for (int i = 0; i < sc->ndiags; i++)
        if (sc->diags[i].severity == DIAG_ERROR && sc->diags[i].line == c->line && c->file && strcmp(sc->diags[i].file, c->file) == 0)
            return true;
    return false;
}

/* A fragment shader that writes gl_FragColor and declares outputs fails
 * glslang's link (Mesa's compile): as the renderer, demote its outputs
 * (glsl_fix) and link again; on success *lm holds the new link's messages
 * and the rewrite's warnings, src and pp the rewritten fragment stage. */
static void relink_fixed(glslang_shader_t **sh, char **pp, shader_src *src, const shader_stage *stages, int nst,
                         const glib_cmd *cmd, vmsgs *lm, char **llog) {
    static const char both[] = "Cannot use gl_FragColor or gl_FragData when using user-defined outputs";
    int fi = -1;
    for (int i = 0; i < nst; i++)
        if (stages[i] == SHADER_FRAGMENT) fi = i;
    if (fi < 0 || !*llog || !strstr(*llog, both)) return;
    shader_src *fs = &src[SHADER_FRAGMENT];
    diag_list why = { 0 }, notes = { 0 };
    diag_add(&why, DIAG_ERROR, "?", 0, "%s", both);
    char *fixed = glsl_fix_rewrite(fs, SHADER_FRAGMENT, fs->text, &why, &notes);
    diag_list_free(&why);
    if (!fixed) { diag_list_free(&notes); return; }
    vmsgs cm = {0}, m2 = {0};
    bool cok = false;
    char *pp2 = NULL, *log2 = NULL;
    glslang_shader_t *s2 = compile_text(fs, fixed, SHADER_FRAGMENT, &cm, &cok, &pp2, NULL);
    glslang_shader_t *old = sh[fi];
    if (s2 && cok) {
        sh[fi] = s2;
        link_stages(sh, nst, cmd, &m2, &log2);
    }
    bool linked = s2 && cok;
    for (int i = 0; linked && i < m2.n; i++) linked = m2.v[i].d.severity != DIAG_ERROR;
    if (linked) {
        glslang_shader_delete(old);
        free(pp[fi]);
        pp[fi] = pp2;
        pp2 = NULL;
        free(fs->text);
        fs->text = fixed;
        fixed = NULL;
        msgs_free(lm);
        msgs_add_list(lm, &notes);   /* glsl_fix's warnings */
        for (int i = 0; i < m2.n; i++) msgs_add(lm, &m2.v[i].d);
        free(*llog);
        *llog = log2;
        log2 = NULL;
    } else {
        sh[fi] = old;
        if (s2) glslang_shader_delete(s2);
    }
    msgs_free(&cm);
    msgs_free(&m2);
    free(pp2);
    free(log2);
    free(fixed);
    diag_list_free(&notes);
}

/* ---- a Program's combinations, on every core ---------------------------------- */

/* What every combination of one Program shares (read-only while the
 * workers run). */
typedef struct combo_job {
    const run *r;
    const glib_scene *scene;
    const glib_cmd *cmd;
    const program_stages *ps;
    const shader_stage *stages;
    int nst;
    const toggle *toggles;
    int nt, nvary;
    const shader_define *fixed;
    int nfixed;
    const slider_value *extra;
    int ncombo, total;       /* toggle combinations; and the sliders' other values after them */
    vmsgs *out;              /* [total]: each combination's messages */
    atomic_int next;         /* the next combination a worker takes */
} combo_job;

/* Combination c's Defines: the fixed ones (a slider's other value after
 * the toggles' combinations), then the toggles that are on. */
static int combo_defines(const combo_job *j, int c, shader_define *defs) {
    int nd = 0;
    for (int i = 0; i < j->nfixed; i++) defs[nd++] = j->fixed[i];
    if (c >= j->ncombo) {   /* a slider's other value, the toggles at their defaults */
        const slider_value *sv = &j->extra[c - j->ncombo];
        snprintf(defs[sv->define].value, sizeof defs[sv->define].value, "%lld", sv->value);
    }
    for (int i = 0; i < j->nt; i++) {
        bool on = i < j->nvary && c < j->ncombo ? (c >> i) & 1 : j->toggles[i].deflt;
        if (!on) continue;
        memset(&defs[nd], 0, sizeof defs[nd]);
        snprintf(defs[nd].name, sizeof defs[nd].name, "%s", j->toggles[i].name);
        snprintf(defs[nd].value, sizeof defs[nd].value, "1");
        nd++;
    }
    return nd;
}

/* One combination: its stages assembled, compiled and linked; the
 * messages into *m. */
static void validate_combo(const combo_job *j, int c, vmsgs *m) {
    shader_define defs[2 * MAX_DEFINES];
    int nd = combo_defines(j, c, defs), nst = j->nst;
    const shader_stage *stages = j->stages;
    shader_src src[SHADER_STAGE_COUNT];
    memset(src, 0, sizeof src);
    glslang_shader_t *sh[SHADER_STAGE_COUNT] = { NULL };
    char *pp[SHADER_STAGE_COUNT] = { NULL };
    int nsh = 0;
    bool ok = true;
    for (int i = 0; i < nst; i++) {
        shader_stage st = stages[i];
        shader_src_desc d = program_stage_desc(j->ps, st, defs, nd, j->r->include_dirs, 1);
        d.gs_input = program_gs_input(j->scene, j->cmd);
        if (!shader_src_load(&d, &src[st])) {
            msgs_add(m, &src[st].error);
            ok = false;
        }
    }
    /* every stage, even after one fails, so each shows its errors */
    for (int i = 0; ok && i < nst; i++) {
        bool cok = false;
        glslang_shader_t *s = compile(&src[stages[i]], stages[i], m, &cok, &pp[i]);
        if (s) sh[nsh++] = s;
        if (!cok || !s) {
            for (int k = i + 1; k < nst; k++) {
                glslang_shader_t *s2 = compile(&src[stages[k]], stages[k], m, &cok, NULL);
                if (s2) sh[nsh++] = s2;
            }
            ok = false;
        }
    }
    if (ok) {
        char *llog = NULL;
        vmsgs lm = {0};
        link_stages(sh, nsh, j->cmd, &lm, &llog);
        relink_fixed(sh, pp, src, stages, nst, j->cmd, &lm, &llog);
        for (int i = 0; i < lm.n; i++) msgs_add(m, &lm.v[i].d);
        msgs_free(&lm);
        const shader_src *srcs[SHADER_STAGE_COUNT] = { NULL };
        for (int i = 0; i < nst; i++) srcs[stages[i]] = &src[stages[i]];
        diag_list hint = { 0 };
        glsl_fix_link_hint(llog, srcs, &hint);   /* a uniform with two types: say where */
        msgs_add_list(m, &hint);
        diag_list_free(&hint);
        free(llog);
        check_interfaces(src, pp, stages, nst, m);
    }
    for (int i = 0; i < nsh; i++) glslang_shader_delete(sh[i]);
    for (int i = 0; i < nst; i++) free(pp[i]);
    for (int i = 0; i < nst; i++) shader_src_free(&src[stages[i]]);
}

static void *combo_worker(void *arg) {
    combo_job *j = arg;
    for (int c; (c = atomic_fetch_add(&j->next, 1)) < j->total;) validate_combo(j, c, &j->out[c]);
    return NULL;
}

#define MAX_WORKERS 16

/* Every combination of the job, on as many threads as there are cores (a
 * combination's glslang objects are its own; glslang's process state is
 * made first, here): tarn validate took 40-47 s on one core of a 2-core
 * machine. Returns each combination's messages ([total], the caller frees). */
static vmsgs *validate_combos(combo_job *j) {
    ensure_glslang();
    j->out = mem_zalloc((size_t)(j->total > 0 ? j->total : 1) * sizeof *j->out);
    atomic_init(&j->next, 0);
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    int n = cores < 1 ? 1 : cores > MAX_WORKERS ? MAX_WORKERS : (int)cores;
    if (n > j->total) n = j->total;
    pthread_t th[MAX_WORKERS];
    int started = 0;
    for (int i = 1; i < n; i++)   /* this thread is the first worker */
        if (pthread_create(&th[started], NULL, combo_worker, j) == 0) started++;
    combo_worker(j);
    for (int i = 0; i < started; i++) pthread_join(th[i], NULL);
    return j->out;
}

static void validate_program(run *r, const glib_scene *scene, const glib_cmd *cmd, const program_stages *ps) {
    r->res.nprograms++;
    shader_stage stages[SHADER_STAGE_COUNT];
    int nst = program_stage_list(ps, stages);
    if (nst == 0) {
        diag_add(&r->diags, DIAG_ERROR, cmd->file, cmd->line, "Program %s has no shader stages: name files with "
                 "Vertex and Fragment before the Program line", cmd->name);
        return;
    }
    r->res.nstages += nst;
    bool missing = false;
    for (int i = 0; i < nst; i++) {
        const glib_cmd *sc = ps->stage[stages[i]];
        if (!is_regular_file(sc->path)) {
            int err = errno;
            missing = true;
            if (glib_reported(scene, sc)) continue;
            diag_add(&r->diags, DIAG_ERROR, sc->file, sc->line, "%s %s: %s (Program %s)", glib_cmd_name(sc->kind),
                     sc->path, is_dir(sc->path) ? "is a directory" : strerror(err), cmd->name);
        }
    }
    if (missing) return;

    /* the toggles vary; other Defines keep their value */
    toggle toggles[MAX_DEFINES];
    int nt = 0;
    shader_define fixed[MAX_DEFINES];
    int nfixed = 0;
    for (int i = 0; i < cmd->ndefines; i++) {
        const unif_decl *u = &cmd->defines[i];
        if (u->kind == UNIF_DECL_BOOL) {
            if (nt < MAX_DEFINES) toggles[nt++] = (toggle){ u->name, u->n > 0 && u->v[0] != 0 };
        } else if (nfixed < MAX_DEFINES) {
            shader_define *d = &fixed[nfixed++];
            memset(d, 0, sizeof *d);
            snprintf(d->name, sizeof d->name, "%s", u->name);
            double v = u->kind == UNIF_DECL_SLIDER && u->n >= 2 ? u->v[1] : u->n > 0 ? u->v[0] : 0;
            format_number(v, d->value, sizeof d->value);
        }
    }
    int nvary = nt < MAX_TOGGLES_VARIED ? nt : MAX_TOGGLES_VARIED;
    int ncombo = 1 << nvary;
    if (nt > nvary) {
        char names[512] = "";
        size_t w = 0;
        for (int i = nvary; i < nt && w < sizeof names; i++)
            w += (size_t)snprintf(names + w, sizeof names - w, "%s%s", i > nvary ? " " : "", toggles[i].name);
        diag_add(&r->diags, DIAG_WARNING, cmd->file, cmd->line, "Program %s has %d Define toggles; validating "
                 "the %d combinations of the first %d, with %s at their defaults", cmd->name, nt, ncombo, nvary,
                 names);
    }
    slider_value extra[MAX_SLIDER_VALUES];
    int nextra = slider_values(cmd, fixed, nfixed, extra), total = ncombo + nextra;
    r->res.ncombinations += total;

    combo_job job = { .r = r, .scene = scene, .cmd = cmd, .ps = ps, .stages = stages, .nst = nst,
                      .toggles = toggles, .nt = nt, .nvary = nvary, .fixed = fixed, .nfixed = nfixed,
                      .extra = extra, .ncombo = ncombo, .total = total };
    vmsgs *per = validate_combos(&job);
    /* merged in the combinations' order: each message names its first */
    vmsgs table = {0};
    for (int c = 0; c < total; c++) {
        msgs_merge(&table, &per[c], c);
        msgs_free(&per[c]);
    }
    free(per);

    for (int i = 0; i < table.n; i++) {
        const vmsg *v = &table.v[i];
        char suffix[1024] = "";
        size_t w = 0;
        bool is_extra = v->first_combo >= ncombo;
        if (nt > 0 || is_extra) {
            w += (size_t)snprintf(suffix + w, sizeof suffix - w, " [with");
            if (is_extra) {
                const slider_value *sv = &extra[v->first_combo - ncombo];
                w += (size_t)snprintf(suffix + w, sizeof suffix - w, " %s=%lld", fixed[sv->define].name, sv->value);
            }
            for (int t = 0; t < nt && w < sizeof suffix; t++) {
                bool on = t < nvary && !is_extra ? (v->first_combo >> t) & 1 : toggles[t].deflt;
                w += (size_t)snprintf(suffix + w, sizeof suffix - w, " %s=%d", toggles[t].name, on);
            }
            if (w < sizeof suffix) w += (size_t)snprintf(suffix + w, sizeof suffix - w, "]");
        }
        if (total > 1 && v->count > 1 && w < sizeof suffix) {
            if (v->count == total) snprintf(suffix + w, sizeof suffix - w, " (all %d combinations)", total);
            else snprintf(suffix + w, sizeof suffix - w, " (%d of %d combinations)", v->count, total);
        }
        add_msg(r, v, suffix);
    }
    msgs_free(&table);
}

static void validate_glib(run *r, const char *path) {
    glib_scene *sc = glib_load(path);
    for (int i = 0; i < sc->ndiags; i++) {
        const diag *d = &sc->diags[i];
        diag_add(&r->diags, d->severity, d->file, d->line, "%s", d->text);
    }
    program_stages ps;
    program_stages_init(&ps);
    for (int i = 0; i < sc->ncmds; i++) {
        const glib_cmd *c = &sc->cmds[i];
        if (c->kind == GLIB_CMD_PROGRAM) validate_program(r, sc, c, &ps);
        else program_stages_step(&ps, c);
    }
    glib_free(sc);
}

/* Does a .glsl without a stage suffix look like a stage (it has main)? */
static bool has_main(const char *path) {
    file_text_opts o = { .max_bytes = SHADER_SRC_MAX_FILE_BYTES };
    char why[MSG_MAX];
    char *text = file_read_text(path, &o, NULL, why, sizeof why);
    bool found = false;
    for (char *p = text; p && !found && (p = strstr(p, "main")) != NULL; p += 4) {
        bool left = p == text || !is_ident_char(p[-1]);
        const char *q = p + 4;
        while (*q == ' ' || *q == '\t' || *q == '\n' || *q == '\r') q++;
        found = left && *q == '(';
    }
    free(text);
    return found;
}

static void validate_stage_file(run *r, const char *path, shader_stage st) {
    r->res.nstages++;
    shader_src src;
    shader_src_desc d = { .path = path, .stage = st, .include_dirs = r->include_dirs, .ninclude_dirs = 1 };
    vmsgs m = {0};
    if (!shader_src_load(&d, &src)) {
        msgs_add(&m, &src.error);
    } else {
        bool ok = false;
        glslang_shader_t *sh = compile(&src, st, &m, &ok, NULL);
        if (sh) glslang_shader_delete(sh);
    }
    shader_src_free(&src);
    for (int i = 0; i < m.n; i++) add_msg(r, &m.v[i], NULL);
    msgs_free(&m);
}

static bool is_stage_ext(const char *ext) {
    static const char *const exts[] = { "vert", "vs", "tesc", "tese", "geom", "gs", "frag", "fs", "glsl" };
    for (size_t i = 0; i < sizeof exts / sizeof exts[0]; i++)
        if (strcasecmp(ext, exts[i]) == 0) return true;
    return false;
}

/* Files under dir (recursively, hidden names skipped), .glib ones or stage ones. */
static void collect(const char *dir, bool glibs, strlist *out) {
    DIR *d = opendir(dir);
    if (!d) return;
    strlist names = {0};
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.') continue;
        strlist_add(&names, xprintf("%s/%s", dir, e->d_name));
    }
    closedir(d);
    qsort(names.v, (size_t)names.n, sizeof *names.v, cmp_str);
    for (int i = 0; i < names.n; i++) {
        const char *p = names.v[i];
        if (is_dir(p)) { collect(p, glibs, out); continue; }
        if (!is_regular_file(p)) continue;
        const char *ext = path_ext(p);
        if (glibs ? strcasecmp(ext, "glib") == 0 : is_stage_ext(ext)) strlist_add(out, mem_strdup(p));
    }
    strlist_free(&names);
}

static void validate_file(run *r, const char *path, bool named) {
    const char *ext = path_ext(path);
    if (strcasecmp(ext, "glib") == 0) { validate_glib(r, path); return; }
    shader_stage st = shader_stage_from_path(path);
    if (st != SHADER_STAGE_COUNT) { validate_stage_file(r, path, st); return; }
    if (strcasecmp(ext, "glsl") == 0) {
        /* a .glsl without a stage suffix is usually an include: say so only
         * when it was named, or when it has a main() */
        if (named || has_main(path))
            diag_add(&r->diags, DIAG_WARNING, path, 0, "cannot tell the stage of this .glsl; name it "
                     "like water.frag.glsl (or .vert .tesc .tese .geom .frag); skipped");
        return;
    }
    diag_add(&r->diags, DIAG_WARNING, path, 0, "not a .glib or a shader stage file "
             "(.vert .tesc .tese .geom .frag .glsl); skipped");
}

static void validate_path(run *r, const char *path) {
    struct stat st;
    if (stat(path, &st) != 0) {
        diag_add(&r->diags, DIAG_ERROR, path, 0, "%s", strerror(errno));
        return;
    }
    if (!S_ISDIR(st.st_mode)) { validate_file(r, path, true); return; }
    strlist files = {0};
    collect(path, true, &files);
    if (files.n == 0) collect(path, false, &files);
    if (files.n == 0)
        diag_add(&r->diags, DIAG_WARNING, path, 0, "no .glib or shader stage files here");
    for (int i = 0; i < files.n; i++) {
        validate_file(r, files.v[i], false);
        flush(r);
    }
    strlist_free(&files);
}

int validate_run_ex(const char *const *paths, int npaths, const char *repo_root, FILE *out,
                    validate_result *res) {
    run r;
    memset(&r, 0, sizeof r);
    r.out = out ? out : stdout;
    if (!repo_root || !repo_root[0]) repo_root = ".";
    snprintf(r.common_dir, sizeof r.common_dir, "%s/packs/common", repo_root);
    r.include_dirs[0] = r.common_dir;

    if (npaths > 0) {
        for (int i = 0; i < npaths; i++) {
            validate_path(&r, paths[i]);
            flush(&r);
        }
    } else {
        strlist files = {0};
        char *packs = xprintf("%s/packs", repo_root);
        DIR *d = opendir(packs);
        if (d) {
            strlist dirs = {0};
            struct dirent *e;
            while ((e = readdir(d)) != NULL)
                if (e->d_name[0] != '.') strlist_add(&dirs, xprintf("%s/%s", packs, e->d_name));
            closedir(d);
            qsort(dirs.v, (size_t)dirs.n, sizeof *dirs.v, cmp_str);
            for (int i = 0; i < dirs.n; i++)
                if (is_dir(dirs.v[i])) collect(dirs.v[i], true, &files);
            strlist_free(&dirs);
        }
        free(packs);
        char *scenes = xprintf("%s/scenes", repo_root);
        collect(scenes, true, &files);
        free(scenes);
        if (files.n == 0)
            diag_add(&r.diags, DIAG_WARNING, repo_root, 0, "no .glib files under packs/*/ or scenes/");
        for (int i = 0; i < files.n; i++) {
            validate_glib(&r, files.v[i]);
            flush(&r);
        }
        strlist_free(&files);
    }
    flush(&r);
    fprintf(r.out, "validate: %d programs, %d stages, %d combinations: %d errors\n", r.res.nprograms,
            r.res.nstages, r.res.ncombinations, r.res.nerrors);
    fflush(r.out);
    if (res) *res = r.res;
    return r.res.nerrors ? 1 : 0;
}

int validate_run(const char *const *paths, int npaths, const char *repo_root, FILE *out) {
    return validate_run_ex(paths, npaths, repo_root, out, NULL);
}
