/* glib_table.c: the command table of the .glib parser: one row per
 * command name (its kind, handler, arguments with their rules and glman's
 * defaults, usage, whether it describes the world), the lookup of a name,
 * "did you mean", and the names of the kinds (glib_internal.h).
 */
#include "glib_internal.h"

#include <ctype.h>
#include <string.h>
#include <strings.h>

/* the names of the kinds, for messages (glib_cmd_name) */
static const char *const kind_names[GLIB_CMD_KIND_COUNT] = {
    [GLIB_CMD_NONE] = "(none)",
    [GLIB_CMD_WINDOW_SIZE] = "WindowSize", [GLIB_CMD_PERSPECTIVE] = "Perspective",
    [GLIB_CMD_ORTHO] = "Ortho", [GLIB_CMD_LOOKAT] = "LookAt",
    [GLIB_CMD_TRANSLATE] = "Translate", [GLIB_CMD_ROTATE] = "Rotate",
    [GLIB_CMD_SCALE] = "Scale", [GLIB_CMD_PUSH_MATRIX] = "PushMatrix",
    [GLIB_CMD_POP_MATRIX] = "PopMatrix",
    [GLIB_CMD_QUAD_XY] = "QuadXY", [GLIB_CMD_QUAD_XZ] = "QuadXZ", [GLIB_CMD_QUAD_YZ] = "QuadYZ",
    [GLIB_CMD_SPHERE] = "Sphere", [GLIB_CMD_TORUS] = "Torus", [GLIB_CMD_BOX] = "Box",
    [GLIB_CMD_CYLINDER] = "Cylinder", [GLIB_CMD_CONE] = "Cone", [GLIB_CMD_TEAPOT] = "Teapot",
    [GLIB_CMD_OBJ] = "Obj", [GLIB_CMD_COLOR] = "Color",
    [GLIB_CMD_TEXTURE2D_FILE] = "Texture2D", [GLIB_CMD_TEXTURE2D_EMPTY] = "Texture2D",
    [GLIB_CMD_TEXTURE3D] = "Texture3D", [GLIB_CMD_CUBEMAP] = "CubeMap",
    [GLIB_CMD_NOISE2D] = "Noise2D", [GLIB_CMD_NOISE3D] = "Noise3D",
    [GLIB_CMD_RENDER_TO_TEXTURE] = "RenderToTexture", [GLIB_CMD_CLEAR] = "Clear",
    [GLIB_CMD_BACKGROUND] = "Background",
    [GLIB_CMD_VERTEX] = "Vertex", [GLIB_CMD_TESS_CONTROL] = "TessControl",
    [GLIB_CMD_TESS_EVALUATION] = "TessEvaluation", [GLIB_CMD_GEOMETRY] = "Geometry",
    [GLIB_CMD_FRAGMENT] = "Fragment", [GLIB_CMD_PROGRAM] = "Program",
    [GLIB_CMD_TIMER] = "Timer", [GLIB_CMD_GSTAP] = "GSTAP",
    [GLIB_CMD_DEFINE] = "Define", [GLIB_CMD_CULL] = "Cull",
    [GLIB_CMD_DEPTH_TEST] = "DepthTest", [GLIB_CMD_BLEND] = "Blend",
    [GLIB_CMD_SUN] = "Sun", [GLIB_CMD_SKY] = "Sky", [GLIB_CMD_SKY_SUN] = "SkySun",
    [GLIB_CMD_CLOUDS] = "Clouds", [GLIB_CMD_HAZE] = "Haze", [GLIB_CMD_GROUND_DETAIL] = "GroundDetail",
    [GLIB_CMD_WATER] = "Water",
    [GLIB_CMD_WATER_MESH] = "WaterMesh", [GLIB_CMD_TERRAIN] = "Terrain",
    [GLIB_CMD_WAVE_SINE] = "WaveSine", [GLIB_CMD_WAVE_GERSTNER] = "WaveGerstner",
    [GLIB_CMD_WAVE_STEEPNESS] = "WaveSteepness", [GLIB_CMD_WAVE_NOISE] = "WaveNoise",
    [GLIB_CMD_WAVE_OCEAN] = "WaveOcean", [GLIB_CMD_WAVE_OCEAN_TILES] = "WaveOceanTiles",
    [GLIB_CMD_WAVE_EXPLOSION] = "WaveExplosion", [GLIB_CMD_WAVE_PERLIN] = "WavePerlin",
    [GLIB_CMD_FLOW] = "Flow", [GLIB_CMD_SPRAY] = "Spray",
    [GLIB_CMD_OBJECT] = "Object", [GLIB_CMD_PACK] = "Pack", [GLIB_CMD_WORLD] = "World",
    [GLIB_CMD_WATER_SURFACE] = "WaterSurface",
    [GLIB_CMD_CAMERA] = "Camera",
    [GLIB_CMD_RENDER_TO_TEXTURE_ONCE] = "RenderToTextureOnce",
    [GLIB_CMD_SPLAT] = "Splat", [GLIB_CMD_IF] = "If", [GLIB_CMD_END_IF] = "EndIf",
    [GLIB_CMD_FLAT] = "Flat", [GLIB_CMD_SMOOTH] = "Smooth", [GLIB_CMD_LINE_WIDTH] = "LineWidth",
    [GLIB_CMD_POINT_SIZE] = "PointSize", [GLIB_CMD_POINT_SIZE_MODE] = "PointSizeMode",
    [GLIB_CMD_CLAMP] = "Clamp",
    [GLIB_CMD_DISK_XY] = "DiskXY", [GLIB_CMD_QUAD_BOX] = "QuadBox",
    [GLIB_CMD_POINT_CLOUD] = "PointCloud", [GLIB_CMD_JITTER_CLOUD] = "JitterCloud",
    [GLIB_CMD_SOCCERBALL] = "Soccerball", [GLIB_CMD_XARROW] = "Xarrow",
    [GLIB_CMD_LINES_ADJACENCY] = "LinesAdjacency", [GLIB_CMD_TRIANGLES] = "Triangles",
    [GLIB_CMD_OBJ_ADJ] = "ObjAdj", [GLIB_CMD_OBJ_PATCH] = "ObjPatch",
    [GLIB_CMD_NUM_PATCH_VERTICES] = "NumPatchVertices", [GLIB_CMD_GL_BEGIN] = "glBegin",
    [GLIB_CMD_GL_VERTEX] = "glVertex", [GLIB_CMD_GL_END] = "glEnd",
    [GLIB_CMD_SHP] = "Shp",
};

