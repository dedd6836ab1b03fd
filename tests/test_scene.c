/* test_scene: the world and camera a .glib describes (viewer/scene/scene.c), and
 * scenes/lake.glib against ref_world_desc_lake(). */
#include "check.h"
#include "program.h"
#include "scene.h"
#include "strbuf.h"

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

static glib_scene *parse(const char *text) {
    return glib_parse(text, strlen(text), "mem.glib");
}

/* Parses text (which must parse cleanly) and fills the world; the
 * repairs' warnings formatted into err, one a line. */
static bool world_of(const char *text, ref_world_desc *d, scene_camera *cam, bool *has, char *err,
                     int errlen) {
    glib_scene *g = parse(text);
    CHECK_MSG(g->nerrors == 0, "the test's glib has %d errors: %s", g->nerrors,
              g->ndiags ? g->diags[0].text : "");
    diag_list dl = { 0 };
    bool ok = scene_from_glib(g, d, cam, has, &dl);
    char *said = diag_list_format(&dl, 0);
    msg_set(err, (size_t)errlen, "%s", said);
    free(said);
    diag_list_free(&dl);
    glib_free(g);
    return ok;
}

static bool zero_bytes(const void *p, size_t n) {
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++)
        if (b[i])
            return false;
    return true;
}

static void test_each_command(void) {
    ref_world_desc d;
    scene_camera cam;
    bool has = false;
    char err[512] = "x";
    bool ok = world_of("##OpenGL GLIB\n"
                       "Sun 1 2 -3  4 5 6\n"
                       "Sky 0.1 0.2 0.3  0.4 0.5 0.6\n"
                       "Water 0.25 1.5 0.7 0.8 0.9\n"
                       "WaterMesh 100\n"
                       "Terrain slope 20 4 -0.5 42 512\n"
                       "WaveSine 160 2.3 0.012\n"
                       "WaveSine 70 1.1 0.006 2.5 0.5\n"
                       "WaveGerstner 20 9 0.1\n"
                       "WaveGerstner -15 5.3 0.06 1.25 1\n"
                       "WaveSteepness 0.6\n"
                       "WaveNoise 0.01 2 3 0.7 30 9 32 0.45\n"
                       "Object sphere 1 2 3 0.5 0.1 0.2 0.3\n"
                       "Object box -1 -2 -3 0.4 0.5 0.6 0.7 0.8 0.9\n"
                       "Object cylinder 5 -2 1 0.12 3.2 0.45 0.32 0.2\n",
                       &d, &cam, &has, err, sizeof err);
    CHECK_MSG(ok && err[0] == '\0', "%s", err);
    CHECK(has);
    CHECK(d.sun_dir[0] == 1 && d.sun_dir[1] == 2 && d.sun_dir[2] == -3);
    CHECK(d.sun_irradiance[0] == 4 && d.sun_irradiance[1] == 5 && d.sun_irradiance[2] == 6);
    CHECK(d.sky_zenith[0] == 0.1 && d.sky_zenith[1] == 0.2 && d.sky_zenith[2] == 0.3);
    CHECK(d.sky_horizon[0] == 0.4 && d.sky_horizon[1] == 0.5 && d.sky_horizon[2] == 0.6);
    CHECK(d.water_level == 0.25 && d.waves.level == 0.25 && d.ior == 1.5);
    CHECK(d.absorption[0] == 0.7 && d.absorption[1] == 0.8 && d.absorption[2] == 0.9);
    CHECK_EQ(d.water_mesh_res, 100);
    CHECK(d.terrain == REF_TERRAIN_SLOPE && d.half_size == 20 && d.depth == 4 &&
          d.slope == -0.5 && d.shore_height == 0 && d.seed == 42 && d.terrain_res == 512);
    const ref_waves_desc *w = &d.waves;
    CHECK(w->sine_count == 2 && w->gerstner_count == 2);
    CHECK(w->sine[0].angle_deg == 160 && w->sine[0].wavelength == 2.3 &&
          w->sine[0].amplitude == 0.012 && w->sine[0].speed == 0 && w->sine[0].phase == 0);
    CHECK(w->sine[1].angle_deg == 70 && w->sine[1].speed == 2.5 && w->sine[1].phase == 0.5);
    CHECK(w->gerstner[0].angle_deg == 20 && w->gerstner[0].wavelength == 9 &&
          w->gerstner[0].amplitude == 0.1);
    CHECK(w->gerstner[1].angle_deg == -15 && w->gerstner[1].speed == 1.25 &&
          w->gerstner[1].phase == 1);
    CHECK_EQ(w->steepness, 0.6);
    CHECK(w->noise.amplitude == 0.01 && w->noise.cell == 2 && w->noise.octaves == 3 &&
          w->noise.speed == 0.7 && w->noise.angle_deg == 30 && w->noise.seed == 9 &&
          w->noise.period == 32 && w->noise.gain == 0.45);
    CHECK_EQ(d.nobjects, 3);
    const ref_object *o = d.objects;
    CHECK(o[0].kind == REF_OBJECT_SPHERE && o[0].center[0] == 1 && o[0].center[1] == 2 &&
          o[0].center[2] == 3 && o[0].size[0] == 0.5 && o[0].albedo[0] == 0.1 &&
          o[0].albedo[2] == 0.3);
    CHECK(o[1].kind == REF_OBJECT_BOX && o[1].center[2] == -3 && o[1].size[0] == 0.4 &&
          o[1].size[1] == 0.5 && o[1].size[2] == 0.6 && o[1].albedo[0] == 0.7 &&
          o[1].albedo[2] == 0.9);
    CHECK(o[2].kind == REF_OBJECT_CYLINDER && o[2].center[1] == -2 && o[2].size[0] == 0.12 &&
          o[2].size[1] == 3.2 && o[2].albedo[1] == 0.32);
}

