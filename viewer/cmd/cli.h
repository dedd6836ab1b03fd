/* cli: the tarn commands. main.c parses the command line into these desc
 * structs (zero means default) and calls one; each returns the exit code:
 * 0 ok, 1 the input had errors, 2 bad usage, 3 no OpenGL context. */
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
    bool quiet;
    const char *pack;           /* replaces the scene's `Pack` */
    const char *const *sets;    /* --set PROGRAM.NAME=V[,V...] or NAME=V: sliders, checkboxes, Defines */
    int nsets;
} cli_render_desc;

int cli_render(const cli_render_desc *d);

/* The scene tarn opens with no arguments. */
const char *cli_default_scene(void);

#endif
