/* test_contract: the table of uniforms tarn sets (viewer/scene/contract.h)
 * agrees with the wave set ref_waves_uniforms uploads and with
 * docs/packs/contract.md, and its lookups say what the renderer skips. */
#include "check.h"
#include "contract.h"
#include "file.h"
#include "ref_waves.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The wave rows are exactly the names ref_waves_uniforms gives. */
static void test_wave_rows_are_ref_waves_uniforms(void) {
    ref_waves calm;
    ref_waves_uniform u[REF_WAVES_UNIFORMS_MAX];
    ref_waves_init(&calm, NULL, NULL, 0);
    int n = ref_waves_uniforms(&calm, u, REF_WAVES_UNIFORMS_MAX);
    for (int i = 0; i < n; i++) {
        const contract_uniform *c = contract_find(u[i].name);
        CHECK_MSG(c && c->source == CONTRACT_WAVES, "%s is not a wave row", u[i].name);
    }
    int rows = 0, nwaves = 0;
    const contract_uniform *t = contract_uniforms(&rows);
    for (int i = 0; i < rows; i++)
        nwaves += t[i].source == CONTRACT_WAVES;
    CHECK_MSG(nwaves == n, "%d wave rows, %d wave uniforms", nwaves, n);
}

/* Every row has a type, a setter and a meaning, and a name used once. */
static void test_rows_are_complete(void) {
    int rows = 0;
    const contract_uniform *t = contract_uniforms(&rows);
    CHECK_GT(rows, 40);
    for (int i = 0; i < rows; i++) {
        CHECK_MSG(t[i].type && t[i].type[0] && t[i].set_by && t[i].set_by[0] && t[i].meaning &&
                  t[i].meaning[0], "row %s", t[i].name);
        CHECK_MSG(contract_find(t[i].name) == &t[i], "%s is listed twice", t[i].name);
    }
}

static void test_lookups(void) {
    CHECK(contract_is_camera_uniform("uCamMainVP") && contract_is_camera_uniform("uTargetSize"));
    CHECK(contract_is_camera_uniform("uPointGrid") && contract_is_camera_uniform("uCamLightHalfSize"));
    CHECK(!contract_is_camera_uniform("uSunDir") && !contract_is_camera_uniform("uSineAmp"));
    CHECK(contract_is_world_uniform("uSunDir") && contract_is_world_uniform("uNoiseSeed"));
    CHECK(contract_is_world_uniform("uCamMirrorInvVP"));
    /* a pack's own names are its own (caustic_tex's uSineWave), as are glman's */
    CHECK(!contract_is_world_uniform("uSineWave") && !contract_is_world_uniform("Timer"));
    CHECK(!contract_find(NULL) && !contract_find(""));
}

/* docs/packs/contract.md names every uniform of the table, as `name`. */
static void test_docs_name_every_uniform(void) {
    char err[256];
    size_t len = 0;
    char *doc = file_read(TARN_SOURCE_DIR "/docs/packs/contract.md", 1 << 20, &len, err, sizeof err);
    CHECK_MSG(doc != NULL, "%s", err);
    if (!doc)
        return;
    int rows = 0;
    const contract_uniform *t = contract_uniforms(&rows);
    for (int i = 0; i < rows; i++) {
        char quoted[80];
        snprintf(quoted, sizeof quoted, "`%s`", t[i].name);
        CHECK_MSG(strstr(doc, quoted) != NULL, "docs/packs/contract.md does not name %s", quoted);
    }
    free(doc);
}

int main(void) {
    RUN(test_wave_rows_are_ref_waves_uniforms);
    RUN(test_rows_are_complete);
    RUN(test_lookups);
    RUN(test_docs_name_every_uniform);
    return check_summary();
}
