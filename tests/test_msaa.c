/* test_msaa: anti-aliasing of the screen passes (render_msaa.h). A tilted
 * square's edges, drawn with 4 samples, have pixels between the square's
 * colour and the background's (multiples of 1/4: the samples covered) and
 * none without; the covered area is the square's (a closed form) either
 * way. The resolve lands in the caller's rectangle only, keeps a float
 * target's precision and values above 1, the reference's subsamples
 * that match a sample count are the nearest square, and the positions the
 * reference takes for MSAA are where the GL samples (the 4x image of the
 * square is its coverage at them, not at the ordered grid). */
#include <GL/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "support.h"
#include "gl_ctx.h"
#include "gl_support.h"
#include "render.h"

#define W 64
#define H 64

static float px[W * H * 4];

/* A white square of side 1 (NDC), turned 30 degrees, on black: a quarter
 * of the 2 x 2 view. */
static render *tilted_square(int samples) {
    scratch_write("flat.vert", flat_vert);
    scratch_write("flat.frag", flat_frag);
    scratch_write("tilt.glib",
                  "##OpenGL GLIB\nOrtho -1 1 -1 1\nBackground 0 0 0\n"
                  "Vertex flat.vert\nFragment flat.frag\n"
                  "Program Flat uColor {1 1 1 1}\n"
                  "PushMatrix\nRotate 30 0 0 1\nScale 0.5\nQuadXY 0 1 1 1\nPopMatrix\n");
    render *r = render_create(&(render_desc){ .samples = samples });
    CHECK_MSG(render_load(r, scratch_path("tilt.glib")), "%s", render_messages(r));
    return r;
}

static void draw(render *r, bool is_float) {
    render_target tg;
    if (!render_target_create(&tg, W, H, is_float)) { fprintf(stderr, "no target\n"); exit(1); }
    render_frame(r, 0, tg.fbo, W, H, NULL);
    CHECK(render_target_read(&tg, px));
    render_target_destroy(&tg);
}

/* Pixels strictly between black and white, and the sum of coverage. */
static int partial_pixels(double *area, bool *quarters) {
    int n = 0;
    *area = 0;
    *quarters = true;
    for (int i = 0; i < W * H; i++) {
        double v = px[i * 4];
        *area += v;
        if (v > 1e-6 && v < 1 - 1e-6) {
            n++;
            if (fabs(v * 4 - round(v * 4)) > 1e-4) *quarters = false;
        }
    }
    return n;
}

static void test_off_has_two_colours(void) {
    render *r = tilted_square(1);
    CHECK_EQ(render_samples(r), 1);
    draw(r, true);
    double area;
    bool quarters;
    CHECK_MSG(partial_pixels(&area, &quarters) == 0, "an edge pixel between the colours without MSAA");
    CHECK_NEAR(area, W * H / 4.0, W * H * 0.01);
    render_destroy(r);
}

static void test_four_samples_blend_the_edges(void) {
    render *r = tilted_square(4);
    if (render_samples(r) < 4) { render_destroy(r); SKIP("this GL has fewer than 4 samples"); }
    draw(r, true);
    double area;
    bool quarters;
    int n = partial_pixels(&area, &quarters);
    /* the perimeter is 4 x 32 pixels long: most pixels it crosses are partly covered */
    CHECK_MSG(n > 64, "%d edge pixels between the colours", n);
    CHECK_MSG(quarters, "coverage is in quarters with 4 samples");
    CHECK_NEAR(area, W * H / 4.0, W * H * 0.005);
    /* and the inside and the outside stay as they were */
    CHECK_NEAR(px[(32 * W + 32) * 4], 1, 1e-6);
    CHECK_NEAR(px[(2 * W + 2) * 4], 0, 1e-6);
    /* an 8-bit target blends too */
    draw(r, false);
    CHECK_GT(partial_pixels(&area, &quarters), 64);
    render_destroy(r);
}

