/* ref_ocean: a spectrum ocean (Tessendorf 2001, "Simulating Ocean Water"),
 * in double precision: the reference's twin of the GL ocean passes
 * (viewer/gfx/render_ocean.c and packs/common/ocean_*.frag).
 *
 * The model. Each cascade c is a periodic tile of side L_c sampled on an
 * N x N grid. Its initial spectrum h0(k), k = 2 pi (m', n') / L_c with
 * m' = m < N/2 ? m : m - N (FFT order, texel (m, n)), is
 *
 *     h0(k) = (xi_r + i xi_i) sqrt(S(-k) dk^2 / 4)     (xi: unit Gaussians)
 *
 * from a hash of (seed, cascade, m, n) (the same numbers on every machine),
 * where S(k) is the directional spectrum (Phillips, JONSWAP or TMA, with
 * a spreading function; see ref_ocean.c for the formulas and sources),
 * masked to the cascade's band of |k| so the cascades add without
 * counting a wave twice. Why S(-k) and 1/4: with h~ below, h0(k) is the
 * wave whose phase is k.x + w t, which travels towards -k; the wave
 * travelling towards +k is 2 Re(conj(h0(-k)) e^{i(k.x - w t)}), of
 * variance 2 |h0(-k)|^2 = S(k) dk^2 on average: so the sea runs
 * downwind and the variance of h is the integral of S (see
 * ref_ocean_variance). Bands (ref_ocean.c): cascade c keeps
 * lo_c <= |k| < hi_c, the edge between c and c + 1 at
 * min(6 dk_(c+1), (N/2 - 1) dk_c), lo_0 = 0, hi_last = (N/2) dk_last. The Nyquist row and column (m or n = N/2) are
 * zero, so every field below is exactly real. At time t
 *
 *     h~(k, t) = h0(k) e^{i w t} + conj(h0(-k)) e^{-i w t},   w = sqrt(g |k| tanh(|k| depth))
 *
 * and the eight real fields are inverse DFTs on the grid x_(m,n) = (m, n) L/N:
 *
 *     h  = sum h~ e^{i k.x}               height
 *     Dx = sum i kx/|k| h~ e^{i k.x}      sideways displacement (times lambda)
 *     Dz = sum i kz/|k| h~ e^{i k.x}
 *     hx = sum i kx h~ e^{i k.x}          slopes dh/dx, dh/dz
 *     hz = sum i kz h~ e^{i k.x}
 *     Dxx, Dzz, Dxz = sum -(kx kx, kz kz, kx kz)/|k| h~ e^{i k.x}  (times lambda)
 *
 * The sign of D: one wave h = A cos(k.x - w t) gets D = -A k^ sin(k.x - w t),
 * Gerstner's displacement (GPU Gems 1 ch. 1), so lambda > 0 draws sharp
 * crests and broad troughs and the sea folds at the crests (Tessendorf's
 * -i k^ with this e^{+i k.x} would sharpen the troughs instead).
 *
 * The surface between grid nodes is the bilinear interpolation of the
 * nodes (periodic), exactly what the GL samples: so "the exact surface" of
 * the reference is the same function the GPU evaluates in float. A rest
 * point (u, v) moves to (u + Dx, h, v + Dz) (Tessendorf's choppy
 * displacement X + lambda D, lambda folded into the D fields).
 *
 * Layout of a frame (and of the GL textures, one layer per cascade):
 *     A = (h, Dx, Dz, Dxz)    B = (hx, hz, Dxx, Dzz)
 * four doubles a texel, row n after row n - 1, m fastest.
 *
 * A ref_ocean is built once from a desc and then read-only; its frames at
 * a time t are computed on first use and kept in a small cache guarded by
 * a mutex, so every query is thread-safe.
 */
#ifndef TARN_REF_OCEAN_H
#define TARN_REF_OCEAN_H

#include <stddef.h>
#include <stdint.h>

#define REF_OCEAN_CASCADES_MAX 3
#define REF_OCEAN_RES_MIN 64
#define REF_OCEAN_RES_MAX 512
#define REF_OCEAN_FIELDS 8         /* h, Dx, Dz, Dxz, hx, hz, Dxx, Dzz */

