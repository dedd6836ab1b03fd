#include "view_script.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "file.h"
#include "mem.h"
#include "strbuf.h"
#include "util.h"

#define SCRIPT_LINE_MAX 512

struct view_script {
    char path[1024];
    char (*lines)[SCRIPT_LINE_MAX];
    int nlines, cap, next;
    int wait_frames;            /* `frames`, `advance`: frames still to be drawn before the next line */
    double frame_dt;            /* ... each this much scene time after the one before (`advance`; 0: `frames`) */
    double wait_until;          /* clock_now_s() until which frames are drawn (0: none) */
    bool acted;                 /* the last step ran an action (set, time, camera...): its frame is owed */
    char arg[SCRIPT_LINE_MAX];
};

view_script *view_script_load(const char *path, char *err, int errlen) {
    char why[MSG_MAX];
    file_text_opts o = { .max_bytes = (size_t)VIEW_SCRIPT_MAX_LINES * SCRIPT_LINE_MAX, .strip_bom = true,
                         .crlf_to_lf = true };
    char *text = file_read_text(path, &o, NULL, why, sizeof why);
    if (!text) { msg_set(err, (size_t)errlen, "%s: cannot open the script (%s)", path, why); return NULL; }
    view_script *s = mem_zalloc(sizeof *s);
    snprintf(s->path, sizeof s->path, "%s", path);
    for (char *line = text; *line;) {
        char *end = line + strcspn(line, "\n");
        bool last = *end == '\0';
        *end = '\0';
        if (s->nlines == VIEW_SCRIPT_MAX_LINES) {
            msg_set(err, (size_t)errlen, "%s: more than %d lines; not a script?", path, VIEW_SCRIPT_MAX_LINES);
            free(text);
            view_script_free(s);
            return NULL;
        }
        s->lines = mem_grow(s->lines, &s->cap, s->nlines + 1, sizeof *s->lines);
        line[strcspn(line, "\r#")] = '\0';
        snprintf(s->lines[s->nlines++], SCRIPT_LINE_MAX, "%s", line);
        line = last ? end : end + 1;
    }
    free(text);
    return s;
}

void view_script_free(view_script *s) {
    if (!s) return;
    free(s->lines);
    free(s);
}

bool view_script_waiting(const view_script *s) {
    return s && !s->acted && s->wait_frames == 0 && s->wait_until > 0 && clock_now_s() < s->wait_until;
}

double view_script_wait_left_s(const view_script *s) {
    return view_script_waiting(s) ? s->wait_until - clock_now_s() : 0.0;
}

const char *view_script_arg(const view_script *s) { return s->arg; }

static int parse_floats(char *rest, float *v, int max) {
    int n = 0;
    for (char *tok = strtok(rest, " \t"); tok && n < max; tok = strtok(NULL, " \t")) {
        char *end;
        v[n] = strtof(tok, &end);
        if (*end) return -1;
        n++;
    }
    return n;
}

static unif_entry *find_entry(render *r, const char *program, const char *name) {
    int n;
    unif_set *sets = render_uniforms(r, &n);
    for (int i = 0; i < n; i++)
        if (strcmp(sets[i].program, program) == 0) return unif_find(&sets[i], name);
    return NULL;
}

/* set/expect PROGRAM UNIFORM v... */
static view_script_status value_action(const char *path, view_script_ctx *c, bool expect, char *rest, int line) {
    char program[64], name[64];
    int used = 0;
    if (sscanf(rest, "%63s %63s %n", program, name, &used) < 2) {
        fprintf(stderr, "%s:%d: expected PROGRAM UNIFORM values\n", path, line);
        return VIEW_SCRIPT_FAILED;
    }
    float v[16];
    int n = parse_floats(rest + used, v, 16);
    if (n <= 0) {
        fprintf(stderr, "%s:%d: expected numbers\n", path, line);
        return VIEW_SCRIPT_FAILED;
    }
    if (!expect) {
        unif_entry *e = find_entry(c->r, program, name);
        if (!e) {
            fprintf(stderr, "%s:%d: no uniform '%s' in program '%s'\n", path, line, name, program);
            return VIEW_SCRIPT_FAILED;
        }
        for (int i = 0; i < n && i < e->ncomp; i++) e->value[i] = v[i];
        return e->is_define ? VIEW_SCRIPT_REBUILD : VIEW_SCRIPT_CONTINUE;
    }
    float got[16];
    if (!render_read_uniform(c->r, program, name, got, n)) {
        fprintf(stderr, "%s:%d: expect: program '%s' has no active uniform '%s'\n", path, line, program, name);
        return VIEW_SCRIPT_FAILED;
    }
    for (int i = 0; i < n; i++)
        if (fabsf(got[i] - v[i]) > 1e-5f) {
            fprintf(stderr, "%s:%d: expect: %s.%s[%d] is %g, expected %g\n", path, line, program, name, i, got[i], v[i]);
            return VIEW_SCRIPT_FAILED;
        }
    fprintf(stderr, "tarn: script: %s.%s holds the expected value\n", program, name);
    return VIEW_SCRIPT_CONTINUE;
}

