// waves_ocean.glsl: the spectrum ocean's surface (reference/ref_ocean.h),
// read from the frame tarn computes on the GPU each frame
// (viewer/gfx/render_ocean.c): per cascade c a periodic tile of side
// uOceanTile[c] sampled on uOceanRes^2 nodes, node (m, n) at
// (m, n) L / N, layer c of
//     uOceanA = (h, Dx, Dz, Dxz)    uOceanB = (hx, hz, Dxx, Dzz)
// (lambda folded into the D fields). Between nodes each field is the
// BILINEAR interpolation of the four nodes around, blended here by hand
// from texelFetch (hardware filtering has 8-bit weights on some GPUs), so
// every GPU evaluates the function the reference does. The cascades add.
// uOceanN = 0: no ocean, and the loop leaves at once (llvmpipe would run
// both sides of an if). Included by waves.glsl; no #version here.
//
//   void wavesOcean(vec2 p0, inout float h, inout vec2 dh, inout vec2 disp, inout vec3 abd)
//       adds, at rest point p0, the height h, its slope dh = (hx, hz), the
//       sideways displacement disp = (Dx, Dz) and its Jacobian entries
//       abd = (dDx/du, dDx/dv = dDz/du, dDz/dv) = (Dxx, Dxz, Dzz), of the
//       frame the textures hold (the time is the frame's).
//   void wavesOceanFiltered(vec2 p0, float footprint, inout float h, inout vec2 dh,
//                           inout vec2 disp, inout vec3 abd, inout float lostVar)
//       the same with each cascade's slope dh and Jacobian abd weighted by
//       wavesOceanWeight(footprint, c) (height and displacement whole), and
//       lostVar += (1 - w^2) sigma_c^2, the slope variance the weights
//       removed (sigma_c^2: the tile's mean hx^2 + hz^2, uOceanFoam's g)
//   float wavesOceanWeight(float footprint, int c)
//       1 - smoothstep(0.5, 2, footprint / (L_c / N)): how much of cascade
//       c a pixel whose footprint on the rest plane is `footprint` metres
//       can show; 1 at footprint 0, 0 past two texels (aliasing)
//   float wavesFoam(vec2 p0)
//       the folding foam at rest point p0, 0..1: the cascades' foam layers
//       (render_ocean.c: max(foam_prev exp(-dt / decay), coverage(J)) each
//       frame, J = (1 + Dxx)(1 + Dzz) - Dxz^2 of the cascade's own
//       fields), bilinear, their maximum
//   float wavesFoamFiltered(vec2 p0, float footprint)
//       the same with each cascade's foam weighted by wavesOceanWeight
//       (a cascade's foam finer than the pixel would sparkle)
// uOceanFoam (unit 27, OCEAN_UNIT_FOAM) = (foam, sigma_c^2) a node, one
// layer a cascade, declared only where WAVES_HAS_OCEAN is.
#ifndef WAVES_OCEAN_GLSL
#define WAVES_OCEAN_GLSL
#include "loops.glsl"        // ROLLED(n): loop bounds

#define WAVES_OCEAN_CASCADES_MAX 3

uniform sampler2DArray uOceanA, uOceanB;
uniform int uOceanN;                               // cascades, 0: no ocean
uniform int uOceanRes;                             // N, a power of two
uniform float uOceanTile[WAVES_OCEAN_CASCADES_MAX];   // L_c

