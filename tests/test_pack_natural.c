/* packs/natural (docs/packs/natural.md) headless on llvmpipe:
 *
 *   - the lake renders without NaN/Inf or GL errors at several times, with
 *     each caustic method and without caustics, in every debug view, and
 *     with the camera under the water;
 *   - on flat water the pack's Fresnel, reflection and refraction agree
 *     with the CPU reference (ref_render) on the same world and camera, from
 *     above and from below, each measured where it arises (the pack's debug
 *     views against the reference's buffers);
 *   - under flat water both caustic methods give a caustic ratio of 1, and
 *     under waves their ratio follows the reference's photon tracer.
 *
 * The figures in docs/packs/natural.md are this test's output.
 */
#include <GL/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "gl_ctx.h"
#include "ref_metrics.h"
#include "ref_optics.h"
#include "ref_render.h"
#include "render.h"
#include "scene.h"
#include "unif.h"

#define W 96
#define H 54
#define NPX (W * H)

static char dir[64];
static float px[NPX * 4];

/* ---- scenes ------------------------------------------------------------- */

static const char *path_in_dir(const char *name) {
    static char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return path;
}

/* Flat water 2 m over a flat floor, no waves: a crate beyond the water to
 * be reflected, a boulder under it; the camera 5 m up looking down at 45
 * degrees, so every pixel of the water lies well inside the world square. */
static const char *flat_scene(void) {
    const char *out = path_in_dir("flat.glib");
    FILE *f = fopen(out, "w");
    if (!f) { perror(out); exit(1); }
    fprintf(f, "##OpenGL GLIB\n"
               "WindowSize %d %d\nPerspective 50 0.1 200\nLookAt 0 5 5  0 -1 -1  0 1 0\n"
               "Sun 0.4 0.8 -0.45  2.2 2.1 1.9\nSky 0.25 0.45 0.85  0.70 0.80 0.92\n"
               "Water 0 1.333  0.45 0.09 0.06\nWaterMesh 64\nTerrain flat 12 2\n"
               "Object box     0  2 -8   3 2 1   0.62 0.30 0.22\n"
               "Object sphere 1.5 -1.4 -2  0.6   0.55 0.50 0.42\n", W, H);
    fclose(f);
    return out;
}

/* The camera under the flat water, looking up through Snell's window. */
static const render_view below_view = { { 0, -1.5f, 4 }, { 0, 0, 2.5f }, { 0, 1, 0 } };

/* Waves short enough to focus the sun within the 2 m of water over a flat
 * floor (a crest of curvature k^2 A ~ 0.2 per metre focuses at ~15 m, so
 * the floor sees the ratio vary by about +-15 %), for the caustic test. */
static const char *wavy_scene(void) {
    const char *out = path_in_dir("wavy.glib");
    FILE *f = fopen(out, "w");
    if (!f) { perror(out); exit(1); }
    fprintf(f, "##OpenGL GLIB\n"
               "Perspective 50 0.1 200\nLookAt 0 5 5  0 -1 -1  0 1 0\n"
               "Sun 0.4 0.8 -0.45  2.2 2.1 1.9\nWater 0 1.333  0.45 0.09 0.06\nTerrain flat 12 2\n"
               "WaveSine   0 2.5 0.030\nWaveSine  60 1.9 0.020\n");
    fclose(f);
    return out;
}

/* ---- rendering ------------------------------------------------------------ */

typedef struct setting {
    const char *name;
    float value;
} setting;

static render *load(const char *scene) {
    render_desc rd = { .pack = "natural" };
    render *r = render_create(&rd);
    bool ok = render_load(r, scene);
    CHECK_MSG(ok, "%s", render_messages(r));
    return r;
}

/* Sets uniforms and Define toggles (by name, in whichever Program has
 * them) and rebuilds the programs whose defines changed. */
static void apply(render *r, const setting *s, int n) {
    int nsets;
    unif_set *sets = render_uniforms(r, &nsets);
    for (int i = 0; i < n; i++) {
        bool found = false;
        for (int k = 0; k < nsets; k++) {
            unif_entry *e = unif_find(&sets[k], s[i].name);
            if (e) { e->value[0] = s[i].value; found = true; }
        }
        CHECK_MSG(found, "no uniform or Define '%s'", s[i].name);
    }
    bool ok = render_rebuild_programs(r);
    CHECK_MSG(ok && !strstr(render_messages(r), ": error"), "%s", render_messages(r));
}

/* One frame into a float target (RGBA, row 0 at the top); no GL error. */
static void draw(render *r, double t, const render_view *view) {
    render_target tg;
    CHECK(render_target_create(&tg, W, H, true));
    render_frame(r, t, tg.fbo, W, H, view);
    bool ok = render_target_read(&tg, px);
    GLenum e = glGetError();
    CHECK_MSG(ok && e == GL_NO_ERROR, "GL error 0x%x", e);
    render_target_destroy(&tg);
}

static int non_finite(void) {
    int bad = 0;
    for (int i = 0; i < NPX * 4; i++)
        if (!isfinite(px[i])) bad++;
    return bad;
}

