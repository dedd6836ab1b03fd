#include "render_res.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <strings.h>
#include <sys/stat.h>

#include "assets.h"
#include "disk_cache.h"
#include "file_cache.h"
#include "geom.h"
#include "image_io.h"
#include "mem.h"
#include "noise.h"
#include "strbuf.h"

bool render_res_is_geometry(glib_cmd_kind k) {
    return k == GLIB_CMD_QUAD_XY || k == GLIB_CMD_QUAD_XZ || k == GLIB_CMD_QUAD_YZ ||
           k == GLIB_CMD_SPHERE || k == GLIB_CMD_TORUS || k == GLIB_CMD_BOX ||
           k == GLIB_CMD_CYLINDER || k == GLIB_CMD_CONE || k == GLIB_CMD_TEAPOT ||
           k == GLIB_CMD_OBJ || k == GLIB_CMD_OBJ_ADJ || k == GLIB_CMD_OBJ_PATCH ||
           k == GLIB_CMD_DISK_XY || k == GLIB_CMD_QUAD_BOX || k == GLIB_CMD_POINT_CLOUD ||
           k == GLIB_CMD_JITTER_CLOUD || k == GLIB_CMD_SOCCERBALL || k == GLIB_CMD_XARROW ||
           k == GLIB_CMD_LINES_ADJACENCY || k == GLIB_CMD_TRIANGLES || k == GLIB_CMD_SHP;
}

bool render_res_writes_pixels(glib_cmd_kind k) {
    return k == GLIB_CMD_CLEAR || render_res_is_geometry(k) || k == GLIB_CMD_GL_BEGIN || k == GLIB_CMD_WATER_SURFACE ||
           k == GLIB_CMD_SPLAT || k == GLIB_CMD_WORLD;
}

bool render_res_is_texture(glib_cmd_kind k) {
    return k == GLIB_CMD_TEXTURE2D_FILE || k == GLIB_CMD_TEXTURE2D_EMPTY ||
           k == GLIB_CMD_TEXTURE3D || k == GLIB_CMD_CUBEMAP ||
           k == GLIB_CMD_NOISE2D || k == GLIB_CMD_NOISE3D;
}

static void append_stamp(char *out, int outlen, const char *path) {
    struct stat st;
    size_t l = strlen(out);
    if (stat(path, &st) == 0)
        snprintf(out + l, (size_t)outlen - l, "|%s@%lld.%ld:%lld", path, (long long)st.st_mtim.tv_sec,
                 st.st_mtim.tv_nsec, (long long)st.st_size);
    else
        snprintf(out + l, (size_t)outlen - l, "|%s@missing", path);
}

void render_res_key(const glib_cmd *c, char *out, int outlen) {
    int l = snprintf(out, (size_t)outlen, "%d%c%d", (int)c->kind, c->wire ? 'w' : 's', (int)c->format);
    for (int i = 0; i < c->nnum && l < outlen; i++)
        l += snprintf(out + l, (size_t)(outlen - l), " %.9g", c->num[i]);
    if (c->kind == GLIB_CMD_TEXTURE2D_EMPTY && (c->name[0] || c->arg[0]) && l < outlen)
        l += snprintf(out + l, (size_t)(outlen - l), " =%s =%s", c->name, c->arg);
    if (c->kind == GLIB_CMD_CUBEMAP && c->cube_paths)
        for (int f = 0; f < 6; f++) append_stamp(out, outlen, c->cube_paths[f]);
    else if (c->path[0])
        append_stamp(out, outlen, c->path);
}

/* ---- meshes ---- */

static int arg_i(const glib_cmd *c, int i, int def) {
    return i < c->nnum ? (int)lrint(c->num[i]) : def;
}
static float arg_f(const glib_cmd *c, int i, float def) {
    return i < c->nnum ? (float)c->num[i] : def;
}

