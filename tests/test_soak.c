/* Reload soak: 1000 reloads of one scene in the headless renderer, the way
 * a person live-editing it saves files: good and broken fragment shaders,
 * good and broken #include files, good and broken glib edits (a uniform's
 * value, the mesh's subdivision), good and broken texture swaps.
 *
 * Every reload is checked on pixels: the scene's left half shows the
 * shader's colour (its literals, a value from the #include, the glib's
 * tint), its right half the texture's only texel. A good reload must show
 * its change; a broken one must report `file:line` and leave the image as
 * it was (the last good program, scene and texture stay).
 *
 * Every cycle of 8 reloads ends in the same structure (one program, one
 * texture, one mesh), so the count of live GL objects of every kind must be
 * the same at every cycle's end, exactly: names are counted with glIs*()
 * over every name GL may have handed out (see count_objects). The process's
 * resident memory must be flat too, within RSS_TOLERANCE_MB from reload 200
 * to reload 1000 (see check_rss for why that bound).
 */
#include <GL/gl.h>
#include <GL/glext.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "check.h"
#include "support.h"
#include "gl_ctx.h"
#include "gl_support.h"
#include "render.h"

#define RELOADS 1000
#define W 32
#define H 32
#define TOL (1.5 / 255.0)
#define RSS_WARMUP 200         /* reloads before the RSS baseline */
#define RSS_TOLERANCE_MB 8.0

#if defined(__SANITIZE_ADDRESS__)
#define UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define UNDER_ASAN 1
#endif
#endif

static float px[W * H * 4];

/* The renderer reuses a texture whose (path, mtime, size) is unchanged; two
 * saves of equal size inside one kernel clock tick (~4 ms) look the same.
 * No editor saves that fast, this test does: every texture write gets its
 * own modification time. */
static void stamp(const char *name, long serial) {
    struct timespec ts[2];
    ts[0].tv_sec = ts[1].tv_sec = 1000000000L + serial;
    ts[0].tv_nsec = ts[1].tv_nsec = 0;
    if (utimensat(AT_FDCWD, scratch_path(name), ts, 0) != 0) { perror(name); exit(1); }
}

/* The viewer reloads a save once the watcher has seen WATCH_QUIET_MS of
 * quiet, so the files a reload reads are older than that; this test
 * reloads at once. Its text files get a modification time a second back,
 * as a save the viewer reloads has: a file modified under FILE_SETTLE_MS
 * ago may still be being written, and each read would wait that out. */
static void soak_write(const char *name, const char *text) {
    scratch_write(name, text);
    struct timespec now, ts[2];
    clock_gettime(CLOCK_REALTIME, &now);
    ts[0] = ts[1] = (struct timespec){ now.tv_sec - 1, now.tv_nsec };
    if (utimensat(AT_FDCWD, scratch_path(name), ts, 0) != 0) { perror(name); exit(1); }
}

