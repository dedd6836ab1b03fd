/* test_bench: what `tarn bench` and the hard-case test are built from —
 * bench.txt and bounds.txt (packset), the Pareto front and the plot — and
 * `tarn bench` end to end on a probe pack in a scratch tree: settings with
 * uniform, Define and scene assignments, a `buffer` line, the cost floor,
 * CSV, JSON, Markdown, the plot, the docs section, and the reference cache
 * on a second run. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bench.h"
#include "check.h"
#include "cli.h"
#include "cmd.h"
#include "image_io.h"
#include "packset.h"
#include "plot.h"

#ifndef TARN_SOURCE_DIR
#define TARN_SOURCE_DIR "."
#endif

static char tmpdir[256];

static const char *tmp(const char *name) {
    static char buf[8][768];
    static int k;
    k = (k + 1) % 8;
    snprintf(buf[k], sizeof buf[k], "%s/%s", tmpdir, name);
    return buf[k];
}

static void write_file(const char *path, const char *text) {
    FILE *f = fopen(path, "w");
    CHECK_MSG(f != NULL, "cannot write %s", path);
    if (!f) return;
    fputs(text, f);
    fclose(f);
}

static char *read_file(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char *buf = calloc(1, 1 << 20);
    if (buf) fread(buf, 1, (1 << 20) - 1, f);
    fclose(f);
    return buf;
}

/* ---- bench.txt ---- */

static void test_bench_txt(void) {
    const char *text =
        "# a comment\n"
        "colour #1f77b4   # the pack's colour\n"
        "\n"
        "fast   Water.STEPS=8  Water.uTint=0.1,0.2,0.3   # a define and a colour\n"
        "exact  *.EXACT=true   scene.WaterMesh=64\n"
        "plain\n"
        "buffer fresnel  Water.DEBUG=3\n"
        "buffer refract_hit Water.DEBUG=1\n";
    packset_bench b;
    char err[1024] = "";
    CHECK_MSG(packset_bench_parse(text, "t/bench.txt", &b, err, sizeof err), "%s", err);
    CHECK_EQ(b.n, 3);
    CHECK(b.has_colour && fabsf(b.colour[0] - 0x1f / 255.0f) < 1e-6f && fabsf(b.colour[2] - 0xb4 / 255.0f) < 1e-6f);
    if (b.n == 3) {
        CHECK(strcmp(b.settings[0].name, "fast") == 0 && b.settings[0].nassign == 2 && b.settings[0].line == 4);
        CHECK_STR_EQ(b.settings[0].assign[0].program, "Water");
        CHECK(strcmp(b.settings[0].assign[0].name, "STEPS") == 0 && b.settings[0].assign[0].value[0] == 8);
        CHECK(b.settings[0].assign[1].nvalue == 3 && fabsf(b.settings[0].assign[1].value[2] - 0.3f) < 1e-7f);
        CHECK(strcmp(b.settings[1].assign[0].program, "*") == 0 && b.settings[1].assign[0].value[0] == 1);
        CHECK_STR_EQ(b.settings[1].assign[1].program, "scene");
        CHECK_EQ(b.settings[2].nassign, 0);
        char lines[256];
        CHECK_GT(packset_scene_lines(&b.settings[1], lines, sizeof lines), 0);
        CHECK_STR_EQ(lines, "WaterMesh 64\n");
        CHECK(packset_scene_lines(&b.settings[0], lines, sizeof lines) == 0 && lines[0] == '\0');
    }
    CHECK_EQ(b.nbuffers, 2);
    if (b.nbuffers == 2) {
        CHECK(strcmp(b.buffers[0].name, "fresnel") == 0 && b.buffers[0].how.assign[0].value[0] == 3);
        CHECK_STR_EQ(b.buffers[1].name, "refract_hit");
    }
    packset_bench_free(&b);

    /* bad lines: file:line messages, the good lines kept */
    err[0] = '\0';
    CHECK(!packset_bench_parse("good Water.a=1\nbad Water.a\nbad2 Water.a=x\ngood Water.a=2\nbuffer nope W.a=1\n"
                               "colour red\n",
                               "t/bench.txt", &b, err, sizeof err));
    CHECK_EQ(b.n, 1);
    CHECK_STR_CONTAINS(err, "t/bench.txt:2: 'Water.a' is not PROGRAM.ENTRY=VALUE");
    CHECK_STR_CONTAINS(err, "t/bench.txt:3: 'Water.a=x': 'x' is not a number");
    CHECK_STR_CONTAINS(err, "t/bench.txt:4: setting 'good' is written twice");
    CHECK_STR_CONTAINS(err, "t/bench.txt:5: buffer wants one of");
    CHECK_STR_CONTAINS(err, "t/bench.txt:6: colour wants #RRGGBB");
    packset_bench_free(&b);

    /* nothing (or no file): one setting, "default" */
    CHECK(packset_bench_parse("# only comments\n", "x", &b, NULL, 0));
    CHECK(b.n == 1 && strcmp(b.settings[0].name, "default") == 0 && b.settings[0].nassign == 0);
    packset_bench_free(&b);
    CHECK(packset_bench_load(tmpdir, "absent", &b, NULL, 0));
    CHECK(b.n == 1 && strcmp(b.settings[0].name, "default") == 0 && b.path[0] == '\0');
    packset_bench_free(&b);
}

