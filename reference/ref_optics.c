/* ref_optics: exact Fresnel, Snell and reflection (see ref_optics.h). */
#include "ref_optics.h"

#include <math.h>
#include <stddef.h>

static double clamp01(double x) {
    if (!(x > 0.0)) return 0.0;   /* also maps NaN to 0 */
    return x < 1.0 ? x : 1.0;
}

int ref_snell_cos(double cos_i, double n1, double n2, double *cos_t) {
    double c = clamp01(fabs(cos_i));
    double eta = n1 / n2;
    double sin2_t = eta * eta * (1.0 - c * c);
    if (sin2_t >= 1.0) return 0;
    *cos_t = sqrt(1.0 - sin2_t);
    return 1;
}

double ref_fresnel_sp(double cos_i, double n1, double n2, double *rs, double *rp) {
    double ci = clamp01(fabs(cos_i)), ct;
    if (!ref_snell_cos(ci, n1, n2, &ct)) {
        if (rs) *rs = 1.0;
        if (rp) *rp = 1.0;
        return 1.0;
    }
    double s = (n1 * ci - n2 * ct) / (n1 * ci + n2 * ct);
    double p = (n1 * ct - n2 * ci) / (n1 * ct + n2 * ci);
    double Rs = s * s, Rp = p * p;
    if (rs) *rs = Rs;
    if (rp) *rp = Rp;
    return 0.5 * (Rs + Rp);
}

double ref_fresnel(double cos_i, double n1, double n2) {
    return ref_fresnel_sp(cos_i, n1, n2, NULL, NULL);
}

double ref_fresnel_schlick(double cos_i, double n1, double n2) {
    double r0 = (n1 - n2) / (n1 + n2);
    r0 *= r0;
    double c = clamp01(fabs(cos_i));
    if (n1 > n2 && !ref_snell_cos(c, n1, n2, &c)) return 1.0;
    double m = 1.0 - c;
    double m2 = m * m;
    return r0 + (1.0 - r0) * m2 * m2 * m;
}

double ref_fresnel_pow(double cos_i, double q) {
    return pow(1.0 - clamp01(fabs(cos_i)), q);
}

double ref_critical_angle(double n1, double n2) {
    if (!(n1 > n2)) return -1.0;
    return asin(n2 / n1);
}

void ref_reflect(const double d[3], const double n[3], double r[3]) {
    double k = 2.0 * (d[0] * n[0] + d[1] * n[1] + d[2] * n[2]);
    double r0 = d[0] - k * n[0], r1 = d[1] - k * n[1], r2 = d[2] - k * n[2];
    r[0] = r0; r[1] = r1; r[2] = r2;
}

int ref_refract(const double d[3], const double n[3], double n1, double n2, double t[3]) {
    double dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    double s = dn > 0.0 ? -1.0 : 1.0;            /* n' = s n faces the incident ray */
    double cos_i = -s * dn, cos_t;
    if (!ref_snell_cos(cos_i, n1, n2, &cos_t)) {
        ref_reflect(d, n, t);
        return 0;
    }
    double eta = n1 / n2;
    double k = s * (eta * clamp01(cos_i) - cos_t);
    double t0 = eta * d[0] + k * n[0], t1 = eta * d[1] + k * n[1], t2 = eta * d[2] + k * n[2];
    double len = sqrt(t0 * t0 + t1 * t1 + t2 * t2);
    t[0] = t0 / len; t[1] = t1 / len; t[2] = t2 / len;
    return 1;
}
