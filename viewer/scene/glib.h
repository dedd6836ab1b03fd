/* glib: the parser of glman-style .glib scene files.
 *
 * A .glib file is a list of commands that glman executes in order every
 * frame. The parser turns the text into that list (glib_cmd), resolving our
 * `Include` extension inline, and collects diagnostics (file:line: message)
 * instead of stopping: unknown commands and bad lines are skipped with a
 * message, so a half-written file still shows what it can.
 *
 * Nothing here touches OpenGL or the file system beyond reading the glib
 * and its includes; paths are resolved relative to the file that names them.
 */
#ifndef TARN_GLIB_H
#define TARN_GLIB_H

#include <stdbool.h>
#include <stddef.h>

#include "diag.h"        /* diagnostics: one type for all of tarn */
#include "unif_decl.h"   /* a Program line's uniforms (unif_decl) */

#define GLIB_NAME_MAX UNIF_NAME_MAX
#define GLIB_PATH_MAX 1024
#define GLIB_MAX_NUMS UNIF_DECL_MAX_NUMS /* numbers one command or uniform may carry */
#define GLIB_MAX_UNITS 8        /* RenderToTexture units at once */

typedef enum glib_cmd_kind {
    GLIB_CMD_NONE = 0,
    /* viewing */
    GLIB_CMD_WINDOW_SIZE,       /* num: w h */
    GLIB_CMD_PERSPECTIVE,       /* num: fov_degrees [near far] */
    GLIB_CMD_ORTHO,             /* num: l r b t [near far] */
    GLIB_CMD_LOOKAT,            /* num: ex ey ez cx cy cz ux uy uz */
    /* transforms */
    GLIB_CMD_TRANSLATE,         /* num: x y z */
    GLIB_CMD_ROTATE,            /* num: deg ax ay az */
    GLIB_CMD_SCALE,             /* num: s, or sx sy sz (nnum 1 or 3) */
    GLIB_CMD_PUSH_MATRIX,
    GLIB_CMD_POP_MATRIX,
    /* geometry; `wire` set for the Wire* variants */
    GLIB_CMD_QUAD_XY,           /* num: z size nx ny */
    GLIB_CMD_QUAD_XZ,           /* num: y size nx nz */
    GLIB_CMD_QUAD_YZ,           /* num: x size ny nz */
    GLIB_CMD_SPHERE,            /* num: r [slices stacks] */
    GLIB_CMD_TORUS,             /* num: r_major r_minor [sides rings] */
    GLIB_CMD_BOX,               /* num: dx [dy dz] (full edge lengths) */
    GLIB_CMD_CYLINDER,          /* num: r h [slices stacks] */
    GLIB_CMD_CONE,              /* num: r h [slices stacks] */
    GLIB_CMD_TEAPOT,            /* num: [size] */
    GLIB_CMD_OBJ,               /* path; wire: WireObj (its edges) */
    GLIB_CMD_COLOR,             /* num: r g b [a] -> gl_Color for what follows */
    /* textures; num[0] is the texture unit */
    GLIB_CMD_TEXTURE2D_FILE,    /* num: unit; path */
    GLIB_CMD_TEXTURE2D_EMPTY,   /* num: unit w h; format; name, arg: the sliders giving
                                 * w and h when written as names (num 0 then) */
    GLIB_CMD_TEXTURE3D,         /* num: unit; path (a 3D image, or w h d empty: nnum 4) */
    GLIB_CMD_CUBEMAP,           /* num: unit; paths[6] in +x -x +y -y +z -z order */
    GLIB_CMD_NOISE2D,           /* num: res (unit 2, sampler Noise2) */
    GLIB_CMD_NOISE3D,           /* num: res (unit 3, sampler Noise3) */
    /* passes */
    GLIB_CMD_RENDER_TO_TEXTURE, /* num: units... (nnum 0 = back to the screen) */
    GLIB_CMD_CLEAR,
    GLIB_CMD_BACKGROUND,        /* num: r g b [a] */
    /* shaders */
    GLIB_CMD_VERTEX,            /* path, or empty to unset the stage */
    GLIB_CMD_TESS_CONTROL,
    GLIB_CMD_TESS_EVALUATION,
    GLIB_CMD_GEOMETRY,
    GLIB_CMD_FRAGMENT,
    GLIB_CMD_PROGRAM,           /* name; uniforms[]; defines[] pending at that point */
    /* time and compatibility */
    GLIB_CMD_TIMER,             /* num: period seconds */
    GLIB_CMD_GSTAP,             /* prepend the GSTAP defines to following stages */
    /* our extensions (docs/glib.md) */
    GLIB_CMD_DEFINE,            /* name; a #define toggle: uniform kind BOOL, or a value */
    GLIB_CMD_CULL,              /* name: "back" | "front" | "none" */
    GLIB_CMD_DEPTH_TEST,        /* num: 0 | 1 (name "off" | "on") */
    GLIB_CMD_BLEND,             /* name: "off" | "alpha" | "add" */
    /* describing the world (docs/glib.md, "Describing the world"). Unlike
     * the commands above, these keep nnum = the numbers written: what is
     * left out takes the world model's default (ref_world_init), and the
     * ranges are checked and repaired by scene_from_glib (viewer/scene/scene.h) */
    GLIB_CMD_SUN,               /* num: dx dy dz [r g b] (nnum 3 or 6) */
    GLIB_CMD_SKY,               /* num: zr zg zb hr hg hb */
    GLIB_CMD_SKY_SUN,           /* num: radius_deg [gain] (the sun's disc) */
    GLIB_CMD_CLOUDS,            /* num: cover [scale height] */
    GLIB_CMD_HAZE,              /* num: distance */
    GLIB_CMD_GROUND_DETAIL,     /* num: amount */
    GLIB_CMD_WATER,             /* num: level [ior [ar ag ab]] (nnum 1, 2 or 5) */
    GLIB_CMD_WATER_MESH,        /* num: res */
    GLIB_CMD_TERRAIN,           /* name: "flat" | "lake" | "slope";
                                 * num: [half_size depth shore_height_or_slope seed res] */
    GLIB_CMD_WAVE_SINE,         /* num: angle_deg wavelength amplitude [speed phase] */
    GLIB_CMD_WAVE_GERSTNER,     /* num: as WaveSine */
    GLIB_CMD_WAVE_STEEPNESS,    /* num: Q */
    GLIB_CMD_WAVE_NOISE,        /* num: amplitude [cell octaves speed angle_deg seed period gain] */
    GLIB_CMD_WAVE_OCEAN,        /* name: "phillips" | "jonswap" | "tma"; num: wind_speed
                                 * [wind_angle_deg choppiness res seed fetch depth spreading amplitude] */
    GLIB_CMD_WAVE_OCEAN_TILES,  /* num: the cascades' tile sides, 1 to 3, decreasing */
    GLIB_CMD_WAVE_EXPLOSION,    /* num: x z start i0 [omega k decay] */
    GLIB_CMD_WAVE_PERLIN,       /* num: amplitude [cell octaves rate stretch angle_deg seed gain] */
    GLIB_CMD_FLOW,              /* name: "current" | "vortex" | "texture" | "detail"; num: current
                                 * vx vz; vortex x z strength radius; texture scale (path: the
                                 * file); detail amplitude [cell period foam] */
    GLIB_CMD_SPRAY,             /* num: threshold rate [life size seed count] */
    GLIB_CMD_OBJECT,            /* name: "sphere" | "box" | "cylinder"; num:
                                 * sphere x y z r R G B; box x y z hx hy hz R G B;
                                 * cylinder x y z r h R G B (y: its base);
                                 * "mesh": path; num x y z [rot_y_deg scale R G B] (nnum 3-8) */
    GLIB_CMD_PACK,              /* name: the pack (after the override); with
                                 * glib_options.packs_dir its pack.glib follows inline */
    /* drawing the world (in packs) */
    GLIB_CMD_CAMERA,            /* name: main|wide|mirror|top|light; num[0] fov scale (nnum 1),
                                   or arg: a float uniform of the last Program */
    GLIB_CMD_RENDER_TO_TEXTURE_ONCE, /* num: units; runs only on the first frame after a load */
    GLIB_CMD_SPLAT,             /* num: src_unit dst_unit (CPU photon splat) */
    GLIB_CMD_IF,                /* name: a condition; num[0] = 1 for `If not NAME` */
    GLIB_CMD_END_IF,
    GLIB_CMD_WORLD,             /* name: "all" | "above" | "below" (default "all") */
    GLIB_CMD_WATER_SURFACE,     /* the water grid, with the current program; name "points":
                                 * N x N points, num[0] = N or arg = the slider giving N;
                                 * name "mesh": the same points as the corners of
                                 * 2 (N - 1)^2 triangles (gl_VertexID = j N + i) */
    /* glman's state commands (seen in real course files) */
    GLIB_CMD_FLAT,              /* shading model flat: the provoking vertex's colour */
    GLIB_CMD_SMOOTH,            /* shading model smooth (the default) */
    GLIB_CMD_LINE_WIDTH,        /* num: width [1] */
    GLIB_CMD_POINT_SIZE,        /* num: size [1] */
    GLIB_CMD_POINT_SIZE_MODE,   /* num: n [1]; nonzero lets the shader set gl_PointSize */
    GLIB_CMD_CLAMP,             /* texture wrap clamp: accepted as state, draws nothing */
    /* glman's other geometry (docs/glib.md, "Geometry") */
    GLIB_CMD_DISK_XY,           /* the unit disk in z = 0 */
    GLIB_CMD_QUAD_BOX,          /* num: n [10] */
    GLIB_CMD_POINT_CLOUD,       /* num: nx ny nz [10 10 10] */
    GLIB_CMD_JITTER_CLOUD,      /* num: nx ny nz [10 10 10] */
    GLIB_CMD_SOCCERBALL,        /* num: r [1] */
    GLIB_CMD_XARROW,            /* num: slices [100] */
    GLIB_CMD_LINES_ADJACENCY,   /* num: 4 points x y z (12) */
    GLIB_CMD_TRIANGLES,         /* num: 3 points x y z (9) */
    GLIB_CMD_OBJ_ADJ,           /* path: drawn as GL_TRIANGLES_ADJACENCY */
    GLIB_CMD_OBJ_PATCH,         /* path: drawn as GL_PATCHES */
    /* tessellation */
    GLIB_CMD_NUM_PATCH_VERTICES, /* num: n, the patch size for the draws that follow */
    GLIB_CMD_GL_BEGIN,          /* name: the primitive, lower case ("gl_patches") */
    GLIB_CMD_GL_VERTEX,         /* num: x y z [w] (nnum 4, w 1 when not written) */
    GLIB_CMD_GL_END,
    GLIB_CMD_SHP,               /* path: an ESRI shapefile (.shp), drawn as lines */
    GLIB_CMD_KIND_COUNT
} glib_cmd_kind;

