/* plot: a small raster plotter for reports, no dependencies: lines, discs
 * and rings with antialiasing, text in a built-in 5x7 pixel font, and the
 * speed-against-error chart of `tarn bench` (log-scale axes, a curve per
 * pack, the Pareto front marked, a legend). Images are 3-channel float
 * sRGB display values in 0..1, row 0 at the top, ready for img_write. */
#ifndef TARN_PLOT_H
#define TARN_PLOT_H

#include <stdbool.h>

#include "image_io.h"

/* Primitives on a 3-channel img; coordinates in pixels, (0, 0) the top-left
 * corner of the top-left pixel. */
void plot_fill(img *im, const float rgb[3]);
void plot_rect(img *im, double x0, double y0, double x1, double y1, const float rgb[3]);
/* A line of width w; dash > 0: dashes of that length with equal gaps. */
void plot_line(img *im, double x0, double y0, double x1, double y1, double w, double dash, const float rgb[3]);
void plot_disc(img *im, double cx, double cy, double r, const float rgb[3]);
void plot_ring(img *im, double cx, double cy, double r, double w, const float rgb[3]);

/* Text at (x, y) = its top-left corner, each font pixel scale x scale;
 * characters outside printable ASCII are drawn as '?'. Returns the width. */
int plot_text(img *im, int x, int y, const char *s, int scale, const float rgb[3]);
int plot_text_width(const char *s, int scale);
#define PLOT_GLYPH_W 6   /* advance, font pixels */
#define PLOT_GLYPH_H 9   /* 7 rows and 2 for descenders */

/* Marks the points not dominated by another (no other point is at most as
 * slow and at most as wrong, and better in one). Non-finite points are
 * never on the front. */
void plot_pareto(const double *x, const double *y, int n, bool *on_front);

/* The front with tolerances: j takes i off the front only when it is no
 * worse than i beyond their summed tolerances in both coordinates
 * (x[j] <= x[i] + dx[i] + dx[j], likewise y) and better beyond them in one.
 * Points within each other's tolerance tie and stay on the front together,
 * so noise below the tolerances cannot change the front. */
void plot_pareto_ties(const double *x, const double *y, const double *dx, const double *dy, int n,
                      bool *on_front);

/* The same with the errors' tolerances combined as uncertainties: i and j
 * tie in error when |y[i] - y[j]| <= sqrt(dy[i]^2 + dy[j]^2) (dy a standard
 * uncertainty of each), in time as in plot_pareto_ties (dx[i] + dx[j]: a
 * run-to-run spread, not independent between settings timed together). */
void plot_pareto_combined(const double *x, const double *y, const double *dx, const double *dy, int n,
                          bool *on_front);

typedef struct plot_point {
    double x, y;              /* time (> 0), error (> 0); non-finite: not drawn */
    const char *label;        /* drawn beside the point (may be NULL) */
    bool pareto;              /* on the front: ringed and joined by the front's line */
} plot_point;

typedef struct plot_series {
    const char *name;
    float rgb[3];
    const plot_point *pts;
    int n;
} plot_series;

typedef struct plot_chart {
    int w, h;                 /* 0: 1000 x 660 */
    const char *title, *subtitle, *xlabel, *ylabel;
    const plot_series *series;
    int nseries;
    double floor_x;           /* the cost floor, a dashed vertical line (<= 0: none) */
    const char *floor_label;
} plot_chart;

/* Draws the chart into out (allocated here, 3 channels; img_free it): both
 * axes logarithmic, each series' points joined in order of x in its colour,
 * points on the Pareto front ringed and the front drawn as a dashed
 * staircase, a legend. False when out of memory. */
bool plot_speed_error(const plot_chart *c, img *out);

#endif
