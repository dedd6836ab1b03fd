#version 330 compatibility
// packs/natural, caustics on the GPU, pass 2: the ratio a landed triangle
// adds to this texel: its rest cells per texel, |det| of the derivatives
// of the rest cell coordinate across the texture (exact: it is affine over
// a triangle), each worth its photon's weight w / texel area, as a point
// splat adds per photon. Under calm water that is 1 exactly.
#include "contract.glsl"
in vec2 vCell;
in float vWeight;
out vec4 fragColor;

// Where the light folds over, a triangle lands as a sliver: its ratio grows
// without bound as its area goes to 0, and a texel centre that falls in it
// would take a spike worth far more than the sliver's light. The cap sits
// above what the reference's photon tracer finds on the lake even at 2.5 cm
// cells (99.9th percentile of the ratio 6.1; 3.8 at its default 10 cm).
#define NAT_MESH_RATIO_MAX 8.0

void main() {
    vec2 a = dFdx(vCell), b = dFdy(vCell);
    float cells = abs(a.x * b.y - a.y * b.x);
    vec2 texel = 2.0 * uTerrainHalfSize / uTargetSize;
    float e = min(vWeight * cells / (texel.x * texel.y), NAT_MESH_RATIO_MAX);
    fragColor = vec4(e, e, e, 1.0);
}
