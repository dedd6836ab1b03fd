/* res_budget: the windows' frame budget. While the picture changes (the
 * camera, a slider, a reload, the clock running) the scene is drawn at a
 * reduced internal resolution chosen from measured frame times so that a
 * frame costs about the budget, and upscaled into the window; once the
 * picture has been still for RES_BUDGET_SETTLE_S one frame is drawn at
 * full resolution, and from then on nothing is drawn again until the
 * picture changes (the client shows the frame it keeps).
 *
 * The controller aims at budget / (1 + RES_BUDGET_DEADBAND): a frame drawn
 * at scale s (of each side) that took m ms asks for s^2 * aim / m of the
 * pixels next time (the fixed point of a cost a + b*pixels with a < aim,
 * reached without overshoot), at most twice the pixels a step, not below
 * RES_BUDGET_FLOOR of each side, and left alone within RES_BUDGET_DEADBAND
 * of the aim (no flicker between two near sizes), so a settled frame is at
 * most the budget. The first frame at a new size is not a measure (it pays
 * once for what later frames at the size keep: the world's layers), and
 * the size changes on two frames in a row, both over or both under the aim
 * (one noisy frame would cost a new size's first frame). A size grown to
 * that shrank at once, its frames over the aim, is a ceiling for
 * RES_BUDGET_CEILING_S: growth goes halfway to it at most, then tries it
 * again, holding twice as long each time the try fails; so a cost step (a
 * pack's targets doubling at a size) with the machine's noise does not
 * send the size across it and back every few frames. The renderer's fixed-size passes and meshes shrink with
 * the frame (render_set_detail), so a cost stays about a + b*pixels. A cost that stays above the budget at the floor (a
 * fixed pass slower than the budget) stays at the floor.
 *
 * Pure C, no GL: the window hands it a key of the picture (any change of
 * what is drawn changes the key), the clock and the wall time of the last
 * frame.
 *
 *     res_budget b; res_budget_init(&b, RES_BUDGET_DEFAULT_MS);
 *     each frame: double s;
 *         if (res_budget_plan(&b, key, now_s, last_frame_ms, force_full, &s))
 *             draw at res_budget_size(s, w, h, ...), then upscale
 *         else show the kept frame
 */
#ifndef TARN_RES_BUDGET_H
#define TARN_RES_BUDGET_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define RES_BUDGET_DEFAULT_MS 50.0
#define RES_BUDGET_MAX_MS 1000.0    /* the panel slider's end */
#define RES_BUDGET_FLOOR 0.125      /* each side at least 1/8 of the window's */
#define RES_BUDGET_SETTLE_S 0.25    /* still this long: the full-resolution frame */
#define RES_BUDGET_DEADBAND 0.15    /* within 15% of the budget: keep the size */
#define RES_BUDGET_FIRST 0.5        /* the first changing frame, before any measure: half a side */
#define RES_BUDGET_CEILING_S 3.0     /* a size found over the aim is not grown back to for this long, */
#define RES_BUDGET_CEILING_MAX_S 24.0 /* ... twice as long each time it fails again, up to this */
#define RES_BUDGET_CEILING_TRIES 3    /* a size grown to that shrinks within this many measures */

typedef struct res_budget {
    double budget_ms;            /* 0 (or less): off, every frame at full resolution */
    double scale;                /* each side's factor for a changing picture, [FLOOR, 1]
                                  * (RES_BUDGET_FIRST before a measure: a window's first
                                  * picture comes a quarter of a full frame's time after its
                                  * load; a cheap scene grows to 1 in a few frames) */
    uint64_t key;                /* the picture last planned */
    bool have_key;
    double still_since;          /* the clock when the key last changed */
    bool full_done;              /* this still picture's full-resolution frame is drawn */
    double drawn_scale;          /* the scale of the frame last drawn (0: none yet) */
    double prev_scale;           /* ... and of the one drawn before it */
    double prev_ms;              /* the time of the last frame measured at drawn_scale (0: none) */
    bool measure;                /* the last frame drew the scene: its time is a measure */
    bool hold_full;              /* the still picture's full frame waits (res_budget_hold_full) */
    bool contended;              /* another job shares the cores (res_budget_contend) */
    double calm_scale;           /* ... scale before it began, taken back at its end */
    double ceiling;              /* the last scale that shrank, over the aim: growth stops short (0: none) */
    double ceiling_until;        /* ... of it until this clock, then tries it */
    double ceiling_s;            /* ... for this long: RES_BUDGET_CEILING_S, doubled by each try that fails */
    uint64_t view_key;           /* the picture but its clock the ceiling was found for (res_budget_view) */
    double grown_to;             /* the scale last grown to (0: none since) */
    int grown_measures;          /* ... and how many measures it has had */
} res_budget;

