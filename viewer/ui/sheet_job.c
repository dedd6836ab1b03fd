#include "sheet_job.h"

#include <errno.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>

extern char **environ;

/* Appends s to the text buffer as the next argument. */
static bool add(char **argv, int *argc, int max, char *text, size_t n, size_t *used, const char *s) {
    size_t len = strlen(s) + 1;
    if (*argc + 1 >= max || *used + len > n) return false;
    memcpy(text + *used, s, len);
    argv[(*argc)++] = text + *used;
    *used += len;
    return true;
}

/* "P.NAME=v[,v...]" for one entry, as `--set` reads it. */
static void set_text(const char *program, const unif_entry *e, char *out, size_t n) {
    int len = snprintf(out, n, "%s.%s=", program, e->name);
    if (e->is_define) {
        unif_define_value(e, out + len, (int)(n - (size_t)len));
        return;
    }
    for (int k = 0; k < e->ncomp && len > 0 && (size_t)len < n; k++)
        len += snprintf(out + len, n - (size_t)len, "%s%.9g", k ? "," : "", (double)e->value[k]);
}

int sheet_job_argv(const sheet_job_desc *d, char **argv, int max, char *text, size_t n) {
    int argc = 0;
    size_t used = 0;
    char buf[512];
    bool ok = add(argv, &argc, max, text, n, &used, d->tarn ? d->tarn : "/proc/self/exe") &&
              add(argv, &argc, max, text, n, &used, "sheet") && add(argv, &argc, max, text, n, &used, d->scene);
    snprintf(buf, sizeof buf, "%s.%s=%.9g:%.9g:%d", d->program, d->uniform, d->min, d->max, d->n > 0 ? d->n : 5);
    ok = ok && add(argv, &argc, max, text, n, &used, "--vary") && add(argv, &argc, max, text, n, &used, buf);
    snprintf(buf, sizeof buf, "%.9g", d->time_s);
    ok = ok && add(argv, &argc, max, text, n, &used, "--time") && add(argv, &argc, max, text, n, &used, buf);
    if (d->pack && d->pack[0])
        ok = ok && add(argv, &argc, max, text, n, &used, "--pack") && add(argv, &argc, max, text, n, &used, d->pack);
    for (int s = 0; ok && s < d->nsets; s++) {
        const unif_set *set = &d->sets[s];
        for (int i = 0; ok && i < set->n; i++) {
            const unif_entry *e = &set->entries[i];
            bool varied = strcmp(set->program, d->program) == 0 && strcmp(e->name, d->uniform) == 0;
            if (varied || e->widget == UNIF_WIDGET_NONE || unif_is_default(e)) continue;
            set_text(set->program, e, buf, sizeof buf);
            ok = add(argv, &argc, max, text, n, &used, "--set") && add(argv, &argc, max, text, n, &used, buf);
        }
    }
    ok = ok && add(argv, &argc, max, text, n, &used, "--quiet") && add(argv, &argc, max, text, n, &used, "-o") &&
         add(argv, &argc, max, text, n, &used, d->out);
    if (!ok) return -1;
    argv[argc] = NULL;
    return argc;
}

bool sheet_job_start(sheet_job *j, const sheet_job_desc *d, char *err, size_t errlen) {
    if (j->pid > 0) {
        snprintf(err, errlen, "a sheet (%s) is still being made", j->what);
        return false;
    }
    char *argv[SHEET_JOB_ARGS_MAX], text[16384];
    if (sheet_job_argv(d, argv, SHEET_JOB_ARGS_MAX, text, sizeof text) < 0) {
        snprintf(err, errlen, "too many changed values for one command line");
        return false;
    }
    pid_t pid;
    int rc = posix_spawn(&pid, argv[0], NULL, NULL, argv, environ);
    if (rc != 0) {
        snprintf(err, errlen, "cannot run %s: %s", argv[0], strerror(rc));
        return false;
    }
    j->pid = pid;
    snprintf(j->out, sizeof j->out, "%s", d->out);
    snprintf(j->what, sizeof j->what, "%s.%s (%d values)", d->program, d->uniform, d->n > 0 ? d->n : 5);
    return true;
}

int sheet_job_poll(sheet_job *j, bool wait) {
    if (j->pid <= 0) return -1;
    int status = 0;
    pid_t r;
    do r = waitpid(j->pid, &status, wait ? 0 : WNOHANG);
    while (r < 0 && errno == EINTR);
    if (r == 0) return -1;
    j->pid = 0;
    if (r < 0) return 1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}
