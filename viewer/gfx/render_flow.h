/* render_flow: the world's flow (ref_scene.h, ref_flow_desc; issue #29) on
 * the GPU: texture advection of the water's fine detail by backward
 * mapping, one fragment pass a frame whose time changed, ping-pong between
 * two RGBA32F maps over the square |x|, |z| <= FLOW_MARGIN half_size, bound
 * at FLOW_UNIT for packs/common/flow.glsl (uFlowMap), which waves.glsl
 * includes when the world has a flow (WAVES_HAS_FLOW): every pack's normal
 * gets the advected ripples (flowSlope), and flowFoam gives the advected
 * foam streaks. A world without a `Flow` never calls flow_create: no
 * texture, no pass, no uniform. Private to render_world.c (and tests).
 *
 * The map holds, per texel x and per layer (A in rg, B in ba), how far the
 * content now at x has travelled since the layer restarted: d = x - source.
 * Layer A restarts at t = k T, layer B at t = (k + 1/2) T (T the period);
 * a layer's age at t is its phase times T,
 *     phase_A = frac(t / T),   phase_B = frac(t / T + 1/2),
 * and its weight 1 - |2 phase - 1| (0 at the restart, so it never shows). */
#ifndef TARN_RENDER_FLOW_H
#define TARN_RENDER_FLOW_H

#include <stdbool.h>
#include "gpu_timer.h"
#include "ref_scene.h"
#include "render_prog.h"

#define FLOW_UNIT 26                /* under the ocean's 27-29 and the height map's 30 */
#define FLOW_UNIT_VEL 22            /* a Flow texture's velocity map, in the pass only */
#define FLOW_RES 256                /* the map's texels a side */
#define FLOW_MARGIN 1.25            /* it covers the world square's half size times this */
#define FLOW_CATCHUP_STEPS 8        /* steps that rebuild the map after a time jump */
#define FLOW_JUMP_DT 0.5            /* a step longer than this (or backwards) is a jump */
/* the defaults of ref_flow_desc's zeros */
#define FLOW_DEFAULT_AMP 0.012
#define FLOW_DEFAULT_CELL 0.5
#define FLOW_DEFAULT_PERIOD 3.0

typedef struct gpu_flow {
    bool active;
    ref_flow_desc d;                /* defaults filled in */
    float half;                     /* the map covers |x|, |z| <= half */
    unsigned tex[2], fbo[2];
    unsigned vel_tex;               /* a Flow texture's map (RG32F), 0: none */
    int cur;                        /* tex[cur] holds the frame's map */
    prog prog;
    unif_set unifs;
    double t;                       /* the time the map holds */
    bool valid;
    int steps;                      /* advection passes run (tests) */
    int catchups;                   /* updates that rebuilt the map from a restart (tests) */
} gpu_flow;

/* Fills ref_flow_desc's defaults (zero means default). */
void flow_desc_resolve(ref_flow_desc *d);

/* A layer's phase in [0, 1) at time t for period T (layer 0: A, 1: B). */
double flow_phase(int layer, double t, double period);

/* The flow velocity (m/s) at (x, z): the C twin of flow.glsl's flowVelocity
 * (without a Flow texture's term, which only the GPU reads). */
void flow_velocity(const ref_flow_desc *d, double x, double z, double v[2]);

/* Creates the maps and builds the pass program from src->common_dir for a
 * world of half size `half_size`. False with a message in log on errors
 * (from: see prog_build). */
bool flow_create(gpu_flow *f, const ref_flow_desc *desc, double half_size, const prog_sources *src,
                  diag_list *log, prog_origins *from);
void flow_free(gpu_flow *f);
bool flow_build_program(gpu_flow *f, const prog_sources *src, diag_list *log, prog_origins *from);

/* Advects the map to time t unless it holds t: one pass for a step of at
 * most FLOW_JUMP_DT forwards (a layer whose phase wrapped restarts in it),
 * else FLOW_CATCHUP_STEPS passes from both layers' restarts (so a frame
 * rendered alone at time t sees the map a played sequence would, up to
 * the step size). Names the pass in timer (may be NULL); binds framebuffer
 * 0, changes the viewport and program. Returns whether it ran passes. */
bool flow_update(gpu_flow *f, double t, gpu_timer *timer);

/* Binds the map at FLOW_UNIT (nothing when inactive). */
void flow_bind(const gpu_flow *f);

/* Sets program p's flow uniforms (uFlowMap, the terms, the detail, the
 * layers' weights at the map's time); nothing when inactive. */
void flow_upload(const gpu_flow *f, unsigned p);

/* Reads the map back: FLOW_RES^2 * 4 floats (d_A.x, d_A.z, d_B.x, d_B.z),
 * row j at z = -half + (j + 1/2) 2 half / FLOW_RES. */
void flow_read(const gpu_flow *f, float *rgba);

#endif
