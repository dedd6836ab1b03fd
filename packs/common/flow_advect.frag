#version 330 compatibility
// flow_advect.frag: one step of the flow map's backward advection
// (flow.glsl tells the method; tarn's render_flow.c runs it a frame):
// each texel finds where its content was dt ago and reads the previous
// map there, bilinearly; a layer being restarted starts from d = 0.
#define FLOW_ADVECT_PASS
#include "flow.glsl"

uniform sampler2D uFlowPrev;   // the map before the step
uniform vec2 uFlowStepDt;      // seconds this step moves layer A, layer B
uniform vec2 uFlowStepReset;   // 1: the layer restarts (its d before is 0)
uniform float uFlowPassRes;    // the map's texels a side
out vec4 oFlow;

vec2 flowStep(vec2 x, float dt) {
    vec2 mid = x - 0.5 * dt * flowVelocity(x);
    return x - dt * flowVelocity(mid);       // the back-traced source point
}

void main() {
    vec2 uv = gl_FragCoord.xy / uFlowPassRes;
    vec2 x = uv / uFlowRect.y - uFlowRect.x;   // the texel's centre in the world
    vec2 backA = flowStep(x, uFlowStepDt.x), backB = flowStep(x, uFlowStepDt.y);
    vec2 dA = uFlowStepReset.x > 0.5 ? vec2(0.0) : texture(uFlowPrev, flowMapUv(backA)).xy;
    vec2 dB = uFlowStepReset.y > 0.5 ? vec2(0.0) : texture(uFlowPrev, flowMapUv(backB)).zw;
    oFlow = vec4(x - backA + dA, x - backB + dB);
}
