/* cmd_opts: what every command's parser needs once (see cmd.h). */
#include "cmd.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "packset.h"
#include "util.h"
#include "render.h"
#include "strbuf.h"
#include "render_setting.h"

bool cmd_wants_help(int argc, char **argv) {
    for (int i = 0; i < argc; i++)
        if (opt_is_help(argv[i])) return true;
    return false;
}

bool cmd_opt_range(const char *s, double lo, double hi, double *out) {
    double v;
    errno = 0;
    if (!opt_double(s, &v) || errno || !(v >= lo && v <= hi)) return false;
    *out = v;
    return true;
}

bool cmd_opt_int(const char *s, int lo, int hi, int *out) {
    char *end;
    if (!s) return false;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end || errno || v < lo || v > hi) return false;
    *out = (int)v;
    return true;
}

bool cmd_opt_msaa(const char *s, int *samples) {
    int n;
    if (!cmd_opt_int(s, 0, 16, &n)) return false;
    *samples = n < 1 ? 1 : n;
    return true;
}

int cmd_split(const char *list, char *buf, size_t buflen, const char **parts, int max) {
    snprintf(buf, buflen, "%s", list);
    int n = 0;
    char *save = NULL;
    for (char *p = strtok_r(buf, ",", &save); p; p = strtok_r(NULL, ",", &save)) {
        if (n >= max) return -1;
        parts[n++] = p;
    }
    return n;
}

bool cmd_opt_pack(const char *name, char *why, size_t whylen) {
    packset_name all[PACKSET_MAX];
    int n = packset_list(tarn_root(), all, PACKSET_MAX);
    for (int i = 0; i < n; i++)
        if (strcmp(all[i], name) == 0) return true;
    char list[PACKSET_MAX * (PACKSET_NAME_MAX + 2)] = "";
    for (int i = 0; i < n; i++) {
        strcat(list, i ? ", " : "");
        strcat(list, all[i]);
    }
    snprintf(why, whylen, "no pack '%s' in %s/packs: the packs are %s", name, tarn_root(),
             n ? list : "(none found)");
    return false;
}

/* --set (and sheet's --vary): what moving a slider or ticking a Define would do, written as
 * bench.txt assignments (PROGRAM.NAME=V, NAME=V for every Program, or
 * scene.Command=ARGS as a setting's). One assignment at a time, in order,
 * so there is no cap on how many and a later one wins as on the panel. */
bool cmd_apply_set(render *r, const char *set, const char *what) {
    const char *eq = strchr(set, '='), *dot = strchr(set, '.');
    bool bare = !dot || (eq && dot > eq);
    char *text = NULL;
    str_appendf(&text, "cli %s%s", bare ? "*." : "", set);
    packset_bench b = {0};
    char err[MSG_MAX] = "";
    bool ok = text && packset_bench_parse(text, what, &b, err, sizeof err) && b.n > 0;
    if (ok) ok = render_setting_assign(r, &b.settings[0], err, sizeof err);
    if (err[0]) fprintf(stderr, "tarn: %s: %s%s", what, err, err[strlen(err) - 1] == '\n' ? "" : "\n");
    packset_bench_free(&b);
    free(text);
    return ok;
}
