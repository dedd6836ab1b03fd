/* plot: raster primitives, a 5x7 font and the speed-against-error chart. */
#include "plot.h"
#include "mem.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the font: printable ASCII 32..126, 7 rows of 5 bits (bit 4 = left) */

static const unsigned char font5x7[95][7] = {
    {0x00,0x00,0x00,0x00,0x00,0x00,0x00}, {0x04,0x04,0x04,0x04,0x04,0x00,0x04}, /* space ! */
    {0x0A,0x0A,0x00,0x00,0x00,0x00,0x00}, {0x0A,0x0A,0x1F,0x0A,0x1F,0x0A,0x0A}, /* " # */
    {0x04,0x0F,0x14,0x0E,0x05,0x1E,0x04}, {0x18,0x19,0x02,0x04,0x08,0x13,0x03}, /* $ % */
    {0x0C,0x12,0x14,0x08,0x15,0x12,0x0D}, {0x04,0x04,0x00,0x00,0x00,0x00,0x00}, /* & ' */
    {0x02,0x04,0x08,0x08,0x08,0x04,0x02}, {0x08,0x04,0x02,0x02,0x02,0x04,0x08}, /* ( ) */
    {0x00,0x04,0x15,0x0E,0x15,0x04,0x00}, {0x00,0x04,0x04,0x1F,0x04,0x04,0x00}, /* * + */
    {0x00,0x00,0x00,0x00,0x0C,0x04,0x08}, {0x00,0x00,0x00,0x1F,0x00,0x00,0x00}, /* , - */
    {0x00,0x00,0x00,0x00,0x00,0x0C,0x0C}, {0x00,0x01,0x02,0x04,0x08,0x10,0x00}, /* . / */
    {0x0E,0x11,0x13,0x15,0x19,0x11,0x0E}, {0x04,0x0C,0x04,0x04,0x04,0x04,0x0E}, /* 0 1 */
    {0x0E,0x11,0x01,0x02,0x04,0x08,0x1F}, {0x1F,0x02,0x04,0x02,0x01,0x11,0x0E}, /* 2 3 */
    {0x02,0x06,0x0A,0x12,0x1F,0x02,0x02}, {0x1F,0x10,0x1E,0x01,0x01,0x11,0x0E}, /* 4 5 */
    {0x06,0x08,0x10,0x1E,0x11,0x11,0x0E}, {0x1F,0x01,0x02,0x04,0x08,0x08,0x08}, /* 6 7 */
    {0x0E,0x11,0x11,0x0E,0x11,0x11,0x0E}, {0x0E,0x11,0x11,0x0F,0x01,0x02,0x0C}, /* 8 9 */
    {0x00,0x0C,0x0C,0x00,0x0C,0x0C,0x00}, {0x00,0x0C,0x0C,0x00,0x0C,0x04,0x08}, /* : ; */
    {0x02,0x04,0x08,0x10,0x08,0x04,0x02}, {0x00,0x00,0x1F,0x00,0x1F,0x00,0x00}, /* < = */
    {0x08,0x04,0x02,0x01,0x02,0x04,0x08}, {0x0E,0x11,0x01,0x02,0x04,0x00,0x04}, /* > ? */
    {0x0E,0x11,0x17,0x15,0x17,0x10,0x0E},                                       /* @ */
    {0x0E,0x11,0x11,0x1F,0x11,0x11,0x11}, {0x1E,0x11,0x11,0x1E,0x11,0x11,0x1E}, /* A B */
    {0x0E,0x11,0x10,0x10,0x10,0x11,0x0E}, {0x1C,0x12,0x11,0x11,0x11,0x12,0x1C}, /* C D */
    {0x1F,0x10,0x10,0x1E,0x10,0x10,0x1F}, {0x1F,0x10,0x10,0x1E,0x10,0x10,0x10}, /* E F */
    {0x0E,0x11,0x10,0x17,0x11,0x11,0x0F}, {0x11,0x11,0x11,0x1F,0x11,0x11,0x11}, /* G H */
    {0x0E,0x04,0x04,0x04,0x04,0x04,0x0E}, {0x07,0x02,0x02,0x02,0x02,0x12,0x0C}, /* I J */
    {0x11,0x12,0x14,0x18,0x14,0x12,0x11}, {0x10,0x10,0x10,0x10,0x10,0x10,0x1F}, /* K L */
    {0x11,0x1B,0x15,0x15,0x11,0x11,0x11}, {0x11,0x11,0x19,0x15,0x13,0x11,0x11}, /* M N */
    {0x0E,0x11,0x11,0x11,0x11,0x11,0x0E}, {0x1E,0x11,0x11,0x1E,0x10,0x10,0x10}, /* O P */
    {0x0E,0x11,0x11,0x11,0x15,0x12,0x0D}, {0x1E,0x11,0x11,0x1E,0x14,0x12,0x11}, /* Q R */
    {0x0F,0x10,0x10,0x0E,0x01,0x01,0x1E}, {0x1F,0x04,0x04,0x04,0x04,0x04,0x04}, /* S T */
    {0x11,0x11,0x11,0x11,0x11,0x11,0x0E}, {0x11,0x11,0x11,0x11,0x11,0x0A,0x04}, /* U V */
    {0x11,0x11,0x11,0x15,0x15,0x15,0x0A}, {0x11,0x11,0x0A,0x04,0x0A,0x11,0x11}, /* W X */
    {0x11,0x11,0x11,0x0A,0x04,0x04,0x04}, {0x1F,0x01,0x02,0x04,0x08,0x10,0x1F}, /* Y Z */
    {0x0E,0x08,0x08,0x08,0x08,0x08,0x0E}, {0x00,0x10,0x08,0x04,0x02,0x01,0x00}, /* [ \ */
    {0x0E,0x02,0x02,0x02,0x02,0x02,0x0E}, {0x04,0x0A,0x11,0x00,0x00,0x00,0x00}, /* ] ^ */
    {0x00,0x00,0x00,0x00,0x00,0x00,0x1F}, {0x08,0x04,0x00,0x00,0x00,0x00,0x00}, /* _ ` */
    {0x00,0x00,0x0E,0x01,0x0F,0x11,0x0F}, {0x10,0x10,0x16,0x19,0x11,0x11,0x1E}, /* a b */
    {0x00,0x00,0x0E,0x10,0x10,0x11,0x0E}, {0x01,0x01,0x0D,0x13,0x11,0x11,0x0F}, /* c d */
    {0x00,0x00,0x0E,0x11,0x1F,0x10,0x0E}, {0x06,0x09,0x08,0x1C,0x08,0x08,0x08}, /* e f */
    {0x00,0x0F,0x11,0x11,0x0F,0x01,0x0E}, {0x10,0x10,0x16,0x19,0x11,0x11,0x11}, /* g h */
    {0x04,0x00,0x0C,0x04,0x04,0x04,0x0E}, {0x02,0x00,0x06,0x02,0x02,0x12,0x0C}, /* i j */
    {0x10,0x10,0x12,0x14,0x18,0x14,0x12}, {0x0C,0x04,0x04,0x04,0x04,0x04,0x0E}, /* k l */
    {0x00,0x00,0x1A,0x15,0x15,0x11,0x11}, {0x00,0x00,0x16,0x19,0x11,0x11,0x11}, /* m n */
    {0x00,0x00,0x0E,0x11,0x11,0x11,0x0E}, {0x00,0x1E,0x11,0x11,0x1E,0x10,0x10}, /* o p */
    {0x00,0x0F,0x11,0x11,0x0F,0x01,0x01}, {0x00,0x00,0x16,0x19,0x10,0x10,0x10}, /* q r */
    {0x00,0x00,0x0F,0x10,0x0E,0x01,0x1E}, {0x08,0x08,0x1C,0x08,0x08,0x09,0x06}, /* s t */
    {0x00,0x00,0x11,0x11,0x11,0x13,0x0D}, {0x00,0x00,0x11,0x11,0x11,0x0A,0x04}, /* u v */
    {0x00,0x00,0x11,0x11,0x15,0x15,0x0A}, {0x00,0x00,0x11,0x0A,0x04,0x0A,0x11}, /* w x */
    {0x00,0x11,0x11,0x11,0x0F,0x01,0x0E}, {0x00,0x00,0x1F,0x02,0x04,0x08,0x1F}, /* y z */
    {0x02,0x04,0x04,0x08,0x04,0x04,0x02}, {0x04,0x04,0x04,0x04,0x04,0x04,0x04}, /* { | */
    {0x08,0x04,0x04,0x02,0x04,0x04,0x08}, {0x00,0x00,0x08,0x15,0x02,0x00,0x00}, /* } ~ */
};

