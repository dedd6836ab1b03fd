// waves.glsl: tarn's wave set in GLSL (float), shared by every pack.
//
// The double-precision twin is reference/ref_waves.c: the same uniforms,
// the same formulas and the same defaults for zero values, one definition
// each, so the CPU reference and the packs draw the same water
// (docs/reference.md). Include it after #version (330 or later: the noise
// hashes with uint arithmetic). No #version here.
//
//   sum of sines (height only):  h += A sin(k D.p0 + omega t + phase)
//   Gerstner (GPU Gems 1 ch. 1, eq. 9), parametric in the rest point p0:
//       P = (x0 + sum Q_i A_i D.x cos th, level + sum A_i sin th, z0 + sum Q_i A_i D.z cos th)
//       with Q_i = Q / (k_i A_i N), N the number of active Gerstner waves
//   noise: octaves of tileable gradient noise (quintic fade), each drifting
//   spectrum ocean (waves_ocean.glsl; Tessendorf 2001, reference/ref_ocean.h):
//       up to 3 cascades of an N x N tile, inverse-FFT'd on the GPU each
//       frame; adds height h, slope, the choppy sideways displacement
//       lambda D and its Jacobian, bilinear between the tile's nodes;
//       the frame's time is the textures' (wavesSums' t does not move it)
//   explosion rings and 3D Perlin wave sets (waves_fx.glsl; height only,
//       reference/ref_wavefx.h): expanding damped rings from a centre and
//       a start time; octaves of improved Perlin noise in (x, z, t)
//
// k = 2 pi / L, omega = S k, S = sqrt(g L / 2 pi) when the speed is 0.
// A wave with L <= 0 or A == 0 is inactive (and not counted in N).
// y is up; p0 = (x0, z0) are the undisplaced coordinates.
//
// Normals: the exact one is normalize(cross(T, B)) with B = dP/dx0 and
// T = dP/dz0 (the chapter's cross(B, T) in its z-up frame). Define
// WAVES_APPROX_NORMAL before the include to get the chapter's eq. 12
// instead, (-sum D.x WA C, 1 - sum Q_i WA S, -sum D.z WA C), which drops the
// cross terms (exact for a single Gerstner wave).
//
// Functions:
//   vec3  wavesDisplace(vec2 p0, float t)            displaced position P
//   vec3  wavesNormal(vec2 p0, float t)              unit normal (exact, or eq. 12)
//   vec3  wavesNormalExact(vec2 p0, float t)
//   vec3  wavesNormalApprox(vec2 p0, float t)
//   void  wavesEval(vec2 p0, float t, out vec3 pos, out vec3 normal)
//   vec3  wavesNoise(vec2 p0, float t)               (height, d/dx0, d/dz0) of the noise
//   vec2  wavesFootprint(vec2 p0)                    the pixel's footprint on the rest plane
//   vec3  wavesNormalFiltered(vec2 p0, float t, vec2 footprint)
//   vec3  wavesNormalFilteredVar(vec2 p0, float t, vec2 footprint, out float lostVar)
//   float wavesToksvig(float shininess, float lostVar, out float energy)
//   vec2  wavesRestPoint(vec2 xz, float t)            p0 under a world (x, z) (Newton)
//   float wavesHeightAt(vec2 xz, float t)             surface height over a world (x, z)
//
// Filtered normals (the spectrum ocean only: #ifdef WAVES_HAS_OCEAN; the
// pack Define OCEAN_FILTER chooses them). Far out, a pixel covers many
// texels of the ocean's finer cascades, and a normal read at one point of
// each aliases into a salt-and-pepper band of white and dark pixels. As
// ocean renderers do, wavesNormalFiltered fades cascade c's slope and
// Jacobian by w_c = 1 - smoothstep(0.5, 2, footprint / (L_c / N)), the
// footprint being max(footprint.x, footprint.y) metres of rest plane a
// pixel spans (wavesFootprint: the lengths of p0's screen derivatives,
// dFdx and dFdy, so call it where control flow is uniform, at the top of
// main); heights and the sideways displacement stay whole. At footprint
// (0, 0) it equals wavesNormal. wavesNormalFilteredVar also returns the
// slope variance the weights removed, sum (1 - w_c^2) sigma_c^2 (each
// cascade's mean hx^2 + hz^2, from its spectrum); wavesToksvig hands it to
// a Blinn-Phong / Phong highlight as roughness (Toksvig; LEAN mapping's
// idea): alpha^2 = 2 / (m + 2) + lostVar, m' = 2 / alpha^2 - 2, and
// energy = (m' + 2) / (m + 2) keeps the lobe's light, so the sun's glitter
// path stays a broad band instead of vanishing with the slopes.
#ifndef WAVES_GLSL
#define WAVES_GLSL
#include "contract_water.glsl"

