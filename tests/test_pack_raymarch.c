/* packs/raymarch: the march of packs/raymarch/march.glsl written again in C
 * (the twin: same float arithmetic, same order) against closed-form hits on
 * a flat and a sloped floor, with the hit error of the source's linear
 * interpolation and of each refinement against step count; every hazard
 * (TIR, no bracket, a zero or sign-less denominator, grazing rays, leaving
 * the footprint, ground above the water and depth zero, NaN); the Fresnel
 * table; then the pack on GL (headless): the lake at several times and
 * under water (no NaN, no GL error), and flat water over a flat and a
 * sloped floor and under a floating box against ref_render's buffers.
 *
 * The figures printed here are in docs/packs/raymarch.md. */
#include <GL/gl.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "assets.h"
#include "check.h"
#include "gl_ctx.h"
#include "ref_metrics.h"
#include "ref_optics.h"
#include "ref_render.h"
#include "render.h"
#include "scene.h"
#include "unif.h"

#define PI 3.14159265358979323846

/* ======================================================================
 * The twin of march.glsl
 * ====================================================================== */

enum { MARCH_HIT = 0, MARCH_INSIDE = 1, MARCH_CAP = 2, MARCH_LEFT = 3 };
enum { REFINE_NONE = 0, REFINE_SECANT = 1, REFINE_BINARY = 2 };
#define MARCH_MAX_ITER 64
#define MARCH_REFINE_MAX 8
#define MARCH_MIN_DIR_Y 0.02f

typedef struct { float x, y, z; } v3;
typedef struct { float x, y; } v2;

