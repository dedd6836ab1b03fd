#version 330 compatibility
// The waves' height map (world_height.frag): the quads tarn draws over the
// target, x and y in [-1, 1], only where a test of wet land reads the map
// (render_world.c, height_quads; world_height_tiles.h).
void main() {
    gl_Position = vec4(gl_Vertex.xy, 0.0, 1.0);
}
