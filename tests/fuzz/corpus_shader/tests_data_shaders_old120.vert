#version 120
// old120.vert: GLSL 1.20 numbers the line after `#line N` as N + 1
varying vec3 vN;
void main() {
    vN = gl_NormalMatrix * gl_Normal * undefined_in_old;
    gl_Position = ftransform();
}
