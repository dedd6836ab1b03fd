#version 330 compatibility
// packs/natural: the water pixel of Mihálik's "Natural Water Shader"
// (docs/packs/natural.md). Two projective lookups into the passes drawn
// before the surface, on the camera's side of the water:
//   refraction  R = refract(-E, N, 1/ior), W = U + dv' R, dv' = clamp(dv, 0,
//               uDepthClamp) uDepthScale with dv the view ray's path in
//               water (from the depth target), W projected with uCamWideVP
//               into the refraction target; C = C_w + exp(-d k) (C_refr - C_w)
//   reflection  W = U + c reflect(-E, N), projected with uCamMirrorVP
//   Fresnel     F = (1 - E.N)^q, or exact (EXACT_FRESNEL)
//   colour      C_refr + F (C_refl - C_refr), plus a specular highlight
// With the camera under the water pack.glib swaps what the passes draw
// (the refraction target holds the world above, the reflection target the
// world below, mirrored); this shader swaps the optics to match: Snell's
// window out of the water, total internal reflection beyond it, and the
// eye's own path through the water.
#include "contract.glsl"
#include "loops.glsl"        // ROLLED(n): loop bounds
#include "waves.glsl"
#include "world.glsl"
#include "natural.glsl"

#if defined(CAUSTICS) && !defined(NAT_WAVES)
#undef CAUSTICS     // calm water: the ratio is 1 (pack.glib's `If waves` runs no photon pass)
#endif


uniform sampler2D uRefraction;        // the far side of the water from the main camera
uniform sampler2D uRefractionDepth;   //   its depth
uniform sampler2D uReflection;        // the near side, mirrored (camera widened by uFovScale)
uniform sampler2D uReflectionDepth;   //   its depth
uniform sampler2D uCaustics;          // caustic ratio over refracted-sun space (natural.glsl)

uniform float uFovScale;         // the reflection pass's field of view over the camera's
uniform float uReflectDist;      // c: reflection lookup distance
uniform float uAttenuation;      // k: attenuation per lake metre (the paper's model; per uWorldScale)
uniform vec3  uWaterColor;       // C_w: what deep water shows (the paper's model)
uniform float uFresnelPower;     // q of (1 - E.N)^q
uniform float uDepthClamp;       // dv clamp (paper: 2)
uniform float uDepthScale;       // dv scale (paper: 1/3)
uniform float uSpecular;         // highlight strength (times the sun's irradiance)
uniform float uShininess;        // highlight exponent
uniform float uCausticStrength;  // 1: the photons' ratio as computed; 0: flat-water light

#ifndef REFINE_BISECT
#define REFINE_BISECT 6          // halvings of the bracket the march found (1/64 of a step)
#endif
#ifndef REFINE_STEPS
#define REFINE_STEPS 0           // march steps finding the refraction hit in the depth target (0: the paper)
#endif
#ifndef DEBUG_PASS
#define DEBUG_PASS 0             // 1: refracted colour only, 2: reflected colour only, 3: caustic ratio / 2,
                                 // 4: the refraction hit point (world xyz: float targets, tests),
                                 // 5: the sun's irradiance there, 6: the refracted path in water (m)
#endif

// A depth at or beyond this is the sky (tarn draws it at the far plane)
// or nothing: with near 0.1 and a world's far plane of 4e4 (at least), beyond
// about 8 km; the land ends at 1e4 m (REF_WORLD_HORIZON).
#define NAT_SKY_DEPTH 0.99999

in vec2 vRest;
in vec3 vWorldPos;
out vec4 fragColor;

// Light lost along a path of length d in water: the paper's blend towards
// the water colour, or Beer-Lambert with the scene's absorption.
vec3 attenuate(vec3 c, float d) {
#ifdef BEER_LAMBERT
    return c * exp(-uAbsorption * d);
#else
    return uWaterColor + exp(-d / uWorldScale * uAttenuation) * (c - uWaterColor);
#endif
}

#define NAT_ON_GROUND 0.15     // how far from the terrain model a shown point counts as ground (lake m)

