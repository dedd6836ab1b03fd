// cycle_a.glsl includes cycle_b.glsl, which includes this file again
#include "cycle_b.glsl"
