// cycle_b.glsl
float cycle_b_value() { return 1.0; }
#include "cycle_a.glsl"
