#include "render_world.h"
#include "world_height_tiles.h"
#include "world_layer_band.h"

#include <assert.h>
#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assets.h"
#include "geom.h"
#include "mem.h"
#include "ref_mesh.h"
#include "util.h"
#include "strbuf.h"

/* ---- baking ---- */

/* Cells a side of a mesh of `res` cells at level of detail lod. */
static int lod_cells(int res, int lod) {
    int n = res >> lod;
    return lod == 0 || n >= WORLD_LOD_MIN_CELLS ? n : (res < WORLD_LOD_MIN_CELLS ? res : WORLD_LOD_MIN_CELLS);
}

/* The terrain's grid at a level of detail, on the heightfield; shaded:
 * with its normals and texture coordinates (not for positions alone). */
static bool terrain_geom(const gpu_world *gw, int lod, bool shaded, geom_mesh *g) {
    const ref_world *w = &gw->w;
    int res = lod_cells(w->d.terrain_res, lod);
    double hs = w->d.half_size;
    if (!geom_quad(g, 1, 0.0f, (float)hs, res, res, false)) return false;
    for (int i = 0; i < g->nvert; i++) {   /* lift the flat grid onto the heightfield */
        double x = g->pos[i * 3], z = g->pos[i * 3 + 2], n[3];
        g->pos[i * 3 + 1] = (float)ref_terrain_height(w, x, z);
        if (!shaded) continue;
        ref_terrain_normal_at(w, x, z, n);
        for (int k = 0; k < 3; k++) g->nrm[i * 3 + k] = (float)n[k];
        /* the albedo texture is addressed by world position: s = x, t = z */
        g->tc[i * 2] = (float)((x + hs) / (2 * hs));
        g->tc[i * 2 + 1] = (float)((z + hs) / (2 * hs));
    }
    return true;
}

static bool build_terrain(gpu_world *gw, int lod) {
    geom_mesh g;
    if (!terrain_geom(gw, lod, true, &g)) return false;
    bool ok = render_res_mesh_upload(&g, &gw->terrain[lod]);
    geom_free(&g);
    return ok;
}

/* A unit box the world program draws around the eye, at the far plane. */
static bool build_sky_box(gpu_world *gw) {
    geom_mesh g;
    if (!geom_box(&g, 2.0f, 2.0f, 2.0f, false)) return false;
    bool ok = render_res_mesh_upload(&g, &gw->sky_box);
    geom_free(&g);
    return ok;
}

/* The land beyond the world square, out to REF_WORLD_HORIZON, where the
 * reference's rays end: its terrain goes on there (the lake: its rim rises
 * to shore height by r = 1.25, then a plain), so the GL view shows the same
 * land to the same horizon. Rings of squares, the first on the square's
 * border with the terrain mesh's own vertices, so no crack. Out to
 * SKIRT_NEAR times the square's half size (past the lake's rim, where the
 * terrain still bends) the rings are as far apart as the terrain mesh's
 * cells; beyond, where the land is a plane (or the slope's plane), each is
 * SKIRT_GROWTH times the last: a plane needs no vertices inside it. The
 * colour and normal come from the terrain's model per fragment
 * (world.frag), so the vertices carry only positions. */
#define SKIRT_NEAR 1.3
#define SKIRT_GROWTH 1.3
#define SKIRT_MAX_RINGS 512

/* The half sizes of the skirt's rings, ring 0 the square's border; returns
 * how many (at least 2, the last at the horizon or further). */
static int skirt_rings(const ref_world *w, int res, double *h) {
    double hs = w->d.half_size, step = 2 * hs / res;
    double horizon = REF_WORLD_HORIZON > SKIRT_NEAR * hs ? REF_WORLD_HORIZON : 2 * SKIRT_NEAR * hs;
    int n = 0;
    h[n++] = hs;
    while (n < SKIRT_MAX_RINGS - 1 && h[n - 1] < horizon) {
        double next = h[n - 1] < SKIRT_NEAR * hs ? h[n - 1] + step : h[n - 1] * SKIRT_GROWTH;
        h[n++] = next < horizon ? next : horizon;
    }
    if (h[n - 1] < horizon) h[n++] = horizon;
    return n;
}

static void skirt_vertex(const ref_world *w, double x, double z, bool shaded, float *pos, float *nrm, float *tc) {
    double n[3], hs = w->d.half_size;
    pos[0] = (float)x;
    pos[1] = (float)ref_terrain_height(w, x, z);
    pos[2] = (float)z;
    if (!shaded) return;
    ref_terrain_normal_at(w, x, z, n);
    for (int k = 0; k < 3; k++) nrm[k] = (float)n[k];
    tc[0] = (float)((x + hs) / (2 * hs));   /* outside [0, 1]: for packs; world.frag does not sample it */
    tc[1] = (float)((z + hs) / (2 * hs));
}

/* Point p (0 <= p < 4 res) along the perimeter of the square of half size h. */
static void perimeter(double h, int res, int p, double *x, double *z) {
    int side = p / res;
    double u = -h + 2 * h * (p % res) / res;
    switch (side) {
    case 0: *x = u; *z = -h; break;
    case 1: *x = h; *z = u; break;
    case 2: *x = -u; *z = h; break;
    default: *x = -h; *z = -u; break;
    }
}

/* The skirt at a level of detail; shaded: with normals and texture
 * coordinates; only the bands that reach within reach of the centre (a
 * half size). */
static bool skirt_geom(const gpu_world *gw, int lod, bool shaded, double reach, geom_mesh *g) {
    const ref_world *w = &gw->w;
    double ring[SKIRT_MAX_RINGS];
    int res = lod_cells(w->d.terrain_res, lod);
    int nrings = skirt_rings(w, res, ring) - 1;   /* the bands between rings */
    while (nrings > 1 && ring[nrings - 1] > reach) nrings--;   /* bands wholly past reach: not wanted */
    int per = 4 * res, nv = per * (nrings + 1);
    memset(g, 0, sizeof *g);
    g->nvert = nv;
    g->nidx = per * nrings * 6;
    g->pos = mem_alloc((size_t)nv * 3 * sizeof(float));
    g->nrm = mem_alloc((size_t)nv * 3 * sizeof(float));
    g->tan = mem_zalloc((size_t)nv * 3 * sizeof(float));
    g->tc = mem_alloc((size_t)nv * 2 * sizeof(float));
    g->idx = mem_alloc((size_t)g->nidx * sizeof(unsigned));
    for (int k = 0; k <= nrings; k++) {
        for (int p = 0; p < per; p++) {
            double x, z;
            perimeter(ring[k], res, p, &x, &z);
            int v = k * per + p;
            skirt_vertex(w, x, z, shaded, g->pos + v * 3, g->nrm + v * 3, g->tc + v * 2);
            g->tan[v * 3] = 1.0f;
        }
    }
    int n = 0;
    for (int k = 0; k < nrings; k++)
        for (int p = 0; p < per; p++) {
            unsigned a = (unsigned)(k * per + p), b = (unsigned)(k * per + (p + 1) % per);
            unsigned c = a + (unsigned)per, d = b + (unsigned)per;
            unsigned quad[6] = { a, c, b, b, c, d };
            memcpy(g->idx + n, quad, sizeof quad);
            n += 6;
        }
    return true;
}

static bool build_skirt(gpu_world *gw, int lod) {
    geom_mesh g;
    if (!skirt_geom(gw, lod, true, INFINITY, &g)) return false;
    bool ok = render_res_mesh_upload(&g, &gw->skirt[lod]);
    geom_free(&g);
    return ok;
}

/* Cells a band of the water grid is wide (geom_grid_bands): its rows' vertices
 * stay in llvmpipe's vertex cache from one row to the next. */
#define WORLD_WATER_BAND 32

