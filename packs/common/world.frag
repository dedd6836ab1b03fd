#version 330 compatibility
#include "waves.glsl"
#include "world.glsl"
#include "terrain.glsl"

uniform sampler2D uTerrainAlbedo;
uniform samplerCube uSky;
// 0 terrain (the terrain's model, below), 1 object, 2 sky. tarn compiles one
// program per mode (WORLD_MODE defined), so a pixel runs only its own
// branch: llvmpipe runs both sides of an `if` on a uniform.
#ifdef WORLD_MODE
const int uWorldMode = WORLD_MODE;
#else
uniform int uWorldMode;
#endif
uniform vec3 uWorldAlbedo;      // objects: one albedo each
uniform vec3 uCameraPos;        // the eye of the current camera
uniform bool uWorldEyePath;     // drawn to the screen: attenuate along the eye's path in water
in vec3 vWorldPos;
in vec3 vWorldNormal;
in vec2 vST;
out vec4 fragColor;

// The length of the segment eye -> p that lies under the mean water level
// (the reference's eye path in water: it fades what an eye under the water
// sees by exp(-sigma s), with no in-scattering).
float eyePathInWater(vec3 eye, vec3 p) {
    float d = distance(eye, p);
    if (eye.y >= uWaterLevel) return 0.0;   // from above, the water surface is drawn over it
    if (p.y <= uWaterLevel) return d;
    return d * (uWaterLevel - eye.y) / max(p.y - eye.y, 1e-6);
}

// Is p under the water surface at this time? Below the mean level is not
// enough: where a trough uncovers the shore, the reference's ray meets the
// land in air and lights it dry (its shading follows the path, not the
// mean level). Within the waves' height bound of the level (waves.glsl's
// sum of amplitudes; gradient noise stays within 0.75 of its amplitude)
// the surface's height is read from tarn's map of it this frame
// (WORLD_HEIGHT_MAP, world_height.frag), or else solved for here: on a
// CPU rasteriser every pixel pays for that solve, wet or dry.
uniform float uTime;
#ifdef WORLD_HEIGHT_MAP
uniform sampler2D uWaveHeight;     // the surface's height over the world (set by tarn)
uniform float uWaveHeightHalf;     // it covers x, z in [-half, half]
#endif
bool worldUnderWater(vec3 p) {
    if (p.y >= uWaterLevel) return false;
    float bound = 0.0;
    for (int i = 0; i < WAVES_MAX; i++) {
        if (i < uSineCount) bound += abs(uSineAmp[i]);
        if (i < uGerstnerCount) bound += abs(uGerstnerAmp[i]);
    }
    int octaves = uNoiseOctaves > 0 ? uNoiseOctaves : 4;
    float gain = uNoiseGain > 0.0 ? uNoiseGain : 0.5, a = abs(uNoiseAmp);
    for (int o = 0; o < WAVES_NOISE_OCTAVES_MAX; o++) {
        if (o >= octaves) break;
        bound += 0.75 * a;
        a *= gain;
    }
    if (p.y < uWaterLevel - bound) return true;
#ifdef WORLD_HEIGHT_MAP
    // the surface's height from tarn's map of it this frame (world_height.frag);
    // beyond the map, the mean level
    vec2 uv = p.xz / uWaveHeightHalf * 0.5 + 0.5;
    float h = all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)))
            ? texture(uWaveHeight, uv).r : uWaterLevel;
    return p.y < h;
#else
    return p.y < wavesHeightAt(p.xz, uTime);
#endif
}

void main() {
    vec3 c;
    if (uWorldMode == 2) {
        c = worldSkyLook(uSky, normalize(vWorldNormal));
    } else if (uWorldMode == 0) {
        vec3 hg = terrainHeightGrad(vWorldPos.xz);
        vec3 n = normalize(vec3(-hg.y, 1.0, -hg.z));
        vec3 albedo = terrainAlbedo(vWorldPos.xz, hg.x, n);
        c = worldUnderWater(vWorldPos) ? worldShadeAt(albedo, n, vWorldPos)
                                       : worldHaze(worldLambert(albedo, n, vec3(1.0)), distance(uCameraPos, vWorldPos));
    } else {
        vec3 n = normalize(vWorldNormal);
        c = worldUnderWater(vWorldPos) ? worldShadeAt(uWorldAlbedo, n, vWorldPos)
                                       : worldHaze(worldLambert(uWorldAlbedo, n, vec3(1.0)), distance(uCameraPos, vWorldPos));
    }
    if (uWorldEyePath) c *= exp(-uAbsorption * eyePathInWater(uCameraPos, vWorldPos));
    fragColor = vec4(c, 1.0);
}
