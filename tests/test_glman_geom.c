/* test_glman_geom: glman's geometry commands, tessellation, raw textures
 * and a failing draw (issue 14), each as a small glman-style project written
 * here (a .glib and its shaders), rendered headless and checked by pixels.
 *
 * Every scene looks down -Z from the origin (no LookAt, as glman) through
 * `Ortho -2 2 -2 2` at 64 x 64: 16 pixels a unit, world (x, y) at pixel
 * ((x + 2) 16, (2 - y) 16). */
#include <GL/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "support.h"
#include "gl_ctx.h"
#include "render.h"

#define W 64
#define H 64
#define TOL (1.5 / 255.0)

static gl_ctx *ctx;
static float px[W * H * 4];
static char msgs[8192];         /* the load's and the draws' messages of the last draw_scene */

/* Renders the glib text (written as name in the scratch folder) into px;
 * false when the load had errors (the picture is drawn anyway). */
static bool draw_scene(const char *name, const char *glib) {
    scratch_write(name, glib);
    /* MSAA off: these check shader outputs pixel for pixel (an ID, a
     * vertex count), which a resolve blends at edges; test_msaa checks MSAA */
    render *r = render_create(&(render_desc){ .samples = 1 });
    bool ok = render_load(r, scratch_path(name));
    render_target tg;
    if (!render_target_create(&tg, W, H, false)) { fprintf(stderr, "no target\n"); exit(1); }
    render_frame(r, 0, tg.fbo, W, H, NULL);
    CHECK_MSG(render_target_read(&tg, px), "reading the picture failed (a GL error left over)");
    render_frame(r, 0, tg.fbo, W, H, NULL);   /* a second frame says nothing new */
    snprintf(msgs, sizeof msgs, "%s", render_messages(r));
    ok = ok && !render_has_errors(r);
    render_target_destroy(&tg);
    render_destroy(r);
    return ok;
}

/* The pixel at world (x, y). */
static const float *at(double x, double y) {
    int i = (int)((x + 2) * 16), j = (int)((2 - y) * 16);
    i = i < 0 ? 0 : i >= W ? W - 1 : i;
    j = j < 0 ? 0 : j >= H ? H - 1 : j;
    return px + ((size_t)j * W + i) * 4;
}

static bool is_rgb(const float *p, double r, double g, double b, double tol) {
    return fabs(p[0] - r) <= tol && fabs(p[1] - g) <= tol && fabs(p[2] - b) <= tol;
}

#define EXPECT(x, y, r, g, b, tol) do { const float *p_ = at(x, y); \
    CHECK_MSG(is_rgb(p_, r, g, b, tol), "at (%g, %g): %.3f %.3f %.3f, want %.3f %.3f %.3f", \
              (double)(x), (double)(y), p_[0], p_[1], p_[2], (double)(r), (double)(g), (double)(b)); } while (0)
#define BACKGROUND(x, y) EXPECT(x, y, 0, 0, 0, TOL)

/* A vertex colour shader (Color before each draw) for shapes. */
static void write_color_shaders(void) {
    scratch_write("col.vert", "#version 120\nvoid main() { gl_FrontColor = gl_Color; gl_Position = ftransform(); }\n");
    scratch_write("col.frag", "#version 120\nvoid main() { gl_FragColor = gl_Color; }\n");
}

#define HEAD "##OpenGL GLIB\nOrtho -2 2 -2 2\n"

/* DiskXY, Triangles, Xarrow, PointCloud: each where and what size glman
 * draws it. */
