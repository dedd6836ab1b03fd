#version 330 compatibility
#include "inc/cycle_a.glsl"
void main() { gl_FragColor = vec4(1.0); }
