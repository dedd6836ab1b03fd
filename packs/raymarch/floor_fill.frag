#version 330 compatibility
// The floor's colour as water.frag reads it (bilinear): the floor pass's,
// except where that pass saw the thing itself rather than the ground
// under it (pack_y.frag's MARCH_GROUND_MODEL texels: the band of a rock
// breaking the water between its equator and the pass's clip). There
// water.frag shades the ground from the terrain's model, and the pass's
// colour (the rock's grey) is never wanted; but a bilinear read of the
// ground beside the band mixed it in: two dotted rings round the rock seen
// through the water. Here the band takes the terrain model's colour
// (water.frag's groundModelColor), so a read mixes ground with ground.
// Drawn once with fullscreen.vert, after pack_y.frag.
#include "world.glsl"
#include "terrain.glsl"
#include "march.glsl"

uniform sampler2D uFloorColorIn;   // the floor pass's colour
uniform sampler2D uWorldY;         // pack_y.frag's
out vec4 fragColor;

void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    fragColor = texelFetch(uFloorColorIn, ij, 0);
    if (texelFetch(uWorldY, ij, 0).w >= MARCH_GROUND_MODEL) {
        vec2 xz = marchWorldXZ((vec2(ij) + 0.5) / vec2(textureSize(uWorldY, 0)));
        vec3 hg = terrainHeightGrad(xz);
        vec3 n = normalize(vec3(-hg.y, 1.0, -hg.z));
        fragColor = vec4(worldShadeAt(terrainAlbedo(xz, hg.x, n), n, vec3(xz.x, hg.x, xz.y)), 1.0);
    }
}