#include "hash.glsl"
#include "loops.glsl"        // ROLLED(n): loop bounds

// Which models the world has, decided when a program is built (llvmpipe runs
// a loop's body even when a uniform count leaves it at once: a world
// without an ocean paid ~40 ms a 960x540 frame for its loop). tarn's
// renderer defines WAVES_MODELS and a WAVES_HAS_* for each model the
// scene's world holds (render_world.c, world_wave_defines); a shader built
// without WAVES_MODELS (a test, another tool) gets every model, each
// switched off at run time by its count as before.
#ifndef WAVES_MODELS
#define WAVES_HAS_SINE
#define WAVES_HAS_GERSTNER
#define WAVES_HAS_NOISE
#define WAVES_HAS_OCEAN
#define WAVES_HAS_EXPLOSION
#define WAVES_HAS_PERLIN
#endif

#include "waves_ocean.glsl"
#include "waves_fx.glsl"

#define WAVES_MAX 8
#define WAVES_NOISE_OCTAVES_MAX 8
#define WAVES_GRAVITY 9.81
#define WAVES_TWO_PI 6.28318530717958647692
#define WAVES_NOISE_TURN 0.5            // radians the drift turns per octave
#ifndef WAVES_NEWTON_ITERATIONS
#define WAVES_NEWTON_ITERATIONS 4       // for wavesRestPoint / wavesHeightAt
#endif

uniform float uSteepness;               // Q = sum Q_i k_i A_i (loop-free while <= 1)

uniform int   uSineCount;               // 0..WAVES_MAX
uniform float uSineAngle[WAVES_MAX];    // direction of travel, degrees from +x towards +z
uniform float uSineLength[WAVES_MAX];   // wavelength L
uniform float uSineAmp[WAVES_MAX];      // amplitude A
uniform float uSineSpeed[WAVES_MAX];    // phase speed S (0: deep water)
uniform float uSinePhase[WAVES_MAX];    // radians

uniform int   uGerstnerCount;
uniform float uGerstnerAngle[WAVES_MAX];
uniform float uGerstnerLength[WAVES_MAX];
uniform float uGerstnerAmp[WAVES_MAX];
uniform float uGerstnerSpeed[WAVES_MAX];
uniform float uGerstnerPhase[WAVES_MAX];

uniform float uNoiseAmp;                // octave 0 amplitude; 0: no noise
uniform float uNoiseCell;               // lattice cell of octave 0 (0: 4)
uniform int   uNoiseOctaves;            // 0: 4
uniform int   uNoisePeriod;             // cells per tile at octave 0 (0: 16)
uniform float uNoiseGain;               // 0: 0.5
uniform float uNoiseAngle;              // drift direction of octave 0, degrees
uniform float uNoiseSpeed;              // drift speed of octave 0 (0: deep water for L = 2 cell)
uniform int   uNoiseSeed;               // 32 bits, read as uint

