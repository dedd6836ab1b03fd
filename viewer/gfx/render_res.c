#include "render_res.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "assets.h"
#include "geom.h"
#include "image_io.h"
#include "mem.h"
#include "noise.h"
#include "strbuf.h"

bool res_is_geometry(glib_cmd_kind k) {
    return k == GLIB_CMD_QUAD_XY || k == GLIB_CMD_QUAD_XZ || k == GLIB_CMD_QUAD_YZ ||
           k == GLIB_CMD_SPHERE || k == GLIB_CMD_TORUS || k == GLIB_CMD_BOX ||
           k == GLIB_CMD_CYLINDER || k == GLIB_CMD_CONE || k == GLIB_CMD_TEAPOT ||
           k == GLIB_CMD_OBJ;
}

bool res_is_texture(glib_cmd_kind k) {
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

void res_key(const glib_cmd *c, char *out, int outlen) {
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

static bool make_mesh(const glib_cmd *c, geom_mesh *g, char *err, int errlen) {
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
    case GLIB_CMD_OBJ: return geom_obj_load(g, c->path, err, errlen);
    default: return false;
    }
}

bool res_mesh_upload(const geom_mesh *g, gpu_mesh *m) {
    if (g->nvert <= 0 || g->nidx <= 0) return false;
    long nv = g->nvert;
    long sz_pos = nv * 3 * (long)sizeof(float), sz_tc = nv * 2 * (long)sizeof(float);
    m->off_nrm = sz_pos;
    m->off_tc = 2 * sz_pos;
    m->off_tan = 2 * sz_pos + sz_tc;
    glGenBuffers(1, &m->vbo);
    glBindBuffer(GL_ARRAY_BUFFER, m->vbo);
    glBufferData(GL_ARRAY_BUFFER, 3 * sz_pos + sz_tc, NULL, GL_STATIC_DRAW);
    glBufferSubData(GL_ARRAY_BUFFER, 0, sz_pos, g->pos);
    glBufferSubData(GL_ARRAY_BUFFER, m->off_nrm, sz_pos, g->nrm);
    glBufferSubData(GL_ARRAY_BUFFER, m->off_tc, sz_tc, g->tc);
    glBufferSubData(GL_ARRAY_BUFFER, m->off_tan, sz_pos, g->tan);
    glGenBuffers(1, &m->ibo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (long)g->nidx * (long)sizeof(unsigned), g->idx, GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    m->nidx = g->nidx;
    m->lines = g->lines;
    return true;
}

bool res_mesh_build(const glib_cmd *c, gpu_mesh *m, char **log) {
    geom_mesh g;
    memset(&g, 0, sizeof g);
    char err[512] = "";
    if (!make_mesh(c, &g, err, sizeof err) || !res_mesh_upload(&g, m)) {
        str_appendf(log, "%s:%d: error: cannot build %s: %s\n", c->file, c->line,
                    glib_cmd_name(c->kind), err[0] ? err : "bad arguments");
        geom_free(&g);
        return false;
    }
    geom_free(&g);
    return true;
}

/* glman's attributes: gl_Vertex, gl_Normal, gl_MultiTexCoord0, Tangent. */
void res_mesh_draw(const gpu_mesh *m, int tangent_loc) {
    if (!m->vbo) return;
    glBindBuffer(GL_ARRAY_BUFFER, m->vbo);
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(3, GL_FLOAT, 0, (const void *)0);
    glEnableClientState(GL_NORMAL_ARRAY);
    glNormalPointer(GL_FLOAT, 0, (const void *)m->off_nrm);
    glClientActiveTexture(GL_TEXTURE0);
    glEnableClientState(GL_TEXTURE_COORD_ARRAY);
    glTexCoordPointer(2, GL_FLOAT, 0, (const void *)m->off_tc);
    if (tangent_loc >= 0) {
        glEnableVertexAttribArray((GLuint)tangent_loc);
        glVertexAttribPointer((GLuint)tangent_loc, 3, GL_FLOAT, GL_FALSE, 0, (const void *)m->off_tan);
    }
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->ibo);
    glDrawElements(m->lines ? GL_LINES : GL_TRIANGLES, m->nidx, GL_UNSIGNED_INT, (const void *)0);
    if (tangent_loc >= 0) glDisableVertexAttribArray((GLuint)tangent_loc);
    glDisableClientState(GL_TEXTURE_COORD_ARRAY);
    glDisableClientState(GL_NORMAL_ARRAY);
    glDisableClientState(GL_VERTEX_ARRAY);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void res_mesh_free(gpu_mesh *m) {
    if (m->vbo) glDeleteBuffers(1, &m->vbo);
    if (m->ibo) glDeleteBuffers(1, &m->ibo);
    m->vbo = m->ibo = 0;
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

void res_sampling(unsigned target, bool mipmaps, unsigned wrap) {
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, mipmaps ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(target, GL_TEXTURE_WRAP_S, (GLint)wrap);
    glTexParameteri(target, GL_TEXTURE_WRAP_T, (GLint)wrap);
    glTexParameteri(target, GL_TEXTURE_WRAP_R, (GLint)wrap);
    if (mipmaps) glGenerateMipmap(target);
}

static bool load_image(const char *path, img *im, const glib_cmd *c, char **log) {
    char err[512] = "";
    memset(im, 0, sizeof *im);
    if (img_read(path, im, err, sizeof err)) return true;
    str_appendf(log, "%s:%d: error: %s: %s\n", c->file, c->line, glib_cmd_name(c->kind), err);
    return false;
}

/* `Texture2D unit @NAME`: a texture tarn generates (viewer/gfx/assets.h). */
static bool tex_2d_generated(const glib_cmd *c, gpu_tex *t, char **log) {
    const char *name = c->path + 1;
    int res = strcmp(name, "caustics") == 0 ? 128 : 256;   /* caustics: photon tracing, ~1 s */
    float *px = mem_alloc((size_t)res * res * 3 * sizeof(float));
    char err[256] = "";
    bool ok = false, one_channel = false;
    if (strcmp(name, "caustics") == 0) { ok = assets_bake_caustics(res, px, err, sizeof err); one_channel = true; }
    else if (strcmp(name, "foam") == 0) ok = assets_bake_foam(res, px);
    else if (strcmp(name, "water_normal") == 0) ok = assets_bake_water_normal(res, px);
    else if (strcmp(name, "terrain_normal") == 0) {
        ref_world w;
        ref_world_desc d;
        ref_world_desc_lake(&d);   /* no world at hand here: the lake's terrain */
        ref_world_init(&w, &d);
        ok = assets_bake_terrain_normal(&w, res, px);
    }
    if (!ok) {
        str_appendf(log, "%s:%d: error: Texture2D %s: %s\n", c->file, c->line, c->path, err[0] ? err : "cannot generate");
        free(px);
        return false;
    }
    t->w = t->h = res;
    glTexImage2D(GL_TEXTURE_2D, 0, one_channel ? GL_R16F : GL_RGB16F, res, res, 0, one_channel ? GL_RED : GL_RGB,
                 GL_FLOAT, px);
    if (one_channel) {   /* read as grey: .rgb all the pattern */
        GLint swizzle[4] = { GL_RED, GL_RED, GL_RED, GL_ONE };
        glTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_RGBA, swizzle);
    }
    free(px);
    res_sampling(GL_TEXTURE_2D, true, GL_REPEAT);
    return true;
}

static bool tex_2d_file(const glib_cmd *c, gpu_tex *t, char **log) {
    if (c->path[0] == '@') return tex_2d_generated(c, t, log);
    img im;
    if (!load_image(c->path, &im, c, log)) return false;
    img_flip_rows(&im);            /* files store the top row first, GL the bottom */
    float *rgba = to_rgba(&im);
    bool hdr = is_hdr(&im);
    t->w = im.w;
    t->h = im.h;
    img_free(&im);
    glTexImage2D(GL_TEXTURE_2D, 0, hdr ? GL_RGBA16F : GL_RGBA8, t->w, t->h, 0, GL_RGBA, GL_FLOAT, rgba);
    free(rgba);
    res_sampling(GL_TEXTURE_2D, true, GL_REPEAT);
    return true;
}

static void target_storage(const gpu_tex *t) {
    GLenum ifmt = GL_RGBA8, fmt = GL_RGBA, type = GL_UNSIGNED_BYTE;
    if (t->format == GLIB_TARGET_RGBA16F) { ifmt = GL_RGBA16F; type = GL_FLOAT; }
    if (t->format == GLIB_TARGET_RGBA32F) { ifmt = GL_RGBA32F; type = GL_FLOAT; }
    if (t->format == GLIB_TARGET_DEPTH) { ifmt = GL_DEPTH_COMPONENT32F; fmt = GL_DEPTH_COMPONENT; type = GL_FLOAT; }
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)ifmt, t->w, t->h, 0, fmt, type, NULL);
}

