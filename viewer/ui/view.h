/* view: `tarn view SCENE.glib`, the live window: the scene with hot reload,
 * the generated slider panel, orbit camera, screenshots and scripts. The
 * window loop is app.h's, shared with compare-view. */
#ifndef TARN_VIEW_H
#define TARN_VIEW_H

typedef struct view_desc {
    const char *glib;
    int width, height;          /* 0: the glib's WindowSize */
    const char *script;         /* a file of scripted actions (tests, demos) */
    double time_s;
    const char *pack;           /* replaces the scene's `Pack` */
    const char *setting;        /* a row of the pack's bench.txt to start from (the Setting combo) */
    const char *record;         /* record a session (session.h) into this file from the start */
    int samples;                /* MSAA (render_desc.samples): 0 the default, 1 off */
    bool verbose;               /* render_desc.verbose: each inactive uniform at its line */
} view_desc;

/* Runs the window until it is closed (or the script quits). Returns a
 * tarn_exit_code. */
int view_run(const view_desc *d);

#endif