/* ---- the lake --------------------------------------------------------------- */

/* The frame's mean and standard deviation of (R + G + B) / 3. */
static void grey_stats(double *mean, double *sd) {
    double s = 0, s2 = 0;
    for (int i = 0; i < NPX; i++) {
        double g = (px[i * 4] + px[i * 4 + 1] + px[i * 4 + 2]) / 3.0;
        s += g;
        s2 += g * g;
    }
    *mean = s / NPX;
    *sd = sqrt(fmax(0.0, s2 / NPX - *mean * *mean));
}

/* Finite, and a picture: the lake in daylight is neither black nor one
 * colour (its sky, shore and water: a mean grey of 0.42 and a spread of
 * 0.23 at 96x54, at any time), and the water moves between the instants. */
static void test_lake_no_nan_at_several_times(void) {
    render *r = load(TARN_SOURCE_DIR "/scenes/lake.glib");
    const double times[] = { 0.0, 3.3, 47.0 };
    static float first[NPX * 4];
    for (int k = 0; k < 3; k++) {
        draw(r, times[k], NULL);
        int bad = non_finite();
        CHECK_MSG(bad == 0, "%d non-finite values at t=%g", bad, times[k]);
        double mean, sd;
        grey_stats(&mean, &sd);
        fprintf(stderr, "  t = %g: mean grey %.3f, spread %.3f\n", times[k], mean, sd);
        CHECK_MSG(mean > 0.1 && mean < 0.9, "t=%g: mean grey %.3f: a black or blown-out frame", times[k], mean);
        CHECK_MSG(sd > 0.05, "t=%g: spread %.3f: a frame of one colour", times[k], sd);
        if (k == 0) memcpy(first, px, sizeof first);
        else CHECK_MSG(memcmp(first, px, sizeof first) != 0, "t=%g draws what t=0 drew: the water stands still",
                       times[k]);
    }
    render_destroy(r);
}

/* Under the water the passes swap roles (If under_water) and the shader
 * its optics; the sky must show through Snell's window, so the top of
 * the image is not black. */
static void test_lake_camera_under_water(void) {
    render *r = load(TARN_SOURCE_DIR "/scenes/lake.glib");
    render_view v = { { 3.0f, -1.2f, 3.0f }, { -2.0f, -0.2f, -1.0f }, { 0, 1, 0 } };
    draw(r, 2.0, &v);
    int bad = non_finite();
    CHECK_MSG(bad == 0, "%d non-finite values under water", bad);
    double top = 0;
    for (int j = 0; j < H / 3; j++)
        for (int i = 0; i < W; i++) top += px[((size_t)j * W + i) * 4 + 2];
    top /= (double)(H / 3) * W;
    fprintf(stderr, "  mean blue of the top third, from under the water: %.3f\n", top);
    CHECK_GT(top, 0.02);
    render_destroy(r);
}

/* The paper's caustics (CPU Splat), no caustics, every debug view and the
 * other toggles compile and draw finite values. */
static void test_lake_toggles_and_views(void) {
    render *r = load(TARN_SOURCE_DIR "/scenes/lake.glib");
    const setting variants[][2] = { { { "CAUSTICS_GPU", 0 }, { "CAUSTICS", 1 } },
                                    { { "CAUSTICS_GPU", 1 }, { "CAUSTICS", 0 } },
                                    { { "CAUSTICS_GPU", 1 }, { "CAUSTICS", 1 } } };
    for (int k = 0; k < 3; k++) {
        apply(r, variants[k], 2);
        draw(r, 1.0, NULL);
        int bad = non_finite();
        CHECK_MSG(bad == 0, "%d non-finite values with CAUSTICS %g, CAUSTICS_GPU %g", bad, variants[k][1].value,
                  variants[k][0].value);
    }
    for (int view = 1; view <= 4; view++) {
        setting s[] = { { "DEBUG_PASS", (float)view } };
        apply(r, s, 1);
        draw(r, 1.0, NULL);
        int bad = non_finite();
        CHECK_MSG(bad == 0, "%d non-finite values in DEBUG_PASS %d", bad, view);
    }
    setting s[] = { { "DEBUG_PASS", 0 }, { "DEBUG_FRESNEL", 1 }, { "EXACT_FRESNEL", 1 }, { "BEER_LAMBERT", 1 },
                    { "SPECULAR", 0 }, { "REFINE_STEPS", 4 } };
    apply(r, s, 6);
    draw(r, 1.0, NULL);
    CHECK_EQ(non_finite(), 0);
    render_destroy(r);
}

/* ---- flat water against the reference ---------------------------------------- */

static ref_world world;
static ref_render_result ref, ref_below;
/* above: water pixels, and those whose refracted ray meets the floor */
static unsigned char water_mask[NPX], floor_mask[NPX];
static float expect_refl[NPX * 3], expect_refr[NPX * 3], ref_F[NPX], ref_hit[NPX * 3], ref_color[NPX * 3];
/* below: water pixels; those whose refracted ray leaves the water */
static unsigned char below_mask[NPX], window_mask[NPX];
static float below_refl[NPX * 3], below_refr[NPX * 3];

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void unit3(const double a[3], const double b[3], double d[3]) {
    for (int k = 0; k < 3; k++) d[k] = b[k] - a[k];
    double l = sqrt(dot3(d, d));
    for (int k = 0; k < 3; k++) d[k] /= l;
}

