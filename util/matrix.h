/* zscan util — the matrix kit beyond the public zs_mat_* (zscan/zscan.h),
 * with the conventions stated there and in raster/raster.h: row-major
 * double[16] acting on column vectors. */
#ifndef ZS_UTIL_MATRIX_H
#define ZS_UTIL_MATRIX_H

#include "zscan/zscan.h"

#define ZS_PI 3.14159265358979323846

/* zs_mat_rotate with the angle in turns (1 turn = 360 degrees): for an
 * angle drawn in turns, which would not survive * 360 / 360 bit for bit. */
void zs_mat_rotate_turns(double m[16], double turns, double x, double y, double z);

/* v scaled by a power of two into out when its square would overflow or
 * vanish (a light's direction 1e200,1e200,1e200), else copied: the same
 * direction, whose unit vector then keeps every bit; a v in range is
 * taken as it is. */
void zs_vec3_in_range(const double v[3], double out[3]);

/* out = m (p, 1): inline, as set-up calls it once or twice per vertex. */
static inline void zs_mat_apply(const double m[16], const double p[3], double out[4]) {
  for (int i = 0; i < 4; i++)
    out[i] = m[4 * i] * p[0] + m[4 * i + 1] * p[1] + m[4 * i + 2] * p[2] + m[4 * i + 3];
}

/* The world position of the eye of a view matrix [R | t] with R a
 * rotation: -R^T t. */
static inline void zs_mat_eye_of_view(const double view[16], double eye[3]) {
  for (int i = 0; i < 3; i++)
    eye[i] = -(view[i] * view[3] + view[4 + i] * view[7] + view[8 + i] * view[11]);
}

/* Newell's normal of a polygon is the sum of this term over its edges a-c
 * (corner i to corner i + 1, the last back to the first): twice its vector
 * area, exact for planar polygons and the best-fitting plane's normal for
 * others; its component along an axis is twice the signed area of the
 * projection onto the plane of the other two.  Every caller sums the edges
 * in that order from nrm = 0, so all get the same bits. */
static inline void zs_newell_add(double nrm[3], const double *a, const double *c) {
  nrm[0] += (a[1] - c[1]) * (a[2] + c[2]);
  nrm[1] += (a[2] - c[2]) * (a[0] + c[0]);
  nrm[2] += (a[0] - c[0]) * (a[1] + c[1]);
}

#endif