static bool make_mesh(const glib_cmd *c, file_cache *files, geom_mesh *g, char *err, int errlen) {
    bool w = c->wire;
    switch (c->kind) {
    case GLIB_CMD_QUAD_XY: return geom_quad(g, 2, arg_f(c, 0, 0), arg_f(c, 1, 1), arg_i(c, 2, 1), arg_i(c, 3, 1), w);
    case GLIB_CMD_QUAD_XZ: return geom_quad(g, 1, arg_f(c, 0, 0), arg_f(c, 1, 1), arg_i(c, 2, 1), arg_i(c, 3, 1), w);
    case GLIB_CMD_QUAD_YZ: return geom_quad(g, 0, arg_f(c, 0, 0), arg_f(c, 1, 1), arg_i(c, 2, 1), arg_i(c, 3, 1), w);
    case GLIB_CMD_SPHERE: return geom_sphere(g, arg_f(c, 0, 1), arg_i(c, 1, 32), arg_i(c, 2, 16), w);
    case GLIB_CMD_TORUS: return geom_torus(g, arg_f(c, 0, 1), arg_f(c, 1, 0.25f), arg_i(c, 2, 24), arg_i(c, 3, 48), w);
    case GLIB_CMD_BOX: {
        float dx = arg_f(c, 0, 1);
        return geom_box(g, dx, arg_f(c, 1, dx), arg_f(c, 2, dx), w);
    }
    case GLIB_CMD_CYLINDER: return geom_cylinder(g, arg_f(c, 0, 1), arg_f(c, 1, 1), arg_i(c, 2, 32), arg_i(c, 3, 1), w);
    case GLIB_CMD_CONE: return geom_cone(g, arg_f(c, 0, 1), arg_f(c, 1, 1), arg_i(c, 2, 32), arg_i(c, 3, 1), w);
    case GLIB_CMD_TEAPOT: return geom_teapot(g, arg_f(c, 0, 1), 10, w);
    case GLIB_CMD_OBJ:
        return geom_obj_read(g, files, c->path, w ? GEOM_LINES : GEOM_TRIANGLES, err, errlen);
    case GLIB_CMD_OBJ_ADJ: return geom_obj_read(g, files, c->path, GEOM_TRIANGLES_ADJACENCY, err, errlen);
    case GLIB_CMD_OBJ_PATCH: return geom_obj_read(g, files, c->path, GEOM_PATCHES, err, errlen);
    case GLIB_CMD_SHP: return geom_shp_read(g, files, c->path, err, errlen);
    case GLIB_CMD_DISK_XY: return geom_disk_xy(g, 0);
    case GLIB_CMD_QUAD_BOX: return geom_quad_box(g, arg_i(c, 0, 10));
    case GLIB_CMD_POINT_CLOUD: case GLIB_CMD_JITTER_CLOUD:
        return geom_point_cloud(g, arg_i(c, 0, 10), arg_i(c, 1, 10), arg_i(c, 2, 10), c->kind == GLIB_CMD_JITTER_CLOUD);
    case GLIB_CMD_SOCCERBALL: return geom_soccerball(g, arg_f(c, 0, 1));
    case GLIB_CMD_XARROW: return geom_xarrow(g, arg_i(c, 0, 100));
    case GLIB_CMD_LINES_ADJACENCY: case GLIB_CMD_TRIANGLES: {
        float xyz[12];
        int n = c->kind == GLIB_CMD_TRIANGLES ? 3 : 4;
        for (int k = 0; k < 3 * n; k++) xyz[k] = arg_f(c, k, 0);
        return geom_points(g, xyz, n, n == 3 ? GEOM_TRIANGLES : GEOM_LINES_ADJACENCY);
    }
    default: return false;
    }
}

