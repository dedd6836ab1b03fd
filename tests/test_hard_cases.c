/* test_hard_cases: every hard case (the scenes in scenes/hard) through every pack
 * there is (packs/NAME/pack.glib, found at run time), and every slider of
 * every pack at each end of its range:
 *
 *   - no NaN or Inf in any pixel of the image (a float target), nor in any
 *     buffer the pack shows (bench.txt `buffer` lines, TARN_OUTPUT) where
 *     the reference sees water; no GL error;
 *   - the colour error over the reference's water pixels against the CPU
 *     reference of the same frame, drawn with the pack's `default` row of
 *     bench.txt as the bench draws it (the ocean's foam off) (RMSE, linear RGB; the whole frame is
 *     printed beside it) within the pack's bound for the case: its
 *     packs/NAME/bounds.txt line for the case, else its `*` line, else the
 *     built-in table (packset_bound_resolve, viewer/scene/packset.c). A bound of
 *     `none` says why the pack cannot hold one there; the test prints the
 *     reason and checks the rest;
 *   - a march that ran out of budget (the refraction-hit buffer's alpha
 *     BENCH_MARCH_CAPPED) on at most 1% of the water pixels.
 *
 * Images are 96x54, the reference at the same size with a coarse caustic
 * grid (48 cells, 9 photons a cell): the bounds are about the pack, not
 * the photon noise. References are cached in ./hard-ref (keyed by the
 * world, camera, size and time, so an edited scene is rendered again).
 * See docs/benchmark.md, "Hard cases". The scenes are every .glib file in
 * scenes/hard. */
#include <GL/gl.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "gl_ctx.h"
#include "packset.h"
#include "ref_metrics.h"
#include "refcache.h"
#include "render.h"
#include "render_setting.h"
#include "ref_buffers.h"
#include "bench.h"

#define W 96
#define H 54
#define T 1.0
#define MAX_CASES 64

typedef struct hard_case { char name[128], path[1024]; } hard_case;

static hard_case cases[MAX_CASES];
static int ncases;
static packset_name packs[PACKSET_MAX];
static int npacks;
static refcache_image refs[MAX_CASES];
static bool have_ref[MAX_CASES];
static float px[W * H * 4];
static long targets_checked;   /* render targets read back by check_targets */
static long capped_checked;    /* refraction-hit buffers checked by check_capped_share */

static double wall_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_case(const void *a, const void *b) {
    return strcmp(((const hard_case *)a)->name, ((const hard_case *)b)->name);
}

static void find_cases(void) {
    const char *dir = TARN_SOURCE_DIR "/scenes/hard";
    DIR *d = opendir(dir);
    if (!d) return;
    struct dirent *e;
    while ((e = readdir(d)) && ncases < MAX_CASES) {
        size_t n = strlen(e->d_name);
        if (n < 6 || strcmp(e->d_name + n - 5, ".glib") != 0 || n - 5 >= sizeof cases[0].name) continue;
        snprintf(cases[ncases].name, sizeof cases[ncases].name, "%.*s", (int)(n - 5), e->d_name);
        snprintf(cases[ncases].path, sizeof cases[ncases].path, "%s/%s", dir, e->d_name);
        ncases++;
    }
    closedir(d);
    qsort(cases, (size_t)ncases, sizeof *cases, cmp_case);
}

static long nonfinite(const float *p, long n) {
    long bad = 0;
    for (long i = 0; i < n; i++)
        for (int c = 0; c < 4; c++)
            if (!isfinite(p[i * 4 + c])) { bad++; break; }
    return bad;
}

/* Draws one frame into the target; false on a GL error (message printed). */
static bool draw(render *r, const render_target *tg, const char *what) {
    while (glGetError() != GL_NO_ERROR) {}
    render_frame(r, T, tg->fbo, W, H, NULL);
    bool ok = render_target_read(tg, px);
    GLenum e = glGetError();
    CHECK_MSG(ok && e == GL_NO_ERROR, "%s: GL error 0x%x", what, e);
    return ok && e == GL_NO_ERROR;
}

