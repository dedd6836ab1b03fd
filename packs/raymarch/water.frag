#version 330 compatibility
// packs/raymarch: Lipp's physically based perturbed planar refraction and
// reflection, by a steep-parallax ray march through top-down world-Y
// textures (docs/packs/raymarch.md has the method, citations and figures).
//
// The world is a texel-wise solid of top-down textures (march.glsl): below
// the floor under the water, and between the bottom of floating things and
// the top seen from above. From above: R = refract(-E, N, 1/ior) is marched
// down through it to the ground, whose colour is fetched there and
// attenuated along the path in water; reflect(-E, N) is marched up through
// the same solid and falls back to the sky cube map; exact Fresnel mixes
// them; a Phong highlight of the sun is added.
// From below (camera under water): the reflected ray goes down through the
// same ground march, the refracted one up through the above-water march,
// with total internal reflection, and the camera's own path in water
// attenuates the result.
#include "contract.glsl"
#include "loops.glsl"        // ROLLED(n): loop bounds
#include "waves.glsl"
#include "world.glsl"
#include "terrain.glsl"
#include "march.glsl"

#ifndef DEBUG_OUTPUT
#define DEBUG_OUTPUT 0
#endif
// The march up (reflections from above, Snell's window from below) meets
// only what stands above the water: tarn defines WORLD_ABOVE_WATER when
// the scene has any (`If above_water`'s test); with only sky there the
// march is compiled out and the sky cube map is exact. (A build without
// tarn's world defines, WAVES_MODELS unset: glslang's validation, keeps it.)
#if !defined(NOREFLECTION) && (defined(WORLD_ABOVE_WATER) || !defined(WAVES_MODELS))
#define RAYMARCH_MARCH_UP 1
#endif
// the march up jumps over the samples the skip map knows are empty
// (march.glsl: the same result, fewer steps)
#ifdef MARCH_SKIP
#define MARCH_SKIP_ON true
#else
#define MARCH_SKIP_ON false
#endif
#if defined(REFINE_BINARY) || defined(REFINE_SECANT)
#define REFINE_COUNT uRefineSteps
#else
#define REFINE_COUNT 0
#endif


uniform sampler2D uTopColor;      // Camera top, World all: colour
uniform sampler2D uUnderColor;    // the same, undersides only: colour
uniform sampler2D uFloorColor;    // World below: colour, a rock's band filled with ground (floor_fill.frag)
uniform sampler2D uLowColor;      // World below 1.5, undersides only: colour
uniform sampler2D uWorldY;        // pack_y.frag: world Y of top, bottom, floor
uniform sampler2D uFresnelLut;       // fresnel_lut.frag's table
uniform sampler2D uWaterNormal;      // @water_normal
uniform sampler2D uSkipCells;        // skip_dist.frag's: cells to the nearest blocked one, per height

uniform float uStepsGrazing;   // steps across the depth for a horizontal ray (source: 10)
uniform float uStepsSteep;     // ... for a vertical ray (source: 3)
uniform int uMaxIter;          // march steps at most (source: 40)
uniform float uMinDepth;       // smallest depth the steps are laid over (lake m: times uWorldScale)
uniform float uMaxStep;        // longest refraction step (lake m: times uWorldScale)
uniform float uReflectStep;    // longest reflection step (lake m: times uWorldScale)
uniform int uRefineSteps;      // regula falsi / bisection steps after the search
uniform float uReflectHeight;  // height of the above-water geometry (lake m: times uWorldScale)
uniform float uAttenLinear;    // linear attenuation per metre (source: 1/7.5)
uniform vec3 uWaterColor;      // what the water fades to
uniform float uSpecular;       // Phong highlight scale
uniform float uShininess;      // Phong exponent (source: 256)
uniform float uBumpMult;       // normal map strength (source: BumptexMult)
uniform float uNormalTile;     // metres per normal map tile
uniform float uNormalSpeed;    // scroll speed scale
uniform vec2 uNormalScroll[4]; // the four scroll velocities, tiles per second at speed 1

in vec2 vRest;
in vec3 vWorldPos;
out vec4 fragColor;

int gFetches = 0;   // world-Y texels the marches read (DEBUG_OUTPUT 5)

