/* ref_hash: the integer hash the wave noises are built on, once for the
 * reference ("lowbias32", Chris Wellons); packs/common/hash.glsl's tarnHash
 * is the same function, so the CPU and the GPU draw the same noise. */
#ifndef TARN_REF_HASH_H
#define TARN_REF_HASH_H

#include <stdint.h>

static inline uint32_t ref_hash32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

#endif
