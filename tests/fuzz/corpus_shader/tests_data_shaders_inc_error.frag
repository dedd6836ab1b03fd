#version 330 compatibility
// inc_error.frag: the only error is on line 4 of inc/bad_line4.glsl
#include "inc/bad_line4.glsl"
in vec3 vN;
void main() { gl_FragColor = vec4(shade(vN), 1.0); }
