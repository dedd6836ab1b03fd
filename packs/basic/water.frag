#version 330 compatibility
#include "contract.glsl"
#include "waves.glsl"
#include "world.glsl"

uniform vec3 uTint;       // what the water adds where light is absorbed
uniform float uOpacity;   // how much of the floor the water hides at normal incidence
in vec2 vRest;
in vec3 vWorldPos;
out vec4 fragColor;

void main() {
    // the normal per fragment, from the rest point: exact, not interpolated;
    // on the spectrum ocean the cascades finer than the pixel filtered out
    // (OCEAN_FILTER, waves.glsl: the horizon does not sparkle)
#if defined(WAVES_HAS_OCEAN) && defined(OCEAN_FILTER)
    vec2 footprint = wavesFootprint(vRest);     // derivatives: in uniform control flow
    vec3 n = wavesNormalFiltered(vRest, uTime, footprint);
#else
    vec2 footprint = vec2(0.0);
    vec3 n = wavesNormal(vRest, uTime);
#endif
    vec3 e = normalize(uCameraPos - vWorldPos);
#ifdef WAVES_HAS_OCEAN
    // The side of the water is the camera's (the mean level), not the
    // normal's: a normal of the ocean's finer cascades turned away from an
    // eye above the water (the back of a ripple on a crest the mesh
    // shows) made the pixel a view from below, dark (black speckles).
    // Such a normal is mirrored about the plane across the view instead,
    // so it faces the eye with its tilt kept.
    bool below = uCameraPos.y < uWaterLevel;
    float en = dot(e, n);
    if (below ? en > 0.0 : en < 0.0) n = normalize(n - 2.0 * en * e);
    if (below) n = -n;
#else
    bool below = dot(e, n) < 0.0;
    if (below) n = -n;
#endif
    float cosI = clamp(dot(e, n), 0.0, 1.0);
#ifdef EXACT_FRESNEL
    float f = below ? worldFresnel(cosI, uIOR, 1.0) : worldFresnel(cosI, 1.0, uIOR);
#else
    float r0 = (uIOR - 1.0) / (uIOR + 1.0);
    r0 *= r0;
    float f = r0 + (1.0 - r0) * pow(1.0 - cosI, 5.0);
#endif
    if (below) {
        // From under the water: outside Snell's window f = 1 (total
        // internal reflection), and what it mirrors is the water below,
        // for which the tint stands (basic traces nothing); inside it the
        // world above shows through, unrefracted, as the floor does from
        // above. Both reach the eye through |eye - surface| of water.
        vec3 t = exp(-uAbsorption * distance(uCameraPos, vWorldPos));
        fragColor = vec4(t * f * uTint, 1.0 - dot(t, vec3(1.0 / 3.0)) * (1.0 - f));
        return;
    }
    vec3 sky = worldSkyLook(uSky, reflect(-e, n));
    vec3 color = f * sky + (1.0 - f) * uTint;
    // Blend premultiplied: out = color + dst * (1 - alpha), the floor seen
    // through what neither reflects nor absorbs
    float alpha = f + (1.0 - f) * uOpacity;
#if defined(WAVES_HAS_OCEAN) && defined(OCEAN_FOAM)
    // the ocean's folding foam (waves_ocean.glsl): white, rough (lit
    // diffusely, no mirror), slightly translucent
    float foam = 0.85 * wavesFoamFiltered(vRest, max(footprint.x, footprint.y));
    vec3 white = 0.9 * (uSunIrradiance * max(dot(n, uSunDir), 0.0) / WORLD_PI + uAmbient);
    color = mix(color, white, foam);
    alpha = mix(alpha, 1.0, foam);
#endif
#ifdef WAVES_HAS_FLOW
    // the flow's advected foam streaks (flow.glsl), lit as the ocean's foam
    float streak = flowFoam(vRest);
    vec3 foamLit = 0.9 * (uSunIrradiance * max(dot(n, uSunDir), 0.0) / WORLD_PI + uAmbient);
    color = mix(color, foamLit, streak);
    alpha = mix(alpha, 1.0, streak);
#endif
    fragColor = vec4(color, clamp(alpha, 0.0, 1.0));
}
