/* The flow map (viewer/gfx/render_flow.c, packs/common/flow_advect.frag,
 * flow.glsl; issue #29) against closed forms.
 *
 * (a) A constant current v: backward advection moves a layer's content by
 *     v times the layer's age, so the advected field F0(x - d(x)) must be
 *     the shifted field F0(x - v age) at every texel, over steps of 1/60 s
 *     that cross both layers' restarts, and after a time jump (the catch-
 *     up). Bound: d is exact for a uniform field (bilinear reads of a
 *     constant, a constant), so what is left is float32 rounding of
 *     x - back (x up to 15 m: ~1e-6 m a step) summed over <= 180 steps:
 *     2e-4 m; the bound is 1e-3 m.
 * (b) A Rankine vortex moves content round its centre: a marked blob (the
 *     texels whose source point lies in a disc) keeps its radius from the
 *     centre, its area, and turns by the closed-form angle (inside the
 *     core, solid rotation at strength / R rad/s). Bounds from the measured
 *     figures (printed) with a margin, justified there.
 * (a') A Flow texture (a velocity map from a file, here uniform) moves the
 *     content as the current it encodes: the same closed form and bound,
 *     and the glib's `Flow texture` line resolves the file and its scale.
 * (c) Two runs of the same steps give bit-identical maps.
 * (d) A world without a Flow creates no map, no program, runs no pass and
 *     its programs declare no flow uniform; one with a Flow has them. */
#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "support.h"
#include "gl_support.h"
#include "image_io.h"
#include "render_flow.h"
#include "render_world.h"
#include "scene.h"

static bool make_flow(gpu_flow *f, const ref_flow_desc *d, double half) {
    diag_list log = { 0 };
    memset(f, 0, sizeof *f);
    bool ok = flow_create(f, d, half, gl_test_sources(), &log, NULL);
    diag_print(&log, stderr);
    diag_list_free(&log);
    return ok;
}

/* texel (i, j)'s centre in the world */
static void texel_xz(const gpu_flow *f, int i, int j, double *x, double *z) {
    *x = -f->half + (i + 0.5) * 2.0 * f->half / FLOW_RES;
    *z = -f->half + (j + 0.5) * 2.0 * f->half / FLOW_RES;
}

static double field(double x, double z) { return sin(1.7 * x + 0.3) * cos(2.3 * z - 0.4) + 0.2 * x; }

/* the largest |F0(x - d) - F0(x - v age)| and |d - v age| over the map */
static void current_error(const gpu_flow *f, const float *map, const double v[2], double t, double *ef, double *ed) {
    double age[2] = { flow_phase(0, t, f->d.period) * f->d.period, flow_phase(1, t, f->d.period) * f->d.period };
    *ef = *ed = 0;
    for (int j = 0; j < FLOW_RES; j++)
        for (int i = 0; i < FLOW_RES; i++) {
            double x, z;
            texel_xz(f, i, j, &x, &z);
            const float *m = map + ((size_t)j * FLOW_RES + i) * 4;
            for (int l = 0; l < 2; l++) {
                double dx = m[2 * l], dz = m[2 * l + 1];
                double e = fabs(field(x - dx, z - dz) - field(x - v[0] * age[l], z - v[1] * age[l]));
                double d = hypot(dx - v[0] * age[l], dz - v[1] * age[l]);
                if (e > *ef) *ef = e;
                if (d > *ed) *ed = d;
            }
        }
}

