/* panel: the generated slider panel (glman's rollouts), a thin C API over
 * Dear ImGui 1.86 and its GLFW + OpenGL3 backends (panel.cpp).
 *
 * Widgets and layout only: values are changed through unif.c
 * (unif_set_component clamps to ranges and rounds ints, unif_reset and
 * unif_reset_all_ex reset), so the rules live in one place.
 *
 * Per frame, with the window's GL context current:
 *     panel_begin_frame(p);
 *     panel_draw(p, sets, nsets, &info, &actions);
 *     ... render the scene to the default framebuffer ...
 *     panel_render(p);
 *     glfwSwapBuffers(window);
 * then act on `actions` (recompile, save/load ...); values the widgets
 * change are in the sets already, and the renderer uploads them.
 */
#ifndef TARN_PANEL_H
#define TARN_PANEL_H

#include <stdbool.h>
#include "unif.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct panel panel;

/* Creates the ImGui context and backends for a GLFWwindow* (void* keeps GLFW
 * out of this header). glsl_version is the backend's shader header, e.g.
 * "#version 130"; NULL picks that. Install the program's own GLFW callbacks
 * before this call: ImGui chains to them. No imgui.ini is written.
 * NULL when the backends cannot start. */
panel *panel_create(void *glfw_window, const char *glsl_version);
void panel_destroy(panel *p);

void panel_begin_frame(panel *p);

typedef struct panel_info {
    const char *scene_path;
    double gpu_ms;               /* GPU time of the frame; < 0 when not measured */
    bool cpu_raster;             /* llvmpipe & co: gpu_ms is labelled as not meaningful */
    double frame_ms, fps;        /* wall time per frame, recent average */
    bool paused;
    double time_s;               /* simulated time */
    const char *error_text;      /* shown in a red overlay window; NULL if none */
    float scene_x;               /* the scene area's left edge, window pixels: the overlay stays right of it */
    const char *passes;          /* GPU time per pass, a line each; NULL or "" if none */
    const char *const *packs;    /* the packs a world scene can be drawn by (npacks 0: no choice) */
    int npacks;
    int pack;                    /* the one drawing it now, an index into packs; -1 none */
    /* The pack's named settings (its bench.txt: default, paper, ...) for
     * the Setting combo (nsettings 0: none shown); tips (may be NULL or
     * hold NULLs) are their tooltips, a setting's comment */
    const char *const *settings;
    const char *const *setting_tips;
    int nsettings;
    int setting;                 /* the last one chosen, an index into settings; -1 none */
    float *budget_ms;            /* the frame budget's slider, ms (0: off); NULL: none */
    const char *resolution;      /* the internal resolution now, "480x270 (50%) of 960x540, ..." */
} panel_info;

typedef struct panel_actions {
    bool recompile;              /* a define changed (also by a reset): recompile */
    bool reset_all;              /* "Reset all" pressed (already applied to the sets) */
    bool save_preset;            /* the app calls unif_preset_save */
    bool load_preset;            /* the app calls unif_preset_load_ex */
    bool reload;                 /* reload the scene now */
    bool toggle_pause;
    bool screenshot;
    bool switch_pack;            /* the Pack combo picked another: draw the scene with packs[pack] */
    int pack;
    bool switch_setting;         /* the Setting combo picked settings[setting] (the app applies it) */
    int setting;
    bool sheet;                  /* a slider's right-click "Hand-in sheet": this uniform over its range */
    char sheet_program[UNIF_NAME_MAX], sheet_uniform[UNIF_NAME_MAX];
    float sheet_min, sheet_max;
} panel_actions;

/* A Pack combo first when info lists packs (switching draws the same world
 * with another pack, live), a Setting combo when it lists settings (each
 * with its tooltip; the app resets the sliders and applies the pick), then one collapsing header per unif_set with a widget per entry by its widget
 * kind (slider, int slider, checkbox, colour, drag, or the fixed value as
 * text), a small reset button per changeable entry, a row of Reset all /
 * Save preset / Load preset / Reload, Pause and Screenshot buttons, and the
 * frame time, fps and time. A type mismatch shows in red under its entry; a
 * uniform the linked program lacks is greyed. out is cleared first.
 * The panel's height follows the window's; the error overlay is kept in
 * front of it, in the scene area. */