typedef enum glib_target_format {
    GLIB_TARGET_RGBA8 = 0,      /* default for `Texture2D unit w h` */
    GLIB_TARGET_RGBA16F,        /* extension: `Texture2D unit w h float16` */
    GLIB_TARGET_RGBA32F,        /* extension: `Texture2D unit w h float` */
    GLIB_TARGET_DEPTH           /* extension: `Texture2D unit w h depth` */
} glib_target_format;

typedef struct glib_cmd {
    glib_cmd_kind kind;
    const char *file;           /* the file it came from (points into glib_scene.files) */
    int line;                   /* 1-based line in that file */
    bool wire;                  /* Wire* geometry variant */
    double num[GLIB_MAX_NUMS];
    int nnum;                   /* optional arguments are filled with their
                                 * defaults and counted (`Sphere 1` -> 1 32 16,
                                 * nnum 3); Scale keeps the 1 or 3 written */
    char name[GLIB_NAME_MAX];   /* Program name, Define name, Cull/Blend mode */
    char path[GLIB_PATH_MAX];   /* resolved file path (absolute or relative to cwd) */
    char (*cube_paths)[GLIB_PATH_MAX]; /* CubeMap: 6 resolved paths (heap) */
    glib_target_format format;  /* Texture2D empty */
    unif_decl *uniforms;     /* Program: its uniforms (heap); Define: uniforms[0] */
    int nuniforms;
    /* Program: the `Define` toggles written since the previous Program
     * (heap copies; kind BOOL for `Define NAME <true>`, SCALAR/SLIDER for
     * `Define NAME 3` / `Define NAME <1 4 8>`) */
    unif_decl *defines;
    int ndefines;
    char arg[GLIB_NAME_MAX];    /* Camera, World: the uniform that gives fov_scale or the clip
                                   offset ("" when a number is written) */
} glib_cmd;