/* Every float and depth render target the scene's passes wrote (the
 * packs' intermediate textures: refraction, reflection, world Y, photons,
 * caustics): no NaN or Inf texel. */
static void check_targets(render *r, const char *what) {
    render_target_info t[32];
    int n = render_targets(r, t, 32);
    for (int k = 0; k < n && k < 32; k++) {
        if (!t[k].is_float && !t[k].is_depth) continue;   /* 8-bit targets hold no NaN */
        int ch = t[k].is_depth ? 1 : 4;
        long count = (long)t[k].w * t[k].h;
        float *texels = malloc((size_t)count * ch * sizeof *texels);
        if (!texels) continue;
        glBindTexture(GL_TEXTURE_2D, t[k].tex);
        glGetTexImage(GL_TEXTURE_2D, 0, t[k].is_depth ? GL_DEPTH_COMPONENT : GL_RGBA, GL_FLOAT, texels);
        glBindTexture(GL_TEXTURE_2D, 0);
        long bad = 0;
        for (long i = 0; i < count * ch; i++) bad += !isfinite(texels[i]);
        CHECK_MSG(bad == 0, "%s: target at unit %d (%s:%d, %dx%d): %ld values are NaN or Inf", what, t[k].unit,
                  t[k].file, t[k].line, t[k].w, t[k].h, bad);
        targets_checked++;
        free(texels);
    }
}

static void test_references(void) {
    CHECK_MSG(ncases >= 13, "%d hard cases in scenes/hard", ncases);
    /* subsampled where the packs' MSAA samples (their default), as tarn
     * bench does: edges are compared with edges */
    refcache_opts o = { .caustic_res = 48, .photons_per_cell = 9 };
    refcache_match_msaa(&o, render_samples_on_this_gl(0));
    for (int c = 0; c < ncases; c++) {
        char err[4096] = "";
        have_ref[c] = refcache_get("hard-ref", cases[c].path, NULL, W, H, T, NULL, &o, NULL, NULL, &refs[c],
                                   err, sizeof err);
        CHECK_MSG(have_ref[c], "%s: %s", cases[c].name, err);
        fprintf(stderr, "  reference %-14s %s\n", cases[c].name, have_ref[c] && refs[c].from_cache ? "(cached)" : "");
    }
}