/* ---- applying a setting ---- */

static void test_apply(void) {
    unif_entry e[3];
    memset(e, 0, sizeof e);
    snprintf(e[0].name, sizeof e[0].name, "uOpacity");
    e[0].type = UNIF_FLOAT;
    e[0].widget = UNIF_WIDGET_SLIDER;
    e[0].ncomp = 1;
    e[0].min = 0;
    e[0].max = 1;
    e[0].value[0] = e[0].def[0] = 0.5f;
    snprintf(e[1].name, sizeof e[1].name, "EXACT");
    e[1].type = UNIF_BOOL;
    e[1].widget = UNIF_WIDGET_CHECKBOX;
    e[1].ncomp = 1;
    e[1].is_define = true;
    e[1].value[0] = e[1].def[0] = 1;
    snprintf(e[2].name, sizeof e[2].name, "uTint");
    e[2].type = UNIF_VEC3;
    e[2].widget = UNIF_WIDGET_COLOR;
    e[2].ncomp = 3;
    unif_set set = { .entries = e, .n = 3, .cap = 3 };
    snprintf(set.program, sizeof set.program, "Water");

    packset_bench b;
    char err[1024] = "";
    CHECK(packset_bench_parse("a Water.uOpacity=0.25 *.EXACT=0 Water.uTint=0.5\n"
                              "b Water.uOpacity=2\n"
                              "c Other.x=1 Water.nope=1 scene.WaterMesh=32\n",
                              "t", &b, err, sizeof err));
    bool defines = false;
    err[0] = '\0';
    CHECK_MSG(packset_apply(&set, 1, &b.settings[0], &defines, err, sizeof err), "%s", err);
    CHECK(e[0].value[0] == 0.25f && e[1].value[0] == 0 && defines);
    CHECK(e[2].value[0] == 0.5f && e[2].value[1] == 0.5f && e[2].value[2] == 0.5f);   /* grey */
    err[0] = '\0';
    CHECK(!packset_apply(&set, 1, &b.settings[1], &defines, err, sizeof err));
    CHECK(e[0].value[0] == 1.0f && !defines);   /* clamped to the slider, and said so */
    CHECK_STR_CONTAINS(err, "Water.uOpacity[0] = 2 is out of its range; it is 1");
    err[0] = '\0';
    CHECK(!packset_apply(&set, 1, &b.settings[2], &defines, err, sizeof err));
    CHECK_STR_CONTAINS(err, "setting 'c': no Program 'Other'");
    CHECK_STR_CONTAINS(err, "setting 'c': no entry 'nope' in Water");
    packset_bench_free(&b);
}

/* ---- bounds.txt ---- */

