/* cmd_sheet: `tarn sheet SCENE.glib --vary P.U=a:b:n [--vary ...] -o
 * sheet.png`, the hand-in sheet of the course's projects ("side-by-side
 * images at different parameter values", issue #27): the scene rendered
 * headless at each value of one uniform (a row) or two (a grid), each tile
 * anti-aliased and labelled with its values in a built-in pixel font (as
 * glman's capture wrote the variables onto the image), in one image. */
#include <GL/gl.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmd.h"
#include "gl_ctx.h"
#include "image_io.h"
#include "mem.h"
#include "packset.h"
#include "plot.h"
#include "ref_metrics.h"
#include "render.h"
#include "render_setting.h"
#include "strbuf.h"
#include "util.h"

#define SHEET_MAX_VARY 2
#define SHEET_MAX_N 64            /* values of one --vary */
#define SHEET_MAX_TILES 256
#define SHEET_MAX_PIXELS (64L << 20)   /* the whole sheet: what a typo in --size can cost */
#define SHEET_DEFAULT_TILE_W 400  /* a WindowSize wider than this is scaled down for a tile */
#define SHEET_GAP 8

typedef struct sheet_vary {
    char name[128];               /* PROGRAM.NAME or NAME, as --set takes it */
    double a, b;
    int n;
} sheet_vary;

typedef struct sheet_desc {
    const char *glib, *out;
    sheet_vary vary[SHEET_MAX_VARY];
    int nvary;
    const char **sets;            /* --set, applied before the varied values */
    int nsets;
    int width, height;            /* a tile; 0: from the glib's WindowSize */
    double time_s;
    int samples;
    bool quiet;
    const char *pack;             /* --pack: replaces the scene's Pack */
} sheet_desc;

static double vary_value(const sheet_vary *v, int i) {
    return v->n <= 1 ? v->a : v->a + (v->b - v->a) * i / (v->n - 1);
}

/* "%g" with few digits, and no "-0". */
static void fmt_value(char *buf, size_t len, double x) {
    if (fabs(x) < 1e-12) x = 0;
    snprintf(buf, len, "%.4g", x);
}

static void blit_tile(img *sheet, const float *rgba, int w, int h, int x0, int y0, bool encode_srgb) {
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const float *s = rgba + ((size_t)y * w + x) * 4;
            float *d = sheet->px + ((size_t)(y0 + y) * sheet->w + (x0 + x)) * 3;
            for (int k = 0; k < 3; k++) {
                double c = encode_srgb ? ref_linear_to_srgb(s[k]) : s[k];
                d[k] = (float)(c < 0 ? 0 : c > 1 ? 1 : c);
            }
        }
}

