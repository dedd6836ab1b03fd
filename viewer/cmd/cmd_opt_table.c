/* cmd_opt_table: the parser, the usage writer and the man-page writer of
 * every command's option table (cmd_opt_table.h). */
#include "cmd_opt_table.h"
#include "strbuf.h"

#include <assert.h>
#include <float.h>
#include <stdarg.h>
#include <string.h>

#include "cmd.h"
#include "util.h"

enum { MAX_OPTIONS = 64, DEFAULT_COLUMN = 19 };

static int count(const cmd_spec *s) {
    int n = 0;
    while (s->options && s->options[n].name) n++;
    assert(n <= MAX_OPTIONS);
    return n;
}

int cmd_bad_usage(const cmd_spec *s, FILE *err, const char *fmt, ...) {
    va_list ap;
    fprintf(err, "tarn %s: ", s->name);
    va_start(ap, fmt);
    vfprintf(err, fmt, ap);
    va_end(ap);
    strbuf usage = {0};
    cmd_usage_text(s, &usage);
    fprintf(err, "\n\n%s", usage.s ? usage.s : "");
    strbuf_free(&usage);
    return TARN_EXIT_USAGE;
}

/* ---- parsing ---- */

static void *at(void *desc, size_t offset) { return (char *)desc + offset; }

/* What "NAME wants ..." says of o's value. */
static const char *wants(const cmd_option *o, char *buf, size_t len) {
    if (o->wants) return o->wants;
    switch (o->kind) {
    case CMD_INT: snprintf(buf, len, "%.0f..%.0f", o->lo, o->hi); return buf;
    case CMD_DOUBLE:
        if (o->lo == 0 && o->hi == 0) return "a number";
        snprintf(buf, len, "%g..%g", o->lo, o->hi);
        return buf;
    case CMD_SIZE: return "WxH";
    case CMD_MSAA: return "0..16 samples";
    default: return o->metavar ? o->metavar : "a value";
    }
}

/* Stores value (NULL when it was missing) where o says; false with why
 * when it is not one o takes (why empty: "wants" says it). */
static bool store(const cmd_option *o, const char *value, void *desc, char *why, size_t whylen) {
    if (o->kind == CMD_FLAG) { *(bool *)at(desc, o->offset) = true; return true; }
    if (o->kind == CMD_CUSTOM || (o->kind == CMD_ARG && o->set)) return o->set(desc, value, why, whylen);
    if (!value) return false;
    switch (o->kind) {
    case CMD_INT: return cmd_opt_int(value, (int)o->lo, (int)o->hi, at(desc, o->offset));
    case CMD_DOUBLE: {
        bool any = o->lo == 0 && o->hi == 0;
        return cmd_opt_range(value, any ? -DBL_MAX : o->lo, any ? DBL_MAX : o->hi, at(desc, o->offset));
    }
    case CMD_SIZE: {
        int w, h;
        if (!opt_size(value, &w, &h)) return false;
        if (o->hi > 0 && (w < o->lo || h < o->lo || w > o->hi || h > o->hi)) return false;
        *(int *)at(desc, o->offset) = w;
        *(int *)at(desc, o->offset2) = h;
        return true;
    }
    case CMD_MSAA: return cmd_opt_msaa(value, at(desc, o->offset));
    case CMD_PACK:
        if (!cmd_opt_pack(value, why, whylen)) return false;
        *(const char **)at(desc, o->offset) = value;
        return true;
    case CMD_LIST: {
        /* the desc's pointer may be declared const char *const *: copied,
         * as the caller's room it points at is not const */
        const char **list;
        memcpy(&list, at(desc, o->offset), sizeof list);
        assert(list);
        int *n = at(desc, o->offset2);
        list[(*n)++] = value;
        return true;
    }
    default: *(const char **)at(desc, o->offset) = value; return true;
    }
}

static const cmd_option *find(const cmd_option *t, int n, const char *name, size_t len) {
    for (int i = 0; i < n; i++) {
        if (t[i].kind == CMD_ARG) continue;
        if (strlen(t[i].name) == len && strncmp(t[i].name, name, len) == 0) return &t[i];
        if (t[i].short_name && strlen(t[i].short_name) == len && strncmp(t[i].short_name, name, len) == 0)
            return &t[i];
    }
    return NULL;
}

