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

/* Where things go on the sheet: each tile's size and labels, the heading. */
typedef struct sheet_layout {
    int w, h;                     /* a tile */
    int cols, rows;
    int scale;                    /* the labels' font scale: 2 where a label fits the tile */
    bool short_names;             /* "uFreq = 5" without its "Stripes." where the tile is narrow */
    int max_chars, line_h, label_h, head_h;
    long sw, sh;                  /* the sheet */
} sheet_layout;

static sheet_layout sheet_lay_out(const sheet_desc *d, render *r) {
    sheet_layout L = { .w = d->width, .h = d->height, .scale = 2 };
    if (L.w <= 0 || L.h <= 0) {
        render_window_size(r, &L.w, &L.h);
        if (L.w > SHEET_DEFAULT_TILE_W) {
            L.h = (int)lround((double)L.h * SHEET_DEFAULT_TILE_W / L.w);
            L.w = SHEET_DEFAULT_TILE_W;
        }
        if (L.h < 1) L.h = 1;
    }
    L.cols = d->vary[0].n;
    L.rows = d->nvary > 1 ? d->vary[1].n : 1;
    /* a label line a varied uniform, in the font at scale 2 where it fits the tile */
    for (int i = 0; i < d->nvary; i++) {
        char probe[256];
        snprintf(probe, sizeof probe, "%s = -0.000", d->vary[i].name);
        if (plot_text_width(probe, 2) > L.w) L.scale = 1;
        if (plot_text_width(probe, 1) > L.w) L.short_names = true;
    }
    L.max_chars = (L.w - 2) / (PLOT_GLYPH_W * L.scale);
    L.line_h = PLOT_GLYPH_H * L.scale + 2;
    L.label_h = d->nvary * L.line_h + 6;
    L.head_h = PLOT_GLYPH_H * 2 + 12;
    L.sw = (long)L.cols * (L.w + SHEET_GAP) + SHEET_GAP;
    L.sh = L.head_h + (long)L.rows * (L.h + L.label_h + SHEET_GAP) + SHEET_GAP;
    return L;
}

/* Tile (i, j)'s values set in the scene and written as its labels; false
 * (having said why) where the scene does not take one. */
static bool sheet_set_tile(const sheet_desc *d, const sheet_layout *L, render *r, int i, int j,
                           char labels[SHEET_MAX_VARY][256]) {
    for (int k = 0; k < d->nvary; k++) {
        char set[256], num[64];
        double v = vary_value(&d->vary[k], k == 0 ? i : j);
        fmt_value(num, sizeof num, v);
        snprintf(set, sizeof set, "%s=%.9g", d->vary[k].name, v);
        const char *shown = d->vary[k].name, *dot = strrchr(shown, '.');
        if (L->short_names && dot) shown = dot + 1;
        snprintf(labels[k], sizeof labels[k], "%s = %s", shown, num);
        if (L->max_chars >= 1 && (int)strlen(labels[k]) > L->max_chars) labels[k][L->max_chars] = '\0';
        /* a value the scene does not take (a missing uniform, clamped to its
         * slider): every tile after it would be labelled wrong */
        if (!cmd_apply_set(r, set, "--vary")) return false;
    }
    return true;
}

/* What a sheet is drawn with: the context, the scene, one tile's target
 * and pixels, the sheet itself. */
typedef struct sheet_run_ctx {
    const sheet_desc *d;
    int samples;                  /* --msaa, or the still default */
    gl_ctx *ctx;
    render *r;
    sheet_layout L;
    render_target t;
    bool have_target, linear_scene;
    float *rgba;
    img sheet;
} sheet_run_ctx;

/* Every tile drawn onto the sheet with its labels; the exit code so far
 * (rc) or what stopped it. */
static int sheet_draw_tiles(sheet_run_ctx *s, int rc) {
    const sheet_desc *d = s->d;
    const sheet_layout *L = &s->L;
    char err[MSG_MAX] = "";
    const float ink[3] = {0, 0, 0};
    for (int j = 0; j < L->rows; j++)
        for (int i = 0; i < L->cols; i++) {
            char labels[SHEET_MAX_VARY][256];
            if (!sheet_set_tile(d, L, s->r, i, j, labels)) return TARN_EXIT_USAGE;
            render_frame(s->r, d->time_s, s->t.fbo, L->w, L->h, NULL);
            glFinish();
            if (gl_ctx_lost(s->ctx, err, sizeof err) || !render_target_read(&s->t, s->rgba)) {
                fprintf(stderr, "tarn: %s\n", err[0] ? err : "reading the framebuffer failed");
                return TARN_EXIT_NO_GL;
            }
            int x0 = SHEET_GAP + i * (L->w + SHEET_GAP), y0 = L->head_h + j * (L->h + L->label_h + SHEET_GAP);
            blit_tile(&s->sheet, s->rgba, L->w, L->h, x0, y0, s->linear_scene);
            for (int k = 0; k < d->nvary; k++)
                plot_text(&s->sheet, x0 + 2, y0 + L->h + 4 + k * L->line_h, labels[k], L->scale, ink);
        }
    return rc;
}

