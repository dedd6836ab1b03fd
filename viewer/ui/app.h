/* app: the one window app loop behind `tarn view` and `tarn compare-view`.
 *
 * The app owns the window (gl_ctx + GLFW), the slider panel's frame, the
 * file watcher, the orbit camera and its mouse, the simulated clock, the
 * screenshot key, the --script stepping and the lost-context check. A
 * client (view.c, compare_view.c) owns its scenes and says what differs
 * through the hooks of app_desc. Use:
 *
 *     app *a = app_create(&desc);        the window, its callbacks, the panel
 *     ... create and load the scenes (they need the context) ...
 *     app_fit_window(a, w, h);           optional: a scene area of w x h
 *     app_home(a, render_default_view(r));
 *     int rc = app_run(a, scenes, n);    until closed, the script quits or
 *                                        the context is lost
 *     ... free the scenes ...
 *     app_destroy(a);
 *
 * Each frame: poll events; advance the clock (not while paused or
 * scripted); on a watched file's change, compile the scenes off the frame
 * (compile_job.h: the last good programs keep drawing, the panel says
 * "compiling water.frag ...") and reload when that ends (hooks.reload,
 * then rewatch; R and the script's reload reload at once); the mouse (hooks.mouse, or the orbit camera's); hooks.draw;
 * the panel frame around hooks.panel; the panel's common actions, then
 * hooks.apply; the lost-context check (exit TARN_EXIT_NO_GL with the
 * message); one script step; swap.
 *
 * Watching: the union of the scenes' render_deps. A dependency in a
 * directory that does not exist (a typo, a folder not made yet) cannot be
 * watched; the rest are watched rather than nothing, and every
 * APP_RETRY_S the app looks whether such a directory has appeared, and if
 * so reloads (which watches it from then on).
 *
 * Keys the app handles (unless the panel has the keyboard): Esc/Q quit,
 * R reload, Shift+R start/stop recording a session (a recordable client),
 * Space pause, P/F12 screenshot, F/Home reset the camera; others go to
 * hooks.key.
 *
 * Recording (session.h): what the user does to scenes[0] (panel values,
 * camera, pause) goes to a session file, a line an event, checked once a
 * frame; "REC" and the file show over the scene meanwhile. desc.record
 * records from the start; Shift+R stops, and starts a new file,
 * tarn-DATE-N.session in the current directory. Closing the window ends
 * the file properly.
 *
 * Screenshots (P/F12, the panel's button, the script's `screenshot`) are
 * opaque: the window's alpha is what the panel's blending left, meaningless
 * in an image viewer. P/F12 write tarn-DATE-N.png in the current directory;
 * the absolute path is shown on screen (app_toast) and on stderr. */
#ifndef TARN_APP_H
#define TARN_APP_H

#include <stdbool.h>
#include <stdint.h>

#include "gl_ctx.h"
#include "panel.h"
#include "render.h"
#include "view_script.h"
#include "view_util.h"

#define APP_PANEL_WIDTH 440   /* the slider panel's column, left of the scene */
#define APP_RETRY_S 0.25      /* how often a missing directory is looked for again */
#define APP_TOAST_S 4.0       /* how long an app_toast message stays on screen */
#define APP_REC_LABEL_S 1.0   /* a still window redraws the REC label's seconds this often */

typedef struct app app;

/* What clients read and change between frames. */
typedef struct app_state {
    orbit cam, cam_home;         /* the camera, and where F/Home puts it back */
    view_mouse mouse;            /* a client's own mouse hook drives it too */
    double t;                    /* simulated time, seconds */
    double frame_ms, fps;        /* wall time per frame over the last second (frame_meter) */
    bool cpu_raster;             /* llvmpipe & co: GPU timestamps do not time the drawing */
    bool paused;
} app_state;

