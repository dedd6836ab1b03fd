/* bench_cost: the cost model of `tarn bench` (bench_int.h, costmodel.h):
 * each pack's default timed over three image sizes and three water grids,
 * a + b·pixels + c·vertices fitted, and the spectrum ocean's passes. */
#include "bench_int.h"
#include "strbuf.h"

#include <math.h>
#include <stdio.h>

#include "render.h"
#include "scene.h"

/* The sweep a pack's cost model is fitted from: its default setting on the
 * first scene at three image sizes (half, the run's, 1.5x a side) and
 * three water grids: 9 timed frames, medians as the run's. */
const int BENCH_COST_MESHES[3] = { 64, 128, 256 };
const double BENCH_COST_SCALES[3] = { 0.5, 1.0, 1.5 };
#define COST_MESHES BENCH_COST_MESHES
#define COST_SCALES BENCH_COST_SCALES

/* One mesh: a wrapper glib adding `WaterMesh m` to the scene, loaded once
 * and timed at each size. Returns the samples added, -1 with why on a
 * failed load. */
static int cost_mesh(bench *b, int p, int m, cost_sample *out, char *why, size_t whylen) {
    char sc[256], path[PATH_LEN + 300];
    bench_stem(b->scene_abs[0], sc, sizeof sc);
    packset_assign as = { .program = "scene", .name = "WaterMesh", .value = { (float)m }, .nvalue = 1 };
    packset_setting st = { .assign = &as, .nassign = 1 };
    snprintf(st.name, sizeof st.name, "cost-mesh-%d", m);
    snprintf(path, sizeof path, "%s/scenes/%s.%s.cost-mesh-%d.glib", b->o.out, sc, b->o.packs[p], m);
    char err[MSG_MAX] = "";
    if (!packset_write_wrapper(&st, b->scene_abs[0], path, err, sizeof err)) {
        snprintf(why, whylen, "%s", err);
        return -1;
    }
    /* no spray: the reference draws none (docs/waves.md), so it is no part of a pack's error or time */
    render_desc rd = { .repo_root = b->root, .pack = b->o.packs[p], .samples = b->o.samples, .no_spray = true };
    render *r = render_create(&rd);
    if (!render_load(r, path)) {
        bench_first_line(render_messages(r), why, whylen);
        render_destroy(r);
        return -1;
    }
    int n = 0;
    for (size_t i = 0; i < sizeof COST_SCALES / sizeof COST_SCALES[0]; i++) {
        int w = (int)lround(b->o.w * COST_SCALES[i]), h = (int)lround(b->o.h * COST_SCALES[i]);
        render_target tg;
        if (w < 1 || h < 1 || !render_target_create(&tg, w, h, true)) continue;
        timing tm = bench_time_frames(b, r, &tg, b->o.times[0], NULL);
        render_target_destroy(&tg);
        out[n++] = (cost_sample){ (double)w * h / 1e6, cost_model_grid_kvertices(m),
                                  bench_axis_ms(b, &tm) };
    }
    render_destroy(r);
    return n;
}

void bench_measure_cost(bench *b, int p) {
    char sc[256];
    bench_stem(b->scene_abs[0], sc, sizeof sc);
    bench_progress_set(&b->pr, b->pr.done, true, "%s %s: cost model", sc, b->o.packs[p]);
    cost_sample samples[COST_SAMPLES];
    int n = 0;
    for (size_t k = 0; k < sizeof COST_MESHES / sizeof COST_MESHES[0]; k++) {
        int got = cost_mesh(b, p, COST_MESHES[k], samples + n, b->cost_note[p], sizeof b->cost_note[p]);
        if (got < 0) return;
        n += got;
    }
    b->has_cost[p] = cost_model_fit(samples, n, &b->cost[p], b->cost_note[p], sizeof b->cost_note[p]);
}

/* The ocean's FFT passes at every size, with the first scene that has an
 * ocean: its cost grows with N^2 log N, whatever the pack draws. */
void bench_measure_ocean(bench *b) {
    for (int s = 0; s < b->o.nscenes; s++) {
        ref_world_desc w;
        if (!scene_load(b->scene_abs[s], NULL, &w, NULL, NULL, NULL, 0) || w.waves.ocean.spectrum == REF_SPECTRUM_NONE)
            continue;
        bench_stem(b->scene_abs[s], b->ocean_scene, sizeof b->ocean_scene);
        bench_progress_set(&b->pr, b->pr.done, true, "%s: the ocean's FFT passes", b->ocean_scene);
        if (!bench_ocean_measure(&w.waves.ocean, &b->ocean)) b->failures++;
        return;
    }
}
