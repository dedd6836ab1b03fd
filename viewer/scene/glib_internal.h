/* glib_internal: what the parts of the .glib parser share; private to
 * viewer/scene/glib*.c (glib.h is the public header).
 *
 *   glib.c          the driver: the parser's state, its diagnostics, the
 *                   lines of a text, load/parse/free
 *   glib_lex.c      the lexer: physical and logical lines, words, numbers
 *   glib_args.c     a command's arguments: numbers, usage, modes, names
 *   glib_path.c     the files a command names, resolved and checked
 *   glib_cmds.c     the handlers of glman's commands
 *   glib_world.c    the handlers of the world's commands (our extensions)
 *   glib_include.c  Include: files read in place of a line
 *   glib_pack.c     Pack: the pack that draws the scene's water
 *   glib_values.c   uniform and Define values
 *   glib_program.c  Program and Define
 *   glib_table.c    the command table and the names of the kinds
 *
 * The functions below have short names, being private: no file outside
 * the parser includes this header.
 */
#ifndef TARN_GLIB_INTERNAL_H
#define TARN_GLIB_INTERNAL_H

#include "glib.h"
#include "unif.h"

#include <stdbool.h>
#include <stddef.h>

/* Every limit exists so that corrupt or hostile input (a binary file, an
 * include loop, a megabyte-long line) costs bounded memory and time. */
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

/* the parser's state, one a glib_load / glib_parse */
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
    struct file_cache *files;
    bool pack_seen;                 /* the scene's (first) Pack command was read */
    const char *pack_file;          /* where, for the message about a second one */
    int pack_line;
    char pack_name[GLIB_NAME_MAX];
    /* an open glBegin (its file and line; NULL when none) */
    const char *begin_file;
    int begin_line, begin_nverts;
} parser;

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
    int nreq, nmax;             /* numbers, for glib_h_nums */
    arg_rule args[12];         /* LinesAdjacency: 4 points */
    const char *usage;          /* NULL: built from args */
    bool world;                 /* describes the world (docs/glib.md, "Describing the
                                 * world"): a scene with one is drawn lit, with tarn's world */
};

/* A mode word (Cull back, Terrain lake): its spelling, its glib_canonical
 * word, and a number it stands for. */
typedef struct keyword { const char *word; const char *canon; double value; } keyword;

/* A value read: good, bad (the line goes on), or the rest of the line lost. */
typedef enum { VAL_OK, VAL_BAD, VAL_STOP } val_result;

/* a seed argument (a 32-bit whole number) */
#define SEED_RULE(s) { s, NULL, 'i', 0, 4294967295.0, 0 }

/* ------------------------------------------------------------------ */
/* characters                                                          */