void res_budget_init(res_budget *b, double budget_ms);

/* This frame: key is the picture (hash_fnv1a of its inputs), now_s a clock in
 * seconds, last_frame_ms the wall time of the previous frame (0: not a fair
 * measure, e.g. it reloaded the scene), force_full a frame that must be at
 * full resolution (a screenshot, heat maps read back). Returns whether the
 * scene must be drawn, at *scale; false: the frame drawn last (at
 * b->drawn_scale) is still the picture. */
bool res_budget_plan(res_budget *b, uint64_t key, double now_s, double last_frame_ms, bool force_full,
                     double *scale);

/* Is the picture still at now_s: its full-resolution frame drawn and its
 * key unchanged for RES_BUDGET_SETTLE_S? (full_done alone is not: a cheap
 * scene's moving frames are full-resolution too.) */
bool res_budget_settled(const res_budget *b, double now_s);

/* While hold is true a still picture keeps its reduced frame past
 * RES_BUDGET_SETTLE_S, and a changing one is drawn at RES_BUDGET_HELD_MAX
 * at most: the full-resolution frame's code is being made off the frame
 * (compile_job.h), and drawing it now would make it again on the frame. A
 * forced full frame (a screenshot) is still drawn. */
#define RES_BUDGET_HELD_MAX 0.95
void res_budget_hold_full(res_budget *b, bool hold);
/* Is a still picture's full-resolution frame due and held (the picture
 * unchanged for RES_BUDGET_SETTLE_S, its reduced frame shown)? Nothing to
 * draw until the hold ends or the picture changes. */
bool res_budget_full_held(const res_budget *b, double now_s);
/* While contended is true a job (a save's compile) takes one of the cores
 * the frames draw on, for a few hundred ms: a frame at the size the budget
 * chose takes about twice as long. The changing picture shrinks at once to
 * RES_BUDGET_CONTENDED of each side (a quarter of the pixels) and the
 * controller shrinks it further where the frames drawn meanwhile are over
 * the aim (never grows it: a new size's first frame costs more than the
 * pixels would give in the job's few hundred ms); at the end the size
 * from before comes back (the job's frames say nothing of the calm
 * machine). A change of either way drops the last frame's measure.
 * 0.6 (a third of the pixels) left the contended frames at the budget's
 * edge, 47-54 ms with the job's noise (scripts/save_bench.sh --running,
 * raymarch, lake); 0.5 leaves them room: 35-46 ms (docs/benchmark.md,
 * "The frames after a save's reload"). */
#define RES_BUDGET_CONTENDED 0.5
void res_budget_contend(res_budget *b, bool contended);
/* The next frames take a path about `cost` times as slow at the same size
 * (the window's water drawn as a grid until a save's job has made its
 * deferred code): the changing picture shrinks at once to 1/sqrt(cost) of
 * its side (not below RES_BUDGET_FLOOR), the last frame's measure
 * dropped. Without it the first frames of that path were over the budget
 * (the size changes only after two frames over the aim). While contended,
 * the size from before the contention still comes back at its end. */
void res_budget_costlier(res_budget *b, double cost);
/* The picture's inputs but its clock (a hash of the camera, the sliders,
 * the scene's load): a change forgets the ceiling, which held another
 * picture's costs. Only while the clock alone runs does it stay. */
void res_budget_view(res_budget *b, uint64_t view_key);
/* One frame drawn at scale took ms: the next changing frame's scale. */
void res_budget_feed(res_budget *b, double ms, double scale);

/* The internal size for a w x h area at scale: each side rounded, at
 * least 1 pixel, exactly w x h at scale 1. */
void res_budget_size(double scale, int w, int h, int *iw, int *ih);

#endif