static void test_defaults(void) {
    ref_world_desc d;
    scene_camera cam;
    bool has = true;
    char err[256];
    memset(&d, 0x55, sizeof d);             /* scene_from_glib zeroes it first */
    CHECK(world_of("##OpenGL GLIB\nSphere 1\n", &d, &cam, &has, err, sizeof err));
    CHECK(!has);
    CHECK(zero_bytes(&d, sizeof d));
    /* glman's defaults (issue 14): OpenGL's view from the origin down -Z, 600x600 */
    CHECK(cam.eye[0] == 0 && cam.eye[1] == 0 && cam.eye[2] == 0);
    CHECK(cam.center[0] == 0 && cam.center[1] == 0 && cam.center[2] == -1);
    CHECK(cam.up[0] == 0 && cam.up[1] == 1 && cam.up[2] == 0);
    CHECK(cam.fov_deg == 50 && cam.near_z == 0.1 && cam.far_z == 1000);
    CHECK(cam.width == 600 && cam.height == 600);

    /* what a command leaves out stays 0, and ref_world_init fills it in */
    CHECK(world_of("##OpenGL GLIB\nTerrain lake\nSun 0 1 0\nWater 0.5\nWaveNoise 0.02\n",
                   &d, &cam, &has, err, sizeof err));
    CHECK(has);
    CHECK(d.terrain == REF_TERRAIN_LAKE && d.half_size == 0 && d.depth == 0 && d.terrain_res == 0);
    CHECK(d.sun_irradiance[0] == 0 && d.ior == 0 && d.absorption[0] == 0);
    CHECK(d.waves.noise.amplitude == 0.02 && d.waves.noise.cell == 0 && d.waves.noise.octaves == 0);
    ref_world w, def;
    ref_world_init(&w, &d);
    ref_world_init(&def, NULL);         /* the world model's defaults */
    CHECK(w.d.half_size == def.d.half_size && w.d.depth == def.d.depth &&
          w.d.shore_height == def.d.shore_height && w.d.terrain_res == def.d.terrain_res);
    CHECK(w.d.half_size > 0 && w.d.depth > 0 && w.d.terrain_res > 0);
    for (int k = 0; k < 3; k++) {
        CHECK(w.d.sun_irradiance[k] == def.d.sun_irradiance[k] && w.d.sun_irradiance[k] > 0);
        CHECK(w.d.absorption[k] == def.d.absorption[k] && w.d.absorption[k] > 0);
    }
    CHECK(w.d.ior == def.d.ior && w.d.ior > 1);
    CHECK_EQ(w.d.water_mesh_res, def.d.water_mesh_res);
    CHECK_EQ(w.d.sun_dir[1], 1);
    CHECK(w.waves.desc.level == 0.5 && w.waves.noctaves == REF_NOISE_DEFAULT_OCTAVES);

    /* Pack says the glib has a world; the drawing commands do not (a pack
     * draws with them; issue 12: an If block made a plain scene a world) */
    CHECK(world_of("##OpenGL GLIB\nWaterSurface\n", &d, &cam, &has, err, sizeof err) && !has);
    CHECK(world_of("##OpenGL GLIB\nPack basic\n", &d, &cam, &has, err, sizeof err) && has);
    CHECK(zero_bytes(&d, sizeof d));

    /* an explicit 0 0 0 stays (nearly) zero instead of turning into the default */
    CHECK(world_of("##OpenGL GLIB\nSun 0 1 0 0 0 0\nWater 0 1.333 0 0 0\n", &d, &cam, &has, err,
                   sizeof err));
    ref_world_init(&w, &d);
    CHECK(w.d.sun_irradiance[0] < 1e-9 && w.d.sun_irradiance[2] < 1e-9);
    CHECK(w.d.absorption[0] < 1e-9 && w.d.absorption[1] < 1e-9);
}