float gCausticRatio = 1.0;      // the last ratio applied (DEBUG_PASS 3)
vec3 gRefractHit = vec3(0.0);   // the point the refraction lookup showed (DEBUG_PASS 4)
vec3 gIrradiance = vec3(0.0);   // the sun's irradiance the last applyCaustics shaded with
vec3 gRefractIrradiance = vec3(0.0);   // that of the refraction lookup (DEBUG_PASS 5)

// The caustic ratio applied to the sun term of a floor colour that tarn's
// world program shaded with flat-water sunlight, albedo (E/pi + A_w):
// the albedo from the terrain's texture at p, the ratio filtered by four
// bilinear taps half a texel apart (a tent two texels wide: it removes the
// period-2 beat of the paper's regular photon grid splatted onto the
// texels, and of the mesh splat's two triangles a cell sampled by them).
vec3 applyCaustics(vec3 c, vec3 p) {
#if defined(CAUSTICS) || DEBUG_PASS == 5
    if (p.y >= uWaterLevel) return c;
    bool applied = false;
    float ratio = 1.0;
#ifdef CAUSTICS
    vec2 uv = natCausticUV(natCausticQ(p));
    // Only on the ground: the reference lights the objects under the water
    // by the flat sun, and the relighting below takes the terrain's albedo,
    // so on a sunken boulder or crate it turned the object's colour into
    // the ground's (bright patches over the boulder of the close-ups). A
    // shown point more than 15 cm off the terrain model (terrain.glsl) is
    // on an object (5 cm lost far ground, whose point the 512^2 depth
    // target gives less closely: lake 0.0479 -> 0.0480).
    if (natInside(uv) && abs(p.y - terrainHeightMarch(p.xz)) < NAT_ON_GROUND * uWorldScale) {
        vec2 o = 0.5 / vec2(textureSize(uCaustics, 0));
        float cr = 0.25 * (texture(uCaustics, uv + vec2(-o.x, -o.y)).r + texture(uCaustics, uv + vec2(o.x, -o.y)).r
                         + texture(uCaustics, uv + vec2(-o.x, o.y)).r + texture(uCaustics, uv + vec2(o.x, o.y)).r);
        ratio = max(1.0 + uCausticStrength * (cr - 1.0), 0.0);
        gCausticRatio = ratio;
        applied = true;
    }
#endif
#if DEBUG_PASS != 5
    if (!applied) return c;    // no albedo fetch where there is nothing to relight
#endif
    vec3 albedo = texture(uTerrainAlbedo, p.xz / uTerrainHalfSize * 0.5 + 0.5).rgb;
    vec3 amb = albedo * natAmbientUnder(p);
    vec3 sun = max(c - amb, vec3(0.0));     // albedo E / pi
#if DEBUG_PASS == 5
    gIrradiance = WORLD_PI * sun * ratio / max(albedo, vec3(1e-3));   // E as this shading has it
#endif
    return applied ? amb + sun * ratio : c;
#else
    return c;
#endif
}

#if REFINE_STEPS > 0
// The march of REFINE_STEPS (below): along U + s r, s in [0, smax], through
// the target a camera (vp, eye) drew with depth depthTex, to where the ray
// passes behind what the target shows (g(s) = |W - eye| - |shown(W) - eye|
// > 0, g(0) = g0 < 0), then REFINE_BISECT halvings of the bracket and one
// regula-falsi step. A ray that leaves the target keeps its last point in
// front; one that never passes behind anything (the sky) ends at smax.
// The refraction (the eye) and, since issue #24, the reflection (the
// mirrored eye) march alike.
// g at U + s r: how far the ray's point lies behind what the target shows
// in its direction, |x - eye| - |shown - eye| = |x - eye| (1 - wv / w)
// (natShownPointZ's point is on the ray eye -> x at view depth wv), with
// the ray's clip coordinates cU + s cR (linear along it: no matrix a step)
// and B the eye's clip z. ok: the target holds something there.
float natGap(vec4 cU, vec4 cR, float B, vec3 eye, sampler2D depthTex, vec3 U, vec3 r, float s, out bool ok) {
    vec4 cx = cU + s * cR;
    vec2 uv = cx.xy / cx.w * 0.5 + 0.5;
    float z = texture(depthTex, uv).r;
    ok = natInside(uv) && z < 1.0 && cx.w > 0.0;
    float A = (B - cx.z) / cx.w;
    float wv = B / (2.0 * z - 1.0 + A);
    return distance(eye, U + s * r) * (1.0 - abs(wv / cx.w));
}

