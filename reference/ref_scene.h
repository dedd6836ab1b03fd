/* ref_scene: the world a scene describes, shared by the GL renderer and the
 * CPU reference: terrain, objects, sky, sun, water and its waves.
 *
 * One definition of each function, in double precision: the GL side bakes
 * what it needs from these (the terrain mesh, its albedo texture, the sky
 * cube map), so packs and the reference see the same world. Shading of
 * everything that is not water is one formula (ref_shade_lambert), written
 * again only in packs/common/world.glsl.
 *
 * Coordinates: y up, metres. The world is the square |x|, |z| <= half_size.
 * ref_world_desc is a desc where zero means default; ref_world_init fills
 * the defaults in one place.
 */
#ifndef TARN_REF_SCENE_H
#define TARN_REF_SCENE_H

#include <stdbool.h>
#include "ref_waves.h"

#define REF_MAX_OBJECTS 32
/* How far the land reaches (m): the reference's rays end at this distance
 * from their origin, and the GL world draws its land out to it (the skirt
 * around the world square) under a far plane beyond it, so both sides show
 * the same land to the same horizon. At 1e4 m land ends within a pixel of
 * the true horizon for any eye a few metres up. */
#define REF_WORLD_HORIZON 1e4
/* The half size the terrain's detail and colours are drawn for: a world of
 * another half size has them scaled in proportion (the lake's 12 m). */
#define REF_WORLD_UNIT 12.0
#define REF_TERRAIN_DETAIL 6       /* sine terms of the terrain's detail */

typedef enum ref_object_kind {
    REF_OBJECT_SPHERE = 1,         /* center, radius */
    REF_OBJECT_BOX,                /* center, half extents (axis-aligned) */
    REF_OBJECT_CYLINDER,           /* base center, radius, height (vertical, capped) */
    REF_OBJECT_MESH                /* an OBJ file's triangles (ref_mesh.h), placed at center */
} ref_object_kind;

#define REF_MESH_PATH_MAX 512

typedef struct ref_object {
    ref_object_kind kind;
    double center[3];              /* the base centre for a cylinder */
    double size[3];                /* sphere: r; box: half x y z; cylinder: r, h */
    double albedo[3];
    /* REF_OBJECT_MESH: the file, turned rot_y_deg about +y and scaled by
     * size[0] (0: 1) around its origin, which goes to center; mesh_hash
     * (the file's bytes' FNV-1a, set by whoever checked it) keys caches on
     * its content. size[1]: its top over center[1] (set with the hash). */
    char mesh_path[REF_MESH_PATH_MAX];
    double rot_y_deg;
    unsigned long long mesh_hash;
} ref_object;

typedef enum ref_terrain_kind {
    REF_TERRAIN_FLAT = 0,          /* y = -depth everywhere (tests) */
    REF_TERRAIN_LAKE,              /* a bowl with a shore rising above the water */
    REF_TERRAIN_SLOPE,             /* a plane rising along +x (tests, the shore) */
    REF_TERRAIN_POOL               /* a tiled pool: a flat floor, walls up to a deck */
} ref_terrain_kind;

/* Flow and spray (issue #29): world features the GL side draws
 * (viewer/gfx/render_flow.c, render_spray.c) and the reference does not:
 * the flow moves only the water's fine detail (normals and streak foam,
 * no height), and the spray is particles above the water (docs/waves.md,
 * "Flow and spray", says what leaving them out costs the error). */
#define REF_FLOW_TERMS_MAX 4
typedef enum ref_flow_kind {
    REF_FLOW_CURRENT = 1,          /* p: vx vz (m/s), everywhere */
    REF_FLOW_VORTEX,               /* p: x z strength radius: a Rankine vortex turning
                                    * anticlockwise seen from above for strength > 0,
                                    * speed strength r/R inside R, strength R/r outside */
    REF_FLOW_TEXTURE               /* p: scale (m/s); ref_flow_desc.texture: a velocity
                                    * map over the world square, (vx, vz) = (2 R - 1,
                                    * 2 G - 1) scale, its top row at z = -half_size */
} ref_flow_kind;

typedef struct ref_flow_term {
    ref_flow_kind kind;
    double p[4];
} ref_flow_term;

