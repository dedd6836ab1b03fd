#version 330 compatibility
// packs/natural, caustics on the GPU: adds the photon's share (Blend add).
in float gWeight;
out vec4 fragColor;

void main() {
    fragColor = vec4(gWeight, gWeight, gWeight, 1.0);
}
