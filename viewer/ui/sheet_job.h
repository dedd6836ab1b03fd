/* sheet_job: a hand-in sheet from the window (issue #27): `tarn sheet`
 * run as a child process for one slider, with every other value as the
 * window has it, so the window stays live while the tiles render. */
#ifndef TARN_SHEET_JOB_H
#define TARN_SHEET_JOB_H

#include <stdbool.h>
#include <stddef.h>
#include <sys/types.h>

#include "unif.h"

#define SHEET_JOB_ARGS_MAX 160

typedef struct sheet_job_desc {
    const char *tarn;             /* the tarn executable (NULL: /proc/self/exe) */
    const char *scene, *pack;     /* pack NULL or "": the scene's own */
    const char *program, *uniform;   /* the slider to vary, from its min to its max */
    double min, max;
    int n;                        /* values; 0: 5 */
    double time_s;
    const unif_set *sets;         /* the window's values: each one not at its default is a --set */
    int nsets;
    const char *out;              /* the sheet's path */
} sheet_job_desc;

typedef struct sheet_job {
    pid_t pid;                    /* 0: none running */
    char out[1024];
    char what[256];               /* "Water.uOpacity (5 values)" */
} sheet_job;

/* The command line of d, argv[0] first and NULL-terminated, its strings in
 * text (n bytes); returns argc, or -1 when it does not fit. */
int sheet_job_argv(const sheet_job_desc *d, char **argv, int max, char *text, size_t n);

/* Starts the child; false with the reason in err when it cannot start or
 * one is still running. */
bool sheet_job_start(sheet_job *j, const sheet_job_desc *d, char *err, size_t errlen);

/* -1 while it runs (or none was started), else its exit code (the job is
 * then free again). wait: block until it ends. */
int sheet_job_poll(sheet_job *j, bool wait);

#endif
