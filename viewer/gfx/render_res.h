/* render_res: GPU meshes and textures made from glib commands, with a key
 * per resource so a reload reuses what did not change. Private to the renderer (render*.c). */
#ifndef TARN_RENDER_RES_H
#define TARN_RENDER_RES_H

#include <stdbool.h>
#include "glib.h"

#define RES_KEY_MAX (GLIB_PATH_MAX * 2)

typedef struct gpu_mesh {
    char key[RES_KEY_MAX];
    unsigned vbo, ibo;
    int nidx;
    int prim;                   /* geom_prim */
    int patch_size;             /* GEOM_PATCHES: vertices a patch; 0: NumPatchVertices */
    long off_nrm, off_tc, off_tan;   /* tc: 3 floats a vertex (s t p) */
    int *part_first;            /* parts drawn one by one (geom.h); NULL: one draw */
    int nparts;
} gpu_mesh;

/* What a draw needs to know of the current program and state. */
typedef struct render_res_draw {
    int tangent_loc;            /* the Tangent attribute, or -1 */
    int face_index_loc;         /* the FaceIndex uniform, or -1 */
    bool face_index_int;        /* declared int (else float) */
    bool tess;                  /* the program tessellates: draws become GL_PATCHES */
    int patch_vertices;         /* NumPatchVertices now */
} render_res_draw;

typedef struct gpu_tex {
    char key[RES_KEY_MAX];      /* command + file stamps: equal key, same texture */
    char path[GLIB_PATH_MAX];   /* first file, to keep the last good image on failure */
    unsigned tex;
    unsigned target;            /* GL_TEXTURE_2D, _3D, _CUBE_MAP */
    int unit, w, h;
    glib_target_format format;
    bool render_target;         /* an empty Texture2D that RenderToTexture draws into */
} gpu_tex;

/* The reuse key of a geometry or texture command (includes file size and
 * modification time of the files it reads). */
void render_res_key(const glib_cmd *c, char *out, int outlen);

/* Gives a render target a new image of w x h texels (same format; the
 * old contents are gone). Nothing happens when the size is the same. */
void render_res_target_resize(gpu_tex *t, int w, int h);

/* The mesh or texture of command c, its files (OBJ, shapefile, images,
 * raw textures) read through files (file_cache.h; NULL: the disk); a
 * failure is a message in *log at c's line. */
struct file_cache;
bool render_res_mesh_build(const glib_cmd *c, struct file_cache *files, gpu_mesh *m, diag_list *log);
struct geom_mesh;
bool render_res_mesh_upload(const struct geom_mesh *g, gpu_mesh *m);
void render_res_mesh_draw(const gpu_mesh *m, int tangent_loc);
/* Draws m for the current program as d says. A draw that cannot work
 * (patches without a tessellating program) is not made: false, with the
 * reason in why (a sentence saying what to do). A draw made with a
 * problem (vertices left over from whole patches) is true with why set. */
bool render_res_mesh_draw_with(const gpu_mesh *m, const render_res_draw *d, char *why, int whylen);
/* The primitive OpenGL gets for m under d, as GL names it ("GL_PATCHES"). */
const char *render_res_mesh_prim_name(const gpu_mesh *m, const render_res_draw *d);
void render_res_mesh_free(gpu_mesh *m);

/* Draws whose vertices come from gl_VertexID alone (a triangle over the
 * viewport, a point a particle): begin pushes the client vertex-array
 * state and turns every array off (a compatibility context would feed an
 * enabled one to the draw), end pops it. */
void render_res_vertexid_begin(void);
void render_res_vertexid_end(void);
/* A pass into a w x h target of its own: viewport, no depth test,
 * blending, scissor or culling. */
void render_res_pass_state(int w, int h);

bool render_res_tex_build(const glib_cmd *c, struct file_cache *files, gpu_tex *t, diag_list *log);
/* img_read through files (file_cache.h; NULL: the disk); a format
 * OpenImageIO reads only from a file (image_io.h) is read from the disk. */
struct img;
bool render_res_read_image(struct file_cache *files, const char *path, struct img *im, char *err, int errlen);
/* Filtering and wrapping of the bound texture; mipmaps are generated. */
void render_res_sampling(unsigned target, bool mipmaps, unsigned wrap);
void render_res_tex_free(gpu_tex *t);
/* glman's Noise2 (unit 2) or Noise3 (unit 3), there without any command:
 * dir's noise2d.064.tex / noise3d.064.tex when present (glman's cache,
 * shipped with real projects), else tarn's 64-texel noise (noise.h). */
bool render_res_noise_builtin(struct file_cache *files, const char *dir, bool is3d, gpu_tex *t);

bool render_res_is_geometry(glib_cmd_kind k);
bool render_res_is_texture(glib_cmd_kind k);
/* Does a command of kind k draw (a clear, geometry, glBegin, the water, a
 * splat, the world)? */
bool render_res_writes_pixels(glib_cmd_kind k);

#endif