/* Lower-case letters with descenders: 9 rows (the x-height starts at row 2,
 * like the other lower-case letters, and rows 7 and 8 hang below). */
static const struct { char c; unsigned char rows[9]; } descenders[] = {
    { 'g', {0x00,0x00,0x0F,0x11,0x11,0x11,0x0F,0x01,0x0E} },
    { 'j', {0x02,0x00,0x06,0x02,0x02,0x02,0x02,0x12,0x0C} },
    { 'p', {0x00,0x00,0x1E,0x11,0x11,0x11,0x1E,0x10,0x10} },
    { 'q', {0x00,0x00,0x0F,0x11,0x11,0x11,0x0F,0x01,0x01} },
    { 'y', {0x00,0x00,0x11,0x11,0x11,0x11,0x0F,0x01,0x0E} },
};

/* ---- primitives ---- */

static void blend(img *im, int x, int y, const float rgb[3], double a) {
    if (x < 0 || y < 0 || x >= im->w || y >= im->h || !(a > 0)) return;
    if (a > 1) a = 1;
    float *p = im->px + ((size_t)y * im->w + x) * im->channels;
    for (int k = 0; k < 3; k++) p[k] = (float)(p[k] * (1 - a) + rgb[k] * a);
}

void plot_fill(img *im, const float rgb[3]) {
    for (long i = 0; i < (long)im->w * im->h; i++)
        for (int k = 0; k < 3; k++) im->px[i * im->channels + k] = rgb[k];
}

