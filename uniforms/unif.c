/* unif: the uniform model behind the generated slider panel (see unif.h). */
#include "unif.h"

#include "file.h"
#include "mem.h"
#include "strbuf.h"

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PRESET_MAGIC "tarn-preset"
#define PRESET_VERSION 1
#define PRESET_MAX_BYTES (16L * 1024 * 1024)

/* ---- messages ---------------------------------------------------------- */

static void copy_name(char *dst, const char *src) {
    snprintf(dst, UNIF_NAME_MAX, "%s", src ? src : "");
}

/* ---- small helpers ----------------------------------------------------- */

static bool to_float(double d, float *out) {
    *out = 0.0f;
    if (!isfinite(d) || fabs(d) > (double)FLT_MAX) return false;
    *out = (float)d;
    return true;
}

static float clampf(float v, float lo, float hi) {
    return v < lo ? lo : v > hi ? hi : v;
}

static bool is_whole(float v) { return floorf(v) == v; }

static bool name_says_colour(const char *name) {
    char low[UNIF_NAME_MAX];
    size_t i = 0;
    for (; name[i] && i + 1 < sizeof low; i++) low[i] = (char)tolower((unsigned char)name[i]);
    low[i] = '\0';
    return strstr(low, "color") || strstr(low, "colour");
}

int unif_type_components(unif_type type) {
    switch (type) {
    case UNIF_FLOAT: case UNIF_INT: case UNIF_BOOL: case UNIF_SAMPLER: return 1;
    case UNIF_VEC2: return 2;
    case UNIF_VEC3: return 3;
    case UNIF_VEC4: return 4;
    case UNIF_MAT3: return 9;
    case UNIF_MAT4: return 16;
    default: return 0;
    }
}

const char *unif_type_name(unif_type type) {
    switch (type) {
    case UNIF_FLOAT: return "float";
    case UNIF_VEC2: return "vec2";
    case UNIF_VEC3: return "vec3";
    case UNIF_VEC4: return "vec4";
    case UNIF_INT: return "int";
    case UNIF_BOOL: return "bool";
    case UNIF_MAT3: return "mat3";
    case UNIF_MAT4: return "mat4";
    case UNIF_SAMPLER: return "sampler";
    default: return "unknown type";
    }
}

bool unif_is_int(const unif_entry *e) {
    return e && (e->type == UNIF_INT || e->type == UNIF_SAMPLER);
}

static void round_values(unif_entry *e) {
    for (int i = 0; i < UNIF_MAX_COMPONENTS; i++) {
        e->def[i] = roundf(e->def[i]);
        e->value[i] = roundf(e->value[i]);
    }
}

static void bool_values(unif_entry *e) {
    for (int i = 0; i < UNIF_MAX_COMPONENTS; i++) {
        e->def[i] = e->def[i] != 0.0f ? 1.0f : 0.0f;
        e->value[i] = e->value[i] != 0.0f ? 1.0f : 0.0f;
    }
}

/* ---- the set ----------------------------------------------------------- */

static unif_entry *set_push(unif_set *set) {
    set->entries = mem_grow(set->entries, &set->cap, set->n + 1, sizeof *set->entries);
    unif_entry *e = &set->entries[set->n++];
    memset(e, 0, sizeof *e);
    e->array_len = 1;
    e->location = -1;
    return e;
}

static unif_entry *find_kind(unif_set *set, const char *name, bool is_define) {
    for (int i = 0; i < set->n; i++)
        if (set->entries[i].is_define == is_define && strcmp(set->entries[i].name, name) == 0)
            return &set->entries[i];
    return NULL;
}

unif_entry *unif_find(unif_set *set, const char *name) {
    if (!set || !name) return NULL;
    for (int i = 0; i < set->n; i++)
        if (strcmp(set->entries[i].name, name) == 0) return &set->entries[i];
    return NULL;
}

void unif_set_free(unif_set *set) {
    if (!set) return;
    free(set->entries);
    set->entries = NULL;
    set->n = set->cap = 0;
}

/* ---- from the glib ----------------------------------------------------- */

typedef struct where {
    const char *file, *what, *name;
    int line;
    diag_list *dl;   /* may be NULL */
    bool ok;
} where;

