#version 330 compatibility
// map_main.frag: an error on line 7, after an include on line 3
#include "inc/map_waves.glsl"
uniform float Timer;
void main() {
    float h = wave(vec2(Timer));
    gl_FragColor = vec4(h) * undefined_in_main;
}
