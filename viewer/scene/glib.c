/* glib.c: the parser of .glib scene files (glib.h; the format is in
 * docs/glib.md).
 *
 * The text is read one logical line at a time (physical lines joined at a
 * trailing backslash, comments cut off); the first word picks a row of the
 * command table at the bottom of this file and that row's handler turns the
 * rest of the line into a glib_cmd. A bad line becomes a diagnostic and is
 * skipped, so one typo never hides the rest of the scene.
 *
 * Every limit below exists so that corrupt or hostile input (a binary file,
 * an include loop, a megabyte-long line) costs bounded memory and time.
 */
#ifndef _DEFAULT_SOURCE
#define _DEFAULT_SOURCE         /* realpath(), which is XSI, not plain POSIX */
#endif
#include "glib.h"
#include "file.h"
#include "mem.h"
#include "unif.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

enum {
    LIM_LINE_CHARS = 16384,     /* one logical line, continuations included */
    LIM_FILE_BYTES = 1 << 20,   /* a .glib is a short text file */
    LIM_DIAGS = 200,            /* the last slot is kept for "N more" */
    LIM_CMDS = 16384,           /* a glib_cmd is ~1.3 KB */
    LIM_PROGRAM_UNIFORMS = 256,
    LIM_SCENE_UNIFORMS = 16384,
    LIM_INCLUDE_DEPTH = 32,     /* nesting levels below the top file */
    LIM_INCLUDE_READS = 256,    /* diamonds of includes could otherwise explode */
    LIM_BINARY_LINES = 5,       /* then the file is not text: stop reading it */
    LIM_WORDS = 24,             /* words kept per command (CubeMap needs 7) */
    LIM_UNIT = 31,              /* highest texture unit */
    LIM_USAGE = 200
};

/* ------------------------------------------------------------------ */
/* memory: bounded by the limits above (mem.h: out of memory aborts)   */

/* Makes room for need elements in *arr (capacity *cap). */
static void *grow(void *arr, int *cap, int need, size_t elem) {
    if (need <= *cap)
        return arr;
    int c = *cap ? *cap : 8;
    while (c < need)
        c *= 2;
    *cap = c;
    return mem_realloc(arr, (size_t)c * elem);
}

/* ------------------------------------------------------------------ */
/* the parser's state and its diagnostics                              */

typedef struct parser {
    glib_scene *sc;
    int cmd_cap, diag_cap, file_cap;
    /* the files being read, outermost first, for include cycle checks */
    const char *stack_name[LIM_INCLUDE_DEPTH + 1];
    char *stack_canon[LIM_INCLUDE_DEPTH + 1];
    int depth;
    int nreads;
    /* Define toggles waiting for the next Program */
    unif_decl *pending;
    int npending, pending_cap;
    int scene_uniforms;
    int dropped, dropped_errors;    /* diagnostics beyond LIM_DIAGS */
    bool stop;                      /* a scene-wide limit was hit */
    /* glib_options */
    const char *packs_dir;
    const char *pack_override;
    bool pack_seen;                 /* the scene's (first) Pack command was read */
    const char *pack_file;          /* where, for the message about a second one */
    int pack_line;
    char pack_name[GLIB_NAME_MAX];
    /* an open glBegin (its file and line; NULL when none) */
    const char *begin_file;
    int begin_line, begin_nverts;
} parser;

static void add_diag(parser *p, diag_severity sev, const char *file, int line,
                     const char *msg) {
    glib_scene *sc = p->sc;
    sc->diags = grow(sc->diags, &p->diag_cap, sc->ndiags + 1, sizeof *sc->diags);
    diag *d = &sc->diags[sc->ndiags++];
    memset(d, 0, sizeof *d);
    d->severity = sev;
    snprintf(d->file, sizeof d->file, "%s", file ? file : "?");
    d->line = line;
    snprintf(d->text, sizeof d->text, "%s", msg);
    if (sev == DIAG_ERROR)
        sc->nerrors++;
}

__attribute__((format(printf, 5, 0)))
static void vdiag(parser *p, diag_severity sev, const char *file, int line,
                  const char *fmt, va_list ap) {
    if (p->sc->ndiags >= LIM_DIAGS - 1) {
        p->dropped++;
        p->dropped_errors += sev == DIAG_ERROR;
        return;
    }
    char msg[sizeof p->sc->diags[0].text];
    vsnprintf(msg, sizeof msg, fmt, ap);
    add_diag(p, sev, file, line, msg);
}

__attribute__((format(printf, 5, 6)))
static void report(parser *p, diag_severity sev, const char *file, int line,
                 const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vdiag(p, sev, file, line, fmt, ap);
    va_end(ap);
}

/* Records a file name in scene->files (once) and returns the stored copy,
 * which commands and diagnostics point at. */
static const char *add_file(parser *p, const char *name) {
    glib_scene *sc = p->sc;
    for (int i = 0; i < sc->nfiles; i++)
        if (strcmp(sc->files[i], name) == 0)
            return sc->files[i];
    sc->files = grow(sc->files, &p->file_cap, sc->nfiles + 1, sizeof *sc->files);
    sc->files[sc->nfiles] = mem_strdup(name);
    return sc->files[sc->nfiles++];
}

/* ------------------------------------------------------------------ */
/* one command being parsed                                            */

typedef struct cmd_spec cmd_spec;

typedef struct cmdctx {
    parser *p;
    const char *file;
    int line;
    const cmd_spec *spec;
    char *rest;                 /* the text after the command name */
    char *words[LIM_WORDS];     /* rest split at whitespace (not for raw rows) */
    int nwords;                 /* all words, even beyond LIM_WORDS */
    char usage[LIM_USAGE];
} cmdctx;

__attribute__((format(printf, 2, 3)))
static void cerr(cmdctx *c, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vdiag(c->p, DIAG_ERROR, c->file, c->line, fmt, ap);
    va_end(ap);
}

__attribute__((format(printf, 2, 3)))
static void cwarn(cmdctx *c, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vdiag(c->p, DIAG_WARNING, c->file, c->line, fmt, ap);
    va_end(ap);
}

static void vdiag_note(cmdctx *c, const char *text) {
    report(c->p, DIAG_NOTE, c->file, c->line, "MessageBox: %.400s", text);
}

/* A numeric argument: its name in the usage line, what a message calls it
 * when it is missing, and the values it may take. */
typedef struct arg_rule {
    const char *sym;
    const char *what;
    char type;                  /* 'r' any, 'p' > 0, 'a' angle in (0, 180), 'i' whole in [lo, hi] */
    double lo, hi;
    double def;                 /* for optional arguments */
} arg_rule;

typedef bool (*cmd_fn)(cmdctx *c, glib_cmd *cmd);

struct cmd_spec {
    const char *name;
    glib_cmd_kind kind;
    bool wire;
    cmd_fn fn;
    bool raw;                   /* the handler reads c->rest itself (brackets) */
    int nreq, nmax;             /* numbers, for h_nums */
    arg_rule args[12];         /* LinesAdjacency: 4 points */
    const char *usage;          /* NULL: built from args */
    bool world;                 /* describes the world (docs/glib.md, "Describing the
                                 * world"): a scene with one is drawn lit, with tarn's world */
};

static const arg_rule unit_rule = { "unit", "a texture unit", 'i', 0, LIM_UNIT, 0 };

/* ------------------------------------------------------------------ */
/* characters and words                                                */

