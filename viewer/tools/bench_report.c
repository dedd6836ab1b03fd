/* bench_report: `tarn bench`'s reports (bench_int.h): report.md, the
 * plots (time against water RMSE and against water FLIP) and the --docs
 * section; and bench_write_results, which writes every result (the tables:
 * bench_csv.c, bench_json.c). */
#include "bench_int.h"
#include "strbuf.h"

#include <dirent.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image_io.h"
#include "file.h"
#include "mem.h"
#include "plot.h"
#include "ref_flip.h"
#include "util.h"

#define stem bench_stem
#define write_text bench_write_text
#define axis_time bench_axis_time
#define COST_SCALES BENCH_COST_SCALES

/* ---- writing ---- */

/* The time axis in words: "GPU", "wall" or "CPU" */
static const char *axis_label(const bench *b) {
    return b->axis == BENCH_AXIS_GPU ? "GPU" : b->axis == BENCH_AXIS_CPU ? "CPU" : "wall";
}

static void md_num(strbuf *o, const char *fmt, double v) {
    if (isnan(v)) strbuf_printf(o, " – |");
    else if (isinf(v)) strbuf_printf(o, " ∞ |");
    else {
        strbuf_printf(o, " ");
        strbuf_printf(o, fmt, v);
        strbuf_printf(o, " |");
    }
}

/* The report: machine, run, floor, a table per scene, the plot. plot_dir is
 * how the Markdown names the plots' directory ("" for beside it). */
/* The cost models: a line a pack, and what its default would cost at 1080p. */
static void cost_md(bench *b, strbuf *o) {
    char sc[256];
    stem(b->scene_abs[0], sc, sizeof sc);
    strbuf_printf(o, "**Cost model** (%s, each pack's default; %s ms a frame = a + b·Mpixels + c·kvertices of the "
                  "water grid, least squares over %d frames: %dx%d, %dx%d and %dx%d, each with WaterMesh 64, 128 "
                  "and 256; the last column extrapolates far beyond them, so read it as an order of magnitude):\n\n",
                  sc, axis_label(b), COST_SAMPLES, (int)lround(b->o.w * COST_SCALES[0]),
                  (int)lround(b->o.h * COST_SCALES[0]), b->o.w, b->o.h, (int)lround(b->o.w * COST_SCALES[2]),
                  (int)lround(b->o.h * COST_SCALES[2]));
    strbuf_printf(o, "| pack | a ms | b ms/Mpixel | c ms/kvertex | R² | residual ms | 1920x1080, mesh 256 |\n"
                  "|---|---:|---:|---:|---:|---:|---:|\n");
    for (int p = 0; p < b->o.npacks; p++) {
        if (!b->has_cost[p]) {
            strbuf_printf(o, "| %s | not fitted: %s | | | | | |\n", b->o.packs[p], b->cost_note[p]);
            continue;
        }
        const cost_model *m = &b->cost[p];
        strbuf_printf(o, "| %s | %.1f | %.1f | %.3f | %.3f | %.1f | %.0f ms |\n", b->o.packs[p], m->a, m->b, m->c,
                      m->r2, m->rms_residual, cost_model_predict(m, 1920 * 1080 / 1e6, cost_model_grid_kvertices(256)));
    }
    strbuf_printf(o, "\n");
}

/* a value and its uncertainty, "0.0383 ± 0.0004" ("0.0383" where the
 * uncertainty is unknown or under a tenth of the last digit shown) */
static void md_pm(strbuf *o, double v, double u, int digits) {
    if (isnan(v)) { strbuf_printf(o, " – |"); return; }
    if (isfinite(u) && u >= 0.5 * pow(10, -digits)) strbuf_printf(o, " %.*f ± %.*f |", digits, v, digits, u);
    else strbuf_printf(o, " %.*f |", digits, v);
}

static double median_of(double *v, int n) {
    int k = 0;
    for (int i = 0; i < n; i++)
        if (isfinite(v[i])) v[k++] = v[i];
    return k ? median_double(v, (size_t)k) : NAN;
}

/* The scene's reference uncertainty and sequence, in words: medians over
 * its settings */