void plot_rect(img *im, double x0, double y0, double x1, double y1, const float rgb[3]) {
    for (int y = (int)floor(y0); y < (int)ceil(y1); y++)
        for (int x = (int)floor(x0); x < (int)ceil(x1); x++) blend(im, x, y, rgb, 1.0);
}

void plot_line(img *im, double x0, double y0, double x1, double y1, double w, double dash, const float rgb[3]) {
    double dx = x1 - x0, dy = y1 - y0, len2 = dx * dx + dy * dy, len = sqrt(len2), hw = w / 2;
    int bx0 = (int)floor(fmin(x0, x1) - hw - 1), bx1 = (int)ceil(fmax(x0, x1) + hw + 1);
    int by0 = (int)floor(fmin(y0, y1) - hw - 1), by1 = (int)ceil(fmax(y0, y1) + hw + 1);
    if (bx0 < 0) bx0 = 0;
    if (by0 < 0) by0 = 0;
    if (bx1 > im->w) bx1 = im->w;
    if (by1 > im->h) by1 = im->h;
    for (int y = by0; y < by1; y++)
        for (int x = bx0; x < bx1; x++) {
            double px = x + 0.5 - x0, py = y + 0.5 - y0;
            double t = len2 > 0 ? (px * dx + py * dy) / len2 : 0;
            if (t < 0) t = 0;
            if (t > 1) t = 1;
            if (dash > 0 && fmod(t * len, 2 * dash) > dash) continue;
            double ex = px - t * dx, ey = py - t * dy, d = sqrt(ex * ex + ey * ey);
            blend(im, x, y, rgb, hw + 0.5 - d);
        }
}