/* Is the water open beyond the world square: the terrain below the lowest
 * trough on the square's border and beyond it (a sea, Terrain flat)? Then
 * its surface goes on to the horizon, as the reference's does. */
static bool water_open(const ref_world *w) {
    double hs = w->d.half_size, low = w->d.water_level - w->waves.height_bound;
    const double reach[] = { 1.0, SKIRT_NEAR, 4.0, REF_WORLD_HORIZON / hs };
    for (int r = 0; r < 4; r++)
        for (int p = 0; p < 4 * 64; p++) {
            double x, z;
            perimeter(hs * reach[r], 64, p, &x, &z);
            if (ref_terrain_height(w, x, z) > low) return false;
        }
    return true;
}

/* The water beyond the square out to the horizon, as rings the way the
 * terrain's skirt has them (LOD rings: as fine as the grid near the square,
 * each SKIRT_GROWTH times the last beyond, where a cell covers ever fewer
 * pixels), its first ring the grid's own border vertices (no crack). The
 * rings are fixed in the world, not around the eye: a still camera then
 * draws the same triangles every frame (no swimming), and the static-world
 * cache's key stays the eye and time. Appended to the grid's mesh, so every
 * pack's water program draws it without a pass of its own. */
static void append_water_rings(geom_mesh *g, const ref_world *w, int res) {
    double ring[SKIRT_MAX_RINGS];
    int nrings = skirt_rings(w, res, ring) - 1, per = 4 * res;
    int base = g->nvert, nv = base + per * nrings, nidx = g->nidx + per * nrings * 6;
    g->pos = mem_realloc(g->pos, (size_t)nv * 3 * sizeof(float));
    g->nrm = mem_realloc(g->nrm, (size_t)nv * 3 * sizeof(float));
    g->tan = mem_realloc(g->tan, (size_t)nv * 3 * sizeof(float));
    g->tc = mem_realloc(g->tc, (size_t)nv * 2 * sizeof(float));
    g->idx = mem_realloc(g->idx, (size_t)nidx * sizeof(unsigned));
    double hs = w->d.half_size;
    for (int k = 1; k <= nrings; k++)
        for (int p = 0; p < per; p++) {
            double x, z;
            perimeter(ring[k], res, p, &x, &z);
            int v = base + (k - 1) * per + p;
            float *pos = g->pos + v * 3, *nrm = g->nrm + v * 3, *tan = g->tan + v * 3, *tc = g->tc + v * 2;
            pos[0] = (float)x; pos[1] = (float)w->d.water_level; pos[2] = (float)z;
            nrm[0] = 0; nrm[1] = 1; nrm[2] = 0;
            tan[0] = 1; tan[1] = 0; tan[2] = 0;
            tc[0] = (float)((x + hs) / (2 * hs));
            tc[1] = (float)((z + hs) / (2 * hs));
        }
    /* ring 0: the grid's border vertices (geom_grid_bands renumbered them),
     * found by position: perimeter()'s sides inverted */
    unsigned *first = mem_zalloc((size_t)per * sizeof(unsigned));
    double tol = 1e-4 * hs;
    for (int v = 0; v < base; v++) {
        double x = g->pos[v * 3], z = g->pos[v * 3 + 2];
        const double on[4] = { z + hs, x - hs, z - hs, x + hs };      /* side's line: 0 on it */
        const double along[4] = { x, z, -x, -z };                     /* u of perimeter() */
        for (int side = 0; side < 4; side++) {
            if (fabs(on[side]) > tol) continue;
            long i = lround((along[side] + hs) / (2 * hs) * res);
            if (i >= 0 && i < res) first[side * res + i] = (unsigned)v;
        }
    }
    int n = g->nidx;
    for (int k = 0; k < nrings; k++)
        for (int p = 0; p < per; p++) {
            int q = (p + 1) % per;
            unsigned a = k == 0 ? first[p] : (unsigned)(base + (k - 1) * per + p);
            unsigned b = k == 0 ? first[q] : (unsigned)(base + (k - 1) * per + q);
            unsigned c = (unsigned)(base + k * per + p), d = (unsigned)(base + k * per + q);
            unsigned quad[6] = { a, c, b, b, c, d };
            memcpy(g->idx + n, quad, sizeof quad);
            n += 6;
        }
    free(first);
    g->nvert = nv;
    g->nidx = n;
}

static bool build_water(gpu_world *gw, int lod) {
    geom_mesh g;
    int res = lod_cells(gw->w.d.water_mesh_res, lod);
    if (!geom_quad(&g, 1, (float)gw->w.d.water_level, (float)gw->w.d.half_size, res, res, false)) return false;
    geom_grid_bands(&g, res, res, WORLD_WATER_BAND);   /* vertex reuse: the water's shaders are heavy */
    if (water_open(&gw->w)) append_water_rings(&g, &gw->w, res);
    for (int i = 0; i < g.nvert; i++) {
        g.pos[i * 3 + 0] += (float)gw->water_shift[0];
        g.pos[i * 3 + 2] += (float)gw->water_shift[1];
    }
    bool ok = render_res_mesh_upload(&g, &gw->water[lod]);
    geom_free(&g);
    return ok;
}

/* A mesh object's triangles, already placed in the world (ref_mesh.h), as
 * flat facets: three vertices a triangle with its normal, the one the
 * reference shades the facet with. */
static bool mesh_object(const ref_mesh *rm, geom_mesh *g) {
    int nt = ref_mesh_count(rm);
    if (nt < 1) return false;
    memset(g, 0, sizeof *g);
    g->nvert = 3 * nt;
    g->nidx = 3 * nt;
    g->pos = mem_alloc((size_t)g->nvert * 3 * sizeof(float));
    g->nrm = mem_alloc((size_t)g->nvert * 3 * sizeof(float));
    g->tan = mem_zalloc((size_t)g->nvert * 3 * sizeof(float));
    g->tc = mem_zalloc((size_t)g->nvert * 2 * sizeof(float));
    g->idx = mem_alloc((size_t)g->nidx * sizeof(unsigned));
    for (int i = 0; i < nt; i++) {
        const double *t = ref_mesh_triangle(rm, i), *n = ref_mesh_normal(rm, i);
        for (int k = 0; k < 3; k++) {
            int v = 3 * i + k;
            for (int a = 0; a < 3; a++) {
                g->pos[v * 3 + a] = (float)t[k * 3 + a];
                g->nrm[v * 3 + a] = (float)n[a];
            }
            g->tan[v * 3] = 1.0f;
            g->idx[v] = (unsigned)v;
        }
    }
    return true;
}

static bool build_object(gpu_world *gw, int index, gpu_mesh *m) {
    const ref_object *ob = &gw->w.d.objects[index];
    geom_mesh g;
    bool ok = false;
    double off_y = 0;
    if (ob->kind == REF_OBJECT_MESH) {   /* in world coordinates already */
        if (!mesh_object(gw->w.meshes[index], &g)) return false;
        ok = render_res_mesh_upload(&g, m);
        geom_free(&g);
        return ok;
    }
    switch (ob->kind) {
    case REF_OBJECT_SPHERE: ok = geom_sphere(&g, (float)ob->size[0], 48, 24, false); break;
    case REF_OBJECT_BOX:
        ok = geom_box(&g, (float)(2 * ob->size[0]), (float)(2 * ob->size[1]), (float)(2 * ob->size[2]), false);
        break;
    case REF_OBJECT_CYLINDER:   /* geom's cylinder is centred; ours stands on its base */
        ok = geom_cylinder(&g, (float)ob->size[0], (float)ob->size[1], 48, 1, false);
        off_y = ob->size[1] / 2;
        break;
    default: break;
    }
    if (!ok) return false;
    for (int i = 0; i < g.nvert; i++) {   /* world space, so shaders need no model matrix */
        g.pos[i * 3] += (float)ob->center[0];
        g.pos[i * 3 + 1] += (float)(ob->center[1] + off_y);
        g.pos[i * 3 + 2] += (float)ob->center[2];
    }
    ok = render_res_mesh_upload(&g, m);
    geom_free(&g);
    return ok;
}