static void problem(where *w, const char *fmt, ...) {
    char text[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    if (w->dl) diag_add(w->dl, DIAG_WARNING, w->file, w->line, "%s '%s': %s", w->what, w->name, text);
    w->ok = false;
}

/* Repairs <min default max> in place; messages through w. */
static void repair_slider(where *w, const unif_decl *u, int n, float *lo, float *df, float *hi) {
    double v[3] = {0.0, 0.0, 1.0};
    if (n >= 3) {
        for (int i = 0; i < 3; i++) v[i] = u->v[i];
        if (n > 3) problem(w, "a slider takes <min default max>, got %d numbers; the rest are ignored", n);
    } else if (n == 2) {
        v[0] = u->v[0]; v[1] = u->v[0]; v[2] = u->v[1];
        problem(w, "a slider takes <min default max>, got 2 numbers; using the first as min and default");
    } else if (n == 1) {
        v[1] = u->v[0];
        if (isfinite(v[1])) { v[0] = fmin(0.0, v[1]); v[2] = fmax(1.0, v[1]); }
        problem(w, "a slider takes <min default max>, got 1 number; using it as the default");
    } else {
        problem(w, "a slider takes <min default max>, got no numbers; using <0 0 1>");
    }
    bool okl = to_float(v[0], lo), okd = to_float(v[1], df), okh = to_float(v[2], hi);
    if (!okl && !okh) { *lo = 0.0f; *hi = 1.0f; }
    else if (!okl) *lo = fminf(0.0f, *hi - 1.0f);
    else if (!okh) *hi = fmaxf(1.0f, *lo + 1.0f);
    if (!okl) problem(w, "min is not a finite number; using %g", (double)*lo);
    if (!okh) problem(w, "max is not a finite number; using %g", (double)*hi);
    if (*lo > *hi) {
        problem(w, "min %g is greater than max %g; swapped", (double)*lo, (double)*hi);
        float t = *lo; *lo = *hi; *hi = t;
    }
    if (!okd) {
        *df = *lo;
        problem(w, "default is not a finite number; using %g", (double)*df);
    } else if (*df < *lo || *df > *hi) {
        float c = clampf(*df, *lo, *hi);
        problem(w, "default %g is outside <%g .. %g>; clamped to %g",
                (double)*df, (double)*lo, (double)*hi, (double)c);
        *df = c;
    }
}

/* Reads component i of u, 0 with a message when not a finite number. */
static float number_at(where *w, const unif_decl *u, int i, const char *label) {
    float f;
    if (to_float(u->v[i], &f)) return f;
    if (label) problem(w, "%s is not a finite number; using 0", label);
    else problem(w, "number %d is not a finite number; using 0", i + 1);
    return 0.0f;
}

static bool fill_entry(unif_entry *e, const unif_decl *u, bool is_define, where *w) {
    int n = u->n < 0 ? 0 : u->n > UNIF_DECL_MAX_NUMS ? UNIF_DECL_MAX_NUMS : u->n;
    if (n > UNIF_MAX_COMPONENTS) n = UNIF_MAX_COMPONENTS;
    copy_name(e->name, u->name);
    e->is_define = is_define;
    e->from_glib = true;
    e->glib_file = w->file;
    e->glib_line = w->line;
    e->glib_kind = u->kind;
    e->ncomp = 1;
    switch (u->kind) {
    case UNIF_DECL_SLIDER: {
        float lo, df, hi;
        repair_slider(w, u, n, &lo, &df, &hi);
        e->widget = UNIF_WIDGET_SLIDER;
        e->type = UNIF_FLOAT;
        e->min = lo; e->max = hi; e->def[0] = df;
        if (is_define && is_whole(lo) && is_whole(df) && is_whole(hi)) e->type = UNIF_INT;
        break;
    }
    case UNIF_DECL_BOOL:
        e->widget = UNIF_WIDGET_CHECKBOX;
        e->type = UNIF_BOOL;
        e->max = 1.0f;
        if (n != 1) problem(w, "a checkbox takes <true> or <false>, got %d values", n);
        if (n >= 1) e->def[0] = number_at(w, u, 0, "the checkbox value") != 0.0f ? 1.0f : 0.0f;
        break;
    case UNIF_DECL_COLOR:
        if (is_define) { problem(w, "a define takes <true|false>, a number or <min default max>; ignored"); return false; }
        e->widget = UNIF_WIDGET_COLOR;
        e->ncomp = n < 3 ? 3 : n > 4 ? 4 : n;
        e->type = e->ncomp == 4 ? UNIF_VEC4 : UNIF_VEC3;
        if (n < 3 || n > 4)
            problem(w, "a colour takes {r g b} or {r g b a}, got %d numbers; %s", n,
                    n < 3 ? "the missing ones are 0" : "the rest are ignored");
        for (int i = 0; i < e->ncomp && i < n; i++) e->def[i] = number_at(w, u, i, NULL);
        break;
    case UNIF_DECL_SCALAR:
        e->widget = UNIF_WIDGET_NONE;
        e->type = UNIF_FLOAT;
        if (n != 1)
            problem(w, "a fixed value takes one number, got %d; %s", n,
                    n == 0 ? "using 0" : "using the first");
        if (n >= 1) e->def[0] = number_at(w, u, 0, "the value");
        if (is_define && is_whole(e->def[0])) e->type = UNIF_INT;
        break;
    case UNIF_DECL_ARRAY:
        if (is_define) { problem(w, "a define takes <true|false>, a number or <min default max>; ignored"); return false; }
        e->widget = UNIF_WIDGET_NONE;
        e->type = UNIF_FLOAT;
        if (n == 0) {
            problem(w, "an empty array []; using a single 0");
        } else {
            e->ncomp = n;
            e->array_len = n;
            for (int i = 0; i < n; i++) e->def[i] = number_at(w, u, i, NULL);
        }
        break;
    default:
        problem(w, "unknown uniform kind %d; ignored", (int)u->kind);
        return false;
    }
    memcpy(e->value, e->def, sizeof e->value);
    return true;
}

static void add_decl(unif_set *set, const unif_decl *u, bool is_define,
                     const unif_program_decl *cmd, diag_list *dl, bool *ok) {
    where w = {
        .file = u->file ? u->file : cmd->file ? cmd->file : "(glib)",
        .what = is_define ? "define" : "uniform",
        .name = u->name,
        .line = u->line > 0 ? u->line : cmd->line,
        .dl = dl, .ok = true,
    };
    if (u->name[0] == '\0') {
        w.name = "";
        problem(&w, "has no name; ignored");
        *ok = false;
        return;
    }
    char name[UNIF_NAME_MAX];
    copy_name(name, u->name);
    unif_entry *e = find_kind(set, name, is_define);
    if (e) {
        problem(&w, "written twice (first at line %d); the last one is used", e->glib_line);
    } else {
        e = set_push(set);
    }
    unif_entry fresh;
    memset(&fresh, 0, sizeof fresh);
    fresh.array_len = 1;
    fresh.location = -1;
    if (fill_entry(&fresh, u, is_define, &w)) {
        *e = fresh;
    } else if (e == &set->entries[set->n - 1] && e->name[0] == '\0') {
        set->n--;              /* the slot just pushed: give it back */
    }
    if (!w.ok) *ok = false;
}

bool unif_set_from_decls(unif_set *set, const unif_program_decl *program, diag_list *dl) {
    if (!set || !program) return false;
    copy_name(set->program, program->name ? program->name : "");
    bool ok = true;
    for (int i = 0; program->defines && i < program->ndefines; i++)
        add_decl(set, &program->defines[i], true, program, dl, &ok);
    for (int i = 0; program->uniforms && i < program->nuniforms; i++)
        add_decl(set, &program->uniforms[i], false, program, dl, &ok);
    return ok;
}

/* ---- shader types ------------------------------------------------------ */

static const char *const MISMATCH_SCALAR = "a single number fits a float, int, bool or sampler";
static const char *const MISMATCH_ARRAY_FILL = "the numbers in [ ] do not make whole values of that type";
static const char *const MISMATCH_ARRAY_LONG = "more numbers in [ ] than the shader's array holds";
static const char *const MISMATCH_SLIDER = "a slider <min default max> fits a float or int";
static const char *const MISMATCH_BOOL = "a checkbox <true|false> fits a bool, int or float";
static const char *const MISMATCH_COLOR = "a colour {r g b [a]} fits a vec3 or vec4";

/* Fits a glib-written entry to the declared type (see unif.h); prev is the
 * type it had (the syntax's guess, or an earlier shader's). */
static void fit_to_shader(unif_entry *e, unif_type prev, unif_type t, int shader_len) {
    e->mismatch = NULL;
    bool whole = t == UNIF_INT || t == UNIF_SAMPLER;
    switch (e->glib_kind) {
    case UNIF_DECL_SCALAR:
        if (t == UNIF_FLOAT) break;
        if (whole) round_values(e);
        else if (t == UNIF_BOOL) bool_values(e);
        else e->mismatch = MISMATCH_SCALAR;
        break;
    case UNIF_DECL_ARRAY: {
        int c = unif_type_components(t);
        if (c == 0 || e->ncomp % c != 0) { e->mismatch = MISMATCH_ARRAY_FILL; break; }
        if (e->ncomp / c > shader_len) { e->mismatch = MISMATCH_ARRAY_LONG; break; }
        e->array_len = e->ncomp / c;
        if (whole) round_values(e);
        else if (t == UNIF_BOOL) bool_values(e);
        break;
    }
    case UNIF_DECL_SLIDER:
        if (t == UNIF_FLOAT) break;
        if (t != UNIF_INT) { e->mismatch = MISMATCH_SLIDER; break; }
        e->min = roundf(e->min);
        e->max = roundf(e->max);
        round_values(e);
        e->def[0] = clampf(e->def[0], e->min, e->max);
        e->value[0] = clampf(e->value[0], e->min, e->max);
        /* a float slider becoming an int one is a type change: a value carried
         * over from the float slider resets (an int one seen again keeps it) */
        if (prev != UNIF_INT) e->value[0] = e->def[0];
        break;
    case UNIF_DECL_BOOL:
        if (t != UNIF_BOOL && t != UNIF_INT && t != UNIF_FLOAT) e->mismatch = MISMATCH_BOOL;
        break;
    case UNIF_DECL_COLOR:
        if (t == UNIF_VEC3) {
            e->ncomp = 3;               /* {r g b a}: alpha has nowhere to go */
        } else if (t == UNIF_VEC4) {
            if (e->ncomp == 3) { e->def[3] = 1.0f; e->value[3] = 1.0f; }
        } else {
            e->mismatch = MISMATCH_COLOR;
        }
        break;
    default:
        break;
    }
}

static void set_identity(unif_entry *e, int dim) {
    for (int i = 0; i < dim; i++) e->def[i * dim + i] = 1.0f;
}

static void fill_introspected(unif_entry *e, const char *name, unif_type t, int len) {
    copy_name(e->name, name);
    e->type = t;
    e->from_glib = false;
    e->glib_kind = 0;
    int c = unif_type_components(t);
    if (c == 0) c = 1;
    if (len > 1) {
        int fit = UNIF_MAX_COMPONENTS / c;
        if (fit < 1) fit = 1;
        e->array_len = len < fit ? len : fit;
        e->ncomp = c * e->array_len;
        e->widget = UNIF_WIDGET_NONE;
        if (e->ncomp > UNIF_MAX_COMPONENTS) e->ncomp = UNIF_MAX_COMPONENTS;
    } else {
        e->array_len = 1;
        e->ncomp = c;
        switch (t) {
        case UNIF_FLOAT:
            if (strcmp(name, "Timer") == 0) { e->widget = UNIF_WIDGET_NONE; break; }
            e->widget = UNIF_WIDGET_SLIDER; e->min = 0.0f; e->max = 1.0f;
            break;
        case UNIF_INT:
            e->widget = UNIF_WIDGET_SLIDER; e->min = 0.0f; e->max = 10.0f;
            break;
        case UNIF_BOOL:
            e->widget = UNIF_WIDGET_CHECKBOX; e->max = 1.0f;
            break;
        case UNIF_VEC3: case UNIF_VEC4:
            if (name_says_colour(name)) {
                e->widget = UNIF_WIDGET_COLOR;
                e->min = 0.0f; e->max = 1.0f;
                for (int i = 0; i < c; i++) e->def[i] = 1.0f;
                break;
            }
            e->widget = UNIF_WIDGET_DRAG;
            break;
        case UNIF_VEC2:
            e->widget = UNIF_WIDGET_DRAG;
            break;
        case UNIF_MAT3: set_identity(e, 3); e->widget = UNIF_WIDGET_NONE; break;
        case UNIF_MAT4: set_identity(e, 4); e->widget = UNIF_WIDGET_NONE; break;
        case UNIF_SAMPLER:
            e->widget = UNIF_WIDGET_NONE;
            if (strcmp(name, "Noise2") == 0) e->def[0] = 2.0f;
            else if (strcmp(name, "Noise3") == 0) e->def[0] = 3.0f;
            break;
        default:
            e->widget = UNIF_WIDGET_NONE;
            break;
        }
    }
    memcpy(e->value, e->def, sizeof e->value);
}

unif_entry *unif_set_shader_type(unif_set *set, const char *name, unif_type type,
                                 int array_len, int location) {
    if (!set || !name || !name[0]) return NULL;
    if (strncmp(name, "gl_", 3) == 0) return NULL;
    char base[UNIF_NAME_MAX];
    copy_name(base, name);
    size_t len = strlen(base);
    if (len > 3 && strcmp(base + len - 3, "[0]") == 0) base[len - 3] = '\0';
    if (array_len < 1) array_len = 1;
    if (type < UNIF_FLOAT || type > UNIF_TYPE_UNKNOWN) type = UNIF_TYPE_UNKNOWN;

    unif_entry *e = find_kind(set, base, false);
    if (!e) {
        e = set_push(set);
        fill_introspected(e, base, type, array_len);
    } else if (e->from_glib) {
        unif_type prev = e->type;
        e->type = type;
        if (type != UNIF_TYPE_UNKNOWN) fit_to_shader(e, prev, type, array_len);
    } else if (e->type != type || (array_len > 1) != (e->array_len > 1)) {
        memset(e, 0, sizeof *e);       /* introspected again with another type */
        fill_introspected(e, base, type, array_len);
    }
    e->location = location;
    e->in_shader = true;
    return e;
}

const char *unif_type_mismatch(const unif_entry *e) {
    return e ? e->mismatch : NULL;
}

int unif_describe_mismatch(const unif_entry *e, char *out, int outlen) {
    if (!out || outlen <= 0) return 0;
    out[0] = '\0';
    if (!e || !e->mismatch) return 0;
    int n = snprintf(out, (size_t)outlen, "%s:%d: uniform '%s': %s, but the shader declares %s",
                     e->glib_file ? e->glib_file : "(glib)", e->glib_line, e->name, e->mismatch,
                     unif_type_name(e->type));
    return n < 0 ? 0 : n >= outlen ? outlen - 1 : n;
}

bool unif_uploadable(const unif_entry *e) {
    if (!e || e->is_define || !e->in_shader || e->location < 0 || e->mismatch) return false;
    if (e->type == UNIF_TYPE_UNKNOWN || unif_type_components(e->type) == 0) return false;
    if (!e->from_glib && e->widget == UNIF_WIDGET_NONE) return false;
    return true;
}

/* ---- values ------------------------------------------------------------ */

bool unif_set_component(unif_entry *e, int i, double v) {
    if (!e || i < 0 || i >= UNIF_MAX_COMPONENTS || isnan(v)) return false;
    if (v > (double)FLT_MAX) v = FLT_MAX;
    if (v < -(double)FLT_MAX) v = -FLT_MAX;
    float f = (float)v;
    if (e->widget == UNIF_WIDGET_CHECKBOX || e->type == UNIF_BOOL) f = f != 0.0f ? 1.0f : 0.0f;
    else if (unif_is_int(e)) f = roundf(f);
    if (e->widget == UNIF_WIDGET_SLIDER) f = clampf(f, e->min, e->max);
    if (e->value[i] == f) return false;
    e->value[i] = f;
    return true;
}

bool unif_is_default(const unif_entry *e) {
    if (!e) return true;
    for (int i = 0; i < UNIF_MAX_COMPONENTS; i++)
        if (e->value[i] != e->def[i]) return false;
    return true;
}

void unif_reset(unif_entry *e) {
    if (e) memcpy(e->value, e->def, sizeof e->value);
}

bool unif_reset_all_ex(unif_set *set) {
    bool defines = false;
    if (!set) return false;
    for (int i = 0; i < set->n; i++) {
        unif_entry *e = &set->entries[i];
        if (e->is_define && !unif_is_default(e)) defines = true;
        unif_reset(e);
    }
    return defines;
}

void unif_reset_all(unif_set *set) { (void)unif_reset_all_ex(set); }

int unif_define_value(const unif_entry *e, char *out, int outlen) {
    char text[64];
    if (!e) text[0] = '\0';
    else if (e->type == UNIF_BOOL || e->widget == UNIF_WIDGET_CHECKBOX)
        snprintf(text, sizeof text, "%d", e->value[0] != 0.0f ? 1 : 0);
    else if (unif_is_int(e))
        snprintf(text, sizeof text, "%ld", lroundf(e->value[0]));
    else {
        snprintf(text, sizeof text, "%.9g", (double)e->value[0]);
        if (!strpbrk(text, ".eEni")) strcat(text, ".0");
    }
    if (out && outlen > 0) snprintf(out, (size_t)outlen, "%s", text);
    return (int)strlen(text);
}

/* ---- merge ------------------------------------------------------------- */

static bool same_shape(const unif_entry *a, const unif_entry *b) {
    if (a->is_define != b->is_define || a->widget != b->widget || a->glib_kind != b->glib_kind)
        return false;
    if (a->ncomp != b->ncomp || a->array_len != b->array_len) return false;
    if (a->type != b->type) {
        /* a type still guessed from the syntax does not count as a change */
        bool a_known = a->in_shader || a->is_define, b_known = b->in_shader || b->is_define;
        if (a_known && b_known) return false;
    }
    return true;
}

static bool same_default(const unif_entry *a, const unif_entry *b) {
    if (a->from_glib != b->from_glib || a->min != b->min || a->max != b->max) return false;
    for (int i = 0; i < UNIF_MAX_COMPONENTS; i++)
        if (a->def[i] != b->def[i]) return false;
    return true;
}

void unif_merge(unif_set *fresh, const unif_set *old) {
    if (!fresh || !old) return;
    for (int i = 0; i < fresh->n; i++) {
        unif_entry *f = &fresh->entries[i];
        const unif_entry *o = NULL;
        for (int j = 0; j < old->n && !o; j++)
            if (old->entries[j].is_define == f->is_define && strcmp(old->entries[j].name, f->name) == 0)
                o = &old->entries[j];
        if (!o || !same_shape(f, o) || !same_default(f, o)) continue;
        memcpy(f->value, o->value, sizeof f->value);
    }
}

/* ---- presets ----------------------------------------------------------- */

static const char *preset_program_token(const char *program) {
    return program[0] ? program : "-";
}

bool unif_preset_save(const unif_set *sets, int nsets, const char *path, char *err, int errlen) {
    msg_clear(err, errlen);
    if (!path || !path[0]) { msg_add(err, errlen, "preset: no path to save to"); return false; }
    size_t plen = strlen(path);
    char *tmp = mem_alloc(plen + 5);
    memcpy(tmp, path, plen);
    memcpy(tmp + plen, ".tmp", 5);

    FILE *f = fopen(tmp, "w");
    if (!f) {
        msg_add(err, errlen, "%s: cannot write the preset: %s", tmp, strerror(errno));
        free(tmp);
        return false;
    }
    fprintf(f, "%s %d\n# program uniform count values...\n", PRESET_MAGIC, PRESET_VERSION);
    for (int s = 0; sets && s < nsets; s++) {
        for (int i = 0; i < sets[s].n; i++) {
            const unif_entry *e = &sets[s].entries[i];
            if (e->widget == UNIF_WIDGET_NONE || e->ncomp < 1 || e->ncomp > UNIF_MAX_COMPONENTS) continue;
            fprintf(f, "%s %s %d", preset_program_token(sets[s].program), e->name, e->ncomp);
            for (int k = 0; k < e->ncomp; k++) fprintf(f, " %.9g", (double)e->value[k]);
            fputc('\n', f);
        }
    }
    int saved_errno = 0;
    bool ok = !ferror(f);
    if (ok && fflush(f) != 0) { ok = false; saved_errno = errno; }
    if (ok && fsync(fileno(f)) != 0 && errno != EINVAL && errno != EROFS) { ok = false; saved_errno = errno; }
    if (fclose(f) != 0 && ok) { ok = false; saved_errno = errno; }
    if (ok && rename(tmp, path) != 0) {
        saved_errno = errno;
        msg_add(err, errlen, "%s: cannot replace the preset: %s", path, strerror(saved_errno));
        remove(tmp);
        free(tmp);
        return false;
    }
    if (!ok) {
        msg_add(err, errlen, "%s: writing the preset failed: %s", tmp,
                saved_errno ? strerror(saved_errno) : "I/O error");
        remove(tmp);
    }
    free(tmp);
    return ok;
}

static char *read_file(const char *path, long *len_out, char *err, int errlen) {
    char why[MSG_MAX];
    size_t len = 0;
    file_text_opts o = { .max_bytes = PRESET_MAX_BYTES, .reject_nul = true };
    char *buf = file_read_text(path, &o, &len, why, sizeof why);
    if (!buf) { msg_add(err, errlen, "%s: cannot read the preset: %s", path, why); return NULL; }
    *len_out = (long)len;
    return buf;
}

/* Splits line (modified in place) into at most max whitespace-separated
 * tokens; returns the count, or max + 1 when there are more. */
static int tokenize(char *line, char **tok, int max) {
    int n = 0;
    char *p = line;
    for (;;) {
        while (*p && isspace((unsigned char)*p)) p++;
        if (!*p) return n;
        if (n == max) return max + 1;
        tok[n++] = p;
        while (*p && !isspace((unsigned char)*p)) p++;
        if (*p) *p++ = '\0';
    }
}

static bool parse_float(const char *s, float *out) {
    char *end;
    errno = 0;
    float f = strtof(s, &end);
    if (end == s || *end != '\0' || !isfinite(f)) return false;
    *out = f;
    return true;
}

static bool parse_int(const char *s, long *out) {
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE) return false;
    *out = v;
    return true;
}

