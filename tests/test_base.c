/* test_base: the base layer (viewer/base): the string builder and message
 * buffers, whole-file reads and writes, mkdir -p, the comparators and
 * median, option values, tarn_root and the diagnostics list. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "datafmt.h"
#include "diag.h"
#include "disk_cache.h"
#include "file.h"
#include "file_cache.h"
#include "mem.h"
#include "path.h"
#include "strbuf.h"
#include "support.h"
#include "util.h"

static void test_strbuf_grows_and_formats(void) {
    strbuf b = { 0 };
    for (int i = 0; i < 1000; i++) strbuf_printf(&b, "%d,", i % 10);
    CHECK_EQ(b.len, 2000);
    CHECK_EQ(strncmp(b.s, "0,1,2,", 6), 0);
    strbuf_put(&b, "xyz", 2);
    CHECK(b.len == 2002 && strcmp(b.s + 2000, "xy") == 0);
    char *s = strbuf_take(&b);
    CHECK(b.s == NULL && b.len == 0);
    CHECK_EQ(strlen(s), 2002);
    free(s);
    s = strbuf_take(&b); /* empty: "" not NULL */
    CHECK(s && s[0] == '\0');
    free(s);
}

static void test_str_appendf(void) {
    char *log = NULL;
    str_appendf(&log, "a%d\n", 1);
    str_appendf(&log, "%s", "b2\n");
    CHECK(log && strcmp(log, "a1\nb2\n") == 0);
    free(log);
}

static void test_messages_never_overrun(void) {
    char err[8];
    msg_set(err, sizeof err, "0123456789");
    CHECK_STR_EQ(err, "0123456");
    msg_set(err, sizeof err, "ab");
    msg_add(err, sizeof err, "cd");
    CHECK_STR_EQ(err, "ab\ncd"); /* a line each */
    msg_add(err, sizeof err, "efghij");
    CHECK_EQ(strlen(err), 7);
    msg_set(NULL, 0, "nothing"); /* no buffer: fine */
    msg_add(err, 0, "nothing");
}

static void test_files(void) {
    char dir[512], sub[1200], path[1300], err[512];
    if (!scratch_create("base")) {
        CHECK(false);
        return;
    }
    snprintf(dir, sizeof dir, "%s", scratch_dir);
    snprintf(sub, sizeof sub, "%s/a/b/c", dir);
    CHECK_MSG(file_mkdir_p(sub, err, sizeof err), "%s", err);
    CHECK(file_is_dir(sub));
    CHECK(file_mkdir_p(sub, err, sizeof err)); /* again: fine */
    snprintf(path, sizeof path, "%s/x.txt", sub);
    CHECK_MSG(file_write(path, "hello\0there", 11, err, sizeof err), "%s", err);
    size_t n = 0;
    char *s = file_read(path, 0, &n, err, sizeof err);
    CHECK(s && n == 11 && memcmp(s, "hello\0there", 11) == 0 && s[11] == '\0');
    free(s);
    CHECK_EQ(file_read(path, 10, &n, err, sizeof err), NULL); /* over the limit */
    CHECK_STR_CONTAINS(err, "larger than 10 bytes");
    CHECK_EQ(file_read(sub, 0, &n, err, sizeof err), NULL); /* a folder */
    CHECK_STR_CONTAINS(err, "it is a directory");
    CHECK_EQ(file_read("/dev/null", 0, &n, err, sizeof err), NULL); /* a device */
    CHECK_STR_CONTAINS(err, "not a regular file");
    snprintf(path, sizeof path, "%s/missing", dir);
    CHECK_EQ(file_read(path, 0, &n, err, sizeof err), NULL);
    CHECK_STR_CONTAINS(err, "cannot open");
    snprintf(path, sizeof path, "%s/a/b/c/x.txt/d", dir); /* under a file */
    CHECK(!file_mkdir_p(path, err, sizeof err));
    scratch_remove();
}

/* Reads text through file_read_text with o; the text's length in *n. */
static char *read_text_as(const char *text, size_t len, const file_text_opts *o, size_t *n, char *why) {
    const char *path = scratch_path("t.txt");
    CHECK(file_write(path, text, len, why, 256));
    return file_read_text(path, o, n, why, 256);
}

