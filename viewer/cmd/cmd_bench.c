/* cmd_bench: `tarn bench [SCENE...] [options]`, speed against error
 * (tools/bench.h, docs/benchmark.md). Exit codes: 0 ok, 1 a scene, pack or
 * output failed, 2 bad usage, 3 no OpenGL context. */
#include "cmd.h"

#include <string.h>

#include "bench.h"
#include "util.h"

static const char usage[] =
    "usage: tarn bench [SCENE.glib...] [--packs a,b] [--size WxH] [--times t1,t2]\n"
    "                  [--frames N] [--out DIR] [--docs FILE] [options]\n"
    "\n"
    "Speed against error: every pack (or those named) at every setting its\n"
    "packs/NAME/bench.txt declares, at fixed simulated times, timed and compared\n"
    "with the CPU reference of the same frame (RMSE, HDR-FLIP, SSIM; water first),\n"
    "over a short animated sequence, and with the reference's own uncertainty;\n"
    "settings are timed round-robin. Writes DIR/bench.csv, bench.json,\n"
    "passes.csv (GPU time per pass), report.md, plot-SCENE.png (time against\n"
    "RMSE), plot-SCENE-flip.png (against FLIP), the frames, their heat maps and\n"
    "the sequence's temporal error strips (DIR/img). The reference images are cached in\n"
    "$XDG_CACHE_HOME/tarn/ref (default ~/.cache/tarn/ref): reruns reuse them.\n"
    "\n"
    "  SCENE.glib         scenes to measure (default: scenes/lake.glib, pool.glib and ocean.glib)\n"
    "  --packs a,b        packs to measure (default: every packs/NAME/pack.glib)\n"
    "  --size WxH         image size (default 480x270)\n"
    "  --times t1,t2      simulated times, seconds (default 1,4)\n"
    "  --frames N         at most N timed frames per setting and time (default 30)\n"
    "  --frame-budget S   ...and no more than S seconds of them, at least 3 frames\n"
    "                     (default 1.5: on a CPU rasteriser frames take long)\n"
    "  --warmup N         untimed frames first (default 1; the first frame\n"
    "                     also runs the RenderToTextureOnce passes)\n"
    "  --out DIR          where the results go (default out/bench)\n"
    "  --docs FILE        also write the report into FILE between the markers\n"
    "                     <!-- bench:begin --> and <!-- bench:end --> (e.g.\n"
    "                     docs/benchmark.md), and the plots beside it\n"
    "  --time-axis A      auto, gpu, wall or cpu: the time the plot and the Pareto\n"
    "                     front use (auto: on a CPU rasteriser such as llvmpipe the\n"
    "                     process's CPU time a frame, the rasteriser's threads\n"
    "                     included, which other processes' load barely moves, where\n"
    "                     its GPU timestamps and the wall time are wall clocks; GPU\n"
    "                     time otherwise)\n"
    "  --msaa N           anti-aliasing of the packs: N samples per pixel, 0 or 1 off\n"
    "                     (default 4 on a GPU, off on a CPU rasteriser such as llvmpipe)\n"
    "  --ref-spp N        reference subsamples on an N x N grid (default: matched to\n"
    "                     --msaa, at the positions the GL samples; 1 x 1 when off)\n"
    "  --ref-photons N    reference photons per caustic cell (default 36)\n"
    "  --ref-caustic-res N  reference caustic grid (default 256)\n"
    "  --ref-cache DIR    where the reference images are cached (default\n"
    "                     $XDG_CACHE_HOME/tarn/ref, else ~/.cache/tarn/ref)\n"
    "  --heat-max E       heat-map scale, linear RGB error (default 0.25)\n"
    "  --no-images        do not write the frames and heat maps\n"
    "  --no-cost-model    skip the cost model: each pack's default timed at three\n"
    "                     sizes and three water grids on the first scene, fitted\n"
    "                     as ms = a + b*Mpixels + c*kvertices and reported\n"
    "  --no-uncertainty   skip the reference's noise (photon seed 1: another sampling) and\n"
    "                     grid bias (a caustic grid twice as fine) at the first time;\n"
    "                     ties then fall back to a 1% error rule\n"
    "  --seq-frames N     frames of the animated sequence each setting is measured\n"
    "                     over, from the first time (default 8; 0 none)\n"
    "  --seq-fps F        its frame rate (default 30)\n"
    "  --seq-size WxH     its image size (default half the --size a side)\n"
    "  --rr-frames N      frames a setting is timed in its round-robin turn (default 2)\n"
    "  --quiet            no progress bar\n"
    "  --root DIR         the tree whose packs/ is used (default: $TARN_ROOT, else\n"
    "                     the installed data, else tarn's source tree)\n"
    "\n"
    "exit codes: 0 ok, 1 a scene, pack or output failed (the rest is measured),\n"
    "2 bad usage, 3 no OpenGL\n";

