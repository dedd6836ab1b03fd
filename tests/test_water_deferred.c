/* Deferred water (gfx/water_deferred.h) on llvmpipe: the screen's water
 * drawn as a G-buffer of the grid and then the program's fragment shader
 * once a pixel gives the grid's own picture. Inputs are interpolated at
 * the same pixel centres either way, so a shader without derivatives gives
 * the same bits (a float, a flat int by its bits, gl_FragCoord.z and
 * gl_FrontFacing stored and read back); the packs' shaders, whose
 * derivatives differ at the water's edge, give the grid's picture but for
 * a few pixels. MSAA frames, shaders it cannot split and the spectrum
 * ocean keep the grid. */
#include <GL/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "support.h"
#include "gl_ctx.h"
#include "render.h"

/* A world 4 m a side, water at 0.5 with a wave (the grid's triangles not
 * coplanar), seen at a slant over its far edge: water, and beyond it
 * nothing (the stencil keeps the background's pixels). */
static const char *world =
    "##OpenGL GLIB\nPerspective 50\nLookAt 0 1.5 3.5  0 0.5 -3  0 1 0\n"
    "Terrain flat 2 1\nWater 0.5\nWaterMesh 16\nWaveGerstner 20 1.5 0.05 0 0\n";

typedef struct frame {
    float *px;
    long deferred_draws;
    char why[256];      /* render_deferred_water_why after the frame ("": none) */
} frame;

/* path drawn once into a w x h float target at time t, deferred or not. */
static frame draw(const char *path, const char *pack, int w, int h, double t, bool deferred, int samples) {
    render *r = render_create(&(render_desc){ .samples = samples, .pack = pack });
    CHECK_MSG(render_load(r, path), "%s", render_messages(r));
    render_set_deferred_water(r, deferred);
    render_target tg;
    CHECK(render_target_create(&tg, w, h, true));
    render_frame(r, t, tg.fbo, w, h, NULL);
    frame f = { malloc((size_t)w * h * 4 * sizeof(float)), render_deferred_water_draws(r) };
    CHECK(render_target_read(&tg, f.px));
    render_target_destroy(&tg);
    GLenum e = glGetError();
    CHECK_MSG(e == GL_NO_ERROR, "GL error 0x%x", e);
    const char *why = render_deferred_water_why(r);
    snprintf(f.why, sizeof f.why, "%s", why ? why : "");
    if (deferred && why) fprintf(stderr, "  %s: not deferred: %s\n", path, why);
    render_destroy(r);
    return f;
}

/* A shader without derivatives: every input kind the G-buffer stores
 * (floats, a flat int array by its bits, gl_FragCoord's z and w,
 * gl_FrontFacing) reaches the shade pass as the grid's draw gave it. */
static void test_inputs_arrive_bit_for_bit(void) {
    scratch_write("in.vert", "#version 330 compatibility\n"
                             "out vec3 vW;\nflat out int vI[2];\nout float vS;\n"
                             "#include \"contract.glsl\"\n#include \"waves.glsl\"\n"
                             "void main() { vec3 p, n; wavesEval(gl_Vertex.xz, uTime, p, n);\n"
                             "  vW = p; vI[0] = gl_VertexID; vI[1] = -gl_VertexID; vS = p.y * 3.0;\n"
                             "  gl_Position = gl_ModelViewProjectionMatrix * vec4(p, 1.0); }\n");
    scratch_write("in.frag", "#version 330 compatibility\n"
                             "in vec3 vW;   // a comment\nflat in int vI[2];\n"
                             "in float\n  vS;\nout vec4 c;\n"
                             "void main() {\n"
                             "  c = vec4(fract(vW.x * 3.0) + float(vI[0] & 7) * 0.1, vS + float(-vI[1] % 5) * 0.01,\n"
                             "           gl_FragCoord.z + gl_FragCoord.w, gl_FrontFacing ? 1.0 : 0.25);\n"
                             "}\n");
    char text[1024];
    snprintf(text, sizeof text, "%sBackground 0 0 0 0\nVertex in.vert\nFragment in.frag\nProgram P\nWaterSurface\n",
             world);
    scratch_write("in.glib", text);
    int w = 96, h = 54;
    frame grid = draw(scratch_path("in.glib"), NULL, w, h, 0.7, false, 1);
    frame dfr = draw(scratch_path("in.glib"), NULL, w, h, 0.7, true, 1);
    CHECK_EQ(grid.deferred_draws, 0L);
    CHECK_EQ(dfr.deferred_draws, 1L);
    int water = 0, differ = 0;
    for (int i = 0; i < w * h; i++) {
        if (grid.px[i * 4 + 3] > 0) water++;
        if (memcmp(grid.px + i * 4, dfr.px + i * 4, 4 * sizeof(float)) != 0) differ++;
    }
    fprintf(stderr, "  %d water pixels, %d differ\n", water, differ);
    CHECK_GT(water, w * h / 4);
    CHECK_LT(water, w * h * 9 / 10);
    CHECK_EQ(differ, 0);
    free(grid.px);
    free(dfr.px);
}

