/* cmd_render: `tarn render FILE.glib -o OUT`, draws a glib without any
 * display through EGL and writes the image through OpenImageIO.
 * Deterministic for a fixed --time. */
#include <GL/gl.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "mem.h"
#include "strbuf.h"
#include "util.h"
#include "cli.h"
#include "cmd.h"
#include "gl_ctx.h"
#include "glib.h"
#include "image_io.h"
#include "packset.h"
#include "ref_metrics.h"
#include "render.h"
#include "render_setting.h"

const char *cli_default_scene(void) {
    static char path[4096];
    snprintf(path, sizeof path, "%s/scenes/showcase.glib", tarn_root());
    return path;
}

const char *cli_default_pack(void) {
    static char pack[64];
    glib_scene *g = glib_load(cli_default_scene());
    snprintf(pack, sizeof pack, "?");
    for (int i = 0; i < g->ncmds; i++)
        if (g->cmds[i].kind == GLIB_CMD_PACK) snprintf(pack, sizeof pack, "%s", g->cmds[i].name);
    glib_free(g);
    return pack;
}

static bool wants_float(const char *path) {
    const char *dot = strrchr(path, '.');
    return dot && (strcmp(dot, ".exr") == 0 || strcmp(dot, ".hdr") == 0 || strcmp(dot, ".tif") == 0);
}

/* A scene with a world is lit in linear radiance (as the reference): float
 * files keep it linear, 8-bit ones get the sRGB encoding a display expects
 * (like the reference's PNG). A plain glman scene is written as drawn. */
static bool write_target(const render_target *t, const char *path, bool encode_srgb, char *err, int errlen) {
    img im;
    memset(&im, 0, sizeof im);
    if (!img_alloc(&im, t->w, t->h, 4)) { snprintf(err, errlen, "out of memory"); return false; }
    bool ok = render_target_read(t, im.px);
    if (!ok) snprintf(err, errlen, "reading the framebuffer failed");
    if (ok && encode_srgb && !wants_float(path))
        for (long i = 0; i < (long)t->w * t->h; i++)
            for (int k = 0; k < 3; k++) im.px[i * 4 + k] = (float)ref_linear_to_srgb(im.px[i * 4 + k]);
    /* 32-bit float .exr, as the help says and as the reference writes: a
     * half's 11 bits quantise hit-point buffers to 4-8 mm at the lake's
     * coordinates, coarser than the errors worth measuring */
    if (ok) ok = img_write_float(path, &im, err, errlen);
    img_free(&im);
    return ok;
}

/* out with its first "%d" replaced by the frame number (frame < 0: as is). */
static void frame_path(char *path, size_t len, const char *out, int frame) {
    const char *pct = frame >= 0 ? strstr(out, "%d") : NULL;
    if (!pct) { snprintf(path, len, "%s", out); return; }
    snprintf(path, len, "%.*s%04d%s", (int)(pct - out), out, frame, pct + 2);
}

/* --setting first (the pack's row, from its defaults), then each --set on top. */
static bool apply_sets(render *r, const cli_render_desc *d) {
    bool ok = true;
    if (d->setting) {
        char err[MSG_MAX] = "";
        ok = render_setting_apply_named(r, NULL, d->setting, err, sizeof err);
        if (err[0]) fprintf(stderr, "tarn: --setting: %s%s", err, err[strlen(err) - 1] == '\n' ? "" : "\n");
    }
    for (int i = 0; i < d->nsets; i++) ok = cmd_apply_set(r, d->sets[i], "--set") && ok;
    return ok;
}

/* The load's messages; --quiet keeps the warnings and errors (a pack's
 * notes, such as uniforms its Defines compile out, are for the panel). */
static void print_load_messages(render *r, bool quiet) {
    if (!quiet) {
        fputs(render_messages(r), stderr);
        return;
    }
    const diag_list *l = render_diags(r);
    for (int i = 0; i < l->n; i++) {
        if (l->d[i].severity < DIAG_WARNING) continue;
        char line[DIAG_FILE_MAX + DIAG_TEXT_MAX + 64];
        diag_format(&l->d[i], line, sizeof line);
        fprintf(stderr, "%s\n", line);
    }
}

/* Frame f's simulated time: 1/60 s apart, or all at --time with --still. */
static double frame_time(const cli_render_desc *d, int f) {
    return d->time_s + (d->still ? 0.0 : f / 60.0);
}

/* --passes: each named pass's GPU times over the frames (a pass a frame
 * runs twice adds up under its name), then their medians. */
typedef struct pass_table {
    int n;
    char name[GPU_TIMER_MARKS][GPU_TIMER_NAME];
    double *ms[GPU_TIMER_MARKS];
    int count[GPU_TIMER_MARKS];
} pass_table;

