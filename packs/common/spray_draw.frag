#version 330 compatibility
// spray_draw.frag: a droplet as a soft disc, lit by the sun and the sky:
// a small water drop scatters the sun forwards and back (a broad lobe
// here, its albedo 0.8) and shows the sky around it; its cover falls off
// towards the rim and fades in its last 0.3 s. Premultiplied alpha.
#include "contract.glsl"
in float vLife;
out vec4 fragColor;

void main() {
    vec2 q = gl_PointCoord * 2.0 - 1.0;
    float r2 = dot(q, q);
    if (r2 > 1.0) discard;
    float cover = (1.0 - r2) * (1.0 - r2) * 0.85 * clamp(vLife / 0.3, 0.0, 1.0);
    vec3 light = 0.8 * (uSunIrradiance * (0.25 + 0.75 * max(uSunDir.y, 0.0)) / 3.14159265 + 2.0 * uAmbient);
    fragColor = vec4(light * cover, cover);
}
