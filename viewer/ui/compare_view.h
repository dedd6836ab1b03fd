/* compare_view: `tarn compare-view SCENE.glib --packs a,b[,c,d]`, two to
 * four packs side by side in one window: one camera, one clock and the
 * scene's world for all, each pack with its own sliders in the panel.
 *
 *   grid    the packs in a row (two) or a 2 x 2 grid (three or four)
 *   wipe    two packs over one view, a divider dragged with the mouse
 *   heat    each pack's per-pixel error against the CPU reference of the
 *           same frame (ref_render at the viewport size, computed on
 *           request with H or the panel's button on a worker thread, with
 *           its progress in the panel; time pauses), in the inferno ramp of
 *           reference/ref_metrics.h at one scale for all, with a legend
 *
 * Each pack's GPU time (timer queries) and wall time (after glFinish) is
 * on screen in its corner and in the panel. Keys: H heat maps (compute, or
 * show/hide), G grid, W wipe, Tab the wipe's right pack, Space pause,
 * R reload, P/F12 screenshot, F/Home reset the camera, Esc/Q quit.
 *
 * Script actions (--script, besides view_script.h's; `set`/`expect` act on
 * the pack chosen by `pack`):
 *   pack N              the N-th pack (1-based) for set/expect
 *   layout grid|wipe    wipe A B: the wipe's two packs (1-based)
 *   divider X           the wipe's divider at X (0..1 from the left)
 *   heat                compute the heat maps now (prints each pack's RMSE)
 *   heat-show on|off    heat-max E (0: automatic scale)
 *   orbit DX DY         turn the camera as a left drag of DX, DY pixels
 *   drag X0 Y0 X1 Y1    a left press at X0 Y0, a move to X1 Y1 and the release, all
 *                       between two frames (window pixels): a slow frame's drag
 *   timings             print each pack's GPU and wall time
 *   expect-heat         fail unless every pack has a heat map with a finite error
 *   expect-divider X    fail unless the wipe's divider is at X (within 0.01)
 *   expect-camera home|moved   fail unless the camera is (not) where F puts it
 */
#ifndef TARN_COMPARE_VIEW_H
#define TARN_COMPARE_VIEW_H

#define COMPARE_VIEW_MAX_PACKS 4

typedef struct compare_view_desc {
    const char *glib;
    const char *packs[COMPARE_VIEW_MAX_PACKS];   /* 2..4; the same pack twice is allowed */
    int npacks;
    int width, height;          /* the scene area (0: the glib's WindowSize) */
    double time_s;
    const char *script;
    int ref_caustic_res;        /* reference quality for the heat maps (0: 128) */
    int ref_photons;            /* photons per caustic cell (0: 16) */
    int samples;                /* MSAA of every pack (render_desc.samples): 0 the default, 1 off;
                                   the heat maps' reference subsamples at the GL's positions
                                   (refcache_match_msaa) */
} compare_view_desc;

int compare_view_run(const compare_view_desc *d);

#endif
