#version 330 compatibility
// Xing's water on a tarn scene (pack.glib). The scene's wave set moves the
// surface; what lies below it comes from the refraction pass (World below,
// seen by this camera: colour on unit 8, depth on unit 9), looked up along
// the refracted ray (two projective steps on the floor's height), and Xing's caustics relight it:
// the world lit it by the sun through flat water (world.glsl), so the sun
// term is multiplied by the caustic factor K, albedo-free, as
//     C' = C (E K + pi A) / (E + pi A)
// with E the flat-water sun irradiance there (worldShadeAt's) and A the
// ambient. Then Beer-Lambert along the view path, Xing's turquoise mix and
// Phong lighting by the sun, the reflection (exact Fresnel: the world above
// from the mirrored pass on units 10 and 11, else the sky) and foam along
// the shore and the crests. With the camera under the water pack.glib
// swaps what the passes hold and fromBelow shows Snell's window and total
// internal reflection.
//   CAUSTIC_FOLLOW     (ours) the caustic tile follows the scene's sun
//                      (read where the refracted sun ray enters) and waves
//                      (scaled by their wavelength, moving with them)
//   XING_FOAM          Xing's foam of circles instead of the noise foam
//   BACKWARD_CAUSTICS  GPU Gems ch. 2 backward caustics instead of the texture
//   UV_FLIP            swap U and V of the second copy of each two-layer lookup
//   SKY_REFLECTION     (ours) the sky's reflection, exact Fresnel
//   BEER_LAMBERT       (ours) attenuation along the refracted path
//   RIPPLE_FILTER      (ours) the ripple map fades where a pixel covers more
//                      than its detail (off: Xing's, point-sampled)
//   SPECULAR_FRESNEL   (ours) the sun's highlight weighted by the Fresnel
//                      reflectance and normalised (off: Xing's Phong lobe)
//   SHOW_IRRADIANCE    (ours) output the sun's irradiance on the floor, E K,
//                      per channel, for measurement against the reference
//   DEBUG_OUTPUT       (ours) 1: the floor point the refracted lookup shows
//                      (world xyz), 2: the point the reflected lookup shows
//                      (its direction where the sky), 3: the Fresnel
//                      reflectance, 4: the path in water to the floor point
//                      (m); raymarch's numbers (one meaning a Define name
//                      across the packs); for the benchmark
#ifndef DEBUG_OUTPUT
#define DEBUG_OUTPUT 0
#endif
#include "contract.glsl"
#include "hash.glsl"
#include "loops.glsl"        // ROLLED(n): loop bounds
#include "waves.glsl"
#include "world.glsl"
#include "terrain.glsl"
#include "xing_look.glsl"
#include "scene_waves.glsl"

uniform sampler2D uRefractColor;   // World below, from this camera
uniform sampler2D uRefractDepth;   // its depth (1: nothing there)
uniform float uWaterRefractMix;    // 0: the floor as refracted, 1: all turquoise
uniform vec3  uColor;              // the water's turquoise
uniform float uKa, uKd, uKs, uShininess;
uniform float uCausticDepth;       // (ours) depth of full caustic contrast
uniform sampler2D uReflectColor;   // World above, mirrored camera (under water: World below)
uniform sampler2D uReflectDepth;   // its depth (1 or the sky: nothing there; cleared when no pass)
// The @caustics tile (viewer/gfx/assets.c): 4 m, traced 2.5 m deep through
// six sines whose curvature-weighted (k^2 A) mean wavelength is this.
#define TEX_CAUSTIC_WAVELENGTH 1.3038
// The mirrored camera of pack.glib's reflection pass widens the field of
// view this much (`Camera mirror 1.3`), so wave-perturbed lookups stay in.
#define REFLECT_FOV_SCALE 1.3
// The ripple map's footprint (tiles a pixel) over which it fades out.
#define RIPPLE_FP_START (1.0 / 128.0)
#define RIPPLE_FP_END (1.0 / 32.0)
// A depth at or beyond this is the sky (drawn at the far plane) or nothing.
#define SKY_DEPTH 0.99999
in vec2 vRest;
in vec3 vWorldPos;
// scene_waves.glsl's figures, the same at every vertex (water.vert): worked
// out per pixel they were two loops over every wave slot, masked
flat in float vWaveAmpSum;
flat in float vCausticWavelength;
flat in vec4 vCausticVel;       // the sines' (xy) and Gerstner waves' (zw)
out vec4 fragColor;

vec2 screenOf(vec3 p) {
    vec4 c = gl_ModelViewProjectionMatrix * vec4(p, 1.0);
    return c.xy / c.w * 0.5 + 0.5;
}

