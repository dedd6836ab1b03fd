/* contract: the uniforms tarn sets in a pack's programs (the pack
 * contract, docs/packs/contract.md), one table for introspection (a
 * uniform tarn sets gets no slider), validation and the docs. No GL. */
#ifndef TARN_CONTRACT_H
#define TARN_CONTRACT_H

#include <stdbool.h>

/* What sets a uniform, and so when a program gets it. */
typedef enum contract_source {
    CONTRACT_CAMERA,     /* the cameras (LookAt, Perspective, Camera): every program, every frame */
    CONTRACT_PASS,       /* the pass (a target's size, WaterSurface points): every program */
    CONTRACT_WORLD,      /* the scene's world (Sun, Sky, Water, Terrain, ...): when it has one */
    CONTRACT_WAVES       /* the wave set (Water's level, Wave*): when it has a world */
} contract_source;

typedef struct contract_uniform {
    const char *name;
    const char *type;    /* as GLSL declares it ("float[8]" for an array) */
    contract_source source;
    const char *set_by;  /* the command or camera that gives the value */
    const char *meaning; /* one line */
} contract_uniform;

/* The whole table; *n gets its length. */
const contract_uniform *contract_uniforms(int *n);

/* The row of name, NULL when tarn does not set it. */
const contract_uniform *contract_find(const char *name);

/* tarn sets name in every program (a camera's or the pass's uniform). */
bool contract_is_camera_uniform(const char *name);

/* tarn sets name in the programs of a scene with a world (any row). */
bool contract_is_world_uniform(const char *name);

#endif