typedef enum ref_spectrum_kind {
    REF_SPECTRUM_NONE = 0,         /* no ocean */
    REF_SPECTRUM_PHILLIPS,         /* Tessendorf's Phillips spectrum */
    REF_SPECTRUM_JONSWAP,          /* Hasselmann et al. 1973, fetch-limited */
    REF_SPECTRUM_TMA               /* JONSWAP with the finite-depth factor */
} ref_spectrum_kind;

/* Zero means default in every field but choppiness and seed. */
typedef struct ref_ocean_desc {
    ref_spectrum_kind spectrum;    /* NONE: no ocean (the rest is ignored) */
    double wind_speed;             /* U10, m/s; 0: 10 */
    double wind_angle_deg;         /* the wind blows towards this angle from +x towards +z */
    double fetch;                  /* m (JONSWAP, TMA); 0: 100 km */
    double depth;                  /* m: the dispersion's and TMA's depth; 0: deep water */
    double spreading;              /* directional spreading: Phillips |k^.w^|^s (0: 2);
                                      JONSWAP/TMA: 0 = Hasselmann's, s > 0 = cos^(2s) */
    double choppiness;             /* lambda of X + lambda D; 0: no sideways displacement */
    double amplitude;              /* a factor on every wave's amplitude; 0: 1 */
    int res;                       /* N, a power of two in 64..512; 0: 128 */
    int cascades;                  /* 1..3; 0: 1 */
    double tile[REF_OCEAN_CASCADES_MAX];   /* L_c, m, decreasing; 0: 250, 37, 5.3 (times
                                      the first one given when only it is) */
    uint32_t seed;
} ref_ocean_desc;

typedef struct ref_ocean ref_ocean;

/* A sample of the ocean at a rest point: the eight fields, summed over the
 * cascades, bilinear between nodes. */
typedef struct ref_ocean_sample {
    double h, dx, dz;              /* height (relative to the level), displacement */
    double hx, hz;                 /* slope of h in (u, v) */
    double dxx, dxz, dzz;          /* d(Dx)/du, d(Dx)/dv = d(Dz)/du, d(Dz)/dv */
} ref_ocean_sample;

/* Bounds of a frame, of the bilinear surface itself (summed over the
 * cascades): |h| <= height (max |h| over nodes, attained); |grad h| <=
 * slope; the derivative of the bilinear sideways map (u, v) -> (Dx, Dz)
 * has spectral norm <= chop. Each cascade's part is its exact maximum over
 * the bilinear surface: both derivatives are bi-affine in a cell, so their
 * norms peak at the cell's corners (proof at cascade_bounds, ref_ocean.c).
 * So the map's Jacobian's smallest singular value >= 1 - chop and world
 * slopes <= slope / (1 - chop) when chop < 1. ref_ocean_bounds_any: the
 * sums of the waves' amplitudes (times k for slope, times lambda k for
 * chop), true at every time. */
typedef struct ref_ocean_bounds {
    double height, slope, chop;
} ref_ocean_bounds;

/* Fills the defaults of a desc (in one place); -1 with a message for bad
 * input (res not a power of two in range, cascades out of 1..3, tiles not
 * decreasing, non-finite or negative numbers). */
int ref_ocean_desc_resolve(ref_ocean_desc *d, char *err, size_t errlen);

/* Builds the ocean (its initial spectra). NULL with a message for a bad
 * desc; a desc with spectrum NONE is an error here (the caller checks). */
ref_ocean *ref_ocean_create(const ref_ocean_desc *desc, char *err, size_t errlen);
void ref_ocean_destroy(ref_ocean *o);

const ref_ocean_desc *ref_ocean_get_desc(const ref_ocean *o);   /* resolved */

/* Bounds that hold at every time (from the spectra's amplitudes; loose),
 * and the exact bounds of the frame at time t. */
void ref_ocean_bounds_any(const ref_ocean *o, ref_ocean_bounds *b);
void ref_ocean_bounds_at(const ref_ocean *o, double t, ref_ocean_bounds *b);

/* The smallest wavelength it holds (the finest cascade's 2 texels). */
double ref_ocean_min_wavelength(const ref_ocean *o);

/* The fields at rest point (u, v), time t: bilinear in the frame at t. */
void ref_ocean_sample_at(const ref_ocean *o, double u, double v, double t, ref_ocean_sample *s);

/* The sideways map alone, bilinear: D = (Dx, Dz) at (u, v) and, when jac is
 * not NULL, the exact derivative of the bilinear interpolant in the cell
 * holding (u, v): jac = (dDx/du, dDx/dv, dDz/du, dDz/dv) (not symmetric in
 * general; the D-derivative fields are the continuous one's). Newton on
 * the map converges fast with it (ref_waves' inversion). */