bool render_res_mesh_upload(const geom_mesh *g, gpu_mesh *m) {
    if (g->nvert <= 0 || g->nidx <= 0) return false;
    long nv = g->nvert;
    long sz_pos = nv * 3 * (long)sizeof(float);
    float *tc = mem_alloc((size_t)sz_pos);   /* s t p: p 0 where the mesh has none */
    for (long k = 0; k < nv; k++) {
        tc[3 * k] = g->tc[2 * k];
        tc[3 * k + 1] = g->tc[2 * k + 1];
        tc[3 * k + 2] = g->tcp ? g->tcp[k] : 0.0f;
    }
    m->off_nrm = sz_pos;
    m->off_tc = 2 * sz_pos;
    m->off_tan = 3 * sz_pos;
    glGenBuffers(1, &m->vbo);
    glBindBuffer(GL_ARRAY_BUFFER, m->vbo);
    glBufferData(GL_ARRAY_BUFFER, 4 * sz_pos, NULL, GL_STATIC_DRAW);
    glBufferSubData(GL_ARRAY_BUFFER, 0, sz_pos, g->pos);
    glBufferSubData(GL_ARRAY_BUFFER, m->off_nrm, sz_pos, g->nrm);
    glBufferSubData(GL_ARRAY_BUFFER, m->off_tc, sz_pos, tc);
    glBufferSubData(GL_ARRAY_BUFFER, m->off_tan, sz_pos, g->tan);
    free(tc);
    glGenBuffers(1, &m->ibo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (long)g->nidx * (long)sizeof(unsigned), g->idx, GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    m->nidx = g->nidx;
    m->prim = (int)g->prim;
    m->patch_size = g->patch_size;
    m->nparts = 0;
    m->part_first = NULL;
    if (g->part_first && g->nparts > 0) {
        m->part_first = mem_alloc(sizeof *m->part_first * (size_t)(g->nparts + 1));
        memcpy(m->part_first, g->part_first, sizeof *m->part_first * (size_t)(g->nparts + 1));
        m->nparts = g->nparts;
    }
    return true;
}

bool render_res_mesh_build(const glib_cmd *c, file_cache *files, gpu_mesh *m, diag_list *log) {
    geom_mesh g;
    memset(&g, 0, sizeof g);
    char err[MSG_MAX] = "";
    if (!make_mesh(c, files, &g, err, sizeof err) || !render_res_mesh_upload(&g, m)) {
        /* a file that is still missing: the parser said so at this line
         * ("cannot open 'x.shp' (from command Shp)"); once is enough */
        bool said = c->path[0] && access(c->path, R_OK) != 0;
        if (!said) diag_add(log, DIAG_ERROR, c->file, c->line, "cannot build %s: %s",
                    glib_cmd_name(c->kind), err[0] ? err : "bad arguments");
        geom_free(&g);
        return false;
    }
    geom_free(&g);
    return true;
}

/* geom_prim -> GL, and the vertices one primitive takes (0: a strip or a
 * patch, which has no fixed size). */
static const struct { GLenum mode; int verts; const char *name; } prims[] = {
    [GEOM_TRIANGLES] = { GL_TRIANGLES, 3, "GL_TRIANGLES" },
    [GEOM_LINES] = { GL_LINES, 2, "GL_LINES" },
    [GEOM_POINTS] = { GL_POINTS, 1, "GL_POINTS" },
    [GEOM_LINES_ADJACENCY] = { GL_LINES_ADJACENCY, 4, "GL_LINES_ADJACENCY" },
    [GEOM_TRIANGLES_ADJACENCY] = { GL_TRIANGLES_ADJACENCY, 6, "GL_TRIANGLES_ADJACENCY" },
    [GEOM_PATCHES] = { GL_PATCHES, 0, "GL_PATCHES" },
    [GEOM_LINE_STRIP] = { GL_LINE_STRIP, 0, "GL_LINE_STRIP" },
    [GEOM_LINE_LOOP] = { GL_LINE_LOOP, 0, "GL_LINE_LOOP" },
    [GEOM_TRIANGLE_STRIP] = { GL_TRIANGLE_STRIP, 0, "GL_TRIANGLE_STRIP" },
    [GEOM_TRIANGLE_FAN] = { GL_TRIANGLE_FAN, 0, "GL_TRIANGLE_FAN" },
    [GEOM_QUADS] = { GL_QUADS, 4, "GL_QUADS" },
};
#define NPRIMS ((int)(sizeof prims / sizeof prims[0]))

/* The mode and patch size of m drawn under d: a tessellating program takes
 * every list primitive as patches of its own size (a triangle list is
 * patches of 3), so a Sphere can feed a triangle tessellation shader;
 * patches are of the mesh's own size or the scene's NumPatchVertices. */
static GLenum draw_mode(const gpu_mesh *m, const render_res_draw *d, int *patch) {
    int p = m->prim >= 0 && m->prim < NPRIMS ? m->prim : GEOM_TRIANGLES;
    *patch = 0;
    if (p == GEOM_PATCHES) {
        *patch = m->patch_size > 0 ? m->patch_size : d->patch_vertices > 0 ? d->patch_vertices : 3;
        return GL_PATCHES;
    }
    if (d->tess && prims[p].verts > 0 && p != GEOM_QUADS) {
        *patch = prims[p].verts;
        return GL_PATCHES;
    }
    return prims[p].mode;
}

const char *render_res_mesh_prim_name(const gpu_mesh *m, const render_res_draw *d) {
    int patch;
    GLenum mode = draw_mode(m, d, &patch);
    for (int i = 0; i < NPRIMS; i++)
        if (prims[i].mode == mode) return prims[i].name;
    return "?";
}

/* One glDrawElements a part, with FaceIndex telling the shader which. */
static void draw_parts(const gpu_mesh *m, const render_res_draw *d, GLenum mode) {
    if (!m->part_first || m->nparts <= 0) {
        glDrawElements(mode, m->nidx, GL_UNSIGNED_INT, (const void *)0);
        return;
    }
    for (int k = 0; k < m->nparts; k++) {
        if (d->face_index_loc >= 0) {
            if (d->face_index_int) glUniform1i(d->face_index_loc, k);
            else glUniform1f(d->face_index_loc, (float)k);
        }
        long first = m->part_first[k], n = m->part_first[k + 1] - first;
        if (n > 0) glDrawElements(mode, (GLsizei)n, GL_UNSIGNED_INT, (const void *)(first * (long)sizeof(unsigned)));
    }
}

bool render_res_mesh_draw_with(const gpu_mesh *m, const render_res_draw *d, char *why, int whylen) {
    if (why && whylen > 0) why[0] = '\0';
    if (!m->vbo) return true;
    int patch = 0;
    GLenum mode = draw_mode(m, d, &patch);
    if (mode == GL_PATCHES && !d->tess) {
        snprintf(why, (size_t)whylen, "it draws GL_PATCHES (patches of %d), which need a Program with a "
                 "TessEvaluation stage (and usually TessControl): name their files before the Program line", patch);
        return false;
    }
    if (mode == GL_PATCHES && m->nidx % patch != 0)
        snprintf(why, (size_t)whylen, "its %d vertices are not whole patches of %d: the last %d are "
                 "dropped (set NumPatchVertices to the patch size)", m->nidx, patch, m->nidx % patch);
    if (mode == GL_PATCHES) glPatchParameteri(GL_PATCH_VERTICES, patch);
    int tangent_loc = d->tangent_loc;
    glBindBuffer(GL_ARRAY_BUFFER, m->vbo);
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(3, GL_FLOAT, 0, (const void *)0);
    glEnableClientState(GL_NORMAL_ARRAY);
    glNormalPointer(GL_FLOAT, 0, (const void *)m->off_nrm);
    glClientActiveTexture(GL_TEXTURE0);
    glEnableClientState(GL_TEXTURE_COORD_ARRAY);
    glTexCoordPointer(3, GL_FLOAT, 0, (const void *)m->off_tc);
    if (tangent_loc >= 0) {
        glEnableVertexAttribArray((GLuint)tangent_loc);
        glVertexAttribPointer((GLuint)tangent_loc, 3, GL_FLOAT, GL_FALSE, 0, (const void *)m->off_tan);
    }
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->ibo);
    draw_parts(m, d, mode);
    if (tangent_loc >= 0) glDisableVertexAttribArray((GLuint)tangent_loc);
    glDisableClientState(GL_TEXTURE_COORD_ARRAY);
    glDisableClientState(GL_NORMAL_ARRAY);
    glDisableClientState(GL_VERTEX_ARRAY);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    return true;
}

