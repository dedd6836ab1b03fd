/* The static-world cache (viewer/gfx/world_cache.h): a frame whose World
 * draws were copied from the cache equals, pixel for pixel, the same frame
 * drawn with the cache off; a changed camera, time, uniform or world draws
 * the world again (the frame equals a fresh render's, and differs from the
 * cached one); a reload that kept the world (a save of a pack's shader)
 * keeps the cache. The packs' passes cover a float colour target with a depth
 * texture (natural's refraction and reflection) and the screen. */
#include <GL/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "gl_ctx.h"
#include "gl_support.h"
#include "render.h"
#include "unif.h"

#define W 160
#define H 90
#define LAKE TARN_SOURCE_DIR "/scenes/lake.glib"
#define POOL TARN_SOURCE_DIR "/scenes/pool.glib"

typedef struct rig {
    render *r;
    render_target tg;
} rig;

/* samples: the screen passes' MSAA (0: the renderer's default) */
static void rig_open_msaa(rig *g, const char *pack, bool cache, bool is_float, int samples) {
    render_desc rd = { .pack = pack, .samples = samples };
    g->r = render_create(&rd);
    CHECK_MSG(render_load(g->r, LAKE), "%s", render_messages(g->r));
    render_set_world_cache(g->r, cache);
    CHECK(render_target_create(&g->tg, W, H, is_float));
}

static void rig_open(rig *g, const char *pack, bool cache, bool is_float) {
    rig_open_msaa(g, pack, cache, is_float, 0);
}

static void rig_close(rig *g) {
    render_target_destroy(&g->tg);
    render_destroy(g->r);
}

/* One frame at t from view v (NULL: the scene's), read back. */
static float *frame(rig *g, double t, const render_view *v) {
    float *px = malloc((size_t)W * H * 4 * sizeof(float));
    render_frame(g->r, t, g->tg.fbo, W, H, v);
    render_target_read(&g->tg, px);
    GLenum e = glGetError();
    CHECK_MSG(e == GL_NO_ERROR, "GL error 0x%x", e);
    return px;
}

static bool same(const float *a, const float *b) { return memcmp(a, b, (size_t)W * H * 4 * sizeof(float)) == 0; }

/* cached (on) and drawn (off) side by side through the same changes */
static void check_pack(const char *pack, bool is_float) {
    rig on, off;
    rig_open(&on, pack, true, is_float);
    rig_open(&off, pack, false, is_float);
    /* the first frame at a time draws, the second keeps, the third copies */
    float *a0 = frame(&on, 2.0, NULL), *a0b = frame(&on, 2.0, NULL);
    long h0 = render_world_cache_hits(on.r);
    CHECK_EQ(h0, 0);
    float *a1 = frame(&on, 2.0, NULL), *b1 = frame(&off, 2.0, NULL);
    CHECK_MSG(render_world_cache_hits(on.r) > h0, "%s: the second frame copied no World", pack);
    CHECK_MSG(render_world_cache_hits(off.r) == 0, "%s: the cache was off", pack);
    CHECK_MSG(same(a0, b1) && same(a0b, b1) && same(a1, b1), "%s: a cached frame differs from a drawn one", pack);

    /* the camera moves: drawn again, as a fresh render draws it */
    render_view v = render_default_view(on.r);
    v.eye[0] -= 1.5f;
    v.eye[1] += 0.7f;
    float *a2 = frame(&on, 2.0, &v), *b2 = frame(&off, 2.0, &v);
    CHECK_MSG(same(a2, b2) && !same(a2, a1), "%s: a moved camera", pack);

    /* the time changes (the shore wets and dries with the waves) */
    float *a3 = frame(&on, 2.5, &v), *b3 = frame(&off, 2.5, &v);
    CHECK_MSG(same(a3, b3), "%s: a later time", pack);
    free(frame(&on, 2.5, &v));   /* kept: the uniform below must not copy it */

    /* a uniform that moves a pass's camera (natural: Camera wide uFovScale) */
    unif_entry *fov = gl_test_uniform(on.r, NULL, "uFovScale"), *fov_off = gl_test_uniform(off.r, NULL, "uFovScale");
    if (fov && fov_off) {
        unif_set_component(fov, 0, 2.0);
        unif_set_component(fov_off, 0, 2.0);
        float *a4 = frame(&on, 2.5, &v), *b4 = frame(&off, 2.5, &v);
        CHECK_MSG(same(a4, b4) && !same(a4, a3), "%s: a changed uniform", pack);
        free(a4);
        free(b4);
    }

    /* a reload that kept the world (its description and programs): kept,
     * the next frame copies (the sliders keep their values on a reload) */
    free(frame(&on, 2.0, NULL));
    free(frame(&on, 2.0, NULL));   /* kept again at the scene's view */
    CHECK(render_load(on.r, LAKE));
    CHECK(render_load(off.r, LAKE));
    long h1 = render_world_cache_hits(on.r);
    float *a5 = frame(&on, 2.0, NULL), *b5 = frame(&off, 2.0, NULL);
    CHECK_MSG(render_world_cache_hits(on.r) > h1, "%s: a reload that kept the world forgot its cache", pack);
    CHECK_MSG(same(a5, b5), "%s: after a reload that kept the world", pack);

    /* another world in between forgets: the next frame draws, then copies again */
    CHECK(render_load(on.r, POOL));
    free(frame(&on, 2.0, NULL));
    CHECK(render_load(on.r, LAKE));
    long h2 = render_world_cache_hits(on.r);
    float *a6 = frame(&on, 2.0, NULL);
    CHECK_MSG(render_world_cache_hits(on.r) == h2, "%s: the first frame after another world copied a World", pack);
    float *a7 = frame(&on, 2.0, NULL), *a8 = frame(&on, 2.0, NULL), *b6 = frame(&off, 2.0, NULL);
    CHECK_GT(render_world_cache_hits(on.r), h2);
    CHECK_MSG(same(a6, b6) && same(a7, b6) && same(a8, b6), "%s: after another world", pack);

    float *all[] = { a0, a0b, a1, b1, a2, b2, a3, b3, a5, b5, a6, a7, a8, b6 };
    for (size_t i = 0; i < sizeof all / sizeof *all; i++) free(all[i]);
    rig_close(&on);
    rig_close(&off);
}

