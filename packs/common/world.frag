#version 330 compatibility
#include "waves.glsl"
#include "world.glsl"

uniform sampler2D uTerrainAlbedo;
uniform samplerCube uSky;
// 0 terrain (the terrain's model, below), 1 object, 2 sky. tarn compiles one
// program per mode (WORLD_MODE defined), so a pixel runs only its own
// branch: llvmpipe runs both sides of an `if` on a uniform.
#ifdef WORLD_MODE
const int uWorldMode = WORLD_MODE;
#else
uniform int uWorldMode;
#endif
uniform vec3 uWorldAlbedo;      // objects: one albedo each
uniform vec3 uCameraPos;        // the eye of the current camera
uniform bool uWorldEyePath;     // drawn to the screen: attenuate along the eye's path in water
// The terrain's model, reference/ref_scene.c's (lake_height, ref_terrain_albedo):
uniform int uTerrainKind;       // REF_TERRAIN_*: 0 flat, 1 lake, 2 slope, 3 pool
uniform vec4 uTerrainShape;     // depth, shore height, slope, -
uniform vec4 uTerrainDetail[6]; // the lake's detail: k.x, k.z, amplitude, phase (REF_TERRAIN_DETAIL)
uniform float uTerrainHalfSize;
in vec3 vWorldPos;
in vec3 vWorldNormal;
in vec2 vST;
out vec4 fragColor;

// The length of the segment eye -> p that lies under the mean water level
// (the reference's eye path in water: it fades what an eye under the water
// sees by exp(-sigma s), with no in-scattering).
float eyePathInWater(vec3 eye, vec3 p) {
    float d = distance(eye, p);
    if (eye.y >= uWaterLevel) return 0.0;   // from above, the water surface is drawn over it
    if (p.y <= uWaterLevel) return d;
    return d * (uWaterLevel - eye.y) / max(p.y - eye.y, 1e-6);
}

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
    if (uTerrainKind == 2) return vec3(uWaterLevel - depth + slope * (p.x + uTerrainHalfSize), slope, 0.0);
    if (uTerrainKind == 3) {   // pool_height: a rounded square, walls from r 0.70 to 0.85 (POOL_WALL_*)
        vec2 e = p / uTerrainHalfSize;
        float r = sqrt(sqrt(e.x * e.x * e.x * e.x + e.y * e.y * e.y * e.y));
        float span = depth + shore, dh = span * refSmoothD(0.70, 0.85, r), r3 = r * r * r;
        vec2 g = dh != 0.0 && r3 > 1e-30 ? dh * e * e * e / (r3 * uTerrainHalfSize) : vec2(0.0);
        return vec3(uWaterLevel - depth + span * refSmooth(0.70, 0.85, r), g);
    }
    if (uTerrainKind != 1) return vec3(uWaterLevel - depth, 0.0, 0.0);
    float hs = uTerrainHalfSize;
    vec2 e = vec2(p.x / hs, 1.3 * p.y / hs);
    float r = length(e);
    vec2 dr = r > 1e-12 ? vec2(e.x / (r * hs), 1.3 * e.y / (r * hs)) : vec2(0.0);
    float bowl = refSmooth(0.35, 0.95, r), bowlD = refSmoothD(0.35, 0.95, r);
    float rim = refSmooth(0.95, 1.25, r), rimD = refSmoothD(0.95, 1.25, r);
    float fade = 1.0 - rim;
    float det = 0.0;
    vec2 dg = vec2(0.0);
    for (int i = 0; i < 6; i++) {
        vec4 d = uTerrainDetail[i];
        float ph = d.x * p.x + d.y * p.y + d.w;
        det += d.z * sin(ph);
        dg += d.z * d.xy * cos(ph);
    }
    float h = uWaterLevel - depth * (1.0 - bowl) + shore * rim + fade * det;
    float dhdr = depth * bowlD + shore * rimD - rimD * det;
    return vec3(h, dhdr * dr + fade * dg);
}