/* glman's attributes: gl_Vertex, gl_Normal, gl_MultiTexCoord0, Tangent. */
void render_res_mesh_draw(const gpu_mesh *m, int tangent_loc) {
    render_res_draw d = { .tangent_loc = tangent_loc, .face_index_loc = -1, .patch_vertices = 3 };
    render_res_mesh_draw_with(m, &d, NULL, 0);
}

void render_res_mesh_free(gpu_mesh *m) {
    if (m->vbo) glDeleteBuffers(1, &m->vbo);
    if (m->ibo) glDeleteBuffers(1, &m->ibo);
    m->vbo = m->ibo = 0;
    free(m->part_first);
    m->part_first = NULL;
    m->nparts = 0;
}

/* ---- textures ---- */

static bool is_hdr(const img *im) {
    long n = (long)im->w * im->h * (im->d > 0 ? im->d : 1) * im->channels;
    for (long i = 0; i < n; i++)
        if (im->px[i] < 0.0f || im->px[i] > 1.0f) return true;
    return false;
}

/* Expands any channel count to RGBA (grey -> rgb, alpha 1). */
static float *to_rgba(const img *im) {
    long n = (long)im->w * im->h * (im->d > 0 ? im->d : 1);
    float *out = mem_alloc((size_t)n * 4 * sizeof(float));
    for (long i = 0; i < n; i++) {
        const float *s = im->px + i * im->channels;
        float *d = out + i * 4;
        switch (im->channels) {
        case 1: d[0] = d[1] = d[2] = s[0]; d[3] = 1; break;
        case 2: d[0] = d[1] = d[2] = s[0]; d[3] = s[1]; break;
        case 3: d[0] = s[0]; d[1] = s[1]; d[2] = s[2]; d[3] = 1; break;
        default: memcpy(d, s, 4 * sizeof(float)); break;
        }
    }
    return out;
}

void render_res_vertexid_begin(void) {
    glPushClientAttrib(GL_CLIENT_VERTEX_ARRAY_BIT);
    glDisableClientState(GL_VERTEX_ARRAY);
    glDisableClientState(GL_NORMAL_ARRAY);
    glDisableClientState(GL_TEXTURE_COORD_ARRAY);
    glDisableClientState(GL_COLOR_ARRAY);
}

void render_res_vertexid_end(void) { glPopClientAttrib(); }

void render_res_pass_state(int w, int h) {
    glViewport(0, 0, w, h);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_CULL_FACE);
}

void render_res_sampling(unsigned target, bool mipmaps, unsigned wrap) {
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, mipmaps ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(target, GL_TEXTURE_WRAP_S, (GLint)wrap);
    glTexParameteri(target, GL_TEXTURE_WRAP_T, (GLint)wrap);
    glTexParameteri(target, GL_TEXTURE_WRAP_R, (GLint)wrap);
    if (mipmaps) glGenerateMipmap(target);
}

/* ---- glman's raw textures ---- */

/* A raw texture as read: sizes (s, t, p; p 1 for 2D) and RGBA floats. */
typedef struct raw_tex {
    int n[3];
    float *px;
    bool bytes;                 /* the file held bytes (else floats) */
} raw_tex;

#define RAW_MAX_TEXELS (1L << 25)

/* glman's raw texture file (docs/glman.md, "Raw texture files"): dims
 * little-endian int32 sizes, then RGBA texels, s fastest, all bytes or all
 * 32-bit floats, told apart by the file size. False with why (a sentence)
 * when the file is not such a file. */