/* A res x res texture of floats over the world square (row 0 at -z),
 * filtered and clamped at its edges: the terrain's baked maps. */
static unsigned world_square_texture(int res, GLint internal, GLenum format, const float *px, bool mipmaps) {
    unsigned tex = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, internal, res, res, 0, format, GL_FLOAT, px);
    render_res_sampling(GL_TEXTURE_2D, mipmaps, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    return tex;
}

/* The albedo texture from assets_bake_albedo: row 0 is t = 0, s runs with
 * world x and t with z, matching build_terrain's texture coordinates. */
static bool bake_albedo(gpu_world *gw) {
    int res = gw->w.d.terrain_res;
    float *px = mem_alloc((size_t)res * res * 3 * sizeof(float));
    if (!assets_bake_albedo(&gw->w, res, px)) { free(px); return false; }
    gw->albedo_tex = world_square_texture(res, GL_RGB16F, GL_RGB, px, true);
    free(px);
    return true;
}

/* The terrain's linear part, (h at x = z = 0, dh/dx, dh/dz): the slope's
 * whole model, nothing for the others. The map holds the height less it,
 * so the clamped edge continues every model beyond the map: the lake's and
 * the pool's are flat past their rims, the slope's rises on. */
static void terrain_plane(const ref_world *w, float plane[3]) {
    plane[0] = plane[1] = plane[2] = 0.0f;
    if (w->d.terrain != REF_TERRAIN_SLOPE) return;
    plane[0] = (float)(w->d.water_level - w->d.depth + w->d.slope * w->d.half_size);
    plane[1] = (float)w->d.slope;
}

/* The terrain's height less its plane at the centres of WORLD_TERRAIN_RES^2
 * texels over +-WORLD_TERRAIN_MARGIN half sizes (row 0 at -z), R32F,
 * bilinear. Off the model by about a k^2 h^2 / 8 for each of the lake's
 * detail sines (texels 6 cm apart on the 12 m lake: under 0.3 mm) and about
 * as much on the pool's walls (a smoothstep over 0.15 half sizes: 2 mm). */
void world_bake_terrain_map(gpu_world *gw) {
    if (!gw->active || gw->terrain_tex) return;
    int res = WORLD_TERRAIN_RES;
    double half = WORLD_TERRAIN_MARGIN * gw->w.d.half_size, texel = 2.0 * half / res;
    float plane[3];
    terrain_plane(&gw->w, plane);
    float *h = mem_alloc((size_t)res * res * sizeof(float));
    for (int j = 0; j < res; j++)
        for (int i = 0; i < res; i++) {
            double x = -half + (i + 0.5) * texel, z = -half + (j + 0.5) * texel;
            h[(size_t)j * res + i] = (float)(ref_terrain_height(&gw->w, x, z) - plane[0] - plane[1] * x - plane[2] * z);
        }
    gw->terrain_tex = world_square_texture(res, GL_R32F, GL_RED, h, false);
    free(h);
}

/* One face of the sky without the sun's disc (ref_sky_smooth): RGB, and in
 * alpha the share of the disc the clouds let through (world.glsl's
 * worldSkyLook adds the disc at full resolution). */
static void bake_sky_face(const ref_world *w, int face, int res, float *rgba) {
    for (int j = 0; j < res; j++)
        for (int i = 0; i < res; i++) {
            double d[3], c[3], clear;
            assets_face_dir(face, (i + 0.5) / res, (j + 0.5) / res, d);
            ref_sky_smooth(w, d, c, &clear);
            float *px = rgba + ((size_t)j * res + i) * 4;
            for (int k = 0; k < 3; k++) px[k] = (float)c[k];
            px[3] = (float)clear;
        }
}

static bool bake_sky(gpu_world *gw) {
    /* clouds are detail a 128-texel face would blur (0.7 degrees a texel) */
    int res = gw->w.d.cloud_cover > 0 ? WORLD_SKY_RES_CLOUDS : WORLD_SKY_RES;
    float *px = mem_alloc((size_t)res * res * 4 * sizeof(float));
    glGenTextures(1, &gw->sky_tex);
    glBindTexture(GL_TEXTURE_CUBE_MAP, gw->sky_tex);
    for (int f = 0; f < 6; f++) {
        bake_sky_face(&gw->w, f, res, px);   /* GL's cube face table */
        glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)f, 0, GL_RGBA16F, res, res, 0, GL_RGBA, GL_FLOAT, px);
    }
    render_res_sampling(GL_TEXTURE_CUBE_MAP, false, GL_CLAMP_TO_EDGE);
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
    free(px);
    return true;
}

/* world.frag reads the height map (WORLD_HEIGHT_MAP) unless it is off. */
static void set_height_define(const gpu_world *gw, prog *p) {
    memset(&p->fixed[1], 0, sizeof p->fixed[1]);
    if (gw->height_map_off) return;
    snprintf(p->fixed[1].name, sizeof p->fixed[1].name, "WORLD_HEIGHT_MAP");
    snprintf(p->fixed[1].value, sizeof p->fixed[1].value, "1");
}

void world_set_defines(const gpu_world *gw, prog *p) {
    for (int k = PROG_FIXED_WORLD; k < PROG_FIXED_MAX - 1; k++) memset(&p->fixed[k], 0, sizeof p->fixed[k]);
    if (!gw->active) return;
    const ref_waves *w = &gw->w.waves;
    const ref_world_desc *d = &gw->w.d;
    const char *has[PROG_FIXED_MAX];
    int n = 0;
    has[n++] = "WAVES_MODELS";
    if (w->nsine) has[n++] = "WAVES_HAS_SINE";
    if (w->ngerstner) has[n++] = "WAVES_HAS_GERSTNER";
    if (w->noctaves) has[n++] = "WAVES_HAS_NOISE";
    if (w->ocean) has[n++] = "WAVES_HAS_OCEAN";
    if (w->nexplosions) has[n++] = "WAVES_HAS_EXPLOSION";
    if (w->has_perlin) has[n++] = "WAVES_HAS_PERLIN";
    if (d->flow.nterms > 0) has[n++] = "WAVES_HAS_FLOW";   /* flow.glsl: the advected detail */
    has[n++] = "WORLD_DEFINES";
    if (d->ground_detail > 0) has[n++] = "WORLD_GROUND_DETAIL";
    if (d->sun_disc_deg > 0) has[n++] = "WORLD_SUN_DISC";
    if (d->haze_distance > 0) has[n++] = "WORLD_HAZE";
    /* these, WORLD_TERRAIN_KIND and render_load's WORLD_ABOVE_WATER fit */
    assert(PROG_FIXED_WORLD + n + 2 <= PROG_FIXED_MAX);
    int k = PROG_FIXED_WORLD;
    for (int i = 0; i < n; i++, k++) {
        snprintf(p->fixed[k].name, sizeof p->fixed[k].name, "%s", has[i]);
        snprintf(p->fixed[k].value, sizeof p->fixed[k].value, "1");
    }
    snprintf(p->fixed[k].name, sizeof p->fixed[k].name, "WORLD_TERRAIN_KIND");
    snprintf(p->fixed[k].value, sizeof p->fixed[k].value, "%d", (int)d->terrain);
}

static void spray_defines(const void *ctx, prog *p) { world_set_defines(ctx, p); }