/* A running clock with the camera still: from the second time on each
 * World is composed from its layers (world_layers.h), from the third the
 * second's whole frame copied and only the band where the surface meets
 * the land composed (world_layer_band.h), and every frame equals, bit for
 * bit, the frame drawn with the cache off: the lake (terrain, objects,
 * sky; the shore uncovered and covered by the waves), and from under the
 * water (the eye's path in water fades the world); with 4x MSAA too
 * (each sample composed, the depth copied). */
static void check_running_clock(const char *pack, bool is_float, const render_view *v, int samples) {
    rig on, off;
    rig_open_msaa(&on, pack, true, is_float, samples);
    rig_open_msaa(&off, pack, false, is_float, samples);
    for (int k = 0; k < 5; k++) {
        double t = 1.0 + 0.37 * k;
        float *a = frame(&on, t, v), *b = frame(&off, t, v);
        CHECK_MSG(same(a, b), "%s, %d samples, t = %.2f: the composed frame differs from the drawn one", pack,
                  samples, t);
        free(a);
        free(b);
    }
    CHECK_MSG(render_world_layer_frames(on.r) >= 3, "%s: %ld World draws composed from layers, want 3 or more", pack,
              render_world_layer_frames(on.r));
    /* from the third frame on, the first whole one copied and the band composed */
    CHECK_MSG(render_world_band_frames(on.r) >= 2, "%s: %ld World draws composed the band alone, want 2 or more", pack,
              render_world_band_frames(on.r));
    CHECK_EQ(render_world_layer_frames(off.r), 0);
    rig_close(&on);
    rig_close(&off);
}

/* One frame of g at t, w x h in the corner of its W x H target, read
 * back. (The detail stays: the wet test's height map follows it, so a
 * frame at another detail is not the layers' size's frame sampled.) */
static float *frame_at(rig *g, double t, int w, int h) {
    float *px = malloc((size_t)W * H * 4 * sizeof(float));
    render_frame(g->r, t, g->tg.fbo, w, h, NULL);
    render_target_read(&g->tg, px);
    return px;
}