static bool tex_2d_empty(const glib_cmd *c, gpu_tex *t, char **log) {
    /* a size that a slider gives starts at 1 texel: render.c sizes it
     * from the slider before the first frame draws into it */
    t->w = c->name[0] ? 1 : arg_i(c, 1, 0);
    t->h = c->arg[0] ? 1 : arg_i(c, 2, 0);
    if (t->w < 1 || t->h < 1 || t->w > 16384 || t->h > 16384) {
        str_appendf(log, "%s:%d: error: Texture2D size %dx%d: use 1..16384\n", c->file, c->line, t->w, t->h);
        return false;
    }
    t->render_target = true;
    t->format = c->format;
    target_storage(t);
    res_sampling(GL_TEXTURE_2D, false, GL_CLAMP_TO_EDGE);
    return true;
}

void res_target_resize(gpu_tex *t, int w, int h) {
    if (!t->tex || !t->render_target || (t->w == w && t->h == h)) return;
    t->w = w;
    t->h = h;
    glBindTexture(GL_TEXTURE_2D, t->tex);
    target_storage(t);   /* a new image of the same format: framebuffers attach it afresh each pass */
    glBindTexture(GL_TEXTURE_2D, 0);
}

static bool tex_3d(const glib_cmd *c, gpu_tex *t, char **log) {
    if (!c->path[0]) {                       /* Texture3D unit w h d: empty */
        int w = arg_i(c, 1, 0), h = arg_i(c, 2, 0), d = arg_i(c, 3, 0);
        if (w < 1 || h < 1 || d < 1 || (long)w * h * d > (1L << 26)) {
            str_appendf(log, "%s:%d: error: Texture3D size %dx%dx%d is out of range\n", c->file, c->line, w, h, d);
            return false;
        }
        glTexImage3D(GL_TEXTURE_3D, 0, GL_RGBA8, w, h, d, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
        res_sampling(GL_TEXTURE_3D, false, GL_REPEAT);
        return true;
    }
    img im;
    if (!load_image(c->path, &im, c, log)) return false;
    float *rgba = to_rgba(&im);
    int d = im.d > 0 ? im.d : 1;
    glTexImage3D(GL_TEXTURE_3D, 0, GL_RGBA16F, im.w, im.h, d, 0, GL_RGBA, GL_FLOAT, rgba);
    img_free(&im);
    free(rgba);
    res_sampling(GL_TEXTURE_3D, true, GL_REPEAT);
    return true;
}

static bool tex_cube(const glib_cmd *c, gpu_tex *t, char **log) {
    if (!c->cube_paths) return false;
    for (int f = 0; f < 6; f++) {
        img im;
        if (!load_image(c->cube_paths[f], &im, c, log)) return false;
        float *rgba = to_rgba(&im);
        /* cube faces keep the file's row order (the cube map convention) */
        glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)f, 0, is_hdr(&im) ? GL_RGBA16F : GL_RGBA8,
                     im.w, im.h, 0, GL_RGBA, GL_FLOAT, rgba);
        img_free(&im);
        free(rgba);
    }
    res_sampling(GL_TEXTURE_CUBE_MAP, true, GL_CLAMP_TO_EDGE);
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    return true;
}

