// map_fresnel.glsl: an error on line 4
float fresnel(float c) {
    float r0 = 0.0204;
    return r0 + (1.0 - r0) * pow(1.0 - c, 5.0) * undefined_in_fresnel;
}