void panel_draw(panel *p, unif_set *sets, int nsets, const panel_info *info, panel_actions *out);

void panel_render(panel *p);     /* ImGui::Render + the OpenGL3 backend's draw */

/* ---- `tarn compare-view`: several packs side by side ---- */

typedef struct panel_compare_pack {
    const char *name;            /* the pack (a second copy shows "basic #2") */
    unif_set *sets;              /* its Programs' entries */
    int nsets;
    double gpu_ms, wall_ms;      /* this pack's frame; < 0 when not measured */
    double rmse, psnr_db;        /* over the reference's water pixels (NaN: no heat map yet) */
    double flip;                 /* HDR-FLIP over the water (NaN: not shown) */
    const char *error_text;      /* its load or build errors, NULL if none */
    const char *passes;          /* its passes' times, a pass a line ("" or NULL: none) */
} panel_compare_pack;

enum { PANEL_LAYOUT_GRID = 0, PANEL_LAYOUT_WIPE = 1 };

#define PANEL_COMPARE_MAX_PACKS 4   /* compare-view's most packs (COMPARE_VIEW_MAX_PACKS) */

typedef struct panel_compare {
    const char *scene_path;
    double frame_ms, fps, time_s;
    bool paused;
    panel_compare_pack *packs;
    int npacks;                  /* at most PANEL_COMPARE_MAX_PACKS are shown */
    /* in and out: the widgets edit these */
    int *layout;                 /* PANEL_LAYOUT_* */
    int *wipe_a, *wipe_b;        /* the two packs of the wipe */
    float *wipe;                 /* the divider, 0..1 from the left */
    bool *show_heat;             /* heat maps instead of the images */
    float *heat_max;             /* the heat map's full scale (0: automatic) */
    const char *heat_status;     /* what the heat maps show, or why there are none */
    const float *legend_rgb;     /* the maps' ramp from 0 to legend_scale, legend_n sRGB triples; NULL: none shown */
    int legend_n;
    double legend_scale;
    bool *passes_over_views;     /* the passes' times over the views too (else only here) */
    int *metric;                 /* what the heat maps show: 0 the largest |RGB| error, 1 HDR-FLIP */
    bool legend_flip;            /* the legend is FLIP's (0..1, magma) */
    const char *note;            /* a line under the timings (the time axis, ...) */
    float *budget_ms;            /* as panel_info's */
    const char *resolution;
} panel_compare;

typedef struct panel_compare_actions {
    panel_actions common;        /* reload, pause, screenshot, save/load preset */
    bool recompile[PANEL_COMPARE_MAX_PACKS];   /* per pack: a define changed (also by its "Reset all") */
    bool compute_heat;           /* "Compute heat maps" */
    bool reset_camera;
} panel_compare_actions;

/* The compare window's panel: the layout (grid or wipe, and which two
 * packs), the heat-map controls, a row per pack with its GPU and wall time
 * and error, then a collapsing section per pack with its sliders. */
void panel_draw_compare(panel *p, const panel_compare *c, panel_compare_actions *out);

/* Text over the scene on a dark box, e.g. a pack's name and time in its
 * corner of the grid: its top-left corner at (x, y) window pixels (top-left
 * origin), or its top-right corner there when right_align. Call between
 * panel_begin_frame and panel_render. */
void panel_label(panel *p, float x, float y, const char *text, bool right_align);

/* The same box centred between x0 and x1 with its top at y, moved
 * sideways to stay between them (at x0 when it is wider): a label that
 * belongs to one part of the scene stays over that part. */
void panel_label_between(panel *p, float x0, float x1, float y, const char *text);

/* A short message (a saved file's path) centred on x with its top at y,
 * window pixels, over everything else. Between panel_begin_frame and
 * panel_render. */
void panel_toast(panel *p, float x, float y, const char *text);

/* true while ImGui uses the mouse / keyboard: the camera should not. */
bool panel_wants_mouse(const panel *p);
/* Is window point (x, y) on one of the panel's windows as last drawn? A
 * press that arrives between two frames lands there before ImGui has seen
 * the cursor move (at 2 fps wants_mouse still says where it was): the
 * press is the panel's (issue #30). */
bool panel_contains(const panel *p, double x, double y);
bool panel_wants_keyboard(const panel *p);

#ifdef __cplusplus
}
#endif

#endif
