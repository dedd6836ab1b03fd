/* cmd_bench: `tarn bench [SCENE...] [options]`, speed against error
 * (tools/bench.h, docs/benchmark.md). Exit codes: 0 ok, 1 a scene, pack or
 * output failed, 2 bad usage, 3 no OpenGL context. */
#include "cmd.h"
#include "strbuf.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "bench.h"
#include "util.h"

/* The command line: the bench's desc and the --packs list it points into. */
typedef struct bench_cli {
    bench_desc d;
    char packs[1024];   /* --packs split in place; d.packs point into it */
} bench_cli;

static bool set_scene(void *desc, const char *value, char *why, size_t whylen) {
    bench_desc *d = &((bench_cli *)desc)->d;
    if (d->nscenes == BENCH_MAX_SCENES) {
        snprintf(why, whylen, "at most %d scenes", BENCH_MAX_SCENES);
        return false;
    }
    d->scenes[d->nscenes++] = value;
    return true;
}

static bool set_packs(void *desc, const char *value, char *why, size_t whylen) {
    bench_cli *c = desc;
    c->d.npacks = cmd_split(value, c->packs, sizeof c->packs, c->d.packs, PACKSET_MAX);
    if (c->d.npacks < 0) snprintf(why, whylen, "at most %d packs", PACKSET_MAX);
    return c->d.npacks >= 0;
}

/* --times t1,t2,...: up to BENCH_MAX_TIMES numbers. */
static bool set_times(void *desc, const char *list, char *why, size_t whylen) {
    bench_desc *d = &((bench_cli *)desc)->d;
    char buf[512];
    const char *parts[BENCH_MAX_TIMES];
    int n = list ? cmd_split(list, buf, sizeof buf, parts, BENCH_MAX_TIMES) : 0;
    bool ok = n > 0;
    for (int i = 0; ok && i < n; i++) ok = cmd_opt_range(parts[i], -1e6, 1e6, &d->times[i]);
    if (!ok) snprintf(why, whylen, "--times wants up to %d numbers, e.g. 1,4", BENCH_MAX_TIMES);
    else d->ntimes = n;
    return ok;
}

static bool set_axis(void *desc, const char *s, char *why, size_t whylen) {
    static const char *const names[] = { "auto", "gpu", "wall", "cpu" };   /* BENCH_AXIS_* */
    for (int i = 0; s && i < 4; i++)
        if (strcmp(s, names[i]) == 0) { ((bench_cli *)desc)->d.time_axis = i; return true; }
    return false;
}

/* --warmup and --frame-budget: given, even as their defaults (bench_run
 * fills those in only where they were not). */
static bool set_warmup(void *desc, const char *s, char *why, size_t whylen) {
    bench_desc *d = &((bench_cli *)desc)->d;
    return (d->warmup_set = cmd_opt_int(s, 0, 1000, &d->warmup));
}

static bool set_frame_budget(void *desc, const char *s, char *why, size_t whylen) {
    bench_desc *d = &((bench_cli *)desc)->d;
    return (d->frame_budget_set = cmd_opt_range(s, 0, 1e5, &d->frame_budget));
}

static bool set_seq_frames(void *desc, const char *s, char *why, size_t whylen) {
    bench_desc *d = &((bench_cli *)desc)->d;
    if (!cmd_opt_int(s, 0, 240, &d->seq_frames)) return false;
    d->no_sequence = d->seq_frames == 0;
    return true;
}

#define OFF(field) offsetof(bench_cli, d.field)

