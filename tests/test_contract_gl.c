/* The pack contract (docs/packs/contract.md) on llvmpipe: the top camera's
 * texel-to-world mapping, the mirror camera's matrix, RenderToTextureOnce,
 * additive photon points, the CPU Splat's energy, generated textures, the
 * terrain's height map. */
#include <GL/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "support.h"
#include "gl_ctx.h"
#include "file.h"
#include "file_cache.h"
#include "render.h"


/* A flat world 4 m a side (half size 2), water at 0.5, no waves. */
static const char *world =
    "##OpenGL GLIB\nPerspective 50\nLookAt 0 3 5  0 0 0  0 1 0\n"
    "Terrain flat 2 1\nWater 0.5\nWaterMesh 8\n";

/* Renders path into a w x h float target; returns RGBA rows, top first. */
static float *draw(const char *path, int w, int h, double t, render **keep) {
    render *r = keep && *keep ? *keep : render_create(NULL);
    if (!keep || !*keep) CHECK_MSG(render_load(r, path), "%s", render_messages(r));
    render_target tg;
    render_target_create(&tg, w, h, true);
    render_frame(r, t, tg.fbo, w, h, NULL);
    float *px = malloc((size_t)w * h * 4 * sizeof(float));
    render_target_read(&tg, px);
    render_target_destroy(&tg);
    GLenum e = glGetError();
    CHECK_MSG(e == GL_NO_ERROR, "GL error 0x%x", e);
    if (keep) *keep = r;
    else render_destroy(r);
    return px;
}

/* Camera top: the water grid drawn with it puts world (x, z) at clip
 * (x / h, z / h), h = uCamTopHalfSize = 1.05 * 2; a fragment writes its
 * interpolated world position, which must equal the texel's own. */
static void test_top_camera_maps_texels_to_world(void) {
    scratch_write("pos.vert", "#version 330 compatibility\nout vec3 vW;\n"
                           "void main() { vW = gl_Vertex.xyz; gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; }\n");
    scratch_write("pos.frag", "#version 330 compatibility\nin vec3 vW;\nout vec4 c;\nvoid main() { c = vec4(vW, 1.); }\n");
    char text[2048];
    snprintf(text, sizeof text, "%sBackground 0 0 0 0\nCamera top\nVertex pos.vert\nFragment pos.frag\nProgram P\n"
             "WaterSurface\n", world);
    scratch_write("top.glib", text);
    int n = 42;
    float *px = draw(scratch_path("top.glib"), n, n, 0, NULL);
    double h = 1.05 * 2, worst = 0;
    int inside = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double x = -h + (i + 0.5) * 2 * h / n, z = -h + ((n - 1 - j) + 0.5) * 2 * h / n;  /* row 0 = top */
            const float *p = px + ((size_t)j * n + i) * 4;
            bool on_water = fabs(x) < 2 - 1e-3 && fabs(z) < 2 - 1e-3;
            if (!on_water) continue;
            inside++;
            CHECK_EQ(p[3], 1.0f);
            worst = fmax(worst, fmax(fabs(p[0] - x), fabs(p[2] - z)));
            CHECK_NEAR(p[1], 0.5, 1e-6);
        }
    fprintf(stderr, "  %d texels, worst |texel centre - world| = %.3g m\n", inside, worst);
    CHECK_GT(inside, n * n / 2);
    CHECK_LT(worst, 1e-4);     /* a linear map interpolated exactly, float rounding only */
    free(px);
}

/* uCamMirrorVP p equals uCamMainVP applied to p reflected about y = level. */
static void test_mirror_matrix_reflects_about_the_water(void) {
    scratch_write("mir.frag", "#version 330 compatibility\nuniform mat4 uCamMainVP, uCamMirrorVP;\nuniform float uWaterLevel;\n"
                           "out vec4 c;\nvoid main() {\n"
                           "  vec4 p = vec4(1.3, 2.7, -0.8, 1.0);\n"
                           "  vec4 m = vec4(p.x, 2.0 * uWaterLevel - p.y, p.z, 1.0);\n"
                           "  vec4 a = uCamMirrorVP * p, b = uCamMainVP * m;\n"
                           "  c = vec4(abs(a - b).xyz, abs(a.w) + abs(b.w));\n}\n");
    char text[2048];
    snprintf(text, sizeof text, "%sVertex pos.vert\nFragment mir.frag\nProgram M\nCamera top\nWaterSurface\n", world);
    scratch_write("mir.glib", text);
    float *px = draw(scratch_path("mir.glib"), 8, 8, 0, NULL);
    const float *p = px + (4 * 8 + 4) * 4;
    CHECK_GT(p[3], 0.1f);                          /* the fragment ran and the matrices were set */
    CHECK(p[0] < 1e-4f && p[1] < 1e-4f && p[2] < 1e-4f);
    free(px);
}

