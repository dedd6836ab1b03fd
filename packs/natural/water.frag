#version 330 compatibility
// packs/natural: the water pixel of Mihálik's "Natural Water Shader"
// (docs/packs/natural.md). Two projective lookups into the passes drawn
// before the surface:
//   refraction  R = refract(-E, N, 1/ior), W = U + dv' R, dv' = clamp(dv, 0,
//               uDepthClamp) uDepthScale with dv the view ray's path in
//               water (depth target), W projected with uCamMainVP into the
//               refraction target; C = C_w + exp(-d k) (C_refr - C_w)
//   reflection  W = U + c reflect(-E, N), projected with uCamMirrorVP
//   Fresnel     F = (1 - E.N)^q, or exact (EXACT_FRESNEL)
//   colour      C_refr + F (C_refl - C_refr), plus a specular highlight
// Seen from below (the camera under water) the roles swap: the internal
// reflection is looked up in the refraction target (the world below), the
// way out into the air in the reflection target (the world above), with
// total internal reflection beyond the critical angle.
#include "waves.glsl"
#include "world.glsl"
#include "natural.glsl"

uniform samplerCube uSky;
uniform sampler2D uTerrainAlbedo;
uniform vec3 uCameraPos;
uniform float uTime;
uniform mat4 uCamMainVP;
uniform mat4 uCamMirrorVP;

uniform sampler2D uRefraction;        // pass 1: world below the water, main camera, widened
uniform sampler2D uRefractionDepth;   //         its depth
uniform sampler2D uReflection;        // pass 2: world above the water, mirror camera, widened
uniform sampler2D uReflectionDepth;   //         its depth (the sky seen from below)
uniform sampler2D uCaustics;          // caustic ratio over refracted-sun space (natural.glsl)

uniform float uFovScale;         // the passes' field of view / the camera's (the Camera lines read it)
uniform float uReflectDist;      // c: reflection lookup distance
uniform float uAttenuation;      // k: attenuation per metre (the paper's model)
uniform vec3  uWaterColor;       // C_w: what deep water shows (the paper's model)
uniform float uFresnelPower;     // q of (1 - E.N)^q
uniform float uDepthClamp;       // dv clamp (paper: 2)
uniform float uDepthScale;       // dv scale (paper: 1/3)
uniform float uSpecular;         // highlight strength (times the sun's irradiance)
uniform float uShininess;        // highlight exponent
uniform float uCausticStrength;  // 1: the photons' ratio as computed; 0: flat-water light

#ifndef REFINE_STEPS
#define REFINE_STEPS 0           // extra depth lookups refining the refraction hit (0: the paper)
#endif
#ifndef DEBUG_PASS
#define DEBUG_PASS 0             // 1: refracted colour only, 2: reflected colour only
#endif

in vec2 vRest;
in vec3 vWorldPos;
out vec4 fragColor;

// Light lost along a path of length d in water: the paper's blend towards
// the water colour, or Beer-Lambert with the scene's absorption.
vec3 attenuate(vec3 c, float d) {
#ifdef BEER_LAMBERT
    return c * exp(-uAbsorption * d);
#else
    return uWaterColor + exp(-d * uAttenuation) * (c - uWaterColor);
#endif
}

// The caustic ratio applied to the sun term of a floor colour that tarn's
// world program shaded with flat-water sunlight: albedo * (E/pi + ambient),
// the albedo read from the terrain's texture at p.
vec3 applyCaustics(vec3 c, vec3 p) {
#ifdef CAUSTICS
    if (p.y < uWaterLevel) {
        vec2 uv = natCausticUV(natCausticQ(p));
        if (natInside(uv)) {
            float ratio = max(1.0 + uCausticStrength * (texture(uCaustics, uv).r - 1.0), 0.0);
            vec3 albedo = texture(uTerrainAlbedo, p.xz / uTerrainHalfSize * 0.5 + 0.5).rgb;
            vec3 amb = albedo * uAmbient;
            c = amb + max(c - amb, vec3(0.0)) * ratio;
        }
    }
#endif
    return c;
}

