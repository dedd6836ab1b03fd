// hash.glsl: the integer hash tarn's GLSL noise is built on, one copy for
// every pack (waves.glsl's wave noise, caustic_tex's rock floor). The
// double-precision twin is ref_waves.c's, so the CPU reference's noise is
// the same. Needs #version 330 or later (uint arithmetic). No #version here.
#ifndef TARN_HASH_GLSL
#define TARN_HASH_GLSL

uint tarnHash(uint x) {                 // "lowbias32"
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

#endif