/* Each option of the one text reader alone, and all of them at once. */
static void test_read_text_options(void) {
    if (!scratch_create("text")) {
        CHECK(false);
        return;
    }
    static const char bom_crlf[] = "\xEF\xBB\xBFone\r\ntwo\r\n\rthree\r";
    size_t n = 0, len = sizeof bom_crlf - 1;
    char why[256];
    char *s = read_text_as(bom_crlf, len, NULL, &n, why);   /* no options: the bytes as they are */
    CHECK(s && n == len && memcmp(s, bom_crlf, len + 1) == 0);
    free(s);
    s = read_text_as(bom_crlf, len, &(file_text_opts){ .strip_bom = true }, &n, why);
    CHECK(s && n == len - 3 && strcmp(s, "one\r\ntwo\r\n\rthree\r") == 0);
    free(s);
    /* a lone \r (old Mac line end) and a \r at the end stay */
    s = read_text_as(bom_crlf, len, &(file_text_opts){ .crlf_to_lf = true }, &n, why);
    CHECK(s && n == len - 2 && strcmp(s, "\xEF\xBB\xBFone\ntwo\n\rthree\r") == 0);
    free(s);
    s = read_text_as("\xEF\xBB", 2, &(file_text_opts){ .strip_bom = true }, &n, why);   /* half a BOM */
    CHECK(s && n == 2 && strcmp(s, "\xEF\xBB") == 0);
    free(s);
    s = read_text_as("", 0, &(file_text_opts){ .strip_bom = true, .crlf_to_lf = true, .reject_nul = true }, &n, why);
    CHECK(s && n == 0 && s[0] == '\0');
    free(s);
    /* a NUL byte: binary, and the reason says at which line */
    static const char nul[] = "a\nb\r\nc\0d\n";
    s = read_text_as(nul, sizeof nul - 1, &(file_text_opts){ .reject_nul = true }, &n, why);
    CHECK(s == NULL && n == 0);
    CHECK_STR_CONTAINS(why, "NUL byte at line 3");
    s = read_text_as(nul, sizeof nul - 1, NULL, &n, why);   /* kept without the option */
    CHECK(s && n == sizeof nul - 1 && memcmp(s, nul, sizeof nul) == 0);
    free(s);
    /* the limit counts the bytes in the file, checked before the options */
    s = read_text_as("ab\r\n", 4, &(file_text_opts){ .max_bytes = 3, .crlf_to_lf = true }, &n, why);
    CHECK_EQ(s, NULL);
    CHECK_STR_CONTAINS(why, "it is larger than 3 bytes");
    s = read_text_as("ab\r\n", 4, &(file_text_opts){ .max_bytes = 4, .crlf_to_lf = true }, &n, why);
    CHECK(s && n == 3 && strcmp(s, "ab\n") == 0);
    free(s);
    CHECK_EQ(file_read_text(scratch_path("missing"), NULL, &n, why, sizeof why), NULL);
    CHECK_STR_EQ(why, "No such file or directory");   /* the reason alone: the caller names the file */
    CHECK_EQ(file_read_text(scratch_dir, NULL, &n, why, sizeof why), NULL);
    CHECK_STR_EQ(why, "it is a directory");
    scratch_remove();
}

/* mem_grow: room for what is asked, capacity doubling from 8, contents kept. */
static void test_mem_grow(void) {
    int *v = NULL, cap = 0;
    v = mem_grow(v, &cap, 1, sizeof *v);
    CHECK(v && cap == 8);
    for (int i = 0; i < 8; i++) v[i] = i;
    int *same = mem_grow(v, &cap, 8, sizeof *v);   /* it fits: nothing moves */
    CHECK(same == v && cap == 8);
    v = mem_grow(v, &cap, 100, sizeof *v);
    CHECK_EQ(cap, 128);
    v[99] = 99;
    bool kept = true;
    for (int i = 0; i < 8; i++) kept &= v[i] == i;
    CHECK(kept && v[99] == 99);
    free(v);
}