static bool build_program(gpu_world *gw, const prog_sources *src,  diag_list *log,
                          prog_origins *from) {
    for (int m = 0; m < WORLD_MODES; m++) {
        prog *p = &gw->progs[m];
        memset(p, 0, sizeof *p);
        memset(&gw->prog_unifs[m], 0, sizeof gw->prog_unifs[m]);
        p->unifs = &gw->prog_unifs[m];
        p->world_uniforms = true;
        snprintf(p->name, sizeof p->name, "World");
        snprintf(p->fixed[0].name, sizeof p->fixed[0].name, "WORLD_MODE");
        snprintf(p->fixed[0].value, sizeof p->fixed[0].value, "%d", m);
        set_height_define(gw, p);
        world_set_defines(gw, p);
        snprintf(p->stage_path[SHADER_VERTEX], GLIB_PATH_MAX, "%s/world.vert", src->common_dir);
        snprintf(p->stage_path[SHADER_FRAGMENT], GLIB_PATH_MAX, "%s/world.frag", src->common_dir);
    }
    prog *h = &gw->height_prog;
    memset(h, 0, sizeof *h);
    memset(&gw->height_unifs, 0, sizeof gw->height_unifs);
    h->unifs = &gw->height_unifs;
    h->world_uniforms = true;
    world_set_defines(gw, h);
    snprintf(h->name, sizeof h->name, "WorldHeight");
    snprintf(h->stage_path[SHADER_VERTEX], GLIB_PATH_MAX, "%s/world_height_cells.vert", src->common_dir);
    snprintf(h->stage_path[SHADER_FRAGMENT], GLIB_PATH_MAX, "%s/world_height.frag", src->common_dir);
    for (int ms = 0; ms < 2; ms++) {
        prog *c = &gw->layers_prog[ms];
        memset(c, 0, sizeof *c);
        memset(&gw->layers_unifs[ms], 0, sizeof gw->layers_unifs[ms]);
        c->unifs = &gw->layers_unifs[ms];
        c->world_uniforms = true;
        if (ms) snprintf(c->fixed[0].name, sizeof c->fixed[0].name, "WORLD_LAYERS_MS");
        if (ms) snprintf(c->fixed[0].value, sizeof c->fixed[0].value, "1");
        set_height_define(gw, c);
        world_set_defines(gw, c);
        snprintf(c->name, sizeof c->name, "WorldLayers");
        snprintf(c->stage_path[SHADER_VERTEX], GLIB_PATH_MAX, "%s/world_layers.vert", src->common_dir);
        snprintf(c->stage_path[SHADER_FRAGMENT], GLIB_PATH_MAX, "%s/world_layers.frag", src->common_dir);
    }
    return world_build_programs(gw, src, log, from);
}

bool world_build_programs(gpu_world *gw, const prog_sources *src, diag_list *log, prog_origins *from) {
    bool ok = true;
    for (int m = 0; m < WORLD_MODES; m++) {
        /* the variants share their source: one log says what is wrong with it */
        diag_list mlog = { 0 }, *to = m == 0 ? log : &mlog;
        if (!prog_build(&gw->progs[m], src, to, m == 0 ? from : NULL)) ok = false;
        prog_introspect(&gw->progs[m], to);
        diag_list_free(&mlog);
    }
    if (!prog_build(&gw->height_prog, src, log, from)) ok = false;
    prog_introspect(&gw->height_prog, log);
    if (!prog_build(&gw->layers_prog[0], src, log, from)) ok = false;
    prog_introspect(&gw->layers_prog[0], log);
    /* the multisampled variant: one source, one log; where it does not
     * build, a multisampled frame draws its World (draw_world_layers) */
    diag_list mlog = { 0 };
    prog_build(&gw->layers_prog[1], src, &mlog, NULL);
    prog_introspect(&gw->layers_prog[1], &mlog);
    diag_list_free(&mlog);
    if (!ocean_build_programs(&gw->ocean, src, log, from)) ok = false;
    if (!flow_build_program(&gw->flow, src, log, from)) ok = false;
    if (!spray_build_programs(&gw->spray, src, log, from)) ok = false;
    return ok;
}

/* Does anything but sky stand above the water? (terrain sampled on the
 * mesh grid; objects by their top) */
static bool above_water(const ref_world *w) {
    double level = w->d.water_level, hs = w->d.half_size;
    for (int i = 0; i < w->d.nobjects; i++) {
        const ref_object *o = &w->d.objects[i];
        double top = o->center[1] + (o->kind == REF_OBJECT_CYLINDER ? o->size[1] : o->kind == REF_OBJECT_SPHERE ? o->size[0] : o->size[1]);
        if (top > level) return true;
    }
    int n = w->d.terrain_res;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++)
            if (ref_terrain_height(w, -hs + 2 * hs * i / n, -hs + 2 * hs * j / n) > level) return true;
    return false;
}

void world_free(gpu_world *gw) {
    ocean_free(&gw->ocean);
    flow_free(&gw->flow);
    spray_free(&gw->spray);
    for (int k = 0; k < WORLD_LODS; k++) {
        render_res_mesh_free(&gw->terrain[k]);
        render_res_mesh_free(&gw->skirt[k]);
        render_res_mesh_free(&gw->water[k]);
    }
    render_res_mesh_free(&gw->sky_box);
    if (gw->points_vbo) glDeleteBuffers(1, &gw->points_vbo);
    if (gw->mesh_ibo) glDeleteBuffers(1, &gw->mesh_ibo);
    for (int i = 0; i < gw->nobjects; i++) render_res_mesh_free(&gw->objects[i]);
    if (gw->albedo_tex) glDeleteTextures(1, &gw->albedo_tex);
    if (gw->sky_tex) glDeleteTextures(1, &gw->sky_tex);
    if (gw->terrain_tex) glDeleteTextures(1, &gw->terrain_tex);
    for (int m = 0; m < WORLD_MODES; m++) prog_free(&gw->progs[m]);
    prog_free(&gw->height_prog);
    for (int ms = 0; ms < 2; ms++) prog_free(&gw->layers_prog[ms]);
    if (gw->height_fbo) glDeleteFramebuffers(1, &gw->height_fbo);
    if (gw->height_tex) glDeleteTextures(1, &gw->height_tex);
    if (gw->height_prev_fbo) glDeleteFramebuffers(1, &gw->height_prev_fbo);
    if (gw->height_prev_tex) glDeleteTextures(1, &gw->height_prev_tex);
    if (gw->height_quads_vbo) glDeleteBuffers(1, &gw->height_quads_vbo);
    free(gw->height_tiles);
    ref_world_release(&gw->w);   /* after ocean_free: its GL passes read the ocean */
    bool off = gw->height_map_off, cells_off = gw->height_cells_off;   /* the renderer's settings, not the world's */
    unsigned builds = gw->builds;
    memset(gw, 0, sizeof *gw);
    gw->height_map_off = off;
    gw->height_cells_off = cells_off;
    gw->builds = builds;
}

