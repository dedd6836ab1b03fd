#version 330 compatibility
uniform vec3 uRockColor;
uniform vec3 uLight;   // eye-space direction to the light
in vec3 vNormal;
out vec4 fragColor;

void main() {
    float diffuse = max(dot(normalize(vNormal), normalize(uLight)), 0.0);
    fragColor = vec4(uRockColor * (0.35 + 0.65 * diffuse), 1.0);
}
