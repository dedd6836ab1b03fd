/* cmd_compare: `tarn compare A B [options]`, the error of image A against
 * reference B (tools/compare.h). Returns 0 when compared, 1 when a file
 * could not be read, compared or written, 2 on bad usage (the usage text
 * goes to err; --help prints it to out, 0). */
#include "cmd.h"

#include <float.h>
#include <stddef.h>
#include <string.h>

#include "compare.h"
#include "util.h"

#define OFF(field) offsetof(compare_desc, field)
#define POSITIVE .kind = CMD_DOUBLE, .lo = DBL_MIN, .hi = DBL_MAX   /* a finite number > 0 */

static const cmd_option options[] = {
    { "A", .kind = CMD_ARG, .offset = OFF(a), .missing = "which images? give A and B" },
    { "B", .kind = CMD_ARG, .offset = OFF(b), .missing = "which images? give A and B" },
    { "--out", "-o", "HEATMAP.png", .kind = CMD_STRING, .offset = OFF(out), .wants = "a file name, e.g. heat.png",
      .help = "write the per-pixel error as an inferno heat map\n"
              "(black = 0, pale yellow = the scale or more,\n"
              "cyan = NaN/Inf in A or B, grey = outside the mask)\n",
      .man = "write the per\\-pixel error as an inferno heat map (black = 0, pale yellow =\n"
             "the scale or more, cyan = NaN/Inf in A or B, grey = outside the mask).\n" },
    { "--flip-map", .metavar = "MAP.png", .kind = CMD_STRING, .offset = OFF(flip_map),
      .wants = "a file name, e.g. flip.png",
      .help = "write the per-pixel FLIP error in the authors' magma\n"
              "colours (black = 0, pale yellow = 1; grey = outside\n"
              "the mask, cyan = NaN/Inf in A or B)\n",
      .man = "write the per\\-pixel FLIP error in the authors' magma colours (black = 0, pale\n"
             "yellow = 1; grey = outside the mask, cyan = NaN/Inf in A or B).\n" },
    { "--max", .metavar = "E", POSITIVE, .offset = OFF(max_err), .wants = "a number > 0, e.g. 0.1",
      .help = "heat-map scale (default: the 99th percentile of the\n"
              "per-pixel error)\n",
      .man = "heat\\-map scale (default: the 99th percentile of the per\\-pixel error).\n" },
    { "--threshold", .metavar = "T", POSITIVE, .offset = OFF(threshold), .wants = "a number > 0, e.g. 0.05",
      .help = "error counted as 'over' when > T (default 0.05)\n",
      .man = "error counted as 'over' when >\n"
             ".I T\n"
             "(default 0.05).\n" },
    { "--mask", .metavar = "M", .kind = CMD_STRING, .offset = OFF(mask), .wants = "a file name",
      .help = "compare only where image M's first channel is > 0.5\n",
      .man = "compare only where image\n"
             ".IR M 's\n"
             "first channel is > 0.5.\n" },
    { "--json", .metavar = "FILE|-", .kind = CMD_STRING, .offset = OFF(json), .wants = "a file name or -",
      .help = "write every metric as JSON (- : stdout)\n",
      .man = "write every metric as JSON\n"
             ".RB ( \\- :\n"
             "stdout).\n" },
    { "--csv", .metavar = "FILE|-", .kind = CMD_STRING, .offset = OFF(csv), .wants = "a file name or -",
      .help = "write every metric as CSV, a header row and a value\n"
              "row (- : stdout); with either on stdout the table\n"
              "goes to stderr\n",
      .man = "write every metric as CSV, a header row and a value row\n"
             ".RB ( \\- :\n"
             "stdout); with either on stdout the table goes to stderr.\n" },
    { "--buffers", .kind = CMD_FLAG, .offset = OFF(buffers),
      .help = "also compare the reference buffers beside A and B:\n"
              "for X.exr, X.refract_hit.exr, X.reflect.exr and\n"
              "X.surface.exr (hit points: distance in world units;\n"
              "a 4th channel is what the ray met), X.fresnel.exr,\n"
              "X.depth.exr and X.irradiance.exr (scalars: absolute\n"
              "and relative error), each pair that exists on both\n"
              "sides; with --out, one heat map per buffer too\n"
              "(HEATMAP.NAME.png)\n",
      .man = "also compare the reference buffers beside\n"
             ".I A\n"
             "and\n"
             ".IR B :\n"
             "for\n"
             ".IR X.exr ,\n"
             ".IR X.refract_hit.exr ,\n"
             ".I X.reflect.exr\n"
             "and\n"
             ".I X.surface.exr\n"
             "(hit points: distance in world units; a 4th channel is what the ray met),\n"
             ".IR X.fresnel.exr ,\n"
             ".I X.depth.exr\n"
             "and\n"
             ".I X.irradiance.exr\n"
             "(scalars: absolute and relative error), each pair that exists on both sides;\n"
             "with\n"
             ".BR \\-\\-out ,\n"
             "one heat map per buffer too\n"
             ".RI ( HEATMAP.NAME.png ).\n" },
    { "--texel", .metavar = "W", POSITIVE, .offset = OFF(texel), .wants = "world units per texel > 0, e.g. 0.05",
      .help = "world units per texel: hit-point errors in texels too\n",
      .man = "world units per texel: hit\\-point errors in texels too.\n" },
    { "--linear", .kind = CMD_FLAG, .offset = OFF(linear),
      .help = "take every input as linear (no sRGB decoding)\n",
      .man = "take every input as linear (no sRGB decoding).\n" },
    { 0 }
};

const cmd_spec cmd_compare_spec = {
    .name = "compare",
    .synopsis = "A B [--out HEATMAP.png] [--threshold T] [--max E]\n"
                "    [--mask M] [--json FILE|-] [--csv FILE|-]\n"
                "    [--flip-map MAP.png] [--buffers] [--texel W]\n"
                "    [--linear]\n",
    .about = "Measures the error of image A (under test) against image B (the reference),\n"
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
             "objects: the world, which should agree), then the whole frame.\n",
    .options = options,
    .notes = "exit codes: 0 compared, 1 a file could not be read, compared or written,\n"
             "2 bad usage\n",
    .column = 21,
    .extra = "two images at a time",
};

CMD_USAGE_FUNCTION(cmd_compare_usage, cmd_compare_spec)

static int parse(int argc, char **argv, compare_desc *o, FILE *err) {
    int rc = cmd_parse(&cmd_compare_spec, argc, argv, o, err);
    if (rc == TARN_EXIT_OK && o->json && o->csv && strcmp(o->json, "-") == 0 && strcmp(o->csv, "-") == 0)
        rc = cmd_bad_usage(&cmd_compare_spec, err, "--json - and --csv - cannot both go to stdout");
    return rc;
}

int cmd_compare_io(int argc, char **argv, FILE *out, FILE *err) {
    if (cmd_wants_help(argc, argv)) { fputs(cmd_compare_usage(), out); return TARN_EXIT_OK; }
    compare_desc d = {0};
    int rc = parse(argc, argv, &d, err);
    return rc == TARN_EXIT_OK ? compare_run(&d, out, err) : rc;
}

int cmd_compare(int argc, char **argv) { return cmd_compare_io(argc, argv, stdout, stderr); }