/* A RenderToTextureOnce block draws on the first frame only: its target
 * keeps the first frame's Timer value. */
static void test_render_to_texture_once(void) {
    scratch_write("time.frag", "#version 330 compatibility\nuniform float Timer;\nout vec4 c;\n"
                            "void main() { c = vec4(Timer, 0., 0., 1.); }\n");
    scratch_write("show.frag", "#version 330 compatibility\nuniform sampler2D uT;\nout vec4 c;\n"
                            "void main() { c = texelFetch(uT, ivec2(0), 0); }\n");
    scratch_write("flat.vert", "#version 330 compatibility\nvoid main() { gl_Position = gl_Vertex; }\n");
    scratch_write("once.glib", "##OpenGL GLIB\nTimer 10\nTexture2D 6 4 4 float\n"
                            "RenderToTextureOnce 6\nClear\nVertex flat.vert\nFragment time.frag\nProgram T\nQuadXY 0 1 1 1\n"
                            "RenderToTexture\nFragment show.frag\nProgram S uT 6\nQuadXY 0 1 1 1\n");
    render *r = NULL;
    float *a = draw(scratch_path("once.glib"), 4, 4, 2.0, &r);
    float *b = draw(scratch_path("once.glib"), 4, 4, 7.0, &r);
    CHECK_NEAR(a[0], 0.2, 1e-6);
    CHECK_NEAR(b[0], 0.2, 1e-6);                 /* not 0.7: the block did not run again */
    CHECK(render_load(r, NULL));                 /* a reload draws it once more */
    free(b);
    b = draw(scratch_path("once.glib"), 4, 4, 7.0, &r);
    CHECK_NEAR(b[0], 0.7, 1e-6);
    free(a);
    free(b);
    render_destroy(r);
}

/* WaterSurface points N with Blend add: every point lands once, so the
 * target sums to N^2 (what GPU photon splatting relies on). */
static void test_points_add_up(void) {
    scratch_write("one.frag", "#version 330 compatibility\nout vec4 c;\nvoid main() { c = vec4(1.); }\n");
    scratch_write("pt.vert", "#version 330 compatibility\nvoid main() { gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; }\n");
    char text[2048];
    snprintf(text, sizeof text, "%sBackground 0 0 0 0\nCamera top\nDepthTest off\nBlend add\n"
             "Vertex pt.vert\nFragment one.frag\nProgram P\nWaterSurface points 20\n", world);
    scratch_write("points.glib", text);
    float *px = draw(scratch_path("points.glib"), 16, 16, 0, NULL);
    double sum = 0;
    for (int i = 0; i < 16 * 16; i++) sum += px[i * 4];
    CHECK_NEAR(sum, 400.0, 1e-3);
    free(px);
}

/* WaterSurface mesh N with Blend add: the triangles between the points of
 * `points N` tile their hull (every pixel there is covered exactly once,
 * none twice: what the mesh splat of packs/natural relies on), and vertex
 * k is point (k % N, k / N) (gl_VertexID, so a shader can fetch its
 * photon): the vertex's grid coordinate, interpolated, agrees with its
 * position's, (x / half size + 1) N / 2 - 1/2, at every pixel. */
