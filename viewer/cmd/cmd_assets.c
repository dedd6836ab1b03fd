/* cmd_assets: `tarn assets [--out DIR] [--size N] [SCENE.glib]`, the
 * generated textures (gfx/assets.h). */
#include "cmd.h"

#include <stddef.h>

#include "assets.h"

static const cmd_option options[] = {
    { "SCENE.glib", .kind = CMD_ARG, .offset = offsetof(assets_desc, scene) },
    { "--out", "-o", "DIR", .kind = CMD_STRING, .offset = offsetof(assets_desc, dir),
      .help = "where the textures go (default: assets/ here)\n",
      .man = "where the textures go (default:\n"
             ".I assets/\n"
             "in the current folder).\n" },
    { "--size", .metavar = "N", .kind = CMD_INT, .offset = offsetof(assets_desc, size), .lo = ASSETS_MIN_SIZE,
      .hi = ASSETS_MAX_SIZE,
      .help = "bake every texture at N x N\n",
      .man = "bake every texture at\n"
             ".IR N \" x \" N .\n" },
    { 0 }
};

const cmd_spec cmd_assets_spec = {
    .name = "assets",
    .synopsis = "[--out DIR] [--size N] [SCENE.glib]\n",
    .about = "Generates the textures the packs use (the same bytes every time) into\n"
             "DIR: terrain albedo and normal map, the sky cube map (sky_px.exr ...\n"
             "sky_nz.exr and .png), water_normal.png, foam.png, caustics.exr and .png.\n"
             "The terrain and sky come from SCENE's world (default: the lake).\n",
    .options = options,
    .extra = "one scene at a time",
};

CMD_USAGE_FUNCTION(cmd_assets_usage, cmd_assets_spec)

int cmd_assets(int argc, char **argv) {
    if (cmd_wants_help(argc, argv)) { fputs(cmd_assets_usage(), stdout); return TARN_EXIT_OK; }
    assets_desc d = {0};
    int rc = cmd_parse(&cmd_assets_spec, argc, argv, &d, stderr);
    return rc == TARN_EXIT_OK ? assets_run(&d) : rc;
}
