#include "ref_scene.h"
#include "strbuf.h"

#include <math.h>
#include <stdbool.h>
#include <string.h>

#include "ref_hash.h"
#include "ref_mesh.h"
#include "ref_trace.h"
#include "vec3.h"

#define PI 3.14159265358979323846
/* the pool (world.frag has the same numbers): its walls between these
 * radii (units of the half size), tiles and grout in the lake's metres */
#define POOL_WALL_IN 0.70
#define POOL_WALL_OUT 0.85
#define POOL_TILE 0.5
#define POOL_GROUT 0.04
#define POOL_DECK_OUT 1.15   /* GroundDetail: the deck's outer edge, a lawn beyond */

static double smoothstep(double e0, double e1, double x) {
    double t = (x - e0) / (e1 - e0);
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return t * t * (3 - 2 * t);
}

/* d/dx smoothstep(e0, e1, x) */
static double smoothstep_d(double e0, double e1, double x) {
    double t = (x - e0) / (e1 - e0);
    if (t <= 0 || t >= 1) return 0;
    return 6 * t * (1 - t) / (e1 - e0);
}

static void default3(double v[3], double a, double b, double c) {
    if (v[0] == 0 && v[1] == 0 && v[2] == 0) { v[0] = a; v[1] = b; v[2] = c; }
}

/* The mesh objects' triangles, placed (ref_mesh.h); a file that fails here
 * was reported where the scene named it (viewer/scene/scene.c). */
static void load_meshes(ref_world *w) {
    for (int i = 0; i < w->d.nobjects; i++) {
        const ref_object *ob = &w->d.objects[i];
        if (ob->kind != REF_OBJECT_MESH) continue;
        ref_mesh_place pl = { { ob->center[0], ob->center[1], ob->center[2] }, ob->rot_y_deg, ob->size[0] };
        char err[MSG_MAX];
        w->meshes[i] = ref_mesh_load(ob->mesh_path, &pl, err, sizeof err);
    }
}

void ref_world_init(ref_world *w, const ref_world_desc *d) {
    memset(w, 0, sizeof *w);
    if (d) w->d = *d;
    ref_world_desc *s = &w->d;
    default3(s->sun_dir, 0.4, 0.8, -0.45);
    vec3_normalize(s->sun_dir);
    default3(s->sun_irradiance, 2.2, 2.1, 1.9);
    default3(s->sky_zenith, 0.25, 0.45, 0.85);
    default3(s->sky_horizon, 0.70, 0.80, 0.92);
    default3(s->absorption, 0.45, 0.09, 0.06);
    if (s->ior <= 0) s->ior = 1.333;
    if (s->water_mesh_res <= 0) s->water_mesh_res = 256;
    if (s->half_size <= 0) s->half_size = 12;
    if (s->depth <= 0) s->depth = 3;
    if (s->shore_height <= 0) s->shore_height = 0.6;
    if (s->slope == 0) s->slope = 0.25;
    if (s->terrain_res <= 0) s->terrain_res = 256;
    if (s->nobjects < 0) s->nobjects = 0;
    if (s->nobjects > REF_MAX_OBJECTS) s->nobjects = REF_MAX_OBJECTS;
    /* what the sky gives a horizontal surface, roughly: half its mean radiance
     * (the lower hemisphere sees ground, not sky) */
    for (int i = 0; i < 3; i++) w->ambient[i] = 0.25 * (s->sky_zenith[i] + s->sky_horizon[i]);
    s->waves.level = s->water_level;
    char err[MSG_MAX];
    if (ref_waves_init(&w->waves, &s->waves, err, sizeof err) != 0) {
        ref_waves_desc calm;
        memset(&calm, 0, sizeof calm);
        calm.level = s->water_level;
        ref_waves_init(&w->waves, &calm, err, sizeof err);
    }
    /* the lake's bottom detail: deterministic from the seed, its
     * wavelengths (like its amplitudes, which follow the depth) in
     * proportion to the world: a lake of half size 1200 is the 12 m lake
     * scaled, not one with 0.8 m ripples on 9 m mesh cells that neither a
     * mesh nor a pixel resolves */
    uint64_t state = 0x9e3779b97f4a7c15ull ^ (uint64_t)s->seed;
    double k_scale = REF_WORLD_UNIT / s->half_size;
    double bound = 0;
    for (int i = 0; i < REF_TERRAIN_DETAIL; i++) {
        double u1 = (double)(ref_splitmix64(&state) >> 11) / 9007199254740992.0;
        double u2 = (double)(ref_splitmix64(&state) >> 11) / 9007199254740992.0;
        double u3 = (double)(ref_splitmix64(&state) >> 11) / 9007199254740992.0;
        double angle = 2 * PI * u1, k = 0.35 * pow(1.8, i) * (0.8 + 0.4 * u2) * k_scale;
        w->detail_k[i][0] = k * cos(angle);
        w->detail_k[i][1] = k * sin(angle);
        w->detail_a[i] = 0.12 * s->depth / pow(1.9, i) / 3.0;
        w->detail_phi[i] = 2 * PI * u3;
        bound += w->detail_a[i] * k;
    }
    /* bowl slope bound: depth * max smoothstep' over the radius, with the
     * 1.3 squeeze in z; shore term likewise */
    double r_scale = 1.3 / s->half_size;
    bound += (s->depth * 1.5 / 0.6 + s->shore_height * 1.5 / 0.3) * r_scale;
    if (s->terrain == REF_TERRAIN_SLOPE) bound = fabs(s->slope);
    /* the pool's walls: (depth + rim) * max smoothstep' over the wall's
     * width, |grad r| <= 1 / half_size (pool_radius) */
    if (s->terrain == REF_TERRAIN_POOL)
        bound = (s->depth + s->shore_height) * 1.5 / (POOL_WALL_OUT - POOL_WALL_IN) / s->half_size;
    if (s->terrain == REF_TERRAIN_FLAT) bound = 0;
    w->terrain_slope_bound = bound;
    load_meshes(w);
}

