// world_wet.glsl: is a world point under the moving water surface now?
// The one time-dependent part of the world's shading: world.frag decides
// each pixel's wet or dry shading by it, and world_layers.frag (a World
// draw's two shadings kept while only the time changes) decides it again
// at each new time, with the same function on the same point. Both take
// the waves' bound (worldWavesBound) once a vertex, flat: it is the same
// for every pixel, and a CPU rasteriser ran its loops in each.
#ifndef WORLD_WET_GLSL
#define WORLD_WET_GLSL
#include "contract.glsl"
#include "loops.glsl"        // ROLLED(n): loop bounds

// Is p under the water surface at this time (worldUnderWaterWithin, bound
// worldWavesBound())? Below the mean level is not enough: where a trough
// uncovers the shore, the reference's ray meets the
// land in air and lights it dry (its shading follows the path, not the
// mean level). Within the waves' height bound of the level (waves.glsl's
// sum of amplitudes; gradient noise stays within 0.75 of its amplitude)
// the surface's height is read from tarn's map of it this frame
// (WORLD_HEIGHT_MAP, world_height.frag), or else solved for here: on a
// CPU rasteriser every pixel pays for that solve, wet or dry.
#ifdef WORLD_HEIGHT_MAP
uniform sampler2D uWaveHeight;     // the surface's height over the world (set by tarn)
uniform float uWaveHeightHalf;     // it covers x, z in [-half, half]
#endif
// The waves' height bound: a sum of the scene's uniforms, the same for
// every pixel (a full-screen pass takes it once a vertex, world_layers).
float worldWavesBound() {
    float bound = 0.0;
    for (int i = 0; i < ROLLED(WAVES_MAX); i++) {
        if (i < uSineCount) bound += abs(uSineAmp[i]);
        if (i < uGerstnerCount) bound += abs(uGerstnerAmp[i]);
    }
    int octaves = uNoiseOctaves > 0 ? uNoiseOctaves : 4;
    float gain = uNoiseGain > 0.0 ? uNoiseGain : 0.5, a = abs(uNoiseAmp);
    for (int o = 0; o < ROLLED(WAVES_NOISE_OCTAVES_MAX); o++) {
        if (o >= octaves) break;
        bound += 0.75 * a;
        a *= gain;
    }
    return bound;
}

bool worldUnderWaterWithin(vec3 p, float bound) {
    if (p.y >= uWaterLevel) return false;
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

#endif // WORLD_WET_GLSL
