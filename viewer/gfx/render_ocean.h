/* render_ocean: the spectrum ocean (reference/ref_ocean.h) on the GPU:
 * per frame, per cascade, one spectrum pass and 2 log2 N radix-2 Stockham
 * inverse-FFT passes, fragment passes into RGBA32F 2D-array textures (one
 * layer per cascade). The result is the reference's frame layout, FFT-order
 * texels:
 *     A = (h, Dx, Dz, Dxz)    B = (hx, hz, Dxx, Dzz)
 * bound at OCEAN_UNIT_A / OCEAN_UNIT_B, which packs/common/waves_ocean.glsl
 * reads (uOceanA, uOceanB) with a bilinear blend made by hand. A world
 * without an ocean never calls ocean_create: no texture, no pass. Private
 * to render_world.c (and tests). */
#ifndef TARN_RENDER_OCEAN_H
#define TARN_RENDER_OCEAN_H

#include <stdbool.h>
#include "gpu_timer.h"
#include "ref_ocean.h"
#include "render_prog.h"

#define OCEAN_UNIT_A 28          /* above glman's units; 30 is the waves' height map */
#define OCEAN_UNIT_B 29
/* The folding foam: 27, beside A and B (31, the last unit of a GL with 32
 * image units, e.g. llvmpipe, is left free) */
#define OCEAN_UNIT_FOAM 27

/* Folding foam (Tessendorf: where J = det(I + dD) falls under a threshold
 * the crest folds): per cascade a foam layer, each frame
 *     foam = max(foam_prev exp(-dt / decay), coverage(J)),
 *     coverage(J) = clamp((OCEAN_FOAM_J - J) / OCEAN_FOAM_SOFT, 0, 1),
 * dt the frame's time step; a time jump backwards or over
 * OCEAN_FOAM_RESET_DT restarts it from the coverage; a still frame (same
 * time) leaves it as it is. */
/* per cascade, J of that cascade's own fields: the cascades' Jacobians add
 * (to first order), so each alone seldom folds; at 0.86 a moderate sea
 * (scenes/ocean.glib: 9 m/s, choppiness 1; each cascade's J has its 1st
 * percentile at ~0.77, 5th at ~0.83, minimum ~0.6) shows whitecaps on its
 * steepest crests, and a choppy one (2.2) far more */
#define OCEAN_FOAM_J 0.86
#define OCEAN_FOAM_SOFT 0.2
#define OCEAN_FOAM_DECAY 2.5     /* seconds for foam to fall to 1/e */
#define OCEAN_FOAM_RESET_DT 1.0

enum { OCEAN_PROG_SPECTRUM, OCEAN_PROG_FFT_H, OCEAN_PROG_FFT_V, OCEAN_PROG_FOAM, OCEAN_PROGS };

typedef struct gpu_ocean {
    bool active;
    int cascades, res, log2res;
    float tile[REF_OCEAN_CASCADES_MAX];
    float lambda;                /* choppiness, folded into the D fields */
    unsigned h0_tex;             /* RGBA32F array: (h0(k), conj(h0(-k))) */
    unsigned omega_tex;          /* R32F array: w(|k|) */
    /* ping-pong: [pair][0] the A-side spectra, [pair][1] the B side;
     * the frame lands in pair 0 (2 log2 N passes after the spectrum's) */
    unsigned tex[2][2];
    unsigned fbo[2][REF_OCEAN_CASCADES_MAX];   /* pair p, layer c: MRT (A, B) */
    prog progs[OCEAN_PROGS];
    unif_set prog_unifs[OCEAN_PROGS];
    /* the foam, RG32F arrays (foam, the cascade's slope variance sigma_c^2,
     * the mean of hx^2 + hz^2 over the tile: waves.glsl's filtered normal
     * hands what it drops to the highlight), ping-pong; foam_cur holds the
     * frame's */
    unsigned foam_tex[2];
    unsigned foam_fbo[2][REF_OCEAN_CASCADES_MAX];
    int foam_cur;
    float slope_var[REF_OCEAN_CASCADES_MAX];
    double foam_t;               /* the time the foam holds */
    bool foam_valid;
    int foam_resets;             /* tests: updates that restarted from the coverage */
    double t;                    /* the time the textures hold */
    bool valid;                  /* they hold a frame */
    unsigned long long hash;     /* of the programs that drew it */
    int frames;                  /* frames computed (tests: a still frame runs no pass) */
} gpu_ocean;

/* Creates the textures from raw initial spectra: h0 is cascades * N * N
 * texels of 4 floats, omega cascades * N * N floats (ref_ocean_gpu_spectrum's
 * layout, cascade after cascade), and builds the pass programs from
 * src->common_dir (packs/common). False with a message in log on errors
 * (from: see prog_build). */
bool ocean_create(gpu_ocean *o, int cascades, int res, const float *tile, float lambda, const float *h0,
                  const float *omega, const prog_sources *src,  diag_list *log,
                  prog_origins *from);

/* The same from a built reference ocean (its resolved desc and
 * ref_ocean_gpu_spectrum): once per world build. */
bool ocean_create_from(gpu_ocean *o, const ref_ocean *ref, const prog_sources *src,
                        diag_list *log, prog_origins *from);

void ocean_free(gpu_ocean *o);

/* Rebuilds the pass programs (a shader file changed); false on errors. */
bool ocean_build_programs(gpu_ocean *o, const prog_sources *src, diag_list *log, prog_origins *from);

/* Computes the frame at time t unless the textures hold it already (and
 * the foam from the frame and the time step since the last), naming
 * the passes in timer (may be NULL), and leaves A and B bound at their
 * units. Binds framebuffer 0, changes the viewport and the program.
 * Returns whether it ran the passes. */
bool ocean_update(gpu_ocean *o, double t, gpu_timer *timer);

/* Reads the foam back: N * N * 2 floats (foam, sigma_c^2) of cascade c. */
void ocean_read_foam(const gpu_ocean *o, int c, float *foam);

/* Binds the frame's A and B at OCEAN_UNIT_A / OCEAN_UNIT_B and the foam at
 * OCEAN_UNIT_FOAM (nothing when inactive). */
void ocean_bind(const gpu_ocean *o);

/* Sets uOceanA / uOceanB / uOceanFoam of program p to their units, with or without an
 * ocean: every program that includes waves.glsl declares them, and two
 * samplers of different types left on unit 0 fail every draw. */
void ocean_upload(unsigned p);

/* Reads the frame back: a and b each N * N * 4 floats of cascade c. */
void ocean_read(const gpu_ocean *o, int c, float *a, float *b);

#endif