static int sheet_run(const sheet_desc *d) {
    char err[MSG_MAX];
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    if (!ctx) { fprintf(stderr, "tarn: %s\n", err); return TARN_EXIT_NO_GL; }
    int samples = d->samples > 0 ? d->samples : CMD_MSAA_STILL_DEFAULT;
    render *r = render_create(&(render_desc){ .samples = samples, .pack = d->pack });
    bool ok = render_load(r, d->glib);
    if (!d->quiet || !ok) fputs(render_messages(r), stderr);
    int rc = ok ? TARN_EXIT_OK : TARN_EXIT_INPUT;
    for (int i = 0; i < d->nsets; i++)
        if (!cmd_apply_set(r, d->sets[i], "--set")) rc = TARN_EXIT_INPUT;
    int w = d->width, h = d->height;
    if (w <= 0 || h <= 0) {
        render_window_size(r, &w, &h);
        if (w > SHEET_DEFAULT_TILE_W) { h = (int)lround((double)h * SHEET_DEFAULT_TILE_W / w); w = SHEET_DEFAULT_TILE_W; }
        if (h < 1) h = 1;
    }
    int cols = d->vary[0].n, rows = d->nvary > 1 ? d->vary[1].n : 1;
    /* a label line a varied uniform, in the font at scale 2 where it fits the tile */
    int scale = 2;
    bool short_names = false;     /* "uFreq = 5" without its "Stripes." where the tile is narrow */
    for (int i = 0; i < d->nvary; i++) {
        char probe[256];
        snprintf(probe, sizeof probe, "%s = -0.000", d->vary[i].name);
        if (plot_text_width(probe, 2) > w) scale = 1;
        if (plot_text_width(probe, 1) > w) short_names = true;
    }
    int max_chars = (w - 2) / (PLOT_GLYPH_W * scale);
    int line_h = PLOT_GLYPH_H * scale + 2;
    int label_h = d->nvary * line_h + 6;
    int head_h = PLOT_GLYPH_H * 2 + 12;
    long sw = (long)cols * (w + SHEET_GAP) + SHEET_GAP;
    long sh = head_h + (long)rows * (h + label_h + SHEET_GAP) + SHEET_GAP;
    img sheet;
    memset(&sheet, 0, sizeof sheet);
    render_target t;
    bool have_target = false;
    float *rgba = NULL;
    if (sw * sh > SHEET_MAX_PIXELS || !gl_ctx_frame_fits(w, h, 16 + 4 + 16 + samples * 20.0, err, sizeof err)) {
        fprintf(stderr, "tarn: sheet: %ldx%ld pixels of %dx%d tiles: %s\n", sw, sh, w, h,
                sw * sh > SHEET_MAX_PIXELS ? "too large (choose a smaller --size)" : err);
        rc = TARN_EXIT_USAGE;
        goto done;
    }
    bool linear_scene = render_has_world(r);
    if (!img_alloc(&sheet, (int)sw, (int)sh, 3) || !(have_target = render_target_create(&t, w, h, linear_scene))) {
        fprintf(stderr, "tarn: cannot make a %dx%d framebuffer and a %ldx%ld sheet\n", w, h, sw, sh);
        rc = TARN_EXIT_NO_GL;
        goto done;
    }
    const float paper[3] = {1, 1, 1}, ink[3] = {0, 0, 0}, grey[3] = {0.35f, 0.35f, 0.35f};
    plot_fill(&sheet, paper);
    {
        const char *base = strrchr(d->glib, '/');
        char head[512];
        snprintf(head, sizeof head, "%s   t = %.3g s", base ? base + 1 : d->glib, d->time_s);
        plot_text(&sheet, SHEET_GAP, 6, head, 2, grey);
    }
    rgba = mem_alloc((size_t)w * h * 4 * sizeof *rgba);
    for (int j = 0; j < rows && rc != TARN_EXIT_NO_GL; j++)
        for (int i = 0; i < cols; i++) {
            char labels[SHEET_MAX_VARY][256];
            for (int k = 0; k < d->nvary; k++) {
                char set[256], num[64];
                double v = vary_value(&d->vary[k], k == 0 ? i : j);
                fmt_value(num, sizeof num, v);
                snprintf(set, sizeof set, "%s=%.9g", d->vary[k].name, v);
                const char *shown = d->vary[k].name, *dot = strrchr(shown, '.');
                if (short_names && dot) shown = dot + 1;
                snprintf(labels[k], sizeof labels[k], "%s = %s", shown, num);
                if (max_chars >= 1 && (int)strlen(labels[k]) > max_chars) labels[k][max_chars] = '\0';
                if (!cmd_apply_set(r, set, "--vary")) {
                    /* a value the scene does not take (a missing uniform, clamped to
                     * its slider): every tile after it would be labelled wrong */
                    rc = TARN_EXIT_USAGE;
                    goto done;
                }
            }
            render_frame(r, d->time_s, t.fbo, w, h, NULL);
            glFinish();
            if (gl_ctx_lost(ctx, err, sizeof err) || !render_target_read(&t, rgba)) {
                fprintf(stderr, "tarn: %s\n", err[0] ? err : "reading the framebuffer failed");
                rc = TARN_EXIT_NO_GL;
                break;
            }
            int x0 = SHEET_GAP + i * (w + SHEET_GAP), y0 = head_h + j * (h + label_h + SHEET_GAP);
            blit_tile(&sheet, rgba, w, h, x0, y0, linear_scene);
            for (int k = 0; k < d->nvary; k++)
                plot_text(&sheet, x0 + 2, y0 + h + 4 + k * line_h, labels[k], scale, ink);
        }
    if (render_draw_messages(r)[0]) {
        fputs(render_draw_messages(r), stderr);
        if (rc == TARN_EXIT_OK && render_has_errors(r)) rc = TARN_EXIT_INPUT;
    }
    if (rc != TARN_EXIT_NO_GL) {
        if (!img_write(d->out, &sheet, err, sizeof err)) {
            fprintf(stderr, "tarn: %s\n", err);
            rc = TARN_EXIT_INPUT;
        } else if (!d->quiet) {
            printf("tarn: wrote %s (%d x %d tiles of %dx%d, %ldx%ld, t=%.3f s)\n", d->out, cols, rows, w, h, sw,
                   sh, d->time_s);
        }
    }
done:
    free(rgba);
    img_free(&sheet);
    if (have_target) render_target_destroy(&t);
    render_destroy(r);
    gl_ctx_destroy(ctx);
    return rc;
}

