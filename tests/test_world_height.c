/* test_world_height: the world's wet and dry land from the height map of
 * the moving surface (render_set_world_height_map, on by default) against
 * the same frame with the surface solved for at every pixel (off), which
 * test_world_gl and the hard cases check against the CPU reference. At
 * moving times, on the lake and on a sloping shore (where the waterline
 * crosses the whole view, past the world square), the two frames agree
 * but for a few pixels at the waterline. */
#include <GL/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "gl_ctx.h"
#include "gl_support.h"
#include "render.h"

#define W 240
#define H 135

static void frame(render *r, double t, float *px) {
    render_target tg;
    if (!render_target_create(&tg, W, H, true)) { fprintf(stderr, "no target\n"); exit(1); }
    render_frame(r, t, tg.fbo, W, H, NULL);
    CHECK(render_target_read(&tg, px));
    render_target_destroy(&tg);
    GLenum e = glGetError();
    CHECK_MSG(e == GL_NO_ERROR, "GL error 0x%x", e);
}

/* Tolerances: a pixel whose wet/dry decision flips changes by up to the
 * sun's share of its radiance (about 0.5); the map is off by about
 * A k^2 h^2 / 8 (lake: under 2 mm), so only pixels within that of the
 * waterline may flip: under 0.5% of the frame, and an RMSE under 0.01. */
static void check_scene(const char *scene, const char *pack) {
    render *r = render_create(&(render_desc){ .pack = pack });
    CHECK_MSG(render_load(r, scene), "%s", render_messages(r));
    float *on = malloc(sizeof(float) * W * H * 4), *off = malloc(sizeof(float) * W * H * 4);
    const double times[] = { 1.3, 4.7 };
    for (int k = 0; k < 2; k++) {
        CHECK(render_set_world_height_map(r, true));
        frame(r, times[k], on);
        CHECK(render_set_world_height_map(r, false));
        frame(r, times[k], off);
        double sum = 0;
        int flipped = 0;
        for (int i = 0; i < W * H; i++) {
            double d = 0;
            for (int c = 0; c < 3; c++) {
                double e = on[4 * i + c] - off[4 * i + c];
                sum += e * e;
                d = fmax(d, fabs(e));
            }
            flipped += d > 0.02;
        }
        double rmse = sqrt(sum / (3.0 * W * H));
        printf("%s, %s, t = %.1f: RMSE %.5f, %d pixels (%.2f%%) differ by more than 0.02\n", scene, pack,
               times[k], rmse, flipped, 100.0 * flipped / (W * H));
        CHECK_MSG(rmse < 0.01, "%s %s t=%g: the height map's frame is %.4f RMSE from the exact one", scene, pack,
                  times[k], rmse);
        CHECK_MSG(flipped < W * H / 200, "%s %s t=%g: %d pixels differ", scene, pack, times[k], flipped);
    }
    free(on);
    free(off);
    render_destroy(r);
}

static void test_lake(void) {
    check_scene(TARN_SOURCE_DIR "/scenes/lake.glib", "basic");
    check_scene(TARN_SOURCE_DIR "/scenes/lake.glib", "natural");
}

static void test_shore(void) { check_scene(TARN_SOURCE_DIR "/scenes/hard/shore.glib", "basic"); }

/* The map drawn only over the cells a wet test reads
 * (render_set_world_height_cells, world_height_tiles.h) against the whole
 * map: the texels those tests read are drawn by the same program in both,
 * so every pixel is the same, at full detail and at a window's reduced one
 * (a coarser map and coarser land meshes). */
static void check_cells(const char *scene, const char *pack) {
    render *r = render_create(&(render_desc){ .pack = pack });
    CHECK_MSG(render_load(r, scene), "%s", render_messages(r));
    float *cells = malloc(sizeof(float) * W * H * 4), *whole = malloc(sizeof(float) * W * H * 4);
    const double times[] = { 1.3, 4.7 }, details[] = { 1.0, 0.3 };
    for (int k = 0; k < 4; k++) {
        render_set_detail(r, details[k / 2]);
        render_set_world_height_cells(r, true);
        frame(r, times[k % 2], cells);
        render_set_world_height_cells(r, false);
        frame(r, times[k % 2], whole);
        int differ = 0;
        for (int i = 0; i < W * H * 4; i++) differ += cells[i] != whole[i];
        CHECK_MSG(differ == 0, "%s %s t=%g detail %g: %d values differ from the whole map's frame", scene, pack,
                  times[k % 2], details[k / 2], differ);
    }
    render_set_world_height_cells(r, true);
    free(cells);
    free(whole);
    render_destroy(r);
}

static void test_cells_match_the_whole_map(void) {
    check_cells(TARN_SOURCE_DIR "/scenes/lake.glib", "basic");
    check_cells(TARN_SOURCE_DIR "/scenes/showcase.glib", "basic");
    check_cells(TARN_SOURCE_DIR "/scenes/hard/shore.glib", "basic");
    check_cells(TARN_SOURCE_DIR "/scenes/hard/crate.glib", "basic");
    check_cells(TARN_SOURCE_DIR "/scenes/harbour.glib", "natural");
}

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    RUN(test_lake);
    RUN(test_shore);
    RUN(test_cells_match_the_whole_map);
    gl_ctx_destroy(ctx);
    return check_summary();
}