static const cmd_option options[] = {
    { "SCENE.glib", .kind = CMD_ARG, .set = set_scene,
      .help = "scenes to measure (default: scenes/lake.glib, pool.glib and ocean.glib)\n",
      .man = "scenes to measure (default:\n"
             ".IR scenes/lake.glib ,\n"
             ".I scenes/pool.glib\n"
             "and\n"
             ".IR scenes/ocean.glib ).\n" },
    { "--packs", .metavar = "a,b", .kind = CMD_CUSTOM, .set = set_packs,
      .help = "packs to measure (default: every packs/NAME/pack.glib)\n",
      .man = "packs to measure (default: every\n"
             ".IR packs/NAME/pack.glib ).\n" },
    /* the bench's own bounds: smaller than 8 says nothing, larger than 8192 takes hours */
    { "--size", .metavar = "WxH", .kind = CMD_SIZE, .offset = OFF(width), .offset2 = OFF(height), .lo = 8,
      .hi = 8192, .wants = "WxH, e.g. 480x270",
      .help = "image size (default 480x270)\n",
      .man = "image size (default 480x270).\n" },
    { "--times", .metavar = "t1,t2", .kind = CMD_CUSTOM, .set = set_times,
      .help = "simulated times, seconds (default 1,4)\n",
      .man = "simulated times, seconds (default 1,4).\n" },
    { "--frames", .metavar = "N", .kind = CMD_INT, .offset = OFF(frames), .lo = 1, .hi = 100000,
      .help = "at most N timed frames per setting and time (default 30)\n",
      .man = "at most\n"
             ".I N\n"
             "timed frames per setting and time (default 30).\n" },
    { "--frame-budget", .metavar = "S", .kind = CMD_CUSTOM, .set = set_frame_budget, .wants = "seconds",
      .help = "...and no more than S seconds of them, at least 3 frames\n"
              "(default 1.5: on a CPU rasteriser frames take long)\n",
      .man = "\\&...and no more than\n"
             ".I S\n"
             "seconds of them, at least 3 frames (default 1.5: on a CPU rasteriser frames\n"
             "take long).\n" },
    { "--warmup", .metavar = "N", .kind = CMD_CUSTOM, .set = set_warmup, .wants = "0..1000",
      .help = "untimed frames first (default 1; the first frame\n"
              "also runs the RenderToTextureOnce passes)\n",
      .man = "untimed frames first (default 1; the first frame also runs the\n"
             ".B RenderToTextureOnce\n"
             "passes).\n" },
    { "--out", .metavar = "DIR", .kind = CMD_STRING, .offset = OFF(out),
      .help = "where the results go (default out/bench)\n",
      .man = "where the results go (default\n"
             ".IR out/bench ).\n" },
    { "--docs", .metavar = "FILE", .kind = CMD_STRING, .offset = OFF(docs),
      .help = "also write the report into FILE between the markers\n"
              "<!-- bench:begin --> and <!-- bench:end --> (e.g.\n"
              "docs/benchmark.md), and the plots beside it\n",
      .man = "also write the report into\n"
             ".I FILE\n"
             "between the markers\n"
             ".B <!\\-\\- bench:begin \\-\\->\n"
             "and\n"
             ".B <!\\-\\- bench:end \\-\\->\n"
             "(e.g.\n"
             ".IR docs/benchmark.md ),\n"
             "and the plots beside it.\n" },
    { "--time-axis", .metavar = "A", .kind = CMD_CUSTOM, .set = set_axis, .wants = "auto, gpu, wall or cpu",
      .help = "auto, gpu, wall or cpu: the time the plot and the Pareto\n"
              "front use (auto: on a CPU rasteriser such as llvmpipe the\n"
              "process's CPU time a frame, the rasteriser's threads\n"
              "included, which other processes' load barely moves, where\n"
              "its GPU timestamps and the wall time are wall clocks; GPU\n"
              "time otherwise)\n",
      .man = ".BR auto \", \" gpu \", \" wall \" or \" cpu :\n"
             "the time the plot and the Pareto front use (auto: on a CPU rasteriser\n"
             "such as llvmpipe the process's CPU time a frame, the rasteriser's\n"
             "threads included, which other processes' load barely moves, where its\n"
             "GPU timestamps and the wall time are wall clocks; GPU time otherwise).\n" },
    { "--msaa", .metavar = "N", .kind = CMD_MSAA, .offset = OFF(samples),
      .help = "anti-aliasing of the packs: N samples per pixel, 0 or 1 off\n"
              "(default 4 on a GPU, off on a CPU rasteriser such as llvmpipe)\n",
      .man = "anti\\-aliasing of the packs (as in\n"
             ".BR render ;\n"
             "default 4 on a GPU, off on a CPU rasteriser; 0 or 1 off).\n"
             "Per\\-pixel buffers (hit point, Fresnel, irradiance, depth) are always drawn\n"
             "without it, as the reference's come from the pixel centre.\n" },
    { "--ref-spp", .metavar = "N", .kind = CMD_INT, .offset = OFF(ref.spp), .lo = 1, .hi = 16,
      .help = "reference subsamples on an N x N grid (default: matched to\n"
              "--msaa, at the positions the GL samples; 1 x 1 when off)\n",
      .man = "reference subsamples on an ordered\n"
             ".IR N \" x \" N\n"
             "grid (default: matched to\n"
             ".BR \\-\\-msaa :\n"
             "at the positions the GL samples, as\n"
             ".B tarn reference \\-\\-msaa\n"
             "takes them; 1 x 1 when off).\n"
             "The report and\n"
             ".I bench.json\n"
             ".RB ( reference_positions )\n"
             "say which.\n" },
    { "--ref-photons", .metavar = "N", .kind = CMD_INT, .offset = OFF(ref.photons_per_cell), .lo = 1, .hi = 1 << 20,
      .help = "reference photons per caustic cell (default 36)\n",
      .man = "reference photons per caustic cell (default 36).\n" },
    { "--ref-caustic-res", .metavar = "N", .kind = CMD_INT, .offset = OFF(ref.caustic_res), .lo = 1, .hi = 8192,
      .help = "reference caustic grid (default 256)\n",
      .man = "reference caustic grid (default 256).\n" },
    { "--ref-cache", .metavar = "DIR", .kind = CMD_STRING, .offset = OFF(ref_cache),
      .help = "where the reference images are cached (default\n"
              "$XDG_CACHE_HOME/tarn/ref, else ~/.cache/tarn/ref)\n",
      .man = "where the reference images are cached (default\n"
             ".IR $XDG_CACHE_HOME/tarn/ref ,\n"
             "else\n"
             ".IR ~/.cache/tarn/ref ;\n"
             "with neither\n"
             ".B XDG_CACHE_HOME\n"
             "nor\n"
             ".B HOME\n"
             "set,\n"
             ".IR DIR/ref\n"
             "under\n"
             ".BR \\-\\-out ).\n" },
    { "--heat-max", .metavar = "E", .kind = CMD_DOUBLE, .offset = OFF(heat_max), .lo = 1e-9, .hi = 1e9,
      .wants = "a positive error",
      .help = "heat-map scale, linear RGB error (default 0.25)\n",
      .man = "heat\\-map scale, linear RGB error (default 0.25).\n" },
    { "--no-images", .kind = CMD_FLAG, .offset = OFF(no_images),
      .help = "do not write the frames and heat maps\n",
      .man = "do not write the frames and heat maps.\n" },
    { "--no-cost-model", .kind = CMD_FLAG, .offset = OFF(no_cost_model),
      .help = "skip the cost model: each pack's default timed at three\n"
              "sizes and three water grids on the first scene, fitted\n"
              "as ms = a + b*Mpixels + c*kvertices and reported\n",
      .man = "skip the cost model: by default each pack's default setting is timed on the\n"
             "first scene at three image sizes (half, the run's, one and a half times a\n"
             "side) and three water grids (WaterMesh 64, 128, 256), and its time fitted as\n"
             "ms = a + b\\(muMpixels + c\\(mukvertices, printed with the report and in\n"
             ".IR bench.json .\n" },
    { "--no-uncertainty", .kind = CMD_FLAG, .offset = OFF(no_uncertainty),
      .help = "skip the reference's noise (photon seed 1: another sampling) and\n"
              "grid bias (a caustic grid twice as fine) at the first time;\n"
              "ties then fall back to a 1% error rule\n",
      .man = "skip the reference's uncertainty: by default each setting's water RMSE and\n"
             "FLIP at the first time are measured again against a reference with another\n"
             "photon sampling ((k+1)\\(mu(k+1) photons a caustic cell instead of k\\(muk) and\n"
             "one with a caustic grid twice as fine; the changes are the figures'\n"
             "uncertainty, and settings whose errors agree within it tie on the Pareto\n"
             "fronts (without it, within 1%).\n" },
    { "--seq-frames", .metavar = "N", .kind = CMD_CUSTOM, .set = set_seq_frames, .wants = "0..240",
      .help = "frames of the animated sequence each setting is measured\n"
              "over, from the first time (default 8; 0 none)\n",
      .man = "frames of the animated sequence each setting is also measured over, from\n"
             "the first time at\n"
             ".B \\-\\-seq\\-fps\n"
             "(default 8; 0: none): the water RMSE over the instants and the temporal\n"
             "error, the RMS over the water of the pack's frame\\-to\\-frame change minus\n"
             "the reference's.\n" },
    { "--seq-fps", .metavar = "F", .kind = CMD_DOUBLE, .offset = OFF(seq_fps), .lo = 0.1, .hi = 1000,
      .help = "its frame rate (default 30)\n",
      .man = "the sequence's frame rate (default 30).\n" },
    { "--seq-size", .metavar = "WxH", .kind = CMD_SIZE, .offset = OFF(seq_width), .offset2 = OFF(seq_height),
      .lo = 11, .hi = 8192, .wants = "WxH, at least 11x11, e.g. 240x135",
      .help = "its image size (default half the --size a side)\n",
      .man = "the sequence's image size (default half of\n"
             ".B \\-\\-size\n"
             "a side, at least 32x18).\n" },
    { "--rr-frames", .metavar = "N", .kind = CMD_INT, .offset = OFF(rr_chunk), .lo = 1, .hi = 1000,
      .help = "frames a setting is timed in its round-robin turn (default 2)\n",
      .man = "settings are timed round\\-robin: every setting of a scene in turn gets N\n"
             "timed frames (default 2), turn after turn, until each has its frames.\n" },
    { "--quiet", .kind = CMD_FLAG, .offset = OFF(quiet),
      .help = "no progress bar\n",
      .man = "no progress bar.\n" },
    { "--root", .metavar = "DIR", .kind = CMD_STRING, .offset = OFF(root),
      .help = "the tree whose packs/ is used (default: $TARN_ROOT, else\n"
              "the installed data, else tarn's source tree)\n",
      .man = "the tree whose\n"
             ".I packs/\n"
             "is used (default:\n"
             ".BR $TARN_ROOT ,\n"
             "else the installed data, else tarn's source tree; see\n"
             ".BR ENVIRONMENT ).\n" },
    { 0 }
};