bool world_build(gpu_world *gw, const ref_world_desc *desc, const prog_sources *src,
                  diag_list *log, prog_origins *from) {
    if (gw->active && memcmp(&gw->desc, desc, sizeof *desc) == 0) {
        /* same world: only the shaders may have changed */
        return world_build_programs(gw, src, log, from);
    }
    world_free(gw);
    gw->builds++;
    gw->desc = *desc;
    ref_world_init(&gw->w, desc);
    gw->nwaves = ref_waves_uniforms(&gw->w.waves, gw->waves, REF_WAVES_UNIFORMS_MAX);
    bool ok = build_terrain(gw, 0) && build_skirt(gw, 0) && build_water(gw, 0) && bake_albedo(gw) && bake_sky(gw) &&
              build_sky_box(gw);
    for (int i = 0; ok && i < gw->w.d.nobjects; i++) {
        const ref_object *ob = &gw->w.d.objects[i];
        if (!build_object(gw, i, &gw->objects[gw->nobjects])) continue;
        for (int k = 0; k < 3; k++) gw->object_albedo[gw->nobjects][k] = (float)ob->albedo[k];
        gw->nobjects++;
    }
    gw->has_above_water = above_water(&gw->w);
    if (!ok) diag_add(log, DIAG_ERROR, NULL, 0, "could not build the scene's world (out of memory?)");
    /* the spectrum ocean's textures and passes: only a world with one */
    if (gw->w.waves.ocean && !ocean_create_from(&gw->ocean, gw->w.waves.ocean, src, log, from))
        ok = false;
    /* the flow map and its pass: only a world with a Flow */
    if (gw->w.d.flow.nterms > 0 &&
        !flow_create(&gw->flow, &gw->w.d.flow, gw->w.d.half_size, src, log, from))
        ok = false;
    /* active before the programs: world_set_defines gives them the
     * scene's defines only for an active world (without them world.frag,
     * its height map's and its layers' programs compiled every wave model
     * and terrain kind, and llvmpipe ran them all) */
    gw->active = true;
    ok = build_program(gw, src, log, from) && ok;
    /* the spray's state and passes: only a world with a Spray; after
     * `active`, which its update program's wave defines need */
    if (gw->w.d.spray.on && !spray_create(&gw->spray, &gw->w.d.spray, gw->w.d.half_size, src,
                                          spray_defines, gw, log, from))
        ok = false;
    return ok;
}

/* ---- per frame ---- */

int world_detail_count(int n, double detail, int min) {
    if (!(detail > 0) || detail >= 1 || n <= min) return n;
    return side_like_full((int)lround(n * detail), n, min);
}

/* The level for a frame at `detail` of each side: the vertices follow the
 * pixels (a quarter of the pixels, a quarter of the vertices). */
static int detail_lod(double detail) {
    if (!(detail > 0) || detail >= 1) return 0;
    int lod = (int)lround(-log2(detail));
    return lod < 0 ? 0 : lod >= WORLD_LODS ? WORLD_LODS - 1 : lod;
}

bool world_set_detail(gpu_world *gw, double detail) {
    if (!gw->active) return true;
    int lod = detail_lod(detail);
    if (lod == gw->lod) return true;
    if (!gw->terrain[lod].vbo && !build_terrain(gw, lod)) return false;
    if (!gw->skirt[lod].vbo && !build_skirt(gw, lod)) return false;
    gw->lod = lod;
    return true;
}

/* Where the rest points of the square moved by shift land, on average,
 * relative to the square's own points. */
static void mean_residual(const gpu_world *gw, const double shift[2], double t, double out[2]) {
    enum { SAMPLES = 8 };
    double hs = gw->w.d.half_size;
    out[0] = out[1] = 0;
    for (int j = 0; j < SAMPLES; j++)
        for (int i = 0; i < SAMPLES; i++) {
            double u = -hs + (i + 0.5) * 2 * hs / SAMPLES, v = -hs + (j + 0.5) * 2 * hs / SAMPLES, p[3];
            ref_waves_displace(&gw->w.waves, u + shift[0], v + shift[1], t, p);
            out[0] += (p[0] - u) / (SAMPLES * SAMPLES);
            out[1] += (p[2] - v) / (SAMPLES * SAMPLES);
        }
}

void world_follow_waves(gpu_world *gw, double t) {
    if (!gw->active) return;
    double cell = 2 * gw->w.d.half_size / gw->w.d.water_mesh_res, shift[2] = { gw->water_shift[0], gw->water_shift[1] };
    double res[2];
    mean_residual(gw, shift, t, res);
    if (!isfinite(res[0]) || !isfinite(res[1]) || hypot(res[0], res[1]) <= cell) return;
    /* a fixed point: the displacement changes a little with the rest point
     * (by its Jacobian, under 1 while Q <= 1), so a few steps settle it */
    for (int it = 0; it < 16 && isfinite(res[0]) && isfinite(res[1]) && hypot(res[0], res[1]) > 0.01 * cell; it++) {
        shift[0] -= res[0];
        shift[1] -= res[1];
        mean_residual(gw, shift, t, res);
    }
    if (!isfinite(shift[0]) || !isfinite(shift[1])) return;
    gw->water_shift[0] = shift[0];
    gw->water_shift[1] = shift[1];
    for (int k = 0; k < WORLD_LODS; k++) render_res_mesh_free(&gw->water[k]);   /* coarser levels: rebuilt when drawn */
    if (!build_water(gw, gw->lod)) memset(&gw->water[gw->lod], 0, sizeof gw->water[gw->lod]);
    gw->points_n = 0;   /* rebuilt with the shift when next drawn */
}

static void set3(unsigned p, const char *name, const double v[3]) {
    GLint loc = glGetUniformLocation(p, name);
    if (loc >= 0) glUniform3f(loc, (float)v[0], (float)v[1], (float)v[2]);
}

static void set1(unsigned p, const char *name, float v) {
    GLint loc = glGetUniformLocation(p, name);
    if (loc >= 0) glUniform1f(loc, v);
}

static void seti(unsigned p, const char *name, int v) {
    GLint loc = glGetUniformLocation(p, name);
    if (loc >= 0) glUniform1i(loc, v);
}

void world_upload(const gpu_world *gw, unsigned p, double t, const float eye[3]) {
    if (p) ocean_upload(p);   /* with or without an ocean (see ocean_upload) */
    if (!gw->active || !p) return;
    flow_upload(&gw->flow, p);   /* nothing without a flow: no uniform is declared then */
    const ref_world_desc *d = &gw->w.d;
    set3(p, "uSunDir", d->sun_dir);
    set3(p, "uSunIrradiance", d->sun_irradiance);
    set3(p, "uSkyZenith", d->sky_zenith);
    set3(p, "uSkyHorizon", d->sky_horizon);
    /* the world's look (issue #25): off (0) unless the scene asks */
    GLint disc = glGetUniformLocation(p, "uSunDisc");
    if (disc >= 0)
        glUniform2f(disc, (float)(d->sun_disc_deg * M_PI / 180.0), (float)(d->sun_disc_gain > 0 ? d->sun_disc_gain : 20.0));
    set1(p, "uHazeDistance", (float)(d->haze_distance * ref_world_scale(&gw->w)));
    set1(p, "uGroundDetail", (float)d->ground_detail);
    set3(p, "uAmbient", gw->w.ambient);
    set3(p, "uAbsorption", d->absorption);
    set1(p, "uIOR", (float)d->ior);
    set1(p, "uTerrainHalfSize", (float)d->half_size);
    set1(p, "uWorldScale", (float)ref_world_scale(&gw->w));
    /* the terrain's model (ref_scene.c), so world.frag evaluates its height,
     * normal and albedo where the reference does, beyond the square too */
    seti(p, "uTerrainKind", (int)d->terrain);
    GLint loc = glGetUniformLocation(p, "uTerrainShape");
    if (loc >= 0) glUniform4f(loc, (float)d->depth, (float)d->shore_height, (float)d->slope, 0.0f);
    loc = glGetUniformLocation(p, "uTerrainDetail");
    if (loc >= 0) {
        float det[REF_TERRAIN_DETAIL][4];
        for (int i = 0; i < REF_TERRAIN_DETAIL; i++) {
            det[i][0] = (float)gw->w.detail_k[i][0];
            det[i][1] = (float)gw->w.detail_k[i][1];
            det[i][2] = (float)gw->w.detail_a[i];
            det[i][3] = (float)gw->w.detail_phi[i];
        }
        glUniform4fv(loc, REF_TERRAIN_DETAIL, &det[0][0]);
    }
    set1(p, "uTime", (float)t);
    /* where world_follow_waves moved the rest points: a pass that makes
     * photons per grid cell without drawing the points needs it */
    GLint shift = glGetUniformLocation(p, "uWaterShift");
    if (shift >= 0) glUniform2f(shift, (float)gw->water_shift[0], (float)gw->water_shift[1]);
    seti(p, "uSky", WORLD_UNIT_SKY);
    seti(p, "uWaveHeight", WORLD_UNIT_HEIGHT);
    set1(p, "uWaveHeightHalf", (float)(WORLD_HEIGHT_MARGIN * d->half_size));
    seti(p, "uTerrainAlbedo", WORLD_UNIT_ALBEDO);
    seti(p, "uTerrainHeightMap", WORLD_UNIT_TERRAIN);
    set1(p, "uTerrainMapHalf", (float)(WORLD_TERRAIN_MARGIN * d->half_size));
    loc = glGetUniformLocation(p, "uTerrainMapPlane");
    if (loc >= 0) {
        float plane[3];
        terrain_plane(&gw->w, plane);
        glUniform3fv(loc, 1, plane);
    }
    loc = glGetUniformLocation(p, "uCameraPos");
    if (loc >= 0) glUniform3fv(loc, 1, eye);
    for (int i = 0; i < gw->nwaves; i++) {
        const ref_waves_uniform *u = &gw->waves[i];
        loc = glGetUniformLocation(p, u->name);
        if (loc < 0) continue;
        if (u->is_int) glUniform1i(loc, u->i);
        else if (u->is_uint) glUniform1uiv(loc, u->count, u->u);
        else if (u->comps == 4) glUniform4fv(loc, u->count, u->v);
        else if (u->comps == 3) glUniform3fv(loc, u->count, u->v);
        else glUniform1fv(loc, u->count, u->v);
    }
}