static v3 V3(float x, float y, float z) { return (v3){ x, y, z }; }
static float dot3f(v3 a, v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static v3 normalize3f(v3 a) {
    float l = 1.0f / sqrtf(dot3f(a, a));
    return V3(a.x * l, a.y * l, a.z * l);
}

/* The top camera (render_camera.c's rules): column-major m[col][row]. */
typedef struct {
    float m[4][4];
} twin_cam;

static twin_cam twin_top_camera(double level, double half_size, double depth) {
    twin_cam c;
    memset(&c, 0, sizeof c);
    double h = half_size * 1.05;
    double ymin = level - 2.0 * depth - 10.0, ymax = level + 50.0, range = ymax - ymin;
    c.m[0][0] = (float)(1.0 / h);
    c.m[2][1] = (float)(1.0 / h);
    c.m[1][2] = (float)(-2.0 / range);
    c.m[3][2] = (float)(1.0 + 2.0 * ymin / range);
    c.m[3][3] = 1.0f;
    return c;
}

/* The packed world-Y texture of pack_y.frag: n x n texels of (top,
 * bottom, floor) world Y (row 0 = t = 0 = the lowest z); fetches out of
 * range are counted. */
typedef struct {
    const twin_cam *cam;
    const float *y3;
    int n;
    long fetches, bad_fetches;
} twin_hf;

#define EMPTY_Y (-1e30f)        /* pack_y.frag: nothing drawn there */
#define MARCH_EMPTY_Y (-1e29f)

/* GLSL's min and max as the spec writes them (y < x ? y : x, x < y ? y : x) */
static float gmin(float x, float y) { return y < x ? y : x; }
static float gmax(float x, float y) { return x < y ? y : x; }

static float twin_depth_to_y(const twin_cam *c, float d) {
    return (2.0f * d - 1.0f - c->m[3][2]) / c->m[1][2];
}

static v2 twin_uv(const twin_cam *c, v3 p) {
    float cx = c->m[0][0] * p.x + c->m[1][0] * p.y + c->m[2][0] * p.z + c->m[3][0];
    float cy = c->m[0][1] * p.x + c->m[1][1] * p.y + c->m[2][1] * p.z + c->m[3][1];
    return (v2){ cx * 0.5f + 0.5f, cy * 0.5f + 0.5f };
}

static v2 twin_uv_dir(const twin_cam *c, v3 d) {
    float cx = c->m[0][0] * d.x + c->m[1][0] * d.y + c->m[2][0] * d.z;
    float cy = c->m[0][1] * d.x + c->m[1][1] * d.y + c->m[2][1] * d.z;
    return (v2){ cx * 0.5f, cy * 0.5f };
}

static bool twin_in_footprint(v2 uv) {
    return uv.x >= 0.0f && uv.x < 1.0f && uv.y >= 0.0f && uv.y < 1.0f;
}

static v3 twin_fetch(twin_hf *hf, v2 uv) {
    int i = (int)(uv.x * (float)hf->n), j = (int)(uv.y * (float)hf->n);
    if (i > hf->n - 1) i = hf->n - 1;
    if (j > hf->n - 1) j = hf->n - 1;
    hf->fetches++;
    if (i < 0 || j < 0) { hf->bad_fetches++; return V3(NAN, NAN, NAN); }
    const float *t = hf->y3 + ((size_t)j * hf->n + i) * 3;
    return V3(t[0], t[1], t[2]);
}

static float twin_solid(v3 t, float y) {
    float f = y - t.x;
    if (t.y < t.x) {
        f = gmax(f, t.y - y);
        if (t.z >= t.y) return f;
    }
    return gmin(f, y - t.z);
}

static float twin_solid_as(v3 t, float y, float level) {
    if (level <= MARCH_EMPTY_Y) return twin_solid(t, y);
    if (t.x < level) return 1e30f;
    return fmaxf(t.y > MARCH_EMPTY_Y && t.y < t.x ? t.y : t.x, level) - y;
}

static float twin_f(twin_hf *hf, v2 uv, float y, float level) {
    return twin_solid_as(twin_fetch(hf, uv), y, level);
}

static float clampf(float v, float lo, float hi) { return v < lo ? lo : v > hi ? hi : v; }
static float mixf(float a, float b, float t) { return a * (1.0f - t) + b * t; }

static float twin_interp(float ta, float fa, float tb, float fb) {
    float den = fa - fb;
    return den > 0.0f ? ta + (tb - ta) * clampf(fa / den, 0.0f, 1.0f) : tb;
}

static float twin_step(float range, float dir_y, float n_grazing, float n_steep, float max_step) {
    float cy = fmaxf(fabsf(dir_y), MARCH_MIN_DIR_Y);
    float n = fmaxf(mixf(n_grazing, n_steep, cy), 1.0f);
    return fminf(range / (n * cy), max_step);
}

static v3 twin_clamp_dir(v3 d, bool down) {
    float y = down ? fminf(d.y, -MARCH_MIN_DIR_Y) : fmaxf(d.y, MARCH_MIN_DIR_Y);
    return normalize3f(V3(d.x, y, d.z));
}

typedef struct {
    float t, f, ta;
    int status;
    int steps;          /* linear search samples (not in the GLSL: for the tables) */
    float tb;           /* the bracket's end (a hit) */
} twin_march;

typedef struct {
    float n_grazing, n_steep, min_range, max_step;
    int max_iter, refine, refine_mode;
    float y_min, y_max;
    float from_below;   /* the paper's reflection solid: the water level; else -1e30 */
    const float *skip;  /* the skip map (twin_skip_build) for a ray going up; NULL: plain */
    float level, scale; /* uWaterLevel, uWorldScale: the skip map's heights */
} twin_params;

static twin_params twin_defaults(void) {
    return (twin_params){ .n_grazing = 10, .n_steep = 3, .min_range = 0.25f, .max_step = 0.5f, .max_iter = 40,
                          .refine = 0, .refine_mode = REFINE_NONE, .y_min = -1e30f, .y_max = 1e30f,
                          .from_below = -1e30f, .skip = NULL, .level = 0.0f, .scale = 1.0f };
}

/* ---- skipping empty space (march.glsl's marchSkip*, skip_blocked.frag,
 * skip_dist.frag) ---- */
#define MARCH_SKIP_CELLS 128
#define MARCH_SKIP_FAR 65.0f

static float twin_skip_level(const twin_params *p, int k) {
    float m = k == 0 ? -0.3f : k == 1 ? 0.05f : k == 2 ? 0.2f : 0.8f;
    return p->level + m * p->scale;
}

/* skip_blocked.frag: per cell and level, 0 where a texel under the cell
 * (one more each side) reaches the level or is off the world, else FAR */
static void twin_skip_blocked(const twin_hf *hf, const twin_params *p, float *out) {
    int n = hf->n, c = MARCH_SKIP_CELLS;
    for (int cj = 0; cj < c; cj++)
        for (int ci = 0; ci < c; ci++) {
            int lo_i = ci * n / c - 1, lo_j = cj * n / c - 1;
            int hi_i = ((ci + 1) * n + c - 1) / c, hi_j = ((cj + 1) * n + c - 1) / c;
            if (lo_i < 0) lo_i = 0;
            if (lo_j < 0) lo_j = 0;
            if (hi_i > n - 1) hi_i = n - 1;
            if (hi_j > n - 1) hi_j = n - 1;
            float high = -1e30f;
            for (int j = lo_j; j <= hi_j; j++)
                for (int i = lo_i; i <= hi_i; i++) {
                    const float *t = hf->y3 + ((size_t)j * n + i) * 3;
                    high = gmax(high, t[0] <= MARCH_EMPTY_Y ? 1e30f : gmax(t[0], t[2]));
                }
            for (int k = 0; k < 4; k++)
                out[((size_t)cj * c + ci) * 4 + k] = high >= twin_skip_level(p, k) ? 0.0f : MARCH_SKIP_FAR;
        }
}

/* skip_dist.frag along one axis: min over |d| <= R of max(in(c + d), |d|),
 * beyond the map 0 */
static void twin_skip_dist(const float *in, int axis, float *out) {
    int c = MARCH_SKIP_CELLS, reach = (int)MARCH_SKIP_FAR - 1;
    for (int y = 0; y < c; y++)
        for (int x = 0; x < c; x++)
            for (int k = 0; k < 4; k++) {
                float r = in[((size_t)y * c + x) * 4 + k];
                for (int d = 1; d <= reach; d++) {
                    int ax = x + (axis == 0 ? d : 0), ay = y + (axis == 0 ? 0 : d);
                    int bx = x - (axis == 0 ? d : 0), by = y - (axis == 0 ? 0 : d);
                    float va = ax < c && ay < c ? in[((size_t)ay * c + ax) * 4 + k] : 0.0f;
                    float vb = bx >= 0 && by >= 0 ? in[((size_t)by * c + bx) * 4 + k] : 0.0f;
                    r = gmin(r, gmax(gmin(va, vb), (float)d));
                }
                out[((size_t)y * c + x) * 4 + k] = r;
            }
}

/* The three passes: the map the march up reads (c * c * 4 floats). */
static void twin_skip_build(const twin_hf *hf, const twin_params *p, float *map) {
    size_t nf = (size_t)MARCH_SKIP_CELLS * MARCH_SKIP_CELLS * 4;
    float *blocked = malloc(nf * sizeof *blocked), *rows = malloc(nf * sizeof *rows);
    twin_skip_blocked(hf, p, blocked);
    twin_skip_dist(blocked, 0, rows);
    twin_skip_dist(rows, 1, map);
    free(blocked);
    free(rows);
}

static int twin_skip_count(const twin_params *p, v2 uv, float y, float adv) {
    int ci = (int)(uv.x * (float)MARCH_SKIP_CELLS), cj = (int)(uv.y * (float)MARCH_SKIP_CELLS);
    ci = ci < 0 ? 0 : ci > MARCH_SKIP_CELLS - 1 ? MARCH_SKIP_CELLS - 1 : ci;
    cj = cj < 0 ? 0 : cj > MARCH_SKIP_CELLS - 1 ? MARCH_SKIP_CELLS - 1 : cj;
    const float *r = p->skip + ((size_t)cj * MARCH_SKIP_CELLS + ci) * 4;
    float cells = y >= twin_skip_level(p, 3) ? r[3] : y >= twin_skip_level(p, 2) ? r[2]
                : y >= twin_skip_level(p, 1) ? r[1] : y >= twin_skip_level(p, 0) ? r[0] : 0.0f;
    float n = floorf(0.999f * (cells - 1.0f) / ((float)MARCH_SKIP_CELLS * adv));
    return (int)clampf(n, 0.0f, (float)MARCH_MAX_ITER);
}

static int twin_skip_next(int cur, int k, int last) {
    if (k <= 0) return cur + 1;
    int j = cur + k < last ? cur + k : last;
    return j > cur + 1 ? j : cur + 1;
}

static twin_march twin_march_hf(twin_hf *hf, v3 o, v3 dir, float step, const twin_params *p) {
    twin_march m = { 0.0f, 0.0f, 0.0f, MARCH_LEFT, 0 };
    v2 uv0 = twin_uv(hf->cam, o), duv = twin_uv_dir(hf->cam, dir);
    if (!twin_in_footprint(uv0)) return m;
    v3 t0 = twin_fetch(hf, uv0);
    if (t0.x <= MARCH_EMPTY_Y) return m;
    float fa = twin_solid_as(t0, o.y, p->from_below);
    if (!(fa > 0.0f)) { m.status = MARCH_INSIDE; return m; }
    if (step <= 0.0f) step = twin_step(fmaxf(fa, p->min_range), dir.y, p->n_grazing, p->n_steep, p->max_step);
    float ta = 0.0f, tb = 0.0f, fb = fa;
    m.status = MARCH_CAP;
    bool skip = p->skip != NULL;
    float adv = step * fmaxf(fabsf(duv.x), fabsf(duv.y));
    int last = p->max_iter - 1;
    if (skip) {
        int ly = (int)fminf(floorf((p->y_max - o.y) / (step * dir.y)), 1e4f) - 2;
        last = ly < last ? ly : last;
    }
    int s = skip ? twin_skip_next(-1, twin_skip_count(p, uv0, o.y, adv), last) : 0;
    for (int i = 0; i < MARCH_MAX_ITER; i++) {
        if (s >= p->max_iter) break;
        float t = step * (float)(s + 1);
        float y = o.y + t * dir.y;
        v2 uv = { uv0.x + t * duv.x, uv0.y + t * duv.y };
        if (!twin_in_footprint(uv) || y < p->y_min || y > p->y_max) { m.status = MARCH_LEFT; break; }
        m.steps++;
        v3 tx = twin_fetch(hf, uv);
        if (tx.x <= MARCH_EMPTY_Y) { m.status = MARCH_LEFT; break; }
        float f = twin_solid_as(tx, y, p->from_below);
        if (f <= 0.0f) { tb = t; fb = f; m.status = MARCH_HIT; break; }
        ta = t;
        fa = f;
        s = skip ? twin_skip_next(s, twin_skip_count(p, uv, y, adv), last) : s + 1;
    }
    m.ta = ta;
    if (m.status != MARCH_HIT) { m.t = ta; m.f = fa; return m; }
    int refine = p->refine_mode == REFINE_NONE ? 0 : p->refine;
    for (int k = 0; k < MARCH_REFINE_MAX; k++) {
        if (k >= refine) break;
        float t = p->refine_mode == REFINE_BINARY ? 0.5f * (ta + tb) : twin_interp(ta, fa, tb, fb);
        v2 uv = { uv0.x + t * duv.x, uv0.y + t * duv.y };
        float f = twin_f(hf, uv, o.y + t * dir.y, p->from_below);
        if (f > 0.0f) { ta = t; fa = f; } else { tb = t; fb = f; }
    }
    m.ta = ta;
    m.tb = tb;
    m.t = twin_interp(ta, fa, tb, fb);
    return m;
}

/* water.frag's groundAlong without the colour: the path in water and the
 * point, with the no-bracket extension down to the last column's ground. */
static float twin_ground_along(twin_hf *hf, v3 p, v3 dir, const twin_params *prm, v3 *hit, int *status) {
    v3 d = twin_clamp_dir(dir, true);
    twin_march m = twin_march_hf(hf, p, d, 0.0f, prm);
    float s = m.t;
    if (m.status == MARCH_CAP || m.status == MARCH_LEFT) s += fmaxf(m.f, 0.0f) / -d.y;
    *hit = V3(p.x + s * d.x, p.y + s * d.y, p.z + s * d.z);
    *status = m.status;
    return s;
}

/* GLSL's refract(I, N, eta): zero on total internal reflection. */
static v3 glsl_refract(v3 i, v3 n, float eta) {
    float c = dot3f(n, i);
    float k = 1.0f - eta * eta * (1.0f - c * c);
    if (k < 0.0f) return V3(0, 0, 0);
    float a = eta * c + sqrtf(k);
    return V3(eta * i.x - a * n.x, eta * i.y - a * n.y, eta * i.z - a * n.z);
}

/* world.glsl's worldFresnel in float. */
static float world_fresnel(float cos_i, float n1, float n2) {
    float eta = n1 / n2;
    float sin_t2 = eta * eta * fmaxf(0.0f, 1.0f - cos_i * cos_i);
    if (sin_t2 >= 1.0f) return 1.0f;
    float cos_t = sqrtf(1.0f - sin_t2);
    float rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    float rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    return 0.5f * (rs * rs + rp * rp);
}

/* ---- the Fresnel table (fresnel_lut.frag, water.frag) ---- */

#define LUT_W 256

static void twin_lut_build(float ior, float lut[2][LUT_W]) {
    float cos_c = sqrtf(fmaxf(1.0f - 1.0f / (ior * ior), 0.0f));
    for (int i = 0; i < LUT_W; i++) {
        float x = (float)i / (float)(LUT_W - 1);
        lut[0][i] = world_fresnel(x, 1.0f, ior);
        lut[1][i] = world_fresnel(cos_c + x * x * (1.0f - cos_c), ior, 1.0f);
    }
}

/* GL_LINEAR along a row, clamped to the edge, at the texture coordinate s. */
static float lut_linear(const float *row, int w, float s) {
    float u = s * (float)w - 0.5f;
    float i0 = floorf(u), a = u - i0;
    int k0 = (int)i0, k1 = k0 + 1;
    if (k0 < 0) k0 = 0;
    if (k1 < 0) k1 = 0;
    if (k0 > w - 1) k0 = w - 1;
    if (k1 > w - 1) k1 = w - 1;
    return row[k0] * (1.0f - a) + row[k1] * a;
}

static float lut_at(const float *row, float x) {
    return lut_linear(row, LUT_W, (x * (float)(LUT_W - 1) + 0.5f) / (float)LUT_W);
}

static float twin_fresnel_from_water(const float lut[2][LUT_W], float ior, float cos_i) {
    float cos_c = sqrtf(fmaxf(1.0f - 1.0f / (ior * ior), 0.0f));
    if (cos_i <= cos_c) return 1.0f;
    return lut_at(lut[1], sqrtf((cos_i - cos_c) / (1.0f - cos_c)));
}

/* ======================================================================
 * Heightfields for the twin
 * ====================================================================== */

#define HF_N 1024
#define HALF 12.0          /* the world square's half size */
#define LEVEL 0.0
#define DEPTH 3.0          /* the top camera's depth range uses the world's depth */

static float hf_y3[HF_N * HF_N * 3];
static twin_cam cam_top;

static double texel_size(void) { return 2.0 * HALF * 1.05 / HF_N; }

static double texel_x(int i) { return -HALF * 1.05 + (i + 0.5) * texel_size(); }

/* the Y a texel holds after the depth round trip: the rasterised depth
 * (float) turned back into Y by marchDepthToY */
static float stored_y(double y) {
    const twin_cam *c = &cam_top;
    float d = (float)(0.5 * ((double)c->m[1][2] * y + (double)c->m[3][2]) + 0.5);
    return twin_depth_to_y(c, d);
}

static float *texel(int i, int j) { return hf_y3 + ((size_t)j * HF_N + i) * 3; }

/* y = a + b x + c z at the texel centres: top and floor; no bottom. */
static void hf_plane(double a, double b, double c) {
    for (int j = 0; j < HF_N; j++)
        for (int i = 0; i < HF_N; i++) {
            float y = stored_y(a + b * texel_x(i) + c * texel_x(j));
            float *t = texel(i, j);
            t[0] = y;
            t[1] = EMPTY_Y;
            t[2] = y;
        }
}

static twin_hf hf_make(void) { return (twin_hf){ .cam = &cam_top, .y3 = hf_y3, .n = HF_N }; }

/* Closed form: o + t d meets y = a + b x + c z at t. */
static double plane_t(double a, double b, double c, v3 o, v3 d) {
    return (a + b * o.x + c * o.z - o.y) / (d.y - b * d.x - c * d.z);
}

/* A refracted ray: from (x, level, z) through flat water seen from the air
 * at incidence theta (degrees) and azimuth phi. */
static v3 refracted_dir(double theta_deg, double phi_deg) {
    double th = theta_deg * PI / 180, ph = phi_deg * PI / 180;
    v3 in = V3((float)(sin(th) * cos(ph)), (float)-cos(th), (float)(sin(th) * sin(ph)));
    return glsl_refract(in, V3(0, 1, 0), 1.0f / 1.333f);
}

/* ======================================================================
 * Twin tests
 * ====================================================================== */

typedef struct {
    double mean, max;     /* world units */
    double steps;         /* mean linear-search samples */
    long n;
} err_acc;

/* The test rays: a grid of origins on the flat surface, incidences and
 * azimuths, refracted into the water. */
#define NRAYS 288
static void test_ray(int k, v3 *o, v3 *d) {
    static const double thetas[] = { 0, 10, 25, 40, 55, 70, 80, 87 };
    int io = k / 48, it = (k / 6) % 8, ip = k % 6;
    *o = V3((float)(-3.0 + 1.13 * io), (float)LEVEL, (float)(-2.0 + 0.71 * io));
    *d = refracted_dir(thetas[it], 17.0 + 60.0 * ip);
}

/* A floor: the plane y = a + b x + c z plus amp sin(2 pi x / wavelength). */
typedef struct { double a, b, c, amp, wavelength; } floor_desc;

static double floor_h(const floor_desc *f, double x, double z) {
    double h = f->a + f->b * x + f->c * z;
    if (f->amp != 0) h += f->amp * sin(2 * PI * x / f->wavelength);
    return h;
}

static void hf_floor(const floor_desc *f) {
    for (int j = 0; j < HF_N; j++)
        for (int i = 0; i < HF_N; i++) {
            float y = stored_y(floor_h(f, texel_x(i), texel_x(j)));
            float *t = texel(i, j);
            t[0] = y;
            t[1] = EMPTY_Y;
            t[2] = y;
        }
}

/* The exact first hit of each test ray: closed form on a plane; on the sine
 * floor, 1 mm steps of the exact function then 60 bisections (double). */
static void exact_hits(const floor_desc *f, double *t_exact) {
    for (int k = 0; k < NRAYS; k++) {
        v3 o, d;
        test_ray(k, &o, &d);
        if (f->amp == 0) { t_exact[k] = plane_t(f->a, f->b, f->c, o, d); continue; }
        double g0 = o.y - floor_h(f, o.x, o.z), t0 = 0, t1 = 0;
        t_exact[k] = NAN;
        for (int i = 1; i < 40000; i++) {
            t1 = i * 1e-3;
            double g1 = o.y + t1 * d.y - floor_h(f, o.x + t1 * d.x, o.z + t1 * d.z);
            if (g1 <= 0) {
                for (int b = 0; b < 60; b++) {
                    double tm = 0.5 * (t0 + t1), gm = o.y + tm * d.y - floor_h(f, o.x + tm * d.x, o.z + tm * d.z);
                    if (gm > 0) t0 = tm; else t1 = tm;
                }
                t_exact[k] = 0.5 * (t0 + t1);
                break;
            }
            t0 = t1;
            g0 = g1;
        }
        (void)g0;
    }
}

/* The error of the marched hits against the exact ones (the heightfield
 * is hf_floor's). */
static err_acc march_error(const double *t_exact, const twin_params *p) {
    err_acc e = { 0, 0, 0, 0 };
    twin_hf hf = hf_make();
    for (int k = 0; k < NRAYS; k++) {
        v3 o, d, hit;
        test_ray(k, &o, &d);
        double t = t_exact[k];
        int st;
        twin_ground_along(&hf, o, d, p, &hit, &st);
        if (st != MARCH_HIT || !(t > 0)) continue;
        double ex = o.x + t * d.x - hit.x, ey = o.y + t * d.y - hit.y, ez = o.z + t * d.z - hit.z;
        double err = sqrt(ex * ex + ey * ey + ez * ez);
        e.mean += err;
        e.max = fmax(e.max, err);
        e.n++;
    }
    if (e.n) e.mean /= (double)e.n;
    return e;
}

/* the (steep, grazing) step counts of the table: the source's (3, 10) and
 * scaled versions of it */
static const float step_sets[][2] = { { 1, 3 }, { 2, 6 }, { 3, 10 }, { 6, 20 }, { 12, 40 } };
#define NSETS 5

static void test_twin_flat_floor_is_exact(void) {
    cam_top = twin_top_camera(LEVEL, HALF, DEPTH);
    floor_desc f = { LEVEL - 2.0, 0, 0, 0, 0 };
    hf_floor(&f);
    static double t_exact[NRAYS];
    exact_hits(&f, t_exact);
    double worst = 0;
    fprintf(stderr, "  flat floor 2 m deep: hit error (m), max over %d rays\n", NRAYS);
    fprintf(stderr, "  %-12s %-10s %-10s %-10s %-10s\n", "steps", "linear", "secant 2", "binary 4", "samples");
    for (int s = 0; s < NSETS; s++) {
        twin_params p = twin_defaults();
        p.n_steep = step_sets[s][0];
        p.n_grazing = step_sets[s][1];
        err_acc lin = march_error(t_exact, &p);
        p.refine_mode = REFINE_SECANT;
        p.refine = 2;
        err_acc sec = march_error(t_exact, &p);
        p.refine_mode = REFINE_BINARY;
        p.refine = 4;
        err_acc bin = march_error(t_exact, &p);
        fprintf(stderr, "  %2.0f..%-8.0f %-10.2g %-10.2g %-10.2g %ld rays\n", p.n_steep, p.n_grazing, lin.max, sec.max,
                bin.max, lin.n);
        CHECK_GT(lin.n, 250);
        worst = fmax(worst, fmax(lin.max, fmax(sec.max, bin.max)));
    }
    /* a plane is linear along the ray: the interpolation is exact up to
     * float rounding of t ~ 10 m and of the depth encoding (1e-6 m) */
    CHECK_MSG(worst < 2e-5, "worst %g", worst);
}

/* The table of hit errors in texels against the step counts, for each
 * refinement; max_step 4 so that the counts, not the cap, set the steps. */
static double error_table(const floor_desc *f, const char *title, double *src_max) {
    cam_top = twin_top_camera(LEVEL, HALF, DEPTH);
    hf_floor(f);
    static double t_exact[NRAYS];
    exact_hits(f, t_exact);
    double tau = texel_size();
    fprintf(stderr, "  %s, texel %.4f m: hit error in texels, mean / max over the rays\n", title, tau);
    fprintf(stderr, "  %-9s %-14s %-14s %-14s %-14s %-14s %-14s %-14s %s\n", "steps", "linear", "secant 1", "secant 2",
            "secant 4", "binary 2", "binary 4", "binary 6", "texels read");
    double final_max = 0;
    for (int s = 0; s < NSETS; s++) {
        twin_params p = twin_defaults();
        p.n_steep = step_sets[s][0];
        p.n_grazing = step_sets[s][1];
        p.max_step = 4;
        struct { int mode, k; } m[] = { { REFINE_NONE, 0 },   { REFINE_SECANT, 1 }, { REFINE_SECANT, 2 },
                                       { REFINE_SECANT, 4 }, { REFINE_BINARY, 2 }, { REFINE_BINARY, 4 },
                                       { REFINE_BINARY, 6 } };
        char line[512];
        int w = snprintf(line, sizeof line, "  %2.0f..%-5.0f", p.n_steep, p.n_grazing);
        for (int k = 0; k < 7; k++) {
            p.refine_mode = m[k].mode;
            p.refine = m[k].k;
            err_acc e = march_error(t_exact, &p);
            w += snprintf(line + w, sizeof line - (size_t)w, " %5.3f / %-6.3f", e.mean / tau, e.max / tau);
            if (k == 6) final_max = fmax(final_max, e.max / tau);
            if (k == 0 && s == 2) *src_max = e.max / tau;
        }
        /* the linear search's samples, mean over the rays (plus 1 + refinement) */
        twin_hf hf = hf_make();
        p.refine_mode = REFINE_NONE;
        double samples = 0;
        for (int k = 0; k < NRAYS; k++) {
            v3 o, d;
            test_ray(k, &o, &d);
            samples += twin_march_hf(&hf, o, twin_clamp_dir(d, true), 0.0f, &p).steps + 1;
        }
        snprintf(line + w, sizeof line - (size_t)w, " %.1f + refinement", samples / NRAYS);
        fprintf(stderr, "%s\n", line);
    }
    return final_max;
}

/* On a sloped floor the nearest-texel heightfield is a staircase: the
 * samples are exact at texel centres, so the interpolated hit is within
 * about g tau / 2 / |g - slope of the ray| of the plane's (g the floor's
 * slope, tau the texel) whatever the step, and the refinements converge to
 * the staircase's crossing, no nearer the plane. */
static void test_twin_sloped_floor_table(void) {
    floor_desc f = { LEVEL - 2.0, 0.25, 0.1, 0, 0 };
    double src = 0, refined = error_table(&f, "floor y = -2 + 0.25 x + 0.1 z", &src);
    fprintf(stderr, "  binary 6 (any steps): max %.3f texel; source (3..10, linear): max %.3f texel\n", refined, src);
    CHECK_MSG(refined < 0.5, "refined hit error %.3f texels", refined);
}

/* A curved floor (a sine of 3 m wavelength, 0.4 m amplitude, on the slope):
 * the linear interpolation's error now grows with the step, and the
 * refinements remove it down to the staircase's. */
static void test_twin_sine_floor_table(void) {
    floor_desc f = { LEVEL - 2.0, 0.1, 0, 0.4, 3.0 };
    double src = 0, refined = error_table(&f, "floor y = -2 + 0.1 x + 0.4 sin(2 pi x / 3)", &src);
    fprintf(stderr, "  binary 6 (any steps): max %.3f texel; source (3..10, linear): max %.3f texel\n", refined, src);
    CHECK_MSG(refined < 1.5, "refined hit error %.3f texels", refined);
    CHECK_GT(src, 2 * refined);
}

/* With the source's step counts, vertical and oblique rays over a flat
 * floor reach it in ceil(n) samples, n = mix(10, 3, |dir.y|). */
static void test_twin_step_count_rule(void) {
    cam_top = twin_top_camera(LEVEL, HALF, DEPTH);
    hf_plane(LEVEL - 1.0, 0, 0);
    twin_hf hf = hf_make();
    twin_params p = twin_defaults();
    p.max_step = 100;
    for (int it = 0; it < 6; it++) {
        double th = it * 8.0;
        v3 d = refracted_dir(th, 30);
        twin_march m = twin_march_hf(&hf, V3(0.3f, 0.0f, -0.2f), d, 0.0f, &p);
        float n = mixf(10, 3, -d.y);
        CHECK_EQ(m.status, MARCH_HIT);
        CHECK_MSG(m.steps == (int)ceilf(n - 1e-4f) || m.steps == (int)ceilf(n - 1e-4f) + 1,
                  "theta %g: %d samples for n = %g", th, m.steps, n);
        CHECK_NEAR(m.t, 1.0 / -d.y, 1e-5);
    }
}

/* ---- hazards ---- */

static void test_hazard_tir(void) {
    float lut[2][LUT_W];
    twin_lut_build(1.333f, lut);
    double crit = asin(1.0 / 1.333) * 180 / PI;
    int tir = 0, pass = 0;
    for (double a = 0; a < 90; a += 0.01) {
        double r = a * PI / 180;
        v3 i = V3((float)sin(r), (float)cos(r), 0);      /* from below, going up */
        v3 n = V3(0, -1, 0);                             /* the normal facing the ray */
        v3 t = glsl_refract(i, n, 1.333f);
        bool is_tir = dot3f(t, t) == 0.0f;
        float cos_i = (float)cos(r);
        float F = is_tir ? 1.0f : twin_fresnel_from_water(lut, 1.333f, cos_i);
        CHECK(isfinite(t.x) && isfinite(t.y) && isfinite(t.z) && isfinite(F));
        if (is_tir) { tir++; CHECK_GT(a, crit - 0.02); }
        else { pass++; CHECK_LT(a, crit + 0.02); CHECK(F >= 0 && F <= 1.0f); CHECK_GT(t.y, 0); }
        /* the table and refract agree on the side of the critical angle */
        if (fabs(a - crit) > 0.02) CHECK_EQ((F == 1.0f), is_tir);
    }
    fprintf(stderr, "  %d angles refract, %d are total internal reflection (critical %.3f deg)\n", pass, tir, crit);
    CHECK(tir > 4000 && pass > 4000);
}

static void test_hazard_no_bracket(void) {
    cam_top = twin_top_camera(LEVEL, HALF, DEPTH);
    hf_plane(LEVEL - 15.0, 0, 0);            /* deeper than 40 steps reach from a shallow start */
    int i0 = HF_N / 2;                       /* one texel 0.5 m deep under the start (its centre) */
    for (int k = 0; k < 3; k += 2) texel(i0, i0)[k] = stored_y(-0.5);
    v3 o = V3((float)texel_x(i0), 0, (float)texel_x(i0));
    twin_hf hf = hf_make();
    twin_params p = twin_defaults();
    p.min_range = 0.01f;
    v3 d = refracted_dir(30, 0);
    twin_march m = twin_march_hf(&hf, o, d, 0.0f, &p);
    CHECK_EQ(m.status, MARCH_CAP);
    CHECK(isfinite(m.t) && m.t > 0 && m.f > 0);
    v3 hit;
    int st;
    float s = twin_ground_along(&hf, o, d, &p, &hit, &st);
    CHECK(st == MARCH_CAP && isfinite(s) && isfinite(hit.x));
    /* the extension goes on down to the floor of the last column */
    CHECK_NEAR(hit.y, -15.0, 1e-3);
    CHECK_EQ(hf.bad_fetches, 0);
}

static void test_hazard_denominator(void) {
    CHECK_EQ(twin_interp(1, 0.5f, 2, -0.5f), 1.5f);
    CHECK_EQ(twin_interp(1, 0.3f, 2, 0.3f), 2);           /* zero denominator */
    CHECK_EQ(twin_interp(1, 0.3f, 2, 0.7f), 2);           /* same sign, negative denominator */
    CHECK_EQ(twin_interp(1, -0.3f, 2, -0.1f), 2);         /* both below */
    CHECK_EQ(twin_interp(1, NAN, 2, -0.1f), 2);           /* NaN */
    CHECK_EQ(twin_interp(1, 1e-30f, 2, -0.0f), 2);        /* denominator a denormal, ratio 1 */
    CHECK_EQ(twin_interp(1, 1e30f, 2, -1e30f), 1.5f);
    float t = twin_interp(1, 1e-38f, 2, -1e-38f);        /* denormal ratio */
    CHECK(t >= 1 && t <= 2);
    /* a floor exactly at a sample: f = 0 there, the hit is that sample */
    cam_top = twin_top_camera(LEVEL, HALF, DEPTH);
    hf_plane(-1.0, 0, 0);
    twin_hf hf = hf_make();
    twin_params p = twin_defaults();
    twin_march m = twin_march_hf(&hf, V3(0, 0, 0), V3(0, -1, 0), 0.25f, &p);
    CHECK_EQ(m.status, MARCH_HIT);
    CHECK_NEAR(m.t, 1.0, 1e-6);
}

static void test_hazard_grazing(void) {
    cam_top = twin_top_camera(LEVEL, HALF, DEPTH);
    hf_plane(LEVEL - 2.0, 0.05, 0);
    twin_hf hf = hf_make();
    twin_params p = twin_defaults();
    const v3 dirs[] = { { 1, 0, 0 }, { 1, 1e-30f, 0 }, { 0.6f, 0.1f, 0.8f }, { 1, -1e-7f, 0 }, { 0, 0, 0 } };
    for (int k = 0; k < 5; k++) {
        v3 d = k == 4 ? V3(0, -1, 0) : normalize3f(dirs[k]);
        v3 hit;
        int st;
        float s = twin_ground_along(&hf, V3(-1, 0, 1), d, &p, &hit, &st);
        CHECK_MSG(isfinite(s) && isfinite(hit.x) && isfinite(hit.y) && isfinite(hit.z), "dir %d", k);
        CHECK(st == MARCH_HIT || st == MARCH_CAP || st == MARCH_LEFT);
        CHECK_LE(hit.y, 0.0f);
        /* the step never exceeds max_step, whatever the slope */
        CHECK_LE(twin_step(2.0f, d.y, 10, 3, p.max_step), p.max_step);
    }
    CHECK(isfinite(twin_step(2.0f, 0.0f, 10, 3, 1e30f)));
    CHECK_EQ(twin_step(2.0f, 0.0f, 10, 3, 1e30f), 2.0f / (mixf(10, 3, MARCH_MIN_DIR_Y) * MARCH_MIN_DIR_Y));
    /* an upward refracted ray (a steep wave) is turned down */
    v3 d = twin_clamp_dir(V3(0.7f, 0.2f, 0.7f), true);
    CHECK(d.y <= -MARCH_MIN_DIR_Y * 0.99f && fabsf(dot3f(d, d) - 1) < 1e-6f);
    CHECK_EQ(hf.bad_fetches, 0);
}

static void test_hazard_leaving_footprint(void) {
    cam_top = twin_top_camera(LEVEL, HALF, DEPTH);
    hf_plane(LEVEL - 50.0, 0, 0);                 /* too deep to meet */
    twin_hf hf = hf_make();
    twin_params p = twin_defaults();
    p.max_step = 4;
    p.max_iter = 64;
    const v3 dirs[] = { { 1, -0.05f, 0 }, { -1, -0.05f, 0 }, { 0, -0.05f, 1 }, { 0, -0.05f, -1 }, { 1, -0.1f, 1 } };
    for (int k = 0; k < 5; k++) {
        v3 d = normalize3f(dirs[k]);
        twin_march m = twin_march_hf(&hf, V3(11.5f, 0, -11.5f), d, 0.0f, &p);
        CHECK_MSG(m.status == MARCH_LEFT, "dir %d: status %d", k, m.status);
        v3 last = V3(11.5f + m.t * d.x, m.t * d.y, -11.5f + m.t * d.z);
        CHECK(twin_in_footprint(twin_uv(&cam_top, last)));
        v3 hit;
        int st;
        float s = twin_ground_along(&hf, V3(11.5f, 0, -11.5f), d, &p, &hit, &st);
        CHECK(isfinite(s) && st == MARCH_LEFT);
    }
    /* the border around the world square (nothing drawn) ends the march
     * like the texture's edge: the last sample is on the world */
    for (int j = 0; j < HF_N; j++)
        for (int i = 0; i < HF_N; i++)
            if (fabs(texel_x(i)) > HALF || fabs(texel_x(j)) > HALF) texel(i, j)[0] = texel(i, j)[1] = texel(i, j)[2] = EMPTY_Y;
    for (int k = 0; k < 5; k++) {
        v3 d = normalize3f(dirs[k]);
        twin_march m = twin_march_hf(&hf, V3(11.5f, 0, -11.5f), d, 0.0f, &p);
        CHECK_EQ(m.status, MARCH_LEFT);
        v3 last = V3(11.5f + m.t * d.x, m.t * d.y, -11.5f + m.t * d.z);
        CHECK(fabsf(last.x) <= HALF + texel_size() && fabsf(last.z) <= HALF + texel_size());
        CHECK(m.f > 0 && m.f < 100);
    }
    /* a start outside the footprint */
    twin_march m = twin_march_hf(&hf, V3(30, 0, 0), V3(0, -1, 0), 0.0f, &p);
    CHECK(m.status == MARCH_LEFT && m.t == 0);
    /* NaN origin: outside, no fetch */
    long before = hf.fetches;
    m = twin_march_hf(&hf, V3(NAN, 0, 0), V3(0, -1, 0), 0.0f, &p);
    CHECK(m.status == MARCH_LEFT && hf.fetches == before);
    CHECK_EQ(hf.bad_fetches, 0);
}

static void test_hazard_shore_and_depth_zero(void) {
    cam_top = twin_top_camera(LEVEL, HALF, DEPTH);
    hf_plane(LEVEL - 1.0, 0.25, 0);               /* the shore: above the water for x > 4 */
    twin_hf hf = hf_make();
    twin_params p = twin_defaults();
    v3 hit;
    int st;
    float s = twin_ground_along(&hf, V3(6, 0, 0), refracted_dir(30, 0), &p, &hit, &st);
    CHECK(st == MARCH_INSIDE && s == 0.0f && hit.x == 6.0f);
    /* depth zero: the ground at the start exactly at the surface */
    hf_plane(LEVEL, 0, 0);
    s = twin_ground_along(&hf, V3(1, 0, 1), refracted_dir(30, 0), &p, &hit, &st);
    CHECK(st == MARCH_INSIDE && s == 0.0f);
    /* a hair under the surface: a hit within the first step, no NaN */
    hf_plane(LEVEL - 1e-4, 0, 0);
    s = twin_ground_along(&hf, V3(1, 0, 1), refracted_dir(30, 0), &p, &hit, &st);
    CHECK(st == MARCH_HIT && isfinite(s) && s >= 0 && s < 0.01f);
    /* NaN in the texture: treated as inside at the start, as outside on
     * the way (no NaN out) */
    hf_plane(LEVEL - 1.0, 0, 0);
    for (int k = 0; k < HF_N * HF_N * 3; k++) hf_y3[k] = NAN;
    s = twin_ground_along(&hf, V3(1, 0, 1), refracted_dir(30, 0), &p, &hit, &st);
    CHECK(st == MARCH_INSIDE && s == 0.0f);
    hf_plane(LEVEL - 1.0, 0, 0);
    for (int j = 0; j < HF_N; j++)
        for (int i = 0; i < HF_N; i++)
            if (texel_x(i) > 1.2) texel(i, j)[0] = texel(i, j)[2] = NAN;
    s = twin_ground_along(&hf, V3(1, 0, 1), refracted_dir(30, 0), &p, &hit, &st);
    CHECK(isfinite(s) && isfinite(hit.x) && isfinite(hit.y) && isfinite(hit.z));
}

/* The solid: a box floating over the water (its underside at y = 1) is
 * passed under by a refracted ray, which meets the floor under it, and met
 * from below by a reflected one. */
static void test_solid_floating_box(void) {
    cam_top = twin_top_camera(LEVEL, HALF, DEPTH);
    hf_plane(LEVEL - 2.0, 0, 0);
    for (int j = 0; j < HF_N; j++)
        for (int i = 0; i < HF_N; i++) {
            if (fabs(texel_x(i)) > 1 || fabs(texel_x(j)) > 1) continue;
            texel(i, j)[0] = stored_y(2.0);   /* its top hides the floor from above */
            texel(i, j)[1] = stored_y(1.0);   /* its underside */
        }
    twin_hf hf = hf_make();
    twin_params p = twin_defaults();
    v3 hit;
    int st;
    float s = twin_ground_along(&hf, V3(0.2f, 0, 0.1f), V3(0, -1, 0), &p, &hit, &st);
    CHECK_EQ(st, MARCH_HIT);
    CHECK_NEAR(s, 2.0, 1e-4);
    /* upwards from (3.5, 0, 0) towards the box: it reaches y = 1 at x = 1,
     * the underside's edge, where f jumps (about 3 outside, 0 inside): the
     * bisection finds the edge, regula falsi stalls on the far side of it
     * (within a step) */
    v3 d = normalize3f(V3(-1, 0.4f, 0));
    p.y_max = 5.0f;
    float step = twin_step(5.0f, d.y, 10, 3, 0.5f);
    p.refine_mode = REFINE_BINARY;
    p.refine = 8;
    twin_march m = twin_march_hf(&hf, V3(3.5f, 0, 0), d, step, &p);
    CHECK_EQ(m.status, MARCH_HIT);
    CHECK_NEAR(3.5f + m.t * d.x, 1.0, 2 * texel_size());
    CHECK_NEAR(m.t * d.y, 1.0, 2 * texel_size());
    p.refine_mode = REFINE_SECANT;
    p.refine = 4;
    m = twin_march_hf(&hf, V3(3.5f, 0, 0), d, step, &p);
    CHECK_EQ(m.status, MARCH_HIT);
    fprintf(stderr, "  the box's edge: secant 4 stops %.3f m past it, binary 8 within a texel (step %.3f m)\n",
            1.0 - (3.5f + m.t * d.x), step);
    CHECK_LT(1.0 - (3.5f + m.t * d.x), step);
    /* steeper: into the underside, from below it */
    d = normalize3f(V3(-1, 1.5f, 0));
    m = twin_march_hf(&hf, V3(1.5f, 0, 0), d, twin_step(5.0f, d.y, 10, 3, 0.5f), &p);
    CHECK_EQ(m.status, MARCH_HIT);
    CHECK_NEAR(m.t * d.y, 1.0, 1e-3);
    CHECK_LT(m.ta * d.y, 1.0f);               /* water.frag then takes the underside's colour */
    /* under it and above its top: free */
    m = twin_march_hf(&hf, V3(0.3f, 2.5f, 0), normalize3f(V3(1, 0.3f, 0)), 0.5f, &p);
    CHECK_EQ(m.status, MARCH_LEFT);
    /* with no bottom the box is a column down to the floor */
    for (int j = 0; j < HF_N; j++)
        for (int i = 0; i < HF_N; i++) texel(i, j)[1] = EMPTY_Y;
    s = twin_ground_along(&hf, V3(0.2f, 0, 0.1f), V3(0, -1, 0), &p, &hit, &st);
    CHECK_EQ(st, MARCH_INSIDE);
    /* a bottom at or above the top (the same faces drawn twice) is no bottom */
    for (int j = 0; j < HF_N; j++)
        for (int i = 0; i < HF_N; i++) texel(i, j)[1] = texel(i, j)[0];
    s = twin_ground_along(&hf, V3(0.2f, 0, 0.1f), V3(0, -1, 0), &p, &hit, &st);
    CHECK_EQ(st, MARCH_INSIDE);
    /* the floor: an overhang left out of it, ground under it kept */
    CHECK_EQ(twin_solid(V3(2, 1, -2), 0.0f), 1.0f);      /* 1 m under the box, 2 m over the floor */
    CHECK_EQ(twin_solid(V3(2, 1, -2), -2.5f), -0.5f);
    CHECK_EQ(twin_solid(V3(2, 1, -2), 1.5f), -0.5f);
    CHECK_EQ(twin_solid(V3(2, EMPTY_Y, EMPTY_Y), 2.5f), 0.5f);
    /* the paper's reflection solid, from below: above the bottom where
     * there is one, else above the top; nothing over a texel under the
     * water; a thing crossing the water is solid from the water up */
    CHECK_EQ(twin_solid_as(V3(2, 1, -2), 1.5f, 0.0f), -0.5f);
    CHECK_EQ(twin_solid_as(V3(2, 1, -2), 2.5f, 0.0f), -1.5f);   /* over the top: still solid */
    CHECK_EQ(twin_solid_as(V3(0.6f, EMPTY_Y, 0.6f), 0.2f, 0.0f), 0.6f - 0.2f);
    CHECK_EQ(twin_solid_as(V3(-2, EMPTY_Y, -2), 0.5f, 0.0f), 1e30f);
    CHECK_EQ(twin_solid_as(V3(0.7f, -1.1f, 0.7f), 0.1f, 0.0f), -0.1f);
    /* a thing under the water (a boulder: top -1.8, bottom -2.4) is seen by
     * the floor pass too (floor = top): it is the slab alone, not a column
     * down from its top (issue #16); 0.2 m under it is free */
    CHECK_NEAR(twin_solid(V3(-1.8f, -2.4f, -1.8f), -2.6f), 0.2, 1e-6);
    CHECK_NEAR(twin_solid(V3(-1.8f, -2.4f, -1.8f), -2.0f), -0.2, 1e-6);
    CHECK_NEAR(twin_solid(V3(-1.8f, -2.4f, -1.8f), -1.5f), 0.3, 1e-6);
    CHECK_EQ(twin_solid(V3(EMPTY_Y, EMPTY_Y, EMPTY_Y), 0.0f), 1e30f);
}

/* ---- skipping empty space ---- */

static uint32_t lcg_state;
static double lcg(void) {   /* uniform in [0, 1) */
    lcg_state = lcg_state * 1664525u + 1013904223u;
    return (lcg_state >> 8) * (1.0 / 16777216.0);
}

/* A world for the march up: a shore rising out of the water along +x
 * (ground from 2 m under the water to 1 m over it), boxes of every kind
 * (under the water, crossing it, floating over it with a bottom, tall
 * poles) and the border with nothing drawn, as pack_y.frag leaves it. */
static void hf_skip_world(void) {
    cam_top = twin_top_camera(LEVEL, HALF, DEPTH);
    floor_desc f = { LEVEL - 0.5, 0.125, 0, 0.3, 5.0 };
    hf_floor(&f);
    lcg_state = 12345u;
    for (int b = 0; b < 60; b++) {
        double cx = -11 + 22 * lcg(), cz = -11 + 22 * lcg(), hx = 0.05 + 0.8 * lcg(), hz = 0.05 + 0.8 * lcg();
        double top = LEVEL - 1.0 + 4.0 * lcg();
        bool floating = lcg() < 0.4;
        double bottom = top - 0.2 - 1.3 * lcg();
        for (int j = 0; j < HF_N; j++)
            for (int i = 0; i < HF_N; i++) {
                if (fabs(texel_x(i) - cx) > hx || fabs(texel_x(j) - cz) > hz) continue;
                float *t = texel(i, j);
                if (stored_y(top) <= t[0]) continue;
                t[0] = stored_y(top);
                if (floating) t[1] = stored_y(bottom);
            }
    }
    int border = HF_N / 42;   /* the 5 % margin beyond the world square, about */
    for (int j = 0; j < HF_N; j++)
        for (int i = 0; i < HF_N; i++)
            if (i < border || j < border || i >= HF_N - border || j >= HF_N - border)
                texel(i, j)[0] = texel(i, j)[1] = texel(i, j)[2] = EMPTY_Y;
}

static float skip_map[MARCH_SKIP_CELLS * MARCH_SKIP_CELLS * 4];

/* The two 1D passes give the L-infinity distance to the nearest blocked
 * cell (beyond the map: blocked), capped at FAR: brute force over the map. */
static void test_skip_map_distances(void) {
    hf_skip_world();
    twin_hf hf = hf_make();
    twin_params p = twin_defaults();
    twin_skip_build(&hf, &p, skip_map);
    static float blocked[MARCH_SKIP_CELLS * MARCH_SKIP_CELLS * 4];
    twin_skip_blocked(&hf, &p, blocked);
    const int c = MARCH_SKIP_CELLS;
    long checked = 0, wrong = 0, free_cells[4] = { 0 };
    for (int y = 0; y < c; y += 3)
        for (int x = 0; x < c; x += 3)
            for (int k = 0; k < 4; k++) {
                int edge = x + 1;   /* the nearest cell beyond the map */
                if (y + 1 < edge) edge = y + 1;
                if (c - x < edge) edge = c - x;
                if (c - y < edge) edge = c - y;
                float r = fminf((float)edge, MARCH_SKIP_FAR);
                for (int by = 0; by < c; by++)
                    for (int bx = 0; bx < c; bx++)
                        if (blocked[((size_t)by * c + bx) * 4 + k] == 0.0f)
                            r = fminf(r, (float)(abs(bx - x) > abs(by - y) ? abs(bx - x) : abs(by - y)));
                float got = skip_map[((size_t)y * c + x) * 4 + k];
                checked++;
                if (got != r) wrong++;
                if (got > 1) free_cells[k]++;
            }
    fprintf(stderr, "  skip map: %ld cells x levels checked, %ld wrong; free (r > 1) per level: %ld %ld %ld %ld\n",
            checked, wrong, free_cells[0], free_cells[1], free_cells[2], free_cells[3]);
    CHECK_EQ(wrong, 0);
    /* the world leaves room at every level, more the higher */
    CHECK_GT(free_cells[0], 50);
    CHECK_GT(free_cells[3], free_cells[0]);
}

/* The march up with the skip map reads fewer samples and ends exactly where
 * the plain march does: the same t, f, ta, tb and status, bit for bit, for
 * rays from the waves' heights in every direction, with water.frag's
 * steps and with short budgets and a low ceiling (the jumps' clamps). */
static void test_skip_march_is_the_plain_march(void) {
    hf_skip_world();
    twin_hf hf = hf_make();
    twin_params p = twin_defaults();
    twin_skip_build(&hf, &p, skip_map);
    struct { int max_iter, refine, mode; float y_max, max_step; } sets[] = {
        { 40, 6, REFINE_BINARY, (float)LEVEL + 5.0f, 0.25f },   /* water.frag's defaults */
        { 12, 3, REFINE_SECANT, (float)LEVEL + 0.8f, 0.1f },
        { 64, 0, REFINE_NONE, (float)LEVEL + 20.0f, 0.5f },
    };
    for (size_t set = 0; set < sizeof sets / sizeof sets[0]; set++) {
        p.max_iter = sets[set].max_iter;
        p.refine = sets[set].refine;
        p.refine_mode = sets[set].mode;
        p.y_max = sets[set].y_max;
        lcg_state = 777u + (uint32_t)set;
        long differ = 0, by_status[4] = { 0 }, samples_plain = 0, samples_skip = 0;
        const int nrays = 20000;
        for (int k = 0; k < nrays; k++) {
            v3 o = V3((float)(-12 + 24 * lcg()), (float)(LEVEL - 0.4 + 0.7 * lcg()), (float)(-12 + 24 * lcg()));
            double az = 2 * PI * lcg(), up = lcg() * lcg();   /* many grazing rays */
            v3 d = twin_clamp_dir(V3((float)cos(az), (float)up, (float)sin(az)), false);
            float step = twin_step(5.0f, d.y, 10, 3, sets[set].max_step);
            p.skip = NULL;
            twin_march a = twin_march_hf(&hf, o, d, step, &p);
            p.skip = skip_map;
            twin_march b = twin_march_hf(&hf, o, d, step, &p);
            bool same = a.status == b.status && memcmp(&a.t, &b.t, sizeof a.t) == 0 &&
                        memcmp(&a.f, &b.f, sizeof a.f) == 0 && memcmp(&a.ta, &b.ta, sizeof a.ta) == 0 &&
                        (a.status != MARCH_HIT || memcmp(&a.tb, &b.tb, sizeof a.tb) == 0);
            if (!same && differ++ < 3)
                fprintf(stderr, "  ray %d: plain %d t %.9g ta %.9g, skipping %d t %.9g ta %.9g\n", k, a.status,
                        a.t, a.ta, b.status, b.t, b.ta);
            by_status[a.status]++;
            samples_plain += a.steps;
            samples_skip += b.steps;
        }
        fprintf(stderr, "  set %zu: %d rays (hit %ld, inside %ld, cap %ld, left %ld), %ld differ; "
                "samples read %.2f -> %.2f a ray\n", set, nrays, by_status[0], by_status[1], by_status[2],
                by_status[3], differ, (double)samples_plain / nrays, (double)samples_skip / nrays);
        CHECK_EQ(differ, 0);
        for (int st = 0; st < 4; st++) CHECK_GT(by_status[st], 10);   /* every ending is exercised */
        CHECK_LT(samples_skip, samples_plain * 3 / 4);
    }
}

/* ---- the Fresnel table ---- */

static void test_fresnel_table(void) {
    const float ior = 1.333f;
    float lut[2][LUT_W];
    twin_lut_build(ior, lut);
    double cos_c = sqrt(1 - 1 / (1.333 * 1.333));
    /* the source's table: the same cos-indexed table for the water side */
    float src_row[LUT_W];
    for (int i = 0; i < LUT_W; i++) src_row[i] = world_fresnel((float)i / (LUT_W - 1), ior, 1.0f);
    double above = 0, below = 0, plain = 0, plain_at = 0;
    for (int k = 0; k <= 200000; k++) {
        double c = k / 200000.0;
        above = fmax(above, fabs(lut_at(lut[0], (float)c) - ref_fresnel(c, 1.0, 1.333)));
        double exact = ref_fresnel(c, 1.333, 1.0);
        below = fmax(below, fabs(twin_fresnel_from_water(lut, ior, (float)c) - exact));
        double e = fabs(lut_at(src_row, (float)c) - exact);
        if (e > plain) { plain = e; plain_at = c; }
    }
    fprintf(stderr, "  Fresnel table %d texels: max error air->water %.2g, water->air %.2g "
            "(a plain cos table: %.3f at %.2f deg, the critical angle is %.2f deg)\n",
            LUT_W, above, below, plain, acos(plain_at) * 180 / PI, acos(cos_c) * 180 / PI);
    CHECK_LT(above, 2e-4);
    CHECK_LT(below, 2e-3);
    CHECK_GT(plain, 0.05);   /* why the table is remapped below the water */
    /* reference values (DESIGN.md) */
    CHECK_NEAR(lut_at(lut[0], 1.0f), 0.0204, 5e-5);
    CHECK_NEAR(lut_at(lut[0], (float)cos(60 * PI / 180)), 0.0597, 2e-4);
    CHECK_NEAR(lut_at(lut[0], (float)cos(80 * PI / 180)), 0.348, 1e-3);
    CHECK_NEAR(lut_at(lut[0], (float)cos(85 * PI / 180)), 0.584, 2e-3);
}

/* ======================================================================
 * The pack on GL (headless)
 * ====================================================================== */

#define W 96
#define H 54
#define LAKE TARN_SOURCE_DIR "/scenes/lake.glib"
#define DATA TARN_SOURCE_DIR "/tests/data/raymarch/"
#define PROGRAM "RaymarchWater"

static bool have_gl;
static bool defines_changed;   /* a Define was set: rebuild before drawing */
static float px[W * H * 4];

static render *load_scene(const char *path) {
    defines_changed = false;
    render_desc rd = { .pack = "raymarch" };
    render *r = render_create(&rd);
    bool ok = render_load(r, path);
    CHECK_MSG(ok && !render_has_errors(r), "%s", render_messages(r));
    return r;
}

static unif_entry *find_entry(render *r, const char *name) {
    int n = 0;
    unif_set *sets = render_uniforms(r, &n);
    for (int i = 0; i < n; i++) {
        if (strcmp(sets[i].program, PROGRAM) != 0) continue;
        for (int k = 0; k < sets[i].n; k++)
            if (strcmp(sets[i].entries[k].name, name) == 0) return &sets[i].entries[k];
    }
    return NULL;
}

/* Sets a uniform's or a Define's value (all components to v); a changed
 * Define rebuilds the programs before the next draw. */
static void set_value(render *r, const char *name, float v) {
    unif_entry *e = find_entry(r, name);
    CHECK_MSG(e != NULL, "no uniform or Define '%s' in %s", name, PROGRAM);
    if (!e) return;
    if (e->is_define && e->value[0] != v) defines_changed = true;
    for (int k = 0; k < e->ncomp && k < UNIF_MAX_COMPONENTS; k++) e->value[k] = v;
}

static void apply_defines(render *r) {
    if (!defines_changed) return;
    CHECK_MSG(render_rebuild_programs(r) && !render_has_errors(r), "%s", render_messages(r));
    defines_changed = false;
}

static void draw(render *r, double t, const render_view *v) {
    apply_defines(r);
    render_target tg;
    CHECK(render_target_create(&tg, W, H, true));
    render_frame(r, t, tg.fbo, W, H, v);
    render_target_read(&tg, px);
    render_target_destroy(&tg);
    GLenum e = glGetError();
    CHECK_MSG(e == GL_NO_ERROR, "GL error 0x%x", e);
}

static long nonfinite(void) {
    long bad = 0;
    for (int i = 0; i < W * H * 4; i++)
        if (!isfinite(px[i])) bad++;
    return bad;
}

static void test_gl_lake_at_several_times(void) {
    if (!have_gl) SKIP("no headless OpenGL");
    render *r = load_scene(LAKE);
    const double times[] = { 0.0, 3.3, 47.0 };
    for (int k = 0; k < 3; k++) {
        draw(r, times[k], NULL);
        CHECK_MSG(nonfinite() == 0, "%ld non-finite values at t = %g", nonfinite(), times[k]);
    }
    /* the top camera looks straight down, as march.glsl's depth-to-Y assumes */
    float m[16];
    CHECK(render_read_uniform(r, PROGRAM, "uCamTopVP", m, 16));
    CHECK(m[2] == 0.0f && m[10] == 0.0f && m[6] != 0.0f);
    render_destroy(r);
}

/* Every toggle on its own and every debug output, above and under the
 * water (looking along the floor, and up at the surface: Snell's window
 * and total internal reflection). */
/* The march up with the skip map (MARCH_SKIP, the default) draws what the
 * plain march draws, bit for bit: the colour and the reflected ray's point
 * and status (DEBUG_OUTPUT 2), from above and from under the water, on the
 * lake and the harbour (piers, boats); and reads fewer texels (DEBUG_OUTPUT
 * 5, both marches' count). */
static void test_gl_skip_is_the_plain_march(void) {
    if (!have_gl) SKIP("no headless OpenGL");
    const char *scenes[] = { LAKE, TARN_SOURCE_DIR "/scenes/harbour.glib" };
    const render_view views[] = {
        { { 9, 2.5f, 9 }, { -2, -0.6f, -1 }, { 0, 1, 0 } },
        { { -6, 0.6f, 7 }, { 4, 0.2f, -5 }, { 0, 1, 0 } },
        { { 0.5f, -1.6f, 0.5f }, { 1.5f, 0.5f, 0.0f }, { 0, 1, 0 } },
    };
    static float plain[W * H * 4];
    for (int sc = 0; sc < 2; sc++) {
        render *r = load_scene(scenes[sc]);
        const int outputs[] = { 0, 2, 5 };   /* colour, reflection hit, texels read */
        for (int o = 0; o < 3; o++) {
            int dbg = outputs[o];
            set_value(r, "DEBUG_OUTPUT", (float)dbg);
            for (int v = 0; v < 3; v++) {
                set_value(r, "MARCH_SKIP", 0);
                draw(r, 2.0, &views[v]);
                memcpy(plain, px, sizeof px);
                set_value(r, "MARCH_SKIP", 1);
                draw(r, 2.0, &views[v]);
                if (dbg == 5) {   /* texels read: fewer, never more */
                    double a = 0, b = 0;
                    for (int i = 0; i < W * H; i++) { a += plain[i * 4]; b += px[i * 4]; }
                    fprintf(stderr, "  %s view %d: world-Y texels read %.1f -> %.1f a pixel\n",
                            sc ? "harbour" : "lake", v, a / (W * H), b / (W * H));
                    CHECK_LT(b, a);
                    continue;
                }
                long differ = 0;
                for (int i = 0; i < W * H * 4; i++) differ += memcmp(&plain[i], &px[i], sizeof px[i]) != 0;
                CHECK_MSG(differ == 0, "%s, view %d, DEBUG_OUTPUT %d: %ld values differ with the skip map",
                          sc ? "harbour" : "lake", v, dbg, differ);
            }
        }
        render_destroy(r);
    }
}

static void test_gl_lake_variants_and_under_water(void) {
    if (!have_gl) SKIP("no headless OpenGL");
    render *r = load_scene(LAKE);
    const render_view views[] = {
        { { 9, 2.5f, 9 }, { -2, -0.6f, -1 }, { 0, 1, 0 } },
        { { -1, -1.2f, 1 }, { 3, -0.4f, -3 }, { 0, 1, 0 } },
        { { 0.5f, -1.6f, 0.5f }, { 1.5f, 0.5f, 0.0f }, { 0, 1, 0 } },
    };
    struct { const char *name; float on, off; } toggles[] = {
        { "NOREFLECTION", 1, 0 },  { "BEER_LAMBERT", 0, 1 }, { "REFINE_SECANT", 0, 1 },
        { "REFINE_BINARY", 1, 0 }, { "FRESNEL_LUT", 0, 1 },  { "NORMAL_MAP", 1, 0 },
    };
    /* flipped one after another, each kept: every toggle is drawn in both
     * states, and with the others in both states */
    for (int k = -1; k < 6; k++) {
        if (k >= 0) set_value(r, toggles[k].name, toggles[k].on);
        for (int v = 0; v < 3; v++) {
            draw(r, 2.0, &views[v]);
            CHECK_MSG(nonfinite() == 0, "%s, view %d: %ld non-finite", k >= 0 ? toggles[k].name : "defaults", v,
                      nonfinite());
        }
    }
    for (int k = 0; k < 6; k++) set_value(r, toggles[k].name, toggles[k].off);
    for (int dbg = 1; dbg <= 4; dbg++) {
        set_value(r, "DEBUG_OUTPUT", (float)dbg);
        for (int v = 0; v < 3; v++) {
            draw(r, 2.0, &views[v]);
            CHECK_MSG(nonfinite() == 0, "DEBUG_OUTPUT %d, view %d: %ld non-finite", dbg, v, nonfinite());
        }
    }
    /* looking up from under the water: Fresnel 1 beyond the critical angle,
     * small inside Snell's window */
    set_value(r, "DEBUG_OUTPUT", 3);
    draw(r, 2.0, &views[2]);
    int tir = 0, window = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            const float *p = px + ((size_t)j * W + i) * 4;
            if (p[3] != 1.0f || p[0] != p[1] || p[1] != p[2]) continue;
            if (p[0] == 1.0f) tir++;
            else if (p[0] < 0.1f) window++;
        }
    fprintf(stderr, "  looking up from under the water: %d pixels of total internal reflection, %d in Snell's window\n",
            tir, window);
    CHECK(tir > 50 && window > 50);
    render_destroy(r);
}