static void test_repairs(void) {
    ref_world_desc d;
    scene_camera cam;
    bool has;
    char err[4096];
    bool ok = world_of("##OpenGL GLIB\n"
                       "Water 0 0.9 -1 0.1 0.1\n"           /* 2 */
                       "WaterMesh 4\n"                      /* 3 */
                       "Terrain lake -5 0 -1 3 9999\n"      /* 4 */
                       "WaveSine 0 -2 0.1\n"                /* 5 */
                       "WaveSine 0 0 0.1\n"                 /* 6 */
                       "WaveGerstner 10 3 -0.2 0 0.5\n"     /* 7 */
                       "WaveSteepness 1.5\n"                /* 8 */
                       "WaveNoise -0.1 -1 12 0 0 0 0 -2\n"  /* 9 */
                       "Object sphere 0 0 0 -1 2 0.5 -1\n"  /* 10 */
                       "Object box 0 0 0 1 0 1 0.5 0.5 0.5\n" /* 11 */
                       "Sky -1 0.5 0.5 0.5 0.5 0.5\n"       /* 12 */
                       "Terrain slope 10 2 0\n"             /* 13 */
                       "Sun 0 1 0 -1 1 1\n",                /* 14 */
                       &d, &cam, &has, err, sizeof err);
    CHECK(!ok);
    CHECK_STR_CONTAINS(err, "mem.glib:2: warning: Water: ior 0.9 must be above 1");
    CHECK_STR_CONTAINS(err, "mem.glib:2: warning: Water: the absorption -1 0.1 0.1 has a negative part; using 0 0.1 0.1");
    CHECK_STR_CONTAINS(err, "mem.glib:3: warning: WaterMesh: res 4 is outside 8..2048; using 8");
    CHECK_STR_CONTAINS(err, "mem.glib:4: warning: Terrain: half_size -5 must be greater than 0; using ");
    CHECK_STR_CONTAINS(err, "mem.glib:4: warning: Terrain: depth 0 must be greater than 0; using ");
    CHECK_STR_CONTAINS(err, "mem.glib:4: warning: Terrain: the shore height -1 must be greater than 0; using ");
    CHECK_STR_CONTAINS(err, "mem.glib:4: warning: Terrain: res 9999 is outside 8..2048; using 2048");
    CHECK_STR_CONTAINS(err, "mem.glib:5: warning: WaveSine: wavelength -2 is negative; using 2");
    CHECK_STR_CONTAINS(err, "mem.glib:6: warning: WaveSine: a wavelength of 0 is no wave; this one is dropped");
    CHECK_STR_CONTAINS(err, "mem.glib:7: warning: WaveGerstner: amplitude -0.2 is negative; using 0.2 with the phase turned by pi");
    CHECK_STR_CONTAINS(err, "mem.glib:8: warning: WaveSteepness: Q 1.5 is above 1");
    CHECK_STR_CONTAINS(err, "mem.glib:9: warning: WaveNoise: amplitude -0.1 is negative; using 0.1");
    CHECK_STR_CONTAINS(err, "mem.glib:9: warning: WaveNoise: cell -1 must be greater than 0; using 4");
    CHECK_STR_CONTAINS(err, "mem.glib:9: warning: WaveNoise: octaves 12 is outside 1..8; using 8");
    CHECK_STR_CONTAINS(err, "mem.glib:9: warning: WaveNoise: period 0 must be at least 1 lattice cell; using 16");
    CHECK_STR_CONTAINS(err, "mem.glib:9: warning: WaveNoise: gain -2 must be greater than 0; using 0.5");
    CHECK_STR_CONTAINS(err, "mem.glib:10: warning: Object: the radius -1 is negative; using 1");
    CHECK_STR_CONTAINS(err, "mem.glib:10: warning: Object: the colour 2 0.5 -1 is a reflectance, from 0 to 1; using 1 0.5 0");
    CHECK_STR_CONTAINS(err, "mem.glib:11: warning: Object: hy is 0; the object is dropped");
    CHECK_STR_CONTAINS(err, "mem.glib:12: warning: Sky: the zenith radiance -1 0.5 0.5 has a negative part");
    CHECK_STR_CONTAINS(err, "mem.glib:13: warning: Terrain: a slope of 0 is the flat terrain (Terrain flat); using ");
    CHECK_STR_CONTAINS(err, "mem.glib:14: warning: Sun: the irradiance -1 1 1 has a negative part; using 0 1 1");

    CHECK(d.ior == 0 && d.absorption[0] == 0 && d.absorption[1] == 0.1);
    CHECK_EQ(d.water_mesh_res, 8);
    CHECK(d.terrain == REF_TERRAIN_SLOPE && d.half_size == 10 && d.slope == 0);   /* the last Terrain wins */
    CHECK(d.waves.sine_count == 1 && d.waves.sine[0].wavelength == 2);
    CHECK(d.waves.gerstner_count == 1 && d.waves.gerstner[0].amplitude == 0.2);
    CHECK_NEAR(d.waves.gerstner[0].phase, 0.5 + PI, 1e-15);
    CHECK_EQ(d.waves.steepness, 1);
    CHECK(d.waves.noise.amplitude == 0.1 && d.waves.noise.cell == 0 && d.waves.noise.octaves == 8 &&
          d.waves.noise.period == 0 && d.waves.noise.gain == 0);
    CHECK(d.nobjects == 1 && d.objects[0].size[0] == 1 && d.objects[0].albedo[0] == 1 &&
          d.objects[0].albedo[2] == 0);
    CHECK(d.sky_zenith[0] == 0 && d.sky_zenith[1] == 0.5);
    CHECK(d.sun_irradiance[0] == 0 && d.sun_irradiance[1] == 1);

    /* the repaired negative-amplitude Gerstner wave is the written one */
    ref_waves_desc neg, pos;
    memset(&neg, 0, sizeof neg);
    neg.gerstner_count = 1;
    neg.steepness = 0.8;
    neg.gerstner[0] = (ref_wave_desc){ .angle_deg = 10, .wavelength = 3, .amplitude = -0.2, .phase = 0.5 };
    pos = neg;
    pos.gerstner[0] = d.waves.gerstner[0];
    ref_waves wn, wp;
    CHECK(ref_waves_init(&wn, &neg, NULL, 0) == 0 && ref_waves_init(&wp, &pos, NULL, 0) == 0);
    for (int i = 0; i < 5; i++) {
        double a[3], b[3];
        ref_waves_displace(&wn, 0.7 * i, -0.3 * i, 0.4 * i, a);
        ref_waves_displace(&wp, 0.7 * i, -0.3 * i, 0.4 * i, b);
        for (int k = 0; k < 3; k++)
            CHECK_NEAR(a[k], b[k], 1e-12);
    }

    /* the world these repairs give resolves */
    ref_world w;
    ref_world_init(&w, &d);
    CHECK(w.d.ior > 1 && w.waves.nsine == 1 && w.waves.ngerstner == 1);
    CHECK_EQ(w.waves.noctaves, 8);
}