static void test_every_case_through_every_pack(void) {
    if (!npacks) SKIP("no packs under %s/packs", TARN_SOURCE_DIR);
    render_target tg;
    CHECK(render_target_create(&tg, W, H, true));
    fprintf(stderr, "  %-12s %-14s %9s %9s %9s  %s\n", "pack", "case", "water", "frame", "bound", "");
    for (int p = 0; p < npacks; p++) {
        packset_bounds pb;
        char err[2048] = "";
        CHECK_MSG(packset_bounds_load(TARN_SOURCE_DIR, packs[p], &pb, err, sizeof err), "%s", err);
        render_desc rd = { .pack = packs[p] };
        render *r = render_create(&rd);
        for (int c = 0; c < ncases; c++) {
            char what[256];
            snprintf(what, sizeof what, "%.120s with %.60s", cases[c].name, packs[p]);
            bool loaded = render_load(r, cases[c].path);
            CHECK_MSG(loaded, "%s: %s", what, render_messages(r));
            if (strcmp(cases[c].name, "steep_over") == 0)
                CHECK_STR_CONTAINS(render_messages(r), "is above 1, where the surface folds into loops; using 1");
            /* the pack's `default` row, as the bench measures it: the
             * ocean's folding foam off (the reference has no foam) */
            char smsg[1024];
            if (loaded) CHECK_MSG(render_setting_apply_named(r, TARN_SOURCE_DIR, "default", smsg, sizeof smsg),
                                  "%s: %s", what, smsg);
            if (!loaded || !draw(r, &tg, what)) continue;
            long bad = nonfinite(px, (long)W * H);
            CHECK_MSG(bad == 0, "%s: %ld pixels are NaN or Inf", what, bad);
            check_targets(r, what);
            if (!have_ref[c]) continue;
            ref_fimage A = { px, W, H, 4 }, B = { refs[c].color, W, H, 3 };
            ref_image_metrics whole, m;
            char merr[256];
            CHECK(ref_metrics_image(&A, &B, NULL, &whole, merr, sizeof merr));
            /* the bound is on the water: the pack's technique, where the
             * reference sees water (the rest is one world, test_world_gl) */
            unsigned char water[W * H];
            ref_mask_water(refs[c].mask, (long)W * H, 1, NULL, water);
            ref_metrics_desc wd = { .mask = water };
            CHECK(ref_metrics_image(&A, &B, &wd, &m, merr, sizeof merr));
            CHECK_MSG(m.count.compared > 0, "%s: the reference sees no water", what);
            const char *from = NULL;
            const packset_bound *pbd = packset_bound_resolve(&pb, cases[c].name, &from);
            double bound = pbd ? pbd->max_rmse : -1;
            const char *why = pbd ? pbd->why : "no bound given";
            if (bound < 0) {
                fprintf(stderr, "  %-12s %-14s %9.4f %9.4f %9s  no bound (%s): %s\n", packs[p], cases[c].name, m.rmse,
                        whole.rmse, "none", from, why && why[0] ? why : "(no reason given)");
                CHECK_MSG(why && why[0], "%s: a bound of 'none' must say why (%s)", what, from);
                continue;
            }
            fprintf(stderr, "  %-12s %-14s %9.4f %9.4f %9.4f  %s\n", packs[p], cases[c].name, m.rmse, whole.rmse,
                    bound, m.rmse <= bound ? "" : "OVER");
            CHECK_MSG(m.rmse <= bound, "%s: water RMSE %.4f is over the bound %.4f (%s)", what, m.rmse, bound, from);
        }
        render_destroy(r);
        packset_bounds_free(&pb);
    }
    fprintf(stderr, "  %ld float and depth render targets read back\n", targets_checked);
    CHECK_GT(targets_checked, 0);   /* the packs have targets: the check ran */
    render_target_destroy(&tg);
}

/* A truncated march is never silent, and never common: in the
 * refraction-hit buffer a pack writes alpha BENCH_MARCH_CAPPED where its
 * march ran out of budget before it met the ground (raymarch's MARCH_CAP).
 * On every hard case at most MAX_CAPPED_SHARE of the water pixels may be
 * so: the march's lengths follow the scene's scale (uWorldScale), so a
 * large or small lake must not exhaust it. Issue #13's figure: 1%. */
#define MAX_CAPPED_SHARE 0.01
static void check_capped_share(const float *rgba, const float *mask, const char *what) {
    long water = 0, capped = 0;
    for (long i = 0; i < (long)W * H; i++)
        if (mask[i] == 1 /* REF_MASK_WATER */) {
            water++;
            capped += rgba[i * 4 + 3] == BENCH_MARCH_CAPPED;
        }
    double share = water ? (double)capped / (double)water : 0.0;
    if (capped) fprintf(stderr, "  %s: march capped on %.2f%% of the water\n", what, 100.0 * share);
    CHECK_MSG(share <= MAX_CAPPED_SHARE, "%s: the march ran out on %ld of %ld water pixels (%.2f%%, at most %.0f%%)",
              what, capped, water, 100.0 * share, 100.0 * MAX_CAPPED_SHARE);
    capped_checked++;
}

/* The per-pixel buffers a pack shows (its bench.txt `buffer` lines, or
 * `Define TARN_OUTPUT`): finite on every hard case, over the pixels where
 * the reference sees water. */
