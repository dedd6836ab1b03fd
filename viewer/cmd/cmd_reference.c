/* cmd_reference: `tarn reference SCENE.glib -o ref.exr [options]`, the CPU
 * ground truth of a scene (reference/ref_render.h) written as a linear EXR,
 * an sRGB PNG and per-pixel buffers. See docs/reference.md, "The renderer".
 * Exit codes: TARN_EXIT_OK, TARN_EXIT_INPUT (scene errors, render or write
 * failure), TARN_EXIT_USAGE. */
#include "cmd.h"
#include "strbuf.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "util.h"
#include "image_io.h"
#include "mem.h"
#include "ref_render.h"
#include "scene.h"
#include "ref_buffers.h"
#include "gl_ctx.h"
#include "render.h"

/* ---- the progress bar ------------------------------------------------- */

typedef struct bar {
    double start, last, last_f;
    int drawn;
} bar;

static void fmt_time(double s, char *buf, size_t n) {
    if (s < 60) snprintf(buf, n, "%.1f s", s);
    else snprintf(buf, n, "%d:%02d", (int)(s / 60), (int)fmod(s, 60));
}

static void bar_progress(void *user, double f) {
    bar *b = user;
    double t = clock_now_s();
    if ((f < 1.0 && t - b->last < 0.1) || (b->drawn && f == b->last_f)) return;
    b->last = t;
    b->last_f = f;
    enum { WIDTH = 30 };
    int fill = (int)(f * WIDTH + 0.5);
    char line[WIDTH + 1], el[32], eta[32] = "";
    for (int i = 0; i < WIDTH; i++) line[i] = i < fill ? '#' : '.';
    line[WIDTH] = '\0';
    double elapsed = t - b->start;
    fmt_time(elapsed, el, sizeof el);
    if (f > 0.005 && f < 1.0) {
        char e[24];
        fmt_time(elapsed * (1.0 - f) / f, e, sizeof e);
        snprintf(eta, sizeof eta, "  ETA %s", e);
    }
    fprintf(stderr, "\r[%s] %5.1f%%  elapsed %s%s\033[K", line, 100.0 * f, el, eta);
    fflush(stderr);
    b->drawn = 1;
}

/* ---- writing ----------------------------------------------------------- */

