#version 120
uniform sampler3D Clouds;
varying vec2 vST;
void main() {
    vec4 b = texture3D(Clouds, vec3(vST, 0.5));
    gl_FragColor = vec4(b.r, b.g, 0.5, 1.);
}