// The same waves resolved once on the CPU (tarn's render_world.c, from the
// reference's ref_waves: inactive waves dropped, defaults filled in): the
// direction's trig, k, omega, Q_i A_i and the noise's drift would otherwise
// be worked out again at every vertex and fragment (on llvmpipe that is
// 1.14-1.17x a frame). wavesSums, wavesNoise and wavesRestPoint read these;
// the u*Angle, u*Length... above stay for packs with their own loops.
uniform int   uWaveSineN;                         // active sine waves
uniform vec4  uWaveSine[WAVES_MAX];               // (k D.x, k D.z, omega, phase)
uniform float uWaveSineAmp[WAVES_MAX];            // A
uniform int   uWaveGerstN;                        // active Gerstner waves
uniform vec4  uWaveGerst[WAVES_MAX];              // (k D.x, k D.z, omega, phase)
uniform vec3  uWaveGerstAmp[WAVES_MAX];           // (A, Q_i A_i D.x, Q_i A_i D.z)
uniform int   uWaveNoiseN;                        // noise octaves (0: no noise)
uniform vec4  uWaveNoise[WAVES_NOISE_OCTAVES_MAX];   // (freq, freq drift.x, freq drift.z, amplitude)
uniform float uWaveNoisePeriod[WAVES_NOISE_OCTAVES_MAX];  // lattice cells per tile
uniform uint  uWaveNoiseSeed[WAVES_NOISE_OCTAVES_MAX];    // hashed per octave

float wavesPhaseSpeed(float speed, float L) {
    return speed != 0.0 ? speed : sqrt(WAVES_GRAVITY * L / WAVES_TWO_PI);
}

// ---- noise ------------------------------------------------------------

// wavesHash is hash.glsl's "lowbias32", as in ref_waves.c
uint wavesHash(uint x) { return tarnHash(x); }

vec2 wavesLatticeGrad(uint seed, float i, float j) {
    uint h = wavesHash(uint(i) + wavesHash(uint(j) + seed));
    float a = float(h >> 8u) * (WAVES_TWO_PI / 16777216.0);
    return vec2(cos(a), sin(a));
}

// One octave at lattice coordinates q: (value, d/dq.x, d/dq.y).
vec3 wavesNoiseOctave(vec2 q, float period, uint seed) {
    vec2 f = floor(q);
    vec2 x = q - f;
    float i0 = mod(f.x, period), i1 = mod(f.x + 1.0, period);
    float j0 = mod(f.y, period), j1 = mod(f.y + 1.0, period);
    vec2 ga = wavesLatticeGrad(seed, i0, j0);
    vec2 gb = wavesLatticeGrad(seed, i1, j0);
    vec2 gc = wavesLatticeGrad(seed, i0, j1);
    vec2 gd = wavesLatticeGrad(seed, i1, j1);
    float va = dot(ga, x);
    float vb = dot(gb, x - vec2(1.0, 0.0));
    float vc = dot(gc, x - vec2(0.0, 1.0));
    float vd = dot(gd, x - vec2(1.0, 1.0));
    vec2 u = x * x * x * (x * (x * 6.0 - 15.0) + 10.0);
    vec2 m = x * (x - 1.0);
    vec2 du = 30.0 * m * m;
    float e = va - vb - vc + vd;
    float n = va + u.x * (vb - va) + u.y * (vc - va) + u.x * u.y * e;
    vec2 dn = ga + u.x * (gb - ga) + u.y * (gc - ga) + u.x * u.y * (ga - gb - gc + gd)
            + du * vec2(vb - va + u.y * e, vc - va + u.x * e);
    return vec3(n, dn);
}

vec3 wavesNoise(vec2 p0, float t) {
    vec3 r = vec3(0.0);
    for (int o = 0; o < ROLLED(WAVES_NOISE_OCTAVES_MAX); o++) {
        if (o >= uWaveNoiseN) break;
        vec4 w = uWaveNoise[o];
        vec3 n = wavesNoiseOctave(p0 * w.x - w.yz * t, uWaveNoisePeriod[o], uWaveNoiseSeed[o]);
        r += w.w * vec3(n.x, w.x * n.yz);
    }
    return r;
}

#ifdef WAVES_HAS_FLOW
#include "flow.glsl"                    // the advected ripples (a Flow; no height: normals only)
#endif

// ---- the sums -----------------------------------------------------------

