// xing_look.glsl: what Xing's water looks like, shared by his two-quad
// scene (water.glib) and the lake (pack.glib):
//   - caustics from a tileable caustic texture in two layers moved by the
//     waves, with chromatic aberration (xingCausticTex), or GPU Gems 1
//     ch. 2's backward caustics (xingCausticBackward);
//   - the tileable ripple normal map, sampled twice (xingRippleSlope);
//   - the foam of red and blue circles, sampled twice (xingFoam).
// Define UV_FLIP to swap U and V of the second copy of each two-layer
// lookup, so that the two scrolled layers never line up.
// Samplers: uCausticTex (@caustics: one channel, mean 1, tileable),
// uFoamTex (@foam: R and B two independent disc masks), uWaterNormalTex
// (@water_normal: rgb = 0.5 + 0.5 (n.x, n.z, n.y)).
#ifndef XING_LOOK_GLSL
#define XING_LOOK_GLSL

uniform sampler2D uCausticTex;
uniform sampler2D uFoamTex;
uniform sampler2D uWaterNormalTex;

uniform float uCausticWave;      // how far each wave's displacement moves its layer
uniform float uCausticOffset;    // the second layer's offset, in tiles
uniform float uCausticVisible;   // 0 none, 1 the traced pattern (mean 1), >1 exaggerated
uniform float uChromaticOffset;  // R and B this far (tiles) each side of G; backward: +-delta n
uniform float uCausticScale;     // (ours) units of the floor per caustic tile
uniform float uWaterTiling;      // ripple tiles across the water
uniform float uWaterBump;        // (ours) how much of the ripple slope is added
uniform bool  uShowFoam;
uniform float uFoamWidth;        // (ours) how far the foam reaches in from the border

#define XING_CAUSTIC_MAX 64.0    // backward caustics: no factor above this
#ifndef CAUSTIC_POWER
#define CAUSTIC_POWER 16         // backward caustics: the exponent (a Define slider)
#endif

vec2 xingFlip(vec2 uv) {
#ifdef UV_FLIP
    return uv.yx;
#else
    return uv;
#endif
}

// A unit horizontal direction along which the colours separate: the
// light's, or the diagonal when the light is straight above.
vec2 xingChromaDir(vec3 towardsLight) {
    float l = length(towardsLight.xz);
    return l > 1e-4 ? towardsLight.xz / l : vec2(0.70710678);
}

// One layer: R, G, B at uv + dc, uv, uv - dc.
vec3 xingCausticLayer(vec2 uv, vec2 dc) {
    return vec3(texture(uCausticTex, uv + dc).r, texture(uCausticTex, uv).r,
                texture(uCausticTex, uv - dc).r);
}

// The caustic factor (per channel, mean 1 at uCausticVisible 1) at floor
// point xz. offA, offB: the displacements of the two wave kinds above it,
// in floor units; contrast scales the pattern's deviation from 1 (the
// visibility, times a depth fade on the lake).
// scale: floor units per tile (xingCausticTex: uCausticScale).
vec3 xingCausticTexScaled(vec2 xz, vec2 offA, vec2 offB, vec2 chromaDir, float contrast, float scale) {
    scale = max(scale, 1e-3);
    vec2 uv = xz / scale;
    vec2 uvA = uv + uCausticWave * offA / scale;
    vec2 uvB = xingFlip(uv + uCausticWave * offB / scale) + vec2(uCausticOffset);
    vec2 dc = uChromaticOffset * chromaDir;
    vec3 k = 0.5 * (xingCausticLayer(uvA, dc) + xingCausticLayer(uvB, dc));
    return max(1.0 + contrast * (k - 1.0), 0.0);
}

vec3 xingCausticTex(vec2 xz, vec2 offA, vec2 offB, vec2 chromaDir, float contrast) {
    return xingCausticTexScaled(xz, offA, offB, chromaDir, contrast, uCausticScale);
}

// GPU Gems 1 ch. 2 (Guardado and Sanchez-Crespo), the backward method:
// the vertical ray from the floor point up to the surface is refracted
// out through the surface normal n there; the closer it points to the
// light (unit, towards it), the brighter: (dot(t, L) / L.y)^p (p the
// Define CAUSTIC_POWER), so flat
// water gives 1. Chromatic aberration: R, G, B refract with the index
// ior - d, ior, ior + d (d = uChromaticOffset). Total internal
// reflection gives 0; the factor is clamped to XING_CAUSTIC_MAX.
vec3 xingCausticBackward(vec3 n, vec3 towardsLight, float ior, float contrast) {
    float ly = max(towardsLight.y, 1e-3);
    float p = max(float(CAUSTIC_POWER), 0.0);
    vec3 k;
    for (int c = 0; c < 3; c++) {
        float eta = max(ior + float(c - 1) * uChromaticOffset, 1.0);
        vec3 t = refract(vec3(0.0, 1.0, 0.0), -n, eta);   // water to air
        float d = clamp(dot(t, towardsLight) / ly, 0.0, 2.0);
        k[c] = min(pow(d, p), XING_CAUSTIC_MAX);
    }
    return max(1.0 + contrast * (k - 1.0), 0.0);
}

// The ripple map sampled twice, scrolled two ways; returns the slope
// (dh/dx, dh/dz) of the mean of the two. The map encodes n as
// (n.x, n.z, n.y); a copy read at uv.yx has its s axis along world z, so
// its components swap too.
vec2 xingRippleSlope(vec2 uv, vec2 scrollA, vec2 scrollB) {
    vec3 a = texture(uWaterNormalTex, uv + scrollA).rgb * 2.0 - 1.0;
    vec3 b = texture(uWaterNormalTex, xingFlip(uv + scrollB)).rgb * 2.0 - 1.0;
    vec2 sa = -a.xy / max(a.z, 0.1);
#ifdef UV_FLIP
    vec2 sb = -b.yx / max(b.z, 0.1);
#else
    vec2 sb = -b.xy / max(b.z, 0.1);
#endif
    return 0.5 * (sa + sb);
}

// The wave normal with the ripple slope added (times uWaterBump).
vec3 xingBumpNormal(vec3 n, vec2 slope) {
    float ny = max(abs(n.y), 0.05);
    vec3 m = vec3(n.x / ny - uWaterBump * slope.x, n.y >= 0.0 ? 1.0 : -1.0, n.z / ny - uWaterBump * slope.y);
    return normalize(m);
}

// Xing's foam: the texture of red and blue circles sampled twice (scrolled
// two ways), the four masks summed and subtracted from 1: white lace with
// round holes. It fades from the border (edge 0, 1 at uFoamWidth in) to
// the centre, and grows with the wave amplitude (full at 0.1).
float xingFoam(vec2 uv, vec2 scrollA, vec2 scrollB, float edge, float ampSum) {
    if (!uShowFoam) return 0.0;
    vec3 a = texture(uFoamTex, uv + scrollA).rgb;
    vec3 b = texture(uFoamTex, xingFlip(uv + scrollB)).rgb;
    float lace = clamp(1.0 - (a.r + a.b + b.r + b.b), 0.0, 1.0);
    float fade = 1.0 - smoothstep(0.0, 1.0, edge / max(uFoamWidth, 1e-4));
    return lace * fade * clamp(ampSum / 0.1, 0.0, 1.0);
}

#endif
