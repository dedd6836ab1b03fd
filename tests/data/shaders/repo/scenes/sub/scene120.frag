#version 120
varying vec3 vN;
varying vec3 vColour;
void main() { gl_FragColor = vec4(vN + vColour, 1.0); }