bool unif_preset_load(unif_set *sets, int nsets, const char *path, char *err, int errlen) {
    return unif_preset_load_ex(sets, nsets, path, err, errlen, NULL);
}

bool unif_preset_load_ex(unif_set *sets, int nsets, const char *path, char *err, int errlen,
                         bool *defines_changed) {
    msg_clear(err, errlen);
    if (defines_changed) *defines_changed = false;
    if (!path || !path[0]) { msg_add(err, errlen, "preset: no path to load from"); return false; }
    long len = 0;
    char *text = read_file(path, &len, err, errlen);
    if (!text) return false;

    /* stage: copies of every entry; the sets change only when all parsed */
    unif_set *stage = mem_zalloc((nsets > 0 ? (size_t)nsets : 1) * sizeof *stage);
    bool ok = true;
    for (int s = 0; s < nsets; s++) {
        stage[s] = sets[s];
        stage[s].entries = NULL;
        stage[s].cap = stage[s].n;
        if (sets[s].n > 0) {
            stage[s].entries = mem_alloc((size_t)sets[s].n * sizeof *stage[s].entries);
            memcpy(stage[s].entries, sets[s].entries, (size_t)sets[s].n * sizeof *stage[s].entries);
        }
    }

    bool header = false;
    int lineno = 0;
    char *p = text, *end = text + len;
    while (ok && p < end) {
        char *line = p;
        char *nl = memchr(p, '\n', (size_t)(end - p));
        if (nl) { *nl = '\0'; p = nl + 1; } else p = end;
        lineno++;
        char *tok[3 + UNIF_MAX_COMPONENTS];
        int ntok = tokenize(line, tok, 3 + UNIF_MAX_COMPONENTS);
        if (ntok == 0 || tok[0][0] == '#') continue;
        if (!header) {
            long version;
            if (strcmp(tok[0], PRESET_MAGIC) != 0) {
                msg_add(err, errlen, "%s:%d: not a tarn preset (expected '%s %d')", path, lineno,
                        PRESET_MAGIC, PRESET_VERSION);
                ok = false;
            } else if (ntok != 2 || !parse_int(tok[1], &version)) {
                msg_add(err, errlen, "%s:%d: bad preset header (expected '%s %d')", path, lineno,
                        PRESET_MAGIC, PRESET_VERSION);
                ok = false;
            } else if (version != PRESET_VERSION) {
                msg_add(err, errlen, "%s:%d: preset version %ld is not supported (this tarn reads version %d); nothing loaded",
                        path, lineno, version, PRESET_VERSION);
                ok = false;
            }
            header = true;
            continue;
        }
        if (ntok > 3 + UNIF_MAX_COMPONENTS) {
            msg_add(err, errlen, "%s:%d: more than %d values; the preset is corrupt", path, lineno,
                    UNIF_MAX_COMPONENTS);
            ok = false;
            break;
        }
        long count;
        if (ntok < 4 || !parse_int(tok[2], &count) || count < 1 || count > UNIF_MAX_COMPONENTS) {
            msg_add(err, errlen, "%s:%d: expected 'program uniform count values...'; the preset is corrupt",
                    path, lineno);
            ok = false;
            break;
        }
        if (ntok - 3 != count) {
            msg_add(err, errlen, "%s:%d: count %ld but %d values; the preset is corrupt", path, lineno,
                    count, ntok - 3);
            ok = false;
            break;
        }
        float vals[UNIF_MAX_COMPONENTS];
        for (int k = 0; k < count; k++) {
            if (!parse_float(tok[3 + k], &vals[k])) {
                msg_add(err, errlen, "%s:%d: '%s' is not a number; the preset is corrupt", path, lineno,
                        tok[3 + k]);
                ok = false;
                break;
            }
        }
        if (!ok) break;

        const char *prog = strcmp(tok[0], "-") == 0 ? "" : tok[0];
        bool program_seen = false, applied = false;
        for (int s = 0; s < nsets; s++) {
            if (strcmp(stage[s].program, prog) != 0) continue;
            program_seen = true;
            unif_entry *e = NULL;
            for (int i = 0; i < stage[s].n && !e; i++)
                if (strcmp(stage[s].entries[i].name, tok[1]) == 0 &&
                    stage[s].entries[i].widget != UNIF_WIDGET_NONE)
                    e = &stage[s].entries[i];
            if (!e) continue;
            if (e->ncomp != count) {
                msg_add(err, errlen, "%s:%d: '%s' in program '%s' has %d values, the preset %ld; skipped",
                        path, lineno, tok[1], tok[0], e->ncomp, count);
                applied = true;
                continue;
            }
            bool clamped = false;
            for (int k = 0; k < count; k++) {
                unif_set_component(e, k, vals[k]);
                if (e->value[k] != vals[k]) clamped = true;
            }
            if (clamped)
                msg_add(err, errlen, "%s:%d: '%s' in program '%s': a value outside its range was clamped",
                        path, lineno, tok[1], tok[0]);
            applied = true;
        }
        if (!program_seen)
            msg_add(err, errlen, "%s:%d: no program '%s' in this scene; skipped", path, lineno, tok[0]);
        else if (!applied)
            msg_add(err, errlen, "%s:%d: program '%s' has no uniform '%s' with a widget; skipped",
                    path, lineno, tok[0], tok[1]);
    }
    if (ok && !header) {
        msg_add(err, errlen, "%s: empty, not a tarn preset", path);
        ok = false;
    }
    if (ok) {
        for (int s = 0; s < nsets; s++) {
            for (int i = 0; i < sets[s].n; i++) {
                unif_entry *e = &sets[s].entries[i];
                const unif_entry *st = &stage[s].entries[i];
                if (e->is_define && memcmp(e->value, st->value, sizeof e->value) != 0 && defines_changed)
                    *defines_changed = true;
                memcpy(e->value, st->value, sizeof e->value);
            }
        }
    }
    for (int s = 0; stage && s < nsets; s++) free(stage[s].entries);
    free(stage);
    free(text);
    return ok;
}

void unif_preset_path(const char *glib_path, char *out, int outlen) {
    if (!out || outlen <= 0) return;
    out[0] = '\0';
    if (!glib_path || !glib_path[0]) return;
    const char *slash = strrchr(glib_path, '/');
    const char *base = slash ? slash + 1 : glib_path;
    if (!base[0]) return;
    const char *dot = strrchr(base, '.');
    size_t stem = (dot && dot != base) ? (size_t)(dot - glib_path) : strlen(glib_path);
    static const char ext[] = ".preset";
    if (stem + sizeof ext > (size_t)outlen) return;
    memcpy(out, glib_path, stem);
    memcpy(out + stem, ext, sizeof ext);
}
