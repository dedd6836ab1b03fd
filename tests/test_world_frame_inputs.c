/* render_world_frame_inputs (viewer/gfx/render.h): what the world-only
 * frame (render_frame_world_at, the window's full-resolution world) is
 * drawn from. In a scratch copy of packs/ and scenes/, each pack on the
 * lake: a save of the water's own shader leaves the hash as it was, and
 * the world-only frame drawn after it equals, pixel for pixel, the one
 * drawn before (so the window may keep its copy); a save of a program
 * that frame draws with (caustic_tex's screen copy, the world's own
 * shading) changes the hash (and the picture, where the save does). */
#include <GL/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "file.h"
#include "gl_ctx.h"
#include "gl_support.h"
#include "render.h"
#include "support.h"

#define W 96
#define H 54

static bool copy_tree(void) {
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "cp -r '%s/packs' '%s/scenes' '%s/data' '%s/'", TARN_SOURCE_DIR, TARN_SOURCE_DIR,
             TARN_SOURCE_DIR, scratch_path(""));
    return system(cmd) == 0;
}

/* A save of a file of the scratch tree: text appended (from NULL), or its
 * first `from` replaced by text. */
static void save(const char *rel, const char *from, const char *text) {
    char *old = NULL;
    if (from) {
        size_t n;
        char why[256];
        old = file_read(scratch_path(rel), 1 << 20, &n, why, sizeof why);
        CHECK_MSG(old && strstr(old, from), "%s has no '%s'", rel, from);
        if (!old || !strstr(old, from)) return;
    }
    FILE *f = fopen(scratch_path(rel), from ? "w" : "a");
    CHECK_MSG(f != NULL, "cannot open %s", scratch_path(rel));
    if (f && from) {
        char *at = strstr(old, from);
        fwrite(old, 1, (size_t)(at - old), f);
        fputs(text, f);
        fputs(at + strlen(from), f);
    } else if (f) fputs(text, f);
    if (f) fclose(f);
    free(old);
}

/* The world-only frame at the scene's view, read back. */
static float *world_frame(render *r, render_target *tg) {
    float *px = malloc((size_t)W * H * 4 * sizeof(float));
    render_view v = render_default_view(r);
    render_frame_world_at(r, 2.0, tg->fbo, 0, 0, W, H, &v);
    render_target_read(tg, px);
    return px;
}

static bool same(const float *a, const float *b) { return memcmp(a, b, (size_t)W * H * 4 * sizeof(float)) == 0; }

/* Loads the lake with pack; saves edit_path with edit; says whether the
 * hash and the world-only frame stayed. */
static void check_save(const char *pack, const char *edit_path, const char *from, const char *edit,
                       bool hash_same, bool pixels_same) {
    render *r = render_create(&(render_desc){ .pack = pack, .repo_root = scratch_path("") });
    CHECK_MSG(render_load(r, scratch_path("scenes/lake.glib")), "%s", render_messages(r));
    render_target tg;
    CHECK(render_target_create(&tg, W, H, true));
    render_frame(r, 2.0, tg.fbo, W, H, NULL);   /* the targets and passes a window's frame leaves */
    unsigned long long before = render_world_frame_inputs(r);
    CHECK(before != 0);
    float *a = world_frame(r, &tg);
    CHECK(render_load(r, NULL));
    CHECK_MSG(render_world_frame_inputs(r) == before, "%s: a reload of unchanged files changed the hash", pack);
    save(edit_path, from, edit);
    CHECK_MSG(render_load(r, NULL), "%s", render_messages(r));
    render_frame(r, 2.0, tg.fbo, W, H, NULL);
    unsigned long long after = render_world_frame_inputs(r);
    float *b = world_frame(r, &tg);
    CHECK_MSG((after == before) == hash_same, "%s: a save of %s %s the world frame's inputs", pack, edit_path,
              hash_same ? "changed" : "left as they were");
    CHECK_MSG(same(a, b) == pixels_same, "%s: the world-only frame %s after a save of %s", pack,
              pixels_same ? "changed" : "stayed", edit_path);
    free(a);
    free(b);
    render_target_destroy(&tg);
    render_destroy(r);
}

static void test_water_saves_keep_it(void) {
    const char *packs[] = { "natural", "raymarch", "caustic_tex", "basic" };
    for (int i = 0; i < 4; i++) {
        char path[128];
        snprintf(path, sizeof path, "packs/%s/water.frag", packs[i]);
        check_save(packs[i], path, NULL, "\n// saved: the water's own shader\n", true, true);
    }
}

/* A program drawn before the water: caustic_tex copies its world pass to
 * the screen (Program ScreenCopy); the world's own shading (every pack). */
static void test_world_saves_change_it(void) {
    check_save("caustic_tex", "packs/caustic_tex/screen_copy.frag", ".rgb, 1.0)", ".rgb * vec3(1.0, 0.5, 0.5), 1.0)",
               false, false);
    /* a comment: the same pixels, but a new text (the hash cannot tell) */
    check_save("natural", "packs/common/world.frag", "void main", "// saved: the world's shading\nvoid main", false,
               true);
}

int main(void) {
    gl_ctx *ctx = gl_test_context();
    if (!ctx) return GL_TEST_SKIP;
    if (!scratch_create("world-frame") || !copy_tree()) return 1;
    RUN(test_water_saves_keep_it);
    RUN(test_world_saves_change_it);
    scratch_remove();
    gl_ctx_destroy(ctx);
    return check_summary();
}
