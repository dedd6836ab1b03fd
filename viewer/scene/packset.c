/* packset: packs on disk, bench.txt and bounds.txt (see packset.h). */
#include "packset.h"
#include "strbuf.h"

#include "file.h"
#include "mem.h"
#include "ref_buffers.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define LINE_MAX_LEN 2048
#define FILE_MAX_LEN (256 * 1024)

static void msg(char *err, int errlen, const char *fmt, ...) {
    if (!err || errlen <= 0) return;
    size_t used = strlen(err);
    if ((int)used >= errlen - 1) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err + used, (size_t)errlen - used, fmt, ap);
    va_end(ap);
}

static bool is_file(const char *path) {
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

bool packset_name_ok(const char *s) {
    if (!s[0] || s[0] == '.' || strlen(s) >= PACKSET_NAME_MAX) return false;
    for (const char *p = s; *p; p++)
        if (!isalnum((unsigned char)*p) && *p != '_' && *p != '-' && *p != '.') return false;
    return true;
}

/* packs_dir/name/pack.glib is a file. */
static bool pack_in(const char *packs_dir, const char *name) {
    if (!packset_name_ok(name)) return false;
    char path[2048];
    if (snprintf(path, sizeof path, "%s/%s/pack.glib", packs_dir, name) >= (int)sizeof path) return false;
    return is_file(path);
}

bool packset_exists(const char *root, const char *name) {
    char dir[2048];
    snprintf(dir, sizeof dir, "%s/packs", root);
    return pack_in(dir, name);
}

static int cmp_name(const void *a, const void *b) { return strcmp((const char *)a, (const char *)b); }

int packset_list(const char *root, packset_name *names, int max) {
    char dir[2048];
    snprintf(dir, sizeof dir, "%s/packs", root);
    return packset_list_dir(dir, names, max);
}

int packset_list_dir(const char *packs_dir, packset_name *names, int max) {
    DIR *d = opendir(packs_dir);
    if (!d) return 0;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) && n < max) {
        if (strcmp(e->d_name, "common") == 0 || !pack_in(packs_dir, e->d_name)) continue;
        size_t len = strlen(e->d_name);   /* < PACKSET_NAME_MAX: pack_in checked it */
        memcpy(names[n], e->d_name, len + 1);
        n++;
    }
    closedir(d);
    qsort(names, (size_t)n, sizeof *names, cmp_name);
    return n;
}

/* A pack's small text file (bench.txt, bounds.txt); NULL when missing.
 * A longer file is read up to FILE_MAX_LEN, as a line limit would. */
static char *read_text(const char *path) {
    char why[MSG_MAX];
    size_t n = 0;
    char *text = file_read_text(path, NULL, &n, why, sizeof why);
    if (text && n > FILE_MAX_LEN) text[FILE_MAX_LEN] = '\0';
    return text;
}

/* Next line of text (comments cut, ends trimmed) into line, the comment's
 * text (after '#', trimmed) into comment; false at the end. */
static bool next_line(const char **pos, char *line, char *comment, int *lineno) {
    const char *p = *pos;
    if (!*p) return false;
    const char *end = p + strcspn(p, "\r\n");
    size_t len = (size_t)(end - p);
    if (len >= LINE_MAX_LEN) len = LINE_MAX_LEN - 1;
    memcpy(line, p, len);
    line[len] = '\0';
    comment[0] = '\0';
    if (*end == '\r' && end[1] == '\n') end++;
    *pos = *end ? end + 1 : end;
    (*lineno)++;
    /* '#' at the start of a word starts a comment, except the #RRGGBB
     * right after `colour` */
    bool colour = strncmp(line, "colour", 6) == 0 || strncmp(line, "color", 5) == 0;
    int word = 0;
    for (char *c = line; *c; c++) {
        bool starts = c == line || isspace((unsigned char)c[-1]);
        if (!starts || isspace((unsigned char)*c)) continue;
        word++;
        if (*c == '#' && !(colour && word == 2)) {
            snprintf(comment, PACKSET_COMMENT_MAX, "%s", c + 1 + strspn(c + 1, " \t#"));
            *c = '\0';
            break;
        }
    }
    size_t clen = strlen(comment);
    while (clen && isspace((unsigned char)comment[clen - 1])) comment[--clen] = '\0';
    len = strlen(line);
    while (len && isspace((unsigned char)line[len - 1])) line[--len] = '\0';
    return true;
}

