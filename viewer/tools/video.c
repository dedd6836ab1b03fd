/* video: frames to ffmpeg through a pipe, or to PNGs (video.h). */
#include "video.h"
#include "strbuf.h"

#include <errno.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "file.h"
#include "image_io.h"
#include "mem.h"

extern char **environ;

struct video {
    video_desc d;
    char where[4096];            /* the file, or the folder with a '/' at its end */
    bool png;
    int frames;
    pid_t pid;                   /* ffmpeg, or 0 */
    int fd;                      /* the pipe to its stdin */
    struct sigaction old_pipe;   /* restored at close */
    bool failed;                 /* a frame was not written: ffmpeg's message explains */
};

void video_png_path(const char *dir, int i, char *out, int outlen) {
    snprintf(out, (size_t)outlen, "%sframe-%05d.png", dir, i);
}

const char *video_where(const video *v) { return v->where; }
bool video_is_png(const video *v) { return v->png; }

static bool ends_with(const char *s, const char *tail) {
    size_t n = strlen(s), k = strlen(tail);
    return n >= k && strcmp(s + n - k, tail) == 0;
}

/* A codec whose usual pixel format is 4:2:0 (x264 for .mp4 & co): it
 * wants even sides and players want yuv420p rather than ffmpeg's default
 * for RGB input (yuv444p, which many cannot play). */
static bool wants_yuv420(const char *out) {
    const char *dot = strrchr(out, '.');
    return dot && (strcmp(dot, ".mp4") == 0 || strcmp(dot, ".m4v") == 0 || strcmp(dot, ".mov") == 0 ||
                   strcmp(dot, ".mkv") == 0);
}

/* ffmpeg reading raw frames from stdin; 0 with errno ENOENT when there is
 * no such program. */
static pid_t spawn_ffmpeg(video *v, int *fd) {
    char size[32], rate[16];
    snprintf(size, sizeof size, "%dx%d", v->d.width, v->d.height);
    snprintf(rate, sizeof rate, "%d", v->d.fps);
    const char *prog = v->d.ffmpeg ? v->d.ffmpeg : "ffmpeg";
    const char *args[24] = { prog, "-hide_banner", "-loglevel", "error", "-y",
                             "-f", "rawvideo", "-pix_fmt", "rgb24", "-s", size, "-framerate", rate, "-i", "-" };
    int n = 0;
    while (args[n]) n++;
    if (wants_yuv420(v->d.out)) {
        args[n++] = "-vf";
        args[n++] = "pad=ceil(iw/2)*2:ceil(ih/2)*2";
        args[n++] = "-pix_fmt";
        args[n++] = "yuv420p";
    }
    args[n++] = v->d.out;
    args[n] = NULL;
    int p[2];
    if (pipe(p) != 0) return 0;
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, p[0], STDIN_FILENO);
    posix_spawn_file_actions_addclose(&fa, p[1]);
    pid_t pid = 0;
    int rc = posix_spawnp(&pid, prog, &fa, NULL, (char *const *)args, environ);
    posix_spawn_file_actions_destroy(&fa);
    close(p[0]);
    if (rc != 0) { close(p[1]); errno = rc; return 0; }
    *fd = p[1];
    return pid;
}

/* out.mp4 -> out-frames/: where the frames go when there is no ffmpeg. */
static void fallback_dir(const char *out, char *dir, size_t len) {
    const char *dot = strrchr(out, '.'), *slash = strrchr(out, '/');
    int keep = dot && (!slash || dot > slash) ? (int)(dot - out) : (int)strlen(out);
    snprintf(dir, len, "%.*s-frames/", keep, out);
}

static bool open_png(video *v, const char *dir, char *err, int errlen) {
    v->png = true;
    snprintf(v->where, sizeof v->where, "%s%s", dir, ends_with(dir, "/") ? "" : "/");
    char why[MSG_MAX];
    if (!file_mkdir_p(v->where, why, sizeof why)) {
        snprintf(err, (size_t)errlen, "%s", why);
        return false;
    }
    return true;
}

video *video_open(const video_desc *d, char *note, int notelen, char *err, int errlen) {
    video *v = mem_zalloc(sizeof *v);
    v->d = *d;
    v->fd = -1;
    note[0] = '\0';
    if (ends_with(d->out, "/") || file_is_dir(d->out)) {
        if (open_png(v, d->out, err, errlen)) return v;
        free(v);
        return NULL;
    }
    snprintf(v->where, sizeof v->where, "%s", d->out);
    /* a closed pipe (ffmpeg refused the file) is an error to report, not a death */
    struct sigaction ign;
    memset(&ign, 0, sizeof ign);
    ign.sa_handler = SIG_IGN;
    sigaction(SIGPIPE, &ign, &v->old_pipe);
    v->pid = spawn_ffmpeg(v, &v->fd);
    if (v->pid > 0) return v;
    int why = errno;
    sigaction(SIGPIPE, &v->old_pipe, NULL);
    char dir[4096];
    fallback_dir(d->out, dir, sizeof dir);
    if (!open_png(v, dir, err, errlen)) { free(v); return NULL; }
    snprintf(note, (size_t)notelen,
             "cannot run %s (%s; on Debian: apt-get install ffmpeg): writing PNG frames to %s instead;\n"
             "  `ffmpeg -framerate %d -i %sframe-%%05d.png -pix_fmt yuv420p %s` makes the video later",
             d->ffmpeg ? d->ffmpeg : "ffmpeg", strerror(why), v->where, d->fps, v->where, d->out);
    return v;
}

static bool write_all(int fd, const unsigned char *p, size_t n) {
    while (n > 0) {
        ssize_t k = write(fd, p, n);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) return false;
        p += k;
        n -= (size_t)k;
    }
    return true;
}

static bool write_png(video *v, const unsigned char *rgb, char *err, int errlen) {
    img im;
    memset(&im, 0, sizeof im);
    if (!img_alloc(&im, v->d.width, v->d.height, 3)) {
        snprintf(err, (size_t)errlen, "a %dx%d frame is too large", v->d.width, v->d.height);
        return false;
    }
    for (long i = 0; i < (long)v->d.width * v->d.height * 3; i++) im.px[i] = rgb[i] / 255.0f;
    char path[4200];
    video_png_path(v->where, v->frames, path, sizeof path);
    bool ok = img_write(path, &im, err, errlen);
    img_free(&im);
    return ok;
}

bool video_frame(video *v, const unsigned char *rgb, char *err, int errlen) {
    bool ok;
    if (v->png) ok = write_png(v, rgb, err, errlen);
    else {
        ok = !v->failed && write_all(v->fd, rgb, (size_t)v->d.width * (size_t)v->d.height * 3);
        if (!ok) snprintf(err, (size_t)errlen, "ffmpeg stopped taking frames (its message is above)");
    }
    if (!ok) v->failed = true;
    else v->frames++;
    return ok;
}

bool video_close(video *v, char *err, int errlen) {
    bool ok = !v->failed;
    err[0] = '\0';
    if (v->pid > 0) {
        close(v->fd);
        int status = 0;
        while (waitpid(v->pid, &status, 0) < 0 && errno == EINTR) {}
        sigaction(SIGPIPE, &v->old_pipe, NULL);
        if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
            snprintf(err, (size_t)errlen, "ffmpeg failed making %s (exit %d; its message is above)", v->where,
                     WIFEXITED(status) ? WEXITSTATUS(status) : -1);
            ok = false;
        }
    }
    if (!ok && !err[0]) snprintf(err, (size_t)errlen, "%s: a frame was not written", v->where);
    free(v);
    return ok;
}