// The slope variance the filtered normal dropped (OCEAN_FILTER): the
// highlight's extra roughness (waves.glsl, wavesToksvig).
float gLostVar = 0.0;

vec3 waterNormal(vec2 footprint) {
#if defined(WAVES_HAS_OCEAN) && defined(OCEAN_FILTER)
    vec3 n = wavesNormalFilteredVar(vRest, uTime, footprint, gLostVar);
#else
    vec3 n = wavesNormal(vRest, uTime);
#endif
#ifdef NORMAL_MAP
    // the source's four scrolled samples of one normal map, averaged; their
    // slopes, times BumptexMult, are added to the waves' slopes
    vec3 m = vec3(0.0);
    vec2 st = vWorldPos.xz / uNormalTile;
    for (int k = 0; k < ROLLED(4); k++) {
        vec3 c = texture(uWaterNormal, st + uNormalScroll[k] * (uNormalSpeed * uTime)).rgb;
        m += vec3(c.r, c.b, c.g) * 2.0 - 1.0;   // the texture stores (x, z, y) / 2 + 1/2
    }
    m.y = max(m.y, 1e-3);
    vec2 slope = -n.xz / max(n.y, 1e-3) - uBumpMult * m.xz / m.y;
    n = normalize(vec3(-slope.x, 1.0, -slope.y));
#endif
    return n;
}

float fresnelLut(float x, float row) {
    float w = float(textureSize(uFresnelLut, 0).x);
    return texture(uFresnelLut, vec2((x * (w - 1.0) + 0.5) / w, row)).r;
}

// Reflectance for light arriving from the air at cos cosI.
float fresnelFromAir(float cosI) {
#ifdef FRESNEL_LUT
    return fresnelLut(cosI, 0.25);            // row 0: texel i at cos = i / (w - 1)
#else
    return worldFresnel(cosI, 1.0, uIOR);
#endif
}

// Reflectance for light arriving from the water: 1 beyond the critical
// angle (exactly, with no table), and the table in sqrt((c - cC)/(1 - cC)),
// in which R is smooth at the critical angle, where in c it is not.
float fresnelFromWater(float cosI) {
    float cosC = sqrt(max(1.0 - 1.0 / (uIOR * uIOR), 0.0));
    if (cosI <= cosC) return 1.0;
#ifdef FRESNEL_LUT
    return fresnelLut(sqrt((cosI - cosC) / (1.0 - cosC)), 0.75);
#else
    return worldFresnel(cosI, uIOR, 1.0);
#endif
}

vec3 attenuate(vec3 c, float s) {
#ifdef BEER_LAMBERT
    vec3 tr = exp(-uAbsorption * s);
    return c * tr + uWaterColor * (1.0 - tr);
#else
    return mix(c, uWaterColor, clamp(s * uAttenLinear, 0.0, 1.0));
#endif
}

// The colour of the solid met at hit: the floor's where the floor makes the
// texel solid there (World below: what lies under an overhang), else the
// underside's when the ray came up through a bottom or met a slab (a thing
// under the water, marchSolid) nearer its bottom than its top, else the
// top's. The texel is hit's, or inside's (the march's first sample in the
// solid) where hit, interpolated between the bracket's ends, is still
// outside: else a ray that met a box's side takes the colour of the grass
// in front of it (issue #16's speckled reflections).
// The ground under a thing under the water, which no pass saw: tarn's world
// shading of the terrain's model there (world.frag's, under the water).
vec3 groundModelColor(vec3 hit) {
    vec3 hg = terrainHeightGrad(hit.xz);
    vec3 n = normalize(vec3(-hg.y, 1.0, -hg.z));
    vec3 p = vec3(hit.x, hg.x, hit.z);
    return worldShadeAt(terrainAlbedo(hit.xz, hg.x, n), n, p);
}

// The undersides' colour at uv, bilinear over the texels that hold an
// underside; `fallback` where none does. Their pass clears to alpha 0 and
// draws alpha 1, so a bilinear read is (coverage-weighted colour,
// coverage): divided by the coverage it leaves out the texels beside a
// thing's rim, where the pass saw nothing of it. A plain read mixed those
// in and striated the thing's side in dark columns (a floating sphere
// seen by total internal reflection from below).
vec3 underColor(vec2 uv, vec3 fallback) {
    vec4 c = texture(uUnderColor, uv);
    return c.a > 1e-3 ? c.rgb / c.a : fallback;
}

