/* render_world: the world a scene describes (scene.h), made drawable: the
 * terrain mesh and its albedo texture, the objects, the sky cube map and
 * the water grid, all baked from reference/ref_scene so the GL side and
 * the CPU reference see one world. Private to the renderer (render*.c).
 *
 * Fixed texture units: 14 the terrain albedo (sampler uTerrainAlbedo),
 * 15 the sky cube map (samplerCube uSky), 28 and 29 the ocean's frame
 * (uOceanA, uOceanB; OCEAN_UNIT_A/B), 27 its folding foam (uOceanFoam,
 * OCEAN_UNIT_FOAM: beside the frame and under 30, so 31, the last unit of
 * a GL with 32 image units such as llvmpipe, stays free), 30 the waves'
 * height map; with a Flow 26 its map (uFlowMap) and 22 a Flow texture's
 * velocities (its pass only), with a Spray 24 and 25 its state and 23 the
 * height map before (its pass only). Every program that declares a
 * world uniform (uSunDir, uWaterLevel, the wave set, ...) gets it set. */
#ifndef TARN_RENDER_WORLD_H
#define TARN_RENDER_WORLD_H

#include <stdbool.h>
#include "ref_scene.h"
#include "render_flow.h"
#include "render_ocean.h"
#include "render_spray.h"
#include "world_layers.h"
#include "render_prog.h"
#include "render_res.h"

#define WORLD_UNIT_ALBEDO 14
#define WORLD_UNIT_SKY 15
#define WORLD_UNIT_HEIGHT 30   /* the waves' height map (world_update_height): above glman's units */
#define WORLD_HEIGHT_RES 256   /* its texels a side at full detail */
#define WORLD_HEIGHT_MARGIN 2.0   /* it covers twice the world square's half size */
/* The terrain's height, a map baked once per world (world_bake_terrain_map)
 * that a march reads at every step instead of the model (the lake's six
 * sines; terrain.glsl's terrainHeightMarch): unit 21 (uTerrainHeightMap),
 * free of the packs' units and under the world's 22-30. It covers 1.3
 * half sizes, past the lake's rim (elliptic radius 1.25) and the pool's
 * deck, and holds the height less the terrain's plane (uTerrainMapPlane:
 * the slope's), so its clamped edge continues every model beyond it. */
#define WORLD_UNIT_TERRAIN 21
#define WORLD_TERRAIN_RES 512
#define WORLD_TERRAIN_MARGIN 1.3
#define WORLD_SKY_RES 128
#define WORLD_SKY_RES_CLOUDS 512   /* faces with clouds (Clouds): 0.18 degrees a texel */
#define WORLD_MODES 3
/* Levels of detail of the terrain, its skirt and the water grid: level k
 * has 1/2^k the cells a side (at least WORLD_LOD_MIN_CELLS). Level 0 is
 * the scene's; the others are built the first time they are drawn. */
#define WORLD_LODS 4
#define WORLD_LOD_MIN_CELLS 8

typedef struct gpu_world {
    bool active;
    ref_world_desc desc;          /* what was built: equal desc, nothing rebuilt */
    unsigned builds;              /* whole builds so far (a new desc; kept by world_free): the
                                   * renderer's world caches hold one build's pixels */
    ref_world w;
    /* skirt: the land beyond the world square; [k]: level of detail k */
    gpu_mesh terrain[WORLD_LODS], skirt[WORLD_LODS], water[WORLD_LODS], sky_box;
    int lod;                      /* the level drawn (world_set_detail) */
    unsigned points_vbo;          /* WaterSurface points N (and mesh N's vertices) */
    int points_n;
    unsigned mesh_ibo;            /* WaterSurface mesh N: its triangles' indices */
    int mesh_n;
    gpu_mesh objects[REF_MAX_OBJECTS];
    float object_albedo[REF_MAX_OBJECTS][3];
    int nobjects;
    bool has_above_water;         /* terrain or an object rises above the water (If above_water) */
    unsigned albedo_tex, sky_tex;
    unsigned terrain_tex;         /* the terrain's height map (WORLD_UNIT_TERRAIN); 0 until asked for */
    /* the built-in program, packs/common/world.{vert,frag}, once per
     * WORLD_MODE (0 terrain, 1 objects, 2 sky): a pixel runs its own branch */
    prog progs[WORLD_MODES];
    unif_set prog_unifs[WORLD_MODES];
    ref_waves_uniform waves[REF_WAVES_UNIFORMS_MAX];
    int nwaves;
    /* the water grid's and the photon points' rest positions are the world
     * square moved by this (x, z): 0 unless the waves slide the whole
     * surface (world_follow_waves) */
    double water_shift[2];
    /* The water surface's height over the world, a map drawn once a frame
     * (packs/common/world_height.frag) that world.frag reads to tell wet
     * land from dry instead of solving for the surface at every pixel. */
    bool height_map_off;          /* world.frag solves per pixel (tests compare the two) */
    prog height_prog;
    unif_set height_unifs;
    prog layers_prog[2];         /* world_layers.frag: a World's layers at a new time; [1] multisampled */
    unif_set layers_unifs[2];
    unsigned height_tex, height_fbo;
    int height_res;
    double height_t;
    /* the map before this one, kept while the world has a spray: the
     * spectrum ocean's upward speed is their difference (render_spray.h) */
    unsigned height_prev_tex, height_prev_fbo;
    int height_prev_res;
    double height_prev_t;
    unsigned long long height_hash;   /* the program the map was drawn with */
    /* the map's cells a wet test reads (world_height_tiles.h), found once a
     * world, and the quads that draw them at height_quads_res texels a side
     * (the whole map while a spray reads it everywhere) */
    struct height_tiles *height_tiles;
    unsigned height_quads_vbo;
    int height_quads_res, height_quads_n;   /* n: vertices */
    bool height_quads_full;
    bool height_cells_off;        /* world_set_height_cells(false): every texel drawn */
    /* The spectrum ocean's frame (render_ocean.h): created with the world
     * when its waves hold an ocean, nothing otherwise. */
    gpu_ocean ocean;
    /* The flow map (render_flow.h, FLOW_UNIT 26): created with the world
     * when it has a `Flow`, nothing otherwise. */
    gpu_flow flow;
    /* The spray (render_spray.h, SPRAY_UNIT_POS/VEL 24, 25): created with
     * the world when it has a `Spray`, nothing otherwise. */
    gpu_spray spray;
} gpu_world;

