/* world_snapshot: a copy of a frame's screen as it was right before its
 * water was drawn on it (the World, and a pack's copy of its world pass),
 * before the water, what follows it and the spray went over it. The
 * window's sharp world (ui/view.c, gfx/upscale.h) compares a reduced frame
 * with it: a pixel the water left as it was is the static world, which the
 * window shows from a full-resolution world instead of enlarging the
 * reduced one.
 *
 * The copy is a render_target of the screen's kind (8-bit sRGB, 8-bit,
 * float), blitted without sRGB conversion, so a pixel nothing drew over
 * reads back as the frame's, bit for bit. Private to the renderer (render*.c). */
#ifndef TARN_WORLD_SNAPSHOT_H
#define TARN_WORLD_SNAPSHOT_H
#include <stdbool.h>

#include "render.h"

typedef struct world_snapshot {
    bool on;                    /* render_set_world_snapshot */
    bool valid;                 /* this frame's screen had its water drawn on it */
    render_target tg;           /* of the screen's kind (sRGB, float, plain), at least w x h */
    int w, h;                   /* the copy's size (its bottom-left corner) */
} world_snapshot;

/* A frame begins: no copy yet. */
void world_snapshot_frame(world_snapshot *s);
/* Copies the rectangle (x, y, w, h) of framebuffer fbo (bound for drawing
 * by the caller, and bound again on return) into the snapshot; the
 * scissor and GL_FRAMEBUFFER_SRGB are as the caller had them after. */
void world_snapshot_take(world_snapshot *s, unsigned fbo, int x, int y, int w, int h);
void world_snapshot_free(world_snapshot *s);
#endif
