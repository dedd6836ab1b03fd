// natural.glsl: what the programs of packs/natural share (docs/packs/natural.md).
//
//   natProject / natRefrPoint   the projective lookups of the water shader
//   natPhoton                   one photon of the sun through the surface to
//                               the floor, found in the light camera's depth
//                               map (both caustic methods)
//   natCausticUV / natCausticRatio   the caustic texture and its lookup
//
// Include after waves.glsl and world.glsl (it uses uWaterLevel, uSunDir,
// uIOR, uAbsorption, uAmbient and worldFresnel). No #version here.
//
// The caustic texture holds a RATIO, not an irradiance: the sun's irradiance
// on the floor divided by what flat water would give there (1 under calm
// water). Its coordinates are "refracted-sun space": a floor point p maps
// to the point q where the sun ray refracted by the FLAT surface, through
// p, leaves the mean plane,
//     q = p.xz - t_s.xz * D / cos_t,   D = level - p.y,  t_s the flat refracted sun,
// over the square |q| <= NAT_CAUSTIC_MARGIN * uTerrainHalfSize. In that space
// flat water spreads the light evenly whatever the floor's slope, so the
// ratio multiplies the sun term of tarn's world shading (worldShadeAt: flat
// sun through flat water) on any floor: exactly under flat water, and to
// first order in the photon directions' departure from t_s under waves.
#ifndef NATURAL_GLSL
#define NATURAL_GLSL
#include "contract.glsl"
#include "loops.glsl"        // ROLLED(n): loop bounds

// Waves of any model in the world: tarn defines WAVES_HAS_* for the models
// the world has (a build without WAVES_MODELS, glslang's validation, has
// them all). pack.glib's `If waves` is the same test: on calm water the
// caustic ratio is exactly 1, so no photon pass runs and water.frag reads
// no caustic texture.
#if !defined(WAVES_MODELS) || defined(WAVES_HAS_SINE) || defined(WAVES_HAS_GERSTNER) || defined(WAVES_HAS_NOISE) || defined(WAVES_HAS_OCEAN) || defined(WAVES_HAS_EXPLOSION) || defined(WAVES_HAS_PERLIN)
#define NAT_WAVES 1
#endif

#define NAT_CAUSTIC_MARGIN 1.25   // caustic square / world square (photons land beyond the edge)

#include "terrain.glsl"     // uTerrainHalfSize; the ground's height (the shore, objects)

float natCausticHalfSize() { return NAT_CAUSTIC_MARGIN * uTerrainHalfSize; }

// The sun refracted by flat water (downward, unit) and the cosines.
vec3 natFlatSun() { return refract(-uSunDir, vec3(0.0, 1.0, 0.0), 1.0 / uIOR); }

// Refracted-sun space of a point under water (see above).
vec2 natCausticQ(vec3 p) {
    vec3 ts = natFlatSun();
    float depth = uWaterLevel - p.y;
    return p.xz - ts.xz * (depth / max(-ts.y, 1e-4));
}

vec2 natCausticUV(vec2 q) { return q / natCausticHalfSize() * 0.5 + 0.5; }

// The ambient term of tarn's world shading under the water at p, as
// worldShadeAt (packs/common/world.glsl) has it: ambient (1 - R0)
// exp(-sigma depth). The caustic ratio scales what is left: the sun term.
vec3 natAmbientUnder(vec3 p) {
    float r0 = (uIOR - 1.0) / (uIOR + 1.0);
    return uAmbient * (1.0 - r0 * r0) * exp(-uAbsorption * max(uWaterLevel - p.y, 0.0));
}

// ---- projective lookups ---------------------------------------------------

// Texture coordinates of a world point in a camera's colour/depth target,
// with the clip w (the view depth for a perspective camera).
vec2 natProject(mat4 vp, vec3 p, out float w) {
    vec4 c = vp * vec4(p, 1.0);
    w = c.w;
    return c.xy / c.w * 0.5 + 0.5;
}

bool natInside(vec2 uv) { return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))); }

// The scene point a perspective target shows in the direction of world
// point x from the camera's eye: on the ray eye -> x at the view depth
// read from the depth target. For P = perspective, clip.z = -A clip.w + B
// with B = clip.z of the eye, so the view depth of an NDC depth z is
// B / (z + A). valid: the target holds something there (depth < 1).
// zt: the depth read (a caller asking whether it is the sky need not read
// it again: on llvmpipe every texture read costs every pixel).
vec3 natShownPointZ(mat4 vp, vec3 eye, sampler2D depthTex, vec3 x, out vec2 uv, out bool valid, out float zt) {
    vec4 cx = vp * vec4(x, 1.0);
    float B = (vp * vec4(eye, 1.0)).z;
    float A = (B - cx.z) / cx.w;
    uv = cx.xy / cx.w * 0.5 + 0.5;
    zt = texture(depthTex, uv).r;
    valid = natInside(uv) && zt < 1.0 && cx.w > 0.0;
    float wv = B / (2.0 * zt - 1.0 + A);
    return eye + (x - eye) * (wv / cx.w);
}