/* A 1x1 24-bit BMP of one colour. */
static void write_bmp(const char *name, int r, int g, int b, long serial) {
    unsigned char file[58] = { 'B', 'M', 58, 0, 0, 0, 0, 0, 0, 0, 54, 0, 0, 0,
        40, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 24, 0, 0, 0, 0, 0, 4, 0, 0, 0,
        0x13, 0x0b, 0, 0, 0x13, 0x0b, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
    file[54] = (unsigned char)b; file[55] = (unsigned char)g; file[56] = (unsigned char)r;
    FILE *f = fopen(scratch_path(name), "wb");
    if (!f) exit(1);
    fwrite(file, 1, sizeof file, f);
    fclose(f);
    stamp(name, serial);
}

/* ---- the scene's generations ---- */

typedef struct gen {
    int shader, inc, glib, tex;
} gen;

/* channel values on a 1/8 grid: exact after the 8-bit target's rounding */
static double shader_r(int g) { return (g % 8) / 8.0; }
static double shader_g(int g) { return ((g / 8) % 8 + 1) / 8.0; }
static double inc_b(int g) { return (g % 7 + 1) / 8.0; }
static double tint_g(int g) { return g % 2 ? 0.5 : 1.0; }
static int tex_r(int g) { return (g * 37) % 256; }
static int tex_g(int g) { return (g * 91 + 50) % 256; }
static int tex_b(int g) { return (g * 13 + 200) % 256; }

static void write_shader(int g) {
    char text[1024];
    snprintf(text, sizeof text,
             "#version 330 compatibility\n"
             "#include \"soak_inc.glsl\"\n"
             "uniform sampler2D uTex;\n"
             "uniform vec4 uTint;\n"
             "in vec2 st;\n"
             "out vec4 c;\n"
             "void main() {\n"
             "    if (st.x < 0.5) c = vec4(%.6f, %.6f, inc_blue(), 1.) * uTint;\n"
             "    else c = texture(uTex, vec2(0.5));\n"
             "}\n", shader_r(g), shader_g(g));
    soak_write("soak.frag", text);
}

#define BROKEN_SHADER_LINE 8
static void write_broken_shader(int g) {
    char text[1024];
    snprintf(text, sizeof text,
             "#version 330 compatibility\n"
             "#include \"soak_inc.glsl\"\n"
             "uniform sampler2D uTex;\n"
             "uniform vec4 uTint;\n"
             "in vec2 st;\n"
             "out vec4 c;\n"
             "void main() {\n"
             "    c = vec4(%.6f, half_typed_name_%d, 0., 1.);\n"
             "}\n", shader_r(g), g);
    soak_write("soak.frag", text);
}

static void write_inc(int g) {
    char text[256];
    snprintf(text, sizeof text, "// the include\nfloat inc_blue() { return %.6f; }\n", inc_b(g));
    soak_write("soak_inc.glsl", text);
}

#define GLIB_PROGRAM_LINE 6
static void write_glib(int g, bool broken) {
    char text[1024];
    snprintf(text, sizeof text,
             "##OpenGL GLIB\n"
             "Ortho -1 1 -1 1\n"
             "Texture2D 5 soak.bmp\n"
             "Vertex soak.vert\n"
             "Fragment soak.frag\n"
             "Program Soak uTex 5 uTint {1. %.2f 1. 1.%s\n"
             "QuadXY 0 1 %d %d\n", tint_g(g), broken ? "" : "}", 1 + g % 2, 1 + g % 2);
    soak_write("soak.glib", text);
}

static void write_tex(int g, long serial) { write_bmp("soak.bmp", tex_r(g), tex_g(g), tex_b(g), serial); }

/* ---- checks ---- */

static render_target target;

static void draw(render *r) {
    render_frame(r, 0, target.fbo, W, H, NULL);
    render_target_read(&target, px);
}

static const float *at(int x, int y) { return px + ((size_t)y * W + x) * 4; }

static bool near(const float *p, double r, double g, double b) {
    return fabs(p[0] - r) <= TOL && fabs(p[1] - g) <= TOL && fabs(p[2] - b) <= TOL;
}

/* What gen should look like, left half and right half. */
static bool shows(const gen *G) {
    const float *l = at(W / 4, H / 2), *rt = at(3 * W / 4, H / 2);
    return near(l, shader_r(G->shader), shader_g(G->shader) * tint_g(G->glib), inc_b(G->inc)) &&
           near(rt, tex_r(G->tex) / 255.0, tex_g(G->tex) / 255.0, tex_b(G->tex) / 255.0);
}

/* ---- GL object counts ---- */

enum { K_PROGRAM, K_SHADER, K_TEXTURE, K_FRAMEBUFFER, K_RENDERBUFFER, K_BUFFER, K_QUERY, K_VERTEX_ARRAY, K_COUNT };
static const char *const kind_name[K_COUNT] = {
    "programs", "shaders", "textures", "framebuffers", "renderbuffers", "buffers", "queries", "vertex arrays" };

/* The highest name GL has handed out so far, per kind, found by asking for
 * a fresh one. Mesa hands out names in increasing order (and even where a
 * driver reuses freed names, a fresh name is at most one past the highest
 * in use), so every live object's name is below the highest fresh name
 * seen plus the objects made since; the scan goes a margin beyond that. */
static GLuint fresh_name(int k) {
    GLuint n = 0;
    switch (k) {
    case K_PROGRAM: n = glCreateProgram(); glDeleteProgram(n); break;
    case K_SHADER: n = glCreateShader(GL_FRAGMENT_SHADER); glDeleteShader(n); break;
    case K_TEXTURE: glGenTextures(1, &n); glDeleteTextures(1, &n); break;
    case K_FRAMEBUFFER: glGenFramebuffers(1, &n); glDeleteFramebuffers(1, &n); break;
    case K_RENDERBUFFER: glGenRenderbuffers(1, &n); glDeleteRenderbuffers(1, &n); break;
    case K_BUFFER: glGenBuffers(1, &n); glDeleteBuffers(1, &n); break;
    case K_QUERY: glGenQueries(1, &n); glDeleteQueries(1, &n); break;
    case K_VERTEX_ARRAY: glGenVertexArrays(1, &n); glDeleteVertexArrays(1, &n); break;
    }
    return n;
}

static bool is_live(int k, GLuint n) {
    switch (k) {
    case K_PROGRAM: return glIsProgram(n);
    case K_SHADER: return glIsShader(n);
    case K_TEXTURE: return glIsTexture(n);
    case K_FRAMEBUFFER: return glIsFramebuffer(n);
    case K_RENDERBUFFER: return glIsRenderbuffer(n);
    case K_BUFFER: return glIsBuffer(n);
    case K_QUERY: return glIsQuery(n);
    case K_VERTEX_ARRAY: return glIsVertexArray(n);
    }
    return false;
}

#define NAME_SCAN_MARGIN 4096
static GLuint highest[K_COUNT];

static void count_objects(int out[K_COUNT]) {
    for (int k = 0; k < K_COUNT; k++) {
        GLuint f = fresh_name(k);
        if (f > highest[k]) highest[k] = f;
        out[k] = 0;
        for (GLuint n = 1; n <= highest[k] + NAME_SCAN_MARGIN; n++)
            if (is_live(k, n)) out[k]++;
    }
    while (glGetError() != GL_NO_ERROR) {}
}

/* ---- resident memory ---- */

static double rss_mb(void) {
    FILE *f = fopen("/proc/self/statm", "r");
    long size = 0, resident = 0;
    if (!f) return -1;
    if (fscanf(f, "%ld %ld", &size, &resident) != 2) resident = -1;
    fclose(f);
    return resident < 0 ? -1 : resident * (double)sysconf(_SC_PAGESIZE) / (1024.0 * 1024.0);
}

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec / 1e9;
}

