/* session: what the user did in `tarn view`, kept as a small text file
 * (recorded by the window, app.c) and replayed frame by frame (`tarn
 * record`, cmd_record.c). One line a thing:
 *
 *   # comment
 *   tarn-session 1                the format and its version (first line)
 *   scene PATH                    the glib; relative to the session file's folder
 *   pack NAME                     the pack drawn ("-": the scene's own Pack)
 *   size W H                      the scene area in pixels when recording began
 *   time SECONDS                  the simulated clock when recording began
 *   t=T KIND ARGS                 an event T seconds after recording began
 *
 * Events, T never decreasing:
 *   slider|colour|checkbox|define|drag PROGRAM NAME V...
 *                                 the panel set that entry to these values
 *   camera CX CY CZ DIST YAW PITCH  the orbit camera after a move
 *   pause 1|0                     the clock stopped / runs again
 *   pack NAME                     the window switched to pack NAME
 *   setting NAME                  the window chose the pack's setting NAME
 *                                 (its bench.txt row, from the pack's defaults)
 *   end                           recording stopped (the replay's length)
 *
 * Times are wall time: the simulated clock of a replay is `time` plus the
 * seconds that were not paused, so it follows the window's. A replay
 * applies every event through view_script_action, the path `--script`
 * uses. */
#ifndef TARN_SESSION_H
#define TARN_SESSION_H

#include <stdbool.h>

#include "diag.h"
#include "render.h"
#include "unif.h"
#include "view_util.h"

#define SESSION_VERSION 1
#define SESSION_LINE_MAX 1024          /* longer lines are errors */
#define SESSION_MAX_BYTES (64L << 20)  /* a bigger file is not a session */

typedef enum session_kind {
    SESSION_SLIDER, SESSION_COLOUR, SESSION_CHECKBOX, SESSION_DEFINE, SESSION_DRAG,
    SESSION_CAMERA, SESSION_PAUSE, SESSION_PACK, SESSION_SETTING, SESSION_END
} session_kind;

typedef struct session_event {
    double t;                    /* seconds after recording began */
    session_kind kind;
    int line;                    /* in the file, for messages */
    char args[SESSION_LINE_MAX]; /* the words after the kind, as written */
} session_event;

typedef struct session {
    char path[1024];             /* the file, for messages */
    char scene[4096];            /* resolved against the file's folder */
    char pack[64];               /* "" for the scene's own */
    int width, height;           /* 0 when the header has no size */
    double time_s;
    session_event *events;
    int n, cap;
} session;

/* Reads text (a session file's contents; path names it in messages) into
 * s (zeroed by the caller). A bad line becomes a file:line diag in dl and
 * is skipped; the rest is kept. Returns false when dl got errors: a file
 * without the first line or a scene is not replayable, bad events are
 * left out. */
bool session_parse(session *s, const char *text, const char *path, diag_list *dl);
/* session_parse of the file at path (a diag when it cannot be read). */
bool session_load(session *s, const char *path, diag_list *dl);
void session_free(session *s);
/* The time of `end`, else of the last event (0 for none). */
double session_duration(const session *s);
const char *session_kind_name(session_kind k);

/* ---- replay ---- */

typedef struct session_player {
    const session *s;
    int next;                    /* the first event not applied */
    double t, sim;               /* the session time reached and the clock there */
    bool paused;
    orbit cam;
    int failed;                  /* events the scene could not take (messages on stderr) */
} session_player;

/* Starts at session time 0 with the camera at home (the glib's LookAt, as
 * the window's F key) and the clock at the header's time. */
void session_player_start(session_player *p, const session *s, render_view home);
/* Applies the events up to session time t (>= the last call's) to r, the
 * camera and the clock, in order; a Define rebuilds r's programs, a pack
 * reloads r with it, a setting is applied as the panel applies it. Returns the simulated time at t. An event the scene
 * cannot take (no such uniform now) is reported and skipped. */
double session_player_advance(session_player *p, render *r, double t);

/* ---- recording ---- */

typedef struct session_rec session_rec;

typedef struct session_header {
    const char *scene;           /* written as an absolute path when it exists */
    const char *pack;            /* NULL or "": the scene's own */
    int width, height;
    double time_s;
} session_header;

/* Creates path with the header and the state at `now` (seconds, any
 * monotonic clock): every entry not at its default, the camera, a pause.
 * NULL with the reason in err when the file cannot be written. */
session_rec *session_rec_start(const char *path, const session_header *h, const unif_set *sets, int nsets,
                               const orbit *cam, bool paused, double now, char *err, int errlen);
/* An event for each panel entry, the camera and the pause that changed
 * since the last call (entries new after a reload are taken as they are). */
void session_rec_frame(session_rec *rec, const unif_set *sets, int nsets, const orbit *cam, bool paused, double now);
void session_rec_pack(session_rec *rec, const char *pack, double now);
/* The panel's Setting combo chose the pack's setting NAME (render_setting.h). */
void session_rec_setting(session_rec *rec, const char *setting, double now);
const char *session_rec_path(const session_rec *rec);
double session_rec_seconds(const session_rec *rec, double now);
/* Writes `end`, closes and frees rec. The events written go to *nevents
 * (may be NULL). False with the reason when the file could not be written. */
bool session_rec_stop(session_rec *rec, double now, int *nevents, char *err, int errlen);

#endif
