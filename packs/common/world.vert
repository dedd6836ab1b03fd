#version 330 compatibility
// The world (terrain and objects) in world space: tarn bakes the meshes in
// world coordinates, so gl_Vertex is the world position.
#include "contract.glsl"
#include "waves.glsl"
#include "world_wet.glsl"
uniform vec4 uWorldClip;       // plane (n, d): keep dot(n, p) + d >= 0
// 0 terrain, 1 object, 2 sky (a unit box around the eye): compiled in
// (WORLD_MODE, one program per mode), or else a uniform
#ifdef WORLD_MODE
const int uWorldMode = WORLD_MODE;
#else
uniform int uWorldMode;
#endif
out vec3 vWorldPos;
out vec3 vWorldNormal;
out vec2 vST;
// the waves' height bound (world_wet.glsl), the same for every pixel:
// taken once a vertex, world.frag's pixels skip its loops
flat out float vWavesBound;

void main() {
    vST = gl_MultiTexCoord0.st;
    vWavesBound = worldWavesBound();
    if (uWorldMode == 2) {
        // the sky: directions from the eye, drawn at the far plane
        vWorldNormal = gl_Vertex.xyz;
        vWorldPos = uCameraPos + gl_Vertex.xyz;
        gl_ClipDistance[0] = 1.0;
        vec4 p = gl_ModelViewProjectionMatrix * vec4(vWorldPos, 1.0);
        gl_Position = vec4(p.xy, p.w * 0.999999, p.w);
        return;
    }
    vWorldPos = gl_Vertex.xyz;
    vWorldNormal = gl_Normal;
    gl_ClipDistance[0] = dot(uWorldClip, vec4(gl_Vertex.xyz, 1.0));
    gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;
}
