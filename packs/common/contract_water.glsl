// contract_water.glsl: the mean water level (a part of the pack contract:
// contract.glsl includes it, and waves.glsl (and world.glsl) includes it
// alone, declaring no more than it always did, so a shader of yours that
// includes it and declares uTime, a camera's matrix... itself still
// compiles). No #version here.
#ifndef TARN_CONTRACT_WATER_GLSL
#define TARN_CONTRACT_WATER_GLSL

uniform float uWaterLevel;         // mean water height

#endif // TARN_CONTRACT_WATER_GLSL
