/* tarn: a live lab for real-time water shaders. The command line. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util.h"
#include "assets.h"
#include "bench.h"
#include "cli.h"
#include "cli_reference.h"
#include "compare.h"
#include "compare_view.h"
#include "view.h"
#include "gl_ctx.h"
#include "validate.h"

static const char *usage_main =
    "usage: tarn [COMMAND] [ARGS]\n"
    "\n"
    "A live lab for real-time water shaders: watches glman-style .glib scenes\n"
    "and hot-reloads their GLSL, with a slider for every uniform.\n"
    "\n"
    "commands:\n"
    "  view FILE.glib       open a window; edits to any file the scene reads reload it\n"
    "  render FILE.glib     render without a display (EGL) to an image\n"
    "  validate [PATH...]   check every shader of every pack with glslang\n"
    "  reference FILE.glib  the CPU ground truth: image and per-pixel buffers (double precision)\n"
    "  compare A B          error of image A against reference B: RMSE, PSNR, heat map, JSON/CSV\n"
    "  assets [--out DIR]   write the generated textures (terrain, sky, normal maps, foam, caustics)\n"
    "  help [COMMAND]       this text, or a command's options\n"
    "\n"
    "With no command, tarn opens the default scene (scenes/pond.glib) in a window,\n"
    "or, when there is no display, renders it to out/default.png.\n"
    "`tarn COMMAND --help` lists a command's options.\n";

static const char *usage_view =
    "usage: tarn view FILE.glib [--pack NAME] [--size WxH] [--time SECONDS] [--script FILE]\n"
    "\n"
    "Opens an OpenGL 4.5 compatibility window on the scene, with a panel of\n"
    "generated sliders (one section per Program). Every file the scene reads is\n"
    "watched; a save reloads within a frame or two. A shader that fails to\n"
    "compile keeps the last good one running and shows the error.\n"
    "\n"
    "  --pack NAME      draw the water with packs/NAME instead of the scene's Pack\n"
    "  --size WxH       window size of the scene (default: the glib's WindowSize)\n"
    "  --time SECONDS   start at this simulated time\n"
    "  --script FILE    run scripted actions (frames N, set P U v, expect P U v,\n"
    "                   screenshot PATH, reload, quit), then exit\n"
    "\n"
    "mouse: left drag orbits, right or middle drag pans, wheel zooms\n"
    "keys:  R reload   Space pause time   P or F12 screenshot   F or Home reset camera\n"
    "       Esc or Q quit\n";

static const char *usage_render =
    "usage: tarn render FILE.glib -o OUT [--pack NAME] [--size WxH] [--time SECONDS] [--frames N]\n"
    "                   [--set PROGRAM.NAME=VALUE]...\n"
    "\n"
    "Renders without any display through EGL (works with DISPLAY unset, on Mesa\n"
    "llvmpipe or a GPU). The image is deterministic for a fixed --time.\n"
    "\n"
    "  -o, --out OUT    output image: .png (8-bit) or .exr (float), any format\n"
    "                   OpenImageIO writes; a %d in the name writes every frame\n"
    "  --pack NAME      draw the water with packs/NAME instead of the scene's Pack\n"
    "  --size WxH       image size (default: the glib's WindowSize)\n"
    "  --time SECONDS   simulated time of the first frame (default 0)\n"
    "  --frames N       render N frames, 1/60 s apart; prints the median GPU time\n"
    "  --set P.NAME=V   set a slider, checkbox, colour (V,V,V) or Define of Program P\n"
    "                   as the panel would (NAME=V: of every Program); repeatable\n"
    "  --quiet          print only errors\n"
    "\n"
    "exit codes: 0 ok, 1 the scene or a shader has errors, 2 bad usage, 3 no OpenGL\n";

static const char *usage_validate =
    "usage: tarn validate [PATH...]\n"
    "\n"
    "Validates shaders with glslang, for every combination of each Program's\n"
    "Define toggles, and prints file:line: message for each error.\n"
    "A PATH is a .glib, a pack directory, a shader file or a directory of them.\n"
    "With no PATH: every pack under packs/ and every scene under scenes/.\n"
    "exit codes: 0 no errors, 1 errors\n";

static bool parse_size(const char *s, int *w, int *h) {
    char x;
    return s && sscanf(s, "%d%c%d", w, &x, h) == 3 && (x == 'x' || x == 'X') &&
           *w > 0 && *h > 0 && *w <= 16384 && *h <= 16384;
}

static bool parse_double(const char *s, double *out) {
    char *end;
    if (!s) return false;
    *out = strtod(s, &end);
    return end != s && *end == '\0';
}

static bool is_help(const char *a) {
    return strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0;
}

static int bad_usage(const char *usage, const char *what) {
    fprintf(stderr, "tarn: %s\n\n%s", what, usage);
    return TARN_EXIT_USAGE;
}

static int main_render(int argc, char **argv) {
    cli_render_desc d = {0};
    static const char *sets[64];
    d.sets = sets;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        if (is_help(a)) { fputs(usage_render, stdout); return TARN_EXIT_OK; }
        if ((strcmp(a, "-o") == 0 || strcmp(a, "--out") == 0) && next) { d.out = next; i++; }
        else if (strcmp(a, "--size") == 0) {
            if (!parse_size(next, &d.width, &d.height)) return bad_usage(usage_render, "--size wants WxH, e.g. 640x360");
            i++;
        } else if (strcmp(a, "--time") == 0) {
            if (!parse_double(next, &d.time_s)) return bad_usage(usage_render, "--time wants seconds, e.g. 2.5");
            i++;
        } else if (strcmp(a, "--frames") == 0) {
            double f;
            if (!parse_double(next, &f) || f < 1 || f > 100000) return bad_usage(usage_render, "--frames wants 1..100000");
            d.frames = (int)f;
            i++;
        } else if (strcmp(a, "--pack") == 0 && next) { d.pack = next; i++; }
        else if (strcmp(a, "--set") == 0 && next) {
            if (d.nsets < (int)(sizeof sets / sizeof *sets)) sets[d.nsets++] = next;
            i++;
        } else if (strcmp(a, "--quiet") == 0) d.quiet = true;
        else if (a[0] == '-') return bad_usage(usage_render, "unknown option");
        else if (!d.glib) d.glib = a;
        else return bad_usage(usage_render, "one scene at a time");
    }
    if (!d.glib) return bad_usage(usage_render, "which scene? give FILE.glib");
    if (!d.out) return bad_usage(usage_render, "where to? give -o OUT.png");
    return cli_render(&d);
}

static int main_view(int argc, char **argv) {
    view_desc d = {0};
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        if (is_help(a)) { fputs(usage_view, stdout); return TARN_EXIT_OK; }
        if (strcmp(a, "--size") == 0) {
            if (!parse_size(next, &d.width, &d.height)) return bad_usage(usage_view, "--size wants WxH");
            i++;
        } else if (strcmp(a, "--time") == 0) {
            if (!parse_double(next, &d.time_s)) return bad_usage(usage_view, "--time wants seconds");
            i++;
        } else if (strcmp(a, "--script") == 0 && next) { d.script = next; i++; }
        else if (strcmp(a, "--pack") == 0 && next) { d.pack = next; i++; }
        else if (a[0] == '-') return bad_usage(usage_view, "unknown option");
        else if (!d.glib) d.glib = a;
        else return bad_usage(usage_view, "one scene at a time");
    }
    if (!d.glib) return bad_usage(usage_view, "which scene? give FILE.glib");
    return view_run(&d);
}

static int main_compare_view(int argc, char **argv) {
    cli_compare_view_desc d = {0};
    const char *u = compare_view_usage();
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        double v;
        if (is_help(a)) { fputs(u, stdout); return TARN_EXIT_OK; }
        if (strcmp(a, "--size") == 0) {
            if (!parse_size(next, &d.width, &d.height)) return bad_usage(u, "--size wants WxH");
            i++;
        } else if (strcmp(a, "--time") == 0) {
            if (!parse_double(next, &d.time_s)) return bad_usage(u, "--time wants seconds");
            i++;
        } else if (strcmp(a, "--script") == 0 && next) { d.script = next; i++; }
        else if (strcmp(a, "--packs") == 0 && next) {
            static char buf[1024];
            snprintf(buf, sizeof buf, "%s", next);
            d.npacks = 0;
            for (char *save = NULL, *p = strtok_r(buf, ",", &save); p; p = strtok_r(NULL, ",", &save)) {
                if (d.npacks >= COMPARE_VIEW_MAX_PACKS) return bad_usage(u, "--packs takes 2 to 4 packs");
                d.packs[d.npacks++] = p;
            }
            i++;
        } else if (strcmp(a, "--ref-caustic-res") == 0) {
            if (!parse_double(next, &v) || v < 1 || v > 8192) return bad_usage(u, "--ref-caustic-res wants 1..8192");
            d.ref_caustic_res = (int)v;
            i++;
        } else if (strcmp(a, "--ref-photons") == 0) {
            if (!parse_double(next, &v) || v < 1 || v > 1e6) return bad_usage(u, "--ref-photons wants 1..1000000");
            d.ref_photons = (int)v;
            i++;
        } else if (a[0] == '-') return bad_usage(u, "unknown option");
        else if (!d.glib) d.glib = a;
        else return bad_usage(u, "one scene at a time");
    }
    if (!d.glib) return bad_usage(u, "which scene? give FILE.glib");
    if (d.npacks < 2) return bad_usage(u, "which packs? give --packs a,b (2 to 4)");
    return cli_compare_view(&d);
}

static int main_validate(int argc, char **argv) {
    for (int i = 0; i < argc; i++)
        if (is_help(argv[i])) { fputs(usage_validate, stdout); return TARN_EXIT_OK; }
    return validate_run((const char *const *)argv, argc, tarn_root(), stdout);
}

/* No arguments: the default scene, in a window when there is a display. */
static int main_default(void) {
    if (gl_ctx_have_display()) {
        view_desc d = { .glib = cli_default_scene() };
        return view_run(&d);
    }
    const char *out = "out/default.png";
    if (system("mkdir -p out") != 0) out = "default.png";
    printf("tarn: no display: rendering the default scene to %s\n", out);
    cli_render_desc d = { .glib = cli_default_scene(), .out = out, .time_s = 2.0 };
    return cli_render(&d);
}

