/* tarn: a live lab for real-time water shaders. The command line: one
 * table of commands drives dispatch, the usage text, `tarn help [COMMAND]`
 * and `tarn COMMAND --help`; each command is a cmd_NAME.c (cmd.h) whose
 * option table (cmd_opt_table.h) gives its usage and its man-page entries
 * (`tarn help --roff`). */
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "cmd.h"
#include "file.h"
#include "gl_ctx.h"
#include "strbuf.h"
#include "util.h"
#include "view.h"

#ifndef TARN_VERSION
#error "TARN_VERSION comes from CMake's project(VERSION) (viewer/CMakeLists.txt)"
#endif

typedef struct command {
    const cmd_spec *spec;           /* its name, usage text and options (cmd_opt_table.h) */
    const char *args;               /* after the name in the list of commands */
    const char *summary;            /* one line */
    int (*run)(int argc, char **argv);   /* the arguments after the name */
} command;

static const cmd_spec help_spec;
static int cmd_help(int argc, char **argv);

static const command commands[] = {
    { &cmd_view_spec, "FILE.glib", "open a window; edits to any file the scene reads reload it", cmd_view },
    { &cmd_render_spec, "FILE.glib", "render without a display (EGL) to an image", cmd_render },
    { &cmd_record_spec, "SESSION -o OUT", "replay a session recorded in the window to a video (ffmpeg) or PNGs",
      cmd_record },
    { &cmd_sheet_spec, "FILE.glib --vary", "a hand-in sheet: the scene at several uniform values, labelled, in one image",
      cmd_sheet },
    { &cmd_validate_spec, "[PATH...]", "check every shader of every pack with glslang", cmd_validate },
    { &cmd_reference_spec, "FILE.glib", "the CPU ground truth: image and per-pixel buffers (double precision)",
      cmd_reference },
    { &cmd_compare_spec, "A B", "error of image A against reference B: RMSE, PSNR, heat map, JSON/CSV", cmd_compare },
    { &cmd_compare_view_spec, "FILE.glib", "two to four packs side by side in one window, heat maps",
      cmd_compare_view },
    { &cmd_bench_spec, "[FILE.glib...]", "speed against error of every pack and setting: CSV, JSON, report, plot",
      cmd_bench },
    { &cmd_assets_spec, "[--out DIR]", "write the generated textures (terrain, sky, normal maps, foam, caustics)",
      cmd_assets },
    { &help_spec, "[COMMAND]", "this text, or a command's options", cmd_help },
};
enum { NCOMMANDS = sizeof commands / sizeof commands[0] };

static const command *find(const char *name) {
    for (int i = 0; i < NCOMMANDS; i++)
        if (strcmp(commands[i].spec->name, name) == 0) return &commands[i];
    return NULL;
}

static void print_help(const command *c, FILE *f) {
    char text[CMD_USAGE_MAX];
    fputs(cmd_usage(c->spec, text, sizeof text), f);
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
        snprintf(left, sizeof left, "%s %s", commands[i].spec->name, commands[i].args);
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

/* `tarn help`'s own command line. */
typedef struct help_args {
    const char *command;
    bool roff;
} help_args;

static const cmd_option help_options[] = {
    { "COMMAND", .kind = CMD_ARG, .offset = offsetof(help_args, command) },
    { "--roff", .kind = CMD_FLAG, .offset = offsetof(help_args, roff),
      .help = "COMMAND's options (every command's, without one) as man-page\n"
              "entries: the lists docs/tarn.1 holds (scripts/man_options.sh\n"
              "writes them there)\n" },
    { 0 }
};

static const cmd_spec help_spec = {
    .name = "help",
    .synopsis = "[COMMAND] [--roff]\n",
    .about = "Lists the commands, or prints COMMAND's usage and options (the same as\n"
             "`tarn COMMAND --help`).\n",
    .options = help_options,
    .extra = "one command at a time",
};

/* --roff: c's option list as man-page entries; every command's, each
 * between the comments that mark it in docs/tarn.1, when c is NULL. */
static void print_roff(const command *c) {
    for (int i = 0; i < NCOMMANDS; i++) {
        const command *k = &commands[i];
        if (c && k != c) continue;
        strbuf b = {0};
        cmd_roff_options(k->spec, &b);
        if (c) fputs(b.s ? b.s : "", stdout);
        else if (b.s) printf(".\\\" BEGIN options: tarn help --roff %s\n%s.\\\" END options\n", k->spec->name, b.s);
        strbuf_free(&b);
    }
}

static int cmd_help(int argc, char **argv) {
    help_args a = {0};
    int rc = cmd_parse(&help_spec, argc, argv, &a, stderr);
    if (rc != TARN_EXIT_OK) return rc;
    const command *c = a.command ? find(a.command) : NULL;
    if (a.command && !c) return unknown(a.command);
    if (a.roff) print_roff(c);
    else if (c) print_help(c, stdout);
    else print_usage(stdout);
    return TARN_EXIT_OK;
}

/* No arguments: the default scene, in a window when there is a display. */
static int main_default(void) {
    if (gl_ctx_have_display()) {
        view_desc d = { .glib = cli_default_scene() };   /* its own Pack, as `tarn view` draws it */
        return view_run(&d);
    }
    const char *out = "out/default.png";
    char err[MSG_MAX];
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
    if (c && cmd_wants_help(argc - 2, argv + 2)) { print_help(c, stdout); return TARN_EXIT_OK; }
    if (c) return c->run(argc - 2, argv + 2);
    if (strstr(name, ".glib")) return cmd_view(argc - 1, argv + 1);   /* `tarn scene.glib` */
    return unknown(name);
}