/* Zero means default in every field; user is passed to every hook. */
typedef struct app_desc {
    const char *name;            /* message prefix and title: 0: "tarn" */
    const char *scene_path;      /* the title's "name — scene_path"; 0: the name alone */
    int width, height;           /* the window at creation (0: 1000 x 700) */
    double time_s;               /* the clock's start */
    const char *script;          /* a view_script file (0: interactive) */
    bool recordable;             /* Shift+R records scenes[0] (one scene: view, not compare-view) */
    const char *record;          /* recordable: record into this session file from the start */
    const char *pack;            /* the --pack drawn, for a session's header (0: the scene's own) */
    bool verbose;                /* say on stderr when the compile job has the scenes loaded */
    void *user;
    /* Draws the scene(s) into the default framebuffer. Required. */
    void (*draw)(void *user, app *a);
    /* The panel's widgets (inside the panel frame); the buttons the app
     * acts on go in *common, the client keeps its own. Required. */
    void (*panel)(void *user, app *a, panel_actions *common);
    /* After the panel is drawn: the client's own panel actions. */
    void (*apply)(void *user, app *a);
    /* Loads every scene again from disk and reports; the app rewatches
     * after. Required. */
    void (*reload)(void *user, app *a);
    /* This frame's mouse (0: the orbit camera's, outside the panel). */
    void (*mouse)(void *user, app *a);
    /* A key press the app does not handle (GLFW_KEY_*). */
    void (*key)(void *user, app *a, int key);
    /* Script actions of the client's own (view_script_ctx.custom). */
    view_script_status (*script_action)(void *user, const char *cmd, char *rest, const char *file, int line);
    /* Work the client does after a frame is on screen, a step a frame,
     * until it returns false (compare-view loads its other packs while the
     * first one's picture shows): meanwhile frames keep coming and a
     * script waits. 0: none. */
    bool (*between_frames)(void *user, app *a);
} app_desc;

/* The window, its key and scroll callbacks and the panel; NULL, with the
 * message on stderr, when there is no window (exit TARN_EXIT_NO_GL). */
app *app_create(const app_desc *d);
void app_destroy(app *a);        /* NULL is fine */

/* The cache the app's watcher feeds (file_cache.h): make the scenes'
 * renders with it (render_desc.files), so a save is read once and a
 * Define toggle, a pack switch or the compile job reads no disk. It lives
 * until app_destroy: destroy the renders first. */
struct file_cache;
struct file_cache *app_files(app *a);

/* Runs the loop over scenes[0..n-1] (watched; script set/expect/rebuild
 * act on scenes[0] until app_script_use). Returns a tarn_exit_code:
 * TARN_EXIT_USAGE for an unreadable script, TARN_EXIT_INPUT when it
 * fails, TARN_EXIT_NO_GL when the context was lost. */
int app_run(app *a, render *const *scenes, int n);

/* The window's size for a scene area of w x h with the panel beside it. */
void app_fit_window(app *a, int w, int h);
/* The camera and F/Home's camera. */
void app_home(app *a, render_view v);
/* The scene that script set/expect/rebuild act on from now (compare-view's `pack N`). */
void app_script_use(app *a, int i);
/* Watches the scenes' files again (after a rebuild that may read others). */
void app_rewatch(app *a);
/* Writes the window's image, opaque, to the next tarn-DATE-N.png in the
 * current directory and shows where (app_toast). */
void app_screenshot(app *a);
/* A line shown over the scene for APP_TOAST_S seconds (the latest wins):
 * what the user did landed somewhere, e.g. a saved preset's path. */
void app_toast(app *a, const char *fmt, ...);
/* The client switched the pack drawing the scene: a recording notes it. */
void app_record_pack(app *a, const char *pack);
/* The client applied the pack's setting NAME (the panel's Setting combo). */
void app_record_setting(app *a, const char *setting);

/* ---- the frame budget (res_budget.h) ----
 * A client draws its scene(s) into a target of its own and shows it
 * upscaled: each frame it asks app_budget_plan with the picture's key
 * whether to draw and at what scale (a screenshot's frame is always full
 * size), draws at res_budget_size(scale, ...) if so, and tells
 * app_budget_drawn the size it has on screen. */

/* The picture a w x h scene area shows: the camera, the time, every
 * scene's uniform values, the reloads (and app_picture_changed's). */
uint64_t app_picture_key(app *a, int w, int h);
/* The same without the time nor the reloads: what stays while only the
 * clock runs; the caller adds what of a reload its use depends on (the
 * view keeps its full-resolution world while this and the world frame's
 * inputs hold, render_world_frame_inputs). */
