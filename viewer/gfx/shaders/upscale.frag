#version 330 core
// upscale.frag: one axis of the window's upscale (viewer/gfx/upscale.h
// says what and why). Built into tarn by embed.cmake; drawn as one
// triangle over the pass's rectangle, twice: across (the frame's rows to
// the destination's width), then up (to its height).
//
// Per output pixel: a cubic through the 4 nearest texels of the axis
// (Keys' family: a = -0.5 is Catmull-Rom, which interpolates and keeps an
// edge's slope where a linear ramp halves it; a more negative a is
// sharper), then clamped to the two nearest texels' range, so neither the
// kernel's negative lobes nor the sharpening overshoot what the reduced
// frame saw (no halo, no ringing: the contrast the sharpening may add is
// bounded by the contrast that is there).

uniform sampler2D uSrc;    // read with texelFetch: one texel a tap, no filter
uniform int uAxis;         // 0: along x, 1: along y
uniform float uScale;      // source texels per output pixel, along the axis
uniform vec2 uOrigin;      // the output rectangle's corner, framebuffer pixels
uniform int uLast;         // the last texel the frame holds along the axis
uniform float uA;          // the cubic's a: -0.5 Catmull-Rom, down to -1 sharper

out vec4 fragColor;

// Keys' cubic weights for the texels at -1, 0, 1, 2 from a fraction t.
vec4 cubic(float t) {
    float a = uA, t2 = t * t, t3 = t2 * t, s = 1.0 - t, s2 = s * s, s3 = s2 * s;
    return vec4(a * (t3 - 2.0 * t2 + t),                 // (1 + t): a|x|^3 - 5a x^2 + 8a|x| - 4a
                (a + 2.0) * t3 - (a + 3.0) * t2 + 1.0,   // t
                (a + 2.0) * s3 - (a + 3.0) * s2 + 1.0,   // 1 - t
                a * (s3 - 2.0 * s2 + s));                // 2 - t
}

void main() {
    vec2 p = gl_FragCoord.xy - uOrigin;
    ivec2 at = ivec2(p);                                   // the texel row (or column) across
    float pos = p[uAxis] * uScale - 0.5;                   // texel centres at integers
    float f = floor(pos);
    vec4 w = cubic(pos - f);
    ivec2 step = uAxis == 0 ? ivec2(1, 0) : ivec2(0, 1);
    ivec2 base = uAxis == 0 ? ivec2(int(f), at.y) : ivec2(at.x, int(f));
    int i0 = int(f);
    vec3 c0 = texelFetch(uSrc, base + step * (clamp(i0 - 1, 0, uLast) - i0), 0).rgb;
    vec3 c1 = texelFetch(uSrc, base + step * (clamp(i0, 0, uLast) - i0), 0).rgb;
    vec3 c2 = texelFetch(uSrc, base + step * (clamp(i0 + 1, 0, uLast) - i0), 0).rgb;
    vec3 c3 = texelFetch(uSrc, base + step * (clamp(i0 + 2, 0, uLast) - i0), 0).rgb;
    vec3 c = (w.x * c0 + w.y * c1 + w.z * c2 + w.w * c3) / (w.x + w.y + w.z + w.w);
    fragColor = vec4(clamp(c, min(c1, c2), max(c1, c2)), 1.0);
}
