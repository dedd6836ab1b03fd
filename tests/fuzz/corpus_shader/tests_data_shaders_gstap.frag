#version 330 compatibility
// gstap.frag: the GSTAP matrices exist in every stage
in vec3 vN;
in vec2 vST;
in vec4 vColor;
void main() {
    vec3 n = normalize(uNormalMatrix * vN);
    gl_FragColor = vec4(n, 1.0) * vColor + vec4(vST, 0.0, 0.0) + uProjectionMatrix[0];
}