// A vertical wall met (the side of a post, a box, a trunk: a column entered
// through its side, well below its top and above its bottom): the top-down
// views never saw it, and the top's colour there (the post's sunlit cap)
// drew the post's submerged shaft as beige discs. The side is shaded the
// way tarn's world program shades it (world.glsl, linear in the albedo):
// the albedo is the top's colour divided by the top's own shading (its
// normal from the heights beside it, one-sided so a flat cap stays flat
// at its rim), and the wall's normal is the horizontal gradient of the
// solid around the hit (a Sobel ring of the texels at the hit's height),
// else the ray's way back. Alpha 0: not a wall under a flat top.
#define RAYMARCH_WALL_MIN 0.05   // lake m: a side at least this far below the top and above the bottom
vec4 wallColor(vec3 hit, ivec2 ij, vec3 t, vec3 dir) {
    ivec2 size = textureSize(uWorldY, 0);
    float gx = 0.0, gz = 0.0;
    float tx[2], tz[2];   // tops at x-1, x+1 and z-1, z+1
    for (int j = -1; j <= ROLLED(1); j++) {
        for (int i = -1; i <= ROLLED(1); i++) {
            if (i == 0 && j == 0) continue;
            vec3 nb = texelFetch(uWorldY, clamp(ij + ivec2(i, j), ivec2(0), size - 1), 0).xyz;
            float occ = nb.x > MARCH_EMPTY_Y && marchSolid(nb, hit.y) <= 0.0 ? 1.0 : 0.0;
            float w = (i == 0 || j == 0) ? 2.0 : 1.0;
            gx += float(i) * w * occ;
            gz += float(j) * w * occ;
            if (j == 0) tx[(i + 1) / 2] = nb.x;
            if (i == 0) tz[(j + 1) / 2] = nb.x;
        }
    }
    // texel side in world metres along s and t (the top camera's square)
    vec2 w0 = marchWorldXZ((vec2(ij) + 0.5) / vec2(size));
    vec2 ws = marchWorldXZ((vec2(ij) + vec2(1.5, 0.5)) / vec2(size)) - w0;
    vec2 wt = marchWorldXZ((vec2(ij) + vec2(0.5, 1.5)) / vec2(size)) - w0;
    // the gradient is in texel axes (s, t); its world direction
    vec2 g = gx * ws / dot(ws, ws) + gz * wt / dot(wt, wt);
    vec2 nh = dot(g, g) > 1e-12 ? -normalize(g) : -normalize(dir.xz + vec2(1e-9, 0.0));
    vec3 nWall = vec3(nh.x, 0.0, nh.y);
    // the top's slope, one-sided: the smaller difference on each axis (the
    // other may fall off the thing's rim), none where the texel is a peak
    // or a pit on that axis (a cap's rim one texel wide: both fall off)
    float ax = t.x - tx[0], bx = tx[1] - t.x, az = t.x - tz[0], bz = tz[1] - t.x;
    float sx = ax * bx <= 0.0 ? 0.0 : abs(ax) < abs(bx) ? ax : bx;
    float sz = az * bz <= 0.0 ? 0.0 : abs(az) < abs(bz) ? az : bz;
    vec2 slope = sx * ws / dot(ws, ws) + sz * wt / dot(wt, wt);
    // only under a flat top (a post's cap, a box's lid): on a curved one
    // (the rock's rim) the slopes of neighbouring texels scatter, and the
    // albedo with them (speckles); its top's colour is near the wall's there
    if (dot(slope, slope) > 0.04) return vec4(0.0);
    vec3 top = texelFetch(uTopColor, ij, 0).rgb;
    vec3 nTop = normalize(vec3(-slope.x, 1.0, -slope.y));
    vec3 topPos = vec3(hit.x, t.x, hit.z);
    vec3 albedo = min(top / max(worldShadeAt(vec3(1.0), nTop, topPos), vec3(1e-4)), vec3(1.0));
    return vec4(worldShadeAt(albedo, nWall, hit), 1.0);
}

