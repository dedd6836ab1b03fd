/* test_contract: the table of uniforms tarn sets (viewer/scene/contract.h)
 * agrees with the wave set ref_waves_uniforms uploads and with
 * docs/packs/contract.md, and its lookups say what the renderer skips. */
#include "check.h"
#include "contract.h"
#include "file.h"
#include "ref_waves.h"
#include "strbuf.h"

#include <ctype.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A row's GLSL declaration as contract.glsl writes it: "float[8]" is
 * "float NAME[8]". */
static void declaration(const contract_uniform *c, char *out, size_t len) {
    const char *br = strchr(c->type, '[');
    if (br)
        snprintf(out, len, "uniform %.*s %s%s;", (int)(br - c->type), c->type, c->name, br);
    else
        snprintf(out, len, "uniform %s %s;", c->type, c->name);
}

/* The rows packs/common/contract.glsl declares: every camera, pass and
 * world row but those of the ocean's module (its samplers), of tarn's own
 * world program and loops.glsl's uLoopZero; of the wave rows, the water
 * level (world.glsl and waves.glsl both read it). */
static bool in_contract_glsl(const contract_uniform *c) {
    static const char *const not_there[] = { "uOceanA", "uOceanB", "uOceanFoam", "uWorldAlbedo", "uWorldMode",
                                             "uWorldClip", "uLoopZero" };
    if (c->source == CONTRACT_WAVES) return strcmp(c->name, "uWaterLevel") == 0;
    for (size_t i = 0; i < sizeof not_there / sizeof not_there[0]; i++)
        if (strcmp(c->name, not_there[i]) == 0) return false;
    return true;
}

static char *read_source(const char *rel) {
    char path[512], err[256];
    size_t len = 0;
    bool fits = snprintf(path, sizeof path, "%s/%s", TARN_SOURCE_DIR, rel) < (int)sizeof path;
    CHECK_MSG(fits, "the path of %s is longer than %zu bytes", rel, sizeof path);
    char *text = fits ? file_read(path, 1 << 20, &len, err, sizeof err) : NULL;
    CHECK_MSG(!fits || text != NULL, "%s", err);
    return text;
}

/* contract.glsl and its parts (contract_*.glsl, which the wave, world and
 * terrain modules include alone) declare each of its rows once, with the
 * table's type, and no uniform of their own. */
static void test_contract_glsl_is_the_table(void) {
    static const char *const parts[] = { "packs/common/contract.glsl", "packs/common/contract_water.glsl",
                                         "packs/common/contract_light.glsl",
                                         "packs/common/contract_terrain.glsl" };
    strbuf all = { 0 };
    for (size_t i = 0; i < sizeof parts / sizeof parts[0]; i++) {
        char *text = read_source(parts[i]);
        if (!text) {
            strbuf_free(&all);
            return;
        }
        strbuf_puts(&all, "\n");
        strbuf_puts(&all, text);
        free(text);
    }
    char *glsl = strbuf_take(&all);
    int rows = 0, want = 0;
    const contract_uniform *t = contract_uniforms(&rows);
    for (int i = 0; i < rows; i++) {
        char decl[128];
        declaration(&t[i], decl, sizeof decl);
        const char *at = strstr(glsl, decl);
        bool there = at && (at == glsl || at[-1] == '\n');
        if (in_contract_glsl(&t[i])) {
            want++;
            CHECK_MSG(there, "packs/common/contract.glsl lacks the line '%s'", decl);
        } else {
            CHECK_MSG(!there, "packs/common/contract.glsl declares '%s', which is not its", decl);
        }
    }
    int declared = 0;
    for (const char *p = glsl; (p = strstr(p, "\nuniform ")) != NULL; p++) declared++;
    CHECK_EQ(declared, want);
    free(glsl);
}

/* The contract uniform a shader line declares ("uniform T a, b;" any of
 * them), NULL if none. */
static const contract_uniform *declares_contract(const char *line) {
    if (strncmp(line, "uniform ", 8) != 0) return NULL;
    const char *p = line + 8;
    while (*p && !isspace((unsigned char)*p)) p++;          /* the type */
    while (*p && *p != ';' && *p != '\n') {
        while (*p == ' ' || *p == ',') p++;
        char name[64];
        size_t n = 0;
        while ((isalnum((unsigned char)*p) || *p == '_') && n + 1 < sizeof name) name[n++] = *p++;
        name[n] = 0;
        const contract_uniform *c = contract_find(name);
        if (c) return c;
        while (*p && *p != ',' && *p != ';' && *p != '\n') p++;
    }
    return NULL;
}

/* Who may declare a contract uniform besides contract.glsl: the wave
 * modules their wave rows (and the ocean its samplers), tarn's world
 * program its own, loops.glsl uLoopZero. */
static bool may_declare(const char *file, const contract_uniform *c) {
    const char *base = strrchr(file, '/') ? strrchr(file, '/') + 1 : file;
    if (strcmp(base, "loops.glsl") == 0) return strcmp(c->name, "uLoopZero") == 0;
    if (strncmp(base, "waves", 5) == 0) return !in_contract_glsl(c);
    if (strcmp(base, "world.frag") == 0 || strcmp(base, "world.vert") == 0)
        return strncmp(c->name, "uWorld", 6) == 0 && !in_contract_glsl(c);
    return false;
}

