/* packs/caustic_tex (Xing's water): the vertex math and its normals, the
 * GLSL against its C twin, no NaN or Inf anywhere in the sliders' ranges,
 * and the caustic irradiance it shows on the floor against the reference's
 * photon-traced floor irradiance (figures in docs/packs/caustic_tex.md).
 *
 *   xing_eval             the C twin of packs/caustic_tex/xing_waves.glsl
 *   test_normals_*        exact normals against central differences
 *   test_glsl_twin        the shader's heights and normals = the twin's
 *   test_*_no_nan         water.glib and the lake over the full slider ranges
 *   test_caustics_vs_reference  statistics of E K against ref_render's
 *                         irradiance buffer on tests/data/caustic_tex/flat.glib
 */
#include <GL/gl.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "gl_ctx.h"
#include "packset.h"
#include "ref_render.h"
#include "render.h"
#include "scene.h"
#include "unif.h"

#define TWO_PI 6.28318530717958647692

/* ---- the C twin of xing_waves.glsl ------------------------------------ */

typedef struct xing_params {
    bool sine_on;
    double sin_dx, sin_dz, sin_amp, sin_freq, sin_speed;
    bool gerst_on;
    double steep, gerst_dx, gerst_dz, gerst_amp, gerst_freq, gerst_speed;
    double timer_seconds;          /* TIMER_SECONDS */
} xing_params;

/* water.glib's defaults: the source's sliders */
static const xing_params xing_defaults = {
    true, 1.0, 0.3, 0.03, 6.0, 0.6,
    true, 0.6, -0.4, 1.0, 0.05, 3.5, 0.8,
    20.0,
};

static void xing_dir(double dx, double dz, double D[2]) {
    double l = sqrt(dx * dx + dz * dz);
    D[0] = l > 1e-6 ? dx / l : 0.0;
    D[1] = l > 1e-6 ? dz / l : 0.0;
}

static double xing_omega(double k, double speed, double T) {
    return TWO_PI * floor(k * speed * T / TWO_PI + 0.5) / T;
}

/* P(u, v, t) relative to the water's plane, and the exact unit normal. */
static void xing_eval(const xing_params *p, double u, double v, double t, double pos[3], double n[3]) {
    double h = 0, dh[2] = { 0, 0 }, disp[2] = { 0, 0 }, a = 0, b = 0, d = 0, D[2];
    if (p->sine_on && p->sin_amp != 0) {
        xing_dir(p->sin_dx, p->sin_dz, D);
        double k = p->sin_freq, A = p->sin_amp;
        double th = k * (D[0] * u + D[1] * v) - xing_omega(k, p->sin_speed, p->timer_seconds) * t;
        h += A * sin(th);
        dh[0] += k * A * cos(th) * D[0];
        dh[1] += k * A * cos(th) * D[1];
    }
    if (p->gerst_on && p->gerst_amp != 0) {
        xing_dir(p->gerst_dx, p->gerst_dz, D);
        double k = p->gerst_freq, A = p->gerst_amp;
        double qa = k > 0 ? p->steep / k : 0;
        double th = k * (D[0] * u + D[1] * v) - xing_omega(k, p->gerst_speed, p->timer_seconds) * t;
        double s = sin(th), c = cos(th);
        h += A * s;
        dh[0] += k * A * c * D[0];
        dh[1] += k * A * c * D[1];
        disp[0] += qa * c * D[0];
        disp[1] += qa * c * D[1];
        a -= qa * k * s * D[0] * D[0];
        b -= qa * k * s * D[0] * D[1];
        d -= qa * k * s * D[1] * D[1];
    }
    pos[0] = u + disp[0];
    pos[1] = h;
    pos[2] = v + disp[1];
    double B[3] = { 1 + a, dh[0], b }, T[3] = { b, dh[1], 1 + d };
    double c[3] = { T[1] * B[2] - T[2] * B[1], T[2] * B[0] - T[0] * B[2], T[0] * B[1] - T[1] * B[0] };
    double l = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    for (int i = 0; i < 3; i++) n[i] = l > 1e-12 ? c[i] / l : (i == 1);
}

/* The normal from central differences of P with step hs. */
static void fd_normal(const xing_params *p, double u, double v, double t, double hs, double n[3]) {
    double pu1[3], pu0[3], pv1[3], pv0[3], dummy[3];
    xing_eval(p, u + hs, v, t, pu1, dummy);
    xing_eval(p, u - hs, v, t, pu0, dummy);
    xing_eval(p, u, v + hs, t, pv1, dummy);
    xing_eval(p, u, v - hs, t, pv0, dummy);
    double B[3], T[3];
    for (int i = 0; i < 3; i++) {
        B[i] = (pu1[i] - pu0[i]) / (2 * hs);
        T[i] = (pv1[i] - pv0[i]) / (2 * hs);
    }
    double c[3] = { T[1] * B[2] - T[2] * B[1], T[2] * B[0] - T[0] * B[2], T[0] * B[1] - T[1] * B[0] };
    double l = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    for (int i = 0; i < 3; i++) n[i] = c[i] / l;
}