// Height h (without level) and its gradient, the sideways displacement D
// (Gerstner waves and the ocean) and its Jacobian entries a = dDx/dx0,
// b = dDx/dz0 = dDz/dx0, d = dDz/dz0, of every model above.
void wavesSumsModels(vec2 p0, float t, bool ocean, out float h, out vec2 dh, out vec2 disp, out vec3 abd) {
    h = 0.0; dh = vec2(0.0); disp = vec2(0.0); abd = vec3(0.0);
#ifdef WAVES_HAS_SINE
    for (int i = 0; i < ROLLED(WAVES_MAX); i++) {
        if (i >= uWaveSineN) break;
        vec4 w = uWaveSine[i];                          // th = k D.p0 + omega t + phase
        float th = dot(w.xy, p0) + w.z * t + w.w, A = uWaveSineAmp[i];
        h += A * sin(th);
        dh += A * cos(th) * w.xy;
    }
#endif
#ifdef WAVES_HAS_GERSTNER
    for (int i = 0; i < ROLLED(WAVES_MAX); i++) {
        if (i >= uWaveGerstN) break;
        vec4 w = uWaveGerst[i];
        vec3 a = uWaveGerstAmp[i];
        float th = dot(w.xy, p0) + w.z * t + w.w;
        float s = sin(th), c = cos(th);
        h += a.x * s;
        dh += a.x * c * w.xy;
        disp += c * a.yz;                               // Q_i A_i D cos th
        abd -= s * vec3(a.y * w.x, a.y * w.y, a.z * w.y);   // Q_i A_i k sin th (DxDx, DxDz, DzDz)
    }
#endif
#ifdef WAVES_HAS_NOISE
    vec3 nz = wavesNoise(p0, t);
    h += nz.x;
    dh += nz.yz;
#endif
#ifdef WAVES_HAS_OCEAN
    if (ocean) wavesOcean(p0, h, dh, disp, abd);
#endif
    vec2 g;                                             // the height-only models
#ifdef WAVES_HAS_EXPLOSION
    h += wavesExplosions(p0, t, g);
    dh += g;
#endif
#ifdef WAVES_HAS_PERLIN
    h += wavesPerlin(p0, t, g);
    dh += g;
#endif
#ifdef WAVES_HAS_FLOW
    dh += flowSlope(p0);                // the map holds the frame's time
#endif
}

void wavesSums(vec2 p0, float t, out float h, out vec2 dh, out vec2 disp, out vec3 abd) {
    wavesSumsModels(p0, t, true, h, dh, disp, abd);
}

// every model but the ocean (wavesNormalFilteredVar adds it filtered)
void wavesSumsNoOcean(vec2 p0, float t, out float h, out vec2 dh, out vec2 disp, out vec3 abd) {
    wavesSumsModels(p0, t, false, h, dh, disp, abd);
}

vec3 wavesDisplace(vec2 p0, float t) {
    float h; vec2 dh, disp; vec3 abd;
    wavesSums(p0, t, h, dh, disp, abd);
    return vec3(p0.x + disp.x, uWaterLevel + h, p0.y + disp.y);
}

vec3 wavesNormalFrom(vec2 dh, vec3 abd, bool approx) {
    if (approx)   // GPU Gems 1 eq. 12 (1 + a + d = 1 - sum Q_i k A sin)
        return normalize(vec3(-dh.x, 1.0 + abd.x + abd.z, -dh.y));
    vec3 B = vec3(1.0 + abd.x, dh.x, abd.y);    // dP/dx0
    vec3 T = vec3(abd.y, dh.y, 1.0 + abd.z);    // dP/dz0
    return normalize(cross(T, B));
}

vec3 wavesNormalExact(vec2 p0, float t) {
    float h; vec2 dh, disp; vec3 abd;
    wavesSums(p0, t, h, dh, disp, abd);
    return wavesNormalFrom(dh, abd, false);
}

vec3 wavesNormalApprox(vec2 p0, float t) {
    float h; vec2 dh, disp; vec3 abd;
    wavesSums(p0, t, h, dh, disp, abd);
    return wavesNormalFrom(dh, abd, true);
}

#ifdef WAVES_APPROX_NORMAL
#define WAVES_USE_APPROX true
#else
#define WAVES_USE_APPROX false
#endif

