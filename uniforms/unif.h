/* unif: the uniform model behind the generated slider panel.
 *
 * One unif_set per linked Program (glman's "rollout"). Entries come from the
 * Program line of the glib (sliders, checkboxes, colours, fixed values), from
 * `Define` toggles (which recompile instead of setting a uniform), and from
 * program introspection for uniforms the glib does not mention. The model
 * has no OpenGL in it: the renderer maps GL types to unif_type and uploads.
 *
 * Values survive a reload: unif_merge() carries each value over from the old
 * set when name and type match and the glib default did not change.
 */
#ifndef TARN_UNIF_H
#define TARN_UNIF_H

#include <stdbool.h>
#include "unif_decl.h"
#include "diag.h"

#ifdef __cplusplus
extern "C" {
#endif

#define UNIF_MAX_COMPONENTS 16

typedef enum unif_type {
    UNIF_FLOAT = 1, UNIF_VEC2, UNIF_VEC3, UNIF_VEC4,
    UNIF_INT, UNIF_BOOL,
    UNIF_MAT3, UNIF_MAT4,
    UNIF_SAMPLER,               /* value[0] is the texture unit */
    UNIF_TYPE_UNKNOWN           /* declared by the glib, not (yet) seen in a shader */
} unif_type;

typedef enum unif_widget {
    UNIF_WIDGET_NONE = 0,       /* fixed value (glib `name 5`, arrays, samplers, built-ins) */
    UNIF_WIDGET_SLIDER,         /* float or int slider over [min, max] */
    UNIF_WIDGET_CHECKBOX,
    UNIF_WIDGET_COLOR,          /* colour picker, 3 or 4 components */
    UNIF_WIDGET_DRAG            /* vector drag for introspected vecN */
} unif_widget;

typedef struct unif_entry {
    char name[UNIF_NAME_MAX];
    unif_type type;             /* from the shader declaration when known */
    unif_widget widget;
    int ncomp;                  /* components in value/def (1..16) */
    int array_len;              /* >1 for `name [a b c]` arrays of scalars */
    float min, max;             /* slider range */
    float def[UNIF_MAX_COMPONENTS];
    float value[UNIF_MAX_COMPONENTS];
    bool is_define;             /* a `Define` toggle: changing it recompiles */
    bool from_glib;             /* written in the glib (false: introspected) */
    bool in_shader;             /* the linked program has it (false: optimised out or absent) */
    const char *glib_file;      /* where the glib wrote it, for messages */
    int glib_line;
    int location;               /* GL uniform location, -1 if none; set by the renderer */
    /* the syntax the glib wrote (0 when introspected), and why it does not fit
     * the type the shader declares (NULL when it fits): see unif_type_mismatch */
    unif_decl_kind glib_kind;
    const char *mismatch;
} unif_entry;

typedef struct unif_set {
    char program[UNIF_NAME_MAX];
    unif_entry *entries;
    int n, cap;
} unif_set;

/* Fills set (zeroed by the caller) from a Program's declarations: its
 * uniforms and its defines (glib_program_decl gives them for a Program
 * command). Types are guessed from the syntax until the renderer calls
 * unif_set_shader_type(). Returns false with a warning at its file and line in dl when a
 * uniform is malformed for its kind (min > max, NaN): the entry is still added
 * with a repaired range so the panel works.
 *
 * Entries: the defines first (file order), then the uniforms. Guessed types:
 * slider FLOAT, checkbox BOOL, colour VEC3/VEC4, number FLOAT, [array] FLOAT
 * with array_len n. A define `<min default max>` or number is INT when all
 * its numbers are whole. Repairs (each a message): non-finite numbers (NaN,
 * inf, beyond float) become 0 (min 0 / max 1), min > max is swapped, a
 * default outside the range is clamped, a wrong count of numbers is padded
 * or cut; a name written twice keeps the last. Each repair is a warning in
 * dl (may be NULL): "uniform 'uX': min 5 is greater than max 0; swapped". */
bool unif_set_from_decls(unif_set *set, const unif_program_decl *program, diag_list *dl);

/* Records the type the linked shader declares for name (and its location).
 * Adds an introspected entry with a sensible default range and widget when
 * the glib did not mention it. Slider of an int uniform becomes an int slider.
 *
 * name may be GL's array spelling "a[0]"; names starting "gl_" are built-ins
 * and are ignored (NULL). array_len is GL's size (1 for a non-array).
 * Fitting the glib syntax to the declaration: `[a b c]` fills a vecN/matN or
 * an array of them when the count fits; a colour {r g b} for a vec4 gets
 * alpha 1 (value[3], ncomp stays 3), {r g b a} for a vec3 drops alpha; int,
 * bool and sampler values are rounded. A syntax that cannot set the declared
 * type (a colour for a float, a slider for a vec3) is left as written and
 * gets a reason in entry->mismatch; such an entry is not uploaded.
 * Introspected entries: float -> slider 0..1 (default 0), int -> slider
 * 0..10, bool -> checkbox, vec2/vec3/vec4 -> DRAG (unbounded: min == max),
 * a vec3/vec4 whose name contains "color"/"colour" -> COLOR (default white),
 * mat/sampler/arrays and `Timer` -> NONE (the renderer owns those; a sampler
 * named Noise2/Noise3 shows unit 2/3).
 * The returned pointer is valid until the next entry is added to the set. */
unif_entry *unif_set_shader_type(unif_set *set, const char *name, unif_type type,
                                 int array_len, int location);

/* Why the glib's syntax does not fit the shader's type, or NULL when it fits
 * (or the shader type is not known yet, or the entry was introspected). */
const char *unif_type_mismatch(const unif_entry *e);

/* Writes `file:line: uniform 'x': REASON, but the shader declares TYPE` for a
 * mismatched entry; returns the length written (0 and "" when it fits). */
int unif_describe_mismatch(const unif_entry *e, char *out, int outlen);

/* true for an entry the renderer should upload with glUniform*: in the
 * linked shader with a location, not a define, no mismatch, and not an
 * introspected fixed value (matrices, samplers, Timer: the renderer's own). */
bool unif_uploadable(const unif_entry *e);

/* Components one value of the type has (vec3 3, mat4 16; 0 for unknown),
 * and its GLSL name ("vec3"). */
int unif_type_components(unif_type type);
const char *unif_type_name(unif_type type);

/* true when the entry holds whole numbers (int, sampler, an int define). */
bool unif_is_int(const unif_entry *e);

/* Sets value[i] from a widget: clamped to [min, max] for a slider, rounded
 * for an int, 0/1 for a checkbox; NaN and out-of-range i are ignored.
 * Returns true when the value changed. */
bool unif_set_component(unif_entry *e, int i, double v);

/* true when value equals def (the reset button has nothing to do). */
bool unif_is_default(const unif_entry *e);

unif_entry *unif_find(unif_set *set, const char *name);

/* Carries values over from old into fresh for entries with the same name and
 * type whose glib default is unchanged (a changed default resets that one).
 * "Same" means: same name, define-ness, widget, glib syntax, ncomp and
 * array_len, and the same type when both sides know the shader's type; the
 * default is def[], min and max. Call it after unif_set_shader_type() has
 * run on fresh for every active uniform, so introspected entries and int
 * sliders are in place (merging before as well is fine: a float slider
 * that turns int resets when its type arrives). Entries missing from fresh
 * are dropped. */
void unif_merge(unif_set *fresh, const unif_set *old);

void unif_reset(unif_entry *e);          /* value = def */
void unif_reset_all(unif_set *set);
/* unif_reset_all that returns true when a define changed (recompile). */
bool unif_reset_all_ex(unif_set *set);

/* The text a define entry stands for in `#define NAME text`: "1"/"0" for a
 * bool, "3" for an int, "0.25" (always with a '.' or exponent) for a float.
 * Returns the length (snprintf-style). */
int unif_define_value(const unif_entry *e, char *out, int outlen);

void unif_set_free(unif_set *set);       /* frees entries; set becomes empty */

/* Presets: a small text file next to the glib (FILE.glib -> FILE.preset).
 * Format (versioned): "tarn-preset 1" then `program name v0 v1 ...` lines.
 * Loading skips unknown programs/names and mismatched counts with a message;
 * a corrupt file or another version changes nothing and returns false. */
bool unif_preset_save(const unif_set *sets, int nsets, const char *path, char *err, int errlen);
bool unif_preset_load(unif_set *sets, int nsets, const char *path, char *err, int errlen);
/* unif_preset_load that also says whether a define's value changed (the
 * program must be recompiled); defines_changed may be NULL.
 * On true err holds the skip messages, one a line ("" when none). Values
 * are clamped to the current ranges (and rounded for ints) as they load.
 * Fixed entries (widget NONE) are neither saved nor loaded. */
bool unif_preset_load_ex(unif_set *sets, int nsets, const char *path, char *err, int errlen,
                         bool *defines_changed);
/* dir/scene.glib -> dir/scene.preset (any extension of the file name is
 * replaced, none is appended to); "" when out is too small. */
void unif_preset_path(const char *glib_path, char *out, int outlen);

#ifdef __cplusplus
}
#endif

#endif
