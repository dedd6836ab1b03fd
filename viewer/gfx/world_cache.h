/* world_cache: the static-world cache. A `World` drawn right after a Clear
 * into a target depends only on what is in its key (the world's inputs,
 * the matrices, the GL state that shapes its pixels, the colour it was
 * cleared to, the target's size and formats); while the key is unchanged
 * its colour and depth are copied from a cache instead of drawn again
 * (issue #15: 1.16-1.48x a frame on llvmpipe, bit for bit the same). One
 * slot per World command; private to the renderer (render_draw.c). */
#ifndef TARN_WORLD_CACHE_H
#define TARN_WORLD_CACHE_H
#include <stdbool.h>

#define WORLD_CACHE_SLOTS 16

/* memcmp'd: fill with world_cache_key_init first, so padding is zero. */
typedef struct world_cache_key {
    /* the world's inputs (render_draw.c) */
    double t;
    float eye[3];
    float offset;
    int which;                  /* 0 all, 1 above, 2 below */
    int to_screen;
    int lod;                    /* the world meshes' level of detail */
    float clear_rgba[4];        /* the colour the target was cleared to */
    /* GL state (world_cache_key_gl) */
    float modelview[16], projection[16];
    int vp_w, vp_h;
    int cull, cull_mode, front_face, depth_test, depth_func, blend, blend_func[4], blend_eq[2];
    int polygon_mode[2];
    int tex_units[2];           /* what the world samples: the albedo (2D) and sky (cube) units' textures */
    unsigned color_fmt, depth_fmt;   /* 0: none */
    int samples;
} world_cache_key;

typedef struct world_cache_slot {
    int cmd;                    /* the World command (-1: free) */
    bool valid;                 /* holds the pixels of key */
    bool broken;                /* a copy failed: this command is drawn, not cached */
    bool seen;                  /* drawn before, at time seen_t */
    double seen_t;
    world_cache_key key;
    unsigned fbo, color_rb, depth_rb;
} world_cache_slot;

typedef struct world_cache {
    world_cache_slot slot[WORLD_CACHE_SLOTS];
    bool off;                   /* render_set_world_cache(false) */
    long hits, stores;
} world_cache;

void world_cache_init(world_cache *c);
/* Forgets every slot (a reload; the world or its program rebuilt). */
void world_cache_free(world_cache *c);

void world_cache_key_init(world_cache_key *k);
/* Adds the bound draw framebuffer's and the GL state's part; false when
 * the target cannot be cached (several colour buffers, a format the cache
 * does not know). albedo_unit, sky_unit: the texture units the world reads. */
bool world_cache_key_gl(world_cache_key *k, int albedo_unit, int sky_unit);

/* Where k's depth buffer attaches: with its stencil (GL_DEPTH_STENCIL_ATTACHMENT)
 * for a depth-stencil format, else GL_DEPTH_ATTACHMENT. */
unsigned world_cache_depth_attachment(const world_cache_key *k);
/* What a copy of k's target takes (glBlitFramebuffer's mask): its colour,
 * and its depth with the stencil whole. llvmpipe copies a format's bytes
 * only when the blit takes all of its channels; the depth alone of a
 * DEPTH24_STENCIL8 went through a shader, a depth at the shore one step off
 * (test_world_cache: a pixel of natural's frame). The stencil copied is no
 * one's: the deferred water clears it before it marks. */
unsigned world_cache_copy_mask(const world_cache_key *k);

/* Copies command cmd's cached pixels for key k into the bound draw
 * framebuffer's viewport; false (nothing done) on a miss. */
bool world_cache_restore(world_cache *c, int cmd, const world_cache_key *k);
/* Keeps the bound draw framebuffer's viewport as command cmd's pixels for
 * k, once command cmd has been drawn twice in a row at k's time: while the
 * time runs (an animation) no copy could be used, and each costs. */
void world_cache_store(world_cache *c, int cmd, const world_cache_key *k);
/* The same at once, whatever came before (world_layers' whole frame). */
void world_cache_store_now(world_cache *c, int cmd, const world_cache_key *k);
#endif
