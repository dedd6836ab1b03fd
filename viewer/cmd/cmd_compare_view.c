/* cmd_compare_view: `tarn compare-view SCENE.glib --packs a,b[,c,d]`, packs
 * side by side in one window (ui/compare_view.h). */
#include "cmd.h"

#include <stddef.h>
#include <stdio.h>

#include "compare_view.h"
#include "util.h"

/* The command line: the window's desc and the --packs list it points into. */
typedef struct compare_view_cli {
    compare_view_desc d;
    char packs[1024];   /* --packs split in place; d.packs point into it */
} compare_view_cli;

static bool set_packs(void *desc, const char *value, char *why, size_t whylen) {
    compare_view_cli *c = desc;
    c->d.npacks = cmd_split(value, c->packs, sizeof c->packs, c->d.packs, COMPARE_VIEW_MAX_PACKS);
    if (c->d.npacks < 0) {
        snprintf(why, whylen, "--packs takes 2 to 4 packs");
        return false;
    }
    for (int k = 0; k < c->d.npacks; k++)
        if (!cmd_opt_pack(c->d.packs[k], why, whylen)) return false;
    return true;
}

#define OFF(field) offsetof(compare_view_cli, d.field)

static const cmd_option options[] = {
    { "SCENE.glib", .kind = CMD_ARG, .offset = OFF(glib), .missing = "which scene? give FILE.glib" },
    { "--packs", .metavar = "a,b,...", .kind = CMD_CUSTOM, .set = set_packs,
      .missing = "which packs? give --packs a,b (2 to 4)",
      .help = "the packs (2 to 4)\n",
      .man = "the packs (2 to 4).\n" },
    { "--size", .metavar = "WxH", .kind = CMD_SIZE, .offset = OFF(width), .offset2 = OFF(height),
      .help = "the scene area beside the panel (default: the glib's WindowSize)\n",
      .man = "the scene area beside the panel (default: the glib's\n"
             ".BR WindowSize ).\n" },
    { "--time", .metavar = "SECONDS", .kind = CMD_DOUBLE, .offset = OFF(time_s), .wants = "seconds",
      .help = "start at this simulated time\n",
      .man = "start at this simulated time.\n" },
    { "--script", .metavar = "FILE", .kind = CMD_STRING, .offset = OFF(script),
      .help = "scripted actions (see `tarn help view`, and pack N, layout\n"
              "grid|wipe, wipe A B, divider X, heat, heat-show on|off,\n"
              "heat-max E, orbit DX DY, timings, expect-heat), then exit\n",
      .man = "scripted actions (those of\n"
             ".BR view ,\n"
             "and\n"
             ".BI pack \" N\" ,\n"
             ".B layout grid\\fR|\\fBwipe\\fR,\n"
             ".BI wipe \" A B\" ,\n"
             ".BI divider \" X\" ,\n"
             ".BR heat ,\n"
             ".B heat\\-show on\\fR|\\fBoff\\fR,\n"
             ".BI heat\\-max \" E\" ,\n"
             ".BI drag \" X0 Y0 X1 Y1\"\n"
             "(a left press, move and release between two frames, window pixels),\n"
             ".BR timings ,\n"
             ".BR expect\\-heat ,\n"
             ".BI expect\\-divider \" X\" ,\n"
             ".B expect\\-camera home\\fR|\\fBmoved\\fR),\n"
             "then exit.\n" },
    { "--ref-caustic-res", .metavar = "N", .kind = CMD_INT, .offset = OFF(ref_caustic_res), .lo = 1, .hi = 8192,
      .help = "the heat maps' reference: caustic grid (default 128)\n",
      .man = "the heat maps' reference: caustic grid (default 128).\n" },
    { "--ref-photons", .metavar = "N", .kind = CMD_INT, .offset = OFF(ref_photons), .lo = 1, .hi = 1000000,
      .help = "...and photons per cell (default 16)\n",
      .man = "\\&...and photons per cell (default 16).\n" },
    { "--msaa", .metavar = "N", .kind = CMD_MSAA, .offset = OFF(samples),
      .help = "anti-aliasing: N samples per pixel, 0 or 1 off (default 4\n"
              "on a GPU, off on a CPU rasteriser such as llvmpipe);\n"
              "the heat maps' reference subsamples where the GL's MSAA\n"
              "samples (the pixel centre when off)\n",
      .man = "anti\\-aliasing of every pack (as in\n"
             ".BR render );\n"
             "the heat maps' reference subsamples where the GL's MSAA samples (the\n"
             "positions\n"
             ".B glGetMultisamplefv\n"
             "gives; off: the pixel centre), so an anti\\-aliased edge is compared with an\n"
             "edge anti\\-aliased alike.\n" },
    { 0 }
};

const cmd_spec cmd_compare_view_spec = {
    .name = "compare-view",
    .synopsis = "SCENE.glib --packs a,b[,c,d] [--size WxH] [--time SECONDS]\n"
                "[--script FILE] [--ref-caustic-res N] [--ref-photons N] [--msaa N]\n",
    .about = "Two to four packs side by side in one window, sharing one camera, one clock\n"
             "and the scene's world; each pack keeps its own sliders in the panel. The\n"
             "same pack may be named twice (compare two of its settings).\n",
    .options = options,
    .notes = "layouts: grid (two in a row, three or four in 2 x 2) and wipe (two packs over\n"
             "one view, the divider dragged with the left mouse button)\n"
             "heat maps: each pack's error against the CPU reference of this frame at the\n"
             "viewport size, computed on request (time pauses), one inferno scale for all\n"
             "mouse: left drag orbits, right or middle drag pans, wheel zooms\n"
             "keys:  H heat maps (compute / show / hide)   G grid   W wipe   Tab wipe's right pack\n"
             "       Space pause   R reload   P or F12 screenshot   F or Home reset camera   Esc or Q quit\n",
    .column = 23,
    .extra = "one scene at a time",
};

CMD_USAGE_FUNCTION(cmd_compare_view_usage, cmd_compare_view_spec)

int cmd_compare_view(int argc, char **argv) {
    if (cmd_wants_help(argc, argv)) { fputs(cmd_compare_view_usage(), stdout); return TARN_EXIT_OK; }
    compare_view_cli c = {0};
    int rc = cmd_parse(&cmd_compare_view_spec, argc, argv, &c, stderr);
    if (rc == TARN_EXIT_OK && c.d.npacks < 2)
        rc = cmd_bad_usage(&cmd_compare_view_spec, stderr, "which packs? give --packs a,b (2 to 4)");
    return rc == TARN_EXIT_OK ? compare_view_run(&c.d) : rc;
}