static bool parse_value(const char *s, float *v) {
    if (strcmp(s, "true") == 0 || strcmp(s, "on") == 0) { *v = 1; return true; }
    if (strcmp(s, "false") == 0 || strcmp(s, "off") == 0) { *v = 0; return true; }
    char *end;
    errno = 0;
    double d = strtod(s, &end);
    if (end == s || *end || errno || !isfinite(d) || fabs(d) > 3e38) return false;
    *v = (float)d;
    return true;
}

/* PROGRAM.NAME=v[,v...] into a; false with the reason in why. */
static bool parse_assign(const char *word, packset_assign *a, char *why, int whylen) {
    memset(a, 0, sizeof *a);
    const char *dot = strchr(word, '.'), *eq = strchr(word, '=');
    if (!dot || !eq || dot > eq) {
        snprintf(why, (size_t)whylen, "'%s' is not PROGRAM.ENTRY=VALUE (or *.ENTRY=VALUE, scene.Command=ARGS)", word);
        return false;
    }
    size_t plen = (size_t)(dot - word), nlen = (size_t)(eq - dot - 1);
    if (plen == 0 || nlen == 0 || plen >= PACKSET_NAME_MAX || nlen >= PACKSET_NAME_MAX) {
        snprintf(why, (size_t)whylen, "'%s': empty or too long a name", word);
        return false;
    }
    memcpy(a->program, word, plen);
    memcpy(a->name, dot + 1, nlen);
    char vals[LINE_MAX_LEN];
    snprintf(vals, sizeof vals, "%s", eq + 1);
    if (!vals[0]) {
        snprintf(why, (size_t)whylen, "'%s': no value after '='", word);
        return false;
    }
    char *save = NULL;
    for (char *tok = strtok_r(vals, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        if (a->nvalue >= 16) {
            snprintf(why, (size_t)whylen, "'%s': at most 16 values", word);
            return false;
        }
        if (!parse_value(tok, &a->value[a->nvalue])) {
            snprintf(why, (size_t)whylen, "'%s': '%s' is not a number (or true/false)", word, tok);
            return false;
        }
        a->nvalue++;
    }
    return true;
}

static bool parse_hex_colour(const char *s, float rgb[3]) {
    if (s[0] == '#') s++;
    if (strlen(s) != 6) return false;
    for (int i = 0; i < 6; i++)
        if (!isxdigit((unsigned char)s[i])) return false;
    unsigned v = (unsigned)strtoul(s, NULL, 16);
    rgb[0] = (float)((v >> 16) & 255) / 255.0f;
    rgb[1] = (float)((v >> 8) & 255) / 255.0f;
    rgb[2] = (float)(v & 255) / 255.0f;
    return true;
}


/* above += " " + c, cut to fit. */
static void join_comment(char *above, size_t cap, const char *c) {
    size_t used = strlen(above), n = strlen(c);
    if (used && used + 1 < cap) above[used++] = ' ';
    if (used + n >= cap) n = cap - 1 - used;
    memcpy(above + used, c, n);
    above[used + n] = '\0';
}

static void add_default(packset_bench *b) {
    b->settings = mem_zalloc(sizeof *b->settings);
    snprintf(b->settings[0].name, PACKSET_NAME_MAX, "default");
    b->n = 1;
}

bool packset_bench_parse(const char *text, const char *path, packset_bench *out, char *err, int errlen) {
    memset(out, 0, sizeof *out);
    snprintf(out->path, sizeof out->path, "%s", path ? path : "bench.txt");
    bool ok = true;
    const char *pos = text ? text : "";
    char line[LINE_MAX_LEN], comment[PACKSET_COMMENT_MAX], above[PACKSET_COMMENT_MAX] = "";
    int lineno = 0;
    while (next_line(&pos, line, comment, &lineno)) {
        char *save = NULL;
        char *first = strtok_r(line, " \t", &save);
        if (!first) {   /* a comment line joins the block above the next setting; a blank one ends it */
            if (comment[0]) join_comment(above, sizeof above, comment);
            else above[0] = '\0';
            continue;
        }
        char tip[PACKSET_COMMENT_MAX];
        snprintf(tip, sizeof tip, "%s", comment[0] ? comment : above);
        above[0] = '\0';
        if (strcmp(first, "colour") == 0 || strcmp(first, "color") == 0) {
            char *c = strtok_r(NULL, " \t", &save);
            if (!c || !parse_hex_colour(c, out->colour)) {
                msg(err, errlen, "%s:%d: colour wants #RRGGBB\n", out->path, lineno);
                ok = false;
            } else {
                out->has_colour = true;
            }
            continue;
        }
        if (strcmp(first, "buffer") != 0 &&
            (strlen(first) >= PACKSET_NAME_MAX || strchr(first, '=') || strchr(first, ','))) {
            msg(err, errlen, "%s:%d: a setting line is NAME ASSIGNMENT...; '%s' is not a name\n", out->path,
                lineno, first);
            ok = false;
            continue;
        }
        bool dup = false;
        for (int i = 0; i < out->n && strcmp(first, "buffer") != 0; i++) dup |= strcmp(out->settings[i].name, first) == 0;
        if (dup) {
            msg(err, errlen, "%s:%d: setting '%s' is written twice; the second is skipped\n", out->path, lineno,
                first);
            ok = false;
            continue;
        }
        bool is_buffer = strcmp(first, "buffer") == 0;
        if (is_buffer) {
            first = strtok_r(NULL, " \t", &save);
            const ref_buffer_info *known = ref_buffer_named(first);
            if (!known || !known->tarn_output) {
                char names[256] = "";
                for (int i = 0; i < REF_BUF_COUNT; i++)
                    if (ref_buffers[i].tarn_output)
                        snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", names[0] ? ", " : "",
                                 ref_buffers[i].name);
                msg(err, errlen, "%s:%d: buffer wants one of %s\n", out->path, lineno, names);
                ok = false;
                continue;
            }
        }
        packset_setting s;
        memset(&s, 0, sizeof s);
        snprintf(s.name, sizeof s.name, "%s", first);
        snprintf(s.comment, sizeof s.comment, "%s", tip);
        s.line = lineno;
        bool line_ok = true;
        for (char *w = strtok_r(NULL, " \t", &save); w; w = strtok_r(NULL, " \t", &save)) {
            packset_assign a;
            char why[MSG_MAX];
            if (!parse_assign(w, &a, why, sizeof why)) {
                msg(err, errlen, "%s:%d: %s\n", out->path, lineno, why);
                line_ok = false;
                break;
            }
            s.assign = mem_realloc(s.assign, (size_t)(s.nassign + 1) * sizeof *s.assign);
            s.assign[s.nassign++] = a;
        }
        if (!line_ok) {
            free(s.assign);
            ok = false;
            continue;
        }
        if (is_buffer) {
            packset_buffer *bg = out->buffers =
                mem_realloc(out->buffers, (size_t)(out->nbuffers + 1) * sizeof *out->buffers);
            snprintf(bg[out->nbuffers].name, PACKSET_NAME_MAX, "%s", s.name);
            bg[out->nbuffers++].how = s;
            continue;
        }
        out->settings = mem_realloc(out->settings, (size_t)(out->n + 1) * sizeof *out->settings);
        out->settings[out->n++] = s;
    }
    if (out->n == 0) add_default(out);
    return ok;
}