/* The CMD_ARG entry at or after *cursor that takes the next positional. */
static const cmd_option *next_arg(const cmd_option *t, int n, int *cursor) {
    while (*cursor < n && t[*cursor].kind != CMD_ARG) ++*cursor;
    return *cursor < n ? &t[*cursor] : NULL;
}

static int complain(const cmd_spec *s, FILE *err, const cmd_option *o, const char *typed, const char *why) {
    char buf[64];
    if (why[0]) return cmd_bad_usage(s, err, "%s", why);
    return cmd_bad_usage(s, err, "%s wants %s", typed, wants(o, buf, sizeof buf));
}

/* A positional argument, to the CMD_ARG entry at or after *cursor. */
static int take_arg(const cmd_spec *s, const char *a, void *desc, int *cursor, bool *given, FILE *err) {
    const cmd_option *t = s->options, *o = next_arg(t, count(s), cursor);
    char why[MSG_MAX] = "";
    if (!o) return cmd_bad_usage(s, err, "%s (got another: '%s')", s->extra ? s->extra : "too many arguments", a);
    if (!store(o, a, desc, why, sizeof why)) return complain(s, err, o, o->name, why);
    given[o - t] = true;
    if (!o->set) ++*cursor;   /* one that sets takes every positional left */
    return TARN_EXIT_OK;
}

/* The option argv[*i] and its value: after its '=', or the next argument
 * (*i then moves past it). */
static int take_option(const cmd_spec *s, int argc, char **argv, int *i, void *desc, bool *given, FILE *err) {
    const char *a = argv[*i], *eq = strncmp(a, "--", 2) == 0 ? strchr(a, '=') : NULL;
    size_t len = eq ? (size_t)(eq - a) : strlen(a);
    const cmd_option *t = s->options, *o = find(t, count(s), a, len);
    if (!o) return cmd_bad_usage(s, err, "unknown option '%s'", a);
    char typed[64], why[1024] = "";   /* typed: as the user spelled it (-o or --out) */
    snprintf(typed, sizeof typed, "%.*s", (int)len, a);
    const char *value = NULL;
    bool flag = o->kind == CMD_FLAG || (o->kind == CMD_CUSTOM && !o->metavar);
    if (flag && eq) return cmd_bad_usage(s, err, "%s takes no value", typed);
    if (!flag) value = eq ? eq + 1 : *i + 1 < argc ? argv[++*i] : NULL;
    if (!store(o, value, desc, why, sizeof why)) return complain(s, err, o, typed, why);
    given[o - t] = true;
    return TARN_EXIT_OK;
}

int cmd_parse(const cmd_spec *s, int argc, char **argv, void *desc, FILE *err) {
    int n = count(s), cursor = 0, rc = TARN_EXIT_OK;
    bool given[MAX_OPTIONS] = { false }, options_over = false;   /* after "--": positionals only */
    for (int i = 0; i < argc && rc == TARN_EXIT_OK; i++) {
        const char *a = argv[i];
        if (!options_over && strcmp(a, "--") == 0) options_over = true;
        else if (options_over || a[0] != '-' || a[1] == '\0') rc = take_arg(s, a, desc, &cursor, given, err);   /* "-" too */
        else rc = take_option(s, argc, argv, &i, desc, given, err);
    }
    for (int k = 0; k < n && rc == TARN_EXIT_OK; k++)
        if (s->options[k].missing && !given[k]) rc = cmd_bad_usage(s, err, "%s", s->options[k].missing);
    return rc;
}

/* ---- the usage text ---- */

/* text with every line after the first indented by indent spaces (empty
 * lines stay empty). */
static void put_indented(strbuf *out, const char *text, int indent) {
    for (const char *p = text; *p;) {
        const char *nl = strchr(p, '\n');
        size_t len = nl ? (size_t)(nl - p) : strlen(p);
        if (p != text && len > 0) strbuf_printf(out, "%*s", indent, "");
        strbuf_put(out, p, len);
        strbuf_puts(out, "\n");
        p += len + (nl ? 1 : 0);
    }
}

