/* cmd_compare: `tarn compare A B [options]`, the error of image A against
 * reference B (tools/compare.h). Returns 0 when compared, 1 when a file
 * could not be read, compared or written, 2 on bad usage (the usage text
 * goes to err; --help prints it to out, 0). */
#include "cmd.h"

#include <math.h>
#include <string.h>

#include "compare.h"
#include "util.h"

static const char usage[] =
    "usage: tarn compare A B [--out HEATMAP.png] [--threshold T] [--max E]\n"
    "                        [--mask M] [--json FILE|-] [--csv FILE|-]\n"
    "                        [--flip-map MAP.png] [--buffers] [--texel W]\n"
    "                        [--linear]\n"
    "\n"
    "Measures the error of image A (under test) against image B (the reference),\n"
    "in linear RGB: RMSE and MAE over all channel values, PSNR (peak 1.0), the\n"
    "largest error and its pixel, the share of pixels whose error (the largest\n"
    "of the R, G, B errors) exceeds a threshold, and NaN/Inf pixels of each side\n"
    "(left out of the statistics and counted). Beside them, two perceptual\n"
    "figures: FLIP (Andersson et al. 2020; 0 = no visible difference, 1 = the\n"
    "largest; LDR-FLIP when A and B are both 8-bit display images, HDR-FLIP\n"
    "otherwise; 67 pixels per degree), its mean, weighted median and quartiles,\n"
    "min and max; and SSIM (Wang et al. 2004, on the sRGB-encoded luminance;\n"
    "1 = identical). A and B are any format\n"
    "OpenImageIO reads, of the same size. PNG, JPEG, BMP, GIF, TGA, WebP and\n"
    "PNM inputs are sRGB-decoded to linear first; EXR, HDR and TIFF are read\n"
    "as linear. Alpha is ignored; a grey image stands for R = G = B.\n"
    "\n"
    "When B is a `tarn reference` image (B.mask.exr beside it), the figures lead\n"
    "with the error over the reference's water pixels (water_rmse,\n"
    "water_flip_mean, water_ssim, ...: what a\n"
    "water technique gets right or wrong), then off the water (sky, land,\n"
    "objects: the world, which should agree), then the whole frame.\n"
    "\n"
    "  -o, --out HEATMAP.png\n"
    "                     write the per-pixel error as an inferno heat map\n"
    "                     (black = 0, pale yellow = the scale or more,\n"
    "                     cyan = NaN/Inf in A or B, grey = outside the mask)\n"
    "  --flip-map MAP.png write the per-pixel FLIP error in the authors' magma\n"
    "                     colours (black = 0, pale yellow = 1; grey = outside\n"
    "                     the mask, cyan = NaN/Inf in A or B)\n"
    "  --max E            heat-map scale (default: the 99th percentile of the\n"
    "                     per-pixel error)\n"
    "  --threshold T      error counted as 'over' when > T (default 0.05)\n"
    "  --mask M           compare only where image M's first channel is > 0.5\n"
    "  --json FILE|-      write every metric as JSON (- : stdout)\n"
    "  --csv FILE|-       write every metric as CSV, a header row and a value\n"
    "                     row (- : stdout); with either on stdout the table\n"
    "                     goes to stderr\n"
    "  --buffers          also compare the reference buffers beside A and B:\n"
    "                     for X.exr, X.refract_hit.exr, X.reflect.exr and\n"
    "                     X.surface.exr (hit points: distance in world units;\n"
    "                     a 4th channel is what the ray met), X.fresnel.exr,\n"
    "                     X.depth.exr and X.irradiance.exr (scalars: absolute\n"
    "                     and relative error), each pair that exists on both\n"
    "                     sides; with --out, one heat map per buffer too\n"
    "                     (HEATMAP.NAME.png)\n"
    "  --texel W          world units per texel: hit-point errors in texels too\n"
    "  --linear           take every input as linear (no sRGB decoding)\n"
    "\n"
    "exit codes: 0 compared, 1 a file could not be read, compared or written,\n"
    "2 bad usage\n";

const char *cmd_compare_usage(void) { return usage; }

#define BAD(...) cmd_bad_usage(err, "tarn compare", usage, __VA_ARGS__)

/* A finite number > 0. */
static bool positive(const char *s, double *v) { return cmd_opt_range(s, 0, INFINITY, v) && *v > 0 && isfinite(*v); }

static int parse(int argc, char **argv, compare_desc *o, FILE *err) {
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--out") == 0 || strcmp(a, "-o") == 0) {
            if (!next) return BAD("%s wants a file name, e.g. heat.png", a);
            o->out = next; i++;
        } else if (strcmp(a, "--json") == 0 || strcmp(a, "--csv") == 0 || strcmp(a, "--mask") == 0) {
            if (!next) return BAD("%s wants a file name%s", a, a[2] == 'm' ? "" : " or -");
            if (a[2] == 'j') o->json = next; else if (a[2] == 'c') o->csv = next; else o->mask = next;
            i++;
        } else if (strcmp(a, "--flip-map") == 0) {
            if (!next) return BAD("--flip-map wants a file name, e.g. flip.png");
            o->flip_map = next; i++;
        } else if (strcmp(a, "--threshold") == 0) {
            if (!positive(next, &o->threshold)) return BAD("--threshold wants a number > 0, e.g. 0.05");
            i++;
        } else if (strcmp(a, "--max") == 0) {
            if (!positive(next, &o->max_err)) return BAD("--max wants a number > 0, e.g. 0.1");
            i++;
        } else if (strcmp(a, "--texel") == 0) {
            if (!positive(next, &o->texel)) return BAD("--texel wants world units per texel > 0, e.g. 0.05");
            i++;
        } else if (strcmp(a, "--buffers") == 0) o->buffers = true;
        else if (strcmp(a, "--linear") == 0) o->linear = true;
        else if (a[0] == '-' && a[1] != '\0') return BAD("unknown option '%s'", a);
        else if (!o->a) o->a = a;
        else if (!o->b) o->b = a;
        else return BAD("two images at a time (got a third: '%s')", a);
    }
    if (!o->a || !o->b) return BAD("which images? give A and B");
    if (o->json && o->csv && strcmp(o->json, "-") == 0 && strcmp(o->csv, "-") == 0)
        return BAD("--json - and --csv - cannot both go to stdout");
    return TARN_EXIT_OK;
}

int cmd_compare_io(int argc, char **argv, FILE *out, FILE *err) {
    if (cmd_wants_help(argc, argv)) { fputs(usage, out); return TARN_EXIT_OK; }
    compare_desc d = {0};
    int rc = parse(argc, argv, &d, err);
    return rc == TARN_EXIT_OK ? compare_run(&d, out, err) : rc;
}

int cmd_compare(int argc, char **argv) { return cmd_compare_io(argc, argv, stdout, stderr); }
