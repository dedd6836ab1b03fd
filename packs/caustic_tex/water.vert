#version 330 compatibility
// The lake's water grid (world space, gl_Vertex the rest point), displaced
// by the scene's wave set (packs/common/waves.glsl), as in packs/basic.
#include "waves.glsl"

uniform float uTime;
out vec2 vRest;
out vec3 vWorldPos;

void main() {
    vec3 pos, normal;
    wavesEval(gl_Vertex.xz, uTime, pos, normal);
    vRest = gl_Vertex.xz;
    vWorldPos = pos;
    gl_Position = gl_ModelViewProjectionMatrix * vec4(pos, 1.0);
}