static void test_current_gives_the_shifted_field(void) {
    ref_flow_desc d = { .nterms = 1, .term = { { REF_FLOW_CURRENT, { 0.6, -0.35 } } }, .period = 2.0 };
    double v[2] = { 0.6, -0.35 };
    gpu_flow f;
    CHECK(make_flow(&f, &d, 12));
    float *map = malloc((size_t)FLOW_RES * FLOW_RES * 4 * sizeof(float));
    double worst_f = 0, worst_d = 0;
    /* a jump to 0.7 (catch-up), then 1/60 s steps past both restarts
     * (B at 1.0, A at 2.0, B at 3.0) */
    double t = 0.7;
    CHECK(flow_update(&f, t, NULL));
    CHECK_EQ(f.catchups, 1);
    for (int s = 0; s <= 150; s++) {
        if (s > 0) {
            t = 0.7 + s / 60.0;
            CHECK(flow_update(&f, t, NULL));
        }
        if (s % 25 != 0) continue;
        flow_read(&f, map);
        double ef, ed;
        current_error(&f, map, v, t, &ef, &ed);
        if (ef > worst_f) worst_f = ef;
        if (ed > worst_d) worst_d = ed;
    }
    CHECK_EQ(f.catchups, 1);   /* the steps were steps */
    CHECK(!flow_update(&f, t, NULL));   /* a still frame runs nothing */
    /* and a jump back in time is rebuilt from the restarts */
    CHECK(flow_update(&f, 0.3, NULL) && f.catchups == 2);
    flow_read(&f, map);
    double ef, ed;
    current_error(&f, map, v, 0.3, &ef, &ed);
    if (ef > worst_f) worst_f = ef;
    if (ed > worst_d) worst_d = ed;
    printf("  current: max |d - v age| %.2e m, max |F0(x - d) - F0(x - v age)| %.2e\n", worst_d, worst_f);
    CHECK_LT(worst_d, 1e-3);
    CHECK_LT(worst_f, 5e-3);   /* |grad F0| <= 2.9: 2.9 x 1e-3 */
    free(map);
    flow_free(&f);
}

static void test_texture_velocity_is_a_current(void) {
    CHECK(scratch_create("flow"));
    img im = { 0 };
    CHECK(img_alloc(&im, 8, 8, 3));
    for (int i = 0; i < 64; i++) {   /* (2 R - 1, 2 G - 1) scale = (0.5, -0.25) 1.2 */
        im.px[3 * i] = 0.75f;
        im.px[3 * i + 1] = 0.375f;
        im.px[3 * i + 2] = 0.0f;
    }
    char err[512];
    CHECK(img_write_float(scratch_path("vel.exr"), &im, err, sizeof err));
    img_free(&im);
    /* through the glib: the file resolved beside the scene, the scale read */
    char glib[512];
    snprintf(glib, sizeof glib, "##OpenGL GLIB\nTerrain flat\nFlow texture vel.exr 1.2\n");
    scratch_write("tex.glib", glib);
    ref_world_desc wd;
    char msgs[512];
    CHECK(scene_load(scratch_path("tex.glib"), NULL, &wd, NULL, NULL, msgs, sizeof msgs));
    CHECK(wd.flow.nterms == 1 && wd.flow.term[0].kind == REF_FLOW_TEXTURE && wd.flow.term[0].p[0] == 1.2);
    CHECK_NE(strstr(wd.flow.texture, "vel.exr"), NULL);
    wd.flow.period = 2.0;
    gpu_flow f;
    CHECK(make_flow(&f, &wd.flow, 12));
    CHECK_NE(f.vel_tex, 0);
    double v[2] = { 0.6, -0.3 };
    float *map = malloc((size_t)FLOW_RES * FLOW_RES * 4 * sizeof(float));
    double worst_d = 0, worst_f = 0, ef, ed;
    for (int s = 0; s <= 60; s++) {
        double t = 0.7 + s / 60.0;
        flow_update(&f, t, NULL);
        if (s % 20) continue;
        flow_read(&f, map);
        current_error(&f, map, v, t, &ef, &ed);
        if (ef > worst_f) worst_f = ef;
        if (ed > worst_d) worst_d = ed;
    }
    printf("  texture: max |d - v age| %.2e m, max field error %.2e\n", worst_d, worst_f);
    CHECK_LT(worst_d, 1e-3);   /* v from a float texture: 0.75 and 0.375 are exact */
    CHECK_LT(worst_f, 5e-3);
    free(map);
    flow_free(&f);
    /* a missing file is an error naming it, not a crash */
    snprintf(wd.flow.texture, sizeof wd.flow.texture, "%s", scratch_path("nope.exr"));
    diag_list log = { 0 };
    memset(&f, 0, sizeof f);
    CHECK(!flow_create(&f, &wd.flow, 12, gl_test_sources(), &log, NULL));
    char *text = diag_list_format(&log, 0);
    CHECK(strstr(text, "nope.exr"));
    free(text);
    diag_list_free(&log);
    flow_free(&f);
    scratch_remove();
}