/* A count the scene fixes (a target's side, points or texels per side)
 * for a frame at `detail` of each side (render_set_detail): scaled with
 * the frame's sides, so its pass costs the same share of a reduced frame
 * as of a full one; never below min (nor above n); a power of two when n
 * is one, else none (side_like_full: one shader variant for the reduced
 * and the full frames); n itself at detail 1, or out of (0, 1). */
int world_detail_count(int n, double detail, int min);

/* The level of detail of the meshes drawn from now on, for a frame drawn
 * at `detail` of each side of full resolution (render_set_detail): 1 the
 * scene's meshes, 1/2 a quarter of the vertices, down to 1/8. A coarser
 * mesh is built the first time it is needed; false when it cannot be
 * (the level stays as it was). */
bool world_set_detail(gpu_world *gw, double detail);

/* Builds (or keeps, when desc is unchanged) the world's GPU resources;
 * the messages go to log, and from records which program's build
 * reported each (prog_build; NULL: not kept). */
bool world_build(gpu_world *gw, const ref_world_desc *desc, const prog_sources *src,
                  diag_list *log, prog_origins *from);
void world_free(gpu_world *gw);
/* Builds the world's programs again (a shader file changed); false on errors. */
bool world_build_programs(gpu_world *gw, const prog_sources *src, diag_list *log, prog_origins *from);

/* The defines that tell the packs' shaders what this world has, so a
 * program compiles only that: llvmpipe runs a loop's body even when its
 * uniform count is 0, and both sides of an `if` even on a uniform. The
 * wave models (packs/common/waves.glsl): WAVES_MODELS, then WAVES_HAS_SINE,
 * _GERSTNER, _NOISE, _OCEAN, _EXPLOSION, _PERLIN for each it holds;
 * WAVES_HAS_FLOW with a Flow. The look (terrain.glsl, world.glsl):
 * WORLD_DEFINES (these are known), WORLD_TERRAIN_KIND (the Terrain's
 * model, REF_TERRAIN_*), and WORLD_GROUND_DETAIL, WORLD_SUN_DISC,
 * WORLD_HAZE where the scene has GroundDetail, SkySun, Haze. All are the
 * scene's, fixed until a reload, which builds the programs again.
 * Into p->fixed[PROG_FIXED_WORLD..] (cleared without a world). */
void world_set_defines(const gpu_world *gw, prog *p);

/* Bakes the terrain's height map (WORLD_UNIT_TERRAIN) unless it is there:
 * 512^2 evaluations of the model, ~40 ms on one core, so only for a scene
 * whose programs read it (render_load). The map lives until the world is
 * rebuilt. */
void world_bake_terrain_map(gpu_world *gw);

/* Sets every world uniform the bound program declares. */
void world_upload(const gpu_world *gw, unsigned program, double t, const float eye[3]);

void world_bind_textures(const gpu_world *gw);

/* Computes the ocean's frame for time t (render_ocean.h), unless the world
 * has none or it holds t already; its passes are named in timer. Returns
 * whether it ran passes. Call it before world_update_height, which reads it. */
