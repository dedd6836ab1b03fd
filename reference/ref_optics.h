/* ref_optics: exact dielectric optics in double precision for the CPU
 * ground truth, plus the cheap forms the shader packs use (so their error
 * can be measured against the exact one).
 *
 * Conventions: directions are unit double[3] vectors; an incident direction
 * points the way the light travels (towards the surface); n1 is the index of
 * the medium the incident ray is in, n2 the one beyond the surface. cos_i is
 * the cosine of the angle between the incident ray and the surface normal,
 * taken in absolute value (the side does not matter, the indices do).
 *
 * Every function is pure and thread-safe. See docs/reference.md.
 */
#ifndef TARN_REF_OPTICS_H
#define TARN_REF_OPTICS_H

#define REF_N_AIR 1.0
#define REF_N_WATER 1.333

/* Exact unpolarised Fresnel reflectance R = (Rs + Rp) / 2 for light going
 * from index n1 into index n2 at incidence cosine cos_i (clamped to [0, 1]).
 * Total internal reflection (n1 > n2 beyond the critical angle) gives 1.
 * Transmittance is 1 - R (no absorption at the interface). */
double ref_fresnel(double cos_i, double n1, double n2);

/* The same, with the s- and p-polarised reflectances separately (either
 * pointer may be NULL); returns the unpolarised R. */
double ref_fresnel_sp(double cos_i, double n1, double n2, double *rs, double *rp);

/* Schlick's approximation R0 + (1 - R0)(1 - c)^5 with R0 = ((n1-n2)/(n1+n2))^2.
 * c is cos_i when n1 <= n2; when n1 > n2 it is the cosine on the less dense
 * side (cos_t), and beyond the critical angle the result is 1 — the usual
 * way to make Schlick work from below. */
double ref_fresnel_schlick(double cos_i, double n1, double n2);

/* The cheap shader form (1 - cos_i)^q (0 at normal incidence). */
double ref_fresnel_pow(double cos_i, double q);

/* Critical angle in radians for light going from n1 to n2, or -1 when there
 * is none (n1 <= n2). */
double ref_critical_angle(double n1, double n2);

/* Cosine of the transmitted angle by Snell's law (n1 sin_i = n2 sin_t).
 * Returns 1 and sets *cos_t, or 0 on total internal reflection. */
int ref_snell_cos(double cos_i, double n1, double n2, double *cos_t);

/* Mirror reflection r = d - 2 (d.n) n; n may face either side. */
void ref_reflect(const double d[3], const double n[3], double r[3]);

/* Refraction of unit direction d at a surface with unit normal n (either
 * side; it is flipped to face the incident ray), from index n1 into n2:
 * t = eta d + (eta cos_i - cos_t) n', eta = n1/n2. Returns 1 and the unit
 * transmitted direction in t, or 0 on total internal reflection (t then
 * holds the reflected direction). t may alias d. */
int ref_refract(const double d[3], const double n[3], double n1, double n2, double t[3]);

#endif
