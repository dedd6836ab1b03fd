/* cmd_reference: `tarn reference SCENE.glib -o ref.exr [options]`, the CPU
 * ground truth of a scene (reference/ref_render.h) written as a linear EXR,
 * an sRGB PNG and per-pixel buffers. See docs/reference.md, "The renderer".
 * Exit codes: TARN_EXIT_OK, TARN_EXIT_INPUT (scene errors, render or write
 * failure), TARN_EXIT_USAGE. */
#include "cmd.h"

#include <math.h>
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

static const char usage[] =
    "usage: tarn reference SCENE.glib -o OUT.exr [--size WxH] [--time SECONDS]\n"
    "                      [--threads N] [--spp N | --msaa N] [--photons N] [--caustic-res N]\n"
    "                      [--seed N] [--flat-caustics] [--radiance-n2] [--quiet]\n"
    "\n"
    "Renders the scene's world on the CPU in double precision: the ground truth\n"
    "the packs are measured against (exact waves, Fresnel, refraction, ray/terrain\n"
    "intersection, Beer-Lambert, caustics by photon tracing). Deterministic: the\n"
    "same output for any number of threads.\n"
    "\n"
    "  -o, --out OUT.exr    the image, linear RGB, 32-bit float; beside it:\n"
    "                         OUT.png              the image, sRGB 8-bit\n"
    "                         OUT.refract_hit.exr  xyz the refracted ray meets, and what (A)\n"
    "                         OUT.reflect.exr      xyz the reflected ray meets, or its\n"
    "                                              direction, and a flag (A)\n"
    "                         OUT.fresnel.exr      Fresnel reflectance at the water\n"
    "                         OUT.depth.exr        path length in water\n"
    "                         OUT.irradiance.exr   sun irradiance at the refraction hit\n"
    "                         OUT.surface.exr      where the ray meets the water\n"
    "                         OUT.mask.exr         0 sky, 1 water, 2 terrain, 3 object\n"
    "                       (NaN where a buffer has no value; docs/reference.md)\n"
    "  --size WxH           image size (default: the scene's WindowSize)\n"
    "  --time SECONDS       simulated time of the waves (default 0)\n"
    "  --threads N          worker threads (default: every core)\n"
    "  --spp N              N x N subsamples per pixel for the colour (default 1);\n"
    "                       the buffers are always the pixel centre's\n"
    "  --msaa N             match N-sample MSAA (a `tarn render --msaa N` frame):\n"
    "                       subsample where the GL samples with N (asked of a headless\n"
    "                       context), or without one at the standard positions of\n"
    "                       2, 4, 8 or 16 samples; 0 or 1: the pixel centre\n"
    "  --photons N          photons per caustic grid cell (default 36)\n"
    "  --caustic-res N      caustic grid cells along the underwater floor (default 256)\n"
    "  --seed N             the photons' random numbers (default 0, the fixed\n"
    "                       sequence); another seed samples the same strata anew, so\n"
    "                       two seeds differ by photon noise alone\n"
    "  --flat-caustics      no photons: the floor lit through flat water\n"
    "  --radiance-n2        scale radiance crossing the surface by (n_t/n_i)^2\n"
    "  --quiet              no progress bar and no summary, only errors\n"
    "\n"
    "exit codes: 0 ok, 1 the scene has errors or an output could not be written,\n"
    "2 bad usage\n";

const char *cmd_reference_usage(void) { return usage; }

static int bad_usage(const char *what) { return cmd_bad_usage(stderr, "tarn reference", usage, "%s", what); }

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
    char err[1024] = "";
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

static int parse(int argc, char **argv, reference_opts *o) {
    ref_render_desc *d = &o->d;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "-o") == 0 || strcmp(a, "--out") == 0) {
            if (!next) return bad_usage("-o wants a path, e.g. -o out/ref.exr");
            o->out = next;
            i++;
        } else if (strcmp(a, "--size") == 0) {
            if (!opt_size(next, &o->width, &o->height)) return bad_usage("--size wants WxH, e.g. 640x360");
            i++;
        } else if (strcmp(a, "--time") == 0) {
            if (!opt_double(next, &d->time) || !isfinite(d->time)) return bad_usage("--time wants seconds, e.g. 2.5");
            i++;
        } else if (strcmp(a, "--threads") == 0) {
            if (!cmd_opt_int(next, 1, 256, &d->threads)) return bad_usage("--threads wants 1..256");
            i++;
        } else if (strcmp(a, "--spp") == 0) {
            if (!cmd_opt_int(next, 1, 16, &d->spp)) return bad_usage("--spp wants 1..16 (N x N subsamples)");
            i++;
        } else if (strcmp(a, "--msaa") == 0) {
            if (!cmd_opt_msaa(next, &o->msaa)) return bad_usage("--msaa wants 0..16 samples");
            i++;
        } else if (strcmp(a, "--photons") == 0) {
            if (!cmd_opt_int(next, 1, 1 << 20, &d->photons_per_cell)) return bad_usage("--photons wants 1..1048576 per cell");
            i++;
        } else if (strcmp(a, "--caustic-res") == 0) {
            if (!cmd_opt_int(next, 1, 8192, &d->caustic_res)) return bad_usage("--caustic-res wants 1..8192");
            i++;
        } else if (strcmp(a, "--seed") == 0) {
            int seed;
            if (!cmd_opt_int(next, 0, 2147483647, &seed)) return bad_usage("--seed wants 0..2147483647");
            d->seed = (uint64_t)seed;
            i++;
        } else if (strcmp(a, "--flat-caustics") == 0) {
            d->caustics = REF_CAUSTICS_FLAT;
        } else if (strcmp(a, "--radiance-n2") == 0) {
            d->radiance_n2 = 1;
        } else if (strcmp(a, "--quiet") == 0) {
            o->quiet = true;
        } else if (a[0] == '-') {
            char what[160];
            snprintf(what, sizeof what, "unknown option '%.100s'", a);
            return bad_usage(what);
        } else if (!o->glib) {
            o->glib = a;
        } else {
            return bad_usage("one scene at a time");
        }
    }
    if (o->msaa && d->spp) return bad_usage("--spp and --msaa: give one (--spp N is an N x N grid, --msaa N matches MSAA)");
    if (!o->glib) return bad_usage("which scene? give SCENE.glib");
    if (!o->out) return bad_usage("where to? give -o OUT.exr");
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
    char err[4096] = "";
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
    if (cmd_wants_help(argc, argv)) { fputs(usage, stdout); return TARN_EXIT_OK; }
    reference_opts o;
    memset(&o, 0, sizeof o);
    int rc = parse(argc, argv, &o);
    return rc == TARN_EXIT_OK ? run(&o) : rc;
}