/* ---- the command line ---- */

/* "NAME=A:B:N" */
static bool parse_vary(const char *s, sheet_vary *v) {
    const char *eq = s ? strrchr(s, '=') : NULL;
    if (!eq || eq == s || (size_t)(eq - s) >= sizeof v->name) return false;
    memcpy(v->name, s, (size_t)(eq - s));
    v->name[eq - s] = '\0';
    char buf[256];
    snprintf(buf, sizeof buf, "%s", eq + 1);
    char *c1 = strchr(buf, ':'), *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
    if (!c1 || !c2 || strchr(c2 + 1, ':')) return false;
    *c1 = *c2 = '\0';
    int n = 0;
    if (!opt_double(buf, &v->a) || !opt_double(c1 + 1, &v->b) || !cmd_opt_int(c2 + 1, 1, SHEET_MAX_N, &n))
        return false;
    v->n = n;
    return isfinite(v->a) && isfinite(v->b);
}

/* --vary: one more varied uniform, at most SHEET_MAX_VARY. */
static bool set_vary(void *desc, const char *value, char *why, size_t whylen) {
    sheet_desc *d = desc;
    if (d->nvary == SHEET_MAX_VARY) {
        snprintf(why, whylen, "at most two --vary: a row, or a grid");
        return false;
    }
    if (!parse_vary(value, &d->vary[d->nvary])) return false;
    d->nvary++;
    return true;
}

#define OFF(field) offsetof(sheet_desc, field)

