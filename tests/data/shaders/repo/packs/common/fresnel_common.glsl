// fresnel_common.glsl: stands in for packs/common in the tests (repo/ is a fake repo root)
#ifndef FRESNEL_COMMON_GLSL
#define FRESNEL_COMMON_GLSL
float schlick(float cosTheta, float r0) {
    return r0 + (1.0 - r0) * pow(1.0 - cosTheta, 5.0);
}
#endif
