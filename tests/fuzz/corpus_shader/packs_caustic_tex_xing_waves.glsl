// xing_waves.glsl: Xing's two vertex waves (one sine, one Gerstner), with
// the uniform names of his glman shader. The C twin is in
// tests/test_pack_caustic_tex.c (xing_eval): change one, change the other.
//
// For a rest point p0 = (x0, z0) of the quad and time t (seconds):
//   D = (Dx, Dz) / |(Dx, Dz)|  (0 when the direction is 0: the wave then
//       bobs in place, no NaN), k = uSinFreq / uGerstFreq (radians per unit),
//   theta = k D.p0 - omega t, omega = k * speed rounded to whole cycles per
//       Timer period (the wave loops with glman's Timer, no jump)
//   sine:      y += A sin(theta)
//   Gerstner:  y += A sin(theta),  (x, z) += Q/k cos(theta) D
//       (GPU Gems 1 ch. 1 eq. 9 for one wave: Q_i A_i = Q / (w_i N), N = 1;
//       uGerstSteep = Q in 0..1, loop-free up to 1; 0 gives the sine)
// The normal is exact for the sum: B = dP/dx0 and T = dP/dz0 add the
// derivatives of both waves, N = normalize(T x B) (docs/reference.md).
// Where T x B vanishes (Q = 1 at a crest of a wave with no height slope)
// the normal is straight up rather than NaN.
#ifndef XING_WAVES_GLSL
#define XING_WAVES_GLSL

#ifndef TIMER_SECONDS
#define TIMER_SECONDS 20        // keep equal to the glib's `Timer` period
#endif
#define XING_TWO_PI 6.28318530717958647692

uniform bool  uSineWave;        // the sine wave on/off
uniform float uSinDx, uSinDz;   // its direction of travel (normalised here)
uniform float uSinAmp;          // amplitude
uniform float uSinFreq;         // wavenumber k, radians per unit
uniform float uSinSpeed;        // phase speed, units per second
uniform bool  uGerstnerWave;    // the Gerstner wave on/off
uniform float uGerstSteep;      // Q: 0 a sine, 1 the sharpest loop-free crest
uniform float uGerstDx, uGerstDz;
uniform float uGerstAmp;
uniform float uGerstFreq;
uniform float uGerstSpeed;

vec2 xingDir(float dx, float dz) {
    vec2 d = vec2(dx, dz);
    float l = length(d);
    return l > 1e-6 ? d / l : vec2(0.0);
}

// omega = k * speed, rounded to whole cycles per Timer period.
float xingOmega(float k, float speed) {
    float T = float(TIMER_SECONDS);
    return XING_TWO_PI * floor(k * speed * T / XING_TWO_PI + 0.5) / T;
}

// Everything the shaders need from the waves at a rest point p0:
//   pos     displaced point relative to the rest point's plane (x, h, z)
//   normal  the exact unit normal
//   offSine, offGerst  each wave's displacement along its direction
//           (A sin th D for the sine, (Q/k cos th + A sin th) D for
//           Gerstner): what moves the two caustic layers
//   ampSum  the amplitudes of the waves that are on (foam strength)
struct XingWave {
    vec3 pos;
    vec3 normal;
    vec2 offSine;
    vec2 offGerst;
    float ampSum;
};

XingWave xingEval(vec2 p0, float t) {
    float h = 0.0;
    vec2 dh = vec2(0.0), disp = vec2(0.0);
    vec3 abd = vec3(0.0);       // dDx/dx0, dDx/dz0 = dDz/dx0, dDz/dz0
    XingWave w;
    w.offSine = vec2(0.0);
    w.offGerst = vec2(0.0);
    w.ampSum = 0.0;
    if (uSineWave && uSinAmp != 0.0) {
        vec2 D = xingDir(uSinDx, uSinDz);
        float k = uSinFreq, A = uSinAmp;
        float th = k * dot(D, p0) - xingOmega(k, uSinSpeed) * t;
        float s = sin(th);
        h += A * s;
        dh += k * A * cos(th) * D;
        w.offSine = A * s * D;
        w.ampSum += abs(A);
    }
    if (uGerstnerWave && uGerstAmp != 0.0) {
        vec2 D = xingDir(uGerstDx, uGerstDz);
        float k = uGerstFreq, A = uGerstAmp;
        float qa = k > 0.0 ? uGerstSteep / k : 0.0;     // Q_i A_i = Q / k
        float th = k * dot(D, p0) - xingOmega(k, uGerstSpeed) * t;
        float s = sin(th), c = cos(th);
        h += A * s;
        dh += k * A * c * D;
        disp += qa * c * D;
        abd -= qa * k * s * vec3(D.x * D.x, D.x * D.y, D.y * D.y);
        w.offGerst = (qa * c + A * s) * D;
        w.ampSum += abs(A);
    }
    w.pos = vec3(p0.x + disp.x, h, p0.y + disp.y);
    vec3 B = vec3(1.0 + abd.x, dh.x, abd.y);     // dP/dx0
    vec3 T = vec3(abd.y, dh.y, 1.0 + abd.z);     // dP/dz0
    vec3 n = cross(T, B);
    float l = length(n);
    w.normal = l > 1e-12 ? n / l : vec3(0.0, 1.0, 0.0);
    return w;
}

// The rest point whose displaced (x, z) is xz: fixed-point iterations
// p0 = xz - D(p0), a contraction with constant Q while Q < 1.
vec2 xingRestPoint(vec2 xz, float t) {
    vec2 p0 = xz;
    for (int i = 0; i < 4; i++) {
        XingWave w = xingEval(p0, t);
        p0 = xz - (w.pos.xz - p0);
    }
    return p0;
}

#endif
