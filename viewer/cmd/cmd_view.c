/* cmd_view: `tarn view FILE.glib`, the live window (ui/view.h). */
#include "cmd.h"

#include <stddef.h>

#include "util.h"
#include "view.h"

static const cmd_option options[] = {
    { "FILE.glib", .kind = CMD_ARG, .offset = offsetof(view_desc, glib), .missing = "which scene? give FILE.glib" },
    CMD_OPTION_PACK(offsetof(view_desc, pack)),
    { "--setting", .metavar = "NAME", .kind = CMD_STRING, .offset = offsetof(view_desc, setting),
      .help = "start from the pack's setting NAME (a row of packs/PACK/bench.txt:\n"
              "default, paper, ...; the panel's Setting combo)\n",
      .man = "start from the pack's setting\n"
             ".I NAME\n"
             "(the\n"
             ".B Setting\n"
             "combo's).\n" },
    { "--size", .metavar = "WxH", .kind = CMD_SIZE, .offset = offsetof(view_desc, width),
      .offset2 = offsetof(view_desc, height),
      .help = "window size of the scene (default: the glib's WindowSize)\n",
      .man = "window size of the scene (default: the glib's\n"
             ".BR WindowSize ).\n" },
    { "--time", .metavar = "SECONDS", .kind = CMD_DOUBLE, .offset = offsetof(view_desc, time_s), .wants = "seconds",
      .help = "start at this simulated time\n",
      .man = "start at this simulated time.\n" },
    { "--script", .metavar = "FILE", .kind = CMD_STRING, .offset = offsetof(view_desc, script),
      .help = "run scripted actions (frames N, set P U v, expect P U v,\n"
              "wait SECONDS, time T, advance DT N (N frames DT apart),\n"
              "screenshot PATH, camera CX CY CZ DIST YAW PITCH,\n"
              "pause 1|0, reload, window W H, pack NAME, setting NAME,\n"
              "help 1|0, slow MS (frames of at least MS: input at a low\n"
              "frame rate), quit),\n"
              "then exit\n",
      .man = "run scripted actions, one a line, then exit:\n"
             ".BI frames \" N\" ,\n"
             ".BI set \" P U v\" ,\n"
             ".BI expect \" P U v\" ,\n"
             ".BI wait \" SECONDS\" ,\n"
             ".BI time \" T\" ,\n"
             ".BI advance \" DT N\"\n"
             "(N frames, each DT seconds of scene time after the one before: a running clock, frame for frame),\n"
             ".BI screenshot \" PATH\" ,\n"
             ".BI camera \" CX CY CZ DIST YAW PITCH\" ,\n"
             ".BR \"pause 1\" | 0 ,\n"
             ".BR \"help 1\" | 0\n"
             "(the key help, as F1),\n"
             ".BI window \" W H\" ,\n"
             ".BI orbit \" DYAW DPITCH\" \" \\fR[\\fPFRAMES\\fR]\\fP\"\n"
             "(turn the camera now and on each of the next frames),\n"
             ".BI budget \" MS\" ,\n"
             ".BI slow \" MS\"\n"
             "(every frame lasts at least MS, as on a slow GPU: input between frames is tested so),\n"
             ".B resolution\n"
             "(print the size drawn),\n"
             ".B expect\\-resolution full\\fR|\\fBreduced\\fR,\n"
             ".B clock\n"
             "(frames and wall ms, for benchmarks),\n"
             ".B stamp on\\fR|\\fBoff\\fR\n"
             "(print when the first frame after a reload is on screen),\n"
             ".BR reload ,\n"
             ".BI pack \" NAME\"\n"
             "(the\n"
             ".B Pack\n"
             "combo),\n"
             ".BI setting \" NAME\"\n"
             "(the\n"
             ".B Setting\n"
             "combo),\n"
             ".BR quit .\n" },
    { "--record", .metavar = "FILE", .kind = CMD_STRING, .offset = offsetof(view_desc, record),
      .help = "record what you do (sliders, camera, pause) into the session\n"
              "FILE from the start; `tarn record FILE -o out.mp4` replays it\n",
      .man = "record what you do into the session\n"
             ".I FILE\n"
             "from the start: slider, colour, checkbox and\n"
             ".B Define\n"
             "changes, camera moves, pauses, pack and setting switches, each a line with its time\n"
             ".RB ( \"t=1.250 slider Water uWaveAmp 0.4\" ).\n"
             ".B Shift+R\n"
             "stops and starts recordings in the window too;\n"
             ".B tarn record\n"
             "replays them.\n" },
    CMD_OPTION_MSAA(offsetof(view_desc, samples)),
    CMD_OPTION_VERBOSE(offsetof(view_desc, verbose)),
    { 0 }
};

const cmd_spec cmd_view_spec = {
    .name = "view",
    .synopsis = "FILE.glib [--pack NAME] [--setting NAME] [--size WxH] [--time SECONDS]\n"
                "[--script FILE] [--record FILE] [--msaa N] [--verbose]\n",
    .about = "Opens an OpenGL 4.5 compatibility window on the scene, with a panel of\n"
             "generated sliders (one section per Program). Every file the scene reads is\n"
             "watched; a save reloads within a frame or two. A shader that fails to\n"
             "compile keeps the last good one running and shows the error.\n",
    .options = options,
    .notes = "mouse: left drag orbits, right or middle drag pans, wheel zooms\n"
             "keys:  R reload   Space pause time   P or F12 screenshot   F or Home reset camera\n"
             "       Shift+R start/stop recording a session (tarn-DATE-N.session)   Esc or Q quit\n"
             "       F1 or ? shows these keys over the scene\n"
             "\n"
             "Screenshots are opaque PNGs, tarn-DATE-N.png in the current directory; the\n"
             "path shows over the scene. Frame time is ms per frame over the last second.\n",
    .extra = "one scene at a time",
};

CMD_USAGE_FUNCTION(cmd_view_usage, cmd_view_spec)

int cmd_view(int argc, char **argv) {
    if (cmd_wants_help(argc, argv)) { fputs(cmd_view_usage(), stdout); return TARN_EXIT_OK; }
    view_desc d = {0};
    int rc = cmd_parse(&cmd_view_spec, argc, argv, &d, stderr);
    return rc == TARN_EXIT_OK ? view_run(&d) : rc;
}