static void test_mesh_tiles_its_points(void) {
    scratch_write("ij.vert", "#version 330 compatibility\nout vec2 vIJ, vXZ;\n"
                          "void main() { vIJ = vec2(gl_VertexID % 9, gl_VertexID / 9); vXZ = gl_Vertex.xz;\n"
                          "  gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; }\n");
    scratch_write("ij.frag", "#version 330 compatibility\nin vec2 vIJ, vXZ;\nuniform float uTerrainHalfSize;\nout vec4 c;\n"
                          "void main() { vec2 g = (vXZ / uTerrainHalfSize + 1.) * 4.5 - 0.5; c = vec4(1., vIJ - g, 0.); }\n");
    char text[2048];
    snprintf(text, sizeof text, "%sBackground 0 0 0 0\nCamera top\nDepthTest off\nBlend add\nCull none\n"
             "Vertex ij.vert\nFragment ij.frag\nProgram P\nWaterSurface mesh 9\n", world);
    scratch_write("mesh.glib", text);
    int n = 48, once = 0, gaps = 0, twice = 0;
    float *px = draw(scratch_path("mesh.glib"), n, n, 0, NULL);
    double worst = 0;
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
            const float *p = px + (y * n + x) * 4;
            bool centre = x >= n / 5 && x < n - n / 5 && y >= n / 5 && y < n - n / 5;
            if (p[0] > 1.5f) twice++;
            else if (p[0] > 0.5f) once++;
            else if (centre) gaps++;
            worst = fmax(worst, fmax(fabs(p[1]), fabs(p[2])));
        }
    CHECK_MSG(twice == 0 && gaps == 0, "%d pixels drawn twice, %d gaps in the middle", twice, gaps);
    /* the hull, 8/9 of the world square, is (8/9 / 1.05)^2 = 72% of the top
     * camera's view: all but a border of pixels along its edge */
    CHECK_MSG(once > 0.6 * n * n && once < 0.8 * n * n, "%d of %d pixels covered", once, n * n);
    CHECK_MSG(worst < 1e-3, "vertex index and position disagree by %g cells", worst);
    free(px);
}

/* Splat: 16 photons of energy 0.25 at world (0.3, -0.7): the irradiance
 * times the texel area sums to 4 and peaks at that point's texel. */
static void test_splat_conserves_energy(void) {
    scratch_write("photon.frag", "#version 330 compatibility\nout vec4 c;\nvoid main() { c = vec4(0.3, -0.7, 0.25, 1.); }\n");
    scratch_write("grid.frag", "#version 330 compatibility\nuniform sampler2D uG;\nout vec4 c;\n"
                            "void main() { c = texelFetch(uG, ivec2(gl_FragCoord.xy), 0); }\n");
    char text[2048];
    snprintf(text, sizeof text, "%sTexture2D 6 4 4 float\nTexture2D 7 10 10 float\n"
             "RenderToTexture 6\nClear\nVertex flat.vert\nFragment photon.frag\nProgram Ph\nQuadXY 0 1 1 1\nRenderToTexture\n"
             "Splat 6 7\nFragment grid.frag\nProgram G uG 7\nQuadXY 0 1 1 1\n", world);
    scratch_write("splat.glib", text);
    float *px = draw(scratch_path("splat.glib"), 10, 10, 0, NULL);
    double texel_area = (4.0 / 10) * (4.0 / 10), sum = 0, peak = 0;
    int pi = -1, pj = -1;
    for (int j = 0; j < 10; j++)
        for (int i = 0; i < 10; i++) {
            double e = px[(j * 10 + i) * 4];
            sum += e * texel_area;
            if (e > peak) { peak = e; pi = i; pj = 9 - j; }   /* back to GL rows: t ~ z */
        }
    CHECK_NEAR(sum, 4.0, 1e-4);
    /* x = 0.3 -> texel 5 (centres at -1.8 + 0.4 i), z = -0.7 -> row 3 */
    CHECK(pi == 5 && pj == 3);
    free(px);
}

static unif_entry *uniform_of(render *r, const char *program, const char *name) {
    int n;
    unif_set *sets = render_uniforms(r, &n);
    for (int i = 0; i < n; i++)
        if (strcmp(sets[i].program, program) == 0) return unif_find(&sets[i], name);
    return NULL;
}

/* `Texture2D 6 screen screen`: the target is the frame's size and
 * follows it; screen_half and screen_quarter are a half and a quarter of
 * it, rounded up; the names are no sliders (no warning). */