static inline bool glib_is_space(int c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

static inline char *glib_skip_space(char *s) {
    while (glib_is_space((unsigned char)*s))
        s++;
    return s;
}

static inline bool glib_is_opener(int c) { return c == '<' || c == '{' || c == '['; }
static inline bool glib_is_closer(int c) { return c == '>' || c == '}' || c == ']'; }

static inline char glib_closer_of(char open) {
    return open == '<' ? '>' : open == '{' ? '}' : ']';
}

/* ------------------------------------------------------------------ */
/* lines                                                               */

typedef struct reader {
    const char *text;
    size_t len, pos;
    int lineno;
} reader;

typedef struct logical {
    char *buf;                  /* LIM_LINE_CHARS + 1 */
    size_t n;
    int first_line;
    bool too_long;
    int bad_byte, bad_col;      /* bad_byte -1: none */
} logical;

/* ------------------------------------------------------------------ */
/* the driver (glib.c)                                                 */

__attribute__((format(printf, 5, 6)))
void glib_report(parser *p, diag_severity sev, const char *file, int line, const char *fmt, ...);
/* An error / a warning at the command's line. */
__attribute__((format(printf, 2, 3)))
void glib_cerr(cmdctx *c, const char *fmt, ...);
__attribute__((format(printf, 2, 3)))
void glib_cwarn(cmdctx *c, const char *fmt, ...);
const char *glib_add_file(parser *p, const char *name);
void glib_push_cmd(parser *p, glib_cmd *cmd);
void glib_parse_text(parser *p, const char *text, size_t len, const char *file, bool top);

/* ------------------------------------------------------------------ */
/* the lexer (glib_lex.c)                                              */

bool glib_is_ident(const char *s);
int glib_split_words(char *s, char **w, int max);
int glib_split_items(char *s, char **w, int max);
bool glib_is_decimal(const char *s);
bool glib_parse_number(const char *s, double *out);
size_t glib_dotted_prefix(const char *s, double *out);
bool glib_is_bool_word(const char *s, double *v);
bool glib_next_phys(reader *r, const char **b, size_t *n);
bool glib_next_logical(reader *r, logical *lg);

/* ------------------------------------------------------------------ */
/* a command's arguments (glib_args.c) and paths (glib_path.c)         */

bool glib_read_number(cmdctx *c, const char *tok, double *out);
void glib_build_usage(const cmd_spec *s, char *out, size_t size);
bool glib_parse_arg(cmdctx *c, const arg_rule *a, const char *tok, double *out);
void glib_missing_args(cmdctx *c, int have);
void glib_warn_extra(cmdctx *c, int max, const char *hint);
bool glib_nums_from(cmdctx *c, glib_cmd *cmd, int w0, const arg_rule *rules, int nreq, int nmax,
               const char *what);
const keyword *glib_find_keyword(cmdctx *c, const keyword *k, size_t n, const char *choices);
const keyword *glib_mode_word(cmdctx *c, const keyword *k, size_t n, const char *choices);
bool glib_take_uniform_name(cmdctx *c, const char *what, const char *w, char *dst, size_t size);

extern const char path_hint[];
bool glib_resolve_path(cmdctx *c, const char *word, char out[GLIB_PATH_MAX]);
void glib_check_readable(cmdctx *c, char path[GLIB_PATH_MAX]);
bool glib_take_path(cmdctx *c, const char *word, char out[GLIB_PATH_MAX]);

/* ------------------------------------------------------------------ */
/* the handlers the command table names                                */

/* glman's commands (glib_cmds.c) */
bool glib_h_nums(cmdctx *c, glib_cmd *cmd);
bool glib_h_stage(cmdctx *c, glib_cmd *cmd);
bool glib_h_obj(cmdctx *c, glib_cmd *cmd);
bool h_tex2d(cmdctx *c, glib_cmd *cmd);
bool h_tex3d(cmdctx *c, glib_cmd *cmd);
bool glib_h_cube(cmdctx *c, glib_cmd *cmd);
bool glib_h_rtt(cmdctx *c, glib_cmd *cmd);
bool glib_h_clamp(cmdctx *c, glib_cmd *cmd);
bool glib_h_message(cmdctx *c, glib_cmd *cmd);
bool glib_h_begin(cmdctx *c, glib_cmd *cmd);
bool glib_h_vertex(cmdctx *c, glib_cmd *cmd);
bool glib_h_end(cmdctx *c, glib_cmd *cmd);
bool glib_h_cull(cmdctx *c, glib_cmd *cmd);
bool glib_h_blend(cmdctx *c, glib_cmd *cmd);
bool glib_h_depth(cmdctx *c, glib_cmd *cmd);

/* the world's commands (glib_world.c) */
bool glib_h_world_nums(cmdctx *c, glib_cmd *cmd);
bool glib_h_terrain(cmdctx *c, glib_cmd *cmd);
bool glib_h_wave_ocean(cmdctx *c, glib_cmd *cmd);
bool glib_h_object(cmdctx *c, glib_cmd *cmd);
bool glib_h_flow(cmdctx *c, glib_cmd *cmd);
bool glib_h_world(cmdctx *c, glib_cmd *cmd);
bool glib_h_camera(cmdctx *c, glib_cmd *cmd);
bool glib_h_if(cmdctx *c, glib_cmd *cmd);
bool glib_h_water_surface(cmdctx *c, glib_cmd *cmd);

/* Program and Define (glib_program.c) */
bool glib_h_program(cmdctx *c, glib_cmd *cmd);
bool glib_h_define(cmdctx *c, glib_cmd *cmd);

/* Include (glib_include.c), Pack (glib_pack.c) */
bool glib_h_include(cmdctx *c, glib_cmd *cmd);
bool glib_h_pack(cmdctx *c, glib_cmd *cmd);

/* ------------------------------------------------------------------ */
/* files read in place of a line (glib_include.c), the pack (glib_pack.c) */

bool glib_read_file(parser *p, const char *path, char **out, size_t *len, char *why, size_t whylen);
void glib_parse_nested(parser *p, const char *text, size_t len, const char *name, char *canon, bool top);
char *glib_canonical(const char *path);
void glib_append_cut(char *buf, size_t size, size_t *n, const char *s);
void glib_include_file(cmdctx *c, const char *path);
void glib_override_pack_at_end(parser *p, const char *file);

/* ------------------------------------------------------------------ */
/* uniform values (glib_values.c)                                      */

val_result glib_read_value(cmdctx *c, char **sp, unif_decl *u, const char *owner);
bool glib_take_name(cmdctx *c, char **sp, char out[GLIB_NAME_MAX], const char *what);

/* ------------------------------------------------------------------ */
/* the command table (glib_table.c)                                    */

const cmd_spec *glib_find_spec(const char *name);
const char *glib_suggest(const char *name);
int glib_edit_distance(const char *a, const char *b);

#endif
