#version 330 compatibility
#include "../../../packs/caustic_tex/xing_waves.glsl"
uniform float Timer;
uniform int uTwinMode;      // 0: (normal, height), 1: (dx, dz, 0, 0)
in vec2 vST;
out vec4 fragColor;
void main() {
    vec2 p0 = -2.0 + 4.0 * vST;
    XingWave w = xingEval(p0, Timer * float(TIMER_SECONDS));
    fragColor = uTwinMode == 0 ? vec4(w.normal, w.pos.y) : vec4(w.pos.xz - p0, 0.0, 0.0);
}