static void test_target_sized_by_the_screen(void) {
    scratch_write("tsize2.frag", "#version 330 compatibility\nuniform sampler2D uT;\nuniform sampler2D uU;\n"
                              "out vec4 c;\nvoid main() { c = vec4(vec2(textureSize(uT, 0)), vec2(textureSize(uU, 0))); }\n");
    scratch_write("screen.glib", "##OpenGL GLIB\nTexture2D 6 screen screen float\n"
                              "Texture2D 7 screen_half screen_quarter depth\n"
                              "Vertex flat.vert\nFragment tsize2.frag\nProgram S uT 6 uU 7\nQuadXY 0 1 1 1\n");
    render *r = NULL;
    float *a = draw(scratch_path("screen.glib"), 5, 3, 0, &r);
    CHECK_MSG(!strstr(render_messages(r), "screen"), "%s", render_messages(r));   /* no 'no Program' warning */
    CHECK_NEAR(a[0], 5, 0);
    CHECK_NEAR(a[1], 3, 0);
    CHECK_NEAR(a[2], 3, 0);      /* 5 / 2 rounded up */
    CHECK_NEAR(a[3], 1, 0);      /* 3 / 4 rounded up */
    float *b = draw(scratch_path("screen.glib"), 9, 8, 0, &r);   /* the frame resized: the targets follow */
    CHECK_NEAR(b[0], 9, 0);
    CHECK_NEAR(b[1], 8, 0);
    CHECK_NEAR(b[2], 5, 0);
    CHECK_NEAR(b[3], 2, 0);
    free(b);
    free(a);
    render_destroy(r);
}

/* `Texture2D 6 uRes uRes`: the target is uRes texels a side and follows
 * the slider; a RenderToTextureOnce block into it draws again after a
 * resize; uTargetSize tells the program drawing into it its size. */
static void test_target_sized_by_a_slider(void) {
    scratch_write("size.frag", "#version 330 compatibility\nuniform vec2 uTargetSize;\nout vec4 c;\n"
                            "void main() { c = vec4(uTargetSize, 0., 1.); }\n");
    scratch_write("tsize.frag", "#version 330 compatibility\nuniform sampler2D uT;\nout vec4 c;\n"
                             "void main() { c = vec4(texelFetch(uT, ivec2(0), 0).xy, vec2(textureSize(uT, 0))); }\n");
    scratch_write("sized.glib", "##OpenGL GLIB\nTexture2D 6 uRes uRes float\n"
                             "RenderToTextureOnce 6\nClear\nVertex flat.vert\nFragment size.frag\nProgram T\nQuadXY 0 1 1 1\n"
                             "RenderToTexture\nFragment tsize.frag\nProgram S uT 6 uRes <8 32 128>\nQuadXY 0 1 1 1\n");
    render *r = NULL;
    float *a = draw(scratch_path("sized.glib"), 4, 4, 0, &r);
    CHECK_MSG(!strstr(render_messages(r), "uRes"), "%s", render_messages(r));   /* no 'not declared' warning */
    CHECK_NEAR(a[0], 32, 0);      /* the once-pass saw a 32 x 32 target */
    CHECK_NEAR(a[2], 32, 0);      /* and it is one */
    unif_entry *e = uniform_of(r, "S", "uRes");
    CHECK(e && unif_is_int(e));   /* a size: a whole-number slider */
    if (e) {
        e->value[0] = 100;
        float *b = draw(scratch_path("sized.glib"), 4, 4, 0, &r);
        CHECK_NEAR(b[0], 100, 0);  /* the once-pass drew again, at the new size */
        CHECK_NEAR(b[3], 100, 0);
        free(b);
        e->max = 1e6f;            /* an absurd slider end: kept to 8192 a side */
        e->value[0] = 1e6f;
        b = draw(scratch_path("sized.glib"), 4, 4, 0, &r);
        CHECK_NEAR(b[2], 8192, 0);
        free(b);
        e->value[0] = NAN;        /* a broken value: the fallback size, no GL error (draw checks) */
        b = draw(scratch_path("sized.glib"), 4, 4, 0, &r);
        CHECK_NEAR(b[2], 256, 0);
        free(b);
    }
    free(a);
    render_destroy(r);
    /* a name no Program has: a warning naming the line, and 256 */
    scratch_write("unsized.glib", "##OpenGL GLIB\nTexture2D 6 uNope 16 float\n"
                               "Vertex flat.vert\nFragment tsize.frag\nProgram S uT 6\nQuadXY 0 1 1 1\n");
    r = NULL;
    a = draw(scratch_path("unsized.glib"), 4, 4, 0, &r);
    CHECK_MSG(strstr(render_messages(r), "unsized.glib:2: warning: Texture2D: no Program") != NULL, "%s",
              render_messages(r));
    CHECK_NEAR(a[2], 256, 0);
    CHECK_NEAR(a[3], 16, 0);
    free(a);
    render_destroy(r);
}

/* `WaterSurface points uN`: N from a slider, and uPointGrid = N, so points
 * of energy 1 / N^2 sum to 1 whatever N is. */