bool world_update_ocean(gpu_world *gw, double t, gpu_timer *timer);

/* Advects the flow map to time t (render_flow.h), unless the world has no
 * flow or it holds t already; its pass is named in timer. Returns whether
 * it ran passes. */
bool world_update_flow(gpu_world *gw, double t, gpu_timer *timer);

/* Moves the spray to time t (render_spray.h), unless the world has none or
 * it is there already; its pass is named in timer. Returns whether it ran
 * passes. */
bool world_update_spray(gpu_world *gw, double t, gpu_timer *timer);

/* Draws the spray's droplets into the bound framebuffer (viewport w x h)
 * through view-projection vp from eye; nothing without a spray. */
void world_draw_spray(const gpu_world *gw, const float vp[16], const float eye[3], int w, int h);

/* Draws the height map for time t at the detail of the frame (its side
 * WORLD_HEIGHT_RES times detail, at least 32), unless it is drawn for t
 * already. Binds framebuffer 0 and leaves the viewport changed: call it
 * before the frame sets its own. */
void world_update_height(gpu_world *gw, double t, double detail);

/* The height pass draws only the cells of the map a wet test reads
 * (world_height_tiles.h; on, the default) or every texel (off: tests
 * compare the two, which must give the same pixels). */
void world_set_height_cells(gpu_world *gw, bool on);

/* The height map on (the default) or off (world.frag solves for the
 * surface at every pixel, as before); rebuilds the world's programs. */
bool world_set_height_map(gpu_world *gw, bool on, const prog_sources *src, diag_list *log,
                          prog_origins *from);

/* Keeps the water's rest grid under the surface at time t. A Gerstner wave
 * moves each rest point by Q_i A_i cos(phase) sideways, at most Q L / (2 pi
 * N): a few centimetres for the lake, but a wave far longer than the world
 * square slides the whole surface (100 km: 1.9 km), and a grid over the
 * world square would leave the lake dry. When the mean displacement over
 * the square is more than a grid cell from the current shift, the grid and
 * the photon points are rebuilt moved back by it, so that the displaced
 * surface covers the square again. */
void world_follow_waves(gpu_world *gw, double t);

/* `World all|above|below`: terrain and objects with the world program,
 * clipped at the water plane for above/below; restores `restore_program`.
 * to_screen: the final image (not a pass into a texture), where an eye
 * under the water sees the world through its own path in water, which the
 * world program then attenuates (a pack attenuates the paths of its
 * passes itself). */
void world_draw(const gpu_world *gw, const char *which, double offset, double t, const float eye[3],
                bool to_screen, unsigned restore_program);
/* The same draw into a world_layers target (world_layers.h): each pixel's
 * wet and dry shading, its point and depth, for any time. */
void world_draw_layers(const gpu_world *gw, const char *which, double offset, const float eye[3], bool to_screen,
                       unsigned restore_program);
/* A World at time t from its layers (tex: wet+depth, dry, point, and
 * multisampled the depth; v: how
 * a pixel finds its texel, world_layers.h), into the bound target's
 * viewport (its corner at x, y): the pixels world_draw gives at t (at the
 * layers' own size). band: NULL, the whole viewport; else only its
 * triangles (world_layers_band_begin). Restores `restore_program` and the
 * texture units it borrows. */
void world_composite_layers(const gpu_world *gw, double t, const float eye[3], const unsigned tex[4],
                            const world_layer_view *v, int x, int y, unsigned restore_program,
                            const world_layer_band *band);
/* Is there a program to compose layers of this many samples a pixel with? */
bool world_can_composite(const gpu_world *gw, int samples);
/* Multisampled layers (v->samples > 1): into the bound one-sample target
 * (world_layers_begin_pick), each pixel's point that lies in [lo, hi] if
 * any of its samples' does, else its first sample's. */
void world_pick_band_points(const gpu_world *gw, const unsigned tex[4], const world_layer_view *v, double lo,
                            double hi, unsigned restore_program);
/* The heights whose points' wetness changes with the time (the band a wet
 * test reads the surface in, world_layer_band.h), for this world's level
 * and waves. */
void world_wet_band(const gpu_world *gw, double *lo, double *hi);

/* `WaterSurface`: the water grid (at the level of detail) with the bound program. */
void world_draw_water(gpu_world *gw, int tangent_loc);

/* `WaterSurface points N`: N x N points over the world square, point
 * (i, j) at cell centre (i, j) of an N x N grid, gl_VertexID j N + i. With
 * mesh, the 2 (N - 1)^2 triangles between the same points instead (an
 * indexed draw, so gl_VertexID is still j N + i): a photon grid drawn as a
 * surface whose triangles a splat can fill. */
void world_draw_points(gpu_world *gw, int n, bool mesh);

#endif