/* What tarn's world program shows at point p (met by a ray from the
 * surface point s): ref_shade_lambert above the water; below it the sun
 * through flat water (worldShadeAt, whose twin is ref_render_flat_sun) and
 * the ambient let through, ambient (1 - R0) exp(-sigma depth), times
 * Beer-Lambert over |p - s|. The pack's passes hold this, so comparing
 * against it measures the pack's approximations, not the world program's
 * (the reference lights the floor with photon caustics instead). */
static void world_radiance(const double s[3], const double p[3], double L[3]) {
    double d[3], t, n[3], albedo[3];
    unit3(s, p, d);
    double dist = sqrt((p[0] - s[0]) * (p[0] - s[0]) + (p[1] - s[1]) * (p[1] - s[1]) + (p[2] - s[2]) * (p[2] - s[2]));
    int ob = ref_objects_hit(&world, s, d, 1e-6, dist + 1e-4, &t, n);
    if (ob >= 0 && fabs(t - dist) < 1e-3) {
        memcpy(albedo, world.d.objects[ob].albedo, sizeof albedo);
    } else {
        ref_terrain_albedo(&world, p[0], p[2], albedo);
        ref_terrain_normal_at(&world, p[0], p[2], n);
    }
    if (p[1] >= world.d.water_level) {
        ref_shade_lambert(&world, albedo, n, 1.0, L);
        return;
    }
    double e[3], r0 = (world.d.ior - 1) / (world.d.ior + 1), depth = world.d.water_level - p[1];
    ref_render_flat_sun(&world, p, n, e);
    for (int k = 0; k < 3; k++) {
        double ambient = world.ambient[k] * (1 - r0 * r0) * exp(-world.d.absorption[k] * depth);
        L[k] = albedo[k] * (e[k] / M_PI + ambient) * exp(-world.d.absorption[k] * dist);
    }
}

static bool render_reference(const scene_camera *cam, const double *eye, const double *center, ref_render_result *out) {
    ref_render_desc rd = { .world = &world, .caustics = REF_CAUSTICS_FLAT };
    memcpy(rd.camera.eye, eye ? eye : cam->eye, sizeof rd.camera.eye);
    memcpy(rd.camera.center, center ? center : cam->center, sizeof rd.camera.center);
    memcpy(rd.camera.up, cam->up, sizeof rd.camera.up);
    rd.camera.fov_deg = cam->fov_deg;
    rd.camera.width = W;
    rd.camera.height = H;
    char err[512];
    if (ref_render(&rd, out, err, sizeof err) == 0) return true;
    fprintf(stderr, "%s\n", err);
    return false;
}

/* The reference for the flat scene at W x H, from above and from below,
 * and from its buffers what the pack's reflected and refracted colours
 * should be. */
