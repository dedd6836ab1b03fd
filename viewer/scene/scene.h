/* scene: the world a .glib describes (terrain, objects, sky, sun, water
 * and waves, camera), read from our world commands into the reference's
 * ref_world_desc, so the GL renderer and the CPU reference draw the same
 * world. See docs/glib.md, "Describing the world". */
#ifndef TARN_SCENE_H
#define TARN_SCENE_H

#include <stdbool.h>
#include "glib.h"
#include "ref_scene.h"

/* What the viewing commands say (the last of each wins). */
typedef struct scene_camera {
    double eye[3], center[3], up[3];   /* LookAt; default (0 0 0) (0 0 -1) (0 1 0), OpenGL's */
    double fov_deg;                    /* Perspective; default 50 */
    double near_z, far_z;              /* default 0.1, 1000 */
    bool ortho;                        /* the last of Perspective / Ortho was Ortho */
    double ortho_lrbt[4];              /* Ortho l r b t */
    int width, height;                 /* WindowSize; default 600 x 600, glman's */
} scene_camera;

/* The one reader of the viewing commands (WindowSize, Perspective, Ortho,
 * LookAt), used by the renderer and the reference alike, so both see the
 * same camera and size. A value out of range (which the parser already
 * refuses) leaves the default. */
void scene_camera_from_glib(const glib_scene *g, scene_camera *cam);

/* Fills world (zeroed first; the defaults are ref_world_init's) and cam from
 * the glib's commands. has_world tells whether the glib has any world
 * command. Returns false with a warning at its command's line in dl (may be
 * NULL) for each value out of range (they are repaired, never fatal). */
bool scene_from_glib(const glib_scene *g, ref_world_desc *world, scene_camera *cam,
                     bool *has_world, diag_list *dl);

/* Parses path (with the scene's Pack included or pack_override, as the
 * renderer does) and fills world and cam. False with the parser's errors
 * in err when the glib has errors, or with scene_from_glib's warnings
 * (`file:line: warning: ...` lines, as many as fit): the one-line reason
 * a command or a test prints. */
bool scene_load(const char *path, const char *pack_override, ref_world_desc *world,
                scene_camera *cam, bool *has_world, char *err, int errlen);

#endif