static const cmd_option options[] = {
    { "FILE.glib", .kind = CMD_ARG, .offset = OFF(glib), .missing = "which scene? give FILE.glib" },
    { "--vary", .metavar = "P.NAME=A:B:N", .kind = CMD_CUSTOM, .set = set_vary,
      .wants = "PROGRAM.NAME=A:B:N, e.g. Stripes.uFreq=1:10:5 (N 1..64)",
      .missing = "what to vary? give --vary PROGRAM.NAME=A:B:N",
      .help = "the uniform NAME of Program P (NAME=...: of every\n"
              "Program), set as --set and the panel set it; N 1..64,\n"
              "at most 256 tiles\n",
      .man = "the uniform\n"
             ".I NAME\n"
             "of\n"
             ".B Program\n"
             ".I P\n"
             ".RI ( NAME =...:\n"
             "of every\n"
             ".BR Program ),\n"
             "set for each tile as\n"
             ".B \\-\\-set\n"
             "and the panel set it;\n"
             ".I N\n"
             "1 to 64, at most 256 tiles.\n"
             "A value the scene does not take (no such uniform, or outside its slider's\n"
             "range, which would be clamped) stops the sheet with exit status 2: its labels\n"
             "would be wrong.\n" },
    { "--out", "-o", "OUT", .kind = CMD_STRING, .offset = OFF(out),
      .help = "the sheet: .png (default sheet.png), .jpg, any 8-bit format\n",
      .man = "the sheet:\n"
             ".I .png\n"
             "(default\n"
             ".IR sheet.png ),\n"
             ".IR .jpg ,\n"
             "any 8\\-bit format OpenImageIO writes.\n" },
    { "--size", .metavar = "WxH", .kind = CMD_SIZE, .offset = OFF(width), .offset2 = OFF(height),
      .wants = "WxH, e.g. 320x240",
      .help = "each tile's size (default: the glib's WindowSize, scaled\n"
              "down to 400 pixels wide)\n",
      .man = "each tile's size (default: the glib's\n"
             ".BR WindowSize ,\n"
             "scaled down to 400 pixels wide).\n" },
    { "--time", .metavar = "SECONDS", .kind = CMD_DOUBLE, .offset = OFF(time_s), .wants = "seconds, e.g. 2.5",
      .help = "simulated time of every tile (default 0)\n",
      .man = "simulated time of every tile (default 0).\n" },
    CMD_OPTION_PACK(OFF(pack)),
    { "--set", .metavar = "P.NAME=V", .kind = CMD_LIST, .offset = OFF(sets), .offset2 = OFF(nsets),
      .help = "set a slider, checkbox, colour or Define first, as in\n"
              "tarn render; repeatable\n",
      .man = "set a slider, checkbox, colour or\n"
             ".B Define\n"
             "before the varied values, as in\n"
             ".BR \"tarn render\" ;\n"
             "repeatable.\n" },
    CMD_OPTION_MSAA_STILL(OFF(samples)),
    { "--quiet", .kind = CMD_FLAG, .offset = OFF(quiet),
      .help = "print only warnings and errors\n",
      .man = "print the load's messages only when it has errors.\n" },
    { 0 }
};

const cmd_spec cmd_sheet_spec = {
    .name = "sheet",
    .synopsis = "FILE.glib --vary PROGRAM.NAME=A:B:N [--vary PROGRAM.NAME=A:B:N] [-o OUT]\n"
                "[--size WxH] [--time SECONDS] [--pack NAME] [--set PROGRAM.NAME=VALUE]... [--msaa N]\n",
    .about = "A hand-in sheet: renders the scene (headless, as tarn render) once for each\n"
             "value of a uniform, N values from A to B evenly (N = 1: A), side by side in\n"
             "one image, each tile labelled with its values. A second --vary makes a grid:\n"
             "the first varies along a row, the second down the columns.\n",
    .options = options,
    .notes = "In tarn view, a slider's right-click menu makes the same sheet of it (5 values\n"
             "over its range, every other value as the window has it).\n"
             "\n"
             "A value the scene does not take (no such uniform, or outside its slider's\n"
             "range, which would be clamped) stops the sheet: its labels would be wrong.\n"
             "\n"
             "exit codes: 0 ok, 1 the scene or a shader has errors, 2 bad usage, 3 no OpenGL\n",
    .extra = "one scene at a time",
};

CMD_USAGE_FUNCTION(cmd_sheet_usage, cmd_sheet_spec)

int cmd_sheet(int argc, char **argv) {
    if (cmd_wants_help(argc, argv)) { fputs(cmd_sheet_usage(), stdout); return TARN_EXIT_OK; }
    const char **sets = mem_zalloc(((size_t)argc + 1) * sizeof *sets);   /* every --set kept */
    sheet_desc d = { .sets = sets, .out = "sheet.png" };
    int rc = cmd_parse(&cmd_sheet_spec, argc, argv, &d, stderr);
    if (rc == TARN_EXIT_OK && d.vary[0].n * (d.nvary > 1 ? d.vary[1].n : 1) > SHEET_MAX_TILES)
        rc = cmd_bad_usage(&cmd_sheet_spec, stderr, "more than 256 tiles");
    if (rc == TARN_EXIT_OK) rc = sheet_run(&d);
    free(sets);
    return rc;
}
