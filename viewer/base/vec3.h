/* vec3: the few double-precision vector helpers the reference and the
 * bakers share (cglm is float; the ground truth is double). */
#ifndef TARN_VEC3_H
#define TARN_VEC3_H

#include <math.h>

static inline double vec3_dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* c = a x b (c may not alias a or b). */
static inline void vec3_cross(const double a[3], const double b[3], double c[3]) {
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* Scales v to unit length and returns the length it had; a zero vector
 * stays zero. */
static inline double vec3_normalize(double v[3]) {
    double l = sqrt(vec3_dot(v, v));
    if (l > 0)
        for (int i = 0; i < 3; i++) v[i] /= l;
    return l;
}

#endif
