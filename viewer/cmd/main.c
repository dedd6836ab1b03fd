/* tarn: a live lab for real-time water shaders. The command line: one
 * table of commands drives dispatch, the usage text, `tarn help [COMMAND]`
 * and `tarn COMMAND --help`; each command is a cmd_NAME.c (cmd.h). */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "cmd.h"
#include "file.h"
#include "gl_ctx.h"
#include "util.h"
#include "view.h"

#ifndef TARN_VERSION
#error "TARN_VERSION comes from CMake's project(VERSION) (viewer/CMakeLists.txt)"
#endif

typedef struct command {
    const char *name;
    const char *args;               /* after the name in the list of commands */
    const char *summary;            /* one line */
    const char *(*usage)(void);     /* the full text: help NAME, NAME --help */
    int (*run)(int argc, char **argv);   /* the arguments after the name */
} command;

static const char *help_usage(void);
static int cmd_help(int argc, char **argv);

static const command commands[] = {
    { "view", "FILE.glib", "open a window; edits to any file the scene reads reload it",
      cmd_view_usage, cmd_view },
    { "render", "FILE.glib", "render without a display (EGL) to an image", cmd_render_usage, cmd_render },
    { "record", "SESSION -o OUT", "replay a session recorded in the window to a video (ffmpeg) or PNGs",
      cmd_record_usage, cmd_record },
    { "sheet", "FILE.glib --vary", "a hand-in sheet: the scene at several uniform values, labelled, in one image",
      cmd_sheet_usage, cmd_sheet },
    { "validate", "[PATH...]", "check every shader of every pack with glslang", cmd_validate_usage,
      cmd_validate },
    { "reference", "FILE.glib", "the CPU ground truth: image and per-pixel buffers (double precision)",
      cmd_reference_usage, cmd_reference },
    { "compare", "A B", "error of image A against reference B: RMSE, PSNR, heat map, JSON/CSV",
      cmd_compare_usage, cmd_compare },
    { "compare-view", "FILE.glib", "two to four packs side by side in one window, heat maps",
      cmd_compare_view_usage, cmd_compare_view },
    { "bench", "[FILE.glib...]", "speed against error of every pack and setting: CSV, JSON, report, plot",
      cmd_bench_usage, cmd_bench },
    { "assets", "[--out DIR]", "write the generated textures (terrain, sky, normal maps, foam, caustics)",
      cmd_assets_usage, cmd_assets },
    { "help", "[COMMAND]", "this text, or a command's options", help_usage, cmd_help },
};
enum { NCOMMANDS = sizeof commands / sizeof commands[0] };

static const command *find(const char *name) {
    for (int i = 0; i < NCOMMANDS; i++)
        if (strcmp(commands[i].name, name) == 0) return &commands[i];
    return NULL;
}

static void print_usage(FILE *f) {
    fputs("usage: tarn [COMMAND] [ARGS]\n"
          "\n"
          "A live lab for real-time water shaders: watches glman-style .glib scenes\n"
          "and hot-reloads their GLSL, with a slider for every uniform.\n"
          "\n"
          "commands:\n", f);
    for (int i = 0; i < NCOMMANDS; i++) {
        char left[64];
        snprintf(left, sizeof left, "%s %s", commands[i].name, commands[i].args);
        fprintf(f, "  %-22s  %s\n", left, commands[i].summary);
    }
    fputs("\n"
          "With no command, tarn opens the default scene (scenes/showcase.glib, a pool\n"
          "drawn by the pack it names, natural) in a window,\n"
          "or, when there is no display, renders it to out/default.png.\n"
          "`tarn COMMAND --help` lists a command's options; `tarn --version` says which tarn\n"
          "and where its packs and scenes are. `man tarn` documents it all.\n", f);
}

/* The version, and which packs and scenes this tarn uses (tarn_root: an
 * install's own, $TARN_ROOT or the source tree): "which tarn" answered
 * whole, and what the install test checks. */
static int print_version(void) {
    printf("tarn %s\ndata: %s\n", TARN_VERSION, tarn_root());
    return TARN_EXIT_OK;
}

static int unknown(const char *name) {
    fprintf(stderr, "tarn: unknown command '%s'\n\n", name);
    print_usage(stderr);
    return TARN_EXIT_USAGE;
}

static const char *help_usage(void) {
    return "usage: tarn help [COMMAND]\n"
           "\n"
           "Lists the commands, or prints COMMAND's usage and options (the same as\n"
           "`tarn COMMAND --help`).\n";
}

static int cmd_help(int argc, char **argv) {
    if (argc == 0) { print_usage(stdout); return TARN_EXIT_OK; }
    const command *c = find(argv[0]);
    if (!c) return unknown(argv[0]);
    fputs(c->usage(), stdout);
    return TARN_EXIT_OK;
}

/* No arguments: the default scene, in a window when there is a display. */
static int main_default(void) {
    if (gl_ctx_have_display()) {
        view_desc d = { .glib = cli_default_scene() };   /* its own Pack, as `tarn view` draws it */
        return view_run(&d);
    }
    const char *out = "out/default.png";
    char err[512];
    if (!file_mkdir_p("out", err, sizeof err)) out = "default.png";   /* a read-only cwd still gets a render */
    printf("tarn: no display: rendering the default scene (scenes/showcase.glib, pack %s) to %s\n",
           cli_default_pack(), out);
    cli_render_desc d = { .glib = cli_default_scene(), .out = out, .time_s = 2.0 };
    return cli_render(&d);
}

int main(int argc, char **argv) {
    if (argc < 2) return main_default();
    const char *name = argv[1];
    if (opt_is_help(name)) { print_usage(stdout); return TARN_EXIT_OK; }
    if (strcmp(name, "--version") == 0) return print_version();
    const command *c = find(name);
    if (c && cmd_wants_help(argc - 2, argv + 2)) { fputs(c->usage(), stdout); return TARN_EXIT_OK; }
    if (c) return c->run(argc - 2, argv + 2);
    if (strstr(name, ".glib")) return cmd_view(argc - 1, argv + 1);   /* `tarn scene.glib` */
    return unknown(name);
}
