#version 330 compatibility
// good_compat.frag: uses a shared include found through an include dir
#include <fresnel_common.glsl>
in vec3 vN;
in vec3 vE;
in vec2 vST;
uniform sampler2D Noise2;
void main() {
    float f = schlick(max(dot(normalize(vN), normalize(vE)), 0.0), 0.0204);
    vec4 n = texture2D(Noise2, vST);
    gl_FragColor = vec4(mix(vec3(0.1, 0.3, 0.4), vec3(1.0), f), 1.0) + 0.1 * n;
}