void plot_disc(img *im, double cx, double cy, double r, const float rgb[3]) {
    for (int y = (int)floor(cy - r - 1); y <= (int)ceil(cy + r + 1); y++)
        for (int x = (int)floor(cx - r - 1); x <= (int)ceil(cx + r + 1); x++) {
            double d = hypot(x + 0.5 - cx, y + 0.5 - cy);
            blend(im, x, y, rgb, r + 0.5 - d);
        }
}

void plot_ring(img *im, double cx, double cy, double r, double w, const float rgb[3]) {
    for (int y = (int)floor(cy - r - w - 1); y <= (int)ceil(cy + r + w + 1); y++)
        for (int x = (int)floor(cx - r - w - 1); x <= (int)ceil(cx + r + w + 1); x++) {
            double d = fabs(hypot(x + 0.5 - cx, y + 0.5 - cy) - r);
            blend(im, x, y, rgb, w / 2 + 0.5 - d);
        }
}

int plot_text_width(const char *s, int scale) {
    return s ? (int)strlen(s) * PLOT_GLYPH_W * scale : 0;
}

int plot_text(img *im, int x, int y, const char *s, int scale, const float rgb[3]) {
    if (!s) return 0;
    int cx = x;
    for (const unsigned char *c = (const unsigned char *)s; *c; c++) {
        int g = *c >= 32 && *c <= 126 ? *c - 32 : '?' - 32;
        const unsigned char *rows = font5x7[g];
        int nrows = 7;
        for (size_t d = 0; d < sizeof descenders / sizeof descenders[0]; d++)
            if (descenders[d].c == (char)*c) { rows = descenders[d].rows; nrows = 9; }
        for (int row = 0; row < nrows; row++)
            for (int col = 0; col < 5; col++)
                if (rows[row] & (0x10 >> col))
                    for (int sy = 0; sy < scale; sy++)
                        for (int sx = 0; sx < scale; sx++)
                            blend(im, cx + col * scale + sx, y + row * scale + sy, rgb, 1.0);
        cx += PLOT_GLYPH_W * scale;
    }
    return cx - x;
}

void plot_pareto(const double *x, const double *y, int n, bool *on_front) {
    for (int i = 0; i < n; i++) {
        on_front[i] = isfinite(x[i]) && isfinite(y[i]);
        for (int j = 0; j < n && on_front[i]; j++) {
            if (j == i || !isfinite(x[j]) || !isfinite(y[j])) continue;
            bool no_worse = x[j] <= x[i] && y[j] <= y[i];
            bool better = x[j] < x[i] || y[j] < y[i];
            if (no_worse && better) on_front[i] = false;
        }
    }
}

void plot_pareto_ties(const double *x, const double *y, const double *dx, const double *dy, int n,
                      bool *on_front) {
    for (int i = 0; i < n; i++) {
        on_front[i] = isfinite(x[i]) && isfinite(y[i]);
        for (int j = 0; j < n && on_front[i]; j++) {
            if (j == i || !isfinite(x[j]) || !isfinite(y[j])) continue;
            double tx = dx[i] + dx[j], ty = dy[i] + dy[j];
            bool no_worse = x[j] <= x[i] + tx && y[j] <= y[i] + ty;
            bool better = x[j] < x[i] - tx || y[j] < y[i] - ty;
            if (no_worse && better) on_front[i] = false;
        }
    }
}

/* ---- the chart ---- */

typedef struct axis {
    double lo, hi;            /* log10 of the range shown */
    double p0, p1;            /* pixel positions of lo and hi */
} axis;

static double axis_px(const axis *a, double v) {
    return a->p0 + (log10(v) - a->lo) / (a->hi - a->lo) * (a->p1 - a->p0);
}