/* The sheet and its target made, its heading drawn, then its tiles; the
 * draw's messages, and the image written. */
static int sheet_make(sheet_run_ctx *s, int rc) {
    const sheet_desc *d = s->d;
    const sheet_layout *L = &s->L;
    char err[MSG_MAX];
    if (L->sw * L->sh > SHEET_MAX_PIXELS ||
        !gl_ctx_frame_fits(L->w, L->h, 16 + 4 + 16 + s->samples * 20.0, err, sizeof err)) {
        fprintf(stderr, "tarn: sheet: %ldx%ld pixels of %dx%d tiles: %s\n", L->sw, L->sh, L->w, L->h,
                L->sw * L->sh > SHEET_MAX_PIXELS ? "too large (choose a smaller --size)" : err);
        return TARN_EXIT_USAGE;
    }
    s->linear_scene = render_has_world(s->r);
    if (!img_alloc(&s->sheet, (int)L->sw, (int)L->sh, 3) ||
        !(s->have_target = render_target_create(&s->t, L->w, L->h, s->linear_scene))) {
        fprintf(stderr, "tarn: cannot make a %dx%d framebuffer and a %ldx%ld sheet\n", L->w, L->h, L->sw, L->sh);
        return TARN_EXIT_NO_GL;
    }
    const float paper[3] = {1, 1, 1}, grey[3] = {0.35f, 0.35f, 0.35f};
    plot_fill(&s->sheet, paper);
    const char *base = strrchr(d->glib, '/');
    char head[512];
    snprintf(head, sizeof head, "%s   t = %.3g s", base ? base + 1 : d->glib, d->time_s);
    plot_text(&s->sheet, SHEET_GAP, 6, head, 2, grey);
    s->rgba = mem_alloc((size_t)L->w * L->h * 4 * sizeof *s->rgba);
    rc = sheet_draw_tiles(s, rc);
    if (rc == TARN_EXIT_USAGE) return rc;
    if (render_draw_messages(s->r)[0]) {
        fputs(render_draw_messages(s->r), stderr);
        if (rc == TARN_EXIT_OK && render_has_errors(s->r)) rc = TARN_EXIT_INPUT;
    }
    if (rc == TARN_EXIT_NO_GL) return rc;
    if (!img_write(d->out, &s->sheet, err, sizeof err)) {
        fprintf(stderr, "tarn: %s\n", err);
        return TARN_EXIT_INPUT;
    }
    if (!d->quiet)
        printf("tarn: wrote %s (%d x %d tiles of %dx%d, %ldx%ld, t=%.3f s)\n", d->out, L->cols, L->rows, L->w, L->h,
               L->sw, L->sh, d->time_s);
    return rc;
}

static int sheet_run(const sheet_desc *d) {
    char err[MSG_MAX];
    sheet_run_ctx s = { .d = d, .samples = d->samples > 0 ? d->samples : CMD_MSAA_STILL_DEFAULT };
    s.ctx = gl_ctx_create_headless(err, sizeof err);
    if (!s.ctx) { fprintf(stderr, "tarn: %s\n", err); return TARN_EXIT_NO_GL; }
    s.r = render_create(&(render_desc){ .samples = s.samples, .pack = d->pack });
    bool ok = render_load(s.r, d->glib);
    if (!d->quiet || !ok) fputs(render_messages(s.r), stderr);
    int rc = ok ? TARN_EXIT_OK : TARN_EXIT_INPUT;
    for (int i = 0; i < d->nsets; i++)
        if (!cmd_apply_set(s.r, d->sets[i], "--set")) rc = TARN_EXIT_INPUT;
    s.L = sheet_lay_out(d, s.r);
    rc = sheet_make(&s, rc);
    free(s.rgba);
    img_free(&s.sheet);
    if (s.have_target) render_target_destroy(&s.t);
    render_destroy(s.r);
    gl_ctx_destroy(s.ctx);
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