static int pass_index(pass_table *p, const char *name, int frames) {
    for (int k = 0; k < p->n; k++)
        if (strcmp(p->name[k], name) == 0) return k;
    if (p->n >= GPU_TIMER_MARKS) return -1;
    snprintf(p->name[p->n], GPU_TIMER_NAME, "%s", name);
    p->ms[p->n] = mem_zalloc((size_t)frames * sizeof(double));
    return p->n++;
}

static void pass_table_add(pass_table *p, render *r, int frames) {
    const char (*names)[GPU_TIMER_NAME];
    const double *t;
    int n = render_pass_times(r, true, &names, &t);
    double frame[GPU_TIMER_MARKS] = { 0 };
    bool seen[GPU_TIMER_MARKS] = { false };
    for (int i = 0; i < n; i++) {
        int k = pass_index(p, names[i], frames);
        if (k < 0 || t[i] < 0) continue;
        frame[k] += t[i];
        seen[k] = true;
    }
    for (int k = 0; k < p->n; k++)
        if (seen[k] && p->count[k] < frames) p->ms[k][p->count[k]++] = frame[k];
}

static void pass_table_print(pass_table *p) {
    printf("tarn: median GPU time a frame, per pass:\n");
    for (int k = 0; k < p->n; k++) {
        qsort(p->ms[k], (size_t)p->count[k], sizeof(double), cmp_double);
        printf("  %-28s %9.3f ms  (%d frame%s)\n", p->name[k], p->count[k] ? p->ms[k][p->count[k] / 2] : 0.0,
               p->count[k], p->count[k] == 1 ? "" : "s");
    }
}

static void pass_table_free(pass_table *p) {
    for (int k = 0; k < p->n; k++) free(p->ms[k]);
}

int cli_render(const cli_render_desc *d) {
    char err[MSG_MAX];
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    if (!ctx) { fprintf(stderr, "tarn: %s\n", err); return TARN_EXIT_NO_GL; }
    int samples = d->samples > 0 ? d->samples : CMD_MSAA_STILL_DEFAULT;   /* a kept image: anti-aliased */
    render_desc rd = { .pack = d->pack, .samples = samples, .verbose = d->verbose };
    render *r = render_create(&rd);
    bool ok = render_load(r, d->glib);
    print_load_messages(r, d->quiet);
    if (!apply_sets(r, d)) ok = false;
    int w = d->width, h = d->height;
    if (w <= 0 || h <= 0) render_window_size(r, &w, &h);
    render_target t;
    bool linear_scene = render_has_world(r);
    /* colour and depth, the multisampled ones (else the deferred water's
     * G-buffer, two RGBA32F for the packs), the image read back */
    double bytes = 16 + 4 + 16 + (samples > 1 ? samples * 20.0 : 32.0);
    if (!gl_ctx_frame_fits(w, h, bytes, err, sizeof err)) {
        fprintf(stderr, "tarn: %s: %s\n", d->glib, err);
        render_destroy(r);
        gl_ctx_destroy(ctx);
        return TARN_EXIT_USAGE;
    }
    if (!render_target_create(&t, w, h, wants_float(d->out) || linear_scene)) {
        fprintf(stderr, "tarn: cannot create a %dx%d framebuffer\n", w, h);
        render_destroy(r);
        gl_ctx_destroy(ctx);
        return TARN_EXIT_NO_GL;
    }
    int frames = d->frames > 0 ? d->frames : 1;
    pass_table passes = { 0 };
    render_set_draw_timing(r, d->passes);
    render_set_deferred_water(r, !d->grid_water);
    if (d->detail > 0) render_set_detail(r, d->detail);
    double *ms = mem_zalloc((size_t)frames * sizeof *ms);
    double *wall = mem_zalloc((size_t)frames * sizeof *wall);
    bool per_frame = strstr(d->out, "%d") != NULL;
    int rc = ok ? TARN_EXIT_OK : TARN_EXIT_INPUT;
    for (int f = 0; f < frames; f++) {
        double t0 = clock_now_s() * 1e3;
        render_frame(r, frame_time(d, f), t.fbo, w, h, NULL);
        glFinish();   /* wall time of the whole frame, including deferred rasterisation */
        if (gl_ctx_lost(ctx, err, sizeof err)) {   /* a GPU reset: nothing drawn can be trusted */
            fprintf(stderr, "tarn: %s\n", err);
            rc = TARN_EXIT_NO_GL;
            break;
        }
        wall[f] = clock_now_s() * 1e3 - t0;
        ms[f] = render_gpu_ms(r, true);
        if (d->passes) pass_table_add(&passes, r, frames);
        if (per_frame || f == frames - 1) {
            char path[2048];
            frame_path(path, sizeof path, d->out, per_frame ? f : -1);
            if (!write_target(&t, path, linear_scene, err, sizeof err)) {
                fprintf(stderr, "tarn: %s\n", err);
                rc = TARN_EXIT_INPUT;
                break;
            }
            if (!d->quiet && (!per_frame || f == frames - 1))
                printf("tarn: wrote %s (%dx%d, t=%.3f s)\n", path, w, h, frame_time(d, f));
        }
    }
    if (render_draw_messages(r)[0]) {   /* a draw that failed: the picture has the rest */
        fputs(render_draw_messages(r), stderr);
        if (rc == TARN_EXIT_OK && render_has_errors(r)) rc = TARN_EXIT_INPUT;
    }
    if (!d->quiet && rc != TARN_EXIT_NO_GL) {
        qsort(ms, (size_t)frames, sizeof *ms, cmp_double);
        qsort(wall, (size_t)frames, sizeof *wall, cmp_double);
        printf("tarn: %d frame(s) at %dx%d: median GPU time %.3f ms, wall %.3f ms, on %s\n", frames, w, h,
               ms[frames / 2], wall[frames / 2], gl_ctx_describe(ctx));
        if (d->passes) {
            pass_table_print(&passes);
            const char *why = render_deferred_water_why(r);
            if (render_deferred_water_draws(r) > 0)
                printf("tarn: the screen's water deferred (shaded once a pixel) in %ld draw(s)\n",
                       render_deferred_water_draws(r));
            if (why) printf("tarn: the screen's water drawn as a grid: %s\n", why);
        }
    }
    pass_table_free(&passes);
    free(ms);
    free(wall);
    render_target_destroy(&t);
    render_destroy(r);
    gl_ctx_destroy(ctx);
    return rc;
}

