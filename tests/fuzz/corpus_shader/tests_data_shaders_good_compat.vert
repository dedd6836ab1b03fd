#version 330 compatibility
// good_compat.vert: glman-style, reads the compatibility built-ins
uniform float Timer;
out vec3 vN;
out vec3 vE;
out vec2 vST;
void main() {
    vec4 ecPos = gl_ModelViewMatrix * gl_Vertex;
    vN = normalize(gl_NormalMatrix * gl_Normal);
    vE = -ecPos.xyz;
    vST = gl_MultiTexCoord0.st + vec2(Timer);
    gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;
}
