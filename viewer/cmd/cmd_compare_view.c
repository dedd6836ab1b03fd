/* cmd_compare_view: `tarn compare-view SCENE.glib --packs a,b[,c,d]`, packs
 * side by side in one window (ui/compare_view.h). */
#include "cmd.h"

#include <string.h>

#include "compare_view.h"
#include "util.h"

static const char usage[] =
    "usage: tarn compare-view SCENE.glib --packs a,b[,c,d] [--size WxH] [--time SECONDS]\n"
    "                         [--script FILE] [--ref-caustic-res N] [--ref-photons N] [--msaa N]\n"
    "\n"
    "Two to four packs side by side in one window, sharing one camera, one clock\n"
    "and the scene's world; each pack keeps its own sliders in the panel. The\n"
    "same pack may be named twice (compare two of its settings).\n"
    "\n"
    "  --packs a,b,...      the packs (2 to 4)\n"
    "  --size WxH           the scene area beside the panel (default: the glib's WindowSize)\n"
    "  --time SECONDS       start at this simulated time\n"
    "  --script FILE        scripted actions (see `tarn help view`, and pack N, layout\n"
    "                       grid|wipe, wipe A B, divider X, heat, heat-show on|off,\n"
    "                       heat-max E, orbit DX DY, timings, expect-heat), then exit\n"
    "  --ref-caustic-res N  the heat maps' reference: caustic grid (default 128)\n"
    "  --ref-photons N      ...and photons per cell (default 16)\n"
    "  --msaa N             anti-aliasing: N samples per pixel, 0 or 1 off (default 4\n"
    "                       on a GPU, off on a CPU rasteriser such as llvmpipe);\n"
    "                       the heat maps' reference subsamples where the GL's MSAA\n"
    "                       samples (the pixel centre when off)\n"
    "\n"
    "layouts: grid (two in a row, three or four in 2 x 2) and wipe (two packs over\n"
    "one view, the divider dragged with the left mouse button)\n"
    "heat maps: each pack's error against the CPU reference of this frame at the\n"
    "viewport size, computed on request (time pauses), one inferno scale for all\n"
    "mouse: left drag orbits, right or middle drag pans, wheel zooms\n"
    "keys:  H heat maps (compute / show / hide)   G grid   W wipe   Tab wipe's right pack\n"
    "       Space pause   R reload   P or F12 screenshot   F or Home reset camera   Esc or Q quit\n";


const char *cmd_compare_view_usage(void) { return usage; }

static int bad(const char *what) { return cmd_bad_usage(stderr, "tarn", usage, "%s", what); }

int cmd_compare_view(int argc, char **argv) {
    compare_view_desc d = {0};
    char packs[1024];   /* --packs split in place; d.packs point into it */
    double v;
    if (cmd_wants_help(argc, argv)) { fputs(usage, stdout); return TARN_EXIT_OK; }
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--size") == 0) {
            if (!opt_size(next, &d.width, &d.height)) return bad("--size wants WxH");
            i++;
        } else if (strcmp(a, "--time") == 0) {
            if (!opt_double(next, &d.time_s)) return bad("--time wants seconds");
            i++;
        } else if (strcmp(a, "--msaa") == 0) {
            if (!cmd_opt_msaa(next, &d.samples)) return bad("--msaa wants 0..16 samples");
            i++;
        } else if (strcmp(a, "--script") == 0 && next) { d.script = next; i++; }
        else if (strcmp(a, "--packs") == 0 && next) {
            d.npacks = cmd_split(next, packs, sizeof packs, d.packs, COMPARE_VIEW_MAX_PACKS);
            if (d.npacks < 0) return bad("--packs takes 2 to 4 packs");
            for (int k = 0; k < d.npacks; k++) {
                char why[512];
                if (!cmd_opt_pack(d.packs[k], why, sizeof why)) return bad(why);
            }
            i++;
        } else if (strcmp(a, "--ref-caustic-res") == 0) {
            if (!cmd_opt_range(next, 1, 8192, &v)) return bad("--ref-caustic-res wants 1..8192");
            d.ref_caustic_res = (int)v;
            i++;
        } else if (strcmp(a, "--ref-photons") == 0) {
            if (!cmd_opt_range(next, 1, 1e6, &v)) return bad("--ref-photons wants 1..1000000");
            d.ref_photons = (int)v;
            i++;
        } else if (a[0] == '-') return bad("unknown option");
        else if (!d.glib) d.glib = a;
        else return bad("one scene at a time");
    }
    if (!d.glib) return bad("which scene? give FILE.glib");
    if (d.npacks < 2) return bad("which packs? give --packs a,b (2 to 4)");
    return compare_view_run(&d);
}