// A wall solidColor met (wallColor's arguments): shaded after both marches,
// once for both rays (wallsWhereWanted). want: the colour solidColor
// returned stands only where wallColor gives none (alpha 0).
struct Wall {
    bool want;
    vec3 hit;
    ivec2 ij;
    vec3 t;
    vec3 dir;
};

vec3 solidColor(vec3 hit, vec3 inside, bool underside, vec3 dir, out bool needModel, out Wall wall) {
    needModel = false;
    wall = Wall(false, hit, ivec2(0), vec3(0.0), dir);
    ivec2 size = textureSize(uWorldY, 0);
    vec2 uv = clamp(marchUV(hit), 0.0, 0.999999);
    vec3 t = marchFetch(uWorldY, size, uv);
    // (clearly outside: by more than rounding. Without refinement, Lipp's
    // paper row, tb is a whole step, up to 0.33 m, past a hit on a flat floor
    // that the interpolation puts a few ulps above it: the pool's tiles took
    // the colour of a tile a step away, in speckles)
    if (marchSolid(t, hit.y) > 1e-3 * uWorldScale) {
        uv = clamp(marchUV(inside), 0.0, 0.999999);
        t = marchFetch(uWorldY, size, uv);
    }
    underside = underside && t.y > MARCH_EMPTY_Y && t.y < t.x;   // no bottom here: no underside colour
    // the floor's colour, read once for the three ways out that show it
    // (llvmpipe runs every branch's read for every pixel: three reads)
    vec3 floorColor = texture(uFloorColor, uv).rgb;
    // w: the highest underside (pack_y.frag), or MARCH_GROUND_MODEL where
    // the ground under a thing under the water is the terrain's model
    float high = texelFetch(uWorldY, ivec2(uv * vec2(size)), 0).w;
    bool model = high >= MARCH_GROUND_MODEL;
    float slab = hit.y - t.x;
    float side = -1.0;   // a side met between the column's bottom and top: how far up, 0..1
    if (t.y < t.x) {
        slab = max(slab, t.y - hit.y);
        if (t.z < t.y && hit.y - t.z <= slab) { needModel = model; return floorColor; }
        if (t.z >= t.y || model) side = clamp((hit.y - t.y) / (t.x - t.y), 0.0, 1.0);   // a thing under the water
    } else if (hit.y - t.z <= slab) {
        return floorColor;   // the ground beside a rock's rim too
    }
    // under the highest underside: a trunk under its crown
    if (!model && t.y < high && hit.y < high) return texture(uLowColor, uv).rgb;
    // (only for things that rise out of the water: on the sunken crate the
    // slab's walls also showed where the reference sees the floor)
    // (wallColor's, where it gives one, comes first: wallsWhereWanted)
    wall.want = !underside && t.x > uWaterLevel && t.x - hit.y > RAYMARCH_WALL_MIN * uWorldScale
        && (t.y >= t.x || hit.y - t.y > RAYMARCH_WALL_MIN * uWorldScale);
    wall.ij = min(ivec2(uv * vec2(size)), size - 1);
    wall.t = t;
    // the ground with nothing over it (the floor pass saw what the top pass
    // saw): the floor's colour, whose texels beside a rock's rim are ground
    // too (floor_fill.frag), where the top's are the rock's: a bilinear read
    // of the top's drew a dotted ring round the rock seen through the water
    if (t.y <= MARCH_EMPTY_Y && abs(t.z - t.x) < RAYMARCH_WALL_MIN * uWorldScale)
        return floorColor;
    vec3 top = texture(uTopColor, uv).rgb;
    vec3 under = underColor(uv, top);   // (once for both ways out)
    if (underside) return under;
    // a side between bottom and top: the two views blended by height, not
    // whichever end is nearer (that flips from column to column along a
    // row and striates a thing seen from the side, as total internal
    // reflection shows the boulder)
    return side >= 0.0 ? mix(under, top, side) : top;
}