static void test_bounds(void) {
    packset_bounds b;
    char err[512] = "";
    CHECK(packset_bounds_parse("# case  rmse  why\n*  0.2\nunderwater none  no refraction from below\n"
                               "grazing 0.05\n",
                               "p/bounds.txt", &b, err, sizeof err));
    CHECK(b.found && b.n == 3);
    const packset_bound *x = packset_bound_for(&b, "underwater");
    CHECK(x && x->max_rmse < 0 && strcmp(x->why, "no refraction from below") == 0);
    x = packset_bound_for(&b, "grazing");
    CHECK(x && fabs(x->max_rmse - 0.05) < 1e-7);
    x = packset_bound_for(&b, "calm");
    CHECK(x && fabs(x->max_rmse - 0.2) < 1e-7 && strcmp(x->case_name, "*") == 0);
    packset_bounds_free(&b);
    err[0] = '\0';
    CHECK(!packset_bounds_parse("calm -1\nshore\n", "p/bounds.txt", &b, err, sizeof err));
    CHECK_STR_CONTAINS(err, "p/bounds.txt:1: '-1' is not a positive RMSE or 'none'");
    CHECK_STR_CONTAINS(err, "p/bounds.txt:2: a bound line is CASE MAX_RMSE|none [why]");
    CHECK_EQ(packset_bound_for(&b, "calm"), NULL);
    packset_bounds_free(&b);
    CHECK(packset_bounds_parse(NULL, "p/bounds.txt", &b, NULL, 0) && !b.found && b.n == 0);
    packset_bounds_free(&b);
}

/* ---- the Pareto front and the plot ---- */

static void test_pareto(void) {
    /* (time, error): 1 and 3 dominate 2; 4 ties 1 in time but is worse; 5 is NaN */
    double x[] = { 1, 2, 3, 1, NAN, 0.5 }, y[] = { 0.5, 0.6, 0.1, 0.7, 0.01, 0.9 };
    bool on[6];
    plot_pareto(x, y, 6, on);
    CHECK(on[0] && !on[1] && on[2] && !on[3] && !on[4] && on[5]);
    double xs[] = { 1, 1 }, ys[] = { 0.2, 0.2 };   /* equal points do not dominate each other */
    plot_pareto(xs, ys, 2, on);
    CHECK(on[0] && on[1]);
}

/* With tolerances: a point only slightly faster or slightly better than
 * another ties with it (both stay), a clear improvement still dominates,
 * and noise within the tolerances cannot change the front. */
static void test_pareto_ties(void) {
    /* 0 and 1 differ by 5% in time and 0.5% in error: a tie; 2 is 3x slower
     * and worse: off; 3 is twice as slow and half the error: on */
    double x[] = { 10, 10.5, 30, 20 }, y[] = { 0.100, 0.1005, 0.2, 0.05 };
    double dx[4], dy[4];
    for (int i = 0; i < 4; i++) { dx[i] = 0.2 * x[i]; dy[i] = 0.01 * y[i]; }
    bool on[4];
    plot_pareto_ties(x, y, dx, dy, 4, on);
    CHECK(on[0] && on[1] && !on[2] && on[3]);
    plot_pareto(x, y, 4, on);                          /* without tolerances 1 falls off */
    CHECK(on[0] && !on[1]);
    /* a second "run" with every time moved by up to 10%: the same front */
    double x2[] = { 10.9, 9.6, 27.5, 21.8 };
    bool on2[4];
    plot_pareto_ties(x2, y, dx, dy, 4, on2);
    plot_pareto_ties(x, y, dx, dy, 4, on);
    for (int i = 0; i < 4; i++) CHECK_EQ(on[i], on2[i]);
}

/* The combined rule: errors tie within sqrt(u_i^2 + u_j^2), not u_i + u_j */
static void test_pareto_combined(void) {
    /* same time; errors 0.100 and 0.113 with u 0.01 each: sqrt(2) 0.01 = 0.0141 > 0.013, a tie;
     * 0.100 and 0.116: 0.016 > 0.0141, the worse one falls off (with the sum rule, 0.02, it stayed) */
    double x[] = { 10, 10 }, dx[] = { 0, 0 }, dy[] = { 0.01, 0.01 };
    bool on[2];
    double y1[] = { 0.100, 0.113 };
    plot_pareto_combined(x, y1, dx, dy, 2, on);
    CHECK(on[0] && on[1]);
    double y2[] = { 0.100, 0.116 };
    plot_pareto_combined(x, y2, dx, dy, 2, on);
    CHECK(on[0] && !on[1]);
    plot_pareto_ties(x, y2, dx, dy, 2, on);
    CHECK(on[0] && on[1]);
}