static void test_limits(void) {
    char text[8192] = "##OpenGL GLIB\n";
    size_t n = strlen(text);
    for (int i = 0; i < REF_WAVES_MAX + 1; i++)
        n += (size_t)snprintf(text + n, sizeof text - n, "WaveSine %d 2 0.01\nWaveGerstner %d 3 0.02\n",
                              10 * i, 10 * i);
    for (int i = 0; i < REF_MAX_OBJECTS + 3; i++)
        n += (size_t)snprintf(text + n, sizeof text - n, "Object sphere %d 0 0 0.5 0.5 0.5 0.5\n", i);
    ref_world_desc d;
    bool has;
    char err[2048];
    CHECK(!world_of(text, &d, NULL, &has, err, sizeof err));
    CHECK(d.waves.sine_count == REF_WAVES_MAX && d.waves.gerstner_count == REF_WAVES_MAX);
    CHECK(d.waves.sine[7].angle_deg == 70 && d.waves.gerstner[7].angle_deg == 70);
    CHECK(d.nobjects == REF_MAX_OBJECTS && d.objects[REF_MAX_OBJECTS - 1].center[0] == REF_MAX_OBJECTS - 1);
    CHECK_STR_CONTAINS(err, "mem.glib:18: warning: WaveSine: more than 8 waves of this kind; this one is dropped");
    CHECK_STR_CONTAINS(err, "mem.glib:19: warning: WaveGerstner: more than 8 waves");
    CHECK_STR_CONTAINS(err, "mem.glib:52: warning: Object: more than 32 objects; this one and the ones after it are dropped");
    CHECK_EQ(strstr(err, "mem.glib:53:"), NULL);     /* said once */

    /* as diags: a warning each, at its command's file and line */
    glib_scene *g = parse(text);
    diag_list dl = { 0 };
    CHECK(!scene_from_glib(g, &d, NULL, &has, &dl));
    CHECK_EQ(dl.n, 3);
    CHECK_EQ(dl.nwarnings, 3);
    if (dl.n == 3) {
        CHECK_STR_EQ(dl.d[0].file, "mem.glib");
        CHECK_EQ(dl.d[0].line, 18);
        CHECK_STR_EQ(dl.d[0].text, "WaveSine: more than 8 waves of this kind; this one is dropped");
        CHECK_EQ(dl.d[2].line, 52);
    }
    diag_list_free(&dl);
    /* NULL outputs are fine */
    CHECK(!scene_from_glib(g, NULL, NULL, NULL, NULL));
    glib_free(g);
}

