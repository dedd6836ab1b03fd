#version 330 compatibility
// The spectrum ocean's folding foam (viewer/gfx/render_ocean.c, after the
// FFT passes), for node (m, n) of cascade uOceanLayer: Tessendorf's
// Jacobian of the choppy map, J = (1 + Dxx)(1 + Dzz) - Dxz^2 (< 0 where
// the surface folds over), its coverage clamp((J0 - J) / soft, 0, 1), and
//     foam = max(foam_prev keep, coverage),   keep = exp(-dt / decay)
// (0 on a restart). g carries the cascade's slope variance sigma_c^2 for
// waves_ocean.glsl's filtered normal.

uniform sampler2DArray uOceanSrcA;       // the frame: (h, Dx, Dz, Dxz)
uniform sampler2DArray uOceanSrcB;       //            (hx, hz, Dxx, Dzz)
uniform sampler2DArray uOceanFoamPrev;   // the foam before: (foam, sigma^2)
uniform int uOceanLayer;
uniform float uOceanFoamKeep;            // exp(-dt / decay), 0: restart
uniform float uOceanFoamJ;               // J at which foam starts
uniform float uOceanFoamSoft;            // J below that to full cover
uniform float uOceanSlopeVar;            // sigma_c^2

layout(location = 0) out vec4 oFoam;

void main() {
    ivec3 at = ivec3(ivec2(gl_FragCoord.xy), uOceanLayer);
    vec4 a = texelFetch(uOceanSrcA, at, 0);
    vec4 b = texelFetch(uOceanSrcB, at, 0);
    float J = (1.0 + b.z) * (1.0 + b.w) - a.w * a.w;
    float cover = clamp((uOceanFoamJ - J) / uOceanFoamSoft, 0.0, 1.0);
    float prev = texelFetch(uOceanFoamPrev, at, 0).x;
    oFoam = vec4(max(prev * uOceanFoamKeep, cover), uOceanSlopeVar, 0.0, 1.0);
}
