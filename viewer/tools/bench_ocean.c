/* bench_ocean: the ocean passes' cost (see bench_ocean.h). */
#include "bench_ocean.h"
#include "strbuf.h"

#include <GL/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render_ocean.h"
#include "util.h"

static const int SIZES[BENCH_OCEAN_SIZES] = { 64, 128, 256, 512 };


/* One configuration: N, cascades; the median ms of a frame's passes. */
static double time_passes(const ref_ocean_desc *scene, int res, int cascades, char *note, size_t notelen) {
    ref_ocean_desc d = *scene;
    d.res = res;
    d.cascades = cascades;
    if (cascades > 1 && (d.tile[1] <= 0 || d.tile[2] <= 0)) memset(d.tile, 0, sizeof d.tile);   /* the defaults */
    char err[MSG_MAX] = "";
    ref_ocean *ro = ref_ocean_create(&d, err, sizeof err);
    if (!ro) {
        snprintf(note, notelen, "%s", err);
        return NAN;
    }
    char common[4096];
    diag_list log = { 0 };
    snprintf(common, sizeof common, "%s/packs/common", tarn_root());
    const char *inc[1] = { common };
    gpu_ocean g;
    memset(&g, 0, sizeof g);
    double ms = NAN;
    if (!ocean_create_from(&g, ro, &(prog_sources){ .include_dirs = inc, .ninclude_dirs = 1, .common_dir = common }, &log,
                           NULL)) {
        char *text = log.n ? diag_list_format(&log, 0) : NULL;
        snprintf(note, notelen, "the ocean's passes do not build: %.200s", text ? text : "?");
        free(text);
    } else {
        double v[BENCH_OCEAN_FRAMES];
        ocean_update(&g, 0.5, NULL);   /* warm: programs linked, textures touched */
        glFinish();
        for (int i = 0; i < BENCH_OCEAN_FRAMES; i++) {
            double t0 = clock_now_s();
            ocean_update(&g, 1.0 + i / 30.0, NULL);   /* a new time each frame: no cache answers */
            glFinish();
            v[i] = (clock_now_s() - t0) * 1e3;
        }
        ms = median_double(v, BENCH_OCEAN_FRAMES);
    }
    diag_list_free(&log);
    ocean_free(&g);
    ref_ocean_destroy(ro);
    return ms;
}

bool bench_ocean_measure(const ref_ocean_desc *scene_ocean, bench_ocean_costs *c) {
    memset(c, 0, sizeof *c);
    for (int s = 0; s < BENCH_OCEAN_SIZES; s++) {
        c->res[s] = SIZES[s];
        for (int k = 0; k < 2; k++) {
            c->ms[s][k] = time_passes(scene_ocean, SIZES[s], k ? 3 : 1, c->note, sizeof c->note);
            if (isnan(c->ms[s][k])) return false;
        }
    }
    c->have = true;
    return true;
}

void bench_ocean_md(const bench_ocean_costs *c, const char *scene, strbuf *o) {
    if (!c->have) {
        if (c->note[0]) strbuf_printf(o, "**Ocean FFT passes**: not measured: %s\n\n", c->note);
        return;
    }
    strbuf_printf(o, "**Ocean FFT passes** (%s's spectrum; one frame's spectrum pass and 2 log2 N inverse-FFT "
                  "passes alone, wall ms after glFinish, median of %d frames each at a new time; every pack pays "
                  "them once a frame before drawing):\n\n", scene, BENCH_OCEAN_FRAMES);
    strbuf_printf(o, "| N | 1 cascade ms | 3 cascades ms | ms a cascade (of 3) |\n|---:|---:|---:|---:|\n");
    for (int s = 0; s < BENCH_OCEAN_SIZES; s++)
        strbuf_printf(o, "| %d² | %.2f | %.2f | %.2f |\n", c->res[s], c->ms[s][0], c->ms[s][1], c->ms[s][1] / 3);
    strbuf_printf(o, "\n");
}
