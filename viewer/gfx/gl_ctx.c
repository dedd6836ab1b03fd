#include "gl_ctx.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/glext.h>
#include <GLFW/glfw3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mem.h"

/* Under AddressSanitizer: the OpenGL driver (Mesa's swrast_dri.so and
 * libLLVM, loaded by EGL at run time) is unloaded again by eglTerminate, so
 * what the driver itself leaks is reported at exit with frames of no
 * module, and a suppression (tests/lsan.supp) cannot name it. Once the
 * context exists, every library loaded so far is marked RTLD_NODELETE, so
 * the driver stays mapped and its leaks are attributed to it. Sanitizer
 * builds only. */
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TARN_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define TARN_ASAN 1
#endif
#ifdef TARN_ASAN
#include <dlfcn.h>
static void keep_driver_loaded(void) {
    FILE *maps = fopen("/proc/self/maps", "r");
    if (!maps) return;
    char line[4352], last[4096] = "";
    while (fgets(line, sizeof line, maps)) {
        char *path = strchr(line, '/');
        if (!path) continue;
        path[strcspn(path, "\n")] = '\0';
        if (!strstr(path, ".so") || strcmp(path, last) == 0) continue;
        snprintf(last, sizeof last, "%s", path);
        void *h = dlopen(path, RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
        if (h) dlclose(h);   /* drops this reference; RTLD_NODELETE stays */
    }
    fclose(maps);
}
#else
static void keep_driver_loaded(void) {}
#endif

/* A CPU rasteriser (llvmpipe) allocates its per-draw vertex and bin
 * buffers anew for every draw and frees them after; glibc then trims the
 * freed top of the heap back to the kernel, and the next frame faults every
 * page in again. Measured on the lake at 120x68, animated (tarn render
 * --frames 12, 2 cores): basic 150 -> 32 ms a frame, caustic_tex 250 ->
 * 109, natural 288 -> 192, a third of the time spent in the kernel's page
 * faults before. Keeping up to 1 GiB of freed heap mapped costs nothing a
 * GPU driver would notice. glibc only; a sanitizer's allocator ignores it. */
#if defined(__GLIBC__)
#include <malloc.h>
static void keep_heap_mapped(void) {
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    mallopt(M_MMAP_THRESHOLD, 32 << 20);   /* glibc's dynamic threshold's ceiling: fixed, as the line above unfixes it */
}
#else
static void keep_heap_mapped(void) {}
#endif

struct gl_ctx {
    EGLDisplay display;
    EGLContext context;
    GLFWwindow *window;
    char description[256];
    bool robust;                /* made with reset notification: losses are reported */
    long checks, lose_after;    /* TARN_SIMULATE_CONTEXT_LOSS (tests): checks before a "loss" */
};

static const char *install_hint =
    "install Mesa's EGL and OpenGL drivers (Debian: apt-get install libegl1 libegl-mesa0 "
    "libgl1-mesa-dri libopengl0), or run scripts/deps.sh";

static void describe(gl_ctx *c) {
    const char *ver = (const char *)glGetString(GL_VERSION);
    const char *ren = (const char *)glGetString(GL_RENDERER);
    snprintf(c->description, sizeof c->description, "%s | %s",
             ver ? ver : "?", ren ? ren : "?");
}

static const char *egl_error_name(EGLint e) {
    switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return "an EGL error";
    }
}

/* How far the attempts got: the furthest stage reached says what is missing. */
typedef enum egl_stage {
    EGL_STAGE_NONE,             /* no attempt was possible: no platform entry point */
    EGL_STAGE_NO_DISPLAY,       /* no display for the platform */
    EGL_STAGE_INIT,             /* eglInitialize failed: the driver did not load */
    EGL_STAGE_API,              /* no desktop OpenGL in this EGL */
    EGL_STAGE_CONTEXT,          /* no OpenGL 4.5 compatibility context */
    EGL_STAGE_CURRENT           /* the context could not be made current */
} egl_stage;

typedef struct egl_diag {
    egl_stage stage;
    EGLint error;
    char vendor[128];
} egl_diag;

