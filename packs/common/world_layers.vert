#version 330 compatibility
// world_layers: a triangle over the whole viewport (no vertex buffer), and
// the waves' height bound, which is the same for every pixel: taken once a
// vertex here, the fragments skip its loops (3-4 ms of a 960x540 pass on
// llvmpipe, which runs every pixel through them).
#include "waves.glsl"
#include "world_wet.glsl"

flat out float vWavesBound;

void main() {
    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    gl_Position = vec4(p, 0.0, 1.0);
    vWavesBound = worldWavesBound();
}