// The world point the refraction pass saw at uv (moved onto the screen's
// edge when it lies outside); false where it saw nothing or the sky (the
// pass draws World all: the screen's world is a copy of it).
bool refractPoint(inout vec2 uv, out vec3 p) {
    ivec2 size = textureSize(uRefractDepth, 0);
    vec2 half_texel = 0.5 / vec2(size);
    uv = clamp(uv, half_texel, 1.0 - half_texel);
    float z = texelFetch(uRefractDepth, ivec2(uv * vec2(size)), 0).r;
    vec4 c = gl_ModelViewProjectionMatrixInverse * vec4(vec3(uv, z) * 2.0 - 1.0, 1.0);
    p = c.xyz / c.w;
    return z < SKY_DEPTH;
}

// The ground along the refracted ray d from P where the refraction pass
// could not show it (the lookup left the screen): the terrain's model
// (terrain.glsl), met by fixed-point steps on its height from the
// level-floor guess s, shaded as tarn's world shades it under the water
// (world.frag), so it joins what the pass saw on the screen without a
// seam. Objects off the screen are not there (nothing saw them). Clamping
// such a lookup to the screen's edge instead repeated the edge's row down
// the frame: vertical streaks (issue #24).
vec3 groundModel(vec3 P, vec3 d, float s, out vec3 hit, out vec3 n) {
    for (int i = 0; i < ROLLED(4); i++) s = max(P.y - terrainHeightMarch((P + s * d).xz), 0.0) / max(-d.y, 1e-4);
    vec3 hg = terrainHeightGrad((P + s * d).xz);
    hit = vec3((P + s * d).x, hg.x, (P + s * d).z);
    n = normalize(vec3(-hg.y, 1.0, -hg.z));
    return worldShadeAt(terrainAlbedo(hit.xz, hg.x, n), n, hit);
}

bool onScreen(vec2 uv) {
    return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
}

// The refracted ray from P (direction d, down) marched over the refraction
// pass's depth: the first sample behind what the pass shows there, by less
// than REFRACT_THICKNESS (more: it went behind a thing, and goes on), then
// bisection between it and the sample before. Returns REFRACT_HIT with the
// uv and the point the pass shows there; REFRACT_MODEL where the ray left
// the screen or went deeper than the terrain goes without meeting
// anything (s: how far it got, the model's first guess); REFRACT_NONE
// never (kept for the caller's reading).
// Issue #24: the two projective steps it replaces took a level floor at
// the depth of the point straight behind P; where that point was a thing
// (the sunken crate, the rock breaking the surface) and the refracted ray
// missed it, the steps stayed on the thing: a dark ghost of the crate's
// side beside it, a pale halo round the rock.
#define REFRACT_NONE  0
#define REFRACT_HIT   1
#define REFRACT_MODEL 2
// 16 steps (24 before, 2026-12-06): the water pass about 20% shorter, the
// animated frame on the lake 1.00-1.26x in three runs (llvmpipe, a noisy
// machine), water RMSE against the reference unchanged to 1e-6, every
// scene and hard case within 0.01 RMSE of 24's (the steps' sub-pixel
// differences along tile lines and caustic sparkles); the crossing's
// thickness allowance grows with a step, so a longer step misses no surface
#define REFRACT_STEPS 16
#define REFRACT_REFINE 8          // halvings closing on a crossing (5 left dashes: the snap below)
#define REFRACT_THICKNESS 0.6      // m on the lake, times uWorldScale
#define REFRACT_SNAP 0.08          // m: a crossing closes to within this
// The ray being marched, P + s d, in clip space as well: clip(P + s d) =
// gClipP + s gClipD, linear in s, so a step applies no matrix; and the
// eye's clip position, for the distance of what the pass shows along a
// step's eye ray. Globals, set by clipRay: a struct passed to
// behindShown at every step cost llvmpipe 15% more than the matrices did.
vec3 gRayP, gRayD;
vec4 gClipP, gClipD, gClipEye;
void clipRay(vec3 P, vec3 d) {
    gRayP = P;
    gRayD = d;
    gClipP = gl_ModelViewProjectionMatrix * vec4(P, 1.0);
    gClipD = gl_ModelViewProjectionMatrix * vec4(d, 0.0);
    gClipEye = gl_ModelViewProjectionMatrix * vec4(uCameraPos, 1.0);
}

