#version 330 compatibility
// mismatch.frag: vN is a vec3 in good_compat.vert
in vec4 vN;
void main() { gl_FragColor = vN; }
