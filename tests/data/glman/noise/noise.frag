#version 120
uniform sampler2D Noise2;
uniform sampler3D Noise3;
varying vec2 vST;
void main() {
    vec4 a = texture2D(Noise2, vST);
    vec4 b = texture3D(Noise3, vec3(vST, 0.5));
    gl_FragColor = vec4(a.r, b.r, 0.5 * (a.g + b.g), 1.);
}
