#version 330 compatibility
// The height of the water surface over a square of the world, a texel a
// sample, drawn by tarn once a frame (render_world.c, world_update_height)
// for world.frag to read. Deciding whether a point of the land is under
// the moving surface takes wavesHeightAt, a Newton solve through the wave
// sum; per pixel that was 40% of a frame of the world on llvmpipe, which
// runs an `if`'s body for every pixel of a block whatever the condition.
// A 256^2 map costs an eighth of that, and bilinear interpolation between
// its texels is off by about A k^2 h^2 / 8 (lake: under 2 mm).
#include "contract.glsl"
#include "waves.glsl"

uniform float uWaveHeightHalf;   // the map covers x, z in [-half, half]
uniform vec2 uHeightRes;         // its texels a side
out vec4 fragColor;

void main() {
    vec2 xz = (gl_FragCoord.xy / uHeightRes * 2.0 - 1.0) * uWaveHeightHalf;
    fragColor = vec4(wavesHeightAt(xz, uTime), 0.0, 0.0, 1.0);
}
