/* render_internal: what the parts of the renderer share, private to them.
 *
 * render.h is the one public header; the renderer's job is cut into files
 * named for their parts of it:
 *   render.c          the render's lifetime, its settings and queries
 *   render_load.c     a scene built from a glib: programs, meshes, textures,
 *                     the world, the files it depends on (and reloads)
 *   render_messages.c the load's messages, each line once, and problems
 *                     met drawing
 *   render_size.c     the sizes of the scene's targets and point grids
 *                     (sliders, the screen, the frame's detail)
 *   render_frame.c    a frame: the water's state, GL's state, the cameras,
 *                     the commands, the resolve
 *   render_exec.c     running one command of the glib in a frame
 *   render_draw.c     the commands that draw: meshes, points, the World
 *   render_check.c    GL errors after a command and a one-colour picture
 *   render_once.c     RenderToTextureOnce blocks kept across a reload
 *   render_splat.c    the photon splat (`Splat`)
 *   render_timing.c   GPU time per frame, pass and draw
 *   render_ref.c      where the reference samples to match MSAA
 *   render_target.c   offscreen targets and the scene's render targets
 * Cross-file functions carry their file's name as prefix. */
#ifndef TARN_RENDER_INTERNAL_H
#define TARN_RENDER_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>

#include "diag.h"
#include "file_cache.h"
#include "glib.h"
#include "gpu_timer.h"
#include "render.h"
#include "render_camera.h"
#include "render_msaa.h"
#include "render_prog.h"
#include "render_res.h"
#include "render_world.h"
#include "scene.h"
#include "world_cache.h"
#include "world_layers.h"
#include "water_deferred.h"
#include "world_snapshot.h"

#define MATRIX_STACK_MAX 30   /* GL guarantees 32 modelview entries */

/* What a glib says about viewing and time (the last command of each wins);
 * the viewing commands are read by the scene layer (scene_camera_from_glib),
 * the one reader the reference uses too. */
typedef struct scene_settings {
    scene_camera cam;
    double timer_s;
    float background[4];
    render_view view;        /* cam's LookAt, as the renderer takes it */
} scene_settings;

/* Everything built from one parse of the glib. */
typedef struct scene_state {
    glib_scene *glib;
    int *cmd_res;            /* per command: index into meshes/texs/progs, or -1 */
    gpu_mesh *meshes;
    int nmeshes;
    gpu_tex *texs;
    int ntexs;
    prog *progs;
    unif_set *unifs;         /* progs[i].unifs == &unifs[i] */
    bool *once_done;         /* per command: a RenderToTextureOnce block already drawn */
    uint64_t *once_sig;      /* per command: what a drawn block drew (render_once_signature) */
    bool *per_frame;         /* per Texture2D target: a RenderToTexture draws it every frame */
    bool *from_view;         /* ... from the view's camera (render_size_drawn_from_view) */
    bool *draw_warned;       /* per command: a problem drawing it was reported */
    bool flat_checked;       /* the first frame was looked at for a one-colour picture */
    bool samples_noise[2];   /* a program samples unit 2 / 3: glman's noise is built (render_load.c) */
    int nprogs;
    scene_settings set;
} scene_state;

struct render {
    char root[GLIB_PATH_MAX];
    char packs_dir[GLIB_PATH_MAX + 16];
    char pack[GLIB_NAME_MAX];      /* --pack: replaces the scene's Pack */
    file_cache *files;             /* every file the scene is made of is read here (render_desc.files) */
    bool shared_files;             /* ... which the caller owns */
    int water_mesh;                /* a setting's WaterMesh (0: the scene's own) */
    int water_mesh_loaded;         /* the one the world on screen was built with */
    gpu_world world;               /* kept across reloads while the world is unchanged */
    world_cache wcache;            /* World commands drawn after a Clear, kept while their key stays */
    world_layers wlayers;          /* ... and their layers, while only the time changes */
    world_snapshot snap;           /* the screen right before its water (render_set_world_snapshot) */
    water_deferred deferred;       /* the screen's water shaded once a pixel (water_deferred.h) */
    bool world_only;               /* inside render_frame_world_at */
    char common_dir[GLIB_PATH_MAX + 16];
    const char *include_dirs[1];
    prog_sources sources;          /* include_dirs, common_dir and files, for every program built */
    char path[GLIB_PATH_MAX];
    scene_state cur;
    char *messages;             /* diags, formatted */
    char *draw_messages;        /* problems met drawing (also in messages), since the load */
    diag_list diags;            /* the load's messages, each once, then the draws' */
    bool errors;
    bool reads_clock;              /* render_reads_clock, decided by each load (render_load.c) */
    const char **deps;
    int ndeps;
    unsigned rtt_fbo, rtt_depth;
    int rtt_w, rtt_h;
    int samples;               /* MSAA requested (render_desc.samples) */
    /* Ask GL for errors after every command, to name the one at fault:
     * in the first frame after a load and after a frame that had an
     * error. Otherwise once a frame: glGetError can stall a GPU's
     * command stream, and the answer is almost always "none". */
    bool gl_check_each;
    bool draw_timing;          /* render_set_draw_timing: an interval per drawing command */
    render_msaa msaa;          /* the screen passes' multisampled target */
    int max_target;            /* the largest side a slider may give a target (0: not asked yet) */
    double detail;             /* render_set_detail: 1 (0 before the first call) everything as the scene says */
    /* The RenderToTextureOnce blocks the scene before a reload drew, by
     * their signature: the first frame after the reload skips a block whose
     * signature is here, its targets holding its pixels already. */
    uint64_t *kept_once;
    int nkept_once;
    long once_reused;          /* blocks so kept since render_create */
    gpu_timer timer;           /* per frame and per pass */
    gpu_tex noise[2];          /* glman's built-in Noise2 / Noise3, bound once a program samples them */
    char noise_dir[GLIB_PATH_MAX];  /* the project folder they were read for */
    bool verbose;              /* render_desc.verbose */
    bool no_spray;             /* render_desc.no_spray */
};

