/* The world's scene defines (render_world.h, world_set_defines): every
 * program tarn builds for a world learns the scene's terrain model
 * (WORLD_TERRAIN_KIND) and whether it has ground detail, a sun disc and
 * haze, so the shaders compile out what the scene lacks (llvmpipe runs
 * both sides of an `if`, even on a uniform). Checked: the defines match
 * the description, and the world program built with them no longer reads
 * the uniforms they replace (glGetUniformLocation -1: compiled out) while
 * it reads those the scene has. That the pictures stay the same is checked
 * where they are compared with the reference (test_world_gl,
 * test_hard_cases) and was checked byte for byte on every scene and pack
 * (docs/benchmark.md, "The scene's constants as defines"). */
#include <GL/gl.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "gl_support.h"
#include "render_world.h"
#include "support.h"

static const char *define_value(const prog *p, const char *name) {
    for (int k = 0; k < PROG_FIXED_MAX; k++)
        if (strcmp(p->fixed[k].name, name) == 0) return p->fixed[k].value;
    return NULL;
}

static void check_scene(ref_terrain_kind kind, double detail, double disc, double haze) {
    ref_world_desc desc;
    memset(&desc, 0, sizeof desc);
    desc.terrain = kind;
    desc.half_size = 12;
    desc.depth = 3;
    desc.ground_detail = detail;
    desc.sun_disc_deg = disc;
    desc.haze_distance = haze;
    desc.waves.gerstner_count = 1;
    desc.waves.gerstner[0] = (ref_wave_desc){ .wavelength = 4, .amplitude = 0.05 };
    gpu_world gw;
    CHECK(gl_test_world_build(&gw, &desc));
    prog p;
    memset(&p, 0, sizeof p);
    world_set_defines(&gw, &p);
    char kind_str[8];
    snprintf(kind_str, sizeof kind_str, "%d", (int)kind);
    CHECK(define_value(&p, "WORLD_DEFINES") != NULL);
    CHECK(define_value(&p, "WAVES_HAS_GERSTNER") != NULL);
    const char *k = define_value(&p, "WORLD_TERRAIN_KIND");
    CHECK_MSG(k && strcmp(k, kind_str) == 0, "WORLD_TERRAIN_KIND %s, the scene's %s", k ? k : "(none)", kind_str);
    CHECK_EQ(define_value(&p, "WORLD_GROUND_DETAIL") != NULL, detail > 0);
    CHECK_EQ(define_value(&p, "WORLD_SUN_DISC") != NULL, disc > 0);
    CHECK_EQ(define_value(&p, "WORLD_HAZE") != NULL, haze > 0);
    /* the world program (world.frag, built with the same defines): the
     * terrain's kind is a constant, and what the scene lacks is gone */
    bool reads[4] = { false, false, false, false };
    const char *names[4] = { "uTerrainKind", "uGroundDetail", "uSunDisc", "uHazeDistance" };
    for (int m = 0; m < WORLD_MODES; m++) {   /* the sky is one mode's */
        CHECK_NE(gw.progs[m].gl, 0u);
        for (int u = 0; u < 4; u++) reads[u] = reads[u] || glGetUniformLocation(gw.progs[m].gl, names[u]) >= 0;
    }
    CHECK(!reads[0]);
    CHECK_EQ(reads[1], detail > 0);
    CHECK_EQ(reads[2], disc > 0);
    CHECK_EQ(reads[3], haze > 0);
    fprintf(stderr, "  terrain %d, detail %g, disc %g, haze %g: defines and the world program agree\n", (int)kind,
            detail, disc, haze);
    world_free(&gw);
}

static void test_defines_follow_the_scene(void) {
    check_scene(REF_TERRAIN_LAKE, 0, 0, 0);
    check_scene(REF_TERRAIN_LAKE, 0.6, 2, 40);
    check_scene(REF_TERRAIN_POOL, 0.8, 0, 0);
    check_scene(REF_TERRAIN_FLAT, 0, 0.5, 0);
}

/* Without a world nothing is defined (a glman scene's programs). */
static void test_no_world_no_defines(void) {
    gpu_world gw;
    memset(&gw, 0, sizeof gw);
    prog p;
    memset(&p, 0, sizeof p);
    world_set_defines(&gw, &p);
    for (int k = 0; k < PROG_FIXED_MAX; k++) CHECK_EQ(p.fixed[k].name[0], '\0');
}

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    RUN(test_defines_follow_the_scene);
    RUN(test_no_world_no_defines);
    gl_ctx_destroy(ctx);
    return check_summary();
}
