// comment first
/* a block
   comment */
#version 450 core // tail
#include "self.glsl"