static void test_shapes(void) {
    write_color_shaders();
    bool ok = draw_scene("shapes.glib", HEAD "Vertex col.vert\nFragment col.frag\nProgram Col\n"
        "Color 1 0 0\nPushMatrix\nTranslate -1 1 -4\nScale 0.8\nDiskXY\nPopMatrix\n"
        "Color 0 1 0\nPushMatrix\nTranslate 0 0 -4\nTriangles 0.3 0.3 0  1.7 0.3 0  0.3 1.7 0\nPopMatrix\n"
        "Color 0 0 1\nPushMatrix\nTranslate -1.8 -1 -4\nScale 1.5 10 10\nXarrow\nPopMatrix\n"
        "Color 1 1 0\nPointSize 4\nPushMatrix\nTranslate 1 -1 -4\nScale 0.5\nPointCloud 2 2 2\nPopMatrix\n");
    CHECK_MSG(ok, "%s", msgs);
    EXPECT(-1, 1, 1, 0, 0, TOL);          /* the disk: radius 0.8 */
    EXPECT(-0.32, 1, 1, 0, 0, TOL);
    BACKGROUND(-1 + 0.7, 1 + 0.7);        /* its bounding square's corner, radius 0.99 */
    EXPECT(0.6, 0.6, 0, 1, 0, TOL);       /* the triangle, and past its hypotenuse */
    BACKGROUND(1.2, 1.2);
    EXPECT(-1.2, -1, 0, 0, 1, TOL);       /* the arrow's shaft (radius 0.2) and head (0.6 at x = -0.6) */
    BACKGROUND(-1.2, -1.4);
    EXPECT(-0.55, -1.35, 0, 0, 1, TOL);
    BACKGROUND(-0.2, -1);                 /* it ends at x = -1.8 + 1.5 */
    EXPECT(1.25, -0.75, 1, 1, 0, TOL);    /* a point of the cloud, and the empty middle */
    EXPECT(0.75, -1.25, 1, 1, 0, TOL);
    BACKGROUND(1, -1);
}

/* QuadBox's third texture coordinate and the sphere's Tangent. */
static void test_attributes(void) {
    scratch_write("stp.vert", "#version 120\nvarying vec3 vSTP;\n"
                  "void main() { vSTP = gl_MultiTexCoord0.stp; gl_Position = ftransform(); }\n");
    scratch_write("stp.frag", "#version 120\nvarying vec3 vSTP;\nvoid main() { gl_FragColor = vec4(vSTP, 1.); }\n");
    /* the nearest of 5 quads is z = 1: p = 1; s, t span the quad 0..1 */
    bool ok = draw_scene("box.glib", HEAD "Vertex stp.vert\nFragment stp.frag\nProgram Stp\n"
                         "Translate 0 0 -4\nQuadBox 5\n");
    CHECK_MSG(ok, "%s", msgs);
    EXPECT(0.03, 0.03, 0.5, 0.5, 1, 0.03);
    EXPECT(-0.9, 0.9, 0.05, 0.95, 1, 0.03);
    BACKGROUND(1.5, 1.5);

    scratch_write("tan.vert", "#version 120\nattribute vec3 Tangent;\nvarying vec3 vT;\n"
                  "void main() { vT = Tangent; gl_Position = ftransform(); }\n");
    scratch_write("tan.frag", "#version 120\nvarying vec3 vT;\n"
                  "void main() { gl_FragColor = vec4(normalize(vT) * 0.5 + 0.5, 1.); }\n");
    /* the sphere's front faces the eye: the tangent there is +y (north) */
    ok = draw_scene("tan.glib", HEAD "Vertex tan.vert\nFragment tan.frag\nProgram Tan\n"
                    "Translate 0 0 -4\nSphere\n");
    CHECK_MSG(ok, "%s", msgs);
    EXPECT(0.03, 0.03, 0.5, 1, 0.5, 0.05);
}

/* Soccerball: FaceIndex is set face by face, 0-11 pentagons, 12-31
 * hexagons; the faces seen from the front carry several of each. */
static void test_soccerball(void) {
    scratch_write("face.vert", "#version 120\nvoid main() { gl_Position = ftransform(); }\n");
    scratch_write("face.frag", "#version 120\nuniform float FaceIndex;\n"
                  "void main() { gl_FragColor = vec4(FaceIndex / 31., 0., 0., 1.); }\n");
    bool ok = draw_scene("ball.glib", HEAD "Vertex face.vert\nFragment face.frag\nProgram Face\n"
                         "Translate 0 0 -4\nSoccerball 1.5\n");
    CHECK_MSG(ok, "%s", msgs);
    bool seen[32] = { false };
    int off = 0, inside = 0;
    for (double y = -1.2; y <= 1.2; y += 1 / 16.0)
        for (double x = -1.2; x <= 1.2; x += 1 / 16.0) {
            if (x * x + y * y > 1.2 * 1.2) continue;
            inside++;
            double k = at(x, y)[0] * 31;
            long ki = lround(k);
            off += fabs(k - (double)ki) > 0.1 || ki < 0 || ki > 31;
            if (ki >= 0 && ki < 32) seen[ki] = true;
        }
    int pent = 0, hex = 0;
    for (int k = 0; k < 32; k++) {
        if (k < 12) pent += seen[k];
        else hex += seen[k];
    }
    CHECK_MSG(off == 0, "%d of %d pixels are not one face's FaceIndex", off, inside);
    CHECK_MSG(pent >= 2 && hex >= 4, "faces seen: %d pentagons, %d hexagons", pent, hex);
    BACKGROUND(1.8, 1.8);
}

