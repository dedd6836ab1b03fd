/* test_msaa_match: the reference matched to MSAA, end to end. The lake
 * drawn by a pack with 4x MSAA is compared with CPU references of the same
 * frame subsampled two ways: at the positions the GL samples
 * (refcache_match_msaa, what bench and compare-view use) and on the
 * ordered 2 x 2 grid (what they used before). Off the water (sky, land,
 * objects: one world drawn alike by every pack, so the error there is
 * mostly at edges) the matched reference must be clearly closer, and no
 * further than the no-MSAA frame is from the 1-sample reference: the AA
 * must not cost error off the water once the reference samples alike. */
#include <GL/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "gl_ctx.h"
#include "gl_support.h"
#include "ref_metrics.h"
#include "refcache.h"
#include "render.h"

#define W 320
#define H 180
#define T 2.0

static float px[W * H * 4];

static const char *lake(void) { return TARN_SOURCE_DIR "/scenes/lake.glib"; }

/* The pack's frame of the lake with this many samples into px (linear). */
static bool draw(const char *pack, int samples) {
    render *r = render_create(&(render_desc){ .pack = pack, .samples = samples });
    bool ok = render_load(r, lake());
    CHECK_MSG(ok, "%s", render_messages(r));
    render_target tg;
    if (ok) ok = render_target_create(&tg, W, H, true);
    if (ok) {
        render_frame(r, T, tg.fbo, W, H, NULL);
        ok = render_target_read(&tg, px);
        render_target_destroy(&tg);
    }
    render_destroy(r);
    return ok;
}

/* RMSE of px against a reference off its water (linear RGB). */
static double off_water(const refcache_image *ref) {
    static unsigned char dry[W * H];
    ref_mask_water(ref->mask, (long)W * H, 0, NULL, dry);
    ref_fimage A = { px, W, H, 4 }, B = { ref->color, W, H, 3 };
    ref_metrics_desc d = { .mask = dry };
    ref_image_metrics m;
    char err[256];
    CHECK_MSG(ref_metrics_image(&A, &B, &d, &m, err, sizeof err), "%s", err);
    return m.rmse;
}

static bool reference(const refcache_opts *base, int spp, bool match, refcache_image *out) {
    refcache_opts o = *base;
    o.spp = spp;
    if (match) refcache_match_msaa(&o, 4);
    char err[4096] = "";
    bool ok = refcache_get(NULL, lake(), NULL, W, H, T, NULL, &o, NULL, NULL, out, err, sizeof err);
    CHECK_MSG(ok, "%s", err);
    return ok;
}

static void test_matched_reference_off_water(void) {
    if (render_samples_on_this_gl(4) < 4) SKIP("this GL has fewer than 4 samples");
    /* a coarse caustic grid: off the water the floor's light plays no part */
    const refcache_opts base = { .caustic_res = 48, .photons_per_cell = 9 };
    refcache_image one = { 0 }, grid = { 0 }, matched = { 0 };
    bool ok = reference(&base, 1, false, &one);
    ok = reference(&base, 2, false, &grid) && ok;
    ok = reference(&base, 0, true, &matched) && ok;
    const char *packs[] = { "raymarch", "natural" };
    for (int p = 0; ok && p < 2; p++) {
        if (!draw(packs[p], 1)) break;
        double e_off = off_water(&one);
        if (!draw(packs[p], 4)) break;
        double e_grid = off_water(&grid), e_matched = off_water(&matched);
        fprintf(stderr, "  %-9s off-water RMSE: no AA %.4f; 4x against the 2x2 grid %.4f, against the GL's "
                        "positions %.4f\n", packs[p], e_off, e_grid, e_matched);
        /* Measured at 320x180 on llvmpipe (raymarch, natural): no AA
         * 0.0083, 0.0083; 4x against the grid 0.0163, 0.0167; against the
         * GL's positions 0.0057, 0.0065 (at 480x270: 0.0076, 0.0131,
         * 0.0051). The mismatched edges double the error; matched, it
         * drops below the no-AA figure (the edges of sky, land and objects
         * are anti-aliased alike, where without AA they alias apart).
         * Bounds: 0.6 of the grid's (measured 0.35-0.39) and the no-AA
         * figure (measured 0.69-0.78 of it), margins for another GL's edge
         * rules. Not at 160x90: there the no-AA error is 0.0009 (the
         * row of pixels along the far horizon, most of it at 320x180,
         * happens to agree) and the matched 4x error, 0.0070, stays above
         * it (the grid's 0.0105). */
        CHECK_MSG(e_matched < 0.6 * e_grid, "%s: matched %.4f not well below the grid's %.4f", packs[p],
                  e_matched, e_grid);
        CHECK_MSG(e_matched < e_off, "%s: matched %.4f above the no-AA %.4f", packs[p], e_matched, e_off);
    }
    refcache_free(&one);
    refcache_free(&grid);
    refcache_free(&matched);
}

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    RUN(test_matched_reference_off_water);
    gl_ctx_destroy(ctx);
    return check_summary();
}