static bool read_raw(file_cache *files, const char *path, int dims, raw_tex *out, char *why, size_t whylen) {
    memset(out, 0, sizeof *out);
    out->n[2] = 1;
    size_t size = 0;
    char err[MSG_MAX];
    unsigned char *file = (unsigned char *)file_cache_bytes(files, path, (size_t)(4L * dims + RAW_MAX_TEXELS * 16),
                                                            &size, err, sizeof err);
    if (!file) { msg_set(why, whylen, "%s", err); return false; }
    bool ok = size >= (size_t)(4 * dims);
    long texels = 1;
    for (int d = 0; ok && d < dims; d++) {
        const unsigned char *h = file + d * 4;
        out->n[d] = (int)((unsigned)h[0] | (unsigned)h[1] << 8 | (unsigned)h[2] << 16 | (unsigned)h[3] << 24);
        if (out->n[d] < 1 || out->n[d] > 16384) {
            snprintf(why, whylen, "'%s' is not a glman raw texture: size %d in its header (use 1..16384)",
                     path, out->n[d]);
            free(file);
            return false;
        }
        texels *= out->n[d];
        ok = texels <= RAW_MAX_TEXELS;
    }
    if (!ok) {
        snprintf(why, whylen, "'%s' is not a glman raw texture: its header is cut short or asks for more "
                 "than %ld texels", path, RAW_MAX_TEXELS);
        free(file);
        return false;
    }
    long body = (long)size - 4L * dims, count = texels * 4;
    out->bytes = body == count;
    if (!out->bytes && body != count * 4) {
        char sizes[48];
        if (dims == 3) snprintf(sizes, sizeof sizes, "%d x %d x %d", out->n[0], out->n[1], out->n[2]);
        else snprintf(sizes, sizeof sizes, "%d x %d", out->n[0], out->n[1]);
        snprintf(why, whylen, "'%s' has %ld bytes after its %d-number header, but %s RGBA texels take %ld "
                 "(bytes) or %ld (floats): the sizes in its header are wrong or the file is cut short",
                 path, body, dims, sizes, count, count * 4);
        free(file);
        return false;
    }
    out->px = mem_alloc((size_t)count * sizeof *out->px);
    const unsigned char *raw = file + 4 * dims;
    for (long i = 0; i < count; i++) {
        if (out->bytes) out->px[i] = raw[i] / 255.0f;
        else memcpy(&out->px[i], raw + i * 4, 4);   /* little-endian, as written */
        if (!isfinite(out->px[i])) out->px[i] = 0;  /* a NaN texel would spread through filtering */
    }
    free(file);
    return true;
}

/* Whether a texture file is glman's raw format: its .tex name. */
static bool is_raw_name(const char *path) {
    size_t n = strlen(path);
    return n > 4 && strcasecmp(path + n - 4, ".tex") == 0;
}

/* Reads a raw file for command c into rt, or says why in the log. */
static bool raw_read_into(file_cache *files, const char *path, int dims, raw_tex *rt, const glib_cmd *c, diag_list *log) {
    char why[MSG_MAX];
    if (read_raw(files, path, dims, rt, why, sizeof why)) return true;
    diag_add(log, DIAG_ERROR, c->file, c->line, "%s: %s", glib_cmd_name(c->kind), why);
    return false;
}

/* Uploads a raw image to the bound 2D target (a face of a cube map too):
 * raw rows run from t = 0, GL's bottom row, as glman uploaded them. */
static void raw_upload_2d(GLenum target, const raw_tex *rt) {
    glTexImage2D(target, 0, rt->bytes ? GL_RGBA8 : GL_RGBA32F, rt->n[0], rt->n[1], 0, GL_RGBA, GL_FLOAT, rt->px);
}

bool render_res_read_image(file_cache *files, const char *path, img *im, char *err, int errlen) {
    if (!img_reads_from_memory(path)) return img_read(path, im, err, errlen);
    size_t n = 0;
    char why[MSG_MAX];
    file_text_opts o = { .max_bytes = IMG_MAX_FILE_BYTES };
    char *bytes = file_cache_read(files, path, &o, &n, NULL, why, sizeof why);
    if (!bytes) snprintf(err, (size_t)errlen, "%s: %s", path, why);
    bool ok = bytes && img_read_bytes(path, bytes, n, im, err, errlen);
    free(bytes);
    return ok;
}

static bool load_image(file_cache *files, const char *path, img *im, const glib_cmd *c, diag_list *log) {
    char err[MSG_MAX] = "";
    memset(im, 0, sizeof *im);
    if (render_res_read_image(files, path, im, err, sizeof err)) return true;
    diag_add(log, DIAG_ERROR, c->file, c->line, "%s: %s", glib_cmd_name(c->kind), err);
    return false;
}

/* The makers of the textures tarn generates (viewer/gfx/assets.h): res x
 * res texels of their channels, as floats. */