static bool has_colour(const img *im, const float rgb[3], double tol) {
    for (long i = 0; i < (long)im->w * im->h; i++) {
        const float *p = im->px + i * im->channels;
        if (fabs(p[0] - rgb[0]) < tol && fabs(p[1] - rgb[1]) < tol && fabs(p[2] - rgb[2]) < tol) return true;
    }
    return false;
}

static void test_plot(void) {
    img im;
    CHECK(img_alloc(&im, 40, 12, 3));
    const float white[3] = { 1, 1, 1 }, black[3] = { 0, 0, 0 };
    plot_fill(&im, white);
    CHECK_EQ(plot_text(&im, 1, 1, "Ag", 1, black), 2 * PLOT_GLYPH_W);
    CHECK(has_colour(&im, black, 1e-6));
    CHECK_EQ(plot_text_width("abc", 2), 3 * PLOT_GLYPH_W * 2);
    img_free(&im);

    plot_point a[] = { { 10, 0.2, "slow", false }, { 2, 0.3, "fast", true }, { 20, 0.05, "best", true } };
    plot_point b[] = { { 5, 0.4, "x", false }, { NAN, 0.1, "nan", false } };
    plot_series s[] = { { "one", { 0.8f, 0.1f, 0.1f }, a, 3 }, { "two", { 0.1f, 0.1f, 0.8f }, b, 2 } };
    plot_chart c = { .w = 500, .h = 320, .title = "t", .xlabel = "ms", .ylabel = "rmse", .series = s,
                     .nseries = 2, .floor_x = 0.5, .floor_label = "floor" };
    CHECK(plot_speed_error(&c, &im));
    CHECK(im.w == 500 && im.h == 320 && im.channels == 3);
    CHECK(has_colour(&im, s[0].rgb, 0.02) && has_colour(&im, s[1].rgb, 0.02));
    int bad = 0;
    for (long i = 0; i < (long)im.w * im.h * 3; i++) bad += !(im.px[i] >= 0 && im.px[i] <= 1);
    CHECK_EQ(bad, 0);
    char err[256];
    CHECK(img_write(tmp("plot.png"), &im, err, sizeof err));
    img_free(&im);
}

/* ---- packs on disk ---- */

static void make_probe_root(void) {
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "mkdir -p %s/root/packs/probe %s/root/packs/nopack %s/root/packs/common.x && "
             "ln -s %s/packs/common %s/root/packs/common",
             tmpdir, tmpdir, tmpdir, TARN_SOURCE_DIR, tmpdir);
    CHECK_EQ(system(cmd), 0);
    write_file(tmp("root/packs/probe/pack.glib"),
               "##OpenGL GLIB\n"
               "# a probe pack: the world, then a flat grey water surface\n"
               "World all\n"
               "Define   PROBE_OUT <0 0 1>\n"
               "Vertex   probe.vert\n"
               "Fragment probe.frag\n"
               "Program  Probe  uLevel <0. 0.5 1.>\n"
               "WaterSurface\n");
    write_file(tmp("root/packs/probe/probe.vert"),
               "#version 330 compatibility\n"
               "void main() { gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; }\n");
    write_file(tmp("root/packs/probe/probe.frag"),
               "#version 330 compatibility\n"
               "uniform float uLevel;\n"
               "out vec4 fragColor;\n"
               "void main() {\n"
               "#if PROBE_OUT == 1\n"
               "    fragColor = vec4(0.25, 0.25, 0.25, 1.0);   // 'Fresnel'\n"
               "#else\n"
               "    fragColor = vec4(vec3(uLevel), 1.0);\n"
               "#endif\n"
               "}\n");
    write_file(tmp("root/packs/probe/bench.txt"),
               "colour #123456\n"
               "dark   Probe.uLevel=0.1\n"
               "light  Probe.uLevel=0.9  scene.WaterMesh=16\n"
               "buffer fresnel  Probe.PROBE_OUT=1\n");
    write_file(tmp("root/packs/nopack/readme"), "not a pack: no pack.glib\n");
}

