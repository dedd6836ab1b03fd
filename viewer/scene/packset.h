/* packset: the packs a repository holds, and the two small text files a
 * pack keeps for comparison (docs/benchmark.md, "Files a pack keeps"):
 *
 *   packs/NAME/bench.txt   the quality settings `tarn bench` sweeps
 *   packs/NAME/bounds.txt  the error tests/test_hard_cases.c allows per hard case
 *
 * A pack is a directory packs/NAME holding pack.glib; packs are found when
 * asked, so a pack that lands later is picked up without a rebuild.
 *
 * bench.txt, one setting a line ('#' starts a comment):
 *
 *     NAME  ASSIGNMENT...
 *     colour #RRGGBB                   (the pack's colour in plots; optional)
 *     buffer BUFFER ASSIGNMENT...      (how the pack shows a per-pixel buffer;
 *                                       optional, one line per buffer)
 *
 * where ASSIGNMENT is
 *
 *     Program.entry=v[,v...]   a slider, checkbox, colour or Define of that
 *                              Program (true/false/on/off are 1/0)
 *     *.entry=v[,v...]         the entry in every Program that has it
 *     scene.Command=a[,b...]   a world command added after the scene
 *                              (e.g. scene.WaterMesh=64): last wins
 *
 * A setting starts from the pack's defaults. No bench.txt: one setting,
 * "default". BUFFER is refract_hit (world xyz the refracted ray meets, in
 * RGB), fresnel (the reflectance, in R), irradiance (the sun's irradiance
 * at the refraction hit, RGB) or depth (the path length in water, in R):
 * with the line's assignments on top of a setting, the pack's colour
 * output is that buffer (see bench.h, TARN_OUTPUT, for the same without a
 * line). bounds.txt, one case a line:
 *
 *     CASE  MAX_RMSE|none  [why ...]
 *
 * CASE is a hard case's name (scenes/hard/CASE.glib, or a test's own case
 * such as "sliders"), or `*` for every case not listed. `none` means the
 * pack cannot hold a bound there; the reason is printed by the test and
 * belongs on the pack's page. */
#ifndef TARN_PACKSET_H
#define TARN_PACKSET_H

#include <stdbool.h>

#include "unif.h"

#define PACKSET_MAX 32
#define PACKSET_NAME_MAX 64
#define PACKSET_WHY_MAX 256
#define PACKSET_COMMENT_MAX 512

typedef char packset_name[PACKSET_NAME_MAX];

/* The packs under root/packs (directories with a pack.glib; not "common"),
 * sorted by name. Returns how many (at most max). */
int packset_list(const char *root, packset_name *names, int max);
/* The same under a packs folder itself (glib_options.packs_dir). */
int packset_list_dir(const char *packs_dir, packset_name *names, int max);

/* A directory name under packs/: letters, digits, '_', '-', '.', not
 * starting with a dot (no path, no "." or ".."), shorter than
 * PACKSET_NAME_MAX. */
bool packset_name_ok(const char *s);

/* true when root/packs/name/pack.glib exists. */
bool packset_exists(const char *root, const char *name);

typedef struct packset_assign {
    char program[PACKSET_NAME_MAX];   /* a Program, "*" (every one), or "scene" */
    char name[PACKSET_NAME_MAX];      /* the entry, or the world command */
    float value[16];
    int nvalue;
} packset_assign;

typedef struct packset_setting {
    char name[PACKSET_NAME_MAX];
    packset_assign *assign;
    int nassign;
    int line;                         /* in bench.txt; 0 for the implicit default */
    char comment[PACKSET_COMMENT_MAX];  /* the line's own comment, else the comment lines
                                         * right above it ("" none): the panel's tooltip */
} packset_setting;

typedef struct packset_buffer {
    char name[PACKSET_NAME_MAX];      /* a buffer of reference/ref_buffers.h a pack can write */
    packset_setting how;              /* its assignments (how.name = the buffer) */
} packset_buffer;

typedef struct packset_bench {
    char path[1024];                  /* bench.txt ("" when the pack has none) */
    packset_setting *settings;
    int n;
    packset_buffer *buffers;
    int nbuffers;
    float colour[3];                  /* 0..1 sRGB */
    bool has_colour;
} packset_bench;

/* Reads root/packs/pack/bench.txt. A missing file gives one setting,
 * "default". A bad line is skipped with `file:line: message` in err (and
 * false is returned; what was good is kept). */
bool packset_bench_load(const char *root, const char *pack, packset_bench *out, char *err, int errlen);

/* The setting named name, or NULL. */
const packset_setting *packset_setting_named(const packset_bench *b, const char *name);

/* The order a menu lists the settings in: `default` first, then `paper`,
 * then the rest as bench.txt has them. Indices into b->settings, with -1
 * first when bench.txt has no `default` (the pack's defaults, nothing
 * assigned, as packset_setting_named(b, "default") == NULL means). Returns
 * how many (b->n or b->n + 1; order has room for b->n + 1). */
int packset_menu(const packset_bench *b, int *order);

/* Parses bench.txt text (tests). path names it in messages. */
bool packset_bench_parse(const char *text, const char *path, packset_bench *out, char *err, int errlen);
void packset_bench_free(packset_bench *b);

/* Applies a setting's uniform and Define assignments to a render's sets
 * (values through unif_set_component: clamped to the slider's range, a
 * clamp is reported). *defines_changed tells whether a Define changed (the
 * caller rebuilds the programs). False, with one message a line, when a
 * Program or entry is missing or a value was clamped; the rest is applied. */
bool packset_apply(unif_set *sets, int nsets, const packset_setting *s, bool *defines_changed,
                   char *err, int errlen);

/* The setting's scene assignments as glib lines ("WaterMesh 64\n"), or ""
 * when it has none. Returns the length. */
int packset_scene_lines(const packset_setting *s, char *out, int outlen);

/* A wrapper glib that includes scene_path (absolute) and adds the setting's
 * scene lines, written to path. False with a message when it cannot be
 * written. */
bool packset_write_wrapper(const packset_setting *s, const char *scene_path, const char *path, char *err,
                           int errlen);

typedef struct packset_bound {
    char case_name[PACKSET_NAME_MAX];
    double max_rmse;                  /* < 0: no bound ("none") */
    char why[PACKSET_WHY_MAX];
    int line;
} packset_bound;

typedef struct packset_bounds {
    char path[1024];
    bool found;                       /* the file exists */
    packset_bound *b;
    int n;
} packset_bounds;

/* Reads root/packs/pack/bounds.txt (missing: found = false, no bounds). */
bool packset_bounds_load(const char *root, const char *pack, packset_bounds *out, char *err, int errlen);
bool packset_bounds_parse(const char *text, const char *path, packset_bounds *out, char *err, int errlen);
void packset_bounds_free(packset_bounds *b);

/* The bound for a case: its own line, else `*`, else NULL. */
const packset_bound *packset_bound_for(const packset_bounds *b, const char *case_name);

/* The bound a pack gets for a case: its bounds.txt's (packset_bound_for),
 * else the built-in table's line for the case, else its `*` line. *from
 * (may be NULL) says which: the bounds.txt path or "built-in". */
const packset_bound *packset_bound_resolve(const packset_bounds *b, const char *case_name, const char **from);

/* A distinct colour for the i-th pack (tab10), 0..1 sRGB. */
void packset_palette(int i, float rgb[3]);

#endif