void ref_world_release(ref_world *w) {
    if (!w) return;
    ref_waves_release(&w->waves);
    for (int i = 0; i < REF_MAX_OBJECTS; i++) {
        ref_mesh_free(w->meshes[i]);
        w->meshes[i] = NULL;
    }
}

/* The lake: r is an elliptic radius in [0, ~1.4]; the bottom is flat-ish
 * below r = 0.35, rises to the water line near r = 0.95 and the shore goes
 * on rising to shore_height at the rim; the detail fades out on land. */
static double lake_radius(const ref_world *w, double x, double z, double dr[2]) {
    double hs = w->d.half_size;
    double ex = x / hs, ez = 1.3 * z / hs;
    double r = sqrt(ex * ex + ez * ez);
    if (dr) {
        if (r > 1e-12) { dr[0] = ex / (r * hs); dr[1] = 1.3 * ez / (r * hs); }
        else dr[0] = dr[1] = 0;
    }
    return r;
}

static double detail(const ref_world *w, double x, double z, double grad[2]) {
    double h = 0;
    if (grad) grad[0] = grad[1] = 0;
    for (int i = 0; i < REF_TERRAIN_DETAIL; i++) {
        double ph = w->detail_k[i][0] * x + w->detail_k[i][1] * z + w->detail_phi[i];
        h += w->detail_a[i] * sin(ph);
        if (grad) {
            grad[0] += w->detail_a[i] * w->detail_k[i][0] * cos(ph);
            grad[1] += w->detail_a[i] * w->detail_k[i][1] * cos(ph);
        }
    }
    return h;
}