/* Geometry shaders get what they declare: LinesAdjacency's 4 points (drawn
 * by the shader as a quad), ObjAdj's neighbours (a triangle with one is
 * red, one without green). WireObj draws the edges only. */
static void test_adjacency(void) {
    scratch_write("pass.vert", "#version 330 compatibility\n"
                  "void main() { gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; }\n");
    scratch_write("red.frag", "#version 330 compatibility\nin vec4 gColor;\n"
                  "void main() { gl_FragColor = gColor; }\n");
    scratch_write("quad.geom", "#version 330 compatibility\nlayout(lines_adjacency) in;\n"
                  "layout(triangle_strip, max_vertices = 4) out;\nout vec4 gColor;\n"
                  "void main() { int o[4] = int[4](0, 1, 3, 2);\n"
                  "  for (int i = 0; i < 4; i++) { gColor = vec4(1., 0., 0., 1.); gl_Position = gl_in[o[i]].gl_Position; EmitVertex(); }\n"
                  "  EndPrimitive(); }\n");
    bool ok = draw_scene("ladj.glib", HEAD "Vertex pass.vert\nGeometry quad.geom\nFragment red.frag\nProgram Q\n"
                         "Translate 0 0 -4\nLinesAdjacency [-1 -1 0] [1 -1 0] [-1 1 0] [1 1 0]\n");
    CHECK_MSG(ok, "%s", msgs);
    EXPECT(0, 0, 1, 0, 0, TOL);
    EXPECT(0.9, 0.9, 1, 0, 0, TOL);
    BACKGROUND(1.5, 1.5);

    scratch_write("two.obj", "v -1.8 -0.8 0\nv -0.2 -0.8 0\nv -0.2 0.8 0\nv -1.8 0.8 0\n"
                  "v 0.2 -0.8 0\nv 1.8 -0.8 0\nv 1.0 0.8 0\n"
                  "f 1 2 3\nf 1 3 4\nf 5 6 7\n");
    scratch_write("adj.geom", "#version 330 compatibility\nlayout(triangles_adjacency) in;\n"
                  "layout(triangle_strip, max_vertices = 3) out;\nout vec4 gColor;\n"
                  "bool differs(int a, int b) { return distance(gl_in[a].gl_Position, gl_in[b].gl_Position) > 1e-4; }\n"
                  "void main() {\n"
                  "  bool neighbour = differs(1, 4) || differs(3, 0) || differs(5, 2);\n"
                  "  for (int i = 0; i < 6; i += 2) { gColor = neighbour ? vec4(1., 0., 0., 1.) : vec4(0., 1., 0., 1.);\n"
                  "    gl_Position = gl_in[i].gl_Position; EmitVertex(); }\n"
                  "  EndPrimitive(); }\n");
    ok = draw_scene("oadj.glib", HEAD "Vertex pass.vert\nGeometry adj.geom\nFragment red.frag\nProgram A\n"
                    "Translate 0 0 -4\nObjAdj two.obj\n");
    CHECK_MSG(ok, "%s", msgs);
    EXPECT(-1.4, 0.4, 1, 0, 0, TOL);      /* both halves of the square have a neighbour */
    EXPECT(-0.6, -0.4, 1, 0, 0, TOL);
    EXPECT(1.0, -0.3, 0, 1, 0, TOL);      /* the lone triangle has none */
    BACKGROUND(0, 1.5);

    write_color_shaders();
    ok = draw_scene("wire.glib", HEAD "Vertex col.vert\nFragment col.frag\nProgram Col\nLineWidth 3\n"
                    "Color 1 1 1\nTranslate 0 0 -4\nWireObj two.obj\n");
    CHECK_MSG(ok, "%s", msgs);
    EXPECT(-1.0, -0.8, 1, 1, 1, TOL);     /* an edge, the diagonal; not the inside */
    EXPECT(-1.0, 0.0, 1, 1, 1, TOL);
    BACKGROUND(-1.4, 0.3);
    BACKGROUND(1.0, -0.3);
}