/* Switching live (the panel, bench's buffers) takes effect on the next frame. */
static void test_set_samples_switches(void) {
    render *r = tilted_square(1);
    double area;
    bool quarters;
    render_set_samples(r, 4);
    if (render_samples(r) < 4) { render_destroy(r); SKIP("this GL has fewer than 4 samples"); }
    draw(r, true);
    CHECK_GT(partial_pixels(&area, &quarters), 64);
    render_set_samples(r, 1);
    draw(r, true);
    CHECK_EQ(partial_pixels(&area, &quarters), 0);
    render_destroy(r);
}

/* Float colour through the multisampled target: a 32-bit float's digits
 * and radiance above 1 survive (a 16-bit float would keep 3 digits). */
static void test_float_precision_kept(void) {
    scratch_write("exact.glib",
                  "##OpenGL GLIB\nOrtho -1 1 -1 1\nBackground 0 0 0\n"
                  "Vertex flat.vert\nFragment flat.frag\n"
                  "Program Flat uColor {0.1234567 2.5 0.0001234 1}\nQuadXY 0 1 1 1\n");
    render *r = render_create(&(render_desc){ .samples = 4 });
    CHECK_MSG(render_load(r, scratch_path("exact.glib")), "%s", render_messages(r));
    draw(r, true);
    CHECK_NEAR(px[(10 * W + 10) * 4 + 0], 0.1234567, 1e-7);
    CHECK_NEAR(px[(10 * W + 10) * 4 + 1], 2.5, 1e-7);
    CHECK_NEAR(px[(10 * W + 10) * 4 + 2], 0.0001234, 1e-9);
    render_destroy(r);
}

/* render_frame_at: the scene goes into its rectangle, the rest of the
 * framebuffer is left as it was (the window's panel side). */
static void test_resolve_into_rectangle(void) {
    render *r = tilted_square(4);
    render_target tg;
    CHECK(render_target_create(&tg, W, H, true));
    glBindFramebuffer(GL_FRAMEBUFFER, tg.fbo);
    glClearColor(0, 1, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    render_frame_at(r, 0, tg.fbo, 16, 8, 32, 48, NULL);
    CHECK(render_target_read(&tg, px));
    render_target_destroy(&tg);
    /* row 0 is the top: GL's y = 8..55 are rows 8..55 */
    const float *outside = &px[(30 * W + 4) * 4], *below = &px[(60 * W + 30) * 4];
    CHECK(outside[0] == 0 && outside[1] == 1);
    CHECK(below[0] == 0 && below[1] == 1);
    const float *centre = &px[(32 * W + 32) * 4], *corner = &px[(10 * W + 17) * 4];
    CHECK_NEAR(centre[0], 1, 1e-6);
    CHECK(corner[0] == 0 && corner[1] == 0);   /* the scene's black background */
    render_destroy(r);
}

static void test_reference_spp_matches(void) {
    CHECK_EQ(render_ref_spp(1), 1);
    CHECK_EQ(render_ref_spp(2), 1);
    CHECK_EQ(render_ref_spp(4), 2);
    CHECK_EQ(render_ref_spp(8), 3);
    CHECK_EQ(render_ref_spp(9), 3);
    CHECK_EQ(render_ref_spp(16), 4);
    CHECK_EQ(render_samples_on_this_gl(1), 1);
    /* the default: off where MSAA costs a CPU rasteriser 3-4.5x, 4 on a GPU */
    const char *gl = (const char *)glGetString(GL_RENDERER);
    bool cpu = gl && (strstr(gl, "llvmpipe") || strstr(gl, "softpipe"));
    int def = render_samples_on_this_gl(0);
    CHECK_MSG(cpu ? def == 1 : def == render_samples_on_this_gl(RENDER_MSAA_DEFAULT), "default %d on %s",
              def, gl ? gl : "?");
}

/* The square's coverage of pixel (i, j) (row 0 the top) at subsample
 * positions in the reference's form (x right, y down): the closed form of
 * tilted_square (turned back by 30 degrees, inside |u|, |v| <= 1/2). */
static double coverage(int i, int j, const double (*pos)[2], int n) {
    const double c = cos(30 * M_PI / 180), s = sin(30 * M_PI / 180);
    int in = 0;
    for (int k = 0; k < n; k++) {
        double x = (i + pos[k][0]) / W * 2 - 1, y = 1 - (j + pos[k][1]) / H * 2;
        double u = c * x + s * y, v = -s * x + c * y;
        in += fabs(u) <= 0.5 && fabs(v) <= 0.5;
    }
    return (double)in / n;
}

/* RMSE of the drawn image (px) against the coverage at these positions,
 * over every pixel, and how many pixels differ. */
static double coverage_rmse(const double (*pos)[2], int n, int *differ) {
    double se = 0;
    *differ = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            double e = px[(j * W + i) * 4] - coverage(i, j, pos, n);
            se += e * e;
            *differ += fabs(e) > 1e-4;
        }
    return sqrt(se / (W * H));
}