static bool is_space(int c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

static char *skip_space(char *s) {
    while (is_space((unsigned char)*s))
        s++;
    return s;
}

static bool is_opener(int c) { return c == '<' || c == '{' || c == '['; }
static bool is_closer(int c) { return c == '>' || c == '}' || c == ']'; }

static char closer_of(char open) {
    return open == '<' ? '>' : open == '{' ? '}' : ']';
}

static bool is_ident(const char *s) {
    if (!isalpha((unsigned char)*s) && *s != '_')
        return false;
    for (s++; *s; s++)
        if (!isalnum((unsigned char)*s) && *s != '_')
            return false;
    return true;
}

/* Splits s in place at whitespace; a "quoted word" keeps its spaces.
 * Stores at most max words and returns how many there are in all, or -1
 * for an unclosed quote. */
static int split_words(char *s, char **w, int max) {
    int n = 0;
    for (;;) {
        s = skip_space(s);
        if (!*s)
            return n;
        char *start = s;
        if (*s == '"') {
            start = ++s;
            s = strchr(s, '"');
            if (!s)
                return -1;
        } else {
            while (*s && !is_space((unsigned char)*s))
                s++;
        }
        if (n < max)
            w[n] = start;
        n++;
        if (*s)
            *s++ = '\0';
    }
}

/* Splits bracket contents in place at whitespace and commas, since real
 * files write both: {0.40, 1.0, 0.95, 1.}. Returns the count of items. */
static int split_items(char *s, char **w, int max) {
    int n = 0;
    for (;;) {
        while (is_space((unsigned char)*s) || *s == ',')
            s++;
        if (!*s)
            return n;
        char *start = s;
        while (*s && !is_space((unsigned char)*s) && *s != ',')
            s++;
        if (n < max)
            w[n] = start;
        n++;
        if (*s)
            *s++ = '\0';
    }
}

/* The decimal forms people write: 1  -2.  .5  1e-3  +3.25E+2. strtod alone
 * would also take hex, "nan" and "inf", which are typos in a scene file. */
static bool is_decimal(const char *s) {
    int digits = 0;
    if (*s == '+' || *s == '-')
        s++;
    for (; isdigit((unsigned char)*s); s++)
        digits++;
    if (*s == '.')
        for (s++; isdigit((unsigned char)*s); s++)
            digits++;
    if (!digits)
        return false;
    if (*s == 'e' || *s == 'E') {
        s++;
        if (*s == '+' || *s == '-')
            s++;
        if (!isdigit((unsigned char)*s))
            return false;
        while (isdigit((unsigned char)*s))
            s++;
    }
    return *s == '\0';
}

static bool parse_number(const char *s, double *out) {
    if (!is_decimal(s))
        return false;
    char *end;
    double v = strtod(s, &end);
    if (*end || !isfinite(v))       /* 1e999 overflows to inf */
        return false;
    *out = v;
    return true;
}

/* glman read numbers with atof: the longest valid prefix counts. Real
 * files hold doubled decimal points (0.1., -0.1., 1..), so a number
 * followed by dots and digits is read as its prefix; letters or other signs
 * after a number (0x10, 1e, 3#x) stay errors, being other mistakes. The
 * length of the prefix read, or 0. */
static size_t dotted_prefix(const char *s, double *out) {
    size_t k = 0;
    if (s[k] == '+' || s[k] == '-')
        k++;
    while (isdigit((unsigned char)s[k]))
        k++;
    if (s[k] == '.')
        for (k++; isdigit((unsigned char)s[k]); k++)
            ;
    if (s[k] != '.' || k > 64)      /* the greedy number must end at a second dot */
        return 0;
    for (const char *r = s + k; *r; r++)
        if (*r != '.' && !isdigit((unsigned char)*r))
            return 0;
    char buf[66];
    memcpy(buf, s, k);
    buf[k] = '\0';
    return parse_number(buf, out) ? k : 0;
}

static bool is_bool_word(const char *s, double *v) {
    if (strcasecmp(s, "true") == 0)
        return *v = 1, true;
    if (strcasecmp(s, "false") == 0)
        return *v = 0, true;
    return false;
}

/* ------------------------------------------------------------------ */
/* numeric arguments                                                   */

/* A number as glman's atof read it: exact, or its prefix with a warning
 * that says what was read. */
static bool read_number(cmdctx *c, const char *tok, double *out) {
    if (parse_number(tok, out))
        return true;
    size_t k = dotted_prefix(tok, out);
    if (k)
        cwarn(c, "%s: '%.60s' read as %.*s (the rest is ignored, as glman's atof did)",
              c->spec->name, tok, (int)k, tok);
    return k > 0;
}

static void build_usage(const cmd_spec *s, char *out, size_t size) {
    if (s->usage) {
        snprintf(out, size, "%s", s->usage);
        return;
    }
    size_t n = (size_t)snprintf(out, size, "%s", s->name);
    for (int i = 0; i < s->nmax && n < size; i++) {
        const char *pre = i == s->nreq ? " [" : " ";
        n += (size_t)snprintf(out + n, size - n, "%s%s%s", pre, s->args[i].sym,
                              i == s->nmax - 1 && i >= s->nreq ? "]" : "");
    }
}

static bool parse_arg(cmdctx *c, const arg_rule *a, const char *tok, double *out) {
    const char *cmd = c->spec->name;
    double v;
    if (!read_number(c, tok, &v)) {
        cerr(c, "%s: bad number '%.60s' for %s (write e.g. 2, -0.5, .25 or 1e-3): %s",
             cmd, tok, a->sym, c->usage);
        return false;
    }
    if (a->type == 'p' && !(v > 0)) {
        cerr(c, "%s: %s must be greater than 0, not '%.60s'", cmd, a->sym, tok);
        return false;
    }
    if (a->type == 'a' && !(v > 0 && v < 180)) {
        cerr(c, "%s: %s must be an angle between 0 and 180 degrees, not '%.60s'",
             cmd, a->sym, tok);
        return false;
    }
    if (a->type == 'i' && (v != floor(v) || v < a->lo || v > a->hi)) {
        cerr(c, "%s: %s must be a whole number from %.15g to %.15g, not '%.60s'",
             cmd, a->sym, a->lo, a->hi, tok);
        return false;
    }
    *out = v;
    return true;
}

static void missing_args(cmdctx *c, int have) {
    const cmd_spec *s = c->spec;
    const arg_rule *a = &s->args[have];
    if (s->nreq - have == 1 && a->what)
        cerr(c, "%s needs %s: %s", s->name, a->what, c->usage);
    else
        cerr(c, "%s needs %s%d numbers, got %d: %s", s->name,
             s->nreq < s->nmax ? "at least " : "", s->nreq, have, c->usage);
}

/* Extra words are ignored with a warning: the command still does what the
 * first words say, which is what glman did. */
static void warn_extra(cmdctx *c, int max, const char *hint) {
    if (c->nwords <= max)
        return;
    const char *more = c->nwords > max + 1 ? " and what follows" : "";
    if (max == 0)
        cwarn(c, "%s takes no arguments; ignoring '%.40s'%s", c->spec->name,
              c->words[0], more);
    else
        cwarn(c, "%s takes at most %d argument%s; ignoring '%.40s'%s%s: %s",
              c->spec->name, max, max == 1 ? "" : "s", c->words[max], more,
              hint, c->usage);
}

static bool same3(const double *a, const double *b) {
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

/* Arguments that are each fine but together make a singular matrix: these
 * would draw nothing (NaN) with no hint why. */
static bool check_degenerate(cmdctx *c, glib_cmd *cmd) {
    const double *n = cmd->num;
    switch (cmd->kind) {
    case GLIB_CMD_PERSPECTIVE:
        if (n[1] >= n[2]) {
            cerr(c, "Perspective: near (%g) must be less than far (%g)", n[1], n[2]);
            return false;
        }
        return true;
    case GLIB_CMD_ORTHO:
        if (n[0] == n[1] || n[2] == n[3] || n[4] == n[5]) {
            cerr(c, "Ortho: left/right, bottom/top and near/far must differ: %s", c->usage);
            return false;
        }
        return true;
    case GLIB_CMD_LOOKAT: {
        double d[3] = { n[3] - n[0], n[4] - n[1], n[5] - n[2] };
        double x[3] = { d[1] * n[8] - d[2] * n[7], d[2] * n[6] - d[0] * n[8],
                        d[0] * n[7] - d[1] * n[6] };
        if (same3(n, n + 3)) {
            cerr(c, "LookAt: the eye and the point looked at are the same");
            return false;
        }
        if (x[0] == 0 && x[1] == 0 && x[2] == 0) {
            cerr(c, "LookAt: the up vector is zero or along the line of sight; use e.g. 0 1 0");
            return false;
        }
        return true;
    }
    case GLIB_CMD_ROTATE:
        if (n[1] == 0 && n[2] == 0 && n[3] == 0) {
            cerr(c, "Rotate: the axis is zero: Rotate deg ax ay az, e.g. Rotate 90 0 1 0");
            return false;
        }
        return true;
    default:
        return true;
    }
}

/* Scale and Box take one number for all three axes or all three. */
static bool one_or_three(cmdctx *c, glib_cmd *cmd, int given) {
    if (given == 2) {
        cerr(c, "%s takes 1 number or 3, not 2: %s", c->spec->name, c->usage);
        return false;
    }
    if (given == 1)
        cmd->num[1] = cmd->num[2] = cmd->num[0];
    if (cmd->kind == GLIB_CMD_SCALE)
        cmd->nnum = given;      /* glib.h: nnum 1 or 3 */
    return true;
}

/* Commands whose arguments are numbers only. Optional ones get their
 * defaults, so nnum is always the full count (but Scale, see above). */
static bool h_nums(cmdctx *c, glib_cmd *cmd) {
    const cmd_spec *s = c->spec;
    if (c->nwords < s->nreq) {
        missing_args(c, c->nwords);
        return false;
    }
    warn_extra(c, s->nmax, "");
    int given = c->nwords < s->nmax ? c->nwords : s->nmax;
    for (int i = 0; i < given; i++)
        if (!parse_arg(c, &s->args[i], c->words[i], &cmd->num[i]))
            return false;
    for (int i = given; i < s->nmax; i++)
        cmd->num[i] = s->args[i].def;
    cmd->nnum = s->nmax;
    if (cmd->kind == GLIB_CMD_SCALE || cmd->kind == GLIB_CMD_BOX)
        return one_or_three(c, cmd, given);
    if (cmd->kind == GLIB_CMD_TRANSLATE && given > 0 && given < 3)
        cwarn(c, "Translate has %d number%s; glman fills the missing ones with 0 (Translate %g %g %g): write "
              "all three", given, given == 1 ? "" : "s", cmd->num[0], cmd->num[1], cmd->num[2]);
    return check_degenerate(c, cmd);
}

/* ------------------------------------------------------------------ */
/* paths                                                               */

/* Paths are relative to the file that names them, so a scene and its
 * shaders move together. Backslashes become slashes: glman ran on Windows
 * and student files say textures\water.bmp. */
static bool resolve_path(cmdctx *c, const char *word, char out[GLIB_PATH_MAX]) {
    size_t dirlen = 0;
    if (word[0] != '/' && word[0] != '\\') {
        const char *slash = strrchr(c->file, '/');
        dirlen = slash ? (size_t)(slash - c->file) + 1 : 0;
    }
    size_t wl = strlen(word);
    if (dirlen + wl >= GLIB_PATH_MAX) {
        cerr(c, "%s: path too long (%zu characters, at most %d): '%.40s...'",
             c->spec->name, dirlen + wl, GLIB_PATH_MAX - 1, word);
        return false;
    }
    memcpy(out, c->file, dirlen);
    memcpy(out + dirlen, word, wl + 1);
    for (char *q = out + dirlen; *q; q++)
        if (*q == '\\')
            *q = '/';
    return true;
}

/* In directory dir (a prefix of a path, "" for the current one) finds the
 * entry named like name but for case; into out (of size size). */
static bool case_entry(const char *dir, const char *name, size_t len, char *out, size_t size) {
    DIR *d = opendir(dir[0] ? dir : ".");
    if (!d)
        return false;
    bool found = false;
    struct dirent *e;
    while (!found && (e = readdir(d)) != NULL)
        found = strlen(e->d_name) == len && strncasecmp(e->d_name, name, len) == 0 &&
                strlen(e->d_name) < size;
    if (found)
        memcpy(out, e->d_name, len + 1);
    closedir(d);
    return found;
}

/* glman ran on Windows, where file names ignore case: a project says
 * TEXTURES/Water.BMP for textures/water.bmp. Finds the real name, one
 * path component at a time (a component that exists as written is kept). */
static bool case_match(const char *path, char alt[GLIB_PATH_MAX]) {
    size_t n = 0, i = 0;
    if (path[0] == '/')
        alt[n++] = path[i++];
    alt[n] = '\0';
    while (path[i]) {
        size_t len = strcspn(path + i, "/");
        if (n + len + 1 >= GLIB_PATH_MAX)
            return false;
        memcpy(alt + n, path + i, len);
        alt[n + len] = '\0';
        struct stat st;
        if (stat(alt, &st) != 0) {
            char dir[GLIB_PATH_MAX];
            memcpy(dir, alt, n);
            dir[n] = '\0';
            if (!case_entry(dir, path + i, len, alt + n, GLIB_PATH_MAX - n))
                return false;
        }
        n += len;
        i += len;
        if (path[i] == '/')
            alt[n++] = path[i++];
        alt[n] = '\0';
    }
    return strcmp(alt, path) != 0;
}

/* The renderer reports a missing file too, but only when it gets there;
 * saying it here puts the message next to the line that named it. A name
 * that differs from the file on disk only in case is that file (glman's
 * Windows habit), with a warning naming the real file. */
static void check_readable(cmdctx *c, char path[GLIB_PATH_MAX]) {
    char why[128];
    struct stat st;
    if (access(path, R_OK) != 0)
        snprintf(why, sizeof why, "%s", strerror(errno));
    else if (stat(path, &st) == 0 && S_ISDIR(st.st_mode))
        snprintf(why, sizeof why, "it is a directory");
    else
        return;
    char alt[GLIB_PATH_MAX];
    if (case_match(path, alt) && access(alt, R_OK) == 0 && stat(alt, &st) == 0 &&
        !S_ISDIR(st.st_mode)) {
        cwarn(c, "%s: '%s' is '%s' on disk; using it (file names are case-sensitive here, "
                 "not on Windows where glman ran)", c->spec->name, path, alt);
        memcpy(path, alt, strlen(alt) + 1);
        return;
    }
    cerr(c, "cannot open '%s' (from command %s): %s", path, c->spec->name, why);
}

/* Resolves and checks a path; false only when it cannot be stored. A file
 * that is missing now keeps its command: it may appear before the render. */
static bool take_path(cmdctx *c, const char *word, char out[GLIB_PATH_MAX]) {
    if (!resolve_path(c, word, out))
        return false;
    check_readable(c, out);
    return true;
}

/* ------------------------------------------------------------------ */
/* files, shaders, textures, passes                                    */

static const char path_hint[] = " (quote a path that has spaces: \"my file.png\")";

static bool h_stage(cmdctx *c, glib_cmd *cmd) {
    warn_extra(c, 1, path_hint);
    if (c->nwords == 0)
        return true;            /* no file: unset the stage */
    return take_path(c, c->words[0], cmd->path);
}

static bool h_obj(cmdctx *c, glib_cmd *cmd) {
    if (c->nwords < 1) {
        cerr(c, "%s needs a file: %s", c->spec->name, c->usage);
        return false;
    }
    warn_extra(c, 1, path_hint);
    return take_path(c, c->words[0], cmd->path);
}

static bool parse_format(cmdctx *c, const char *w, glib_target_format *f) {
    static const struct { const char *word; glib_target_format f; } formats[] = {
        { "float", GLIB_TARGET_RGBA32F }, { "float32", GLIB_TARGET_RGBA32F },
        { "float16", GLIB_TARGET_RGBA16F }, { "half", GLIB_TARGET_RGBA16F },
        { "depth", GLIB_TARGET_DEPTH }, { "rgba8", GLIB_TARGET_RGBA8 },
    };
    for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++)
        if (strcasecmp(w, formats[i].word) == 0)
            return *f = formats[i].f, true;
    cerr(c, "Texture2D: unknown format '%.40s': write float, float16 or depth, or nothing for 8-bit RGBA",
         w);
    return false;
}

static bool parse_sizes(cmdctx *c, glib_cmd *cmd, int count, double max) {
    static const char *const syms[] = { "w", "h", "d" };
    for (int i = 0; i < count; i++) {
        arg_rule r = { syms[i], NULL, 'i', 1, max, 0 };
        if (!parse_arg(c, &r, c->words[1 + i], &cmd->num[1 + i]))
            return false;
    }
    cmd->nnum = 1 + count;
    return true;
}

/* A name where a number may stand (a uniform whose value the renderer
 * reads): into dst, with an error if it does not fit. */
static bool take_uniform_name(cmdctx *c, const char *what, const char *w, char *dst, size_t size) {
    if (strlen(w) >= size) {
        cerr(c, "%s: the uniform name '%.40s...' is too long", what, w);
        return false;
    }
    snprintf(dst, size, "%s", w);
    return true;
}

/* The w and h of an empty Texture2D: each a number, or the name of a
 * slider of a Program of this glib (kept in cmd->name and cmd->arg; the
 * renderer sizes the target from the slider's value, num 0 until then). */
static bool parse_target_size(cmdctx *c, glib_cmd *cmd) {
    static const char *const syms[] = { "w", "h" };
    char *names[] = { cmd->name, cmd->arg };
    for (int i = 0; i < 2; i++) {
        const char *w = c->words[1 + i];
        if (is_ident(w)) {
            if (!take_uniform_name(c, "Texture2D", w, names[i], GLIB_NAME_MAX))
                return false;
            cmd->num[1 + i] = 0;
            continue;
        }
        arg_rule r = { syms[i], NULL, 'i', 1, 16384, 0 };
        if (!parse_arg(c, &r, w, &cmd->num[1 + i]))
            return false;
    }
    cmd->nnum = 3;
    return true;
}

/* Texture2D unit file | Texture2D unit w h [format]: a size after the
 * unit means an empty render target. */
static bool h_tex2d(cmdctx *c, glib_cmd *cmd) {
    if (c->nwords < 2) {
        cerr(c, "Texture2D needs a unit and a file, or a unit and a size: %s", c->usage);
        return false;
    }
    if (!parse_arg(c, &unit_rule, c->words[0], &cmd->num[0]))
        return false;
    cmd->nnum = 1;
    if (c->words[1][0] == '@') {       /* a texture tarn generates: not a file */
        warn_extra(c, 2, "");
        static const char *const known[] = { "@caustics", "@foam", "@water_normal", "@terrain_normal" };
        for (size_t i = 0; i < sizeof known / sizeof known[0]; i++)
            if (strcmp(c->words[1], known[i]) == 0) {
                snprintf(cmd->path, sizeof cmd->path, "%s", known[i]);
                return true;
            }
        cerr(c, "Texture2D: unknown generated texture '%.40s': write @caustics, @foam, "
                "@water_normal or @terrain_normal", c->words[1]);
        return false;
    }
    /* a size is a number or the name of a slider (`Texture2D 4 uRes uRes`);
     * a single word that is no number is a file */
    bool sized = is_decimal(c->words[1]) ||
                 (c->nwords >= 3 && is_ident(c->words[1]) && (is_ident(c->words[2]) || is_decimal(c->words[2])));
    if (!sized) {
        warn_extra(c, 2, path_hint);
        return take_path(c, c->words[1], cmd->path);
    }
    if (c->nwords < 3) {
        cerr(c, "Texture2D: an empty texture needs a width and a height: %s", c->usage);
        return false;
    }
    cmd->kind = GLIB_CMD_TEXTURE2D_EMPTY;
    warn_extra(c, 4, "");
    if (!parse_target_size(c, cmd))
        return false;
    return c->nwords < 4 || parse_format(c, c->words[3], &cmd->format);
}

static bool h_tex3d(cmdctx *c, glib_cmd *cmd) {
    if (c->nwords < 2) {
        cerr(c, "Texture3D needs a unit and a file, or a unit and a size: %s", c->usage);
        return false;
    }
    if (!parse_arg(c, &unit_rule, c->words[0], &cmd->num[0]))
        return false;
    cmd->nnum = 1;
    if (!is_decimal(c->words[1])) {
        warn_extra(c, 2, path_hint);
        return take_path(c, c->words[1], cmd->path);
    }
    if (c->nwords < 4) {
        cerr(c, "Texture3D: an empty texture needs a width, a height and a depth: %s", c->usage);
        return false;
    }
    warn_extra(c, 4, "");
    return parse_sizes(c, cmd, 3, 2048);
}

static bool h_cube(cmdctx *c, glib_cmd *cmd) {
    if (c->nwords < 7) {
        cerr(c, "CubeMap needs a unit and 6 files, got %d file%s: %s",
             c->nwords ? c->nwords - 1 : 0, c->nwords == 2 ? "" : "s", c->usage);
        return false;
    }
    warn_extra(c, 7, path_hint);
    if (!parse_arg(c, &unit_rule, c->words[0], &cmd->num[0]))
        return false;
    cmd->nnum = 1;
    cmd->cube_paths = mem_alloc(6 * sizeof *cmd->cube_paths);
    for (int i = 0; i < 6; i++)
        if (!take_path(c, c->words[1 + i], cmd->cube_paths[i]))
            return false;
    return true;
}

static bool h_rtt(cmdctx *c, glib_cmd *cmd) {
    warn_extra(c, GLIB_MAX_UNITS, "");
    int n = c->nwords < GLIB_MAX_UNITS ? c->nwords : GLIB_MAX_UNITS;
    for (int i = 0; i < n; i++) {
        if (!parse_arg(c, &unit_rule, c->words[i], &cmd->num[i]))
            return false;
        for (int j = 0; j < i; j++)
            if (cmd->num[j] == cmd->num[i])
                cwarn(c, "RenderToTexture: unit %g is listed twice", cmd->num[i]);
    }
    cmd->nnum = n;
    return true;
}

/* Clamp: real files write it (with or without words after it) before a
 * draw; glman took it as a texture wrap state. It is kept as a command
 * that changes nothing, never an error. */
static bool h_clamp(cmdctx *c, glib_cmd *cmd) {
    (void)c;
    (void)cmd;
    return true;
}

/* MessageBox text: glman pops the text up; tarn prints it as a note. */
static bool h_message(cmdctx *c, glib_cmd *cmd) {
    (void)cmd;
    char *s = skip_space(c->rest);
    size_t n = strlen(s);
    if (n >= 2 && s[0] == '"' && s[n - 1] == '"') {
        s[n - 1] = '\0';
        s++;
    }
    vdiag_note(c, s);
    return false;               /* nothing to run */
}

/* ------------------------------------------------------------------ */
/* immediate mode: glBegin mode, glVertex x y z [w] ..., glEnd          */

/* The primitives glBegin takes, as glman passed them to OpenGL. */
static const char *const begin_modes[] = {
    "gl_points", "gl_lines", "gl_line_strip", "gl_line_loop", "gl_triangles",
    "gl_triangle_strip", "gl_triangle_fan", "gl_quads", "gl_lines_adjacency",
    "gl_triangles_adjacency", "gl_patches",
};

static bool h_begin(cmdctx *c, glib_cmd *cmd) {
    parser *p = c->p;
    if (p->begin_file) {
        cerr(c, "glBegin inside the glBegin of %s:%d: end that one with glEnd first", p->begin_file,
             p->begin_line);
        return false;
    }
    if (c->nwords < 1) {
        cerr(c, "glBegin needs a primitive, e.g. glBegin gl_patches: %s", c->usage);
        return false;
    }
    warn_extra(c, 1, "");
    for (size_t i = 0; i < sizeof begin_modes / sizeof begin_modes[0]; i++)
        if (strcasecmp(c->words[0], begin_modes[i]) == 0) {
            snprintf(cmd->name, sizeof cmd->name, "%s", begin_modes[i]);
            p->begin_file = c->file;
            p->begin_line = c->line;
            p->begin_nverts = 0;
            return true;
        }
    cerr(c, "glBegin: unknown primitive '%.40s': write gl_patches, gl_triangles, gl_lines, gl_points, "
            "gl_lines_adjacency, gl_triangles_adjacency, gl_line_strip, gl_triangle_strip, ...", c->words[0]);
    return false;
}

static bool h_vertex(cmdctx *c, glib_cmd *cmd) {
    if (!c->p->begin_file) {
        cwarn(c, "glVertex outside glBegin ... glEnd draws nothing (skipped): put it after a glBegin line");
        return false;
    }
    if (!h_nums(c, cmd))
        return false;
    if (cmd->num[3] != 1)
        cwarn(c, "glVertex: w = %g is not passed on; tarn draws the point x y z with w = 1", cmd->num[3]);
    c->p->begin_nverts++;
    return true;
}

static bool h_end(cmdctx *c, glib_cmd *cmd) {
    (void)cmd;
    parser *p = c->p;
    warn_extra(c, 0, "");
    if (!p->begin_file) {
        cwarn(c, "glEnd without a glBegin (skipped)");
        return false;
    }
    if (p->begin_nverts == 0)
        cwarn(c, "glBegin (line %d) ... glEnd has no glVertex: it draws nothing", p->begin_line);
    p->begin_file = NULL;
    return true;
}

/* ------------------------------------------------------------------ */
/* keyword commands (our extensions)                                   */

typedef struct keyword { const char *word; const char *canon; double value; } keyword;

static const keyword *find_keyword(cmdctx *c, const keyword *k, size_t n, const char *choices) {
    if (c->nwords < 1) {
        cerr(c, "%s needs one of %s: %s", c->spec->name, choices, c->usage);
        return NULL;
    }
    warn_extra(c, 1, "");
    for (size_t i = 0; i < n; i++)
        if (strcasecmp(c->words[0], k[i].word) == 0)
            return &k[i];
    cerr(c, "%s: unknown mode '%.40s': write %s", c->spec->name, c->words[0], choices);
    return NULL;
}

static bool h_cull(cmdctx *c, glib_cmd *cmd) {
    static const keyword k[] = {
        { "back", "back", 0 }, { "front", "front", 0 }, { "none", "none", 0 }, { "off", "none", 0 },
    };
    const keyword *m = find_keyword(c, k, sizeof k / sizeof k[0], "back, front or none");
    if (m)
        snprintf(cmd->name, sizeof cmd->name, "%s", m->canon);
    return m != NULL;
}

static bool h_blend(cmdctx *c, glib_cmd *cmd) {
    static const keyword k[] = {
        { "off", "off", 0 }, { "none", "off", 0 }, { "alpha", "alpha", 0 }, { "add", "add", 0 },
        { "premultiplied", "premultiplied", 0 },
    };
    const keyword *m = find_keyword(c, k, sizeof k / sizeof k[0], "off, alpha, premultiplied or add");
    if (m)
        snprintf(cmd->name, sizeof cmd->name, "%s", m->canon);
    return m != NULL;
}

static bool h_depth(cmdctx *c, glib_cmd *cmd) {
    static const keyword k[] = {
        { "on", "on", 1 }, { "off", "off", 0 }, { "1", "on", 1 }, { "0", "off", 0 },
        { "true", "on", 1 }, { "false", "off", 0 },
    };
    const keyword *m = find_keyword(c, k, sizeof k / sizeof k[0], "on or off");
    if (!m)
        return false;
    cmd->num[0] = m->value;
    cmd->nnum = 1;
    snprintf(cmd->name, sizeof cmd->name, "%s", m->canon);
    return true;
}

/* ------------------------------------------------------------------ */
/* describing the world (our extensions; docs/glib.md)                 */

/* These commands keep nnum = the numbers written: what is left out takes
 * the world model's default (ref_world_init), which lives in one place.
 * Here only the form is checked (numbers, whole numbers, counts); ranges
 * are repaired by scene_from_glib, with a message, so a slider-happy user
 * never loses the scene to one absurd value. */

/* Reads the numbers words[w0..] by rules[0..]; nreq..nmax of them. */
static bool nums_from(cmdctx *c, glib_cmd *cmd, int w0, const arg_rule *rules, int nreq,
                      int nmax, const char *what) {
    int have = c->nwords - w0;
    if (have < nreq) {
        if (nreq - have == 1 && rules[have].what)
            cerr(c, "%s needs %s: %s", what, rules[have].what, c->usage);
        else
            cerr(c, "%s needs %s%d numbers, got %d: %s", what, nreq < nmax ? "at least " : "",
                 nreq, have < 0 ? 0 : have, c->usage);
        return false;
    }
    warn_extra(c, w0 + nmax, "");
    int given = have < nmax ? have : nmax;
    for (int i = 0; i < given; i++)
        if (!parse_arg(c, &rules[i], c->words[w0 + i], &cmd->num[i]))
            return false;
    cmd->nnum = given;
    return true;
}

/* Sun, Sky, Water, WaterMesh, Wave*: numbers only, nnum as written. */
static bool h_world_nums(cmdctx *c, glib_cmd *cmd) {
    const cmd_spec *s = c->spec;
    if (!nums_from(c, cmd, 0, s->args, s->nreq, s->nmax, s->name))
        return false;
    const double *n = cmd->num;
    int given = cmd->nnum;
    if (cmd->kind == GLIB_CMD_SUN && given != 3 && given != 6) {
        cerr(c, "Sun: the irradiance needs 3 numbers (r g b), got %d: %s", given - 3, c->usage);
        return false;
    }
    if (cmd->kind == GLIB_CMD_SUN && n[0] == 0 && n[1] == 0 && n[2] == 0) {
        cerr(c, "Sun: the direction is zero; write the direction towards the sun, e.g. Sun 0.4 0.8 -0.45");
        return false;
    }
    if (cmd->kind == GLIB_CMD_WATER && given > 2 && given != 5) {
        cerr(c, "Water: the absorption needs 3 numbers (ar ag ab), got %d: %s", given - 2, c->usage);
        return false;
    }
    return true;
}

/* The first word is a mode from k; its canonical word goes to cmd->name. */
static const keyword *mode_word(cmdctx *c, const keyword *k, size_t n, const char *choices) {
    if (c->nwords < 1) {
        cerr(c, "%s needs one of %s: %s", c->spec->name, choices, c->usage);
        return NULL;
    }
    for (size_t i = 0; i < n; i++)
        if (strcasecmp(c->words[0], k[i].word) == 0)
            return &k[i];
    cerr(c, "%s: unknown kind '%.40s': write %s", c->spec->name, c->words[0], choices);
    return NULL;
}

#define SEED_RULE(s) { s, NULL, 'i', 0, 4294967295.0, 0 }
#define RES_RULE(s) { s, NULL, 'i', 0, 65536, 0 }

static bool h_terrain(cmdctx *c, glib_cmd *cmd) {
    static const keyword k[] = { { "flat", "flat", 0 }, { "lake", "lake", 1 }, { "slope", "slope", 2 },
                                 { "pool", "pool", 3 } };
    static const arg_rule rules[] = {
        { "half_size", NULL, 'r', 0, 0, 0 }, { "depth", NULL, 'r', 0, 0, 0 },
        { "shore_height_or_slope", NULL, 'r', 0, 0, 0 }, SEED_RULE("seed"), RES_RULE("res"),
    };
    const keyword *m = mode_word(c, k, sizeof k / sizeof k[0], "flat, lake, slope or pool");
    if (!m)
        return false;
    snprintf(cmd->name, sizeof cmd->name, "%s", m->canon);
    return nums_from(c, cmd, 1, rules, 0, 5, "Terrain");
}

static bool h_wave_ocean(cmdctx *c, glib_cmd *cmd) {
    static const keyword k[] = { { "phillips", "phillips", 1 }, { "jonswap", "jonswap", 2 },
                                 { "tma", "tma", 3 } };
    static const arg_rule rules[] = {
        { "wind_speed", "a wind speed in m/s", 'r', 0, 0, 0 }, { "wind_angle_deg", NULL, 'r', 0, 0, 0 },
        { "choppiness", NULL, 'r', 0, 0, 0 }, { "res", NULL, 'i', 0, 65536, 0 }, SEED_RULE("seed"),
        { "fetch", NULL, 'r', 0, 0, 0 }, { "depth", NULL, 'r', 0, 0, 0 },
        { "spreading", NULL, 'r', 0, 0, 0 }, { "amplitude", NULL, 'r', 0, 0, 0 },
    };
    const keyword *m = mode_word(c, k, sizeof k / sizeof k[0], "phillips, jonswap or tma");
    if (!m)
        return false;
    snprintf(cmd->name, sizeof cmd->name, "%s", m->canon);
    return nums_from(c, cmd, 1, rules, 1, 9, "WaveOcean");
}

/* Object mesh FILE x y z [rot_y_deg [scale [R G B]]] (issue #25): the
 * file resolved like Obj's, the numbers as written (nnum 3 to 8). */
static bool object_mesh(cmdctx *c, glib_cmd *cmd) {
    static const arg_rule rules[8] = {
        { "x", NULL, 'r', 0, 0, 0 }, { "y", NULL, 'r', 0, 0, 0 }, { "z", NULL, 'r', 0, 0, 0 },
        { "rot_y_deg", NULL, 'r', 0, 0, 0 }, { "scale", NULL, 'r', 0, 0, 0 },
        { "R", NULL, 'r', 0, 0, 0 }, { "G", NULL, 'r', 0, 0, 0 }, { "B", NULL, 'r', 0, 0, 0 },
    };
    snprintf(c->usage, sizeof c->usage, "Object mesh file.obj x y z [rot_y_deg [scale [R G B]]]");
    snprintf(cmd->name, sizeof cmd->name, "mesh");
    if (c->nwords < 2) {
        cerr(c, "Object mesh needs a file: %s", c->usage);
        return false;
    }
    if (!take_path(c, c->words[1], cmd->path))
        return false;
    if (!nums_from(c, cmd, 2, rules, 3, 8, "Object mesh"))
        return false;
    if (cmd->nnum > 5 && cmd->nnum < 8) {
        cerr(c, "Object mesh: the colour needs 3 numbers (R G B), got %d: %s", cmd->nnum - 5, c->usage);
        return false;
    }
    return true;
}

static bool h_object(cmdctx *c, glib_cmd *cmd) {
    static const keyword k[] = { { "sphere", "sphere", 7 }, { "box", "box", 9 },
                                 { "cylinder", "cylinder", 8 } };
    static const char *const syms[3][9] = {
        { "x", "y", "z", "r", "R", "G", "B" },
        { "x", "y", "z", "hx", "hy", "hz", "R", "G", "B" },
        { "x", "y", "z", "r", "h", "R", "G", "B" },
    };
    if (c->nwords >= 1 && strcasecmp(c->words[0], "mesh") == 0)
        return object_mesh(c, cmd);
    const keyword *m = mode_word(c, k, sizeof k / sizeof k[0], "sphere, box, cylinder or mesh");
    if (!m)
        return false;
    int which = (int)(m - k), n = (int)m->value;
    arg_rule rules[9];
    char what[64], usage[96];
    size_t u = (size_t)snprintf(usage, sizeof usage, "Object %s", m->canon);
    for (int i = 0; i < n; i++) {
        rules[i] = (arg_rule){ syms[which][i], NULL, 'r', 0, 0, 0 };
        u += (size_t)snprintf(usage + u, sizeof usage - u, " %s", syms[which][i]);
    }
    snprintf(what, sizeof what, "Object %s", m->canon);
    snprintf(cmd->name, sizeof cmd->name, "%s", m->canon);
    snprintf(c->usage, sizeof c->usage, "%s", usage);   /* the usage of this kind */
    return nums_from(c, cmd, 1, rules, n, n, what);
}

/* Flow: one term of the flow field (its velocities add), or the look of
 * the detail it carries; the numbers each kind takes, as Object's. */
static bool h_flow(cmdctx *c, glib_cmd *cmd) {
    static const keyword k[] = { { "current", "current", 2 }, { "vortex", "vortex", 4 },
                                 { "detail", "detail", 4 } };
    static const arg_rule rules[3][4] = {
        { { "vx", "a speed vx (m/s)", 'r', 0, 0, 0 }, { "vz", "a speed vz (m/s)", 'r', 0, 0, 0 } },
        { { "x", NULL, 'r', 0, 0, 0 }, { "z", NULL, 'r', 0, 0, 0 }, { "strength", "a speed (m/s)", 'r', 0, 0, 0 },
          { "radius", "a radius (m)", 'r', 0, 0, 0 } },
        { { "amplitude", "an amplitude (m)", 'r', 0, 0, 0 }, { "cell", NULL, 'r', 0, 0, 0 },
          { "period", NULL, 'r', 0, 0, 0 }, { "foam", NULL, 'r', 0, 0, 0 } },
    };
    static const char *const usages[3] = { "Flow current vx vz", "Flow vortex x z strength radius",
                                           "Flow detail amplitude [cell [period [foam]]]" };
    static const arg_rule scale_rule = { "scale", "a speed scale (m/s)", 'r', 0, 0, 0 };
    if (c->nwords >= 1 && strcasecmp(c->words[0], "texture") == 0) {   /* Flow texture file scale */
        snprintf(cmd->name, sizeof cmd->name, "texture");
        snprintf(c->usage, sizeof c->usage, "Flow texture file scale");
        if (c->nwords < 3) {
            cerr(c, "Flow texture needs a file and a scale: %s", c->usage);
            return false;
        }
        return take_path(c, c->words[1], cmd->path) && nums_from(c, cmd, 2, &scale_rule, 1, 1, "Flow texture");
    }
    const keyword *m = mode_word(c, k, sizeof k / sizeof k[0], "current, vortex, texture or detail");
    if (!m)
        return false;
    int which = (int)(m - k), n = (int)m->value;
    char what[32];
    snprintf(what, sizeof what, "Flow %s", m->canon);
    snprintf(cmd->name, sizeof cmd->name, "%s", m->canon);
    snprintf(c->usage, sizeof c->usage, "%s", usages[which]);
    return nums_from(c, cmd, 1, rules[which], which == 2 ? 1 : n, n, what);
}

static bool h_world(cmdctx *c, glib_cmd *cmd) {
    static const arg_rule offset_rule = { "offset", "a clip offset", 'r', 0, 0, 0 };
    static const char *const modes[] = { "all", "above", "below" };
    snprintf(cmd->name, sizeof cmd->name, "all");
    if (c->nwords == 0)
        return true;
    size_t m = 0;
    while (m < 3 && strcasecmp(c->words[0], modes[m]) != 0)
        m++;
    if (m == 3) {
        cerr(c, "World: unknown mode '%.40s': write World all|above|below [offset]", c->words[0]);
        return false;
    }
    snprintf(cmd->name, sizeof cmd->name, "%s", modes[m]);
    warn_extra(c, 2, "");
    if (c->nwords < 2)
        return true;
    const char *w = c->words[1];
    if (isalpha((unsigned char)w[0]) || w[0] == '_') {   /* a float slider of the last Program */
        return take_uniform_name(c, "World", w, cmd->arg, sizeof cmd->arg);
    }
    if (!parse_arg(c, &offset_rule, w, &cmd->num[0]))
        return false;
    cmd->nnum = 1;
    return true;
}

/* Camera main|mirror|top|light [fov_scale | uniform] */
static bool h_camera(cmdctx *c, glib_cmd *cmd) {
    static const arg_rule scale_rule = { "fov_scale", "a field-of-view scale", 'p', 0, 0, 0 };
    static const char *const kinds[] = { "main", "wide", "mirror", "top", "light" };
    if (c->nwords < 1) {
        cerr(c, "Camera needs main, wide, mirror, top or light: %s", c->usage);
        return false;
    }
    size_t k = 0;
    while (k < 5 && strcasecmp(c->words[0], kinds[k]) != 0)
        k++;
    if (k == 5) {
        cerr(c, "Camera: unknown camera '%.40s': write main, wide, mirror, top or light", c->words[0]);
        return false;
    }
    snprintf(cmd->name, sizeof cmd->name, "%s", kinds[k]);
    warn_extra(c, 2, "");
    if (c->nwords < 2)
        return true;
    const char *w = c->words[1];
    if (isalpha((unsigned char)w[0]) || w[0] == '_') {
        return take_uniform_name(c, "Camera", w, cmd->arg, sizeof cmd->arg);
    }
    if (!parse_arg(c, &scale_rule, w, &cmd->num[0]))
        return false;
    cmd->nnum = 1;
    return true;
}

/* If [not] NAME: a block the renderer skips while NAME is false */
static bool h_if(cmdctx *c, glib_cmd *cmd) {
    int w = 0;
    if (c->nwords >= 1 && strcasecmp(c->words[0], "not") == 0) {
        cmd->num[0] = 1;
        cmd->nnum = 1;
        w = 1;
    }
    if (c->nwords <= w) {
        cerr(c, "If needs a condition: %s", c->usage);
        return false;
    }
    warn_extra(c, w + 1, "");
    const char *name = c->words[w];
    if (!(isalpha((unsigned char)name[0]) || name[0] == '_') || strlen(name) >= sizeof cmd->name) {
        cerr(c, "If: '%.40s' is not a condition: write a Define name, above_water, under_water or waves", name);
        return false;
    }
    snprintf(cmd->name, sizeof cmd->name, "%s", name);
    return true;
}

/* WaterSurface [points|mesh N|uniform] */
static bool h_water_surface(cmdctx *c, glib_cmd *cmd) {
    static const arg_rule n_rule = { "N", "a point count per side", 'i', 1, 4096, 0 };
    if (c->nwords == 0)
        return true;
    bool points = strcasecmp(c->words[0], "points") == 0, mesh = strcasecmp(c->words[0], "mesh") == 0;
    if (!(points || mesh) || c->nwords < 2) {
        cerr(c, "WaterSurface: write WaterSurface, WaterSurface points N or WaterSurface mesh N");
        return false;
    }
    warn_extra(c, 2, "");
    snprintf(cmd->name, sizeof cmd->name, "%s", points ? "points" : "mesh");
    if (is_ident(c->words[1]))   /* N from a slider: `WaterSurface points uPhotonGrid` */
        return take_uniform_name(c, "WaterSurface", c->words[1], cmd->arg, sizeof cmd->arg);
    if (!parse_arg(c, &n_rule, c->words[1], &cmd->num[0]))
        return false;
    cmd->nnum = 1;
    return true;
}

/* ---- Pack: a scene names the pack that draws its water ---- */

static void push_cmd(parser *p, glib_cmd *cmd);
static void include_file(cmdctx *c, const char *path);
static void append_cut(char *buf, size_t size, size_t *n, const char *s);
static int edit_distance(const char *a, const char *b);

/* A directory name under packs/: no path separators, no leading dot. */
static bool is_pack_name(const char *s) {
    if (!*s || *s == '.' || strlen(s) >= GLIB_NAME_MAX)
        return false;
    for (; *s; s++)
        if (!isalnum((unsigned char)*s) && *s != '_' && *s != '-' && *s != '.')
            return false;
    return true;
}

static int cmp_str(const void *a, const void *b) {
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* "basic, natural, raymarch" (the directories of dir holding a pack.glib)
 * into out, and the one closest to name into near (or ""). */
static void list_packs(const char *dir, const char *name, char *out, size_t outlen,
                       char near[GLIB_NAME_MAX]) {
    enum { MAXP = 64 };
    char *names[MAXP];
    int n = 0;
    out[0] = near[0] = '\0';
    DIR *d = opendir(dir);
    struct dirent *e;
    while (d && n < MAXP && (e = readdir(d)) != NULL) {
        char path[GLIB_PATH_MAX];
        struct stat st;
        if (!is_pack_name(e->d_name) ||
            snprintf(path, sizeof path, "%s/%s/pack.glib", dir, e->d_name) >= (int)sizeof path)
            continue;
        if (stat(path, &st) == 0 && S_ISREG(st.st_mode))
            names[n++] = mem_strdup(e->d_name);
    }
    if (d)
        closedir(d);
    qsort(names, (size_t)n, sizeof names[0], cmp_str);
    size_t len = 0;
    int best = 3;
    for (int i = 0; i < n; i++) {
        append_cut(out, outlen, &len, i ? ", " : "");
        append_cut(out, outlen, &len, names[i]);
        int dist = edit_distance(name, names[i]);
        if (dist < best) {
            best = dist;
            snprintf(near, GLIB_NAME_MAX, "%s", names[i]);
        }
        free(names[i]);
    }
}

/* The scene's pack is `name` (or the override): records the command and,
 * with a packs directory, reads the pack's pack.glib in place. */
static void use_pack(cmdctx *c, glib_cmd *cmd, const char *written) {
    parser *p = c->p;
    const char *name = p->pack_override ? p->pack_override : written;
    if (!is_pack_name(name)) {
        cerr(c, "Pack: '%.60s'%s is not a pack name: write the name of a directory under packs/, e.g. Pack basic",
             name, p->pack_override ? " (the pack chosen instead of the scene's)" : "");
        return;
    }
    p->pack_seen = true;
    p->pack_file = c->file;
    p->pack_line = c->line;
    snprintf(p->pack_name, sizeof p->pack_name, "%s", name);
    snprintf(cmd->name, sizeof cmd->name, "%s", name);
    push_cmd(p, cmd);
    memset(cmd, 0, sizeof *cmd);        /* pushed: the caller frees nothing */
    if (!p->packs_dir || p->stop)
        return;
    char path[GLIB_PATH_MAX];
    if (snprintf(path, sizeof path, "%s/%s/pack.glib", p->packs_dir, name) >= (int)sizeof path) {
        cerr(c, "Pack %s: the path of its pack.glib is too long (at most %d characters)", name,
             GLIB_PATH_MAX - 1);
        return;
    }
    struct stat st;
    if (stat(path, &st) != 0 || !S_ISREG(st.st_mode)) {
        char packs[160], near[GLIB_NAME_MAX], hint[GLIB_NAME_MAX + 24] = "";
        list_packs(p->packs_dir, name, packs, sizeof packs, near);
        if (near[0])
            snprintf(hint, sizeof hint, "; did you mean '%s'?", near);
        cerr(c, "Pack: no pack '%s' in %s (no %s/pack.glib); the packs are: %s%s", name,
             p->packs_dir, name, packs[0] ? packs : "(none)", hint);
        return;
    }
    include_file(c, path);
}

static bool h_pack(cmdctx *c, glib_cmd *cmd) {
    parser *p = c->p;
    if (c->nwords < 1) {
        cerr(c, "Pack needs a name: %s", c->usage);
        return false;
    }
    warn_extra(c, 1, "");
    if (p->pack_seen) {
        cwarn(c, "Pack %.60s ignored: this scene's pack is already '%s' (%s:%d); a scene has one pack",
              c->words[0], p->pack_name, p->pack_file, p->pack_line);
        return false;
    }
    use_pack(c, cmd, c->words[0]);
    return false;               /* pushed by use_pack, before the pack's commands */
}

/* ------------------------------------------------------------------ */
/* uniform values: 5  [a b c]  <min default max>  <true>  {r g b a}     */

typedef enum { VAL_OK, VAL_BAD, VAL_STOP } val_result;

static const char *bracket_example(char open) {
    return open == '<' ? "<min default max> or <true>"
         : open == '{' ? "{r g b} or {r g b a}" : "[a b c]";
}

static val_result bracket_numbers(cmdctx *c, char **items, int n, unif_decl *u,
                                  const char *owner) {
    for (int i = 0; i < n; i++)
        if (!read_number(c, items[i], &u->v[i])) {
            cerr(c, "%s: bad number '%.60s' (write e.g. 2, -0.5, .25 or 1e-3)", owner, items[i]);
            return VAL_BAD;
        }
    u->n = n;
    return VAL_OK;
}

static val_result slider_value(cmdctx *c, unif_decl *u, const char *owner) {
    double *v = u->v;
    if (v[0] > v[2]) {
        cerr(c, "%s: slider minimum %g is greater than its maximum %g: write <min default max>",
             owner, v[0], v[2]);
        return VAL_BAD;
    }
    if (v[1] < v[0] || v[1] > v[2]) {
        double d = v[1] < v[0] ? v[0] : v[2];
        cwarn(c, "%s: default %g is outside <%g .. %g>; using %g", owner, v[1], v[0], v[2], d);
        v[1] = d;
    }
    return VAL_OK;
}

static val_result typed_bracket(cmdctx *c, char open, char **items, int n,
                                unif_decl *u, const char *owner) {
    /* <true>, <false>, and glman's <0> / <1> (nonzero: checked) */
    if (open == '<' && n == 1 &&
        (is_bool_word(items[0], &u->v[0]) || read_number(c, items[0], &u->v[0]))) {
        u->v[0] = u->v[0] != 0;
        u->kind = UNIF_DECL_BOOL;
        u->n = 1;
        return VAL_OK;
    }
    int lo = open == '<' ? 3 : open == '{' ? 3 : 1;
    int hi = open == '<' ? 3 : open == '{' ? 4 : GLIB_MAX_NUMS;
    if (n < lo || n > hi) {
        const char *need = open == '<' ? "3 numbers <min default max> or <true>/<false>"
                         : open == '{' ? "3 or 4 numbers {r g b [a]}" : "1 to 16 numbers [a b c]";
        cerr(c, "%s: %c%c needs %s, got %d", owner, open, closer_of(open), need, n);
        return VAL_BAD;
    }
    u->kind = open == '<' ? UNIF_DECL_SLIDER
            : open == '{' ? UNIF_DECL_COLOR : UNIF_DECL_ARRAY;
    val_result r = bracket_numbers(c, items, n, u, owner);
    if (r == VAL_OK && u->kind == UNIF_DECL_SLIDER)
        r = slider_value(c, u, owner);
    return r;
}

/* A slider with more than three numbers (`< 0,01 0.1 1.0 >`: a comma for
 * a decimal point). glman split the bracket on blanks only and read each
 * word with atof, so "0,01" was 0 and the slider <0 0.1 1.0>; with four
 * or more blank-separated words it used the first three. So does tarn,
 * with a warning. False when the words are not numbers at all. */
static bool slider_glman_words(cmdctx *c, char *raw, unif_decl *u, const char *owner) {
    char *w[GLIB_MAX_NUMS];
    int n = 0;
    for (char *save = NULL, *t = strtok_r(raw, " \t", &save); t && n < GLIB_MAX_NUMS; t = strtok_r(NULL, " \t", &save))
        w[n++] = t;
    if (n < 3)
        return false;
    for (int i = 0; i < 3; i++) {
        char *end;
        u->v[i] = strtod(w[i], &end);
        if (end == w[i])
            return false;
    }
    u->kind = UNIF_DECL_SLIDER;
    u->n = 3;
    char extra[160] = "";
    size_t len = 0;
    for (int i = 3; i < n && len < sizeof extra; i++)
        len += (size_t)snprintf(extra + len, sizeof extra - len, " %s", w[i]);
    cwarn(c, "%s: a slider has more than 3 numbers (%s %s %s%s); glman read its words with atof and used "
          "<%g %g %g>: write <min default max> with a '.' for the decimal point", owner, w[0], w[1], w[2], extra,
          u->v[0], u->v[1], u->v[2]);
    return true;
}

/* A bracketed value at *sp. An unclosed bracket ends the line: nothing
 * after it can be told apart from the bracket's contents. */
static val_result read_bracket(cmdctx *c, char **sp, unif_decl *u, const char *owner) {
    char *s = *sp;
    char open = *s, close = closer_of(open);
    char *e = s + 1;
    while (*e && *e != close && !is_opener(*e) && !is_closer(*e))
        e++;
    if (*e != close) {
        if (*e)
            cerr(c, "%s: '%c' is not closed before '%c': write %s", owner, open, *e,
                 bracket_example(open));
        else
            cerr(c, "%s: unclosed '%c': add '%c' (%s)", owner, open, close, bracket_example(open));
        *sp = s + strlen(s);
        return VAL_STOP;
    }
    *e = '\0';
    *sp = e + 1;
    char raw[512];
    snprintf(raw, sizeof raw, "%s", s + 1);
    char *items[GLIB_MAX_NUMS];
    int n = split_items(s + 1, items, GLIB_MAX_NUMS);
    if (open == '<' && n > 3 && slider_glman_words(c, raw, u, owner))
        return slider_value(c, u, owner);
    return typed_bracket(c, open, items, n, u, owner);
}

static val_result read_value(cmdctx *c, char **sp, unif_decl *u, const char *owner) {
    char *s = skip_space(*sp);
    if (is_opener(*s)) {
        *sp = s;
        return read_bracket(c, sp, u, owner);
    }
    char *e = s;
    while (*e && !is_space((unsigned char)*e))
        e++;
    *sp = *e ? e + 1 : e;
    *e = '\0';
    double b;
    if (is_closer(*s)) {
        cerr(c, "%s: '%c' closes a bracket that was not opened", owner, *s);
        return VAL_BAD;
    }
    if (is_bool_word(s, &b)) {
        cerr(c, "%s: write <%s> (with the angle brackets) for a checkbox", owner, s);
        return VAL_BAD;
    }
    if (!read_number(c, s, &u->v[0])) {
        cerr(c, "%s: bad number '%.60s' (write e.g. 2, -0.5, .25 or 1e-3)", owner, s);
        return VAL_BAD;
    }
    u->kind = UNIF_DECL_SCALAR;
    u->n = 1;
    return VAL_OK;
}

/* Copies a name at *sp (up to whitespace or a bracket, which may follow
 * with no space: uKa<0 1 2>) into out and checks it is a GLSL identifier. */
static bool take_name(cmdctx *c, char **sp, char out[GLIB_NAME_MAX], const char *what) {
    char *s = *sp, *e = s;
    while (*e && !is_space((unsigned char)*e) && !is_opener(*e))
        e++;
    *sp = e;
    size_t n = (size_t)(e - s);
    if (n >= GLIB_NAME_MAX) {
        cerr(c, "%s name '%.40s...' is too long (at most %d characters)", what, s,
             GLIB_NAME_MAX - 1);
        return false;
    }
    memcpy(out, s, n);
    out[n] = '\0';
    if (!is_ident(out)) {
        cerr(c, "'%s' is not a valid %s name: use letters, digits and _, not starting with a digit",
             out, what);
        return false;
    }
    return true;
}

static void add_uniform(cmdctx *c, glib_cmd *cmd, const unif_decl *u, int *cap) {
    for (int i = 0; i < cmd->nuniforms; i++)
        if (strcmp(cmd->uniforms[i].name, u->name) == 0) {
            cwarn(c, "Program %s: uniform '%s' is given twice; the later value wins",
                  cmd->name, u->name);
            cmd->uniforms[i] = *u;
            return;
        }
    if (cmd->nuniforms >= LIM_PROGRAM_UNIFORMS || c->p->scene_uniforms >= LIM_SCENE_UNIFORMS) {
        cerr(c, "Program %s: too many uniforms (at most %d on one Program); '%s' ignored",
             cmd->name, LIM_PROGRAM_UNIFORMS, u->name);
        return;
    }
    cmd->uniforms = grow(cmd->uniforms, cap, cmd->nuniforms + 1, sizeof *cmd->uniforms);
    cmd->uniforms[cmd->nuniforms++] = *u;
    c->p->scene_uniforms++;
}

static void take_pending_defines(parser *p, glib_cmd *cmd) {
    cmd->defines = p->pending;
    cmd->ndefines = p->npending;
    p->pending = NULL;
    p->npending = p->pending_cap = 0;
}

/* Reads one `name value` pair of a Program line into u; false when the
 * rest of the line cannot be read. *ok says whether u is usable. */
static bool program_uniform(cmdctx *c, glib_cmd *cmd, char **sp, unif_decl *u, bool *ok) {
    char *s = *sp;
    bool named = !is_opener(*s);
    if (!named)
        cerr(c, "Program %s: a value '%c...' has no uniform name before it", cmd->name, *s);
    else
        named = take_name(c, &s, u->name, "uniform");
    s = skip_space(s);
    *sp = s;
    *ok = false;
    if (!*s) {
        if (named)
            cerr(c, "Program %s: uniform '%s' has no value: write %s 5, <min default max>, <true>, [a b c] or {r g b}",
                 cmd->name, u->name, u->name);
        return false;
    }
    char owner[GLIB_NAME_MAX * 2 + 32];
    snprintf(owner, sizeof owner, "Program %s: uniform '%s'", cmd->name, u->name);
    val_result r = read_value(c, sp, u, owner);
    *ok = r == VAL_OK && named;
    return r != VAL_STOP;
}

static bool h_program(cmdctx *c, glib_cmd *cmd) {
    char *s = skip_space(c->rest), *e = s;
    while (*e && !is_space((unsigned char)*e) && !is_opener(*e))
        e++;
    if (e == s) {
        cerr(c, "Program needs a name: %s", c->usage);
        return false;
    }
    if (e - s >= GLIB_NAME_MAX) {
        cerr(c, "Program name '%.40s...' is too long (at most %d characters)", s, GLIB_NAME_MAX - 1);
        return false;
    }
    memcpy(cmd->name, s, (size_t)(e - s));
    /* `Program Cold Giraffe uA <0 1 2>`: glman's name is one word, the
     * rest name/value pairs. A bare word followed by another word that is
     * no value (or by nothing) cannot be a pair: it is more of the name
     * the student wrote. tarn keeps glman's one-word name and skips the
     * rest of it, so the pairs after it line up as they did in glman. */
    for (s = skip_space(e);;) {
        char *we = s;
        while (*we && !is_space((unsigned char)*we) && !is_opener(*we))
            we++;
        if (we == s || is_opener(*we) || !isalpha((unsigned char)*s))
            break;
        char *next = skip_space(we);
        char *ne = next;
        while (*ne && !is_space((unsigned char)*ne) && !is_opener(*ne))
            ne++;
        char *num_end = next;
        if (*next && ne > next)
            (void)strtod(next, &num_end);
        double bv;
        char saved = *ne;
        *ne = '\0';
        bool boolword = *next && is_bool_word(next, &bv);
        *ne = saved;
        bool value_next = is_opener(*next) || (*next && num_end > next) || *next == '.' || *next == '-' || boolword;
        /* a last bare word: a name's word when capitalised (Giraffe), else a
         * uniform without its value (uA), which is an error below */
        if (value_next || (!*next && !isupper((unsigned char)*s)))
            break;
        cwarn(c, "Program %s: '%.*s' read as part of the program's name (glman's name is one word; the "
              "words after it are uniform/value pairs): write the name as one word, e.g. %s_%.*s",
              cmd->name, (int)(we - s), s, cmd->name, (int)(we - s), s);
        s = skip_space(we);
    }
    e = s;
    int cap = 0;
    for (s = skip_space(e); *s; s = skip_space(s)) {
        unif_decl u = { .file = c->file, .line = c->line };
        bool ok;
        bool go_on = program_uniform(c, cmd, &s, &u, &ok);
        if (ok)
            add_uniform(c, cmd, &u, &cap);
        if (!go_on)
            break;
    }
    take_pending_defines(c->p, cmd);
    return true;
}

static void add_pending(cmdctx *c, const unif_decl *u) {
    parser *p = c->p;
    for (int i = 0; i < p->npending; i++)
        if (strcmp(p->pending[i].name, u->name) == 0) {
            cwarn(c, "Define %s is given twice before the next Program; the later one wins", u->name);
            p->pending[i] = *u;
            return;
        }
    p->pending = grow(p->pending, &p->pending_cap, p->npending + 1, sizeof *p->pending);
    p->pending[p->npending++] = *u;
}

/* Define NAME [<true>|<false>|value|<min default max>]: a #define the
 * shaders of the next Program are compiled with (a bare name is <true>). */
static bool h_define(cmdctx *c, glib_cmd *cmd) {
    unif_decl u = { .file = c->file, .line = c->line, .kind = UNIF_DECL_BOOL,
                       .v = { 1 }, .n = 1 };
    char *s = skip_space(c->rest);
    if (!*s) {
        cerr(c, "Define needs a name: %s", c->usage);
        return false;
    }
    if (!take_name(c, &s, u.name, "Define"))
        return false;
    s = skip_space(s);
    if (*s) {
        char owner[GLIB_NAME_MAX + 16];
        snprintf(owner, sizeof owner, "Define %s", u.name);
        if (read_value(c, &s, &u, owner) != VAL_OK)
            return false;
        if (u.kind == UNIF_DECL_ARRAY || u.kind == UNIF_DECL_COLOR) {
            cerr(c, "Define %s takes <true>, <false>, a number or <min default max>, not a list",
                 u.name);
            return false;
        }
        s = skip_space(s);
        if (*s)
            cwarn(c, "Define %s: ignoring '%.40s' after the value", u.name, s);
    }
    memcpy(cmd->name, u.name, sizeof cmd->name);
    cmd->uniforms = mem_alloc(sizeof u);
    cmd->uniforms[0] = u;
    cmd->nuniforms = 1;
    add_pending(c, &u);
    return true;
}

/* ------------------------------------------------------------------ */
/* reading files and lines                                             */

/* Reads a whole regular file of at most LIM_FILE_BYTES into *out (NUL
 * terminated, freed by the caller); on failure *why says why. Its lines, a
 * byte order mark and binary bytes are parse_text's: glib_parse reads text
 * from memory too. */
static bool read_file(const char *path, char **out, size_t *len, char *why, size_t whylen) {
    /* settled: a reload during a save reads the saved text, not a torn or empty one */
    file_text_opts o = { .max_bytes = LIM_FILE_BYTES, .settle = true };
    *out = file_read_text(path, &o, len, why, whylen);
    return *out != NULL;
}

typedef struct reader {
    const char *text;
    size_t len, pos;
    int lineno;
} reader;

/* The next physical line, without its end (\n, \r\n or a lone \r). */
static bool next_phys(reader *r, const char **b, size_t *n) {
    if (r->pos >= r->len)
        return false;
    size_t i = r->pos;
    while (i < r->len && r->text[i] != '\n' && r->text[i] != '\r')
        i++;
    *b = r->text + r->pos;
    *n = i - r->pos;
    if (i + 1 < r->len && r->text[i] == '\r' && r->text[i + 1] == '\n')
        i++;
    r->pos = i + 1;
    r->lineno++;
    return true;
}

/* Where a comment starts in a physical line: `#` or `//` at the start of a
 * word (so a/b//c.png stays a path), not inside "quotes". */
static size_t comment_start(const char *s, size_t n) {
    bool quoted = false;
    for (size_t i = 0; i < n; i++) {
        if (s[i] == '"')
            quoted = !quoted;
        if (quoted)
            continue;
        bool word_start = i == 0 || is_space((unsigned char)s[i - 1]) || is_closer(s[i - 1]);
        if (word_start && (s[i] == '#' || (s[i] == '/' && i + 1 < n && s[i + 1] == '/')))
            return i;
    }
    return n;
}

/* Index of the first byte that cannot be in a text line: a control code
 * (NUL, ...) or broken UTF-8; n when there is none. */
static size_t first_bad_byte(const unsigned char *s, size_t n) {
    size_t i = 0;
    while (i < n) {
        unsigned c = s[i];
        if (c < 0x80) {
            if ((c < 0x20 && !is_space((int)c)) || c == 0x7f)
                return i;
            i++;
            continue;
        }
        size_t extra = c >= 0xc2 && c <= 0xdf ? 1 : c >= 0xe0 && c <= 0xef ? 2
                     : c >= 0xf0 && c <= 0xf4 ? 3 : 0;
        if (!extra || i + extra >= n)   /* not a lead byte, or cut off */
            return i;
        for (size_t k = 1; k <= extra; k++)
            if ((s[i + k] & 0xc0) != 0x80)
                return i;
        i += extra + 1;
    }
    return n;
}

typedef struct logical {
    char *buf;                  /* LIM_LINE_CHARS + 1 */
    size_t n;
    int first_line;
    bool too_long;
    int bad_byte, bad_col;      /* bad_byte -1: none */
} logical;

static void append_phys(logical *lg, const char *b, size_t n, bool cont) {
    if (lg->bad_byte < 0) {
        size_t bad = first_bad_byte((const unsigned char *)b, n);
        if (bad < n) {
            lg->bad_byte = (unsigned char)b[bad];
            lg->bad_col = (int)bad + 1;
        }
    }
    if (lg->too_long || lg->n + n + 1 > LIM_LINE_CHARS) {
        lg->too_long = true;
        return;
    }
    memcpy(lg->buf + lg->n, b, n);
    lg->n += n;
    if (cont)
        lg->buf[lg->n++] = ' ';     /* the backslash separates, like a space */
}

/* Joins physical lines ending in `\` into one logical line, comments cut. */
static bool next_logical(reader *r, logical *lg) {
    const char *b;
    size_t n;
    lg->n = 0;
    lg->too_long = false;
    lg->bad_byte = -1;
    if (!next_phys(r, &b, &n))
        return false;
    lg->first_line = r->lineno;
    for (;;) {
        n = comment_start(b, n);
        while (n > 0 && is_space((unsigned char)b[n - 1]))
            n--;
        bool cont = n > 0 && b[n - 1] == '\\';
        append_phys(lg, b, cont ? n - 1 : n, cont);
        if (!cont || !next_phys(r, &b, &n))
            break;
    }
    lg->buf[lg->n] = '\0';
    return true;
}

/* ------------------------------------------------------------------ */
/* commands                                                            */

static void free_cmd_parts(glib_cmd *cmd) {
    free(cmd->cube_paths);
    free(cmd->uniforms);
    free(cmd->defines);
}

static void push_cmd(parser *p, glib_cmd *cmd) {
    glib_scene *sc = p->sc;
    if (sc->ncmds >= LIM_CMDS) {
        report(p, DIAG_ERROR, cmd->file, cmd->line,
             "too many commands (more than %d); the rest of the scene is ignored", LIM_CMDS);
        free_cmd_parts(cmd);
        p->stop = true;
        return;
    }
    sc->cmds = grow(sc->cmds, &p->cmd_cap, sc->ncmds + 1, sizeof *sc->cmds);
    sc->cmds[sc->ncmds++] = *cmd;
}

static const cmd_spec *find_spec(const char *name);
static const char *suggest(const char *name);

static void unknown_command(parser *p, const char *name, char *rest, const char *file, int line) {
    const char *near = suggest(name);
    char hint[96] = "";
    if (near)
        snprintf(hint, sizeof hint, "; did you mean '%s'?", near);
    else if (is_opener(*skip_space(rest)))
        snprintf(hint, sizeof hint, "; a uniform on its own line? end the Program line above with '\\'");
    report(p, DIAG_WARNING, file, line, "unknown command '%.60s' (skipped)%s", name, hint);
}

/* glman tolerated brackets around plain numbers and commas between them
 * (`Color [1 0 0]`, `Color 1, 0, 0`): on a command of numbers only they
 * are blanks. */
static void blank_brackets(char *s) {
    for (; *s; s++)
        if (*s == '[' || *s == ']' || *s == ',')
            *s = ' ';
}

static void process_line(parser *p, char *s, const char *file, int line) {
    s = skip_space(s);
    if (!*s)
        return;
    char *name = s;
    while (*s && !is_space((unsigned char)*s))
        s++;
    if (*s)
        *s++ = '\0';
    const cmd_spec *spec = find_spec(name);
    if (!spec) {
        unknown_command(p, name, s, file, line);
        return;
    }
    cmdctx c = { .p = p, .file = file, .line = line, .spec = spec, .rest = s };
    build_usage(spec, c.usage, sizeof c.usage);
    if (spec->fn == h_nums || spec->fn == h_world_nums || spec->fn == h_vertex)
        blank_brackets(s);
    if (!spec->raw && (c.nwords = split_words(s, c.words, LIM_WORDS)) < 0) {
        cerr(&c, "%s: unclosed '\"': add the closing quote", spec->name);
        return;
    }
    glib_cmd cmd;
    memset(&cmd, 0, sizeof cmd);
    cmd.kind = spec->kind;
    cmd.file = file;
    cmd.line = line;
    cmd.wire = spec->wire;
    if (spec->fn(&c, &cmd))
        push_cmd(p, &cmd);
    else
        free_cmd_parts(&cmd);
}

/* glman demands the header; we only remind (a header with a trailing
 * comment or odd spacing still counts). */
static bool is_header(const char *b, size_t n) {
    static const char want[] = "##openglglib";
    size_t k = 0;
    for (size_t i = 0; i < n && want[k]; i++) {
        if (is_space((unsigned char)b[i]))
            continue;
        if (tolower((unsigned char)b[i]) != want[k++])
            return false;
    }
    return want[k] == '\0';
}

static bool all_space(const char *s, size_t n) {
    for (size_t i = 0; i < n; i++)
        if (!is_space((unsigned char)s[i]) && s[i] != '\n')
            return false;
    return true;
}

/* The top file must say what it is; an included file need not. */
static bool check_top(parser *p, const reader *r, const char *file) {
    if (all_space(r->text + r->pos, r->len - r->pos)) {
        report(p, DIAG_ERROR, file, 1, "empty file: expected '##OpenGL GLIB' and commands");
        return false;
    }
    reader first = *r;
    const char *b = "";
    size_t n = 0;
    next_phys(&first, &b, &n);
    if (is_header(b, n))
        return true;
    /* glman opened files whose header follows blank or comment lines
     * (projects that ran in glman do this): the header anywhere before
     * the first command is fine; only a file without it is worth a word */
    for (int line = 1;; line++) {
        size_t k = 0;
        while (k < n && is_space((unsigned char)b[k]))
            k++;
        bool blank = k == n || b[k] == '\n' || b[k] == '\r';
        bool comment = !blank && (b[k] == '#' || (b[k] == '/' && k + 1 < n && b[k + 1] == '/'));
        if (is_header(b, n)) {
            report(p, DIAG_NOTE, file, line, "the '##OpenGL GLIB' header is on line %d, after blank or comment "
                   "lines; glman read it there too", line);
            return true;
        }
        if (!blank && !comment)
            break;
        if (first.pos >= first.len)
            break;
        next_phys(&first, &b, &n);
    }
    report(p, DIAG_WARNING, file, 1,
           "first line is not '##OpenGL GLIB': glman will not open this file; add that line");
    return true;
}

/* A pack chosen from outside for a scene that names none: as if the top
 * file ended with `Pack name` (at its line 0). */
static void override_pack_at_end(parser *p, const char *file) {
    /* A pack draws the water of a world (Terrain, Water, Sun, Sky...). A
     * plain glman scene draws its own floor and water: given a pack, it
     * would get the pack's world and water on top of its own. Refuse, and
     * say what to do instead. */
    bool world = false;
    for (int i = 0; i < p->sc->ncmds && !world; i++)
        world = p->sc->cmds[i].kind != GLIB_CMD_PACK && glib_cmd_describes_world(p->sc->cmds[i].kind);
    if (!world) {
        report(p, DIAG_ERROR, file, 0,
               "--pack %.60s: this scene describes no world (no Terrain, Water, Sun or Sky command), so a pack "
               "has no water of its own to draw here: it would draw its world over the scene's. Give --pack a "
               "world scene (scenes/lake.glib, scenes/pool.glib), or open this one without --pack",
               p->pack_override);
        return;
    }
    cmdctx c = { .p = p, .file = file, .line = 0, .spec = find_spec("Pack") };
    build_usage(c.spec, c.usage, sizeof c.usage);
    glib_cmd cmd;
    memset(&cmd, 0, sizeof cmd);
    cmd.kind = GLIB_CMD_PACK;
    cmd.file = file;
    use_pack(&c, &cmd, p->pack_override);
}

static void parse_text(parser *p, const char *text, size_t len, const char *file, bool top) {
    reader r = { text ? text : "", text ? len : 0, 0, 0 };
    if (r.len >= 3 && memcmp(r.text, "\xEF\xBB\xBF", 3) == 0)
        r.pos = 3;              /* a UTF-8 byte order mark from a Windows editor */
    if (top && !check_top(p, &r, file))
        return;
    logical lg = { .buf = mem_alloc(LIM_LINE_CHARS + 1) };
    int binary = 0;
    while (!p->stop && next_logical(&r, &lg)) {
        if (lg.too_long) {
            report(p, DIAG_ERROR, file, lg.first_line,
                 "line too long (over %d characters); command skipped", LIM_LINE_CHARS);
        } else if (lg.bad_byte >= 0) {
            report(p, DIAG_ERROR, file, lg.first_line,
                 lg.bad_byte >= 0x80 ? "byte 0x%02X at column %d is not UTF-8 text; line skipped (save the file as UTF-8)"
                                     : "binary data (byte 0x%02X at column %d) in a text file; line skipped",
                 lg.bad_byte, lg.bad_col);
            if (++binary >= LIM_BINARY_LINES) {
                report(p, DIAG_ERROR, file, lg.first_line,
                     "this does not look like a .glib text file; stopped reading it");
                break;
            }
        } else {
            process_line(p, lg.buf, file, lg.first_line);
        }
    }
    free(lg.buf);
    if (top && p->pack_override && !p->pack_seen && !p->stop)
        override_pack_at_end(p, file);
}

/* Reads text as the file `name` with the include stack pushed; takes canon. */
static void parse_nested(parser *p, const char *text, size_t len, const char *name,
                         char *canon, bool top) {
    p->stack_name[p->depth] = name;
    p->stack_canon[p->depth] = canon;
    p->depth++;
    parse_text(p, text, len, name, top);
    p->depth--;
    free(canon);
}

/* A path that names the same file however it is spelled, for cycles. */
static char *canonical(const char *path) {
    char *real = realpath(path, NULL);
    return real ? real : mem_strdup(path);
}

/* Appends s to buf (size bytes, *n used), cutting what does not fit. */
static void append_cut(char *buf, size_t size, size_t *n, const char *s) {
    size_t l = strlen(s);
    if (*n + l >= size)
        l = size - 1 - *n;
    memcpy(buf + *n, s, l);
    *n += l;
    buf[*n] = '\0';
}

static void report_cycle(cmdctx *c, int at, const char *path) {
    char chain[256] = "";
    size_t n = 0;
    for (int i = at; i < c->p->depth; i++) {
        append_cut(chain, sizeof chain, &n, c->p->stack_name[i]);
        append_cut(chain, sizeof chain, &n, " -> ");
    }
    append_cut(chain, sizeof chain, &n, path);
    cerr(c, "%s cycle: %s; remove one of these Includes", c->spec->name, chain);
}

/* Reads the file at path in place of the current line (Include, Pack). */
static void include_file(cmdctx *c, const char *path) {
    parser *p = c->p;
    char why[128], *buf;
    size_t len;
    if (p->nreads >= LIM_INCLUDE_READS) {
        cerr(c, "more than %d Includes in one scene; '%s' skipped", LIM_INCLUDE_READS, path);
        return;
    }
    char real[GLIB_PATH_MAX];
    snprintf(real, sizeof real, "%s", path);
    if (access(real, R_OK) != 0) {
        check_readable(c, real);            /* says why, or finds the name in another case */
        if (access(real, R_OK) != 0)
            return;
    }
    path = real;
    if (!read_file(path, &buf, &len, why, sizeof why)) {   /* a directory or huge */
        cerr(c, "cannot open '%s' (from command %s): %s", path, c->spec->name, why);
        return;
    }
    p->nreads++;
    char *canon = canonical(path);
    for (int i = 0; i < p->depth; i++)
        if (strcmp(p->stack_canon[i], canon) == 0) {
            report_cycle(c, i, path);
            free(canon);
            free(buf);
            return;
        }
    if (p->depth > LIM_INCLUDE_DEPTH) {
        cerr(c, "%s '%s' is nested more than %d files deep; is there a loop?", c->spec->name,
             path, LIM_INCLUDE_DEPTH);
        free(canon);
        free(buf);
        return;
    }
    parse_nested(p, buf, len, add_file(p, path), canon, false);
    free(buf);
}

/* Include file: its commands are read in place of this line. */
static bool h_include(cmdctx *c, glib_cmd *cmd) {
    char path[GLIB_PATH_MAX];
    if (c->nwords < 1) {
        cerr(c, "Include needs a file: %s", c->usage);
        return false;
    }
    warn_extra(c, 1, path_hint);
    if (resolve_path(c, c->words[0], path))
        include_file(c, path);
    return false;               /* no command of its own: its lines are inlined */
}

/* ------------------------------------------------------------------ */
/* the public functions                                                */

static void finish(parser *p) {
    glib_scene *sc = p->sc;
    if (p->begin_file)
        report(p, DIAG_ERROR, p->begin_file, p->begin_line,
               "glBegin without a glEnd: its vertices draw nothing; add glEnd after the last glVertex");
    for (int i = 0; i < p->npending; i++)
        report(p, DIAG_WARNING, p->pending[i].file, p->pending[i].line,
             "Define %s comes after the last Program, so no shader sees it; move it above a Program",
             p->pending[i].name);
    free(p->pending);
    p->pending = NULL;
    if (sc->ncmds == 0 && sc->nerrors == 0 && sc->nfiles > 0)
        report(p, DIAG_WARNING, sc->files[0], 1, "no commands: the scene draws nothing");
    if (p->dropped) {
        char msg[128];
        snprintf(msg, sizeof msg, "too many errors: %d more diagnostics not shown (%d errors); fix the ones above first",
                 p->dropped, p->dropped_errors);
        add_diag(p, p->dropped_errors ? DIAG_ERROR : DIAG_WARNING,
                 sc->files[0], 0, msg);
    }
}

static glib_scene *new_scene(parser *p) {
    memset(p, 0, sizeof *p);
    p->sc = mem_alloc(sizeof *p->sc);
    memset(p->sc, 0, sizeof *p->sc);
    return p->sc;
}

glib_scene *glib_parse(const char *text, size_t len, const char *virtual_path) {
    parser p;
    glib_scene *sc = new_scene(&p);
    const char *name = add_file(&p, virtual_path ? virtual_path : "<memory>");
    parse_nested(&p, text, len, name, canonical(name), true);
    finish(&p);
    return sc;
}

glib_scene *glib_load(const char *path) {
    return glib_load_opts(path, NULL);
}

glib_scene *glib_load_opts(const char *path, const glib_options *opt) {
    parser p;
    glib_scene *sc = new_scene(&p);
    if (opt) {
        p.packs_dir = opt->packs_dir && opt->packs_dir[0] ? opt->packs_dir : NULL;
        p.pack_override = opt->pack_override && opt->pack_override[0] ? opt->pack_override : NULL;
    }
    const char *name = add_file(&p, path ? path : "<null>");
    char *buf, why[128];
    size_t len;
    if (!path || !read_file(path, &buf, &len, why, sizeof why)) {
        report(&p, DIAG_ERROR, name, 0, "cannot open '%s': %s", name, path ? why : "no path given");
    } else {
        parse_nested(&p, buf, len, name, canonical(path), true);
        free(buf);
    }
    finish(&p);
    return sc;
}

void glib_free(glib_scene *scene) {
    if (!scene)
        return;
    for (int i = 0; i < scene->ncmds; i++)
        free_cmd_parts(&scene->cmds[i]);
    for (int i = 0; i < scene->nfiles; i++)
        free(scene->files[i]);
    free(scene->cmds);
    free(scene->diags);
    free(scene->files);
    free(scene);
}

void glib_print_diags(const glib_scene *scene, void *stream) {
    diag_list l = { .d = scene ? scene->diags : NULL, .n = scene ? scene->ndiags : 0 };
    diag_print(&l, stream);
}

static const char *const kind_names[GLIB_CMD_KIND_COUNT] = {
    [GLIB_CMD_NONE] = "(none)",
    [GLIB_CMD_WINDOW_SIZE] = "WindowSize", [GLIB_CMD_PERSPECTIVE] = "Perspective",
    [GLIB_CMD_ORTHO] = "Ortho", [GLIB_CMD_LOOKAT] = "LookAt",
    [GLIB_CMD_TRANSLATE] = "Translate", [GLIB_CMD_ROTATE] = "Rotate",
    [GLIB_CMD_SCALE] = "Scale", [GLIB_CMD_PUSH_MATRIX] = "PushMatrix",
    [GLIB_CMD_POP_MATRIX] = "PopMatrix",
    [GLIB_CMD_QUAD_XY] = "QuadXY", [GLIB_CMD_QUAD_XZ] = "QuadXZ", [GLIB_CMD_QUAD_YZ] = "QuadYZ",
    [GLIB_CMD_SPHERE] = "Sphere", [GLIB_CMD_TORUS] = "Torus", [GLIB_CMD_BOX] = "Box",
    [GLIB_CMD_CYLINDER] = "Cylinder", [GLIB_CMD_CONE] = "Cone", [GLIB_CMD_TEAPOT] = "Teapot",
    [GLIB_CMD_OBJ] = "Obj", [GLIB_CMD_COLOR] = "Color",
    [GLIB_CMD_TEXTURE2D_FILE] = "Texture2D", [GLIB_CMD_TEXTURE2D_EMPTY] = "Texture2D",
    [GLIB_CMD_TEXTURE3D] = "Texture3D", [GLIB_CMD_CUBEMAP] = "CubeMap",
    [GLIB_CMD_NOISE2D] = "Noise2D", [GLIB_CMD_NOISE3D] = "Noise3D",
    [GLIB_CMD_RENDER_TO_TEXTURE] = "RenderToTexture", [GLIB_CMD_CLEAR] = "Clear",
    [GLIB_CMD_BACKGROUND] = "Background",
    [GLIB_CMD_VERTEX] = "Vertex", [GLIB_CMD_TESS_CONTROL] = "TessControl",
    [GLIB_CMD_TESS_EVALUATION] = "TessEvaluation", [GLIB_CMD_GEOMETRY] = "Geometry",
    [GLIB_CMD_FRAGMENT] = "Fragment", [GLIB_CMD_PROGRAM] = "Program",
    [GLIB_CMD_TIMER] = "Timer", [GLIB_CMD_GSTAP] = "GSTAP",
    [GLIB_CMD_DEFINE] = "Define", [GLIB_CMD_CULL] = "Cull",
    [GLIB_CMD_DEPTH_TEST] = "DepthTest", [GLIB_CMD_BLEND] = "Blend",
    [GLIB_CMD_SUN] = "Sun", [GLIB_CMD_SKY] = "Sky", [GLIB_CMD_SKY_SUN] = "SkySun",
    [GLIB_CMD_CLOUDS] = "Clouds", [GLIB_CMD_HAZE] = "Haze", [GLIB_CMD_GROUND_DETAIL] = "GroundDetail",
    [GLIB_CMD_WATER] = "Water",
    [GLIB_CMD_WATER_MESH] = "WaterMesh", [GLIB_CMD_TERRAIN] = "Terrain",
    [GLIB_CMD_WAVE_SINE] = "WaveSine", [GLIB_CMD_WAVE_GERSTNER] = "WaveGerstner",
    [GLIB_CMD_WAVE_STEEPNESS] = "WaveSteepness", [GLIB_CMD_WAVE_NOISE] = "WaveNoise",
    [GLIB_CMD_WAVE_OCEAN] = "WaveOcean", [GLIB_CMD_WAVE_OCEAN_TILES] = "WaveOceanTiles",
    [GLIB_CMD_WAVE_EXPLOSION] = "WaveExplosion", [GLIB_CMD_WAVE_PERLIN] = "WavePerlin",
    [GLIB_CMD_FLOW] = "Flow", [GLIB_CMD_SPRAY] = "Spray",
    [GLIB_CMD_OBJECT] = "Object", [GLIB_CMD_PACK] = "Pack", [GLIB_CMD_WORLD] = "World",
    [GLIB_CMD_WATER_SURFACE] = "WaterSurface",
    [GLIB_CMD_CAMERA] = "Camera",
    [GLIB_CMD_RENDER_TO_TEXTURE_ONCE] = "RenderToTextureOnce",
    [GLIB_CMD_SPLAT] = "Splat", [GLIB_CMD_IF] = "If", [GLIB_CMD_END_IF] = "EndIf",
    [GLIB_CMD_FLAT] = "Flat", [GLIB_CMD_SMOOTH] = "Smooth", [GLIB_CMD_LINE_WIDTH] = "LineWidth",
    [GLIB_CMD_POINT_SIZE] = "PointSize", [GLIB_CMD_POINT_SIZE_MODE] = "PointSizeMode",
    [GLIB_CMD_CLAMP] = "Clamp",
    [GLIB_CMD_DISK_XY] = "DiskXY", [GLIB_CMD_QUAD_BOX] = "QuadBox",
    [GLIB_CMD_POINT_CLOUD] = "PointCloud", [GLIB_CMD_JITTER_CLOUD] = "JitterCloud",
    [GLIB_CMD_SOCCERBALL] = "Soccerball", [GLIB_CMD_XARROW] = "Xarrow",
    [GLIB_CMD_LINES_ADJACENCY] = "LinesAdjacency", [GLIB_CMD_TRIANGLES] = "Triangles",
    [GLIB_CMD_OBJ_ADJ] = "ObjAdj", [GLIB_CMD_OBJ_PATCH] = "ObjPatch",
    [GLIB_CMD_NUM_PATCH_VERTICES] = "NumPatchVertices", [GLIB_CMD_GL_BEGIN] = "glBegin",
    [GLIB_CMD_GL_VERTEX] = "glVertex", [GLIB_CMD_GL_END] = "glEnd",
    [GLIB_CMD_SHP] = "Shp",
};

const char *glib_cmd_name(glib_cmd_kind kind) {
    if ((int)kind < 0 || kind >= GLIB_CMD_KIND_COUNT || !kind_names[kind])
        return "?";
    return kind_names[kind];
}

/* ------------------------------------------------------------------ */
/* the command table                                                   */

#define ARG_R(s, w)             { s, w, 'r', 0, 0, 0 }
#define ARG_RD(s, d)            { s, NULL, 'r', 0, 0, d }
#define ARG_P(s, w)             { s, w, 'p', 0, 0, 0 }
#define ARG_PD(s, d)            { s, NULL, 'p', 0, 0, d }
#define ARG_ID(s, lo, hi, d)    { s, NULL, 'i', lo, hi, d }
#define ARG_I(s, w, lo, hi)     { s, w, 'i', lo, hi, 0 }

/* Missing arguments take glman's defaults (docs/glib.md) */
#define QUAD_ARGS(a, b, c) { ARG_RD(a, 0), ARG_PD("size", 1), \
    ARG_ID(b, 1, 4096, 1), ARG_ID(c, 1, 4096, 1) }
#define SPHERE_ARGS { ARG_PD("r", 1), ARG_ID("slices", 3, 1024, 60), \
    ARG_ID("stacks", 2, 1024, 60) }
