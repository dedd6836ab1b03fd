// flow.glsl: the world's flow field and the fine detail it carries
// (issue #29; tarn's viewer/gfx/render_flow.c runs the pass, docs/waves.md
// "Flow and spray" tells the method). Included by waves.glsl when the world
// has a `Flow` (WAVES_HAS_FLOW) and by flow_advect.frag (FLOW_ADVECT_PASS,
// the velocity and the map's frame only). No #version here.
//
// Texture advection by backward mapping, the flow-map way: the map
// uFlowMap (unit 26, RGBA16F over the square |x|, |z| <= uFlowRect.x)
// holds for two layers A and B how far the content now at each texel has
// travelled since the layer last restarted, d = x - source (rg: A, ba: B).
// Each frame every texel looks up where its content came from, semi-
// Lagrangian with a midpoint step and a bilinear read:
//     back = x - dt v(x - dt v(x) / 2),   d'(x) = (x - back) + d(back)
// so no texel is left empty and none stuck (forward mapping's faults).
// The detail, noise ripples and foam streaks, is drawn at the source point
// x - d of each layer; a layer restarts (d = 0) every uFlowDetail.w seconds,
// half a period apart, and the two are blended with weights that are 0 at
// a layer's restart, so the stretching a shear or a vortex builds up never
// shows (Max & Becker 1995; Vlachos 2010's two-phase flow map).
//
//   vec2  flowVelocity(vec2 xz)          m/s, the sum of the terms
//   vec2  flowMapUv(vec2 xz)             the map's texture coordinates
//   vec2  flowSlope(vec2 xz)             the advected ripples' (dh/dx, dh/dz)
//   float flowFoam(vec2 xz)              the advected foam streaks' cover, 0..1
#ifndef FLOW_GLSL
#define FLOW_GLSL
#include "loops.glsl"        // ROLLED(n): loop bounds

#define FLOW_TERMS_MAX 4
#define FLOW_CURRENT 1
#define FLOW_VORTEX 2
#define FLOW_TEXTURE 3

uniform int   uFlowN;                       // terms, 1..FLOW_TERMS_MAX
uniform int   uFlowKind[FLOW_TERMS_MAX];    // FLOW_CURRENT, FLOW_VORTEX
uniform vec4  uFlowTerm[FLOW_TERMS_MAX];    // current (vx, vz, 0, 0); vortex (x, z, strength, radius)
uniform vec2  uFlowRect;                    // (half side of the map's square, 1 / side)
#ifdef FLOW_ADVECT_PASS
uniform sampler2D uFlowVel;                 // unit 22: a Flow texture's velocity map, (vx, vz) = (2 rg - 1) scale
uniform float uFlowVelHalf;                 // it covers |x|, |z| <= this (the world square), top row at -z
#endif

vec2 flowVelocity(vec2 xz) {
    vec2 v = vec2(0.0);
    for (int i = 0; i < ROLLED(FLOW_TERMS_MAX); i++) {
        if (i >= uFlowN) break;
        vec4 p = uFlowTerm[i];
        if (uFlowKind[i] == FLOW_CURRENT) {
            v += p.xy;
#ifdef FLOW_ADVECT_PASS
        } else if (uFlowKind[i] == FLOW_TEXTURE) {
            vec2 st = (xz / uFlowVelHalf) * 0.5 + 0.5;
            v += (texture(uFlowVel, st).rg * 2.0 - 1.0) * p.x;
#endif
        } else if (uFlowKind[i] == FLOW_VORTEX) {                                // Rankine: s r / R inside, s R / r outside
            vec2 r = xz - p.xy;
            float d = length(r), R = p.w;
            float speed = d < R ? p.z * d / R : p.z * R / d;
            if (d > 0.0) v += speed * vec2(-r.y, r.x) / d;   // anticlockwise from +y for s > 0
        }
    }
    return v;
}

vec2 flowMapUv(vec2 xz) { return (xz + uFlowRect.x) * uFlowRect.y; }

#ifndef FLOW_ADVECT_PASS
uniform sampler2D uFlowMap;                 // unit 26: (d_A.xz, d_B.xz) metres
uniform vec4  uFlowDetail;                  // (amplitude m, 1 / cell, foam cover, 0)
uniform vec2  uFlowWeight;                  // the layers' weights now, 1 - |2 phase - 1| and its complement

// Two octaves of the wave noise at q (lattice units), as (h, dh/dq).
vec3 flowNoise(vec2 q, uint seed) {
    vec3 a = wavesNoiseOctave(q, 4096.0, seed);
    vec3 b = wavesNoiseOctave(q * 2.03 + 17.0, 4096.0, seed + 101u);
    return a + 0.5 * vec3(b.x, 2.03 * b.yz);
}

vec2 flowSlope(vec2 xz) {
    vec4 d = texture(uFlowMap, flowMapUv(xz));
    float f = uFlowDetail.y;
    vec2 sa = flowNoise((xz - d.xy) * f, 0x6a09e667u).yz;
    vec2 sb = flowNoise((xz - d.zw) * f + 311.0, 0xbb67ae85u).yz;
    // two independent layers blended keep their variance with this norm
    vec2 w = uFlowWeight / max(length(uFlowWeight), 1e-4);
    return uFlowDetail.x * f * (w.x * sa + w.y * sb);
}

// Foam streaks: thin lines along a noise's zero contour, in patches of a
// coarser noise, both drawn at the layers' source points, so a current
// carries them and a vortex winds them into spirals.
float flowFoamLayer(vec2 q, float seed) {
    float line = 1.0 - smoothstep(0.015, 0.07, abs(flowNoise(q + seed, 0x3c6ef372u).x));
    float patch = smoothstep(0.0, 0.25, flowNoise(q * 0.37 + 2.0 * seed, 0xa54ff53au).x);
    return line * patch;
}

float flowFoam(vec2 xz) {
    if (uFlowDetail.z <= 0.0) return 0.0;
    vec4 d = texture(uFlowMap, flowMapUv(xz));
    float f = uFlowDetail.y * 0.5;              // streaks coarser than the ripples
    float a = flowFoamLayer((xz - d.xy) * f, 53.0), b = flowFoamLayer((xz - d.zw) * f, 97.0);
    return uFlowDetail.z * (uFlowWeight.x * a + uFlowWeight.y * b);
}
#endif

#endif // FLOW_GLSL