static void scene_notes_md(bench *b, strbuf *o, int sc) {
    int n = 0;
    double *v[6];
    for (int k = 0; k < 6; k++) v[k] = mem_zalloc((size_t)(b->nsums + 1) * sizeof(double));
    double ref_change = NAN;
    for (int i = 0; i < b->nsums; i++) {
        const summary *s = &b->sums[i];
        if (s->scene != sc || !s->ok) continue;
        v[0][n] = s->u_noise_rmse;
        v[1][n] = s->u_grid_rmse;
        v[2][n] = s->u_noise_flip;
        v[3][n] = s->u_grid_flip;
        v[4][n] = s->u_rmse / s->water_rmse;
        v[5][n] = s->u_flip / s->water_flip;
        if (isfinite(s->seq_ref_change)) ref_change = s->seq_ref_change;
        n++;
    }
    double m[6];
    for (int k = 0; k < 6; k++) m[k] = median_of(v[k], n);
    if (b->o.uncertainty && isfinite(m[0]))
        strbuf_printf(o, "Uncertainty (t = %g s, median over the settings): another photon sampling of the "
                      "reference (photon seed %llu instead of %llu, %d photons a caustic cell) moves a setting's "
                      "water RMSE by %.5f "
                      "and its water FLIP by %.4f; a caustic grid twice as fine (%d cells instead of %d) by %.5f "
                      "and %.4f. Combined: %.1f%% of the water RMSE, %.1f%% of the water FLIP. Each setting's "
                      "own figures are the ± in the table; they decide the ties.\n\n",
                      b->o.times[0], (unsigned long long)b->o.ref.seed + 1, (unsigned long long)b->o.ref.seed,
                      b->o.ref_photons, m[0], m[2],
                      2 * b->o.ref_caustic_res, b->o.ref_caustic_res, m[1], m[3], 100 * m[4], 100 * m[5]);
    if (b->o.seq_frames >= 2 && isfinite(ref_change))
        strbuf_printf(o, "Over time: %d frames at %g fps from t = %g s at %dx%d; the reference's own frame-to-frame "
                      "change over the water is %.4f RMS. \"temporal\" is the RMS of the pack's change minus the "
                      "reference's: a setting that flickers where the reference moves smoothly (aliased glints, "
                      "march steps) scores high.\n\n",
                      b->o.seq_frames, b->o.seq_fps, b->o.times[0], b->o.seq_w, b->o.seq_h, ref_change);
    for (int k = 0; k < 6; k++) free(v[k]);
}

/* The run: when and how long, the machine, the images and times, the
 * anti-aliasing, the time axis and the cost floor. */