// What the refraction target shows along direction r from the surface point
// U: W = U + s r with s from `s0`, refined by REFINE_STEPS fixed-point steps
// s <- |shown(W) - U|. fallback: the unperturbed lookup. path: |shown - U|.
vec3 lookBelow(vec3 U, vec3 r, float s0, bool useFallback, out float path) {
    vec3 W = U + s0 * r;
    vec2 uv;
    bool ok;
    for (int i = 0; i < REFINE_STEPS; i++) {
        vec3 b = natShownPoint(uCamMainVP, uCameraPos, uRefractionDepth, W, uv, ok);
        if (!ok) break;
        W = U + distance(U, b) * r;
    }
    vec3 shown = natShownPoint(uCamMainVP, uCameraPos, uRefractionDepth, W, uv, ok);
    if (!ok && useFallback)   // the perturbed lookup left the water: the classic fix
        shown = natShownPoint(uCamMainVP, uCameraPos, uRefractionDepth, U, uv, ok);
    path = ok ? distance(U, shown) : 1e4;
    if (!ok) return vec3(0.0);
    return applyCaustics(texture(uRefraction, uv).rgb, shown);
}

void main() {
    vec3 U = vWorldPos;
    vec3 N = wavesNormal(vRest, uTime);
    vec3 E = normalize(uCameraPos - U);
    bool fromBelow = dot(E, N) < 0.0;
    vec3 n = fromBelow ? -N : N;               // faces the eye
    float cosI = clamp(dot(E, n), 0.0, 1.0);
    vec3 Rr = reflect(-E, n);
    vec3 refr, refl, color;
    float F;

    if (!fromBelow) {
        // ---- from above: the paper ----
        vec3 R = refract(-E, n, 1.0 / uIOR);
        vec2 uv0;
        bool ok0;
        vec3 b0 = natShownPoint(uCamMainVP, uCameraPos, uRefractionDepth, U, uv0, ok0);
        float dv = ok0 ? distance(U, b0) : 1e4;          // the view ray's path in water
        float path;
        vec3 c = lookBelow(U, R, clamp(dv, 0.0, uDepthClamp) * uDepthScale, true, path);
#ifdef BEER_LAMBERT
        refr = attenuate(c, path);
#else
        refr = attenuate(c, dv);                         // the paper's d: the pixel's depth difference
#endif
#ifdef SKY_REFLECTION
        refl = texture(uSky, Rr).rgb;
#else
        float w;
        vec2 uv = natProject(uCamMirrorVP, U + uReflectDist * Rr, w);
        refl = w > 0.0 && natInside(uv) ? texture(uReflection, uv).rgb : texture(uSky, Rr).rgb;
#endif
#ifdef EXACT_FRESNEL
        F = worldFresnel(cosI, 1.0, uIOR);
#else
        F = pow(1.0 - cosI, uFresnelPower);
#endif
        color = refr + F * (refl - refr);
#ifdef SPECULAR
        vec3 H = normalize(E + uSunDir);
        color += uSpecular * pow(max(dot(n, H), 0.0), uShininess) * uSunIrradiance;
#endif
    } else {
        // ---- from below: roles swapped ----
        vec3 T = refract(-E, n, uIOR);                   // out into the air; 0 on TIR
        bool tir = dot(T, T) == 0.0;
        // the way out: the world above (mirror target) or, where that shows
        // the sky, the sky along T itself
        refr = vec3(0.0);
        if (!tir) {
            float w;
            vec2 uv = natProject(uCamMirrorVP, U + uReflectDist * T, w);
            bool sky = !(w > 0.0 && natInside(uv)) || texture(uReflectionDepth, uv).r >= 0.99999;
            refr = sky ? texture(uSky, T).rgb : texture(uReflection, uv).rgb;
        }
        // the internal reflection: the world below (refraction target)
        float path;
        vec3 c = lookBelow(U, Rr, uReflectDist, false, path);
        refl = attenuate(c, path);
#ifdef EXACT_FRESNEL
        F = worldFresnel(cosI, uIOR, 1.0);
#else
        F = tir ? 1.0 : pow(1.0 - clamp(-dot(T, n), 0.0, 1.0), uFresnelPower);
#endif
        color = refr + F * (refl - refr);
        color = attenuate(color, distance(uCameraPos, U));   // the eye's own path in water
    }

#ifdef DEBUG_FRESNEL
    color = vec3(F);                                     // white: reflection, black: refraction
#endif
#if DEBUG_PASS == 1
    color = refr;
#elif DEBUG_PASS == 2
    color = refl;
#endif
    fragColor = vec4(color, 1.0);
}
