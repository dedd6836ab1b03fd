/* render_splat: `Splat SRC DST`, the paper's caustics on the CPU: photons
 * read back from one texture, their irradiance splatted into another. */
#include "util.h"
#include "render_internal.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdlib.h>

#include "mem.h"

static const gpu_tex *tex_at_unit(const scene_state *s, int unit) {
    const gpu_tex *t = NULL;
    for (int i = 0; i < s->ntexs; i++)   /* the last one declared at a unit wins, as bound */
        if (s->texs[i].tex && s->texs[i].unit == unit) t = &s->texs[i];
    return t;
}

/* Adds every photon's energy bilinearly into the w x h grid over the world
 * square |x|, |z| <= hs (texel (i, j) centred at x = -hs + (i + 0.5) 2hs / w,
 * row j likewise in z), as irradiance: energy over the texel's area. */
static void splat_photons(const float *photons, long n, float *grid, int w, int h, double hs) {
    double cw = 2 * hs / w, ch = 2 * hs / h, inv_area = 1.0 / (cw * ch);
    for (long p = 0; p < n; p++) {
        const float *ph = photons + p * 4;
        if (!(ph[3] > 0) || !isfinite(ph[0]) || !isfinite(ph[1]) || !isfinite(ph[2])) continue;
        double gx = (ph[0] + hs) / cw - 0.5, gy = (ph[1] + hs) / ch - 0.5;
        int i0 = (int)floor(gx), j0 = (int)floor(gy);
        double fx = gx - i0, fy = gy - j0;
        for (int dj = 0; dj < 2; dj++)
            for (int di = 0; di < 2; di++) {
                int i = i0 + di, j = j0 + dj;
                if (i < 0 || j < 0 || i >= w || j >= h) continue;
                double wgt = (di ? fx : 1 - fx) * (dj ? fy : 1 - fy);
                float *g = grid + ((size_t)j * w + i) * 4;
                float e = (float)(ph[2] * wgt * inv_area);
                g[0] += e;
                g[1] += e;
                g[2] += e;
                g[3] = 1.0f;
            }
    }
}

/* `Splat SRC DST`: the paper's CPU caustics. Each texel of SRC is a photon
 * (R, G: world x, z of its floor hit; B: energy; A > 0: valid); DST gets the
 * irradiance they make over the world square and is uploaded. */
void render_splat(const render *r, int src_unit, int dst_unit) {
    const scene_state *s = &r->cur;
    const gpu_tex *src = tex_at_unit(s, src_unit), *dst = tex_at_unit(s, dst_unit);
    if (!src || !dst || src->target != GL_TEXTURE_2D || dst->target != GL_TEXTURE_2D) return;
    float *in = mem_alloc((size_t)src->w * src->h * 4 * sizeof(float));
    float *out = mem_zalloc((size_t)dst->w * dst->h * 4 * sizeof(float));
    glBindTexture(GL_TEXTURE_2D, src->tex);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, in);
    double hs = r->world.active ? r->world.w.d.half_size : 12.0;
    splat_photons(in, (long)src->w * src->h, out, dst->w, dst->h, hs);
    glBindTexture(GL_TEXTURE_2D, dst->tex);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, dst->w, dst->h, GL_RGBA, GL_FLOAT, out);
    glBindTexture(GL_TEXTURE_2D, 0);
    free(in);
    free(out);
}
