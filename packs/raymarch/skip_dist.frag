#version 330 compatibility
// The skip map's distance passes (march.glsl, "Skipping empty space"): the
// L-infinity distance transform of skip_blocked.frag's cells, in two 1D
// passes (uAxis 0 along rows, then 1 along columns on the rows' result):
// out(c) = min over |d| <= R of max(in(c + d), |d|), with cells beyond the
// map counted as blocked (0). From blocked (0) / free (MARCH_SKIP_FAR) this
// is the distance along the row to the nearest blocked cell; from that, the
// L-infinity distance in the plane; both at most MARCH_SKIP_FAR = R + 1
// (nothing within R). Each channel is one height threshold. Drawn once
// with fullscreen.vert over a MARCH_SKIP_CELLS² target.
#include "march.glsl"

uniform sampler2D uSkipIn;   // skip_blocked.frag's, or this pass's along rows
uniform int uAxis;           // 0: along rows (x), 1: along columns (y)
out vec4 fragColor;

void main() {
    ivec2 c = ivec2(gl_FragCoord.xy);
    ivec2 axis = uAxis == 0 ? ivec2(1, 0) : ivec2(0, 1);
    int reach = int(MARCH_SKIP_FAR) - 1;
    vec4 r = texelFetch(uSkipIn, c, 0);
    for (int d = 1; d <= reach; d++) {
        float fd = float(d);
        ivec2 a = c + d * axis, b = c - d * axis;
        vec4 va = all(lessThan(a, ivec2(MARCH_SKIP_CELLS))) ? texelFetch(uSkipIn, a, 0) : vec4(0.0);
        vec4 vb = all(greaterThanEqual(b, ivec2(0))) ? texelFetch(uSkipIn, b, 0) : vec4(0.0);
        r = min(r, max(min(va, vb), vec4(fd)));
    }
    fragColor = r;
}