typedef struct ref_flow_desc {
    int nterms;                    /* 0: no flow (no pass, no texture) */
    ref_flow_term term[REF_FLOW_TERMS_MAX];   /* their velocities add */
    double detail_amp;             /* height amplitude (m) of the advected ripples; 0: 0.012 */
    double detail_cell;            /* their noise cell (m); 0: 0.5 */
    double period;                 /* seconds a layer lives before it restarts; 0: 3 */
    double foam;                   /* cover of the advected foam streaks, 0..1; 0: none */
    char texture[1024];            /* REF_FLOW_TEXTURE's file (resolved), one a world */
} ref_flow_desc;

typedef struct ref_spray_desc {
    bool on;                       /* false: no spray (no pass, no texture) */
    double threshold;              /* upward surface speed (m/s) over which it emits */
    double rate;                   /* particles a second were the whole square over it */
    double life;                   /* seconds a droplet lives at most; 0: 2 */
    double size;                   /* droplet diameter (m); 0: 0.05 */
    unsigned seed;
    int count;                     /* particle slots; 0: 16384 */
} ref_spray_desc;

typedef struct ref_world_desc {
    /* light */
    double sun_dir[3];             /* towards the sun (normalised); 0: (0.4, 0.8, -0.45) */
    double sun_irradiance[3];      /* W/m^2-like units per channel; 0: (2.2, 2.1, 1.9) */
    double sky_zenith[3];          /* sky radiance straight up; 0: (0.25, 0.45, 0.85) */
    double sky_horizon[3];         /* at the horizon; 0: (0.70, 0.80, 0.92) */
    /* the world's look (issue #25; every one off by default, so a scene
     * without these commands draws as before) */
    double sun_disc_deg;           /* SkySun: the disc's angular radius (deg); 0: no disc */
    double sun_disc_gain;          /* its radiance in units of E_sun / 3 (the glow's); 0: 20 */
    double cloud_cover;            /* Clouds: the sky's fraction under cloud, 0..1; 0: none */
    double cloud_scale;            /* their features' size (m); 0: 600 */
    double cloud_height;           /* the layer's height over the eye (m); 0: 1500 */
    double haze_distance;          /* Haze: land at this air path (m) is 63 % horizon colour; 0: none */
    double ground_detail;          /* GroundDetail: the terrain's noise (0..1); 0: none */
    /* water */
    double water_level;            /* mean height (the waves' level follows it) */
    double ior;                    /* 0: 1.333 */
    double absorption[3];          /* Beer-Lambert sigma per metre; 0: (0.45, 0.09, 0.06) */
    int water_mesh_res;            /* GL surface grid cells per side; 0: 256 */
    ref_waves_desc waves;          /* level is overwritten by water_level */
    /* ground */
    ref_terrain_kind terrain;
    double half_size;              /* 0: 12 */
    double depth;                  /* deepest point below the water; 0: 3 */
    double shore_height;           /* rim (lake shore, pool deck) above the water; 0: 0.6 */
    double slope;                  /* REF_TERRAIN_SLOPE: dy/dx; 0: 0.25 */
    unsigned seed;                 /* detail of the lake's bottom */
    int terrain_res;               /* GL mesh / albedo texture cells per side; 0: 256 */
    /* objects */
    int nobjects;
    ref_object objects[REF_MAX_OBJECTS];
    /* drawn by the GL side only (above) */
    ref_flow_desc flow;
    ref_spray_desc spray;
} ref_world_desc;

typedef struct ref_world {
    ref_world_desc d;              /* with the defaults filled in */
    ref_waves waves;               /* resolved */
    double ambient[3];             /* sky ambient radiance: half the mean of zenith and horizon */
    /* the lake's detail: sum of a_i sin(k_i . (x, z) + phi_i) */
    double detail_k[REF_TERRAIN_DETAIL][2];
    double detail_a[REF_TERRAIN_DETAIL];
    double detail_phi[REF_TERRAIN_DETAIL];
    double terrain_slope_bound;    /* |grad h| <= this everywhere (for tracing) */
    struct ref_mesh *meshes[REF_MAX_OBJECTS];   /* REF_OBJECT_MESH objects' triangles (else NULL);
                                                   one that failed to load is NULL and never hit */
} ref_world;