/* ---- against the reference ---- */

typedef struct {
    ref_world world;
    scene_camera cam;
    ref_render_result ref;
    double texel;           /* world units per texel of the top-down textures */
} ref_scene;

static bool reference(const char *path, ref_scene *s) {
    ref_world_desc desc;
    bool has_world = false;
    char err[2048];
    if (!scene_load(path, "raymarch", &desc, &s->cam, &has_world, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        return false;
    }
    ref_world_init(&s->world, &desc);
    ref_render_desc d = { .world = &s->world, .caustics = REF_CAUSTICS_FLAT, .threads = 2 };
    for (int k = 0; k < 3; k++) {
        d.camera.eye[k] = s->cam.eye[k];
        d.camera.center[k] = s->cam.center[k];
        d.camera.up[k] = s->cam.up[k];
    }
    d.camera.fov_deg = s->cam.fov_deg;
    d.camera.width = W;
    d.camera.height = H;
    s->texel = 2.0 * 1.05 * s->world.d.half_size / 1024.0;
    if (ref_render(&d, &s->ref, err, sizeof err) != 0) {
        fprintf(stderr, "ref_render: %s\n", err);
        return false;
    }
    return true;
}

/* Water pixels away from the water's edge in the reference, on the world
 * square (the reference's water goes on beyond it, tarn's grid does not). */
static bool interior_water(const ref_scene *s, int i, int j) {
    for (int dj = -1; dj <= 1; dj++)
        for (int di = -1; di <= 1; di++) {
            int x = i + di, y = j + dj;
            if (x < 0 || y < 0 || x >= W || y >= H) return false;
            size_t p = (size_t)y * W + x;
            if (s->ref.mask[p] != REF_MASK_WATER) return false;
            double lim = s->world.d.half_size - 0.2;
            if (!(fabs(s->ref.surface[p * 3]) < lim && fabs(s->ref.surface[p * 3 + 2]) < lim)) return false;
        }
    return true;
}

typedef struct {
    long n, status_other;
    double mean, p95, max;      /* texels (hit points) or the quantity's units */
} cmp_stats;

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static cmp_stats finish(double *v, long n, long other) {
    cmp_stats c = { n, other, 0, 0, 0 };
    if (n == 0) return c;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    for (long k = 0; k < n; k++) c.mean += v[k];
    c.mean /= (double)n;
    c.p95 = ref_percentile_sorted(v, n, 95);
    c.max = v[n - 1];
    return c;
}

/* The refraction hit (DEBUG_OUTPUT 1) against ref refract_hit, in texels,
 * over the pixels whose march bracketed the ground; status_other counts
 * the others (no bracket: the ray left the world square, where the
 * reference's plane goes on; their hit is the extension). */
static cmp_stats compare_refract_hits(render *r, const ref_scene *s) {
    set_value(r, "DEBUG_OUTPUT", 1);
    draw(r, 0.0, NULL);
    static double v[W * H];
    long n = 0, other = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            size_t p = (size_t)j * W + i;
            if (!interior_water(s, i, j) || s->ref.refract_hit[p * 4 + 3] != REF_MASK_TERRAIN) continue;
            const float *g = px + p * 4;
            if (g[3] != (float)MARCH_HIT) { other++; continue; }
            double d = 0;
            for (int k = 0; k < 3; k++) d += (g[k] - s->ref.refract_hit[p * 4 + k]) * (g[k] - s->ref.refract_hit[p * 4 + k]);
            v[n++] = sqrt(d) / s->texel;
        }
    return finish(v, n, other);
}

