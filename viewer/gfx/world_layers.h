/* world_layers: a World draw's time-independent layers. The world's
 * shading depends on the time only through whether a point is under the
 * moving water surface (packs/common/world_wet.glsl); so while a World
 * command's key (world_cache.h) stays the same except for its time (the
 * camera still, the clock running: the window animating, `tarn render
 * --frames`), its pixels are drawn once into layers that keep, per pixel,
 * the wet and the dry shading, the point and the depth, and every later
 * time is a full-screen pass that picks one of the two
 * (world_layers.frag): the pixels the World draw gives, at the cost of
 * one test a pixel instead of the terrain's and objects' shading. One
 * layer target per World command (WCACHE_SLOTS); single-sample targets
 * without blending only. Private to render.c. */
#ifndef TARN_WORLD_LAYERS_H
#define TARN_WORLD_LAYERS_H
#include <stdbool.h>

#include "world_cache.h"

typedef struct wlayers_slot {
    int cmd;                    /* the World command (-1: free) */
    bool valid;                 /* the layers hold key's world (its time aside) */
    bool broken;                /* the target could not be made: drawn as before */
    bool seen;                  /* last: the command's key at its last frame */
    wcache_key last, key;       /* key: what the layers hold, t zeroed */
    unsigned fbo, tex[3], depth_rb;
} wlayers_slot;

typedef struct world_layers {
    wlayers_slot slot[WCACHE_SLOTS];
    bool off;                   /* render_set_world_layers(false) */
    long builds, composites;
    struct {                    /* what a build changes, put back after it */
        int draw_fbo, rb, vp[4];
        float clear[4];
        bool scissor;
    } saved;
} world_layers;

void wlayers_init(world_layers *l);
/* Forgets every slot (a reload; the world or its program rebuilt). */
void wlayers_free(world_layers *l);

/* Whether command cmd at key k can take its layers: they hold k's world
 * (k's time aside; WLAYERS_READY), or the command was drawn at the last
 * frame with the same key at another time (its size aside: the window's
 * budget may have drawn it larger or smaller), so the clock runs and the
 * layers pay (WLAYERS_BUILD), or neither (WLAYERS_NO: draw it). Records k
 * as the command's last key. */
typedef enum { WLAYERS_NO, WLAYERS_BUILD, WLAYERS_READY } wlayers_use;
wlayers_use wlayers_check(world_layers *l, int cmd, const wcache_key *k);

/* Binds command cmd's layer target for k (made or resized), cleared (the
 * wet layer's depth to 1: nothing drawn), with its three draw buffers and
 * a viewport at its corner; the caller draws the World with uWorldLayers
 * set, then wlayers_end_build. false: it could not be made (the command
 * is drawn as before from now on). */
bool wlayers_begin_build(world_layers *l, int cmd, const wcache_key *k);
/* Puts back the target and viewport wlayers_begin_build found; the layers
 * now hold k's world. */
void wlayers_end_build(world_layers *l, int cmd, const wcache_key *k);

/* The three layer textures of command cmd (wet+depth, dry, point), or NULL. */
const unsigned *wlayers_textures(world_layers *l, int cmd);
#endif