static double dist3(const double a[3], const double b[3]) {
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* Largest |n - n_fd| over a grid of rest points and times; also the
 * smallest det J met (the surface's horizontal Jacobian). */
static double max_normal_error(const xing_params *p, double hs) {
    double worst = 0;
    for (int j = 0; j < 23; j++)
        for (int i = 0; i < 23; i++)
            for (int k = 0; k < 3; k++) {
                double u = -2 + 4.0 * i / 22, v = -2 + 4.0 * j / 22, t = 0.37 + 6.1 * k;
                double pos[3], n[3], nf[3];
                xing_eval(p, u, v, t, pos, n);
                fd_normal(p, u, v, t, hs, nf);
                double e = dist3(n, nf);
                if (e > worst) worst = e;
            }
    return worst;
}

/* Step 1e-4: the error of a central difference is h^2/6 |P'''| plus
 * rounding eps |P| / h. For the source's defaults |P'''| <= k^3 A + k^2 Q
 * (sine: 6^3 0.03 = 6.5; Gerstner 3.5^3 0.05 + 3.5^2 0.6 = 9.5), so the
 * truncation is < 3e-8 on B and T (|B|, |T| >= 1 - Q), rounding 2e-12; the
 * normal's error is of that order: tolerance 1e-7. Halving h must divide
 * the error by about 4 (second order), which shows the analytic normal is
 * the surface's and not merely close to it. */
static void test_normals_both_waves_source_defaults(void) {
    xing_params p = xing_defaults;
    double e1 = max_normal_error(&p, 1e-4), e2 = max_normal_error(&p, 5e-5);
    fprintf(stderr, "  both waves, defaults: max |n - n_fd| = %.3g (h = 1e-4), %.3g (h = 5e-5), ratio %.2f\n",
            e1, e2, e1 / e2);
    CHECK_LT(e1, 1e-7);
    CHECK(e1 / e2 > 3.5 && e1 / e2 < 4.5);
}

/* Steepness across 0..0.95 and the waves crossing at right angles and in
 * parallel, amplitudes at the sliders' maximum (0.2) and frequency 6:
 * |P'''| <= 6^3 0.2 + 36 = 79, truncation < 1.4e-7 / (1 - Q) for h = 1e-4;
 * tolerance 2e-6 (up to Q = 0.95, where 1 / (1 - Q) = 20). */
static void test_normals_across_steepness_and_directions(void) {
    const double steep[] = { 0.0, 0.3, 0.6, 0.9, 0.95 };
    const double dirs[][4] = { { 1, 0.3, -0.4, 1 }, { 1, 0, 0, 1 }, { 1, 0, 1, 0 }, { 0, 0, 0.6, -0.8 } };
    double worst = 0;
    for (size_t s = 0; s < sizeof steep / sizeof *steep; s++)
        for (size_t d = 0; d < sizeof dirs / sizeof *dirs; d++) {
            xing_params p = xing_defaults;
            p.steep = steep[s];
            p.sin_amp = p.gerst_amp = 0.2;
            p.sin_freq = p.gerst_freq = 6.0;
            p.sin_dx = dirs[d][0];
            p.sin_dz = dirs[d][1];
            p.gerst_dx = dirs[d][2];
            p.gerst_dz = dirs[d][3];
            double e = max_normal_error(&p, 1e-4);
            if (e > worst) worst = e;
            CHECK_MSG(e < 2e-6, "steepness %g, directions %zu: max |n - n_fd| = %g", steep[s], d, e);
        }
    fprintf(stderr, "  steepness 0..0.95, amplitude 0.2: max |n - n_fd| = %.3g\n", worst);
}

/* Steepness 0 gives a sine: the Gerstner wave's normal is then
 * normalize(-h_x, 1, -h_z) of the two summed sines, written out here. */
static void test_steepness_zero_is_a_sine(void) {
    xing_params p = xing_defaults;
    p.steep = 0;
    double worst = 0;
    for (int i = 0; i < 50; i++) {
        double u = -2 + 0.08 * i, v = 1.3 - 0.05 * i, t = 3.3, pos[3], n[3], Ds[2], Dg[2];
        xing_eval(&p, u, v, t, pos, n);
        xing_dir(p.sin_dx, p.sin_dz, Ds);
        xing_dir(p.gerst_dx, p.gerst_dz, Dg);
        double ths = p.sin_freq * (Ds[0] * u + Ds[1] * v) - xing_omega(p.sin_freq, p.sin_speed, 20) * t;
        double thg = p.gerst_freq * (Dg[0] * u + Dg[1] * v) - xing_omega(p.gerst_freq, p.gerst_speed, 20) * t;
        double hx = p.sin_freq * p.sin_amp * cos(ths) * Ds[0] + p.gerst_freq * p.gerst_amp * cos(thg) * Dg[0];
        double hz = p.sin_freq * p.sin_amp * cos(ths) * Ds[1] + p.gerst_freq * p.gerst_amp * cos(thg) * Dg[1];
        double l = sqrt(hx * hx + 1 + hz * hz), want[3] = { -hx / l, 1 / l, -hz / l };
        double e = dist3(n, want);
        if (e > worst) worst = e;
        CHECK_NEAR(pos[0], u, 1e-15);
        CHECK_NEAR(pos[2], v, 1e-15);
        CHECK_NEAR(pos[1], p.sin_amp * sin(ths) + p.gerst_amp * sin(thg), 1e-15);
    }
    CHECK_LT(worst, 1e-14);
}

/* Steepness 1 with parallel waves: the Gerstner crest is a cusp where
 * T x B = 0; the twin (like the shader) answers straight up, never NaN.
 * Directions of length 0: the waves bob in place, the normal is up. */
static void test_degenerate_cases_are_finite(void) {
    xing_params p = xing_defaults;
    p.steep = 1;
    p.sine_on = false;
    p.gerst_dx = 1;
    p.gerst_dz = 0;
    /* the crest: k x - omega t = pi / 2 at t = 0 */
    double u = (TWO_PI / 4) / p.gerst_freq, pos[3], n[3];
    xing_eval(&p, u, 0.3, 0, pos, n);
    CHECK(isfinite(n[0]) && isfinite(n[1]) && isfinite(n[2]));
    CHECK_NEAR(n[1], 1.0, 1e-9);
    p = xing_defaults;
    p.sin_dx = p.sin_dz = p.gerst_dx = p.gerst_dz = 0;
    p.steep = 1;
    p.sin_amp = p.gerst_amp = 0.2;
    for (int i = 0; i < 10; i++) {
        xing_eval(&p, 0.1 * i, -0.2 * i, 1.7 * i, pos, n);
        CHECK_NEAR(n[1], 1.0, 1e-15);
        CHECK_NEAR(pos[0], 0.1 * i, 1e-15);
    }
}

/* ---- GL helpers ---------------------------------------------------------- */

static gl_ctx *ctx;
static char ctx_err[512];

#define NEED_GL() do { if (!ctx) SKIP("no headless OpenGL: %s", ctx_err); } while (0)

static unif_entry *find_unif(render *r, const char *program, const char *name) {
    int n = 0;
    unif_set *sets = render_uniforms(r, &n);
    for (int i = 0; i < n; i++)
        if (strcmp(sets[i].program, program) == 0) return unif_find(&sets[i], name);
    return NULL;
}

/* Sets a uniform or a Define; true when a Define changed (recompile). */
static bool set_value(render *r, const char *program, const char *name, double v) {
    unif_entry *e = find_unif(r, program, name);
    CHECK_MSG(e != NULL, "no uniform %s in %s", name, program);
    if (!e) return false;
    return unif_set_component(e, 0, v) && e->is_define;
}

static unif_set *program_set(render *r, const char *program) {
    int n = 0;
    unif_set *sets = render_uniforms(r, &n);
    for (int i = 0; i < n; i++)
        if (strcmp(sets[i].program, program) == 0) return &sets[i];
    return NULL;
}

/* Renders into a float target and reads it back (row 0 the top). */
static void draw(render *r, double t, int w, int h, float *px) {
    render_target tg;
    CHECK(render_target_create(&tg, w, h, true));
    render_frame(r, t, tg.fbo, w, h, NULL);
    render_target_read(&tg, px);
    render_target_destroy(&tg);
    GLenum e = glGetError();
    CHECK_MSG(e == GL_NO_ERROR, "GL error 0x%x", e);
}

static int count_bad(const float *px, int n) {
    int bad = 0;
    for (int i = 0; i < n; i++)
        if (!isfinite(px[i])) bad++;
    return bad;
}

/* ---- the shader against the twin ----------------------------------------- */

/* tests/data/caustic_tex/twin.glib draws one screen-filling quad whose
 * fragments evaluate xingEval at p0 = -2 + 4 (s, t) and write (n, h) or
 * (dx, dz, 0, 0). Tolerance 1e-4: float arithmetic on phases up to
 * k |p0| + omega t ~ 60 rad (ulp 4e-6) times k A <= 1.2, plus the
 * interpolated (s, t) (~1e-7). */
#define TW 48
#define TH 48
static float twin_px[TW * TH * 4];

static void check_twin(render *r, const xing_params *p, double t, const char *what) {
    double worst_n = 0, worst_p = 0;
    for (int mode = 0; mode < 2; mode++) {
        set_value(r, "Twin", "uTwinMode", mode);
        draw(r, t, TW, TH, twin_px);
        for (int j = 0; j < TH; j++)
            for (int i = 0; i < TW; i++) {
                const float *q = twin_px + ((size_t)j * TW + i) * 4;
                double s = (i + 0.5) / TW, tt = 1.0 - (j + 0.5) / TH;   /* row 0 is the top */
                double pos[3], n[3];
                xing_eval(p, -2 + 4 * s, -2 + 4 * tt, t, pos, n);
                if (mode == 0) {
                    double e = fmax(fmax(fabs(q[0] - n[0]), fabs(q[1] - n[1])), fabs(q[2] - n[2]));
                    worst_n = fmax(worst_n, e);
                    worst_p = fmax(worst_p, fabs(q[3] - pos[1]));
                } else {
                    worst_p = fmax(worst_p, fabs(q[0] - (pos[0] - (-2 + 4 * s))));
                    worst_p = fmax(worst_p, fabs(q[1] - (pos[2] - (-2 + 4 * tt))));
                }
            }
    }
    fprintf(stderr, "  %s: GLSL vs C: normal %.2g, position %.2g\n", what, worst_n, worst_p);
    CHECK_MSG(worst_n < 1e-4 && worst_p < 1e-4, "%s: normal %g, position %g", what, worst_n, worst_p);
}

static void set_xing(render *r, const char *prog, const xing_params *p) {
    set_value(r, prog, "uSineWave", p->sine_on);
    set_value(r, prog, "uSinDx", p->sin_dx);
    set_value(r, prog, "uSinDz", p->sin_dz);
    set_value(r, prog, "uSinAmp", p->sin_amp);
    set_value(r, prog, "uSinFreq", p->sin_freq);
    set_value(r, prog, "uSinSpeed", p->sin_speed);
    set_value(r, prog, "uGerstnerWave", p->gerst_on);
    set_value(r, prog, "uGerstSteep", p->steep);
    set_value(r, prog, "uGerstDx", p->gerst_dx);
    set_value(r, prog, "uGerstDz", p->gerst_dz);
    set_value(r, prog, "uGerstAmp", p->gerst_amp);
    set_value(r, prog, "uGerstFreq", p->gerst_freq);
    set_value(r, prog, "uGerstSpeed", p->gerst_speed);
}

static void test_glsl_twin(void) {
    NEED_GL();
    render *r = render_create(NULL);
    CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/tests/data/caustic_tex/twin.glib"), "%s", render_messages(r));
    xing_params p = xing_defaults;
    set_xing(r, "Twin", &p);
    check_twin(r, &p, 3.7, "defaults");
    p.steep = 0.95;
    p.sin_amp = p.gerst_amp = 0.2;
    p.sin_freq = 11;
    set_xing(r, "Twin", &p);
    check_twin(r, &p, 12.25, "steep, large");
    p.sine_on = false;
    p.gerst_dx = p.gerst_dz = 0;
    set_xing(r, "Twin", &p);
    check_twin(r, &p, 1.0, "Gerstner only, direction 0");
    render_destroy(r);
}

/* ---- no NaN or Inf anywhere in the sliders' ranges ----------------------- */

#define NW 40
#define NH 24
static float nan_px[NW * NH * 4];

/* Renders at several times and returns the number of non-finite values. */
static int render_bad(render *r, const char *what) {
    const double times[] = { 0.0, 19.99 };
    int bad = 0;
    for (int k = 0; k < 2; k++) {
        draw(r, times[k], NW, NH, nan_px);
        int b = count_bad(nan_px, NW * NH * 4);
        CHECK_MSG(b == 0, "%s at t = %g: %d non-finite values", what, times[k], b);
        bad += b;
    }
    return bad;
}

/* Every uniform back to its default; the Defines stay as they are (they
 * match the compiled program). */
static void reset_uniforms(unif_set *set) {
    for (int i = 0; set && i < set->n; i++)
        if (!set->entries[i].is_define) unif_reset(&set->entries[i]);
}

/* Every slider of the program at its minimum, then at its maximum. */
static void all_extremes(render *r, const char *prog) {
    unif_set *set = program_set(r, prog);
    for (int end = 0; set && end < 2; end++) {
        for (int i = 0; i < set->n; i++) {
            unif_entry *e = &set->entries[i];
            if (!e->is_define && e->widget == UNIF_WIDGET_SLIDER) unif_set_component(e, 0, end ? e->max : e->min);
        }
        render_bad(r, end ? "all sliders at their maximum" : "all sliders at their minimum");
    }
    reset_uniforms(set);
}

/* Every slider of the program set to its extremes: each alone (others at
 * their defaults), then all at their minimum, all at their maximum. */
static void sweep_sliders(render *r, const char *prog) {
    unif_set *set = program_set(r, prog);
    CHECK_NE(set, NULL);
    if (!set) return;
    int nsliders = 0;
    for (int i = 0; i < set->n; i++) {
        unif_entry *e = &set->entries[i];
        if (e->is_define || e->widget != UNIF_WIDGET_SLIDER) continue;
        nsliders++;
        char what[128];
        for (int end = 0; end < 2; end++) {
            unif_set_component(e, 0, end ? e->max : e->min);
            snprintf(what, sizeof what, "%s: %s = %g", prog, e->name, end ? e->max : e->min);
            draw(r, 7.31, NW, NH, nan_px);
            int b = count_bad(nan_px, NW * NH * 4);
            CHECK_MSG(b == 0, "%s: %d non-finite values", what, b);
        }
        unif_reset(e);
    }
    all_extremes(r, prog);
    fprintf(stderr, "  %s: %d sliders swept\n", prog, nsliders);
}

/* Sets up to three Defines (name NULL: none), then recompiles once if any
 * changed. */
static void set_defines(render *r, const char *prog, const char *n1, double v1, const char *n2, double v2,
                        const char *n3, double v3) {
    bool changed = false;
    if (n1) changed |= set_value(r, prog, n1, v1);
    if (n2) changed |= set_value(r, prog, n2, v2);
    if (n3) changed |= set_value(r, prog, n3, v3);
    if (changed) CHECK_MSG(render_rebuild_programs(r), "%s", render_messages(r));
}

static void test_water_glib_no_nan(void) {
    NEED_GL();
    render *r = render_create(NULL);
    CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/packs/caustic_tex/water.glib"), "%s", render_messages(r));
    for (int mode = 0; mode < 4; mode++) {
        set_defines(r, "Xing", "BACKWARD_CAUSTICS", mode & 1, "UV_FLIP", mode & 2,
                    "CAUSTIC_POWER", mode == 1 ? 64 : mode == 3 ? 1 : 16);   /* its ends */
        render_bad(r, "defaults");
        /* the hard corner: steepness 1, amplitudes at their maximum,
         * directions of length 0, then parallel (a cusp at every crest) */
        xing_params p = xing_defaults;
        p.steep = 1;
        p.sin_amp = p.gerst_amp = 0.2;
        p.sin_dx = p.sin_dz = p.gerst_dx = p.gerst_dz = 0;
        set_xing(r, "Xing", &p);
        render_bad(r, "steepness 1, amplitude 0.2, directions 0");
        p.sin_dx = p.gerst_dx = 1;
        set_xing(r, "Xing", &p);
        render_bad(r, "steepness 1, amplitude 0.2, parallel");
        p.sin_freq = p.gerst_freq = 20;
        set_xing(r, "Xing", &p);
        render_bad(r, "steepness 1, amplitude 0.2, frequency 20");
        reset_uniforms(program_set(r, "Xing"));
        if (mode == 0) sweep_sliders(r, "Xing");   /* the other modes: all at min, all at max */
        else all_extremes(r, "Xing");
    }
    /* something was drawn: the water is not the background */
    draw(r, 1.0, NW, NH, nan_px);
    const float *c = nan_px + ((size_t)(NH / 2) * NW + NW / 2) * 4;
    CHECK_GT(fabs(c[0] - 0.62) + fabs(c[1] - 0.76) + fabs(c[2] - 0.90), 0.05);
    render_destroy(r);
}

static void test_lake_no_nan(void) {
    NEED_GL();
    render_desc rd = { .pack = "caustic_tex" };
    render *r = render_create(&rd);
    CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/scenes/lake.glib"), "%s", render_messages(r));
    unif_set *set = program_set(r, "CausticTex");
    CHECK_NE(set, NULL);
    if (!set) { render_destroy(r); return; }
    for (int mode = 0; mode < 4; mode++) {
        set_defines(r, "CausticTex", "BACKWARD_CAUSTICS", mode & 1, "SHOW_IRRADIANCE", mode & 2,
                    "CAUSTIC_POWER", mode == 1 ? 64 : mode == 3 ? 1 : 16);
        for (int end = 0; end < 3; end++) {
            reset_uniforms(set);
            for (int i = 0; end < 2 && i < set->n; i++) {
                unif_entry *e = &set->entries[i];
                if (!e->is_define && e->widget == UNIF_WIDGET_SLIDER) unif_set_component(e, 0, end ? e->max : e->min);
            }
            draw(r, mode * 11.3, NW, NH, nan_px);
            int b = count_bad(nan_px, NW * NH * 4);
            CHECK_MSG(b == 0, "lake, mode %d, sliders %s: %d non-finite values", mode,
                      end == 0 ? "min" : end == 1 ? "max" : "default", b);
        }
    }
    render_destroy(r);
}

/* ---- the paper's setting, reflections, the view from below ---------------- */

/* bench.txt's `paper` row carries Xing's water.glib slider defaults (issue
 * #16 quotes them), and every entry it names exists in CausticTex. */
static void test_paper_setting(void) {
    static const struct { const char *name; float v[3]; int n; } xing[] = {
        { "uWaterRefractMix", { 0.65f }, 1 }, { "uCausticVisible", { 0.6f }, 1 },
        { "uCausticWave", { 0.8f }, 1 },      { "uCausticOffset", { 0.1f }, 1 },
        { "uChromaticOffset", { 0.005f }, 1 }, { "uKa", { 0.45f }, 1 },
        { "uKd", { 0.35f }, 1 },              { "uKs", { 0.20f }, 1 },
        { "uShininess", { 250.f }, 1 },       { "uColor", { 0.40f, 1.0f, 0.95f }, 3 },
        { "CAUSTIC_FOLLOW", { 0.f }, 1 },     { "XING_FOAM", { 1.f }, 1 },
        { "uShowFoam", { 0.f }, 1 },          { "SKY_REFLECTION", { 0.f }, 1 },
        { "BEER_LAMBERT", { 0.f }, 1 },
    };
    packset_bench b;
    char err[512];
    CHECK_MSG(packset_bench_load(TARN_SOURCE_DIR, "caustic_tex", &b, err, sizeof err), "%s", err);
    const packset_setting *paper = NULL;
    for (int i = 0; i < b.n; i++)
        if (strcmp(b.settings[i].name, "paper") == 0) paper = &b.settings[i];
    CHECK_NE(paper, NULL);
    render *r = NULL;
    if (ctx) {
        render_desc rd = { .pack = "caustic_tex" };
        r = render_create(&rd);
        CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/scenes/lake.glib"), "%s", render_messages(r));
    }
    for (size_t k = 0; paper && k < sizeof xing / sizeof xing[0]; k++) {
        const packset_assign *a = NULL;
        for (int i = 0; i < paper->nassign; i++)
            if (strcmp(paper->assign[i].name, xing[k].name) == 0) a = &paper->assign[i];
        CHECK_MSG(a != NULL, "paper: no %s", xing[k].name);
        if (!a) continue;
        CHECK_MSG(a->nvalue == xing[k].n, "paper: %s has %d values", xing[k].name, a->nvalue);
        for (int c = 0; c < xing[k].n && c < a->nvalue; c++)
            CHECK_MSG(fabsf(a->value[c] - xing[k].v[c]) < 1e-6f, "paper: %s = %g, Xing's %g", xing[k].name,
                      a->value[c], xing[k].v[c]);
    }
    for (int i = 0; r && paper && i < paper->nassign; i++)
        CHECK_MSG(find_unif(r, "CausticTex", paper->assign[i].name) != NULL, "paper: %s is not in CausticTex",
                  paper->assign[i].name);
    if (r) render_destroy(r);
    packset_bench_free(&b);
}

#define RW 96
#define RH 54
static float refl_on[RW * RH * 4], refl_off[RW * RH * 4];

static const float *px_at(const float *px, double x, double y) {
    return px + ((size_t)(y * RH) * RW + (size_t)(x * RW)) * 4;
}

/* The mean over a 3 x 3 patch of what the reflection adds at (x, y). */
static void reflection_adds(double x, double y, double d[3]) {
    d[0] = d[1] = d[2] = 0;
    for (int j = -1; j <= 1; j++)
        for (int i = -1; i <= 1; i++) {
            const float *a = px_at(refl_on, x + (double)i / RW, y + (double)j / RH);
            const float *b = px_at(refl_off, x + (double)i / RW, y + (double)j / RH);
            for (int c = 0; c < 3; c++) d[c] += (a[c] - b[c]) / 9.0;
        }
}

/* The lake's red box on the far shore seen in the water: there the
 * reflection (the box, darker than the sky in green and blue) adds little
 * green and blue, where the sky adds much of both on open water. */
static void test_object_reflection(void) {
    NEED_GL();
    render_desc rd = { .pack = "caustic_tex" };
    render *r = render_create(&rd);
    CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/scenes/lake.glib"), "%s", render_messages(r));
    draw(r, 1.0, RW, RH, refl_on);
    set_defines(r, "CausticTex", "SKY_REFLECTION", 0, NULL, 0, NULL, 0);
    draw(r, 1.0, RW, RH, refl_off);
    double box[3], open[3];
    reflection_adds(0.82, 0.53, box);
    reflection_adds(0.50, 0.45, open);
    fprintf(stderr, "  reflection adds under the box (%.3f %.3f %.3f), on open water (%.3f %.3f %.3f)\n", box[0],
            box[1], box[2], open[0], open[1], open[2]);
    /* the box, not the sky: under it the reflection adds under a quarter of
     * the green and blue it adds on open water (the sky's), and more red
     * than blue (the box is red); read at the box's own distance since
     * issue #24, the patch also holds a little of the water's own colour */
    CHECK(open[1] > 0 && open[2] > 0);
    CHECK(box[1] < 0.25 * open[1] && box[2] < 0.25 * open[2] && box[0] > box[2]);
    render_destroy(r);
}

/* From under the water (scenes/hard/underwater.glib looks up at the
 * surface): Snell's window shows the sky, brighter than the total internal
 * reflection around it, which shows the dim world below. */
static void test_view_from_below(void) {
    NEED_GL();
    render_desc rd = { .pack = "caustic_tex" };
    render *r = render_create(&rd);
    CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/scenes/hard/underwater.glib"), "%s", render_messages(r));
    draw(r, 1.0, RW, RH, refl_on);
    const float *w = px_at(refl_on, 0.45, 0.0), *t = px_at(refl_on, 0.05, 0.2);
    fprintf(stderr, "  from below: window (%.3f %.3f %.3f), total internal reflection (%.3f %.3f %.3f)\n", w[0],
            w[1], w[2], t[0], t[1], t[2]);
    CHECK(w[2] > 0.3 && w[2] > 3.0 * t[2]);
    render_destroy(r);
}

/* ---- caustics against the reference -------------------------------------- */

/* What tests/data/caustic_tex/flat.glib shows: the lake's sun, water and
 * waves over a flat floor 2.5 m deep, from 14 m straight above. The
 * reference traces photons through the exact surface (ref_render's
 * irradiance buffer: the sun's irradiance where each pixel's refracted ray
 * meets the floor); the pack shows E K there (SHOW_IRRADIANCE). The
 * patterns differ (a texture against the scene's own waves), so the
 * comparison is of statistics over the floor pixels: the mean, the
 * contrast (standard deviation over mean) and upper percentiles over the
 * mean, per channel. */
#define CW 96
#define CH 96
static float pack_px[CW * CH * 4];

typedef struct stats { double mean, contrast, p50, p95, p99, max; int n; } stats;

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static stats stats_of(double *v, int n) {
    stats s = { 0 };
    s.n = n;
    if (n == 0) return s;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; i++) sum += v[i];
    s.mean = sum / n;
    for (int i = 0; i < n; i++) sum2 += (v[i] - s.mean) * (v[i] - s.mean);
    s.contrast = sqrt(sum2 / n) / s.mean;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    s.p50 = v[n / 2] / s.mean;
    s.p95 = v[(int)(0.95 * (n - 1))] / s.mean;
    s.p99 = v[(int)(0.99 * (n - 1))] / s.mean;
    s.max = v[n - 1] / s.mean;
    return s;
}

static void print_stats(const char *who, int c, const stats *s, double e_flat) {
    fprintf(stderr, "  | %-24s | %c | %6.4f | %5.3f | %5.3f | %5.3f | %5.3f | %5.3f | %5.2f |\n", who, "RGB"[c],
            s->mean, s->mean / e_flat, s->contrast, s->p50, s->p95, s->p99, s->max);
}

static ref_world flat_world;
static ref_render_result ref_result;
static bool have_ref;
static bool floor_px[CW * CH];
static int nfloor;

static void reference_once(void) {
    if (have_ref) return;
    ref_world_desc desc;
    scene_camera cam;
    bool has_world = false;
    char err[1024];
    CHECK_MSG(scene_load(TARN_SOURCE_DIR "/tests/data/caustic_tex/flat.glib", NULL, &desc, &cam, &has_world,
                         err, sizeof err), "%s", err);
    ref_world_init(&flat_world, &desc);
    ref_render_desc d = { .world = &flat_world, .time = 2.0, .caustic_res = 128, .photons_per_cell = 16 };
    for (int k = 0; k < 3; k++) {
        d.camera.eye[k] = cam.eye[k];
        d.camera.center[k] = cam.center[k];
        d.camera.up[k] = cam.up[k];
    }
    d.camera.fov_deg = cam.fov_deg;
    d.camera.width = CW;
    d.camera.height = CH;
    CHECK_MSG(ref_render(&d, &ref_result, err, sizeof err) == 0, "%s", err);
    fprintf(stderr, "  reference: %d x %d photon grid, %.1f s photons, %.1f s pixels (%d threads)\n",
            ref_result.caustics.nx, ref_result.caustics.nz, ref_result.seconds_photons,
            ref_result.seconds_pixels, ref_result.threads);
    nfloor = 0;
    for (int p = 0; p < CW * CH; p++) {
        floor_px[p] = ref_result.mask[p] == REF_MASK_WATER && ref_result.refract_hit[4 * p + 3] == REF_MASK_TERRAIN &&
                      isfinite(ref_result.irradiance[3 * p]);
        nfloor += floor_px[p];
    }
    have_ref = true;
}

/* The irradiance the pack shows on the floor, one render. */
static void pack_irradiance(render *r, bool backward, double visible) {
    set_defines(r, "CausticTex", "SHOW_IRRADIANCE", 1, "BACKWARD_CAUSTICS", backward, NULL, 0);
    set_value(r, "CausticTex", "uCausticVisible", visible);
    draw(r, 2.0, CW, CH, pack_px);
}

static stats pack_stats(int c, int *bad) {
    static double v[CW * CH];
    int n = 0;
    for (int p = 0; p < CW * CH; p++) {
        if (!floor_px[p]) continue;
        double e = pack_px[4 * p + c];
        if (!isfinite(e)) { (*bad)++; continue; }
        v[n++] = e;
    }
    return stats_of(v, n);
}

static void test_caustics_vs_reference(void) {
    NEED_GL();
    reference_once();
    CHECK_GT(nfloor, CW * CH * 9 / 10);
    /* the flat-water irradiance on this floor, for scale */
    double fp[3] = { 0, -2.5, 0 }, up[3] = { 0, 1, 0 }, e_flat[3];
    ref_render_flat_sun(&flat_world, fp, up, e_flat);

    render_desc rd = { .pack = "caustic_tex" };
    render *r = render_create(&rd);
    CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/tests/data/caustic_tex/flat.glib"), "%s", render_messages(r));

    /* uCausticVisible 0: the pack's E is the flat-water irradiance, the
     * twin of ref_render_flat_sun: every floor pixel equals it (float and
     * the reconstructed floor normal: 2e-3 relative) */
    pack_irradiance(r, false, 0.0);
    double worst = 0;
    for (int p = 0; p < CW * CH; p++)
        for (int c = 0; floor_px[p] && c < 3; c++)
            worst = fmax(worst, fabs(pack_px[4 * p + c] / e_flat[c] - 1));
    fprintf(stderr, "  visibility 0: max |E / E_flat - 1| = %.2g\n", worst);
    CHECK_LT(worst, 2e-3);

    fprintf(stderr, "  | %-24s | c | mean   | /flat | contr | p50   | p95   | p99   | max   |\n", "floor irradiance");
    stats ref[3], tex[3], back[3];
    for (int c = 0; c < 3; c++) {
        static double v[CW * CH];
        int n = 0;
        for (int p = 0; p < CW * CH; p++)
            if (floor_px[p]) v[n++] = ref_result.irradiance[3 * p + c];
        ref[c] = stats_of(v, n);
        print_stats(c == 0 ? "reference (photons)" : "", c, &ref[c], e_flat[c]);
    }
    int bad = 0;
    stats def;
    unif_entry *vis_e = find_unif(r, "CausticTex", "uCausticVisible");
    double vis_default = vis_e ? vis_e->def[0] : 0.8;
    pack_irradiance(r, false, vis_default);
    for (int c = 0; c < 3; c++) {
        def = pack_stats(c, &bad);
        print_stats(c == 0 ? "texture, visible default" : "", c, &def, e_flat[c]);
    }
    pack_irradiance(r, false, 1.0);
    for (int c = 0; c < 3; c++) {
        tex[c] = pack_stats(c, &bad);
        print_stats(c == 0 ? "texture, visible 1" : "", c, &tex[c], e_flat[c]);
    }
    pack_irradiance(r, true, 1.0);
    for (int c = 0; c < 3; c++) {
        back[c] = pack_stats(c, &bad);
        print_stats(c == 0 ? "backward, power 16" : "", c, &back[c], e_flat[c]);
    }
    CHECK_EQ(bad, 0);
    /* what the visibility that matches the reference's contrast would be:
     * the contrast is linear in it while K stays above 0 */
    double vis = ref[1].contrast / tex[1].contrast;
    pack_irradiance(r, false, fmin(vis, 3.0));
    stats m = pack_stats(1, &bad);
    fprintf(stderr, "  visibility %.2f (default %.2f) matches the reference's contrast (G): mean %.4f, "
            "contrast %.3f, p95 %.3f, p99 %.3f\n", vis, vis_default, m.mean, m.contrast, m.p95, m.p99);
    for (int c = 0; c < 3; c++) {
        /* the texture keeps the mean (mean 1 by construction, chromatic
         * offsets and filtering aside); the reference's mean is the flat
         * irradiance times the mean transmittance of a wavy surface, within
         * a few percent of flat */
        CHECK_MSG(fabs(tex[c].mean / ref[c].mean - 1) < 0.05, "channel %d: mean %g against %g", c, tex[c].mean,
                  ref[c].mean);
        CHECK_LT(fabs(ref[c].mean / e_flat[c] - 1), 0.05);
        /* both show caustics: contrast well above the photon noise */
        CHECK(ref[c].contrast > 0.1 && tex[c].contrast > 0.1 && back[c].contrast > 0.02);
    }
    render_destroy(r);
}

int main(void) {
    RUN(test_normals_both_waves_source_defaults);
    RUN(test_normals_across_steepness_and_directions);
    RUN(test_steepness_zero_is_a_sine);
    RUN(test_degenerate_cases_are_finite);
    ctx = gl_ctx_create_headless(ctx_err, sizeof ctx_err);
    RUN(test_glsl_twin);
    RUN(test_water_glib_no_nan);
    RUN(test_lake_no_nan);
    RUN(test_caustics_vs_reference);
    RUN(test_paper_setting);
    RUN(test_object_reflection);
    RUN(test_view_from_below);
    if (have_ref) ref_render_free(&ref_result);
    if (ctx) gl_ctx_destroy(ctx);
    return check_summary();
}