static void test_points_from_a_slider(void) {
    scratch_write("share.frag", "#version 330 compatibility\nuniform float uPointGrid;\nout vec4 c;\n"
                             "void main() { c = vec4(1. / (uPointGrid * uPointGrid)); }\n");
    char text[2048];
    snprintf(text, sizeof text, "%sBackground 0 0 0 0\nCamera top\nDepthTest off\nBlend add\n"
             "Vertex pt.vert\nFragment share.frag\nProgram P uN <1 20 64>\nWaterSurface points uN\n", world);
    scratch_write("npoints.glib", text);
    render *r = NULL;
    for (int k = 0; k < 2; k++) {
        float *px = draw(scratch_path("npoints.glib"), 16, 16, 0, &r);
        double sum = 0;
        for (int i = 0; i < 16 * 16; i++) sum += px[i * 4];
        CHECK_NEAR(sum, 1.0, 1e-4);
        free(px);
        unif_entry *e = uniform_of(r, "P", "uN");
        CHECK_NE(e, NULL);
        if (e) e->value[0] = 37;
    }
    render_destroy(r);
}

/* A Gerstner wave far longer than the world square slides the whole
 * surface (here Q L / 2 pi = 9.5 km along +x): the water grid's rest
 * points follow (world_follow_waves), so the displaced surface, drawn from
 * above, still covers the world square. */
static void test_water_grid_follows_a_sliding_surface(void) {
    scratch_write("disp.vert", "#version 330 compatibility\n#include \"waves.glsl\"\nuniform float uTime;\n"
                            "uniform mat4 uCamTopVP;\nout vec3 vP;\n"
                            "void main() { vec3 n; wavesEval(gl_Vertex.xz, uTime, vP, n); gl_Position = uCamTopVP * vec4(vP, 1.); }\n");
    scratch_write("disp.frag", "#version 330 compatibility\nin vec3 vP;\nout vec4 c;\nvoid main() { c = vec4(vP, 1.); }\n");
    char text[2048];
    snprintf(text, sizeof text, "%sWaveGerstner 0 100000 0.1 0.000001 0\nWaveSteepness 0.6\n"
             "Background 0 0 0 0\nVertex disp.vert\nFragment disp.frag\nProgram P\nWaterSurface\n", world);
    scratch_write("slide.glib", text);
    int n = 40, inside = 0, covered = 0;
    float *px = draw(scratch_path("slide.glib"), n, n, 3.0, NULL);
    double h = 1.05 * 2;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double x = -h + (i + 0.5) * 2 * h / n, z = -h + ((n - 1 - j) + 0.5) * 2 * h / n;
            if (fabs(x) > 1.9 || fabs(z) > 1.9) continue;   /* a cell's margin inside the square */
            inside++;
            covered += px[((size_t)j * n + i) * 4 + 3] == 1.0f;
        }
    fprintf(stderr, "  %d of %d texels inside the square covered\n", covered, inside);
    CHECK(inside > 0 && covered == inside);
    free(px);
}

/* uWaterShift is where tarn moved the rest points of a sliding surface:
 * the one point of `WaterSurface points 1` (the cell centre 0 0 before the
 * move) writes its rest point into the left pixel, a quad writes
 * uWaterShift into the right one; they agree, and the move is not 0. */
static void test_water_shift_uniform(void) {
    scratch_write("restpt.vert", "#version 330 compatibility\nout vec2 vR;\n"
                              "void main() { vR = gl_Vertex.xz; gl_Position = vec4(-0.5, 0., 0., 1.); }\n");
    scratch_write("restpt.frag", "#version 330 compatibility\nin vec2 vR;\nout vec4 c;\n"
                              "void main() { c = vec4(vR, 0., 1.); }\n");
    scratch_write("right.vert", "#version 330 compatibility\n"
                             "void main() { gl_Position = vec4(gl_Vertex.x * 0.5 + 0.5, gl_Vertex.y, 0., 1.); }\n");
    scratch_write("shift.frag", "#version 330 compatibility\nuniform vec2 uWaterShift;\nout vec4 c;\n"
                             "void main() { c = vec4(uWaterShift, 0., 1.); }\n");
    char text[2048];
    snprintf(text, sizeof text, "%sWaveGerstner 0 100000 0.1 0.000001 0\nWaveSteepness 0.6\n"
             "Background 0 0 0 0\nDepthTest off\nVertex restpt.vert\nFragment restpt.frag\nProgram P\n"
             "WaterSurface points 1\nVertex right.vert\nFragment shift.frag\nProgram S\nQuadXY 0 1 1 1\n", world);
    scratch_write("shift.glib", text);
    float *px = draw(scratch_path("shift.glib"), 2, 1, 3.0, NULL);
    fprintf(stderr, "  rest point of the centre cell %.4f %.4f, uWaterShift %.4f %.4f\n", px[0], px[1], px[4],
            px[5]);
    CHECK_GT(fabs(px[0]), 0.1);              /* the surface slid: the points moved */
    CHECK_NEAR(px[4], px[0], 1e-5);
    CHECK_NEAR(px[5], px[1], 1e-5);
    free(px);
}