/* Tessellation: a patch of 4 from glBegin gl_patches (and the same from
 * ObjPatch) through a quads evaluation shader that bends the patch up by
 * 0.5 sin(pi u) and colours it (u, v): the bend shows only where the patch
 * was cut into many triangles. A plain QuadXY under a triangles
 * tessellation program is drawn as patches of 3. */
static void test_tessellation(void) {
    scratch_write("tess.vert", "#version 400 compatibility\nvoid main() { gl_Position = gl_Vertex; }\n");
    scratch_write("quad.tcs", "#version 400 compatibility\nlayout(vertices = 4) out;\n"
                  "void main() { gl_out[gl_InvocationID].gl_Position = gl_in[gl_InvocationID].gl_Position;\n"
                  "  gl_TessLevelOuter[0] = gl_TessLevelOuter[1] = gl_TessLevelOuter[2] = gl_TessLevelOuter[3] = 16.;\n"
                  "  gl_TessLevelInner[0] = gl_TessLevelInner[1] = 16.; }\n");
    scratch_write("quad.tes", "#version 400 compatibility\nlayout(quads, equal_spacing, ccw) in;\nout vec2 vUV;\n"
                  "void main() { vec2 uv = gl_TessCoord.xy; vUV = uv;\n"
                  "  vec4 a = mix(gl_in[0].gl_Position, gl_in[1].gl_Position, uv.x);\n"
                  "  vec4 b = mix(gl_in[3].gl_Position, gl_in[2].gl_Position, uv.x);\n"
                  "  vec4 p = mix(a, b, uv.y); p.y += 0.5 * sin(3.14159265 * uv.x);\n"
                  "  gl_Position = gl_ModelViewProjectionMatrix * p; }\n");
    scratch_write("uv.frag", "#version 400 compatibility\nin vec2 vUV;\n"
                  "void main() { gl_FragColor = vec4(vUV, 0., 1.); }\n");
    const char *progs = HEAD "Vertex tess.vert\nTessControl quad.tcs\nTessEvaluation quad.tes\n"
                        "Fragment uv.frag\nProgram Bend\nTranslate 0 0 -4\nNumPatchVertices 4\n";
    char text[1024];
    snprintf(text, sizeof text, "%sglBegin gl_patches\nglVertex -1 -1 0\nglVertex 1 -1 0\nglVertex 1 1 0\n"
             "glvertex -1 1 0\nglend\n", progs);
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1) {
            scratch_write("patch.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
            snprintf(text, sizeof text, "%sObjPatch patch.obj\n", progs);
        }
        bool ok = draw_scene("tess.glib", text);
        CHECK_MSG(ok, "pass %d: %s", pass, msgs);
        EXPECT(0.5 + 1 / 32.0, -0.5 + 0.5 * 0.7071 + 1 / 32.0, 0.75, 0.25, 0, 0.04);   /* u 0.75, v 0.25, bent up */
        /* the top edge bulges to y = 1.5 at x = 0: the pixel at (0.031, 1.281) has u 0.516 and
         * v = (1.281 + 1 - 0.5 sin(pi u)) / 2 = 0.891 */
        EXPECT(0, 1.3, 0.516, 0.891, 0, 0.02);
        BACKGROUND(0, -0.8);                  /* the bottom edge too: up to -0.5 */
        BACKGROUND(0.9, 1.3);
    }

    scratch_write("tri.tcs", "#version 400 compatibility\nlayout(vertices = 3) out;\n"
                  "void main() { gl_out[gl_InvocationID].gl_Position = gl_in[gl_InvocationID].gl_Position;\n"
                  "  gl_TessLevelOuter[0] = gl_TessLevelOuter[1] = gl_TessLevelOuter[2] = 2.; gl_TessLevelInner[0] = 2.; }\n");
    scratch_write("tri.tes", "#version 400 compatibility\nlayout(triangles) in;\nout vec2 vUV;\n"
                  "void main() { vec3 b = gl_TessCoord; vUV = vec2(1., 1.);\n"
                  "  gl_Position = gl_ModelViewProjectionMatrix * (b.x * gl_in[0].gl_Position + b.y * gl_in[1].gl_Position + b.z * gl_in[2].gl_Position); }\n");
    bool ok = draw_scene("tri.glib", HEAD "Vertex tess.vert\nTessControl tri.tcs\nTessEvaluation tri.tes\n"
                         "Fragment uv.frag\nProgram Tri\nTranslate 0 0 -4\nQuadXY 0 1\n");
    CHECK_MSG(ok, "%s", msgs);
    EXPECT(0.5, 0.5, 1, 1, 0, TOL);
    EXPECT(-0.5, -0.5, 1, 1, 0, TOL);
    BACKGROUND(1.5, 1.5);

    /* ObjPatch keeps its faces' size (triangles: 3) over a NumPatchVertices
     * meant for glBegin, and says so */
    scratch_write("tri3.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nf 1 2 3\n");
    ok = draw_scene("tri3.glib", HEAD "Vertex tess.vert\nTessControl tri.tcs\nTessEvaluation tri.tes\n"
                    "Fragment uv.frag\nProgram Tri\nTranslate 0 0 -4\nNumPatchVertices 4\nObjPatch tri3.obj\n");
    CHECK_MSG(ok, "%s", msgs);
    CHECK_STR_CONTAINS(msgs, "tri3.glib:10: warning: ObjPatch draws patches of its faces' 3 corners; NumPatchVertices 4 (line 9)");
    EXPECT(0.5, -0.5, 1, 1, 0, TOL);
    BACKGROUND(-0.5, 0.5);
}

