#version 330 compatibility
// Leaves alpha 0.5 in the window, as a blended water surface does: the
// screenshot must still be opaque.
out vec4 fragColor;
void main() { fragColor = vec4(0.2, 0.4, 0.5, 0.5); }