/* A scalar debug output (3 Fresnel, 4 path in water) against a ref buffer. */
static cmp_stats compare_scalar(render *r, const ref_scene *s, int dbg, const double *buf, bool relative) {
    set_value(r, "DEBUG_OUTPUT", (float)dbg);
    draw(r, 0.0, NULL);
    static double v[W * H];
    long n = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            size_t p = (size_t)j * W + i;
            if (!interior_water(s, i, j) || !isfinite(buf[p])) continue;
            if (dbg == 4 && s->ref.refract_hit[p * 4 + 3] != REF_MASK_TERRAIN) continue;
            double e = fabs(px[p * 4] - buf[p]);
            v[n++] = relative ? e / fmax(fabs(buf[p]), 1e-3) : e;
        }
    return finish(v, n, 0);
}

/* The colour (DEBUG_OUTPUT 0, no highlight, no in-scattering) against the
 * reference's over the interior water pixels. */
static ref_image_metrics compare_color(render *r, const ref_scene *s) {
    set_value(r, "DEBUG_OUTPUT", 0);
    set_value(r, "uSpecular", 0);
    set_value(r, "uWaterColor", 0);
    draw(r, 0.0, NULL);
    static float a[W * H * 3], b[W * H * 3];
    static unsigned char mask[W * H];
    for (int p = 0; p < W * H; p++) {
        for (int k = 0; k < 3; k++) {
            a[p * 3 + k] = px[p * 4 + k];
            b[p * 3 + k] = (float)s->ref.color[p * 3 + k];
        }
        mask[p] = interior_water(s, p % W, p / W);
    }
    ref_fimage fa = { a, W, H, 3 }, fb = { b, W, H, 3 };
    ref_metrics_desc md = { .mask = mask };
    ref_image_metrics m;
    char err[256];
    CHECK_MSG(ref_metrics_image(&fa, &fb, &md, &m, err, sizeof err), "%s", err);
    return m;
}