void world_bind_textures(const gpu_world *gw) {
    if (!gw->active) return;
    glActiveTexture(GL_TEXTURE0 + WORLD_UNIT_ALBEDO);
    glBindTexture(GL_TEXTURE_2D, gw->albedo_tex);
    glActiveTexture(GL_TEXTURE0 + WORLD_UNIT_SKY);
    glBindTexture(GL_TEXTURE_CUBE_MAP, gw->sky_tex);
    glActiveTexture(GL_TEXTURE0 + WORLD_UNIT_HEIGHT);
    glBindTexture(GL_TEXTURE_2D, gw->height_tex);
    glActiveTexture(GL_TEXTURE0 + WORLD_UNIT_TERRAIN);
    glBindTexture(GL_TEXTURE_2D, gw->terrain_tex);
    glActiveTexture(GL_TEXTURE0);
    ocean_bind(&gw->ocean);
    flow_bind(&gw->flow);
}

/* Binds the world's program for a mode with everything it reads set. */
static void use_mode(const gpu_world *gw, int m, double t, const float eye[3], bool to_screen, const float plane[4],
                     bool layers) {
    unsigned p = gw->progs[m].gl;
    glUseProgram(p);
    world_upload(gw, p, t, eye);
    seti(p, "uWorldLayers", layers ? 1 : 0);
    GLint eye_path = glGetUniformLocation(p, "uWorldEyePath");
    if (eye_path >= 0) glUniform1i(eye_path, to_screen ? 1 : 0);
    GLint clip = glGetUniformLocation(p, "uWorldClip");
    if (clip >= 0) glUniform4fv(clip, 1, plane);
    seti(p, "uWorldMode", m);   /* a world.frag that takes the mode as a uniform */
}

static void draw_modes(const gpu_world *gw, const char *which, double offset, double t, const float eye[3],
                       bool to_screen, unsigned restore_program, bool layers) {
    if (!gw->active) return;
    for (int m = 0; m < WORLD_MODES; m++)
        if (!gw->progs[m].gl) return;
    /* clip at the water plane: "above" keeps y > level, "below" y < level */
    /* the offset is in lake metres, like every length a pack writes */
    float level = (float)(gw->w.d.water_level + offset * ref_world_scale(&gw->w)), plane[4] = { 0, 0, 0, 1 };
    if (strcmp(which, "above") == 0) { plane[1] = 1; plane[3] = -level; }
    if (strcmp(which, "below") == 0) { plane[1] = -1; plane[3] = level; }
    glEnable(GL_CLIP_DISTANCE0);
    if (strcmp(which, "below") != 0) {   /* the sky, behind everything */
        use_mode(gw, 2, t, eye, to_screen, plane, layers);
        render_res_mesh_draw(&gw->sky_box, -1);
    }
    use_mode(gw, 0, t, eye, to_screen, plane, layers);
    render_res_mesh_draw(&gw->terrain[gw->lod], -1);
    render_res_mesh_draw(&gw->skirt[gw->lod], -1);
    use_mode(gw, 1, t, eye, to_screen, plane, layers);
    GLint albedo = glGetUniformLocation(gw->progs[1].gl, "uWorldAlbedo");
    for (int i = 0; i < gw->nobjects; i++) {
        if (albedo >= 0) glUniform3fv(albedo, 1, gw->object_albedo[i]);
        render_res_mesh_draw(&gw->objects[i], -1);
    }
    glDisable(GL_CLIP_DISTANCE0);
    glUseProgram(restore_program);
}

void world_draw(const gpu_world *gw, const char *which, double offset, double t, const float eye[3],
                bool to_screen, unsigned restore_program) {
    draw_modes(gw, which, offset, t, eye, to_screen, restore_program, false);
}

void world_draw_layers(const gpu_world *gw, const char *which, double offset, const float eye[3], bool to_screen,
                       unsigned restore_program) {
    draw_modes(gw, which, offset, 0, eye, to_screen, restore_program, true);   /* no shading reads the time */
}

/* the units the composite borrows: above the world's fixed ones (14, 15,
 * 22-30) and glman's, the last of a GL with 32; a multisampled frame's
 * depth the fourth */
static const int LAYER_UNITS[4] = { 31, 21, 20, 19 };

/* What a composite changes, put back after it. */
typedef struct layers_bound {
    GLint active, before[4];
    GLenum target;
} layers_bound;

/* Binds the layers' program and textures for a frame that reads them as v
 * says; 0: no program to compose with (the caller draws the World). */
static unsigned layers_bind(const gpu_world *gw, double t, const float eye[3], const unsigned tex[4],
                            const world_layer_view *v, layers_bound *b) {
    int ms = v->samples > 1;
    unsigned p = gw->layers_prog[ms].gl;
    if (!gw->active || !p) return 0;
    b->target = ms ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &b->active);
    glUseProgram(p);
    world_upload(gw, p, t, eye);
    static const char *const names[4] = { "uLayerWet", "uLayerDry", "uLayerPos", "uLayerDepth" };
    for (int i = 0; i < 3 + ms; i++) {
        glActiveTexture(GL_TEXTURE0 + LAYER_UNITS[i]);
        glGetIntegerv(ms ? GL_TEXTURE_BINDING_2D_MULTISAMPLE : GL_TEXTURE_BINDING_2D, &b->before[i]);
        glBindTexture(b->target, tex[i]);
        seti(p, names[i], LAYER_UNITS[i]);
    }
    seti(p, "uLayerSamples", v->samples);
    seti(p, "uLayerPickBand", 0);
    GLint scale = glGetUniformLocation(p, "uLayerScale"), offset = glGetUniformLocation(p, "uLayerOffset");
    if (scale >= 0) glUniform2f(scale, v->scale[0], v->scale[1]);
    if (offset >= 0) glUniform2f(offset, v->offset[0], v->offset[1]);
    return p;
}

static void layers_unbind(const world_layer_view *v, const layers_bound *b, unsigned restore_program) {
    for (int i = 0; i < 3 + (v->samples > 1); i++) {
        glActiveTexture(GL_TEXTURE0 + LAYER_UNITS[i]);
        glBindTexture(b->target, (GLuint)b->before[i]);
    }
    glActiveTexture((GLenum)b->active);
    glUseProgram(restore_program);
}