#define TORUS_ARGS { ARG_PD("r_major", 1), ARG_PD("r_minor", 0.5), \
    ARG_ID("sides", 3, 1024, 20), ARG_ID("rings", 3, 1024, 40) }
#define BOX_ARGS { ARG_PD("dx", 2), ARG_PD("dy", 2), ARG_PD("dz", 2) }
#define ROUND_ARGS { ARG_PD("r", 1), ARG_PD("h", 1), \
    ARG_ID("slices", 3, 1024, 32), ARG_ID("stacks", 1, 1024, 8) }
#define WAVE_ARGS { ARG_R("angle_deg", NULL), ARG_R("wavelength", NULL), \
    ARG_R("amplitude", "an amplitude"), ARG_RD("speed", 0), ARG_RD("phase", 0) }
#define XYZ_ARGS(i) ARG_R("x" #i, NULL), ARG_R("y" #i, NULL), ARG_R("z" #i, NULL)
#define CLOUD_ARGS { ARG_ID("nx", 1, 1024, 10), ARG_ID("ny", 1, 1024, 10), ARG_ID("nz", 1, 1024, 10) }
#define RGBA_ARGS { ARG_R("r", NULL), ARG_R("g", NULL), ARG_R("b", "a blue value"), ARG_RD("a", 1) }