static double lake_height(const ref_world *w, double x, double z, double grad[2]) {
    const ref_world_desc *s = &w->d;
    double dr[2], dg[2];
    double r = lake_radius(w, x, z, dr);
    double bowl = smoothstep(0.35, 0.95, r), bowl_d = smoothstep_d(0.35, 0.95, r);
    double rim = smoothstep(0.95, 1.25, r), rim_d = smoothstep_d(0.95, 1.25, r);
    double fade = 1.0 - rim;                         /* the detail fades on land */
    /* its sines (and their cosines only for a gradient) where they count:
     * past the rim fade and rim_d are 0, and so are their terms */
    double det = fade > 0 || grad ? detail(w, x, z, grad ? dg : NULL) : 0.0;
    double h = s->water_level - s->depth * (1.0 - bowl) + s->shore_height * rim + fade * det;
    if (grad) {
        double dh_dr = s->depth * bowl_d + s->shore_height * rim_d - rim_d * det;
        grad[0] = dh_dr * dr[0] + fade * dg[0];
        grad[1] = dh_dr * dr[1] + fade * dg[1];
    }
    return h;
}

/* The pool: r = (ex^4 + ez^4)^(1/4), a rounded square in units of the half
 * size, so the floor is flat (r < POOL_WALL_IN), the walls rise with a
 * smoothstep to the deck at level + shore_height (r > POOL_WALL_OUT), and the
 * whole is C1 (r is C1 away from 0, and the floor is flat there). Its
 * gradient (ex^3, ez^3) / (r^3 hs) has length <= 1 / hs. */
static double pool_height(const ref_world *w, double x, double z, double grad[2]) {
    const ref_world_desc *s = &w->d;
    double hs = s->half_size, ex = x / hs, ez = z / hs;
    double r4 = ex * ex * ex * ex + ez * ez * ez * ez, r = sqrt(sqrt(r4));
    double span = s->depth + s->shore_height;
    double h = s->water_level - s->depth + span * smoothstep(POOL_WALL_IN, POOL_WALL_OUT, r);
    if (grad) {
        double dh = span * smoothstep_d(POOL_WALL_IN, POOL_WALL_OUT, r);
        double r3 = r * r * r;
        if (dh != 0 && r3 > 1e-30) {
            grad[0] = dh * ex * ex * ex / (r3 * hs);
            grad[1] = dh * ez * ez * ez / (r3 * hs);
        } else {
            grad[0] = grad[1] = 0;
        }
    }
    return h;
}

static double pool_radius(const ref_world *w, double x, double z) {
    double ex = x / w->d.half_size, ez = z / w->d.half_size;
    return sqrt(sqrt(ex * ex * ex * ex + ez * ez * ez * ez));
}

static void mix3(const double a[3], const double b[3], double t, double out[3]);
static void ground_detail_albedo(const ref_world *w, double x, double z, int lawn, double rgb[3]);
static void ground_noise(double x, double z, double *broad, double *close);

double ref_terrain_height(const ref_world *w, double x, double z) {
    switch (w->d.terrain) {
    case REF_TERRAIN_LAKE: return lake_height(w, x, z, NULL);
    case REF_TERRAIN_POOL: return pool_height(w, x, z, NULL);
    case REF_TERRAIN_SLOPE: return w->d.water_level - w->d.depth + w->d.slope * (x + w->d.half_size);
    default: return w->d.water_level - w->d.depth;
    }
}

void ref_terrain_gradient(const ref_world *w, double x, double z, double grad[2]) {
    switch (w->d.terrain) {
    case REF_TERRAIN_LAKE: lake_height(w, x, z, grad); break;
    case REF_TERRAIN_POOL: pool_height(w, x, z, grad); break;
    case REF_TERRAIN_SLOPE: grad[0] = w->d.slope; grad[1] = 0; break;
    default: grad[0] = grad[1] = 0; break;
    }
}

void ref_terrain_normal_at(const ref_world *w, double x, double z, double n[3]) {
    double g[2];
    ref_terrain_gradient(w, x, z, g);
    n[0] = -g[0];
    n[1] = 1.0;
    n[2] = -g[1];
    vec3_normalize(n);
}

static void mix3(const double a[3], const double b[3], double t, double out[3]) {
    for (int i = 0; i < 3; i++) out[i] = a[i] + (b[i] - a[i]) * t;
}

/* ---- the world's look (issue #25) ---- */

