#version 330 compatibility
// The waves' height map (world_height.frag): one triangle over the target,
// made from the vertex index (no mesh).
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
