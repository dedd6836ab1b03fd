/* fuzz_glib: libFuzzer target for the .glib parser and what consumes its
 * output without OpenGL: glib_parse on the bytes (Include resolved next to
 * a scratch file, where fixture files wait), the uniform model built from
 * every Program (glib_unif_set, typed as a shader might declare it,
 * merged as a reload does), and the world model (scene_from_glib,
 * ref_world_init). A text that names a pack also goes through glib_load_opts
 * with a packs directory.
 *
 * Invariants checked beyond "no crash, no sanitizer report, no leak":
 * diagnostics are capped and counted, every command and diagnostic points
 * into the scene's files, a uniform model's ranges are finite and ordered.
 *
 * Built with libFuzzer when TARN_FUZZ is on (tests/fuzz/fuzz.cmake); in a
 * normal build replay_main.c replays the corpus and the regressions. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_util.h"
#include "glib.h"
#include "ref_scene.h"
#include "scene.h"
#include "unif.h"

static FILE *devnull;

int LLVMFuzzerInitialize(int *argc, char ***argv) {
    (void)argc; (void)argv;
    fuzz_scratch("tarn-fuzz-glib");
    devnull = fopen("/dev/null", "w");
    /* files the fuzzed text may name (the seeds do) */
    fuzz_write_text("inc.glib", "##OpenGL GLIB\nLookAt 0 0 3  0 0 0  0 1 0\nSphere 1\n");
    fuzz_write_text("self.glib", "Include self.glib\n");
    fuzz_write_text("a.glib", "Include b.glib\n");
    fuzz_write_text("b.glib", "Include a.glib\n");
    fuzz_write_text("water.vert", "#version 330 compatibility\nvoid main() { gl_Position = ftransform(); }\n");
    fuzz_write_text("water.frag", "#version 330 compatibility\nout vec4 c;\nvoid main() { c = vec4(1.); }\n");
    fuzz_write_text("tex.bmp", "BM not really");
    fuzz_write_text("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    fuzz_mkdir("sub");
    fuzz_write_text("sub/up.glib", "Include ../inc.glib\nVertex ../water.vert\n");
    fuzz_mkdir("packs");
    fuzz_mkdir("packs/p");
    fuzz_write_text("packs/p/pack.glib", "Vertex ../../water.vert\nFragment ../../water.frag\n"
                                         "Program Water uA <0. .5 1.>\nWaterSurface\n");
    return 0;
}

static void check(bool ok, const char *what) {
    if (!ok) { fprintf(stderr, "fuzz_glib: invariant broken: %s\n", what); abort(); }
}

static bool points_into_files(const glib_scene *g, const char *f) {
    if (!f) return false;
    for (int i = 0; i < g->nfiles; i++)
        if (g->files[i] == f) return true;
    return false;
}

/* A diagnostic keeps its own copy of the file name: one of the files read. */
static bool names_a_file(const glib_scene *g, const char *f) {
    for (int i = 0; i < g->nfiles; i++)
        if (strcmp(g->files[i], f) == 0) return true;
    return false;
}

static unif_type type_for(const char *name, int salt) {
    unsigned h = 2166136261u;
    for (const char *p = name; *p; p++) h = (h ^ (unsigned char)*p) * 16777619u;
    h ^= (unsigned)salt * 2654435761u;
    return (unif_type)(UNIF_FLOAT + (int)(h % (UNIF_TYPE_UNKNOWN - UNIF_FLOAT + 1)));
}

