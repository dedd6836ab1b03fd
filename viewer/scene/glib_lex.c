/* glib_lex.c: the lexer of .glib files: physical lines, logical lines
 * (joined at a trailing backslash, comments cut, binary bytes found),
 * words and quoted words, bracket items, and the number tokens people
 * write (glib_internal.h).
 */
#include "glib_internal.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* ------------------------------------------------------------------ */
/* characters and words                                               */

bool glib_is_ident(const char *s) {
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
int glib_split_words(char *s, char **w, int max) {
    int n = 0;
    for (;;) {
        s = glib_skip_space(s);
        if (!*s)
            return n;
        char *start = s;
        if (*s == '"') {
            start = ++s;
            s = strchr(s, '"');
            if (!s)
                return -1;
        } else {
            while (*s && !glib_is_space((unsigned char)*s))
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
int glib_split_items(char *s, char **w, int max) {
    int n = 0;
    for (;;) {
        while (glib_is_space((unsigned char)*s) || *s == ',')
            s++;
        if (!*s)
            return n;
        char *start = s;
        while (*s && !glib_is_space((unsigned char)*s) && *s != ',')
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
bool glib_is_decimal(const char *s) {
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

bool glib_parse_number(const char *s, double *out) {
    if (!glib_is_decimal(s))
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
size_t glib_dotted_prefix(const char *s, double *out) {
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
    return glib_parse_number(buf, out) ? k : 0;
}

bool glib_is_bool_word(const char *s, double *v) {
    if (strcasecmp(s, "true") == 0)
        return *v = 1, true;
    if (strcasecmp(s, "false") == 0)
        return *v = 0, true;
    return false;
}

/* ------------------------------------------------------------------ */
/* physical and logical lines                                         */

/* The next physical line, without its end (\n, \r\n or a lone \r). */
bool glib_next_phys(reader *r, const char **b, size_t *n) {
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
        bool word_start = i == 0 || glib_is_space((unsigned char)s[i - 1]) || glib_is_closer(s[i - 1]);
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
            if ((c < 0x20 && !glib_is_space((int)c)) || c == 0x7f)
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
bool glib_next_logical(reader *r, logical *lg) {
    const char *b;
    size_t n;
    lg->n = 0;
    lg->too_long = false;
    lg->bad_byte = -1;
    if (!glib_next_phys(r, &b, &n))
        return false;
    lg->first_line = r->lineno;
    for (;;) {
        n = comment_start(b, n);
        while (n > 0 && glib_is_space((unsigned char)b[n - 1]))
            n--;
        bool cont = n > 0 && b[n - 1] == '\\';
        append_phys(lg, b, cont ? n - 1 : n, cont);
        if (!cont || !glib_next_phys(r, &b, &n))
            break;
    }
    lg->buf[lg->n] = '\0';
    return true;
}