const char *glib_cmd_name(glib_cmd_kind kind) {
    if ((int)kind < 0 || kind >= GLIB_CMD_KIND_COUNT || !kind_names[kind])
        return "?";
    return kind_names[kind];
}

/* ------------------------------------------------------------------ */
/* the command table                                                  */

#define ARG_R(s, w)             { s, w, 'r', 0, 0, 0 }
#define ARG_RD(s, d)            { s, NULL, 'r', 0, 0, d }
#define ARG_P(s, w)             { s, w, 'p', 0, 0, 0 }
#define ARG_PD(s, d)            { s, NULL, 'p', 0, 0, d }
#define ARG_ID(s, lo, hi, d)    { s, NULL, 'i', lo, hi, d }
#define ARG_I(s, w, lo, hi)     { s, w, 'i', lo, hi, 0 }

/* Missing arguments take glman's defaults (docs/glib.md) */
#define QUAD_ARGS(a, b, c) { ARG_RD(a, 0), ARG_PD("size", 1), \
    ARG_ID(b, 1, 4096, 1), ARG_ID(c, 1, 4096, 1) }
#define SPHERE_ARGS { ARG_PD("r", 1), ARG_ID("slices", 3, 1024, 60), \
    ARG_ID("stacks", 2, 1024, 60) }
#define TORUS_ARGS { ARG_PD("r_major", 1), ARG_PD("r_minor", 0.5), \
    ARG_ID("sides", 3, 1024, 20), ARG_ID("rings", 3, 1024, 40) }
