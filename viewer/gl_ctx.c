#include "gl_ctx.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GLFW/glfw3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Under AddressSanitizer, LeakSanitizer's check at exit runs after Mesa's
 * own exit handler has unloaded the driver (swrast_dri.so, libLLVM), so
 * whatever the driver leaks shows as frames of no module, and a
 * suppression cannot name it. An exit handler registered after the context
 * exists runs before Mesa's: it does the leak check while the driver is
 * still mapped (tests/lsan.supp then names the driver's libraries). */
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TARN_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define TARN_ASAN 1
#endif
#ifdef TARN_ASAN
#include <sanitizer/lsan_interface.h>
static void leak_check_now(void) { __lsan_do_leak_check(); }
static void leak_check_before_driver_unloads(void) {
    static bool registered;
    if (!registered) registered = atexit(leak_check_now) == 0;
}
#else
static void leak_check_before_driver_unloads(void) {}
#endif

struct gl_ctx {
    EGLDisplay display;
    EGLContext context;
    GLFWwindow *window;
    char description[256];
};

static const char *install_hint =
    "install Mesa's EGL and OpenGL drivers (Debian: apt-get install libegl-mesa0 "
    "libgl1-mesa-dri libopengl0), or run scripts/deps.sh";

static void describe(gl_ctx *c) {
    const char *ver = (const char *)glGetString(GL_VERSION);
    const char *ren = (const char *)glGetString(GL_RENDERER);
    snprintf(c->description, sizeof c->description, "%s | %s",
             ver ? ver : "?", ren ? ren : "?");
}

/* Tries one EGL platform; on success fills c and returns true. */
static bool try_egl_platform(gl_ctx *c, EGLenum platform, void *native) {
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (!get_display) return false;
    EGLDisplay d = get_display(platform, native, NULL);
    if (d == EGL_NO_DISPLAY) return false;
    EGLint major, minor;
    if (!eglInitialize(d, &major, &minor)) return false;
    if (!eglBindAPI(EGL_OPENGL_API)) { eglTerminate(d); return false; }
    static const EGLint attribs[] = {
        EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT,
        EGL_NONE };
    EGLContext ctx = eglCreateContext(d, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (ctx == EGL_NO_CONTEXT) { eglTerminate(d); return false; }
    if (!eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        eglDestroyContext(d, ctx);
        eglTerminate(d);
        return false;
    }
    c->display = d;
    c->context = ctx;
    return true;
}

/* The device platform finds a GPU without a display server (NVIDIA's EGL). */
static bool try_egl_devices(gl_ctx *c) {
    PFNEGLQUERYDEVICESEXTPROC query_devices =
        (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
    if (!query_devices) return false;
    EGLDeviceEXT devices[16];
    EGLint n = 0;
    if (!query_devices(16, devices, &n)) return false;
    for (EGLint i = 0; i < n; i++)
        if (try_egl_platform(c, EGL_PLATFORM_DEVICE_EXT, devices[i])) return true;
    return false;
}

gl_ctx *gl_ctx_create_headless(char *err, int errlen) {
    gl_ctx *c = calloc(1, sizeof *c);
    if (!c) { snprintf(err, errlen, "out of memory"); return NULL; }
    /* TARN_EGL_PLATFORM=device forces the device platform (GPU machines). */
    const char *want = getenv("TARN_EGL_PLATFORM");
    bool device_first = want && strcmp(want, "device") == 0;
    bool ok = device_first ? try_egl_devices(c) : false;
    if (!ok) ok = try_egl_platform(c, EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY);
    if (!ok && !device_first) ok = try_egl_devices(c);
    if (!ok) {
        snprintf(err, errlen, "cannot create a headless OpenGL 4.5 compatibility context "
                 "through EGL (EGL error 0x%x): %s", (unsigned)eglGetError(), install_hint);
        free(c);
        return NULL;
    }
    describe(c);
    leak_check_before_driver_unloads();
    return c;
}

static void glfw_error(int code, const char *msg) {
    fprintf(stderr, "tarn: GLFW error 0x%x: %s\n", code, msg);
}

gl_ctx *gl_ctx_create_window(int w, int h, const char *title, char *err, int errlen) {
    glfwSetErrorCallback(glfw_error);
    if (!glfwInit()) {
        snprintf(err, errlen, "cannot open a window: GLFW failed to initialise "
                 "(no display? set DISPLAY, or use `tarn render` for headless)");
        return NULL;
    }
    gl_ctx *c = calloc(1, sizeof *c);
    if (!c) { glfwTerminate(); snprintf(err, errlen, "out of memory"); return NULL; }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_COMPAT_PROFILE);
    glfwWindowHint(GLFW_SRGB_CAPABLE, GLFW_TRUE);   /* scenes with a world are lit in linear radiance */
    c->window = glfwCreateWindow(w, h, title, NULL, NULL);
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
    leak_check_before_driver_unloads();
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

bool gl_ctx_have_display(void) {
    const char *x = getenv("DISPLAY"), *wl = getenv("WAYLAND_DISPLAY");
    return (x && *x) || (wl && *wl);
}