vec3 natShownPoint(mat4 vp, vec3 eye, sampler2D depthTex, vec3 x, out vec2 uv, out bool valid) {
    float zt;
    return natShownPointZ(vp, eye, depthTex, x, uv, valid, zt);
}

// The nearest of the four texels a bilinear read of the depth target mixes
// at x's projection, as a point on the ray eye -> x, and how much farther
// the farthest of them is (view depth ratio; 1 on a surface, more at a
// silhouette, where a thing stands in front of what is behind it).
vec3 natNearestShown(mat4 vp, vec3 eye, sampler2D depthTex, vec3 x, out float spread) {
    vec4 cx = vp * vec4(x, 1.0);
    float B = (vp * vec4(eye, 1.0)).z;
    float A = (B - cx.z) / cx.w;
    vec2 uv = cx.xy / cx.w * 0.5 + 0.5;
    ivec2 size = textureSize(depthTex, 0);
    ivec2 i0 = clamp(ivec2(floor(uv * vec2(size) - 0.5)), ivec2(0), size - 2);
    float lo = 1e30, hi = 0.0;
    for (int k = 0; k < ROLLED(4); k++) {
        float z = texelFetch(depthTex, i0 + ivec2(k & 1, k >> 1), 0).r;
        if (z >= 1.0) continue;                    // nothing drawn there
        float wv = B / (2.0 * z - 1.0 + A);        // view depth
        lo = min(lo, wv);
        hi = max(hi, wv);
    }
    spread = hi > 0.0 ? hi / lo : 1.0;
    return eye + (x - eye) * (min(lo, 1e6) / cx.w);
}

// Where the ray U + s r (downward) meets the ground of the terrain model
// (terrain.glsl), objects left out: for a ray whose hit the camera's
// target hides. Fixed-point steps on the drop under the current point,
// on the model, not the height map: the map's textureLod in this loop made
// llvmpipe's LLVM take 5.5 s instead of 0.35 s to compile the water shader
// (every save of it; the map alone in the loop, 122 s), for no frame time
// (lake 960x540 animated, 142 against 143 ms; docs/benchmark.md,
// "natural's compile").
vec3 natGroundAlong(vec3 U, vec3 r) {
    float s = 0.0, dy = max(-r.y, 1e-3);
    for (int i = 0; i < ROLLED(8); i++) s = max(U.y - terrainHeightGrad((U + s * r).xz).x, 0.0) / dy;
    return U + s * r;
}

// ---- photons ----------------------------------------------------------------

uniform sampler2D uLightDepth;   // the light camera's depth of the world below the water

// Light-target coordinates (xy) and depth (z), both 0..1.
vec3 natLightTex(vec3 p) {
    vec4 c = uCamLightVP * vec4(p, 1.0);
    return c.xyz / c.w * 0.5 + 0.5;
}

// > 0 when p lies behind (under) the floor as the light sees it; -2 off the map.
// The terrain model (terrain.glsl) counts as floor too: the map lost the
// ground within its clip of the level (World below -0.02), so at the shore
// photons from the water over that strip ran on to the first ground under
// the clip and piled up there: no light on the strip along the waterline
// (a dark line), too much just past it (white specks; issue #24). Its
// height difference is put in the map's depth units along the sun.
float natBehindFloor(vec3 p) {
    vec3 l = natLightTex(p);
    if (!natInside(l.xy)) return -2.0;
    vec3 row2 = vec3(uCamLightVP[0][2], uCamLightVP[1][2], uCamLightVP[2][2]);
    float kz = 0.5 * dot(row2, -uSunDir);           // map depth per unit along -sun
    float gt = (terrainHeightGrad(p.xz).x - p.y) / max(uSunDir.y, 1e-4) * kz;
    return max(l.z - texture(uLightDepth, l.xy).r, gt);
}

#ifndef PHOTON_STEPS
#define PHOTON_STEPS 8
#endif

