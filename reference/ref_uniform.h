/* ref_uniform: one GLSL uniform's value as the reference resolves it, so
 * the GL side uploads what the CPU worked out once (the wave set's
 * uWave*, the explosion rings' and Perlin sets' uniforms). No GL here. */
#ifndef TARN_REF_UNIFORM_H
#define TARN_REF_UNIFORM_H

#include <stdint.h>

#define REF_UNIFORM_ARRAY_MAX 8    /* elements of an array uniform */

typedef struct ref_waves_uniform {
    const char *name;        /* e.g. "uGerstnerLength" */
    int is_int;              /* an int uniform: its value is in i */
    int is_uint;             /* a uint array: its values are in u */
    int count;               /* 1, or the array length (at most REF_UNIFORM_ARRAY_MAX) */
    int comps;               /* floats an element: 1, 3 (vec3) or 4 (vec4) */
    int i;                   /* value of an int uniform (uNoiseSeed: the seed's bits) */
    uint32_t u[REF_UNIFORM_ARRAY_MAX];
    float v[REF_UNIFORM_ARRAY_MAX * 4];  /* values of a float uniform or array, element after element */
} ref_waves_uniform;

#endif
