#version 120
varying vec3 vN;
void main() { vN = gl_Normal; gl_Position = ftransform(); }
