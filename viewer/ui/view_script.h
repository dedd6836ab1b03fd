/* view_script: scripted actions for the interactive window, so tests and
 * demos can drive `tarn view --script FILE` under Xvfb. One action a line:
 *   frames N                      draw N frames, then the next line (until 2026-12-07
 *                                 N + 1 frames passed)
 *   wait SECONDS                  draw frames for this long (wall time: a test
 *                                 changes files meanwhile); while the window's
 *                                 compile job runs over a still picture, the window
 *                                 sleeps instead, as without a script, after the
 *                                 frame that shows what the lines before it changed
 *   time T                        set the simulated time (seconds)
 *   advance DT N                  draw N frames, each DT seconds of simulated time after
 *                                 the one before, then the next line (on the last of
 *                                 them: a `grab` after it takes that frame); a clock
 *                                 running at 1/DT frames a second, every frame a new
 *                                 picture (scripts/live_error.sh)
 *   set PROGRAM UNIFORM v...      what moving that slider does
 *   expect PROGRAM UNIFORM v...   the linked GL program holds these values (±1e-5)
 *   screenshot PATH               write the window's image
 *   reload                        reload the scene, as a save would
 *   camera CX CY CZ DIST YAW PITCH  the orbit camera (centre, distance, radians),
 *                                 as a drag leaves it
 *   pause 0|1                     stop or run the simulated clock
 *   window W H                    resize the window (app.c's; give it a few frames)
 *   quit
 * The window loop (app.c) adds, for both windows:
 *   orbit DYAW DPITCH [N]         turn the camera now and on each of the next N-1 frames
 *   budget MS                     the frame budget (0: off)
 *   resolution                    print the internal resolution drawn
 *   expect-resolution full|reduced
 *   clock                         print frames drawn and the wall clock (benchmarks)
 *   stamp on|off                  print when the first frame after a reload is swapped
 *   play 1|0                      the clock runs on the wall clock, as without a script
 *                                 (unless paused); 0: only `time` moves it (the default)
 *   grab PATH                     write the scene area as this frame showed it (reduced
 *                                 or not: not drawn again, unlike screenshot), and print
 *                                 its time and the size drawn (scripts/live_error.sh)
 * `#` starts a comment. A window may add actions of its own (ctx.custom):
 * `tarn compare-view` does (compare_view.h), and `tarn view` has
 *   pack NAME                     draw the scene with another pack (the panel's Pack combo)
 *   setting NAME                  the pack's defaults, then its bench.txt setting NAME
 *                                 (the panel's Setting combo; render_setting.h)
 *   world-cache 1|0               keep the world's unchanging parts between frames (the
 *                                 default) or draw it whole every frame (A/B benchmarks)
 *   sharp-world 1|0               while only the clock runs, the reduced frame's water
 *                                 over the world kept at full resolution (the default),
 *                                 or the whole frame enlarged (A/B: scripts/live_error.sh) */
#ifndef TARN_VIEW_SCRIPT_H
#define TARN_VIEW_SCRIPT_H

#include <stdbool.h>

#include "render.h"
#include "view_util.h"

typedef struct view_script view_script;

typedef enum view_script_status {
    VIEW_SCRIPT_CONTINUE = 0,
    VIEW_SCRIPT_SCREENSHOT,     /* the caller writes view_script_arg() */
    VIEW_SCRIPT_RELOAD,
    VIEW_SCRIPT_REBUILD,        /* a Define toggle was set: rebuild programs */
    VIEW_SCRIPT_DONE,
    VIEW_SCRIPT_FAILED          /* an `expect` did not hold, or a bad line */
} view_script_status;

typedef struct view_script_ctx {
    render *r;
    double *time_s;
    orbit *cam;                 /* `camera` moves it (NULL: the action fails) */
    bool *paused;               /* `pause` sets it (NULL: the action fails) */
    /* An action this module does not know goes here (NULL: unknown actions
     * fail). cmd is its first word, rest the words after it; return what
     * the caller must do, VIEW_SCRIPT_FAILED with a message on stderr. */
    view_script_status (*custom)(void *user, const char *cmd, char *rest, const char *file, int line);
    void *user;
} view_script_ctx;

#define VIEW_SCRIPT_MAX_LINES 65536   /* 32 MiB of lines: a script is a few dozen */

/* The script at path, or NULL with the reason in err (not there, or more
 * than VIEW_SCRIPT_MAX_LINES lines). */
view_script *view_script_load(const char *path, char *err, int errlen);
/* Runs actions up to the next frame boundary; returns what the caller must do. */
view_script_status view_script_step(view_script *s, view_script_ctx *ctx);
const char *view_script_arg(const view_script *s);
/* Is a `wait SECONDS` running (frames or nothing, the caller's choice)?
 * Not on the frame after a step that ran an action before the wait (`set`
 * then `wait`): that frame shows the change, and a recording (session.h)
 * notes it when it was made, not when the wait ends (until 2026-12-07 a
 * sleeping window drew it, and the recorder saw it, only then). */
bool view_script_waiting(const view_script *s);
/* Seconds until that wait ends (0: none runs): a caller asleep meanwhile
 * wakes for it. */
double view_script_wait_left_s(const view_script *s);
/* One action that needs no frame boundary (set, expect, time, camera,
 * pause, or ctx->custom's), text as a script line; file and line name it
 * in messages. The one path scripts and session replays (session.h) change
 * a running scene by. frames/wait/screenshot/reload/quit are the script's
 * own and fail here. text is changed. */
view_script_status view_script_action(view_script_ctx *ctx, char *text, const char *file, int line);
void view_script_free(view_script *s);

#endif
