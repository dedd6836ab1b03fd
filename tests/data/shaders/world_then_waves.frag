#version 330 compatibility
// packs/common's world.glsl, then waves.glsl: either may come first (issue 12)
#include "world.glsl"
#include "waves.glsl"
out vec4 fragColor;
void main() {
    vec3 p = wavesDisplace(vec2(0.0), 0.0);
    fragColor = vec4(worldLambert(vec3(0.5), vec3(0.0, 1.0, 0.0), vec3(1.0)) + p * 0.0, 1.0);
}