// Cascade c's fields at rest point p0, bilinear between its nodes.
void wavesOceanFetch(vec2 p0, int c, out vec4 a, out vec4 b) {
    float L = uOceanTile[c];
    vec2 q = p0 / L;
    q = (q - floor(q)) * float(uOceanRes);         // in [0, N]: the rest point in nodes
    vec2 f = floor(q), w = q - f;
    int mask = uOceanRes - 1;
    ivec2 i0 = ivec2(f) & mask, i1 = (i0 + 1) & mask;
    vec4 a00 = texelFetch(uOceanA, ivec3(i0.x, i0.y, c), 0);
    vec4 a10 = texelFetch(uOceanA, ivec3(i1.x, i0.y, c), 0);
    vec4 a01 = texelFetch(uOceanA, ivec3(i0.x, i1.y, c), 0);
    vec4 a11 = texelFetch(uOceanA, ivec3(i1.x, i1.y, c), 0);
    vec4 b00 = texelFetch(uOceanB, ivec3(i0.x, i0.y, c), 0);
    vec4 b10 = texelFetch(uOceanB, ivec3(i1.x, i0.y, c), 0);
    vec4 b01 = texelFetch(uOceanB, ivec3(i0.x, i1.y, c), 0);
    vec4 b11 = texelFetch(uOceanB, ivec3(i1.x, i1.y, c), 0);
    a = mix(mix(a00, a10, w.x), mix(a01, a11, w.x), w.y);
    b = mix(mix(b00, b10, w.x), mix(b01, b11, w.x), w.y);
}

void wavesOcean(vec2 p0, inout float h, inout vec2 dh, inout vec2 disp, inout vec3 abd) {
    for (int c = 0; c < ROLLED(WAVES_OCEAN_CASCADES_MAX); c++) {
        if (c >= uOceanN) break;
        vec4 a, b;
        wavesOceanFetch(p0, c, a, b);
        h += a.x;
        disp += a.yz;
        dh += b.xy;
        abd += vec3(b.z, a.w, b.w);
    }
}

float wavesOceanWeight(float footprint, int c) {
    return 1.0 - smoothstep(0.5, 2.0, footprint * float(uOceanRes) / uOceanTile[c]);
}

#ifdef WAVES_HAS_OCEAN
uniform sampler2DArray uOceanFoam;                 // unit 27: (foam, sigma_c^2) a node, a layer a cascade

void wavesOceanFiltered(vec2 p0, float footprint, inout float h, inout vec2 dh, inout vec2 disp, inout vec3 abd,
                        inout float lostVar) {
    for (int c = 0; c < ROLLED(WAVES_OCEAN_CASCADES_MAX); c++) {
        if (c >= uOceanN) break;
        vec4 a, b;
        wavesOceanFetch(p0, c, a, b);
        float wc = wavesOceanWeight(footprint, c);
        h += a.x;
        disp += a.yz;
        dh += wc * b.xy;
        abd += wc * vec3(b.z, a.w, b.w);
        lostVar += (1.0 - wc * wc) * texelFetch(uOceanFoam, ivec3(0, 0, c), 0).y;
    }
}

float wavesFoamFiltered(vec2 p0, float footprint) {
    float foam = 0.0;
    for (int c = 0; c < ROLLED(WAVES_OCEAN_CASCADES_MAX); c++) {
        if (c >= uOceanN) break;
        float wc = wavesOceanWeight(footprint, c);
        vec2 q = p0 / uOceanTile[c];
        q = (q - floor(q)) * float(uOceanRes);
        vec2 f = floor(q), w = q - f;
        int mask = uOceanRes - 1;
        ivec2 i0 = ivec2(f) & mask, i1 = (i0 + 1) & mask;
        float f00 = texelFetch(uOceanFoam, ivec3(i0.x, i0.y, c), 0).x;
        float f10 = texelFetch(uOceanFoam, ivec3(i1.x, i0.y, c), 0).x;
        float f01 = texelFetch(uOceanFoam, ivec3(i0.x, i1.y, c), 0).x;
        float f11 = texelFetch(uOceanFoam, ivec3(i1.x, i1.y, c), 0).x;
        foam = max(foam, wc * mix(mix(f00, f10, w.x), mix(f01, f11, w.x), w.y));
    }
    return clamp(foam, 0.0, 1.0);
}

float wavesFoam(vec2 p0) { return wavesFoamFiltered(p0, 0.0); }
#endif

#endif // WAVES_OCEAN_GLSL
