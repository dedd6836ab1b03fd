/* render_camera: the cameras of the pack contract (docs/packs/contract.md):
 * main, main mirrored about the water plane, orthographic top-down and
 * orthographic along the sun. All four are computed at the start of each
 * frame, so any program can project with any of them (uCam*VP). Private to
 * the renderer (render_frame.c, render_exec.c, render_once.c). */
#ifndef TARN_RENDER_CAMERA_H
#define TARN_RENDER_CAMERA_H

#include <stdbool.h>
#include "render.h"

typedef enum render_camera_kind {
    RENDER_CAMERA_MAIN = 0,
    RENDER_CAMERA_WIDE,
    RENDER_CAMERA_MIRROR,
    RENDER_CAMERA_TOP,
    RENDER_CAMERA_LIGHT,
    RENDER_CAMERA_COUNT
} render_camera_kind;

typedef struct render_camera_inputs {
    render_view view;             /* the viewer's camera */
    double fov_deg, near_z, far_z;
    bool ortho;                   /* the glib's Ortho instead of Perspective */
    double ortho_lrbt[4];
    float aspect;
    float fov_scale[RENDER_CAMERA_COUNT];   /* Camera main|wide|mirror 1.5 (1: as written) */
    double level, half_size, depth;   /* the world (defaults when there is none) */
    double sun_dir[3];
} render_camera_inputs;

typedef struct render_camera_set {
    float view[RENDER_CAMERA_COUNT][16], proj[RENDER_CAMERA_COUNT][16];
    float vp[RENDER_CAMERA_COUNT][16], inv_vp[RENDER_CAMERA_COUNT][16];
    float top_half, light_half;
} render_camera_set;

void render_camera_compute(const render_camera_inputs *in, render_camera_set *out);

/* RENDER_CAMERA_MAIN..RENDER_CAMERA_LIGHT for "main", "wide", "mirror",
 * "top", "light"; -1 otherwise. */
int render_camera_kind_from_name(const char *name);

/* Loads kind's projection and view into GL's matrices (front face flipped
 * for the mirror, whose image is reflected). */
void render_camera_load(const render_camera_set *c, int kind);

/* The eye of camera kind (the mirror's is reflected), for the sky box. */
void render_camera_eye(const render_camera_inputs *in, int kind, float eye[3]);

/* Sets uCam{Main,Wide,Mirror,Top,Light}VP, their inverses uCam*InvVP (clip to
 * world), uCamTopHalfSize, uCamLightHalfSize on the bound program where
 * declared. */
void render_camera_upload(const render_camera_set *c, unsigned program);

/* Which names these are: contract_is_camera_uniform (scene/contract.h). */

#endif