static void print_hits(const char *what, cmp_stats c) {
    fprintf(stderr, "  %-34s %5ld px  mean %.3f  p95 %.3f  max %.3f texel%s", what, c.n, c.mean, c.p95, c.max,
            c.status_other ? "" : "\n");
    if (c.status_other) fprintf(stderr, "  (%ld px left the world)\n", c.status_other);
}

/* REFINE_SECANT / REFINE_BINARY and uRefineSteps */
static void set_refine(render *r, int mode, int steps) {
    set_value(r, "REFINE_SECANT", mode == REFINE_SECANT ? 1.0f : 0.0f);
    set_value(r, "REFINE_BINARY", mode == REFINE_BINARY ? 1.0f : 0.0f);
    set_value(r, "uRefineSteps", (float)steps);
}

/* The reference of a test scene (its buffers in s) and the scene loaded
 * with the pack; NULL (a failed check) when the reference cannot be made. */
static render *with_reference(const char *file, ref_scene *s) {
    memset(s, 0, sizeof *s);
    CHECK(reference(file, s));
    if (!s->ref.color) return NULL;
    return load_scene(file);
}

static void check_floor_scene(const char *file, double bound_refined) {
    if (!have_gl) SKIP("no headless OpenGL");
    ref_scene s;
    render *r = with_reference(file, &s);
    if (!r) return;
    fprintf(stderr, "  %s at %dx%d, top-down texel %.4f m\n", strrchr(file, '/') + 1, W, H, s.texel);
    set_refine(r, REFINE_NONE, 0);
    cmp_stats lin = compare_refract_hits(r, &s);
    print_hits("refraction hit, linear (source)", lin);
    set_refine(r, REFINE_SECANT, 2);
    print_hits("refraction hit, secant 2", compare_refract_hits(r, &s));
    set_refine(r, REFINE_SECANT, 4);
    cmp_stats sec4 = compare_refract_hits(r, &s);
    print_hits("refraction hit, secant 4", sec4);
    set_refine(r, REFINE_BINARY, 6);
    cmp_stats bin6 = compare_refract_hits(r, &s);
    print_hits("refraction hit, binary 6 (default)", bin6);
    CHECK_GT(bin6.n, W * H / 4);
    CHECK_MSG(sec4.p95 <= bound_refined && bin6.p95 <= bound_refined, "p95 %.3f / %.3f texels", sec4.p95,
              bin6.p95);
    cmp_stats fr = compare_scalar(r, &s, 3, s.ref.fresnel, false);
    fprintf(stderr, "  %-34s %5ld px  mean %.2g  p95 %.2g  max %.2g\n", "Fresnel (table), absolute", fr.n, fr.mean,
            fr.p95, fr.max);
    CHECK_LT(fr.max, 2e-3);
    cmp_stats dp = compare_scalar(r, &s, 4, s.ref.depth, true);
    fprintf(stderr, "  %-34s %5ld px  mean %.2g  p95 %.2g  max %.2g\n", "path in water, relative", dp.n, dp.mean,
            dp.p95, dp.max);
    CHECK_LT(dp.p95, 0.02);
    ref_image_metrics m = compare_color(r, &s);
    fprintf(stderr, "  colour (water px, no highlight):   rmse %.4f  psnr %.1f dB  mae %.4f  max %.4f  "
            "bias %+.4f %+.4f %+.4f\n", m.rmse, m.psnr_db, m.mae, m.max_abs, m.bias[0], m.bias[1], m.bias[2]);
    CHECK_LT(m.rmse, 0.05);
    render_destroy(r);
    ref_render_free(&s.ref);
}