/* ---- raw textures ---- */

static void put_i32(FILE *f, int v) {
    unsigned char b[4] = { (unsigned char)v, (unsigned char)(v >> 8), (unsigned char)(v >> 16), (unsigned char)(v >> 24) };
    fwrite(b, 1, 4, f);
}

/* A raw texture of s x t x p (p 0: a 2D file) whose texel (i, j, k) has
 * colour rgba(i, j, k) (as bytes, or as floats when is_float). */
typedef void (*texel_fn)(int i, int j, int k, float rgba[4]);

static void write_raw(const char *name, int s, int t, int p, bool is_float, texel_fn fn) {
    FILE *f = fopen(scratch_path(name), "wb");
    if (!f) { CHECK_NE(f, NULL); return; }
    put_i32(f, s);
    put_i32(f, t);
    if (p) put_i32(f, p);
    for (int k = 0; k < (p ? p : 1); k++)
        for (int j = 0; j < t; j++)
            for (int i = 0; i < s; i++) {
                float c[4];
                fn(i, j, k, c);
                for (int q = 0; q < 4; q++) {
                    if (is_float) fwrite(&c[q], 4, 1, f);
                    else fputc((int)lroundf(c[q] * 255), f);
                }
            }
    fclose(f);
}

/* 4 x 4: the left half red, the right blue; rows t >= 2 get green */
static void quadrants(int i, int j, int k, float c[4]) {
    (void)k;
    c[0] = i < 2;
    c[1] = j >= 2 ? 1.0f : 0.0f;
    c[2] = i >= 2;
    c[3] = 1;
}

/* floats beyond 1 stay floats: the shader halves them */
static void bright(int i, int j, int k, float c[4]) {
    (void)j; (void)k;
    c[0] = i < 2 ? 1.6f : 0.2f;
    c[1] = 0.4f;
    c[2] = 1.2f;
    c[3] = 1;
}

static void depth_halves(int i, int j, int k, float c[4]) {
    (void)i; (void)j;
    c[0] = k < 2;
    c[1] = 0;
    c[2] = k >= 2;
    c[3] = 1;
}

static int cube_face;
static void face_colour(int i, int j, int k, float c[4]) {
    (void)i; (void)j; (void)k;
    static const float cols[6][3] = { {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1} };
    memcpy(c, cols[cube_face], 3 * sizeof(float));
    c[3] = 1;
}

/* Texture2D with a raw file of bytes (rows from t = 0 at the bottom, as
 * glman uploaded them) and of floats; Texture3D raw; CubeMap raw faces. */