static void test_buffers_are_finite(void) {
    if (!npacks) SKIP("no packs");
    render_target tg;
    CHECK(render_target_create(&tg, W, H, true));
    int shown = 0;
    for (int p = 0; p < npacks; p++) {
        packset_bench pb;
        char err[2048] = "";
        packset_bench_load(TARN_SOURCE_DIR, packs[p], &pb, err, sizeof err);
        render_desc rd = { .pack = packs[p] };
        render *r = render_create(&rd);
        for (int mode = 1; mode <= 4; mode++) {
            const packset_buffer *spec = NULL;
            for (int i = 0; i < pb.nbuffers; i++)
                if (strcmp(pb.buffers[i].name, ref_buffer_for_output(mode)->name) == 0) spec = &pb.buffers[i];
            for (int c = 0; c < ncases; c++) {
                if (!render_load(r, cases[c].path)) continue;   /* reported by the case test */
                int nsets;
                unif_set *sets = render_uniforms(r, &nsets);
                bool any = false;
                if (spec) {
                    bool changed;
                    any = packset_apply(sets, nsets, &spec->how, &changed, err, sizeof err);
                    CHECK_MSG(any, "%s: buffer %s: %s", pb.path, spec->name, err);
                } else {
                    for (int i = 0; i < nsets; i++) {
                        unif_entry *e = unif_find(&sets[i], "TARN_OUTPUT");
                        if (e && e->is_define && e->min <= mode && e->max >= mode) {
                            e->value[0] = (float)mode;
                            any = true;
                        }
                    }
                }
                if (!any) break;
                render_rebuild_programs(r);
                char what[256];
                snprintf(what, sizeof what, "%.60s buffer %s on %.100s", packs[p], ref_buffer_for_output(mode)->name,
                         cases[c].name);
                if (!draw(r, &tg, what) || !have_ref[c]) continue;
                long bad = 0;
                for (long i = 0; i < (long)W * H; i++)
                    if (refs[c].mask[i] == 1 /* REF_MASK_WATER */)
                        for (int k = 0; k < 3; k++)
                            if (!isfinite(px[i * 4 + k])) { bad++; break; }
                CHECK_MSG(bad == 0, "%s: %ld water pixels are NaN or Inf", what, bad);
                if (mode == REF_OUTPUT_REFRACT_HIT) check_capped_share(px, refs[c].mask, what);
                shown++;
                for (int i = 0; i < nsets; i++) unif_reset_all(&sets[i]);
            }
        }
        render_destroy(r);
        packset_bench_free(&pb);
    }
    fprintf(stderr, "  %d buffer images checked, %ld of them for a capped march\n", shown, capped_checked);
    CHECK_GE(capped_checked, ncases);   /* raymarch shows its refraction hits: the check ran */
    render_target_destroy(&tg);
}

/* Sets an entry to one end of its range (a colour: every component 0 or 1;
 * a checkbox: 0 or 1). False for entries without a range. */
static bool set_end(unif_entry *e, bool high) {
    switch (e->widget) {
    case UNIF_WIDGET_SLIDER:
        e->value[0] = high ? e->max : e->min;
        return true;
    case UNIF_WIDGET_CHECKBOX:
        e->value[0] = high ? 1.0f : 0.0f;
        return true;
    case UNIF_WIDGET_COLOR:
        for (int k = 0; k < e->ncomp; k++) e->value[k] = high ? 1.0f : 0.0f;
        return true;
    case UNIF_WIDGET_DRAG:
        if (!(e->min < e->max)) return false;
        for (int k = 0; k < e->ncomp; k++) e->value[k] = high ? e->max : e->min;
        return true;
    default:
        return false;
    }
}

/* Every slider, checkbox and colour of every pack at each end of its range:
 * all at once on the lake and under water, then one at a time on the lake
 * (a define's rebuild is shared with the next entry's; an end that is the
 * default was drawn already): no NaN, no Inf, no GL error. The error is not bounded here: a slider at an end
 * is a deliberate departure (opacity 1 hides the floor). */
