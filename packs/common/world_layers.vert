#version 330 compatibility
// world_layers: a triangle over the whole viewport (no vertex buffer), or
// the band's triangles (uLayerBand: gl_Vertex, in the viewport's [-1, 1];
// world_layer_band.h: the tiles whose pixels can change with the time),
// and the waves' height bound, which is the same for every pixel: taken
// once a vertex here, the fragments skip its loops (3-4 ms of a 960x540
// pass on llvmpipe, which runs every pixel through them).
#include "waves.glsl"
#include "world_wet.glsl"

uniform bool uLayerBand;
flat out float vWavesBound;

void main() {
    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    gl_Position = vec4(uLayerBand ? gl_Vertex.xy : p, 0.0, 1.0);
    vWavesBound = worldWavesBound();
}