static void note(egl_diag *g, egl_stage st) {
    EGLint e = eglGetError();
    if (st >= g->stage) { g->stage = st; g->error = e; }
}

/* Tries one EGL platform; on success fills c and returns true. */
static bool try_egl_platform(gl_ctx *c, EGLenum platform, void *native, egl_diag *g) {
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (!get_display) return false;
    EGLDisplay d = get_display(platform, native, NULL);
    if (d == EGL_NO_DISPLAY) { note(g, EGL_STAGE_NO_DISPLAY); return false; }
    EGLint major, minor;
    if (!eglInitialize(d, &major, &minor)) { note(g, EGL_STAGE_INIT); return false; }
    /* the driver is loaded now: keep it mapped even when no context can be
     * made (a driver too old), so what it leaks is named (sanitizer builds) */
    keep_driver_loaded();
    const char *vendor = eglQueryString(d, EGL_VENDOR);
    if (vendor) snprintf(g->vendor, sizeof g->vendor, "%s", vendor);
    if (!eglBindAPI(EGL_OPENGL_API)) { note(g, EGL_STAGE_API); eglTerminate(d); return false; }
    /* Ask to be told about a GPU reset (EGL 1.5 / EGL_EXT_create_context_robustness),
     * so that a lost context ends tarn with a message instead of black frames;
     * a driver that cannot do that still gets a context without it. */
    const char *ext = eglQueryString(d, EGL_EXTENSIONS);
    bool can_robust = (major > 1 || (major == 1 && minor >= 5)) ||
                      (ext && strstr(ext, "EGL_EXT_create_context_robustness"));
    static const EGLint robust_attribs[] = {
        EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT,
        EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY, EGL_LOSE_CONTEXT_ON_RESET,
        EGL_NONE };
    static const EGLint attribs[] = {
        EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT,
        EGL_NONE };
    EGLContext ctx = can_robust ? eglCreateContext(d, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, robust_attribs)
                                : EGL_NO_CONTEXT;
    c->robust = ctx != EGL_NO_CONTEXT;
    if (ctx == EGL_NO_CONTEXT) ctx = eglCreateContext(d, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (ctx == EGL_NO_CONTEXT) { note(g, EGL_STAGE_CONTEXT); eglTerminate(d); return false; }
    if (!eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        note(g, EGL_STAGE_CURRENT);
        eglDestroyContext(d, ctx);
        eglTerminate(d);
        return false;
    }
    c->display = d;
    c->context = ctx;
    return true;
}

/* The device platform finds a GPU without a display server (NVIDIA's EGL). */
static bool try_egl_devices(gl_ctx *c, egl_diag *g) {
    PFNEGLQUERYDEVICESEXTPROC query_devices =
        (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
    if (!query_devices) return false;
    EGLDeviceEXT devices[16];
    EGLint n = 0;
    if (!query_devices(16, devices, &n)) return false;
    for (EGLint i = 0; i < n; i++)
        if (try_egl_platform(c, EGL_PLATFORM_DEVICE_EXT, devices[i], g)) return true;
    return false;
}

/* Names the environment variables that steer EGL and Mesa, when set. */
static void env_note(char *out, size_t len) {
    static const char *const vars[] = { "__EGL_VENDOR_LIBRARY_FILENAMES", "__EGL_VENDOR_LIBRARY_DIRS",
        "EGL_PLATFORM", "LIBGL_DRIVERS_PATH", "MESA_LOADER_DRIVER_OVERRIDE", "MESA_GL_VERSION_OVERRIDE",
        "LIBGL_ALWAYS_SOFTWARE", "GALLIUM_DRIVER", "TARN_EGL_PLATFORM" };
    size_t n = 0;
    out[0] = '\0';
    for (size_t i = 0; i < sizeof vars / sizeof vars[0] && n < len; i++) {
        const char *v = getenv(vars[i]);
        if (!v) continue;
        n += (size_t)snprintf(out + n, len - n, "%s%s=%s", n ? ", " : " (set in the environment: ",
                              vars[i], v);
    }
    if (n && n < len) snprintf(out + n, len - n, ")");
}

static void explain(const egl_diag *g, char *err, int errlen) {
    char env[512];
    env_note(env, sizeof env);
    const char *ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    bool no_vendor = !ext || !ext[0];
    if (no_vendor || g->stage <= EGL_STAGE_NO_DISPLAY) {
        snprintf(err, (size_t)errlen,
                 "cannot start OpenGL: no EGL driver was found (libglvnd's libEGL found no vendor "
                 "library, or none offers a display without a window system: Mesa's is libEGL_mesa.so.0, "
                 "listed in /usr/share/glvnd/egl_vendor.d/50_mesa.json)%s; %s", env, install_hint);
    } else if (g->stage == EGL_STAGE_INIT) {
        snprintf(err, (size_t)errlen,
                 "cannot start OpenGL: EGL (%s) could not load an OpenGL driver (%s; Mesa's software "
                 "renderer is swrast_dri.so, in libgl1-mesa-dri)%s; %s",
                 g->vendor[0] ? g->vendor : "the EGL vendor library", egl_error_name(g->error), env, install_hint);
    } else if (g->stage == EGL_STAGE_API) {
        snprintf(err, (size_t)errlen,
                 "cannot start OpenGL: the EGL driver (%s) offers OpenGL ES only, not desktop OpenGL%s; %s",
                 g->vendor[0] ? g->vendor : "?", env, install_hint);
    } else if (g->stage == EGL_STAGE_CONTEXT) {
        snprintf(err, (size_t)errlen,
                 "cannot start OpenGL: the driver (%s) gives no OpenGL 4.5 compatibility-profile context "
                 "(%s); tarn needs OpenGL 4.5 (Mesa 20 or later, whose llvmpipe runs on any CPU, or a GPU "
                 "driver)%s; %s", g->vendor[0] ? g->vendor : "?", egl_error_name(g->error), env, install_hint);
    } else {
        snprintf(err, (size_t)errlen, "cannot start OpenGL: the driver (%s) made a context but could not "
                 "make it current (%s)%s; %s", g->vendor[0] ? g->vendor : "?", egl_error_name(g->error), env,
                 install_hint);
    }
}

static void loss_setup(gl_ctx *c) {
    const char *sim = getenv("TARN_SIMULATE_CONTEXT_LOSS");
    c->lose_after = sim && sim[0] ? atol(sim) : -1;
}

gl_ctx *gl_ctx_create_headless(char *err, int errlen) {
    keep_heap_mapped();
    gl_ctx *c = mem_zalloc(sizeof *c);
    egl_diag g = { EGL_STAGE_NONE, EGL_SUCCESS, "" };
    /* TARN_EGL_PLATFORM=device forces the device platform (GPU machines). */
    const char *want = getenv("TARN_EGL_PLATFORM");
    bool device_first = want && strcmp(want, "device") == 0;
    bool ok = device_first ? try_egl_devices(c, &g) : false;
    if (!ok) ok = try_egl_platform(c, EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, &g);
    if (!ok && !device_first) ok = try_egl_devices(c, &g);
    if (!ok) {
        explain(&g, err, errlen);
        free(c);
        return NULL;
    }
    describe(c);
    loss_setup(c);
    keep_driver_loaded();
    return c;
}

bool gl_ctx_lost(gl_ctx *c, char *err, int errlen) {
    if (!c) return false;
    c->checks++;
    GLenum st = GL_NO_ERROR;
    if (c->lose_after >= 0 && c->checks > c->lose_after) st = GL_UNKNOWN_CONTEXT_RESET;
    else if (c->robust) st = glGetGraphicsResetStatus();
    if (st == GL_NO_ERROR) return false;
    const char *why = st == GL_GUILTY_CONTEXT_RESET ? "a GPU reset that tarn's own drawing caused (a shader "
                                                      "that runs too long, or reads out of bounds)"
                    : st == GL_INNOCENT_CONTEXT_RESET ? "a GPU reset caused by another program"
                    : "a GPU reset or a driver restart of unknown cause";
    snprintf(err, (size_t)errlen,
             "the OpenGL context was lost: %s. Nothing more can be drawn in it; your files are unchanged, "
             "start tarn again. If it happens again, update or reinstall the GPU driver (Debian: apt-get "
             "install --reinstall libgl1-mesa-dri libegl-mesa0, or your GPU vendor's driver)%s",
             why, st == GL_GUILTY_CONTEXT_RESET ? ", or make the scene lighter (a smaller --size, fewer steps)" : "");
    return true;
}

static void glfw_error(int code, const char *msg) {
    fprintf(stderr, "tarn: GLFW error 0x%x: %s\n", code, msg);
}

gl_ctx *gl_ctx_create_window(int w, int h, const char *title, char *err, int errlen) {
    keep_heap_mapped();
    glfwSetErrorCallback(glfw_error);
    if (!glfwInit()) {
        snprintf(err, errlen, "cannot open a window: GLFW failed to initialise "
                 "(no display? set DISPLAY, or use `tarn render` for headless)");
        return NULL;
    }
    gl_ctx *c = mem_zalloc(sizeof *c);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_COMPAT_PROFILE);
    glfwWindowHint(GLFW_SRGB_CAPABLE, GLFW_TRUE);   /* scenes with a world are lit in linear radiance */
    glfwWindowHint(GLFW_CONTEXT_ROBUSTNESS, GLFW_LOSE_CONTEXT_ON_RESET);   /* report a GPU reset */
    c->window = glfwCreateWindow(w, h, title, NULL, NULL);
    c->robust = c->window != NULL;
    if (!c->window) {   /* a driver without robustness: a context without it */
        glfwWindowHint(GLFW_CONTEXT_ROBUSTNESS, GLFW_NO_ROBUSTNESS);
        c->window = glfwCreateWindow(w, h, title, NULL, NULL);
    }
    if (!c->window) {
        snprintf(err, errlen, "cannot create an OpenGL 4.5 compatibility window: %s",
                 install_hint);
        free(c);
        glfwTerminate();
        return NULL;
    }
    glfwMakeContextCurrent(c->window);
    glfwSwapInterval(1);
    describe(c);
    loss_setup(c);
    keep_driver_loaded();
    return c;
}

void gl_ctx_destroy(gl_ctx *c) {
    if (!c) return;
    if (c->window) {
        glfwDestroyWindow(c->window);
        glfwTerminate();
    } else if (c->display != EGL_NO_DISPLAY) {
        eglMakeCurrent(c->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(c->display, c->context);
        eglTerminate(c->display);
    }
    free(c);
}

void *gl_ctx_window(gl_ctx *c) { return c ? c->window : NULL; }
const char *gl_ctx_describe(gl_ctx *c) { return c->description; }

bool gl_ctx_cpu_rasteriser(void) {
    const char *r = (const char *)glGetString(GL_RENDERER);
    return r && (strstr(r, "llvmpipe") || strstr(r, "softpipe") || strstr(r, "SwiftShader") || strstr(r, "lavapipe"));
}

bool gl_ctx_have_display(void) {
    const char *x = getenv("DISPLAY"), *wl = getenv("WAYLAND_DISPLAY");
    return (x && *x) || (wl && *wl);
}

bool gl_ctx_frame_fits(int w, int h, double bytes_per_pixel, char *why, int whylen) {
    GLint vp[2] = { 0, 0 }, rb = 0, tex = 0;
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, vp);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &rb);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &tex);
    int max = vp[0];
    if (vp[1] > 0 && vp[1] < max) max = vp[1];
    if (rb > 0 && rb < max) max = rb;
    if (tex > 0 && tex < max) max = tex;
    if (max > 0 && (w > max || h > max)) {
        snprintf(why, (size_t)whylen, "%dx%d is beyond this OpenGL's largest frame, %d a side; ask for less",
                 w, h, max);
        return false;
    }
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    double have = pages > 0 && page > 0 ? (double)pages * (double)page : 0;
    double need = (double)w * (double)h * bytes_per_pixel;
    if (have > 0 && need > have / 4) {
        snprintf(why, (size_t)whylen, "%dx%d needs about %.1f GB for its targets, more than a quarter of this "
                 "machine's %.1f GB; ask for less", w, h, need / 1e9, have / 1e9);
        return false;
    }
    return true;
}
