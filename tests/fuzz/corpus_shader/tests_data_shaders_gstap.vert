#version 330 compatibility
// gstap.vert: glman's GSTAP names (compiles only with GSTAP)
out vec3 vN;
out vec2 vST;
out vec4 vColor;
void main() {
    vN = normalize(uNormalMatrix * aNormal);
    vST = aTexCoord0.st + aTexCoord7.st;
    vColor = aColor;
    vec4 ec = uModelViewMatrix * aVertex;
    vec4 back = uModelViewMatrixInverse * ec;
    gl_Position = uProjectionMatrix * ec + 0.0 * (uModelViewProjectionMatrix * back);
}