// Is the ray's point at s behind what the pass shows at its pixel? uv: the
// pixel; off: it is off the screen; gap: how far behind (m, along the eye
// ray; < 0 in front). The shown point Y lies on the eye ray through X,
// Y = eye + k (X - eye), and its depth z fixes k: clip(Y) = clip(eye) +
// k (clip(X) - clip(eye)) has z / w = 2 z - 1, so the gap is
// |X - eye| (1 - k) without unprojecting the depth.
bool behindShown(float s, out vec2 uv, out bool off, out float gap) {
    vec4 c = gClipP + s * gClipD;
    uv = c.xy / c.w * 0.5 + 0.5;
    off = c.w <= 0.0 || !onScreen(uv);
    gap = 0.0;
    if (off) return false;
    ivec2 size = textureSize(uRefractDepth, 0);
    float z = texelFetch(uRefractDepth, min(ivec2(uv * vec2(size)), size - 1), 0).r;
    if (z >= SKY_DEPTH) return false;           // nothing there: go on
    vec4 e = gClipEye, dc = c - e;
    float zn = 2.0 * z - 1.0;
    float k = (zn * e.w - e.z) / (dc.z - zn * dc.w);
    gap = distance(uCameraPos, gRayP + s * gRayD) * (1.0 - k);
    return gap >= 0.0;
}

// The march's events: where a step stops being a plain step in front of
// what the pass shows.
#define STEP_ON     0   // nothing met: the next step
#define STEP_EDGE   1   // the step left the screen
#define STEP_CROSS  2   // the step went through (or behind) a surface of the pass
#define STEP_MODEL  3   // the step went under the terrain's model

// Close on a crossing between a (in front) and b (behind): a sample counts
// as through the surface when it is behind it by less than the interval.
// A surface the ray goes through closes to a gap of 0 (true: uvF, F, s the
// hit); one it goes behind (a silhouette: a ridge of the floor, the post)
// leaves the gap it jumped by, and the ray goes on (false).
bool closeCrossing(float a, float b, float thick, inout vec2 uvF, inout vec3 F, inout float s) {
    for (int k = 0; k < ROLLED(REFRACT_REFINE); k++) {
        float mid = 0.5 * (a + b);
        vec2 uvm;
        bool offm;
        float gm;
        if (behindShown(mid, uvm, offm, gm) && gm < thick + (b - a)) b = mid; else a = mid;
    }
    vec2 uvh;
    bool off;
    float gh;
    behindShown(b, uvh, off, gh);
    if (gh >= REFRACT_SNAP * uWorldScale + 4.0 * (b - a)) return false;
    s = b;
    uvF = uvh;
    refractPoint(uvF, F);
    return true;
}

// The march runs in rounds: the inner loop takes plain steps (one lookup
// and one height of the model each) until an event, which the round then
// resolves by bisection. Written with the bisections inside the steps'
// loop, a CPU rasteriser (llvmpipe: a block of pixels runs both sides of
// every `if`, masked) paid all three bisections at every step.
int refractMarch(vec3 P, vec3 d, out vec2 uvF, out vec3 F, out float s) {
    // no deeper than the terrain's deepest (its depth, uTerrainShape.x,
    // with a margin for the lake's detail), nor further than 100 m
    float floorY = uWaterLevel - 1.2 * max(uTerrainShape.x, 0.1 * uWorldScale);
    float sMax = min(max(P.y - floorY, 0.0) / -d.y, 100.0 * uWorldScale);
    float thick = REFRACT_THICKNESS * uWorldScale;
    float lo = 0.0;
    float above = 0.0;      // the last sample above the terrain's model
    s = 0.0;
    clipRay(P, d);
    uvF = screenOf(P);
    F = P;
    int i = 1;
    // each round ends on an event at step i and goes on from i + 1: at most
    // one round a step
    for (int round = 0; round <= ROLLED(REFRACT_STEPS); round++) {
        int event = STEP_ON;
        vec2 uv;
        bool off;
        float gap;
        bool behind = false;
        for (; i <= ROLLED(REFRACT_STEPS); i++) {
            float f = float(i) / float(REFRACT_STEPS);
            s = sMax * f * f;                       // finer near P, where things are close
            behind = behindShown(s, uv, off, gap);
            if (off) { event = STEP_EDGE; break; }
            if (behind && gap < thick + (s - lo)) { event = STEP_CROSS; break; }
            if ((P + s * d).y < terrainHeightMarch((P + s * d).xz)) { event = STEP_MODEL; break; }
            above = s;                              // above the model
            lo = s;                                 // in front, or behind a thing (passed it)
        }
        if (event == STEP_ON) return REFRACT_MODEL;
        if (event == STEP_EDGE) {
            // the step left the screen: close on the edge, and take the
            // ray's last sample on the screen (a thing there, the crate
            // by the frame's edge, is still met); else the model
            float hi = s;
            for (int k = 0; k < ROLLED(REFRACT_REFINE); k++) {
                float mid = 0.5 * (lo + hi);
                vec2 uvm;
                float gm;
                behindShown(mid, uvm, off, gm);
                if (off) hi = mid; else lo = mid;
            }
            s = lo;
            behind = behindShown(s, uv, off, gap);
            if (!(behind && gap < thick + (hi - lo))) {
                // a thing at the edge (above the terrain's model there)
                // that the ray's last sample has nearly reached (within
                // REFRACT_THICKNESS in front of it) most likely goes on
                // past the edge, and the ray meets it there: show the
                // edge's point, as the clamped lookup did (the crate at the
                // frame's bottom in look_down); farther in front, the ray
                // goes on to the ground (the terrain model knows no things)
                vec3 S;
                if (refractPoint(uv, S) && S.y > terrainHeightGrad(S.xz).x + 0.05 * uWorldScale && -gap < thick) {
                    uvF = uv;
                    F = S;
                    return REFRACT_HIT;
                }
                return REFRACT_MODEL;
            }
            lo = max(lo - (hi - lo) * 8.0, 0.0);   // an interval in front, to close on below
            event = behind && gap < thick + (s - lo) ? STEP_CROSS : STEP_ON;
        }
        if (event == STEP_CROSS && closeCrossing(lo, s, thick, uvF, F, s)) return REFRACT_HIT;
        if (event != STEP_MODEL && (P + s * d).y >= terrainHeightMarch((P + s * d).xz)) {
            above = s;
            lo = s;
            i++;
            continue;
        }
        // under the terrain's model with no surface of the pass there:
        // the ground is hidden from the camera (behind a ridge of the
        // floor, a thing); the model's own crossing, by bisection from
        // the last sample above the model: lo may be under it already
        // (a crossing of the pass's floor that did not close, taken
        // for a silhouette), and a bisection from there stayed at that
        // sample, deeper than the floor, its longer path in water
        // darker: dark dashes along a contour of the lake's shallow
        // floor, where closed and unclosed crossings alternate
        float a = above, hi = s;
        for (int k = 0; k < ROLLED(REFRACT_REFINE + 2); k++) {
            float mid = 0.5 * (a + hi);
            vec3 X = P + mid * d;
            if (X.y < terrainHeightMarch(X.xz)) hi = mid; else a = mid;
        }
        s = hi;
        return REFRACT_MODEL;
    }
    return REFRACT_MODEL;
}

