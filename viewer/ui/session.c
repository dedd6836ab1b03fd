/* session: the session file, its replay and its recording (session.h). */
#include "session.h"
#include "strbuf.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "file.h"
#include "mem.h"
#include "path.h"
#include "render_setting.h"
#include "view_script.h"

static const char *const kind_names[] = {
    [SESSION_SLIDER] = "slider", [SESSION_COLOUR] = "colour", [SESSION_CHECKBOX] = "checkbox",
    [SESSION_DEFINE] = "define", [SESSION_DRAG] = "drag", [SESSION_CAMERA] = "camera",
    [SESSION_PAUSE] = "pause", [SESSION_PACK] = "pack",
    [SESSION_SETTING] = "setting", [SESSION_END] = "end",
};
enum { NKINDS = sizeof kind_names / sizeof kind_names[0] };

const char *session_kind_name(session_kind k) {
    return (int)k >= 0 && (int)k < NKINDS ? kind_names[k] : "?";
}

static bool is_value_kind(session_kind k) { return k <= SESSION_DRAG; }

/* ---- parsing ---- */

/* Whitespace-separated finite numbers of s into v (at most max); their
 * count, or -1 for a word that is not one or more than max. */
static int parse_numbers(const char *s, double *v, int max) {
    int n = 0;
    for (;;) {
        while (isspace((unsigned char)*s)) s++;
        if (!*s) return n;
        char *end;
        errno = 0;
        double x = strtod(s, &end);
        if (end == s || (*end && !isspace((unsigned char)*end)) || errno == ERANGE || !isfinite(x) || n >= max)
            return -1;
        v[n++] = x;
        s = end;
    }
}

static bool valid_name(const char *s, size_t max) {
    size_t n = strlen(s);
    if (n == 0 || n >= max) return false;
    for (size_t i = 0; i < n; i++)
        if (!isalnum((unsigned char)s[i]) && !strchr("_.-", s[i])) return false;
    return true;
}

/* The arguments of an event of kind k: what is wrong with them, or NULL. */
static const char *check_args(session_kind k, const char *args) {
    double v[UNIF_MAX_COMPONENTS + 1];
    if (is_value_kind(k)) {
        char program[UNIF_NAME_MAX + 1], name[UNIF_NAME_MAX + 1];
        int used = 0;
        if (sscanf(args, "%64s %64s %n", program, name, &used) < 2 || !valid_name(program, UNIF_NAME_MAX) ||
            !valid_name(name, UNIF_NAME_MAX))
            return "expected PROGRAM NAME and values";
        int n = parse_numbers(args + used, v, UNIF_MAX_COMPONENTS);
        if (n <= 0) return "expected 1 to 16 numbers after PROGRAM NAME";
        return NULL;
    }
    switch (k) {
    case SESSION_CAMERA:
        if (parse_numbers(args, v, 7) != 6 || !(v[3] > 0))
            return "camera wants CX CY CZ DISTANCE YAW PITCH (distance > 0)";
        return NULL;
    case SESSION_PAUSE:
        return strcmp(args, "0") == 0 || strcmp(args, "1") == 0 ? NULL : "pause wants 1 or 0";
    case SESSION_PACK: return valid_name(args, 64) ? NULL : "pack wants a pack's name";
    case SESSION_SETTING: return valid_name(args, 64) ? NULL : "setting wants a setting's name";
    case SESSION_END: return args[0] ? "end takes nothing after it" : NULL;
    default: return "unknown event";
    }
}

static bool find_kind(const char *word, session_kind *k) {
    for (int i = 0; i < NKINDS; i++)
        if (strcmp(word, kind_names[i]) == 0) { *k = (session_kind)i; return true; }
    return false;
}

static double last_t(const session *s) { return s->n ? s->events[s->n - 1].t : 0; }

