#version 330 compatibility
// A World draw again at a new time from its layers (render.c, world_cache):
// the world's shading depends on the time only through whether a point is
// under the moving surface (world_wet.glsl), so a draw that kept, per
// pixel, both shadings, the point and the depth is finished here by that
// one test: the pixels a drawn World gives, at the cost of a full-screen
// pass instead of the terrain's and objects' shading.
#include "waves.glsl"
#include "world.glsl"
#include "world_wet.glsl"

uniform sampler2D uLayerWet;    // rgb the wet shading, a the depth
uniform sampler2D uLayerDry;    // rgb the dry shading
uniform sampler2D uLayerPos;    // xyz the point, w 1 (0: the sky, never wet)
uniform ivec2 uLayerOrigin;     // the viewport's corner in the target
uniform vec2 uLayerScale;       // texel = (pixel + 0.5) * scale + offset: larger layers serve
uniform vec2 uLayerOffset;      // a smaller frame (world_layers.h); 1, 1 and 0, 0 the texel itself
flat in float vWavesBound;      // worldWavesBound(), once a vertex
out vec4 fragColor;

void main() {
    vec2 at = (gl_FragCoord.xy - vec2(uLayerOrigin)) * uLayerScale + uLayerOffset;
    ivec2 px = clamp(ivec2(at), ivec2(0), textureSize(uLayerWet, 0) - 1);
    vec4 wet = texelFetch(uLayerWet, px, 0);
    vec4 pos = texelFetch(uLayerPos, px, 0);
    if (wet.a >= 1.0) discard;   // nothing drawn there: the target keeps its clear
    gl_FragDepth = wet.a;
    bool under = pos.w > 0.5 && worldUnderWaterWithin(pos.xyz, vWavesBound);
    fragColor = vec4(under ? wet.rgb : texelFetch(uLayerDry, px, 0).rgb, 1.0);
}