/* Each pack on the lake, single-sample: the deferred picture is the
 * grid's but where derivatives differ (the water's edge; caustic_tex's
 * ripple footprint across triangles): almost every pixel within 1/255,
 * and the whole frame within a few thousandths RMSE. */
static void test_packs_draw_the_grids_picture(void) {
    static const char *packs[] = { "basic", "raymarch", "natural", "caustic_tex" };
    int w = 192, h = 108;
    for (size_t k = 0; k < sizeof packs / sizeof packs[0]; k++) {
        frame grid = draw(TARN_SOURCE_DIR "/scenes/lake.glib", packs[k], w, h, 2.0, false, 1);
        frame dfr = draw(TARN_SOURCE_DIR "/scenes/lake.glib", packs[k], w, h, 2.0, true, 1);
        CHECK_MSG(dfr.deferred_draws >= 1, "%s", packs[k]);
        double se = 0;
        int off = 0;
        for (int i = 0; i < w * h * 4; i++) {
            if (i % 4 == 3) continue;
            double d = (double)dfr.px[i] - grid.px[i];
            se += d * d;
            if (fabs(d) > 1.0 / 255) off++;
        }
        double rmse = sqrt(se / (w * h * 3));
        fprintf(stderr, "  %-12s RMSE %.3g against the grid, %d of %d channels off by more than 1/255\n", packs[k],
                rmse, off, w * h * 3);
        CHECK_LT(rmse, 0.005);
        CHECK_LT(off, w * h * 3 / 50);
        free(grid.px);
        free(dfr.px);
    }
}

/* A frame is the same whatever frames the render drew before it: the
 * G-buffer's texels beside the water are an earlier draw's, read as
 * cleared ones (glsl_deferred.stamped: caustic_tex's shader has a spare
 * slot, and takes derivatives there: its ripple footprint). */
static void test_no_history(void) {
    int w = 160, h = 90;
    render *r = render_create(&(render_desc){ .samples = 1, .pack = "caustic_tex" });
    CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/scenes/lake.glib"), "%s", render_messages(r));
    render_target tg;
    CHECK(render_target_create(&tg, w, h, true));
    render_view v = render_default_view(r);
    render_frame(r, 2.0, tg.fbo, w, h, NULL);   /* the water elsewhere on the screen */
    v.eye[0] -= 2.0f;
    v.eye[1] += 1.0f;
    render_frame(r, 2.5, tg.fbo, w, h, &v);
    float *after = malloc((size_t)w * h * 4 * sizeof(float));
    CHECK(render_target_read(&tg, after));
    CHECK_EQ(render_deferred_water_draws(r), 2L);
    render_target_destroy(&tg);
    render_destroy(r);
    r = render_create(&(render_desc){ .samples = 1, .pack = "caustic_tex" });
    CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/scenes/lake.glib"), "%s", render_messages(r));
    CHECK(render_target_create(&tg, w, h, true));
    render_frame(r, 2.5, tg.fbo, w, h, &v);
    float *fresh = malloc((size_t)w * h * 4 * sizeof(float));
    CHECK(render_target_read(&tg, fresh));
    int differ = 0;
    for (int i = 0; i < w * h * 4; i++) differ += after[i] != fresh[i];
    CHECK_EQ(differ, 0);
    render_target_destroy(&tg);
    render_destroy(r);
    free(after);
    free(fresh);
}

