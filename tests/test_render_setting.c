/* test_render_setting: a pack's bench.txt setting applied to a running
 * scene (render_setting.h) draws the same pixels as `tarn bench` draws it
 * — a fresh load with the row's assignments, and for scene.WaterMesh the
 * scene with the line added — whatever was on screen before; the sliders
 * go back to the pack's defaults first; a scene command the renderer
 * cannot take at run time is reported, the rest still applied. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "gl_ctx.h"
#include "gl_support.h"
#include "packset.h"
#include "render.h"
#include "render_setting.h"
#include "support.h"

#ifndef TARN_SOURCE_DIR
#define TARN_SOURCE_DIR "."
#endif

enum { W = 96, H = 54 };
static const double T = 1.0;
#define LAKE TARN_SOURCE_DIR "/scenes/lake.glib"

static float *draw(render *r) {
    render_target tg;
    float *px = calloc((size_t)W * H * 4, sizeof *px);
    CHECK(render_target_create(&tg, W, H, true));
    render_frame(r, T, tg.fbo, W, H, NULL);
    render_target_read(&tg, px);
    render_target_destroy(&tg);
    return px;
}

static double max_diff(const float *a, const float *b) {
    double m = 0;
    for (long i = 0; i < (long)W * H * 4; i++) m = fmax(m, fabs((double)a[i] - b[i]));
    return m;
}

/* What bench draws for pack's setting name: a fresh render of the scene
 * (with the row's scene lines added), then the row's assignments. */
static float *bench_way(const char *pack, const char *name) {
    packset_bench b;
    CHECK(packset_bench_load(TARN_SOURCE_DIR, pack, &b, NULL, 0));
    const packset_setting *s = packset_setting_named(&b, name);
    CHECK_MSG(s != NULL, "%s has no setting %s", pack, name);
    const char *scene = LAKE;
    char lines[256];
    if (s && packset_scene_lines(s, lines, sizeof lines) > 0) {
        scene = scratch_path("wrapper.glib");
        CHECK(packset_write_wrapper(s, LAKE, scene, NULL, 0));
    }
    render *r = render_create(&(render_desc){ .repo_root = TARN_SOURCE_DIR, .pack = pack });
    CHECK_MSG(render_load(r, scene), "%s", render_messages(r));
    int n;
    bool defines = false;
    unif_set *sets = render_uniforms(r, &n);
    if (s) CHECK(packset_apply(sets, n, s, &defines, NULL, 0));
    if (defines) CHECK(render_rebuild_programs(r));
    float *px = draw(r);
    render_destroy(r);
    packset_bench_free(&b);
    return px;
}

/* natural's paper (Defines off, the CPU splat) then mesh-64 then default,
 * one after another on one render whose sliders were moved first. */
static void test_same_pixels_as_bench(void) {
    render *r = render_create(&(render_desc){ .repo_root = TARN_SOURCE_DIR, .pack = "natural" });
    CHECK_MSG(render_load(r, LAKE), "%s", render_messages(r));
    unif_entry *att = gl_test_uniform(r, "NaturalWater", "uAttenuation");
    CHECK_NE(att, NULL);
    if (!att) { render_destroy(r); return; }
    float def = att->def[0];
    unif_set_component(att, 0, def + 0.7f);
    free(draw(r));

    const char *order[] = { "paper", "mesh-64", "default" };
    for (int k = 0; k < 3; k++) {
        char msg[2048] = "";
        CHECK_MSG(render_setting_apply_named(r, TARN_SOURCE_DIR, order[k], msg, sizeof msg), "%s: %s", order[k],
                  msg);
        att = gl_test_uniform(r, "NaturalWater", "uAttenuation");
        CHECK_MSG(att && att->value[0] == def, "%s: the slider moved before is back at its default", order[k]);
        unif_entry *gpu = gl_test_uniform(r, "NaturalWater", "CAUSTICS_GPU");
        CHECK(gpu && gpu->value[0] == (strcmp(order[k], "paper") == 0 ? 0.0f : 1.0f));
        float *got = draw(r), *want = bench_way("natural", order[k]);
        double d = max_diff(got, want);
        CHECK_MSG(d == 0, "%s: the applied setting differs from bench's by up to %g", order[k], d);
        free(got);
        free(want);
    }
    render_destroy(r);
}

