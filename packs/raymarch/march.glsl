// march.glsl: the steep-parallax ray march of packs/raymarch through a
// top-down world-Y texture (Lipp, after McGuire's steep parallax mapping
// and Sousa, GPU Gems 2 ch. 19). No #version.
//
// The heightfield is rendered once with `Camera top` (orthographic,
// straight down): for a world point p, clip = uCamTopVP * p, the texture
// coordinates are uv = clip.xy / 2 + 1/2 and the depth is d = clip.z / 2 +
// 1/2 with clip.z = M[1][2] y + M[3][2] (the camera looks straight down:
// M[0][2] = M[2][2] = 0), so world Y is affine in the depth
// (marchDepthToY). pack_y.frag turns three depth targets into one RGBA32F
// texel of world Y, read here with texelFetch (nearest, as the source):
//   x  top:    the highest surface, seen from above (World all)
//   y  bottom: the highest face turned away from the camera (World all
//              with the undersides only): the bottom of a floating thing
//   z  floor:  the highest surface below the water (World below): what
//              lies under an overhang
// (-1e30 where nothing was drawn). A texel is solid where y <= floor, or
// bottom <= y <= top (for bottom < top; else y <= top): f(y) below is
// positive outside, <= 0 inside.
//
// The C twin of every function here is in tests/test_pack_raymarch.c
// (same float arithmetic, same order); change one, change the other.
//
// A march steps along o + t dir by a fixed length from t = 0 until f <= 0
// (the first sample at or inside the solid), at most `maxIter` steps, then
// refines the bracket [ta, tb] (f(ta) > 0 >= f(tb)) by `refine` regula
// falsi (REFINE_SECANT) or bisection (REFINE_BINARY) steps, and ends with
// the linear interpolation between the bracket's ends (the source's step).
//
// Hazards, each a status rather than a NaN:
//   MARCH_INSIDE  f(0) <= 0 (or NaN): the start is already inside (shore,
//                 ground above the water, depth zero): t = 0.
//   MARCH_CAP     no sample inside within maxIter steps: t is the last
//                 sample, f its distance above the ground there.
//   MARCH_LEFT    the ray left the texture's square, the drawn world (a
//                 texel with no top: the border around the world square)
//                 or [yMin, yMax] (or its start is outside): t, f of the
//                 last sample inside.
//   The interpolation's denominator f(ta) - f(tb) is > 0 for a bracket; if
//   it is not (a NaN, equal or same-signed values) tb is returned.
//
// Skipping empty space (the march up only, MARCH_SKIP): a coarse map of
// MARCH_SKIP_CELLS² cells over the same square (skip_blocked.frag,
// skip_dist.frag) holds, per cell and per height threshold L_k
// (marchSkipLevels), the L-infinity distance in cells to the nearest cell
// with a texel whose top or floor reaches L_k (or off the drawn world, or
// beyond the square). A sample at height y >= L_k whose cell is r cells from
// such a cell knows that every point less than r - 1 cells away (L-infinity,
// in uv) lies over texels that are empty at every height from L_k up, so
// a ray going up meets nothing there. The march then jumps over those of
// its samples, to the last one known outside: the samples it reads are
// a subset of the plain march's, on the same lattice t = step (i + 1),
// and every sample the plain march stops on, with the one before it, is
// read, so t, f, ta, tb and the status are bit for bit the plain march's.
// On llvmpipe a block of pixels runs the loop as long as its slowest ray:
// the grazing rays over open water, which took all uMaxIter steps, now
// leave it in a few.
#ifndef RAYMARCH_MARCH_GLSL
#define RAYMARCH_MARCH_GLSL
#include "contract.glsl"
#include "loops.glsl"        // ROLLED(n): loop bounds

#define MARCH_MAX_ITER 64       // compile-time bound of the uMaxIter slider
#define MARCH_REFINE_MAX 8      // compile-time bound of the uRefineSteps slider
#define MARCH_MIN_DIR_Y 0.02    // |dir.y| is clamped to this (grazing rays)

#define MARCH_EMPTY_Y -1e29     // pack_y.frag writes -1e30 where nothing was drawn
#define MARCH_GROUND_MODEL 1e30 // w: the floor (z) is the terrain's model, not seen (pack_y.frag)

#define MARCH_SKIP_CELLS 128    // the skip map's cells a side (pack.glib's targets 17-19)
#define MARCH_SKIP_FAR 65.0     // its distances are capped here (skip_dist.frag's reach + 1)

#define MARCH_HIT 0
#define MARCH_INSIDE 1
#define MARCH_CAP 2
#define MARCH_LEFT 3


