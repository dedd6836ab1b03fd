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
// Drawn once with fullscreen.vert over a target the size of the depth
// targets, so gl_FragCoord names the texel.
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
    fragColor = vec4(worldY(uTopDepth, ij), bottom, worldY(uFloorDepth, ij), high);
}