void ref_ocean_sample_map(const ref_ocean *o, double u, double v, double t, double d[2], double jac[4]);

/* A snapshot: the frame at one time, held (refcounted) and read-only, so
 * that a ray, a photon or a whole render looks the frame up ONCE (one lock)
 * and samples it without locks. The per-call functions above take the
 * cache's lock on every sample, which costs more than the sample itself
 * when a march inverts the surface thousands of times a ray. A snapshot
 * gives the same numbers as they do, bit for bit (the same formulas on the
 * same nodes), and may be shared by any number of threads. Release every
 * snapshot before ref_ocean_destroy. */
typedef struct ref_ocean_snapshot ref_ocean_snapshot;

const ref_ocean_snapshot *ref_ocean_snapshot_acquire(const ref_ocean *o, double t);
void ref_ocean_snapshot_release(const ref_ocean_snapshot *s);

/* ref_ocean_bounds_at, ref_ocean_sample_at and ref_ocean_sample_map on the
 * snapshot. The map also gives the sample's h when height is not NULL (an
 * inversion then has the height at its rest point for free); and
 * ref_ocean_snapshot_height is h alone. Both read packed (Dx, Dz, h) nodes,
 * not the eight fields: what a march needs. */
void ref_ocean_snapshot_bounds(const ref_ocean_snapshot *s, ref_ocean_bounds *b);
void ref_ocean_snapshot_sample(const ref_ocean_snapshot *s, double u, double v, ref_ocean_sample *out);
void ref_ocean_snapshot_map(const ref_ocean_snapshot *s, double u, double v, double d[2], double jac[4],
                            double *height);
double ref_ocean_snapshot_height(const ref_ocean_snapshot *s, double u, double v);

/* Bounds by region. disp_range: (Dx, Dz) lies in [lo, hi] (per axis) at
 * every rest point (the cascades' node minima and maxima summed).
 * box_bounds: over the rest points of the box [u0, u1] x [v0, v1] (u0 <=
 * u1, v0 <= v1) h is Lipschitz with constant slope and the sideways map
 * (Dx, Dz) with constant chop (spectral norm), each the sum over the
 * cascades of the largest exact cell maximum (ref_ocean_bounds) among the
 * cells of a few blocks of cells that cover the box (a max pyramid of each
 * cascade's cells: 2 x 2 blocks of the finest level that covers it so,
 * rounded up to float). At most the frame's bounds (up to that rounding);
 * O(cascades) a call. */
void ref_ocean_snapshot_disp_range(const ref_ocean_snapshot *s, double lo[2], double hi[2]);
void ref_ocean_snapshot_box_bounds(const ref_ocean_snapshot *s, double u0, double v0, double u1, double v1,
                                   double *slope, double *chop);

/* The same fields by a direct sum of every wave of every cascade at (u, v)
 * (no FFT, no interpolation): equal to ref_ocean_sample_at at grid nodes
 * up to rounding. For tests; O(N^2) a call. */
void ref_ocean_direct_sum(const ref_ocean *o, double u, double v, double t, ref_ocean_sample *s);

/* The frame at time t of one cascade, as the GL passes compute it: a and b
 * each N * N * 4 doubles in the layout above (for tests). */
void ref_ocean_frame(const ref_ocean *o, int cascade, double t, double *a, double *b);

/* What the GL passes start from, for cascade c (N * N texels, FFT order):
 * h0 4 floats a texel, (Re h0(k), Im h0(k), Re conj(h0(-k)), Im conj(h0(-k))),
 * and omega 1 float a texel, w(|k|). */
void ref_ocean_gpu_spectrum(const ref_ocean *o, int cascade, float *h0, float *omega);

/* Statistics of the spectrum for tests and docs: the variance of h it
 * holds (sum of |h0|^2 + |h0(-k)|^2 over every k), and the variance the
 * continuous spectrum S integrates to over the cascades' bands. */
double ref_ocean_variance(const ref_ocean *o);
double ref_ocean_spectrum_variance(const ref_ocean *o);

/* The continuous directional spectrum S(kx, kz) in m^4 (for tests and docs). */
double ref_ocean_spectrum(const ref_ocean *o, double kx, double kz);

#endif
