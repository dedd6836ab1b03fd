#version 330 compatibility
// Xing's fragment shader for water.glib: the rock floor lit through
// caustics, and the water over it: the floor seen through the refracted
// ray (exact refraction to the floor plane), mixed with turquoise,
// per-fragment Phong lighting and foam at the border.
#include "xing_waves.glsl"
#include "xing_look.glsl"
#include "rock.glsl"

#define XING_IOR 1.333

uniform float Timer;
uniform float uFloorY;
uniform float uWaterRefractMix; // 0: the floor as refracted, 1: all turquoise
uniform vec4  uColor;           // the water's turquoise
uniform float uKa, uKd, uKs, uShininess;
uniform float uLightX, uLightY, uLightZ;   // the light's position (model space)
in vec3 vPos;
in vec2 vRest;
in vec2 vST;
flat in int vIsFloor;
out vec4 fragColor;

// Scrolled layers loop with the Timer: whole tiles per period, per axis.
vec2 xingScroll(float dx, float dz, float speed, float t) {
    float T = float(TIMER_SECONDS);
    return floor(0.25 * speed * xingDir(dx, dz) * T + 0.5) / T * t;
}

// The rock at floor point F lit by the light at lp through the caustics
// of the waves above it.
vec3 floorColor(vec3 F, vec3 lp, float t) {
    vec3 albedo, nr;
    rockFloor(F.xz, albedo, nr);
    vec3 l = normalize(lp - F);
#ifdef BACKWARD_CAUSTICS
    XingWave w = xingEval(xingRestPoint(F.xz, t), t);
    vec3 k = xingCausticBackward(w.normal, l, XING_IOR, uCausticVisible);
#else
    XingWave w = xingEval(F.xz, t);     // the waves over the point (rest ~ F)
    vec3 k = xingCausticTex(F.xz, w.offSine, w.offGerst, xingChromaDir(l), uCausticVisible);
#endif
    return albedo * (uKa + uKd * max(dot(nr, l), 0.0) * k);
}

void main() {
    float t = Timer * float(TIMER_SECONDS);
    vec3 lp = vec3(uLightX, uLightY, uLightZ);
    if (vIsFloor == 1) {
        fragColor = vec4(floorColor(vPos, lp, t), 1.0);
        return;
    }
    XingWave w = xingEval(vRest, t);
    vec2 uv = vST * uWaterTiling;
    vec2 sa = xingScroll(uSinDx, uSinDz, uSineWave ? uSinSpeed : 0.0, t);
    vec2 sb = xingScroll(uGerstDx, uGerstDz, uGerstnerWave ? uGerstSpeed : 0.0, t);
    vec3 n = xingBumpNormal(w.normal, xingRippleSlope(uv, sa, sb));
    vec3 eye = (gl_ModelViewMatrixInverse * vec4(0.0, 0.0, 0.0, 1.0)).xyz;
    vec3 e = normalize(eye - vPos);
    bool below = dot(e, n) < 0.0;
    if (below) n = -n;
    vec3 l = normalize(lp - vPos);
    float diffuse = max(dot(n, l), 0.0);

    // what lies under the water: the floor plane along the refracted ray
    vec3 under = uColor.rgb;
    vec3 tr = refract(-e, n, below ? XING_IOR : 1.0 / XING_IOR);
    if (!below && tr.y < -1e-4) {
        float s = (uFloorY - vPos.y) / tr.y;
        if (s > 0.0) under = floorColor(vPos + s * tr, lp, t);
    }
    vec3 turquoise = uColor.rgb * (uKa + uKd * diffuse);
    vec3 color = mix(under, turquoise, uWaterRefractMix);
    color += uKs * pow(max(dot(reflect(-l, n), e), 0.0), max(uShininess, 1.0)) * vec3(1.0);

    // foam: from the quad's border towards its centre
    float edge = min(min(vST.x, 1.0 - vST.x), min(vST.y, 1.0 - vST.y));
    float foam = xingFoam(uv, 2.0 * sa, -sb, edge, w.ampSum);
    color = mix(color, vec3(uKa + uKd * diffuse), foam);
    fragColor = vec4(color, 1.0);
}