static bool make_caustics(int res, float *px, char *err, size_t errlen) {
    return assets_bake_caustics(res, px, err, (int)errlen);
}
static bool make_foam(int res, float *px, char *err, size_t errlen) {
    (void)err, (void)errlen;
    return assets_bake_foam(res, px);
}
static bool make_water_normal(int res, float *px, char *err, size_t errlen) {
    (void)err, (void)errlen;
    return assets_bake_water_normal(res, px);
}
static bool make_terrain_normal(int res, float *px, char *err, size_t errlen) {
    (void)err, (void)errlen;
    ref_world w;
    ref_world_desc d;
    ref_world_desc_lake(&d);   /* no world at hand here: the lake's terrain */
    ref_world_init(&w, &d);
    bool ok = assets_bake_terrain_normal(&w, res, px);
    ref_world_release(&w);
    return ok;
}

/* The textures tarn generates (glib_cmds.c accepts these names): their
 * side, channels and maker. The caustic tile is photon tracing, about a
 * second at 128; the others are quick. */
typedef struct generated_tex {
    const char *name;
    int res, channels;
    bool keep;   /* kept on disk across runs (disk_cache.h): its making is slow */
    bool (*make)(int res, float *px, char *err, size_t errlen);
} generated_tex;
static const generated_tex GENERATED[] = {
    { "caustics", 128, 1, true, make_caustics },
    { "foam", 256, 3, false, make_foam },
    { "water_normal", 256, 3, false, make_water_normal },
    { "terrain_normal", 256, 3, false, make_terrain_normal },
};

/* file_cache_made's maker (user: the generated_tex): res x res texels of
 * its channels, as floats; a kept one from tarn's cache folder when this
 * binary made it before (the key changes with the binary, whose code made
 * it), else made and kept there. */
static bool bake_generated(void *user, void *out, size_t len, char *err, size_t errlen) {
    const generated_tex *g = user;
    char name[64];
    snprintf(name, sizeof name, "%s-%d.f32", g->name, g->res);
    uint64_t key = g->keep ? disk_cache_build_key() : 0;
    if (key && disk_cache_read(name, key, out, len)) return true;
    if (!g->make(g->res, out, err, errlen)) return false;
    if (key) disk_cache_write(name, key, out, len);   /* a failure only means making it again next time */
    return true;
}

/* `Texture2D unit @NAME`: a texture tarn generates, made once per cache
 * (the window's reloads, its compile job and compare-view's packs share
 * it). */
static bool tex_2d_generated(const glib_cmd *c, file_cache *files, gpu_tex *t, diag_list *log) {
    const generated_tex *g = NULL;
    for (size_t k = 0; k < sizeof GENERATED / sizeof GENERATED[0]; k++)
        if (strcmp(c->path + 1, GENERATED[k].name) == 0) g = &GENERATED[k];
    char err[MSG_MAX] = "", key[RES_KEY_MAX];
    float *px = NULL;
    if (g) {
        size_t len = (size_t)g->res * g->res * g->channels * sizeof(float);
        px = mem_alloc(len);
        snprintf(key, sizeof key, "@%s/%d", g->name, g->res);
        if (!file_cache_made(files, key, px, len, bake_generated, (void *)g, err, sizeof err)) {
            free(px);
            px = NULL;
        }
    }
    if (!px) {
        diag_add(log, DIAG_ERROR, c->file, c->line, "Texture2D %s: %s", c->path, err[0] ? err : "cannot generate");
        return false;
    }
    int res = g->res;
    bool one_channel = g->channels == 1;
    t->w = t->h = res;
    glTexImage2D(GL_TEXTURE_2D, 0, one_channel ? GL_R16F : GL_RGB16F, res, res, 0, one_channel ? GL_RED : GL_RGB,
                 GL_FLOAT, px);
    if (one_channel) {   /* read as grey: .rgb all the pattern */
        GLint swizzle[4] = { GL_RED, GL_RED, GL_RED, GL_ONE };
        glTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_RGBA, swizzle);
    }
    free(px);
    render_res_sampling(GL_TEXTURE_2D, true, GL_REPEAT);
    return true;
}

static bool tex_2d_file(const glib_cmd *c, file_cache *files, gpu_tex *t, diag_list *log) {
    if (c->path[0] == '@') return tex_2d_generated(c, files, t, log);
    if (is_raw_name(c->path)) {
        raw_tex rt;
        if (!raw_read_into(files, c->path, 2, &rt, c, log)) return false;
        t->w = rt.n[0];
        t->h = rt.n[1];
        raw_upload_2d(GL_TEXTURE_2D, &rt);
        free(rt.px);
        render_res_sampling(GL_TEXTURE_2D, true, GL_REPEAT);
        return true;
    }
    img im;
    if (!load_image(files, c->path, &im, c, log)) return false;
    img_flip_rows(&im);            /* files store the top row first, GL the bottom */
    float *rgba = to_rgba(&im);
    bool hdr = is_hdr(&im);
    t->w = im.w;
    t->h = im.h;
    img_free(&im);
    glTexImage2D(GL_TEXTURE_2D, 0, hdr ? GL_RGBA16F : GL_RGBA8, t->w, t->h, 0, GL_RGBA, GL_FLOAT, rgba);
    free(rgba);
    render_res_sampling(GL_TEXTURE_2D, true, GL_REPEAT);
    return true;
}

