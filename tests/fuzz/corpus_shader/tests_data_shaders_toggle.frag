#version 330 compatibility
// toggle.frag: compiles unless FOO is set (line 8 is wrong then); BAR is harmless
in vec3 vN;
in vec3 vE;
in vec2 vST;
void main() {
#ifdef FOO
    vec3 c = vST;
#else
    vec3 c = vN;
#endif
#if BAR
    c *= 0.5;
#endif
    gl_FragColor = vec4(c + vE * 0.0, 1.0);
}
