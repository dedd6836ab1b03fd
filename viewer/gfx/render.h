/* render: executes a parsed .glib scene with OpenGL, as glman does, and
 * reloads it without losing what worked.
 *
 * render_load() parses the glib, loads textures and meshes, and builds every
 * Program. A reload builds into new objects and swaps per part: a glib with
 * errors keeps the whole previous scene; a shader that fails keeps that
 * Program's last good build; a texture that fails keeps its last good image.
 * Messages (file:line: ...) of the latest load are in render_messages().
 */
#ifndef TARN_RENDER_H
#define TARN_RENDER_H

#include <stdbool.h>
#include "diag.h"
#include "unif.h"

typedef struct render render;

typedef struct render_desc {
    const char *repo_root;      /* 0: tarn_root(); packs/common is an include dir */
    const char *pack;           /* 0: the scene's own `Pack`; else this pack instead */
    int samples;                /* MSAA of the screen passes: 0 the default, 1 off, else N */
    bool verbose;               /* every inactive uniform a note at its glib line, not one summary */
    bool no_spray;              /* leave the world's Spray out (tarn bench: the reference has none) */
    /* Where the scene's files (glib, shaders, models, textures) are read,
     * shared with the caller's watcher and other renders (file_cache.h);
     * borrowed, it must outlive the render. 0: a cache of the render's own,
     * so a Define toggle or a reload of unchanged files reads no disk. */
    struct file_cache *files;
} render_desc;

/* Anti-aliasing: the screen passes are drawn multisampled and resolved
 * into the caller's framebuffer (render_msaa.h); RenderToTexture passes
 * are single-sample. The default is RENDER_MSAA_DEFAULT samples on a GPU
 * and off on a CPU rasteriser (llvmpipe), where 4x costs 3-4.5x the frame. */
#define RENDER_MSAA_DEFAULT 4

typedef struct render_view {
    float eye[3], center[3], up[3];
} render_view;

render *render_create(const render_desc *desc);
void render_destroy(render *r);

/* The desc r was made with, as it is now (render_set_pack changes .pack;
 * repo_root always set): another render made from it draws the same scene
 * the same way (the window's compile job warms the driver's shader cache
 * with one). The strings point into r. */
render_desc render_desc_of(const render *r);

/* Loads (or reloads, when path equals the current one or is NULL) the scene.
 * Returns false if the load had errors; what could be kept is in use. */
bool render_load(render *r, const char *glib_path);

/* Rebuilds programs whose `Define` toggles changed in the panel. */
bool render_rebuild_programs(render *r);

const char *render_messages(const render *r);   /* "" when the last load was clean; each line once */
/* Problems met drawing since the last load (each command's once, with its
 * glib line: a GL error, patches without a tessellation program); they
 * are in render_messages too. "" when every draw worked. A failed draw
 * draws nothing; the rest of the frame is drawn. */
const char *render_draw_messages(const render *r);
/* The same as diagnostics (severity, file, line, text), the form the
 * renderer records them in: render_messages is these, formatted, a line
 * that several programs reported naming them all (its text ends in
 * " (fragment shader of programs 'Water', 'Sky')"). */
const diag_list *render_diags(const render *r);
bool render_has_errors(const render *r);
bool render_has_scene(const render *r);
/* The scene describes a world (lit in linear radiance, like the reference). */
bool render_has_world(const render *r);
/* A hash of the texts the world's own programs were built from (its
 * shading, height map and layers, and the ocean's and flow's passes that
 * move the water its shore is wet under), 0 without a world: a load that
 * changed it rebuilt them (its caches forgotten; ui/compile_job.c: only
 * then do the clock's frames need new code). */
unsigned long long render_world_programs_hash(const render *r);
/* Does the picture depend on the time it is drawn at? A program of the
 * scene reads the clock (glman's Timer, tarn's uTime), or the world does
 * (its water, sky and wet shore; an ocean, a flow, a spray). A glman scene
 * without Timer does not: a window keeps its picture still, at full
 * resolution and asleep, while the clock runs. Decided at each load and
 * rebuild of the programs. */