static void target_storage(const gpu_tex *t) {
    GLenum ifmt = GL_RGBA8, fmt = GL_RGBA, type = GL_UNSIGNED_BYTE;
    if (t->format == GLIB_TARGET_RGBA16F) { ifmt = GL_RGBA16F; type = GL_FLOAT; }
    if (t->format == GLIB_TARGET_RGBA32F) { ifmt = GL_RGBA32F; type = GL_FLOAT; }
    if (t->format == GLIB_TARGET_DEPTH) { ifmt = GL_DEPTH_COMPONENT32F; fmt = GL_DEPTH_COMPONENT; type = GL_FLOAT; }
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)ifmt, t->w, t->h, 0, fmt, type, NULL);
}

static bool tex_2d_empty(const glib_cmd *c, gpu_tex *t, diag_list *log) {
    /* a size that a slider gives starts at 1 texel: render.c sizes it
     * from the slider before the first frame draws into it */
    t->w = c->name[0] ? 1 : arg_i(c, 1, 0);
    t->h = c->arg[0] ? 1 : arg_i(c, 2, 0);
    if (t->w < 1 || t->h < 1 || t->w > 16384 || t->h > 16384) {
        diag_add(log, DIAG_ERROR, c->file, c->line, "Texture2D size %dx%d: use 1..16384", t->w, t->h);
        return false;
    }
    t->render_target = true;
    t->format = c->format;
    target_storage(t);
    render_res_sampling(GL_TEXTURE_2D, false, GL_CLAMP_TO_EDGE);
    return true;
}

void render_res_target_resize(gpu_tex *t, int w, int h) {
    if (!t->tex || !t->render_target || (t->w == w && t->h == h)) return;
    t->w = w;
    t->h = h;
    glBindTexture(GL_TEXTURE_2D, t->tex);
    target_storage(t);   /* a new image of the same format: framebuffers attach it afresh each pass */
    glBindTexture(GL_TEXTURE_2D, 0);
}

static bool tex_3d(const glib_cmd *c, file_cache *files, gpu_tex *t, diag_list *log) {
    if (!c->path[0]) {                       /* Texture3D unit w h d: empty */
        int w = arg_i(c, 1, 0), h = arg_i(c, 2, 0), d = arg_i(c, 3, 0);
        if (w < 1 || h < 1 || d < 1 || (long)w * h * d > (1L << 26)) {
            diag_add(log, DIAG_ERROR, c->file, c->line, "Texture3D size %dx%dx%d is out of range", w, h, d);
            return false;
        }
        glTexImage3D(GL_TEXTURE_3D, 0, GL_RGBA8, w, h, d, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
        render_res_sampling(GL_TEXTURE_3D, false, GL_REPEAT);
        return true;
    }
    if (is_raw_name(c->path)) {
        raw_tex rt;
        if (!raw_read_into(files, c->path, 3, &rt, c, log)) return false;
        glTexImage3D(GL_TEXTURE_3D, 0, rt.bytes ? GL_RGBA8 : GL_RGBA32F, rt.n[0], rt.n[1], rt.n[2], 0, GL_RGBA,
                     GL_FLOAT, rt.px);
        free(rt.px);
        render_res_sampling(GL_TEXTURE_3D, true, GL_REPEAT);
        return true;
    }
    img im;
    if (!load_image(files, c->path, &im, c, log)) return false;
    float *rgba = to_rgba(&im);
    int d = im.d > 0 ? im.d : 1;
    glTexImage3D(GL_TEXTURE_3D, 0, GL_RGBA16F, im.w, im.h, d, 0, GL_RGBA, GL_FLOAT, rgba);
    img_free(&im);
    free(rgba);
    render_res_sampling(GL_TEXTURE_3D, true, GL_REPEAT);
    return true;
}

static bool tex_cube(const glib_cmd *c, file_cache *files, gpu_tex *t, diag_list *log) {
    if (!c->cube_paths) return false;
    for (int f = 0; f < 6; f++) {
        if (is_raw_name(c->cube_paths[f])) {
            raw_tex rt;
            if (!raw_read_into(files, c->cube_paths[f], 2, &rt, c, log)) return false;
            raw_upload_2d(GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)f, &rt);
            free(rt.px);
            continue;
        }
        img im;
        if (!load_image(files, c->cube_paths[f], &im, c, log)) return false;
        float *rgba = to_rgba(&im);
        /* cube faces keep the file's row order (the cube map convention) */
        glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)f, 0, is_hdr(&im) ? GL_RGBA16F : GL_RGBA8,
                     im.w, im.h, 0, GL_RGBA, GL_FLOAT, rgba);
        img_free(&im);
        free(rgba);
    }
    render_res_sampling(GL_TEXTURE_CUBE_MAP, true, GL_CLAMP_TO_EDGE);
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    return true;
}