// The terrain model's colour where a march met ground no pass saw
// (solidColor's needModel), written in one place: llvmpipe runs the code of
// every branch for a whole block of pixels, so each call written out cost
// every pixel one shading of the model (ground noise, albedo, light), at
// the two marches' solidColor and the open sea's edge. The loop takes a
// second turn only where a block has a pixel whose both rays want it.
void groundModelWhereWanted(bool wantD, vec3 hitD, inout vec3 down, bool wantU, vec3 hitU, inout vec3 up) {
    for (int k = 0; k < ROLLED(2); k++) {
        if (!wantD && !wantU) break;
        vec3 c = groundModelColor(wantD ? hitD : hitU);
        if (wantD) { down = c; wantD = false; } else { up = c; wantU = false; }
    }
}

// The walls the two marches met (solidColor's Wall), shaded in one place
// the same way: written in each solidColor, the reflected ray's copy cost
// the water pass 4-8% and its compile 35 ms (12%), though few blocks of
// pixels have both rays on a wall (next to a post).
void wallsWhereWanted(Wall wallD, inout vec3 down, Wall wallU, inout vec3 up) {
    bool wantD = wallD.want, wantU = wallU.want;
    for (int k = 0; k < ROLLED(2); k++) {
        if (!wantD && !wantU) break;
        Wall w = wantD ? wallD : wallU;
        vec4 c = wallColor(w.hit, w.ij, w.t, w.dir);
        if (wantD) {
            if (c.a > 0.0) down = c.rgb;
            wantD = false;
        } else {
            if (c.a > 0.0) up = c.rgb;
            wantU = false;
        }
    }
}

// The ground seen from p along dir (downwards, in water): its colour, the
// path s in water, the point and the march's status.
vec3 groundAlong(vec3 p, vec3 dir, out float s, out vec3 hit, out int status, out bool needModel, out Wall wall) {
    vec3 d = marchClampDir(dir, true);
#ifdef WAVES_HAS_OCEAN
    // Water beyond the world square (the open sea's rings): no top-down
    // texel under it, so the march would leave at once with a path of 0
    // and the colour of the texture's edge (black speckles and a floor
    // 60 m down shown unattenuated). The ground there is the terrain's
    // model, as world.frag draws it: the ray goes on down to it (a few
    // fixed-point steps on its height) through the water all the way.
    if (!marchInFootprint(marchUV(p))) {
        s = 0.0;
        for (int i = 0; i < ROLLED(3); i++) s = max(p.y - terrainHeightMarch((p + s * d).xz), 0.0) / -d.y;
        hit = p + s * d;
        status = MARCH_LEFT;
        needModel = true;
        wall = Wall(false, hit, ivec2(0), vec3(0.0), d);
        return vec3(0.0);
    }
#endif
#ifdef PAPER_REFRACTION
    // Lipp's: n = mix(10, 3, -R.y) steps of 1/n m each along R (the
    // sliders' 10 and 3), uMaxIter (40) of them at most
    float n = max(mix(uStepsGrazing, uStepsSteep, -d.y), 1.0);
    March m = marchHeightfield(uWorldY, p, d, uWorldScale / n, 0.0, uStepsGrazing, uStepsSteep, 4.0 * uWorldScale,
                               -1e30, 1e30, uMaxIter, REFINE_COUNT, -1e30, uSkipCells, false);
#else
    // The step cap (0.25 m: under a thin thing's width) must not stop the
    // march reaching the ground within its budget: on the deep open sea 40
    // steps of 0.25 m ran out 10 m down (scenes/hard/ocean_fold: 75 % of
    // the water capped). So it is at least what descends the depth under
    // the point (the terrain's model; things only make it shallower) in
    // three quarters of uMaxIter steps, up to 1 m (the cap before issue
    // #24): more, and grazing rays (from below, by total internal
    // reflection) stepped over what they should meet (underwater's error
    // 0.0081 -> 0.0124 at 96x54).
    float depth = max(p.y - terrainHeightGrad(p.xz).x, 0.0);
    float cap = clamp(depth / (max(-d.y, MARCH_MIN_DIR_Y) * 0.75 * float(uMaxIter)),
                      uMaxStep * uWorldScale, max(uMaxStep, 1.0) * uWorldScale);
    March m = marchHeightfield(uWorldY, p, d, 0.0, uMinDepth * uWorldScale, uStepsGrazing,
                               uStepsSteep, cap, -1e30, 1e30, uMaxIter, REFINE_COUNT,
                               -1e30, uSkipCells, false);
#endif
    gFetches += m.fetches;
    s = m.t;
    // no bracket: on down to the ground height of the last column
    if (m.status == MARCH_CAP || m.status == MARCH_LEFT) s += max(m.f, 0.0) / -d.y;
    hit = p + s * d;
    status = m.status;
    return solidColor(hit, m.status == MARCH_HIT ? p + m.tb * d : hit, false, d, needModel, wall);
}