static void test_pack_list(void) {
    packset_name names[8];
    int n = packset_list(tmp("root"), names, 8);
    CHECK(n == 1 && strcmp(names[0], "probe") == 0);   /* not common, not a dir without pack.glib */
    CHECK(packset_exists(tmp("root"), "probe"));
    CHECK(!packset_exists(tmp("root"), "nopack") && !packset_exists(tmp("root"), "../probe"));
    n = packset_list(TARN_SOURCE_DIR, names, 8);
    bool basic = false;
    for (int i = 0; i < n; i++) basic |= strcmp(names[i], "basic") == 0;
    CHECK(basic);
}

/* ref_cache NULL: the default cache, $XDG_CACHE_HOME/tarn/ref (main points
 * XDG_CACHE_HOME into the test's folder, never the user's cache). */
static int bench(const char *out, bool docs, const char *ref_cache, const char *msaa) {
    char docs_path[768], cache[768];
    snprintf(docs_path, sizeof docs_path, "%s", tmp("docs/benchmark.md"));
    snprintf(cache, sizeof cache, "%s", ref_cache ? ref_cache : "");
    const char *argv[24] = { TARN_SOURCE_DIR "/scenes/lake.glib", "--root", tmp("root"), "--size", "64x36",
                             "--times", "0.5,2", "--frames", "3", "--ref-caustic-res", "16", "--ref-photons", "1",
                             "--out", out, "--quiet" };
    int argc = 16;
    if (ref_cache) { argv[argc++] = "--ref-cache"; argv[argc++] = cache; }
    if (docs) { argv[argc++] = "--docs"; argv[argc++] = docs_path; }
    if (msaa) { argv[argc++] = "--msaa"; argv[argc++] = msaa; }
    return cmd_bench(argc, (char **)argv);
}

/* Files in dir whose name ends in suffix. */
static int count_files(const char *dir, const char *suffix) {
    DIR *d = opendir(dir);
    if (!d) return 0;
    int n = 0;
    size_t ls = strlen(suffix);
    for (struct dirent *e; (e = readdir(d));) {
        size_t l = strlen(e->d_name);
        n += l > ls && strcmp(e->d_name + l - ls, suffix) == 0;
    }
    closedir(d);
    return n;
}

