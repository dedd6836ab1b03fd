#version 330 compatibility
// Xing's water on a tarn scene (pack.glib). The scene's wave set moves the
// surface; what lies below it comes from the refraction pass (World below,
// seen by this camera: colour on unit 8, depth on unit 9), looked up along
// the refracted ray (two projective steps on the floor's height), and Xing's caustics relight it:
// the world lit it by the sun through flat water (world.glsl), so the sun
// term is multiplied by the caustic factor K, albedo-free, as
//     C' = C (E K + pi A) / (E + pi A)
// with E the flat-water sun irradiance there (worldShadeAt's) and A the
// ambient. Then Beer-Lambert along the view path, Xing's turquoise mix and
// Phong lighting by the sun, the sky's reflection (exact Fresnel) and foam
// along the shore.
//   BACKWARD_CAUSTICS  GPU Gems ch. 2 backward caustics instead of the texture
//   UV_FLIP            swap U and V of the second copy of each two-layer lookup
//   SKY_REFLECTION     (ours) the sky's reflection, exact Fresnel
//   BEER_LAMBERT       (ours) attenuation along the refracted path
//   SHOW_IRRADIANCE    (ours) output the sun's irradiance on the floor, E K,
//                      per channel, for measurement against the reference
//   DEBUG_OUTPUT       (ours) 1: the floor point the refracted lookup shows
//                      (world xyz), 2: the Fresnel reflectance, 3: the path
//                      in water to that point (m); for the benchmark
#ifndef DEBUG_OUTPUT
#define DEBUG_OUTPUT 0
#endif
#include "waves.glsl"
#include "world.glsl"
#include "xing_look.glsl"

uniform samplerCube uSky;
uniform vec3 uCameraPos;
uniform float uTime;
uniform float uTerrainHalfSize;
uniform sampler2D uRefractColor;   // World below, from this camera
uniform sampler2D uRefractDepth;   // its depth (1: nothing there)
uniform float uWaterRefractMix;    // 0: the floor as refracted, 1: all turquoise
uniform vec3  uColor;              // the water's turquoise
uniform float uKa, uKd, uKs, uShininess;
uniform float uCausticDepth;       // (ours) depth of full caustic contrast
in vec2 vRest;
in vec3 vWorldPos;
out vec4 fragColor;

vec2 screenOf(vec3 p) {
    vec4 c = gl_ModelViewProjectionMatrix * vec4(p, 1.0);
    return c.xy / c.w * 0.5 + 0.5;
}

// The world point the refraction pass saw at uv (moved onto the screen's
// edge when it lies outside); false where it saw nothing.
bool refractPoint(inout vec2 uv, out vec3 p) {
    ivec2 size = textureSize(uRefractDepth, 0);
    vec2 half_texel = 0.5 / vec2(size);
    uv = clamp(uv, half_texel, 1.0 - half_texel);
    float z = texelFetch(uRefractDepth, ivec2(uv * vec2(size)), 0).r;
    vec4 c = gl_ModelViewProjectionMatrixInverse * vec4(vec3(uv, z) * 2.0 - 1.0, 1.0);
    p = c.xyz / c.w;
    return z < 1.0;
}

// The floor's normal at uv from the depth of two neighbouring texels.
vec3 refractNormal(vec2 uv, vec3 p, vec3 eye) {
    vec2 texel = 1.0 / vec2(textureSize(uRefractDepth, 0));
    vec3 px, pz;
    vec2 uvx = uv + vec2(texel.x, 0.0), uvz = uv + vec2(0.0, texel.y);
    bool okx = refractPoint(uvx, px);
    bool okz = refractPoint(uvz, pz);
    vec3 n = cross(pz - p, px - p);
    float l = length(n);
    if (!okx || !okz || !(l > 1e-12)) return vec3(0.0, 1.0, 0.0);
    n /= l;
    return dot(n, eye - p) < 0.0 ? -n : n;
}

// Each wave kind's displacement along its directions at xz: the sines'
// sum of A sin(th) D, the Gerstner waves' sum of (Q_i A_i cos th + A sin th) D.
void waveOffsets(vec2 xz, float t, out vec2 offS, out vec2 offG) {
    offS = vec2(0.0);
    offG = vec2(0.0);
    for (int i = 0; i < WAVES_MAX; i++) {
        if (i >= uSineCount) break;
        float L = uSineLength[i], A = uSineAmp[i];
        if (L <= 0.0 || A == 0.0) continue;
        float ang = radians(uSineAngle[i]), k = WAVES_TWO_PI / L;
        vec2 D = vec2(cos(ang), sin(ang));
        float th = k * dot(D, xz) + wavesPhaseSpeed(uSineSpeed[i], L) * k * t + uSinePhase[i];
        offS += A * sin(th) * D;
    }
    int n = 0;
    for (int i = 0; i < WAVES_MAX; i++) {
        if (i >= uGerstnerCount) break;
        if (uGerstnerLength[i] > 0.0 && uGerstnerAmp[i] != 0.0) n++;
    }
    for (int i = 0; i < WAVES_MAX; i++) {
        if (i >= uGerstnerCount) break;
        float L = uGerstnerLength[i], A = uGerstnerAmp[i];
        if (L <= 0.0 || A == 0.0) continue;
        float ang = radians(uGerstnerAngle[i]), k = WAVES_TWO_PI / L;
        vec2 D = vec2(cos(ang), sin(ang));
        float qa = uSteepness / (k * float(n)) * sign(A);
        float th = k * dot(D, xz) + wavesPhaseSpeed(uGerstnerSpeed[i], L) * k * t + uGerstnerPhase[i];
        offG += (qa * cos(th) + A * sin(th)) * D;
    }
}