static void test_median_and_sort(void) {
    double v[] = { 5, 1, 4, 2, 3 };
    CHECK_EQ(median_double(v, 5), 3);
    double w[] = { 4, 1, 3, 2 };
    CHECK_EQ(median_double(w, 4), 2.5);
    CHECK_EQ(median_double(NULL, 0), 0);
    const char *s[] = { "pear", "apple", "fig" };
    qsort(s, 3, sizeof *s, cmp_str_ptr);
    CHECK(strcmp(s[0], "apple") == 0 && strcmp(s[2], "pear") == 0);
}

static void test_options(void) {
    int w = 0, h = 0;
    CHECK(opt_size("640x360", &w, &h) && w == 640 && h == 360);
    CHECK(opt_size("8X4", &w, &h) && w == 8 && h == 4);
    CHECK(!opt_size("640", &w, &h) && !opt_size("0x5", &w, &h) && !opt_size("20000x5", &w, &h));
    CHECK(!opt_size(NULL, &w, &h));
    double d;
    CHECK(opt_double("2.5", &d) && d == 2.5);
    CHECK(!opt_double("2.5s", &d) && !opt_double("", &d) && !opt_double(NULL, &d));
    CHECK(opt_is_help("-h") && opt_is_help("--help") && !opt_is_help("help") && !opt_is_help(NULL));
}

static void test_root_follows_environment(void) {
    const char *old = getenv("TARN_ROOT");
    char keep[4096] = "";
    if (old) snprintf(keep, sizeof keep, "%s", old);
    setenv("TARN_ROOT", "/some/where", 1);
    CHECK_STR_EQ(tarn_root(), "/some/where");
    unsetenv("TARN_ROOT");
    char packs[4200];
    snprintf(packs, sizeof packs, "%s/packs", tarn_root()); /* this build's tree */
    CHECK_MSG(file_is_dir(packs), "%s", packs);
    if (keep[0]) setenv("TARN_ROOT", keep, 1);
}

/* The XDG rule: an absolute $XDG_CACHE_HOME, else $HOME/.cache; neither: none. */
static void test_cache_dir_follows_xdg(void) {
    char keep_xdg[4096] = "", keep_home[4096] = "", dir[256];
    const char *x = getenv("XDG_CACHE_HOME"), *h = getenv("HOME");
    if (x) snprintf(keep_xdg, sizeof keep_xdg, "%s", x);
    if (h) snprintf(keep_home, sizeof keep_home, "%s", h);
    setenv("XDG_CACHE_HOME", "/c", 1);
    setenv("HOME", "/h", 1);
    CHECK(tarn_cache_dir(dir, sizeof dir) && strcmp(dir, "/c/tarn") == 0);
    setenv("XDG_CACHE_HOME", "relative", 1);   /* the spec says to ignore it */
    CHECK(tarn_cache_dir(dir, sizeof dir) && strcmp(dir, "/h/.cache/tarn") == 0);
    unsetenv("XDG_CACHE_HOME");
    CHECK(tarn_cache_dir(dir, sizeof dir) && strcmp(dir, "/h/.cache/tarn") == 0);
    unsetenv("HOME");
    CHECK(!tarn_cache_dir(dir, sizeof dir));
    setenv("HOME", "/h", 1);
    CHECK(!tarn_cache_dir(dir, 4));   /* too small is no answer, not a cut one */
    if (keep_xdg[0]) setenv("XDG_CACHE_HOME", keep_xdg, 1);
    else unsetenv("XDG_CACHE_HOME");
    if (keep_home[0]) setenv("HOME", keep_home, 1);
    else unsetenv("HOME");
}