static void test_camera(void) {
    ref_world_desc d;
    scene_camera cam;
    bool has;
    char err[256];
    CHECK(world_of("##OpenGL GLIB\n"
                   "WindowSize 640 480\nPerspective 30\nLookAt 1 2 3  4 5 6  0 0 1\n"
                   "WindowSize 960 540\nPerspective 70 0.5 300\nLookAt 9 2.5 9  -2 -0.6 -1  0 1 0\n",
                   &d, &cam, &has, err, sizeof err));
    CHECK(!has);
    CHECK(cam.width == 960 && cam.height == 540);
    CHECK(cam.fov_deg == 70 && cam.near_z == 0.5 && cam.far_z == 300);
    CHECK(cam.eye[0] == 9 && cam.eye[1] == 2.5 && cam.eye[2] == 9);
    CHECK(cam.center[0] == -2 && cam.center[1] == -0.6 && cam.center[2] == -1);
    CHECK(cam.up[0] == 0 && cam.up[1] == 1 && cam.up[2] == 0);
    CHECK(world_of("##OpenGL GLIB\nPerspective 30\n", &d, &cam, &has, err, sizeof err));
    CHECK(cam.fov_deg == 30 && cam.near_z == 0.1 && cam.far_z == 1000 && cam.width == 600);
}

/* scenes/lake.glib and ref_world_desc_lake() are one world. */
static void test_lake_matches_reference(void) {
    glib_scene *g = glib_load(TARN_SOURCE_DIR "/scenes/lake.glib");
    CHECK_MSG(g->nerrors == 0 && g->ndiags == 0, "%s", g->ndiags ? g->diags[0].text : "");
    ref_world_desc dg, dr;
    scene_camera cam;
    bool has = false;
    diag_list dl = { 0 };
    CHECK_MSG(scene_from_glib(g, &dg, &cam, &has, &dl), "%s", dl.n ? dl.d[0].text : "");
    diag_list_free(&dl);
    glib_free(g);
    CHECK(has);
    CHECK(cam.width == 960 && cam.height == 540);
    ref_world_desc_lake(&dr);
    ref_world *a = malloc(sizeof *a), *b = malloc(sizeof *b);
    ref_world_init(a, &dg);
    ref_world_init(b, &dr);
    const ref_world_desc *x = &a->d, *y = &b->d;
    const double tol = 1e-12;
    for (int i = 0; i < 3; i++) {
        CHECK_NEAR(x->sun_dir[i], y->sun_dir[i], tol);
        CHECK_NEAR(x->sun_irradiance[i], y->sun_irradiance[i], tol);
        CHECK_NEAR(x->sky_zenith[i], y->sky_zenith[i], tol);
        CHECK_NEAR(x->sky_horizon[i], y->sky_horizon[i], tol);
        CHECK_NEAR(x->absorption[i], y->absorption[i], tol);
    }
    CHECK_NEAR(x->water_level, y->water_level, tol);
    CHECK_NEAR(x->ior, y->ior, tol);
    CHECK_EQ(x->water_mesh_res, y->water_mesh_res);
    CHECK(x->terrain == y->terrain && x->seed == y->seed && x->terrain_res == y->terrain_res);
    CHECK_NEAR(x->half_size, y->half_size, tol);
    CHECK_NEAR(x->depth, y->depth, tol);
    CHECK_NEAR(x->shore_height, y->shore_height, tol);
    CHECK_EQ(x->nobjects, y->nobjects);
    for (int i = 0; i < x->nobjects && i < y->nobjects; i++) {
        CHECK_MSG(x->objects[i].kind == y->objects[i].kind, "object %d", i);
        for (int k = 0; k < 3; k++) {
            CHECK_NEAR(x->objects[i].center[k], y->objects[i].center[k], tol);
            CHECK_NEAR(x->objects[i].size[k], y->objects[i].size[k], tol);
            CHECK_NEAR(x->objects[i].albedo[k], y->objects[i].albedo[k], tol);
        }
    }
    /* the resolved wave sets */
    CHECK(a->waves.nsine == b->waves.nsine && a->waves.ngerstner == b->waves.ngerstner &&
          a->waves.noctaves == b->waves.noctaves);
    CHECK_NEAR(a->waves.q_sum, b->waves.q_sum, tol);
    /* heights of the terrain, sky radiance, wave heights at a few points */
    static const double pts[][2] = { { 0, 0 }, { 3.3, -2.1 }, { -7.5, 6.5 }, { 11.9, 11.9 },
                                     { -10, 2 }, { 2.5, 1 }, { 0.123, -8.7 } };
    for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++) {
        double px = pts[i][0], pz = pts[i][1];
        CHECK_NEAR(ref_terrain_height(a, px, pz), ref_terrain_height(b, px, pz), tol);
        double ca[3], cb[3];
        ref_terrain_albedo(a, px, pz, ca);
        ref_terrain_albedo(b, px, pz, cb);
        CHECK_NEAR(ca[0], cb[0], tol);
        for (int t = 0; t < 3; t++) {
            double ha = ref_waves_height(&a->waves, px, pz, 1.7 * t);
            double hb = ref_waves_height(&b->waves, px, pz, 1.7 * t);
            CHECK_MSG(fabs(ha - hb) <= tol && ha == ha, "wave height at (%g, %g, t %d): %.17g vs %.17g",
                      px, pz, t, ha, hb);
        }
    }
    static const double dirs[][3] = { { 0, 1, 0 }, { 1, 0, 0 }, { 0.4, 0.8, -0.45 },
                                      { -0.3, 0.2, 0.9 }, { 0, -1, 0 }, { 0.6, -0.1, 0.2 } };
    for (size_t i = 0; i < sizeof dirs / sizeof dirs[0]; i++) {
        double dd[3], l = sqrt(dirs[i][0] * dirs[i][0] + dirs[i][1] * dirs[i][1] + dirs[i][2] * dirs[i][2]);
        for (int k = 0; k < 3; k++)
            dd[k] = dirs[i][k] / l;
        double ra[3], rb[3];
        ref_sky_radiance(a, dd, ra);
        ref_sky_radiance(b, dd, rb);
        for (int k = 0; k < 3; k++)
            CHECK_NEAR(ra[k], rb[k], tol);
    }
    free(a);
    free(b);
}