/* The blob: texels whose layer-A source point is within rb of c0. */
typedef struct blob { int n; double cx, cz, rmax_err; } blob;

static blob marked(const gpu_flow *f, const float *map, const double c[2], const double c0[2], double rb) {
    blob b = { 0 };
    for (int j = 0; j < FLOW_RES; j++)
        for (int i = 0; i < FLOW_RES; i++) {
            double x, z;
            texel_xz(f, i, j, &x, &z);
            const float *m = map + ((size_t)j * FLOW_RES + i) * 4;
            double sx = x - m[0], sz = z - m[1];
            if (hypot(sx - c0[0], sz - c0[1]) > rb) continue;
            b.n++;
            b.cx += x;
            b.cz += z;
            /* each point keeps its own radius from the centre */
            double e = fabs(hypot(x - c[0], z - c[1]) - hypot(sx - c[0], sz - c[1]));
            if (e > b.rmax_err) b.rmax_err = e;
        }
    if (b.n) { b.cx /= b.n; b.cz /= b.n; }
    return b;
}

static void test_vortex_keeps_a_blob_on_its_circle(void) {
    double c[2] = { 1.0, -0.5 }, S = 1.0, R = 2.0;
    ref_flow_desc d = { .nterms = 1, .term = { { REF_FLOW_VORTEX, { c[0], c[1], S, R } } }, .period = 4.0 };
    gpu_flow f;
    CHECK(make_flow(&f, &d, 12));
    float *map = malloc((size_t)FLOW_RES * FLOW_RES * 4 * sizeof(float));
    double t = 1.0 / 60;
    flow_update(&f, t, NULL);
    for (int s = 2; s <= 120; s++) flow_update(&f, t = s / 60.0, NULL);   /* layer A's age: 2 s */
    flow_read(&f, map);
    double age = flow_phase(0, t, d.period) * d.period;
    /* inside the core: solid rotation by S / R rad/s, anticlockwise from +y
     * (x towards -z... flow.glsl: v = speed (-r.z, r.x) / |r|) */
    double r0 = 1.2, rb = 0.75, c0[2] = { c[0] + r0, c[1] };
    blob b = marked(&f, map, c, c0, rb);
    double th = S / R * age;
    double ex = c[0] + r0 * cos(th), ez = c[1] + r0 * sin(th);
    double cell = 2.0 * f.half / FLOW_RES, area = M_PI * rb * rb / (cell * cell);
    double rc = hypot(b.cx - c[0], b.cz - c[1]);
    printf("  vortex core: blob of %d texels (disc %.1f), centroid radius %.4f m (was %.2f), "
           "off the closed form by %.4f m, worst point radius error %.2e m\n",
           b.n, area, rc, r0, hypot(b.cx - ex, b.cz - ez), b.rmax_err);
    CHECK_LT(fabs(b.n - area), 0.05 * area);            /* area kept: a rotation; the count's edge noise ~ perimeter/area */
    /* the centroid of a set of whole texels: its quantisation, ~ a texel
     * (0.117 m) over sqrt(texels), is what these bounds allow */
    CHECK_LT(fabs(rc - r0), 0.02);
    CHECK_LT(hypot(b.cx - ex, b.cz - ez), 0.03);        /* and where the closed form puts it */
    /* each point: solid rotation's d is linear in x, so bilinear reads are
     * exact but where the blob's edge (r up to 1.95) reads across the core's
     * rim r = R, where the speed's slope jumps: measured 6.7e-3 m there,
     * 2.7e-4 m well inside; the bound is a tenth of a texel */
    CHECK_LT(b.rmax_err, 1.2e-2);
    /* outside the core the speed falls as R / r: sheared, but each point
     * stays on its circle */
    double c1[2] = { c[0], c[1] + 3.5 };
    blob o = marked(&f, map, c, c1, 0.5);
    printf("  vortex outside the core: blob of %d texels (disc %.1f), worst point radius error %.2e m\n", o.n,
           M_PI * 0.25 / (cell * cell), o.rmax_err);
    CHECK_LT(fabs(o.n - M_PI * 0.25 / (cell * cell)), 0.05 * M_PI * 0.25 / (cell * cell));
    CHECK_LT(o.rmax_err, 1.2e-2);   /* measured 4.8e-3: the 1/r field's curvature over a texel */
    free(map);
    flow_free(&f);
}

