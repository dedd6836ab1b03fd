#version 330 compatibility
#include "world.glsl"

uniform sampler2D uTerrainAlbedo;
uniform samplerCube uSky;
uniform int uWorldMode;         // 0 terrain (albedo from the baked texture), 1 object, 2 sky
uniform vec3 uWorldAlbedo;      // objects: one albedo each
in vec3 vWorldPos;
in vec3 vWorldNormal;
in vec2 vST;
out vec4 fragColor;

void main() {
    if (uWorldMode == 2) {
        fragColor = vec4(texture(uSky, normalize(vWorldNormal)).rgb, 1.0);
        return;
    }
    vec3 albedo = uWorldMode == 0 ? texture(uTerrainAlbedo, vST).rgb : uWorldAlbedo;
    fragColor = vec4(worldShadeAt(albedo, normalize(vWorldNormal), vWorldPos), 1.0);
}
