#version 330 compatibility
// The water grid is in world space (gl_Vertex is the rest point); the wave
// set of packs/common/waves.glsl displaces it.
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