static void test_same_steps_same_map(void) {
    ref_flow_desc d = { .nterms = 2,
                        .term = { { REF_FLOW_CURRENT, { 0.5, 0.1 } }, { REF_FLOW_VORTEX, { 0, 0, 1.2, 1.5 } } } };
    size_t n = (size_t)FLOW_RES * FLOW_RES * 4;
    float *m[2] = { malloc(n * sizeof(float)), malloc(n * sizeof(float)) };
    for (int run = 0; run < 2; run++) {
        gpu_flow f;
        CHECK(make_flow(&f, &d, 12));
        for (int s = 0; s < 40; s++) flow_update(&f, 5.0 + s / 30.0, NULL);
        flow_read(&f, m[run]);
        flow_free(&f);
    }
    CHECK_EQ(memcmp(m[0], m[1], n * sizeof(float)), 0);
    free(m[0]);
    free(m[1]);
}

/* ---- (d) a world without a Flow pays nothing ---- */

static bool frame_has_pass(const char *scene, const char *what) {
    render *r = render_create(&(render_desc){ .pack = "basic" });
    CHECK_MSG(render_load(r, scene), "%s", render_messages(r));
    render_target tg;
    CHECK(render_target_create(&tg, 64, 36, true));
    render_frame(r, 1.0, tg.fbo, 64, 36, NULL);
    render_frame(r, 1.5, tg.fbo, 64, 36, NULL);
    bool has = gl_test_has_pass(r, what);
    render_target_destroy(&tg);
    render_destroy(r);
    return has;
}

static bool defines_flow(const prog *p) {
    for (int k = 0; k < PROG_FIXED_MAX; k++)
        if (strcmp(p->fixed[k].name, "WAVES_HAS_FLOW") == 0) return true;
    return false;
}

static void test_no_flow_no_pass(void) {
    CHECK(!frame_has_pass(TARN_SOURCE_DIR "/scenes/lake.glib", "flow"));
    CHECK(frame_has_pass(TARN_SOURCE_DIR "/scenes/river.glib", "flow advect"));
    for (int with = 0; with < 2; with++) {
        ref_world_desc desc;
        memset(&desc, 0, sizeof desc);
        desc.waves.gerstner_count = 1;
        desc.waves.gerstner[0] = (ref_wave_desc){ .wavelength = 4, .amplitude = 0.05 };
        if (with) desc.flow = (ref_flow_desc){ .nterms = 1, .term = { { REF_FLOW_CURRENT, { 0.3, 0 } } } };
        gpu_world gw;
        CHECK(gl_test_world_build(&gw, &desc));
        CHECK(gw.active);
        CHECK_EQ(gw.flow.active, (with == 1));
        CHECK((gw.flow.tex[0] != 0) == (with == 1) && (gw.flow.prog.gl != 0) == (with == 1));
        CHECK_EQ(world_update_flow(&gw, 1.0, NULL), (with == 1));
        /* what every pack program is built with (render_load.c) */
        prog p;
        memset(&p, 0, sizeof p);
        world_set_defines(&gw, &p);
        CHECK_EQ(defines_flow(&p), (with == 1));
        if (!with)   /* no flow: not one flow uniform in any world program */
            for (int m = 0; m < WORLD_MODES; m++) {
                CHECK_LT(glGetUniformLocation(gw.progs[m].gl, "uFlowMap"), 0);
                CHECK_LT(glGetUniformLocation(gw.progs[m].gl, "uFlowN"), 0);
            }
        world_free(&gw);
    }
}

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    RUN(test_current_gives_the_shifted_field);
    RUN(test_texture_velocity_is_a_current);
    RUN(test_vortex_keeps_a_blob_on_its_circle);
    RUN(test_same_steps_same_map);
    RUN(test_no_flow_no_pass);
    gl_ctx_destroy(ctx);
    return check_summary();
}