/* camera CX CY CZ DIST YAW PITCH: the orbit as a drag leaves it (up stays). */
static view_script_status camera_action(const char *path, view_script_ctx *c, char *rest, int line) {
    float v[7];
    int n = parse_floats(rest, v, 7);
    bool finite = n == 6;
    for (int i = 0; finite && i < 6; i++) finite = isfinite(v[i]);
    if (!finite || v[3] <= 0) {
        fprintf(stderr, "%s:%d: camera wants CX CY CZ DISTANCE YAW PITCH (finite, distance > 0)\n", path, line);
        return VIEW_SCRIPT_FAILED;
    }
    if (!c->cam) {
        fprintf(stderr, "%s:%d: no camera to move here\n", path, line);
        return VIEW_SCRIPT_FAILED;
    }
    for (int i = 0; i < 3; i++) c->cam->center[i] = v[i];
    c->cam->distance = v[3];
    c->cam->yaw = v[4];
    c->cam->pitch = v[5];
    return VIEW_SCRIPT_CONTINUE;
}

static view_script_status pause_action(const char *path, view_script_ctx *c, char *rest, int line) {
    char word[8] = "";
    if (sscanf(rest, "%7s", word) != 1 || (strcmp(word, "0") != 0 && strcmp(word, "1") != 0)) {
        fprintf(stderr, "%s:%d: pause wants 1 (stop the clock) or 0 (run it)\n", path, line);
        return VIEW_SCRIPT_FAILED;
    }
    if (!c->paused) {
        fprintf(stderr, "%s:%d: no clock to pause here\n", path, line);
        return VIEW_SCRIPT_FAILED;
    }
    *c->paused = word[0] == '1';
    return VIEW_SCRIPT_CONTINUE;
}

view_script_status view_script_action(view_script_ctx *c, char *text, const char *file, int line) {
    char cmd[32];
    int used = 0;
    if (sscanf(text, "%31s %n", cmd, &used) < 1) return VIEW_SCRIPT_CONTINUE;   /* blank */
    char *rest = text + used;
    if (strcmp(cmd, "time") == 0) { *c->time_s = atof(rest); return VIEW_SCRIPT_CONTINUE; }
    if (strcmp(cmd, "set") == 0) return value_action(file, c, false, rest, line);
    if (strcmp(cmd, "expect") == 0) return value_action(file, c, true, rest, line);
    if (strcmp(cmd, "camera") == 0) return camera_action(file, c, rest, line);
    if (strcmp(cmd, "pause") == 0) return pause_action(file, c, rest, line);
    if (c->custom) return c->custom(c->user, cmd, rest, file, line);
    fprintf(stderr, "%s:%d: unknown script action '%s'\n", file, line, cmd);
    return VIEW_SCRIPT_FAILED;
}

/* advance DT N: the next N frames each drawn DT seconds of scene time
 * after the one before (the first DT after the time now), then the next
 * line, on the frame the last one showed: a clock running at 1/DT frames a
 * second, frame for frame, whatever the frames cost (a benchmark's
 * animation at fixed instants, every frame a new picture). */
static view_script_status advance_action(view_script *s, view_script_ctx *c, char *rest, int line) {
    float v[2];
    int n = parse_floats(rest, v, 2);
    if (n != 2 || !isfinite(v[0]) || v[1] < 1 || v[1] != floorf(v[1])) {
        fprintf(stderr, "%s:%d: advance wants DT (seconds) and N (frames, 1 or more)\n", s->path, line);
        return VIEW_SCRIPT_FAILED;
    }
    s->frame_dt = v[0];
    s->wait_frames = (int)v[1];
    *c->time_s += s->frame_dt;
    return VIEW_SCRIPT_CONTINUE;
}

/* The actions that pace the script, then view_script_action's. */
static view_script_status run_line(view_script *s, view_script_ctx *c, char *text, int line) {
    char cmd[32];
    int used = 0;
    if (sscanf(text, "%31s %n", cmd, &used) < 1) return VIEW_SCRIPT_CONTINUE;   /* blank */
    char *rest = text + used;
    if (strcmp(cmd, "frames") == 0) {
        s->wait_frames = atoi(rest);
        s->frame_dt = 0;
        return VIEW_SCRIPT_CONTINUE;
    }
    if (strcmp(cmd, "wait") == 0) { s->wait_until = clock_now_s() + atof(rest); return VIEW_SCRIPT_CONTINUE; }
    if (strcmp(cmd, "advance") == 0) return advance_action(s, c, rest, line);
    if (strcmp(cmd, "reload") == 0) return VIEW_SCRIPT_RELOAD;
    if (strcmp(cmd, "quit") == 0) return VIEW_SCRIPT_DONE;
    if (strcmp(cmd, "screenshot") == 0) {
        snprintf(s->arg, sizeof s->arg, "%s", rest);
        s->arg[strcspn(s->arg, " \t")] = '\0';
        return VIEW_SCRIPT_SCREENSHOT;
    }
    s->acted = true;
    return view_script_action(c, text, s->path, line);
}

view_script_status view_script_step(view_script *s, view_script_ctx *c) {
    s->acted = false;   /* the frame before this step showed it */
    if (s->wait_frames > 0 && --s->wait_frames > 0) {   /* a frame drawn; on the Nth, the next line now */
        if (s->frame_dt != 0) *c->time_s += s->frame_dt;
        return VIEW_SCRIPT_CONTINUE;
    }
    if (s->wait_until > 0) {
        if (clock_now_s() < s->wait_until) return VIEW_SCRIPT_CONTINUE;
        s->wait_until = 0;
    }
    while (s->next < s->nlines) {
        int line = s->next + 1;
        char text[SCRIPT_LINE_MAX];
        memcpy(text, s->lines[s->next++], sizeof text);
        view_script_status st = run_line(s, c, text, line);
        if (st != VIEW_SCRIPT_CONTINUE || s->wait_frames > 0 || s->wait_until > 0) return st;
    }
    return VIEW_SCRIPT_DONE;
}
