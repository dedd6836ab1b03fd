#version 330 compatibility
// The lake's water grid (world space, gl_Vertex the rest point), displaced
// by the scene's wave set (packs/common/waves.glsl), as in packs/basic.
#include "contract.glsl"
#include "waves.glsl"
#include "scene_waves.glsl"

out vec2 vRest;
out vec3 vWorldPos;
flat out float vWaveAmpSum;         // water.frag's foam strength
flat out float vCausticWavelength;  // and its caustic tile's scale
flat out vec4 vCausticVel;          // and motion

void main() {
    vec3 pos, normal;
    wavesEval(gl_Vertex.xz, uTime, pos, normal);
    vRest = gl_Vertex.xz;
    vWorldPos = pos;
    vWaveAmpSum = waveAmpSum();
    vec2 velS, velG;
    vCausticWavelength = sceneCausticWavelength(velS, velG);
    vCausticVel = vec4(velS, velG);
    gl_Position = gl_ModelViewProjectionMatrix * vec4(pos, 1.0);
}