static void report_header_md(bench *b, strbuf *o) {
    int extra_r = 0, extra_c = 0;
    for (int k = 1; k < REFK_COUNT; k++) {
        extra_r += b->extra_rendered[k];
        extra_c += b->extra_cached[k];
    }
    strbuf_printf(o, "Measured %s by `tarn bench` in %.0f s (%d:%02d; references: %d rendered, %d read from "
                 "the cache; for the sequence, the uncertainty and flat lighting: %d rendered, %d read).\n\n",
              b->started, b->seconds, (int)(b->seconds / 60), (int)fmod(b->seconds, 60), b->refs_rendered,
              b->refs_cached, extra_r, extra_c);
    strbuf_printf(o, "| machine | |\n|---|---|\n| CPU | %s (%d cores online) |\n| GL renderer | %s |\n"
                 "| GL version | %s |\n| load average (1, 5, 15 min) | before %.2f %.2f %.2f, after %.2f %.2f %.2f |\n\n",
              b->cpu, b->cores, b->gl_renderer, b->gl_version, b->load_before[0], b->load_before[1],
              b->load_before[2], b->load_after[0], b->load_after[1], b->load_after[2]);
    strbuf_printf(o, "Images %dx%d at t =", b->o.w, b->o.h);
    for (int i = 0; i < b->o.ntimes; i++) strbuf_printf(o, "%s %g", i ? "," : "", b->o.times[i]);
    strbuf_printf(o, " s; per setting and time %d warm-up frame(s), then up to %d timed frames (at least 3, "
                 "stopping after %.3g s), timed round-robin: every setting of a scene in turn, %d frames a turn "
                 "after an untimed one, so a load that comes and goes falls on all of them; medians, with the "
                 "quartiles of the frames "
                 "(q1–q3). Error: the mean over the times of the error against the CPU reference of the same "
                 "frame, first over the pixels where the reference sees water (what ranks the techniques), then "
                 "off the water and over the whole frame: RMSE of linear RGB, HDR-ꟻLIP (docs/metrics.md) and "
                 "SSIM. Two Pareto fronts: time against water RMSE (\"Pareto\", the summary's `pareto`) and "
                 "against water ꟻLIP (\"ꟻLIP front\", `pareto_flip`). Settings whose times agree within their "
                 "run-to-run noise (%.0f%%, or their medians' uncertainty, the frames' spread over √frames, "
                 "when larger) and whose water errors agree within their combined uncertainty (the ±, in quadrature; %.0f%% where not measured) tie: both stay on the "
                 "front.\n\n",
              b->o.warmup, b->o.frames, b->o.frame_budget, b->o.rr_chunk, 100 * BENCH_TIME_NOISE,
              100 * BENCH_ERROR_TIE);
    char aa[32] = "off";
    if (b->o.samples_used > 1) snprintf(aa, sizeof aa, "MSAA %dx", b->o.samples_used);
    char subs[96];
    refcache_describe_samples(&b->o.ref, subs, (int)sizeof subs);
    strbuf_printf(o, "Anti-aliasing: %s; the reference takes %s%s. Per-pixel "
                 "buffers (hit point, Fresnel, irradiance, depth) are drawn without MSAA and compared with the "
                 "reference's pixel-centre buffers.\n\n",
              aa, subs, b->o.spp_matched ? ", to match" : " (--ref-spp)");
    if (b->cpu_raster)
        strbuf_printf(o, "**%s is a CPU rasteriser**: its GPU timestamps are taken when commands are issued, "
                     "not when pixels are drawn, so the GPU column is not meaningful here, and its wall time "
                     "(after `glFinish`) stretches with whatever else the machine runs. \"CPU ms\" is this "
                     "process's CPU time a frame (`CLOCK_PROCESS_CPUTIME_ID`): the rasteriser's threads are "
                     "the process's, so it is the work the frame took, which other processes' load barely "
                     "moves.\n\n",
                  b->gl_renderer);
    strbuf_printf(o, "Time axis: **%s** time (`time_axis` \"%s\"): what the plots, \"× floor\" and the Pareto "
                 "fronts use.\n\n", axis_label(b), bench_axis_name(b));
    strbuf_printf(o, "Cost floor (a full-screen pass with one texture fetch): %.3f ms GPU, %.3f ms wall, %.3f ms "
                 "CPU. \"× floor\" is a setting's %s time over the floor's.\n\n",
              b->floor_gpu, b->floor_wall, b->floor_cpu, axis_label(b));
}

/* One setting's row of a scene's table. */
static void report_row_md(bench *b, strbuf *o, int sc, const summary *s) {
    strbuf_printf(o, "| %s | %s |", b->o.packs[s->pack], b->pb[s->pack].settings[s->setting].name);
    if (!s->ok) {
        const row *r = NULL;
        for (int j = 0; j < b->nrows; j++)
            if (b->rows[j].scene == sc && b->rows[j].pack == s->pack && b->rows[j].setting == s->setting)
                r = &b->rows[j];
        strbuf_printf(o, " failed: %s | | | | | | | | | | | | | | | | | | | | | | | |\n",
                      r && r->error[0] ? r->error : "?");
        return;
    }
    md_num(o, "%.2f", s->gpu_ms);
    md_num(o, "%.1f", s->wall_ms);
    if (isfinite(s->wall_q1)) strbuf_printf(o, " %.1f–%.1f |", s->wall_q1, s->wall_q3);
    else strbuf_printf(o, " – |");
    md_num(o, "%.1f", s->cpu_ms);
    if (isfinite(s->cpu_q1)) strbuf_printf(o, " %.1f–%.1f |", s->cpu_q1, s->cpu_q3);
    else strbuf_printf(o, " – |");
    md_num(o, "%.1f", axis_time(b, s) / bench_axis_floor(b));
    md_pm(o, s->water_rmse, s->u_rmse, 4);
    md_pm(o, s->water_flip, s->u_flip, 3);
    md_num(o, "%.3f", s->water_ssim);
    md_num(o, "%.1f", s->water_psnr);
    md_num(o, "%.4f", s->off_rmse);
    md_num(o, "%.4f", s->rmse);
    md_num(o, "%.3f", s->flip);
    md_num(o, "%.4f", s->p95);
    md_num(o, "%.1f%%", 100 * s->over_share);
    md_num(o, "%.4f", s->seq_water_rmse);
    md_num(o, "%.4f", s->temporal_rmse);
    md_num(o, "%.3f", s->has[1] ? s->comp[1] : NAN);
    md_num(o, "%.1f%%", 100 * s->capped_share);
    md_num(o, "%.4f", s->has[2] ? s->comp[2] : NAN);
    if (s->has[3] && s->irr_flat) strbuf_printf(o, " %.3f (flat) |", s->comp[3]);
    else md_num(o, "%.3f", s->has[3] ? s->comp[3] : NAN);
    md_num(o, "%.3f", s->has[4] ? s->comp[4] : NAN);
    strbuf_printf(o, " %s | %s |\n", s->pareto ? "●" : "", s->pareto_flip ? "●" : "");
    if (s->nan_px)
        strbuf_printf(o, "| | ⚠ %ld non-finite pixels | | | | | | | | | | | | | | | | | | | | | | | |\n",
                      s->nan_px);
}

