#version 330 compatibility
#ifdef WORLD_LAYERS_MS
#extension GL_ARB_sample_shading : require
#endif
// A World draw again at a new time from its layers (render.c, world_cache):
// the world's shading depends on the time only through whether a point is
// under the moving surface (world_wet.glsl), so a draw that kept, per
// pixel, both shadings, the point and the depth is finished here by that
// one test: the pixels a drawn World gives, at the cost of a full-screen
// pass instead of the terrain's and objects' shading.
//
// WORLD_LAYERS_MS: the layers and the frame are multisampled (`tarn
// render`'s default 4x MSAA). The build shaded a pixel once and wrote it
// to the samples its triangle covers, as the drawn World does; here each
// sample is composed on its own (gl_SampleID runs this once a sample),
// the depth copied from the layers' beforehand, so an edge keeps the
// samples, and the resolve the colour, the drawn World's. With uLayerPickBand the
// pass instead writes, into a one-sample target, a pixel's point that lies
// in the band of heights uLayerBandHeights if any of its samples' does
// (world_layer_band.h reads those back to find the tiles to compose).
#include "waves.glsl"
#include "world.glsl"
#include "world_wet.glsl"

#ifdef WORLD_LAYERS_MS
uniform sampler2DMS uLayerWet;   // rgb the wet shading
uniform sampler2DMS uLayerDry;   // rgb the dry shading
uniform sampler2DMS uLayerPos;   // xyz the point, w 1 (0: the sky, never wet)
uniform sampler2DMS uLayerDepth; // the depth (1: nothing drawn)
uniform int uLayerSamples;       // the samples a pixel
uniform bool uLayerPickBand;
uniform vec2 uLayerBandHeights;
#define LAYER_FETCH(s, px) texelFetch(s, px, gl_SampleID)
#define LAYER_SIZE(s) textureSize(s)
#else
uniform sampler2D uLayerWet;    // rgb the wet shading, a the depth
uniform sampler2D uLayerDry;    // rgb the dry shading
uniform sampler2D uLayerPos;    // xyz the point, w 1 (0: the sky, never wet)
#define LAYER_FETCH(s, px) texelFetch(s, px, 0)
#define LAYER_SIZE(s) textureSize(s, 0)
#endif
uniform ivec2 uLayerOrigin;     // the viewport's corner in the target
uniform vec2 uLayerScale;       // texel = (pixel + 0.5) * scale + offset: larger layers serve
uniform vec2 uLayerOffset;      // a smaller frame (world_layers.h); 1, 1 and 0, 0 the texel itself
flat in float vWavesBound;      // worldWavesBound(), once a vertex
out vec4 fragColor;

#ifdef WORLD_LAYERS_MS
// The point of one of px's samples that lies in the band, else sample 0's.
vec4 pickBandPoint(ivec2 px) {
    vec4 first = texelFetch(uLayerPos, px, 0);
    for (int i = 0; i < uLayerSamples; i++) {
        vec4 p = texelFetch(uLayerPos, px, i);
        if (p.w > 0.5 && !(p.y < uLayerBandHeights.x || p.y > uLayerBandHeights.y)) return p;
    }
    return first;
}
#endif

void main() {
    vec2 at = (gl_FragCoord.xy - vec2(uLayerOrigin)) * uLayerScale + uLayerOffset;
    ivec2 px = clamp(ivec2(at), ivec2(0), LAYER_SIZE(uLayerWet) - 1);
    vec4 wet = LAYER_FETCH(uLayerWet, px);
    vec4 pos = LAYER_FETCH(uLayerPos, px);
#ifdef WORLD_LAYERS_MS
    if (uLayerPickBand) {
        fragColor = pickBandPoint(px);
        return;
    }
    // the depth is copied from the layers' (world_layers_copy_depth): a
    // sample's depth written from here went through a float and back
    if (LAYER_FETCH(uLayerDepth, px).r >= 1.0) discard;   // nothing drawn there
#else
    if (wet.a >= 1.0) discard;   // nothing drawn there: the target keeps its clear
    gl_FragDepth = wet.a;
#endif
    bool under = pos.w > 0.5 && worldUnderWaterWithin(pos.xyz, vWavesBound);
    fragColor = vec4(under ? wet.rgb : LAYER_FETCH(uLayerDry, px).rgb, 1.0);
}