static bool tex_noise(const glib_cmd *c, gpu_tex *t, char **log) {
    bool is3d = c->kind == GLIB_CMD_NOISE3D;
    int res = arg_i(c, 0, 64);
    int maxres = is3d ? NOISE_3D_MAX_RES : NOISE_2D_MAX_RES;
    if (res < 4 || res > maxres) {
        str_appendf(log, "%s:%d: error: %s resolution %d: use 4..%d\n", c->file, c->line,
                    glib_cmd_name(c->kind), res, maxres);
        return false;
    }
    long n = (long)res * res * (is3d ? res : 1) * 4;
    float *px = mem_alloc((size_t)n * sizeof(float));
    bool ok = is3d ? noise_3d(res, px) : noise_2d(res, px);
    if (ok && is3d) glTexImage3D(GL_TEXTURE_3D, 0, GL_RGBA16F, res, res, res, 0, GL_RGBA, GL_FLOAT, px);
    if (ok && !is3d) glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, res, res, 0, GL_RGBA, GL_FLOAT, px);
    free(px);
    if (ok) res_sampling(t->target, true, GL_REPEAT);
    return ok;
}

/* glman's raw texture file (docs/glman.md, "Raw texture files"): dims
 * little-endian int32 sizes, then RGBA texels, all bytes or all floats
 * (told apart by the file size). A cube of side *res, as RGBA floats, or
 * NULL when the file is not there or not such a file. */
