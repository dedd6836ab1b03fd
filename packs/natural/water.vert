#version 330 compatibility
// packs/natural: the water grid, displaced by the scene's wave set
// (packs/common/waves.glsl), through the current camera.
#include "contract.glsl"
#include "waves.glsl"

out vec2 vRest;
out vec3 vWorldPos;

void main() {
    vec3 pos, normal;
    wavesEval(gl_Vertex.xz, uTime, pos, normal);
    vRest = gl_Vertex.xz;
    vWorldPos = pos;
    gl_Position = gl_ModelViewProjectionMatrix * vec4(pos, 1.0);
}
