// map_waves.glsl: included by map_main.frag; includes map_fresnel.glsl
#include "map_fresnel.glsl"
float wave(vec2 p) {
    return sin(p.x) * fresnel(0.5) * undefined_in_waves;
}
