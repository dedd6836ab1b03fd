#version 330 compatibility
// A screen-filling quad: `QuadXY 0 1` spans clip space (-1..1) as it is,
// so the screen is covered pixel for pixel, whatever camera.
void main() {
    gl_Position = vec4(gl_Vertex.xy, 0.0, 1.0);
}
