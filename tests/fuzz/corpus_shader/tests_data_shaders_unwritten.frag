#version 330 compatibility
// unwritten.frag: vNormal (line 4) is not written by good_compat.vert
in vec3 vN;
in vec3 vNormal;
in float vUnused;
void main() { gl_FragColor = vec4(vN + vNormal, 1.0); }