double ref_value_noise(double x, double z, unsigned seed) {
    double fx = floor(x), fz = floor(z), u = x - fx, v = z - fz;
    uint32_t i = (uint32_t)(int32_t)fx, j = (uint32_t)(int32_t)fz, c[4];
    for (int k = 0; k < 4; k++)
        c[k] = ref_hash32((i + (uint32_t)(k & 1)) * 0x8da6b343U ^
                          ref_hash32((j + (uint32_t)(k >> 1)) * 0xd8163841U ^ seed));
    u = u * u * u * (u * (u * 6 - 15) + 10);
    v = v * v * v * (v * (v * 6 - 15) + 10);
    double a = c[0] / 4294967295.0, b = c[1] / 4294967295.0, e = c[2] / 4294967295.0, f = c[3] / 4294967295.0;
    return (a + (b - a) * u) + ((e + (f - e) * u) - (a + (b - a) * u)) * v;
}

/* fbm of value noise over `octaves`, the first of cell size `cell`, each
 * half the last; normalised to [0, 1] (mean 0.5) */
static double fbm(double x, double z, double cell, int octaves, unsigned seed) {
    double sum = 0, amp = 1, norm = 0;
    for (int k = 0; k < octaves; k++) {
        sum += amp * ref_value_noise(x / cell, z / cell, seed + (unsigned)k);
        norm += amp;
        amp *= 0.5;
        cell *= 0.5;
    }
    return sum / norm;
}

/* GroundDetail's two noises at (x, z) in the lake's units: broad patches
 * (cells of 6 m) and close detail (0.6 m, faded out from 30 to 60 m off the
 * centre, where a pixel spans many of its cells and it would only alias);
 * terrain.glsl's terrainGroundNoise is the same */
static void ground_noise(double x, double z, double *broad, double *close) {
    *broad = fbm(x, z, 6.0, 3, 0x6c616e64u);
    double fade = 1.0 - smoothstep(30.0, 60.0, sqrt(x * x + z * z));
    *close = 0.5 + (fbm(x, z, 0.6, 3, 0x67726173u) - 0.5) * fade;
}

/* The pool's lawn and deck with GroundDetail (x, z in the lake's units). */
static void ground_detail_albedo(const ref_world *w, double x, double z, int lawn, double rgb[3]) {
    static const double stone[3] = { 0.55, 0.52, 0.47 }, grass[3] = { 0.20, 0.38, 0.12 },
                        dry[3] = { 0.38, 0.42, 0.18 };
    double g = w->d.ground_detail, broad, close;
    ground_noise(x, z, &broad, &close);
    if (!lawn) {
        for (int i = 0; i < 3; i++) rgb[i] = stone[i] * (1.0 + g * 0.5 * (close - 0.5));
        return;
    }
    double c[3];
    mix3(grass, dry, g * smoothstep(0.35, 0.75, broad), c);
    for (int i = 0; i < 3; i++) rgb[i] = c[i] * (1.0 + g * 0.8 * (close - 0.5));
}

void ref_haze(const ref_world *w, double dist, double rgb[3]) {
    if (!(w->d.haze_distance > 0) || !(dist > 0)) return;
    double f = 1.0 - exp(-dist / (w->d.haze_distance * ref_world_scale(w)));
    for (int i = 0; i < 3; i++) rgb[i] += (w->d.sky_horizon[i] - rgb[i]) * f;
}

/* The pool's tiles: light and dark squares of POOL_TILE m (lake units) in a
 * checker, with dark grout lines POOL_GROUT wide, under the deck; the deck
 * plain stone. Strong contrast at the scale of a refraction hit's error (cm
 * to dm), so an error in where the refracted ray meets the floor becomes an
 * error in colour. The edges are hard: the GL world (world.frag, the same
 * formula in float) and the reference both sample one point per pixel
 * centre, so a pixel's colour flips only where the two points straddle an
 * edge; the comparison masks nothing there. */
