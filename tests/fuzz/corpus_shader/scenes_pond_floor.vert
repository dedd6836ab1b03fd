#version 330 compatibility
// The pond floor: a flat quad with sand ripples from the noise texture.
out vec2 vST;
out vec3 vPos;

void main() {
    vST = gl_MultiTexCoord0.st;
    vPos = gl_Vertex.xyz;
    gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;
}
