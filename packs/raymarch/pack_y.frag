#version 330 compatibility
// Packs the three top-down depth targets into the world-Y texture the march
// reads (RGBA32F, one texelFetch a step): x the top (World all), y the
// bottom of floating things (World all, undersides only), z the floor under
// overhangs (World below); -1e30 where nothing was drawn (the depth clear).
// A lower underside (World below 1.5, undersides only) lowers y: a trunk
// under a crown is hidden from above, and the crown's underside alone made
// the texel's slab start at the crown (issue #16's missing trunk): the slab
// then runs from the trunk's foot to the crown's top, and w keeps the
// highest underside, where water.frag's colour changes from the low pass's
// to the underside's.
// Where the floor pass saw the thing itself (a thing under the water, or
// the part of one crossing it below the pass's clip: floor >= bottom), the
// ground under it was hidden from every pass: z becomes the terrain's
// model there (terrain.glsl) and w MARCH_GROUND_MODEL, so water.frag
// shades that ground from the model too. Without it a ray passing under
// the thing met the ground only beside it, on the side of the next
// column: a floating sphere stood on a tube of ground-coloured walls.
// Drawn once with fullscreen.vert over a target the size of the depth
// targets, so gl_FragCoord names the texel.
#include "world.glsl"
#include "terrain.glsl"
#include "march.glsl"

uniform sampler2D uTopDepth;
uniform sampler2D uBottomDepth;
uniform sampler2D uFloorDepth;
uniform sampler2D uLowDepth;
out vec4 fragColor;

float worldY(sampler2D s, ivec2 ij) {
    float d = texelFetch(s, ij, 0).r;
    return d >= 1.0 ? -1e30 : marchDepthToY(d);
}

void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    float high = worldY(uBottomDepth, ij), low = worldY(uLowDepth, ij);
    float bottom = low > -1e29 && low < high ? low : high;
    float top = worldY(uTopDepth, ij), ground = worldY(uFloorDepth, ij);
    if (bottom > MARCH_EMPTY_Y && bottom < top && ground >= bottom) {
        vec2 uv = (vec2(ij) + 0.5) / vec2(textureSize(uFloorDepth, 0));
        ground = terrainHeightGrad(marchWorldXZ(uv)).x;
        high = MARCH_GROUND_MODEL;
    }
    fragColor = vec4(top, bottom, ground, high);
}