typedef struct glib_scene {
    glib_cmd *cmds;
    int ncmds;
    diag *diags;                /* file points to a copy of the file name */
    int ndiags;
    int nerrors;                /* diags with DIAG_ERROR */
    /* every file read (the glib and its includes), each a heap string;
     * cmds and diags point into these */
    char **files;
    int nfiles;
    /* the cache its files were read through (glib_options.files; NULL: the
     * disk), borrowed: the files its commands name (OBJ models, textures,
     * the reference's meshes) are read through it too */
    struct file_cache *read_through;
} glib_scene;

/* Parses a .glib file from disk. Always returns a scene (never NULL); the
 * caller checks scene->nerrors and prints scene->diags. A missing or empty
 * file is an error diagnostic at line 1 (or 0 when it cannot be opened).
 *
 * Bounds (bad input costs bounded memory): a file of at most 1 MiB, logical
 * lines of 16384 characters, 16384 commands, 256 uniforms on a Program,
 * Includes 32 levels deep and 256 in all, 200 diagnostics (the last one
 * then says how many more there were). A command whose required arguments
 * are missing or malformed is skipped; a Program keeps its good uniforms.
 * A file named by a command but missing now is an error that keeps the
 * command (it may appear before the renderer needs it). */
glib_scene *glib_load(const char *path);