static void axis_range(axis *a, double vmin, double vmax) {
    if (!(vmin > 0) || !(vmax > 0)) { vmin = 1; vmax = 10; }
    double lo = log10(vmin), hi = log10(vmax);
    if (hi - lo < 0.3) {   /* at least a factor of 2 shown */
        double mid = (lo + hi) / 2;
        lo = mid - 0.15;
        hi = mid + 0.15;
    }
    double pad = (hi - lo) * 0.08;
    a->lo = lo - pad;
    a->hi = hi + pad;
}

static void fmt_tick(double v, char *buf, size_t n) {
    if (v >= 1e4 || v < 1e-3) snprintf(buf, n, "%.0e", v);
    else snprintf(buf, n, "%.3g", v);
}

/* Ticks at 1, 2, 5 x 10^k (only 1 x 10^k when the range spans many decades). */
static int ticks(const axis *a, double *out, int max) {
    int n = 0;
    static const double coarse[] = { 1, 2, 5 }, fine[] = { 1, 1.5, 2, 3, 4, 5, 6, 7, 8, 9 };
    double span = a->hi - a->lo;
    const double *steps = span > 3 ? coarse : span > 1.2 ? coarse : fine;
    int nsteps = span > 3 ? 1 : span > 1.2 ? 3 : 10;
    for (int e = (int)floor(a->lo); e <= (int)ceil(a->hi) && n < max; e++)
        for (int s = 0; s < nsteps && n < max; s++) {
            double v = steps[s] * pow(10, e), l = log10(v);
            if (l >= a->lo && l <= a->hi) out[n++] = v;
        }
    return n;
}

static int cmp_x(const void *a, const void *b) {
    double x = ((const plot_point *)a)->x, y = ((const plot_point *)b)->x;
    return (x > y) - (x < y);
}

static const float ink[3] = { 0.1f, 0.1f, 0.12f }, grid_rgb[3] = { 0.88f, 0.88f, 0.9f },
                   grey_rgb[3] = { 0.45f, 0.45f, 0.48f };

static bool drawable(const plot_point *p) {
    return p->x > 0 && p->y > 0 && isfinite(p->x) && isfinite(p->y);
}

/* One chart being drawn: its axes and the points placed so far (for the
 * labels and the legend to avoid). */
typedef struct chart {
    const plot_chart *c;
    img *out;
    int W, H, left, top;
    axis ax, ay;
    double *px;               /* placed points, x y pairs */
    const char **labels;      /* their labels */
    int nplaced;
} chart;

/* The axes' ranges from the drawable points and the floor. */
static void chart_axes(chart *k) {
    const plot_chart *c = k->c;
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    int npts = 0;
    for (int s = 0; s < c->nseries; s++)
        for (int i = 0; i < c->series[s].n; i++) {
            const plot_point *p = &c->series[s].pts[i];
            if (!drawable(p)) continue;
            xmin = fmin(xmin, p->x);
            xmax = fmax(xmax, p->x);
            ymin = fmin(ymin, p->y);
            ymax = fmax(ymax, p->y);
            npts++;
        }
    if (c->floor_x > 0 && isfinite(c->floor_x)) {
        xmin = fmin(xmin, c->floor_x);
        xmax = fmax(xmax, c->floor_x);
    }
    if (!npts) { ymin = 0.01; ymax = 0.1; }
    if (!isfinite(xmin)) { xmin = 1; xmax = 10; }
    k->left = 96;
    k->top = c->subtitle ? 92 : 70;
    int right = 28, bottom = 74;
    k->ax = (axis){ .p0 = k->left, .p1 = k->W - right };
    k->ay = (axis){ .p0 = k->H - bottom, .p1 = k->top };
    axis_range(&k->ax, xmin, xmax);
    axis_range(&k->ay, ymin, ymax);
}

/* The grid and tick labels (a label that would touch the previous one is
 * left out), then the axes' lines. */