/* `t=T KIND ARGS` (text starts after "t="). */
static void parse_event(session *s, char *text, int line, diag_list *dl) {
    char *end;
    double t = strtod(text, &end);
    if (end == text || !isspace((unsigned char)*end) || !isfinite(t) || t < 0) {
        diag_add(dl, DIAG_ERROR, s->path, line, "expected t=SECONDS (a number, 0 or more) then the event");
        return;
    }
    if (t < last_t(s)) {
        diag_add(dl, DIAG_ERROR, s->path, line, "t=%g comes before the previous event's t=%g: events go in time order",
                 t, last_t(s));
        return;
    }
    char word[32];
    int used = 0;
    session_kind k;
    if (sscanf(end, " %31s %n", word, &used) < 1 || !find_kind(word, &k)) {
        diag_add(dl, DIAG_ERROR, s->path, line,
                 "unknown event: expected slider, colour, checkbox, define, drag, camera, pause, pack, setting or "
                 "end");
        return;
    }
    const char *args = end + used, *why = check_args(k, args);
    if (why) { diag_add(dl, DIAG_ERROR, s->path, line, "%s: %s", word, why); return; }
    if (s->n == s->cap) {
        s->cap = s->cap ? s->cap * 2 : 64;
        s->events = mem_realloc(s->events, (size_t)s->cap * sizeof *s->events);
    }
    session_event *e = &s->events[s->n++];
    e->t = t;
    e->kind = k;
    e->line = line;
    snprintf(e->args, sizeof e->args, "%s", args);
}

static void parse_scene(session *s, const char *rest, int line, diag_list *dl) {
    if (!rest[0]) { diag_add(dl, DIAG_ERROR, s->path, line, "scene wants the glib's path"); return; }
    char *dir = path_dir(s->path);
    if (rest[0] == '/' || strcmp(dir, ".") == 0) snprintf(s->scene, sizeof s->scene, "%s", rest);
    else snprintf(s->scene, sizeof s->scene, "%s/%s", dir, rest);
    free(dir);
}

/* A header line (its first word is key); false when key is none. */
static bool parse_header(session *s, const char *key, const char *rest, int line, diag_list *dl) {
    double v[3];
    if (strcmp(key, "scene") == 0) parse_scene(s, rest, line, dl);
    else if (strcmp(key, "pack") == 0) {
        if (strcmp(rest, "-") == 0) s->pack[0] = '\0';
        else if (valid_name(rest, sizeof s->pack)) snprintf(s->pack, sizeof s->pack, "%s", rest);
        else diag_add(dl, DIAG_ERROR, s->path, line, "pack wants a pack's name, or - for the scene's own");
    } else if (strcmp(key, "size") == 0) {
        if (parse_numbers(rest, v, 3) == 2 && v[0] >= 1 && v[0] <= 16384 && v[1] >= 1 && v[1] <= 16384 &&
            v[0] == floor(v[0]) && v[1] == floor(v[1])) {
            s->width = (int)v[0];
            s->height = (int)v[1];
        } else diag_add(dl, DIAG_ERROR, s->path, line, "size wants W H, whole pixels 1..16384");
    } else if (strcmp(key, "time") == 0) {
        if (parse_numbers(rest, v, 2) == 1) s->time_s = v[0];
        else diag_add(dl, DIAG_ERROR, s->path, line, "time wants the simulated clock's start in seconds");
    } else return false;
    return true;
}

/* The first line that says something: `tarn-session 1`. */
static bool parse_magic(session *s, const char *text, int line, diag_list *dl) {
    int version = 0;
    char tail = 0;
    if (sscanf(text, "tarn-session %d %c", &version, &tail) != 1) {
        diag_add(dl, DIAG_ERROR, s->path, line, "not a tarn session: the first line should be `tarn-session %d`",
                 SESSION_VERSION);
        return false;
    }
    if (version != SESSION_VERSION) {
        diag_add(dl, DIAG_ERROR, s->path, line, "session version %d: this tarn reads version %d", version,
                 SESSION_VERSION);
        return false;
    }
    return true;
}

/* One line, comment and surrounding blanks gone. False: stop reading. */
static bool parse_line(session *s, char *text, int line, bool *magic, diag_list *dl) {
    char *hash = strchr(text, '#');
    if (hash) *hash = '\0';
    while (isspace((unsigned char)*text)) text++;
    size_t len = strlen(text);
    while (len > 0 && isspace((unsigned char)text[len - 1])) text[--len] = '\0';
    if (!len) return true;
    if (!*magic) return *magic = parse_magic(s, text, line, dl);
    if (strncmp(text, "t=", 2) == 0) { parse_event(s, text + 2, line, dl); return true; }
    char key[32] = "";
    int used = 0;
    sscanf(text, "%31s %n", key, &used);
    if (!parse_header(s, key, text + used, line, dl))
        diag_add(dl, DIAG_ERROR, s->path, line,
                 "unknown line: expected t=SECONDS EVENT ..., or scene, pack, size or time");
    return true;
}