uint64_t app_picture_key_timeless(app *a, int w, int h);
/* This frame: true to draw the scene at *scale (1: full resolution);
 * false: the frame drawn last is still the picture. force_full: the
 * client needs full-resolution pixels (heat maps). */
bool app_budget_plan(app *a, uint64_t key, bool force_full, double *scale);
/* What the client has on screen: iw x ih drawn for a w x h area. */
void app_budget_drawn(app *a, int iw, int ih, int w, int h);
/* A rebuild or pack switch of the client's: the picture is new. */
void app_picture_changed(app *a);
/* The client shows a running clock's world at full resolution, not from
 * its reduced frames (the view's sharp world; off by default): those may
 * then read a larger frame's World layers, each pixel the nearest texel,
 * whenever the budget's size moves (render_keep_world_layers). */
void app_sharp_world(app *a, bool on);

/* A still window sleeps (waits for input, a window event, a watched
 * file's news or a compile job's ready, each of which wakes it at once:
 * fd_wake.h, compile_job_desc.wake; at most APP_IDLE_WAIT_S at a time)
 * instead of drawing the same frame; a client with work in flight
 * (compare-view's heat maps) calls this in its draw to have the next
 * frame drawn. */
#define APP_IDLE_WAIT_S 0.25   /* 0.05 before fd_wake: each wake cost ~2 ms, 4.6% of a core */
/* the frames a client asks for (app_keep_awake) come at most this often */
#define APP_CLIENT_POLL_S 0.05
/* how often a still window looks whether a compile job has ended, had its
 * wake not come */
#define APP_COMPILE_POLL_S 0.02
/* the frame stays drawn smaller (res_budget_contend) this long after the
 * reload at a save's job's ready: the first frame at the calm size right
 * after it took 55-70 ms (natural, lake, 50 ms budget; every pass slower,
 * the process still busy with the new build), 40-41 ms once 0.15 s later */
#define APP_CONTEND_TAIL_S 0.15
/* After a save the water is drawn as a grid until the job has made its
 * deferred code (reload_compiled): at the window's reduced sizes a grid
 * frame takes about this many times the deferred one (`tarn render
 * --frames 6 --msaa 1 --size 336x189 --detail 0.35`, --grid-water against
 * deferred, medians of 3: 1.14-1.46x over the four packs on the lake and
 * the showcase), so the frame shrinks by as much at the reload
 * (res_budget_costlier): its first grid frames were 55-72 ms at the 50 ms
 * budget (raymarch, clock running, the job compiling beside it) */
#define APP_GRID_WATER_COST 1.35
/* the script's `stamp on` times the first frame after each reload, then
 * the longest frame gap in this long after it (benchmarks) */
#define APP_STAMP_AFTER_S 1.0
void app_keep_awake(app *a);

/* A message alone on a dark window, shown at once (before a scene's first
 * frame: "loading ... compiling N programs" instead of a black window). */
void app_splash(app *a, const char *text);
/* The panel's "Frame budget ms" (0: off), read and written by its slider. */
float *app_budget_ms(app *a);
/* "480x270 (50%) of 960x540, budget 50 ms" for the panel. */
void app_budget_text(const app *a, char *out, int len);

/* Inside hooks.reload: why it runs, "water.frag changed" (the files the
 * watcher saw change), "a missing folder appeared", or "" (R, the panel's
 * button, a script). */
const char *app_reload_cause(const app *a);
/* During hooks.reload: how long the compile job ran that compiled what
 * it loads, off the frame (seconds); -1 when it compiles on the frame. */
double app_reload_compiled_s(const app *a);

app_state *app_get_state(app *a);
void *app_window(app *a);        /* the GLFWwindow* */
gl_ctx *app_gl(app *a);
panel *app_panel(app *a);

/* The scene area's left edge in a framebuffer w pixels wide: right of the
 * panel when the window has room for both, else 0. */
int app_scene_x(int fb_w);
/* The same edge in window pixels (ImGui's; differs on a HiDPI screen). */
float app_scene_x_window(app *a);

#endif