static void chart_grid(const chart *k) {
    img *out = k->out;
    const axis *ax = &k->ax, *ay = &k->ay;
    double tv[64];
    char buf[64];
    int nt = ticks(ax, tv, 64);
    double last_right = -1e9;
    for (int i = 0; i < nt; i++) {
        double x = axis_px(ax, tv[i]);
        plot_line(out, x, ay->p1, x, ay->p0, 1, 0, grid_rgb);
        plot_line(out, x, ay->p0, x, ay->p0 + 6, 1.5, 0, ink);
        fmt_tick(tv[i], buf, sizeof buf);
        double lx = x - plot_text_width(buf, 2) / 2.0;
        if (lx < last_right + 10) continue;
        plot_text(out, (int)lx, (int)ay->p0 + 12, buf, 2, ink);
        last_right = lx + plot_text_width(buf, 2);
    }
    nt = ticks(ay, tv, 64);
    double last_y = 1e9;
    for (int i = 0; i < nt; i++) {
        double y = axis_px(ay, tv[i]);
        plot_line(out, ax->p0, y, ax->p1, y, 1, 0, grid_rgb);
        plot_line(out, ax->p0 - 6, y, ax->p0, y, 1.5, 0, ink);
        if (last_y - y < 22) continue;
        fmt_tick(tv[i], buf, sizeof buf);
        plot_text(out, (int)ax->p0 - 10 - plot_text_width(buf, 2), (int)y - 7, buf, 2, ink);
        last_y = y;
    }
    plot_line(out, ax->p0, ay->p0, ax->p1, ay->p0, 2, 0, ink);
    plot_line(out, ax->p0, ay->p0, ax->p0, ay->p1, 2, 0, ink);
}

/* Titles, axis labels and the cost floor. */
static void chart_titles(const chart *k) {
    const plot_chart *c = k->c;
    img *out = k->out;
    if (c->title) plot_text(out, k->left, 14, c->title, 2, ink);
    if (c->subtitle) plot_text(out, k->left, 38, c->subtitle, 2, grey_rgb);
    if (c->xlabel)
        plot_text(out, (int)((k->ax.p0 + k->ax.p1) / 2 - plot_text_width(c->xlabel, 2) / 2.0), k->H - 30, c->xlabel,
                  2, ink);
    if (c->ylabel)   /* vertical text is hard to read in a pixel font: above the axis */
        plot_text(out, 12, k->top - 24, c->ylabel, 2, ink);
    if (c->floor_x > 0 && isfinite(c->floor_x)) {
        double x = axis_px(&k->ax, c->floor_x);
        plot_line(out, x, k->ay.p1, x, k->ay.p0, 1.5, 6, grey_rgb);
        if (c->floor_label) plot_text(out, (int)x + 5, (int)k->ay.p1 + 4, c->floor_label, 1, grey_rgb);
    }
}

/* The Pareto front: a staircase through the ringed points, by time. */
static void chart_front(const chart *k) {
    const plot_chart *c = k->c;
    plot_point front[256];
    int nf = 0;
    for (int s = 0; s < c->nseries; s++)
        for (int i = 0; i < c->series[s].n && nf < 256; i++)
            if (c->series[s].pts[i].pareto) front[nf++] = c->series[s].pts[i];
    qsort(front, (size_t)nf, sizeof *front, cmp_x);
    for (int i = 0; i + 1 < nf; i++) {
        double x0 = axis_px(&k->ax, front[i].x), y0 = axis_px(&k->ay, front[i].y);
        double x1 = axis_px(&k->ax, front[i + 1].x), y1 = axis_px(&k->ay, front[i + 1].y);
        plot_line(k->out, x0, y0, x1, y0, 1.5, 5, ink);
        plot_line(k->out, x1, y0, x1, y1, 1.5, 5, ink);
    }
}

