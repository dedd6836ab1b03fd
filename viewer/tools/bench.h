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

/* The `Define` a pack declares to expose its per-pixel buffers, and what
 * each of its values writes to the colour output (RGB, alpha 1): */
#define BENCH_OUTPUT_DEFINE "TARN_OUTPUT"
enum {
    BENCH_OUTPUT_COLOR = 0,       /* the normal image */
    BENCH_OUTPUT_REFRACT_HIT = 1, /* world xyz the refracted ray meets */
    BENCH_OUTPUT_FRESNEL = 2,     /* the Fresnel reflectance, in R */
    BENCH_OUTPUT_IRRADIANCE = 3,  /* sun irradiance at the refraction hit, RGB */
    BENCH_OUTPUT_DEPTH = 4,       /* the path length in water, in R */
    BENCH_OUTPUT_COUNT
};

#endif
