#version 330 compatibility
// packs/natural, the paper's caustics: the water surface seen from the
// light camera (orthographic along the sun), one photon per light texel.
#include "contract.glsl"
#include "waves.glsl"

out vec2 vRest;
out vec3 vWorldPos;
out vec2 vLightNdc;

void main() {
    vec3 pos, normal;
    wavesEval(gl_Vertex.xz, uTime, pos, normal);
    vRest = gl_Vertex.xz;
    vWorldPos = pos;
    vec4 c = uCamLightVP * vec4(pos, 1.0);
    vLightNdc = c.xy / c.w;
    gl_Position = c;
}
