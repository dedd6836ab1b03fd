/* scene.c: the world and the camera a .glib describes (scene.h).
 *
 * The world commands (docs/glib.md, "Describing the world") fill a
 * ref_world_desc, zeroed first, so what a glib leaves out takes
 * ref_world_init's defaults: the defaults live there and nowhere else (the
 * messages below read them from a world built from the zero desc). The
 * parser checked the form of each command; here the values are checked
 * and absurd ones are repaired, each with a `file:line: warning:` message,
 * so one bad number never loses the scene.
 */
#include "util.h"
#include "scene.h"
#include "file_cache.h"
#include "strbuf.h"
#include "obj.h"
#include "ref_mesh.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

/* An explicit 0 0 0 (a dark sun, a black sky, clear water) would read as
 * "default" in a desc; this keeps it (almost exactly) zero. */
#define SCENE_ZERO 1e-12

enum { MESH_RES_MIN = 8, MESH_RES_MAX = 2048 };
#define HALF_SIZE_MAX 10000.0
#define DEPTH_MAX 1000.0

typedef struct ctx {
    diag_list *dl;              /* may be NULL */
    int nmsgs;
    ref_world def;              /* the defaults, for messages */
    struct file_cache *files;   /* where the glib's files were read (its meshes are read there too) */
} ctx;