const packset_setting *packset_setting_named(const packset_bench *b, const char *name) {
    for (int i = 0; i < b->n; i++)
        if (strcmp(b->settings[i].name, name) == 0) return &b->settings[i];
    return NULL;
}

int packset_menu(const packset_bench *b, int *order) {
    const char *first[2] = { "default", "paper" };
    int n = 0;
    if (!packset_setting_named(b, "default")) order[n++] = -1;
    for (int f = 0; f < 2; f++)
        for (int i = 0; i < b->n; i++)
            if (strcmp(b->settings[i].name, first[f]) == 0) order[n++] = i;
    for (int i = 0; i < b->n; i++)
        if (strcmp(b->settings[i].name, first[0]) != 0 && strcmp(b->settings[i].name, first[1]) != 0)
            order[n++] = i;
    return n;
}

bool packset_bench_load(const char *root, const char *pack, packset_bench *out, char *err, int errlen) {
    char path[2048];
    snprintf(path, sizeof path, "%s/packs/%s/bench.txt", root, pack);
    char *text = read_text(path);
    if (!text) {
        memset(out, 0, sizeof *out);
        add_default(out);
        return true;
    }
    bool ok = packset_bench_parse(text, path, out, err, errlen);
    free(text);
    return ok;
}

void packset_bench_free(packset_bench *b) {
    for (int i = 0; i < b->n; i++) free(b->settings[i].assign);
    free(b->settings);
    for (int i = 0; i < b->nbuffers; i++) free(b->buffers[i].how.assign);
    free(b->buffers);
    memset(b, 0, sizeof *b);
}

