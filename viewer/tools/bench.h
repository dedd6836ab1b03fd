/* bench: `tarn bench [SCENE...] [options]`, speed against error. For every
 * pack present (or those named) and every setting its packs/NAME/bench.txt
 * declares (packset.h), at fixed simulated times: the median GPU time and
 * wall time per frame, and the error against the CPU reference of the same
 * frame (refcache.h, reference/ref_metrics.h) — the colour image always,
 * and hit point, Fresnel, irradiance and depth where the pack exposes them
 * (`Define TARN_OUTPUT`). The cost floor (a full-screen pass with one
 * texture fetch) is measured in the same run. Writes CSV, JSON, a Markdown
 * report and a speed-against-error plot per scene; with --docs, the report
 * section of docs/benchmark.md. See docs/benchmark.md. */
#ifndef TARN_BENCH_H
#define TARN_BENCH_H

/* argv holds the arguments after "bench". Exit codes: 0 ok, 1 a scene,
 * pack or output failed (the rest is still measured and written), 2 bad
 * usage, 3 no OpenGL context. */
int cli_bench(int argc, char **argv);

const char *bench_usage(void);

/* The `Define` a pack declares to expose its per-pixel buffers; what each
 * of its values writes is reference/ref_buffers.h's ref_output. */
#define BENCH_OUTPUT_DEFINE "TARN_OUTPUT"

/* The alpha a pack writes in its refraction-hit buffer where its march ran
 * out of steps before it found the ground (raymarch's MARCH_CAP); bench
 * reports the share of water pixels so. */
#define BENCH_MARCH_CAPPED 2.0f

#endif