float natMarch(mat4 vp, vec3 eye, sampler2D depthTex, vec3 U, vec3 r, float smax, float g0, out bool left) {
    bool ok;
    float s = smax;
    left = false;
    vec4 cU = vp * vec4(U, 1.0), cR = vp * vec4(r, 0.0);
    float B = (vp * vec4(eye, 1.0)).z;
    float sa = 0.0, ga = min(g0, -1e-4), sb = smax, gb = 0.0;
    bool crossed = false;
    for (int i = 1; i <= ROLLED(REFINE_STEPS); i++) {
        sb = smax * float(i) / float(REFINE_STEPS);
        gb = natGap(cU, cR, B, eye, depthTex, U, r, sb, ok);
        if (!ok) { s = sa; left = true; break; }
        if (gb > 0.0) { crossed = true; break; }
        sa = sb;
        ga = gb;
    }
    // after the steps' loop, not inside it: llvmpipe runs an if's body for
    // every pixel of a block, masked, so a bisection inside the loop cost
    // every step a second lookup
    if (crossed) {
        // bisection, then one interpolation: two regula-falsi steps
        // (as before) stalled at one end where g bends (a floor seen at
        // a slant), so the hits of whole rows of pixels stopped at the
        // same step's end and showed as bands on the shallow floor
        for (int k = 0; k < ROLLED(REFINE_BISECT); k++) {
            float sm = 0.5 * (sa + sb);
            float gm = natGap(cU, cR, B, eye, depthTex, U, r, sm, ok);
            if (!ok) gm = 1.0;
            if (gm > 0.0) { sb = sm; gb = gm; } else { sa = sm; ga = gm; }
        }
        s = sa + (sb - sa) * (-ga) / (gb - ga);
    }
    return s;
}
#endif

// What the refraction target shows along direction r from the surface
// point U, as the target holds it: main relights it by the caustics, at
// litAt when lit. The paper: W = U + s0 r. With REFINE_STEPS > 0, a march:
// W = U + s r for s = smax i / REFINE_STEPS until W passes behind what the
// target shows at W (g(s) = |W - eye| - |shown(W) - eye| > 0; g(0) = g0 =
// -|shown(U) - U| < 0), then REFINE_BISECT halvings of the bracket and one
// regula-falsi step; a ray
// that leaves the target keeps its last point in front. fallback: the
// unperturbed lookup (b0 at uv0, depth z0, valid ok0: main's) when W
// leaves the target or meets nothing. path: |shown - U|. sky: the lookup
// met the sky (or nothing).
vec3 lookThrough(vec3 U, vec3 r, float s0, float smax, float g0, bool fallback, vec3 b0, vec2 uv0, bool ok0, float z0,
                 out float path, out bool sky, out vec3 litAt, out bool lit) {
    float s = s0;
    lit = false;
    litAt = vec3(0.0);
    vec2 uv;
    bool ok;
#if REFINE_STEPS > 0
    bool left;
    s = natMarch(uCamWideVP, uCameraPos, uRefractionDepth, U, r, smax, g0, left);
#endif
    float zt;
    vec3 shown = natShownPointZ(uCamWideVP, uCameraPos, uRefractionDepth, U + s * r, uv, ok, zt);
    // The perturbed lookup left the target, or the march closed on the
    // silhouette of a thing standing out of the water (a floating sphere):
    // the ray went behind it, where what it meets is hidden from the
    // camera, and the halvings walked it to the edge, whose colour showed
    // in arcs beside the thing. The same where the thing is under the
    // water (a sunken boulder): a ray that passes behind it closed on its
    // silhouette, and rows of pixels whose brackets straddled it showed as
    // horizontal slivers (scenes/hard/crate_narrow). Where the bracket
    // closes on a silhouette the ray meets the terrain model's ground
    // (below); the point behind U itself where the lookup left the target.
    bool edge = false;
#if REFINE_STEPS > 0
    if (ok) {
        float spread;
        vec3 near = natNearestShown(uCamWideVP, uCameraPos, uRefractionDepth, U + s * r, spread);
        edge = spread > 1.25;
    }
    // A march that left the target (the refracted ray went off its edge,
    // the frame's bottom looking down) kept its last point in front, on
    // the edge's row: rows of pixels showed the same row, horizontal
    // slivers below the sunken boulder in crate_narrow. Such a ray meets
    // the terrain model's ground too.
    edge = edge || left;
#endif
#if REFINE_STEPS > 0
    if (edge && fallback) {
        // Behind a thing standing out of the water, the point behind U is
        // that thing too, up to the pass's clip (World below 0.3): the
        // thing's dry band showed as a pale halo round it in the water
        // (scenes/hard/look_down's rock). What the ray meets there is
        // hidden from the camera; the ground is not: the terrain model
        // (terrain.glsl), shaded as tarn's world program shades it.
        vec3 g = natGroundAlong(U, r);
        vec3 hg = terrainHeightGrad(g.xz);
        vec3 gn = normalize(vec3(-hg.y, 1.0, -hg.z));
        sky = false;
        path = distance(U, g);
        gRefractHit = g;
        litAt = g;
        lit = true;
        return worldShadeAt(terrainAlbedo(g.xz, hg.x, gn), gn, g);
    }
#endif
    if ((!ok || edge) && fallback) {
        shown = b0;
        uv = uv0;
        ok = ok0;
        zt = z0;
    }
    sky = !ok || zt >= NAT_SKY_DEPTH;
    path = ok ? distance(U, shown) : 1e4;
    gRefractHit = ok ? shown : vec3(0.0);
    if (!ok) return vec3(0.0);
    litAt = shown;
    lit = true;
    return texture(uRefraction, uv).rgb;
}