/* @caustics is generated, tileable, with mean 1. */
static void test_generated_caustics(void) {
    scratch_write("caus.frag", "#version 330 compatibility\nuniform sampler2D uC;\nout vec4 c;\n"
                            "void main() { c = texture(uC, gl_FragCoord.xy / 64.0); }\n");
    scratch_write("caus.glib", "##OpenGL GLIB\nTexture2D 5 @caustics\nVertex flat.vert\nFragment caus.frag\n"
                            "Program C uC 5\nQuadXY 0 1 1 1\n");
    float *px = draw(scratch_path("caus.glib"), 64, 64, 0, NULL);
    double mean = 0, var = 0;
    for (int i = 0; i < 64 * 64; i++) mean += px[i * 4] / (64.0 * 64.0);
    for (int i = 0; i < 64 * 64; i++) var += (px[i * 4] - mean) * (px[i * 4] - mean) / (64.0 * 64.0);
    fprintf(stderr, "  caustics: mean %.3f, std %.3f\n", mean, sqrt(var));
    CHECK_NEAR(mean, 1.0, 0.05);   /* 64^2 samples of a 128^2 texture with mip filtering: ~1% off */
    CHECK_GT(sqrt(var), 0.1);        /* a pattern, not a constant */
    /* made once per file cache: a second scene loading it (the window's
     * compile job, compare-view's next pack) gets the same texels from
     * memory, no photon tracing */
    file_cache *files = file_cache_create();
    render_desc d = { .files = files };
    render *a = render_create(&d), *b = render_create(&d);
    CHECK_MSG(render_load(a, scratch_path("caus.glib")), "%s", render_messages(a));
    CHECK_MSG(render_load(b, scratch_path("caus.glib")), "%s", render_messages(b));
    CHECK_EQ(file_cache_counts_of(files).made, 1);   /* the tracing ran once */
    float *pa = draw(scratch_path("caus.glib"), 64, 64, 0, &a), *pb = draw(scratch_path("caus.glib"), 64, 64, 0, &b);
    CHECK_EQ(memcmp(pa, px, 64 * 64 * 4 * sizeof(float)), 0);
    CHECK_EQ(memcmp(pb, px, 64 * 64 * 4 * sizeof(float)), 0);
    free(pa);
    free(pb);
    render_destroy(a);
    render_destroy(b);
    file_cache_destroy(files);
    free(px);
}

static double caustics_mean(void) {
    float *px = draw(scratch_path("caus.glib"), 64, 64, 0, NULL);   /* a new renderer: a new file cache */
    double mean = 0;
    for (int i = 0; i < 64 * 64; i++) mean += px[i * 4] / (64.0 * 64.0);
    free(px);
    return mean;
}

/* @caustics is kept in tarn's cache folder across runs (disk_cache.h): a
 * new process (here a new renderer with its own file cache) reads it from
 * there. Shown by changing the kept texels: a load reads the change; a
 * damaged file is traced again and rewritten. */
