/* res_budget: the windows' frame budget controller (see res_budget.h). */
#include "res_budget.h"

#include <math.h>

#include "util.h"

void res_budget_init(res_budget *b, double budget_ms) {
    *b = (res_budget){ .budget_ms = budget_ms, .scale = budget_ms > 0 ? RES_BUDGET_FIRST : 1.0 };
}

static double clampd(double x, double lo, double hi) { return x < lo ? lo : x > hi ? hi : x; }

void res_budget_feed(res_budget *b, double ms, double scale) {
    if (b->budget_ms <= 0 || !(ms > 0) || !(scale > 0)) return;
    /* aim below the budget by the dead band, so a frame the dead band
     * leaves alone is still within the budget (50 ms: 20 fps or more) */
    double ratio = b->budget_ms / (1.0 + RES_BUDGET_DEADBAND) / ms;
    if (fabs(ratio - 1.0) <= RES_BUDGET_DEADBAND && scale == b->scale) return;
    /* contended, only shrinking: the job ends in a few hundred ms, and a
     * new size's first frame costs more than the pixels it would add */
    if (b->contended && ratio > 1.0) return;
    /* pixels in proportion to the time left; growing at most twice a step
     * (a cheap frame may be noise), shrinking at once (a slow one is felt) */
    double area = scale * scale * (ratio > 2.0 ? 2.0 : ratio);
    b->scale = clampd(sqrt(area), RES_BUDGET_FLOOR, 1.0);
}

/* After the measure at scale drawn. A size grown to whose first measures
 * (RES_BUDGET_CEILING_TRIES) shrink it, over the aim, not while a job
 * shares the cores, is the ceiling for ceiling_s; meanwhile growth stops
 * halfway to it (its geometric mean with drawn), or stays where that
 * gains under 2% of a side; once it lapses, growth tries the ceiling
 * itself (not beyond), and a try that fails again soon holds twice as
 * long (up to RES_BUDGET_CEILING_MAX_S). A size that holds at the ceiling
 * clears it. A size that held a while and then shrank (the machine's
 * noise, a job) sets none: a ceiling from such a shrink kept the window
 * small for seconds. Without it a size just over a cost step came back
 * every few frames: the lake in the window, natural 337x189 <-> 374x210
 * (its targets double at 0.354 of a side), a frame in four over the
 * budget. */
static void ceiling(res_budget *b, double drawn, double now_s) {
    bool fresh = b->grown_to == drawn && b->grown_measures++ < RES_BUDGET_CEILING_TRIES;
    if (b->scale < drawn) {
        b->grown_to = 0;
        if (!fresh || b->contended) return;
        bool again = b->ceiling > 0 && drawn <= b->ceiling * 1.05 && now_s < b->ceiling_until + b->ceiling_s;
        b->ceiling_s = again ? fmin(2 * b->ceiling_s, RES_BUDGET_CEILING_MAX_S) : RES_BUDGET_CEILING_S;
        b->ceiling = drawn;
        b->ceiling_until = now_s + b->ceiling_s;
        return;
    }
    if (b->ceiling > 0 && drawn >= b->ceiling * 0.999) b->ceiling = 0;   /* it holds there now */
    if (b->scale <= drawn) return;
    if (b->ceiling > 0) {
        double cap = now_s < b->ceiling_until ? sqrt(drawn * b->ceiling) : b->ceiling;
        if (b->scale > cap) b->scale = cap > drawn * 1.02 ? cap : drawn;
    }
    if (b->scale > drawn) {
        b->grown_to = b->scale;
        b->grown_measures = 0;
    }
}

void res_budget_view(res_budget *b, uint64_t view_key) {
    if (view_key == b->view_key) return;
    b->view_key = view_key;
    b->ceiling = 0;
}

/* The last frame's time, as a measure of its size. The first frame at a
 * new size is none: it pays once for what the next ones keep (the world's
 * layers built at the size, targets made), and sizing by it would shrink
 * the picture and pay again, frame after frame. Nor is one frame: the
 * size changes when two in a row at it were both over the aim (by the
 * smaller time) or both under it (by the larger), so one slow or quick
 * frame (the machine's noise) does not cost a new size's first frame. */
static void measure(res_budget *b, double ms, double now_s) {
    if (!(ms > 0) || b->drawn_scale != b->prev_scale) {
        b->prev_ms = 0;
        return;
    }
    double aim = b->budget_ms / (1.0 + RES_BUDGET_DEADBAND), prev = b->prev_ms;
    b->prev_ms = ms;
    if (!(prev > 0)) return;
    if (ms > aim && prev > aim) res_budget_feed(b, fmin(ms, prev), b->drawn_scale);
    else if (ms < aim && prev < aim) res_budget_feed(b, fmax(ms, prev), b->drawn_scale);
    ceiling(b, b->drawn_scale, now_s);
}

bool res_budget_plan(res_budget *b, uint64_t key, double now_s, double last_frame_ms, bool force_full,
                     double *scale) {
    if (b->measure) measure(b, last_frame_ms, now_s);
    b->measure = false;
    bool changed = !b->have_key || key != b->key;
    if (changed) {
        b->key = key;
        b->have_key = true;
        b->still_since = now_s;
        b->full_done = false;
    }
    bool off = b->budget_ms <= 0;
    double s;
    if (b->full_done) {
        *scale = b->drawn_scale;
        return false;                     /* the kept frame is the picture, at full resolution */
    }
    if (off || force_full || (now_s - b->still_since >= RES_BUDGET_SETTLE_S && !b->hold_full)) s = 1.0;
    else if (changed) s = b->hold_full ? fmin(b->scale, RES_BUDGET_HELD_MAX) : b->scale;
    else {
        *scale = b->drawn_scale;          /* settling: the reduced frame stays a moment */
        return false;
    }
    b->prev_scale = b->drawn_scale;
    b->drawn_scale = s;
    b->full_done = s >= 1.0;
    b->measure = true;
    *scale = s;
    return true;
}

void res_budget_contend(res_budget *b, bool contended) {
    if (contended == b->contended) return;
    b->contended = contended;
    if (contended) {
        b->calm_scale = b->scale;
        b->scale = clampd(b->scale * RES_BUDGET_CONTENDED, RES_BUDGET_FLOOR, 1.0);
    } else {
        b->scale = b->calm_scale;
    }
    b->measure = false;
    b->prev_ms = 0;
}

void res_budget_costlier(res_budget *b, double cost) {
    if (b->budget_ms <= 0 || !(cost > 1.0)) return;
    b->scale = clampd(b->scale / sqrt(cost), RES_BUDGET_FLOOR, 1.0);
    b->measure = false;
    b->prev_ms = 0;
}

void res_budget_hold_full(res_budget *b, bool hold) { b->hold_full = hold; }

bool res_budget_full_held(const res_budget *b, double now_s) {
    return b->hold_full && b->have_key && !b->full_done && b->drawn_scale > 0 &&
           now_s - b->still_since >= RES_BUDGET_SETTLE_S;
}

bool res_budget_settled(const res_budget *b, double now_s) {
    return b->full_done && b->have_key && now_s - b->still_since >= RES_BUDGET_SETTLE_S;
}

void res_budget_size(double scale, int w, int h, int *iw, int *ih) {
    if (scale >= 1.0) {
        *iw = w;
        *ih = h;
        return;
    }
    *iw = (int)lround(w * scale);
    *ih = (int)lround(h * scale);
    if (*iw < 1) *iw = 1;
    if (*ih < 1) *ih = 1;
    *iw = side_off_pow2(*iw, w);   /* the screen-sized targets' sides */
    *ih = side_off_pow2(*ih, h);
}