#define BOX_ARGS { ARG_PD("dx", 2), ARG_PD("dy", 2), ARG_PD("dz", 2) }
#define ROUND_ARGS { ARG_PD("r", 1), ARG_PD("h", 1), \
    ARG_ID("slices", 3, 1024, 32), ARG_ID("stacks", 1, 1024, 8) }
#define WAVE_ARGS { ARG_R("angle_deg", NULL), ARG_R("wavelength", NULL), \
    ARG_R("amplitude", "an amplitude"), ARG_RD("speed", 0), ARG_RD("phase", 0) }
#define XYZ_ARGS(i) ARG_R("x" #i, NULL), ARG_R("y" #i, NULL), ARG_R("z" #i, NULL)
#define CLOUD_ARGS { ARG_ID("nx", 1, 1024, 10), ARG_ID("ny", 1, 1024, 10), ARG_ID("nz", 1, 1024, 10) }
#define RGBA_ARGS { ARG_R("r", NULL), ARG_R("g", NULL), ARG_R("b", "a blue value"), ARG_RD("a", 1) }

static const cmd_spec specs[] = {
    { "WindowSize", GLIB_CMD_WINDOW_SIZE, false, glib_h_nums, false, 2, 2,
      { ARG_I("w", NULL, 1, 16384), ARG_I("h", "a height", 1, 16384) }, NULL },
    { "Perspective", GLIB_CMD_PERSPECTIVE, false, glib_h_nums, false, 0, 3,
      { { "fov", "a field of view in degrees", 'a', 0, 0, 50 }, ARG_PD("near", 0.1),
        ARG_PD("far", 1000) }, NULL },
    { "Ortho", GLIB_CMD_ORTHO, false, glib_h_nums, false, 0, 6,
      { ARG_RD("l", -3), ARG_RD("r", 3), ARG_RD("b", -3), ARG_RD("t", 3),
        ARG_RD("near", 0.1), ARG_RD("far", 1000) }, NULL },
    { "LookAt", GLIB_CMD_LOOKAT, false, glib_h_nums, false, 9, 9,
      { ARG_R("ex", NULL), ARG_R("ey", NULL), ARG_R("ez", NULL), ARG_R("cx", NULL),
        ARG_R("cy", NULL), ARG_R("cz", NULL), ARG_R("ux", NULL), ARG_R("uy", NULL),
        ARG_R("uz", "an up vector") }, NULL },
    { "Translate", GLIB_CMD_TRANSLATE, false, glib_h_nums, false, 0, 3,
      { ARG_RD("x", 0), ARG_RD("y", 0), ARG_RD("z", 0) }, NULL },
    { "Rotate", GLIB_CMD_ROTATE, false, glib_h_nums, false, 4, 4,
      { ARG_R("deg", NULL), ARG_R("ax", NULL), ARG_R("ay", NULL), ARG_R("az", "an axis z") }, NULL },
    { "Scale", GLIB_CMD_SCALE, false, glib_h_nums, false, 1, 3,
      { ARG_R("s", "a scale factor"), ARG_RD("sy", 0), ARG_RD("sz", 0) }, "Scale s | Scale sx sy sz" },
    { "PushMatrix", GLIB_CMD_PUSH_MATRIX, false, glib_h_nums, false, 0, 0, { { 0 } }, NULL },
    { "TransformBegin", GLIB_CMD_PUSH_MATRIX, false, glib_h_nums, false, 0, 0, { { 0 } }, NULL },
    { "PopMatrix", GLIB_CMD_POP_MATRIX, false, glib_h_nums, false, 0, 0, { { 0 } }, NULL },
    { "TransformEnd", GLIB_CMD_POP_MATRIX, false, glib_h_nums, false, 0, 0, { { 0 } }, NULL },
    { "QuadXY", GLIB_CMD_QUAD_XY, false, glib_h_nums, false, 0, 4, QUAD_ARGS("z", "nx", "ny"), NULL },
    { "QuadXZ", GLIB_CMD_QUAD_XZ, false, glib_h_nums, false, 0, 4, QUAD_ARGS("y", "nx", "nz"), NULL },
    { "QuadYZ", GLIB_CMD_QUAD_YZ, false, glib_h_nums, false, 0, 4, QUAD_ARGS("x", "ny", "nz"), NULL },
    { "Sphere", GLIB_CMD_SPHERE, false, glib_h_nums, false, 0, 3, SPHERE_ARGS, NULL },
    { "Torus", GLIB_CMD_TORUS, false, glib_h_nums, false, 0, 4, TORUS_ARGS, NULL },
    { "Box", GLIB_CMD_BOX, false, glib_h_nums, false, 0, 3, BOX_ARGS, "Box dx | Box dx dy dz" },
    { "Cylinder", GLIB_CMD_CYLINDER, false, glib_h_nums, false, 0, 4, ROUND_ARGS, NULL },
    { "Cone", GLIB_CMD_CONE, false, glib_h_nums, false, 0, 4, ROUND_ARGS, NULL },
    { "Teapot", GLIB_CMD_TEAPOT, false, glib_h_nums, false, 0, 1, { ARG_PD("size", 1) }, NULL },
    { "WireQuadXY", GLIB_CMD_QUAD_XY, true, glib_h_nums, false, 0, 4, QUAD_ARGS("z", "nx", "ny"), NULL },
    { "WireQuadXZ", GLIB_CMD_QUAD_XZ, true, glib_h_nums, false, 0, 4, QUAD_ARGS("y", "nx", "nz"), NULL },
    { "WireQuadYZ", GLIB_CMD_QUAD_YZ, true, glib_h_nums, false, 0, 4, QUAD_ARGS("x", "ny", "nz"), NULL },
    { "WireSphere", GLIB_CMD_SPHERE, true, glib_h_nums, false, 0, 3, SPHERE_ARGS, NULL },
    { "WireTorus", GLIB_CMD_TORUS, true, glib_h_nums, false, 0, 4, TORUS_ARGS, NULL },
    { "WireBox", GLIB_CMD_BOX, true, glib_h_nums, false, 0, 3, BOX_ARGS, "WireBox dx | WireBox dx dy dz" },
    { "WireCylinder", GLIB_CMD_CYLINDER, true, glib_h_nums, false, 0, 4, ROUND_ARGS, NULL },
    { "WireCone", GLIB_CMD_CONE, true, glib_h_nums, false, 0, 4, ROUND_ARGS, NULL },
    { "WireTeapot", GLIB_CMD_TEAPOT, true, glib_h_nums, false, 0, 1, { ARG_PD("size", 1) }, NULL },
    { "Obj", GLIB_CMD_OBJ, false, glib_h_obj, false, 0, 0, { { 0 } }, "Obj file.obj" },
    { "WireObj", GLIB_CMD_OBJ, true, glib_h_obj, false, 0, 0, { { 0 } }, "WireObj file.obj" },
    { "ObjAdj", GLIB_CMD_OBJ_ADJ, false, glib_h_obj, false, 0, 0, { { 0 } }, "ObjAdj file.obj" },
    { "ObjPatch", GLIB_CMD_OBJ_PATCH, false, glib_h_obj, false, 0, 0, { { 0 } }, "ObjPatch file.obj" },
    { "Shp", GLIB_CMD_SHP, false, glib_h_obj, false, 0, 0, { { 0 } }, "Shp file.shp" },
    { "DiskXY", GLIB_CMD_DISK_XY, false, glib_h_nums, false, 0, 0, { { 0 } }, NULL },
    { "QuadBox", GLIB_CMD_QUAD_BOX, false, glib_h_nums, false, 0, 1, { ARG_ID("n", 1, 2048, 10) }, NULL },
    { "PointCloud", GLIB_CMD_POINT_CLOUD, false, glib_h_nums, false, 0, 3, CLOUD_ARGS, NULL },
    { "JitterCloud", GLIB_CMD_JITTER_CLOUD, false, glib_h_nums, false, 0, 3, CLOUD_ARGS, NULL },
    { "Soccerball", GLIB_CMD_SOCCERBALL, false, glib_h_nums, false, 0, 1, { ARG_PD("r", 1) }, NULL },
    { "Xarrow", GLIB_CMD_XARROW, false, glib_h_nums, false, 0, 1, { ARG_ID("slices", 3, 2048, 100) }, NULL },
    { "LinesAdjacency", GLIB_CMD_LINES_ADJACENCY, false, glib_h_nums, false, 12, 12,
      { XYZ_ARGS(0), XYZ_ARGS(1), XYZ_ARGS(2), XYZ_ARGS(3) }, "LinesAdjacency x0 y0 z0 x1 y1 z1 x2 y2 z2 x3 y3 z3" },
    { "Triangles", GLIB_CMD_TRIANGLES, false, glib_h_nums, false, 9, 9,
      { XYZ_ARGS(0), XYZ_ARGS(1), XYZ_ARGS(2) }, "Triangles x0 y0 z0 x1 y1 z1 x2 y2 z2" },
    { "NumPatchVertices", GLIB_CMD_NUM_PATCH_VERTICES, false, glib_h_nums, false, 1, 1,
      { ARG_I("n", "a patch size (vertices a patch)", 1, 32) }, NULL },
    { "glBegin", GLIB_CMD_GL_BEGIN, false, glib_h_begin, false, 0, 0, { { 0 } }, "glBegin gl_patches" },
    { "glVertex", GLIB_CMD_GL_VERTEX, false, glib_h_vertex, false, 3, 4,
      { ARG_R("x", NULL), ARG_R("y", NULL), ARG_R("z", "a z"), ARG_RD("w", 1) }, NULL },
    { "glEnd", GLIB_CMD_GL_END, false, glib_h_end, false, 0, 0, { { 0 } }, "glEnd" },
    { "Color", GLIB_CMD_COLOR, false, glib_h_nums, false, 3, 4, RGBA_ARGS, NULL },
    { "Texture2D", GLIB_CMD_TEXTURE2D_FILE, false, h_tex2d, false, 0, 0, { { 0 } },
      "Texture2D unit file | Texture2D unit w h [float|float16|depth]" },
    { "Texture3D", GLIB_CMD_TEXTURE3D, false, h_tex3d, false, 0, 0, { { 0 } },
      "Texture3D unit file | Texture3D unit w h d" },
    { "CubeMap", GLIB_CMD_CUBEMAP, false, glib_h_cube, false, 0, 0, { { 0 } },
      "CubeMap unit +x -x +y -y +z -z" },
    { "Noise2D", GLIB_CMD_NOISE2D, false, glib_h_nums, false, 0, 1, { ARG_ID("res", 1, 4096, 64) }, NULL },
    { "Noise3D", GLIB_CMD_NOISE3D, false, glib_h_nums, false, 0, 1, { ARG_ID("res", 1, 400, 64) }, NULL },
    { "RenderToTexture", GLIB_CMD_RENDER_TO_TEXTURE, false, glib_h_rtt, false, 0, 0, { { 0 } },
      "RenderToTexture [unit ...]" },
    { "Clear", GLIB_CMD_CLEAR, false, glib_h_nums, false, 0, 0, { { 0 } }, NULL },
    { "Background", GLIB_CMD_BACKGROUND, false, glib_h_nums, false, 3, 4, RGBA_ARGS, NULL },
    { "Vertex", GLIB_CMD_VERTEX, false, glib_h_stage, false, 0, 0, { { 0 } }, "Vertex file.vert" },
    { "TessControl", GLIB_CMD_TESS_CONTROL, false, glib_h_stage, false, 0, 0, { { 0 } }, "TessControl file.tcs" },
    { "TessEvaluation", GLIB_CMD_TESS_EVALUATION, false, glib_h_stage, false, 0, 0, { { 0 } },
      "TessEvaluation file.tes" },
    { "Geometry", GLIB_CMD_GEOMETRY, false, glib_h_stage, false, 0, 0, { { 0 } }, "Geometry file.geom" },
    { "Fragment", GLIB_CMD_FRAGMENT, false, glib_h_stage, false, 0, 0, { { 0 } }, "Fragment file.frag" },
    { "Program", GLIB_CMD_PROGRAM, false, glib_h_program, true, 0, 0, { { 0 } },
      "Program Name [uniform value ...]" },
    { "Timer", GLIB_CMD_TIMER, false, glib_h_nums, false, 1, 1, { ARG_P("secs", "a period in seconds") }, NULL },
    { "GSTAP", GLIB_CMD_GSTAP, false, glib_h_nums, false, 0, 0, { { 0 } }, NULL },
    { "Include", GLIB_CMD_NONE, false, glib_h_include, false, 0, 0, { { 0 } }, "Include file.glib" },
    { "Define", GLIB_CMD_DEFINE, false, glib_h_define, true, 0, 0, { { 0 } },
      "Define NAME [<true>|<false>|value|<min default max>]" },
    { "Cull", GLIB_CMD_CULL, false, glib_h_cull, false, 0, 0, { { 0 } }, "Cull back|front|none" },
    { "DepthTest", GLIB_CMD_DEPTH_TEST, false, glib_h_depth, false, 0, 0, { { 0 } }, "DepthTest on|off" },
    { "Blend", GLIB_CMD_BLEND, false, glib_h_blend, false, 0, 0, { { 0 } }, "Blend off|alpha|add" },
    /* glman's state commands and its message box */
    { "Flat", GLIB_CMD_FLAT, false, glib_h_nums, false, 0, 0, { { 0 } }, NULL },
    { "Smooth", GLIB_CMD_SMOOTH, false, glib_h_nums, false, 0, 0, { { 0 } }, NULL },
    { "LineWidth", GLIB_CMD_LINE_WIDTH, false, glib_h_nums, false, 0, 1, { ARG_PD("width", 1) }, NULL },
    { "PointSize", GLIB_CMD_POINT_SIZE, false, glib_h_nums, false, 0, 1, { ARG_PD("size", 1) }, NULL },
    { "PointSizeMode", GLIB_CMD_POINT_SIZE_MODE, false, glib_h_nums, false, 0, 1, { ARG_RD("n", 1) }, NULL },
    { "Clamp", GLIB_CMD_CLAMP, false, glib_h_clamp, false, 0, 0, { { 0 } }, "Clamp" },
    { "MessageBox", GLIB_CMD_NONE, false, glib_h_message, true, 0, 0, { { 0 } }, "MessageBox text" },
    /* describing the world */
    { "Sun", GLIB_CMD_SUN, false, glib_h_world_nums, false, 3, 6,
      { ARG_R("dx", NULL), ARG_R("dy", NULL), ARG_R("dz", "a direction z"), ARG_RD("r", 0),
        ARG_RD("g", 0), ARG_RD("b", 0) }, NULL, true },
    { "Sky", GLIB_CMD_SKY, false, glib_h_world_nums, false, 6, 6,
      { ARG_R("zr", NULL), ARG_R("zg", NULL), ARG_R("zb", NULL), ARG_R("hr", NULL),
        ARG_R("hg", NULL), ARG_R("hb", "a horizon blue") }, NULL, true },
    { "SkySun", GLIB_CMD_SKY_SUN, false, glib_h_world_nums, false, 1, 2,
      { ARG_R("radius_deg", "an angular radius in degrees"), ARG_RD("gain", 0) }, "SkySun radius_deg [gain]", true },
    { "Clouds", GLIB_CMD_CLOUDS, false, glib_h_world_nums, false, 1, 3,
      { ARG_R("cover", "a cloud cover from 0 to 1"), ARG_RD("scale", 0), ARG_RD("height", 0) },
      "Clouds cover [scale [height]]", true },
    { "Haze", GLIB_CMD_HAZE, false, glib_h_world_nums, false, 1, 1, { ARG_R("distance", "a distance in metres") },
      "Haze distance", true },
    { "GroundDetail", GLIB_CMD_GROUND_DETAIL, false, glib_h_world_nums, false, 1, 1,
      { ARG_R("amount", "an amount from 0 to 1") }, "GroundDetail amount", true },
    { "Water", GLIB_CMD_WATER, false, glib_h_world_nums, false, 1, 5,
      { ARG_R("level", "a water level"), ARG_RD("ior", 0), ARG_RD("ar", 0), ARG_RD("ag", 0),
        ARG_RD("ab", 0) }, "Water level [ior [ar ag ab]]", true },
    { "WaterMesh", GLIB_CMD_WATER_MESH, false, glib_h_world_nums, false, 1, 1,
      { { "res", "a resolution (grid cells per side)", 'i', 0, 65536, 0 } }, NULL, true },
    { "Terrain", GLIB_CMD_TERRAIN, false, glib_h_terrain, false, 0, 0, { { 0 } },
      "Terrain flat|lake|slope|pool [half_size [depth [shore_height_or_slope [seed [res]]]]]", true },
    { "WaveSine", GLIB_CMD_WAVE_SINE, false, glib_h_world_nums, false, 3, 5, WAVE_ARGS,
      "WaveSine angle_deg wavelength amplitude [speed [phase]]", true },
    { "WaveGerstner", GLIB_CMD_WAVE_GERSTNER, false, glib_h_world_nums, false, 3, 5, WAVE_ARGS,
      "WaveGerstner angle_deg wavelength amplitude [speed [phase]]", true },
    { "WaveSteepness", GLIB_CMD_WAVE_STEEPNESS, false, glib_h_world_nums, false, 1, 1,
      { ARG_R("Q", "a steepness Q") }, NULL, true },
    { "WaveNoise", GLIB_CMD_WAVE_NOISE, false, glib_h_world_nums, false, 1, 8,
      { ARG_R("amplitude", "an amplitude"), ARG_RD("cell", 0), { "octaves", NULL, 'i', 0, 64, 0 },
        ARG_RD("speed", 0), ARG_RD("angle_deg", 0), SEED_RULE("seed"),
        { "period", NULL, 'i', 0, 65536, 0 }, ARG_RD("gain", 0) },
      "WaveNoise amplitude [cell [octaves [speed [angle_deg [seed [period [gain]]]]]]]", true },
    { "WaveOcean", GLIB_CMD_WAVE_OCEAN, false, glib_h_wave_ocean, false, 0, 0, { { 0 } },
      "WaveOcean phillips|jonswap|tma wind_speed [wind_angle_deg [choppiness [res [seed [fetch [depth [spreading [amplitude]]]]]]]]", true },
    { "WaveOceanTiles", GLIB_CMD_WAVE_OCEAN_TILES, false, glib_h_world_nums, false, 1, 3,
      { ARG_R("tile", "a tile side in metres"), ARG_RD("tile2", 0), ARG_RD("tile3", 0) },
      "WaveOceanTiles tile [tile2 [tile3]]", true },
    { "WaveExplosion", GLIB_CMD_WAVE_EXPLOSION, false, glib_h_world_nums, false, 4, 7,
      { ARG_R("x", NULL), ARG_R("z", NULL), ARG_R("start", NULL), ARG_R("i0", "an amplitude I0"),
        ARG_RD("omega", 0), ARG_RD("k", 0), ARG_RD("decay", 0) },
      "WaveExplosion x z start i0 [omega [k [decay]]]", true },
    { "WavePerlin", GLIB_CMD_WAVE_PERLIN, false, glib_h_world_nums, false, 1, 8,
      { ARG_R("amplitude", "an amplitude"), ARG_RD("cell", 0), { "octaves", NULL, 'i', 0, 64, 0 },
        ARG_RD("rate", 0), ARG_RD("stretch", 0), ARG_RD("angle_deg", 0), SEED_RULE("seed"),
        ARG_RD("gain", 0) },
      "WavePerlin amplitude [cell [octaves [rate [stretch [angle_deg [seed [gain]]]]]]]", true },
    { "Flow", GLIB_CMD_FLOW, false, glib_h_flow, false, 0, 0, { { 0 } },
      "Flow current vx vz | Flow vortex x z strength radius | Flow texture file scale | Flow detail amplitude [cell [period [foam]]]", true },
    { "Spray", GLIB_CMD_SPRAY, false, glib_h_world_nums, false, 2, 6,
      { ARG_R("threshold", "an upward speed threshold (m/s)"), ARG_R("rate", "a rate (particles/s)"),
        ARG_RD("life", 0), ARG_RD("size", 0), SEED_RULE("seed"), { "count", NULL, 'i', 0, 1048576, 0 } },
      "Spray threshold rate [life [size [seed [count]]]]", true },
    { "Object", GLIB_CMD_OBJECT, false, glib_h_object, false, 0, 0, { { 0 } },
      "Object sphere x y z r R G B | Object box x y z hx hy hz R G B | Object cylinder x y z r h R G B | "
      "Object mesh file.obj x y z [rot_y_deg [scale [R G B]]]", true },
    { "Pack", GLIB_CMD_PACK, false, glib_h_pack, false, 0, 0, { { 0 } }, "Pack name", true },
    /* drawing the world (packs) */
    { "World", GLIB_CMD_WORLD, false, glib_h_world, false, 0, 0, { { 0 } }, "World [all|above|below [offset|uniform]]" },
    { "WaterSurface", GLIB_CMD_WATER_SURFACE, false, glib_h_water_surface, false, 0, 0, { { 0 } },
      "WaterSurface [points N|mesh N]" },
    { "Camera", GLIB_CMD_CAMERA, false, glib_h_camera, false, 0, 0, { { 0 } },
      "Camera main|wide|mirror|top|light [fov_scale|uniform]" },
    { "RenderToTextureOnce", GLIB_CMD_RENDER_TO_TEXTURE_ONCE, false, glib_h_rtt, false, 0, 0, { { 0 } },
      "RenderToTextureOnce unit [unit...]" },
    { "If", GLIB_CMD_IF, false, glib_h_if, false, 0, 0, { { 0 } }, "If [not] DEFINE|above_water|under_water|waves" },
    { "EndIf", GLIB_CMD_END_IF, false, glib_h_nums, false, 0, 0, { { 0 } }, NULL },
    { "Splat", GLIB_CMD_SPLAT, false, glib_h_nums, false, 2, 2,
      { { "src", "a texture unit", 'i', 0, LIM_UNIT, 0 }, { "dst", "a texture unit", 'i', 0, LIM_UNIT, 0 } },
      "Splat src_unit dst_unit" },
};