static bool reference_flat(const char *scene) {
    ref_world_desc desc;
    scene_camera cam;
    bool has_world;
    char err[1024];
    if (!scene_load(scene, NULL, &desc, &cam, &has_world, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        return false;
    }
    ref_world_init(&world, &desc);
    double eye[3], center[3];
    for (int k = 0; k < 3; k++) {
        eye[k] = below_view.eye[k];
        center[k] = below_view.center[k];
    }
    if (!render_reference(&cam, NULL, NULL, &ref) || !render_reference(&cam, eye, center, &ref_below)) return false;

    int nwater = 0, nfloor = 0, nbelow = 0, nwindow = 0;
    for (int i = 0; i < NPX; i++) {
        const double *s = ref.surface + i * 3, *rh = ref.refract_hit + i * 4, *rf = ref.reflect + i * 4;
        for (int k = 0; k < 3; k++) ref_color[i * 3 + k] = (float)ref.color[i * 3 + k];
        water_mask[i] = ref.mask[i] == REF_MASK_WATER && fabs(s[0]) < 11 && fabs(s[2]) < 11;
        if (water_mask[i]) {
            nwater++;
            ref_F[i] = (float)ref.fresnel[i];
            double L[3] = { NAN, NAN, NAN }, Lt[3] = { NAN, NAN, NAN };
            if ((int)rf[3] == REF_REFLECT_SKY) ref_sky_radiance(&world, rf, L);
            else if ((int)rf[3] == REF_REFLECT_POINT) world_radiance(s, rf, L);
            int what = (int)rh[3];
            if (what == REF_MASK_TERRAIN || what == REF_MASK_OBJECT) world_radiance(s, rh, Lt);
            for (int k = 0; k < 3; k++) {
                expect_refl[i * 3 + k] = (float)L[k];
                expect_refr[i * 3 + k] = (float)Lt[k];
                ref_hit[i * 3 + k] = (float)rh[k];
            }
            floor_mask[i] = what == REF_MASK_TERRAIN && fabs(rh[0]) < 9 && fabs(rh[2]) < 9;
            nfloor += floor_mask[i];
        }
        /* from below */
        s = ref_below.surface + i * 3;
        rh = ref_below.refract_hit + i * 4;
        rf = ref_below.reflect + i * 4;
        below_mask[i] = ref_below.mask[i] == REF_MASK_WATER && fabs(s[0]) < 11 && fabs(s[2]) < 11 &&
                        (int)rf[3] == REF_REFLECT_POINT;
        if (!below_mask[i]) continue;
        nbelow++;
        double L[3], Lt[3] = { NAN, NAN, NAN }, d[3], t[3], up[3] = { 0, 1, 0 };
        world_radiance(s, rf, L);
        unit3(eye, s, d);
        window_mask[i] = ref_below.fresnel[i] < 1.0 && ref_refract(d, up, world.d.ior, REF_N_AIR, t);
        if (window_mask[i]) {
            nwindow++;
            if ((int)rh[3] == REF_MASK_SKY) ref_sky_radiance(&world, t, Lt);
            else world_radiance(s, rh, Lt);
        }
        for (int k = 0; k < 3; k++) {
            below_refl[i * 3 + k] = (float)L[k];
            below_refr[i * 3 + k] = (float)Lt[k];
        }
    }
    fprintf(stderr, "  reference %dx%d: from above %d water pixels (%d see the floor); from below %d (%d in "
            "Snell's window)\n", W, H, nwater, nfloor, nbelow, nwindow);
    return nwater > NPX / 3 && nbelow > NPX / 3 && nwindow > 100;
}

/* Colour metrics of the render's RGB against an expected RGB, over a mask. */
static ref_image_metrics colour_error(const float *expect, const unsigned char *mask) {
    static float rgb[NPX * 3];
    for (int i = 0; i < NPX; i++)
        for (int k = 0; k < 3; k++) rgb[i * 3 + k] = px[i * 4 + k];
    ref_fimage a = { rgb, W, H, 3 }, b = { expect, W, H, 3 };
    ref_metrics_desc md = { .mask = mask, .threshold = 0.02 };
    ref_image_metrics m;
    char err[256];
    CHECK_MSG(ref_metrics_image(&a, &b, &md, &m, err, sizeof err), "%s", err);
    return m;
}

static void print_colour(const char *what, const ref_image_metrics *m) {
    fprintf(stderr, "  %-46s n %5ld  RMSE %.4f  median %.4f  p95 %.4f  max %.4f  bias %+.4f %+.4f %+.4f\n", what,
            m->count.compared, m->rmse, m->pixel_err.median, m->pixel_err.p95, m->pixel_err.max, m->bias[0],
            m->bias[1], m->bias[2]);
}

/* Exact Fresnel on flat water is the reference's formula at the same
 * geometry: the fragment's interpolated position lies on the plane where
 * the pixel-centre ray meets it, so only float rounding differs (cos to
 * ~1e-6, R to < 1e-5 even at grazing incidence): tolerance 1e-4, from
 * above and from below (total internal reflection beyond 48.6 degrees).
 * The paper's (1 - E.N)^4.5 is reported, not bounded. */
static void test_flat_fresnel(render *r) {
    setting exact[] = { { "DEBUG_FRESNEL", 1 }, { "EXACT_FRESNEL", 1 } };
    apply(r, exact, 2);
    draw(r, 0.0, NULL);
    double worst = 0;
    for (int i = 0; i < NPX; i++)
        if (water_mask[i]) worst = fmax(worst, fabs(px[i * 4] - ref_F[i]));
    fprintf(stderr, "  Fresnel, exact: max |F - R_ref| = %.2g\n", worst);
    CHECK_LT(worst, 1e-4);

    setting paper[] = { { "EXACT_FRESNEL", 0 } };
    apply(r, paper, 1);
    draw(r, 0.0, NULL);
    double sum = 0, max = 0;
    int n = 0;
    for (int i = 0; i < NPX; i++)
        if (water_mask[i]) {
            double e = px[i * 4] - ref_F[i];
            sum += e * e;
            max = fmax(max, fabs(e));
            n++;
        }
    fprintf(stderr, "  Fresnel, paper's (1 - E.N)^4.5: RMSE %.4f, max %.4f over %d pixels\n", sqrt(sum / n), max, n);

    setting exact_again[] = { { "EXACT_FRESNEL", 1 } };
    apply(r, exact_again, 1);
    draw(r, 0.0, &below_view);
    worst = 0;
    n = 0;
    int tir = 0;
    for (int i = 0; i < NPX; i++) {
        if (ref_below.mask[i] != REF_MASK_WATER) continue;
        const double *s = ref_below.surface + i * 3;
        if (fabs(s[0]) > 11 || fabs(s[2]) > 11) continue;
        worst = fmax(worst, fabs(px[i * 4] - ref_below.fresnel[i]));
        tir += ref_below.fresnel[i] == 1.0;
        n++;
    }
    fprintf(stderr, "  Fresnel from below, exact: max |F - R_ref| = %.2g over %d pixels (%d in TIR)\n", worst, n, tir);
    CHECK(n > 100 && tir > 10 && tir < n - 100);
    CHECK_LT(worst, 1e-4);
    setting off[] = { { "DEBUG_FRESNEL", 0 } };
    apply(r, off, 1);
}

/* Reflection on flat water, from above and below: the mirror pass is exact
 * (U + c R projects to the mirror image of U for any c), so what is left is
 * sampling: the sky cube map (128 texels a face, bilinear: < 0.02, see
 * test_world_gl), the float16 target (< 1e-3 relative) and silhouettes,
 * where a pixel of the 96x54 image straddles two surfaces in the 512-texel
 * target. Bounds: median 0.005, 95th percentile 0.02; silhouette pixels
 * (< 5 %) may be off by the whole contrast across the edge. From below the
 * reflection is of the floor through the water (Beer-Lambert on, so the
 * pack's attenuation is the reference's). */
static void test_flat_reflection(render *r) {
    setting s[] = { { "DEBUG_PASS", 2 }, { "BEER_LAMBERT", 1 } };
    apply(r, s, 2);
    draw(r, 0.0, NULL);
    ref_image_metrics m = colour_error(expect_refl, water_mask);
    print_colour("reflected colour (mirror pass)", &m);
    CHECK_GT(m.count.compared, NPX / 3);
    CHECK_LT(m.pixel_err.median, 0.005);
    CHECK_LT(m.pixel_err.p95, 0.02);
    draw(r, 0.0, &below_view);
    m = colour_error(below_refl, below_mask);
    print_colour("reflected colour from below (mirror pass)", &m);
    CHECK_GT(m.count.compared, NPX / 3);
    CHECK_LT(m.pixel_err.median, 0.005);
    CHECK_LT(m.pixel_err.p95, 0.02);
}

/* Point metrics of the DEBUG_PASS 4 output (the refraction lookup's point)
 * against the reference's refraction hit, over the floor mask. */
static ref_point_metrics hit_error(void) {
    static float xyz[NPX * 3];
    for (int i = 0; i < NPX; i++)
        for (int k = 0; k < 3; k++) xyz[i * 3 + k] = px[i * 4 + k];
    ref_fimage a = { xyz, W, H, 3 }, b = { ref_hit, W, H, 3 };
    ref_metrics_desc md = { .mask = floor_mask };
    ref_point_metrics m;
    char err[256];
    CHECK_MSG(ref_metrics_points(&a, &b, &md, &m, err, sizeof err), "%s", err);
    return m;
}

static void print_hits(const char *what, const ref_point_metrics *m) {
    fprintf(stderr, "  %-46s n %5ld  mean %.3f m  median %.3f  p95 %.3f  max %.3f\n", what, m->count.compared,
            m->world.mean, m->world.median, m->world.p95, m->world.max);
}

/* Refraction on flat water, hit point and colour. The paper's estimate
 * W = U + clamp(dv, 0, 2)/3 R falls short of the floor (it is meant to
 * perturb, not to find the hit), and so does dv unscaled: both reported.
 * With REFINE_STEPS 8 (a march along R against the depth target, then
 * regula falsi) the lookup finds the refracted ray's hit on this floor:
 * bound 0.01 m at the median and 0.05 m at the 95th percentile (a texel
 * of the 512 target is ~0.03 m here; the tail is the boulder's
 * silhouette, where the bracket straddles two surfaces). The colour then follows tarn's shading at that point times
 * Beer-Lambert on the estimated path: bounds as for the reflection. From
 * below, Snell's window shows the sky through the world-above pass. */
static void test_flat_refraction(render *r) {
    setting paper[] = { { "DEBUG_PASS", 4 }, { "BEER_LAMBERT", 0 }, { "REFINE_STEPS", 0 } };
    apply(r, paper, 3);
    draw(r, 0.0, NULL);
    ref_point_metrics hp = hit_error();
    print_hits("refraction hit, paper (dv/3, clamp 2)", &hp);

    setting depth1[] = { { "uDepthScale", 1 }, { "uDepthClamp", 20 } };
    apply(r, depth1, 2);
    draw(r, 0.0, NULL);
    ref_point_metrics h1 = hit_error();
    print_hits("refraction hit, dv unscaled", &h1);

    setting refine[] = { { "REFINE_STEPS", 8 } };
    apply(r, refine, 1);
    draw(r, 0.0, NULL);
    ref_point_metrics h3 = hit_error();
    print_hits("refraction hit, REFINE_STEPS 8", &h3);
    CHECK_GT(h3.count.compared, NPX / 4);
    CHECK_LT(h3.world.median, 0.01);
    CHECK_LT(h3.world.p95, 0.05);

    setting colour[] = { { "DEBUG_PASS", 1 }, { "BEER_LAMBERT", 1 } };
    apply(r, colour, 2);
    draw(r, 0.0, NULL);
    ref_image_metrics m = colour_error(expect_refr, floor_mask);
    print_colour("refracted colour, Beer-Lambert, REFINE_STEPS 8", &m);
    CHECK_LT(m.pixel_err.median, 0.005);
    CHECK_LT(m.pixel_err.p95, 0.02);

    draw(r, 0.0, &below_view);
    m = colour_error(below_refr, window_mask);
    print_colour("refracted colour from below (Snell's window)", &m);
    CHECK_GT(m.count.compared, 100);
    CHECK_LT(m.pixel_err.median, 0.005);
    CHECK_LT(m.pixel_err.p95, 0.02);
}

/* The whole water colour against the reference image (flat water, so the
 * reference's photon caustics are the flat sun). With the settings matched
 * to the reference's model (exact Fresnel, Beer-Lambert, no highlight, the
 * march) it is F refl + (1 - F) refr of the parts bounded above: the same
 * bounds. With the paper's defaults: reported for the pack's page. */
static void test_flat_final_colour(render *r) {
    setting matched[] = { { "DEBUG_PASS", 0 }, { "SPECULAR", 0 }, { "EXACT_FRESNEL", 1 } };
    apply(r, matched, 3);
    draw(r, 0.0, NULL);
    ref_image_metrics m = colour_error(ref_color, water_mask);
    print_colour("water colour, matched settings", &m);
    CHECK_GT(m.count.compared, NPX / 3);
    CHECK_LT(m.pixel_err.median, 0.005);
    CHECK_LT(m.pixel_err.p95, 0.02);
    setting paper[] = { { "SPECULAR", 1 }, { "EXACT_FRESNEL", 0 }, { "BEER_LAMBERT", 0 }, { "REFINE_STEPS", 0 },
                        { "uDepthScale", 0.333f }, { "uDepthClamp", 2 } };
    apply(r, paper, 6);
    draw(r, 0.0, NULL);
    m = colour_error(ref_color, water_mask);
    print_colour("water colour, the paper's defaults", &m);
}

static void test_flat_water_against_reference(void) {
    const char *scene = flat_scene();
    if (!reference_flat(scene)) {
        CHECK_MSG(0, "reference render failed");
        return;
    }
    render *r = load(scene);
    setting no_caustics[] = { { "CAUSTICS", 0 } };
    apply(r, no_caustics, 1);
    test_flat_fresnel(r);
    test_flat_reflection(r);
    test_flat_refraction(r);
    test_flat_final_colour(r);
    render_destroy(r);
}

/* The water behind a sphere floating across the lake's surface, close up:
 * the refraction march of a pixel whose ray goes behind the sphere (as the
 * camera sees it) closed on the sphere's silhouette in the refraction
 * target, and the pixel showed the sphere's edge, in arcs beside it. It
 * now takes the point behind U instead (lookThrough). Over the water
 * pixels whose reference ray meets the terrain within 3 m of the sphere,
 * the pack's refraction hits (DEBUG_PASS 4) that lie in open water, more
 * than 0.3 m over the terrain and off the sphere (the silhouette's
 * phantom points, where the target's depth is read across the edge):
 * measured 36 of 2023 before, 5 after (those at its waterline); bound 12. */
static void test_lake_behind_a_floating_sphere(void) {
    const char *scene = path_in_dir("sphere.glib");
    FILE *f = fopen(scene, "w");
    if (!f) { perror(scene); exit(1); }
    fprintf(f, "##OpenGL GLIB\nInclude \"%s/scenes/lake.glib\"\nWindowSize %d %d\n"
               "LookAt -1 2.2 0.5  -3 -0.3 -2  0 1 0\n", TARN_SOURCE_DIR, W, H);
    fclose(f);
    ref_world_desc desc;
    scene_camera cam;
    bool has_world;
    char err[1024];
    CHECK_MSG(scene_load(scene, NULL, &desc, &cam, &has_world, err, sizeof err), "%s", err);
    ref_world w;
    ref_world_init(&w, &desc);
    ref_render_desc rd = { .world = &w, .caustics = REF_CAUSTICS_FLAT, .time = 1.0 };
    memcpy(rd.camera.eye, cam.eye, sizeof rd.camera.eye);
    memcpy(rd.camera.center, cam.center, sizeof rd.camera.center);
    memcpy(rd.camera.up, cam.up, sizeof rd.camera.up);
    rd.camera.fov_deg = cam.fov_deg;
    rd.camera.width = W;
    rd.camera.height = H;
    ref_render_result rr;
    if (ref_render(&rd, &rr, err, sizeof err) != 0) {
        CHECK_MSG(0, "%s", err);
        return;
    }
    render *r = load(scene);
    setting hit[] = { { "DEBUG_PASS", 4 } };
    apply(r, hit, 1);
    draw(r, 1.0, NULL);
    long n = 0, phantom = 0;
    for (int i = 0; i < NPX; i++) {
        const double *h = rr.refract_hit + i * 4;
        if (rr.mask[i] != REF_MASK_WATER || (int)h[3] != REF_MASK_TERRAIN) continue;
        if (hypot(h[0] + 3.0, h[2] + 2.0) > 3.0) continue;
        n++;
        /* the pack's hit in open water: over the terrain there by more than
         * 0.3 m and off the sphere (centre (-3, -0.2, -2), radius 0.9) */
        const float *g = px + i * 4;
        double above = g[1] - ref_terrain_height(&w, g[0], g[2]);
        double from_sphere = sqrt(pow(g[0] + 3.0, 2) + pow(g[1] + 0.2, 2) + pow(g[2] + 2.0, 2));
        phantom += above > 0.3 && from_sphere > 1.0;
    }
    fprintf(stderr, "  behind a floating sphere: %ld of %ld refraction hits in open water\n", phantom, n);
    CHECK_GT(n, NPX / 8);
    CHECK_MSG(phantom <= 12, "%ld of %ld", phantom, n);
    render_destroy(r);
    ref_render_free(&rr);
    unlink(scene);
}

/* Under flat water both caustic methods must give the ratio 1 (the
 * photons spread evenly in refracted-sun space). The GPU's mesh splat
 * lands every cell of the photon mesh on a cell of the same area, so it is
 * 1 to float rounding (bound 1e-3); the paper's bilinear point splat of
 * ~1 photon a texel (512^2 light texels into 256^2, its setting) samples a
 * regular grid, read through the shader's tent filter: bound 0.05. Both
 * |mean - 1| < 0.01. */
static void test_flat_caustic_ratio_is_one(void) {
    render *r = load(flat_scene());
    const double p95_bound[] = { 1e-3, 0.05 };
    for (int gpu = 1; gpu >= 0; gpu--) {
        setting s[] = { { "CAUSTICS", 1 }, { "CAUSTICS_GPU", (float)gpu }, { "DEBUG_PASS", 3 },
                        { "uPhotonGrid", gpu ? 256.0f : 512.0f }, { "uCausticRes", gpu ? 384.0f : 256.0f } };
        apply(r, s, 5);
        draw(r, 0.0, NULL);
        double *dev = malloc(NPX * sizeof *dev), mean = 0;
        int n = 0;
        for (int i = 0; i < NPX; i++)
            if (floor_mask[i]) {
                double ratio = 2.0 * px[i * 4];
                mean += ratio;
                dev[n++] = fabs(ratio - 1);
            }
        mean /= n > 0 ? n : 1;
        double p95 = ref_percentile(dev, n, 95), max = ref_percentile(dev, n, 100);
        fprintf(stderr, "  caustic ratio on flat water, %-5s n %d  mean %.4f  p95 |r-1| %.4f  max %.4f\n",
                gpu ? "GPU" : "paper", n, mean, p95, max);
        CHECK_GT(n, NPX / 4);
        CHECK_LT(fabs(mean - 1), 0.01);
        CHECK_LT(p95, p95_bound[gpu ? 0 : 1]);
        free(dev);
    }
    render_destroy(r);
}

/* The caustic texture of the last frame (unit 10), RGBA rows from t = 0. */
static float *caustic_texture(int *tw, int *th) {
    GLint tex = 0;
    glActiveTexture(GL_TEXTURE10);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &tex);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, (GLuint)tex);
    glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, tw);
    glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, th);
    float *buf = malloc((size_t)*tw * *th * 4 * sizeof(float));
    if (buf) glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, buf);
    glBindTexture(GL_TEXTURE_2D, 0);
    return buf;
}