static void test_generated_caustics_kept_on_disk(void) {
    char keep_xdg[4096] = "", path[4096], err[256];
    const char *x = getenv("XDG_CACHE_HOME");
    if (x) snprintf(keep_xdg, sizeof keep_xdg, "%s", x);
    setenv("XDG_CACHE_HOME", scratch_dir, 1);
    snprintf(path, sizeof path, "%s/tarn/made/caustics-128.f32", scratch_dir);
    CHECK(!file_exists(path));
    CHECK_NEAR(caustics_mean(), 1.0, 0.05);                 /* traced, and kept */
    size_t n = 0;
    char *bytes = file_read(path, 1 << 20, &n, err, sizeof err);
    CHECK_MSG(bytes != NULL, "%s", err);
    const size_t header = 24, texels = 128 * 128;
    CHECK_EQ(n, header + texels * sizeof(float));
    if (bytes && n == header + texels * sizeof(float)) {
        for (size_t i = 0; i < texels; i++) {
            float two = 2.0f;
            memcpy(bytes + header + i * sizeof(float), &two, sizeof two);
        }
        CHECK(file_write(path, bytes, n, err, sizeof err));
        CHECK_NEAR(caustics_mean(), 2.0, 1e-5);             /* read from the folder, not traced */
        bytes[0] ^= 1;                                       /* not a kept file any more */
        CHECK(file_write(path, bytes, n, err, sizeof err));
        CHECK_NEAR(caustics_mean(), 1.0, 0.05);             /* traced again */
        free(bytes);
        bytes = file_read(path, 1 << 20, &n, err, sizeof err);
        CHECK(bytes && memcmp(bytes, "tarnmade", 8) == 0);  /* and kept again */
    }
    free(bytes);
    remove(path);
    char dir[4200];
    snprintf(dir, sizeof dir, "%s/tarn/made", scratch_dir);
    rmdir(dir);
    snprintf(dir, sizeof dir, "%s/tarn", scratch_dir);
    rmdir(dir);
    if (keep_xdg[0]) setenv("XDG_CACHE_HOME", keep_xdg, 1);
    else unsetenv("XDG_CACHE_HOME");
}

/* uTerrainHeightMap (terrainHeightMarch) against the terrain's model
 * (terrainHeightGrad) over 1.6 half sizes, past the map's 1.3, for each
 * kind of terrain. The bounds, in the world's scale: bilinear error
 * a k^2 h^2 / 8 summed over the lake's detail sines (texels 2.6 hs / 512
 * apart: 0.3 mm on the 12 m lake), the pool walls' smoothstep about 2 mm,
 * the slope exact but float rounding. A map half a texel off would be
 * ~15 mm out on the lake's floor; a clamped edge that lost the slope's
 * plane, metres. */
static void test_terrain_map_matches_the_model(void) {
    scratch_write("terr.frag", "#version 330 compatibility\nuniform float uWaterLevel;\n#include \"terrain.glsl\"\n"
                            "out vec4 c;\nvoid main() {\n"
                            "  vec2 xz = (gl_FragCoord.xy / 96.0 * 2.0 - 1.0) * 1.6 * uTerrainHalfSize;\n"
                            "  float h = terrainHeightGrad(xz).x;\n"
                            "  c = vec4(terrainHeightMarch(xz) - h, h, 0., 1.);\n}\n");
    const struct { const char *terrain; double bound; } cases[] = {
        { "Terrain lake 12 3 0.6 7", 0.0005 },
        { "Terrain lake 1200 300 60 7", 0.05 },    /* the same lake 100 times larger */
        { "Terrain pool 12 1.5 0.4", 0.003 },
        { "Terrain slope 12 2 0.25", 1e-5 },
        { "Terrain flat 12 2", 1e-6 },
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char text[1024];
        snprintf(text, sizeof text, "##OpenGL GLIB\n%s\nWater 0\nVertex flat.vert\nFragment terr.frag\nProgram T\n"
                 "QuadXY 0 1 1 1\n", cases[k].terrain);
        scratch_write("terr.glib", text);
        float *px = draw(scratch_path("terr.glib"), 96, 96, 0, NULL);
        double worst = 0, lo = 1e30, hi = -1e30;
        for (int i = 0; i < 96 * 96; i++) {
            worst = fmax(worst, fabs(px[i * 4]));
            lo = fmin(lo, px[i * 4 + 1]);
            hi = fmax(hi, px[i * 4 + 1]);
        }
        fprintf(stderr, "  %s: heights %.3g..%.3g m, map off the model by at most %.3g m\n", cases[k].terrain, lo, hi,
                worst);
        CHECK_MSG(worst < cases[k].bound, "%s: the map is %g m off the model (bound %g)", cases[k].terrain, worst,
                  cases[k].bound);
        free(px);
    }
}

/* If blocks: a Define toggle of the pack, and scene facts. The flat world
 * (floor 1 m under the water, no objects) has nothing above the water. */