// The amplitudes of every wave, noise included (foam strength).
float waveAmpSum() {
    float s = abs(uNoiseAmp);
    for (int i = 0; i < WAVES_MAX; i++) {
        if (i < uSineCount && uSineLength[i] > 0.0) s += abs(uSineAmp[i]);
        if (i < uGerstnerCount && uGerstnerLength[i] > 0.0) s += abs(uGerstnerAmp[i]);
    }
    return s;
}

// A scroll of 0.25 of the first wave's phase speed, in tiles (foam and
// ripples drift much slower than the crests).
vec2 firstWaveScroll(bool gerstner, float tilesPerUnit, float t) {
    int count = gerstner ? uGerstnerCount : uSineCount;
    if (count < 1) return vec2(0.0);
    float ang = radians(gerstner ? uGerstnerAngle[0] : uSineAngle[0]);
    float L = gerstner ? uGerstnerLength[0] : uSineLength[0];
    float S = L > 0.0 ? wavesPhaseSpeed(gerstner ? uGerstnerSpeed[0] : uSineSpeed[0], L) : 0.0;
    return 0.25 * S * tilesPerUnit * t * vec2(cos(ang), sin(ang));
}

// The caustic factor at floor point p.
vec3 causticFactor(vec3 p, float t) {
    float depth = uWaterLevel - p.y;
    if (depth <= 0.0) return vec3(1.0);
    float contrast = uCausticVisible * clamp(depth / max(uCausticDepth * uWorldScale, 1e-9), 0.0, 1.0);
#ifdef BACKWARD_CAUSTICS
    vec3 n = wavesNormal(wavesRestPoint(p.xz, t), t);
    return xingCausticBackward(n, uSunDir, uIOR, contrast);
#else
    vec2 offS, offG;
    waveOffsets(p.xz, t, offS, offG);
    return xingCausticTex(p.xz, offS, offG, xingChromaDir(uSunDir), contrast);
#endif
}

void main() {
    float t = uTime;
    vec3 P = vWorldPos;
    vec3 n = wavesNormal(vRest, t);
    float tilesPerUnit = uWaterTiling / (2.0 * uTerrainHalfSize);
    vec2 uv = P.xz * tilesPerUnit;
    vec2 sa = firstWaveScroll(false, tilesPerUnit, t), sb = firstWaveScroll(true, tilesPerUnit, t);
    n = xingBumpNormal(n, xingRippleSlope(uv, sa, sb));
    vec3 e = normalize(uCameraPos - P);
    bool below = dot(e, n) < 0.0;
    if (below) n = -n;
    float cosI = clamp(dot(e, n), 0.0, 1.0);

    // the floor along the refracted ray: the point seen straight behind
    // gives the depth D of a level floor under P; the refracted ray meets
    // that level at P + tr D / -tr.y; the point seen there gives the next
    // D (twice: a fixed-point iteration on the floor's height)
    vec3 tr = refract(-e, n, below ? uIOR : 1.0 / uIOR);
    vec2 uv0 = screenOf(P), uvF = uv0;
    vec3 F0, F;
    bool hit0 = refractPoint(uv0, F0), hit = hit0;
    F = F0;
    float D = P.y - F0.y;
    if (!below && hit0 && D > 0.0 && tr.y < -1e-4) {
        for (int i = 0; i < 2; i++) {
            vec2 uvi = screenOf(P + tr * (D / -tr.y));
            vec3 Fi;
            if (!refractPoint(uvi, Fi) || Fi.y >= P.y) break;
            uvF = uvi;
            F = Fi;
            D = P.y - Fi.y;
        }
    }
    vec3 under = vec3(0.0);         // nothing seen: all absorbed
    vec3 E = vec3(0.0), K = vec3(1.0);
    if (hit && !below) {
        E = worldSunBelow(refractNormal(uvF, F, uCameraPos), F);   // world.glsl
        K = causticFactor(F, t);
        vec3 ambient = WORLD_PI * uAmbient;
        under = texture(uRefractColor, uvF).rgb * (E * K + ambient) / max(E + ambient, vec3(1e-6));
#ifdef BEER_LAMBERT
        under *= exp(-uAbsorption * distance(P, F));
#endif
    }
#ifdef SHOW_IRRADIANCE
    fragColor = vec4(E * K, 1.0);
    return;
#endif
    float R = below ? worldFresnel(cosI, uIOR, 1.0) : worldFresnel(cosI, 1.0, uIOR);
#if DEBUG_OUTPUT == 1
    fragColor = vec4(hit ? F : vec3(0.0), 1.0);
    return;
#elif DEBUG_OUTPUT == 2
    fragColor = vec4(vec3(R), 1.0);
    return;
#elif DEBUG_OUTPUT == 3
    fragColor = vec4(vec3(below ? distance(uCameraPos, P) : hit ? distance(P, F) : 1e4), 1.0);
    return;
#endif
    float diffuse = max(dot(n, uSunDir), 0.0);
    vec3 turquoise = uColor * (uKa + uKd * diffuse);
    vec3 color = mix(under, turquoise, uWaterRefractMix);
#ifdef SKY_REFLECTION
    color = R * texture(uSky, reflect(-e, n)).rgb + (1.0 - R) * color;
#endif
    color += uKs * pow(max(dot(reflect(-uSunDir, n), e), 0.0), max(uShininess, 1.0)) * uSunIrradiance;

    // foam where the water is shallow (the shore is the lake's border)
    float shallow = hit0 ? max(P.y - F0.y, 0.0) : 1e6;
    float foam = xingFoam(uv * 4.0, 2.0 * sa, -sb, shallow, waveAmpSum());
    vec3 white = 0.9 * (uSunIrradiance * diffuse / WORLD_PI + uAmbient);
    color = mix(color, white, foam);
    fragColor = vec4(color, 1.0);
}