static const cmd_spec specs[] = {
    { "WindowSize", GLIB_CMD_WINDOW_SIZE, false, h_nums, false, 2, 2,
      { ARG_I("w", NULL, 1, 16384), ARG_I("h", "a height", 1, 16384) }, NULL },
    { "Perspective", GLIB_CMD_PERSPECTIVE, false, h_nums, false, 0, 3,
      { { "fov", "a field of view in degrees", 'a', 0, 0, 50 }, ARG_PD("near", 0.1),
        ARG_PD("far", 1000) }, NULL },
    { "Ortho", GLIB_CMD_ORTHO, false, h_nums, false, 0, 6,
      { ARG_RD("l", -3), ARG_RD("r", 3), ARG_RD("b", -3), ARG_RD("t", 3),
        ARG_RD("near", 0.1), ARG_RD("far", 1000) }, NULL },
    { "LookAt", GLIB_CMD_LOOKAT, false, h_nums, false, 9, 9,
      { ARG_R("ex", NULL), ARG_R("ey", NULL), ARG_R("ez", NULL), ARG_R("cx", NULL),
        ARG_R("cy", NULL), ARG_R("cz", NULL), ARG_R("ux", NULL), ARG_R("uy", NULL),
        ARG_R("uz", "an up vector") }, NULL },
    { "Translate", GLIB_CMD_TRANSLATE, false, h_nums, false, 0, 3,
      { ARG_RD("x", 0), ARG_RD("y", 0), ARG_RD("z", 0) }, NULL },
    { "Rotate", GLIB_CMD_ROTATE, false, h_nums, false, 4, 4,
      { ARG_R("deg", NULL), ARG_R("ax", NULL), ARG_R("ay", NULL), ARG_R("az", "an axis z") }, NULL },
    { "Scale", GLIB_CMD_SCALE, false, h_nums, false, 1, 3,
      { ARG_R("s", "a scale factor"), ARG_RD("sy", 0), ARG_RD("sz", 0) }, "Scale s | Scale sx sy sz" },
    { "PushMatrix", GLIB_CMD_PUSH_MATRIX, false, h_nums, false, 0, 0, { { 0 } }, NULL },
    { "TransformBegin", GLIB_CMD_PUSH_MATRIX, false, h_nums, false, 0, 0, { { 0 } }, NULL },
    { "PopMatrix", GLIB_CMD_POP_MATRIX, false, h_nums, false, 0, 0, { { 0 } }, NULL },
    { "TransformEnd", GLIB_CMD_POP_MATRIX, false, h_nums, false, 0, 0, { { 0 } }, NULL },
    { "QuadXY", GLIB_CMD_QUAD_XY, false, h_nums, false, 0, 4, QUAD_ARGS("z", "nx", "ny"), NULL },
    { "QuadXZ", GLIB_CMD_QUAD_XZ, false, h_nums, false, 0, 4, QUAD_ARGS("y", "nx", "nz"), NULL },
    { "QuadYZ", GLIB_CMD_QUAD_YZ, false, h_nums, false, 0, 4, QUAD_ARGS("x", "ny", "nz"), NULL },
    { "Sphere", GLIB_CMD_SPHERE, false, h_nums, false, 0, 3, SPHERE_ARGS, NULL },
    { "Torus", GLIB_CMD_TORUS, false, h_nums, false, 0, 4, TORUS_ARGS, NULL },
    { "Box", GLIB_CMD_BOX, false, h_nums, false, 0, 3, BOX_ARGS, "Box dx | Box dx dy dz" },
    { "Cylinder", GLIB_CMD_CYLINDER, false, h_nums, false, 0, 4, ROUND_ARGS, NULL },
    { "Cone", GLIB_CMD_CONE, false, h_nums, false, 0, 4, ROUND_ARGS, NULL },
    { "Teapot", GLIB_CMD_TEAPOT, false, h_nums, false, 0, 1, { ARG_PD("size", 1) }, NULL },
    { "WireQuadXY", GLIB_CMD_QUAD_XY, true, h_nums, false, 0, 4, QUAD_ARGS("z", "nx", "ny"), NULL },
    { "WireQuadXZ", GLIB_CMD_QUAD_XZ, true, h_nums, false, 0, 4, QUAD_ARGS("y", "nx", "nz"), NULL },
    { "WireQuadYZ", GLIB_CMD_QUAD_YZ, true, h_nums, false, 0, 4, QUAD_ARGS("x", "ny", "nz"), NULL },
    { "WireSphere", GLIB_CMD_SPHERE, true, h_nums, false, 0, 3, SPHERE_ARGS, NULL },
    { "WireTorus", GLIB_CMD_TORUS, true, h_nums, false, 0, 4, TORUS_ARGS, NULL },
    { "WireBox", GLIB_CMD_BOX, true, h_nums, false, 0, 3, BOX_ARGS, "WireBox dx | WireBox dx dy dz" },
    { "WireCylinder", GLIB_CMD_CYLINDER, true, h_nums, false, 0, 4, ROUND_ARGS, NULL },
    { "WireCone", GLIB_CMD_CONE, true, h_nums, false, 0, 4, ROUND_ARGS, NULL },
    { "WireTeapot", GLIB_CMD_TEAPOT, true, h_nums, false, 0, 1, { ARG_PD("size", 1) }, NULL },
    { "Obj", GLIB_CMD_OBJ, false, h_obj, false, 0, 0, { { 0 } }, "Obj file.obj" },
    { "WireObj", GLIB_CMD_OBJ, true, h_obj, false, 0, 0, { { 0 } }, "WireObj file.obj" },
    { "ObjAdj", GLIB_CMD_OBJ_ADJ, false, h_obj, false, 0, 0, { { 0 } }, "ObjAdj file.obj" },
    { "ObjPatch", GLIB_CMD_OBJ_PATCH, false, h_obj, false, 0, 0, { { 0 } }, "ObjPatch file.obj" },
    { "Shp", GLIB_CMD_SHP, false, h_obj, false, 0, 0, { { 0 } }, "Shp file.shp" },
    { "DiskXY", GLIB_CMD_DISK_XY, false, h_nums, false, 0, 0, { { 0 } }, NULL },
    { "QuadBox", GLIB_CMD_QUAD_BOX, false, h_nums, false, 0, 1, { ARG_ID("n", 1, 2048, 10) }, NULL },
    { "PointCloud", GLIB_CMD_POINT_CLOUD, false, h_nums, false, 0, 3, CLOUD_ARGS, NULL },
    { "JitterCloud", GLIB_CMD_JITTER_CLOUD, false, h_nums, false, 0, 3, CLOUD_ARGS, NULL },
    { "Soccerball", GLIB_CMD_SOCCERBALL, false, h_nums, false, 0, 1, { ARG_PD("r", 1) }, NULL },
    { "Xarrow", GLIB_CMD_XARROW, false, h_nums, false, 0, 1, { ARG_ID("slices", 3, 2048, 100) }, NULL },
    { "LinesAdjacency", GLIB_CMD_LINES_ADJACENCY, false, h_nums, false, 12, 12,
      { XYZ_ARGS(0), XYZ_ARGS(1), XYZ_ARGS(2), XYZ_ARGS(3) }, "LinesAdjacency x0 y0 z0 x1 y1 z1 x2 y2 z2 x3 y3 z3" },
    { "Triangles", GLIB_CMD_TRIANGLES, false, h_nums, false, 9, 9,
      { XYZ_ARGS(0), XYZ_ARGS(1), XYZ_ARGS(2) }, "Triangles x0 y0 z0 x1 y1 z1 x2 y2 z2" },
    { "NumPatchVertices", GLIB_CMD_NUM_PATCH_VERTICES, false, h_nums, false, 1, 1,
      { ARG_I("n", "a patch size (vertices a patch)", 1, 32) }, NULL },
    { "glBegin", GLIB_CMD_GL_BEGIN, false, h_begin, false, 0, 0, { { 0 } }, "glBegin gl_patches" },
    { "glVertex", GLIB_CMD_GL_VERTEX, false, h_vertex, false, 3, 4,
      { ARG_R("x", NULL), ARG_R("y", NULL), ARG_R("z", "a z"), ARG_RD("w", 1) }, NULL },
    { "glEnd", GLIB_CMD_GL_END, false, h_end, false, 0, 0, { { 0 } }, "glEnd" },
    { "Color", GLIB_CMD_COLOR, false, h_nums, false, 3, 4, RGBA_ARGS, NULL },
    { "Texture2D", GLIB_CMD_TEXTURE2D_FILE, false, h_tex2d, false, 0, 0, { { 0 } },
      "Texture2D unit file | Texture2D unit w h [float|float16|depth]" },
    { "Texture3D", GLIB_CMD_TEXTURE3D, false, h_tex3d, false, 0, 0, { { 0 } },
      "Texture3D unit file | Texture3D unit w h d" },
    { "CubeMap", GLIB_CMD_CUBEMAP, false, h_cube, false, 0, 0, { { 0 } },
      "CubeMap unit +x -x +y -y +z -z" },
    { "Noise2D", GLIB_CMD_NOISE2D, false, h_nums, false, 0, 1, { ARG_ID("res", 1, 4096, 64) }, NULL },
    { "Noise3D", GLIB_CMD_NOISE3D, false, h_nums, false, 0, 1, { ARG_ID("res", 1, 400, 64) }, NULL },
    { "RenderToTexture", GLIB_CMD_RENDER_TO_TEXTURE, false, h_rtt, false, 0, 0, { { 0 } },
      "RenderToTexture [unit ...]" },
    { "Clear", GLIB_CMD_CLEAR, false, h_nums, false, 0, 0, { { 0 } }, NULL },
    { "Background", GLIB_CMD_BACKGROUND, false, h_nums, false, 3, 4, RGBA_ARGS, NULL },
    { "Vertex", GLIB_CMD_VERTEX, false, h_stage, false, 0, 0, { { 0 } }, "Vertex file.vert" },
    { "TessControl", GLIB_CMD_TESS_CONTROL, false, h_stage, false, 0, 0, { { 0 } }, "TessControl file.tcs" },
    { "TessEvaluation", GLIB_CMD_TESS_EVALUATION, false, h_stage, false, 0, 0, { { 0 } },
      "TessEvaluation file.tes" },
    { "Geometry", GLIB_CMD_GEOMETRY, false, h_stage, false, 0, 0, { { 0 } }, "Geometry file.geom" },
    { "Fragment", GLIB_CMD_FRAGMENT, false, h_stage, false, 0, 0, { { 0 } }, "Fragment file.frag" },
    { "Program", GLIB_CMD_PROGRAM, false, h_program, true, 0, 0, { { 0 } },
      "Program Name [uniform value ...]" },
    { "Timer", GLIB_CMD_TIMER, false, h_nums, false, 1, 1, { ARG_P("secs", "a period in seconds") }, NULL },
    { "GSTAP", GLIB_CMD_GSTAP, false, h_nums, false, 0, 0, { { 0 } }, NULL },
    { "Include", GLIB_CMD_NONE, false, h_include, false, 0, 0, { { 0 } }, "Include file.glib" },
    { "Define", GLIB_CMD_DEFINE, false, h_define, true, 0, 0, { { 0 } },
      "Define NAME [<true>|<false>|value|<min default max>]" },
    { "Cull", GLIB_CMD_CULL, false, h_cull, false, 0, 0, { { 0 } }, "Cull back|front|none" },
    { "DepthTest", GLIB_CMD_DEPTH_TEST, false, h_depth, false, 0, 0, { { 0 } }, "DepthTest on|off" },
    { "Blend", GLIB_CMD_BLEND, false, h_blend, false, 0, 0, { { 0 } }, "Blend off|alpha|add" },
    /* glman's state commands and its message box */
    { "Flat", GLIB_CMD_FLAT, false, h_nums, false, 0, 0, { { 0 } }, NULL },
    { "Smooth", GLIB_CMD_SMOOTH, false, h_nums, false, 0, 0, { { 0 } }, NULL },
    { "LineWidth", GLIB_CMD_LINE_WIDTH, false, h_nums, false, 0, 1, { ARG_PD("width", 1) }, NULL },
    { "PointSize", GLIB_CMD_POINT_SIZE, false, h_nums, false, 0, 1, { ARG_PD("size", 1) }, NULL },
    { "PointSizeMode", GLIB_CMD_POINT_SIZE_MODE, false, h_nums, false, 0, 1, { ARG_RD("n", 1) }, NULL },
    { "Clamp", GLIB_CMD_CLAMP, false, h_clamp, false, 0, 0, { { 0 } }, "Clamp" },
    { "MessageBox", GLIB_CMD_NONE, false, h_message, true, 0, 0, { { 0 } }, "MessageBox text" },
    /* describing the world */
    { "Sun", GLIB_CMD_SUN, false, h_world_nums, false, 3, 6,
      { ARG_R("dx", NULL), ARG_R("dy", NULL), ARG_R("dz", "a direction z"), ARG_RD("r", 0),
        ARG_RD("g", 0), ARG_RD("b", 0) }, NULL, true },
    { "Sky", GLIB_CMD_SKY, false, h_world_nums, false, 6, 6,
      { ARG_R("zr", NULL), ARG_R("zg", NULL), ARG_R("zb", NULL), ARG_R("hr", NULL),
        ARG_R("hg", NULL), ARG_R("hb", "a horizon blue") }, NULL, true },
    { "SkySun", GLIB_CMD_SKY_SUN, false, h_world_nums, false, 1, 2,
      { ARG_R("radius_deg", "an angular radius in degrees"), ARG_RD("gain", 0) }, "SkySun radius_deg [gain]", true },
    { "Clouds", GLIB_CMD_CLOUDS, false, h_world_nums, false, 1, 3,
      { ARG_R("cover", "a cloud cover from 0 to 1"), ARG_RD("scale", 0), ARG_RD("height", 0) },
      "Clouds cover [scale [height]]", true },
    { "Haze", GLIB_CMD_HAZE, false, h_world_nums, false, 1, 1, { ARG_R("distance", "a distance in metres") },
      "Haze distance", true },
    { "GroundDetail", GLIB_CMD_GROUND_DETAIL, false, h_world_nums, false, 1, 1,
      { ARG_R("amount", "an amount from 0 to 1") }, "GroundDetail amount", true },
    { "Water", GLIB_CMD_WATER, false, h_world_nums, false, 1, 5,
      { ARG_R("level", "a water level"), ARG_RD("ior", 0), ARG_RD("ar", 0), ARG_RD("ag", 0),
        ARG_RD("ab", 0) }, "Water level [ior [ar ag ab]]", true },
    { "WaterMesh", GLIB_CMD_WATER_MESH, false, h_world_nums, false, 1, 1,
      { { "res", "a resolution (grid cells per side)", 'i', 0, 65536, 0 } }, NULL, true },
    { "Terrain", GLIB_CMD_TERRAIN, false, h_terrain, false, 0, 0, { { 0 } },
      "Terrain flat|lake|slope|pool [half_size [depth [shore_height_or_slope [seed [res]]]]]", true },
    { "WaveSine", GLIB_CMD_WAVE_SINE, false, h_world_nums, false, 3, 5, WAVE_ARGS,
      "WaveSine angle_deg wavelength amplitude [speed [phase]]", true },
    { "WaveGerstner", GLIB_CMD_WAVE_GERSTNER, false, h_world_nums, false, 3, 5, WAVE_ARGS,
      "WaveGerstner angle_deg wavelength amplitude [speed [phase]]", true },
    { "WaveSteepness", GLIB_CMD_WAVE_STEEPNESS, false, h_world_nums, false, 1, 1,
      { ARG_R("Q", "a steepness Q") }, NULL, true },
    { "WaveNoise", GLIB_CMD_WAVE_NOISE, false, h_world_nums, false, 1, 8,
      { ARG_R("amplitude", "an amplitude"), ARG_RD("cell", 0), { "octaves", NULL, 'i', 0, 64, 0 },
        ARG_RD("speed", 0), ARG_RD("angle_deg", 0), SEED_RULE("seed"),
        { "period", NULL, 'i', 0, 65536, 0 }, ARG_RD("gain", 0) },
      "WaveNoise amplitude [cell [octaves [speed [angle_deg [seed [period [gain]]]]]]]", true },
    { "WaveOcean", GLIB_CMD_WAVE_OCEAN, false, h_wave_ocean, false, 0, 0, { { 0 } },
      "WaveOcean phillips|jonswap|tma wind_speed [wind_angle_deg [choppiness [res [seed [fetch [depth [spreading [amplitude]]]]]]]]", true },
    { "WaveOceanTiles", GLIB_CMD_WAVE_OCEAN_TILES, false, h_world_nums, false, 1, 3,
      { ARG_R("tile", "a tile side in metres"), ARG_RD("tile2", 0), ARG_RD("tile3", 0) },
      "WaveOceanTiles tile [tile2 [tile3]]", true },
    { "WaveExplosion", GLIB_CMD_WAVE_EXPLOSION, false, h_world_nums, false, 4, 7,
      { ARG_R("x", NULL), ARG_R("z", NULL), ARG_R("start", NULL), ARG_R("i0", "an amplitude I0"),
        ARG_RD("omega", 0), ARG_RD("k", 0), ARG_RD("decay", 0) },
      "WaveExplosion x z start i0 [omega [k [decay]]]", true },
    { "WavePerlin", GLIB_CMD_WAVE_PERLIN, false, h_world_nums, false, 1, 8,
      { ARG_R("amplitude", "an amplitude"), ARG_RD("cell", 0), { "octaves", NULL, 'i', 0, 64, 0 },
        ARG_RD("rate", 0), ARG_RD("stretch", 0), ARG_RD("angle_deg", 0), SEED_RULE("seed"),
        ARG_RD("gain", 0) },
      "WavePerlin amplitude [cell [octaves [rate [stretch [angle_deg [seed [gain]]]]]]]", true },
    { "Flow", GLIB_CMD_FLOW, false, h_flow, false, 0, 0, { { 0 } },
      "Flow current vx vz | Flow vortex x z strength radius | Flow texture file scale | Flow detail amplitude [cell [period [foam]]]", true },
    { "Spray", GLIB_CMD_SPRAY, false, h_world_nums, false, 2, 6,
      { ARG_R("threshold", "an upward speed threshold (m/s)"), ARG_R("rate", "a rate (particles/s)"),
        ARG_RD("life", 0), ARG_RD("size", 0), SEED_RULE("seed"), { "count", NULL, 'i', 0, 1048576, 0 } },
      "Spray threshold rate [life [size [seed [count]]]]", true },
    { "Object", GLIB_CMD_OBJECT, false, h_object, false, 0, 0, { { 0 } },
      "Object sphere x y z r R G B | Object box x y z hx hy hz R G B | Object cylinder x y z r h R G B | "
      "Object mesh file.obj x y z [rot_y_deg [scale [R G B]]]", true },
    { "Pack", GLIB_CMD_PACK, false, h_pack, false, 0, 0, { { 0 } }, "Pack name", true },
    /* drawing the world (packs) */
    { "World", GLIB_CMD_WORLD, false, h_world, false, 0, 0, { { 0 } }, "World [all|above|below [offset|uniform]]" },
    { "WaterSurface", GLIB_CMD_WATER_SURFACE, false, h_water_surface, false, 0, 0, { { 0 } },
      "WaterSurface [points N|mesh N]" },
    { "Camera", GLIB_CMD_CAMERA, false, h_camera, false, 0, 0, { { 0 } },
      "Camera main|wide|mirror|top|light [fov_scale|uniform]" },
    { "RenderToTextureOnce", GLIB_CMD_RENDER_TO_TEXTURE_ONCE, false, h_rtt, false, 0, 0, { { 0 } },
      "RenderToTextureOnce unit [unit...]" },
    { "If", GLIB_CMD_IF, false, h_if, false, 0, 0, { { 0 } }, "If [not] DEFINE|above_water|under_water|waves" },
    { "EndIf", GLIB_CMD_END_IF, false, h_nums, false, 0, 0, { { 0 } }, NULL },
    { "Splat", GLIB_CMD_SPLAT, false, h_nums, false, 2, 2,
      { { "src", "a texture unit", 'i', 0, LIM_UNIT, 0 }, { "dst", "a texture unit", 'i', 0, LIM_UNIT, 0 } },
      "Splat src_unit dst_unit" },
};

