#version 330 compatibility
// The Fresnel table, rendered once (RenderToTextureOnce) into a w x 2
// float target; water.frag reads it with linear filtering when FRESNEL_LUT.
//   row 0, air -> water: texel i holds R at cos = i / (w - 1)
//   row 1, water -> air: texel i holds R at cos = cC + x^2 (1 - cC),
//          x = i / (w - 1), cC the cosine of the critical angle. R has a
//          vertical tangent in cos at cC (R ~ 1 - k sqrt(cos - cC)) and is
//          smooth in x, so the table starts exactly at the critical angle
//          and linear filtering stays accurate beside it.
#include "world.glsl"

uniform float uLutWidth;   // the target's width (pack.glib says both)
out vec4 fragColor;

void main() {
    float x = floor(gl_FragCoord.x) / max(uLutWidth - 1.0, 1.0);
    float r;
    if (gl_FragCoord.y < 1.0) {
        r = worldFresnel(x, 1.0, uIOR);
    } else {
        float cosC = sqrt(max(1.0 - 1.0 / (uIOR * uIOR), 0.0));
        r = worldFresnel(cosC + x * x * (1.0 - cosC), uIOR, 1.0);
    }
    fragColor = vec4(r, r, r, 1.0);
}