/* One frame's run through the commands (render_frame_at). */
typedef struct frame_state {
    unsigned screen_fbo;
    int x, y, w, h;
    bool in_rtt;
    bool skipping;           /* inside a RenderToTextureOnce block already drawn */
    render_camera_inputs cam_in;
    float cam_eye[3];        /* the current camera's eye (the mirror's is reflected): the sky box's centre */
    int if_depth, if_false;  /* If blocks: nesting, and how deep the first false one is (0: none) */
    render_camera_set cams;
    int depth;
    const prog *cur;
    double t;
    float eye[3];
    int patch_vertices;      /* NumPatchVertices: the size of the patches drawn next */
    int patch_cmd;           /* the NumPatchVertices command that set it, or -1 */
    int cam_kind;            /* the camera loaded last (render_camera_kind) */
    /* The static-world cache: the current target holds only what a Clear
     * to clean_rgba left (nothing drawn since); the screen's own state
     * while a pass draws into a texture. */
    bool clean, screen_clean;
    float clean_rgba[4], screen_rgba[4];
    bool check_each;         /* render.gl_check_each for this frame */
    bool once_drawn;         /* a RenderToTextureOnce block was drawn this frame */
    bool in_once;            /* drawing one: at full detail, whatever the frame's (it is kept) */
    bool replaying;          /* in one a reload kept: its commands run, but none that writes pixels */
    bool water_reached;      /* the first WaterSurface on the screen has come (water_on_screen) */
} frame_state;

/* ---- render_load.c ---- */
void render_load_scene_free(scene_state *s);
void render_load_free_deps(render *r);
void render_load_settings_default(scene_settings *s);

/* ---- render_messages.c ---- */
/* The load's messages (dl, from: which program's build reported each):
 * each line once, naming every program that reported it. Takes (frees)
 * both. */
void render_messages_set(render *r, diag_list *dl, prog_origins *from);
/* A problem met drawing command ci: said once a load, with its glib line,
 * in the messages (and the draw messages, for `tarn render`). */
__attribute__((format(printf, 4, 5)))
void render_messages_draw_problem(render *r, int ci, bool error, const char *fmt, ...);

/* ---- render_size.c ---- */
int render_size_slider_count(const scene_state *s, const char *name, int max);
int render_size_detail_count(const render *r, int n);
bool render_size_drawn_every_frame(const glib_scene *g, int unit);
bool render_size_drawn_from_view(const glib_scene *g, int unit);
void render_size_targets(render *r, int screen_w, int screen_h);
void render_size_check_names(const scene_state *s, diag_list *log);
bool render_size_screen_unit(const scene_state *s, int unit);

/* ---- render_exec.c ---- */
float render_exec_cmd_number(const scene_state *s, int ci, float def);
void render_exec_bind_textures(render *r);
void render_exec_commands(render *r, frame_state *f);
void render_exec_end_pass(frame_state *f);

/* ---- render_draw.c ---- */
void render_draw_water(render *r, const frame_state *f, const glib_cmd *c);
void render_draw_mesh(render *r, const frame_state *f, int ci, const gpu_mesh *m);
void render_draw_world(render *r, frame_state *f, int i);

/* ---- render_check.c ---- */
void render_check_gl(render *r, const frame_state *f, int ci, const gpu_mesh *m, const render_res_draw *d);
void render_check_frame_errors(render *r, const frame_state *f);
void render_check_flat_picture(render *r, unsigned fbo, int x, int y, int w, int h);

/* ---- render_once.c ---- */
void render_once_keep(render *r, const scene_state *s);
uint64_t render_once_signature(const render *r, const frame_state *f, int i);
bool render_once_kept(render *r, const frame_state *f, uint64_t sig);
void render_once_redraw_unit(scene_state *s, int unit);

/* ---- render_splat.c ---- */
void render_splat(const render *r, int src_unit, int dst_unit);

/* ---- render_timing.c ---- */
void render_timing_mark_pass(render *r, const glib_cmd *c);
void render_timing_mark_now(render *r, const char *name);

#endif
