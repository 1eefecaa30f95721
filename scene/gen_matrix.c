/* Placing generated parts: the matrices the generators build on zs_mat_*
 * (util/matrix.c) and zs_mat_rotate_turns.  See gen_internal.h. */
#include <math.h>

#include "util/exactmath.h"
#include "util/matrix.h"
#include "scene/gen_internal.h"

void zs_gen_random_rotation(zs_rng *rng, double m[16]) {
  double u1 = zs_rng_uniform(rng);
  double u2 = zs_rng_uniform(rng);
  double u3 = zs_rng_uniform(rng);
  double a = sqrt(1.0 - u1), b = sqrt(u1);
  double s2, c2, s3, c3;
  zs_sincos_turns(u2, &s2, &c2);
  zs_sincos_turns(u3, &s3, &c3);
  double x = a * s2, y = a * c2, z = b * s3, w = b * c3;
  zs_mat_identity(m);
  m[0] = 1.0 - 2.0 * (y * y + z * z);
  m[1] = 2.0 * (x * y - z * w);
  m[2] = 2.0 * (x * z + y * w);
  m[4] = 2.0 * (x * y + z * w);
  m[5] = 1.0 - 2.0 * (x * x + z * z);
  m[6] = 2.0 * (y * z - x * w);
  m[8] = 2.0 * (x * z - y * w);
  m[9] = 2.0 * (y * z + x * w);
  m[10] = 1.0 - 2.0 * (x * x + y * y);
}

void zs_gen_mul3(double out[16], const double a[16], const double b[16],
                 const double c[16]) {
  double bc[16];
  zs_mat_mul(bc, b, c);
  zs_mat_mul(out, a, bc);
}

void zs_gen_frame(double m[16], const double ax[3], const double ay[3],
                  const double az[3], const double o[3]) {
  zs_mat_identity(m);
  for (int r = 0; r < 3; r++) {
    m[4 * r + 0] = ax[r];
    m[4 * r + 1] = ay[r];
    m[4 * r + 2] = az[r];
    m[4 * r + 3] = o[r];
  }
}

void zs_gen_box_matrix(double m[16], const double lo[3], const double hi[3]) {
  zs_mat_identity(m);
  for (int k = 0; k < 3; k++) {
    m[5 * k] = hi[k] - lo[k];
    m[4 * k + 3] = 0.5 * (lo[k] + hi[k]);
  }
}

/* A right-handed frame whose y axis is the unit direction d: local x -> a,
 * y -> d, z -> b = a x d, with a the part of +y (or +x when d is along y)
 * across d.  Axis-parallel d gives exact 0 and +-1 entries. */
static void frame_of(const double d[3], double a[3], double b[3]) {
  double h[3] = {0.0, 1.0, 0.0};
  if (fabs(d[1]) > 0.9) {
    h[0] = 1.0;
    h[1] = 0.0;
  }
  double hd = h[0] * d[0] + h[1] * d[1] + h[2] * d[2];
  for (int k = 0; k < 3; k++) a[k] = h[k] - hd * d[k];
  double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  for (int k = 0; k < 3; k++) a[k] /= la;
  b[0] = a[1] * d[2] - a[2] * d[1];
  b[1] = a[2] * d[0] - a[0] * d[2];
  b[2] = a[0] * d[1] - a[1] * d[0];
}

void zs_gen_along(double m[16], const double from[3], const double d[3], double len,
                  double r) {
  double a[3], b[3], ax[3], ay[3], az[3];
  frame_of(d, a, b);
  for (int k = 0; k < 3; k++) {
    ax[k] = r * a[k];
    ay[k] = len * d[k];
    az[k] = r * b[k];
  }
  zs_gen_frame(m, ax, ay, az, from);
}

void zs_gen_between(double m[16], const double a[3], const double b[3], double r) {
  double d[3], len = 0.0;
  for (int k = 0; k < 3; k++) len += (b[k] - a[k]) * (b[k] - a[k]);
  len = sqrt(len);
  for (int k = 0; k < 3; k++) d[k] = (b[k] - a[k]) / len;
  zs_gen_along(m, a, d, len, r);
}
