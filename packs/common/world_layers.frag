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
flat in float vWavesBound;      // worldWavesBound(), once a vertex
out vec4 fragColor;

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy) - uLayerOrigin;
    vec4 wet = texelFetch(uLayerWet, px, 0);
    vec4 pos = texelFetch(uLayerPos, px, 0);
    if (wet.a >= 1.0) discard;   // nothing drawn there: the target keeps its clear
    gl_FragDepth = wet.a;
    bool under = pos.w > 0.5 && worldUnderWaterWithin(pos.xyz, vWavesBound);
    fragColor = vec4(under ? wet.rgb : texelFetch(uLayerDry, px, 0).rgb, 1.0);
}
