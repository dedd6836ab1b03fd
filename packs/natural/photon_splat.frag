#version 330 compatibility
// packs/natural, caustics on the GPU, pass 2: a photon's share of this
// texel, the tent (bilinear) weight of its distance from the landing point.
flat in vec2 vTexel;
flat in float vWeight;
out vec4 fragColor;

void main() {
    vec2 t = max(1.0 - abs(gl_FragCoord.xy - vTexel), 0.0);
    float e = vWeight * t.x * t.y;
    fragColor = vec4(e, e, e, 1.0);
}
