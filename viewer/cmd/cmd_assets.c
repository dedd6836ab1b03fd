/* cmd_assets: `tarn assets [--out DIR] [--size N] [SCENE.glib]`, the
 * generated textures (gfx/assets.h). */
#include "cmd.h"

#include <string.h>

#include "assets.h"

static const char usage[] =
    "usage: tarn assets [--out DIR] [--size N] [SCENE.glib]\n"
    "  Generates the textures the packs use (the same bytes every time) into\n"
    "  DIR (default: assets/ here): terrain albedo and normal map, the sky cube\n"
    "  map (sky_px.exr ... sky_nz.exr and .png), water_normal.png, foam.png,\n"
    "  caustics.exr and .png. The terrain and sky come from SCENE's world\n"
    "  (default: the lake). --size N bakes every texture at N x N.\n";

const char *cmd_assets_usage(void) { return usage; }

int cmd_assets(int argc, char **argv) {
    assets_desc d = {0};
    if (cmd_wants_help(argc, argv)) { fputs(usage, stdout); return TARN_EXIT_OK; }
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        if ((strcmp(a, "--out") == 0 || strcmp(a, "-o") == 0) && next) {
            d.dir = next;
            i++;
        } else if (strcmp(a, "--size") == 0 && next) {
            if (!cmd_opt_int(next, ASSETS_MIN_SIZE, ASSETS_MAX_SIZE, &d.size)) {
                fprintf(stderr, "tarn assets: --size takes a whole number from %d to %d, not '%s'\n",
                        ASSETS_MIN_SIZE, ASSETS_MAX_SIZE, next);
                return TARN_EXIT_USAGE;
            }
            i++;
        } else if (a[0] != '-' && !d.scene) {
            d.scene = a;
        } else {
            fprintf(stderr, "tarn assets: unexpected argument '%s'\n%s", a, usage);
            return TARN_EXIT_USAGE;
        }
    }
    return assets_run(&d);
}
