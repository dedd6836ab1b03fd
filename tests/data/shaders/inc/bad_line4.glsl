// bad_line4.glsl: line 4 assigns a vec2 to a vec3
vec3 shade(vec3 n) {
    vec3 c = n * 0.5 + 0.5;
    vec3 d = vec2(1.0, 0.0);
    return c + d;
}