static void test_raw_textures(void) {
    scratch_write("st.vert", "#version 120\nvarying vec2 vST;\n"
                  "void main() { vST = gl_MultiTexCoord0.st; gl_Position = ftransform(); }\n");
    scratch_write("t2.frag", "#version 120\nuniform sampler2D uTex;\nuniform float uGain;\nvarying vec2 vST;\n"
                  "void main() { gl_FragColor = texture2D(uTex, vST) * uGain; }\n");
    write_raw("q.tex", 4, 4, 0, false, quadrants);
    bool ok = draw_scene("raw2.glib", HEAD "Texture2D 5 q.tex\nVertex st.vert\nFragment t2.frag\n"
                         "Program T uTex 5 uGain 1\nTranslate 0 0 -4\nQuadXY 0 2\n");
    CHECK_MSG(ok, "%s", msgs);
    EXPECT(-1, -1, 1, 0, 0, TOL);   /* s, t 0.25: bottom left, texel (0, 0) */
    EXPECT(-1, 1, 1, 1, 0, TOL);    /* t 0.75: rows 2, 3 are green too */
    EXPECT(1, -1, 0, 0, 1, TOL);
    write_raw("f.tex", 4, 4, 0, true, bright);
    ok = draw_scene("rawf.glib", HEAD "Texture2D 5 f.tex\nVertex st.vert\nFragment t2.frag\n"
                    "Program T uTex 5 uGain 0.5\nTranslate 0 0 -4\nQuadXY 0 2\n");
    CHECK_MSG(ok, "%s", msgs);
    EXPECT(-1, 0, 0.8, 0.2, 0.6, TOL);
    EXPECT(1, 0, 0.1, 0.2, 0.6, TOL);

    scratch_write("t3.frag", "#version 120\nuniform sampler3D uVol;\nvarying vec2 vST;\n"
                  "void main() { gl_FragColor = texture3D(uVol, vec3(0.5, 0.5, vST.s)); }\n");
    write_raw("v.tex", 4, 4, 4, false, depth_halves);
    ok = draw_scene("raw3.glib", HEAD "Texture3D 6 v.tex\nVertex st.vert\nFragment t3.frag\n"
                    "Program V uVol 6\nTranslate 0 0 -4\nQuadXY 0 2\n");
    CHECK_MSG(ok, "%s", msgs);
    EXPECT(-1, 0, 1, 0, 0, TOL);    /* p 0.25 */
    EXPECT(1, 0, 0, 0, 1, TOL);     /* p 0.75 */

    static const char *const names[6] = { "px.tex", "nx.tex", "py.tex", "ny.tex", "pz.tex", "nz.tex" };
    for (cube_face = 0; cube_face < 6; cube_face++) write_raw(names[cube_face], 2, 2, 0, false, face_colour);
    scratch_write("cube.frag", "#version 120\nuniform samplerCube uCube;\nvarying vec2 vST;\n"
                  "void main() { gl_FragColor = textureCube(uCube, vST.s < 0.5 ? vec3(1., 0., 0.) : vec3(0., -1., 0.)); }\n");
    ok = draw_scene("cube.glib", HEAD "CubeMap 7 px.tex nx.tex py.tex ny.tex pz.tex nz.tex\nVertex st.vert\n"
                    "Fragment cube.frag\nProgram C uCube 7\nTranslate 0 0 -4\nQuadXY 0 2\n");
    CHECK_MSG(ok, "%s", msgs);
    EXPECT(-1, 0, 1, 0, 0, TOL);    /* +x */
    EXPECT(1, 0, 1, 1, 0, TOL);     /* -y */
}

/* A raw file whose header does not fit its size, or cut short: a message
 * with the Texture2D's line and the sizes; nothing crashes, the rest draws. */
static void test_bad_raw_files(void) {
    FILE *f = fopen(scratch_path("bad.tex"), "wb");
    if (!f) { CHECK_NE(f, NULL); return; }
    put_i32(f, 8);
    put_i32(f, 8);
    for (int i = 0; i < 100; i++) fputc(7, f);
    fclose(f);
    f = fopen(scratch_path("short.tex"), "wb");
    if (!f) { CHECK_NE(f, NULL); return; }
    put_i32(f, 8);
    fclose(f);
    f = fopen(scratch_path("huge.tex"), "wb");
    if (!f) { CHECK_NE(f, NULL); return; }
    put_i32(f, -5);
    put_i32(f, 1 << 30);
    put_i32(f, 3);
    fclose(f);
    write_color_shaders();
    bool ok = draw_scene("badraw.glib", HEAD "Texture2D 5 bad.tex\nTexture2D 6 short.tex\nTexture3D 7 huge.tex\n"
                         "Vertex col.vert\nFragment col.frag\nProgram Col\nColor 1 0 0\nTranslate 0 0 -4\nQuadXY 0 1\n");
    CHECK(!ok);
    CHECK_STR_CONTAINS(msgs, "badraw.glib:3: error: Texture2D:");
    CHECK_STR_CONTAINS(msgs, "has 100 bytes after its 2-number header, but 8 x 8 RGBA texels take 256 (bytes) or 1024 (floats)");
    CHECK_STR_CONTAINS(msgs, "badraw.glib:4: error: Texture2D:");
    CHECK_STR_CONTAINS(msgs, "badraw.glib:5: error: Texture3D:");
    EXPECT(0, 0, 1, 0, 0, TOL);
}