static void usage_option(const cmd_option *o, int column, strbuf *out) {
    char left[256];
    int len = snprintf(left, sizeof left, "  %s%s%s%s%s", o->short_name ? o->short_name : "",
                       o->short_name ? ", " : "", o->name, o->metavar ? " " : "", o->metavar ? o->metavar : "");
    if (len + 1 <= column) strbuf_printf(out, "%-*s", column, left);
    else strbuf_printf(out, "%s\n%*s", left, column, "");
    put_indented(out, o->help, column);
}

void cmd_usage_text(const cmd_spec *s, strbuf *out) {
    char head[64];
    int indent = snprintf(head, sizeof head, "usage: tarn %s ", s->name);
    strbuf_puts(out, head);
    put_indented(out, s->synopsis, indent);
    if (s->about && s->about[0]) {
        strbuf_puts(out, "\n");
        strbuf_puts(out, s->about);
    }
    int n = count(s), column = s->column > 0 ? s->column : DEFAULT_COLUMN;
    bool listed = false;
    for (int i = 0; i < n; i++) {
        if (!s->options[i].help) continue;
        if (!listed) strbuf_puts(out, "\n");
        listed = true;
        usage_option(&s->options[i], column, out);
    }
    if (s->notes) {
        strbuf_puts(out, "\n");
        strbuf_puts(out, s->notes);
    }
}

const char *cmd_usage(const cmd_spec *s, char *buf, size_t len) {
    strbuf b = {0};
    cmd_usage_text(s, &b);
    snprintf(buf, len, "%s", b.s ? b.s : "");
    assert(b.len < len);   /* CMD_USAGE_MAX is too small: raise it */
    strbuf_free(&b);
    return buf;
}

/* ---- the man page ---- */

/* s with roff's escapes: \ as \e, - as \- (a minus sign, not a hyphen). */
static void roff_escaped(strbuf *out, const char *s, size_t len) {
    for (size_t i = 0; i < len; i++) {
        if (s[i] == '\\') strbuf_puts(out, "\\e");
        else if (s[i] == '-') strbuf_puts(out, "\\-");
        else strbuf_put(out, &s[i], 1);
    }
}

static void roff_word(strbuf *out, const char *s) { roff_escaped(out, s, strlen(s)); }

/* The usage's help as roff text: its lines unindented (an indented line
 * would break the filled paragraph), escaped, and a line that would read
 * as a request (a leading . or ') guarded with \&. */
static void roff_help(strbuf *out, const char *help) {
    for (const char *p = help; *p;) {
        while (*p == ' ') p++;
        const char *nl = strchr(p, '\n');
        size_t len = nl ? (size_t)(nl - p) : strlen(p);
        if (len > 0) {
            if (*p == '.' || *p == '\'') strbuf_puts(out, "\\&");
            roff_escaped(out, p, len);
            strbuf_puts(out, "\n");
        }
        p += len + (nl ? 1 : 0);
    }
}

static void roff_option(const cmd_option *o, strbuf *out) {
    strbuf_puts(out, ".TP\n");
    if (o->kind == CMD_ARG) {
        strbuf_puts(out, ".I ");
        roff_word(out, o->name);
    } else if (o->short_name) {
        strbuf_puts(out, ".BR ");
        roff_word(out, o->short_name);
        strbuf_puts(out, " \", \" ");
        roff_word(out, o->name);
        if (o->metavar) {
            strbuf_puts(out, " \" \\fI");
            roff_word(out, o->metavar);
            strbuf_puts(out, "\\fR\"");
        }
    } else {
        strbuf_puts(out, o->metavar ? ".BI " : ".B ");
        roff_word(out, o->name);
        if (o->metavar) {
            strbuf_puts(out, " \" ");
            roff_word(out, o->metavar);
            strbuf_puts(out, "\"");
        }
    }
    strbuf_puts(out, "\n");
    if (o->man) {
        strbuf_puts(out, o->man);
        if (o->man[0] && o->man[strlen(o->man) - 1] != '\n') strbuf_puts(out, "\n");
    } else {
        roff_help(out, o->help);
    }
}

void cmd_roff_options(const cmd_spec *s, strbuf *out) {
    int n = count(s);
    for (int i = 0; i < n; i++)
        if (s->options[i].help) roff_option(&s->options[i], out);
}
