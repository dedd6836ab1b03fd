/* costmodel: a frame's time as a + b·Mpixels + c·kvertices, fitted by least
 * squares to frames timed at several image sizes and water-grid sizes, so
 * a user can predict what a setting costs at another resolution or mesh
 * (`tarn bench` fits one per pack and prints it with its report).
 *
 *   a   ms a frame whatever the size: passes into fixed-size targets,
 *       state changes, the CPU's share
 *   b   ms per million pixels of the image (fragment work)
 *   c   ms per thousand vertices of the water grid (vertex work, in every
 *       pass that draws the surface)
 *
 * The fit needs at least four samples spanning at least two pixel counts
 * and two vertex counts; r2 says how much of the times' variance the three
 * terms explain. */
#ifndef TARN_COSTMODEL_H
#define TARN_COSTMODEL_H

#include <stdbool.h>
#include <stddef.h>

typedef struct cost_sample {
    double mpixels;      /* image pixels / 1e6 */
    double kvertices;    /* water-grid vertices / 1e3 */
    double ms;           /* the frame's time (a median) */
} cost_sample;

typedef struct cost_model {
    double a, b, c;      /* ms, ms per Mpixel, ms per kvertex */
    double r2;           /* 1 - residual / total sum of squares */
    double rms_residual; /* ms */
    int n;               /* samples fitted */
} cost_model;

/* Fits out from n samples. False with the reason in err when the samples
 * cannot determine the three terms (too few, or all at one size or one
 * mesh, or a time that is not a finite positive number). */
bool cost_model_fit(const cost_sample *s, int n, cost_model *out, char *err, size_t errlen);

/* The model's time for a frame of mpixels and kvertices, ms. */
double cost_model_predict(const cost_model *m, double mpixels, double kvertices);

/* The water grid's vertex count, in thousands, for `WaterMesh n`: (n+1)². */
double cost_model_grid_kvertices(int n);

#endif