/* Does the w x h frame a (in the GL corner of a W x H read-back, whose
 * rows run from the top) hold, pixel for pixel, the texel of the lw x lh
 * frame b that sees what the pixel sees: what the composite picks from
 * layers larger than the frame (world_layers.frag)? The scene's
 * projection takes its aspect from the viewport, so a pixel's normalised
 * x is b's over r = (w / h) / (lw / lh). A texel within 1e-3 of a texel's
 * edge may round either way (the GL's float arithmetic, not this). */
static bool nearest_of(const float *a, int w, int h, const float *b, int lw, int lh) {
    double r = ((double)w / h) / ((double)lw / lh);
    for (int y = 0; y < h; y++)   /* GL's rows, from the bottom */
        for (int x = 0; x < w; x++) {
            double tx = (((x + 0.5) / w * 2 - 1) * r + 1) / 2 * lw, ty = (y + 0.5) / h * lh;
            const float *p = a + ((size_t)(H - 1 - y) * W + x) * 4;
            bool found = false;
            for (int e = 0; e < 4 && !found; e++) {
                int bx = (int)floor(tx + ((e & 1) ? 1e-3 : -1e-3)), by = (int)floor(ty + ((e & 2) ? 1e-3 : -1e-3));
                bx = bx < 0 ? 0 : bx >= lw ? lw - 1 : bx;
                const float *q = b + ((size_t)(H - 1 - by) * W + bx) * 4;
                found = memcmp(p, q, 4 * sizeof(float)) == 0;
            }
            if (!found) return false;
        }
    return true;
}

/* The window's budget draws a running clock at a new size from frame to
 * frame. Each size builds its layers, every frame the frame drawn whole;
 * while render_keep_world_layers is set (the window draws a third of the
 * pixels while a save's job compiles, then the size from before), a
 * smaller frame is composed from the larger layers instead (exactly the
 * frame drawn at the layers' size, each pixel the texel that sees what it
 * sees) and growing back to them builds nothing; a larger one builds. A
 * second frame at a size composes only the band over the first, kept
 * (one whole frame is kept a World: another size's replaces it).
 * Checked against frames drawn with the cache off, on a scene of the
 * lake's world alone (no water pass over it). */
static void check_running_clock_resizing(const char *pack, bool is_float) {
    (void)pack;
    char path[512];
    const char *tmp = getenv("TMPDIR");
    snprintf(path, sizeof path, "%s/tarn_world_layers_%d.glib", tmp && *tmp ? tmp : "/tmp", (int)getpid());
    FILE *in = fopen(LAKE, "r"), *out = fopen(path, "w");
    CHECK(in && out);
    if (!in || !out) return;
    char line[1024];
    while (fgets(line, sizeof line, in))
        if (strncmp(line, "Pack", 4) != 0) fputs(line, out);
    fputs("Clear\nWorld all\n", out);
    fclose(in);
    fclose(out);
    /* w, h, keep; the layers' size the frame is composed from (0: drawn
     * whole); 1: the band alone over the whole frame kept at its size */
    static const int steps[][6] = {
        { 144, 81, 0, 0, 0, 0 },     { 144, 81, 0, 144, 81, 0 }, { 86, 48, 1, 144, 81, 0 },
        { 86, 48, 1, 144, 81, 1 },   { 97, 55, 1, 144, 81, 0 },  { 144, 81, 0, 144, 81, 0 },
        { 131, 74, 0, 131, 74, 0 },  { 144, 81, 1, 144, 81, 0 }, { 131, 74, 1, 144, 81, 0 },
        { 131, 74, 1, 144, 81, 1 },  { 160, 90, 1, 160, 90, 0 }, { 89, 50, 1, 160, 90, 0 },
        { 89, 50, 1, 160, 90, 1 },   { 89, 50, 1, 160, 90, 1 },
    };
    const int n = (int)(sizeof steps / sizeof *steps);
    rig on, off;
    render_desc rd = { 0 };
    on.r = render_create(&rd);
    off.r = render_create(&rd);
    CHECK_MSG(render_load(on.r, path), "%s", render_messages(on.r));
    CHECK(render_load(off.r, path));
    render_set_world_cache(off.r, false);
    CHECK(render_target_create(&on.tg, W, H, is_float) && render_target_create(&off.tg, W, H, is_float));
    for (int k = 0; k < n; k++) {
        double t = 1.0 + 0.37 * k;   /* far enough apart that the shore moves */
        int w = steps[k][0], h = steps[k][1], lw = steps[k][3], lh = steps[k][4];
        render_keep_world_layers(on.r, steps[k][2] != 0);
        long before = render_world_layer_frames(on.r), band_before = render_world_band_frames(on.r);
        float *a = frame_at(&on, t, w, h);
        CHECK_MSG(render_world_layer_frames(on.r) == before + (lw > 0), "%s, %dx%d: composed %ld times, want %d", pack, w,
                  h, render_world_layer_frames(on.r) - before, lw > 0);
        CHECK_MSG(render_world_band_frames(on.r) == band_before + steps[k][5], "%dx%d, step %d: the band alone %ld times, want %d",
                  w, h, k, render_world_band_frames(on.r) - band_before, steps[k][5]);
        /* the truth: the frame drawn whole at the layers' size (or its own) */
        float *b = frame_at(&off, t, lw > 0 ? lw : w, lh > 0 ? lh : h);
        CHECK_MSG(nearest_of(a, w, h, b, lw > 0 ? lw : w, lh > 0 ? lh : h),
                  "%dx%d at t = %.2f: not the frame drawn at %dx%d%s", w, h, t, lw > 0 ? lw : w, lh > 0 ? lh : h,
                  lw > 0 && lw != w ? ", nearest texels" : "");
        free(a);
        free(b);
    }
    rig_close(&on);
    rig_close(&off);
    remove(path);
}