static double srgb_encode(double v) {
    if (!(v > 0)) return 0;
    if (v >= 1) return 1;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

/* Writes n doubles a pixel (from src, stride n) as a float image. */
static int write_buffer(const char *path, const double *src, const unsigned char *bytes, int w,
                        int h, int n, int srgb, char *err, int errlen) {
    img im;
    if (!img_alloc(&im, w, h, n)) {
        snprintf(err, (size_t)errlen, "%s: out of memory", path);
        return 0;
    }
    size_t count = (size_t)w * h * n;
    for (size_t i = 0; i < count; i++) {
        double v = bytes ? (double)bytes[i] : src[i];
        im.px[i] = (float)(srgb ? srgb_encode(v) : v);
    }
    int ok = srgb ? img_write(path, &im, err, errlen) : img_write_float(path, &im, err, errlen);
    img_free(&im);
    return ok;
}

static int write_outputs(const char *out, const ref_render_result *r, int quiet) {
    size_t stem_len = strlen(out) - 4;   /* without ".exr" */
    size_t cap = stem_len + 32;
    char *path = mem_alloc(cap), err[512];
    /* every buffer of ref_buffers.h, and the image once more as sRGB PNG */
    struct { const char *suffix; const double *px; const unsigned char *bytes; int n, srgb; } files[REF_BUF_COUNT + 1];
    int nfiles = 0;
    for (int i = 0; i < REF_BUF_COUNT; i++) {
        const ref_buffer_info *bi = &ref_buffers[i];
        files[nfiles].suffix = bi->suffix;
        files[nfiles].px = ref_buffer_data(r, bi->id);
        files[nfiles].bytes = bi->id == REF_BUF_MASK ? r->mask : NULL;
        files[nfiles].n = bi->channels;
        files[nfiles++].srgb = 0;
        if (bi->id == REF_BUF_COLOR) {
            files[nfiles] = files[nfiles - 1];
            files[nfiles].suffix = ".png";
            files[nfiles++].srgb = 1;
        }
    }
    int ok = 1;
    for (int i = 0; i < nfiles; i++) {
        snprintf(path, cap, "%.*s%s", (int)stem_len, out, files[i].suffix);
        if (!write_buffer(path, files[i].px, files[i].bytes, r->width, r->height, files[i].n,
                          files[i].srgb, err, sizeof err)) {
            fprintf(stderr, "tarn reference: cannot write %s\n", err);
            ok = 0;
            break;
        }
    }
    if (ok && !quiet)
        printf("wrote %s, %.*s.png and the buffers %.*s.{refract_hit,reflect,fresnel,depth,"
               "irradiance,surface,mask}.exr\n", out, (int)stem_len, out, (int)stem_len, out);
    free(path);
    return ok;
}

/* ---- matching MSAA ------------------------------------------------------ */

/* --msaa N: the subsample positions of N-sample MSAA into d. Asked of a
 * headless GL (the samples it gives for N, as `tarn render --msaa N` gets
 * them), else the standard positions; says which on stdout (unless quiet).
 * False, with a message, when neither knows N. */
static bool match_msaa(int samples, bool quiet, ref_render_desc *d) {
    if (samples <= 1) return true;   /* off: the pixel centre */
    char err[MSG_MAX] = "";
    const char *from = "this GL's";
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    bool have_gl = ctx != NULL;
    int used = samples, n = 0;
    if (have_gl) {
        used = render_samples_on_this_gl(samples);
        n = render_ref_positions(used, d->samples, REF_MAX_SAMPLES);
        gl_ctx_destroy(ctx);
        if (used <= 1) {
            if (!quiet) printf("tarn reference: this GL has no MSAA: one subsample at the pixel centre\n");
            return true;
        }
    }
    if (n <= 0) {
        n = render_ref_standard_positions(used, d->samples, REF_MAX_SAMPLES);
        from = "the standard";
        if (n <= 0) {
            fprintf(stderr, "tarn reference: no GL to ask where %d-sample MSAA samples%s, and no standard "
                            "positions for %d (there are for 2, 4, 8 and 16): give --msaa 2, 4, 8 or 16\n",
                    used, have_gl ? "" : " (no headless context)", used);
            return false;
        }
    }
    d->nsamples = n;
    if (!quiet) {
        printf("tarn reference: matching %d-sample MSAA at %s sample positions%s:", n, from,
               have_gl ? "" : " (no GL context to ask)");
        for (int k = 0; k < n; k++) printf(" (%g, %g)", d->samples[k][0], d->samples[k][1]);
        printf(" (x right, y down in the pixel)\n");
    }
    return true;
}

/* ---- the command -------------------------------------------------------- */

/* The command line: the scene, where to write, the image size (0: the
 * scene's) and the reference's own desc (zero means its defaults). */
typedef struct reference_opts {
    const char *glib, *out;
    int width, height;
    bool quiet;
    int msaa;                   /* --msaa N (0: not given) */
    ref_render_desc d;
} reference_opts;

static bool set_seed(void *desc, const char *value, char *why, size_t whylen) {
    int seed;
    if (!cmd_opt_int(value, 0, 2147483647, &seed)) return false;
    ((reference_opts *)desc)->d.seed = (uint64_t)seed;
    return true;
}

static bool set_flat_caustics(void *desc, const char *value, char *why, size_t whylen) {
    ((reference_opts *)desc)->d.caustics = REF_CAUSTICS_FLAT;
    return true;
}

static bool set_radiance_n2(void *desc, const char *value, char *why, size_t whylen) {
    ((reference_opts *)desc)->d.radiance_n2 = 1;
    return true;
}

#define OFF(field) offsetof(reference_opts, field)

static const cmd_option options[] = {
    { "SCENE.glib", .kind = CMD_ARG, .offset = OFF(glib), .missing = "which scene? give SCENE.glib" },
    { "--out", "-o", "OUT.exr", .kind = CMD_STRING, .offset = OFF(out), .wants = "a path, e.g. -o out/ref.exr",
      .missing = "where to? give -o OUT.exr",
      .help = "the image, linear RGB, 32-bit float; beside it:\n"
              "  OUT.png              the image, sRGB 8-bit\n"
              "  OUT.refract_hit.exr  xyz the refracted ray meets, and what (A)\n"
              "  OUT.reflect.exr      xyz the reflected ray meets, or its\n"
              "                       direction, and a flag (A)\n"
              "  OUT.fresnel.exr      Fresnel reflectance at the water\n"
              "  OUT.depth.exr        path length in water\n"
              "  OUT.irradiance.exr   sun irradiance at the refraction hit\n"
              "  OUT.surface.exr      where the ray meets the water\n"
              "  OUT.mask.exr         0 sky, 1 water, 2 terrain, 3 object\n"
              "(NaN where a buffer has no value; docs/reference.md)\n",
      .man = "the image, linear RGB, 32\\-bit float; beside it\n"
             ".I OUT.png\n"
             "(the image, sRGB 8\\-bit),\n"
             ".I OUT.refract_hit.exr\n"
             "(xyz the refracted ray meets, and what, in A),\n"
             ".I OUT.reflect.exr\n"
             "(xyz the reflected ray meets, or its direction, and a flag in A),\n"
             ".I OUT.fresnel.exr\n"
             "(Fresnel reflectance at the water),\n"
             ".I OUT.depth.exr\n"
             "(path length in water),\n"
             ".I OUT.irradiance.exr\n"
             "(sun irradiance at the refraction hit),\n"
             ".I OUT.surface.exr\n"
             "(where the ray meets the water) and\n"
             ".I OUT.mask.exr\n"
             "(0 sky, 1 water, 2 terrain, 3 object); NaN where a buffer has no value\n"
             ".RI ( docs/reference.md ).\n" },
    { "--size", .metavar = "WxH", .kind = CMD_SIZE, .offset = OFF(width), .offset2 = OFF(height),
      .wants = "WxH, e.g. 640x360",
      .help = "image size (default: the scene's WindowSize)\n",
      .man = "image size (default: the scene's\n"
             ".BR WindowSize ).\n" },
    { "--time", .metavar = "SECONDS", .kind = CMD_DOUBLE, .offset = OFF(d.time), .wants = "seconds, e.g. 2.5",
      .help = "simulated time of the waves (default 0)\n",
      .man = "simulated time of the waves (default 0).\n" },
    { "--threads", .metavar = "N", .kind = CMD_INT, .offset = OFF(d.threads), .lo = 1, .hi = 256,
      .help = "worker threads (default: every core)\n",
      .man = "worker threads (default: every core).\n" },
    { "--spp", .metavar = "N", .kind = CMD_INT, .offset = OFF(d.spp), .lo = 1, .hi = 16,
      .wants = "1..16 (N x N subsamples)",
      .help = "N x N subsamples per pixel for the colour (default 1);\n"
              "the buffers are always the pixel centre's\n",
      .man = ".IR N \" x \" N\n"
             "subsamples per pixel for the colour (default 1); the buffers are always the\n"
             "pixel centre's.\n" },
    { "--msaa", .metavar = "N", .kind = CMD_MSAA, .offset = OFF(msaa),
      .help = "match N-sample MSAA (a `tarn render --msaa N` frame):\n"
              "subsample where the GL samples with N (asked of a headless\n"
              "context), or without one at the standard positions of\n"
              "2, 4, 8 or 16 samples; 0 or 1: the pixel centre\n",
      .man = "match a frame drawn with\n"
             ".I N\n"
             "MSAA samples\n"
             ".RB ( \"tarn render \\-\\-msaa\" \" N):\"\n"
             "subsample the colour where the GL samples with\n"
             ".I N\n"
             "(asked of a headless context with\n"
             ".BR glGetMultisamplefv ;\n"
             "with 4 on llvmpipe: (0.375, 0.125), (0.875, 0.375), (0.125, 0.625),\n"
             "(0.625, 0.875) with y up), not on an ordered grid, so edges cover a pixel\n"
             "alike in both; without a context, at the standard positions of 2, 4, 8 or\n"
             "16 samples (it says which). 0 or 1: the pixel centre. Not with\n"
             ".BR \\-\\-spp .\n" },
    { "--photons", .metavar = "N", .kind = CMD_INT, .offset = OFF(d.photons_per_cell), .lo = 1, .hi = 1 << 20,
      .wants = "1..1048576 per cell",
      .help = "photons per caustic grid cell (default 36)\n",
      .man = "photons per caustic grid cell (default 36).\n" },
    { "--caustic-res", .metavar = "N", .kind = CMD_INT, .offset = OFF(d.caustic_res), .lo = 1, .hi = 8192,
      .help = "caustic grid cells along the underwater floor (default 256)\n",
      .man = "caustic grid cells along the underwater floor (default 256; at most 8192,\n"
             "and the grids of all threads at most 8 GiB).\n" },
    { "--seed", .metavar = "N", .kind = CMD_CUSTOM, .set = set_seed, .wants = "0..2147483647",
      .help = "the photons' random numbers (default 0, the fixed\n"
              "sequence); another seed samples the same strata anew, so\n"
              "two seeds differ by photon noise alone\n",
      .man = "the photons' random numbers (default 0, the fixed sequence); another seed\n"
             "samples the same strata anew, so two seeds differ by photon noise alone.\n" },
    { "--flat-caustics", .kind = CMD_CUSTOM, .set = set_flat_caustics,
      .help = "no photons: the floor lit through flat water\n",
      .man = "no photons: the floor lit through flat water.\n" },
    { "--radiance-n2", .kind = CMD_CUSTOM, .set = set_radiance_n2,
      .help = "scale radiance crossing the surface by (n_t/n_i)^2\n",
      .man = "scale radiance crossing the surface by\n"
             ".RI ( n_t / n_i )^2.\n" },
    { "--quiet", .kind = CMD_FLAG, .offset = OFF(quiet),
      .help = "no progress bar and no summary, only errors\n",
      .man = "no progress bar and no summary, only errors.\n" },
    { 0 }
};

const cmd_spec cmd_reference_spec = {
    .name = "reference",
    .synopsis = "SCENE.glib -o OUT.exr [--size WxH] [--time SECONDS]\n"
                "[--threads N] [--spp N | --msaa N] [--photons N] [--caustic-res N]\n"
                "[--seed N] [--flat-caustics] [--radiance-n2] [--quiet]\n",
    .about = "Renders the scene's world on the CPU in double precision: the ground truth\n"
             "the packs are measured against (exact waves, Fresnel, refraction, ray/terrain\n"
             "intersection, Beer-Lambert, caustics by photon tracing). Deterministic: the\n"
             "same output for any number of threads.\n",
    .options = options,
    .notes = "exit codes: 0 ok, 1 the scene has errors or an output could not be written,\n"
             "2 bad usage\n",
    .column = 23,
    .extra = "one scene at a time",
};

CMD_USAGE_FUNCTION(cmd_reference_usage, cmd_reference_spec)

static int bad_usage(const char *what) { return cmd_bad_usage(&cmd_reference_spec, stderr, "%s", what); }

static int parse(int argc, char **argv, reference_opts *o) {
    int rc = cmd_parse(&cmd_reference_spec, argc, argv, o, stderr);
    if (rc != TARN_EXIT_OK) return rc;
    if (o->msaa && o->d.spp) return bad_usage("--spp and --msaa: give one (--spp N is an N x N grid, --msaa N matches MSAA)");
    size_t ol = strlen(o->out);
    if (ol < 5 || strcmp(o->out + ol - 4, ".exr") != 0)
        return bad_usage("-o wants a .exr path (the PNG and the buffers go beside it)");
    return TARN_EXIT_OK;
}

static int run(reference_opts *o) {
    const char *glib = o->glib, *out = o->out;
    int width = o->width, height = o->height, quiet = o->quiet;
    ref_render_desc d = o->d;
    if (!match_msaa(o->msaa, quiet, &d)) return TARN_EXIT_INPUT;
    ref_world_desc wd;
    scene_camera cam;
    bool has_world = false;
    char err[MSG_MAX] = "";
    if (!scene_load(glib, NULL, &wd, &cam, &has_world, err, (int)sizeof err)) {
        if (strstr(err, ": error:")) {
            fprintf(stderr, "%s\ntarn reference: %s has errors\n", err, glib);
            return TARN_EXIT_INPUT;
        }
        fprintf(stderr, "%s\n", err);   /* warnings: repaired values */
    }
    if (!has_world) {
        fprintf(stderr, "tarn reference: %s describes no world (no Sun, Water, Terrain, Wave... or "
                        "Object commands; see docs/glib.md)\n", glib);
        return TARN_EXIT_INPUT;
    }
    ref_world world;
    ref_world_init(&world, &wd);

    d.world = &world;
    memcpy(d.camera.eye, cam.eye, sizeof cam.eye);
    memcpy(d.camera.center, cam.center, sizeof cam.center);
    memcpy(d.camera.up, cam.up, sizeof cam.up);
    d.camera.fov_deg = cam.fov_deg;
    d.camera.width = width ? width : cam.width;
    d.camera.height = height ? height : cam.height;
    bar b = { .start = clock_now_s() };
    if (!quiet && isatty(STDERR_FILENO)) {
        d.progress = bar_progress;
        d.progress_user = &b;
    }
    ref_render_desc rd = ref_render_resolve(&d);
    if (!quiet && rd.nsamples > 0)
        printf("tarn reference: %s at t = %g s, %dx%d, %d subsamples at those positions, %d threads\n", glib,
               rd.time, rd.camera.width, rd.camera.height, rd.nsamples, rd.threads);
    else if (!quiet)
        printf("tarn reference: %s at t = %g s, %dx%d, %d x %d subsamples, %d threads\n", glib,
               rd.time, rd.camera.width, rd.camera.height, rd.spp, rd.spp, rd.threads);
    fflush(stdout);

    ref_render_result r;
    char rerr[512] = "";
    double t0 = clock_now_s();
    int rc = ref_render(&d, &r, rerr, sizeof rerr);
    double total = clock_now_s() - t0;
    if (b.drawn) fputc('\n', stderr);
    ref_world_release(&world);
    if (rc != 0) {
        fprintf(stderr, "tarn reference: %s\n", rerr);
        return TARN_EXIT_INPUT;
    }
    if (!quiet) {
        if (r.have_caustics)
            printf("photons: %ld on a %dx%d grid (%.3g m cells) in %.2f s\n", r.caustics.stats.photons,
                   r.caustics.nx, r.caustics.nz, (r.caustics.x1 - r.caustics.x0) / r.caustics.nx,
                   r.seconds_photons);
        else
            printf("photons: none (the floor is lit through flat water)\n");
        printf("pixels: %.2f s; total %.2f s\n", r.seconds_pixels, total);
    }
    int ok = write_outputs(out, &r, quiet);
    ref_render_free(&r);
    return ok ? TARN_EXIT_OK : TARN_EXIT_INPUT;
}

int cmd_reference(int argc, char **argv) {
    if (cmd_wants_help(argc, argv)) { fputs(cmd_reference_usage(), stdout); return TARN_EXIT_OK; }
    reference_opts o;
    memset(&o, 0, sizeof o);
    int rc = parse(argc, argv, &o);
    return rc == TARN_EXIT_OK ? run(&o) : rc;
}