#define NSPECS (sizeof specs / sizeof specs[0])

bool glib_cmd_describes_world(glib_cmd_kind kind) {
    /* every spelling of a kind shares the row's flag */
    for (size_t i = 0; i < NSPECS; i++)
        if (specs[i].kind == kind)
            return specs[i].world;
    return false;
}

const cmd_spec *glib_find_spec(const char *name) {
    for (size_t i = 0; i < NSPECS; i++)
        if (strcasecmp(specs[i].name, name) == 0)
            return &specs[i];
    return NULL;
}

/* Case-insensitive edit distance, for "did you mean"; long words don't
 * get a suggestion. */
int glib_edit_distance(const char *a, const char *b) {
    enum { MAXW = 32 };
    size_t la = strlen(a), lb = strlen(b);
    if (la >= MAXW || lb >= MAXW)
        return MAXW;
    int d[MAXW][MAXW];
    for (size_t i = 0; i <= la; i++)
        d[i][0] = (int)i;
    for (size_t j = 0; j <= lb; j++)
        d[0][j] = (int)j;
    for (size_t i = 1; i <= la; i++)
        for (size_t j = 1; j <= lb; j++) {
            int sub = d[i - 1][j - 1] +
                      (tolower((unsigned char)a[i - 1]) != tolower((unsigned char)b[j - 1]));
            int del = d[i - 1][j] + 1, ins = d[i][j - 1] + 1;
            d[i][j] = sub < del ? (sub < ins ? sub : ins) : (del < ins ? del : ins);
        }
    return d[la][lb];
}

const char *glib_suggest(const char *name) {
    const char *best = NULL;
    int best_d = 3;             /* at most 2 edits */
    for (size_t i = 0; i < NSPECS; i++) {
        int dist = glib_edit_distance(name, specs[i].name);
        if (dist < best_d && (size_t)dist < strlen(name) / 2 + 1) {
            best_d = dist;
            best = specs[i].name;
        }
    }
    return best;
}