static void pool_albedo(const ref_world *w, double x, double z, double rgb[3]) {
    static const double light[3] = { 0.80, 0.84, 0.86 }, dark[3] = { 0.08, 0.22, 0.42 },
                        grout[3] = { 0.05, 0.05, 0.06 }, deck[3] = { 0.55, 0.52, 0.47 };
    double unit = w->d.half_size / REF_WORLD_UNIT;
    const double *c;
    if (ref_terrain_height(w, x, z) > w->d.water_level + 0.5 * w->d.shore_height) {
        c = deck;
        if (w->d.ground_detail > 0) {   /* a stone deck round the pool, a lawn beyond it */
            ground_detail_albedo(w, x / unit, z / unit, pool_radius(w, x, z) > POOL_DECK_OUT, rgb);
            return;
        }
    } else {
        double u = x / (unit * POOL_TILE), v = z / (unit * POOL_TILE);
        double fu = u - floor(u), fv = v - floor(v), g = 0.5 * POOL_GROUT / POOL_TILE;
        double sum = floor(u) + floor(v), odd = sum - 2.0 * floor(0.5 * sum);
        if (fu < g || fu > 1.0 - g || fv < g || fv > 1.0 - g) c = grout;
        else c = odd > 0.5 ? dark : light;
    }
    for (int i = 0; i < 3; i++) rgb[i] = c[i];
}

void ref_terrain_albedo(const ref_world *w, double x, double z, double rgb[3]) {
    if (w->d.terrain == REF_TERRAIN_POOL) {
        pool_albedo(w, x, z, rgb);
        return;
    }
    static const double silt[3] = { 0.30, 0.28, 0.20 }, sand[3] = { 0.76, 0.68, 0.50 },
                        grass[3] = { 0.22, 0.40, 0.14 }, rock[3] = { 0.42, 0.40, 0.37 };
    /* heights and the pattern in the lake's units (half size 12), so a
     * scaled world has the scaled colours: its bands and stripes stay as
     * many pixels wide, and a pixel never spans many stripes */
    double unit = w->d.half_size / REF_WORLD_UNIT;
    double h = (ref_terrain_height(w, x, z) - w->d.water_level) / unit;
    double n[3];
    ref_terrain_normal_at(w, x, z, n);
    double c[3];
    x /= unit;
    z /= unit;
    double g = w->d.ground_detail, broad = 0.5, close = 0.5;
    if (g > 0) ground_noise(x, z, &broad, &close);
    /* GroundDetail: the beach's edge and the rock's slope wander with the
     * noise, the grass dries in patches and every colour varies close up */
    double hy = h + g * 0.3 * (broad - 0.5), ny = n[1] + g * 0.12 * (close - 0.5);
    mix3(silt, sand, smoothstep(-1.6, -0.4, h), c);          /* deep silt to shallow sand */
    if (g > 0) {
        static const double dry[3] = { 0.38, 0.42, 0.18 };
        double gr[3];
        mix3(grass, dry, g * smoothstep(0.35, 0.75, broad), gr);
        mix3(c, gr, smoothstep(0.15, 0.35, hy), c);
    } else {
        mix3(c, grass, smoothstep(0.15, 0.35, h), c);        /* grass above the beach */
    }
    mix3(c, rock, smoothstep(0.80, 0.65, ny), c);            /* rock where it is steep */
    /* a faint pattern so perturbed lookups show: ripples of the detail */
    double stripes = 0.06 * sin(3.1 * x + 1.7 * sin(0.9 * z)) * sin(2.3 * z + 1.3 * sin(0.7 * x));
    double grain = g * 0.6 * (close - 0.5);
    for (int i = 0; i < 3; i++) rgb[i] = c[i] * (1.0 + stripes + grain);
}

