/* cli: headless rendering, which lives in the cmd layer (cmd_render.c) as
 * `tarn render` and the no-display default of main.c use it. cmd_render
 * parses the command line into this desc (zero means default); cli_render
 * returns the exit code: 0 ok, 1 the input had errors, 3 no OpenGL. */
#ifndef TARN_CLI_H
#define TARN_CLI_H

#include <stdbool.h>

#include "exit_code.h"

typedef struct cli_render_desc {
    const char *glib;
    const char *out;            /* .png, .exr, ... ; "%d" in it writes every frame */
    int width, height;          /* 0: the glib's WindowSize */
    double time_s;              /* simulated time of the (first) frame */
    int frames;                 /* 0: 1 */
    bool still;                 /* every frame at time_s (a paused window, tarn bench), not 1/60 s apart */
    bool passes;                /* print each named pass's median GPU time over the frames */
    bool grid_water;            /* the screen's water as a grid, not deferred (render_set_deferred_water) */
    double detail;              /* 0: 1, full; else a window's reduced frame's (render_set_detail) */
    bool quiet;
    bool verbose;               /* each inactive uniform a note at its glib line */
    const char *pack;           /* replaces the scene's `Pack` */
    const char *setting;        /* --setting NAME: a row of the pack's bench.txt, before the --sets */
    const char *const *sets;    /* --set PROGRAM.NAME=V[,V...] or NAME=V: sliders, checkboxes, Defines */
    int nsets;
    int samples;                /* MSAA (render_desc.samples): 0 the default, 1 off */
} cli_render_desc;

int cli_render(const cli_render_desc *d);

/* The scene tarn opens with no arguments: scenes/showcase.glib, a pool in
 * bright sun with a floating sphere, drawn by the pack its Pack line names
 * (natural: the lowest water error of the packs that draw caustics,
 * docs/benchmark.md), so `tarn` and `tarn view scenes/showcase.glib`
 * show the same picture (issue #30). */
const char *cli_default_scene(void);
/* The pack the default scene names (its Pack line; "?" when it has none). */
const char *cli_default_pack(void);

#endif
