/* glib_values.c: the values of uniforms and Defines: 5  [a b c]
 * <min default max>  <true>  {r g b a}, with glman's leniencies, and the
 * names they are given to (glib_internal.h).
 */
#include "glib_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *bracket_example(char open) {
    return open == '<' ? "<min default max> or <true>"
         : open == '{' ? "{r g b} or {r g b a}" : "[a b c]";
}

static val_result bracket_numbers(cmdctx *c, char **items, int n, unif_decl *u,
                                  const char *owner) {
    for (int i = 0; i < n; i++)
        if (!glib_read_number(c, items[i], &u->v[i])) {
            glib_cerr(c, "%s: bad number '%.60s' (write e.g. 2, -0.5, .25 or 1e-3)", owner, items[i]);
            return VAL_BAD;
        }
    u->n = n;
    return VAL_OK;
}

static val_result slider_value(cmdctx *c, unif_decl *u, const char *owner) {
    double *v = u->v;
    if (v[0] > v[2]) {
        glib_cerr(c, "%s: slider minimum %g is greater than its maximum %g: write <min default max>",
             owner, v[0], v[2]);
        return VAL_BAD;
    }
    if (v[1] < v[0] || v[1] > v[2]) {
        double d = v[1] < v[0] ? v[0] : v[2];
        glib_cwarn(c, "%s: default %g is outside <%g .. %g>; using %g", owner, v[1], v[0], v[2], d);
        v[1] = d;
    }
    return VAL_OK;
}

static val_result typed_bracket(cmdctx *c, char open, char **items, int n,
                                unif_decl *u, const char *owner) {
    /* <true>, <false>, and glman's <0> / <1> (nonzero: checked) */
    if (open == '<' && n == 1 &&
        (glib_is_bool_word(items[0], &u->v[0]) || glib_read_number(c, items[0], &u->v[0]))) {
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
        glib_cerr(c, "%s: %c%c needs %s, got %d", owner, open, glib_closer_of(open), need, n);
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
    glib_cwarn(c, "%s: a slider has more than 3 numbers (%s %s %s%s); glman read its words with atof and used "
          "<%g %g %g>: write <min default max> with a '.' for the decimal point", owner, w[0], w[1], w[2], extra,
          u->v[0], u->v[1], u->v[2]);
    return true;
}

/* A bracketed value at *sp. An unclosed bracket ends the line: nothing
 * after it can be told apart from the bracket's contents. */
static val_result read_bracket(cmdctx *c, char **sp, unif_decl *u, const char *owner) {
    char *s = *sp;
    char open = *s, close = glib_closer_of(open);
    char *e = s + 1;
    while (*e && *e != close && !glib_is_opener(*e) && !glib_is_closer(*e))
        e++;
    if (*e != close) {
        if (*e)
            glib_cerr(c, "%s: '%c' is not closed before '%c': write %s", owner, open, *e,
                 bracket_example(open));
        else
            glib_cerr(c, "%s: unclosed '%c': add '%c' (%s)", owner, open, close, bracket_example(open));
        *sp = s + strlen(s);
        return VAL_STOP;
    }
    *e = '\0';
    *sp = e + 1;
    char raw[512];
    snprintf(raw, sizeof raw, "%s", s + 1);
    char *items[GLIB_MAX_NUMS];
    int n = glib_split_items(s + 1, items, GLIB_MAX_NUMS);
    if (open == '<' && n > 3 && slider_glman_words(c, raw, u, owner))
        return slider_value(c, u, owner);
    return typed_bracket(c, open, items, n, u, owner);
}

val_result glib_read_value(cmdctx *c, char **sp, unif_decl *u, const char *owner) {
    char *s = glib_skip_space(*sp);
    if (glib_is_opener(*s)) {
        *sp = s;
        return read_bracket(c, sp, u, owner);
    }
    char *e = s;
    while (*e && !glib_is_space((unsigned char)*e))
        e++;
    *sp = *e ? e + 1 : e;
    *e = '\0';
    double b;
    if (glib_is_closer(*s)) {
        glib_cerr(c, "%s: '%c' closes a bracket that was not opened", owner, *s);
        return VAL_BAD;
    }
    if (glib_is_bool_word(s, &b)) {
        glib_cerr(c, "%s: write <%s> (with the angle brackets) for a checkbox", owner, s);
        return VAL_BAD;
    }
    if (!glib_read_number(c, s, &u->v[0])) {
        glib_cerr(c, "%s: bad number '%.60s' (write e.g. 2, -0.5, .25 or 1e-3)", owner, s);
        return VAL_BAD;
    }
    u->kind = UNIF_DECL_SCALAR;
    u->n = 1;
    return VAL_OK;
}

/* Copies a name at *sp (up to whitespace or a bracket, which may follow
 * with no space: uKa<0 1 2>) into out and checks it is a GLSL identifier. */
bool glib_take_name(cmdctx *c, char **sp, char out[GLIB_NAME_MAX], const char *what) {
    char *s = *sp, *e = s;
    while (*e && !glib_is_space((unsigned char)*e) && !glib_is_opener(*e))
        e++;
    *sp = e;
    size_t n = (size_t)(e - s);
    if (n >= GLIB_NAME_MAX) {
        glib_cerr(c, "%s name '%.40s...' is too long (at most %d characters)", what, s,
             GLIB_NAME_MAX - 1);
        return false;
    }
    memcpy(out, s, n);
    out[n] = '\0';
    if (!glib_is_ident(out)) {
        glib_cerr(c, "'%s' is not a valid %s name: use letters, digits and _, not starting with a digit",
             out, what);
        return false;
    }
    return true;
}
