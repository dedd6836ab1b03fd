/* test_man: docs/tarn.1 keeps up with the program. Every command `tarn help`
 * lists has its own section (.SS NAME) in COMMANDS, and every --option its
 * usage text names is in that section; the page has the sections a man
 * page has, the four exit codes, and the version `tarn --version` prints.
 * The lists come from the program itself, so a new option without a line
 * in the man page fails here. And every command's option list in the page
 * is what its option table generates (`tarn help --roff NAME`, written
 * there by scripts/man_options.sh), so the two cannot drift. No OpenGL:
 * help never makes a context. */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "support.h"

#ifndef TARN_SOURCE_DIR
#define TARN_SOURCE_DIR "."
#endif

enum { MAX_NAMES = 32, NAME_LEN = 32, OUT_LEN = 16384 };

static const char *bin;

static int tarn(const char *args, char *out, size_t outlen) {
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "%s %s 2>&1", bin, args);
    return run_command(cmd, out, outlen);
}

/* docs/tarn.1 as it reads, after a leading newline (every line starts after
 * one): troff's \- is a -, and the font changes (\fB, \fI, \fR, \fP) and
 * the zero-width \& are nothing. NULL when it cannot be read. */
static char *read_page(void) {
    FILE *f = fopen(TARN_SOURCE_DIR "/docs/tarn.1", "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *raw = malloc((size_t)n + 1), *out = malloc((size_t)n + 2);
    size_t got = raw && out ? fread(raw, 1, (size_t)n, f) : 0;
    fclose(f);
    if (!raw || !out) { free(raw); free(out); return NULL; }
    size_t k = 0;
    out[k++] = '\n';
    for (size_t i = 0; i < got; i++) {
        if (raw[i] == '\\' && i + 1 < got && raw[i + 1] == '-') { out[k++] = '-'; i++; }
        else if (raw[i] == '\\' && i + 2 < got && raw[i + 1] == 'f') i += 2;
        else if (raw[i] == '\\' && i + 1 < got && raw[i + 1] == '&') i++;
        else out[k++] = raw[i];
    }
    out[k] = '\0';
    free(raw);
    return out;
}

/* docs/tarn.1 as it is on disk (NULL when it cannot be read). */
static char *read_raw_page(void) {
    FILE *f = fopen(TARN_SOURCE_DIR "/docs/tarn.1", "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *raw = malloc((size_t)n + 1);
    size_t got = raw ? fread(raw, 1, (size_t)n, f) : 0;
    fclose(f);
    if (raw) raw[got] = '\0';
    return raw;
}

/* The names in the "commands:" block of `tarn help`: the first word of each
 * indented line up to the blank line. */
static int listed_names(const char *out, char names[][NAME_LEN], int max) {
    const char *p = strstr(out, "commands:\n");
    int n = 0;
    for (p = p ? strchr(p, '\n') + 1 : NULL; p && *p == ' ' && n < max;) {
        while (*p == ' ') p++;
        int len = 0;
        while (p[len] && !isspace((unsigned char)p[len]) && len < NAME_LEN - 1) len++;
        memcpy(names[n], p, (size_t)len);
        names[n++][len] = '\0';
        p = strchr(p, '\n');
        if (p) p++;
    }
    return n;
}

/* The text of COMMANDS' ".SS name" section, up to the next .SS or .SH (a
 * pointer into page, its length in *len); NULL when there is none. */
static const char *section(const char *page, const char *name, size_t *len) {
    char head[64];
    int hl = snprintf(head, sizeof head, "\n.SS %s\n", name);
    const char *s = strstr(page, head);
    if (!s) return NULL;
    s += hl;
    const char *ss = strstr(s, "\n.SS "), *sh = strstr(s, "\n.SH ");
    const char *end = ss && (!sh || ss < sh) ? ss : sh ? sh : s + strlen(s);
    *len = (size_t)(end - s);
    return s;
}

static bool opt_char(char c) { return isalnum((unsigned char)c) || c == '-'; }

/* opt as a whole word in s[0..len): not part of a longer option. */
static bool has_word(const char *s, size_t len, const char *opt) {
    size_t ol = strlen(opt);
    for (size_t i = 0; i + ol <= len; i++)
        if (memcmp(s + i, opt, ol) == 0 && (i == 0 || !opt_char(s[i - 1])) &&
            (i + ol == len || !opt_char(s[i + ol])))
            return true;
    return false;
}

/* Every --option in usage appears in sec (as a word). */
static void check_options(const char *name, const char *usage, const char *sec, size_t seclen) {
    for (const char *p = strstr(usage, "--"); p; p = strstr(p + 2, "--")) {
        if ((p > usage && opt_char(p[-1])) || !isalpha((unsigned char)p[2])) continue;   /* "<!--", "-->" */
        char opt[64];
        size_t n = 0;
        while (opt_char(p[n]) && n < sizeof opt - 1) { opt[n] = p[n]; n++; }
        while (n > 2 && opt[n - 1] == '-') n--;   /* "--frames-" at a line break is not an option */
        opt[n] = '\0';
        CHECK_MSG(has_word(sec, seclen, opt), "tarn.1's section '%s' lacks %s (in `tarn help %s`)", name, opt,
                  name);
    }
}

static void test_every_command_and_option(void) {
    char *page = read_page();
    CHECK_MSG(page != NULL, "cannot read %s/docs/tarn.1", TARN_SOURCE_DIR);
    if (!page) return;
    static char out[OUT_LEN], usage[OUT_LEN];
    char names[MAX_NAMES][NAME_LEN];
    CHECK_EQ(tarn("help", out, sizeof out), 0);
    int n = listed_names(out, names, MAX_NAMES);
    CHECK_MSG(n >= 9, "%d commands in `tarn help`:\n%s", n, out);
    for (int i = 0; i < n; i++) {
        size_t seclen = 0;
        const char *sec = section(page, names[i], &seclen);
        CHECK_MSG(sec != NULL, "tarn.1 has no '.SS %s' for the command '%s'", names[i], names[i]);
        if (!sec) continue;
        char args[128];
        snprintf(args, sizeof args, "help %.31s", names[i]);
        CHECK_MSG(tarn(args, usage, sizeof usage) == 0, "`tarn %s` failed", args);
        check_options(names[i], usage, sec, seclen);
    }
    free(page);
}

/* The first line where a and b differ, for the message. */
static void first_difference(const char *a, const char *b, char *buf, size_t len) {
    const char *line_a = a, *line_b = b;
    for (; *a && *a == *b; a++, b++)
        if (*a == '\n') { line_a = a + 1; line_b = b + 1; }
    snprintf(buf, len, "page: %.*s\n  table: %.*s", (int)strcspn(line_a, "\n"), line_a, (int)strcspn(line_b, "\n"),
             line_b);
}

/* Each command's option list in the page is exactly what its table gives:
 * the block between ".\" BEGIN options: tarn help --roff NAME" and ".\" END
 * options" is `tarn help --roff NAME`; a command with options has one, and
 * every block names a command. */
static void test_option_lists_are_generated(void) {
    char *page = read_raw_page();
    CHECK_MSG(page != NULL, "cannot read %s/docs/tarn.1", TARN_SOURCE_DIR);
    if (!page) return;
    static char out[OUT_LEN], roff[OUT_LEN];
    char names[MAX_NAMES][NAME_LEN];
    CHECK_EQ(tarn("help", out, sizeof out), 0);
    int n = listed_names(out, names, MAX_NAMES);
    static const char fix[] = "regenerate it from the tables (viewer/cmd/cmd_*.c): scripts/man_options.sh build/tarn";
    int blocks = 0;
    for (int i = 0; i < n; i++) {
        char args[128], begin[128];
        snprintf(args, sizeof args, "help --roff %.31s", names[i]);
        CHECK_MSG(tarn(args, roff, sizeof roff) == 0, "`tarn %s` failed", args);
        snprintf(begin, sizeof begin, "\n.\\\" BEGIN options: tarn help --roff %.31s\n", names[i]);
        const char *b = strstr(page, begin);
        if (!roff[0] && !b) continue;   /* no options, no list */
        CHECK_MSG(b != NULL, "docs/tarn.1 has no option list for '%s' (a line %.*s): add the markers and %s",
                  names[i], (int)strlen(begin) - 2, begin + 1, fix);
        if (!b) continue;
        blocks++;
        b += strlen(begin);
        const char *e = strstr(b, ".\\\" END options\n");
        CHECK_MSG(e != NULL, "docs/tarn.1's option list for '%s' has no END line", names[i]);
        if (!e) continue;
        bool same = (size_t)(e - b) == strlen(roff) && strncmp(b, roff, strlen(roff)) == 0;
        char diff[512] = "";
        if (!same) first_difference(b, roff, diff, sizeof diff);
        CHECK_MSG(same, "docs/tarn.1's options of '%s' are not its table's (`tarn help --roff %s`); %s\n  %s",
                  names[i], names[i], fix, diff);
    }
    int markers = 0;
    for (const char *p = strstr(page, ".\\\" BEGIN options:"); p; p = strstr(p + 1, ".\\\" BEGIN options:"))
        markers++;
    CHECK_MSG(markers == blocks, "docs/tarn.1 has %d option lists, %d of them for commands `tarn help` lists",
              markers, blocks);
    free(page);
}

static void test_sections(void) {
    char *page = read_page();
    CHECK_MSG(page != NULL, "cannot read %s/docs/tarn.1", TARN_SOURCE_DIR);
    if (!page) return;
    static const char *const want[] = { "\n.SH NAME\n", "\n.SH SYNOPSIS\n", "\n.SH DESCRIPTION\n",
        "\n.SH COMMANDS\n", "\n.SH WINDOW KEYS AND MOUSE\n", "\n.SH EXIT STATUS\n", "\n.SH ENVIRONMENT\n",
        "\n.SH FILES\n", "\n.SH SEE ALSO\n" };
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++)
        CHECK_MSG(strstr(page, want[i]) != NULL, "tarn.1 lacks%s", want[i]);
    const char *exits = strstr(page, "\n.SH EXIT STATUS\n");
    for (int code = 0; exits && code <= 3; code++) {
        char b[16];
        snprintf(b, sizeof b, "\n.B %d\n", code);
        CHECK_MSG(strstr(exits, b) != NULL, "tarn.1's EXIT STATUS lacks %d", code);
    }
    const char *env = strstr(page, "\n.SH ENVIRONMENT\n");
    static const char *const vars[] = { "TARN_ROOT", "XDG_CACHE_HOME", "DISPLAY", "TARN_COMPILE_ON_FRAME" };
    for (size_t i = 0; env && i < sizeof vars / sizeof vars[0]; i++)
        CHECK_MSG(strstr(env, vars[i]) != NULL, "tarn.1's ENVIRONMENT lacks %s", vars[i]);
    free(page);
}

/* .TH says the version the program does (a version bump updates the page). */
static void test_version(void) {
    char *page = read_page();
    CHECK_MSG(page != NULL, "cannot read %s/docs/tarn.1", TARN_SOURCE_DIR);
    if (!page) return;
    char out[512], want[80];
    CHECK_EQ(tarn("--version", out, sizeof out), 0);
    char *nl = strchr(out, '\n');
    if (nl) *nl = '\0';
    snprintf(want, sizeof want, "\"%.70s\"", out);
    const char *th = strstr(page, "\n.TH TARN 1 ");
    const char *end = th ? strchr(th + 1, '\n') : NULL;
    const char *at = th ? strstr(th, want) : NULL;
    CHECK_MSG(at && at < end, "tarn.1's .TH line does not name %s", want);
    free(page);
}

int main(void) {
    bin = getenv("TARN_BIN");
    if (!bin) { fprintf(stderr, "run through ctest (TARN_BIN)\n"); return 1; }
    RUN(test_every_command_and_option);
    RUN(test_option_lists_are_generated);
    RUN(test_sections);
    RUN(test_version);
    return check_summary();
}