/* Fills defaults, normalises, resolves the waves. The waves may hold heap
 * memory (a spectrum ocean, owned by w->waves): release the world with
 * ref_world_release when it dies. A struct copy of a ref_world shares that
 * memory: release exactly one copy, and use none after. */
void ref_world_init(ref_world *w, const ref_world_desc *d);

/* Frees what ref_world_init allocated; safe on a zeroed or released world. */
void ref_world_release(ref_world *w);

/* Terrain: height, gradient (dh/dx, dh/dz), unit normal; C1 everywhere. */
double ref_terrain_height(const ref_world *w, double x, double z);
void ref_terrain_gradient(const ref_world *w, double x, double z, double grad[2]);
void ref_terrain_normal_at(const ref_world *w, double x, double z, double n[3]);

/* Ground colour (linear RGB reflectance) by height over the water, depth
 * and slope: silt in the deep, sand at the shore, grass above, rock on
 * steep slopes. The pool: light and dark tiles of 0.5 m (in the lake's
 * units) with dark grout under its rim, a plain stone deck above. */
void ref_terrain_albedo(const ref_world *w, double x, double z, double rgb[3]);

/* Sky radiance along unit direction dir (linear RGB): a zenith-horizon
 * gradient, a smooth glow around the sun, and a dim ground colour below
 * the horizon; with Clouds, the clouds over it, and with SkySun the sun's
 * disc: ref_sky_smooth + clear * ref_sun_disc. */
void ref_sky_radiance(const ref_world *w, const double dir[3], double rgb[3]);

/* The sky without the sun's disc: what the GL side bakes into its cube
 * map (RGB), with in *clear (may be NULL) the fraction of the disc that
 * shows through the clouds there (the cube map's alpha). Clouds (Clouds):
 * fbm of hashed value noise on a plane cloud_height over the eye, seen
 * along dir, lit by the sun and thinning into the horizon; static. */
void ref_sky_smooth(const ref_world *w, const double dir[3], double rgb[3], double *clear);

/* The sun's disc (SkySun) along unit dir: radiance sun_disc_gain E_sun / 3
 * over a core of angular radius sun_disc_deg with a soft, limb-darkened
 * edge (0.75 to 1.25 radii) and an aureole falling off beyond it; 0 past
 * 40 radii or with no disc. packs/common/world.glsl's worldSunDisc is the
 * same formula in float. */
void ref_sun_disc(const ref_world *w, const double dir[3], double rgb[3]);

/* Value noise: a smooth (quintic) interpolation of hashed lattice values
 * (ref_hash32) in [0, 1]; terrain.glsl's terrainValueNoise is its twin. */
double ref_value_noise(double x, double z, unsigned seed);

/* Aerial perspective (Haze): radiance seen over an air path of length
 * dist, blended towards the horizon colour by 1 - exp(-dist / (haze_distance
 * times the world scale)); rgb unchanged with no haze. world.frag's
 * worldHaze is the same. */
void ref_haze(const ref_world *w, double dist, double rgb[3]);

/* Radiance leaving a Lambertian surface lit by the sun and the sky ambient:
 * albedo * (E_sun * max(0, n . l) / pi + ambient). sun_scale scales the sun
 * term (shadow or caustic factor; 1 for plain sunlight). */
void ref_shade_lambert(const ref_world *w, const double albedo[3], const double n[3],
                       double sun_scale, double rgb[3]);

/* Ray against the objects: the nearest hit with t in (tmin, tmax); returns
 * the object index or -1, with t, the point and its unit normal. */
int ref_objects_hit(const ref_world *w, const double o[3], const double d[3], double tmin,
                    double tmax, double *t, double n[3]);

/* The lake scene's world (what scenes/lake.glib describes). */
void ref_world_desc_lake(ref_world_desc *d);

/* The scene's length unit relative to the lake's (terrain half size
 * REF_WORLD_UNIT): what a pack's lengths, written for the lake, are
 * multiplied by (uWorldScale), so a scaled scene gets scaled steps,
 * offsets and reaches. */
double ref_world_scale(const ref_world *w);

#endif