#define NSPECS (sizeof specs / sizeof specs[0])

bool glib_cmd_describes_world(glib_cmd_kind kind) {
    /* every spelling of a kind shares the row's flag */
    for (size_t i = 0; i < NSPECS; i++)
        if (specs[i].kind == kind)
            return specs[i].world;
    return false;
}

static const cmd_spec *find_spec(const char *name) {
    for (size_t i = 0; i < NSPECS; i++)
        if (strcasecmp(specs[i].name, name) == 0)
            return &specs[i];
    return NULL;
}

/* Case-insensitive edit distance, for "did you mean"; long words don't
 * get a suggestion. */
static int edit_distance(const char *a, const char *b) {
    enum { MAXW = 32 };
    size_t la = strlen(a), lb = strlen(b);
    if (la >= MAXW || lb >= MAXW)
        return MAXW;
    int d[MAXW][MAXW];
    for (size_t i = 0; i <= la; i++)
        d[i][0] = (int)i;
    for (size_t j = 0; j <= lb; j++)
        d[0][j] = (int)j;
    for (size_t i = 1; i <= la; i++)
        for (size_t j = 1; j <= lb; j++) {
            int sub = d[i - 1][j - 1] +
                      (tolower((unsigned char)a[i - 1]) != tolower((unsigned char)b[j - 1]));
            int del = d[i - 1][j] + 1, ins = d[i][j - 1] + 1;
            d[i][j] = sub < del ? (sub < ins ? sub : ins) : (del < ins ? del : ins);
        }
    return d[la][lb];
}