static void test_gl_flat_floor_against_reference(void) { check_floor_scene(DATA "flat.glib", 0.05); }

static void test_gl_sloped_floor_against_reference(void) { check_floor_scene(DATA "slope.glib", 0.75); }

/* A sphere floating across the surface (tests/data/raymarch/sphere.glib):
 * the floor pass sees the sphere itself between its waterline and its rim,
 * so no pass saw the ground under that ring; the refracted rays that pass
 * under the sphere must still meet the floor, 2 m down, as the reference's
 * do (pack_y.frag takes the terrain's model there). Refraction hits over
 * the water pixels whose reference hit is the floor: none more than 0.1 m
 * off (measured: 0; before, 98 of 4348 met the side of the ring's next
 * column, up to 130 texels, 2.1 m, off). */
static void test_gl_floor_under_a_floating_sphere(void) {
    if (!have_gl) SKIP("no headless OpenGL");
    ref_scene s;
    render *r = with_reference(DATA "sphere.glib", &s);
    if (!r) return;
    cmp_stats c = compare_refract_hits(r, &s);
    print_hits("floor hit round a floating sphere", c);
    CHECK_GT(c.n, W * H / 4);
    CHECK_MSG(c.max * s.texel < 0.1, "max %.2f texels (%.3f m)", c.max, c.max * s.texel);
    render_destroy(r);
    ref_render_free(&s.ref);
}

