// contract_terrain.glsl: the terrain's model (a part of the pack contract:
// contract.glsl includes it, and terrain.glsl includes it alone, declaring
// no more than it always did, so a shader of yours that includes it and
// declares uTime, a camera's matrix... itself still compiles). No #version
// here.
#ifndef TARN_CONTRACT_TERRAIN_GLSL
#define TARN_CONTRACT_TERRAIN_GLSL

uniform float uTerrainHalfSize;    // the world is the square |x|, |z| <= this
uniform int uTerrainKind;          // REF_TERRAIN_*: 0 flat, 1 lake, 2 slope, 3 pool
uniform vec4 uTerrainShape;        // depth, shore height, slope, -
uniform vec4 uTerrainDetail[6];    // the lake's detail: k.x, k.z, amplitude, phase (REF_TERRAIN_DETAIL)
uniform float uGroundDetail;       // GroundDetail: the ground's noise, 0 to 1
uniform sampler2D uTerrainHeightMap; // the height less uTerrainMapPlane, baked once per world
uniform float uTerrainMapHalf;     // the map covers |x|, |z| <= this (clamped beyond)
uniform vec3 uTerrainMapPlane;     // the terrain's linear part: h at x = z = 0, dh/dx, dh/dz

// The terrain's model and the ground's noise as the scene's constants
// where tarn built the program (WORLD_DEFINES: viewer/gfx/render_world.h,
// world_set_defines; a reload builds it again): llvmpipe runs both sides
// of an `if`, even on a uniform, so every kind's model and the noise cost
// every pixel that asks for the ground. Without tarn's defines (glslang's
// validation, a build elsewhere) the uniforms decide.
#ifdef WORLD_DEFINES
#define TERRAIN_KIND WORLD_TERRAIN_KIND
#ifdef WORLD_GROUND_DETAIL
#define TERRAIN_GROUND_DETAIL uGroundDetail
#else
#define TERRAIN_GROUND_DETAIL 0.0
#endif
#else
#define TERRAIN_KIND uTerrainKind
#define TERRAIN_GROUND_DETAIL uGroundDetail
#endif

#endif // TARN_CONTRACT_TERRAIN_GLSL
