// rock.glsl: the floor of Xing's scene, a rock texture and its normal map,
// generated here rather than read from files: fractal value noise (five
// octaves, quintic fade, so the normal is continuous) over world (x, z).
#ifndef XING_ROCK_GLSL
#define XING_ROCK_GLSL

#include "hash.glsl"   // packs/common: the hash waves.glsl's noise uses

float rockLattice(vec2 i) {
    uint h = tarnHash(uint(int(i.x)) + tarnHash(uint(int(i.y)) + 0x9e3779b9u));
    return float(h >> 8) / 16777216.0;
}

// Value noise in [0, 1] and its gradient.
vec3 rockNoise(vec2 p) {
    vec2 i = floor(p), f = p - i;
    float a = rockLattice(i), b = rockLattice(i + vec2(1, 0));
    float c = rockLattice(i + vec2(0, 1)), d = rockLattice(i + vec2(1, 1));
    vec2 u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    vec2 du = 30.0 * f * f * (f * (f - 2.0) + 1.0);
    float v = a + (b - a) * u.x + (c - a) * u.y + (a - b - c + d) * u.x * u.y;
    vec2 g = du * vec2(b - a + (a - b - c + d) * u.y, c - a + (a - b - c + d) * u.x);
    return vec3(v, g);
}

// Height (about 0..1) and gradient of the rock at world xz; scale: units
// per base cell.
vec3 rockHeight(vec2 xz, float scale) {
    vec3 r = vec3(0.0);
    float amp = 0.5, freq = 1.0 / scale;
    for (int o = 0; o < 5; o++) {
        vec3 n = rockNoise(xz * freq + float(o) * 17.31);
        r += amp * vec3(n.x, n.yz * freq);
        amp *= 0.5;
        freq *= 2.07;
    }
    return r;
}

// Albedo and unit normal of the rock floor at world xz.
void rockFloor(vec2 xz, out vec3 albedo, out vec3 normal) {
    vec3 h = rockHeight(xz, 0.35);
    float v = smoothstep(0.2, 0.8, h.x);
    vec3 dark = vec3(0.30, 0.27, 0.22), light = vec3(0.62, 0.58, 0.50);
    float speck = rockNoise(xz * 23.0).x;
    albedo = mix(dark, light, v) * (0.85 + 0.3 * speck);
    normal = normalize(vec3(-0.12 * h.y, 1.0, -0.12 * h.z));
}

#endif