bool packset_apply(unif_set *sets, int nsets, const packset_setting *s, bool *defines_changed,
                   char *err, int errlen) {
    bool ok = true;
    if (defines_changed) *defines_changed = false;
    for (int k = 0; k < s->nassign; k++) {
        const packset_assign *a = &s->assign[k];
        if (strcmp(a->program, "scene") == 0) continue;
        bool all = strcmp(a->program, "*") == 0, found_prog = false, found = false;
        for (int i = 0; i < nsets; i++) {
            if (!all && strcmp(sets[i].program, a->program) != 0) continue;
            found_prog = true;
            unif_entry *e = unif_find(&sets[i], a->name);
            if (!e) continue;
            found = true;
            int n = a->nvalue;
            if (n == 1 && e->ncomp > 1 && e->widget == UNIF_WIDGET_COLOR) n = e->ncomp;   /* grey */
            for (int c = 0; c < n && c < e->ncomp; c++) {
                float v = a->value[a->nvalue == 1 ? 0 : c];
                float before = e->value[c];
                unif_set_component(e, c, v);
                if (e->value[c] != v && !(unif_is_int(e) && fabsf(e->value[c] - v) < 0.5f)) {
                    msg(err, errlen, "setting '%s': %s.%s[%d] = %g is out of its range; it is %g\n", s->name,
                        sets[i].program, a->name, c, v, e->value[c]);
                    ok = false;
                }
                if (e->is_define && e->value[c] != before && defines_changed) *defines_changed = true;
            }
            if (a->nvalue > e->ncomp) {
                msg(err, errlen, "setting '%s': %s.%s has %d components, %d values given\n", s->name,
                    sets[i].program, a->name, e->ncomp, a->nvalue);
                ok = false;
            }
        }
        if (!found) {
            if (!all && !found_prog) msg(err, errlen, "setting '%s': no Program '%s'\n", s->name, a->program);
            else msg(err, errlen, "setting '%s': no entry '%s' in %s\n", s->name, a->name,
                     all ? "any Program" : a->program);
            ok = false;
        }
    }
    return ok;
}

int packset_scene_lines(const packset_setting *s, char *out, int outlen) {
    int len = 0;
    if (outlen > 0) out[0] = '\0';
    for (int k = 0; k < s->nassign; k++) {
        const packset_assign *a = &s->assign[k];
        if (strcmp(a->program, "scene") != 0) continue;
        len += snprintf(out + (len < outlen ? len : outlen), (size_t)(len < outlen ? outlen - len : 0), "%s",
                        a->name);
        for (int i = 0; i < a->nvalue; i++)
            len += snprintf(out + (len < outlen ? len : outlen), (size_t)(len < outlen ? outlen - len : 0),
                            " %.9g", a->value[i]);
        len += snprintf(out + (len < outlen ? len : outlen), (size_t)(len < outlen ? outlen - len : 0), "\n");
    }
    return len;
}

bool packset_write_wrapper(const packset_setting *s, const char *scene_path, const char *path, char *err,
                           int errlen) {
    char lines[4096];
    packset_scene_lines(s, lines, sizeof lines);
    FILE *f = fopen(path, "w");
    if (!f) {
        snprintf(err, (size_t)errlen, "%s: %s", path, strerror(errno));
        return false;
    }
    fprintf(f, "##OpenGL GLIB\n# written by tarn bench: %s with setting '%s'\nInclude \"%s\"\n%s", scene_path,
            s->name, scene_path, lines);
    bool ok = fclose(f) == 0;
    if (!ok) snprintf(err, (size_t)errlen, "%s: %s", path, strerror(errno));
    return ok;
}