/* ---- the soak ---- */

static int bad_good, bad_broken, bad_message;

static void expect_good(render *r, const gen *G, int i, const char *what) {
    bool ok = render_load(r, NULL);
    draw(r);
    if (!ok || !shows(G)) {
        if (bad_good++ < 5)
            fprintf(stderr, "reload %d (%s): good reload %s; left %.3f %.3f %.3f right %.3f %.3f %.3f\n%s", i, what,
                    ok ? "not applied" : "failed", at(W / 4, H / 2)[0], at(W / 4, H / 2)[1], at(W / 4, H / 2)[2],
                    at(3 * W / 4, H / 2)[0], at(3 * W / 4, H / 2)[1], at(3 * W / 4, H / 2)[2], render_messages(r));
    }
}

static void expect_broken(render *r, const gen *G, int i, const char *what, const char *file, int line) {
    bool ok = render_load(r, NULL);
    draw(r);
    if (ok || !render_has_errors(r) || !shows(G)) {
        if (bad_broken++ < 5)
            fprintf(stderr, "reload %d (%s): broken reload %s\n%s", i, what,
                    ok ? "reported no error" : "did not keep the last good image", render_messages(r));
    }
    char want[600];
    if (line > 0) snprintf(want, sizeof want, "%s:%d:", scratch_path(file), line);
    else snprintf(want, sizeof want, "%s", scratch_path(file));
    if (!strstr(render_messages(r), want) && bad_message++ < 5)
        fprintf(stderr, "reload %d (%s): expected \"%s\" in:\n%s", i, what, want, render_messages(r));
}