/* A `for` whose bound is a constant (a number or an upper-case macro)
 * not written ROLLED(...): on a CPU rasteriser the compiler unrolls it and
 * LLVM compiles every copy (loops.glsl). Xing's course files (xing_*,
 * rock.glsl) stay as glman ran them. */
static bool unrolled_constant_loop(const char *file, const char *text) {
    const char *base = strrchr(file, '/') ? strrchr(file, '/') + 1 : file;
    if (strncmp(base, "xing", 4) == 0 || strcmp(base, "rock.glsl") == 0) return false;
    char line[512];
    snprintf(line, sizeof line, "%.*s", (int)strcspn(text, "\n"), text);
    char *comment = strstr(line, "//");
    if (comment) *comment = 0;
    const char *f = strstr(line, "for (");
    const char *cond = f ? strchr(f, ';') : NULL;
    const char *op = cond ? strchr(cond, '<') : NULL;
    const char *end = op ? strchr(op, ';') : NULL;
    if (!end) return false;
    op += op[1] == '=' ? 2 : 1;
    while (*op == ' ') op++;
    if (strncmp(op, "ROLLED(", 7) == 0) return false;
    for (const char *p = op; p < end; p++)
        if (islower((unsigned char)*p)) return false;    /* a uniform or a variable: not a constant */
    return true;
}

static void check_shader_file(const char *rel, int *files) {
    char *text = read_source(rel);
    if (!text) return;
    (*files)++;
    int n = 1;
    for (const char *line = text; line && *line; line = strchr(line, '\n') ? strchr(line, '\n') + 1 : NULL, n++) {
        const contract_uniform *c = declares_contract(line);
        CHECK_MSG(!c || may_declare(rel, c), "%s declares %s again: #include \"contract.glsl\" instead", rel,
                  c ? c->name : "");
        CHECK_MSG(!unrolled_constant_loop(rel, line), "%s:%d: a loop with a constant bound: write it ROLLED(n) "
                  "(#include \"loops.glsl\")", rel, n);
    }
    free(text);
}

static bool is_shader(const char *name) {
    static const char *const ext[] = { ".frag", ".vert", ".geom", ".tesc", ".tese", ".glsl" };
    const char *dot = strrchr(name, '.');
    for (size_t i = 0; dot && i < sizeof ext / sizeof ext[0]; i++)
        if (strcmp(dot, ext[i]) == 0) return true;
    return false;
}

static void walk_packs(const char *rel, int *files) {
    char path[512];
    snprintf(path, sizeof path, "%s/%s", TARN_SOURCE_DIR, rel);
    DIR *d = opendir(path);
    CHECK_MSG(d != NULL, "cannot open %s", path);
    if (!d) return;
    for (struct dirent *e; (e = readdir(d)) != NULL;) {
        if (e->d_name[0] == '.') continue;
        char sub[512];
        snprintf(sub, sizeof sub, "%s/%s", rel, e->d_name);
        if (is_shader(e->d_name)) {
            if (strncmp(e->d_name, "contract", 8) != 0 || strcmp(rel, "packs/common") != 0)
                check_shader_file(sub, files);
        } else if (!strchr(e->d_name, '.')) {
            walk_packs(sub, files);
        }
    }
    closedir(d);
}

/* No shader of the packs declares a contract uniform of contract.glsl's
 * itself (a second declaration, with its own type, drifts from the table),
 * and every loop with a constant bound is ROLLED (loops.glsl). */
static void test_packs_take_the_contract_from_contract_glsl(void) {
    int files = 0;
    walk_packs("packs", &files);
    CHECK_GT(files, 30);
    CHECK(declares_contract("uniform mat4 uCamMirrorVP, uCamMirrorInvVP;") != NULL);
    CHECK(declares_contract("uniform float uMine, uTime;   // x") != NULL);
    CHECK(declares_contract("uniform float uTint;") == NULL);
    CHECK(unrolled_constant_loop("packs/x/a.frag", "    for (int i = 0; i < WAVES_MAX; i++) {\n"));
    CHECK(unrolled_constant_loop("packs/x/a.frag", "for (int j = -1; j <= 1; j++) s += 1.0;\n"));
    CHECK(unrolled_constant_loop("packs/x/a.frag", "for (int k = 0; k < REFRACT_REFINE + 2; k++) {\n"));
    CHECK(!unrolled_constant_loop("packs/x/a.frag", "    for (int i = 0; i < ROLLED(WAVES_MAX); i++) {\n"));
    CHECK(!unrolled_constant_loop("packs/x/a.frag", "    for (int i = 0; i < uCount; i++) {\n"));
    CHECK(!unrolled_constant_loop("packs/x/a.frag", "// Loops run `for (i < MAX) { if (i >= N) break; }`\n"));
    CHECK(!unrolled_constant_loop("packs/caustic_tex/xing_look.glsl", "for (int c = 0; c < 3; c++) {\n"));
}

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
    RUN(test_contract_glsl_is_the_table);
    RUN(test_packs_take_the_contract_from_contract_glsl);
    return check_summary();
}
