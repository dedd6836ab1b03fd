/* contract.c: the table of uniforms tarn sets (contract.h). The names must
 * match what the gfx layer uploads (gfx/render_world.c, render_camera.c,
 * render_*.c) and, for the wave set, ref_waves_uniforms (test_contract
 * checks both this and docs/packs/contract.md). */
#include "contract.h"

#include <stddef.h>
#include <string.h>

#define CAM(n, t, by, m) { n, t, CONTRACT_CAMERA, by, m }
#define PASS(n, t, by, m) { n, t, CONTRACT_PASS, by, m }
#define WORLD(n, t, by, m) { n, t, CONTRACT_WORLD, by, m }
#define WAVES(n, t, by, m) { n, t, CONTRACT_WAVES, by, m }

static const contract_uniform table[] = {
    CAM("uCamMainVP", "mat4", "Camera main", "world to clip of the viewer's camera"),
    CAM("uCamWideVP", "mat4", "Camera wide", "world to clip of the main camera, field of view widened"),
    CAM("uCamMirrorVP", "mat4", "Camera mirror", "world to clip of the main camera mirrored about the water plane"),
    CAM("uCamTopVP", "mat4", "Camera top", "world to clip of the orthographic top-down camera"),
    CAM("uCamLightVP", "mat4", "Camera light", "world to clip of the orthographic camera along the sun"),
    CAM("uCamMainInvVP", "mat4", "Camera main", "clip to world of the main camera"),
    CAM("uCamWideInvVP", "mat4", "Camera wide", "clip to world of the wide camera"),
    CAM("uCamMirrorInvVP", "mat4", "Camera mirror", "clip to world of the mirror camera"),
    CAM("uCamTopInvVP", "mat4", "Camera top", "clip to world of the top-down camera"),
    CAM("uCamLightInvVP", "mat4", "Camera light", "clip to world of the light camera"),
    CAM("uCamTopHalfSize", "float", "Camera top", "half the side of the top-down camera's square"),
    CAM("uCamLightHalfSize", "float", "Camera light", "half the side of the light camera's square"),
    PASS("uTargetSize", "vec2", "RenderToTexture", "the size in texels of what the program draws into"),
    PASS("uPointGrid", "float", "WaterSurface points", "N of the N x N points drawn (or of the mesh between them), as a float (glUniform1f)"),
    PASS("uLoopZero", "int", "(never set)", "always 0, GL's start value: on a CPU rasteriser loops.glsl's ROLLED(n) adds it to a loop's constant bound so the compiler keeps the loop rolled"),
    WORLD("uSunDir", "vec3", "Sun", "towards the sun, unit"),
    WORLD("uSunIrradiance", "vec3", "Sun", "the sun's irradiance"),
    WORLD("uSkyZenith", "vec3", "Sky", "sky radiance at the zenith"),
    WORLD("uSkyHorizon", "vec3", "Sky", "sky radiance at the horizon"),
    WORLD("uAmbient", "vec3", "Sky", "ambient radiance of the sky"),
    WORLD("uIOR", "float", "Water", "the water's index of refraction"),
    WORLD("uAbsorption", "vec3", "Water", "Beer-Lambert sigma per metre"),
    WORLD("uTerrainHalfSize", "float", "Terrain", "the world is the square |x|, |z| <= this"),
    WORLD("uCameraPos", "vec3", "LookAt", "the current camera's eye, world space"),
    WORLD("uTime", "float", "(the clock)", "simulated seconds"),
    WORLD("uWaterShift", "vec2", "WaterSurface", "x, z by which the water grid's rest points (and the photon points) are moved"),
    WORLD("uSky", "samplerCube", "Sky", "unit 15: the sky without the sun's disc (ref_sky_smooth); alpha: the disc's share through the clouds"),
    WORLD("uSunDisc", "vec2", "SkySun", "the sun's disc: angular radius (rad, 0: none), gain (world.glsl's worldSunDisc)"),
    WORLD("uHazeDistance", "float", "Haze", "air path to 63 % horizon colour, scene units (0: none)"),
    WORLD("uGroundDetail", "float", "GroundDetail", "the ground's noise, 0 to 1 (terrain.glsl)"),
    WORLD("uTerrainAlbedo", "sampler2D", "Terrain", "unit 14: terrain albedo, s = x, t = z over the world square"),
    WORLD("uOceanA", "sampler2DArray", "WaveOcean", "unit 28: the ocean's frame, (h, Dx, Dz, Dxz) a node, a layer a cascade"),
    WORLD("uOceanB", "sampler2DArray", "WaveOcean", "unit 29: (hx, hz, Dxx, Dzz) a node, a layer a cascade"),
    WORLD("uOceanFoam", "sampler2DArray", "WaveOcean", "unit 27: (folding foam, the cascade's slope variance) a node, a layer a cascade"),
    WORLD("uWorldScale", "float", "Terrain", "the scene's length unit: terrain half size / 12 m (1 on the lake)"),
    WORLD("uTerrainKind", "int", "Terrain", "the terrain's model: 0 flat, 1 lake, 2 slope, 3 pool (REF_TERRAIN_*)"),
    WORLD("uTerrainShape", "vec4", "Terrain", "the model's depth, shore height and slope"),
    WORLD("uTerrainDetail", "vec4[6]", "Terrain", "the lake's detail waves: k.x, k.z, amplitude, phase"),
    WORLD("uTerrainHeightMap", "sampler2D", "Terrain", "unit 21: the terrain's height less uTerrainMapPlane, baked once per world (terrainHeightMarch)"),
    WORLD("uTerrainMapHalf", "float", "Terrain", "the height map covers |x|, |z| <= this (clamped beyond)"),
    WORLD("uTerrainMapPlane", "vec3", "Terrain", "the terrain's linear part: h at x = z = 0, dh/dx, dh/dz (the slope's; 0 for the others)"),
    WORLD("uWorldAlbedo", "vec3", "Object", "tarn's world program: an object's albedo"),
    WORLD("uWorldMode", "int", "World", "tarn's world program: 0 terrain, 1 object, 2 sky"),
    WORLD("uWorldClip", "vec4", "World above|below", "tarn's world program: the clip plane (n, d)"),
    WAVES("uWaterLevel", "float", "Water", "mean water height"),
    WAVES("uSteepness", "float", "WaveSteepness", "Q = sum Q_i k_i A_i of the Gerstner waves"),
    WAVES("uSineCount", "int", "WaveSine", "how many sine waves"),
    WAVES("uSineAngle", "float[8]", "WaveSine", "direction of travel, degrees from +x towards +z"),
    WAVES("uSineLength", "float[8]", "WaveSine", "wavelength"),
    WAVES("uSineAmp", "float[8]", "WaveSine", "amplitude"),
    WAVES("uSineSpeed", "float[8]", "WaveSine", "phase speed (0: deep water)"),
    WAVES("uSinePhase", "float[8]", "WaveSine", "phase, radians"),
    WAVES("uGerstnerCount", "int", "WaveGerstner", "how many Gerstner waves"),
    WAVES("uGerstnerAngle", "float[8]", "WaveGerstner", "direction of travel, degrees"),
    WAVES("uGerstnerLength", "float[8]", "WaveGerstner", "wavelength"),
    WAVES("uGerstnerAmp", "float[8]", "WaveGerstner", "amplitude"),
    WAVES("uGerstnerSpeed", "float[8]", "WaveGerstner", "phase speed (0: deep water)"),
    WAVES("uGerstnerPhase", "float[8]", "WaveGerstner", "phase, radians"),
    WAVES("uNoiseAmp", "float", "WaveNoise", "amplitude of octave 0 (0: no noise)"),
    WAVES("uNoiseCell", "float", "WaveNoise", "lattice cell of octave 0"),
    WAVES("uNoiseOctaves", "int", "WaveNoise", "octaves"),
    WAVES("uNoisePeriod", "int", "WaveNoise", "cells per tile at octave 0"),
    WAVES("uNoiseGain", "float", "WaveNoise", "amplitude ratio between octaves"),
    WAVES("uNoiseAngle", "float", "WaveNoise", "drift direction of octave 0, degrees"),
    WAVES("uNoiseSpeed", "float", "WaveNoise", "drift speed of octave 0"),
    WAVES("uNoiseSeed", "int", "WaveNoise", "the seed's 32 bits, read as uint"),
    /* the same waves resolved on the CPU (inactive ones dropped, defaults
     * filled in): what waves.glsl's functions read */
    WAVES("uWaveSineN", "int", "WaveSine", "active sine waves"),
    WAVES("uWaveSine", "vec4[8]", "WaveSine", "k D.x, k D.z, omega, phase of each active sine wave"),
    WAVES("uWaveSineAmp", "float[8]", "WaveSine", "amplitude of each active sine wave"),
    WAVES("uWaveGerstN", "int", "WaveGerstner", "active Gerstner waves"),
    WAVES("uWaveGerst", "vec4[8]", "WaveGerstner", "k D.x, k D.z, omega, phase of each active Gerstner wave"),
    WAVES("uWaveGerstAmp", "vec3[8]", "WaveGerstner", "A, Q_i A_i D.x, Q_i A_i D.z"),
    WAVES("uWaveNoiseN", "int", "WaveNoise", "noise octaves (0: no noise)"),
    WAVES("uWaveNoise", "vec4[8]", "WaveNoise", "frequency, frequency times drift (x, z), amplitude per octave"),
    WAVES("uWaveNoisePeriod", "float[8]", "WaveNoise", "lattice cells per tile per octave"),
    WAVES("uWaveNoiseSeed", "uint[8]", "WaveNoise", "hashed seed per octave"),
    /* the explosion rings and the Perlin set (ref_wavefx_uniforms; waves_fx.glsl) */
    WAVES("uExplosionN", "int", "WaveExplosion", "explosion rings (0: none)"),
    WAVES("uExplosion", "vec4[4]", "WaveExplosion", "centre x, z, start time, I0 of each ring"),
    WAVES("uExplosionWave", "vec4[4]", "WaveExplosion", "omega, k, decay, k^2 of each ring"),
    WAVES("uPerlinN", "int", "WavePerlin", "Perlin octaves (0: no Perlin set)"),
    WAVES("uPerlinOctave", "vec4[8]", "WavePerlin", "spatial frequency, time frequency, amplitude per octave"),
    WAVES("uPerlinFrame", "vec4", "WavePerlin", "cos and sin of the wind's angle, 1 / stretch"),
    WAVES("uPerlinSeed", "uint[8]", "WavePerlin", "hashed seed per octave"),
    /* the spectrum ocean (ref_waves_uniforms; waves_ocean.glsl) */
    WAVES("uOceanN", "int", "WaveOcean", "cascades (0: no ocean)"),
    WAVES("uOceanRes", "int", "WaveOcean", "N, the FFT's nodes a side"),
    WAVES("uOceanTile", "float[3]", "WaveOceanTiles", "each cascade's tile side"),
};

#define NTABLE ((int)(sizeof table / sizeof table[0]))

const contract_uniform *contract_uniforms(int *n) {
    if (n)
        *n = NTABLE;
    return table;
}

const contract_uniform *contract_find(const char *name) {
    for (int i = 0; name && i < NTABLE; i++)
        if (strcmp(name, table[i].name) == 0)
            return &table[i];
    return NULL;
}

bool contract_is_camera_uniform(const char *name) {
    const contract_uniform *u = contract_find(name);
    return u && (u->source == CONTRACT_CAMERA || u->source == CONTRACT_PASS);
}

bool contract_is_world_uniform(const char *name) {
    return contract_find(name) != NULL;
}
