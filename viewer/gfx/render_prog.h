/* render_prog: builds one glib Program into a linked GL program, maps the
 * driver's messages to file:line through shader_src, and keeps the uniform
 * model in step with what the program declares. Private to the renderer (render*.c). */
#ifndef TARN_RENDER_PROG_H
#define TARN_RENDER_PROG_H

#include <stdbool.h>
#include "glib.h"
#include "shader_src.h"
#include "unif.h"

/* fixed[0], [1]: the world program's variants (WORLD_MODE, WORLD_HEIGHT_MAP);
 * from PROG_FIXED_WORLD on: the world's wave models and look
 * (world_set_defines, 13 at most); the last: WORLD_ABOVE_WATER (render_load) */
#define PROG_FIXED_WORLD 2
#define PROG_FIXED_MAX 16

/* The program's water split for deferred shading (water_deferred.h),
 * made at its first deferred draw and dropped with the build it came from. */
typedef struct prog_deferred {
    bool tried;                  /* made (or found impossible) for the current build */
    unsigned gbuffer, shade;     /* linked programs, 0: none (why says) */
    int ntex;                    /* the G-buffer's RGBA32F targets */
    bool stamped;                /* glsl_deferred.stamped: no clear of the G-buffer */
    int gbuffer_tangent;         /* the G-buffer program's Tangent attribute */
    char why[192];
} prog_deferred;

typedef struct prog {
    char name[GLIB_NAME_MAX];
    const glib_cmd *cmd;                     /* the Program line (for messages) */
    char stage_path[SHADER_STAGE_COUNT][GLIB_PATH_MAX];  /* "" = stage unused */
    bool gstap;
    unsigned gl;                             /* linked program, 0 when none */
    unsigned long long hash;                 /* of all stage texts: unchanged -> no rebuild */
    bool good;                               /* gl is the build of the current sources */
    unif_set *unifs;                         /* owned by the scene (an array the panel walks) */
    char **deps;                             /* shader files read, incl. #includes */
    int ndeps;
    int timer_loc, tangent_loc;
    int face_index_loc;                      /* glman's FaceIndex (Soccerball), set per face */
    bool face_index_int;
    bool tess;                               /* the build has a TessEvaluation stage */
    unsigned gs_input;                       /* its geometry shader's input primitive (GL enum), 0: none */
    bool world_uniforms;                     /* the scene has a world: its uniforms get no slider */
    shader_define fixed[PROG_FIXED_MAX];     /* defines always built with (name "": none): the world's variants */
    char *source;                            /* all stage texts as compiled (for messages) */
    char *vertex_text, *fragment_text;       /* the vertex and fragment stages as compiled */
    prog_deferred deferred;                  /* water_deferred.h */
    const glib_scene *scene;                 /* its glib: sliders that glib commands read */
} prog;

struct file_cache;

/* Where a program's sources come from: the dirs an `#include` searches
 * after the including file's own, packs/common (where tarn's own world
 * programs live), and the cache every file is read through (file_cache.h),
 * so a rebuild of unchanged files compiles from memory. */
typedef struct prog_sources {
    const char *const *include_dirs;
    int ninclude_dirs;
    const char *common_dir;
    struct file_cache *files;
} prog_sources;

/* The program, and the stage of it, whose build reported diag number d of
 * a load's list: a line that several programs report (an error in a file
 * they all include) is said once, naming them all (render_messages.c). */
typedef struct prog_origin {
    int d;
    shader_stage stage;
    char prog[GLIB_NAME_MAX];
} prog_origin;

typedef struct prog_origins {
    prog_origin *o;   /* in the order of d */
    int n, cap;
} prog_origins;

void prog_origins_free(prog_origins *o);

/* Builds p from its stage paths and defines (from p->unifs' define
 * entries), read through sources. On failure p->gl is left as it was (the last good build)
 * and the messages (the driver's, mapped to the user's files, with hints)
 * are added to dl; from (NULL: not kept) records which of them a stage
 * reported. Returns true on success or when nothing changed. */
bool prog_build(prog *p, const prog_sources *sources, diag_list *dl, prog_origins *from);

/* Introspects p->gl: types, locations, uniforms the glib did not mention,
 * glib uniforms the program lacks (a warning in dl). */
void prog_introspect(prog *p, diag_list *dl);

/* The glib's uniforms that p declares but its build does not use
 * (compiled out by a Define, or unused and optimised out): not mistakes,
 * so the renderer says them in one summary line a load. Fills up to max
 * entries (NULL: just count; each knows its glib file and line); returns
 * how many there are. */
int prog_inactive_uniforms(const prog *p, const unif_entry **found, int max);

/* Uploads every uniform value and Timer (0..1 sawtooth of period timer_s). */
void prog_upload(const prog *p, double t, double timer_s);

/* The same values to gl, another program built from p's texts (its
 * deferred water: water_deferred.h), each uniform found there by name. */
void prog_upload_to(const prog *p, unsigned gl, double t, double timer_s);

/* Drops p's deferred water programs (a rebuild, a free). */
void prog_deferred_free(prog *p);

void prog_free(prog *p);

#endif