// A hit the march closed on the ground, moved to where the ray meets the
// terrain's model, when the pass shows that point (the model and the pass
// agree there to a texel): the march reads the pass's depth at the
// nearest texel, and on the shallow floor seen at a slant the texels' steps
// put the closed hit up to a texel's span off along the ray: dark dashes
// along a contour of the lake's floor (issue #24). Things (the crate, the
// post) keep the march's hit.
#define GROUND_SNAP 0.15           // m on the lake, times uWorldScale
void snapToGround(vec3 P, vec3 d, inout vec2 uvF, inout vec3 F) {
    if (abs(F.y - terrainHeightMarch(F.xz)) > GROUND_SNAP * uWorldScale) return;
    float s = distance(P, F);
    for (int i = 0; i < ROLLED(4); i++) s = max(P.y - terrainHeightMarch((P + s * d).xz), 0.0) / max(-d.y, 1e-4);
    vec3 G = P + s * d;
    vec2 uv;
    bool off;
    float gap;
    clipRay(P, d);
    behindShown(s, uv, off, gap);
    if (off || abs(gap) > GROUND_SNAP * uWorldScale) return;
    uvF = uv;
    F = G;
}

// The floor's normal at uv from the depth of two neighbouring texels.
vec3 refractNormal(vec2 uv, vec3 p, vec3 eye) {
    vec2 texel = 1.0 / vec2(textureSize(uRefractDepth, 0));
    vec3 px, pz;
    vec2 uvx = uv + vec2(texel.x, 0.0), uvz = uv + vec2(0.0, texel.y);
    bool okx = refractPoint(uvx, px);
    bool okz = refractPoint(uvz, pz);
    vec3 n = cross(pz - p, px - p);
    float l = length(n);
    if (!okx || !okz || !(l > 1e-12)) return vec3(0.0, 1.0, 0.0);
    n /= l;
    return dot(n, eye - p) < 0.0 ? -n : n;
}

// Each wave kind's displacement along its directions at xz: the sines'
// sum of A sin(th) D, the Gerstner waves' sum of (Q_i A_i cos th + A sin th) D,
// from the waves resolved once on the CPU (waves.glsl's uWave*: k D, omega,
// phase, Q_i A_i D): per pixel, the directions' and wavenumbers' trig was
// most of this.
void waveOffsets(vec2 xz, float t, out vec2 offS, out vec2 offG) {
    offS = vec2(0.0);
    offG = vec2(0.0);
#ifdef WAVES_HAS_SINE
    for (int i = 0; i < ROLLED(WAVES_MAX); i++) {
        if (i >= uWaveSineN) break;
        vec4 w = uWaveSine[i];                  // th = k D.xz + omega t + phase
        float th = dot(w.xy, xz) + w.z * t + w.w;
        offS += uWaveSineAmp[i] * sin(th) * normalize(w.xy);
    }
#endif
#ifdef WAVES_HAS_GERSTNER
    for (int i = 0; i < ROLLED(WAVES_MAX); i++) {
        if (i >= uWaveGerstN) break;
        vec4 w = uWaveGerst[i];
        vec3 a = uWaveGerstAmp[i];              // A, Q_i A_i D
        float th = dot(w.xy, xz) + w.z * t + w.w;
        offG += cos(th) * a.yz + a.x * sin(th) * normalize(w.xy);
    }
#endif
}

