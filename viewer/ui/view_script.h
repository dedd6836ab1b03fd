/* view_script: scripted actions for the interactive window, so tests and
 * demos can drive `tarn view --script FILE` under Xvfb. One action a line:
 *   frames N                      draw N frames
 *   wait SECONDS                  draw frames for this long (wall time: a test
 *                                 changes files meanwhile)
 *   time T                        set the simulated time (seconds)
 *   set PROGRAM UNIFORM v...      what moving that slider does
 *   expect PROGRAM UNIFORM v...   the linked GL program holds these values (±1e-5)
 *   screenshot PATH               write the window's image
 *   reload                        reload the scene, as a save would
 *   window W H                    resize the window (app.c's; give it a few frames)
 *   quit
 * `#` starts a comment. A window may add actions of its own (ctx.custom):
 * `tarn compare-view` does (compare_view.h), and `tarn view` has
 *   pack NAME                     draw the scene with another pack (the panel's Pack combo) */
#ifndef TARN_VIEW_SCRIPT_H
#define TARN_VIEW_SCRIPT_H

#include "render.h"

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
    /* An action this module does not know goes here (NULL: unknown actions
     * fail). cmd is its first word, rest the words after it; return what
     * the caller must do, VIEW_SCRIPT_FAILED with a message on stderr. */
    view_script_status (*custom)(void *user, const char *cmd, char *rest, const char *file, int line);
    void *user;
} view_script_ctx;

view_script *view_script_load(const char *path, char *err, int errlen);
/* Runs actions up to the next frame boundary; returns what the caller must do. */
view_script_status view_script_step(view_script *s, view_script_ctx *ctx);
const char *view_script_arg(const view_script *s);
void view_script_free(view_script *s);

#endif