/* The normal map's sense (NORMAL_MAP, uBumpMult: Lipp's BumptexMult). Seen
 * straight down over calm water with the map standing still (uNormalSpeed
 * 0, so the four taps agree), a pixel's normal is n = (a, 1) normalised
 * with a = uBumpMult m.xz / m.y, m the map's normal at the pixel's surface
 * point; the reflected ray goes to the sky, so DEBUG_OUTPUT 2 gives its
 * direction r, n is the half vector of r and the eye direction e, and
 * a = (r + e).xz / (r + e).y. Against a from the baked map
 * itself (assets_bake_water_normal, read bilinearly here), the regression
 * slope must be 1 within 2 % and the correlation over 0.999 at BumptexMult
 * 1 and 2: a map added in the opposite sense gives -1, a wrong scale its
 * factor. GL's 16-bit texels and its 8-bit bilinear weights leave a little
 * scatter (measured: slope 1.000, correlation 1.0000), hence the bounds. */
static void test_gl_normal_map_sense(void) {
    if (!have_gl) SKIP("no headless OpenGL");
    ref_scene s;
    render *r = with_reference(DATA "normal_map.glib", &s);
    if (!r) return;
    enum { RES = 256 };   /* render_res.c's size for a generated texture */
    static float map[RES * RES * 3];
    CHECK(assets_bake_water_normal(RES, map));
    set_value(r, "NORMAL_MAP", 1);
    set_value(r, "uNormalSpeed", 0);
    set_value(r, "DEBUG_OUTPUT", 2);
    unif_entry *tile = find_entry(r, "uNormalTile");
    for (int bump = 1; bump <= 2; bump++) {
        set_value(r, "uBumpMult", (float)bump);
        apply_defines(r);
        draw(r, 0.0, NULL);
        double sxy = 0, sxx = 0, syy = 0;
        long n = 0;
        for (int p = 0; p < W * H; p++) {
            const float *g = px + p * 4;
            const double *q = s.ref.surface + p * 3;
            if (g[3] != (float)MARCH_LEFT || !isfinite(q[0]) || !tile) continue;
            /* the map at st = xz / tile, bilinear with wrap, as GL reads it */
            double u = q[0] / tile->value[0] * RES - 0.5, v = q[2] / tile->value[0] * RES - 0.5;
            int i0 = (int)floor(u), j0 = (int)floor(v);
            double fu = u - i0, fv = v - j0, m[3] = { 0, 0, 0 };
            for (int dj = 0; dj < 2; dj++)
                for (int di = 0; di < 2; di++) {
                    int i = ((i0 + di) % RES + RES) % RES, j = ((j0 + dj) % RES + RES) % RES;
                    double wgt = (di ? fu : 1 - fu) * (dj ? fv : 1 - fv);
                    for (int k = 0; k < 3; k++) m[k] += wgt * map[((size_t)j * RES + i) * 3 + k];
                }
            double mx = 2 * m[0] - 1, mz = 2 * m[1] - 1, my = 2 * m[2] - 1;   /* stored (x, z, y) */
            double want[2] = { bump * mx / my, bump * mz / my };
            /* the normal is the half vector of the eye and reflected directions */
            double e[3], el = 0;
            for (int k = 0; k < 3; k++) { e[k] = s.cam.eye[k] - q[k]; el += e[k] * e[k]; }
            el = sqrt(el);
            double h[3] = { g[0] + e[0] / el, g[1] + e[1] / el, g[2] + e[2] / el };
            double got[2] = { h[0] / h[1], h[2] / h[1] };
            for (int k = 0; k < 2; k++) {
                sxy += got[k] * want[k];
                sxx += want[k] * want[k];
                syy += got[k] * got[k];
            }
            n++;
        }
        double slope = sxx > 0 ? sxy / sxx : 0, corr = sxx > 0 && syy > 0 ? sxy / sqrt(sxx * syy) : 0;
        fprintf(stderr, "  normal map, BumptexMult %d: %ld px, slope %.3f (want 1), correlation %.4f, rms slope %.4f\n",
                bump, n, slope, corr, sqrt(sxx / (2.0 * (n > 0 ? n : 1))));
        CHECK_GT(n, W * H / 3);
        CHECK_MSG(fabs(slope - 1) < 0.02, "slope %.3f", slope);
        CHECK_MSG(corr > 0.999, "correlation %.4f", corr);
    }
    render_destroy(r);
    ref_render_free(&s.ref);
}