static void test_diagnostics(void) {
    diag_list l = { 0 };
    diag_add(&l, DIAG_WARNING, "a.glib", 3, "unknown command '%s'", "Foo");
    diag_add_log(&l, DIAG_ERROR, "water.frag:12: error: 'x' undeclared\nplain words\n\nb.glsl:1: warning: w\n");
    CHECK(l.n == 4 && l.nerrors == 2 && l.nwarnings == 2);
    diag_add_log(&l, DIAG_NOTE, "tarn: error: no context\nscene.glib: warning: no commands\n");
    CHECK(l.n == 6 && l.nerrors == 3 && l.nwarnings == 3);
    CHECK(l.d[4].file[0] == '\0' && l.d[4].line == 0 && strcmp(l.d[4].text, "no context") == 0);
    CHECK(strcmp(l.d[5].file, "scene.glib") == 0 && l.d[5].line == 0);
    CHECK(strcmp(l.d[1].file, "water.frag") == 0 && l.d[1].line == 12 && l.d[1].severity == DIAG_ERROR);
    CHECK_STR_EQ(l.d[1].text, "'x' undeclared");
    CHECK(l.d[2].file[0] == '\0' && l.d[2].severity == DIAG_ERROR && strcmp(l.d[2].text, "plain words") == 0);
    char line[2048];
    diag_format(&l.d[0], line, sizeof line);
    CHECK_STR_EQ(line, "a.glib:3: warning: unknown command 'Foo'");
    /* a line of no known shape is kept as the tool wrote it */
    diag_format(&l.d[2], line, sizeof line);
    CHECK(l.d[2].bare && !l.d[1].bare);
    CHECK_STR_EQ(line, "plain words");
    diag_format(&l.d[4], line, sizeof line);
    CHECK_STR_EQ(line, "tarn: error: no context");
    char *all = diag_list_format(&l, 4);
    CHECK_STR_EQ(all, "tarn: error: no context\nscene.glib:0: warning: no commands\n");
    free(all);
    /* the first severity of a line is its own, whatever its text says later */
    diag_add_log(&l, DIAG_NOTE, "a.frag:7: error: 'w' : no such field: warning: x\n");
    CHECK(l.n == 7 && l.d[6].severity == DIAG_ERROR && l.d[6].line == 7 && strcmp(l.d[6].file, "a.frag") == 0);
    CHECK_STR_EQ(l.d[6].text, "'w' : no such field: warning: x");
    diag_list_free(&l);
    CHECK(l.n == 0 && l.d == NULL);
}


/* f(in) == want, f's heap result freed. */
static void check_path(char *(*f)(const char *), const char *in, const char *want) {
    char *got = f(in);
    CHECK_MSG(got && strcmp(got, want) == 0, "'%s' gave '%s', not '%s'", in, got ? got : "(null)", want);
    free(got);
}

/* path.h against Go's filepath.Clean on the same inputs (its documented
 * rules: one separator, no ".", ".." eats the name before it, "/.." is
 * "/", a relative path keeps its leading "..", "" is "."). */
