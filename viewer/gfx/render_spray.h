/* render_spray: spray particles (ref_scene.h, ref_spray_desc; issue #29,
 * [DSoSF]): where the water's surface rises faster than a threshold,
 * droplets are emitted; they do not interact, fly under gravity, and are
 * removed when they fall back into the water or their life ends. All on
 * the GPU: the particles' state is two RGBA32F textures, a texel a particle
 * slot (SPRAY_UNIT_POS: position and life left; SPRAY_UNIT_VEL: velocity),
 * updated by a fragment pass a frame (packs/common/spray_update.frag) and
 * drawn as soft point sprites lit by the sun and sky, blended over the
 * finished frame (spray_draw.vert/.frag). A world without a `Spray` never
 * calls spray_create: no texture, no pass, no uniform. Private to
 * render_world.c and render_frame.c (and tests).
 *
 * Motion: a step of dt moves a live particle exactly along its parabola,
 *     p += v dt - g dt^2 / 2 y,   v -= g dt y,   life -= dt,
 * so after any steps p(t) = p0 + v0 (t - t0) - g (t - t0)^2 / 2 y (the
 * closed form, up to float rounding). It is removed when its life runs
 * out, or when it is falling and below the surface (wavesHeightAt).
 *
 * Emission, deterministic: in a step at time t, a dead slot s tries once,
 * with the numbers of hash(seed, s, round(t * 1000)): it goes on with
 * probability min(1, rate dt / count), picks a rest point uniformly on the
 * world square, and emits there when the surface's upward speed, the
 * time derivative of the wave sum's height by a backward difference of
 * SPRAY_DT_FD, exceeds the threshold: along the surface's normal, spread
 * a little, at 1 to 1.6 times that speed, with a life of 0.6 to 1 times
 * the desc's. So `rate` is the particles a second were the whole square
 * over the threshold, and a run of the same steps gives the same spray.
 * The spectrum ocean's height comes from textures of one time (its
 * derivative would take another inverse FFT), so in a world with an ocean
 * the step that ends at the height map's time takes the upward speed from
 * the last two height maps instead (render_world.c keeps the one before
 * while there is a spray), (H_t - H_prev) / (t - t_prev) at the candidate's
 * displaced point: every model at once, Eulerian. A played sequence emits
 * on the ocean's crests; the steps of a catch-up after a jump (no maps
 * of their times) take the other models' speed only. */
#ifndef TARN_RENDER_SPRAY_H
#define TARN_RENDER_SPRAY_H

#include <stdbool.h>
#include "gpu_timer.h"
#include "ref_scene.h"
#include "render_prog.h"

#define SPRAY_UNIT_POS 24            /* under the flow's 26 and the ocean's 27-29 */
#define SPRAY_UNIT_VEL 25
#define SPRAY_UNIT_HEIGHT_PREV 23    /* the height map before (the ocean's upward speed) */
#define SPRAY_GRAVITY 9.81
#define SPRAY_DT_FD (1.0 / 256.0)    /* the upward speed's backward difference (s) */
#define SPRAY_STEP_MAX (1.0 / 30.0)  /* a longer step is cut into steps of at most this */
#define SPRAY_JUMP_DT 0.25           /* a step longer than this (or backwards) is a jump */
#define SPRAY_COUNT_MAX (1 << 20)
/* the defaults of ref_spray_desc's zeros */
#define SPRAY_DEFAULT_LIFE 2.0
#define SPRAY_DEFAULT_SIZE 0.05
#define SPRAY_DEFAULT_COUNT 16384

enum { SPRAY_PROG_UPDATE, SPRAY_PROG_DRAW, SPRAY_PROGS };

typedef struct gpu_spray {
    bool active;
    ref_spray_desc d;                /* defaults filled in */
    float half;                      /* emission over |x|, |z| <= half */
    int res;                         /* the state textures' side: res^2 >= count */
    unsigned pos_tex[2], vel_tex[2], fbo[2];
    int cur;                         /* [cur] holds the frame's state */
    prog progs[SPRAY_PROGS];
    unif_set unifs[SPRAY_PROGS];
    double t;                        /* the time the state holds */
    bool valid;
    int steps;                       /* update passes run (tests) */
} gpu_spray;

/* Fills ref_spray_desc's defaults (zero means default). */
void spray_desc_resolve(ref_spray_desc *d);

/* Creates the state (every slot dead) and builds the programs from
 * src->common_dir for a world square of half size half_size; the update
 * program with the world's wave defines (set_defines, may be NULL, is
 * called on each program before it is built). False with messages in log
 * on errors. */
bool spray_create(gpu_spray *s, const ref_spray_desc *desc, double half_size, const prog_sources *src,
                  void (*set_defines)(const void *ctx, prog *p), const void *ctx,
                  diag_list *log, prog_origins *from);
void spray_free(gpu_spray *s);
bool spray_build_programs(gpu_spray *s, const prog_sources *src, diag_list *log, prog_origins *from);

/* Empties every slot (a time jump; tests). */
void spray_clear(gpu_spray *s);

/* Moves the particles to time t unless they are there: steps of at most
 * SPRAY_STEP_MAX from the state's time; after a jump (backwards, over
 * SPRAY_JUMP_DT, or the first update) it starts empty at t - life and
 * steps to t in SPRAY_STEP_MAX steps, so a frame drawn alone at t shows
 * the spray a played sequence at that step would. upload(ctx, program,
 * time) sets the world's uniforms (the waves) of the update program.
 * Names the pass in timer (may be NULL). Binds framebuffer 0, changes the
 * viewport and program. Returns whether it ran passes. */
bool spray_update(gpu_spray *s, double t, gpu_timer *timer, void (*upload)(const void *ctx, unsigned p, double t),
                  const void *ctx);

/* Draws the live particles into the bound framebuffer (viewport w x h) as
 * seen through view-projection vp (column-major) from eye, blended
 * (premultiplied alpha) over what is there, depth-tested, not written.
 * upload as in spray_update (the sun and sky). */
void spray_draw(const gpu_spray *s, const float vp[16], const float eye[3], int w, int h,
                void (*upload)(const void *ctx, unsigned p, double t), const void *ctx);

/* Reads the state back: res^2 * 4 floats each, (x, y, z, life) and
 * (vx, vy, vz, 0); slot k at texel (k % res, k / res). */
void spray_read(const gpu_spray *s, float *pos, float *vel);

#endif
