#version 330 compatibility
// packs/natural, caustics on the GPU, pass 1: a full-screen quad (`QuadXY`,
// x, y in [-1, 1]) over the photon target, so photon_pass.frag runs once
// per photon. Why a fragment pass: a CPU rasteriser runs vertex and
// geometry shaders on one thread and fragments on all of them.
void main() {
    gl_Position = vec4(gl_Vertex.xy, 0.0, 1.0);
}
