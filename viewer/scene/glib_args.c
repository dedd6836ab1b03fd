/* glib_args.c: the arguments of a command (glib_internal.h): numbers
 * read as glman read them and checked against their rules, the usage line,
 * missing and extra words, mode keywords, uniform names where a number may
 * stand.
 */
#include "glib_internal.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

/* ------------------------------------------------------------------ */
/* numeric arguments                                                  */

/* A number as glman's atof read it: exact, or its prefix with a warning
 * that says what was read. */
bool glib_read_number(cmdctx *c, const char *tok, double *out) {
    if (glib_parse_number(tok, out))
        return true;
    size_t k = glib_dotted_prefix(tok, out);
    if (k)
        glib_cwarn(c, "%s: '%.60s' read as %.*s (the rest is ignored, as glman's atof did)",
              c->spec->name, tok, (int)k, tok);
    return k > 0;
}

void glib_build_usage(const cmd_spec *s, char *out, size_t size) {
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

bool glib_parse_arg(cmdctx *c, const arg_rule *a, const char *tok, double *out) {
    const char *cmd = c->spec->name;
    double v;
    if (!glib_read_number(c, tok, &v)) {
        glib_cerr(c, "%s: bad number '%.60s' for %s (write e.g. 2, -0.5, .25 or 1e-3): %s",
             cmd, tok, a->sym, c->usage);
        return false;
    }
    if (a->type == 'p' && !(v > 0)) {
        glib_cerr(c, "%s: %s must be greater than 0, not '%.60s'", cmd, a->sym, tok);
        return false;
    }
    if (a->type == 'a' && !(v > 0 && v < 180)) {
        glib_cerr(c, "%s: %s must be an angle between 0 and 180 degrees, not '%.60s'",
             cmd, a->sym, tok);
        return false;
    }
    if (a->type == 'i' && (v != floor(v) || v < a->lo || v > a->hi)) {
        glib_cerr(c, "%s: %s must be a whole number from %.15g to %.15g, not '%.60s'",
             cmd, a->sym, a->lo, a->hi, tok);
        return false;
    }
    *out = v;
    return true;
}

void glib_missing_args(cmdctx *c, int have) {
    const cmd_spec *s = c->spec;
    const arg_rule *a = &s->args[have];
    if (s->nreq - have == 1 && a->what)
        glib_cerr(c, "%s needs %s: %s", s->name, a->what, c->usage);
    else
        glib_cerr(c, "%s needs %s%d numbers, got %d: %s", s->name,
             s->nreq < s->nmax ? "at least " : "", s->nreq, have, c->usage);
}

/* Extra words are ignored with a warning: the command still does what the
 * first words say, which is what glman did. */
void glib_warn_extra(cmdctx *c, int max, const char *hint) {
    if (c->nwords <= max)
        return;
    const char *more = c->nwords > max + 1 ? " and what follows" : "";
    if (max == 0)
        glib_cwarn(c, "%s takes no arguments; ignoring '%.40s'%s", c->spec->name,
              c->words[0], more);
    else
        glib_cwarn(c, "%s takes at most %d argument%s; ignoring '%.40s'%s%s: %s",
              c->spec->name, max, max == 1 ? "" : "s", c->words[max], more,
              hint, c->usage);
}

/* Reads the numbers words[w0..] by rules[0..]; nreq..nmax of them. */
bool glib_nums_from(cmdctx *c, glib_cmd *cmd, int w0, const arg_rule *rules, int nreq,
               int nmax, const char *what) {
    int have = c->nwords - w0;
    if (have < nreq) {
        if (nreq - have == 1 && rules[have].what)
            glib_cerr(c, "%s needs %s: %s", what, rules[have].what, c->usage);
        else
            glib_cerr(c, "%s needs %s%d numbers, got %d: %s", what, nreq < nmax ? "at least " : "",
                 nreq, have < 0 ? 0 : have, c->usage);
        return false;
    }
    glib_warn_extra(c, w0 + nmax, "");
    int given = have < nmax ? have : nmax;
    for (int i = 0; i < given; i++)
        if (!glib_parse_arg(c, &rules[i], c->words[w0 + i], &cmd->num[i]))
            return false;
    cmd->nnum = given;
    return true;
}

/* ------------------------------------------------------------------ */
/* words                                                              */

const keyword *glib_find_keyword(cmdctx *c, const keyword *k, size_t n, const char *choices) {
    if (c->nwords < 1) {
        glib_cerr(c, "%s needs one of %s: %s", c->spec->name, choices, c->usage);
        return NULL;
    }
    glib_warn_extra(c, 1, "");
    for (size_t i = 0; i < n; i++)
        if (strcasecmp(c->words[0], k[i].word) == 0)
            return &k[i];
    glib_cerr(c, "%s: unknown mode '%.40s': write %s", c->spec->name, c->words[0], choices);
    return NULL;
}

/* The first word is a mode from k; its canonical word goes to cmd->name. */
const keyword *glib_mode_word(cmdctx *c, const keyword *k, size_t n, const char *choices) {
    if (c->nwords < 1) {
        glib_cerr(c, "%s needs one of %s: %s", c->spec->name, choices, c->usage);
        return NULL;
    }
    for (size_t i = 0; i < n; i++)
        if (strcasecmp(c->words[0], k[i].word) == 0)
            return &k[i];
    glib_cerr(c, "%s: unknown kind '%.40s': write %s", c->spec->name, c->words[0], choices);
    return NULL;
}

/* A name where a number may stand (a uniform whose value the renderer
 * reads): into dst, with an error if it does not fit. */
bool glib_take_uniform_name(cmdctx *c, const char *what, const char *w, char *dst, size_t size) {
    if (strlen(w) >= size) {
        glib_cerr(c, "%s: the uniform name '%.40s...' is too long", what, w);
        return false;
    }
    snprintf(dst, size, "%s", w);
    return true;
}