static const char *suggest(const char *name) {
    const char *best = NULL;
    int best_d = 3;             /* at most 2 edits */
    for (size_t i = 0; i < NSPECS; i++) {
        int dist = edit_distance(name, specs[i].name);
        if (dist < best_d && (size_t)dist < strlen(name) / 2 + 1) {
            best_d = dist;
            best = specs[i].name;
        }
    }
    return best;
}

bool glib_uniform_consumed(const glib_scene *scene, const char *name, bool *is_count) {
    for (int i = 0; scene && i < scene->ncmds; i++) {
        const glib_cmd *c = &scene->cmds[i];
        bool count = c->kind == GLIB_CMD_WATER_SURFACE || c->kind == GLIB_CMD_TEXTURE2D_EMPTY;
        if (!count && c->kind != GLIB_CMD_CAMERA && c->kind != GLIB_CMD_WORLD)
            continue;
        if (strcmp(c->arg, name) == 0 || (c->kind == GLIB_CMD_TEXTURE2D_EMPTY && strcmp(c->name, name) == 0)) {
            if (is_count)
                *is_count = count;
            return true;
        }
    }
    return false;
}

unif_program_decl glib_program_decl(const glib_cmd *c) {
    unif_program_decl d = {
        .name = c->name, .file = c->file, .line = c->line,
        .defines = c->defines, .ndefines = c->ndefines,
        .uniforms = c->uniforms, .nuniforms = c->nuniforms,
    };
    return d;
}

bool glib_unif_set(unif_set *set, const glib_cmd *program, char *err, int errlen) {
    if (err && errlen > 0) err[0] = '\0';
    if (!set || !program) return false;
    if (program->kind != GLIB_CMD_PROGRAM) {
        if (err && errlen > 0)
            snprintf(err, (size_t)errlen, "%s:%d: not a Program command", program->file ? program->file : "(glib)",
                     program->line);
        return false;
    }
    unif_program_decl d = glib_program_decl(program);
    return unif_set_from_decls(set, &d, err, errlen);
}