/* ---- the command line ---- */

#define OFF(field) offsetof(cli_render_desc, field)

static const cmd_option options[] = {
    { "FILE.glib", .kind = CMD_ARG, .offset = OFF(glib), .missing = "which scene? give FILE.glib" },
    { "--out", "-o", "OUT", .kind = CMD_STRING, .offset = OFF(out), .missing = "where to? give -o OUT.png",
      .help = "output image: .png (8-bit) or .exr (float), any format\n"
              "OpenImageIO writes; a %d in the name writes every frame\n",
      .man = "output image:\n"
             ".I .png\n"
             "(8\\-bit) or\n"
             ".I .exr\n"
             "(float), any format OpenImageIO writes; a\n"
             ".B %d\n"
             "in the name writes every frame.\n" },
    CMD_OPTION_PACK(OFF(pack)),
    { "--size", .metavar = "WxH", .kind = CMD_SIZE, .offset = OFF(width), .offset2 = OFF(height),
      .wants = "WxH, e.g. 640x360",
      .help = "image size (default: the glib's WindowSize)\n",
      .man = "image size (default: the glib's\n"
             ".BR WindowSize ).\n" },
    { "--time", .metavar = "SECONDS", .kind = CMD_DOUBLE, .offset = OFF(time_s), .wants = "seconds, e.g. 2.5",
      .help = "simulated time of the first frame (default 0)\n",
      .man = "simulated time of the first frame (default 0).\n" },
    { "--frames", .metavar = "N", .kind = CMD_INT, .offset = OFF(frames), .lo = 1, .hi = 100000,
      .help = "render N frames, 1/60 s apart; prints the median GPU time\n"
              "and wall time per frame\n",
      .man = "render\n"
             ".I N\n"
             "frames, 1/60 s apart; prints the median GPU time and wall time per frame.\n" },
    { "--still", .kind = CMD_FLAG, .offset = OFF(still),
      .help = "...all N at --time, as a paused window and tarn bench draw\n"
              "them (what does not change is reused: the static-world cache)\n",
      .man = "render the\n"
             ".B \\-\\-frames\n"
             "all at\n"
             ".BR \\-\\-time ,\n"
             "as a paused window and\n"
             ".B tarn bench\n"
             "draw them: what does not change from frame to frame is reused (the\n"
             "static\\-world cache), so the median is a still picture's cost.\n" },
    { "--passes", .kind = CMD_FLAG, .offset = OFF(passes),
      .help = "...and the median GPU time of each pass and of each drawing\n"
              "command (KIND:LINE) over the N frames: where a frame's time goes\n",
      .man = "also print the median GPU time of each pass and of each drawing command\n"
             "(its kind and glib line:\n"
             ".BR World:12 ,\n"
             ".BR WaterSurface:40 ),\n"
             "and of the world's height map: where a frame's time goes. Each mark\n"
             "finishes the work before it (on a CPU rasteriser the time of a draw's\n"
             "pixels otherwise falls in a later draw), so the total is a little more\n"
             "than without.\n" },
    { "--grid-water", .kind = CMD_FLAG, .offset = OFF(grid_water),
      .help = "draw the screen's water as a grid, each triangle shaded, not\n"
              "deferred (one shading a pixel): the same picture but at the\n"
              "water's edge, slower on a CPU rasteriser; for A/B runs\n",
      .man = "draw the screen's water as a grid whose triangles are each shaded, not\n"
             "deferred (a G\\-buffer of the grid, then the pack's fragment shader once a\n"
             "pixel; single\\-sample frames only: with\n"
             ".B \\-\\-msaa 1\n"
             "or 0): the same picture but at the water's edge, slower on a CPU\n"
             "rasteriser, where a block of pixels is shaded for every small triangle\n"
             "that touches it. For A/B runs.\n" },
    { "--detail", .metavar = "D", .kind = CMD_DOUBLE, .offset = OFF(detail), .lo = 0.01, .hi = 1,
      .wants = "a fraction of each side, e.g. 0.5",
      .help = "draw the scene's fixed-size work as the window's reduced frame\n"
              "at D of each side does (targets, photon grids, meshes; 0.01-1,\n"
              "default 1); with --size at D of the full size, its frame's cost\n",
      .man = "draw the scene's fixed\\-size work as the view window's reduced frame\n"
             "at\n"
             ".I D\n"
             "of each side draws it while the picture moves (0.01 to 1, default 1):\n"
             "render targets drawn every frame at a fixed or slider size, photon grids,\n"
             ".B WaterSurface points|mesh N\n"
             "and the terrain and water meshes shrink with it. With\n"
             ".B \\-\\-size\n"
             "at\n"
             ".I D\n"
             "of the full size and\n"
             ".BR \\-\\-frames ,\n"
             "what one of the window's reduced frames costs.\n" },
    { "--setting", .metavar = "NAME", .kind = CMD_STRING, .offset = OFF(setting),
      .help = "start from the pack's setting NAME (a row of packs/PACK/bench.txt:\n"
              "default, paper, ...), as the panel's Setting combo does\n",
      .man = "start from the pack's setting\n"
             ".I NAME\n"
             "(a row of\n"
             ".BI packs/ PACK /bench.txt ,\n"
             "e.g.\n"
             ".BR paper ),\n"
             "applied as the view window's\n"
             ".B Setting\n"
             "combo applies it, before any\n"
             ".BR \\-\\-set .\n" },
    { "--set", .metavar = "P.NAME=V", .kind = CMD_LIST, .offset = OFF(sets), .offset2 = OFF(nsets),
      .help = "set a slider, checkbox, colour (V,V,V) or Define of Program P\n"
              "as the panel would (NAME=V: of every Program); repeatable\n",
      .man = "set a slider, checkbox, colour\n"
             ".RI ( V , V , V )\n"
             "or\n"
             ".B Define\n"
             "of\n"
             ".B Program\n"
             ".I P\n"
             "as the panel would\n"
             ".RI ( NAME = V :\n"
             "of every\n"
             ".BR Program ;\n"
             ".BI scene. Command = ARGS :\n"
             "a world command the renderer takes at run time,\n"
             ".BR WaterMesh );\n"
             "repeatable.\n" },
    CMD_OPTION_MSAA_STILL(OFF(samples)),
    { "--quiet", .kind = CMD_FLAG, .offset = OFF(quiet),
      .help = "print only warnings and errors\n",
      .man = "print only warnings and errors (not notes, such as the uniforms a pack's Defines compile out).\n" },
    CMD_OPTION_VERBOSE(OFF(verbose)),
    { 0 }
};