// How far a march leg from P along t (downward) looks for the floor: twice
// the slant distance of the drop under P along the sun in the light's depth
// map, plus 0.25 u (u the scene's unit); negative when nothing is below.
float natLegLength(vec3 P, vec3 t) {
    vec3 l = natLightTex(P);
    if (!natInside(l.xy)) return -1.0;
    float zF = texture(uLightDepth, l.xy).r;
    if (zF >= 1.0) return -1.0;
    // d(depth)/d(distance) along -sun: the light's ortho depth is linear
    vec3 row2 = vec3(uCamLightVP[0][2], uCamLightVP[1][2], uCamLightVP[2][2]);
    float kz = 0.5 * dot(row2, -uSunDir);
    float drop = abs(kz) > 1e-8 ? max(zF - l.z, 0.0) / kz * uSunDir.y : 1.0;
    return 2.0 * max(drop, 0.0) / -t.y + 0.25 * uWorldScale;   // (world.glsl's scene unit)
}

// Where the ray S + s t (t refracted, downward) meets the floor of the
// light's depth map: PHOTON_STEPS steps over a leg of natLegLength, then
// three regula-falsi steps in the bracket. A photon that passes beside what
// stood under its start (an object's edge, a bank, as the sun sees them)
// has not met the floor by the leg's end: a second leg, as long as the drop
// under that end asks, follows it down. False when it meets nothing.
bool natTraceFloor(vec3 S, vec3 t, out float s, out vec3 hit) {
    s = 0.0;
    hit = S;
    if (!natInside(natLightTex(S).xy) || t.y >= 0.0) return false;
    float s0 = 0.0, g0 = natBehindFloor(S);
    if (g0 >= 0.0) return true;                    // the floor touches the surface here
    // S under the ground (the water grid runs on under a beach), which the
    // map may not show (its clip, World below -0.02, cut the ground at the
    // water's edge away, and the sun sees deeper ground through the cut):
    // the ground is at the surface, the photon lands at S
    if (terrainHeightGrad(S.xz).x >= S.y) return true;
    for (int leg = 0; leg < ROLLED(2); leg++) {
        float start = s0, len = natLegLength(S + start * t, t);
        // Nothing under S in the map, but the ground stands within the
        // light pass's clip (World below -0.02) of the level here: the
        // shore, where the clip cut the ground away, so the sun sees
        // through it. The ground is at the surface: the photon lands at
        // S. Lost, these photons drew a black line along the waterline.
        if (len < 0.0 && leg == 0 && terrainHeightGrad(S.xz).x >= uWaterLevel - 0.02 * uWorldScale)
            return true;
        if (len < 0.0) return false;
        for (int i = 1; i <= ROLLED(PHOTON_STEPS); i++) {
            float s1 = start + len * float(i) / float(PHOTON_STEPS);
            float g1 = natBehindFloor(S + s1 * t);
            if (g1 >= 0.0) {
                for (int k = 0; k < ROLLED(3); k++) {      // regula falsi in [s0, s1]
                    float sm = s0 + (s1 - s0) * (-g0) / max(g1 - g0, 1e-12);
                    float gm = natBehindFloor(S + sm * t);
                    if (gm >= 0.0) { s1 = sm; g1 = gm; } else { s0 = sm; g0 = gm; }
                }
                s = s0 + (s1 - s0) * (-g0) / max(g1 - g0, 1e-12);
                hit = S + s * t;
                return true;
            }
            if (g1 < -1.5) return false;           // left the map
            s0 = s1;
            g0 = g1;
        }
    }
    return false;
}

// One photon through the surface point S with unit normal N, standing for
// `area` of the mean water plane under a sun of unit flux density (flat
// water: area; waves: the patch's projected area / cos_s). Its weight w is
// that area times the flux it brings to the floor relative to flat water:
//     w = area (1 - R(cos_i)) / (1 - R(cos_s)) exp(-sigma (s - D / cos_t))
// (sigma the mean absorption, s its path in water, D the depth of its hit).
// Summed per unit of refracted-sun-space area, the weights give the ratio.
bool natPhoton(vec3 S, vec3 N, float area, out vec2 q, out float w) {
    vec3 ts = natFlatSun();
    float cosT = max(-ts.y, 1e-4);
    // q also where the photon is lost (w = 0): at the point it stopped, so a
    // mesh splat's triangle with a lost corner stays where its light went
    q = S.xz;
    w = 0.0;
    float cosS = max(uSunDir.y, 1e-4);
    float cosI = dot(N, uSunDir);
    if (cosI <= 0.0 || area <= 0.0) return false;
    vec3 t = refract(-uSunDir, N, 1.0 / uIOR);
    float s;
    vec3 hit;
    bool met = natTraceFloor(S, t, s, hit);
    float depth = uWaterLevel - hit.y;
    q = hit.xz - ts.xz * (depth / cosT);
    if (!met) return false;
    // S under the ground (the water grid runs on under a beach): the
    // photon lands where it is, with no path in water. Lost (w 0), as
    // before issue #24, it darkened the triangles it shares with the
    // photons just off the shore: a black line along every waterline
    // that the reference, whose photons light the ground at the water's
    // edge, does not have. (Where S is above the mean level the ratio is
    // not read: applyCaustics leaves points above the level alone.)
    if (s <= 0.0) {
        w = area * (1.0 - worldFresnel(cosI, 1.0, uIOR)) / (1.0 - worldFresnel(cosS, 1.0, uIOR));
        return true;
    }
    // (a hit above the mean level, on a beach under a crest, keeps its
    // light too: applyCaustics does not read the ratio there, but a lost
    // corner would darken the triangles it shares with the wet side)
    float sigma = dot(uAbsorption, vec3(1.0 / 3.0));
    w = area * (1.0 - worldFresnel(cosI, 1.0, uIOR)) / (1.0 - worldFresnel(cosS, 1.0, uIOR))
        * exp(-sigma * (s - depth / cosT));
    return true;
}