/* A draw OpenGL refuses (a Sphere into a geometry shader that takes
 * triangles_adjacency; patches with no tessellation stage) draws nothing,
 * says so once with its line and what to do, and the rest is drawn: the
 * picture is not lost. */
static void test_failed_draw_keeps_the_picture(void) {
    write_color_shaders();
    scratch_write("pass.vert", "#version 330 compatibility\n"
                  "void main() { gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; }\n");
    scratch_write("red.frag", "#version 330 compatibility\nin vec4 gColor;\n"
                  "void main() { gl_FragColor = gColor; }\n");
    scratch_write("adj2.geom", "#version 330 compatibility\nlayout(triangles_adjacency) in;\n"
                  "layout(triangle_strip, max_vertices = 3) out;\nout vec4 gColor;\n"
                  "void main() { for (int i = 0; i < 6; i += 2) { gColor = vec4(0., 0., 1., 1.);\n"
                  "  gl_Position = gl_in[i].gl_Position; EmitVertex(); } EndPrimitive(); }\n");
    bool ok = draw_scene("errs.glib", HEAD "Vertex pass.vert\nGeometry adj2.geom\nFragment red.frag\nProgram Adj\n"
                         "Translate 0 0 -4\nSphere 1.5\n"
                         "Geometry\nVertex col.vert\nFragment col.frag\nProgram Col\nColor 1 0 0\nQuadXY 0 0.5\n"
                         "glBegin gl_patches\nglVertex 1 1 0\nglVertex 1.5 1 0\nglVertex 1.5 1.5 0\nglEnd\n"
                         "Color 0 1 0\nTranslate 1.5 -1.5 0\nQuadXY 0 0.25\n");
    CHECK(!ok);
    EXPECT(0, 0, 1, 0, 0, TOL);          /* the quads after the failed draws */
    EXPECT(1.5, -1.5, 0, 1, 0, TOL);
    BACKGROUND(0, 1.2);                  /* the sphere drew nothing */
    CHECK_STR_CONTAINS(msgs, "errs.glib:8: error: Sphere drew nothing (GL_INVALID_OPERATION)");
    CHECK_STR_CONTAINS(msgs, "(layout(triangles_adjacency) in); draw ObjAdj with it");
    CHECK_STR_CONTAINS(msgs, "errs.glib:15: error: glBegin drew nothing: it draws GL_PATCHES");
    CHECK_STR_CONTAINS(msgs, "TessEvaluation");
    const char *first = strstr(msgs, "errs.glib:8:");
    CHECK_MSG(first && !strstr(first + 1, "errs.glib:8:"), "said more than once:\n%s", msgs);

    /* `tarn render` (ctest gives its path): the picture is written, the
     * message printed, and the exit code says the input had errors */
    const char *bin = getenv("TARN_BIN");
    if (!bin || !bin[0]) return;
    char cmd[1200], out[8192];
    snprintf(cmd, sizeof cmd, "'%s' render '%s' -o '%s' --size 32x32 2>&1", bin, scratch_path("errs.glib"),
             scratch_path("errs.png"));
    int rc = run_command(cmd, out, sizeof out);
    CHECK_MSG(rc == 1, "tarn render exited %d:\n%s", rc, out);
    CHECK_STR_CONTAINS(out, "errs.glib:8: error: Sphere drew nothing");
    CHECK_STR_CONTAINS(out, "wrote");
    FILE *f = fopen(scratch_path("errs.png"), "rb");
    CHECK_MSG(f != NULL, "no picture written");
    if (f) fclose(f);
}

/* Shp: a shapefile of one Polygon record, a square ring from (-1, -1) to
 * (1, 1), written here; drawn as its outline on the XY plane in the file's
 * units. A missing or broken file is an error naming it. */
