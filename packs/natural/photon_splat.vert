#version 330 compatibility
// packs/natural, caustics on the GPU, pass 2: `WaterSurface mesh N` draws
// the triangles between the photons of photon_pass.frag's target (vertex
// k = j N + i is photon (i, j)), each corner moved to where its photon
// lands in refracted-sun space. A triangle spreads the light of the rest
// area it spans over the area it lands on (photon_splat.frag), so a
// caustic is as sharp as the surface focuses it, and there is no photon
// noise: the mesh tiles the texture, every texel centre lies in one
// triangle (or, where the light folds over, in one per layer). Wallace's
// WebGL Water lights its pool so. No geometry shader: on a CPU rasteriser
// it would run on one thread.
#include "contract.glsl"
uniform sampler2D uPhotons;  // photon_pass.frag's target
out vec2 vCell;              // the photon's rest cell (i, j): area in the mean plane
out float vWeight;           // its weight per rest cell (scaled as for Splat); 0 if lost

void main() {
    int n = int(uPointGrid + 0.5);
    ivec2 ij = ivec2(gl_VertexID % n, gl_VertexID / n);
    vec4 ph = texelFetch(uPhotons, ij, 0);
    // a lost photon (A = 0: blocked above the water, or no floor met)
    // brings no light and keeps the point where it stopped, so the
    // triangles it corners fade to nothing towards it
    bool finite = !any(isnan(ph.rgb)) && !any(isinf(ph.rgb));
    vec2 rest = (-1.0 + (vec2(ij) + 0.5) * (2.0 / float(n))) * uTerrainHalfSize;
    vCell = vec2(ij);
    vWeight = finite && ph.a > 0.5 ? ph.b : 0.0;
    gl_Position = vec4((finite ? ph.rg : rest) / uTerrainHalfSize, 0.0, 1.0);
}
