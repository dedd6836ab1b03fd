// loops.glsl: ROLLED(n), the bound of a loop that runs at most n times
// (n a constant), which a CPU rasteriser's compiler is kept from unrolling.
//
//     for (int i = 0; i < ROLLED(WAVES_MAX); i++) { if (i >= uWaveSineN) break; ... }
//
// Why: Mesa's NIR unrolls every loop whose trip count it can prove, and
// llvmpipe then hands LLVM n copies of the body; LLVM's compile time grows
// with the copies while the frame gains nothing (llvmpipe's lanes run in
// lockstep either way). Measured cold on the lake at 64x36 (a save pays the
// same compile): the water programs compiled in about half the time (basic
// 240 -> 128 ms, caustic_tex 1282 -> 657, raymarch 595 -> 423, natural 730
// -> 550), the waves' height map in half (545-795 -> 258-458 ms), with the
// same pixels and frames as fast (docs/benchmark.md, "Rolled loops").
//
// tarn defines TARN_CPU_RASTER when GL_RENDERER is a CPU rasteriser
// (llvmpipe, softpipe, ...): there the bound is n plus uLoopZero, a uniform
// tarn never sets, so GL's start value 0 (the compiler cannot know it). On
// a GPU, where compiles are quick and unrolling may pay, ROLLED(n) is n.
// No #version here.
#ifndef TARN_LOOPS_GLSL
#define TARN_LOOPS_GLSL

#ifdef TARN_CPU_RASTER
uniform int uLoopZero;              // always 0: never set (packs/common/loops.glsl)
#define ROLLED(n) ((n) + uLoopZero)
#else
#define ROLLED(n) (n)
#endif

#endif // TARN_LOOPS_GLSL
