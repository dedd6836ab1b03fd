#version 330 compatibility
// The spectrum ocean's first pass (viewer/gfx/render_ocean.c; the model is
// reference/ref_ocean.h): for texel (m, n) of cascade uLayer, wave vector
// k = 2 pi (m', n') / L (m' = m < N/2 ? m : m - N, FFT order),
//
//     h~(k, t) = h0(k) e^{i w t} + conj(h0(-k)) e^{-i w t}
//
// and from it the spectra of the eight real fields (lambda folded into the
// D terms, k^ = k / |k|; all 0 at k = 0 and on the Nyquist row and column):
//     h~   Dx~ = i lambda k^x h~   Dz~ = i lambda k^z h~
//     hx~ = i kx h~   hz~ = i kz h~
//     Dxx~ = -lambda kx k^x h~   Dzz~ = -lambda kz k^z h~   Dxz~ = -lambda kz k^x h~
// (D's sign as ref_ocean.c's: points move towards the crests, as in a
// Gerstner wave, so lambda > 0 sharpens the crests.)
// packed as four complex spectra, each X + i Y of two Hermitian ones, so
// the inverse transform's real and imaginary parts are the two fields:
//     A = (Z0, Z1) = (h~ + i Dx~, Dz~ + i Dxz~)
//     B = (Z2, Z3) = (hx~ + i hz~, Dxx~ + i Dzz~)
// ocean_fft.frag then transforms them in place of the layout: the frame's
// A = (h, Dx, Dz, Dxz) and B = (hx, hz, Dxx, Dzz).

#include "contract.glsl"
uniform sampler2DArray uOceanH0;      // (Re h0(k), Im h0(k), Re conj(h0(-k)), Im conj(h0(-k)))
uniform sampler2DArray uOceanOmega;   // w(|k|)
uniform int uOceanLayer;              // the cascade
uniform int uOceanPassRes;            // N
uniform float uOceanPassTile;         // L of the cascade
uniform float uOceanLambda;           // choppiness

layout(location = 0) out vec4 oA;
layout(location = 1) out vec4 oB;

vec2 oceanMul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
vec2 oceanI(vec2 a) { return vec2(-a.y, a.x); }   // i a

void main() {
    ivec2 mn = ivec2(gl_FragCoord.xy);
    ivec3 at = ivec3(mn, uOceanLayer);
    vec4 h0 = texelFetch(uOceanH0, at, 0);
    float w = texelFetch(uOceanOmega, at, 0).x;
    int half_n = uOceanPassRes >> 1;
    vec2 s = vec2(mn.x < half_n ? mn.x : mn.x - uOceanPassRes, mn.y < half_n ? mn.y : mn.y - uOceanPassRes);
    vec2 k = s * (6.28318530717958647692 / uOceanPassTile);
    float kl = length(k);
    if (kl == 0.0 || mn.x == half_n || mn.y == half_n) { oA = vec4(0.0); oB = vec4(0.0); return; }
    vec2 kh = k / kl;
    float ph = w * uTime;
    vec2 e = vec2(cos(ph), sin(ph));
    vec2 H = oceanMul(h0.xy, e) + oceanMul(h0.zw, vec2(e.x, -e.y));
    vec2 iH = oceanI(H);
    vec2 dx = (uOceanLambda * kh.x) * iH, dz = (uOceanLambda * kh.y) * iH;
    vec2 hx = k.x * iH, hz = k.y * iH;
    vec2 dxx = (-uOceanLambda * kh.x * k.x) * H, dzz = (-uOceanLambda * kh.y * k.y) * H;
    vec2 dxz = (-uOceanLambda * kh.x * k.y) * H;
    oA = vec4(H + oceanI(dx), dz + oceanI(dxz));
    oB = vec4(hx + oceanI(hz), dxx + oceanI(dzz));
}