struct March {
    float t;        // ray parameter of the hit (or of the last sample, see above)
    float f;        // f at t for MARCH_CAP / MARCH_LEFT (0 otherwise)
    float ta;       // the last sample above the ground (the bracket's start)
    float tb;       // the first sample inside (the bracket's end; t for MARCH_INSIDE)
    int status;
    int fetches;    // texels read (the cost; DEBUG_OUTPUT 5)
};

// World Y of a depth value of a `Camera top` depth texture.
float marchDepthToY(float d) {
    return (2.0 * d - 1.0 - uCamTopVP[3][2]) / uCamTopVP[1][2];
}

// Texture coordinates of a world point, and their derivative along a direction.
vec2 marchUV(vec3 p) { return (uCamTopVP * vec4(p, 1.0)).xy * 0.5 + 0.5; }
// the world (x, z) under texture coordinate uv: marchUV inverted (the
// camera looks straight down, so y does not move uv)
vec2 marchWorldXZ(vec2 uv) {
    mat2 m = mat2(uCamTopVP[0].xy, uCamTopVP[2].xy);
    return inverse(m) * (uv * 2.0 - 1.0 - uCamTopVP[3].xy);
}
vec2 marchUVDir(vec3 d) { return (uCamTopVP * vec4(d, 0.0)).xy * 0.5; }

bool marchInFootprint(vec2 uv) {   // false for NaN too
    return uv.x >= 0.0 && uv.x < 1.0 && uv.y >= 0.0 && uv.y < 1.0;
}

// (top, bottom, floor) of the texel under uv (nearest); uv in the footprint.
vec3 marchFetch(sampler2D hf, ivec2 size, vec2 uv) {
    ivec2 ij = min(ivec2(uv * vec2(size)), size - 1);
    return texelFetch(hf, ij, 0).xyz;
}

// f of height y in a texel: > 0 outside the solid, <= 0 inside. A texel
// with a bottom whose floor is at or above that bottom is one where the
// floor pass saw the thing itself (an object under the water: its top is
// below the floor pass's clip), not ground under an overhang: its solid is
// the slab [bottom, top] alone. With the floor, a boulder would be a
// column from its top down through the ground (issue #16's striated
// columns); without it, a ray passes under the slab to the ground beside.
float marchSolid(vec3 t, float y) {
    float f = y - t.x;
    if (t.y < t.x) {
        f = max(f, t.y - y);
        if (t.z >= t.y) return f;
    }
    return min(f, y - t.z);
}

// The paper's reflection solid (PAPER_REFLECTION, level > MARCH_EMPTY_Y):
// Lipp marches reflected rays through textures of the world over the water
// rendered from below, a heightfield of its lowest surface: everything above
// it is solid. Without a camera from below it is the bottom where there is
// one, else the top, and the water level for a thing that crosses the
// water; a texel whose top is under the water has nothing over it.
float marchSolidAs(vec3 t, float y, float level) {
    if (level <= MARCH_EMPTY_Y) return marchSolid(t, y);
    if (t.x < level) return 1e30;
    return max(t.y > MARCH_EMPTY_Y && t.y < t.x ? t.y : t.x, level) - y;
}

float marchF(sampler2D hf, ivec2 size, vec2 uv, float y, float level) {
    return marchSolidAs(marchFetch(hf, size, uv), y, level);
}

// The skip map's height thresholds L_0..L_3 (its channels): a little
// below the water (a ray starts on the waves: from a trough deeper than
// this it does not skip), then above it. Lake metres times uWorldScale.
vec4 marchSkipLevels() {
    return uWaterLevel + vec4(-0.3, 0.05, 0.2, 0.8) * uWorldScale;
}

// How many samples after the one at (uv, y) a ray going up can jump over
// (all outside, see above); adv: the L-infinity uv length of one step;
// levels: marchSkipLevels(), taken once a march.
int marchSkipCount(sampler2D skip, vec2 uv, float y, float adv, vec4 levels) {
    ivec2 c = clamp(ivec2(uv * float(MARCH_SKIP_CELLS)), ivec2(0), ivec2(MARCH_SKIP_CELLS - 1));
    vec4 r = texelFetch(skip, c, 0);
    float cells = y >= levels.w ? r.w : y >= levels.z ? r.z : y >= levels.y ? r.y : y >= levels.x ? r.x : 0.0;
    // strictly less than (cells - 1) cells: 0.999 keeps uv's rounding inside
    float n = floor(0.999 * (cells - 1.0) / (float(MARCH_SKIP_CELLS) * adv));
    return int(clamp(n, 0.0, float(MARCH_MAX_ITER)));
}

// The next sample to read after sample `cur` (-1: the start) when the k
// after it are known outside: the last of them, but none past `last`
// (the last sample the plain march could read without stopping).
int marchSkipNext(int cur, int k, int last) {
    return k > 0 ? max(min(cur + k, last), cur + 1) : cur + 1;
}