// A scroll of 0.25 of the first wave's phase speed, in tiles (foam and
// ripples drift much slower than the crests).
vec2 firstWaveScroll(bool gerstner, float tilesPerUnit, float t) {
    int count = gerstner ? uGerstnerCount : uSineCount;
    if (count < 1) return vec2(0.0);
    float ang = radians(gerstner ? uGerstnerAngle[0] : uSineAngle[0]);
    float L = gerstner ? uGerstnerLength[0] : uSineLength[0];
    float S = L > 0.0 ? wavesPhaseSpeed(gerstner ? uGerstnerSpeed[0] : uSineSpeed[0], L) : 0.0;
    return 0.25 * S * tilesPerUnit * t * vec2(cos(ang), sin(ang));
}

// The caustic factor at floor point p.
vec3 causticFactor(vec3 p, float t) {
    float depth = uWaterLevel - p.y;
    if (depth <= 0.0) return vec3(1.0);
    float fullDepth = uCausticDepth * uWorldScale;
#ifdef BACKWARD_CAUSTICS
    float contrast = uCausticVisible * clamp(depth / max(fullDepth, 1e-9), 0.0, 1.0);
    vec3 n = wavesNormal(wavesRestPoint(p.xz, t), t);
    return xingCausticBackward(n, uSunDir, uIOR, contrast);
#else
    vec2 q = p.xz, offS, offG, scroll = vec2(0.0);
    float scale = uCausticScale * uWorldScale;
#ifdef CAUSTIC_FOLLOW
    // the light reaching p entered the surface where the refracted sun ray
    // through p leaves the mean level: the pattern is the surface's there,
    // so it slides away from the sun with depth. The tile is the texture's
    // waves scaled to the scene's: size and depth of focus grow with the
    // wavelength (a surface scaled by s focuses the same at s times the
    // depth), and it travels with the waves' phase velocity.
    vec3 ts = refract(-uSunDir, vec3(0.0, 1.0, 0.0), 1.0 / uIOR);
    q -= ts.xz * depth / max(-ts.y, 0.05);
    vec2 velS = vCausticVel.xy, velG = vCausticVel.zw;
    float L = vCausticWavelength;
    if (L <= 0.0) return vec3(1.0);            // no waves: no caustics
    float s = L / TEX_CAUSTIC_WAVELENGTH;
    scale = uCausticScale * s;
    fullDepth = uCausticDepth * s;
    waveOffsets(q, t, offS, offG);
    offS -= velS * t;
    offG -= velG * t;
#else
    waveOffsets(q, t, offS, offG);
#endif
    float contrast = uCausticVisible * clamp(depth / max(fullDepth, 1e-9), 0.0, 1.0);
    return xingCausticTexScaled(q, offS, offG, xingChromaDir(uSunDir), contrast, scale);
#endif
}

// Value noise in [0, 1] on the integer lattice (tarnHash), and four
// octaves of it.
float valueNoise(vec2 p) {
    vec2 i = floor(p), f = p - i;
    f = f * f * (3.0 - 2.0 * f);
    uvec2 c = uvec2(ivec2(i));
    float h00 = float(tarnHash(c.x * 73856093u ^ tarnHash(c.y)));
    float h10 = float(tarnHash((c.x + 1u) * 73856093u ^ tarnHash(c.y)));
    float h01 = float(tarnHash(c.x * 73856093u ^ tarnHash(c.y + 1u)));
    float h11 = float(tarnHash((c.x + 1u) * 73856093u ^ tarnHash(c.y + 1u)));
    return mix(mix(h00, h10, f.x), mix(h01, h11, f.x), f.y) / 4294967295.0;
}

float fbm(vec2 p) {
    float s = 0.0, a = 0.5;
    for (int o = 0; o < ROLLED(4); o++) {
        s += a * valueNoise(p);
        p = mat2(1.6, 1.2, -1.2, 1.6) * p + 17.0;
        a *= 0.5;
    }
    return s / 0.9375;
}

