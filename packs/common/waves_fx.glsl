// waves_fx.glsl: the explosion rings and 3D Perlin wave sets in GLSL
// (float), height-only wave models shared by every pack. The double-
// precision twin is reference/ref_wavefx.c (formulas and bounds in
// reference/ref_wavefx.h): the same functions, term for term; the uniforms
// come resolved from ref_wavefx_uniforms, so no vertex works out a
// default, an octave's frequency or a seed again. Include it after
// #version (330 or later: uint hashing). No #version here.
//
//   ring i (uExplosion[i] = (cx, cz, t0, I0), uExplosionWave[i] = (omega, k, b, k^2)):
//       tau = t - t0 (no wave for tau <= 0), q = k s = sqrt(k^2 r^2 + 1),
//       phi = q - omega tau, E = 1 - fade(clamp(1 + phi / 2pi, 0, 1)),
//       h = I0 e^{-b tau} E sin(phi) / sqrt(q)
//   Perlin set: (a, c) = p0 in the wind's frame (uPerlinFrame = (cos, sin,
//       1/stretch, 0)), octave o (uPerlinOctave[o] = (f_o, rate_o, A_o, 0),
//       uPerlinSeed[o]): h = sum A_o noise3(a f_o, c f_o / stretch, t rate_o, seed_o)
//
// Functions (heights relative to the level; grad in (x0, z0), or the
// noise's lattice coordinates for wavesPerlin3):
//   float wavesExplosions(vec2 p0, float t, out vec2 grad)
//   float wavesPerlin(vec2 p0, float t, out vec2 grad)
//   float wavesPerlin3(vec3 p, uint seed, out vec3 grad)
//
// Loops run `for (i < MAX) { if (i >= N) break; }`: llvmpipe executes both
// sides of an if on a uniform but leaves a loop at once, so a scene with no
// rings or no Perlin set pays for neither.
//
// Float precision (what the GL test's tolerance rests on):
//   ring: phi = q - omega tau is formed from q and omega tau, each rounded
//   to a relative 2^-24 (sqrt, products: a few ulps), so
//   |d phi| <~ 3 * 2^-24 (q + omega tau) + omega |d tau|, and tau = t - t0
//   carries 2^-24 |t|. At t = 60 s, omega 8 rad/s, r = 30 m, k = 2 pi:
//   q + omega tau ~ 670 rad -> 1.2e-4 rad, plus 8 * 3.6e-6 rad; the height
//   error is then <= |I0| |d phi| (sqrt(q) >= 1) and the gradient's
//   <= 1.28 |I0| k |d phi|. Keep times small (the app may wrap them).
//   Perlin: the lattice coordinate X = a f_o is rounded to 2^-24 |X| (plus
//   the rotation's 2^-24 |p0| f_o), so the fraction inside the cell is off
//   by ~2^-23 |X| cells and the height by <= A_o 3.75 sqrt(2) 2^-23 |X|:
//   1e-4 A_o at |X| = 200 cells, which is 25 m at octave 7 of a 4 m cell.
//   Time is a lattice coordinate too: t rate_o, same rule.
#ifndef WAVES_FX_GLSL
#define WAVES_FX_GLSL

#include "hash.glsl"
#include "loops.glsl"        // ROLLED(n): loop bounds

#define WAVES_EXPLOSIONS_MAX 4
#define WAVES_PERLIN_OCTAVES_MAX 8

uniform int   uExplosionN;                               // live rings (I0 != 0), 0..4
uniform vec4  uExplosion[WAVES_EXPLOSIONS_MAX];          // (centre x, centre z, t0, I0)
uniform vec4  uExplosionWave[WAVES_EXPLOSIONS_MAX];      // (omega, k, decay b, k^2)
uniform int   uPerlinN;                                  // octaves; 0: no Perlin set
uniform vec4  uPerlinOctave[WAVES_PERLIN_OCTAVES_MAX];   // (f_o 1/m, rate_o lattice/s, A_o m, 0)
uniform vec4  uPerlinFrame;                              // (cos angle, sin angle, 1 / stretch, 0)
uniform uint  uPerlinSeed[WAVES_PERLIN_OCTAVES_MAX];     // seed_o

const float WAVES_FX_TWO_PI = 6.28318530717958648;