const char *cmd_bench_usage(void) { return usage; }

#define BAD(...) cmd_bad_usage(stderr, "tarn bench", usage, __VA_ARGS__)

/* --times t1,t2,...: up to BENCH_MAX_TIMES numbers. */
static bool parse_times(const char *list, bench_desc *d) {
    char buf[512];
    const char *parts[BENCH_MAX_TIMES];
    int n = list ? cmd_split(list, buf, sizeof buf, parts, BENCH_MAX_TIMES) : 0;
    if (n <= 0) return false;
    for (int i = 0; i < n; i++)
        if (!cmd_opt_range(parts[i], -1e6, 1e6, &d->times[i])) return false;
    d->ntimes = n;
    return true;
}

static bool parse_axis(const char *s, int *axis) {
    static const char *const names[] = { "auto", "gpu", "wall", "cpu" };   /* BENCH_AXIS_* */
    for (int i = 0; s && i < 4; i++)
        if (strcmp(s, names[i]) == 0) { *axis = i; return true; }
    return false;
}

/* The numeric options: NAME, range, where it goes, the complaint. */
static int parse_number(const char *a, const char *next, bench_desc *d, bool *matched) {
    double v;
    *matched = true;
    if (strcmp(a, "--frames") == 0) {
        if (!cmd_opt_range(next, 1, 100000, &v)) return BAD("--frames wants 1..100000");
        d->frames = (int)v;
    } else if (strcmp(a, "--warmup") == 0) {
        if (!cmd_opt_range(next, 0, 1000, &v)) return BAD("--warmup wants 0..1000");
        d->warmup = (int)v;
        d->warmup_set = true;
    } else if (strcmp(a, "--frame-budget") == 0) {
        if (!cmd_opt_range(next, 0, 1e5, &d->frame_budget)) return BAD("--frame-budget wants seconds");
        d->frame_budget_set = true;
    } else if (strcmp(a, "--ref-spp") == 0) {
        if (!cmd_opt_range(next, 1, 16, &v)) return BAD("--ref-spp wants 1..16");
        d->ref.spp = (int)v;
    } else if (strcmp(a, "--msaa") == 0) {
        if (!cmd_opt_msaa(next, &d->samples)) return BAD("--msaa wants 0..16 samples");
    } else if (strcmp(a, "--ref-photons") == 0) {
        if (!cmd_opt_range(next, 1, 1 << 20, &v)) return BAD("--ref-photons wants 1..1048576");
        d->ref.photons_per_cell = (int)v;
    } else if (strcmp(a, "--ref-caustic-res") == 0) {
        if (!cmd_opt_range(next, 1, 8192, &v)) return BAD("--ref-caustic-res wants 1..8192");
        d->ref.caustic_res = (int)v;
    } else if (strcmp(a, "--seq-frames") == 0) {
        if (!cmd_opt_range(next, 0, 240, &v)) return BAD("--seq-frames wants 0..240");
        d->seq_frames = (int)v;
        d->no_sequence = v == 0;
    } else if (strcmp(a, "--seq-fps") == 0) {
        if (!cmd_opt_range(next, 0.1, 1000, &d->seq_fps)) return BAD("--seq-fps wants 0.1..1000");
    } else if (strcmp(a, "--rr-frames") == 0) {
        if (!cmd_opt_range(next, 1, 1000, &v)) return BAD("--rr-frames wants 1..1000");
        d->rr_chunk = (int)v;
    } else if (strcmp(a, "--heat-max") == 0) {
        if (!cmd_opt_range(next, 1e-9, 1e9, &d->heat_max)) return BAD("--heat-max wants a positive error");
    } else {
        *matched = false;
    }
    return TARN_EXIT_OK;
}

