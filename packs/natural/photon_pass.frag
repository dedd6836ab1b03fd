#version 330 compatibility
// packs/natural, caustics on the GPU, pass 1: one photon per texel of the
// uPhotonGrid^2 target, texel (i, j) the cell centre (i, j) of that grid
// over the world square (the points of `WaterSurface points`, in the same
// order, moved like them by uWaterShift). Each traces its photon to the
// floor (natural.glsl) and writes what `Splat` reads: RG the landing point
// in refracted-sun space scaled onto the world square, B its weight scaled
// the same way, A 1 when valid (photon.frag's layout). photon_splat.vert
// splats it on the GPU; `Splat` would on the CPU.
#include "contract.glsl"
#include "waves.glsl"
#include "world.glsl"
#include "natural.glsl"

out vec4 fragColor;

void main() {
    vec2 cell = 2.0 * uTerrainHalfSize / uTargetSize;
    vec2 p0 = -uTerrainHalfSize + floor(gl_FragCoord.xy) * cell + 0.5 * cell + uWaterShift;
    float h;
    vec2 dh, disp;
    vec3 abd;
    wavesSums(p0, uTime, h, dh, disp, abd);
    vec3 S = vec3(p0.x + disp.x, uWaterLevel + h, p0.y + disp.y);
    vec3 B = vec3(1.0 + abd.x, dh.x, abd.y);     // dP/dx0
    vec3 T = vec3(abd.y, dh.y, 1.0 + abd.z);     // dP/dz0
    vec3 nu = cross(T, B);                        // |nu| = area of the displaced cell per rest area
    // the flux through the displaced cell over that of a flat cell
    float area = cell.x * cell.y * max(dot(nu, uSunDir), 0.0) / max(uSunDir.y, 1e-4);
    vec2 q;
    float w;
    bool valid = natPhoton(S, normalize(nu), area, q, w);
    float s = uTerrainHalfSize / natCausticHalfSize();
    // a lost photon (A = 0, no weight) keeps the q where it stopped: the
    // mesh splat places its corner there
    fragColor = vec4(q * s, w * s * s, valid ? 1.0 : 0.0);
}