vec3 wavesNormal(vec2 p0, float t) {
    float h; vec2 dh, disp; vec3 abd;
    wavesSums(p0, t, h, dh, disp, abd);
    return wavesNormalFrom(dh, abd, WAVES_USE_APPROX);
}

void wavesEval(vec2 p0, float t, out vec3 pos, out vec3 normal) {
    float h; vec2 dh, disp; vec3 abd;
    wavesSums(p0, t, h, dh, disp, abd);
    pos = vec3(p0.x + disp.x, uWaterLevel + h, p0.y + disp.y);
    normal = wavesNormalFrom(dh, abd, WAVES_USE_APPROX);
}

// ---- filtered normals (see the header) ----------------------------------

// a macro, not a function: waves.glsl is in vertex shaders too, which have no dFdx
#define wavesFootprint(p0) vec2(length(dFdx(p0)), length(dFdy(p0)))

float wavesToksvig(float shininess, float lostVar, out float energy) {
    float m = max(shininess, 0.0);
    float m2 = 2.0 / (2.0 / (m + 2.0) + max(lostVar, 0.0)) - 2.0;
    energy = (m2 + 2.0) / (m + 2.0);
    return m2;
}

#ifdef WAVES_HAS_OCEAN
vec3 wavesNormalFilteredVar(vec2 p0, float t, vec2 footprint, out float lostVar) {
    float h; vec2 dh, disp; vec3 abd;
    lostVar = 0.0;
    // every model but the ocean, then the ocean filtered
    wavesSumsNoOcean(p0, t, h, dh, disp, abd);
    wavesOceanFiltered(p0, max(footprint.x, footprint.y), h, dh, disp, abd, lostVar);
    return wavesNormalFrom(dh, abd, WAVES_USE_APPROX);
}

vec3 wavesNormalFiltered(vec2 p0, float t, vec2 footprint) {
    float lostVar;
    return wavesNormalFilteredVar(p0, t, footprint, lostVar);
}
#endif

// ---- inversion -----------------------------------------------------------

// The rest point p0 whose displaced position lies over the world (x, z):
// Newton on p0 + D(p0) = xz from p0 = xz (Gerstner waves and the ocean's
// choppy displacement move points sideways; the ocean's Jacobian is its
// Dxx, Dxz, Dzz fields, bilinear like the displacement);
// WAVES_NEWTON_ITERATIONS steps (the reference iterates to 1e-12).
vec2 wavesRestPoint(vec2 xz, float t) {
    vec2 p0 = xz;
#if !defined(WAVES_HAS_GERSTNER) && !defined(WAVES_HAS_OCEAN)
    return p0;                                          // nothing moves points sideways
#else
    if ((uWaveGerstN == 0 || uSteepness == 0.0) && uOceanN == 0) return p0;
    for (int it = 0; it < ROLLED(WAVES_NEWTON_ITERATIONS); it++) {
        vec2 disp = vec2(0.0);
        vec3 abd = vec3(0.0);
#ifdef WAVES_HAS_GERSTNER
        for (int i = 0; i < ROLLED(WAVES_MAX); i++) {
            if (i >= uWaveGerstN) break;
            vec4 w = uWaveGerst[i];
            vec3 a = uWaveGerstAmp[i];
            float th = dot(w.xy, p0) + w.z * t + w.w;
            disp += cos(th) * a.yz;
            abd -= sin(th) * vec3(a.y * w.x, a.y * w.y, a.z * w.y);
        }
#endif
#ifdef WAVES_HAS_OCEAN
        float oh = 0.0;
        vec2 odh = vec2(0.0);
        wavesOcean(p0, oh, odh, disp, abd);             // its height: unused, dropped
#endif
        vec2 F = p0 + disp - xz;
        mat2 J = mat2(1.0 + abd.x, abd.y, abd.y, 1.0 + abd.z);
        float det = determinant(J);
        p0 -= abs(det) > 1e-6 ? inverse(J) * F : F;
    }
    return p0;
#endif
}

float wavesHeightAt(vec2 xz, float t) {
    return wavesDisplace(wavesRestPoint(xz, t), t).y;
}

#endif // WAVES_GLSL