/* A multisampled frame keeps the grid (one shading a sample's pixel
 * would lose the water's anti-aliased edge). */
static void test_msaa_keeps_the_grid(void) {
    char text[1024];
    snprintf(text, sizeof text, "%sVertex in.vert\nFragment in.frag\nProgram P\nWaterSurface\n", world);
    scratch_write("ms.glib", text);
    frame f = draw(scratch_path("ms.glib"), NULL, 64, 36, 0.7, true, 4);
    CHECK_EQ(f.deferred_draws, 0L);
    CHECK_STR_CONTAINS(f.why, "multisampled");   /* --passes says why */
    free(f.px);
}

/* A shader reading a compatibility built-in input (gl_Color) cannot be
 * split: its water is drawn as a grid, and says why. */
static void test_unsplittable_shader_keeps_the_grid(void) {
    scratch_write("col.vert", "#version 330 compatibility\n"
                              "void main() { gl_FrontColor = vec4(0.2, 0.6, 0.9, 1.0);\n"
                              "  gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; }\n");
    scratch_write("col.frag", "#version 330 compatibility\nout vec4 c;\nvoid main() { c = gl_Color; }\n");
    char text[1024];
    snprintf(text, sizeof text, "%sBackground 0 0 0 0\nVertex col.vert\nFragment col.frag\nProgram C\nWaterSurface\n",
             world);
    scratch_write("col.glib", text);
    render *r = render_create(&(render_desc){ .samples = 1 });
    CHECK_MSG(render_load(r, scratch_path("col.glib")), "%s", render_messages(r));
    render_target tg;
    CHECK(render_target_create(&tg, 48, 27, true));
    render_frame(r, 0, tg.fbo, 48, 27, NULL);
    float px[48 * 27 * 4];
    CHECK(render_target_read(&tg, px));
    CHECK_EQ(render_deferred_water_draws(r), 0L);
    const char *why = render_deferred_water_why(r);
    CHECK(why != NULL);
    if (why) CHECK_STR_CONTAINS(why, "gl_Color");
    int blue = 0;
    for (int i = 0; i < 48 * 27; i++) blue += fabsf(px[i * 4 + 2] - 0.9f) < 1e-3f;
    CHECK_GT(blue, 48 * 27 / 4);   /* the water drawn all the same */
    render_target_destroy(&tg);
    render_destroy(r);
}

/* The spectrum ocean keeps the grid (its filtered normals take the grid's
 * own derivatives), and says why. */
static void test_ocean_keeps_the_grid(void) {
    frame f = draw(TARN_SOURCE_DIR "/scenes/ocean.glib", "raymarch", 64, 36, 1.0, true, 1);
    CHECK_EQ(f.deferred_draws, 0L);
    CHECK_STR_CONTAINS(f.why, "ocean");
    free(f.px);
}

int main(void) {
    char err[512];
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    if (!ctx) { fprintf(stderr, "skip: %s\n", err); return 77; }
    if (!scratch_create("water_deferred")) return 1;
    RUN(test_inputs_arrive_bit_for_bit);
    RUN(test_packs_draw_the_grids_picture);
    RUN(test_no_history);
    RUN(test_msaa_keeps_the_grid);
    RUN(test_unsplittable_shader_keeps_the_grid);
    RUN(test_ocean_keeps_the_grid);
    gl_ctx_destroy(ctx);
    scratch_remove();
    return check_summary();
}