// What is seen from p along dir (upwards, in air): the above-water geometry
// where the march meets it, else the sky. hit: the point, or the direction
// when the sky.
vec3 aboveAlong(vec3 p, vec3 dir, out vec3 hit, out int status, out bool needModel, out Wall wall) {
    hit = dir;
    needModel = false;
    wall = Wall(false, dir, ivec2(0), vec3(0.0), dir);
    status = MARCH_LEFT;
#ifdef RAYMARCH_MARCH_UP
    vec3 d = marchClampDir(dir, false);
    float reach = uReflectHeight * uWorldScale;
#ifdef PAPER_REFLECTION
    // Lipp's: a step of 1 / mix(0.5, 4, 1 - R.y) m (0.25 m for a grazing
    // ray, 2 m for a vertical one), 60 of them, through the solid seen from
    // below; the march stops once the position is more than 0.8 m above the
    // water (his cap is on the height reached, not on R.y): the sky there
    float step = uWorldScale / mix(0.5, 4.0, 1.0 - d.y);
    March m = marchHeightfield(uWorldY, p, d, step, 0.0, uStepsGrazing, uStepsSteep, step, -1e30,
                               uWaterLevel + 0.8 * uWorldScale, 60, REFINE_COUNT, uWaterLevel, uSkipCells, false);
#else
    float step = marchStep(reach, d.y, uStepsGrazing, uStepsSteep, uReflectStep * uWorldScale);
    March m = marchHeightfield(uWorldY, p, d, step, 0.0, uStepsGrazing, uStepsSteep,
                               uReflectStep * uWorldScale, -1e30, uWaterLevel + reach, uMaxIter, REFINE_COUNT,
                               -1e30, uSkipCells, MARCH_SKIP_ON);
#endif
    status = m.status;
    gFetches += m.fetches;
    if (m.status == MARCH_HIT || m.status == MARCH_INSIDE) {
        hit = p + m.t * d;
        // the side met: the underside when the ray was below the bottom of
        // the column it left (it came up through a bottom), else the top
        vec3 a = p + m.ta * d;
        vec2 uva = clamp(marchUV(a), 0.0, 0.999999);
        vec3 ya = marchFetch(uWorldY, textureSize(uWorldY, 0), uva);
        bool underside = m.status == MARCH_HIT && ya.y < ya.x && a.y < ya.y;
#ifdef PAPER_REFLECTION
        underside = true;   // the textures from below: the underside's colour where there is one
#endif
        return solidColor(hit, p + m.tb * d, underside, d, needModel, wall);
    }
#endif
    return worldSkyLook(uSky, dir);
}

