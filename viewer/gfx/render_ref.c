/* render_ref: where the CPU reference should subsample a pixel to match
 * the GL's multisampling (render.h): its grid, or the GL's own positions
 * in the reference's form. */
#include "util.h"
#include "render_internal.h"

#include <math.h>

int render_ref_spp(int samples) {
    int n = 1;
    while ((n + 1) * (n + 1) <= samples || (n + 1) * (n + 1) - samples < samples - n * n) n++;
    return n;
}

/* GL's y up in the pixel as the image's y down, kept inside [0, 1). */
static int to_image_positions(int n, double (*pos)[2], int max) {
    for (int i = 0; i < n && i < max; i++) {
        pos[i][1] = 1.0 - pos[i][1];
        for (int k = 0; k < 2; k++) {
            if (pos[i][k] >= 1.0) pos[i][k] = nextafter(1.0, 0.0);
            if (!(pos[i][k] >= 0.0)) pos[i][k] = 0.0;
        }
    }
    return n < max ? n : max;
}

int render_ref_positions(int samples, double (*pos)[2], int max) {
    return to_image_positions(render_msaa_positions(samples, pos, max), pos, max);
}

int render_ref_standard_positions(int samples, double (*pos)[2], int max) {
    return to_image_positions(render_msaa_standard_positions(samples, pos, max), pos, max);
}