/* The GPU time of each pass, per setting, at the first time. */
static void report_passes_md(bench *b, strbuf *o, int sc) {
    strbuf_printf(o, "\nGPU time per pass (median, first time; `pass:LINE units` is the glib line of the "
                 "RenderToTexture that begins it, `screen:LINE` what is drawn to the screen):\n\n");
    for (int i = 0; i < b->nrows; i++) {
        const row *r = &b->rows[i];
        if (r->scene != sc || r->ti != 0 || !r->npasses) continue;
        strbuf_printf(o, "- %s / %s:", b->o.packs[r->pack], b->pb[r->pack].settings[r->setting].name);
        for (int k = 0; k < r->npasses; k++)
            strbuf_printf(o, "%s `%s` %.2f ms", k ? "," : "", r->pass_name[k], r->pass_ms[k]);
        strbuf_printf(o, "\n");
    }
}

static void report_md(bench *b, strbuf *o, const char *plot_prefix) {
    report_header_md(b, o);
    for (int sc = 0; sc < b->o.nscenes; sc++) {
        char st[256];
        stem(b->scene_abs[sc], st, sizeof st);
        strbuf_printf(o, "### %s\n\n", st);
        scene_notes_md(b, o, sc);
        strbuf_printf(o, "| pack | setting | GPU ms | wall ms | wall q1–q3 | CPU ms | CPU q1–q3 | × floor | "
                     "water RMSE | water ꟻLIP | "
                     "water SSIM | water PSNR dB | off-water RMSE | frame RMSE | frame ꟻLIP | p95 error | > 0.05 | "
                     "water RMSE over time | temporal | hit p95 m | march capped | Fresnel MAE | "
                     "irradiance rel. median | depth MAE m | Pareto | ꟻLIP front |\n"
                     "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
                     "---:|---:|---:|:-:|:-:|\n");
        for (int i = 0; i < b->nsums; i++)
            if (b->sums[i].scene == sc) report_row_md(b, o, sc, &b->sums[i]);
        report_passes_md(b, o, sc);
        strbuf_printf(o, "\n![speed against error, %s](%splot-%s.png)\n", st, plot_prefix, st);
        strbuf_printf(o, "![speed against ꟻLIP, %s](%splot-%s-flip.png)\n\n", st, plot_prefix, st);
    }
    if (b->o.cost_model) {
        cost_md(b, o);
        bench_ocean_md(&b->ocean, b->ocean_scene, o);
    }
    strbuf_printf(o, "– : not measured: the pack shows no such buffer (a `buffer` line in its bench.txt, or "
                 "`Define %s`; docs/benchmark.md). Irradiance \"(flat)\": the pack shows no irradiance buffer "
                 "and lights the floor as the world does, by the sun through the flat mean surface; that "
                 "lighting is measured (the flat-caustics reference's irradiance against the reference's).\n",
              BENCH_OUTPUT_DEFINE);
}

