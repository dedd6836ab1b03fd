/* ref_wavefx: two height-only wave models in double precision, twins of
 * packs/common/waves_fx.glsl (float): an explosion ring (the lake-water
 * seed 001, "[UVTDFRWR]") and 3D Perlin wave sets (the RIT report, seed
 * 002: octaves of Perlin noise in (x, z, time) with a stretch factor).
 * Neither moves points sideways, so neither changes how a world point is
 * inverted to its rest point; both give a height and its gradient in the
 * rest coordinates (u, v).
 *
 * Explosion ring (centre c, start t0, I0, omega, k, decay b):
 *     tau = t - t0; no wave for tau <= 0
 *     r = |(u, v) - c|,  s = sqrt(r^2 + 1/k^2)     (smooth at r = 0)
 *     R = (omega / k) tau                          (the front, at the phase speed)
 *     E = 1 - fade(clamp((s - R + W) / W, 0, 1)),  W = 2 pi / k   (quintic fade)
 *     h = I0 e^{-b tau} E sin(k s - omega tau) / sqrt(k s)
 * so the ring is born flat at tau = 0 (h = 0 until R reaches s's least
 * value 1/k, at tau = 1/omega), spreads at omega / k behind a smooth front
 * one wavelength wide, loses amplitude as 1/sqrt(r) (energy spread on a
 * growing circle) and e^{-b tau} (damping), and is C2 everywhere: every
 * term is a function of s, which is smooth in (u, v) (r alone, or
 * sqrt(1 + k r), would put a cone at the centre), and the gradient is 0 at
 * r = 0. (s - R + W) / W = 1 + (k s - omega tau) / 2 pi: the envelope is a
 * function of the phase.
 *
 * Perlin set (amplitude A, cell, octaves, gain g, stretch, angle, rate, seed):
 *     (a, c) = the rest point in the wind's frame: a along angle, c across
 *     octave o: f_o = 2^o / cell, A_o = A g^o, rate_o = rate sqrt(2^o)
 *               (lattice units a second; deep water: omega ~ sqrt(k)),
 *               seed_o = hash(seed + o 0x9E3779B9)
 *     h = sum_o A_o noise3(a f_o, c f_o / stretch, t rate_o, seed_o)
 * where noise3 is Perlin's improved gradient noise (2002: quintic fade,
 * gradients from the 12 cube edges picked by tarn's lowbias32 hash of the
 * lattice point and the octave's seed: hash(X + hash(Y + hash(Z + seed)))
 * % 12), in [-1, 1] in practice (|noise3| <= 1.0364 for any hash; see
 * ref_wavefx.c). A stretch > 1 draws crests long across the wind (the
 * correlation length across is stretch times that along), as the report's
 * stretch factor does.
 *
 * Descs: zero means default (ref_wavefx_resolve_* fill them in one place).
 */
#ifndef TARN_REF_WAVEFX_H
#define TARN_REF_WAVEFX_H

#include <stddef.h>
#include <stdint.h>

#include "ref_uniform.h"

#define REF_EXPLOSIONS_MAX 4
#define REF_PERLIN_OCTAVES_MAX 8

typedef struct ref_explosion_desc {
    double center[2];      /* (x, z) */
    double start;          /* t0, seconds */
    double i0;             /* initial amplitude, m; 0: no ring */
    double omega;          /* rad/s; 0: deep water sqrt(g k) */
    double k;              /* rad/m; 0: 2 pi (a 1 m wavelength) */
    double decay;          /* b, 1/s; 0: none */
} ref_explosion_desc;

typedef struct ref_perlin_desc {
    double amplitude;      /* of octave 0, m; 0: no Perlin set */
    double cell;           /* lattice cell of octave 0, m; 0: 4 */
    int octaves;           /* 0: 4 */
    double gain;           /* 0: 0.5 */
    double stretch;        /* 0: 1 */
    double angle_deg;      /* the wind's direction, from +x towards +z */
    double rate;           /* lattice cells a second along time at octave 0; 0: 0.5 */
    uint32_t seed;
} ref_perlin_desc;

/* Fill the defaults; -1 with a message for non-finite values, a negative
 * k, omega, cell, stretch or decay, or octaves out of 1..REF_PERLIN_OCTAVES_MAX. */
int ref_explosion_resolve(ref_explosion_desc *e, char *err, size_t errlen);
int ref_perlin_resolve(ref_perlin_desc *p, char *err, size_t errlen);

/* Height (relative to the level) and, when grad is not NULL, its gradient
 * in (u, v), of one resolved ring / set. */
double ref_explosion_height(const ref_explosion_desc *e, double u, double v, double t, double grad[2]);
double ref_perlin_height(const ref_perlin_desc *p, double u, double v, double t, double grad[2]);

/* Bounds at every time: |h| and |grad h| (derived in ref_wavefx.c):
 * ring |I0| and 1.2797 |I0| k; set 1.04 sum|A_o| and
 * 15 sqrt(2)/4 max(1, 1/stretch) sum |A_o| f_o. */
void ref_explosion_bounds(const ref_explosion_desc *e, double *height, double *slope);
void ref_perlin_bounds(const ref_perlin_desc *p, double *height, double *slope);

/* Raw 3D improved Perlin noise at lattice coordinates (x, y, z) with its
 * gradient (may be NULL); the GLSL's wavesPerlin3 is the same function. */
double ref_perlin3(double x, double y, double z, uint32_t seed, double grad[3]);

/* The uniforms packs/common/waves_fx.glsl reads for n resolved rings and
 * one resolved Perlin set (amplitude 0 or p NULL: none): returns how many
 * were written (at most max; REF_WAVEFX_UNIFORMS_MAX fits all):
 *   int  uExplosionN                 rings with I0 != 0 (the first 4)
 *   vec4 uExplosion[4]               (centre x, centre z, t0, I0)
 *   vec4 uExplosionWave[4]           (omega, k, decay, k^2)
 *   int  uPerlinN                    octaves (0: no set)
 *   vec4 uPerlinOctave[8]            (f_o, rate_o, A_o, 0)
 *   vec4 uPerlinFrame                (cos angle, sin angle, 1 / stretch, 0)
 *   uint uPerlinSeed[8]              seed_o */
#define REF_WAVEFX_UNIFORMS_MAX 8
int ref_wavefx_uniforms(const ref_explosion_desc *e, int n, const ref_perlin_desc *p,
                        ref_waves_uniform *out, int max);

#endif