bool session_parse(session *s, const char *text, const char *path, diag_list *dl) {
    snprintf(s->path, sizeof s->path, "%s", path);
    int errors = dl->nerrors, line = 0;
    bool magic = false;
    for (const char *p = text; *p;) {
        const char *nl = strchr(p, '\n');
        size_t len = nl ? (size_t)(nl - p) : strlen(p);
        line++;
        if (len >= SESSION_LINE_MAX) diag_add(dl, DIAG_ERROR, path, line, "line longer than %d characters", SESSION_LINE_MAX - 1);
        else {
            char buf[SESSION_LINE_MAX];
            memcpy(buf, p, len);
            buf[len] = '\0';
            if (memchr(buf, '\0', len)) diag_add(dl, DIAG_ERROR, path, line, "a NUL byte: not a text file");
            else if (!parse_line(s, buf, line, &magic, dl)) break;
        }
        p = nl ? nl + 1 : p + len;
    }
    if (!magic && dl->nerrors == errors)
        diag_add(dl, DIAG_ERROR, path, 0, "empty: a session starts with `tarn-session %d`", SESSION_VERSION);
    else if (magic && !s->scene[0]) diag_add(dl, DIAG_ERROR, path, 0, "no `scene PATH` line: which glib to replay?");
    return dl->nerrors == errors;
}

bool session_load(session *s, const char *path, diag_list *dl) {
    char err[MSG_MAX];
    size_t len;
    char *text = file_read(path, SESSION_MAX_BYTES, &len, err, sizeof err);
    if (!text) {
        snprintf(s->path, sizeof s->path, "%s", path);
        diag_add(dl, DIAG_ERROR, path, 0, "cannot read the session: %s", err);
        return false;
    }
    bool ok = true;
    if (strlen(text) != len) {   /* a NUL inside: the line loop would stop there */
        snprintf(s->path, sizeof s->path, "%s", path);
        diag_add(dl, DIAG_ERROR, path, 0, "a NUL byte: not a text file");
        ok = false;
    } else ok = session_parse(s, text, path, dl);
    free(text);
    return ok;
}

void session_free(session *s) {
    free(s->events);
    s->events = NULL;
    s->n = s->cap = 0;
}

double session_duration(const session *s) {
    for (int i = s->n - 1; i >= 0; i--)
        if (s->events[i].kind == SESSION_END) return s->events[i].t;
    return last_t(s);
}

/* ---- replay ---- */

void session_player_start(session_player *p, const session *s, render_view home) {
    memset(p, 0, sizeof *p);
    p->s = s;
    p->sim = s->time_s;
    p->cam = orbit_from_view(home);
}

/* The script actions a replay adds: `pack NAME` reloads with that pack
 * (the sliders' values carry over as in any reload); `setting NAME`
 * applies the pack's setting as the panel does. */
static view_script_status pack_action(void *user, const char *cmd, char *rest, const char *file, int line) {
    render *r = user;
    if (strcmp(cmd, "setting") == 0) {
        char msg[MSG_MAX] = "";
        bool ok = render_setting_apply_named(r, NULL, rest, msg, sizeof msg);
        if (msg[0]) fprintf(stderr, "%s:%d: %s", file, line, msg);
        return ok ? VIEW_SCRIPT_CONTINUE : VIEW_SCRIPT_FAILED;
    }
    if (strcmp(cmd, "pack") != 0) {
        fprintf(stderr, "%s:%d: unknown event '%s'\n", file, line, cmd);
        return VIEW_SCRIPT_FAILED;
    }
    render_set_pack(r, rest);
    if (!render_load(r, NULL)) fprintf(stderr, "%s:%d: pack %s: %s", file, line, rest, render_messages(r));
    return VIEW_SCRIPT_CONTINUE;
}