static bool tex_noise(const glib_cmd *c, gpu_tex *t, diag_list *log) {
    bool is3d = c->kind == GLIB_CMD_NOISE3D;
    int res = arg_i(c, 0, 64);
    int maxres = is3d ? NOISE_3D_MAX_RES : NOISE_2D_MAX_RES;
    if (res < 4 || res > maxres) {
        diag_add(log, DIAG_ERROR, c->file, c->line, "%s resolution %d: use 4..%d",
                    glib_cmd_name(c->kind), res, maxres);
        return false;
    }
    long n = (long)res * res * (is3d ? res : 1) * 4;
    float *px = mem_alloc((size_t)n * sizeof(float));
    bool ok = is3d ? noise_3d(res, px) : noise_2d(res, px);
    if (ok && is3d) glTexImage3D(GL_TEXTURE_3D, 0, GL_RGBA16F, res, res, res, 0, GL_RGBA, GL_FLOAT, px);
    if (ok && !is3d) glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, res, res, 0, GL_RGBA, GL_FLOAT, px);
    free(px);
    if (ok) render_res_sampling(t->target, true, GL_REPEAT);
    return ok;
}

bool render_res_noise_builtin(file_cache *files, const char *dir, bool is3d, gpu_tex *t) {
    char path[GLIB_PATH_MAX + 32], why[768];
    snprintf(path, sizeof path, "%s%snoise%dd.064.tex", dir, dir[0] ? "/" : "", is3d ? 3 : 2);
    raw_tex rt;
    if (!read_raw(files, path, is3d ? 3 : 2, &rt, why, sizeof why)) {   /* else the project's own, as glman cached it */
        rt.n[0] = rt.n[1] = 64;
        rt.n[2] = is3d ? 64 : 1;
        rt.px = mem_alloc((size_t)64 * 64 * rt.n[2] * 4 * sizeof *rt.px);
        if (!(is3d ? noise_3d(64, rt.px) : noise_2d(64, rt.px))) {
            free(rt.px);
            return false;
        }
    }
    t->unit = is3d ? 3 : 2;
    t->target = is3d ? GL_TEXTURE_3D : GL_TEXTURE_2D;
    glGenTextures(1, &t->tex);
    glBindTexture(t->target, t->tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    if (is3d) glTexImage3D(GL_TEXTURE_3D, 0, GL_RGBA16F, rt.n[0], rt.n[1], rt.n[2], 0, GL_RGBA, GL_FLOAT, rt.px);
    else glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, rt.n[0], rt.n[1], 0, GL_RGBA, GL_FLOAT, rt.px);
    render_res_sampling(t->target, true, GL_REPEAT);
    glBindTexture(t->target, 0);
    free(rt.px);
    return true;
}

bool render_res_tex_build(const glib_cmd *c, file_cache *files, gpu_tex *t, diag_list *log) {
    t->unit = c->kind == GLIB_CMD_NOISE2D ? 2 : c->kind == GLIB_CMD_NOISE3D ? 3 : arg_i(c, 0, 0);
    if (t->unit < 0 || t->unit > 31) {
        diag_add(log, DIAG_ERROR, c->file, c->line, "texture unit %d: use 0..31", t->unit);
        return false;
    }
    t->target = GL_TEXTURE_2D;
    if (c->kind == GLIB_CMD_TEXTURE3D || c->kind == GLIB_CMD_NOISE3D) t->target = GL_TEXTURE_3D;
    if (c->kind == GLIB_CMD_CUBEMAP) t->target = GL_TEXTURE_CUBE_MAP;
    snprintf(t->path, sizeof t->path, "%s", c->kind == GLIB_CMD_CUBEMAP && c->cube_paths ? c->cube_paths[0] : c->path);
    glGenTextures(1, &t->tex);
    glBindTexture(t->target, t->tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    bool ok = false;
    switch (c->kind) {
    case GLIB_CMD_TEXTURE2D_FILE: ok = tex_2d_file(c, files, t, log); break;
    case GLIB_CMD_TEXTURE2D_EMPTY: ok = tex_2d_empty(c, t, log); break;
    case GLIB_CMD_TEXTURE3D: ok = tex_3d(c, files, t, log); break;
    case GLIB_CMD_CUBEMAP: ok = tex_cube(c, files, t, log); break;
    case GLIB_CMD_NOISE2D: case GLIB_CMD_NOISE3D: ok = tex_noise(c, t, log); break;
    default: break;
    }
    glBindTexture(t->target, 0);
    if (!ok) render_res_tex_free(t);
    return ok;
}

void render_res_tex_free(gpu_tex *t) {
    if (t->tex) glDeleteTextures(1, &t->tex);
    t->tex = 0;
}
