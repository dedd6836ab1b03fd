/* cmd_record: `tarn record SESSION -o OUT`, a recorded session (ui/session.h)
 * replayed without a display (EGL, as `tarn render`) into a video or PNG
 * frames (tools/video.h). Frame i shows session time i/fps and its
 * simulated clock follows from the session alone, never from the wall
 * clock: the same session gives the same frames at any speed. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmd.h"
#include "strbuf.h"
#include "file.h"
#include "gl_ctx.h"
#include "mem.h"
#include "ref_metrics.h"
#include "render.h"
#include "session.h"
#include "util.h"
#include "video.h"
#include "view_util.h"

#define RECORD_MAX_FRAMES 1000000

typedef struct record_desc {
    const char *session, *out;
    int width, height;           /* 0: the session's size, else the glib's WindowSize */
    int fps;                     /* 0: 30 */
    int samples;                 /* MSAA (render_desc.samples): 0 the default, 1 off */
    bool quiet;
} record_desc;

/* The target's RGBA floats as 8-bit RGB; a world scene (linear radiance)
 * gets the sRGB encoding the window shows. */
static void to_rgb8(const float *rgba, unsigned char *rgb, long npx, bool srgb) {
    for (long i = 0; i < npx; i++)
        for (int k = 0; k < 3; k++) {
            double c = rgba[i * 4 + k];
            if (srgb) c = ref_linear_to_srgb(c);
            c = c < 0 ? 0 : c > 1 ? 1 : c;
            rgb[i * 3 + k] = (unsigned char)lround(c * 255.0);
        }
}

static int frame_count(const session *s, int fps) {
    double n = ceil(session_duration(s) * fps - 1e-9);
    if (n < 1) return 1;
    return n > RECORD_MAX_FRAMES ? RECORD_MAX_FRAMES : (int)n;
}

/* Draws every frame into the sink; returns an exit code. */
static int replay(const session *s, render *r, gl_ctx *ctx, const render_target *t, video *v, int fps) {
    long npx = (long)t->w * t->h;
    float *rgba = mem_alloc((size_t)npx * 4 * sizeof *rgba);
    unsigned char *rgb = mem_alloc((size_t)npx * 3);
    session_player p;
    session_player_start(&p, s, render_default_view(r));
    int frames = frame_count(s, fps), rc = TARN_EXIT_OK;
    char err[MSG_MAX];
    for (int i = 0; i < frames && rc == TARN_EXIT_OK; i++) {
        double sim = session_player_advance(&p, r, (double)i / fps);
        render_view view = orbit_view(&p.cam);
        render_frame(r, sim, t->fbo, t->w, t->h, &view);
        if (gl_ctx_lost(ctx, err, sizeof err)) { fprintf(stderr, "tarn: %s\n", err); rc = TARN_EXIT_NO_GL; break; }
        if (!render_target_read(t, rgba)) { fprintf(stderr, "tarn: reading the frame failed\n"); rc = TARN_EXIT_NO_GL; break; }
        to_rgb8(rgba, rgb, npx, render_has_world(r));
        if (!video_frame(v, rgb, err, sizeof err)) { fprintf(stderr, "tarn: %s\n", err); rc = TARN_EXIT_INPUT; }
    }
    if (rc == TARN_EXIT_OK && p.failed > 0) {
        fprintf(stderr, "tarn: %d event(s) of %s did not apply to the scene (messages above)\n", p.failed, s->path);
        rc = TARN_EXIT_INPUT;
    }
    free(rgba);
    free(rgb);
    return rc;
}

/* The scene, loaded with the session's pack (*ok: without errors; what
 * compiled is still drawn, as `tarn render` does); NULL when there is none. */
static render *load_scene(const session *s, int samples, bool *ok) {
    if (!file_exists(s->scene)) {
        fprintf(stderr, "%s: error: the session's scene %s is not there (moved? edit its `scene` line)\n", s->path,
                s->scene);
        return NULL;
    }
    render_desc rd = { .pack = s->pack[0] ? s->pack : NULL, .samples = samples };
    render *r = render_create(&rd);
    *ok = render_load(r, s->scene);
    if (render_messages(r)[0]) fputs(render_messages(r), stderr);
    return r;
}