static void test_bench_end_to_end(void) {
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "mkdir -p %s/docs", tmpdir);
    CHECK_EQ(system(cmd), 0);
    write_file(tmp("docs/benchmark.md"), "# Benchmark\n\nkept\n\n<!-- bench:begin -->\nold\n<!-- bench:end -->\n\ntail\n");
    int rc = bench(tmp("out"), true, NULL, "4");
    if (rc == TARN_EXIT_NO_GL) SKIP("no OpenGL context");
    CHECK_EQ(rc, TARN_EXIT_OK);

    char *csv = read_file(tmp("out/bench.csv"));
    CHECK_NE(csv, NULL);
    if (csv) {
        CHECK_EQ(strncmp(csv, "scene,pack,setting,time_s,width,height,frames,gpu_ms,wall_ms", 60), 0);
        CHECK_STR_CONTAINS(csv, "\"lake\",\"probe\",\"dark\",0.5,64,36,");
        CHECK_STR_CONTAINS(csv, "\"lake\",\"probe\",\"light\",2,64,36,");
        int lines = 0;
        for (char *p = csv; *p; p++) lines += *p == '\n';
        CHECK_EQ(lines, 1 + 2 * 2);
    }
    free(csv);
    char *json = read_file(tmp("out/bench.json"));
    CHECK_NE(json, NULL);
    if (json) {
        CHECK_STR_CONTAINS(json, "\"machine\": {\"cpu\": ");
        CHECK_STR_CONTAINS(json, "\"floor\": {\"gpu_ms\": ");
        CHECK_STR_CONTAINS(json, "\"setting\": \"light\", \"ok\": true");
        CHECK_STR_CONTAINS(json, "\"fresnel\": {\"median\": ");   /* the buffer line */
        CHECK_STR_CONTAINS(json, "\"references_rendered\": 2, \"references_cached\": 0");
        /* MSAA 4 is compared with a reference subsampled where the GL samples */
        CHECK_STR_CONTAINS(json, "\"msaa\": 4, \"reference_spp\": 1, \"reference_positions\": [[");
        CHECK(!strstr(json, ": nan") && !strstr(json, "NaN") && !strstr(json, "\"rmse\": null"));
        /* FLIP, SSIM, the uncertainty, the sequence, the timing's load and quartiles, both fronts */
        const char *finite_keys[] = { "water_flip", "flip", "water_ssim", "water_rmse_u", "water_rmse_u_noise",
                                      "water_rmse_u_grid", "water_flip_u", "wall_q1_ms", "wall_q3_ms",
                                      "seq_water_rmse", "temporal_rmse", "seq_ref_change_rms" };
        const char *summary = strstr(json, "\"summary\": [");
        for (size_t k = 0; summary && k < sizeof finite_keys / sizeof *finite_keys; k++) {
            char key[64];
            snprintf(key, sizeof key, "\"%s\": ", finite_keys[k]);
            const char *at = strstr(summary, key);
            CHECK_MSG(at != NULL, "no %s in the summary", key);
            if (!at) continue;
            double v = strtod(at + strlen(key), NULL);
            CHECK_MSG(isfinite(v) && strncmp(at + strlen(key), "null", 4) != 0, "%s is not finite", key);
        }
        CHECK_STR_CONTAINS(json, "\"pareto_flip\": ");
        CHECK_STR_CONTAINS(json, "\"load_before\": [");
        CHECK_STR_CONTAINS(json, "\"timing\": \"round-robin\"");
        CHECK_STR_CONTAINS(json, "\"sequence\": {\"frames\": 8, \"fps\": 30, \"width\": 32, \"height\": 18");
        /* the probe shows no irradiance buffer: its flat lighting is measured */
        CHECK_STR_CONTAINS(json, "\"irradiance_flat\": true");
        CHECK_STR_CONTAINS(json, "\"flat\": true}");
    }
    free(json);
    csv = read_file(tmp("out/bench.csv"));
    if (csv) {
        CHECK_STR_CONTAINS(csv, ",water_flip,flip,water_ssim,gpu_q1_ms,gpu_q3_ms,wall_q1_ms,wall_q3_ms,");
        CHECK_STR_CONTAINS(csv, ",temporal_rmse,");
    }
    free(csv);
    struct stat st0;
    CHECK(stat(tmp("out/plot-lake-flip.png"), &st0) == 0 && st0.st_size > 1000);
    CHECK_EQ(stat(tmp("out/img/lake.probe.dark.temporal.png"), &st0), 0);
    char *md = read_file(tmp("out/report.md"));
    CHECK_NE(md, NULL);
    if (md) {
        CHECK_STR_CONTAINS(md, "| probe | dark |");
        CHECK_STR_CONTAINS(md, "Cost floor (a full-screen pass with one texture fetch)");
        CHECK_STR_CONTAINS(md, "| load average (1, 5, 15 min) | before ");
        CHECK_STR_CONTAINS(md, "(flat) |");
        CHECK_STR_CONTAINS(md, "(plot-lake-flip.png)");
        CHECK_STR_CONTAINS(md, "Anti-aliasing: MSAA 4x; the reference takes 4 subsamples per pixel at the GL's MSAA "
                                   "sample positions, to match.");
    }
    free(md);
    char *page = read_file(tmp("docs/benchmark.md"));
    CHECK_NE(page, NULL);
    if (page) {
        CHECK_EQ(strncmp(page, "# Benchmark\n\nkept\n\n<!-- bench:begin -->\n", 40), 0);
        CHECK(!strstr(page, "\nold\n"));
        CHECK_STR_CONTAINS(page, "| probe | light |");
        CHECK_STR_CONTAINS(page, "(benchmark-plot-lake.png)");
        CHECK_STR_CONTAINS(page, "<!-- bench:end -->\n\ntail\n");
    }
    free(page);
    struct stat st;
    CHECK(stat(tmp("docs/benchmark-plot-lake.png"), &st) == 0 && st.st_size > 1000);
    CHECK_EQ(stat(tmp("out/scenes/lake.probe.light.glib"), &st), 0);   /* scene.WaterMesh=16 */
    CHECK_EQ(stat(tmp("out/passes.csv"), &st), 0);
    img plot;
    char err[512];
    CHECK_MSG(img_read(tmp("out/plot-lake.png"), &plot, err, sizeof err), "%s", err);
    if (plot.px) {
        const float rgb[3] = { 0x12 / 255.0f, 0x34 / 255.0f, 0x56 / 255.0f };   /* the pack's colour */
        CHECK(has_colour(&plot, rgb, 0.01));
        img_free(&plot);
    }

    /* the references went to the XDG cache, not the output folder */
    CHECK_GT(count_files(tmp("cache/tarn/ref"), ".exr"), 0);
    CHECK_NE(stat(tmp("out/ref"), &st), 0);

    /* again: the references come from the cache */
    CHECK_EQ(bench(tmp("out"), false, NULL, "4"), TARN_EXIT_OK);
    json = read_file(tmp("out/bench.json"));
    if (json) CHECK_STR_CONTAINS(json, "\"references_rendered\": 0, \"references_cached\": 2");
    free(json);

    /* --ref-cache DIR: an empty cache there, so rendered again, into DIR */
    CHECK_EQ(bench(tmp("out"), false, tmp("alt-cache"), "4"), TARN_EXIT_OK);
    json = read_file(tmp("out/bench.json"));
    if (json) CHECK_STR_CONTAINS(json, "\"references_rendered\": 2, \"references_cached\": 0");
    free(json);

    /* MSAA off: a 1 x 1 reference, which the 4-position ones in the cache are not */
    CHECK_EQ(bench(tmp("out"), false, tmp("alt-cache"), "0"), TARN_EXIT_OK);
    json = read_file(tmp("out/bench.json"));
    if (json) {
        CHECK_STR_CONTAINS(json, "\"msaa\": 1, \"reference_spp\": 1");
        CHECK_STR_CONTAINS(json, "\"references_rendered\": 2, \"references_cached\": 0");
    }
    free(json);
    md = read_file(tmp("out/report.md"));
    if (md) CHECK_STR_CONTAINS(md, "Anti-aliasing: off; the reference takes 1 x 1 subsamples per pixel, to match.");
    free(md);
    CHECK_GT(count_files(tmp("alt-cache"), ".exr"), 0);
}