static void test_soak(void) {
    soak_write("soak.vert", "#version 330 compatibility\nout vec2 st;\n"
                            "void main() { st = gl_MultiTexCoord0.st; gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; }\n");
    gen G = { 1, 1, 1, 1 };
    long serial = 0;
    write_shader(G.shader);
    write_inc(G.inc);
    write_glib(G.glib, false);
    write_tex(G.tex, ++serial);
    CHECK(render_target_create(&target, W, H, false));
    render *r = gl_test_load_scratch("soak.glib");
    draw(r);
    CHECK_MSG(shows(&G), "the first load is not on screen");

    int base[K_COUNT] = {0}, cur[K_COUNT];
    bool have_base = false;
    int count_mismatch = 0, checkpoints = 0;
    double rss_base = -1, rss_max = 0, rss_end = 0;
    double t0 = now_s();
    for (int i = 1; i <= RELOADS; i++) {
        switch (i % 8) {
        case 1:   /* a new fragment shader */
            write_inc(G.inc);                         /* (undoes the broken include) */
            write_shader(++G.shader);
            expect_good(r, &G, i, "shader edit");
            break;
        case 2:   /* a typo in it */
            write_broken_shader(G.shader);
            expect_broken(r, &G, i, "broken shader", "soak.frag", BROKEN_SHADER_LINE);
            break;
        case 3:   /* the shader fixed, and the glib edited (tint, mesh) */
            write_shader(G.shader);
            write_glib(++G.glib, false);
            expect_good(r, &G, i, "glib edit");
            break;
        case 4:   /* a half-written glib */
            write_glib(G.glib + 1, true);
            expect_broken(r, &G, i, "broken glib", "soak.glib", GLIB_PROGRAM_LINE);
            break;
        case 5:   /* the glib fixed, the texture swapped */
            write_glib(G.glib, false);
            write_tex(++G.tex, ++serial);
            expect_good(r, &G, i, "texture swap");
            break;
        case 6:   /* a texture that is not an image */
            scratch_write("soak.bmp", "BM this is not a bitmap any more");
            stamp("soak.bmp", ++serial);
            expect_broken(r, &G, i, "broken texture", "soak.glib", 3);
            break;
        case 7:   /* the texture back, the #include edited */
            write_tex(G.tex, ++serial);
            write_inc(++G.inc);
            expect_good(r, &G, i, "include edit");
            break;
        case 0:   /* an #include that loops, or one that is missing */
            if ((i / 8) % 2) {
                soak_write("soak_inc.glsl", "// the include\n#include \"soak_inc.glsl\"\n");
                expect_broken(r, &G, i, "include cycle", "soak_inc.glsl", 2);
            } else {
                soak_write("soak_inc.glsl", "// the include\n#include \"soak_missing.glsl\"\n");
                expect_broken(r, &G, i, "missing include", "soak_inc.glsl", 2);
            }
            /* the end of a cycle: the same structure every time */
            count_objects(cur);
            checkpoints++;
            if (!have_base && i >= 16) {
                memcpy(base, cur, sizeof base);
                have_base = true;
                fprintf(stderr, "  live GL objects at reload %d:", i);
                for (int k = 0; k < K_COUNT; k++) fprintf(stderr, " %s %d", kind_name[k], cur[k]);
                fputc('\n', stderr);
            } else if (have_base && memcmp(base, cur, sizeof base) != 0) {
                if (count_mismatch++ < 3) {
                    fprintf(stderr, "reload %d: live GL objects changed:", i);
                    for (int k = 0; k < K_COUNT; k++)
                        if (cur[k] != base[k]) fprintf(stderr, " %s %d -> %d", kind_name[k], base[k], cur[k]);
                    fputc('\n', stderr);
                }
            }
            if (i >= RSS_WARMUP && rss_base < 0) rss_base = rss_mb();
            if (rss_base >= 0) {
                double m = rss_mb();
                if (m > rss_max) rss_max = m;
                rss_end = m;
            }
            if (i % 200 == 0)
                fprintf(stderr, "  reload %4d: %.1f s, RSS %.1f MiB\n", i, now_s() - t0, rss_mb());
            break;
        }
    }
    double secs = now_s() - t0;
    fprintf(stderr, "  %d reloads in %.1f s (%.1f ms each); %d checkpoints; RSS %.1f MiB at reload %d, "
            "%.1f at the end, %.1f at most\n", RELOADS, secs, secs * 1e3 / RELOADS, checkpoints, rss_base,
            RSS_WARMUP, rss_end, rss_max);
    fprintf(stderr, "  highest names seen:");
    for (int k = 0; k < K_COUNT; k++) fprintf(stderr, " %s %u", kind_name[k], highest[k]);
    fputc('\n', stderr);
    CHECK_MSG(bad_good == 0, "%d good reloads were not applied", bad_good);
    CHECK_MSG(bad_broken == 0, "%d broken reloads lost the last good state", bad_broken);
    CHECK_MSG(bad_message == 0, "%d broken reloads did not name the file and line", bad_message);
    CHECK(have_base);
    CHECK_MSG(count_mismatch == 0, "the count of live GL objects changed at %d of %d checkpoints",
              count_mismatch, checkpoints);
    /* Why RSS_TOLERANCE_MB: after the warm-up (the driver's shader caches,
     * malloc's arenas and LLVM's pools reach their working size) the RSS
     * still moves by a few MiB as malloc trims and regrows arenas. A real
     * leak of what a reload makes is far beyond 8 MiB over 800 reloads: a
     * program on llvmpipe is ~100 KiB of JIT code and IR (80 MiB), a
     * texture, mesh or assembled shader text 1-10 KiB (1-8 MiB: at the
     * edge, which is why the GL object counts above are exact and the
     * AddressSanitizer build runs LeakSanitizer over this test). */
#ifdef UNDER_ASAN
    fprintf(stderr, "  RSS not asserted under AddressSanitizer (its quarantine holds freed memory "
                    "by design); LeakSanitizer checks for leaks instead\n");
#else
    CHECK_MSG(rss_base > 0 && rss_max - rss_base <= RSS_TOLERANCE_MB,
              "RSS grew from %.1f MiB (reload %d) to %.1f MiB, more than %.0f MiB", rss_base, RSS_WARMUP,
              rss_max, RSS_TOLERANCE_MB);
#endif
    render_destroy(r);
    render_target_destroy(&target);
}

int main(void) {
    char err[512];
    /* every shader really compiled, as when a person edits one: no hits in
     * Mesa's on-disk cache of earlier runs (the texts repeat run to run) */
    setenv("MESA_SHADER_CACHE_DISABLE", "true", 1);
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    if (!ctx) {
        fprintf(stderr, "skip: %s\n", err);
        return 77;
    }
    fprintf(stderr, "context: %s\n", gl_ctx_describe(ctx));
    if (!scratch_create("soak")) return 1;
    RUN(test_soak);
    gl_ctx_destroy(ctx);
    scratch_remove();
    return check_summary();
}
