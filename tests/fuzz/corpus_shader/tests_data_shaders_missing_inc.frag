#version 330 compatibility
// missing_inc.frag: line 3 includes a file that does not exist
#include "no_such_file.glsl"
void main() { gl_FragColor = vec4(1.0); }
