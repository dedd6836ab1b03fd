#version 330 compatibility
// Xing's vertex shader: one program draws both quads of water.glib. The
// floor is the quad at y = uFloorY and stays put; every other vertex is the
// water surface, displaced by the sine and the Gerstner wave.
#include "xing_waves.glsl"

uniform float Timer;            // glman's 0..1 sawtooth, period TIMER_SECONDS
uniform float uFloorY;          // the floor quad's height
out vec3 vPos;                  // the displaced position (model space)
out vec2 vRest;                 // the rest point (x0, z0)
out vec2 vST;                   // the quad's texture coordinates
flat out int vIsFloor;

void main() {
    vST = gl_MultiTexCoord0.st;
    vRest = gl_Vertex.xz;
    vIsFloor = abs(gl_Vertex.y - uFloorY) < 1e-3 ? 1 : 0;
    vec3 p = gl_Vertex.xyz;
    if (vIsFloor == 0) {
        XingWave w = xingEval(gl_Vertex.xz, Timer * float(TIMER_SECONDS));
        p = vec3(w.pos.x, gl_Vertex.y + w.pos.y, w.pos.z);
    }
    vPos = p;
    gl_Position = gl_ModelViewProjectionMatrix * vec4(p, 1.0);
}