bool packset_bounds_parse(const char *text, const char *path, packset_bounds *out, char *err, int errlen) {
    memset(out, 0, sizeof *out);
    snprintf(out->path, sizeof out->path, "%s", path ? path : "bounds.txt");
    out->found = text != NULL;
    bool ok = true;
    const char *pos = text ? text : "";
    char line[LINE_MAX_LEN], comment[PACKSET_COMMENT_MAX];
    int lineno = 0;
    while (next_line(&pos, line, comment, &lineno)) {
        char name[LINE_MAX_LEN], val[LINE_MAX_LEN];
        int used = 0;
        if (sscanf(line, "%2047s %2047s %n", name, val, &used) < 2) {
            if (sscanf(line, "%2047s", name) == 1) {
                msg(err, errlen, "%s:%d: a bound line is CASE MAX_RMSE|none [why]\n", out->path, lineno);
                ok = false;
            }
            continue;
        }
        packset_bound b;
        memset(&b, 0, sizeof b);
        b.line = lineno;
        if (strlen(name) >= PACKSET_NAME_MAX) {
            msg(err, errlen, "%s:%d: case name too long\n", out->path, lineno);
            ok = false;
            continue;
        }
        snprintf(b.case_name, sizeof b.case_name, "%s", name);
        float v;
        if (strcmp(val, "none") == 0) b.max_rmse = -1;
        else if (parse_value(val, &v) && v > 0) b.max_rmse = v;
        else {
            msg(err, errlen, "%s:%d: '%s' is not a positive RMSE or 'none'\n", out->path, lineno, val);
            ok = false;
            continue;
        }
        if (used > 0) snprintf(b.why, sizeof b.why, "%s", line + used);
        out->b = mem_realloc(out->b, (size_t)(out->n + 1) * sizeof *out->b);
        out->b[out->n++] = b;
    }
    return ok;
}

bool packset_bounds_load(const char *root, const char *pack, packset_bounds *out, char *err, int errlen) {
    char path[2048];
    snprintf(path, sizeof path, "%s/packs/%s/bounds.txt", root, pack);
    char *text = read_text(path);
    bool ok = packset_bounds_parse(text, path, out, err, errlen);
    free(text);
    return ok;
}

void packset_bounds_free(packset_bounds *b) {
    free(b->b);
    memset(b, 0, sizeof *b);
}

const packset_bound *packset_bound_for(const packset_bounds *b, const char *case_name) {
    const packset_bound *star = NULL;
    for (int i = 0; i < b->n; i++) {
        if (strcmp(b->b[i].case_name, case_name) == 0) return &b->b[i];
        if (strcmp(b->b[i].case_name, "*") == 0) star = &b->b[i];
    }
    return star;
}

/* The bounds of a pack without a bounds.txt line for the case: loose
 * (RMSE, linear RGB, 96x54); each pack tightens its own. */
static const packset_bound builtin_bounds[] = {
    { "*", 0.30, "", 0 },
};

const packset_bound *packset_bound_resolve(const packset_bounds *b, const char *case_name, const char **from) {
    const packset_bound *own = b ? packset_bound_for(b, case_name) : NULL;
    if (own) {
        if (from) *from = b->path;
        return own;
    }
    if (from) *from = "built-in";
    const packset_bound *star = NULL;
    for (size_t i = 0; i < sizeof builtin_bounds / sizeof builtin_bounds[0]; i++) {
        if (strcmp(builtin_bounds[i].case_name, case_name) == 0) return &builtin_bounds[i];
        if (strcmp(builtin_bounds[i].case_name, "*") == 0) star = &builtin_bounds[i];
    }
    return star;
}

void packset_palette(int i, float rgb[3]) {
    static const unsigned tab10[] = { 0x1f77b4, 0xff7f0e, 0x2ca02c, 0xd62728, 0x9467bd,
                                      0x8c564b, 0xe377c2, 0x7f7f7f, 0xbcbd22, 0x17becf };
    unsigned v = tab10[(unsigned)i % 10];
    rgb[0] = (float)((v >> 16) & 255) / 255.0f;
    rgb[1] = (float)((v >> 8) & 255) / 255.0f;
    rgb[2] = (float)(v & 255) / 255.0f;
}