/* One series: its curve by time, then its points, each placed. */
static void chart_series(chart *k, const plot_series *se) {
    plot_point *sorted = mem_alloc((size_t)(se->n > 0 ? se->n : 1) * sizeof *sorted);
    int n = 0;
    for (int i = 0; i < se->n; i++)
        if (drawable(&se->pts[i])) sorted[n++] = se->pts[i];
    qsort(sorted, (size_t)n, sizeof *sorted, cmp_x);
    const axis *ax = &k->ax, *ay = &k->ay;
    for (int i = 0; i + 1 < n; i++)
        plot_line(k->out, axis_px(ax, sorted[i].x), axis_px(ay, sorted[i].y), axis_px(ax, sorted[i + 1].x),
                  axis_px(ay, sorted[i + 1].y), 2.5, 0, se->rgb);
    for (int i = 0; i < n; i++) {
        double x = axis_px(ax, sorted[i].x), y = axis_px(ay, sorted[i].y);
        plot_disc(k->out, x, y, 6, ink);
        plot_disc(k->out, x, y, 4.8, se->rgb);
        if (sorted[i].pareto) plot_ring(k->out, x, y, 10, 2, ink);
        k->px[k->nplaced * 2] = x;
        k->px[k->nplaced * 2 + 1] = y;
        k->labels[k->nplaced++] = sorted[i].label;
    }
    free(sorted);
}

/* Whether a label's box at (x0, y0) lies inside the plot and clear of the
 * boxes placed before and of every point. */
static bool label_clear(const chart *k, double x0, double y0, double tw, double th, double (*rects)[4],
                        int nrects) {
    bool clear = x0 >= k->ax.p0 && x0 + tw <= k->W && y0 >= k->ay.p1 && y0 + th <= k->ay.p0;
    for (int r = 0; r < nrects && clear; r++)
        clear = x0 + tw < rects[r][0] || x0 > rects[r][2] || y0 + th < rects[r][1] || y0 > rects[r][3];
    for (int p = 0; p < k->nplaced && clear; p++)
        clear = k->px[p * 2] + 7 < x0 || k->px[p * 2] - 7 > x0 + tw || k->px[p * 2 + 1] + 7 < y0 ||
                k->px[p * 2 + 1] - 7 > y0 + th;
    return clear;
}

/* Labels: the first of eight places around the point that overlaps no
 * label placed before and no point (else the first place). */
static void chart_labels(const chart *k) {
    double (*rects)[4] = mem_alloc((size_t)(k->nplaced > 0 ? k->nplaced : 1) * sizeof *rects);
    int nrects = 0;
    for (int i = 0; i < k->nplaced; i++) {
        if (!k->labels[i]) continue;
        double tw = plot_text_width(k->labels[i], 1), th = PLOT_GLYPH_H;
        const double off[8][2] = { { 12, -12 }, { 12, 4 }, { -12 - tw, -12 }, { -12 - tw, 4 },
                                   { -tw / 2, -22 }, { -tw / 2, 12 }, { 14, -4 }, { -14 - tw, -4 } };
        int best = 0;
        for (int q = 0; q < 8; q++)
            if (label_clear(k, k->px[i * 2] + off[q][0], k->px[i * 2 + 1] + off[q][1], tw, th, rects, nrects)) {
                best = q;
                break;
            }
        double x0 = k->px[i * 2] + off[best][0], y0 = k->px[i * 2 + 1] + off[best][1];
        rects[nrects][0] = x0 - 2;
        rects[nrects][1] = y0 - 2;
        rects[nrects][2] = x0 + tw + 2;
        rects[nrects][3] = y0 + th + 2;
        nrects++;
        plot_text(k->out, (int)x0, (int)y0, k->labels[i], 1, grey_rgb);
    }
    free(rects);
}

