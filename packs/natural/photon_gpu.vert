#version 330 compatibility
// packs/natural, caustics on the GPU: `WaterSurface points N` gives one
// point per cell centre of an N x N grid over the world square (tarn sets
// uPointGrid to that N and uTargetSize to the caustic target's size). Each traces its photon to the floor (natural.glsl)
// and hands the landing point, in caustic-texture texels, to the geometry
// shader, which splats it bilinearly with additive blending.
#include "waves.glsl"
#include "world.glsl"
#include "natural.glsl"

uniform float uTime;
uniform float uPointGrid;    // N of `WaterSurface points N` (set by tarn)
uniform vec2 uTargetSize;    // the caustic target's size in texels (set by tarn)
out vec2 vTexel;             // landing point in texels (texel centres at i + 0.5)
out float vWeight;           // weight per texel area: the ratio it adds
out float vValid;

void main() {
    vec2 p0 = gl_Vertex.xz;
    float h;
    vec2 dh, disp;
    vec3 abd;
    wavesSums(p0, uTime, h, dh, disp, abd);
    vec3 S = vec3(p0.x + disp.x, uWaterLevel + h, p0.y + disp.y);
    vec3 B = vec3(1.0 + abd.x, dh.x, abd.y);     // dP/dx0
    vec3 T = vec3(abd.y, dh.y, 1.0 + abd.z);     // dP/dz0
    vec3 nu = cross(T, B);                        // |nu| = area of the displaced cell per rest area
    float cell = 2.0 * uTerrainHalfSize / uPointGrid;
    // the flux through the displaced cell over that of a flat cell
    float area = cell * cell * max(dot(nu, uSunDir), 0.0) / max(uSunDir.y, 1e-4);
    vec2 q;
    float w;
    vValid = natPhoton(S, normalize(nu), area, q, w) ? 1.0 : 0.0;
    vec2 texel = 2.0 * natCausticHalfSize() / uTargetSize;
    vTexel = natCausticUV(q) * uTargetSize;
    vWeight = w / (texel.x * texel.y);
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