// Foam as it forms: along the shore (water shallower than uFoamWidth over
// the terrain's model) and where the waves fold (the Jacobian J of the
// Gerstner/ocean displacement under FOAM_J_START: steep crests about to
// break), broken up by drifting noise into soft streaks and patches; more
// of it the rougher the water (full at a 0.1 amplitude sum). Issue #24:
// it was a hard threshold of the noise (a 0.1 ramp) over every crest in
// the top 35-75 % of the amplitude and wherever the refraction pass showed
// a thing near the surface: hard white blobs round the rock that breaks
// the surface and on gentle crests, white specks along the shoreline,
// where the reference, and the waves, have none.
#define FOAM_J_START 0.5     // J = 1 flat; 0 folds (the surface loops)
#define FOAM_J_FULL 0.1
// abd: the Jacobian entries of the waves' sums but the ocean's (which folds
// under its own foam, OCEAN_FOAM) at the point.
float noiseFoam(vec3 P, vec3 abd, float shallow, float ampSum, float t) {
    if (!uShowFoam || ampSum <= 0.0) return 0.0;
    float shore = 1.0 - smoothstep(0.0, max(uFoamWidth * uWorldScale, 1e-4), shallow);
    float J = (1.0 + abd.x) * (1.0 + abd.z) - abd.y * abd.y;
    float crest = 1.0 - smoothstep(FOAM_J_FULL, FOAM_J_START, J);
    float cover = clamp(max(shore, crest), 0.0, 1.0) * clamp(ampSum / (0.1 * uWorldScale), 0.0, 1.0);
    vec2 drift = vec2(0.11, 0.07) * t;
    float n = fbm((P.xz + drift * uWorldScale) / (0.35 * uWorldScale));
    // soft: the noise (mean 0.5) ramps over 0.3 above a threshold the
    // cover lowers, and the foam is as opaque as the cover
    float threshold = mix(0.75, 0.35, cover);
    return smoothstep(threshold, threshold + 0.3, n) * cover;
}