/* Options of glib_load_opts (zero or NULL fields: off). */
typedef struct glib_options {
    /* Where packs live (e.g. tarn_root() + "/packs"). When set, a
     * `Pack name` command reads <packs_dir>/<name>/pack.glib in place, like
     * Include (its diagnostics name the pack's file and lines); a pack that
     * is not there is an error at the Pack line that lists the packs there
     * are (directories holding a pack.glib). The Pack command itself stays
     * in the list, before the pack's commands. */
    const char *packs_dir;
    /* A pack chosen from outside (`--pack`): it replaces the name on the
     * scene's Pack command; when the scene has none, a Pack command for it
     * (line 0 of the top file) is added at the end of the top file. */
    const char *pack_override;
    /* Where the scene's files are read (file_cache.h); NULL: from disk. */
    struct file_cache *files;
} glib_options;

/* glib_load with options; glib_load(path) is glib_load_opts(path, NULL).
 * Only the first Pack command of a scene counts: later ones are warnings
 * and skipped. */
glib_scene *glib_load_opts(const char *path, const glib_options *opt);

/* Parses text in memory, as if it were the file `virtual_path` (used for
 * tests and the fuzzer). Includes are resolved relative to virtual_path. */
glib_scene *glib_parse(const char *text, size_t len, const char *virtual_path);

void glib_free(glib_scene *scene);

/* Writes every diagnostic as `file:line: warning|error: message` to stream
 * (a FILE*; void* keeps stdio out of this header). */
void glib_print_diags(const glib_scene *scene, void *stream);

/* Whether a command of the scene reads the uniform `name` itself (Camera,
 * World, WaterSurface points, a Texture2D size): a slider the glib uses,
 * which the shaders need not declare. *is_count (may be NULL) says whether
 * it is read as a whole number (a size or a point count). */
bool glib_uniform_consumed(const glib_scene *scene, const char *name, bool *is_count);

/* A Program command's declarations as the uniform model takes them
 * (pointers into the command). */
unif_program_decl glib_program_decl(const glib_cmd *program);

/* Fills set (zeroed by the caller) from a Program command through
 * unif_set_from_decls (its repairs warnings in dl, which may be NULL).
 * False, with an error in dl, when it is not a Program command. */
struct unif_set;
bool glib_unif_set(struct unif_set *set, const glib_cmd *program, diag_list *dl);

/* Whether a command of this kind describes the world (Sun, Sky, Water,
 * WaterMesh, Terrain, Wave*, Object, Pack: docs/glib.md, "Describing the
 * world"), a flag of its row in the command table. The commands packs draw
 * the world with (World, WaterSurface, Camera, If, ...) do not: a plain
 * glman scene may use them and still has no world. */
bool glib_cmd_describes_world(glib_cmd_kind kind);

/* The command's name as written in docs ("QuadXZ"), for messages. */
const char *glib_cmd_name(glib_cmd_kind kind);

#endif