// ref_terrain_albedo: silt in the deep, sand at the shore, grass above,
// rock where steep, and a faint pattern.
vec3 terrainAlbedo(vec2 p, float h, vec3 n) {
    float unit = uTerrainHalfSize / 12.0;   // REF_WORLD_UNIT: a scaled world's colours scale with it
    if (uTerrainKind == 3) {   // pool_albedo: 0.5 m tiles in a checker, 0.04 m grout, a stone deck
        if (h > uWaterLevel + 0.5 * uTerrainShape.y) return vec3(0.55, 0.52, 0.47);
        vec2 t = p / (unit * 0.5), f = t - floor(t);
        float g = 0.5 * 0.04 / 0.5, sum = floor(t.x) + floor(t.y), odd = sum - 2.0 * floor(0.5 * sum);
        if (f.x < g || f.x > 1.0 - g || f.y < g || f.y > 1.0 - g) return vec3(0.05, 0.05, 0.06);
        return odd > 0.5 ? vec3(0.08, 0.22, 0.42) : vec3(0.80, 0.84, 0.86);
    }
    p /= unit;
    const vec3 silt = vec3(0.30, 0.28, 0.20), sand = vec3(0.76, 0.68, 0.50);
    const vec3 grass = vec3(0.22, 0.40, 0.14), rock = vec3(0.42, 0.40, 0.37);
    float y = (h - uWaterLevel) / unit;
    vec3 c = mix(silt, sand, refSmooth(-1.6, -0.4, y));
    c = mix(c, grass, refSmooth(0.15, 0.35, y));
    c = mix(c, rock, refSmooth(0.80, 0.65, n.y));
    float stripes = 0.06 * sin(3.1 * p.x + 1.7 * sin(0.9 * p.y)) * sin(2.3 * p.y + 1.3 * sin(0.7 * p.x));
    return c * (1.0 + stripes);
}

// Is p under the water surface at this time? Below the mean level is not
// enough: where a trough uncovers the shore, the reference's ray meets the
// land in air and lights it dry (its shading follows the path, not the
// mean level). Within the waves' height bound of the level (waves.glsl's
// sum of amplitudes; gradient noise stays within 0.75 of its amplitude)
// the surface's height is read from tarn's map of it this frame
// (WORLD_HEIGHT_MAP, world_height.frag), or else solved for here: on a
// CPU rasteriser every pixel pays for that solve, wet or dry.
uniform float uTime;
#ifdef WORLD_HEIGHT_MAP
uniform sampler2D uWaveHeight;     // the surface's height over the world (set by tarn)
uniform float uWaveHeightHalf;     // it covers x, z in [-half, half]
#endif
bool worldUnderWater(vec3 p) {
    if (p.y >= uWaterLevel) return false;
    float bound = 0.0;
    for (int i = 0; i < WAVES_MAX; i++) {
        if (i < uSineCount) bound += abs(uSineAmp[i]);
        if (i < uGerstnerCount) bound += abs(uGerstnerAmp[i]);
    }
    int octaves = uNoiseOctaves > 0 ? uNoiseOctaves : 4;
    float gain = uNoiseGain > 0.0 ? uNoiseGain : 0.5, a = abs(uNoiseAmp);
    for (int o = 0; o < WAVES_NOISE_OCTAVES_MAX; o++) {
        if (o >= octaves) break;
        bound += 0.75 * a;
        a *= gain;
    }
    if (p.y < uWaterLevel - bound) return true;
#ifdef WORLD_HEIGHT_MAP
    // the surface's height from tarn's map of it this frame (world_height.frag);
    // beyond the map, the mean level
    vec2 uv = p.xz / uWaveHeightHalf * 0.5 + 0.5;
    float h = all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)))
            ? texture(uWaveHeight, uv).r : uWaterLevel;
    return p.y < h;
#else
    return p.y < wavesHeightAt(p.xz, uTime);
#endif
}

void main() {
    vec3 c;
    if (uWorldMode == 2) {
        c = texture(uSky, normalize(vWorldNormal)).rgb;
    } else if (uWorldMode == 0) {
        vec3 hg = terrainHeightGrad(vWorldPos.xz);
        vec3 n = normalize(vec3(-hg.y, 1.0, -hg.z));
        vec3 albedo = terrainAlbedo(vWorldPos.xz, hg.x, n);
        c = worldUnderWater(vWorldPos) ? worldShadeAt(albedo, n, vWorldPos) : worldLambert(albedo, n, vec3(1.0));
    } else {
        vec3 n = normalize(vWorldNormal);
        c = worldUnderWater(vWorldPos) ? worldShadeAt(uWorldAlbedo, n, vWorldPos)
                                       : worldLambert(uWorldAlbedo, n, vec3(1.0));
    }
    if (uWorldEyePath) c *= exp(-uAbsorption * eyePathInWater(uCameraPos, vWorldPos));
    fragColor = vec4(c, 1.0);
}