static void test_paths(void) {
    static const struct { char *(*f)(const char *); const char *in, *want; } cases[] = {
        { path_clean, "a/./b/../c", "a/c" }, { path_clean, "a//b/", "a/b" }, { path_clean, "/..", "/" },
        { path_clean, "/a/b/../../..", "/" }, { path_clean, "../a/..", ".." }, { path_clean, "a/../../b", "../b" },
        { path_clean, "", "." }, { path_clean, "./", "." }, { path_clean, "/", "/" },
        { path_dir, "a/b.glib", "a" }, { path_dir, "b.glib", "." }, { path_dir, "/b.glib", "/" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) check_path(cases[i].f, cases[i].in, cases[i].want);
    char *j = path_join("packs/common", "../natural/water.frag");
    CHECK_STR_EQ(j, "packs/natural/water.frag");
    free(j);
    j = path_join("x", "/abs/f.glsl");
    CHECK_STR_EQ(j, "/abs/f.glsl");
    free(j);
    char cwd[1024], want[1200];
    CHECK(getcwd(cwd, sizeof cwd) != NULL);
    snprintf(want, sizeof want, "%s/b", strcmp(cwd, "/") == 0 ? "" : cwd);
    check_path(path_absolute, "a/../b", want);
    check_path(path_absolute, "/x/./y", "/x/y");
}

/* Writes text to name in the scratch folder, dated age_s seconds back. */
static const char *write_aged(const char *name, const char *text, double age_s) {
    scratch_write(name, text);
    CHECK(scratch_age(name, age_s));
    return scratch_path(name);
}

/* The one reader of scene files: the disk once, then memory while the
 * file is unchanged; a changed, young or refreshed file is read again. */
static void test_file_cache(void) {
    if (!scratch_create("cache")) {
        CHECK(false);
        return;
    }
    file_cache *c = file_cache_create();
    const char *path = write_aged("w.frag", "void main() {}\r\n", 10);
    file_text_opts o = { .crlf_to_lf = true };
    char why[256] = "";
    size_t n = 0;
    uint64_t h = 0;
    char *a = file_cache_read(c, path, &o, &n, &h, why, sizeof why);
    CHECK_STR_EQ(a, "void main() {}\n");   /* the options applied */
    CHECK_EQ(n, strlen("void main() {}\n"));
    CHECK_EQ(h, hash_fnv1a(HASH_FNV1A_BASIS, "void main() {}\r\n", 16));   /* of the bytes on disk */
    file_cache_counts k = file_cache_counts_of(c);
    CHECK_EQ(k.reads, 1);
    CHECK_EQ(k.hits, 0);
    /* again, spelled another way: memory, the same text, a copy of its own */
    char spelled[1400];
    snprintf(spelled, sizeof spelled, "%s/./x/../w.frag", scratch_dir);
    char *b = file_cache_read(c, spelled, &o, &n, NULL, why, sizeof why);
    CHECK_STR_EQ(b, "void main() {}\n");
    CHECK(a != b);
    k = file_cache_counts_of(c);
    CHECK_EQ(k.reads, 1);
    CHECK_EQ(k.hits, 1);
    /* the raw bytes of the held copy, without the options */
    char *raw = file_cache_bytes(c, path, 0, &n, why, sizeof why);
    CHECK(raw && n == 16 && memcmp(raw, "void main() {}\r\n", 16) == 0);
    CHECK_EQ(file_cache_counts_of(c).hits, 2);
    /* a tighter limit than the held copy: the disk says why */
    CHECK_EQ(file_cache_bytes(c, path, 8, &n, why, sizeof why), NULL);
    CHECK_STR_CONTAINS(why, "larger than 8 bytes");
    free(a); free(b); free(raw);
    /* changed on disk (same size, another time): read again */
    write_aged("w.frag", "void main() {1}\n", 5);
    a = file_cache_read(c, path, &o, &n, NULL, why, sizeof why);
    CHECK_STR_EQ(a, "void main() {1}\n");
    free(a);
    /* a file written just now may be rewritten within the kernel's clock
     * tick unseen: it is read every time until it has aged */
    const char *young = write_aged("y.frag", "young", 0);
    long reads = file_cache_counts_of(c).reads;
    for (int i = 0; i < 2; i++) free(file_cache_read(c, young, NULL, &n, NULL, why, sizeof why));
    CHECK_EQ(file_cache_counts_of(c).reads, reads + 2);
    /* the watcher's refresh reads whatever is held, and keeps it */
    write_aged("w.frag", "void main() {2}\n", 5);
    uint64_t hr = 0;
    CHECK(file_cache_refresh(c, path, &hr));
    CHECK_EQ(hr, hash_fnv1a(HASH_FNV1A_BASIS, "void main() {2}\n", 16));
    reads = file_cache_counts_of(c).reads;
    a = file_cache_read(c, path, NULL, &n, NULL, why, sizeof why);
    CHECK_STR_EQ(a, "void main() {2}\n");
    CHECK_EQ(file_cache_counts_of(c).reads, reads);
    free(a);
    /* missing: the reason alone; no cache: the disk, the same answers */
    CHECK_EQ(file_cache_read(c, scratch_path("none.frag"), NULL, &n, NULL, why, sizeof why), NULL);
    CHECK_STR_EQ(why, "No such file or directory");
    CHECK(!file_cache_refresh(c, scratch_path("none.frag"), &hr));
    a = file_cache_read(NULL, path, NULL, &n, &h, why, sizeof why);
    CHECK_STR_EQ(a, "void main() {2}\n");
    CHECK_EQ(h, hr);
    free(a);
    file_cache_destroy(c);
    scratch_remove();
}

/* file_cache_made's maker for the test: counts its calls, fills the bytes
 * with the call's number; "fail" fails. */
typedef struct make_probe {
    int calls;
    bool fail;
} make_probe;

static bool make_counted(void *user, void *out, size_t len, char *err, size_t errlen) {
    make_probe *p = user;
    p->calls++;
    if (p->fail) {
        snprintf(err, errlen, "the maker failed");
        return false;
    }
    memset(out, p->calls, len);
    return true;
}

/* Made content (a generated texture): made once per cache and copied after;
 * a failure keeps nothing; another length is refused; no cache: made each
 * time. */
static void test_file_cache_made(void) {
    file_cache *c = file_cache_create();
    make_probe p = { 0 };
    unsigned char out[8] = { 0 };
    char err[256] = "";
    CHECK(file_cache_made(c, "@tile/8", out, sizeof out, make_counted, &p, err, sizeof err));
    CHECK_EQ(p.calls, 1);
    CHECK_EQ(out[7], 1);
    memset(out, 0, sizeof out);
    CHECK(file_cache_made(c, "@tile/8", out, sizeof out, make_counted, &p, err, sizeof err));
    CHECK_EQ(p.calls, 1);          /* memory: the maker not called again */
    CHECK_EQ(out[0], 1);
    CHECK_EQ(out[7], 1);
    file_cache_counts k = file_cache_counts_of(c);
    CHECK_EQ(k.made, 1);
    CHECK_EQ(k.hits, 1);
    CHECK_EQ(k.reads, 0);
    unsigned char small[4];
    CHECK(!file_cache_made(c, "@tile/8", small, sizeof small, make_counted, &p, err, sizeof err));
    CHECK_STR_CONTAINS(err, "held at 8 bytes, asked for 4");
    /* another name is made apart; a failed make keeps nothing */
    p.fail = true;
    CHECK(!file_cache_made(c, "@other/8", out, sizeof out, make_counted, &p, err, sizeof err));
    CHECK_STR_EQ(err, "the maker failed");
    p.fail = false;
    CHECK(file_cache_made(c, "@other/8", out, sizeof out, make_counted, &p, err, sizeof err));
    CHECK_EQ(p.calls, 3);
    CHECK_EQ(out[0], 3);
    CHECK_EQ(file_cache_counts_of(c).made, 2);
    file_cache_destroy(c);
    /* no cache: made every time */
    p.calls = 0;
    for (int i = 0; i < 2; i++) CHECK(file_cache_made(NULL, "@tile/8", out, sizeof out, make_counted, &p, err, sizeof err));
    CHECK_EQ(p.calls, 2);
}

/* disk_cache: kept bytes come back only under their name, key and length,
 * whole; a damaged or foreign file, a bad name or no cache folder is a
 * miss, never an error. In a scratch XDG_CACHE_HOME. */
static void test_disk_cache(void) {
    if (!scratch_create("disk-cache")) return;
    char keep_xdg[4096] = "";
    const char *x = getenv("XDG_CACHE_HOME");
    if (x) snprintf(keep_xdg, sizeof keep_xdg, "%s", x);
    setenv("XDG_CACHE_HOME", scratch_dir, 1);
    float a[16], b[16];
    for (int i = 0; i < 16; i++) a[i] = (float)i * 0.25f;
    CHECK(!disk_cache_read("tile-4.f32", 7, b, sizeof b));           /* nothing kept yet */
    CHECK(disk_cache_write("tile-4.f32", 7, a, sizeof a));
    memset(b, 0, sizeof b);
    CHECK(disk_cache_read("tile-4.f32", 7, b, sizeof b));
    CHECK_EQ(memcmp(a, b, sizeof a), 0);
    CHECK(!disk_cache_read("tile-4.f32", 8, b, sizeof b));           /* another key: another binary made it */
    CHECK(!disk_cache_read("tile-4.f32", 7, b, sizeof b - 4));       /* another length */
    CHECK(!disk_cache_read("tile-8.f32", 7, b, sizeof b));           /* another name */
    CHECK(!disk_cache_read("tile-4.f32", 0, b, sizeof b));           /* key 0: nothing is kept */
    CHECK(!disk_cache_write("../x", 7, a, sizeof a));                /* no folders in a name */
    CHECK(!disk_cache_write("", 7, a, sizeof a));
    /* a file cut short, or with bytes after its length, is not the content */
    char path[4096], err[256];
    snprintf(path, sizeof path, "%s/tarn/made/tile-4.f32", scratch_dir);
    size_t n = 0;
    char *whole = file_read(path, 1 << 20, &n, err, sizeof err);
    CHECK(whole != NULL);
    if (whole) {
        CHECK(file_write(path, whole, n - 1, err, sizeof err));
        CHECK(!disk_cache_read("tile-4.f32", 7, b, sizeof b));
        char *longer = mem_alloc(n + 1);
        memcpy(longer, whole, n);
        longer[n] = 'x';
        CHECK(file_write(path, longer, n + 1, err, sizeof err));
        CHECK(!disk_cache_read("tile-4.f32", 7, b, sizeof b));
        free(longer);
        free(whole);
    }
    /* rewritten whole again; no leftover temporary file beside it */
    CHECK(disk_cache_write("tile-4.f32", 7, a, sizeof a));
    CHECK(disk_cache_read("tile-4.f32", 7, b, sizeof b));
    char tmp[4200];
    snprintf(tmp, sizeof tmp, "%s.%ld.tmp", path, (long)getpid());
    CHECK(!file_exists(tmp));
    /* the binary's key: the same within a run, never 0 */
    CHECK_NE(disk_cache_build_key(), 0);
    CHECK_EQ(disk_cache_build_key(), disk_cache_build_key());
    /* no cache folder: a miss and a refused write */
    char keep_home[4096] = "";
    const char *h = getenv("HOME");
    if (h) snprintf(keep_home, sizeof keep_home, "%s", h);
    unsetenv("XDG_CACHE_HOME");
    unsetenv("HOME");
    CHECK(!disk_cache_write("tile-4.f32", 7, a, sizeof a));
    CHECK(!disk_cache_read("tile-4.f32", 7, b, sizeof b));
    if (keep_home[0]) setenv("HOME", keep_home, 1);
    if (keep_xdg[0]) setenv("XDG_CACHE_HOME", keep_xdg, 1);
    char rm[512];
    snprintf(rm, sizeof rm, "rm -rf '%s/tarn'", scratch_dir);
    CHECK_EQ(system(rm), 0);
    scratch_remove();
}

/* The JSON and CSV spellings (RFC 8259's escapes, RFC 4180's quoting). */
static void test_data_formats(void) {
    strbuf o = { 0 };
    json_put_str(&o, "a\"b\\c\nd\te\x01");
    strbuf_puts(&o, " ");
    json_put_num(&o, 0.1);
    strbuf_puts(&o, " ");
    json_put_num(&o, NAN);
    strbuf_puts(&o, " ");
    json_put_num(&o, -INFINITY);
    CHECK_STR_EQ(o.s, "\"a\\\"b\\\\c\\nd\\te\\u0001\" 0.1 null \"-inf\"");
    strbuf_free(&o);
    csv_put_str(&o, "plain", false);
    strbuf_puts(&o, "|");
    csv_put_str(&o, "plain", true);
    strbuf_puts(&o, "|");
    csv_put_str(&o, "a,\"b\"", false);
    strbuf_puts(&o, "|");
    csv_put_num(&o, NAN);
    strbuf_puts(&o, "|");
    csv_put_num(&o, 1e-3);
    strbuf_puts(&o, "|");
    csv_put_num(&o, INFINITY);
    CHECK_STR_EQ(o.s, "plain|\"plain\"|\"a,\"\"b\"\"\"||0.001|inf");
    strbuf_free(&o);
}

int main(void) {
    RUN(test_strbuf_grows_and_formats);
    RUN(test_str_appendf);
    RUN(test_messages_never_overrun);
    RUN(test_files);
    RUN(test_read_text_options);
    RUN(test_paths);
    RUN(test_file_cache);
    RUN(test_file_cache_made);
    RUN(test_disk_cache);
    RUN(test_data_formats);
    RUN(test_mem_grow);
    RUN(test_median_and_sort);
    RUN(test_options);
    RUN(test_root_follows_environment);
    RUN(test_cache_dir_follows_xdg);
    RUN(test_diagnostics);
    return check_summary();
}
