/* cmd_opt_table: a command's options as one table that drives its parser,
 * its usage text (`tarn help NAME`, `tarn NAME --help`) and its option list
 * in the man page (`tarn help --roff NAME`, the lists docs/tarn.1 holds),
 * so the three cannot drift apart.
 *
 * A command is a cmd_spec: its name, synopsis, prose, and a table of
 * cmd_option ending at an entry with no name. Each option says where its
 * value goes in the command's desc struct (an offset, or a setter for the
 * odd ones); cmd_parse fills the desc, and a bad command line is a usage
 * error (exit 2) that says what to give, then prints the usage.
 *
 * The command line cmd_parse reads:
 *   --name VALUE, --name=VALUE, -o VALUE   an option with a value
 *   --flag                                  a flag (no value)
 *   ARG                                     a positional argument: the
 *                                           CMD_ARG entries in table order
 *   -                                       a positional argument too
 *   --                                      the end of the options: every
 *                                           argument after it is positional
 * An option given twice keeps the last value, except a CMD_LIST (each
 * value kept) and a CMD_CUSTOM (its setter sees each). */
#ifndef TARN_CMD_OPT_TABLE_H
#define TARN_CMD_OPT_TABLE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "strbuf.h"

typedef enum cmd_opt_kind {
    CMD_FLAG,    /* a bool at offset, set true */
    CMD_INT,     /* a whole number lo..hi into an int */
    CMD_DOUBLE,  /* a finite number lo..hi into a double (lo = hi = 0: any finite number) */
    CMD_STRING,  /* the value as given, a const char * (argv outlives the desc) */
    CMD_LIST,    /* repeatable string: appended to the const char * array the
                  * pointer at offset points at (the caller points it at room
                  * for argc values), the int count at offset2 */
    CMD_SIZE,    /* WxH into int width (offset) and height (offset2); when hi > 0
                  * each side lo..hi as well */
    CMD_MSAA,    /* 0..16 samples into an int render_desc.samples value (cmd_opt_msaa) */
    CMD_PACK,    /* a pack of tarn's, a const char * (else the packs are listed) */
    CMD_CUSTOM,  /* set() takes it: a flag when metavar is NULL (value NULL) */
    CMD_ARG      /* a positional argument: a const char * at offset, or each one
                  * to set() (then it takes every positional left) */
} cmd_opt_kind;

/* A setter: false when value is not one it takes, with why (for "tarn NAME:
 * why"), or why left empty for "NAME wants WANTS". desc is cmd_parse's. */
typedef bool (*cmd_opt_setter)(void *desc, const char *value, char *why, size_t whylen);

typedef struct cmd_option {
    const char *name;       /* "--size"; a CMD_ARG's as the usage shows it ("FILE.glib") */
    const char *short_name; /* "-o": another spelling (NULL: none) */
    const char *metavar;    /* "WxH" of "--size WxH"; NULL: a flag */
    const char *help;       /* the usage's text: lines after the first are indented to
                             * the column; NULL: not listed (shown in the synopsis only) */
    const char *man;        /* the man page's text, roff (NULL: help, escaped): a man
                             * page says more than a usage has room for */
    cmd_opt_kind kind;
    size_t offset, offset2; /* in the desc cmd_parse fills (offsetof) */
    double lo, hi;          /* CMD_INT, CMD_DOUBLE, CMD_SIZE's range */
    const char *wants;      /* "NAME wants WANTS" on a bad or missing value (NULL:
                             * the range, "WxH", or the metavar) */
    const char *missing;    /* required: the complaint when it is not given (NULL: optional) */
    cmd_opt_setter set;     /* CMD_CUSTOM, and a CMD_ARG that takes many */
} cmd_option;

typedef struct cmd_spec {
    const char *name;           /* "render": "usage: tarn render ...", "tarn render: ..." */
    const char *synopsis;       /* after "usage: tarn NAME ": lines after the first are
                                 * indented under the first argument */
    const char *about;          /* the paragraphs before the options ("": none) */
    const cmd_option *options;  /* ends at an entry with no name; NULL: none */
    const char *notes;          /* the paragraphs after the options (NULL: none) */
    int column;                 /* where the options' help starts (0: 19); a longer
                                 * name and metavar puts it on the next line */
    const char *extra;          /* a positional argument too many: "EXTRA (got another:
                                 * 'ARG')" ("one scene at a time"; NULL: "too many arguments") */
} cmd_spec;

enum { CMD_USAGE_MAX = 16384 };

/* Parses argv (the arguments after the command word) into desc by s's
 * table, then checks the required ones. TARN_EXIT_OK, or TARN_EXIT_USAGE
 * after "tarn NAME: what to give" and the usage on err. */
int cmd_parse(const cmd_spec *s, int argc, char **argv, void *desc, FILE *err);

/* "tarn NAME: WHAT\n\nUSAGE" on err; returns TARN_EXIT_USAGE: the checks a
 * command makes after cmd_parse (options valid only together, ...). */
int cmd_bad_usage(const cmd_spec *s, FILE *err, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* The usage text: "usage: tarn NAME SYNOPSIS", the about, the options (one
 * entry each, help aligned at the column), the notes. */
void cmd_usage_text(const cmd_spec *s, strbuf *out);

/* The same into buf (CMD_USAGE_MAX holds any of tarn's); returns buf. */
const char *cmd_usage(const cmd_spec *s, char *buf, size_t len);

/* The option list as man-page entries, ".TP", the option in bold and its
 * metavar in italics, then its man text (or help): what the docs/tarn.1
 * section of the command holds between its "BEGIN options" and "END
 * options" comments (scripts/man_options.sh writes them there). */
void cmd_roff_options(const cmd_spec *s, strbuf *out);

#endif
