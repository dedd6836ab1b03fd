#version 330 compatibility
uniform float uGrey;
uniform vec3 uTint;
uniform bool uOn;
out vec4 fragColor;
void main() { fragColor = vec4(uOn ? uGrey * uTint : vec3(0.), 1.); }