static int record_with(const record_desc *d, const session *s, bool parsed_ok) {
    char err[MSG_MAX], note[2048];
    gl_ctx *ctx = gl_ctx_create_headless(err, sizeof err);
    if (!ctx) { fprintf(stderr, "tarn: %s\n", err); return TARN_EXIT_NO_GL; }
    bool scene_ok = false;
    render *r = load_scene(s, d->samples > 0 ? d->samples : CMD_MSAA_STILL_DEFAULT, &scene_ok);   /* a kept video */
    if (!r) { gl_ctx_destroy(ctx); return TARN_EXIT_INPUT; }
    int w = d->width, h = d->height;
    if (w <= 0 || h <= 0) { w = s->width; h = s->height; }
    if (w <= 0 || h <= 0) render_window_size(r, &w, &h);
    render_target t;
    int rc = TARN_EXIT_NO_GL;
    if (!render_target_create(&t, w, h, render_has_world(r))) {
        fprintf(stderr, "tarn: cannot create a %dx%d framebuffer\n", w, h);
    } else {
        video_desc vd = { .out = d->out, .width = w, .height = h, .fps = d->fps, .ffmpeg = getenv("TARN_FFMPEG") };
        video *v = video_open(&vd, note, sizeof note, err, sizeof err);
        if (!v) { fprintf(stderr, "tarn: %s\n", err); rc = TARN_EXIT_INPUT; }
        else {
            if (note[0]) fprintf(stderr, "tarn: %s\n", note);
            rc = replay(s, r, ctx, &t, v, d->fps);
            char where[4096];
            snprintf(where, sizeof where, "%s", video_where(v));
            if (!video_close(v, err, sizeof err)) { fprintf(stderr, "tarn: %s\n", err); if (!rc) rc = TARN_EXIT_INPUT; }
            else if (!d->quiet)
                printf("tarn: wrote %s (%d frames, %dx%d, %d fps, %.3f s of %s)\n", where,
                       frame_count(s, d->fps), w, h, d->fps, session_duration(s), s->path);
        }
        render_target_destroy(&t);
    }
    render_destroy(r);
    gl_ctx_destroy(ctx);
    return rc == TARN_EXIT_OK && !(parsed_ok && scene_ok) ? TARN_EXIT_INPUT : rc;
}

static int record(const record_desc *d) {
    session s;
    memset(&s, 0, sizeof s);
    diag_list dl = {0};
    bool ok = session_load(&s, d->session, &dl);
    diag_print(&dl, stderr);
    diag_list_free(&dl);
    int rc = TARN_EXIT_INPUT;
    if (s.scene[0]) rc = record_with(d, &s, ok);   /* bad events are left out, the rest plays */
    session_free(&s);
    return rc;
}

/* ---- the command line ---- */

#define OFF(field) offsetof(record_desc, field)

static const cmd_option options[] = {
    { "SESSION", .kind = CMD_ARG, .offset = OFF(session),
      .missing = "which session? give the file `tarn view --record` wrote" },
    { "--out", "-o", "OUT", .kind = CMD_STRING, .offset = OFF(out), .missing = "where to? give -o out.mp4 or -o frames/",
      .help = "a video made by the ffmpeg program (.mp4, .webm, .mkv, .gif:\n"
              "whatever it writes), or DIR/ for PNG frames frame-00000.png...;\n"
              "without ffmpeg the frames go to OUT-frames/ as PNGs\n",
      .man = "a video\n"
             ".RI ( .mp4 \", \" .webm \", \" .mkv \", \" .gif :\n"
             "whatever ffmpeg writes), or\n"
             ".I DIR/\n"
             "for PNG frames\n"
             ".IR DIR/frame\\-00000.png \", ....\"\n"
             "Without ffmpeg the frames become PNGs in\n"
             ".I OUT\\-frames/\n"
             "and a message says how to make the video later.\n" },
    { "--size", .metavar = "WxH", .kind = CMD_SIZE, .offset = OFF(width), .offset2 = OFF(height),
      .wants = "WxH, e.g. 640x360",
      .help = "frame size (default: the window's when recording)\n",
      .man = "frame size (default: the window's scene area when recording).\n" },
    { "--fps", .metavar = "N", .kind = CMD_INT, .offset = OFF(fps), .lo = 1, .hi = 240,
      .wants = "a whole number 1..240",
      .help = "frames per second, 1..240 (default 30)\n",
      .man = "frames per second, 1 to 240 (default 30).\n" },
    CMD_OPTION_MSAA_STILL(OFF(samples)),
    { "--quiet", .kind = CMD_FLAG, .offset = OFF(quiet),
      .help = "print only errors\n",
      .man = "print only errors.\n" },
    { 0 }
};

const cmd_spec cmd_record_spec = {
    .name = "record",
    .synopsis = "SESSION -o OUT [--size WxH] [--fps N] [--msaa N] [--quiet]\n",
    .about = "Replays a session recorded by `tarn view` (Shift+R, or --record FILE)\n"
             "without any display (EGL, as `tarn render`): its slider, colour, checkbox\n"
             "and Define changes, camera moves, pack switches and pauses at their times.\n"
             "Frame i shows the session at i/N seconds; the simulated clock follows from\n"
             "the session alone, so the same session gives the same frames.\n",
    .options = options,
    .notes = "exit codes: 0 ok, 1 the session or scene has errors, 2 bad usage, 3 no OpenGL\n",
    .extra = "one session at a time",
};

CMD_USAGE_FUNCTION(cmd_record_usage, cmd_record_spec)

int cmd_record(int argc, char **argv) {
    if (cmd_wants_help(argc, argv)) { fputs(cmd_record_usage(), stdout); return TARN_EXIT_OK; }
    record_desc d = { .fps = 30 };
    int rc = cmd_parse(&cmd_record_spec, argc, argv, &d, stderr);
    if (rc != TARN_EXIT_OK) return rc;
    /* ffmpeg picks the format by the extension: without one it can only fail, after the replay */
    const char *base = strrchr(d.out, '/') ? strrchr(d.out, '/') + 1 : d.out;
    if (base[0] && !strchr(base, '.') && !file_is_dir(d.out))
        return cmd_bad_usage(&cmd_record_spec, stderr,
                             "-o wants a video with its extension (out.mp4) or a folder ending in / (frames/)");
    return record(&d);
}