/* Clouds along dir: the cover (0..1) and the clouds' own radiance. */
static double clouds(const ref_world *w, const double dir[3], double crgb[3]) {
    const ref_world_desc *s = &w->d;
    double fade = smoothstep(0.02, 0.25, dir[1]);   /* thinning into the horizon's haze */
    if (!(s->cloud_cover > 0) || fade <= 0) return 0;
    double scale = s->cloud_scale > 0 ? s->cloud_scale : 600, height = s->cloud_height > 0 ? s->cloud_height : 1500;
    double k = height / dir[1] / scale, x = dir[0] * k, z = dir[2] * k;
    /* octaves turned against each other, so no lattice lines show; each
     * fades to its mean where its features, seen foreshortened, span under
     * 3-6 texels of the GL side's cube map (0.003 rad): towards the horizon
     * they shrink below any pixel, and a point sample of them is noise */
    double sum = 0, amp = 1, norm = 0, ca = cos(0.61), sa = sin(0.61);
    double angle = scale * dir[1] * dir[1] / height;   /* the first octave's cell, in radians */
    for (int o = 0; o < 6; o++) {
        double keep = smoothstep(0.01, 0.02, angle);
        angle /= 2.03;
        sum += amp * (0.5 + keep * (ref_value_noise(x, z, 0x636c6f75u + (unsigned)o) - 0.5));
        norm += amp;
        double nx = 2.03 * (ca * x - sa * z), nz = 2.03 * (sa * x + ca * z);
        x = nx;
        z = nz;
        amp *= 0.5;
    }
    double d = 0.5 + 2.2 * (sum / norm - 0.5), thr = 1.0 - s->cloud_cover;   /* fbm's spread is narrow */
    double alpha = smoothstep(thr - 0.2, thr + 0.2, d) * fade;
    double thick = smoothstep(thr, thr + 0.35, d);
    double c = dir[0] * s->sun_dir[0] + dir[1] * s->sun_dir[1] + dir[2] * s->sun_dir[2];
    double lit = 0.95 - 0.45 * thick + 0.6 * pow(c > 0 ? c : 0, 8.0) * (1.0 - thick);   /* silver lining */
    for (int i = 0; i < 3; i++) crgb[i] = s->sun_irradiance[i] / PI * lit + 0.9 * w->ambient[i];
    return alpha;
}

void ref_sky_smooth(const ref_world *w, const double dir[3], double rgb[3], double *clear) {
    const ref_world_desc *s = &w->d;
    double y = dir[1];
    if (y >= 0) {
        double t = pow(y, 0.6);
        mix3(s->sky_horizon, s->sky_zenith, t, rgb);
    } else {   /* below the horizon: a dim ground, continuous at y = 0 */
        static const double ground[3] = { 0.18, 0.17, 0.15 };
        mix3(s->sky_horizon, ground, smoothstep(0.0, 0.15, -y), rgb);
    }
    double c = dir[0] * s->sun_dir[0] + dir[1] * s->sun_dir[1] + dir[2] * s->sun_dir[2];
    if (c > 0) {   /* a smooth glow, not a disc: it stays band-limited for image metrics */
        double glow = 0.6 * pow(c, 64.0) + 0.25 * pow(c, 8.0);
        for (int i = 0; i < 3; i++) rgb[i] += glow * s->sun_irradiance[i] / 3.0;
    }
    double crgb[3], a = clouds(w, dir, crgb);
    if (a > 0) mix3(rgb, crgb, a, rgb);
    if (clear) *clear = 1.0 - a;
}

void ref_sun_disc(const ref_world *w, const double dir[3], double rgb[3]) {
    const ref_world_desc *s = &w->d;
    rgb[0] = rgb[1] = rgb[2] = 0;
    if (!(s->sun_disc_deg > 0)) return;
    double dd[3] = { dir[0] - s->sun_dir[0], dir[1] - s->sun_dir[1], dir[2] - s->sun_dir[2] };
    double half = 0.5 * sqrt(dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2]);
    double a = 2.0 * asin(half < 1 ? half : 1), x = a / (s->sun_disc_deg * PI / 180.0);
    if (x > 40) return;
    double core = (1.0 - smoothstep(0.75, 1.25, x)) * (1.0 - 0.35 * (x < 1 ? x * x : 1.0));
    double aureole = 0.015 * exp(-0.5 * (x > 1 ? x - 1 : 0));
    double gain = s->sun_disc_gain > 0 ? s->sun_disc_gain : 20;
    for (int i = 0; i < 3; i++) rgb[i] = s->sun_irradiance[i] / 3.0 * gain * (core + aureole);
}