/* metric 0: time against water RMSE; 1: against water FLIP */
static bool write_plot(bench *b, int sc, int metric, const char *path) {
    plot_series series[PACKSET_MAX];
    plot_point *pts = mem_zalloc((size_t)(b->nsums > 0 ? b->nsums : 1) * sizeof *pts);
    int np = 0, ns = 0;
    for (int p = 0; p < b->o.npacks; p++) {
        plot_series *se = &series[ns];
        se->name = b->o.packs[p];
        if (b->pb[p].has_colour) memcpy(se->rgb, b->pb[p].colour, sizeof se->rgb);
        else packset_palette(p, se->rgb);
        se->pts = pts + np;
        se->n = 0;
        for (int i = 0; i < b->nsums; i++) {
            const summary *s = &b->sums[i];
            if (s->scene != sc || s->pack != p || !s->ok) continue;
            double e = metric == 0 ? (isfinite(s->water_rmse) ? s->water_rmse : s->rmse)
                                   : (isfinite(s->water_flip) ? s->water_flip : s->flip);
            pts[np++] = (plot_point){ axis_time(b, s), e, b->pb[p].settings[s->setting].name,
                                      metric == 0 ? s->pareto : s->pareto_flip };
            se->n++;
        }
        ns++;
    }
    char st[256], title[512], sub[512], floor[64];
    stem(b->scene_abs[sc], st, sizeof st);
    snprintf(title, sizeof title, "%s %dx%d: speed against %s", st, b->o.w, b->o.h,
             metric == 0 ? "error" : "FLIP (perceptual error)");
    snprintf(sub, sizeof sub, "%.60s", b->gl_renderer);
    snprintf(floor, sizeof floor, "floor %.3g ms", bench_axis_floor(b));
    char xlabel[64];
    snprintf(xlabel, sizeof xlabel, "%s time per frame, ms (log)", axis_label(b));
    plot_chart c = { .title = title, .subtitle = sub,
                     .xlabel = xlabel,
                     .ylabel = metric == 0 ? "water RMSE vs reference (log)" : "water HDR-FLIP vs reference (log)", .series = series, .nseries = ns,
                     .floor_x = bench_axis_floor(b), .floor_label = floor };
    img im;
    bool ok = plot_speed_error(&c, &im);
    char err[MSG_MAX];
    if (ok) ok = img_write(path, &im, err, sizeof err);
    img_free(&im);
    free(pts);
    return ok;
}

/* text with what lies between the markers replaced by content (or, when
 * text has no such markers, with a section `heading` holding them added at
 * its end). A new string. */
static char *replace_section(const char *text, const char *begin, const char *end, const char *heading,
                             const char *content) {
    strbuf o = { 0 };
    const char *bp = strstr(text, begin), *ep = bp ? strstr(bp, end) : NULL;
    if (bp && ep) strbuf_printf(&o, "%.*s%s\n%s%s", (int)(bp - text), text, begin, content, ep);
    else strbuf_printf(&o, "%s\n%s\n\n%s\n%s%s\n", text, heading, begin, content, end);
    return o.s;
}


/* The hard-case bounds of every pack (bounds.txt, else the built-in table),
 * a row per scenes/hard case, with the reasons where a pack has none. */
static void bounds_md(bench *b, strbuf *o) {
    char dir[PATH_LEN + 16];
    bench_fmt(dir, sizeof dir, "%s/scenes/hard", b->root);
    char *cases[128];
    int nc = 0;
    DIR *d = opendir(dir);
    struct dirent *e;
    while (d && (e = readdir(d)) && nc < 128) {
        size_t len = strlen(e->d_name);
        if (len > 5 && strcmp(e->d_name + len - 5, ".glib") == 0) cases[nc++] = mem_strndup(e->d_name, len - 5);
    }
    if (d) closedir(d);
    qsort(cases, (size_t)nc, sizeof *cases, cmp_str_ptr);
    packset_name packs[PACKSET_MAX];
    int np = packset_list(b->root, packs, PACKSET_MAX);
    packset_bounds pb[PACKSET_MAX];
    for (int p = 0; p < np; p++) packset_bounds_load(b->root, packs[p], &pb[p], NULL, 0);
    strbuf_printf(o, "RMSE (linear RGB) that tests/test_hard_cases.c allows, 96x54 at t = 1 s: from each pack's "
                 "bounds.txt, else (*in italics*) the built-in table of viewer/scene/packset.c. Written by `tarn bench "
                 "--docs` from the files as they were then.\n\n| case |");
    for (int p = 0; p < np; p++) strbuf_printf(o, " %s |", packs[p]);
    strbuf_printf(o, "\n|---|");
    for (int p = 0; p < np; p++) strbuf_printf(o, "---:|");
    strbuf_printf(o, "\n");
    strbuf notes = { 0 };
    int nnotes = 0;
    for (int c = 0; c < nc; c++) {
        strbuf_printf(o, "| %s |", cases[c]);
        for (int p = 0; p < np; p++) {
            const char *from = NULL;
            const packset_bound *bd = packset_bound_resolve(&pb[p], cases[c], &from);
            bool builtin = from && strcmp(from, "built-in") == 0;
            if (!bd) {
                strbuf_printf(o, " – |");
            } else if (bd->max_rmse >= 0) {
                strbuf_printf(o, builtin ? " *%.3g* |" : " %.3g |", bd->max_rmse);
            } else {
                nnotes++;
                strbuf_printf(o, builtin ? " *none* (%d) |" : " none (%d) |", nnotes);
                strbuf_printf(&notes, "%d. %s, %s: %s\n", nnotes, packs[p], cases[c],
                          bd->why[0] ? bd->why : "(no reason given)");
            }
        }
        strbuf_printf(o, "\n");
    }
    if (notes.s) strbuf_printf(o, "\nWhere a pack holds no bound:\n\n%s", notes.s);
    free(notes.s);
    for (int p = 0; p < np; p++) packset_bounds_free(&pb[p]);
    for (int c = 0; c < nc; c++) free(cases[c]);
}