void main() {
#if defined(WAVES_HAS_OCEAN) && defined(OCEAN_FILTER)
    vec2 footprint = wavesFootprint(vRest);   // in uniform control flow: derivatives
#else
    vec2 footprint = vec2(0.0);
#endif
    vec3 n = waterNormal(footprint);
    vec3 p = vWorldPos;
    vec3 e = normalize(uCameraPos - p);
#ifdef WAVES_HAS_OCEAN
    // The side of the water is the camera's (pack.glib's passes: the mean
    // level), not the normal's: a per-pixel normal of the ocean's finer
    // cascades turned away from an eye above the water (the back of a
    // ripple on a crest the mesh shows) made the pixel a view from below,
    // its total internal reflection marched 60 m down: black speckles.
    // Such a normal is mirrored about the plane across the view instead,
    // so it faces the eye with its tilt kept.
    bool below = uCameraPos.y < uWaterLevel;
    float en = dot(e, n);
    if (below ? en > 0.0 : en < 0.0) n = normalize(n - 2.0 * en * e);
#else
    bool below = dot(e, n) < 0.0;
#endif
    // Each side of the surface marches one ray down (through the ground
    // solid) and one up (the above-water one): from above, the refracted
    // ray down and the reflected one up; from below, the reflected ray down
    // and the refracted one up. The directions are chosen first and each
    // march is written once: llvmpipe runs both sides of a per-pixel `if`
    // (masked), so a march in each branch costs every fragment four.
    vec3 nb = below ? -n : n;
    float cosI = clamp(dot(e, nb), 0.0, 1.0);
    vec3 rdir = reflect(-e, nb);
    vec3 tdir = refract(-e, nb, below ? uIOR : 1.0 / uIOR);   // (0, 0, 0) on TIR (from below only)
    bool tir = below && dot(tdir, tdir) == 0.0;
    float F = below ? (tir ? 1.0 : fresnelFromWater(cosI)) : fresnelFromAir(cosI);
    float s;
    vec3 hitD, hitU;
    int stD, stU;
    bool modelD, modelU;
    Wall wallD, wallU;
    vec3 down = groundAlong(p, below ? rdir : tdir, s, hitD, stD, modelD, wallD);
    vec3 up = aboveAlong(p, below ? tdir : rdir, hitU, stU, modelU, wallU);
    groundModelWhereWanted(modelD, hitD, down, modelU, hitU, up);
    wallsWhereWanted(wallD, down, wallU, up);
    down = attenuate(down, s);
    vec3 color, hitT, hitR;
    int stT, stR;
    if (!below) {
#if defined(WAVES_HAS_OCEAN) && defined(OCEAN_FILTER)
        // the slopes the filter dropped widen the highlight, its light kept
        float energy;
        float shin = wavesToksvig(uShininess, gLostVar, energy);
        vec3 spec = uSpecular * energy * uSunIrradiance * pow(max(dot(rdir, uSunDir), 0.0), shin);
#else
        vec3 spec = uSpecular * uSunIrradiance * pow(max(dot(rdir, uSunDir), 0.0), uShininess);
#endif
        color = F * (up + spec) + (1.0 - F) * down;
        hitT = hitD; stT = stD; hitR = hitU; stR = stU;
    } else {
        vec3 refr = tir ? vec3(0.0) : up;
        color = F * down + (1.0 - F) * refr;
        hitR = hitD; stR = stD;
        hitT = tir ? vec3(0.0) : hitU;
        stT = tir ? MARCH_LEFT : stU;
        // the camera's own path in water (camera under the mean level)
        if (uCameraPos.y < uWaterLevel) color = attenuate(color, length(uCameraPos - p));
    }
#if defined(WAVES_HAS_OCEAN) && defined(OCEAN_FOAM)
    // the ocean's folding foam (waves_ocean.glsl): white, rough (lit
    // diffusely, no mirror), slightly translucent
    float foam = 0.85 * wavesFoamFiltered(vRest, max(footprint.x, footprint.y));
    vec3 white = 0.9 * (uSunIrradiance * max(dot(n, uSunDir), 0.0) / WORLD_PI + uAmbient);
    color = mix(color, white, foam);
#endif
#ifdef WAVES_HAS_FLOW
    // the flow's advected foam streaks (flow.glsl), lit as the ocean's foam
    float streak = flowFoam(vRest);
    vec3 foamLit = 0.9 * (uSunIrradiance * max(dot(n, uSunDir), 0.0) / WORLD_PI + uAmbient);
    color = mix(color, foamLit, streak);
#endif
    fragColor = vec4(color, 1.0);
#if DEBUG_OUTPUT == 1
    fragColor = vec4(hitT, float(stT));     // refracted ray: point met, status
#elif DEBUG_OUTPUT == 2
    fragColor = vec4(hitR, float(stR));     // reflected ray: point met (or direction), status
#elif DEBUG_OUTPUT == 3
    fragColor = vec4(F, F, F, 1.0);         // Fresnel reflectance
#elif DEBUG_OUTPUT == 4
    fragColor = vec4(s, s, s, 1.0);         // path in water of the marched ray (m)
#elif DEBUG_OUTPUT == 5
    fragColor = vec4(float(gFetches), 0.0, 0.0, 1.0);   // world-Y texels read
#endif
}