bool render_reads_clock(const render *r);
/* The pack the next render_load draws the scene with, as render_desc.pack
 * (NULL or "": the scene's own `Pack`). What is on screen stays until that
 * load; a load that fails (a glman scene has no world for a pack) keeps it.
 * The view window's Pack combo, and a session replay's pack switch. */
void render_set_pack(render *r, const char *pack);
/* A world command (glib.md) a pack's setting changes (packset.h's
 * scene.Command=ARGS), set on top of the scene's own for every later
 * render_load, like render_set_pack: true when the renderer takes that
 * command at run time (WaterMesh N: N clamped to the glib's 8..2048),
 * false when not (the caller says it does not apply). */
bool render_set_world_override(render *r, const char *command, const float *v, int n);
/* Back to the scene's own world commands (at the next render_load). */
void render_clear_world_overrides(render *r);
/* true when an override is set that the scene on screen was not loaded with. */
bool render_world_overrides_pending(const render *r);
/* The pack the current scene is drawn by (its Pack command, after any
 * override), "" when it has none. */
const char *render_pack(const render *r);

/* MSAA samples of the next frames (as render_desc.samples), and those in
 * use: 1 when off, else the request clamped to what the GL allows. */
void render_set_samples(render *r, int samples);
int render_samples(render *r);
/* The same for a request, before any render exists (a GL context must be
 * current). */
int render_samples_on_this_gl(int requested);
/* The reference's subsamples a side (N x N, `tarn reference --spp`) nearest
 * to MSAA with this many samples (render_samples): the nearest square, 2x2
 * for 4x, 1x1 off. Only a fallback: an ordered grid meets edges otherwise
 * than GL's rotated sample pattern; render_ref_positions matches it. */
int render_ref_spp(int samples);
/* Where the reference should subsample to match MSAA with this many
 * samples (render_samples): where this GL samples (asked of it once; a GL
 * context must be current), in the reference's form (ref_render_desc.samples:
 * x right, y DOWN, in [0, 1)^2: GL's y-up (x, y) becomes (x, 1 - y)), into
 * pos[0..max). Returns how many: 0 when MSAA is off (samples <= 1) or the
 * GL cannot say (then render_ref_spp's grid is the fallback). */
int render_ref_positions(int samples, double (*pos)[2], int max);
/* The same without a GL: the standard positions of 2, 4, 8 or 16 samples
 * (which GPUs and llvmpipe use); 0 for another count. */
int render_ref_standard_positions(int samples, double (*pos)[2], int max);

/* Every file the scene depends on (glib, includes, shader stages and their
 * #includes, textures, OBJs): what the watcher watches. */
int render_deps(const render *r, const char *const **paths);

/* Draws one frame at simulated time t (seconds) into framebuffer `fbo`
 * (0: the window) of w x h. view NULL: the glib's LookAt. */
void render_frame(render *r, double t, unsigned fbo, int w, int h, const render_view *view);
/* The same into the rectangle (x, y, w, h) of the framebuffer (the window
 * beside the panel). */
void render_frame_at(render *r, double t, unsigned fbo, int x, int y, int w, int h, const render_view *view);

/* The window's sharp world (ui/view.c): the static world at full
 * resolution under a reduced frame's water.
 * With snapshots on, each frame keeps a copy of its screen as it was right
 * before its first WaterSurface on the screen (the world, and what the
 * scene drew before its water: caustic_tex's copy of its world pass):
 * render_world_snapshot gives that texture (its bottom-left w x h texels,
 * the screen's kind of colour, copied without sRGB conversion so a pixel
 * nothing drew over after reads back as the frame's, bit for bit), or 0 when the last frame drew no WaterSurface on
 * its screen (a glman scene). */