void main() {
    vec3 U = vWorldPos;
#if defined(WAVES_HAS_OCEAN) && defined(OCEAN_FILTER)
    // the spectrum ocean's cascades finer than the pixel filtered out
    // (waves.glsl: the horizon does not sparkle); what they held widens the
    // sun's highlight (lostVar)
    vec2 footprint = wavesFootprint(vRest);     // derivatives: in uniform control flow
    float lostVar;
    vec3 N = wavesNormalFilteredVar(vRest, uTime, footprint, lostVar);
#else
    vec2 footprint = vec2(0.0);
    vec3 N = wavesNormal(vRest, uTime);
#endif
    vec3 E = normalize(uCameraPos - U);
    vec3 n = dot(E, N) < 0.0 ? -N : N;          // faces the eye
    float cosI = clamp(dot(E, n), 0.0, 1.0);
    vec3 Rr = reflect(-E, n);
    bool under = uCameraPos.y < uWaterLevel;    // pack.glib's under_water: the passes' roles
    vec3 refr, refl, color;
    vec3 hit = vec3(0.0);
    float F, path;
    bool sky;

    // The refracted lookup, from above (the paper) and from below (the
    // passes' roles swapped: Snell's window, the refraction target holding
    // the world above) alike: one call of lookThrough for both. llvmpipe
    // runs both sides of an if for a block of pixels, even on a uniform
    // condition: written in each side, the march and its shading cost every
    // pixel twice.
    vec3 dirT = refract(-E, n, under ? uIOR : 1.0 / uIOR);   // from below: 0 on TIR
    bool tir = dot(dirT, dirT) == 0.0;
    vec2 uv0;
    bool ok0;
    float z0;
    vec3 b0 = natShownPointZ(uCamWideVP, uCameraPos, uRefractionDepth, U, uv0, ok0, z0);
    float dv = ok0 ? distance(U, b0) : 1e4;             // what lies behind U: from above the view ray's path in water
    float s0 = under ? uReflectDist * uWorldScale : clamp(dv, 0.0, uDepthClamp * uWorldScale) * uDepthScale;
    vec3 refrAt;
    bool refrLit;
    vec3 c = lookThrough(U, dirT, s0, min(1.5 * dv + 0.5 * uWorldScale, 50.0 * uWorldScale), -dv, !under, b0, uv0, ok0, z0,
                         path, sky, refrAt, refrLit);
    hit = gRefractHit;

    // The mirror target, read once for both sides: from above the
    // reflection, the paper's lookup W = U + c Rr (c fixed: exact for flat
    // water, a guess on waves, where a thing's reflection came apart: the
    // crate over grazing_sun's waves, two dark wedges where the reference
    // has one; with REFINE_STEPS the reflected ray is marched through the
    // mirror target as the refracted one is through the refraction target,
    // natMarch, from the mirrored eye: issue #24); from below the internal
    // reflection (the target then holds the world below, mirrored; c
    // fixed). The sky's cube map and the Fresnel term are read once too:
    // llvmpipe runs both sides of an `if` on a uniform for every pixel, and
    // a lookup written in each cost natural's water pass 8-12% and its
    // compile 20 ms (docs/benchmark.md, "natural's two sides in one").
    vec3 mirrorEye = vec3(uCameraPos.x, 2.0 * uWaterLevel - uCameraPos.y, uCameraPos.z);
    float cr = uReflectDist * uWorldScale;
#if REFINE_STEPS > 0
    if (!under) {
        vec2 uvm0;
        bool okm;
        float zm;
        vec3 m0 = natShownPointZ(uCamMirrorVP, mirrorEye, uReflectionDepth, U, uvm0, okm, zm);
        float dm = okm && zm < NAT_SKY_DEPTH ? distance(U, m0) : 50.0 * uWorldScale;
        bool leftm;   // the reflected ray left the mirror target: its last point in front serves
        cr = natMarch(uCamMirrorVP, mirrorEye, uReflectionDepth, U, Rr, min(1.5 * dm + 0.5 * uWorldScale, 50.0 * uWorldScale), -dm, leftm);
        // closed on a silhouette: the ray passed behind a thing (as the
        // mirrored eye sees it), not into it; what it meets there is
        // hidden from the mirror pass (the crate mirrored in open water
        // mid-lake): the paper's lookup then
        float spread;
        natNearestShown(uCamMirrorVP, mirrorEye, uReflectionDepth, U + cr * Rr, spread);
        if (spread > 1.25) cr = uReflectDist * uWorldScale;
    }
#endif
    vec2 uvm;
    bool mirrorOk;
    float mirrorZ;
    vec3 mirrorAt = natShownPointZ(uCamMirrorVP, mirrorEye, uReflectionDepth, U + cr * Rr, uvm, mirrorOk, mirrorZ);
    vec3 mirrorColor = texture(uReflection, uvm).rgb;
    // from above the reflection's sky (along Rr), from below Snell's
    // window's (along dirT: 0 on TIR, where it is not used)
    vec3 skyLook = worldSkyLook(uSky, under ? dirT : Rr);
#ifdef EXACT_FRESNEL
    F = worldFresnel(cosI, under ? uIOR : 1.0, under ? 1.0 : uIOR);
#else
    F = under && tir ? 1.0 : pow(1.0 - (under ? clamp(-dot(dirT, n), 0.0, 1.0) : cosI), uFresnelPower);
#endif

    // The caustics relight one lookup, the one under the water: from above
    // the refracted, from below the internal reflection (the refracted
    // lookup then shows the world above). One call for both: llvmpipe runs
    // every call site for every pixel, whichever side of an if it is on,
    // and three (this, the ground fallback's, the reflection's) cost 8-11
    // ms of the lake's water pass at 960x540 against one.
    gIrradiance = vec3(0.0);
    vec3 litIn = under ? mirrorColor : c;
    vec3 lit = (under ? mirrorOk : refrLit) ? applyCaustics(litIn, under ? mirrorAt : refrAt) : litIn;

    if (!under) {
        // ---- from above: the paper ----
        c = lit;
        gRefractIrradiance = gIrradiance;
#ifdef BEER_LAMBERT
        refr = attenuate(c, path);
#else
        refr = attenuate(c, dv);                         // the paper's d: the pixel's depth difference
#endif
        // Reflection. Only perturbed lookups reach the band of the widened
        // target that the camera's own view leaves out (about 1/2 (1 -
        // 1/uFovScale) of it each side): fade them into the sky over the
        // band's outer half, so no seam shows where they leave the target.
        // Where the target shows the sky or nothing (no reflection pass: only
        // sky above the water), the cube map along Rr.
        float w;
        vec2 uv = natProject(uCamMirrorVP, U + cr * Rr, w);
        float band = 0.5 * (1.0 - 1.0 / max(uFovScale, 1.0));
        float inside = min(min(uv.x, uv.y), min(1.0 - uv.x, 1.0 - uv.y));
        float keep = w <= 0.0 ? 0.0 : band > 0.0 ? clamp(inside / (0.5 * band), 0.0, 1.0) : float(inside >= 0.0);
        refl = skyLook;
        if (keep > 0.0 && mirrorZ < NAT_SKY_DEPTH) refl = mix(refl, mirrorColor, keep);
        color = refr + F * (refl - refr);
#ifdef SPECULAR
        // the sun mirrored by the facet: a lobe about the half vector. The
        // paper's lobe, s (n.H)^m E_sun, is the same at every angle: 20-50
        // times what a surface that reflects F of the light can send back,
        // large white blobs on the waves. SPECULAR_FRESNEL weighs it by F
        // and normalises it, (m + 8) / (8 pi) (Blinn-Phong's energy
        // conserving factor): a small bright glint, as the sun's own
        // reflection is, whose light does not grow with m
        vec3 H = normalize(E + uSunDir);
#if defined(WAVES_HAS_OCEAN) && defined(OCEAN_FILTER)
        float energy;
        float shin = wavesToksvig(uShininess, lostVar, energy);
        vec3 spec = uSpecular * pow(max(dot(n, H), 0.0), shin) * uSunIrradiance;
#ifdef SPECULAR_FRESNEL
        spec *= F * (shin + 8.0) / (8.0 * 3.14159265);   // normalised: its light kept as it widens
#else
        spec *= energy;
#endif
#else
        vec3 spec = uSpecular * pow(max(dot(n, H), 0.0), uShininess) * uSunIrradiance;
#ifdef SPECULAR_FRESNEL
        spec *= F * (uShininess + 8.0) / (8.0 * 3.14159265);
#endif
#endif
        color += spec;
#endif
    } else {
        // ---- from below: the roles swapped ----
        // Snell's window (dirT: out into the air); nothing on TIR
        refr = tir ? vec3(0.0) : sky ? skyLook : c;
        if (tir) {
            hit = vec3(0.0);
            gRefractIrradiance = vec3(0.0);
        }
        // the internal reflection (above: relit)
        refl = mirrorOk ? attenuate(lit, distance(U, mirrorAt)) : attenuate(vec3(0.0), 1e4);
        color = refr + F * (refl - refr);
        color = attenuate(color, distance(uCameraPos, U));   // the eye's own path in water
    }

#if defined(WAVES_HAS_OCEAN) && defined(OCEAN_FOAM)
    // the ocean's folding foam (waves_ocean.glsl): white, rough (lit
    // diffusely, no mirror), slightly translucent
    float foam = 0.85 * wavesFoamFiltered(vRest, max(footprint.x, footprint.y));
    vec3 white = 0.9 * (uSunIrradiance * max(dot(n, uSunDir), 0.0) / WORLD_PI + uAmbient);
    if (under) white *= exp(-uAbsorption * distance(uCameraPos, U));
    color = mix(color, white, foam);
#endif
#ifdef WAVES_HAS_FLOW
    // the flow's advected foam streaks (flow.glsl), lit as the ocean's foam
    float streak = flowFoam(vRest);
    vec3 foamLit = 0.9 * (uSunIrradiance * max(dot(n, uSunDir), 0.0) / WORLD_PI + uAmbient);
    if (under) foamLit *= exp(-uAbsorption * distance(uCameraPos, U));
    color = mix(color, foamLit, streak);
#endif
#ifdef DEBUG_FRESNEL
    color = vec3(F);                                     // white: reflection, black: refraction
#endif
#if DEBUG_PASS == 1
    color = refr;
#elif DEBUG_PASS == 2
    color = refl;
#elif DEBUG_PASS == 3
    color = vec3(0.5 * gCausticRatio);
#elif DEBUG_PASS == 4
    color = hit;
#elif DEBUG_PASS == 5
    color = gRefractIrradiance;
#elif DEBUG_PASS == 6
    color = vec3(under ? distance(uCameraPos, U) : path);   // the reference's `depth`: the eye's path under water
#endif
    fragColor = vec4(color, 1.0);
}