// The source's linear interpolation between the last two samples, guarded.
float marchInterp(float ta, float fa, float tb, float fb) {
    float den = fa - fb;
    return den > 0.0 ? ta + (tb - ta) * clamp(fa / den, 0.0, 1.0) : tb;
}

// Step length: the ray crosses `range` metres of height in n = mix(nGrazing,
// nSteep, |dir.y|) steps (the source's mix(10, 3, -R.y)), at most maxStep.
float marchStep(float range, float dirY, float nGrazing, float nSteep, float maxStep) {
    float cy = max(abs(dirY), MARCH_MIN_DIR_Y);
    float n = max(mix(nGrazing, nSteep, cy), 1.0);
    return min(range / (n * cy), maxStep);
}

// dir with |dir.y| >= MARCH_MIN_DIR_Y and the sign `down` asks for, unit.
vec3 marchClampDir(vec3 dir, bool down) {
    float y = down ? min(dir.y, -MARCH_MIN_DIR_Y) : max(dir.y, MARCH_MIN_DIR_Y);
    return normalize(vec3(dir.x, y, dir.z));
}

// The march. step <= 0: the step comes from the depth under the start,
// marchStep(max(f(0), minRange), ...) (the refraction march). fromBelow:
// the water level for the paper's reflection solid, else -1e30. skip (a
// ray going up, the plain solid, fromBelow -1e30): jump over samples the
// skip map knows are outside (see above).
March marchHeightfield(sampler2D hf, vec3 o, vec3 dir,
                       float step, float minRange, float nGrazing, float nSteep, float maxStep,
                       float yMin, float yMax, int maxIter, int refine, float fromBelow,
                       sampler2D skipMap, bool skip) {
    March m;
    m.t = 0.0;
    m.f = 0.0;
    m.ta = 0.0;
    m.tb = 0.0;
    m.status = MARCH_LEFT;
    m.fetches = 0;
    ivec2 size = textureSize(hf, 0);
    vec2 uv0 = marchUV(o), duv = marchUVDir(dir);
    if (!marchInFootprint(uv0)) return m;
    vec3 t0 = marchFetch(hf, size, uv0);
    m.fetches++;
    if (t0.x <= MARCH_EMPTY_Y) return m;
    float fa = marchSolidAs(t0, o.y, fromBelow);
    if (!(fa > 0.0)) { m.status = MARCH_INSIDE; return m; }
    if (step <= 0.0) step = marchStep(max(fa, minRange), dir.y, nGrazing, nSteep, maxStep);
    float ta = 0.0, tb = 0.0, fb = fa;
    m.status = MARCH_CAP;
    // skipping: a step's L-infinity length in uv, and the last sample the
    // plain march reads before the ray passes yMax (two short: rounding)
    float adv = step * max(abs(duv.x), abs(duv.y));
    int last = maxIter - 1;
    if (skip) last = min(last, int(min(floor((yMax - o.y) / (step * dir.y)), 1e4)) - 2);
    vec4 levels = marchSkipLevels();
    int s = skip ? marchSkipNext(-1, marchSkipCount(skipMap, uv0, o.y, adv, levels), last) : 0;
    for (int i = 0; i < ROLLED(MARCH_MAX_ITER); i++) {
        if (s >= maxIter) break;
        float t = step * float(s + 1);
        float y = o.y + t * dir.y;
        vec2 uv = uv0 + t * duv;
        if (!marchInFootprint(uv) || y < yMin || y > yMax) { m.status = MARCH_LEFT; break; }
        vec3 tx = marchFetch(hf, size, uv);
        m.fetches++;
        if (tx.x <= MARCH_EMPTY_Y) { m.status = MARCH_LEFT; break; }   // off the world square
        float f = marchSolidAs(tx, y, fromBelow);
        if (f <= 0.0) { tb = t; fb = f; m.status = MARCH_HIT; break; }
        ta = t;
        fa = f;
        s = skip ? marchSkipNext(s, marchSkipCount(skipMap, uv, y, adv, levels), last) : s + 1;
    }
    m.ta = ta;
    if (m.status != MARCH_HIT) { m.t = ta; m.f = fa; return m; }
    for (int k = 0; k < ROLLED(MARCH_REFINE_MAX); k++) {
        if (k >= refine) break;
#ifdef REFINE_BINARY
        float t = 0.5 * (ta + tb);
#else
        float t = marchInterp(ta, fa, tb, fb);
#endif
        float f = marchF(hf, size, uv0 + t * duv, o.y + t * dir.y, fromBelow);
        m.fetches++;
        if (f > 0.0) { ta = t; fa = f; } else { tb = t; fb = f; }
    }
    m.ta = ta;
    m.tb = tb;
    m.t = marchInterp(ta, fa, tb, fb);
    return m;
}

#endif
