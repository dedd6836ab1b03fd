#version 330 compatibility
#include "world.glsl"

uniform sampler2D uTerrainAlbedo;
uniform samplerCube uSky;
uniform int uWorldMode;         // 0 terrain (albedo from the baked texture), 1 object, 2 sky
uniform vec3 uWorldAlbedo;      // objects: one albedo each
uniform vec3 uCameraPos;        // the eye of the current camera
uniform bool uWorldEyePath;     // drawn to the screen: attenuate along the eye's path in water
in vec3 vWorldPos;
in vec3 vWorldNormal;
in vec2 vST;
out vec4 fragColor;

// The length of the segment eye -> p that lies under the mean water level
// (the reference's eye path in water: it fades what an eye under the water
// sees by exp(-sigma s), with no in-scattering).
float eyePathInWater(vec3 eye, vec3 p) {
    float d = distance(eye, p);
    if (eye.y >= uWaterLevel) return 0.0;   // from above, the water surface is drawn over it
    if (p.y <= uWaterLevel) return d;
    return d * (uWaterLevel - eye.y) / max(p.y - eye.y, 1e-6);
}

void main() {
    vec3 c;
    if (uWorldMode == 2) {
        c = texture(uSky, normalize(vWorldNormal)).rgb;
    } else {
        vec3 albedo = uWorldMode == 0 ? texture(uTerrainAlbedo, vST).rgb : uWorldAlbedo;
        c = worldShadeAt(albedo, normalize(vWorldNormal), vWorldPos);
    }
    if (uWorldEyePath) c *= exp(-uAbsorption * eyePathInWater(uCameraPos, vWorldPos));
    fragColor = vec4(c, 1.0);
}
