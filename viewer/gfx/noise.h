/* noise: glman's built-in noise textures (Noise2D / Noise3D, samplers
 * Noise2 on unit 2 and Noise3 on unit 3).
 *
 * Each texture is tileable gradient (Perlin) noise; each channel is one
 * octave, centred on 0.5, with the standard deviation glman's own textures
 * have (measured on its noise2d.064.tex / noise3d.064.tex):
 *
 *   channel   periods over the texture   std 2D    std 3D
 *   R         4                          0.074     0.066
 *   G         8                          0.024     0.032
 *   B         16                         0.014     0.017
 *   A         32                         0.0070    0.0075
 *
 * Every channel's mean over the texture is 0.5. The result is the same on
 * every run (fixed seeds, no rand()).
 *
 * Texel (x, y[, z]) samples the noise at its centre, ((x + 0.5) / res) of a
 * period, so the texture wraps seamlessly with GL_REPEAT.
 */
#ifndef TARN_NOISE_H
#define TARN_NOISE_H

#include <stdbool.h>

#define NOISE_BASE_PERIODS 4    /* R channel: periods over the texture */
#define NOISE_2D_MAX_RES 4096
#define NOISE_3D_MAX_RES 400   /* glman allowed about 400 */

/* Fills rgba (res*res*4 floats, row-major, x fastest) with the 2D texture.
 * False (rgba untouched) for res < 1 or > NOISE_2D_MAX_RES, or NULL. */
bool noise_2d(int res, float *rgba);

/* Fills rgba (res*res*res*4 floats, x fastest, then y, then z).
 * False for res < 1 or > NOISE_3D_MAX_RES, or NULL. */
bool noise_3d(int res, float *rgba);

/* Raw gradient noise in lattice units, about -1..1 and 0 at lattice points.
 * Periodic in every axis with `period` lattice cells when period > 0
 * (f(x + period) == f(x)); not periodic when period <= 0. Different seeds
 * give independent noise. */
double noise_perlin2(double x, double y, int period, unsigned seed);
double noise_perlin3(double x, double y, double z, int period, unsigned seed);

#endif
