#version 330 compatibility
// world_layers: a triangle over the whole viewport (no vertex buffer), or
// the band's triangles (uLayerBand; world_layer_band.h: the tiles whose
// pixels can change with the time; gl_Vertex.xy in the layers' viewport,
// placed in the frame's by uLayerBandMap, each corner moved outward by
// uLayerBandPad along gl_Vertex.zw), and the waves' height bound, which is
// the same for every pixel: taken once a vertex here, the fragments skip
// its loops (3-4 ms of a 960x540 pass on llvmpipe, which runs every pixel
// through them).
#include "waves.glsl"
#include "world_wet.glsl"

uniform bool uLayerBand;
uniform vec4 uLayerBandMap;
uniform vec2 uLayerBandPad;
flat out float vWavesBound;

void main() {
    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    vec2 band = gl_Vertex.xy * uLayerBandMap.xy + uLayerBandMap.zw + gl_Vertex.zw * uLayerBandPad;
    gl_Position = vec4(uLayerBand ? band : p, 0.0, 1.0);
    vWavesBound = worldWavesBound();
}