/* mesh-64's grid differs from the default's: the pixels tell them apart
 * (so the test above would see a WaterMesh that was not applied). */
static void test_water_mesh_shows(void) {
    float *a = bench_way("natural", "default"), *b = bench_way("natural", "mesh-64");
    CHECK_MSG(max_diff(a, b) > 1e-3, "WaterMesh 64 draws as the default grid (max diff %g)", max_diff(a, b));
    free(a);
    free(b);
}

static void test_not_applicable_and_unknown(void) {
    render *r = render_create(&(render_desc){ .repo_root = TARN_SOURCE_DIR, .pack = "natural" });
    CHECK_MSG(render_load(r, LAKE), "%s", render_messages(r));
    packset_bench b;
    CHECK(packset_bench_parse("odd scene.Sun=1,2,3 NaturalWater.uAttenuation=0.25 scene.WaterMesh=32\n", "t", &b,
                              NULL, 0));
    char why[256], msg[2048] = "";
    CHECK(!render_setting_applicable(&b.settings[0], why, sizeof why));
    CHECK_STR_CONTAINS(why, "scene.Sun");
    CHECK(!render_setting_apply(r, &b.settings[0], msg, sizeof msg));
    CHECK_STR_CONTAINS(msg, "scene.Sun does not apply to a running scene");
    unif_entry *att = gl_test_uniform(r, "NaturalWater", "uAttenuation");
    CHECK(att && fabsf(att->value[0] - 0.25f) < 1e-6f);   /* the rest applied */
    packset_bench_free(&b);

    msg[0] = '\0';
    CHECK(!render_setting_apply_named(r, TARN_SOURCE_DIR, "nope", msg, sizeof msg));
    CHECK_STR_CONTAINS(msg, "the natural pack has no such setting; it has default paper ");
    render_destroy(r);

    /* a glman scene has no pack: nothing to choose from */
    scratch_write("plain.glib", "##OpenGL GLIB\nOrtho -1 1 -1 1\n");
    r = render_create(&(render_desc){ .repo_root = TARN_SOURCE_DIR });
    render_load(r, scratch_path("plain.glib"));
    msg[0] = '\0';
    CHECK(!render_setting_apply_named(r, TARN_SOURCE_DIR, "paper", msg, sizeof msg));
    CHECK_STR_CONTAINS(msg, "drawn by no pack");
    render_destroy(r);
}

/* ---- a scene pays only for the passes its content needs (issue #24) ----- */

/* The units the last frame's RenderToTexture passes drew into, as bits
 * (names "pass:LINE u1 u2 ..."); the names go to stderr, the passes per
 * case. */
static unsigned pass_units(render *r, const char *what) {
    const char (*names)[GPU_TIMER_NAME];
    const double *ms;
    int n = render_pass_times(r, true, &names, &ms);
    unsigned units = 0;
    fprintf(stderr, "  %-40s", what);
    for (int i = 0; i < n; i++) {
        fprintf(stderr, " [%s]", names[i]);
        if (strncmp(names[i], "pass:", 5) != 0) continue;
        const char *u = strchr(names[i], ' ');
        while (u && *u) {
            char *end;
            long v = strtol(u, &end, 10);
            if (end == u) break;
            if (v >= 0 && v < 32) units |= 1u << v;
            u = end;
        }
    }
    fprintf(stderr, "\n");
    return units;
}

/* A scene loaded with pack at setting (bench.txt's row), one frame drawn
 * twice (the timer's names are the previous frame's). */
