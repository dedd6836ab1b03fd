#version 330 compatibility
// One radix-2 Stockham pass of the spectrum ocean's inverse FFT
// (viewer/gfx/render_ocean.c): along x (rows), or along z (columns) with
// OCEAN_FFT_VERTICAL defined. log2 N passes a direction, uOceanSize = 2, 4,
// ..., N, ping-ponging between two texture pairs; natural order in and out
// (no bit reversal). After the pass of size s the line holds N / s
// transforms of size s; output i = j + s b (j < s) is
//     E[j mod s/2] + e^{+2 pi i j / s} O[j mod s/2]
// with E at input index b s/2 + (j mod s/2) and O at that + N/2 (the even
// and odd halves of transform b). The sign is +: the inverse transform,
// sum h~ e^{i k.x}; no 1/N (h0 holds amplitudes). Each texel carries four
// complex numbers in A and B, each transformed alike.

uniform sampler2DArray uOceanSrcA, uOceanSrcB;
uniform int uOceanLayer;
uniform int uOceanPassRes;     // N
uniform int uOceanSize;        // s: the transforms' size after this pass

layout(location = 0) out vec4 oA;
layout(location = 1) out vec4 oB;

vec2 oceanMul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
#ifdef OCEAN_FFT_VERTICAL
    int i = p.y;
#else
    int i = p.x;
#endif
    int hs = uOceanSize >> 1;
    int j = i & (uOceanSize - 1);
    int e = (i / uOceanSize) * hs + (j & (hs - 1));
    int o = e + (uOceanPassRes >> 1);
#ifdef OCEAN_FFT_VERTICAL
    ivec3 pe = ivec3(p.x, e, uOceanLayer), po = ivec3(p.x, o, uOceanLayer);
#else
    ivec3 pe = ivec3(e, p.y, uOceanLayer), po = ivec3(o, p.y, uOceanLayer);
#endif
    vec4 ea = texelFetch(uOceanSrcA, pe, 0), oa = texelFetch(uOceanSrcA, po, 0);
    vec4 eb = texelFetch(uOceanSrcB, pe, 0), ob = texelFetch(uOceanSrcB, po, 0);
    // the angle in (-pi, pi], where GPUs' sin and cos are accurate
    float a = 6.28318530717958647692 * float(j > hs ? j - uOceanSize : j) / float(uOceanSize);
    vec2 w = vec2(cos(a), sin(a));
    oA = vec4(ea.xy + oceanMul(w, oa.xy), ea.zw + oceanMul(w, oa.zw));
    oB = vec4(eb.xy + oceanMul(w, ob.xy), eb.zw + oceanMul(w, ob.zw));
}
