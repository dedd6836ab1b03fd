#version 330 compatibility
// The world as this camera sees it, drawn once into the refraction targets
// (pack.glib), copied to the screen with its depth: the screen's world and
// the refraction pass are one draw of the world, not two (on llvmpipe a
// world pass costs about a quarter of the frame whatever its size).
uniform sampler2D uWorldColor;
uniform sampler2D uWorldDepth;
out vec4 fragColor;

void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    fragColor = vec4(texelFetch(uWorldColor, ij, 0).rgb, 1.0);
    gl_FragDepth = texelFetch(uWorldDepth, ij, 0).r;
}