// Where a perspective target shows world point x: its uv, the point there
// (from the depth target; false where nothing or the sky) and w > 0.
bool targetPoint(mat4 vp, mat4 inv, sampler2D depthTex, vec3 x, out vec2 uv, out vec3 shown) {
    vec4 c = vp * vec4(x, 1.0);
    uv = c.xy / c.w * 0.5 + 0.5;
    shown = x;
    if (c.w <= 0.0 || any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return false;
    float z = texture(depthTex, uv).r;
    vec4 h = inv * vec4(vec3(uv, z) * 2.0 - 1.0, 1.0);
    shown = h.xyz / h.w;
    return z < SKY_DEPTH;
}

// How much of a perturbed lookup into the widened mirror target to keep:
// fades out over the outer half of the band the camera's own view leaves out.
float mirrorKeep(vec2 uv) {
    float band = 0.5 * (1.0 - 1.0 / REFLECT_FOV_SCALE);
    float inside = min(min(uv.x, uv.y), min(1.0 - uv.x, 1.0 - uv.y));
    return clamp(inside / (0.5 * band), 0.0, 1.0);
}

// The mirrored pass along r: where it shows something (uv, the point
// there and its colour). Both sides of the surface read it once (main):
// llvmpipe runs both sides of a per-pixel `if`, masked, so a lookup written
// in each costs every fragment two.
struct Mirror {
    bool hit;
    vec2 uv;
    vec3 shown;
    vec3 color;
};

// The lookup at P + L r with L first 1 m (exact for flat water at any L),
// then twice the distance to the point the target shows there: with waves
// the lookup must be at the reflected thing's own distance, or the pixel
// it reads moves with the normal times the distance's error. From below
// (total internal reflection at grazing angles, where r changes fast) the
// fixed 1 m read the sphere in horizontal strips (issue #24).
#define MIRROR_ITERATIONS 2
Mirror mirrorAlong(vec3 P, vec3 r) {
    Mirror m;
    m.hit = targetPoint(uCamMirrorVP, uCamMirrorInvVP, uReflectDepth, P + uWorldScale * r, m.uv, m.shown);
    for (int i = 0; i < ROLLED(MIRROR_ITERATIONS); i++) {
        if (!m.hit) break;
        vec2 uv;
        vec3 shown;
        float L = max(dot(m.shown - P, r), 0.05 * uWorldScale);
        if (!targetPoint(uCamMirrorVP, uCamMirrorInvVP, uReflectDepth, P + L * r, uv, shown)) break;
        m.uv = uv;
        m.shown = shown;
    }
    m.color = texture(uReflectColor, m.uv).rgb;
    return m;
}

// Above the water: what the surface reflects, the world above from the
// mirrored pass where it shows something, else the sky (along r).
vec3 reflectionAbove(vec3 sky, Mirror m) {
    return m.hit ? mix(sky, m.color, mirrorKeep(m.uv)) : sky;
}

// Under the water (the passes swapped: the refraction target holds the
// world above, the mirror target the world below): Snell's window, the
// world above and the sky (along the refracted ray T) and total internal
// reflection outside it; the eye's own path in water absorbs both. R: the
// Fresnel reflectance from the water.
vec3 fromBelow(vec3 P, vec3 T, vec3 sky, Mirror m, float R) {
    vec3 outside = vec3(0.0);
    vec2 uv;
    vec3 shown;
    if (dot(T, T) > 0.0) {                       // 0 past the critical angle
        outside = sky;
        if (targetPoint(gl_ModelViewProjectionMatrix, gl_ModelViewProjectionMatrixInverse, uRefractDepth,
                        P + uWorldScale * T, uv, shown))
            outside = texture(uRefractColor, uv).rgb;
    }
    vec3 inside = vec3(0.0);                     // nothing seen: all absorbed
    if (m.hit) inside = m.color * exp(-uAbsorption * distance(P, m.shown)) * mirrorKeep(m.uv);
    return mix(outside, inside, R) * exp(-uAbsorption * distance(uCameraPos, P));
}

void main() {
    float t = uTime;
    vec3 P = vWorldPos;
#if defined(WAVES_HAS_OCEAN) && defined(OCEAN_FILTER)
    // the spectrum ocean's cascades finer than the pixel filtered out
    // (waves.glsl: the horizon does not sparkle); what they held widens the
    // sun's highlight (lostVar)
    vec2 footprint = wavesFootprint(vRest);     // derivatives: in uniform control flow
    float lostVar;
    vec3 n = wavesNormalFilteredVar(vRest, t, footprint, lostVar);
#endif
    // the waves' sums at the point but the ocean's, once: the foam's
    // folding takes them, and without an ocean they are the normal's too
    // (two evaluations of every wave, written out, are two on any GPU)
    float sumH;
    vec2 sumDh, sumDisp;
    vec3 sumAbd;
    wavesSumsNoOcean(vRest, t, sumH, sumDh, sumDisp, sumAbd);
#if defined(WAVES_HAS_OCEAN) && !defined(OCEAN_FILTER)
    vec2 footprint = vec2(0.0);
    vec3 n = wavesNormal(vRest, t);
#elif !defined(WAVES_HAS_OCEAN)
    vec2 footprint = vec2(0.0);
    vec3 n = wavesNormalFrom(sumDh, sumAbd, WAVES_USE_APPROX);   // wavesNormal's
#endif
    float tilesPerUnit = uWaterTiling / (2.0 * uTerrainHalfSize);
    vec2 uv = P.xz * tilesPerUnit;
    vec2 sa = firstWaveScroll(false, tilesPerUnit, t), sb = firstWaveScroll(true, tilesPerUnit, t);
    // the ripple map filtered by the pixel's footprint (in tiles; uniform
    // control flow): its slopes average out over a footprint wider than
    // its detail (about 1/32 tile), as a mip chain of the normal map would
    // flatten them. Point-sampled, at a slant or far off, they were
    // compressed into bands: the sphere's reflection from below in strips,
    // the pool's tile lines jagged (issue #24); the reference has no ripples
#ifdef RIPPLE_FILTER
    vec2 rippleFp = max(abs(dFdx(uv)), abs(dFdy(uv)));
    float rippleKeep = 1.0 - smoothstep(RIPPLE_FP_START, RIPPLE_FP_END, max(rippleFp.x, rippleFp.y));
#else
    float rippleKeep = 1.0;     // Xing's: the map point-sampled at every distance
#endif
    n = xingBumpNormal(n, rippleKeep * xingRippleSlope(uv, sa, sb));
    vec3 e = normalize(uCameraPos - P);
    bool underCam = uCameraPos.y < uWaterLevel;  // pack.glib's under_water passes
    bool below = dot(e, n) < 0.0;
    if (below) n = -n;
    bool fromWater = below || underCam;
    float cosI = clamp(dot(e, n), 0.0, 1.0);
    vec3 r = reflect(-e, n);
    vec3 tr = refract(-e, n, fromWater ? uIOR : 1.0 / uIOR);   // 0 past the critical angle
#ifdef SKY_REFLECTION
    Mirror mirror = mirrorAlong(P, r);
#else
    // no reflection (pack.glib skips the mirror passes): nothing mirrored,
    // from below too (outside Snell's window the water shows nothing)
    Mirror mirror = Mirror(false, vec2(0.0), P, vec3(0.0));
#endif
    vec3 sky = worldSkyLook(uSky, underCam && dot(tr, tr) > 0.0 ? tr : r);
    float R = worldFresnel(cosI, fromWater ? uIOR : 1.0, fromWater ? 1.0 : uIOR);
    if (underCam) {
        fragColor = vec4(fromBelow(P, tr, sky, mirror, R), 1.0);
        return;
    }

    // the floor along the refracted ray, marched over the refraction pass's
    // depth (refractMarch); off the screen, the terrain's model. F0, the
    // point straight behind, stays the lookup where no ray goes down.
    vec2 uv0 = screenOf(P), uvF = uv0;
    vec3 F0, F;
    bool hit0 = refractPoint(uv0, F0), hit = hit0, model = false;
    F = F0;
    float sModel = 0.0;
    if (!below && tr.y < -1e-4) {
        int m = refractMarch(P, tr, uvF, F, sModel);
        hit = m != REFRACT_NONE;
        model = m == REFRACT_MODEL;
    }
    vec3 under = vec3(0.0);         // nothing seen: all absorbed
    vec3 E = vec3(0.0), K = vec3(1.0);
    if (hit && !below) {
        vec3 floorColor, floorN;
        if (model) {
            floorColor = groundModel(P, tr, sModel, F, floorN);
        } else {
            snapToGround(P, tr, uvF, F);
            floorColor = texture(uRefractColor, uvF).rgb;
            floorN = refractNormal(uvF, F, uCameraPos);
        }
        E = worldSunBelow(floorN, F);   // world.glsl
        K = causticFactor(F, t);
        vec3 ambient = WORLD_PI * uAmbient;
        under = floorColor * (E * K + ambient) / max(E + ambient, vec3(1e-6));
#ifdef BEER_LAMBERT
        under *= exp(-uAbsorption * distance(P, F));
#endif
    }
#ifdef SHOW_IRRADIANCE
    fragColor = vec4(E * K, 1.0);
    return;
#endif
#if DEBUG_OUTPUT == 1
    fragColor = vec4(hit ? F : vec3(0.0), 1.0);
    return;
#elif DEBUG_OUTPUT == 2
    fragColor = vec4(mirror.hit ? mirror.shown : r, 1.0);
    return;
#elif DEBUG_OUTPUT == 3
    fragColor = vec4(vec3(R), 1.0);
    return;
#elif DEBUG_OUTPUT == 4
    fragColor = vec4(vec3(below ? distance(uCameraPos, P) : hit ? distance(P, F) : 1e4), 1.0);
    return;
#endif
    float diffuse = max(dot(n, uSunDir), 0.0);
    vec3 turquoise = uColor * (uKa + uKd * diffuse);
    vec3 color = mix(under, turquoise, uWaterRefractMix);
#ifdef SKY_REFLECTION
    color = R * reflectionAbove(sky, mirror) + (1.0 - R) * color;
#endif
    // the sun's highlight, Xing's Phong lobe Ks (r.e)^m E_sun. With
    // SPECULAR_FRESNEL (ours) it is weighted by R, the share of the sun the
    // surface reflects, and normalised by (m + 2) / (2 pi) (Phong's energy
    // conserving factor), as packs/natural and raymarch weigh theirs: the
    // unweighted lobe sends back 30-50 times the light a water surface
    // reflects, a white patch that clips (issue #24's look_down). Linear
    // HDR, no clamp: the lobe's peak is ~Ks R (m + 2) / (2 pi) E_sun.
    float shin = max(uShininess, 1.0);
#if defined(WAVES_HAS_OCEAN) && defined(OCEAN_FILTER)
    float energy;
    shin = wavesToksvig(shin, lostVar, energy);
#else
    float energy = 1.0;
#endif
    vec3 spec = uKs * pow(max(dot(reflect(-uSunDir, n), e), 0.0), shin) * uSunIrradiance;
#ifdef SPECULAR_FRESNEL
    spec *= R * (shin + 2.0) / (2.0 * WORLD_PI);   // normalised: its light kept as Toksvig widens it
#else
    spec *= energy;
#endif
    color += spec;

    // foam where the water is shallow (the shore is the lake's border)
    // (over the terrain's model: a thing near the surface is no shore)
    float shallow = max(P.y - terrainHeightGrad(P.xz).x, 0.0);
#ifdef XING_FOAM
    float foam = xingFoam(uv * 4.0, 2.0 * sa, -sb, shallow, vWaveAmpSum);
#else
    float foam = noiseFoam(P, sumAbd, shallow, vWaveAmpSum, t);
#endif
#if defined(WAVES_HAS_OCEAN) && defined(OCEAN_FOAM)
    // the ocean's folding foam (waves_ocean.glsl) joins the pack's own,
    // slightly translucent
    if (uShowFoam) foam = max(foam, 0.85 * wavesFoamFiltered(vRest, max(footprint.x, footprint.y)));
#endif
#ifdef WAVES_HAS_FLOW
    foam = max(foam, flowFoam(vRest));   // the flow's advected streaks (flow.glsl)
#endif
    vec3 white = 0.9 * (uSunIrradiance * diffuse / WORLD_PI + uAmbient);
    color = mix(color, white, foam);
    fragColor = vec4(color, 1.0);
}