// ---- the paper's photon: Mihálik's equation (1) -------------------------------
//
// The paper's caustics (photon.frag, CAUSTICS_GPU off) take for each photon
// the same one-shot estimate as the view ray (water.frag with REFINE_STEPS
// 0), with the sun in place of the eye: d is the photon's path in water to
// the floor the light camera sees under S (its depth map, along the sun,
// unrefracted), the hit is W = S + clamp(d, 0, 2)/3 R (R the refracted
// sun), and the light it brings is (1 - (1 - L.N)^4.5) exp(-d k) (k 0.5
// a metre, the water shader's uAttenuation default). No march, no exact
// Fresnel. Lengths are lake metres times uWorldScale.
// Tarn's caustic texture holds a ratio to the flat-water light that
// tarn's world shading already gives the floor (worldShadeAt), so the
// weight is the paper's illumination over the same formula for flat water
// on the same sun ray (L.N = cos_s, d from the mean plane): 1 exactly under
// calm water, where W lies on the flat refracted sun ray through S and q =
// S.xz.
#define NAT_PAPER_CLAMP 2.0        // clamp(d, 0, 2)
#define NAT_PAPER_SCALE (1.0 / 3.0)
#define NAT_PAPER_Q 4.5            // (1 - E.N)^4.5
#define NAT_PAPER_K 0.5            // exp(-d k), per lake metre

bool natPhotonPaper(vec3 S, vec3 N, float area, out vec2 q, out float w) {
    vec3 ts = natFlatSun();
    float cosT = max(-ts.y, 1e-4);
    q = S.xz;
    w = 0.0;
    float cosS = max(uSunDir.y, 1e-4);
    float cosI = dot(N, uSunDir);
    if (cosI <= 0.0 || area <= 0.0) return false;
    vec3 l = natLightTex(S);
    if (!natInside(l.xy)) return false;
    float zF = texture(uLightDepth, l.xy).r;
    // the light's ortho depth is linear in distance along -sun
    vec3 row2 = vec3(uCamLightVP[0][2], uCamLightVP[1][2], uCamLightVP[2][2]);
    float kz = 0.5 * dot(row2, -uSunDir);
    if (abs(kz) < 1e-8) return false;
    // d: the map's, or the terrain model's where that is nearer (the
    // map's clip, World below -0.02, cut the ground at the water's edge
    // away, so over that strip d ran on to deeper ground and the photons
    // piled up in a jagged line along the shore; issue #24)
    float dT = (S.y - terrainHeightGrad(S.xz).x) / max(uSunDir.y, 1e-4);
    if (zF >= 1.0 && dT < 0.0) return false;
    float d = max(min(zF < 1.0 ? (zF - l.z) / kz : 1e30, max(dT, 0.0)), 0.0);
    vec3 R = refract(-uSunDir, N, 1.0 / uIOR);
    vec3 W = S + clamp(d, 0.0, NAT_PAPER_CLAMP * uWorldScale) * NAT_PAPER_SCALE * R;
    q = W.xz - ts.xz * ((uWaterLevel - W.y) / cosT);
    float d0 = max(d + (uWaterLevel - S.y) / cosS, 0.0);   // from the mean plane on the same sun ray
    float k = NAT_PAPER_K / uWorldScale;
    float light = (1.0 - pow(1.0 - clamp(cosI, 0.0, 1.0), NAT_PAPER_Q)) * exp(-d * k);
    float flat_ = (1.0 - pow(1.0 - cosS, NAT_PAPER_Q)) * exp(-d0 * k);
    w = area * light / max(flat_, 1e-6);
    return true;
}

#endif // NATURAL_GLSL