bool world_can_composite(const gpu_world *gw, int samples) {
    return gw->active && gw->layers_prog[samples > 1].gl != 0;
}

/* one triangle over the viewport */
static void draw_full_viewport(void) {
    render_res_vertexid_begin();   /* the vertices come from gl_VertexID */
    glDrawArrays(GL_TRIANGLES, 0, 3);
    render_res_vertexid_end();
}

void world_composite_layers(const gpu_world *gw, double t, const float eye[3], const unsigned tex[4],
                            const world_layer_view *v, int x, int y, unsigned restore_program,
                            const world_layer_band *band) {
    layers_bound b;
    unsigned p = layers_bind(gw, t, eye, tex, v, &b);
    if (!p) return;
    GLint origin = glGetUniformLocation(p, "uLayerOrigin");
    if (origin >= 0) glUniform2i(origin, x, y);
    seti(p, "uLayerBand", band ? 1 : 0);
    if (band) {   /* the band's triangles */
        GLint map = glGetUniformLocation(p, "uLayerBandMap"), pad = glGetUniformLocation(p, "uLayerBandPad");
        if (map >= 0) glUniform4fv(map, 1, band->map);
        if (pad >= 0) glUniform2fv(pad, 1, band->pad);
        glPushClientAttrib(GL_CLIENT_VERTEX_ARRAY_BIT);
        glBindBuffer(GL_ARRAY_BUFFER, band->vbo);
        glEnableClientState(GL_VERTEX_ARRAY);
        glVertexPointer(4, GL_FLOAT, 0, NULL);
        if (band->verts > 0) glDrawArrays(GL_TRIANGLES, 0, band->verts);
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        glPopClientAttrib();
    } else {
        draw_full_viewport();
    }
    layers_unbind(v, &b, restore_program);
}

void world_pick_band_points(const gpu_world *gw, const unsigned tex[4], const world_layer_view *v, double lo,
                            double hi, unsigned restore_program) {
    static const float eye[3] = { 0, 0, 0 };   /* nothing picked reads the eye or the time */
    layers_bound b;
    unsigned p = v->samples > 1 ? layers_bind(gw, 0, eye, tex, v, &b) : 0;
    if (!p) return;
    GLint origin = glGetUniformLocation(p, "uLayerOrigin"), band = glGetUniformLocation(p, "uLayerBandHeights");
    if (origin >= 0) glUniform2i(origin, 0, 0);
    if (band >= 0) glUniform2f(band, (float)lo, (float)hi);
    seti(p, "uLayerBand", 0);
    seti(p, "uLayerPickBand", 1);
    draw_full_viewport();
    layers_unbind(v, &b, restore_program);
}

/* world_wet.glsl's bound sums the sines', Gerstner waves' and noise
 * octaves' amplitudes; fixed_height is that and more (find_height_tiles) */
void world_wet_band(const gpu_world *gw, double *lo, double *hi) {
    layer_band_heights(gw->w.d.water_level, gw->w.waves.fixed_height, lo, hi);
}

void world_draw_water(gpu_world *gw, int tangent_loc) {
    if (!gw->active) return;
    if (!gw->water[gw->lod].vbo && !build_water(gw, gw->lod)) return;   /* moved by world_follow_waves */
    render_res_mesh_draw(&gw->water[gw->lod], tangent_loc);
}

/* N x N points at the cell centres of the world square, at the mean level;
 * built on first use and kept while N and the world stay the same. */
static void build_points(gpu_world *gw, int n) {
    if (!gw->points_vbo) glGenBuffers(1, &gw->points_vbo);
    float *p = mem_alloc((size_t)n * n * 3 * sizeof(float));
    double hs = gw->w.d.half_size;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            float *v = p + ((size_t)j * n + i) * 3;
            v[0] = (float)(-hs + (i + 0.5) * 2 * hs / n + gw->water_shift[0]);
            v[1] = (float)gw->w.d.water_level;
            v[2] = (float)(-hs + (j + 0.5) * 2 * hs / n + gw->water_shift[1]);
        }
    glBindBuffer(GL_ARRAY_BUFFER, gw->points_vbo);
    glBufferData(GL_ARRAY_BUFFER, (long)n * n * 3 * (long)sizeof(float), p, GL_STATIC_DRAW);
    free(p);
    gw->points_n = n;
}

/* The triangles between the N x N points: two per cell of the grid of
 * points, both wound the same way (a splat draws them unculled). */
static void build_mesh_indices(gpu_world *gw, int n) {
    if (!gw->mesh_ibo) glGenBuffers(1, &gw->mesh_ibo);
    size_t cells = (size_t)(n - 1) * (n - 1);
    unsigned *idx = mem_alloc(cells * 6 * sizeof(unsigned)), *o = idx;
    for (int j = 0; j + 1 < n; j++)
        for (int i = 0; i + 1 < n; i++) {
            unsigned a = (unsigned)(j * n + i), b = a + 1, c = a + (unsigned)n, d = c + 1;
            *o++ = a; *o++ = c; *o++ = b;
            *o++ = b; *o++ = c; *o++ = d;
        }
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gw->mesh_ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (long)(cells * 6 * sizeof(unsigned)), idx, GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    free(idx);
    gw->mesh_n = n;
}

void world_draw_points(gpu_world *gw, int n, bool mesh) {
    if (!gw->active || n < 1 || (mesh && n < 2)) return;
    if (gw->points_n != n) build_points(gw, n);
    if (mesh && gw->mesh_n != n) build_mesh_indices(gw, n);
    glBindBuffer(GL_ARRAY_BUFFER, gw->points_vbo);
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(3, GL_FLOAT, 0, (const void *)0);
    if (mesh) {
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gw->mesh_ibo);
        glDrawElements(GL_TRIANGLES, 6 * (n - 1) * (n - 1), GL_UNSIGNED_INT, (const void *)0);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    } else {
        glPointSize(1.0f);
        glDrawArrays(GL_POINTS, 0, n * n);
    }
    glDisableClientState(GL_VERTEX_ARRAY);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

/* ---- the spectrum ocean ---- */

bool world_update_ocean(gpu_world *gw, double t, gpu_timer *timer) {
    if (!gw->active) return false;
    return ocean_update(&gw->ocean, t, timer);
}

static void spray_upload(const void *ctx, unsigned p, double t) {
    static const float origin[3] = { 0, 0, 0 };
    const gpu_world *gw = ctx;
    world_upload(gw, p, t, origin);
    /* the last two height maps, for the ocean's upward speed in the step
     * that ends at the map's time (a short step after the one before) */
    double gap = gw->height_t - gw->height_prev_t;
    bool rate = gw->height_tex && gw->height_prev_tex && gw->height_prev_res == gw->height_res &&
                t == gw->height_t && gap > 0 && gap <= SPRAY_JUMP_DT;
    glActiveTexture(GL_TEXTURE0 + WORLD_UNIT_HEIGHT);
    glBindTexture(GL_TEXTURE_2D, gw->height_tex);
    glActiveTexture(GL_TEXTURE0 + SPRAY_UNIT_HEIGHT_PREV);
    glBindTexture(GL_TEXTURE_2D, gw->height_prev_tex);
    glActiveTexture(GL_TEXTURE0);
    seti(p, "uSprayHeightPrev", SPRAY_UNIT_HEIGHT_PREV);
    set1(p, "uSprayHeightRate", rate ? (float)(1.0 / gap) : 0.0f);
}

bool world_update_spray(gpu_world *gw, double t, gpu_timer *timer) {
    if (!gw->active) return false;
    return spray_update(&gw->spray, t, timer, spray_upload, gw);
}

void world_draw_spray(const gpu_world *gw, const float vp[16], const float eye[3], int w, int h) {
    if (!gw->active) return;
    spray_draw(&gw->spray, vp, eye, w, h, spray_upload, gw);
}