void render_set_world_snapshot(render *r, bool on);
unsigned render_world_snapshot(const render *r, int *w, int *h);
/* A frame of what the screen holds at that point and nothing after: the
 * commands up to its first WaterSurface on the screen, with the passes
 * into screen-sized targets ("screen", "screen_half", "screen_quarter")
 * and no other (the water's mirror, refraction, light and photon passes,
 * RenderToTextureOnce blocks), at full detail, drawn past the world's
 * caches (the window's frames keep theirs), leaving the water's state
 * (ocean, flow, spray, height map) and the other targets as the last frame
 * left them: the world the water is drawn over, at any size, for one time. */
void render_frame_world_at(render *r, double t, unsigned fbo, int x, int y, int w, int h, const render_view *view);
/* A hash of what such a frame is drawn from besides the camera, the time,
 * the size and the uniform values: the world's description and programs,
 * and the commands it runs with the textures, meshes and programs they
 * draw with (0: no scene). A save of the water's own shader leaves it as
 * it was: the window keeps its full-resolution world (ui/view.c) instead
 * of drawing it again (89 ms on the frame after a save of natural's water,
 * lake, 960x540, llvmpipe). A target such a frame samples but does not
 * draw (a pass it skips) counts as the frame's own inputs do not: as the
 * last frame left it, the world-only frame's documented state. */
unsigned long long render_world_frame_inputs(const render *r);

/* Deferred water (on by default; water_deferred.h): the screen's
 * `WaterSurface`, into a single-sample target, drawn as a G-buffer of the
 * grid then one full-screen pass of the program's fragment shader, so a
 * CPU rasteriser shades each water pixel once (the grid's small triangles
 * shaded blocks of pixels several times). Off: the grid as drawn before.
 * draws: how many water draws went so since render_create; why: the
 * reason a program of the scene could not (NULL: none found). */
void render_set_deferred_water(render *r, bool on);
long render_deferred_water_draws(const render *r);
const char *render_deferred_water_why(const render *r);

/* The static-world cache (on by default): a `World` drawn right after a
 * Clear is copied from the last frame's pixels while its camera, clip,
 * target, GL state, time and the world are unchanged (bit for bit what
 * drawing it gives). Off: always drawn. hits: how many World draws it
 * saved since render_create. */
void render_set_world_cache(render *r, bool on);
long render_world_cache_hits(const render *r);
/* With the cache on, a World whose key stays while only the time changes
 * (the clock running, the camera still) is drawn once into layers that
 * hold each pixel's wet and dry shading, and each later time from them by
 * one full-screen pass (world_layers.h): the same pixels. How many World
 * draws were so composed since render_create: */
long render_world_layer_frames(const render *r);
/* ... and how many of those copied the last whole one and composed only
 * the tiles where the moving surface meets the land (world_layer_band.h): */
long render_world_band_frames(const render *r);
/* While keep is true (off by default), a frame smaller than the layers of
 * its World (the same world and camera) is composed from them, each pixel
 * from the texel that sees what it sees, instead of building its own: for
 * a picture whose size moves (the window's budget, and while a save's job
 * compiles), so that neither the shrink nor the growth back to the
 * layers' size builds them (a World drawn whole, 15-80 ms). Off, a frame
 * of a new size builds its own, and every frame is the frame drawn
 * whole (a served one is that of the layers' size, resampled). */
void render_keep_world_layers(render *r, bool keep);

/* The world's wet and dry land (where the moving surface is above it)
 * from a height map of the surface drawn once a frame, bilinear between
 * samples WORLD_HEIGHT_RES a side over twice the world square (the
 * default), or solved for at every pixel (off: as exact as the
 * reference's, and on a CPU rasteriser 40% of a frame of the world). */
bool render_set_world_height_map(render *r, bool on);

/* The height map drawn only over the cells a test of wet land reads (on,
 * the default: on the lake a tenth of the map, 14 -> 5 ms a frame on
 * llvmpipe) or over all of it (off): the same pixels either way. */
void render_set_world_height_cells(render *r, bool on);

