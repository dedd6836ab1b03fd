// contract_light.glsl: the sun, the sky and the water's optics, and the
// length unit (a part of the pack contract: contract.glsl includes it, and
// world.glsl includes it alone, declaring no more than it always did, so a
// shader of yours that includes it and declares uTime, a camera's matrix...
// itself still compiles). No #version here.
#ifndef TARN_CONTRACT_LIGHT_GLSL
#define TARN_CONTRACT_LIGHT_GLSL

uniform vec3 uSunDir;              // towards the sun, unit
uniform vec3 uSunIrradiance;
uniform vec2 uSunDisc;             // SkySun: angular radius (rad; 0: none), gain
uniform vec3 uSkyHorizon;
uniform vec3 uAmbient;             // the sky's ambient radiance
uniform float uHazeDistance;       // Haze: air path (scene units) to 63 % horizon colour; 0: none
uniform float uIOR;                // the water's index of refraction
uniform vec3 uAbsorption;          // Beer-Lambert sigma per metre
uniform float uWorldScale;         // the scene's length unit: 1 on the lake (terrain half size 12 m);
                                   // a pack's lengths in lake metres are multiplied by it

#endif // TARN_CONTRACT_LIGHT_GLSL
