#version 330 compatibility
// Two crossing sine waves displace the surface; the normal is the exact
// one of that height field: normalize(-dh/dx, 1, -dh/dz).
uniform float Timer;       // 0..1 over the glib's Timer period
uniform float uAmp, uFreq, uSpeed;
uniform bool uShowWaves;
out vec3 vNormalEye;
out vec3 vPosEye;

const float PERIOD = 20.0;   // matches `Timer 20` in pond.glib

void main() {
    float t = Timer * PERIOD * uSpeed;
    vec4 p = gl_Vertex;
    float a = uShowWaves ? uAmp : 0.0;
    float k1 = uFreq, k2 = 1.7 * uFreq;
    float ph1 = k1 * (p.x + 0.3 * p.z) - 2.0 * t;
    float ph2 = k2 * (0.6 * p.x - p.z) - 2.7 * t;
    p.y += a * sin(ph1) + 0.5 * a * sin(ph2);
    float dhdx = a * k1 * cos(ph1) + 0.5 * a * k2 * 0.6 * cos(ph2);
    float dhdz = a * k1 * 0.3 * cos(ph1) - 0.5 * a * k2 * cos(ph2);
    vNormalEye = normalize(gl_NormalMatrix * vec3(-dhdx, 1.0, -dhdz));
    vPosEye = (gl_ModelViewMatrix * p).xyz;
    gl_Position = gl_ModelViewProjectionMatrix * p;
}
