/* fuzz_preset: libFuzzer target for preset files (unif_preset_load_ex),
 * loaded into the uniform model of a fixed two-Program glib.
 *
 * Invariants beyond "no crash, no report, no leak": a preset that does not
 * load changes nothing (every entry byte for byte as before); one that
 * loads leaves sliders inside their ranges, and saving it and loading the
 * saved file again gives the same values. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_util.h"
#include "glib.h"
#include "unif.h"

static const char fixture[] =
    "##OpenGL GLIB\n"
    "Vertex water.vert\nFragment water.frag\n"
    "Define FOAM <true>\nDefine STEPS <1 8 32>\n"
    "Program Water uA <0. .5 1.> uN <0 3 10> uOn <true> uCol {0.2 0.4 0.6} uRGBA {1 1 1 1} uFix 5 uArr [1 2 3]\n"
    "Program Sky uSun <-1. 0.2 1.> uTint {1 0.9 0.8}\n";

static glib_scene *scene;

int LLVMFuzzerInitialize(int *argc, char ***argv) {
    (void)argc; (void)argv;
    fuzz_scratch("tarn-fuzz-preset");
    scene = glib_parse(fixture, sizeof fixture - 1, fuzz_path("s.glib"));
    return 0;
}

static void check(bool ok, const char *what) {
    if (!ok) { fprintf(stderr, "fuzz_preset: invariant broken: %s\n", what); abort(); }
}

/* The sets a renderer would have: from the glib, typed as the shaders declare. */
static int make_sets(unif_set sets[2]) {
    int n = 0;
    memset(sets, 0, 2 * sizeof *sets);
    for (int i = 0; i < scene->ncmds && n < 2; i++) {
        const glib_cmd *c = &scene->cmds[i];
        if (c->kind != GLIB_CMD_PROGRAM) continue;
        unif_set *s = &sets[n++];
        glib_unif_set(s, c, NULL);
        snprintf(s->program, sizeof s->program, "%s", c->name);
        static const struct { const char *name; unif_type t; int len; } decl[] = {
            { "uA", UNIF_FLOAT, 1 }, { "uN", UNIF_INT, 1 }, { "uOn", UNIF_BOOL, 1 },
            { "uCol", UNIF_VEC3, 1 }, { "uRGBA", UNIF_VEC4, 1 }, { "uFix", UNIF_FLOAT, 1 },
            { "uArr", UNIF_FLOAT, 3 }, { "uSun", UNIF_FLOAT, 1 }, { "uTint", UNIF_VEC3, 1 },
            { "uExtra", UNIF_VEC2, 1 },
        };
        for (size_t k = 0; k < sizeof decl / sizeof decl[0]; k++)
            if (unif_find(s, decl[k].name) || strcmp(decl[k].name, "uExtra") == 0)
                unif_set_shader_type(s, decl[k].name, decl[k].t, decl[k].len, (int)k);
    }
    return n;
}

static void free_sets(unif_set *sets, int n) {
    for (int i = 0; i < n; i++) unif_set_free(&sets[i]);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (!scene) LLVMFuzzerInitialize(NULL, NULL);
    unif_set sets[2], before[2];
    int n = make_sets(sets);
    make_sets(before);
    fuzz_write("p.preset", data, size);
    char err[4096];
    bool changed = false;
    bool ok = unif_preset_load_ex(sets, n, fuzz_path("p.preset"), err, sizeof err, &changed);
    if (!ok) {
        check(err[0] != '\0', "a failed load says why");
        for (int s = 0; s < n; s++) {
            check(sets[s].n == before[s].n, "a failed load adds nothing");
            for (int i = 0; i < sets[s].n; i++)
                check(memcmp(sets[s].entries[i].value, before[s].entries[i].value,
                             sizeof sets[s].entries[i].value) == 0, "a failed load changes nothing");
        }
    } else {
        for (int s = 0; s < n; s++)
            for (int i = 0; i < sets[s].n; i++) {
                const unif_entry *e = &sets[s].entries[i];
                for (int k = 0; k < e->ncomp; k++) check(isfinite(e->value[k]), "values finite");
                if (e->widget == UNIF_WIDGET_SLIDER)
                    check(e->value[0] >= e->min && e->value[0] <= e->max, "slider value in range");
            }
        check(unif_preset_save(sets, n, fuzz_path("q.preset"), err, sizeof err), "a loaded preset saves");
        unif_set again[2];
        make_sets(again);
        check(unif_preset_load(again, n, fuzz_path("q.preset"), err, sizeof err), "a saved preset loads");
        for (int s = 0; s < n; s++)
            for (int i = 0; i < sets[s].n; i++)
                if (sets[s].entries[i].widget != UNIF_WIDGET_NONE)
                    check(memcmp(sets[s].entries[i].value, again[s].entries[i].value,
                                 sizeof sets[s].entries[i].value) == 0, "save then load round-trips");
        free_sets(again, n);
    }
    free_sets(sets, n);
    free_sets(before, n);
    return 0;
}