static void test_if_blocks(void) {
    scratch_write("red.frag", "#version 330 compatibility\nout vec4 c;\nvoid main() { c = vec4(1., 0., 0., 1.); }\n");
    scratch_write("green.frag", "#version 330 compatibility\nout vec4 c;\nvoid main() { c = vec4(0., 1., 0., 1.); }\n");
    char text[2048];
    snprintf(text, sizeof text, "%sBackground 0 0 0 0\nVertex flat.vert\n"
             "Fragment red.frag\nDefine EXTRA <false>\nProgram R\n"
             "If EXTRA\nQuadXY 0 1 1 1\nEndIf\n"
             "Fragment green.frag\nProgram G\n"
             "If above_water\nQuadXY 0 1 1 1\nEndIf\n"
             "Blend add\nIf not above_water\nIf not EXTRA\nQuadXY 0 1 1 1\nEndIf\nEndIf\n", world);
    scratch_write("if.glib", text);
    render *r = NULL;
    float *px = draw(scratch_path("if.glib"), 4, 4, 0, &r);
    CHECK_NEAR(px[0], 0.0, 1e-6);    /* EXTRA off: no red */
    CHECK_NEAR(px[1], 1.0, 1e-6);    /* one green: only the `not above_water` block */
    free(px);
    int n;
    unif_set *sets = render_uniforms(r, &n);
    unif_entry *extra = n ? unif_find(&sets[0], "EXTRA") : NULL;
    CHECK_NE(extra, NULL);
    if (extra) {
        extra->value[0] = 1;
        render_rebuild_programs(r);
        px = draw(scratch_path("if.glib"), 4, 4, 0, &r);
        CHECK_NEAR(px[0], 1.0, 1e-6);    /* EXTRA on: red, and the nested green block is off */
        CHECK_NEAR(px[1], 0.0, 1e-6);
        free(px);
    }
    render_destroy(r);
}

/* loops.glsl: on a CPU rasteriser tarn builds with TARN_CPU_RASTER and
 * ROLLED(n) adds uLoopZero, which nobody sets: the loop still runs n
 * times, the uniform gets no slider and no message; on a GPU ROLLED(n) is
 * n. (The compile time it saves is docs/benchmark.md's, not a test's.) */
static void test_rolled_loops(void) {
    scratch_write("rolled.frag", "#version 330 compatibility\n#include \"loops.glsl\"\nout vec4 c;\n"
                                 "void main() {\n    float s = 0.;\n"
                                 "    for (int i = 0; i < ROLLED(5); i++) s += 1.;\n"
                                 "    for (int i = -1; i <= ROLLED(1); i++) s += 10.;\n"
                                 "#ifdef TARN_CPU_RASTER\n    c = vec4(s, 1., 0., 1.);\n"
                                 "#else\n    c = vec4(s, 0., 0., 1.);\n#endif\n}\n");
    scratch_write("rolled.glib", "##OpenGL GLIB\nVertex flat.vert\nFragment rolled.frag\nProgram S\nQuadXY 0 1 1 1\n");
    render *r = NULL;
    float *px = draw(scratch_path("rolled.glib"), 4, 4, 0, &r);
    CHECK_MSG(!render_has_errors(r), "%s", render_messages(r));
    CHECK_NEAR(px[0], 35.0, 0);                               /* 5 + 3 times 10: uLoopZero is 0 */
    CHECK_NEAR(px[1], gl_ctx_cpu_rasteriser() ? 1.0 : 0.0, 0);   /* the define where it belongs */
    CHECK(uniform_of(r, "S", "uLoopZero") == NULL);             /* no slider */
    CHECK_MSG(!strstr(render_messages(r), "uLoopZero"), "%s", render_messages(r));
    free(px);
    render_destroy(r);
}

int main(void) {
    char err[512];
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    if (!ctx) { fprintf(stderr, "skip: %s\n", err); return 77; }
    if (!scratch_create("contract")) return 1;
    RUN(test_top_camera_maps_texels_to_world);
    RUN(test_mirror_matrix_reflects_about_the_water);
    RUN(test_render_to_texture_once);
    RUN(test_points_add_up);
    RUN(test_target_sized_by_a_slider);
    RUN(test_target_sized_by_the_screen);
    RUN(test_points_from_a_slider);
    RUN(test_mesh_tiles_its_points);
    RUN(test_water_grid_follows_a_sliding_surface);
    RUN(test_water_shift_uniform);
    RUN(test_splat_conserves_energy);
    RUN(test_generated_caustics);
    RUN(test_generated_caustics_kept_on_disk);
    RUN(test_if_blocks);
    RUN(test_terrain_map_matches_the_model);
    RUN(test_rolled_loops);
    gl_ctx_destroy(ctx);
    scratch_remove();
    return check_summary();
}
