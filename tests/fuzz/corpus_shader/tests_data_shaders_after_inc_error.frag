#version 330 compatibility
// after_inc_error.frag: a good include, then an error on line 6
#include <fresnel_common.glsl>
in vec3 vN;
void main() {
    float f = schlick(vN.z, 0.02) + no_such_variable;
    gl_FragColor = vec4(f);
}
