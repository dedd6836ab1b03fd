/* bench_ocean: what the spectrum ocean's GPU passes cost (issue #23): the
 * spectrum pass and the 2 log2 N inverse-FFT passes (gfx/render_ocean.h)
 * of one frame, alone, at N = 64, 128, 256 and 512, with one cascade and
 * with three. Every timed frame is at a new simulated time, so the
 * ocean's own "same time, same frame" check never answers for the work;
 * wall time after glFinish (on llvmpipe the GPU timestamps are taken when
 * commands are queued), the median of BENCH_OCEAN_FRAMES. `tarn bench`
 * runs it when a scene has an ocean and reports it beside the cost model. */
#ifndef TARN_BENCH_OCEAN_H
#define TARN_BENCH_OCEAN_H

#include <stdbool.h>

#include "ref_ocean.h"
#include "strbuf.h"

#define BENCH_OCEAN_SIZES 4          /* 64, 128, 256, 512 */
#define BENCH_OCEAN_FRAMES 9

typedef struct bench_ocean_costs {
    bool have;
    int res[BENCH_OCEAN_SIZES];
    double ms[BENCH_OCEAN_SIZES][2];       /* [size][0]: 1 cascade, [1]: 3 cascades; NAN: not measured */
    char note[256];                        /* why not, when !have */
} bench_ocean_costs;

/* Measures with the scene's spectrum (its wind, fetch, seed: the cost does
 * not depend on them, but the measure is of a real sea); needs a current
 * GL context. False with the reason in c->note. */
bool bench_ocean_measure(const ref_ocean_desc *scene_ocean, bench_ocean_costs *c);

/* The Markdown table of c (nothing when !c->have). */
void bench_ocean_md(const bench_ocean_costs *c, const char *scene, strbuf *o);

#endif