/* The reference's positions for 4x MSAA are where this GL samples: the
 * tilted square's 4x image is its coverage at those positions, pixel for
 * pixel, and much closer to it than to the ordered 2 x 2 grid's coverage
 * (what the reference took before: the edges disagree). Tolerance: a
 * sample exactly on an edge may go either way under GL's fill rules; at
 * 30 degrees on a 64 x 64 grid that is rare, so at most 1% of the ~180 edge
 * pixels may differ. The positions are inside the pixel, and on llvmpipe
 * they are the standard ones. */
static void test_reference_positions_match(void) {
    double pos[32][2], std[32][2];
    int n = render_ref_positions(4, pos, 32);
    if (n < 4) SKIP("this GL does not say where it samples with 4 samples");
    render *r = tilted_square(n);
    CHECK_EQ(render_samples(r), n);
    draw(r, true);
    render_destroy(r);
    for (int k = 0; k < n; k++)
        CHECK(pos[k][0] >= 0 && pos[k][0] < 1 && pos[k][1] >= 0 && pos[k][1] < 1);
    int d_matched, d_grid, d_mirror;
    double e_matched = coverage_rmse((const double (*)[2])pos, n, &d_matched);
    const double grid[4][2] = { { 0.25, 0.25 }, { 0.75, 0.25 }, { 0.25, 0.75 }, { 0.75, 0.75 } };
    double e_grid = coverage_rmse(grid, 4, &d_grid);
    double mirror[32][2];   /* GL's y up taken as y down: the wrong way round */
    for (int k = 0; k < n; k++) {
        mirror[k][0] = pos[k][0];
        mirror[k][1] = 1 - pos[k][1];
    }
    double e_mirror = coverage_rmse((const double (*)[2])mirror, n, &d_mirror);
    fprintf(stderr, "4x edge RMSE: matched %.5f (%d pixels differ), ordered 2x2 %.5f (%d), mirrored %.5f (%d)\n",
            e_matched, d_matched, e_grid, d_grid, e_mirror, d_mirror);
    CHECK_MSG(d_matched <= 2, "%d pixels differ from the coverage at GL's positions", d_matched);
    CHECK_LT(e_matched, 0.25 * e_grid);
    CHECK_LT(e_matched, 0.25 * e_mirror);
    const char *gl = (const char *)glGetString(GL_RENDERER);
    if (n == 4 && gl && strstr(gl, "llvmpipe")) {
        CHECK_EQ(render_ref_standard_positions(4, std, 32), 4);
        for (int k = 0; k < 4; k++) CHECK(pos[k][0] == std[k][0] && pos[k][1] == std[k][1]);
    }
    CHECK_EQ(render_ref_positions(1, pos, 32), 0);   /* MSAA off: the grid */
    CHECK_EQ(render_ref_standard_positions(3, std, 32), 0);
    CHECK_EQ(render_ref_standard_positions(16, std, 32), 16);
}

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    if (!scratch_create("msaa")) return 1;
    RUN(test_off_has_two_colours);
    RUN(test_four_samples_blend_the_edges);
    RUN(test_set_samples_switches);
    RUN(test_float_precision_kept);
    RUN(test_resolve_into_rectangle);
    RUN(test_reference_spp_matches);
    RUN(test_reference_positions_match);
    gl_ctx_destroy(ctx);
    scratch_remove();
    return check_summary();
}
