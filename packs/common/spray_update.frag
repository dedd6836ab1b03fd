#version 330 compatibility
// spray_update.frag: one step of the spray's particles, a texel a slot
// (tarn's render_spray.h tells the model: exact parabolas under gravity,
// removal at the water or at the end of life, deterministic emission where
// the surface rises faster than a threshold).
#include "contract.glsl"
#include "waves.glsl"

uniform sampler2D uSprayPos;    // (x, y, z, life left; <= 0: dead)
uniform sampler2D uSprayVel;    // (vx, vy, vz, 0)
uniform int   uSprayRes;        // the state's side
uniform int   uSprayCount;      // live slots: 0 .. count - 1
uniform uint  uSpraySeed;
uniform uint  uSprayStep;       // round(t * 1000): the step's numbers
uniform float uSprayDt;
uniform vec4  uSprayEmit;       // (threshold m/s, emission probability a slot, life s, half square m)
uniform float uSprayFd;         // the backward difference's step (s)
uniform float uSprayHeightRate; // 1 / the time between the last two height maps; 0: not this step
#ifdef WAVES_HAS_OCEAN
uniform sampler2D uWaveHeight;      // unit 30: the surface's height over the world, now
uniform sampler2D uSprayHeightPrev; // the map before
uniform float uWaveHeightHalf;      // the maps cover x, z in [-half, half]
#endif
layout(location = 0) out vec4 oPos;
layout(location = 1) out vec4 oVel;

#define SPRAY_G 9.81

float sprayRand(uint k) { return float(tarnHash(k) >> 8) * (1.0 / 16777216.0); }

void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    int slot = ij.y * uSprayRes + ij.x;
    vec4 p = texelFetch(uSprayPos, ij, 0);
    vec4 v = texelFetch(uSprayVel, ij, 0);
    float dt = uSprayDt;
    oPos = vec4(p.xyz, 0.0);
    oVel = vec4(0.0);
    if (p.w > 0.0) {                               // live: along its parabola
        vec3 np = p.xyz + v.xyz * dt - vec3(0.0, 0.5 * SPRAY_G * dt * dt, 0.0);
        vec3 nv = v.xyz - vec3(0.0, SPRAY_G * dt, 0.0);
        float life = p.w - dt;
        bool wet = nv.y < 0.0 && np.y < wavesHeightAt(np.xz, uTime);
        if (life > 0.0 && !wet) {
            oPos = vec4(np, life);
            oVel = vec4(nv, 0.0);
        } else {
            oPos = vec4(np, 0.0);                  // removed where it ended
        }
        return;
    }
    if (slot >= uSprayCount) return;
    uint k = tarnHash(uint(slot) * 0x9E3779B9u ^ tarnHash(uSpraySeed ^ tarnHash(uSprayStep + 0x632BE5ABu)));
    if (sprayRand(k) >= uSprayEmit.y) return;
    vec2 p0 = (vec2(sprayRand(k + 1u), sprayRand(k + 2u)) * 2.0 - 1.0) * uSprayEmit.w;
    float h, hb;
    vec2 dh, disp, dhb, dispb;
    vec3 abd, abdb;
    wavesSums(p0, uTime, h, dh, disp, abd);
    wavesSums(p0, uTime - uSprayFd, hb, dhb, dispb, abdb);
    float w = (h - hb) / uSprayFd;                 // the surface's upward speed
#ifdef WAVES_HAS_OCEAN
    // the ocean's textures hold one time: the speed of every model from the
    // last two height maps instead, where the step ends at the map's time
    if (uSprayHeightRate > 0.0) {
        vec2 uv = (p0 + disp) / (2.0 * uWaveHeightHalf) + 0.5;
        w = (texture(uWaveHeight, uv).r - texture(uSprayHeightPrev, uv).r) * uSprayHeightRate;
    }
#endif
    if (w <= uSprayEmit.x) return;
    vec3 n = normalize(vec3(-dh.x, 1.0, -dh.y));
    vec3 jitter = vec3(sprayRand(k + 3u) - 0.5, 0.0, sprayRand(k + 4u) - 0.5) * 0.7;
    vec3 vel = normalize(n + jitter) * w * (1.0 + 0.6 * sprayRand(k + 5u));
    oPos = vec4(p0.x + disp.x, uWaterLevel + h, p0.y + disp.y, uSprayEmit.z * (0.6 + 0.4 * sprayRand(k + 6u)));
    oVel = vec4(vel, 0.0);
}