static void test_scene_load(void) {
    ref_world_desc d;
    scene_camera cam;
    bool has = false;
    char err[1024] = "";
    /* the lake with its pack (packs/raymarch) read in */
    bool ok = scene_load(TARN_SOURCE_DIR "/scenes/lake.glib", NULL, &d, &cam, &has, err, sizeof err);
    CHECK_MSG(ok, "%s", err);
    CHECK(has && d.terrain == REF_TERRAIN_LAKE && d.nobjects == 7 && cam.width == 960);
    /* the pool: Terrain pool maps to REF_TERRAIN_POOL, its third number the deck's height */
    ok = scene_load(TARN_SOURCE_DIR "/scenes/pool.glib", NULL, &d, &cam, &has, err, sizeof err);
    CHECK_MSG(ok && err[0] == '\0', "%s", err);
    CHECK(has && d.terrain == REF_TERRAIN_POOL && d.half_size == 12 && d.depth == 1.5 &&
          d.shore_height == 0.4 && d.nobjects == 0 && cam.width == 960);
    /* a pack that is not there: the parser's error, and still the world */
    ok = scene_load(TARN_SOURCE_DIR "/scenes/lake.glib", "no_such_pack", &d, &cam, &has, err, sizeof err);
    CHECK(!ok);
    CHECK_STR_CONTAINS(err, "lake.glib:");
    CHECK_STR_CONTAINS(err, ": error: Pack: no pack 'no_such_pack' in " TARN_SOURCE_DIR "/packs");
    CHECK_STR_CONTAINS(err, "basic");
    CHECK(has && d.nobjects == 7);
    /* a file that is not there */
    ok = scene_load("/nonexistent/x.glib", NULL, &d, &cam, &has, err, sizeof err);
    CHECK(!ok);
    CHECK_STR_CONTAINS(err, "/nonexistent/x.glib:0: error: cannot open");
    CHECK(!has && cam.fov_deg == 50);
}

/* Only the commands that describe the world make one: an If block, a
 * Camera, World or WaterSurface (what a pack draws with) do not. */
static void test_plain_glman_scene_has_no_world(void) {
    ref_world_desc d;
    scene_camera cam;
    bool has = true;
    char err[256];
    CHECK(world_of("##OpenGL GLIB\nDefine FOO <true>\nIf FOO\nSphere 1\nEndIf\n"
                   "Camera main\nWorld all\nWaterSurface\nRenderToTextureOnce 5\nRenderToTexture\n",
                   &d, &cam, &has, err, sizeof err));
    CHECK(!has);
    CHECK(world_of("##OpenGL GLIB\nIf FOO\nEndIf\nWaveSine 0 2 0.1\n", &d, &cam, &has, err, sizeof err));
    CHECK(has);
    CHECK(glib_cmd_describes_world(GLIB_CMD_SUN) && glib_cmd_describes_world(GLIB_CMD_PACK));
    CHECK(!glib_cmd_describes_world(GLIB_CMD_IF) && !glib_cmd_describes_world(GLIB_CMD_SPLAT));
}

