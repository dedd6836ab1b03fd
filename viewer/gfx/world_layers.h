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
 * layer target per World command (WORLD_CACHE_SLOTS); targets without
 * blending only. A multisampled frame (`tarn render`'s default 4x MSAA)
 * gets multisampled layers and a depth texture, composed a sample at a
 * time (world_layers.frag, WORLD_LAYERS_MS). Private to the renderer
 * (render*.c). */
#ifndef TARN_WORLD_LAYERS_H
#define TARN_WORLD_LAYERS_H
#include <stdbool.h>

#include "world_cache.h"

typedef struct world_layers_slot {
    int cmd;                    /* the World command (-1: free) */
    bool valid;                 /* the layers hold key's world (its time aside) */
    bool broken;                /* the target could not be made: drawn as before */
    bool seen;                  /* last: the command's key at its last frame */
    world_cache_key last, key;       /* key: what the layers hold, t zeroed */
    int samples;                /* the layers' samples a pixel (the frame's) */
    unsigned fbo, tex[4], depth_rb;   /* tex: wet (+ its depth), dry, point; multisampled, [3] the depth */
    unsigned pick_fbo, pick_tex;     /* multisampled: a point a pixel, read back (world_layers_begin_pick) */
    bool picked;                /* this build's points were picked there */
    long gen;                   /* counts the builds: a whole frame is of one */
    unsigned band_vbo;          /* the band's tiles as triangles (world_layer_band.h) */
    int band_verts;             /* their vertices; -1: none to draw alone (the whole frame then) */
} world_layers_slot;

typedef struct world_layers {
    world_layers_slot slot[WORLD_CACHE_SLOTS];
    bool off;                   /* render_set_world_cache(false) */
    bool keep_larger;           /* render_keep_world_layers */
    long builds, composites, band_composites;
    world_cache whole;          /* each command's last whole composed frame, keyed by its build */
    struct {                    /* what a build changes, put back after it */
        int draw_fbo, rb, vp[4];
        float clear[4];
        bool scissor;
    } saved;
} world_layers;

void world_layers_init(world_layers *l);
/* Forgets every slot (a reload; the world or its program rebuilt). */
void world_layers_free(world_layers *l);

/* Whether command cmd at key k can take its layers: they hold k's world
 * (k's time aside; WORLD_LAYERS_READY) at k's size, or, while
 * keep_larger is set, larger (the same world and camera, the projection's
 * aspect within 5%: a frame drawn smaller for a moment is composed from
 * the layers of the larger one, a pixel the texel that sees what it sees,
 * world_layer_view), or the command was drawn at the last
 * frame with the same key at another time (its size aside: the window's
 * budget may have drawn it larger or smaller), so the clock runs and the
 * layers pay (WORLD_LAYERS_BUILD), or neither (WORLD_LAYERS_NO: draw it). Records k
 * as the command's last key. */
typedef enum { WORLD_LAYERS_NO, WORLD_LAYERS_BUILD, WORLD_LAYERS_READY } world_layers_use;
world_layers_use world_layers_check(world_layers *l, int cmd, const world_cache_key *k);

/* Binds command cmd's layer target for k (made or resized), cleared (the
 * wet layer's depth to 1: nothing drawn), with its three draw buffers and
 * a viewport at its corner; the caller draws the World with uWorldLayers
 * set, then world_layers_end_build. false: it could not be made (the command
 * is drawn as before from now on). */
bool world_layers_begin_build(world_layers *l, int cmd, const world_cache_key *k);
/* Multisampled layers only, after the World is drawn into them: binds a
 * one-sample target of the layers' size for the pass that writes a
 * pixel's point in the band if any sample's is (world_pick_band_points),
 * which world_layers_end_build then reads back; returns the layers'
 * textures for that pass. NULL: single-sample layers (their point layer
 * is read itself), or it could not be made (no band: the whole frame is
 * composed each time). */
const unsigned *world_layers_begin_pick(world_layers *l, int cmd);
/* Puts back the target and viewport world_layers_begin_build found; the layers
 * now hold k's world. Reads the point layer (multisampled: the picked
 * points) back once to find the tiles
 * whose points reach the band of heights [band_lo, band_hi]
 * (layer_band_heights): where a composed pixel can change with the time. */
void world_layers_end_build(world_layers *l, int cmd, const world_cache_key *k, double band_lo, double band_hi);

/* Where a frame's pixel finds its texel: texel = (pixel + 0.5) * scale
 * + offset (the pixel counted from the viewport's corner), clamped to the
 * layers; (1, 1) and (0, 0) for layers of the frame's own size, the texel
 * itself. */
typedef struct world_layer_view {
    float scale[2], offset[2];
    int samples;                /* > 1: the textures are multisampled, tex[3] the depth */
} world_layer_view;

/* The layer textures of command cmd (wet+depth, dry, point; multisampled,
 * the depth fourth), or NULL; *v: how a frame at key k (the one world_layers_check took) reads
 * them. */
const unsigned *world_layers_textures(world_layers *l, int cmd, const world_cache_key *k, world_layer_view *v);

/* Multisampled layers: copies their depth (and stencil) into the bound
 * draw framebuffer's viewport at x, y, bit for bit the drawn World's; the
 * caller then composes the colour with the depth test off (a sample's
 * depth written by a shader went through a float and back: a step off at
 * the shore). false: single-sample layers (composed with their depth). */
bool world_layers_copy_depth(world_layers *l, int cmd, const world_cache_key *k, int x, int y);

/* The band's tiles to compose over a copied whole frame. */
typedef struct world_layer_band {
    unsigned vbo;               /* triangles, 4 floats a vertex: x, y in the layers' viewport's
                                 * [-1, 1], then the corner's outward direction (-1 or 1 each) */
    int verts;
    float map[4];               /* the frame's x, y = the layers' x, y * map.xy + map.zw */
    float pad[2];               /* each corner moved outward this far (the frame's [-1, 1]): a
                                 * pixel where the frame resamples larger layers, 0 where not */
} world_layer_band;

/* Composing only the band. Where a whole composed frame of the same
 * layers at k's size was kept (world_layers_keep_whole), copies its colour
 * and depth into the bound draw framebuffer's viewport and gives the
 * band's triangles to compose over it: every other pixel is the same at
 * every time. false: nothing done, compose the whole frame. The depth of
 * every pixel is the copy's, so the caller composes the band with the
 * depth test off; only a World whose depth test passes every point
 * against the cleared 1 (off, LESS, LEQUAL, ALWAYS) takes this. */
bool world_layers_band_begin(world_layers *l, int cmd, const world_cache_key *k, const world_layer_view *v,
                             world_layer_band *band);
/* After a whole composed frame of command cmd at k in the bound draw
 * framebuffer's viewport: kept for world_layers_band_begin. */
void world_layers_keep_whole(world_layers *l, int cmd, const world_cache_key *k);
#endif
