/* world_snapshot: a copy of a frame's screen as it was right before its
 * water was drawn on it (the World, and a pack's copy of its world pass),
 * before the water, what follows it and the spray went over it. The
 * window's sharp world (ui/view.c, gfx/upscale.h) compares a reduced frame
 * with it: a pixel the water left as it was is the static world, which the
 * window shows from a full-resolution world instead of enlarging the
 * reduced one.
 *
 * The copy is raw (no sRGB conversion, the screen's own format), so a pixel
 * nothing drew over is bit for bit the frame's. Private to render.c. */
#ifndef TARN_WORLD_SNAPSHOT_H
#define TARN_WORLD_SNAPSHOT_H
#include <stdbool.h>

typedef struct world_snapshot {
    bool on;                    /* render_set_world_snapshot */
    bool valid;                 /* this frame's screen had a World drawn on it */
    unsigned tex, fbo, format;  /* format: the screen's, the texture made for it */
    int tex_w, tex_h;           /* the texture's size */
    int w, h;                   /* the copy's (its bottom-left corner) */
} world_snapshot;

/* A frame begins: no copy yet. */
void world_snapshot_frame(world_snapshot *s);
/* Copies the rectangle (x, y, w, h) of framebuffer fbo (bound for drawing
 * by the caller, and bound again on return) into the snapshot; the
 * scissor and GL_FRAMEBUFFER_SRGB are as the caller had them after. */
void world_snapshot_take(world_snapshot *s, unsigned fbo, int x, int y, int w, int h);
void world_snapshot_free(world_snapshot *s);
#endif
