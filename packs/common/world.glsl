// The shading of everything that is not water, the GLSL twin of
// reference/ref_scene.c's ref_shade_lambert:
//   radiance = albedo * (E_sun * max(0, n.l) * sunScale / pi + ambient)
// Below the water the sun arrives refracted through a flat surface: it is
// scaled by the Fresnel transmittance and Beer-Lambert along the refracted
// sun ray (the flat-water caustic; packs with caustics replace sunScale).
#ifndef TARN_WORLD_GLSL
#define TARN_WORLD_GLSL
#include "contract_water.glsl"
#include "contract_light.glsl"


const float WORLD_PI = 3.14159265358979;

// The world's look (issue #25; ref_scene.h): the sun's disc (SkySun) and
// the haze (Haze), both off (0) unless the scene asks.

// ref_sun_disc: a soft-edged, limb-darkened core and an aureole.
// (Where tarn built the program, WORLD_DEFINES, a scene without the disc
// or the haze compiles them out: llvmpipe runs the code behind a uniform
// `if` for every pixel.)
vec3 worldSunDisc(vec3 dir) {
#if defined(WORLD_DEFINES) && !defined(WORLD_SUN_DISC)
    return vec3(0.0);
#else
    if (uSunDisc.x <= 0.0) return vec3(0.0);
    float half_ = 0.5 * length(normalize(dir) - uSunDir);
    float x = 2.0 * asin(min(half_, 1.0)) / uSunDisc.x;
    if (x > 40.0) return vec3(0.0);
    float core = (1.0 - smoothstep(0.75, 1.25, x)) * (1.0 - 0.35 * min(x * x, 1.0));
    float aureole = 0.015 * exp(-0.5 * max(x - 1.0, 0.0));
    return uSunIrradiance / 3.0 * uSunDisc.y * (core + aureole);
#endif
}

// The sky along dir, as ref_sky_radiance has it: the cube map tarn bakes
// (ref_sky_smooth: gradient, glow, clouds; alpha the share of the disc the
// clouds let through) plus the sun's disc, evaluated here at full
// resolution. Every pack reads the sky through this.
vec3 worldSkyLook(samplerCube sky, vec3 dir) {
    vec4 s = texture(sky, dir);
    return s.rgb + s.a * worldSunDisc(dir);
}

// ref_haze: what an air path of length dist does to the radiance c.
vec3 worldHaze(vec3 c, float dist) {
#if defined(WORLD_DEFINES) && !defined(WORLD_HAZE)
    return c;
#else
    if (uHazeDistance <= 0.0) return c;
    return mix(c, uSkyHorizon, 1.0 - exp(-dist / uHazeDistance));
#endif
}

vec3 worldLambert(vec3 albedo, vec3 n, vec3 sunScale) {
    float c = max(dot(n, uSunDir), 0.0);
    return albedo * (uSunIrradiance * c * sunScale / WORLD_PI + uAmbient);
}

// Exact unpolarised Fresnel reflectance for cos of the incidence angle,
// from medium n1 to n2; 1 under total internal reflection.
float worldFresnel(float cosI, float n1, float n2) {
    float eta = n1 / n2;
    float sinT2 = eta * eta * max(0.0, 1.0 - cosI * cosI);
    if (sinT2 >= 1.0) return 1.0;
    float cosT = sqrt(1.0 - sinT2);
    float rs = (n1 * cosI - n2 * cosT) / (n1 * cosI + n2 * cosT);
    float rp = (n2 * cosI - n1 * cosT) / (n2 * cosI + n1 * cosT);
    return 0.5 * (rs * rs + rp * rp);
}

// The sun's irradiance on a surface (normal n) at pos below flat water:
// the refracted beam, scaled by transmittance and attenuation. (Packs that
// light a floor themselves, like caustic_tex, use it too.)
vec3 worldSunBelow(vec3 n, vec3 pos) {
    float depth = max(uWaterLevel - pos.y, 0.0);
    float cosI = max(uSunDir.y, 1e-4);
    vec3 lt = refract(-uSunDir, vec3(0.0, 1.0, 0.0), 1.0 / uIOR);   // downward
    float cosT = max(-lt.y, 1e-4);
    vec3 trans = (1.0 - worldFresnel(cosI, 1.0, uIOR)) * exp(-uAbsorption * depth / cosT);
    // The beam carries E_sun cosI (1 - R) per unit of horizontal area, so
    // E_sun cosI (1 - R) / cosT per unit of its own cross-section; a
    // surface with normal n receives that times n.(-lt). On a flat floor
    // this is E_sun cosI (1 - R) attenuated, the photon tracer's figure.
    return uSunIrradiance * trans * max(dot(n, -lt), 0.0) * cosI / cosT;
}

// Sunlight reaching a point below flat water: the refracted direction's
// cosine replaces n.l's light, scaled by transmittance and attenuation.
vec3 worldShadeAt(vec3 albedo, vec3 n, vec3 pos) {
    float depth = uWaterLevel - pos.y;
    if (depth <= 0.0) return worldLambert(albedo, n, vec3(1.0));
    vec3 e = worldSunBelow(n, pos);
    // the sky's ambient reaches down through the surface like the reference
    // has it: ambient (1 - R0) exp(-sigma depth)
    float r0 = (uIOR - 1.0) / (uIOR + 1.0);
    vec3 ambient = uAmbient * (1.0 - r0 * r0) * exp(-uAbsorption * depth);
    return albedo * (e / WORLD_PI + ambient);
}

#endif
