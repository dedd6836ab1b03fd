// contract.glsl: the uniforms tarn sets in a pack's programs (the pack
// contract, docs/packs/contract.md; the table is viewer/scene/contract.c),
// declared once for every shader: include it rather than declaring uTime,
// uCameraPos, a camera's matrix... again. A uniform a shader does not use
// is not active and costs nothing. Not here: the wave set's own (waves.glsl,
// waves_fx.glsl, waves_ocean.glsl, twins of reference/ref_waves.c, declare
// them beside the code that reads them) and tarn's world program's
// (uWorldAlbedo, uWorldMode, uWorldClip: world.frag's, not a pack's).
// Three parts are files of their own (contract_water.glsl,
// contract_light.glsl, contract_terrain.glsl) that waves.glsl, world.glsl and
// terrain.glsl include: those modules declare what they always declared,
// so a shader that includes them and declares uTime itself still compiles.
// test_contract checks this file against the table. No #version here.
#ifndef TARN_CONTRACT_GLSL
#define TARN_CONTRACT_GLSL

#include "contract_water.glsl"
#include "contract_light.glsl"
#include "contract_terrain.glsl"

// ---- the cameras (every program, every frame) ----
uniform mat4 uCamMainVP;           // world to clip of the viewer's camera
uniform mat4 uCamWideVP;           // the main camera, field of view widened
uniform mat4 uCamMirrorVP;         // the main camera mirrored about the water plane
uniform mat4 uCamTopVP;            // the orthographic top-down camera
uniform mat4 uCamLightVP;          // the orthographic camera along the sun
uniform mat4 uCamMainInvVP;        // their inverses, clip to world
uniform mat4 uCamWideInvVP;
uniform mat4 uCamMirrorInvVP;
uniform mat4 uCamTopInvVP;
uniform mat4 uCamLightInvVP;
uniform float uCamTopHalfSize;     // half the side of the orthographic cameras' squares
uniform float uCamLightHalfSize;

// ---- the pass ----
uniform vec2 uTargetSize;          // texels of what the program draws into
uniform float uPointGrid;          // N of `WaterSurface points N` or `mesh N`

// ---- the world (a scene with one) ----
uniform float uTime;               // simulated seconds
uniform vec3 uCameraPos;           // the current camera's eye, world space
uniform vec3 uSkyZenith;           // sky radiance at the zenith and the horizon
uniform samplerCube uSky;          // unit 15: the sky without the sun's disc (world.glsl's worldSkyLook)
uniform vec2 uWaterShift;          // x, z by which the water grid's rest points are moved
uniform sampler2D uTerrainAlbedo;  // unit 14: s = x, t = z over the world square

#endif // TARN_CONTRACT_GLSL