/* A value repaired: a warning at c's line, "Water: the level ..." */
__attribute__((format(printf, 3, 4)))
static void msg(ctx *x, const glib_cmd *c, const char *fmt, ...) {
    x->nmsgs++;
    if (!x->dl) return;
    char text[DIAG_TEXT_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    diag_add(x->dl, DIAG_WARNING, c->file ? c->file : "?", c->line, "%s: %s", glib_cmd_name(c->kind), text);
}

/* r g b that may not be negative; an explicit 0 0 0 stays zero. */
static void set_rgb(ctx *x, const glib_cmd *c, const double *v, double out[3], const char *what) {
    bool neg = false;
    for (int i = 0; i < 3; i++) {
        out[i] = v[i] < 0 ? 0 : v[i];
        neg |= v[i] < 0;
    }
    if (neg)
        msg(x, c, "%s %g %g %g has a negative part; using %g %g %g", what, v[0], v[1], v[2],
            out[0], out[1], out[2]);
    if (out[0] == 0 && out[1] == 0 && out[2] == 0)
        out[0] = out[1] = out[2] = SCENE_ZERO;
}

static int clamp_res(ctx *x, const glib_cmd *c, double v, const char *what) {
    if (v >= MESH_RES_MIN && v <= MESH_RES_MAX)
        return (int)v;
    int r = v < MESH_RES_MIN ? MESH_RES_MIN : MESH_RES_MAX;
    msg(x, c, "%s %g is outside %d..%d; using %d", what, v, MESH_RES_MIN, MESH_RES_MAX, r);
    return r;
}

static void do_sun(ctx *x, const glib_cmd *c, ref_world_desc *w) {
    memcpy(w->sun_dir, c->num, sizeof w->sun_dir);   /* the parser refused zero */
    if (c->nnum >= 6)
        set_rgb(x, c, c->num + 3, w->sun_irradiance, "the irradiance");
    else
        memset(w->sun_irradiance, 0, sizeof w->sun_irradiance);
}

static void do_water(ctx *x, const glib_cmd *c, ref_world_desc *w) {
    w->water_level = c->num[0];
    w->ior = 0;
    if (c->nnum >= 2) {
        if (c->num[1] > 1 && c->num[1] <= 4)
            w->ior = c->num[1];
        else
            msg(x, c, "ior %g must be above 1 (air) and at most 4 (water is 1.333); using %g",
                c->num[1], x->def.d.ior);
    }
    memset(w->absorption, 0, sizeof w->absorption);
    if (c->nnum >= 5)
        set_rgb(x, c, c->num + 2, w->absorption, "the absorption");
}

static void do_terrain(ctx *x, const glib_cmd *c, ref_world_desc *w) {
    const double *n = c->num;
    w->terrain = strcmp(c->name, "lake") == 0 ? REF_TERRAIN_LAKE
               : strcmp(c->name, "slope") == 0 ? REF_TERRAIN_SLOPE
               : strcmp(c->name, "pool") == 0 ? REF_TERRAIN_POOL : REF_TERRAIN_FLAT;
    w->half_size = w->depth = w->shore_height = w->slope = 0;
    w->seed = 0;
    w->terrain_res = 0;
    if (c->nnum >= 1) {
        if (n[0] > 0 && n[0] <= HALF_SIZE_MAX)
            w->half_size = n[0];
        else if (n[0] > HALF_SIZE_MAX)
            msg(x, c, "half_size %g is above %g; using %g", n[0], HALF_SIZE_MAX,
                w->half_size = HALF_SIZE_MAX);
        else
            msg(x, c, "half_size %g must be greater than 0; using %g", n[0], x->def.d.half_size);
    }
    if (c->nnum >= 2) {
        if (n[1] > 0 && n[1] <= DEPTH_MAX)
            w->depth = n[1];
        else if (n[1] > DEPTH_MAX)
            msg(x, c, "depth %g is above %g; using %g", n[1], DEPTH_MAX, w->depth = DEPTH_MAX);
        else
            msg(x, c, "depth %g must be greater than 0; using %g", n[1], x->def.d.depth);
    }
    if (c->nnum >= 3) {
        if (w->terrain == REF_TERRAIN_LAKE || w->terrain == REF_TERRAIN_POOL) {
            if (n[2] > 0)
                w->shore_height = n[2];
            else
                msg(x, c, "the shore height %g must be greater than 0; using %g", n[2],
                    x->def.d.shore_height);
        } else if (w->terrain == REF_TERRAIN_SLOPE) {
            if (n[2] != 0)
                w->slope = n[2];
            else
                msg(x, c, "a slope of 0 is the flat terrain (Terrain flat); using %g",
                    x->def.d.slope);
        } else if (n[2] != 0) {
            msg(x, c, "flat terrain has no shore height or slope; ignoring %g", n[2]);
        }
    }
    if (c->nnum >= 4)
        w->seed = (unsigned)n[3];
    if (c->nnum >= 5)
        w->terrain_res = clamp_res(x, c, n[4], "res");
}

static void do_wave(ctx *x, const glib_cmd *c, ref_waves_desc *wd) {
    bool sine = c->kind == GLIB_CMD_WAVE_SINE;
    int *count = sine ? &wd->sine_count : &wd->gerstner_count;
    if (*count >= REF_WAVES_MAX) {
        msg(x, c, "more than %d waves of this kind; this one is dropped", REF_WAVES_MAX);
        return;
    }
    ref_wave_desc v = { .angle_deg = c->num[0], .wavelength = c->num[1], .amplitude = c->num[2],
                        .speed = c->nnum >= 4 ? c->num[3] : 0, .phase = c->nnum >= 5 ? c->num[4] : 0 };
    if (v.wavelength == 0) {
        msg(x, c, "a wavelength of 0 is no wave; this one is dropped");
        return;
    }
    if (v.wavelength < 0) {
        msg(x, c, "wavelength %g is negative; using %g", v.wavelength, -v.wavelength);
        v.wavelength = -v.wavelength;
    }
    if (v.amplitude < 0) {
        /* A sin(t) = |A| sin(t + pi), and the Gerstner sideways term
         * follows the sign of A likewise: the same wave */
        msg(x, c, "amplitude %g is negative; using %g with the phase turned by pi (the same wave)",
            v.amplitude, -v.amplitude);
        v.amplitude = -v.amplitude;
        v.phase += PI;
    }
    (sine ? wd->sine : wd->gerstner)[(*count)++] = v;
}

static void do_steepness(ctx *x, const glib_cmd *c, ref_waves_desc *wd) {
    double q = c->num[0];
    if (q < 0) {
        msg(x, c, "Q %g is negative; using 0 (the Gerstner waves become sines)", q);
        q = 0;
    } else if (q > 1) {
        msg(x, c, "Q %g is above 1, where the surface folds into loops; using 1", q);
        q = 1;
    }
    wd->steepness = q;
}

static void do_noise(ctx *x, const glib_cmd *c, ref_noise_desc *nd) {
    const double *n = c->num;
    memset(nd, 0, sizeof *nd);
    nd->amplitude = n[0];
    if (n[0] < 0) {
        msg(x, c, "amplitude %g is negative; using %g", n[0], -n[0]);
        nd->amplitude = -n[0];
    }
    if (c->nnum >= 2) {
        if (n[1] > 0)
            nd->cell = n[1];
        else if (n[1] < 0)
            msg(x, c, "cell %g must be greater than 0; using %g", n[1], REF_NOISE_DEFAULT_CELL);
    }
    if (c->nnum >= 3) {
        int o = (int)n[2];
        if (o < 1 || o > REF_NOISE_OCTAVES_MAX) {
            int r = o < 1 ? 1 : REF_NOISE_OCTAVES_MAX;
            msg(x, c, "octaves %d is outside 1..%d; using %d", o, REF_NOISE_OCTAVES_MAX, r);
            o = r;
        }
        nd->octaves = o;
    }
    if (c->nnum >= 4)
        nd->speed = n[3];
    if (c->nnum >= 5)
        nd->angle_deg = n[4];
    if (c->nnum >= 6)
        nd->seed = (uint32_t)n[5];
    if (c->nnum >= 7) {
        if (n[6] >= 1)
            nd->period = (int)n[6];
        else
            msg(x, c, "period %g must be at least 1 lattice cell; using %d", n[6],
                REF_NOISE_DEFAULT_PERIOD);
    }
    if (c->nnum >= 8) {
        if (n[7] > 0)
            nd->gain = n[7];
        else
            msg(x, c, "gain %g must be greater than 0; using %g", n[7], REF_NOISE_DEFAULT_GAIN);
    }
}

/* WaveOcean kind wind_speed [wind_angle choppiness res seed fetch depth
 * spreading amplitude]: a spectrum ocean (reference/ref_ocean.h). What is
 * not written takes the model's default, except the choppiness: 1 here
 * (Tessendorf's X + D), 0 in the desc. */
static void do_ocean(ctx *x, const glib_cmd *c, ref_ocean_desc *od) {
    const double *n = c->num;
    int k = c->nnum;
    double tiles[REF_OCEAN_CASCADES_MAX];
    int cascades = od->cascades;
    memcpy(tiles, od->tile, sizeof tiles);   /* WaveOceanTiles may come first */
    memset(od, 0, sizeof *od);
    od->cascades = cascades;
    memcpy(od->tile, tiles, sizeof tiles);
    od->spectrum = !strcmp(c->name, "phillips") ? REF_SPECTRUM_PHILLIPS
                 : !strcmp(c->name, "tma") ? REF_SPECTRUM_TMA : REF_SPECTRUM_JONSWAP;
    od->wind_speed = fabs(n[0]);
    if (n[0] < 0)
        msg(x, c, "wind speed %g is negative; using %g (turn the wind with its angle)", n[0], -n[0]);
    if (n[0] == 0)
        msg(x, c, "a wind speed of 0 raises no waves; using the default 10 m/s");
    od->wind_angle_deg = k >= 2 ? n[1] : 0;
    od->choppiness = k >= 3 ? n[2] : 1.0;
    if (od->choppiness < 0) {
        msg(x, c, "choppiness %g is negative (the crests would round, the troughs sharpen); using %g",
            od->choppiness, -od->choppiness);
        od->choppiness = -od->choppiness;
    }
    if (k >= 4 && n[3] != 0) {
        int r = REF_OCEAN_RES_MIN;
        while (r < REF_OCEAN_RES_MAX && r < n[3]) r *= 2;
        if (r != n[3])
            msg(x, c, "res %g is not a power of two in %d..%d; using %d", n[3], REF_OCEAN_RES_MIN,
                REF_OCEAN_RES_MAX, r);
        od->res = r;
    }
    if (k >= 5) od->seed = (uint32_t)n[4];
    const char *what[] = { "fetch", "depth", "spreading", "amplitude" };
    double *dst[] = { &od->fetch, &od->depth, &od->spreading, &od->amplitude };
    for (int i = 0; i < 4 && 5 + i < k; i++) {
        double v = n[5 + i];
        if (v < 0) {
            msg(x, c, "%s %g is negative; using %g", what[i], v, -v);
            v = -v;
        }
        *dst[i] = v;
    }
}

/* WaveOceanTiles L1 [L2 [L3]]: the cascades, largest tile first. */
static void do_ocean_tiles(ctx *x, const glib_cmd *c, ref_ocean_desc *od) {
    double t[REF_OCEAN_CASCADES_MAX] = { 0 };
    int n = 0;
    for (int i = 0; i < c->nnum && i < REF_OCEAN_CASCADES_MAX; i++) {
        double v = fabs(c->num[i]);
        if (v == 0) {
            msg(x, c, "a tile of 0 m holds no waves; it is dropped");
            continue;
        }
        t[n++] = v;
    }
    for (int i = 1; i < n; i++)   /* largest first: the bands follow the order */
        for (int j = i; j > 0 && t[j] > t[j - 1]; j--) {
            double s = t[j]; t[j] = t[j - 1]; t[j - 1] = s;
            if (i == j) msg(x, c, "the tiles go largest first; using %g %g%s", t[0], t[1], n > 2 ? " ..." : "");
        }
    for (int i = 1; i < n; i++)
        if (t[i] == t[i - 1]) {
            msg(x, c, "two tiles of %g m would hold the same waves; drop one", t[i]);
            n = i;
            break;
        }
    memcpy(od->tile, t, sizeof t);
    od->cascades = n;
}

static void do_explosion(ctx *x, const glib_cmd *c, ref_waves_desc *wd) {
    if (wd->explosion_count >= REF_EXPLOSIONS_MAX) {
        msg(x, c, "more than %d explosion rings; this one is dropped", REF_EXPLOSIONS_MAX);
        return;
    }
    const double *n = c->num;
    ref_explosion_desc e = { .center = { n[0], n[1] }, .start = n[2], .i0 = n[3],
                             .omega = c->nnum >= 5 ? n[4] : 0, .k = c->nnum >= 6 ? n[5] : 0,
                             .decay = c->nnum >= 7 ? n[6] : 0 };
    if (e.i0 == 0) {
        msg(x, c, "an amplitude I0 of 0 is no ring; this one is dropped");
        return;
    }
    if (e.omega < 0 || e.k < 0 || e.decay < 0) {
        msg(x, c, "omega, k and decay are magnitudes; using %g %g %g", fabs(e.omega), fabs(e.k), fabs(e.decay));
        e.omega = fabs(e.omega); e.k = fabs(e.k); e.decay = fabs(e.decay);
    }
    wd->explosion[wd->explosion_count++] = e;
}

/* Flow current / vortex add a term to the flow field; Flow detail sets
 * the look of what it carries (ref_scene.h, ref_flow_desc). */
static void do_flow(ctx *x, const glib_cmd *c, ref_flow_desc *f) {
    const double *n = c->num;
    if (strcmp(c->name, "detail") == 0) {
        f->detail_amp = fabs(n[0]);
        if (c->nnum >= 2) f->detail_cell = fabs(n[1]);
        if (c->nnum >= 3) f->period = fabs(n[2]);
        if (c->nnum >= 4) {
            f->foam = n[3] < 0 ? 0 : n[3] > 1 ? 1 : n[3];
            if (f->foam != n[3]) msg(x, c, "the foam cover is 0..1; using %g", f->foam);
        }
        return;
    }
    if (f->nterms >= REF_FLOW_TERMS_MAX) {
        msg(x, c, "more than %d flow terms; this one is dropped", REF_FLOW_TERMS_MAX);
        return;
    }
    if (strcmp(c->name, "texture") == 0) {
        if (f->texture[0] && strcmp(f->texture, c->path) != 0) {
            msg(x, c, "one velocity texture a world; this one is dropped");
            return;
        }
        snprintf(f->texture, sizeof f->texture, "%s", c->path);
        f->term[f->nterms++] = (ref_flow_term){ .kind = REF_FLOW_TEXTURE, .p = { n[0] } };
        return;
    }
    ref_flow_term t = { .kind = strcmp(c->name, "vortex") == 0 ? REF_FLOW_VORTEX : REF_FLOW_CURRENT };
    for (int i = 0; i < c->nnum && i < 4; i++) t.p[i] = n[i];
    if (t.kind == REF_FLOW_VORTEX && !(t.p[3] > 0)) {
        msg(x, c, "a vortex needs a radius > 0; this one is dropped");
        return;
    }
    f->term[f->nterms++] = t;
}

static void do_spray(ctx *x, const glib_cmd *c, ref_spray_desc *s) {
    const double *n = c->num;
    memset(s, 0, sizeof *s);
    s->on = true;
    s->threshold = n[0];
    s->rate = n[1];
    if (c->nnum >= 3) s->life = n[2];
    if (c->nnum >= 4) s->size = n[3];
    if (c->nnum >= 5) s->seed = (unsigned)n[4];
    if (c->nnum >= 6) s->count = (int)n[5];
    if (s->rate < 0 || s->life < 0 || s->size < 0) {
        msg(x, c, "rate, life and size are magnitudes; using %g %g %g", fabs(s->rate), fabs(s->life), fabs(s->size));
        s->rate = fabs(s->rate); s->life = fabs(s->life); s->size = fabs(s->size);
    }
}

static void do_perlin(ctx *x, const glib_cmd *c, ref_perlin_desc *pd) {
    const double *n = c->num;
    int k = c->nnum;
    memset(pd, 0, sizeof *pd);
    pd->amplitude = fabs(n[0]);
    if (n[0] < 0)
        msg(x, c, "amplitude %g is negative; using %g", n[0], -n[0]);
    if (k >= 2) {
        if (n[1] > 0) pd->cell = n[1];
        else msg(x, c, "cell %g must be greater than 0; using the default", n[1]);
    }
    if (k >= 3) {
        int o = (int)n[2];
        if (o < 1 || o > REF_PERLIN_OCTAVES_MAX) {
            int r = o < 1 ? 1 : REF_PERLIN_OCTAVES_MAX;
            msg(x, c, "octaves %d is outside 1..%d; using %d", o, REF_PERLIN_OCTAVES_MAX, r);
            o = r;
        }
        pd->octaves = o;
    }
    if (k >= 4) pd->rate = fabs(n[3]);
    if (k >= 5) {
        if (n[4] > 0) pd->stretch = n[4];
        else msg(x, c, "stretch %g must be greater than 0; using 1", n[4]);
    }
    if (k >= 6) pd->angle_deg = n[5];
    if (k >= 7) pd->seed = (uint32_t)n[6];
    if (k >= 8) {
        if (n[7] > 0) pd->gain = n[7];
        else msg(x, c, "gain %g must be greater than 0; using 0.5", n[7]);
    }
}

/* A size that must be positive: |v| for a negative one; false for 0. */
static bool positive(ctx *x, const glib_cmd *c, double *v, const char *what) {
    if (*v > 0)
        return true;
    if (*v == 0) {
        msg(x, c, "%s is 0; the object is dropped", what);
        return false;
    }
    msg(x, c, "%s %g is negative; using %g", what, *v, -*v);
    *v = -*v;
    return true;
}

/* Object mesh: the file loaded once here, so that what is wrong with it is
 * said at the line that names it (the world loads it again, ref_world_init);
 * its content's hash keys the reference's cache, its top the GL side's
 * "above the water" test. False: the object is dropped. */
static bool object_mesh(ctx *x, const glib_cmd *c, ref_object *o) {
    const double *n = c->num;
    o->kind = REF_OBJECT_MESH;
    o->rot_y_deg = c->nnum > 3 ? n[3] : 0;
    o->size[0] = c->nnum > 4 ? n[4] : 1;
    if (c->nnum > 4 && !positive(x, c, &o->size[0], "the scale"))
        return false;
    for (int i = 0; i < 3; i++) o->albedo[i] = c->nnum > 7 ? fmin(fmax(n[5 + i], 0), 1) : 0.5;
    if (snprintf(o->mesh_path, sizeof o->mesh_path, "%s", c->path) >= (int)sizeof o->mesh_path) {
        msg(x, c, "the path is longer than %d characters; the object is dropped", REF_MESH_PATH_MAX - 1);
        return false;
    }
    char err[MSG_MAX];
    size_t len = 0;
    uint64_t hash = 0;
    file_text_opts fo = { .max_bytes = OBJ_MAX_BYTES };
    char why[MSG_MAX];
    char *bytes = file_cache_read(x->files, c->path, &fo, &len, &hash, why, sizeof why);
    if (!bytes) msg_set(err, sizeof err, "cannot open '%s': %s", c->path, why);
    ref_mesh_place pl = { { n[0], n[1], n[2] }, o->rot_y_deg, o->size[0] };
    /* the bytes hashed are the bytes parsed: one read of the file */
    ref_mesh *m = bytes ? ref_mesh_parse(bytes, len, c->path, &pl, err, sizeof err) : NULL;
    if (!m) {
        msg(x, c, "%s; the object is dropped", err);
        free(bytes);
        return false;
    }
    o->mesh_hash = hash;
    double lo[3], hi[3];
    ref_mesh_bounds(m, lo, hi);
    o->size[1] = hi[1] - n[1];
    ref_mesh_free(m);
    free(bytes);
    return true;
}

static void do_object(ctx *x, const glib_cmd *c, ref_world_desc *w, bool *full_told) {
    if (w->nobjects >= REF_MAX_OBJECTS) {
        if (!*full_told)
            msg(x, c, "more than %d objects; this one and the ones after it are dropped",
                REF_MAX_OBJECTS);
        *full_told = true;
        return;
    }
    ref_object o;
    memset(&o, 0, sizeof o);
    const double *n = c->num;
    memcpy(o.center, n, sizeof o.center);
    int col;
    if (strcmp(c->name, "mesh") == 0) {
        if (!object_mesh(x, c, &o))
            return;
        w->objects[w->nobjects++] = o;
        return;
    }
    if (strcmp(c->name, "sphere") == 0) {
        o.kind = REF_OBJECT_SPHERE;
        o.size[0] = n[3];
        if (!positive(x, c, &o.size[0], "the radius"))
            return;
        col = 4;
    } else if (strcmp(c->name, "box") == 0) {
        static const char *const names[3] = { "hx", "hy", "hz" };
        o.kind = REF_OBJECT_BOX;
        for (int i = 0; i < 3; i++) {
            o.size[i] = n[3 + i];
            if (!positive(x, c, &o.size[i], names[i]))
                return;
        }
        col = 6;
    } else {
        o.kind = REF_OBJECT_CYLINDER;
        o.size[0] = n[3];
        o.size[1] = n[4];
        if (!positive(x, c, &o.size[0], "the radius") || !positive(x, c, &o.size[1], "the height"))
            return;
        col = 5;
    }
    bool clamped = false;
    for (int i = 0; i < 3; i++) {
        double v = n[col + i];
        o.albedo[i] = v < 0 ? 0 : v > 1 ? 1 : v;
        clamped |= o.albedo[i] != v;
    }
    if (clamped)
        msg(x, c, "the colour %g %g %g is a reflectance, from 0 to 1; using %g %g %g", n[col],
            n[col + 1], n[col + 2], o.albedo[0], o.albedo[1], o.albedo[2]);
    w->objects[w->nobjects++] = o;
}

/* A number of the world's look that must lie in [lo, hi] (hi 0: no upper
 * bound): out of it, a warning naming the command, and the nearest value. */
static double in_range(ctx *x, const glib_cmd *c, double v, double lo, double hi, const char *what) {
    double r = v < lo ? lo : (hi > 0 && v > hi) ? hi : v;
    if (r != v)
        msg(x, c, "%s %g is out of range; using %g", what, v, r);
    return r;
}

/* SkySun, Clouds, Haze, GroundDetail (issue #25): what the world looks like. */
static void do_look(ctx *x, const glib_cmd *c, ref_world_desc *w) {
    const double *n = c->num;
    switch (c->kind) {
    case GLIB_CMD_SKY_SUN:
        w->sun_disc_deg = in_range(x, c, n[0], 0, 20, "the disc's radius (degrees)");
        if (c->nnum > 1) w->sun_disc_gain = in_range(x, c, n[1], 0, 1e4, "the gain");
        break;
    case GLIB_CMD_CLOUDS:
        w->cloud_cover = in_range(x, c, n[0], 0, 1, "the cover");
        if (c->nnum > 1) w->cloud_scale = in_range(x, c, n[1], 0, 0, "the scale");
        if (c->nnum > 2) w->cloud_height = in_range(x, c, n[2], 0, 0, "the height");
        break;
    case GLIB_CMD_HAZE: w->haze_distance = in_range(x, c, n[0], 0, 0, "the distance"); break;
    case GLIB_CMD_GROUND_DETAIL: w->ground_detail = in_range(x, c, n[0], 0, 1, "the amount"); break;
    default: break;
    }
}

/* WindowSize's range, as docs/glib.md gives it (the parser's too). */
enum { WINDOW_MIN = 1, WINDOW_MAX = 16384 };

static void camera_default(scene_camera *cam) {
    /* glman's defaults: a 600x600 window, and with no LookAt OpenGL's own
     * view (the eye at the origin looking down -Z; glman files push the
     * scene back with Translate 0 0 -4) */
    memset(cam, 0, sizeof *cam);
    cam->center[2] = -1;
    cam->up[1] = 1;
    cam->fov_deg = 50;
    cam->near_z = 0.1;
    cam->far_z = 1000;
    cam->width = 600;
    cam->height = 600;
}

static void camera_cmd(scene_camera *cm, const glib_cmd *c) {
    const double *n = c->num;
    switch (c->kind) {
    case GLIB_CMD_WINDOW_SIZE:
        if (c->nnum >= 2 && n[0] >= WINDOW_MIN && n[1] >= WINDOW_MIN && n[0] <= WINDOW_MAX &&
            n[1] <= WINDOW_MAX) {
            cm->width = (int)n[0];
            cm->height = (int)n[1];
        }
        break;
    case GLIB_CMD_PERSPECTIVE:
        cm->ortho = false;
        if (c->nnum >= 1 && n[0] > 0 && n[0] < 180)
            cm->fov_deg = n[0];
        if (c->nnum >= 3 && n[1] > 0 && n[2] > n[1]) {
            cm->near_z = n[1];
            cm->far_z = n[2];
        }
        break;
    case GLIB_CMD_ORTHO:
        if (c->nnum >= 4) {
            cm->ortho = true;
            memcpy(cm->ortho_lrbt, n, sizeof cm->ortho_lrbt);
        }
        break;
    case GLIB_CMD_LOOKAT:
        if (c->nnum >= 9) {
            memcpy(cm->eye, n, sizeof cm->eye);
            memcpy(cm->center, n + 3, sizeof cm->center);
            memcpy(cm->up, n + 6, sizeof cm->up);
        }
        break;
    default: break;
    }
}

void scene_camera_from_glib(const glib_scene *g, scene_camera *cam) {
    camera_default(cam);
    for (int i = 0; g && i < g->ncmds; i++)
        camera_cmd(cam, &g->cmds[i]);
}

bool scene_from_glib(const glib_scene *g, ref_world_desc *world, scene_camera *cam,
                     bool *has_world, diag_list *dl) {
    ctx x = { .dl = dl, .files = g ? g->read_through : NULL };
    ref_world_init(&x.def, NULL);
    ref_world_desc w;
    memset(&w, 0, sizeof w);
    bool any = false, full_told = false;
    for (int i = 0; g && i < g->ncmds; i++) {
        const glib_cmd *c = &g->cmds[i];
        const double *n = c->num;
        any |= glib_cmd_describes_world(c->kind);
        switch (c->kind) {
        case GLIB_CMD_SUN: do_sun(&x, c, &w); break;
        case GLIB_CMD_SKY:
            set_rgb(&x, c, n, w.sky_zenith, "the zenith radiance");
            set_rgb(&x, c, n + 3, w.sky_horizon, "the horizon radiance");
            break;
        case GLIB_CMD_SKY_SUN:
        case GLIB_CMD_CLOUDS:
        case GLIB_CMD_HAZE:
        case GLIB_CMD_GROUND_DETAIL: do_look(&x, c, &w); break;
        case GLIB_CMD_WATER: do_water(&x, c, &w); break;
        case GLIB_CMD_WATER_MESH: w.water_mesh_res = clamp_res(&x, c, n[0], "res"); break;
        case GLIB_CMD_TERRAIN: do_terrain(&x, c, &w); break;
        case GLIB_CMD_WAVE_SINE:
        case GLIB_CMD_WAVE_GERSTNER: do_wave(&x, c, &w.waves); break;
        case GLIB_CMD_WAVE_STEEPNESS: do_steepness(&x, c, &w.waves); break;
        case GLIB_CMD_WAVE_NOISE: do_noise(&x, c, &w.waves.noise); break;
        case GLIB_CMD_WAVE_OCEAN: do_ocean(&x, c, &w.waves.ocean); break;
        case GLIB_CMD_WAVE_OCEAN_TILES: do_ocean_tiles(&x, c, &w.waves.ocean); break;
        case GLIB_CMD_WAVE_EXPLOSION: do_explosion(&x, c, &w.waves); break;
        case GLIB_CMD_WAVE_PERLIN: do_perlin(&x, c, &w.waves.perlin); break;
        case GLIB_CMD_FLOW: do_flow(&x, c, &w.flow); break;
        case GLIB_CMD_SPRAY: do_spray(&x, c, &w.spray); break;
        case GLIB_CMD_OBJECT: do_object(&x, c, &w, &full_told); break;
        default: break;
        }
    }
    w.waves.level = w.water_level;
    if (world)
        *world = w;
    if (cam)
        scene_camera_from_glib(g, cam);
    if (has_world)
        *has_world = any;
    ref_world_release(&x.def);
    return x.nmsgs == 0;
}


bool scene_load(const char *path, const char *pack_override, ref_world_desc *world,
                scene_camera *cam, bool *has_world, char *err, int errlen) {
    char packs[4096];
    snprintf(packs, sizeof packs, "%s/packs", tarn_root());
    glib_options opt = { .packs_dir = packs, .pack_override = pack_override };
    glib_scene *g = glib_load_opts(path, &opt);
    diag_list dl = { 0 };
    bool ok;
    if (g->nerrors > 0) {   /* the parser's errors say why */
        scene_from_glib(g, world, cam, has_world, NULL);
        for (int i = 0; i < g->ndiags; i++)
            if (g->diags[i].severity == DIAG_ERROR) diag_push(&dl, &g->diags[i]);
        ok = false;
    } else {
        ok = scene_from_glib(g, world, cam, has_world, &dl);
    }
    char *text = diag_list_format(&dl, 0);
    msg_set(err, (size_t)(errlen > 0 ? errlen : 0), "%s", text);
    free(text);
    diag_list_free(&dl);
    glib_free(g);
    return ok;
}
