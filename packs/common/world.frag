#version 330 compatibility
#include "contract.glsl"
#include "waves.glsl"
#include "world.glsl"
#include "terrain.glsl"
#include "world_wet.glsl"

// 0 terrain (the terrain's model, below), 1 object, 2 sky. tarn compiles one
// program per mode (WORLD_MODE defined), so a pixel runs only its own
// branch: llvmpipe runs both sides of an `if` on a uniform.
#ifdef WORLD_MODE
const int uWorldMode = WORLD_MODE;
#else
uniform int uWorldMode;
#endif
uniform vec3 uWorldAlbedo;      // objects: one albedo each
uniform bool uWorldEyePath;     // drawn to the screen: attenuate along the eye's path in water
in vec3 vWorldPos;
in vec3 vWorldNormal;
in vec2 vST;
flat in float vWavesBound;      // worldWavesBound(), once a vertex (world.vert)
// world_layers (render.c): with uWorldLayers the draw keeps both of a
// pixel's shadings, wet and dry, and its point, for frames that differ
// only in time; location 0 then holds the wet colour and the depth
layout(location = 0) out vec4 fragColor;
layout(location = 1) out vec4 fragDry;
layout(location = 2) out vec4 fragPos;
uniform bool uWorldLayers;

// The length of the segment eye -> p that lies under the mean water level
// (the reference's eye path in water: it fades what an eye under the water
// sees by exp(-sigma s), with no in-scattering).
float eyePathInWater(vec3 eye, vec3 p) {
    float d = distance(eye, p);
    if (eye.y >= uWaterLevel) return 0.0;   // from above, the water surface is drawn over it
    if (p.y <= uWaterLevel) return d;
    return d * (uWaterLevel - eye.y) / max(p.y - eye.y, 1e-6);
}

// A pixel's shading under the water (the flat-water sun, the sky's ambient
// through the surface) or in air (Lambert, then the haze); the eye's path
// in water fades both.
vec3 eyeFade(vec3 c) {
    return uWorldEyePath ? c * exp(-uAbsorption * eyePathInWater(uCameraPos, vWorldPos)) : c;
}

vec3 shadeAs(bool wet, vec3 albedo, vec3 n) {
    return eyeFade(wet ? worldShadeAt(albedo, n, vWorldPos)
                       : worldHaze(worldLambert(albedo, n, vec3(1.0)), distance(uCameraPos, vWorldPos)));
}

void main() {
    if (uWorldMode == 2) {   // the sky: never wet
        vec3 c = eyeFade(worldSkyLook(uSky, normalize(vWorldNormal)));
        fragColor = uWorldLayers ? vec4(c, gl_FragCoord.z) : vec4(c, 1.0);
        fragDry = vec4(c, 1.0);
        fragPos = vec4(vWorldPos, 0.0);
        return;
    }
    vec3 albedo, n;
    if (uWorldMode == 0) {
        vec3 hg = terrainHeightGrad(vWorldPos.xz);
        n = normalize(vec3(-hg.y, 1.0, -hg.z));
        albedo = terrainAlbedo(vWorldPos.xz, hg.x, n);
    } else {
        n = normalize(vWorldNormal);
        albedo = uWorldAlbedo;
    }
    if (uWorldLayers) {
        fragColor = vec4(shadeAs(true, albedo, n), gl_FragCoord.z);
        fragDry = vec4(shadeAs(false, albedo, n), 1.0);
        fragPos = vec4(vWorldPos, 1.0);
        return;
    }
    fragColor = vec4(shadeAs(worldUnderWaterWithin(vWorldPos, vWavesBound), albedo, n), 1.0);
}
