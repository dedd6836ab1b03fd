#version 330 compatibility
// packs/natural, the paper's caustics: one photon per texel of the light
// camera's target, its hit and light by Mihálik's equation (1)
// (natPhotonPaper). RG: where it lands on the floor, in refracted-sun space
// scaled so that tarn's `Splat` (which maps the world square onto the
// caustic texture) maps the caustic square instead; B: its weight, scaled
// the same way, so the splatted "irradiance" (weight per texel area) is the
// caustic ratio; A: 1 when valid (0: the cleared texel, no photon).
#include "contract.glsl"
#include "waves.glsl"
#include "world.glsl"
#include "natural.glsl"

in vec2 vRest;
in vec3 vWorldPos;
in vec2 vLightNdc;
out vec4 fragColor;

void main() {
    // the light texel's cross-section (world units) over cos_s: the mean
    // plane's area its flux would light under flat water
    float texel = uCamLightHalfSize * uCamLightHalfSize * abs(dFdx(vLightNdc.x) * dFdy(vLightNdc.y));
    float area = texel / max(uSunDir.y, 1e-4);
    vec3 N = wavesNormal(vRest, uTime);
    vec2 q;
    float w;
    if (!natPhotonPaper(vWorldPos, N, area, q, w)) {   // Mihálik's eq. (1) (natural.glsl)
        fragColor = vec4(0.0);
        return;
    }
    float s = uTerrainHalfSize / natCausticHalfSize();
    fragColor = vec4(q * s, w * s * s, 1.0);
}