static void apply(session_player *p, render *r, const session_event *e) {
    const char *verb = is_value_kind(e->kind) ? "set" : e->kind == SESSION_END ? NULL : kind_names[e->kind];
    if (!verb) return;
    char text[SESSION_LINE_MAX + 16];
    snprintf(text, sizeof text, "%s %s", verb, e->args);
    view_script_ctx c = { .r = r, .time_s = &p->sim, .cam = &p->cam, .paused = &p->paused,
                          .custom = pack_action, .user = r };
    view_script_status st = view_script_action(&c, text, p->s->path, e->line);
    if (st == VIEW_SCRIPT_REBUILD) render_rebuild_programs(r);
    if (st == VIEW_SCRIPT_FAILED) p->failed++;
}

/* The clock runs from the session time reached to t unless paused. */
static void run_clock(session_player *p, double t) {
    if (t <= p->t) return;
    if (!p->paused) p->sim += t - p->t;
    p->t = t;
}

double session_player_advance(session_player *p, render *r, double t) {
    const session *s = p->s;
    while (p->next < s->n && s->events[p->next].t <= t) {
        const session_event *e = &s->events[p->next++];
        run_clock(p, e->t);
        apply(p, r, e);
    }
    run_clock(p, t);
    return p->sim;
}

/* ---- recording ---- */

typedef struct rec_value {
    char program[UNIF_NAME_MAX], name[UNIF_NAME_MAX];
    int ncomp;
    float v[UNIF_MAX_COMPONENTS];
} rec_value;

struct session_rec {
    FILE *f;
    char path[1024];
    double t0;
    rec_value *vals;             /* what the file says each entry holds now */
    int n, cap;
    orbit cam;
    bool paused;
    int nevents;
};

static session_kind entry_kind(const unif_entry *e) {
    if (e->is_define) return SESSION_DEFINE;
    switch (e->widget) {
    case UNIF_WIDGET_CHECKBOX: return SESSION_CHECKBOX;
    case UNIF_WIDGET_COLOR: return SESSION_COLOUR;
    case UNIF_WIDGET_DRAG: return SESSION_DRAG;
    default: return SESSION_SLIDER;
    }
}

/* Entries the panel can change: widgets and Defines (fixed values are the scene's). */
static bool recorded(const unif_entry *e) { return e->is_define || e->widget != UNIF_WIDGET_NONE; }

static rec_value *find_value(session_rec *rec, const char *program, const unif_entry *e) {
    for (int i = 0; i < rec->n; i++)
        if (strcmp(rec->vals[i].name, e->name) == 0 && strcmp(rec->vals[i].program, program) == 0 &&
            rec->vals[i].ncomp == e->ncomp)
            return &rec->vals[i];
    return NULL;
}

static rec_value *add_value(session_rec *rec, const char *program, const unif_entry *e, const float *v) {
    if (rec->n == rec->cap) {
        rec->cap = rec->cap ? rec->cap * 2 : 32;
        rec->vals = mem_realloc(rec->vals, (size_t)rec->cap * sizeof *rec->vals);
    }
    rec_value *r = &rec->vals[rec->n++];
    memset(r, 0, sizeof *r);
    snprintf(r->program, sizeof r->program, "%s", program);
    snprintf(r->name, sizeof r->name, "%s", e->name);
    r->ncomp = e->ncomp;
    memcpy(r->v, v, (size_t)e->ncomp * sizeof *v);
    return r;
}

static void write_t(session_rec *rec, double now) {
    double t = now - rec->t0;
    fprintf(rec->f, "t=%.3f ", t > 0 ? t : 0);
    rec->nevents++;
}

static void write_value(session_rec *rec, const char *program, const unif_entry *e, double now) {
    write_t(rec, now);
    fprintf(rec->f, "%s %s %s", kind_names[entry_kind(e)], program, e->name);
    for (int i = 0; i < e->ncomp; i++) fprintf(rec->f, " %.9g", (double)e->value[i]);   /* round-trips a float */
    fputc('\n', rec->f);
}