const cmd_spec cmd_render_spec = {
    .name = "render",
    .synopsis = "FILE.glib -o OUT [--pack NAME] [--size WxH] [--time SECONDS] [--frames N]\n"
                "[--still] [--passes] [--grid-water] [--detail D] [--setting NAME] [--set PROGRAM.NAME=VALUE]...\n"
                "[--msaa N] [--quiet | --verbose]\n",
    .about = "Renders without any display through EGL (works with DISPLAY unset, on Mesa\n"
             "llvmpipe or a GPU). The image is deterministic for a fixed --time.\n",
    .options = options,
    .notes = "exit codes: 0 ok, 1 the scene or a shader has errors, 2 bad usage, 3 no OpenGL\n",
    .extra = "one scene at a time",
};

CMD_USAGE_FUNCTION(cmd_render_usage, cmd_render_spec)

int cmd_render(int argc, char **argv) {
    if (cmd_wants_help(argc, argv)) { fputs(cmd_render_usage(), stdout); return TARN_EXIT_OK; }
    const char **sets = mem_zalloc(((size_t)argc + 1) * sizeof *sets);   /* every --set kept */
    cli_render_desc d = { .sets = sets };
    int rc = cmd_parse(&cmd_render_spec, argc, argv, &d, stderr);
    if (rc == TARN_EXIT_OK) rc = cli_render(&d);
    free(sets);
    return rc;
}