static void test_usage(void) {
    const char *a1[] = { "--packs", "nosuchpack", "--root", tmp("root") };
    CHECK_EQ(cmd_bench(4, (char **)a1), TARN_EXIT_USAGE);
    const char *a2[] = { "--size", "12" };
    CHECK_EQ(cmd_bench(2, (char **)a2), TARN_EXIT_USAGE);
    const char *a3[] = { "--times", "1,x" };
    CHECK_EQ(cmd_bench(2, (char **)a3), TARN_EXIT_USAGE);
    const char *a4[] = { "no/such/scene.glib" };
    CHECK_EQ(cmd_bench(1, (char **)a4), TARN_EXIT_USAGE);
    const char *a5[] = { "--help" };
    CHECK_EQ(cmd_bench(1, (char **)a5), TARN_EXIT_OK);
}

int main(void) {
    snprintf(tmpdir, sizeof tmpdir, "/tmp/tarn-test-bench-XXXXXX");
    if (!mkdtemp(tmpdir)) { perror("mkdtemp"); return 1; }
    /* bench caches references in $XDG_CACHE_HOME/tarn: the test's own, not the user's */
    setenv("XDG_CACHE_HOME", tmp("cache"), 1);
    make_probe_root();
    RUN(test_bench_txt);
    RUN(test_apply);
    RUN(test_bounds);
    RUN(test_pareto);
    RUN(test_pareto_ties);
    RUN(test_pareto_combined);
    RUN(test_plot);
    RUN(test_pack_list);
    RUN(test_usage);
    RUN(test_bench_end_to_end);
    char cmd[512];
    snprintf(cmd, sizeof cmd, "%s", getenv("KEEP") ? "true" : "rm -rf "); strcat(cmd, tmpdir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", tmpdir);
    return check_summary();
}
