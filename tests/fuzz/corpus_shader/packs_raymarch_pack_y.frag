#version 330 compatibility
// Packs the three top-down depth targets into the world-Y texture the march
// reads (RGBA32F, one texelFetch a step): x the top (World all), y the
// bottom of floating things (World all, undersides only), z the floor under
// overhangs (World below); -1e30 where nothing was drawn (the depth clear).
// Drawn once with fullscreen.vert over a target the size of the depth
// targets, so gl_FragCoord names the texel.
#include "march.glsl"

uniform sampler2D uTopDepth;
uniform sampler2D uBottomDepth;
uniform sampler2D uFloorDepth;
out vec4 fragColor;

float worldY(sampler2D s, ivec2 ij) {
    float d = texelFetch(s, ij, 0).r;
    return d >= 1.0 ? -1e30 : marchDepthToY(d);
}

void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    fragColor = vec4(worldY(uTopDepth, ij), worldY(uBottomDepth, ij), worldY(uFloorDepth, ij), 1.0);
}