static void test_every_slider_at_each_end(void) {
    if (!npacks) SKIP("no packs");
    render_target tg;
    CHECK(render_target_create(&tg, W, H, true));
    const char *scenes[] = { TARN_SOURCE_DIR "/scenes/lake.glib", TARN_SOURCE_DIR "/scenes/hard/underwater.glib" };
    for (int p = 0; p < npacks; p++) {
        double t0 = wall_s();
        render_desc rd = { .pack = packs[p] };
        render *r = render_create(&rd);
        int tried = 0;
        for (int s = 0; s < 2; s++) {
            if (!render_load(r, scenes[s])) {
                CHECK_MSG(false, "%s: %s", packs[p], render_messages(r));
                continue;
            }
            int nsets;
            unif_set *sets = render_uniforms(r, &nsets);
            bool stale = false;   /* the programs were built with a define since reset */
            for (int high = 0; high < 2; high++) {
                /* every entry at once (k = -1), then (on the lake) one entry at a time */
                for (int i = 0; i < nsets; i++)
                    for (int k = -1; k < sets[i].n; k++) {
                        if (k < 0 && i > 0) continue;
                        if (k >= 0 && s > 0) break;
                        bool rebuild = false, any = false;
                        for (int i2 = 0; i2 < nsets; i2++)
                            for (int k2 = 0; k2 < sets[i2].n; k2++) {
                                unif_entry *e = &sets[i2].entries[k2];
                                if ((k < 0 || (i2 == i && k2 == k)) && set_end(e, high)) {
                                    rebuild |= e->is_define && !unif_is_default(e);
                                    any |= !unif_is_default(e);   /* an end at the default: drawn already */
                                }
                            }
                        if (!any) continue;
                        if (rebuild || stale)
                            CHECK_MSG(render_rebuild_programs(r), "%s: %s", packs[p], render_messages(r));
                        stale = rebuild;
                        char what[512];
                        snprintf(what, sizeof what, "%.60s, %.63s at its %s (%.300s)", packs[p],
                                 k < 0 ? "every entry" : sets[i].entries[k].name, high ? "max" : "min", scenes[s]);
                        if (draw(r, &tg, what)) {
                            long bad = nonfinite(px, (long)W * H);
                            CHECK_MSG(bad == 0, "%s: %ld pixels are NaN or Inf", what, bad);
                            check_targets(r, what);
                        }
                        tried++;
                        for (int i2 = 0; i2 < nsets; i2++) unif_reset_all(&sets[i2]);
                    }
                if (stale) render_rebuild_programs(r);
                stale = false;
            }
        }
        fprintf(stderr, "  %-12s %d slider ends drawn in %.1f s\n", packs[p], tried, wall_s() - t0);
        render_destroy(r);
    }
    render_target_destroy(&tg);
}

int main(void) {
    char err[512];
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    if (!ctx) { fprintf(stderr, "skip: %s\n", err); return 77; }
    find_cases();
    npacks = packset_list(TARN_SOURCE_DIR, packs, PACKSET_MAX);
    fprintf(stderr, "  %d hard cases, %d packs:", ncases, npacks);
    for (int p = 0; p < npacks; p++) fprintf(stderr, " %s", packs[p]);
    fputc('\n', stderr);
    double t = wall_s();
    RUN(test_references);
    fprintf(stderr, "  %.1f s\n", wall_s() - t);
    t = wall_s();
    RUN(test_every_case_through_every_pack);
    fprintf(stderr, "  %.1f s\n", wall_s() - t);
    t = wall_s();
    RUN(test_buffers_are_finite);
    fprintf(stderr, "  %.1f s\n", wall_s() - t);
    t = wall_s();
    RUN(test_every_slider_at_each_end);
    fprintf(stderr, "  %.1f s\n", wall_s() - t);
    for (int c = 0; c < ncases; c++) refcache_free(&refs[c]);
    gl_ctx_destroy(ctx);
    return check_summary();
}