/* Detail of the next frames, for a frame drawn at `detail` (0..1] of
 * each side of its full resolution (the windows' frame budget): the
 * scene's fixed-size work shrinks with it, so a reduced frame costs about
 * detail^2 of a full one, not a fixed floor: RenderToTexture targets of a
 * fixed or slider-given size and `WaterSurface points|mesh N` are scaled by
 * detail (at least 16 a side; a target drawn from the view's camera, `Camera
 * main|wide|mirror`, by twice detail, up to its own size: its texels reach
 * the screen through widened, perturbed lookups), and the world's terrain and water grid are
 * drawn with about detail^2 of their vertices (coarser meshes, built when
 * first needed). Targets whose size follows the frame (`screen`) follow
 * it already. 1 (the default): everything as the scene says. */
void render_set_detail(render *r, double detail);

/* A RenderToTextureOnce block is drawn on the first frame after a load
 * (glman's rule), except after a reload that changed nothing it draws
 * from: its commands, the programs it uses (source and slider values),
 * the program and camera it starts with, the scene's textures and the
 * world. Its targets then still hold its pixels (a texture is kept across
 * a reload while its command is unchanged), and drawing it again would
 * cost the first frame after every save (raymarch's top-down views: half
 * a second on a CPU). How many blocks were kept so since render_create: */
long render_once_reused(const render *r);

/* GPU time of the last finished frame in ms (timer query), or -1. When
 * wait is true, blocks until the latest frame's time is known. */
double render_gpu_ms(render *r, bool wait);

/* GPU time per pass of the last finished frame: names are "screen:LINE" or
 * "pass:LINE u1 u2" (the glib line of the RenderToTexture that began it). */
#include "gpu_timer.h"
int render_pass_times(render *r, bool wait, const char (**names)[GPU_TIMER_NAME], const double **ms);

/* Per-draw timing (off by default): each glib command that draws (a
 * World, the water, a mesh) also starts an interval of its own, named
 * "KIND:LINE" (World:12, WaterSurface:40), and the world's per-frame
 * height map is "world height"; so render_pass_times says where a frame's
 * time goes draw by draw. A name can then come more than once a frame.
 * For `tarn render --passes`; GPU_TIMER_MARKS intervals a frame at most. */
void render_set_draw_timing(render *r, bool on);

/* The same as text, a pass a line ("pass:63 10 12.40 ms"), cut to fit
 * len; "" before the first frame's times are known. */
void render_pass_summary(render *r, char *out, int len);

unif_set *render_uniforms(render *r, int *nsets);
void render_window_size(const render *r, int *w, int *h);   /* WindowSize, default 800x600 */
render_view render_default_view(const render *r);          /* the glib's LookAt */
const char *render_scene_path(const render *r);

/* Reads a uniform's current value from the linked GL program (tests). */
/* A render target of the loaded scene (an empty `Texture2D`), as it is
 * now: for checks of what the passes wrote (tests read it back). */
typedef struct render_target_info {
    int unit, w, h;
    bool is_float;        /* float or float16 colour */
    bool is_depth;
    unsigned tex;         /* the GL texture */
    const char *file;     /* the Texture2D line */
    int line;
} render_target_info;

/* Fills out[0..max-1] with the scene's render targets in glib order and
 * returns how many there are (which may be more than max). */
int render_targets(const render *r, render_target_info *out, int max);

bool render_read_uniform(render *r, const char *program, const char *name, float *out, int n);

/* An offscreen colour+depth framebuffer for headless rendering. */
typedef struct render_target { unsigned fbo, color, depth; int w, h; bool is_float, is_srgb; } render_target;
bool render_target_create(render_target *t, int w, int h, bool is_float);
/* The same with 8-bit sRGB-encoded colour (the window's encoding): what a
 * window draws a world into and upscales from. */
bool render_target_create_srgb(render_target *t, int w, int h);
void render_target_destroy(render_target *t);
/* Reads the target back as RGBA floats, row 0 = top (the file order). */
bool render_target_read(const render_target *t, float *rgba);

#endif