/* Writes the report and the bounds between their markers in the docs page
 * (adding the sections when the page has no markers), the plots beside it. */
static bool write_docs(bench *b, const char *path) {
    strbuf gen = { 0 };
    char dir[PATH_LEN];
    snprintf(dir, sizeof dir, "%s", path);
    char *slash = strrchr(dir, '/');
    if (slash) *slash = '\0';
    else snprintf(dir, sizeof dir, ".");
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    char prefix[256];
    snprintf(prefix, sizeof prefix, "%.*s-", (int)(strcspn(base, ".")), base);
    report_md(b, &gen, prefix);
    for (int sc = 0; sc < b->o.nscenes; sc++) {
        char st[256], pp[PATH_LEN + 300];
        stem(b->scene_abs[sc], st, sizeof st);
        bench_fmt(pp, sizeof pp, "%s/%splot-%s.png", dir, prefix, st);
        write_plot(b, sc, 0, pp);
        bench_fmt(pp, sizeof pp, "%s/%splot-%s-flip.png", dir, prefix, st);
        write_plot(b, sc, 1, pp);
    }
    char why[MSG_MAX];
    file_text_opts o = { .max_bytes = 1 << 20 };
    char *old = file_read_text(path, &o, NULL, why, sizeof why);   /* none yet: a new page */
    strbuf bounds = { 0 };
    bounds_md(b, &bounds);
    char *mid = replace_section(old ? old : "# Benchmark\n", "<!-- bench:begin -->", "<!-- bench:end -->",
                                "## Latest results", gen.s ? gen.s : "");
    char *page = mid ? replace_section(mid, "<!-- bounds:begin -->", "<!-- bounds:end -->", "## Hard-case bounds",
                                       bounds.s ? bounds.s : "")
                     : NULL;
    bool ok = page && write_text(path, page);
    free(page);
    free(mid);
    free(bounds.s);
    free(gen.s);
    free(old);
    return ok;
}


bool bench_write_results(bench *b, strbuf *md) {
    char path[PATH_LEN + 64];
    snprintf(path, sizeof path, "%s/bench.csv", b->o.out);
    bool ok = bench_write_csv(b, path);
    snprintf(path, sizeof path, "%s/passes.csv", b->o.out);
    ok &= bench_write_passes_csv(b, path);
    snprintf(path, sizeof path, "%s/bench.json", b->o.out);
    ok &= bench_write_json(b, path);
    strbuf_printf(md, "# tarn bench\n\n");
    report_md(b, md, "");
    snprintf(path, sizeof path, "%s/report.md", b->o.out);
    ok &= md->s && write_text(path, md->s);
    for (int sc = 0; sc < b->o.nscenes; sc++) {
        char st[256];
        stem(b->scene_abs[sc], st, sizeof st);
        snprintf(path, sizeof path, "%s/plot-%s.png", b->o.out, st);
        ok &= write_plot(b, sc, 0, path);
        snprintf(path, sizeof path, "%s/plot-%s-flip.png", b->o.out, st);
        ok &= write_plot(b, sc, 1, path);
    }
    if (!ok) fprintf(stderr, "tarn bench: cannot write the results in %s\n", b->o.out);
    if (b->o.docs && !write_docs(b, b->o.docs)) {
        fprintf(stderr, "tarn bench: cannot write %s\n", b->o.docs);
        ok = false;
    }
    return ok;
}