/* packs holds the --packs list split in place (d->packs point into it). */
static int parse(int argc, char **argv, bench_desc *d, char *packs, size_t packslen) {
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        bool matched;
        int rc = parse_number(a, next, d, &matched);
        if (rc != TARN_EXIT_OK) return rc;
        if (matched) { i++; continue; }
        if (strcmp(a, "--packs") == 0 && next) {
            d->npacks = cmd_split(next, packs, packslen, d->packs, PACKSET_MAX);
            if (d->npacks < 0) return BAD("at most %d packs", PACKSET_MAX);
            i++;
        } else if (strcmp(a, "--root") == 0 && next) { d->root = next; i++; }
        else if (strcmp(a, "--size") == 0) {
            /* the bench's own bounds: smaller than 8 says nothing, larger than 8192 takes hours */
            if (!opt_size(next, &d->width, &d->height) || d->width < 8 || d->height < 8 || d->width > 8192 ||
                d->height > 8192)
                return BAD("--size wants WxH, e.g. 480x270");
            i++;
        } else if (strcmp(a, "--seq-size") == 0) {
            if (!opt_size(next, &d->seq_width, &d->seq_height) || d->seq_width < 11 || d->seq_height < 11 ||
                d->seq_width > 8192 || d->seq_height > 8192)
                return BAD("--seq-size wants WxH, at least 11x11, e.g. 240x135");
            i++;
        } else if (strcmp(a, "--times") == 0) {
            if (!parse_times(next, d)) return BAD("--times wants up to %d numbers, e.g. 1,4", BENCH_MAX_TIMES);
            i++;
        } else if (strcmp(a, "--out") == 0 && next) { d->out = next; i++; }
        else if (strcmp(a, "--docs") == 0 && next) { d->docs = next; i++; }
        else if (strcmp(a, "--ref-cache") == 0 && next) { d->ref_cache = next; i++; }
        else if (strcmp(a, "--time-axis") == 0 && next) {
            if (!parse_axis(next, &d->time_axis)) return BAD("--time-axis wants auto, gpu, wall or cpu");
            i++;
        } else if (strcmp(a, "--no-images") == 0) d->no_images = true;
        else if (strcmp(a, "--no-cost-model") == 0) d->no_cost_model = true;
        else if (strcmp(a, "--no-uncertainty") == 0) d->no_uncertainty = true;
        else if (strcmp(a, "--quiet") == 0) d->quiet = true;
        else if (a[0] == '-') return BAD("unknown option '%s'", a);
        else if (d->nscenes < BENCH_MAX_SCENES) d->scenes[d->nscenes++] = a;
        else return BAD("at most %d scenes", BENCH_MAX_SCENES);
    }
    return TARN_EXIT_OK;
}

int cmd_bench(int argc, char **argv) {
    if (cmd_wants_help(argc, argv)) { fputs(usage, stdout); return TARN_EXIT_OK; }
    bench_desc d = {0};
    char packs[1024], why[1024] = "";
    int rc = parse(argc, argv, &d, packs, sizeof packs);
    if (rc != TARN_EXIT_OK) return rc;
    rc = bench_run(&d, why, sizeof why);
    if (rc == TARN_EXIT_USAGE) return BAD("%s", why);   /* a root, scene or pack that is not there */
    return rc;
}
