#version 330 compatibility
uniform vec3 uSandColor;
uniform float uRipple;
uniform sampler2D Noise2;
in vec2 vST;
in vec3 vPos;
out vec4 fragColor;

void main() {
    vec4 n = texture(Noise2, vST * 3.0);
    float ripple = sin(vPos.x * 9.0 + 6.0 * (n.r + n.g - 1.0));
    float shade = 1.0 + uRipple * 0.25 * ripple + 0.2 * (n.b - 0.5);
    fragColor = vec4(uSandColor * shade, 1.0);
}