int main(int argc, char **argv) {
    if (argc < 2) return main_default();
    const char *cmd = argv[1];
    if (is_help(cmd)) { fputs(usage_main, stdout); return TARN_EXIT_OK; }
    if (strcmp(cmd, "help") == 0) {
        const char *which = argc > 2 ? argv[2] : "";
        fputs(strcmp(which, "view") == 0 ? usage_view : strcmp(which, "render") == 0 ? usage_render
              : strcmp(which, "validate") == 0 ? usage_validate
              : strcmp(which, "compare") == 0 ? compare_usage()
              : strcmp(which, "bench") == 0 ? bench_usage()
              : strcmp(which, "compare-view") == 0 ? compare_view_usage() : usage_main, stdout);
        return TARN_EXIT_OK;
    }
    if (strcmp(cmd, "render") == 0) return main_render(argc - 2, argv + 2);
    if (strcmp(cmd, "view") == 0) return main_view(argc - 2, argv + 2);
    if (strcmp(cmd, "validate") == 0) return main_validate(argc - 2, argv + 2);
    if (strcmp(cmd, "compare") == 0) return cli_compare(argc - 2, argv + 2);
    if (strcmp(cmd, "reference") == 0) return cli_reference(argc - 2, argv + 2);
    if (strcmp(cmd, "bench") == 0) return cli_bench(argc - 2, argv + 2);
    if (strcmp(cmd, "compare-view") == 0) return main_compare_view(argc - 2, argv + 2);
    if (strcmp(cmd, "assets") == 0) return cli_assets(argc - 2, argv + 2);
    if (strstr(cmd, ".glib")) return main_view(argc - 1, argv + 1);   /* `tarn scene.glib` */
    fprintf(stderr, "tarn: unknown command '%s'\n\n%s", cmd, usage_main);
    return TARN_EXIT_USAGE;
}