static float *read_raw_cube(const char *path, int dims, int *res) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    unsigned char hdr[12];
    float *px = NULL;
    struct stat st;
    if (fstat(fileno(f), &st) == 0 && fread(hdr, 4, (size_t)dims, f) == (size_t)dims) {
        int n[3] = { 0, 0, 0 };
        for (int d = 0; d < dims; d++)
            n[d] = (int)((unsigned)hdr[d * 4] | (unsigned)hdr[d * 4 + 1] << 8 |
                         (unsigned)hdr[d * 4 + 2] << 16 | (unsigned)hdr[d * 4 + 3] << 24);
        long count = n[0] > 0 && n[0] <= 512 && n[1] == n[0] && (dims == 2 || n[2] == n[0])
                   ? (long)n[0] * n[0] * (dims == 3 ? n[0] : 1) * 4 : 0;
        long body = (long)st.st_size - 4L * dims;
        bool floats = count && body == count * 4, bytes = count && body == count;
        px = floats || bytes ? mem_alloc((size_t)count * sizeof *px) : NULL;
        unsigned char *raw = px ? mem_alloc((size_t)body) : NULL;
        if (raw && fread(raw, 1, (size_t)body, f) == (size_t)body) {
            for (long i = 0; i < count; i++) {
                if (bytes) px[i] = raw[i] / 255.0f;
                else memcpy(&px[i], raw + i * 4, 4);   /* little-endian, as written */
            }
            *res = n[0];
        } else {
            free(px);
            px = NULL;
        }
        free(raw);
    }
    fclose(f);
    return px;
}

bool res_noise_builtin(const char *dir, bool is3d, gpu_tex *t) {
    char path[GLIB_PATH_MAX + 32];
    snprintf(path, sizeof path, "%s%snoise%dd.064.tex", dir, dir[0] ? "/" : "", is3d ? 3 : 2);
    int res = 64;
    float *px = read_raw_cube(path, is3d ? 3 : 2, &res);   /* the project's own, as glman cached it */
    if (!px) {
        res = 64;
        px = mem_alloc((size_t)res * res * (is3d ? res : 1) * 4 * sizeof *px);
        if (!(is3d ? noise_3d(res, px) : noise_2d(res, px))) {
            free(px);
            return false;
        }
    }
    t->unit = is3d ? 3 : 2;
    t->target = is3d ? GL_TEXTURE_3D : GL_TEXTURE_2D;
    glGenTextures(1, &t->tex);
    glBindTexture(t->target, t->tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    if (is3d) glTexImage3D(GL_TEXTURE_3D, 0, GL_RGBA16F, res, res, res, 0, GL_RGBA, GL_FLOAT, px);
    else glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, res, res, 0, GL_RGBA, GL_FLOAT, px);
    res_sampling(t->target, true, GL_REPEAT);
    glBindTexture(t->target, 0);
    free(px);
    return true;
}

bool res_tex_build(const glib_cmd *c, gpu_tex *t, char **log) {
    t->unit = c->kind == GLIB_CMD_NOISE2D ? 2 : c->kind == GLIB_CMD_NOISE3D ? 3 : arg_i(c, 0, 0);
    if (t->unit < 0 || t->unit > 31) {
        str_appendf(log, "%s:%d: error: texture unit %d: use 0..31\n", c->file, c->line, t->unit);
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
    case GLIB_CMD_TEXTURE2D_FILE: ok = tex_2d_file(c, t, log); break;
    case GLIB_CMD_TEXTURE2D_EMPTY: ok = tex_2d_empty(c, t, log); break;
    case GLIB_CMD_TEXTURE3D: ok = tex_3d(c, t, log); break;
    case GLIB_CMD_CUBEMAP: ok = tex_cube(c, t, log); break;
    case GLIB_CMD_NOISE2D: case GLIB_CMD_NOISE3D: ok = tex_noise(c, t, log); break;
    default: break;
    }
    glBindTexture(t->target, 0);
    if (!ok) res_tex_free(t);
    return ok;
}

void res_tex_free(gpu_tex *t) {
    if (t->tex) glDeleteTextures(1, &t->tex);
    t->tex = 0;
}