void ref_sky_radiance(const ref_world *w, const double dir[3], double rgb[3]) {
    double clear, disc[3];
    ref_sky_smooth(w, dir, rgb, &clear);
    ref_sun_disc(w, dir, disc);
    for (int i = 0; i < 3; i++) rgb[i] += clear * disc[i];
}

void ref_shade_lambert(const ref_world *w, const double albedo[3], const double n[3],
                       double sun_scale, double rgb[3]) {
    const double *l = w->d.sun_dir;
    double c = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
    if (c < 0) c = 0;
    for (int i = 0; i < 3; i++)
        rgb[i] = albedo[i] * (w->d.sun_irradiance[i] * c * sun_scale / PI + w->ambient[i]);
}

/* ---- objects ---- */

static bool hit_sphere(const ref_object *ob, const double o[3], const double d[3], double tmin,
                       double tmax, double *t, double n[3]) {
    double oc[3] = { o[0] - ob->center[0], o[1] - ob->center[1], o[2] - ob->center[2] };
    double b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
    double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    double c = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - ob->size[0] * ob->size[0];
    double disc = b * b - dd * c;
    if (disc < 0) return false;
    double sq = sqrt(disc);
    double ts[2] = { (-b - sq) / dd, (-b + sq) / dd };
    for (int k = 0; k < 2; k++) {
        if (ts[k] > tmin && ts[k] < tmax) {
            *t = ts[k];
            for (int i = 0; i < 3; i++) n[i] = (oc[i] + ts[k] * d[i]) / ob->size[0];
            return true;
        }
    }
    return false;
}

static bool hit_box(const ref_object *ob, const double o[3], const double d[3], double tmin,
                    double tmax, double *t, double n[3]) {
    double t0 = -INFINITY, t1 = INFINITY;
    int axis0 = 0, axis1 = 0;
    for (int a = 0; a < 3; a++) {
        double lo = ob->center[a] - ob->size[a], hi = ob->center[a] + ob->size[a];
        if (fabs(d[a]) < 1e-300) {
            if (o[a] < lo || o[a] > hi) return false;
            continue;
        }
        double ta = (lo - o[a]) / d[a], tb = (hi - o[a]) / d[a];
        if (ta > tb) { double tmp = ta; ta = tb; tb = tmp; }
        if (ta > t0) { t0 = ta; axis0 = a; }
        if (tb < t1) { t1 = tb; axis1 = a; }
    }
    if (t0 > t1) return false;
    double th = t0 > tmin ? t0 : t1;
    int axis = t0 > tmin ? axis0 : axis1;
    if (th <= tmin || th >= tmax) return false;
    *t = th;
    n[0] = n[1] = n[2] = 0;
    double p = o[axis] + th * d[axis];
    n[axis] = p > ob->center[axis] ? 1 : -1;
    return true;
}

static bool hit_cylinder(const ref_object *ob, const double o[3], const double d[3], double tmin,
                         double tmax, double *t, double n[3]) {
    double r = ob->size[0], h = ob->size[1];
    double ox = o[0] - ob->center[0], oz = o[2] - ob->center[2];
    double best = tmax;
    bool found = false;
    double a = d[0] * d[0] + d[2] * d[2];
    if (a > 1e-300) {   /* the side */
        double b = ox * d[0] + oz * d[2], c = ox * ox + oz * oz - r * r;
        double disc = b * b - a * c;
        if (disc >= 0) {
            double sq = sqrt(disc);
            double ts[2] = { (-b - sq) / a, (-b + sq) / a };
            for (int k = 0; k < 2; k++) {
                double y = o[1] + ts[k] * d[1] - ob->center[1];
                if (ts[k] > tmin && ts[k] < best && y >= 0 && y <= h) {
                    best = ts[k];
                    n[0] = (ox + ts[k] * d[0]) / r;
                    n[1] = 0;
                    n[2] = (oz + ts[k] * d[2]) / r;
                    found = true;
                }
            }
        }
    }
    if (fabs(d[1]) > 1e-300) {   /* the caps */
        for (int k = 0; k < 2; k++) {
            double yc = ob->center[1] + (k ? h : 0);
            double tc = (yc - o[1]) / d[1];
            double px = ox + tc * d[0], pz = oz + tc * d[2];
            if (tc > tmin && tc < best && px * px + pz * pz <= r * r) {
                best = tc;
                n[0] = 0;
                n[1] = k ? 1 : -1;
                n[2] = 0;
                found = true;
            }
        }
    }
    if (found) *t = best;
    return found;
}