/* GL's bilinear lookup of channel 0 at (u, v), clamped to the edge. */
static double bilinear(const float *t, int tw, int th, double u, double v) {
    double x = u * tw - 0.5, y = v * th - 0.5;
    int i0 = (int)floor(x), j0 = (int)floor(y);
    double a = x - i0, b = y - j0, sum = 0;
    for (int dj = 0; dj < 2; dj++)
        for (int di = 0; di < 2; di++) {
            int i = i0 + di < 0 ? 0 : i0 + di >= tw ? tw - 1 : i0 + di;
            int j = j0 + dj < 0 ? 0 : j0 + dj >= th ? th - 1 : j0 + dj;
            sum += (di ? a : 1 - a) * (dj ? b : 1 - b) * t[((size_t)j * tw + i) * 4];
        }
    return sum;
}

/* The caustics against the reference's photon tracer (ref_render's grid:
 * 64 cells over the 24 m floor, 64 stratified photons a cell, so its own
 * noise is at most ~5 %). The pack's ratio, as water.frag reads it (the
 * 4-tap tent at the point's refracted-sun coordinates), averaged over each
 * reference cell (3 x 3 points), against the reference's irradiance over
 * the flat-water irradiance there (green channel), over |x|, |z| < 9.
 * Bounds: the mean within 2 % of the reference's, the pattern correlated
 * (r > 0.9), RMSE below half the pattern's own standard deviation (the
 * GPU's photons; the paper's eq. (1) ones are fainter, see below). */
