/* cmd_view: `tarn view FILE.glib`, the live window (ui/view.h). */
#include "cmd.h"

#include <string.h>

#include "util.h"
#include "view.h"

static const char usage[] =
    "usage: tarn view FILE.glib [--pack NAME] [--setting NAME] [--size WxH] [--time SECONDS]\n"
    "                 [--script FILE] [--record FILE] [--msaa N] [--verbose]\n"
    "\n"
    "Opens an OpenGL 4.5 compatibility window on the scene, with a panel of\n"
    "generated sliders (one section per Program). Every file the scene reads is\n"
    "watched; a save reloads within a frame or two. A shader that fails to\n"
    "compile keeps the last good one running and shows the error.\n"
    "\n"
    "  --pack NAME      draw the water with packs/NAME instead of the scene's Pack\n"
    "  --setting NAME   start from the pack's setting NAME (a row of packs/PACK/bench.txt:\n"
    "                   default, paper, ...; the panel's Setting combo)\n"
    "  --size WxH       window size of the scene (default: the glib's WindowSize)\n"
    "  --time SECONDS   start at this simulated time\n"
    "  --script FILE    run scripted actions (frames N, set P U v, expect P U v,\n"
    "                   wait SECONDS, screenshot PATH, camera CX CY CZ DIST YAW PITCH,\n"
    "                   pause 1|0, reload, window W H, pack NAME, setting NAME,\n"
    "                   help 1|0, slow MS (frames of at least MS: input at a low\n"
    "                   frame rate), quit),\n"
    "                   then exit\n"
    "  --record FILE    record what you do (sliders, camera, pause) into the session\n"
    "                   FILE from the start; `tarn record FILE -o out.mp4` replays it\n"
    CMD_MSAA_HELP
    "  --verbose        each uniform the shaders declare but do not use, a note at\n"
    "                   its glib line (by default one summary line a load)\n"
    "\n"
    "mouse: left drag orbits, right or middle drag pans, wheel zooms\n"
    "keys:  R reload   Space pause time   P or F12 screenshot   F or Home reset camera\n"
    "       Shift+R start/stop recording a session (tarn-DATE-N.session)   Esc or Q quit\n"
    "       F1 or ? shows these keys over the scene\n"
    "\n"
    "Screenshots are opaque PNGs, tarn-DATE-N.png in the current directory; the\n"
    "path shows over the scene. Frame time is ms per frame over the last second.\n";

const char *cmd_view_usage(void) { return usage; }

int cmd_view(int argc, char **argv) {
    view_desc d = {0};
    if (cmd_wants_help(argc, argv)) { fputs(usage, stdout); return TARN_EXIT_OK; }
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--size") == 0) {
            if (!opt_size(next, &d.width, &d.height)) return cmd_bad_usage(stderr, "tarn", usage, "--size wants WxH");
            i++;
        } else if (strcmp(a, "--time") == 0) {
            if (!opt_double(next, &d.time_s)) return cmd_bad_usage(stderr, "tarn", usage, "--time wants seconds");
            i++;
        } else if (strcmp(a, "--msaa") == 0) {
            if (!cmd_opt_msaa(next, &d.samples)) return cmd_bad_usage(stderr, "tarn", usage, "--msaa wants 0..16 samples");
            i++;
        } else if (strcmp(a, "--script") == 0 && next) { d.script = next; i++; }
        else if (strcmp(a, "--pack") == 0 && next) {
            char why[512];
            if (!cmd_opt_pack(next, why, sizeof why)) return cmd_bad_usage(stderr, "tarn", usage, "%s", why);
            d.pack = next;
            i++;
        }
        else if (strcmp(a, "--record") == 0 && next) { d.record = next; i++; }
        else if (strcmp(a, "--verbose") == 0) d.verbose = true;
        else if (strcmp(a, "--setting") == 0 && next) { d.setting = next; i++; }
        else if (a[0] == '-') return cmd_bad_usage(stderr, "tarn", usage, "unknown option");
        else if (!d.glib) d.glib = a;
        else return cmd_bad_usage(stderr, "tarn", usage, "one scene at a time");
    }
    if (!d.glib) return cmd_bad_usage(stderr, "tarn", usage, "which scene? give FILE.glib");
    return view_run(&d);
}