static render *with_setting(const char *scene, const char *pack, const char *setting) {
    render *r = render_create(&(render_desc){ .repo_root = TARN_SOURCE_DIR, .pack = pack });
    CHECK_MSG(render_load(r, scene), "%s", render_messages(r));
    char msg[2048] = "";
    CHECK_MSG(render_setting_apply_named(r, TARN_SOURCE_DIR, setting, msg, sizeof msg), "%s: %s", setting, msg);
    free(draw(r));
    free(draw(r));
    return r;
}

#define CALM TARN_SOURCE_DIR "/scenes/hard/calm.glib"
#define OCEAN TARN_SOURCE_DIR "/scenes/ocean.glib"

/* natural: the photon passes (light depth 8, once; photons 9; the GPU's
 * splat 10, the paper's is the CPU's `Splat`) only on water with waves (`If waves`): on calm water the ratio is exactly 1.
 * caustic_tex: the mirror pass (10 11) only with SKY_REFLECTION (its paper
 * row has it off). raymarch: the reflection march (no pass of its own:
 * compiled in only when something stands above the water,
 * WORLD_ABOVE_WATER) is in the lake's water program and not in the open
 * sea's, which has only sky above its water (uReflectStep is read by that
 * march alone, so it is active in the program exactly when the default's
 * march is). */
static void test_passes_per_scene_and_setting(void) {
    static const char *settings[] = { "default", "paper" };
    for (int k = 0; k < 2; k++) {
        char what[128];
        render *r = with_setting(LAKE, "natural", settings[k]);
        snprintf(what, sizeof what, "natural %s, lake:", settings[k]);
        CHECK_MSG(pass_units(r, what) & (1u << 9), "natural %s: the lake has waves, no photon pass ran", settings[k]);
        render_destroy(r);
        r = with_setting(CALM, "natural", settings[k]);
        snprintf(what, sizeof what, "natural %s, calm:", settings[k]);
        CHECK_MSG(!(pass_units(r, what) & (1u << 8 | 1u << 9 | 1u << 10)), "natural %s: a photon pass ran on calm water",
                  settings[k]);
        render_destroy(r);
    }
    render *r = with_setting(LAKE, "caustic_tex", "default");
    CHECK_MSG(pass_units(r, "caustic_tex default, lake:") & (1u << 10), "caustic_tex default: no mirror pass");
    render_destroy(r);
    r = with_setting(LAKE, "caustic_tex", "paper");
    CHECK_MSG(!(pass_units(r, "caustic_tex paper (no reflection), lake:") & (1u << 10 | 1u << 11)),
              "caustic_tex paper: a mirror pass ran with SKY_REFLECTION off");
    render_destroy(r);
    for (int k = 0; k < 2; k++) {
        float v;
        r = with_setting(LAKE, "raymarch", settings[k]);
        bool lake = render_read_uniform(r, "RaymarchWater", "uReflectStep", &v, 1) ||
                    render_read_uniform(r, "RaymarchWater", "uReflectHeight", &v, 1);
        render_destroy(r);
        r = with_setting(OCEAN, "raymarch", settings[k]);
        bool sea = render_read_uniform(r, "RaymarchWater", "uReflectStep", &v, 1) ||
                   render_read_uniform(r, "RaymarchWater", "uReflectHeight", &v, 1);
        render_destroy(r);
        fprintf(stderr, "  raymarch %s: reflection march compiled in on the lake %s, on the open sea %s\n", settings[k],
                lake ? "yes" : "no", sea ? "yes" : "no");
        /* (the paper's march reads neither: its steps and 0.8 m cap are Lipp's constants) */
        if (k == 0) CHECK_MSG(lake, "raymarch default: the lake has a box, a post and a tree above its water: no march");
        CHECK_MSG(!sea, "raymarch %s: the open sea has only sky above it, yet the march is compiled in", settings[k]);
    }
}

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    if (!scratch_create("render-setting")) return 1;
    RUN(test_same_pixels_as_bench);
    RUN(test_water_mesh_shows);
    RUN(test_not_applicable_and_unknown);
    RUN(test_passes_per_scene_and_setting);
    scratch_remove();
    gl_ctx_destroy(ctx);
    return check_summary();
}