int ref_objects_hit(const ref_world *w, const double o[3], const double d[3], double tmin,
                    double tmax, double *t, double n[3]) {
    int best = -1;
    double best_t = tmax, nn[3];
    for (int i = 0; i < w->d.nobjects; i++) {
        const ref_object *ob = &w->d.objects[i];
        double ti;
        bool hit = false;
        switch (ob->kind) {
        case REF_OBJECT_SPHERE: hit = hit_sphere(ob, o, d, tmin, best_t, &ti, nn); break;
        case REF_OBJECT_BOX: hit = hit_box(ob, o, d, tmin, best_t, &ti, nn); break;
        case REF_OBJECT_CYLINDER: hit = hit_cylinder(ob, o, d, tmin, best_t, &ti, nn); break;
        case REF_OBJECT_MESH: hit = ref_mesh_hit(w->meshes[i], o, d, tmin, best_t, &ti, nn); break;
        default: break;
        }
        if (hit && ti < best_t) {
            best_t = ti;
            best = i;
            memcpy(n, nn, sizeof nn);
        }
    }
    if (best >= 0) *t = best_t;
    return best;
}

void ref_world_desc_lake(ref_world_desc *d) {
    memset(d, 0, sizeof *d);
    d->terrain = REF_TERRAIN_LAKE;
    d->waves = ref_waves_default();
    d->water_level = 0.0;
    d->water_mesh_res = 128;   /* scenes/lake.glib's WaterMesh (the GL grid; the reference has the exact surface) */
    d->seed = 7;
    ref_object objs[] = {
        { REF_OBJECT_CYLINDER, { 2.5, -2.0, 1.0 }, { 0.12, 3.2, 0 }, { 0.45, 0.32, 0.20 } },  /* pier post */
        { REF_OBJECT_SPHERE, { -3.0, -0.2, -2.0 }, { 0.9, 0, 0 }, { 0.50, 0.48, 0.45 } },    /* a rock breaking the surface */
        { REF_OBJECT_BOX, { 4.0, 0.5, -5.0 }, { 0.6, 0.8, 0.6 }, { 0.62, 0.30, 0.22 } },     /* a crate on the far shore */
        { REF_OBJECT_CYLINDER, { -7.5, 0.3, 6.5 }, { 0.25, 2.2, 0 }, { 0.35, 0.25, 0.15 } }, /* tree trunk */
        { REF_OBJECT_SPHERE, { -7.5, 3.2, 6.5 }, { 1.3, 0, 0 }, { 0.18, 0.42, 0.15 } },      /* its crown */
        { REF_OBJECT_SPHERE, { 1.0, -2.4, -1.5 }, { 0.6, 0, 0 }, { 0.55, 0.50, 0.42 } },     /* a boulder below */
        { REF_OBJECT_BOX, { -1.5, -2.6, 2.0 }, { 0.5, 0.3, 0.8 }, { 0.40, 0.28, 0.18 } },    /* a sunken crate */
    };
    d->nobjects = (int)(sizeof objs / sizeof objs[0]);
    memcpy(d->objects, objs, sizeof objs);
}

double ref_world_scale(const ref_world *w) { return w->d.half_size / REF_WORLD_UNIT; }