static void test_running_clock_layers(void) {
    check_running_clock_resizing("basic", false);
    check_running_clock("basic", false, NULL, 1);
    check_running_clock("natural", true, NULL, 1);
    /* `tarn render`'s default: multisampled layers, a sample at a time */
    check_running_clock("basic", false, NULL, 4);
    check_running_clock("natural", true, NULL, 4);
    /* under the water, looking at the rock and the shore */
    render_view below = { .eye = { 0.0f, -0.6f, 2.0f }, .center = { -3.0f, -0.2f, -3.0f }, .up = { 0, 1, 0 } };
    check_running_clock("basic", false, &below, 1);
}

static void test_basic_rgba8(void) { check_pack("basic", false); }

/* A pass drawn once (RenderToTextureOnce, skipped from the second frame)
 * before the screen's World: the screen stays clean and is copied. */
static void test_screen_after_a_once_pass(void) {
    FILE *in = fopen(LAKE, "r");
    char path[512], line[1024];
    const char *tmp = getenv("TMPDIR");
    snprintf(path, sizeof path, "%s/tarn_world_cache_%d.glib", tmp && *tmp ? tmp : "/tmp", (int)getpid());
    FILE *out = fopen(path, "w");
    CHECK(in && out);
    if (!in || !out) return;
    while (fgets(line, sizeof line, in))
        if (strncmp(line, "Pack", 4) != 0) fputs(line, out);
    fputs("Texture2D 4 32 32 float16\nRenderToTextureOnce 4\nClear\nWorld all\nRenderToTexture\nWorld all\n", out);
    fclose(in);
    fclose(out);
    render *on = render_create(NULL), *off = render_create(NULL);
    CHECK_MSG(render_load(on, path), "%s", render_messages(on));
    CHECK(render_load(off, path));
    render_set_world_cache(off, false);
    rig g = { .r = on }, h = { .r = off };
    CHECK(render_target_create(&g.tg, W, H, true) && render_target_create(&h.tg, W, H, true));
    float *a[3];
    for (int i = 0; i < 3; i++) a[i] = frame(&g, 1.0, NULL);
    float *b = frame(&h, 1.0, NULL);
    CHECK_MSG(render_world_cache_hits(on) >= 1, "the screen's World after a skipped pass was not copied");
    for (int i = 0; i < 3; i++) CHECK(same(a[i], b));
    for (int i = 0; i < 3; i++) free(a[i]);
    free(b);
    rig_close(&g);
    rig_close(&h);
    remove(path);
}
static void test_natural_float(void) { check_pack("natural", true); }

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    RUN(test_screen_after_a_once_pass);
    RUN(test_basic_rgba8);
    RUN(test_running_clock_layers);
    RUN(test_natural_float);
    gl_ctx_destroy(ctx);
    return check_summary();
}