/* WindowSize, Perspective, Ortho and LookAt: the reader keeps small sizes
 * and takes Ortho (render and reference use it both). */
static void test_viewing_reader(void) {
    glib_scene *g = parse("##OpenGL GLIB\nWindowSize 12 10\nPerspective 40\nOrtho -2 2 -1 1\n");
    scene_camera cam;
    scene_camera_from_glib(g, &cam);
    glib_free(g);
    CHECK(cam.width == 12 && cam.height == 10);
    CHECK(cam.ortho && cam.ortho_lrbt[0] == -2 && cam.ortho_lrbt[3] == 1 && cam.fov_deg == 40);
    scene_camera_from_glib(NULL, &cam);
    CHECK(cam.width == 600 && cam.height == 600 && !cam.ortho && cam.fov_deg == 50);   /* glman's */
}

/* The stage state each Program takes (program.h, shared by the renderer
 * and validate): the stages named so far, a bare stage command unsets one,
 * GSTAP stays on. */
static void test_program_stages(void) {
    glib_scene *g = parse("##OpenGL GLIB\nVertex a.vert\nFragment b.frag\nProgram A\n"
                          "Vertex\nGSTAP\nGeometry g.geom\nProgram B\n");
    program_stages st;
    program_stages_init(&st);
    int seen = 0;
    for (int i = 0; i < g->ncmds; i++) {
        const glib_cmd *c = &g->cmds[i];
        if (c->kind != GLIB_CMD_PROGRAM) {
            program_stages_step(&st, c);
            continue;
        }
        shader_stage list[SHADER_STAGE_COUNT];
        int n = program_stage_list(&st, list);
        if (seen++ == 0) {
            CHECK(n == 2 && list[0] == SHADER_VERTEX && list[1] == SHADER_FRAGMENT && !st.gstap);
            CHECK_STR_CONTAINS(program_stage_path(&st, SHADER_VERTEX), "a.vert");
        } else {
            CHECK(n == 2 && list[0] == SHADER_GEOMETRY && list[1] == SHADER_FRAGMENT && st.gstap);
            CHECK_EQ(program_stage_path(&st, SHADER_VERTEX)[0], '\0');
            shader_src_desc d = program_stage_desc(&st, SHADER_GEOMETRY, NULL, 0, NULL, 0);
            CHECK(d.gstap && d.stage == SHADER_GEOMETRY && strstr(d.path, "g.geom"));
        }
    }
    CHECK_EQ(seen, 2);
    CHECK_EQ(program_stage_of(GLIB_CMD_PROGRAM), SHADER_STAGE_COUNT);
    glib_free(g);
}

/* A geometry shader without `layout(...) in;` gets the primitive of the
 * first draw after its Program: a Wire draw hands it lines, WaterSurface
 * points points, Shp lines, a solid or no draw at all triangles; the next Program's
 * draws are not this one's. */
static void test_program_gs_input(void) {
    glib_scene *g = parse("##OpenGL GLIB\nGeometry g.geom\nProgram A\nTranslate 0 0 1\nWireSphere\nSphere\n"
                          "Program B\nColor 1 0 0\nBox\nWireBox\nProgram C\nProgram D\nWireTorus\n"
                          "Program E\nShp coast.shp\n");
    const shader_gs_input want[] = { SHADER_GS_IN_LINES, SHADER_GS_IN_TRIANGLES, SHADER_GS_IN_TRIANGLES,
                                     SHADER_GS_IN_LINES, SHADER_GS_IN_LINES };   /* a shapefile: line strips */
    int k = 0;
    for (int i = 0; i < g->ncmds; i++) {
        if (g->cmds[i].kind != GLIB_CMD_PROGRAM || k >= 5) continue;
        CHECK_MSG(program_gs_input(g, &g->cmds[i]) == want[k], "Program %s: %d", g->cmds[i].name,
                  (int)program_gs_input(g, &g->cmds[i]));
        k++;
    }
    CHECK_EQ(k, 5);
    CHECK_EQ(program_gs_input(NULL, NULL), SHADER_GS_IN_TRIANGLES);
    glib_free(g);
}

/* The wave models of issue #23: each command fills its desc as docs/glib.md
 * says, the glib's defaults where the desc's differ (choppiness 1), and
 * absurd values are repaired with a warning at their line. */
