#version 330 compatibility
// The skip map's first pass (march.glsl, "Skipping empty space"): for each
// of its MARCH_SKIP_CELLS² cells, per height threshold L_k (marchSkipLevels,
// one a channel), whether a texel of the world-Y texture under the cell
// could stop a ray going up at a height of L_k or more: its top or floor
// reaches L_k, or it is off the drawn world (the march leaves there).
// Written as skip_dist.frag reads it: 0 where blocked, MARCH_SKIP_FAR
// (farther than it looks) where free. The texels read are those under the
// cell and one more on each side, so a sample whose uv rounds to a
// neighbouring texel is still counted. Drawn once with fullscreen.vert
// over a MARCH_SKIP_CELLS² target, after pack_y.frag.
#include "march.glsl"

uniform sampler2D uWorldY;   // pack_y.frag's
out vec4 fragColor;

void main() {
    ivec2 cell = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(uWorldY, 0);
    ivec2 lo = max(cell * size / MARCH_SKIP_CELLS - 1, ivec2(0));
    ivec2 hi = min(((cell + 1) * size + MARCH_SKIP_CELLS - 1) / MARCH_SKIP_CELLS, size - 1);
    float high = -1e30;   // the highest top or floor; +1e30 where off the world
    for (int j = lo.y; j <= hi.y; j++) {
        for (int i = lo.x; i <= hi.x; i++) {
            vec3 t = texelFetch(uWorldY, ivec2(i, j), 0).xyz;
            high = max(high, t.x <= MARCH_EMPTY_Y ? 1e30 : max(t.x, t.z));
        }
    }
    fragColor = mix(vec4(MARCH_SKIP_FAR), vec4(0.0), greaterThanEqual(vec4(high), marchSkipLevels()));
}