static void write_camera(session_rec *rec, const orbit *c, double now) {
    write_t(rec, now);
    fprintf(rec->f, "camera %.9g %.9g %.9g %.9g %.9g %.9g\n", (double)c->center[0], (double)c->center[1],
            (double)c->center[2], (double)c->distance, (double)c->yaw, (double)c->pitch);
}

/* Which values changed; returns how many events were written. */
static int diff_values(session_rec *rec, const unif_set *sets, int nsets, double now) {
    int written = 0;
    for (int s = 0; s < nsets; s++)
        for (int i = 0; i < sets[s].n; i++) {
            const unif_entry *e = &sets[s].entries[i];
            if (!recorded(e)) continue;
            rec_value *v = find_value(rec, sets[s].program, e);
            if (!v) { add_value(rec, sets[s].program, e, e->value); continue; }
            if (memcmp(v->v, e->value, (size_t)e->ncomp * sizeof *v->v) == 0) continue;
            memcpy(v->v, e->value, (size_t)e->ncomp * sizeof *v->v);
            write_value(rec, sets[s].program, e, now);
            written++;
        }
    return written;
}

void session_rec_frame(session_rec *rec, const unif_set *sets, int nsets, const orbit *cam, bool paused, double now) {
    int written = diff_values(rec, sets, nsets, now);
    if (!orbit_equal(cam, &rec->cam)) {
        rec->cam = *cam;
        write_camera(rec, cam, now);
        written++;
    }
    if (paused != rec->paused) {
        rec->paused = paused;
        write_t(rec, now);
        fprintf(rec->f, "pause %d\n", paused ? 1 : 0);
        written++;
    }
    if (written) fflush(rec->f);   /* a crash keeps what was done */
}

void session_rec_pack(session_rec *rec, const char *pack, double now) {
    write_t(rec, now);
    fprintf(rec->f, "pack %s\n", pack);
    fflush(rec->f);
}

void session_rec_setting(session_rec *rec, const char *setting, double now) {
    write_t(rec, now);
    fprintf(rec->f, "setting %s\n", setting);
    fflush(rec->f);
}

static void write_header(session_rec *rec, const session_header *h) {
    char abs[PATH_MAX];
    const char *scene = realpath(h->scene, abs) ? abs : h->scene;
    fprintf(rec->f,
            "# tarn session: what was done in `tarn view`; `tarn record FILE -o out.mp4` replays it\n"
            "tarn-session %d\nscene %s\npack %s\nsize %d %d\ntime %.9g\n",
            SESSION_VERSION, scene, h->pack && h->pack[0] ? h->pack : "-", h->width, h->height, h->time_s);
}

session_rec *session_rec_start(const char *path, const session_header *h, const unif_set *sets, int nsets,
                               const orbit *cam, bool paused, double now, char *err, int errlen) {
    FILE *f = fopen(path, "w");
    if (!f) { snprintf(err, (size_t)errlen, "%s: %s", path, strerror(errno)); return NULL; }
    session_rec *rec = mem_zalloc(sizeof *rec);
    rec->f = f;
    rec->t0 = now;
    snprintf(rec->path, sizeof rec->path, "%s", path);
    write_header(rec, h);
    /* the replay starts from the scene's defaults and its LookAt: what
     * differs from them now is the first events' */
    for (int s = 0; s < nsets; s++)
        for (int i = 0; i < sets[s].n; i++)
            if (recorded(&sets[s].entries[i])) add_value(rec, sets[s].program, &sets[s].entries[i], sets[s].entries[i].def);
    rec->cam.distance = -1;      /* no orbit has this: the camera is written */
    session_rec_frame(rec, sets, nsets, cam, paused, now);
    return rec;
}

const char *session_rec_path(const session_rec *rec) { return rec->path; }

double session_rec_seconds(const session_rec *rec, double now) { return now - rec->t0; }

bool session_rec_stop(session_rec *rec, double now, int *nevents, char *err, int errlen) {
    write_t(rec, now);
    fputs("end\n", rec->f);
    bool ok = !ferror(rec->f);
    if (fclose(rec->f) != 0) ok = false;
    if (!ok) snprintf(err, (size_t)errlen, "%s: writing failed (disk full?)", rec->path);
    if (nevents) *nevents = rec->nevents - 1;   /* not `end` */
    free(rec->vals);
    free(rec);
    return ok;
}