const cmd_spec cmd_bench_spec = {
    .name = "bench",
    .synopsis = "[SCENE.glib...] [--packs a,b] [--size WxH] [--times t1,t2]\n"
                "[--frames N] [--out DIR] [--docs FILE] [options]\n",
    .about = "Speed against error: every pack (or those named) at every setting its\n"
             "packs/NAME/bench.txt declares, at fixed simulated times, timed and compared\n"
             "with the CPU reference of the same frame (RMSE, HDR-FLIP, SSIM; water first),\n"
             "over a short animated sequence, and with the reference's own uncertainty;\n"
             "settings are timed round-robin. Writes DIR/bench.csv, bench.json,\n"
             "passes.csv (GPU time per pass), report.md, plot-SCENE.png (time against\n"
             "RMSE), plot-SCENE-flip.png (against FLIP), the frames, their heat maps and\n"
             "the sequence's temporal error strips (DIR/img). The reference images are cached in\n"
             "$XDG_CACHE_HOME/tarn/ref (default ~/.cache/tarn/ref): reruns reuse them.\n",
    .options = options,
    .notes = "exit codes: 0 ok, 1 a scene, pack or output failed (the rest is measured),\n"
             "2 bad usage, 3 no OpenGL\n",
    .column = 21,
};

CMD_USAGE_FUNCTION(cmd_bench_usage, cmd_bench_spec)

int cmd_bench(int argc, char **argv) {
    if (cmd_wants_help(argc, argv)) { fputs(cmd_bench_usage(), stdout); return TARN_EXIT_OK; }
    bench_cli c = {0};
    char why[MSG_MAX] = "";
    int rc = cmd_parse(&cmd_bench_spec, argc, argv, &c, stderr);
    if (rc != TARN_EXIT_OK) return rc;
    rc = bench_run(&c.d, why, sizeof why);
    if (rc == TARN_EXIT_USAGE) return cmd_bad_usage(&cmd_bench_spec, stderr, "%s", why);   /* a root, scene or pack that is not there */
    return rc;
}