static void put32(unsigned char *b, unsigned v, bool big) {
    for (int k = 0; k < 4; k++) b[k] = (unsigned char)(v >> (big ? 24 - 8 * k : 8 * k));
}
static void put64(unsigned char *b, double d) {
    unsigned long long u;
    memcpy(&u, &d, sizeof u);
    for (int k = 0; k < 8; k++) b[k] = (unsigned char)(u >> (8 * k));
}

static void test_shapefile(void) {
    unsigned char f[100 + 8 + 44 + 4 + 5 * 16];
    memset(f, 0, sizeof f);
    put32(f, 9994, true);
    put32(f + 24, (unsigned)(sizeof f / 2), true);
    put32(f + 28, 1000, false);
    put32(f + 32, 5, false);
    put64(f + 36, -1); put64(f + 44, -1); put64(f + 52, 1); put64(f + 60, 1);
    unsigned char *r = f + 100;
    put32(r, 1, true);
    put32(r + 4, (44 + 4 + 5 * 16) / 2, true);
    put32(r + 8, 5, false);
    put32(r + 8 + 36, 1, false);
    put32(r + 8 + 40, 5, false);
    const double ring[] = {-1, -1, -1, 1, 1, 1, 1, -1, -1, -1};   /* clockwise, as the format's outer rings */
    for (int i = 0; i < 10; i++) put64(r + 8 + 48 + 8 * i, ring[i]);
    FILE *fp = fopen(scratch_path("square.shp"), "wb");
    CHECK(fp && fwrite(f, 1, sizeof f, fp) == sizeof f);
    if (fp) fclose(fp);
    write_color_shaders();
    bool ok = draw_scene("shp.glib", HEAD "Vertex col.vert\nFragment col.frag\nProgram Col\n"
                         "LineWidth 3\nColor 0 1 0\nTranslate 0 0 -4\nShp square.shp\n");
    CHECK_MSG(ok, "%s", msgs);
    int lit = 0;
    for (int k = -30; k <= 30; k++) {        /* each edge, away from the corners */
        double u = k / 32.0;
        lit += at(u, 1)[1] > 0.5 || at(u, 1 - 1 / 16.0)[1] > 0.5;
        lit += at(u, -1)[1] > 0.5 || at(u, -1 - 1 / 16.0)[1] > 0.5;
        lit += at(1, u)[1] > 0.5 || at(1 - 1 / 16.0, u)[1] > 0.5;
        lit += at(-1, u)[1] > 0.5 || at(-1 - 1 / 16.0, u)[1] > 0.5;
    }
    CHECK_MSG(lit == 4 * 61, "%d of %d outline samples lit", lit, 4 * 61);
    BACKGROUND(0, 0);                        /* an outline: the inside stays empty */
    BACKGROUND(1.5, 1.5);

    ok = draw_scene("noshp.glib", HEAD "Vertex col.vert\nFragment col.frag\nProgram Col\nShp world_borders.shp\n");
    CHECK(!ok);
    CHECK_MSG(strstr(msgs, "world_borders.shp") && strstr(msgs, "Shp"), "%s", msgs);
    CHECK_MSG(!strstr(msgs, "unknown command"), "%s", msgs);
    scratch_write("notshp.shp", "this is not a shapefile, it is a text file of more than one hundred bytes ......"
                                "......................................................................\n");
    ok = draw_scene("badshp.glib", HEAD "Vertex col.vert\nFragment col.frag\nProgram Col\nShp notshp.shp\n");
    CHECK(!ok);
    CHECK_MSG(strstr(msgs, "notshp.shp") && strstr(msgs, "not a shapefile"), "%s", msgs);
}

int main(void) {
    char err[512];
    ctx = gl_ctx_create_headless(err, sizeof err);
    if (!ctx) {
        fprintf(stderr, "skip: %s\n", err);
        return 77;
    }
    if (!scratch_create("glman-geom")) return 1;
    RUN(test_shapes);
    RUN(test_attributes);
    RUN(test_soccerball);
    RUN(test_adjacency);
    RUN(test_tessellation);
    RUN(test_raw_textures);
    RUN(test_bad_raw_files);
    RUN(test_failed_draw_keeps_the_picture);
    RUN(test_shapefile);
    gl_ctx_destroy(ctx);
    scratch_remove();
    return check_summary();
}
