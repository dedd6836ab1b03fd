/* test_once_reload: a RenderToTextureOnce block is kept across a reload
 * that changed nothing it draws from (render_once_reused), and drawn
 * again after one that did: its shader's source, a slider of its program,
 * its target's size. Each frame after a reload is compared, pixel for
 * pixel, with a fresh load of the same files: keeping a block must never
 * show what a fresh load would not. */
#include <GL/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "support.h"
#include "gl_ctx.h"
#include "gl_support.h"
#include "render.h"
#include "unif.h"

#define W 64
#define H 32

static const char *vert = "#version 330 compatibility\n"
                          "void main() { gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; }\n";

/* The Once block's colour: its slider times a constant of the source. */
static void write_once_frag(const char *k) {
    char src[512];
    snprintf(src, sizeof src,
             "#version 330 compatibility\nuniform float uLevel;\nout vec4 fragColor;\n"
             "void main() { fragColor = vec4(uLevel * %s, 0.25, 0.5, 1.0); }\n", k);
    scratch_write("once.frag", src);
}

/* The screen: the Once target, plus a tint of its own source. */
static void write_show_frag(const char *tint) {
    char src[512];
    snprintf(src, sizeof src,
             "#version 330 compatibility\nuniform sampler2D uOnce;\nout vec4 fragColor;\n"
             "void main() { fragColor = texelFetch(uOnce, ivec2(0), 0) + vec4(0.0, %s, 0.0, 0.0); }\n", tint);
    scratch_write("show.frag", src);
}

static void write_glib(int side) {
    char g[1024];
    snprintf(g, sizeof g,
             "##OpenGL GLIB\nOrtho -1 1 -1 1\nBackground 0 0 0\n"
             "Texture2D 3 %d %d float16\n"
             "RenderToTextureOnce 3\n    Clear\n"
             "    Vertex v.vert\n    Fragment once.frag\n    Program Once uLevel <0 0.5 1>\n"
             "    QuadXY 0 1\n"
             "RenderToTexture\n"
             "Vertex v.vert\nFragment show.frag\nProgram Show uOnce 3\nQuadXY 0 1\n",
             side, side);
    scratch_write("once.glib", g);
}

static void frame(render *r, float *px) {
    render_target tg;
    if (!render_target_create(&tg, W, H, true)) { fprintf(stderr, "no target\n"); exit(1); }
    render_frame(r, 0, tg.fbo, W, H, NULL);
    CHECK(render_target_read(&tg, px));
    render_target_destroy(&tg);
}

static render *loaded(void) {
    render *r = gl_test_load_scratch("once.glib");
    return r;
}

/* r, reloaded, draws what a fresh load of the same files draws. */
static void check_like_fresh(render *r, const char *what) {
    static float a[W * H * 4], b[W * H * 4];
    frame(r, a);
    render *fresh = loaded();
    frame(fresh, b);
    render_destroy(fresh);
    CHECK_MSG(memcmp(a, b, sizeof a) == 0, "%s: the frame after the reload is not a fresh load's (%g vs %g)", what,
              a[0], b[0]);
}

static void set_level(render *r, float v) {
    unif_entry *e = gl_test_uniform(r, "Once", "uLevel");
    CHECK_NE(e, NULL);
    if (e) e->value[0] = v;
}

static void reload(render *r) { CHECK_MSG(render_load(r, NULL), "%s", render_messages(r)); }

static void test_kept_and_redrawn(void) {
    scratch_write("v.vert", vert);
    write_once_frag("1.0");
    write_show_frag("0.0");
    write_glib(16);
    render *r = loaded();
    float px[W * H * 4];
    frame(r, px);
    CHECK_EQ(render_once_reused(r), 0);

    write_show_frag("0.125");   /* the screen's shader only: the block is kept */
    reload(r);
    check_like_fresh(r, "screen shader edited");
    CHECK_MSG(render_once_reused(r) == 1, "kept %ld blocks, want 1", render_once_reused(r));

    write_once_frag("2.0");     /* the block's own shader: drawn again */
    reload(r);
    check_like_fresh(r, "block's shader edited");
    CHECK_MSG(render_once_reused(r) == 1, "a block whose shader changed was kept");

    reload(r);                  /* nothing changed: kept */
    check_like_fresh(r, "nothing edited");
    CHECK_EQ(render_once_reused(r), 2);

    /* a slider of the block's program moved since its pixels were drawn:
     * a fresh load would start from the glib's value, a reload keeps the
     * slider, so compare with the colour itself */
    set_level(r, 0.25f);
    reload(r);
    frame(r, px);
    CHECK_MSG(render_once_reused(r) == 2, "a block whose slider moved was kept");
    CHECK_NEAR(px[0], 0.25 * 2.0, 1e-3);

    write_glib(32);             /* its target's size: drawn again */
    reload(r);
    frame(r, px);
    CHECK_MSG(render_once_reused(r) == 2, "a block whose target was resized was kept");
    CHECK_NEAR(px[0], 0.25 * 2.0, 1e-3);
    render_destroy(r);
}

/* raymarch's ten once-blocks (six top-down views, the floor fill of issue
 * #24 and the skip map's three passes, all counted from
 * packs/raymarch/pack.glib): a reload of the lake keeps them all, and the
 * frame is the same as before it. */
static void test_raymarch_lake(void) {
    render *r = render_create(&(render_desc){ .pack = "raymarch" });
    CHECK_MSG(render_load(r, TARN_SOURCE_DIR "/scenes/lake.glib"), "%s", render_messages(r));
    static float a[W * H * 4], b[W * H * 4];
    frame(r, a);
    reload(r);
    frame(r, b);
    CHECK_MSG(render_once_reused(r) == 10, "raymarch: kept %ld of its 10 Once blocks", render_once_reused(r));
    CHECK_MSG(memcmp(a, b, sizeof a) == 0, "raymarch: the frame after a reload differs");
    render_destroy(r);
}

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    if (!scratch_create("once")) return 1;
    RUN(test_kept_and_redrawn);
    RUN(test_raymarch_lake);
    gl_ctx_destroy(ctx);
    scratch_remove();
    return check_summary();
}