bool world_update_flow(gpu_world *gw, double t, gpu_timer *timer) {
    if (!gw->active) return false;
    return flow_update(&gw->flow, t, timer);
}

/* ---- the waves' height map ---- */

static void height_target(gpu_world *gw, int res) {
    if (!gw->height_tex) {
        glGenTextures(1, &gw->height_tex);
        glGenFramebuffers(1, &gw->height_fbo);
    }
    glBindTexture(GL_TEXTURE_2D, gw->height_tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, res, res, 0, GL_RED, GL_FLOAT, NULL);
    render_res_sampling(GL_TEXTURE_2D, false, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, gw->height_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, gw->height_tex, 0);
    /* the texels the pass never draws (height_quads) hold the level: never
     * read, but defined */
    GLfloat clear[4];
    glGetFloatv(GL_COLOR_CLEAR_VALUE, clear);
    glClearColor((float)gw->w.d.water_level, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glClearColor(clear[0], clear[1], clear[2], clear[3]);
    gw->height_res = res;
}

/* The box an object's triangles lie in. */
static void object_box(const gpu_world *gw, int k, double lo[3], double hi[3]) {
    const ref_object *o = &gw->w.d.objects[k];
    for (int a = 0; a < 3; a++) {
        double half = o->kind == REF_OBJECT_BOX ? o->size[a] : o->size[0];
        lo[a] = o->center[a] - half;
        hi[a] = o->center[a] + half;
    }
    if (o->kind == REF_OBJECT_CYLINDER) {   /* it stands on its base */
        lo[1] = o->center[1];
        hi[1] = o->center[1] + o->size[1];
    }
    if (o->kind == REF_OBJECT_MESH && gw->w.meshes[k]) ref_mesh_bounds(gw->w.meshes[k], lo, hi);
}

/* The cells of the map a wet test reads: under the triangles of the land
 * at every level of detail (the frame picks one) and the objects' boxes,
 * for heights within the waves' bound below the level. world_wet.glsl's
 * bound sums the sines', Gerstner waves' and noise octaves' amplitudes; the
 * reference's bound of every model but the ocean (fixed_height) is that
 * and the explosion rings' and Perlin set's: never less. */
static void find_height_tiles(gpu_world *gw) {
    if (!gw->height_tiles) gw->height_tiles = mem_alloc(sizeof *gw->height_tiles);
    height_tiles *t = gw->height_tiles;
    double map_half = WORLD_HEIGHT_MARGIN * gw->w.d.half_size;
    height_tiles_start(t, map_half, gw->w.d.water_level, gw->w.waves.fixed_height);
    for (int lod = 0; lod < WORLD_LODS; lod++) {
        geom_mesh g;
        if (terrain_geom(gw, lod, false, &g)) {
            height_tiles_add_triangles(t, g.pos, g.idx, g.nidx);
            geom_free(&g);
        }
        if (skirt_geom(gw, lod, false, map_half, &g)) {
            height_tiles_add_triangles(t, g.pos, g.idx, g.nidx);
            geom_free(&g);
        }
    }
    for (int k = 0; k < gw->w.d.nobjects; k++) {
        double lo[3], hi[3];
        object_box(gw, k, lo, hi);
        height_tiles_add_box(t, lo, hi);
    }
}

#define HEIGHT_RECTS_MAX 1024

/* The quads the height pass draws at res texels a side, into
 * height_quads_vbo (made once per res): the cells a wet test reads, or the
 * whole map while a spray reads all of it. Returns their vertex count. */
static int height_quads(gpu_world *gw, int res) {
    bool full = gw->spray.active || gw->height_cells_off;
    if (gw->height_quads_vbo && gw->height_quads_res == res && gw->height_quads_full == full) return gw->height_quads_n;
    if (!full && !gw->height_tiles) find_height_tiles(gw);
    static const float whole[4] = { 0, 0, 1, 1 };
    float *rects = mem_alloc(4 * HEIGHT_RECTS_MAX * sizeof *rects);
    int n = full ? -1 : height_tiles_rects(gw->height_tiles, res, rects, HEIGHT_RECTS_MAX);
    if (n < 0) {
        memcpy(rects, whole, sizeof whole);
        n = 1;
    }
    float *v = mem_alloc((size_t)n * 12 * sizeof *v);
    for (int k = 0; k < n; k++) {
        const float *r = rects + 4 * k;
        float x0 = r[0] * 2 - 1, z0 = r[1] * 2 - 1, x1 = r[2] * 2 - 1, z1 = r[3] * 2 - 1;
        const float tri[12] = { x0, z0, x1, z0, x1, z1, x0, z0, x1, z1, x0, z1 };
        memcpy(v + 12 * k, tri, sizeof tri);
    }
    if (!gw->height_quads_vbo) glGenBuffers(1, &gw->height_quads_vbo);
    glBindBuffer(GL_ARRAY_BUFFER, gw->height_quads_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)((size_t)n * 12 * sizeof *v), v, GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    free(v);
    free(rects);
    gw->height_quads_res = res;
    gw->height_quads_full = full;
    gw->height_quads_n = n * 6;
    return gw->height_quads_n;
}

void world_update_height(gpu_world *gw, double t, double detail) {
    if (!gw->active || gw->height_map_off || !gw->height_prog.gl) return;
    int res = world_detail_count(WORLD_HEIGHT_RES, detail, 32);
    if (gw->height_tex && res == gw->height_res && t == gw->height_t && gw->height_prog.hash == gw->height_hash)
        return;   /* drawn for this time already: a still frame, or a second view */
    if (gw->spray.active && gw->height_tex) {
        /* keep the map before: draw into the other one (swapped, no copy) */
        unsigned tex = gw->height_tex, fbo = gw->height_fbo;
        int r = gw->height_res;
        gw->height_tex = gw->height_prev_tex;
        gw->height_fbo = gw->height_prev_fbo;
        gw->height_res = gw->height_prev_res;
        gw->height_prev_tex = tex;
        gw->height_prev_fbo = fbo;
        gw->height_prev_res = r;
        gw->height_prev_t = gw->height_t;
    }
    if (!gw->height_tex || res != gw->height_res) height_target(gw, res);
    glBindFramebuffer(GL_FRAMEBUFFER, gw->height_fbo);
    render_res_pass_state(res, res);
    unsigned p = gw->height_prog.gl;
    glUseProgram(p);
    const float eye[3] = { 0, 0, 0 };
    world_upload(gw, p, t, eye);
    GLint loc = glGetUniformLocation(p, "uHeightRes");
    if (loc >= 0) glUniform2f(loc, (float)res, (float)res);
    int nverts = height_quads(gw, res);
    glPushClientAttrib(GL_CLIENT_VERTEX_ARRAY_BIT);
    glBindBuffer(GL_ARRAY_BUFFER, gw->height_quads_vbo);
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(2, GL_FLOAT, 0, NULL);
    glDrawArrays(GL_TRIANGLES, 0, nverts);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glPopClientAttrib();
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    gw->height_t = t;
    gw->height_hash = gw->height_prog.hash;
}

void world_set_height_cells(gpu_world *gw, bool on) {
    gw->height_cells_off = !on;
    gw->height_t = NAN;   /* drawn again at the next frame, whatever its time */
}

bool world_set_height_map(gpu_world *gw, bool on, const prog_sources *src, diag_list *log,
                          prog_origins *from) {
    if (gw->height_map_off == !on) return true;
    gw->height_map_off = !on;
    if (!gw->active) return true;
    for (int m = 0; m < WORLD_MODES; m++) set_height_define(gw, &gw->progs[m]);
    for (int ms = 0; ms < 2; ms++) set_height_define(gw, &gw->layers_prog[ms]);
    return world_build_programs(gw, src, log, from);
}
