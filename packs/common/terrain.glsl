// terrain.glsl: the terrain's model, reference/ref_scene.c's (lake_height,
// ref_terrain_gradient, ref_terrain_albedo), evaluated in a shader: tarn's
// world program shades the terrain with it per fragment, and a pack may
// ask it for the ground where its own passes could not see it (raymarch:
// under a thing under the water). Needs uWaterLevel (world.glsl or
// waves.glsl, included first). No #version here.
#ifndef TERRAIN_GLSL
#define TERRAIN_GLSL
#include "contract_terrain.glsl"
#include "hash.glsl"
#include "loops.glsl"        // ROLLED(n): loop bounds


// ref_scene.c's smoothstep, which (unlike GLSL's) allows e0 > e1.
float refSmooth(float e0, float e1, float x) {
    float t = clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

float refSmoothD(float e0, float e1, float x) {
    float t = (x - e0) / (e1 - e0);
    return t <= 0.0 || t >= 1.0 ? 0.0 : 6.0 * t * (1.0 - t) / (e1 - e0);
}

// The terrain's height over (x, z) and its gradient: (h, dh/dx, dh/dz),
// ref_terrain_height and ref_terrain_gradient. Evaluated per fragment
// rather than interpolated from the mesh, so the albedo and the normal are
// the reference's at the point the fragment shows (within the square and
// beyond it), with no texture filtering between.
vec3 terrainHeightGrad(vec2 p) {
    float depth = uTerrainShape.x, shore = uTerrainShape.y, slope = uTerrainShape.z;
    if (TERRAIN_KIND == 2) return vec3(uWaterLevel - depth + slope * (p.x + uTerrainHalfSize), slope, 0.0);
    if (TERRAIN_KIND == 3) {   // pool_height: a rounded square, walls from r 0.70 to 0.85 (POOL_WALL_*)
        vec2 e = p / uTerrainHalfSize;
        float r = sqrt(sqrt(e.x * e.x * e.x * e.x + e.y * e.y * e.y * e.y));
        float span = depth + shore, dh = span * refSmoothD(0.70, 0.85, r), r3 = r * r * r;
        vec2 g = dh != 0.0 && r3 > 1e-30 ? dh * e * e * e / (r3 * uTerrainHalfSize) : vec2(0.0);
        return vec3(uWaterLevel - depth + span * refSmooth(0.70, 0.85, r), g);
    }
    if (TERRAIN_KIND != 1) return vec3(uWaterLevel - depth, 0.0, 0.0);
    float hs = uTerrainHalfSize;
    vec2 e = vec2(p.x / hs, 1.3 * p.y / hs);
    float r = length(e);
    vec2 dr = r > 1e-12 ? vec2(e.x / (r * hs), 1.3 * e.y / (r * hs)) : vec2(0.0);
    float bowl = refSmooth(0.35, 0.95, r), bowlD = refSmoothD(0.35, 0.95, r);
    float rim = refSmooth(0.95, 1.25, r), rimD = refSmoothD(0.95, 1.25, r);
    float fade = 1.0 - rim;
    float det = 0.0;
    vec2 dg = vec2(0.0);
    for (int i = 0; i < ROLLED(6); i++) {
        vec4 d = uTerrainDetail[i];
        float ph = d.x * p.x + d.y * p.y + d.w;
        det += d.z * sin(ph);
        dg += d.z * d.xy * cos(ph);
    }
    float h = uWaterLevel - depth * (1.0 - bowl) + shore * rim + fade * det;
    float dhdr = depth * bowlD + shore * rimD - rimD * det;
    return vec3(h, dhdr * dr + fade * dg);
}

// The terrain's height for a march's check at every step, from tarn's map
// of it (uTerrainHeightMap, baked once per world from the reference's
// model; bilinear: within 0.3 mm of the lake's model, 2 mm on the pool's
// walls). On llvmpipe the lake model's six sines at each of caustic_tex's
// 24 steps were a quarter of its water pass; a branch on the terrain's
// kind that kept the cheap models cost as much again (the lake's code
// runs in every kind's frame). The map decides and guides: whether a
// step went under the ground, which half a bisection keeps, the
// fixed-point steps towards the ground along a ray, whether a point is on
// the ground (caustic_tex's model bisection and ground steps on the map:
// its frame 224 -> 202 ms, the water's error unchanged to 1e-6). Where a
// result is read off the terrain (a floor point's height, its normal and
// colour) the model's terrainHeightGrad stays.
float terrainHeightMarch(vec2 p) {
    float rest = textureLod(uTerrainHeightMap, p / uTerrainMapHalf * 0.5 + 0.5, 0.0).r;
    return rest + uTerrainMapPlane.x + dot(uTerrainMapPlane.yz, p);
}

// ref_value_noise (needs hash.glsl): hashed lattice values, quintic blend.
float terrainValueNoise(vec2 p, uint seed) {
    vec2 f = floor(p), t = p - f;
    uint i = uint(int(f.x)), j = uint(int(f.y));
    float c[4];
    for (int k = 0; k < ROLLED(4); k++)
        c[k] = float(tarnHash((i + uint(k & 1)) * 0x8da6b343u ^ tarnHash((j + uint(k >> 1)) * 0xd8163841u ^ seed)))
             / 4294967295.0;
    t = t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
    float a = mix(c[0], c[1], t.x), b = mix(c[2], c[3], t.x);
    return a + (b - a) * t.y;
}

float terrainFbm(vec2 p, float cell, uint seed) {   // 3 octaves, ref_scene.c's fbm
    float sum = 0.0, amp = 1.0, norm = 0.0;
    for (int k = 0; k < ROLLED(3); k++) {
        sum += amp * terrainValueNoise(p / cell, seed + uint(k));
        norm += amp;
        amp *= 0.5;
        cell *= 0.5;
    }
    return sum / norm;
}

// ref_scene.c's ground_noise: broad patches and close detail (lake units).
vec2 terrainGroundNoise(vec2 p) {
    float broad = terrainFbm(p, 6.0, 0x6c616e64u);
    float fade = 1.0 - refSmooth(30.0, 60.0, length(p));
    return vec2(broad, 0.5 + (terrainFbm(p, 0.6, 0x67726173u) - 0.5) * fade);
}

// ref_terrain_albedo: silt in the deep, sand at the shore, grass above,
// rock where steep, and a faint pattern.
vec3 terrainAlbedo(vec2 p, float h, vec3 n) {
    float unit = uTerrainHalfSize / 12.0;   // REF_WORLD_UNIT: a scaled world's colours scale with it
    if (TERRAIN_KIND == 3) {   // pool_albedo: 0.5 m tiles in a checker, 0.04 m grout, a stone deck
        if (h > uWaterLevel + 0.5 * uTerrainShape.y) {
            if (TERRAIN_GROUND_DETAIL <= 0.0) return vec3(0.55, 0.52, 0.47);
            // ground_detail_albedo: a stone deck, a lawn beyond r 1.15 (POOL_DECK_OUT)
            vec2 e = p / uTerrainHalfSize, q = p / unit, gn = terrainGroundNoise(q);
            float g = TERRAIN_GROUND_DETAIL;
            if (sqrt(sqrt(e.x * e.x * e.x * e.x + e.y * e.y * e.y * e.y)) <= 1.15)
                return vec3(0.55, 0.52, 0.47) * (1.0 + g * 0.5 * (gn.y - 0.5));
            vec3 c = mix(vec3(0.20, 0.38, 0.12), vec3(0.38, 0.42, 0.18), g * refSmooth(0.35, 0.75, gn.x));
            return c * (1.0 + g * 0.8 * (gn.y - 0.5));
        }
        vec2 t = p / (unit * 0.5), f = t - floor(t);
        float g = 0.5 * 0.04 / 0.5, sum = floor(t.x) + floor(t.y), odd = sum - 2.0 * floor(0.5 * sum);
        if (f.x < g || f.x > 1.0 - g || f.y < g || f.y > 1.0 - g) return vec3(0.05, 0.05, 0.06);
        return odd > 0.5 ? vec3(0.08, 0.22, 0.42) : vec3(0.80, 0.84, 0.86);
    }
    p /= unit;
    const vec3 silt = vec3(0.30, 0.28, 0.20), sand = vec3(0.76, 0.68, 0.50);
    const vec3 grass = vec3(0.22, 0.40, 0.14), rock = vec3(0.42, 0.40, 0.37);
    float y = (h - uWaterLevel) / unit, g = TERRAIN_GROUND_DETAIL;
    vec2 gn = g > 0.0 ? terrainGroundNoise(p) : vec2(0.5);
    float hy = y + g * 0.3 * (gn.x - 0.5), ny = n.y + g * 0.12 * (gn.y - 0.5);
    vec3 c = mix(silt, sand, refSmooth(-1.6, -0.4, y));
    vec3 gr = mix(grass, vec3(0.38, 0.42, 0.18), g * refSmooth(0.35, 0.75, gn.x));
    c = mix(c, gr, refSmooth(0.15, 0.35, hy));
    c = mix(c, rock, refSmooth(0.80, 0.65, ny));
    float stripes = 0.06 * sin(3.1 * p.x + 1.7 * sin(0.9 * p.y)) * sin(2.3 * p.y + 1.3 * sin(0.7 * p.x));
    return c * (1.0 + stripes + g * 0.6 * (gn.y - 0.5));
}

#endif // TERRAIN_GLSL
