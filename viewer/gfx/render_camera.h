/* render_camera: the cameras of the pack contract (docs/packs/contract.md):
 * main, main mirrored about the water plane, orthographic top-down and
 * orthographic along the sun. All four are computed at the start of each
 * frame, so any program can project with any of them (uCam*VP). Private to
 * render.c. */
#ifndef TARN_RENDER_CAMERA_H
#define TARN_RENDER_CAMERA_H

#include <stdbool.h>
#include "render.h"

typedef enum cam_kind { CAM_MAIN = 0, CAM_WIDE, CAM_MIRROR, CAM_TOP, CAM_LIGHT, CAM_COUNT } cam_kind;

typedef struct cam_inputs {
    render_view view;             /* the viewer's camera */
    double fov_deg, near_z, far_z;
    bool ortho;                   /* the glib's Ortho instead of Perspective */
    double ortho_lrbt[4];
    float aspect;
    float fov_scale[CAM_COUNT];   /* Camera main|wide|mirror 1.5 (1: as written) */
    double level, half_size, depth;   /* the world (defaults when there is none) */
    double sun_dir[3];
} cam_inputs;

typedef struct cam_set {
    float view[CAM_COUNT][16], proj[CAM_COUNT][16], vp[CAM_COUNT][16], inv_vp[CAM_COUNT][16];
    float top_half, light_half;
} cam_set;

void cam_compute(const cam_inputs *in, cam_set *out);

/* CAM_MAIN..CAM_LIGHT for "main", "wide", "mirror", "top", "light"; -1 otherwise. */
int cam_kind_from_name(const char *name);

/* Loads kind's projection and view into GL's matrices (front face flipped
 * for the mirror, whose image is reflected). */
void cam_load(const cam_set *c, int kind);

/* The eye of camera kind (the mirror's is reflected), for the sky box. */
void cam_eye(const cam_inputs *in, int kind, float eye[3]);

/* Sets uCam{Main,Wide,Mirror,Top,Light}VP, their inverses uCam*InvVP (clip to
 * world), uCamTopHalfSize, uCamLightHalfSize on the bound program where
 * declared. */
void cam_upload(const cam_set *c, unsigned program);

/* Which names these are: contract_is_camera_uniform (scene/contract.h). */

#endif