/* Reflections of a floating box: the reflected ray meets its underside
 * (the solid's bottom) where the reference's does. */
typedef struct { long n, ref_only, gl_only, sky; cmp_stats c; } refl_cmp;

static refl_cmp compare_reflections(render *r, const ref_scene *s) {
    set_value(r, "DEBUG_OUTPUT", 2);
    draw(r, 0.0, NULL);
    static double v[W * H];
    refl_cmp out = { 0, 0, 0, 0, { 0, 0, 0, 0, 0 } };
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            size_t p = (size_t)j * W + i;
            if (!interior_water(s, i, j)) continue;
            const float *g = px + p * 4;
            bool gl_hit = g[3] == (float)MARCH_HIT || g[3] == (float)MARCH_INSIDE;
            bool ref_hit = s->ref.reflect[p * 4 + 3] == REF_REFLECT_POINT;
            if (gl_hit && ref_hit) {
                double d = 0;
                for (int k = 0; k < 3; k++) d += (g[k] - s->ref.reflect[p * 4 + k]) * (g[k] - s->ref.reflect[p * 4 + k]);
                v[out.n++] = sqrt(d) / s->texel;
            } else if (ref_hit) out.ref_only++;
            else if (gl_hit) out.gl_only++;
            else out.sky++;
        }
    out.c = finish(v, out.n, 0);
    return out;
}

static void print_refl(const char *what, refl_cmp c) {
    fprintf(stderr, "  %-20s %4ld px meet the box in both: mean %.2f, p95 %.2f, max %.2f texel; "
            "%ld only in the reference, %ld only in GL, %ld sky in both\n", what, c.n, c.c.mean, c.c.p95, c.c.max,
            c.ref_only, c.gl_only, c.sky);
}

static void test_gl_floating_box_reflection(void) {
    if (!have_gl) SKIP("no headless OpenGL");
    ref_scene s;
    render *r = with_reference(DATA "box.glib", &s);
    if (!r) return;
    fprintf(stderr, "  box.glib at %dx%d, reflections, top-down texel %.4f m\n", W, H, s.texel);
    refl_cmp bin = compare_reflections(r, &s);
    print_refl("binary 6 (default)", bin);
    set_refine(r, REFINE_NONE, 0);
    print_refl("linear (source)", compare_reflections(r, &s));
    set_refine(r, REFINE_SECANT, 4);
    refl_cmp sec = compare_reflections(r, &s);
    print_refl("secant 4", sec);
    set_refine(r, REFINE_BINARY, 6);
    set_value(r, "uReflectStep", 0.5f);
    print_refl("binary 6, step 0.5", compare_reflections(r, &s));
    set_value(r, "uReflectStep", 0.1f);
    print_refl("binary 6, step 0.1", compare_reflections(r, &s));
    CHECK(sec.n > 100 && bin.n > 100);
    CHECK_LT(bin.c.p95, sec.c.p95);   /* f jumps at the box's edge: bisection beats regula falsi */
    CHECK_LT(bin.ref_only + bin.gl_only, bin.n / 5);
    CHECK_LT(bin.c.p95, 8);
    render_destroy(r);
    ref_render_free(&s.ref);
}

/* Mean world-Y texels read per interior water pixel (DEBUG_OUTPUT 5). */
static double mean_fetches(render *r, const ref_scene *s) {
    set_value(r, "DEBUG_OUTPUT", 5);
    draw(r, 0.0, NULL);
    double sum = 0;
    long n = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            if (interior_water(s, i, j)) { sum += px[((size_t)j * W + i) * 4]; n++; }
    return n ? sum / (double)n : 0;
}

/* The lake (waves, shore, objects) against the reference, for a few
 * settings: the refraction hit, the Fresnel factor, the colour, and the
 * cost in texels read: the page's speed-against-error table. */
static void test_gl_lake_against_reference(void) {
    if (!have_gl) SKIP("no headless OpenGL");
    ref_scene s;
    render *r = with_reference(LAKE, &s);
    if (!r) return;
    fprintf(stderr, "  lake.glib at %dx%d, t = 0, top-down texel %.4f m; per interior water pixel:\n", W, H, s.texel);
    fprintf(stderr, "  %-44s %-9s %-16s %-8s %-8s %s\n", "setting", "texels", "refr. hit p95", "rmse", "psnr",
            "p95 px error");
    struct { const char *what; int refine, steps; float max_step; int noreflection; } set[] = {
        { "source: linear, step 0.5", REFINE_NONE, 0, 0.5f, 0 },
        { "source, NOREFLECTION", REFINE_NONE, 0, 0.5f, 1 },
        { "secant 4, step 0.5", REFINE_SECANT, 4, 0.5f, 0 },
        { "binary 6, step 0.5", REFINE_BINARY, 6, 0.5f, 0 },
        { "binary 6, step 0.25 (defaults)", REFINE_BINARY, 6, 0.25f, 0 },
        { "binary 6, step 1 (the cap before issue #24)", REFINE_BINARY, 6, 1.0f, 0 },
        { "binary 6, step 0.1", REFINE_BINARY, 6, 0.1f, 0 },
    };
    cmp_stats def_hits = { 0, 0, 0, 0, 0 };
    ref_image_metrics def_m;
    memset(&def_m, 0, sizeof def_m);
    for (size_t k = 0; k < sizeof set / sizeof *set; k++) {
        set_refine(r, set[k].refine, set[k].steps);
        set_value(r, "uMaxStep", set[k].max_step);
        set_value(r, "NOREFLECTION", (float)set[k].noreflection);
        double cost = mean_fetches(r, &s);
        cmp_stats hits = compare_refract_hits(r, &s);
        ref_image_metrics m = compare_color(r, &s);
        fprintf(stderr, "  %-44s %-9.1f %-16.3f %-8.4f %-8.1f %.4f\n", set[k].what, cost, hits.p95, m.rmse, m.psnr_db,
                m.pixel_err.p95);
        if (set[k].max_step == 0.25f && set[k].refine == REFINE_BINARY) { def_hits = hits; def_m = m; }
    }
    set_value(r, "uMaxStep", 0.25f);
    cmp_stats fr = compare_scalar(r, &s, 3, s.ref.fresnel, false);
    fprintf(stderr, "  refraction hit, defaults: %ld px, mean %.3f, p95 %.3f texel (%ld px left the world)\n",
            def_hits.n, def_hits.mean, def_hits.p95, def_hits.status_other);
    fprintf(stderr, "  Fresnel, defaults: mean %.2g, p95 %.2g, max %.2g; colour bias %+.4f %+.4f %+.4f\n", fr.mean,
            fr.p95, fr.max, def_m.bias[0], def_m.bias[1], def_m.bias[2]);
    CHECK(def_hits.n > 1000 && def_hits.p95 < 2);
    CHECK_LT(fr.p95, 0.01);
    CHECK_LT(def_m.rmse, 0.05);
    render_destroy(r);
    ref_render_free(&s.ref);
}

static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

#define RUN_TIMED(fn) do { double t_ = now(); clock_t c_ = clock(); RUN(fn); \
    fprintf(stderr, "  (%.1f s, cpu %.1f s)\n", now() - t_, (double)(clock() - c_) / CLOCKS_PER_SEC); } while (0)

int main(void) {
    clock_t t0 = clock();
    RUN(test_twin_flat_floor_is_exact);
    RUN(test_twin_sloped_floor_table);
    RUN(test_twin_sine_floor_table);
    RUN(test_twin_step_count_rule);
    RUN(test_hazard_tir);
    RUN(test_hazard_no_bracket);
    RUN(test_hazard_denominator);
    RUN(test_hazard_grazing);
    RUN(test_hazard_leaving_footprint);
    RUN(test_hazard_shore_and_depth_zero);
    RUN(test_solid_floating_box);
    RUN(test_skip_map_distances);
    RUN(test_skip_march_is_the_plain_march);
    RUN(test_fresnel_table);
    char err[512];
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    have_gl = ctx != NULL;
    if (!ctx) fprintf(stderr, "no headless OpenGL: %s\n", err);
    RUN_TIMED(test_gl_lake_at_several_times);
    RUN_TIMED(test_gl_lake_variants_and_under_water);
    RUN_TIMED(test_gl_skip_is_the_plain_march);
    RUN_TIMED(test_gl_flat_floor_against_reference);
    RUN_TIMED(test_gl_sloped_floor_against_reference);
    RUN_TIMED(test_gl_floating_box_reflection);
    RUN_TIMED(test_gl_floor_under_a_floating_sphere);
    RUN_TIMED(test_gl_normal_map_sense);
    RUN_TIMED(test_gl_lake_against_reference);
    if (ctx) gl_ctx_destroy(ctx);
    fprintf(stderr, "cpu time %.1f s\n", (double)(clock() - t0) / CLOCKS_PER_SEC);
    return check_summary();
}