static void test_wavy_caustics_against_photon_tracing(void) {
    const char *scene = wavy_scene();
    ref_world_desc desc;
    scene_camera cam;
    bool has_world;
    char err[1024];
    if (!scene_load(scene, NULL, &desc, &cam, &has_world, err, sizeof err)) {
        CHECK_MSG(0, "%s", err);
        return;
    }
    ref_world w;
    ref_world_init(&w, &desc);
    ref_render_desc rd = { .world = &w, .caustic_res = 64, .photons_per_cell = 64 };
    memcpy(rd.camera.eye, cam.eye, sizeof cam.eye);
    memcpy(rd.camera.center, cam.center, sizeof cam.center);
    rd.camera.width = 8;
    rd.camera.height = 8;
    ref_render_result res;
    if (ref_render(&rd, &res, err, sizeof err) != 0) {
        CHECK_MSG(0, "%s", err);
        return;
    }
    double ts[3], down[3] = { -w.d.sun_dir[0], -w.d.sun_dir[1], -w.d.sun_dir[2] }, up[3] = { 0, 1, 0 };
    ref_refract(down, up, REF_N_AIR, w.d.ior, ts);
    double floor_y = w.d.water_level - w.d.depth, shift = w.d.depth / -ts[1], hc = 1.25 * w.d.half_size;
    render *r = load(scene);
    for (int gpu = 1; gpu >= 0; gpu--) {
        setting s[] = { { "CAUSTICS", 1 }, { "CAUSTICS_GPU", (float)gpu },   /* each at its setting's grids */
                        { "uPhotonGrid", gpu ? 256.0f : 512.0f }, { "uCausticRes", gpu ? 384.0f : 256.0f } };
        apply(r, s, 4);
        draw(r, 0.0, NULL);
        int tw = 0, th = 0;
        float *tex = caustic_texture(&tw, &th);
        CHECK(tex && tw > 0 && th > 0);
        if (!tex) break;
        double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, se = 0;
        int n = 0;
        for (double z = -9 + 0.1875; z < 9; z += 0.375)
            for (double x = -9 + 0.1875; x < 9; x += 0.375) {
                double p[3] = { x, floor_y, z }, e[3], ef[3];
                ref_render_caustic_at(&res, &w, x, z, e);
                ref_render_flat_sun(&w, p, up, ef);
                double b = e[1] / ef[1], a = 0;
                for (int sj = -1; sj <= 1; sj++)
                    for (int si = -1; si <= 1; si++) {
                        double qx = x + si * 0.125 - ts[0] * shift, qz = z + sj * 0.125 - ts[2] * shift;
                        double u = qx / hc * 0.5 + 0.5, v = qz / hc * 0.5 + 0.5, ou = 0.5 / tw, ov = 0.5 / th;
                        a += 0.25 * (bilinear(tex, tw, th, u - ou, v - ov) + bilinear(tex, tw, th, u + ou, v - ov) +
                                     bilinear(tex, tw, th, u - ou, v + ov) + bilinear(tex, tw, th, u + ou, v + ov)) / 9;
                    }
                sa += a;
                sb += b;
                saa += a * a;
                sbb += b * b;
                sab += a * b;
                se += (a - b) * (a - b);
                n++;
            }
        double ma = sa / n, mb = sb / n, va = saa / n - ma * ma, vb = sbb / n - mb * mb;
        double corr = (sab / n - ma * mb) / sqrt(va * vb), rmse = sqrt(se / n);
        fprintf(stderr, "  caustic ratio vs photon tracing, %-5s n %d  mean %.4f (ref %.4f)  std %.3f (ref %.3f)  "
                "RMSE %.4f  r %.3f\n", gpu ? "GPU" : "paper", n, ma, mb, sqrt(va), sqrt(vb), rmse, corr);
        CHECK_LT(fabs(ma - mb), 0.02);
        CHECK_GT(corr, 0.9);
        /* the paper's eq. (1) puts a photon's hit at most 2/3 m down its
         * refracted ray (issue #24): the pattern is where the tracer's is
         * (r above) but far fainter (std 0.027 against 0.139 here), so
         * only the GPU's photons are held to the RMSE bound */
        if (gpu) CHECK_LT(rmse, 0.5 * sqrt(vb));
        else CHECK_LT(sqrt(va), 0.5 * sqrt(vb));
        free(tex);
    }
    render_destroy(r);
    ref_render_free(&res);
}

int main(void) {
    char err[512];
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    if (!ctx) { fprintf(stderr, "skip: %s\n", err); return 77; }
    snprintf(dir, sizeof dir, "/tmp/tarn_natural_XXXXXX");
    if (!mkdtemp(dir)) { perror("mkdtemp"); return 1; }
    RUN(test_lake_no_nan_at_several_times);
    RUN(test_lake_camera_under_water);
    RUN(test_lake_toggles_and_views);
    RUN(test_flat_water_against_reference);
    RUN(test_lake_behind_a_floating_sphere);
    RUN(test_flat_caustic_ratio_is_one);
    RUN(test_wavy_caustics_against_photon_tracing);
    ref_render_free(&ref);
    ref_render_free(&ref_below);
    gl_ctx_destroy(ctx);
    unlink(path_in_dir("flat.glib"));
    unlink(path_in_dir("wavy.glib"));
    rmdir(dir);
    return check_summary();
}