static void exercise_set(unif_set *set, int salt) {
    for (int i = 0; i < set->n; i++) {
        unif_entry *e = &set->entries[i];
        check(e->ncomp >= 0 && e->ncomp <= UNIF_MAX_COMPONENTS, "ncomp in range");
        if (e->widget == UNIF_WIDGET_SLIDER) check(isfinite(e->min) && isfinite(e->max) && e->min <= e->max,
                                                   "slider range finite and ordered");
        char text[256];
        if (e->is_define) { unif_define_value(e, text, sizeof text); continue; }
        char name[UNIF_NAME_MAX];
        snprintf(name, sizeof name, "%s", e->name);
        int len = 1 + (salt + i) % 3;
        unif_entry *t = unif_set_shader_type(set, name, type_for(name, salt), len, i);
        if (!t) continue;
        (void)unif_type_mismatch(t);
        unif_describe_mismatch(t, text, sizeof text);
        (void)unif_uploadable(t);
        unif_set_component(t, 0, 0.5);
        unif_set_component(t, t->ncomp - 1, -1e30);
        (void)unif_is_default(t);
    }
    (void)unif_reset_all_ex(set);
}

static void exercise(const glib_scene *g) {
    check(g->ndiags <= 200, "diagnostics capped");
    int nerr = 0;
    for (int i = 0; i < g->ndiags; i++) {
        check(names_a_file(g, g->diags[i].file), "diag names one of the files read");
        check(g->diags[i].line >= 0, "diag line >= 0");
        if (g->diags[i].severity == DIAG_ERROR) nerr++;
    }
    check(nerr <= g->nerrors, "nerrors counts the error diagnostics");
    if (devnull) glib_print_diags(g, devnull);
    for (int i = 0; i < g->ncmds; i++) {
        const glib_cmd *c = &g->cmds[i];
        check(c->kind > GLIB_CMD_NONE && c->kind < GLIB_CMD_KIND_COUNT, "command kind");
        check(points_into_files(g, c->file), "command file points into files");
        check(c->nnum >= 0 && c->nnum <= GLIB_MAX_NUMS, "nnum in range");
        (void)glib_cmd_name(c->kind);
        if (c->kind != GLIB_CMD_PROGRAM) continue;
        diag_list said = {0};
        unif_set old = {0}, fresh = {0};
        glib_unif_set(&old, c, &said);
        exercise_set(&old, i);
        glib_unif_set(&fresh, c, &said);
        unif_merge(&fresh, &old);          /* what a reload does */
        exercise_set(&fresh, i + 1);
        unif_merge(&fresh, &old);
        unif_set_free(&old);
        unif_set_free(&fresh);
        diag_list_free(&said);
    }
    ref_world_desc world;
    scene_camera cam;
    bool has_world = false;
    diag_list repairs = {0};
    scene_from_glib(g, &world, &cam, &has_world, &repairs);
    check(repairs.nwarnings == repairs.n, "the world's repairs are warnings");
    diag_list_free(&repairs);
    if (has_world) {
        static ref_world w;
        ref_world_init(&w, &world);
        double rgb[3], n[3], dir[3] = { 0, 1, 0 };
        (void)ref_terrain_height(&w, 0.5, -0.25);
        ref_terrain_normal_at(&w, 1, 1, n);
        ref_sky_radiance(&w, dir, rgb);
        ref_world_release(&w);   /* a WaveOcean's spectra live on the heap */
    }
}

static bool names_a_pack(const uint8_t *data, size_t size) {
    for (size_t i = 0; i + 4 <= size; i++)
        if ((data[i] | 32) == 'p' && (data[i + 1] | 32) == 'a' && (data[i + 2] | 32) == 'c' &&
            (data[i + 3] | 32) == 'k')
            return true;
    return false;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (!fuzz_dir[0]) LLVMFuzzerInitialize(NULL, NULL);
    glib_scene *g = glib_parse((const char *)data, size, fuzz_path("fuzz.glib"));
    check(g != NULL, "glib_parse returns a scene");
    exercise(g);
    glib_free(g);
    if (names_a_pack(data, size)) {
        fuzz_write("top.glib", data, size);
        glib_options opt = { .packs_dir = fuzz_path("packs"), .pack_override = (size & 1) ? "p" : NULL };
        g = glib_load_opts(fuzz_path("top.glib"), &opt);
        exercise(g);
        glib_free(g);
    }
    return 0;
}