float wavesExplosions(vec2 p0, float t, out vec2 grad) {
    float h = 0.0;
    grad = vec2(0.0);
    for (int i = 0; i < ROLLED(WAVES_EXPLOSIONS_MAX); i++) {
        if (i >= uExplosionN) break;
        vec4 e = uExplosion[i];
        vec4 w = uExplosionWave[i];
        float tau = t - e.z;
        vec2 d = p0 - e.xy;
        float q = sqrt(w.w * dot(d, d) + 1.0);            // k s >= 1
        float phi = q - w.x * tau;
        float x = 1.0 + phi / WAVES_FX_TWO_PI;             // (s - R + W) / W
        if (tau <= 0.0 || x >= 1.0) continue;              // before the start, or beyond the front
        float xc = max(x, 0.0);
        float E = 1.0 - xc * xc * xc * (xc * (xc * 6.0 - 15.0) + 10.0);
        float dE = -30.0 * xc * xc * (xc - 1.0) * (xc - 1.0) / WAVES_FX_TWO_PI;
        float amp = e.w * exp(-w.z * tau) * inversesqrt(q);
        float sn = sin(phi), cs = cos(phi);
        float dhdq = amp * ((dE - E / (2.0 * q)) * sn + E * cs);
        h += amp * E * sn;
        grad += (dhdq * w.w / q) * d;                      // grad q = k^2 (p0 - c) / q
    }
    return h;
}

const vec3 WAVES_FX_EDGE[12] = vec3[12](
    vec3( 1.0,  1.0,  0.0), vec3(-1.0,  1.0,  0.0), vec3( 1.0, -1.0,  0.0), vec3(-1.0, -1.0,  0.0),
    vec3( 1.0,  0.0,  1.0), vec3(-1.0,  0.0,  1.0), vec3( 1.0,  0.0, -1.0), vec3(-1.0,  0.0, -1.0),
    vec3( 0.0,  1.0,  1.0), vec3( 0.0, -1.0,  1.0), vec3( 0.0,  1.0, -1.0), vec3( 0.0, -1.0, -1.0));

// One corner b (0 or 1 per axis) of the cell il: adds its weighted term.
void wavesFxCorner(uvec3 il, uvec3 b, vec3 f, vec3 w0, vec3 w1, vec3 dw, uint seed,
                   inout float n, inout vec3 g) {
    uint h = tarnHash(il.x + b.x + tarnHash(il.y + b.y + tarnHash(il.z + b.z + seed)));
    vec3 gv = WAVES_FX_EDGE[h % 12u];
    vec3 bf = vec3(b);
    float val = dot(gv, f - bf);
    vec3 w = mix(w0, w1, bf);                      // weights of this corner along each axis
    vec3 s = mix(-dw, dw, bf);                     // their derivatives
    float wc = w.x * w.y * w.z;
    n += wc * val;
    g += vec3(s.x * w.y * w.z, w.x * s.y * w.z, w.x * w.y * s.z) * val + wc * gv;
}

float wavesPerlin3(vec3 p, uint seed, out vec3 grad) {
    vec3 fl = floor(p);
    vec3 f = p - fl;
    uvec3 il = uvec3(ivec3(fl));
    vec3 w1 = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    vec3 w0 = 1.0 - w1;
    vec3 dw = 30.0 * f * f * (f - 1.0) * (f - 1.0);
    float n = 0.0;
    grad = vec3(0.0);
    wavesFxCorner(il, uvec3(0u, 0u, 0u), f, w0, w1, dw, seed, n, grad);
    wavesFxCorner(il, uvec3(1u, 0u, 0u), f, w0, w1, dw, seed, n, grad);
    wavesFxCorner(il, uvec3(0u, 1u, 0u), f, w0, w1, dw, seed, n, grad);
    wavesFxCorner(il, uvec3(1u, 1u, 0u), f, w0, w1, dw, seed, n, grad);
    wavesFxCorner(il, uvec3(0u, 0u, 1u), f, w0, w1, dw, seed, n, grad);
    wavesFxCorner(il, uvec3(1u, 0u, 1u), f, w0, w1, dw, seed, n, grad);
    wavesFxCorner(il, uvec3(0u, 1u, 1u), f, w0, w1, dw, seed, n, grad);
    wavesFxCorner(il, uvec3(1u, 1u, 1u), f, w0, w1, dw, seed, n, grad);
    return n;
}

float wavesPerlin(vec2 p0, float t, out vec2 grad) {
    float h = 0.0;
    vec2 gac = vec2(0.0);                          // d/da, d/dc
    vec2 ac = vec2(dot(p0, uPerlinFrame.xy), uPerlinFrame.x * p0.y - uPerlinFrame.y * p0.x);
    for (int o = 0; o < ROLLED(WAVES_PERLIN_OCTAVES_MAX); o++) {
        if (o >= uPerlinN) break;
        vec4 oc = uPerlinOctave[o];
        vec2 sc = vec2(oc.x, oc.x * uPerlinFrame.z);   // lattice units per metre along a, c
        vec3 g3;
        float n = wavesPerlin3(vec3(ac * sc, t * oc.y), uPerlinSeed[o], g3);
        h += oc.z * n;
        gac += oc.z * sc * g3.xy;
    }
    grad = vec2(gac.x * uPerlinFrame.x - gac.y * uPerlinFrame.y,
                gac.x * uPerlinFrame.y + gac.y * uPerlinFrame.x);
    return h;
}

#endif
