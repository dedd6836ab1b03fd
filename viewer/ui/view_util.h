/* view_util: what the interactive windows share (`tarn view`, `tarn
 * compare-view`): the orbit camera, the mouse that drives it, and window
 * screenshots. */
#ifndef TARN_VIEW_UTIL_H
#define TARN_VIEW_UTIL_H

#include <stdbool.h>
#include <stddef.h>

#include "render.h"

typedef struct orbit {
    float center[3], up[3];
    float distance, yaw, pitch;      /* radians */
} orbit;

/* "loading lake.glib: compiling 7 programs ..." (then `extra`), for the
 * window at once: the first frame waits for every program to compile (1-6 s
 * on a CPU rasteriser), and a black window says nothing (issue #30). pack
 * replaces the scene's Pack (NULL: its own). */
void view_loading_text(const char *glib, const char *pack, const char *extra, char *out, size_t n);

orbit orbit_from_view(render_view v);
render_view orbit_view(const orbit *o);
/* Moves the centre in the view plane by a mouse delta in pixels. */
void orbit_pan(orbit *o, float dx, float dy);
/* A left drag of (dx, dy) pixels: yaw and pitch (clamped short of the poles). */
void orbit_rotate(orbit *o, float dx, float dy);
/* Wheel clicks: each 10% closer (positive) or further. */
void orbit_zoom(orbit *o, double clicks);
bool orbit_equal(const orbit *a, const orbit *b);

/* The mouse over a window: drags that started outside the panel move the
 * camera. GLFWwindow* as void* keeps GLFW out of this header. */
typedef struct view_mouse {
    double last_x, last_y;
    bool dragging_orbit, dragging_pan;
    double scroll;                   /* wheel clicks not applied yet */
    /* buttons pressed since the last frame (VIEW_MOUSE_LEFT | _PAN), and
     * where the first of them was, from the button callback: at 1 fps the
     * cursor is far from the press by the next frame */
    int pressed;
    double press_x, press_y;
    /* the panel's right edge, window pixels (0: no panel): a press left of
     * it is the panel's whatever ImGui said last frame; at 2 fps ImGui has
     * not yet seen the cursor arrive over the panel (issue #30: a press on
     * a slider dragged the slider and orbited the camera too) */
    double ui_right;
} view_mouse;

#define VIEW_MOUSE_LEFT 1
#define VIEW_MOUSE_PAN 2              /* the right or middle button */

/* One frame's mouse, window pixels (top-left origin). */
typedef struct view_mouse_input {
    double x, y;                     /* the cursor now */
    bool left, pan;                  /* held now */
    int pressed;                     /* pressed since the last frame (VIEW_MOUSE_*) */
    double press_x, press_y;         /* where */
} view_mouse_input;

/* From the button callback: a press of VIEW_MOUSE_LEFT or _PAN at (x, y). */
void view_mouse_press(view_mouse *m, int button, double x, double y);
/* This frame's input: the cursor and buttons now, and the presses
 * recorded since the last call (which it clears). */
void view_mouse_read(view_mouse *m, void *glfw_window, view_mouse_input *in);
/* Applies one frame's input to the camera: a drag runs from where its
 * press was (not from where the cursor was at the next frame); the wheel.
 * ui_wants is true while the panel has the mouse (a drag started over it
 * is the panel's). */
void view_mouse_step(view_mouse *m, const view_mouse_input *in, bool ui_wants, orbit *cam);
/* view_mouse_read, then view_mouse_step. */
void view_mouse_update(view_mouse *m, void *glfw_window, bool ui_wants, orbit *cam);

/* Writes the window's back buffer to path (any img_write format), opaque:
 * alpha is set to 1, since what the panel's blending leaves there washes the
 * image out in a viewer. said gets "screenshot ABSOLUTE-PATH" or
 * "screenshot failed: why". */
bool view_screenshot(void *glfw_window, const char *path, char *said, size_t len);
/* The same of the rectangle (x, y, w, h) of the back buffer (bottom-left origin). */
bool view_screenshot_area(int x, int y, int w, int h, const char *path, char *said, size_t len);

/* A pass as a student reads it, from the renderer's timer name (whose
 * "pass:LINE units" form bench's CSV and tests keep): "pass:65 10" is
 * "RenderToTexture 10 (line 65)", "screen:24" is "to the screen (line 24)";
 * other names are kept. */
void view_pass_name(const char *timer_name, char *out, size_t len);
/* The last finished frame's GPU time per pass, a line each, by view_pass_name. */
void view_pass_summary(render *r, char *out, size_t len);

/* Why a reload happened, from the files the watcher saw change (any
 * form of path; their file names are shown): "water.frag changed",
 * "water.frag and lake.glib changed", "a.frag, b.frag and 2 more changed";
 * "" for none (R, the panel's button). */
void view_reload_cause(const char *const *paths, int n, char *out, size_t len);

/* The reload's line on stderr: "WHO: reloaded SCENE (CAUSE)", and
 * ", compiled off the frame in 0.91 s" when compiled_s >= 0
 * (app_reload_compiled_s). */
void view_reload_line(const char *who, const char *scene, const char *cause, double compiled_s, char *out,
                      size_t len);

/* What the window shows while a change compiles off the frame, from the
 * reload's cause: "water.frag changed" -> "compiling water.frag ... (the
 * last good build draws meanwhile)"; "" -> "compiling ...". */
void view_compiling_text(const char *cause, char *out, size_t len);

/* "tarn-YYYYmmdd-HHMMSS-N.png" into out. */
void view_shot_path(int n, char *out, size_t len);

#endif
