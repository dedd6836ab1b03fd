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
#ifndef WAVES_OCEAN_GLSL
#define WAVES_OCEAN_GLSL

#define WAVES_OCEAN_CASCADES_MAX 3

uniform sampler2DArray uOceanA, uOceanB;
uniform int uOceanN;                               // cascades, 0: no ocean
uniform int uOceanRes;                             // N, a power of two
uniform float uOceanTile[WAVES_OCEAN_CASCADES_MAX];   // L_c

void wavesOcean(vec2 p0, inout float h, inout vec2 dh, inout vec2 disp, inout vec3 abd) {
    for (int c = 0; c < WAVES_OCEAN_CASCADES_MAX; c++) {
        if (c >= uOceanN) break;
        float L = uOceanTile[c];
        vec2 q = p0 / L;
        q = (q - floor(q)) * float(uOceanRes);     // in [0, N]: the rest point in nodes
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
        vec4 a = mix(mix(a00, a10, w.x), mix(a01, a11, w.x), w.y);
        vec4 b = mix(mix(b00, b10, w.x), mix(b01, b11, w.x), w.y);
        h += a.x;
        disp += a.yz;
        dh += b.xy;
        abd += vec3(b.z, a.w, b.w);
    }
}

#endif // WAVES_OCEAN_GLSL