/* The legend, inside the plot in the corner with the fewest points. */
static void chart_legend(const chart *k) {
    const plot_chart *c = k->c;
    img *out = k->out;
    int lw = plot_text_width("Pareto front", 2);
    for (int s = 0; s < c->nseries; s++) {
        int tw = plot_text_width(c->series[s].name, 2);
        if (tw > lw) lw = tw;
    }
    int rows = c->nseries + 1, lwid = lw + 52, lhei = rows * 24 + 10;
    int lx0 = (int)k->ax.p1 - 10 - lwid, ly0 = (int)k->ay.p1 + 10, fewest = k->nplaced + 1;
    for (int corner = 0; corner < 4; corner++) {
        int cx0 = corner & 1 ? (int)k->ax.p0 + 10 : (int)k->ax.p1 - 10 - lwid;
        int cy0 = corner & 2 ? (int)k->ay.p0 - 10 - lhei : (int)k->ay.p1 + 10;
        int inside = 0;
        for (int p = 0; p < k->nplaced; p++)
            inside += k->px[p * 2] > cx0 - 8 && k->px[p * 2] < cx0 + lwid + 8 && k->px[p * 2 + 1] > cy0 - 8 &&
                      k->px[p * 2 + 1] < cy0 + lhei + 8;
        if (inside < fewest) { fewest = inside; lx0 = cx0; ly0 = cy0; }
    }
    int lx1 = lx0 + lwid;
    const float frame[3] = { 0.7f, 0.7f, 0.72f }, bg[3] = { 0.98f, 0.98f, 0.98f };
    plot_rect(out, lx0, ly0, lx1, ly0 + rows * 24 + 10, frame);
    plot_rect(out, lx0 + 1, ly0 + 1, lx1 - 1, ly0 + rows * 24 + 9, bg);
    for (int s = 0; s < c->nseries; s++) {
        int y = ly0 + 10 + s * 24;
        plot_line(out, lx0 + 8, y + 7, lx0 + 36, y + 7, 2.5, 0, c->series[s].rgb);
        plot_disc(out, lx0 + 22, y + 7, 5, ink);
        plot_disc(out, lx0 + 22, y + 7, 3.8, c->series[s].rgb);
        plot_text(out, lx0 + 44, y, c->series[s].name, 2, ink);
    }
    int y = ly0 + 10 + c->nseries * 24;
    plot_ring(out, lx0 + 22, y + 7, 8, 2, ink);
    plot_line(out, lx0 + 4, y + 7, lx0 + 12, y + 7, 1.5, 0, ink);
    plot_line(out, lx0 + 32, y + 7, lx0 + 40, y + 7, 1.5, 0, ink);
    plot_text(out, lx0 + 44, y, "Pareto front", 2, ink);
}

bool plot_speed_error(const plot_chart *c, img *out) {
    chart k = { .c = c, .out = out, .W = c->w > 0 ? c->w : 1000, .H = c->h > 0 ? c->h : 660 };
    memset(out, 0, sizeof *out);
    if (!img_alloc(out, k.W, k.H, 3)) return false;
    const float white[3] = { 1, 1, 1 };
    plot_fill(out, white);
    chart_axes(&k);
    chart_grid(&k);
    chart_titles(&k);
    chart_front(&k);
    int total = 0;
    for (int s = 0; s < c->nseries; s++) total += c->series[s].n;
    k.px = mem_alloc((size_t)(total > 0 ? total : 1) * 2 * sizeof *k.px);
    k.labels = mem_alloc((size_t)(total > 0 ? total : 1) * sizeof *k.labels);
    for (int s = 0; s < c->nseries; s++) chart_series(&k, &c->series[s]);
    chart_labels(&k);
    chart_legend(&k);
    free(k.px);
    free(k.labels);
    return true;
}

void plot_pareto_combined(const double *x, const double *y, const double *dx, const double *dy, int n,
                          bool *on_front) {
    for (int i = 0; i < n; i++) {
        on_front[i] = isfinite(x[i]) && isfinite(y[i]);
        for (int j = 0; j < n && on_front[i]; j++) {
            if (j == i || !isfinite(x[j]) || !isfinite(y[j])) continue;
            double tx = dx[i] + dx[j], ty = sqrt(dy[i] * dy[i] + dy[j] * dy[j]);
            bool no_worse = x[j] <= x[i] + tx && y[j] <= y[i] + ty;
            bool better = x[j] < x[i] - tx || y[j] < y[i] - ty;
            if (no_worse && better) on_front[i] = false;
        }
    }
}