static void test_wave_models(void) {
    ref_world_desc d;
    scene_camera cam;
    bool has;
    char err[4096];
    CHECK_MSG(world_of("##OpenGL GLIB\n"
                       "WaveOceanTiles 160 37 5.3\n"
                       "WaveOcean jonswap 9 -80\n"
                       "WaveExplosion 6 -4 1.0 0.25 0 3.0 0.4\n"
                       "WavePerlin 0.02 6 3 0.3 2 20 5 0.6\n",
                       &d, &cam, &has, err, sizeof err), "%s", err);
    CHECK(has);
    const ref_ocean_desc *o = &d.waves.ocean;
    CHECK(o->spectrum == REF_SPECTRUM_JONSWAP && o->wind_speed == 9 && o->wind_angle_deg == -80);
    CHECK(o->choppiness == 1.0 && o->res == 0 && o->fetch == 0 && o->depth == 0);
    CHECK(o->cascades == 3 && o->tile[0] == 160 && o->tile[1] == 37 && o->tile[2] == 5.3);   /* tiles first: kept */
    CHECK_EQ(d.waves.explosion_count, 1);
    const ref_explosion_desc *e = &d.waves.explosion[0];
    CHECK(e->center[0] == 6 && e->center[1] == -4 && e->start == 1.0 && e->i0 == 0.25 && e->omega == 0 &&
          e->k == 3.0 && e->decay == 0.4);
    const ref_perlin_desc *pl = &d.waves.perlin;
    CHECK(pl->amplitude == 0.02 && pl->cell == 6 && pl->octaves == 3 && pl->rate == 0.3 && pl->stretch == 2 &&
          pl->angle_deg == 20 && pl->seed == 5 && pl->gain == 0.6);
    /* and the world resolves it: the ocean is built, the ring and the set counted */
    ref_world w;
    ref_world_init(&w, &d);
    CHECK(w.waves.ocean != NULL && w.waves.nexplosions == 1 && w.waves.has_perlin);
    ref_world_release(&w);

    bool ok = world_of("##OpenGL GLIB\n"
                       "WaveOcean tma -5 0 -1 100 3 -1000 20\n"   /* 2 */
                       "WaveOceanTiles 5 40 0\n"                 /* 3 */
                       "WaveExplosion 0 0 1 0\n"                 /* 4 */
                       "WavePerlin -0.1 -2 20 0 -1\n",           /* 5 */
                       &d, &cam, &has, err, sizeof err);
    CHECK(!ok);
    fprintf(stderr, "%s\n", err);
    CHECK_STR_CONTAINS(err, "mem.glib:2: warning: WaveOcean: wind speed -5 is negative; using 5");
    CHECK_STR_CONTAINS(err, "mem.glib:2: warning: WaveOcean: choppiness -1 is negative");
    CHECK_STR_CONTAINS(err, "mem.glib:2: warning: WaveOcean: res 100 is not a power of two in 64..512; using 128");
    CHECK_STR_CONTAINS(err, "mem.glib:2: warning: WaveOcean: fetch -1000 is negative; using 1000");
    CHECK_STR_CONTAINS(err, "mem.glib:3: warning: WaveOceanTiles: a tile of 0 m holds no waves");
    CHECK_STR_CONTAINS(err, "mem.glib:3: warning: WaveOceanTiles: the tiles go largest first; using 40 5");
    CHECK_STR_CONTAINS(err, "mem.glib:4: warning: WaveExplosion: an amplitude I0 of 0 is no ring");
    CHECK_STR_CONTAINS(err, "mem.glib:5: warning: WavePerlin: amplitude -0.1 is negative; using 0.1");
    CHECK_STR_CONTAINS(err, "mem.glib:5: warning: WavePerlin: octaves 20 is outside 1..8; using 8");
    CHECK_STR_CONTAINS(err, "mem.glib:5: warning: WavePerlin: stretch -1 must be greater than 0");
    CHECK(d.waves.ocean.spectrum == REF_SPECTRUM_TMA && d.waves.ocean.wind_speed == 5 &&
          d.waves.ocean.choppiness == 1 && d.waves.ocean.res == 128 && d.waves.ocean.depth == 20);
    CHECK(d.waves.ocean.cascades == 2 && d.waves.ocean.tile[0] == 40 && d.waves.ocean.tile[1] == 5);
    CHECK_EQ(d.waves.explosion_count, 0);
    CHECK(d.waves.perlin.amplitude == 0.1 && d.waves.perlin.octaves == 8 && d.waves.perlin.stretch == 0);
}

int main(void) {
    RUN(test_each_command);
    RUN(test_wave_models);
    RUN(test_defaults);
    RUN(test_repairs);
    RUN(test_limits);
    RUN(test_camera);
    RUN(test_plain_glman_scene_has_no_world);
    RUN(test_viewing_reader);
    RUN(test_program_stages);
    RUN(test_program_gs_input);
    RUN(test_lake_matches_reference);
    RUN(test_scene_load);
    return check_summary();
}
