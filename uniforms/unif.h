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
#include "glib.h"

#define UNIF_NAME_MAX 64
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
} unif_entry;

typedef struct unif_set {
    char program[UNIF_NAME_MAX];
    unif_entry *entries;
    int n, cap;
} unif_set;

/* Fills set (zeroed by the caller) from a glib Program command: its uniforms
 * and its defines. Types are guessed from the syntax until the renderer calls
 * unif_set_shader_type(). Returns false with a file:line message in err when a
 * uniform is malformed for its kind (min > max, NaN): the entry is still added
 * with a repaired range so the panel works. */
bool unif_set_from_glib(unif_set *set, const glib_cmd *program, char *err, int errlen);

/* Records the type the linked shader declares for name (and its location).
 * Adds an introspected entry with a sensible default range and widget when
 * the glib did not mention it. Slider of an int uniform becomes an int slider. */
unif_entry *unif_set_shader_type(unif_set *set, const char *name, unif_type type,
                                 int array_len, int location);

unif_entry *unif_find(unif_set *set, const char *name);

/* Carries values over from old into fresh for entries with the same name and
 * type whose glib default is unchanged (a changed default resets that one). */
void unif_merge(unif_set *fresh, const unif_set *old);

void unif_reset(unif_entry *e);          /* value = def */
void unif_reset_all(unif_set *set);

void unif_set_free(unif_set *set);       /* frees entries; set becomes empty */

/* Presets: a small text file next to the glib (FILE.glib -> FILE.preset).
 * Format (versioned): "tarn-preset 1" then `program name v0 v1 ...` lines.
 * Loading skips unknown programs/names and mismatched counts with a message;
 * a corrupt file or another version changes nothing and returns false. */
bool unif_preset_save(const unif_set *sets, int nsets, const char *path, char *err, int errlen);
bool unif_preset_load(unif_set *sets, int nsets, const char *path, char *err, int errlen);
void unif_preset_path(const char *glib_path, char *out, int outlen);

#endif
